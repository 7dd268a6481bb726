//! `machine NAME { kind = cnc … }`: a CNC, programmed in G-code: its axes,
//! the dialect and the lines that override it, the travel limits and where
//! the part sits.

use super::{common, height_sensor, limits_block, motion, Written};
use crate::diag::{message, Diagnostics};
use crate::ir::{
    AxisLimits, Cnc, Dialect, FeedUnit, Kinematics, Machine, Placement, RotaryTable, TableOutput,
};
use crate::sema::eval::Env;
use crate::sema::fields::{self, Fields};
use crate::sema::machine::cell;
use crate::sema::program_text;
use crate::sema::schema::machine::{
    limits, AXES, CLEARANCE, CNC, C_AXIS, DIALECT, DWELL, FEED_UNITS, KINEMATICS, LASER_OFF,
    LASER_ON, MAX_SPEED, ORIGIN, POSTAMBLE, PREAMBLE, ROTARY_SPEED, SAFE_HEIGHT, S_DECIMALS,
    S_PER_WATT, TABLE_OUTPUT, TCP_OFF, TCP_ON, TILT_AXIS, WORK_OFFSET,
};
use crate::sema::schema::Field;
use crate::sema::value::{Spanned, Value};
use crate::span::Span;
use crate::syntax::ast::Stmt;
use crate::target::gcode as dialect;

/// Reads a CNC's block: the CNC, and where its fields are written.
pub(super) fn read<'a>(
    env: &mut Env<'a>,
    name: &str,
    stmts: &'a [Stmt],
    span: Span,
    diags: &mut Diagnostics,
) -> Option<(Machine, Written)> {
    let f = Fields::block(env, stmts, &CNC, format!("CNC `{name}`"), span, diags);
    let limits = limits_block(env, &f, diags);
    let mut at: Written = f.written().collect();
    at.extend(limits.iter().flat_map(Fields::written));
    let c = cnc(name, &f, limits.as_ref(), diags);
    let profile = c
        .as_ref()
        .map_or("linuxcnc", |c| c.dialect.profile.as_str())
        .to_string();
    let outputs = if profile == "linuxcnc" {
        crate::target::outputs::LINUXCNC
    } else {
        crate::target::outputs::OTHER_CNC
    };
    let lines = cell::cnc_lines(&f, &profile, diags);
    let cell = cell::read(
        env,
        &f,
        (outputs, cell::Naming::Cnc),
        lines.clone().map(|l| (l, profile.as_str())),
        &[],
        diags,
    );
    let head = super::head::read(env, &f, name, &mut at, diags);
    let (mut c, cell, head) = (c?, cell?, head?);
    lines?;
    at.extend(cell.spans);
    c.common.cell = cell.cell;
    c.common.head = head;
    Some((Machine::Cnc(c), at))
}

fn cnc(
    name: &str,
    f: &Fields<'_>,
    limits: Option<&Fields<'_>>,
    diags: &mut Diagnostics,
) -> Option<Cnc> {
    let (axes, kin) = axes(f, diags);
    let profile = f.word(&DIALECT, diags);
    let mut d = match profile {
        Some((p, _)) => dialect::profile(p),
        None if f.has(&DIALECT) => None,
        None => dialect::profile("linuxcnc"),
    };
    let text_ok = d.as_mut().is_none_or(|d| overrides(f, d, diags));
    let vmax = f.quantity(&MAX_SPEED, diags);
    let clearance = f.quantity_or_default(&CLEARANCE, diags);
    let lim = match limits {
        Some(l) => axis_limits(l, kin, diags),
        None => Some(DEFAULT_LIMITS),
    };
    let placement = placement(f, diags);
    let (table, rotary_speed) = table(f, kin, diags);
    let safe = f.optional(&SAFE_HEIGHT, f.quantity(&SAFE_HEIGHT, diags).map(|q| q.0));
    let moves = motion(f, diags);
    let sensor = height_sensor(f, 0, dialect::MAX_ANALOG_INPUT, diags);
    if !text_ok {
        return None;
    }
    Some(Cnc {
        common: common(name, vmax.map(|v| v.0), clearance, sensor, moves)?,
        axes: axes?,
        kinematics: kin?,
        dialect: d?,
        limits: lim?,
        placement: placement?,
        safe_height: safe?,
        table: table?,
        rotary_speed: rotary_speed?,
    })
}

/// A tilting table's axes and output (`c_axis`, `tilt_axis`,
/// `table_output`) and the rotary axes' `rotary_speed`, each refused on a
/// machine that has no such axes.
#[allow(clippy::type_complexity)]
fn table(
    f: &Fields<'_>,
    kin: Option<Kinematics>,
    diags: &mut Diagnostics,
) -> (Option<Option<RotaryTable>>, Option<Option<f64>>) {
    let is_table = kin.is_some_and(Kinematics::is_table);
    let mut ok = true;
    for field in [&C_AXIS, &TILT_AXIS, &TABLE_OUTPUT] {
        if let (Some(s), Some(k), false) = (f.span(field), kin, is_table) {
            diags.push(message::machine::not_a_table(field.key, k.word(), s));
            ok = false;
        }
    }
    let speed = f.quantity(&ROTARY_SPEED, diags).map(|q| q.0.to_degrees());
    if let (Some(s), Some(Kinematics::Xyz)) = (f.span(&ROTARY_SPEED), kin) {
        diags.push(message::machine::not_a_table(ROTARY_SPEED.key, "xyz", s));
        ok = false;
    }
    let rotary_speed = f.optional(&ROTARY_SPEED, speed);
    if !is_table {
        return (ok.then_some(None), rotary_speed);
    }
    // Where the axes are decides where every point goes: no default.
    let mut missing = false;
    for field in [&C_AXIS, &TILT_AXIS] {
        if !f.has(field) {
            let k = kin.map_or("table_ac", Kinematics::word);
            diags.push(message::machine::table_axis_missing(
                field.key,
                k,
                f.span(&KINEMATICS),
            ));
            missing = true;
        }
    }
    let c_axis = point(f, &C_AXIS, diags).filter(|_| !missing);
    let tilt_axis = point(f, &TILT_AXIS, diags);
    let output = f.word_or_default(&TABLE_OUTPUT, diags).map(|w| match w {
        "machine" => TableOutput::Machine,
        _ => TableOutput::Tcp,
    });
    let table = match (c_axis, tilt_axis, output) {
        (Some(Some(c_axis)), Some(Some(tilt_axis)), Some(output)) => Some(Some(RotaryTable {
            c_axis,
            tilt_axis,
            output,
        })),
        _ => None,
    };
    (table, rotary_speed)
}

/// A point `[x, y, z]` (lengths) in `field`: `Some(None)` when it is not
/// written, `None` when it is wrong (reported).
fn point(f: &Fields<'_>, field: &Field, diags: &mut Diagnostics) -> Option<Option<[f64; 3]>> {
    let v = match f.value(field, diags) {
        None if f.has(field) => return None,
        None => return Some(None),
        Some(v) => v,
    };
    match &v.value {
        Value::List(items) if items.len() == 3 => xyz(items, diags).map(Some),
        other => {
            diags.push(message::machine::axis_point_not_a_point(
                field.key,
                v.span,
                &other.describe(),
            ));
            None
        }
    }
}

/// Three lengths `[x, y, z]`, each checked; `None` when one is wrong
/// (reported).
fn xyz(items: &[Spanned], diags: &mut Diagnostics) -> Option<[f64; 3]> {
    let c: Vec<_> = ["x", "y", "z"]
        .iter()
        .zip(items)
        .map(|(k, it)| fields::quantity(it, crate::units::Dim::LENGTH, k, diags))
        .collect();
    match c[..] {
        [Some(x), Some(y), Some(z)] => Some([x, y, z]),
        _ => None,
    }
}

/// `axes = 3 | 5` and `kinematics = …`, which must agree: 3 axes move the
/// nozzle vertically (`xyz`), 5 tilt it.
fn axes(f: &Fields<'_>, diags: &mut Diagnostics) -> (Option<u8>, Option<Kinematics>) {
    let axes = match f.count(&AXES, diags) {
        Some((4, s)) => {
            diags.push(message::machine::four_axes(s));
            None
        }
        a => a.map(|a| a.0 as u8),
    };
    let kin = f.word(&KINEMATICS, diags);
    let kin_span = kin.map(|k| k.1);
    let kin = kin.map(|(k, _)| match k {
        "head_ac" => Kinematics::HeadAc,
        "head_bc" => Kinematics::HeadBc,
        "table_ac" => Kinematics::TableAc,
        "table_bc" => Kinematics::TableBc,
        _ => Kinematics::Xyz,
    });
    let kin = match (axes, kin) {
        (Some(3), None) if !f.has(&KINEMATICS) => Some(Kinematics::Xyz),
        (Some(5), None) if !f.has(&KINEMATICS) => Some(Kinematics::HeadAc),
        (Some(a), Some(k)) if (a == 3) != (k == Kinematics::Xyz) => {
            diags.push(message::machine::kinematics_mismatch(
                k.word(),
                a,
                kin_span,
                f.span(&AXES),
            ));
            None
        }
        (_, k) => k,
    };
    (axes, kin)
}

/// The dialect's lines and numbers the block overrides, each checked;
/// whether every line is one a control can read.
fn overrides(f: &Fields<'_>, d: &mut Dialect, diags: &mut Diagnostics) -> bool {
    let mut text_ok = true;
    for (field, slot) in [
        (&LASER_ON, &mut d.laser_on),
        (&LASER_OFF, &mut d.laser_off),
        (&TCP_ON, &mut d.tcp_on),
        (&TCP_OFF, &mut d.tcp_off),
        (&DWELL, &mut d.dwell),
    ] {
        if let Some((t, span)) = f.text(field, diags) {
            let key = field.key;
            let ok = if std::ptr::eq(field, &LASER_ON) || std::ptr::eq(field, &LASER_OFF) {
                program_text::switch(&t, key, span, diags)
            } else if std::ptr::eq(field, &DWELL) {
                program_text::dwell(&t, span, diags)
            } else {
                program_text::line(&t, key, span, diags)
            };
            if ok {
                *slot = t;
            } else {
                text_ok = false;
            }
        }
    }
    // S words are plain numbers on the control: `s_per_watt` is how many S
    // units one watt is (1 when S is programmed in W).
    if let Some((s, _)) = f.quantity(&S_PER_WATT, diags) {
        d.s_per_watt = s;
    }
    if let Some((u, _)) = f.word(&FEED_UNITS, diags) {
        d.feed = if u == "mm_per_s" {
            FeedUnit::MmPerS
        } else {
            FeedUnit::MmPerMin
        };
    }
    if let Some((n, _)) = f.count(&S_DECIMALS, diags) {
        d.s_decimals = n;
    }
    for field in [&PREAMBLE, &POSTAMBLE] {
        text_ok &= program_lines(f, field, d, diags);
    }
    text_ok
}

/// `preamble = […]` or `postamble = […]` (`field`), into the dialect when
/// right: a text or list of texts, each a line a control can read, a
/// postamble ending the program.
fn program_lines(f: &Fields<'_>, field: &Field, d: &mut Dialect, diags: &mut Diagnostics) -> bool {
    let Some(v) = f.value(field, diags) else {
        return true;
    };
    let key = field.key;
    let items: Vec<&_> = match &v.value {
        Value::List(items) => items.iter().collect(),
        _ => vec![v],
    };
    let lines = items
        .iter()
        .map(|i| match &i.value {
            Value::Str(s) => Some((s.clone(), i.span)),
            _ => None,
        })
        .collect::<Option<Vec<_>>>();
    let Some(lines) = lines else {
        diags.push(message::machine::lines_not_texts(key, v.span));
        return true;
    };
    let ok = lines
        .iter()
        .filter(|(t, span)| !program_text::line(t, key, *span, diags))
        .count()
        == 0;
    let lines: Vec<String> = lines.into_iter().map(|(t, _)| t).collect();
    if std::ptr::eq(field, &PREAMBLE) {
        d.preamble = lines;
        return ok;
    }
    let ends = program_text::ends_program(&lines);
    if !ends {
        diags.push(message::machine::postamble_without_end(v.span));
    }
    d.postamble = lines;
    ok && ends
}

/// The travel when `limits { … }` does not say.
const DEFAULT_LIMITS: AxisLimits = AxisLimits {
    x: [-1000.0, 1000.0],
    y: [-1000.0, 1000.0],
    z: [-1000.0, 1000.0],
    tilt: [-110.0, 110.0],
    rotary: [-360.0, 360.0],
};

/// `limits { … }` of a CNC whose kinematics is `kin`: the linear axes, and
/// the tilt axis its head has (`a` or `b`) and C; `None` when a range is
/// wrong or names an axis the head lacks.
fn axis_limits(
    l: &Fields<'_>,
    kin: Option<Kinematics>,
    diags: &mut Diagnostics,
) -> Option<AxisLimits> {
    let mut lim = DEFAULT_LIMITS;
    let mut ok = true;
    for (field, slot) in [
        (&limits::X, &mut lim.x),
        (&limits::Y, &mut lim.y),
        (&limits::Z, &mut lim.z),
    ] {
        match l.range(field, diags) {
            Some((r, _)) => *slot = r,
            None => ok &= !l.has(field),
        }
    }
    let (tilt, other) = if kin.and_then(Kinematics::tilt_letter) == Some('B') {
        (&limits::B, &limits::A)
    } else {
        (&limits::A, &limits::B)
    };
    if kin == Some(Kinematics::Xyz) {
        // A vertical nozzle: no rotary axis to bound.
        for field in [&limits::A, &limits::B, &limits::C] {
            if let Some(s) = l.span(field) {
                diags.push(message::machine::no_rotary_axes(field.key, s));
                ok = false;
            }
        }
    } else if let Some(s) = l.span(other) {
        diags.push(message::machine::no_such_head_axis(other.key, tilt.key, s));
        ok = false;
    }
    for (field, slot) in [(tilt, &mut lim.tilt), (&limits::C, &mut lim.rotary)] {
        match l.range(field, diags) {
            Some((r, _)) => *slot = [r[0].to_degrees(), r[1].to_degrees()],
            None => ok &= !l.has(field),
        }
    }
    ok.then_some(lim)
}

/// `work_offset = 1` (G54 … 6: G59) and `origin = [x, y, z]`: where the part
/// sits on the machine.
fn placement(f: &Fields<'_>, diags: &mut Diagnostics) -> Option<Placement> {
    let offset = f.count(&WORK_OFFSET, diags).map(|(n, _)| n as u8);
    let offset = f.or_default(&WORK_OFFSET, offset, 0);
    let origin = match f.value(&ORIGIN, diags) {
        None if f.has(&ORIGIN) => None,
        None => Some([0.0; 3]),
        Some(v) => match &v.value {
            Value::List(items) if items.len() == 3 => xyz(items, diags),
            other => {
                diags.push(message::machine::origin_not_a_point(
                    v.span,
                    &other.describe(),
                ));
                None
            }
        },
    };
    Some(Placement {
        work_offset: offset?,
        origin: origin?,
    })
}
