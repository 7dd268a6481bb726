//! `machine NAME { kind = robot | cnc, … }`: the cells lmdc writes programs for.
//! A machine is plain data, so the checked declaration is already the IR's
//! [`Machine`].

use super::cell;
use super::eval::Env;
use super::fields::{self, Fields};
use super::program_text;
use super::value::Value;
use crate::diag::{message, Diagnostics};
use crate::ir::{
    AxisLimits, Cnc, FeedUnit, FrameRef, HeightSensor, Kinematics, Machine, Placement, Pose, Robot,
    ToolAxis,
};
use crate::span::Span;
use crate::syntax::ast::{Body, Stmt};
use crate::target::gcode as dialect;
use crate::target::kuka;
use crate::units::{Dim, Power};

use crate::target::kuka::VEL_CP_MAX as ROBOT_VEL_CP_MAX;

/// Largest angle a robot axis or frame is declared with, deg.
const MAX_ANGLE_DEG: f64 = 360.0;
/// Largest frame offset, mm: beyond any cell.
const MAX_FRAME_MM: f64 = 100_000.0;

const ROBOT_FIELDS: &[&str] = &[
    "kind",
    "tool",
    "base",
    "beam",
    "laser",
    "power_output",
    "full_scale",
    "max_speed",
    "home",
    "clearance",
    "module_lines",
    "height_input",
    "height_full_scale",
    "height_delay",
];

const CNC_FIELDS: &[&str] = &[
    "kind",
    "axes",
    "kinematics",
    "dialect",
    "laser_on",
    "laser_off",
    "s_per_watt",
    "s_decimals",
    "preamble",
    "postamble",
    "tcp_on",
    "tcp_off",
    "dwell",
    "work_offset",
    "origin",
    "feed_units",
    "max_speed",
    "clearance",
    "output_on",
    "output_off",
    "analog_output",
    "height_input",
    "height_full_scale",
    "height_delay",
];

/// Blocks a robot takes.
const ROBOT_BLOCKS: &[&str] = &["gas", "powder"];
/// Blocks a CNC takes.
const CNC_BLOCKS: &[&str] = &["limits", "gas", "powder"];

/// Axes a CNC's `limits { … }` block may bound.
const LIMIT_AXES: &[&str] = &["x", "y", "z", "a", "b", "c"];

/// Where each field the checks refer to is written, by name (`limits.x`, the
/// tilt axis' limit as `limits.tilt`).
fn spans(f: &Fields<'_>, keys: &[&str], prefix: &str, out: &mut Vec<(String, Span)>) {
    for k in keys {
        if let Some(s) = f.span(k) {
            let name = match *k {
                "a" | "b" => "tilt",
                k => k,
            };
            out.push((format!("{prefix}{name}"), s));
        }
    }
}

/// Reads a machine block: the machine, and where its fields are written.
pub fn read<'a>(
    env: &mut Env<'a>,
    name: &str,
    stmts: &'a [Stmt],
    span: Span,
    diags: &mut Diagnostics,
) -> Option<(Machine, Vec<(String, Span)>)> {
    let kind_stmt = stmts.iter().find(|s| s.kind.node == "kind");
    let kind = match kind_stmt.map(|s| &s.body) {
        // Evaluated quietly: reading the block below reports its errors.
        Some(Body::Assign(e)) => env
            .eval(e, &mut Diagnostics::new())
            .and_then(|v| fields::symbol(&v, "kind", &["robot", "cnc"], diags)),
        Some(_) => None,
        None => {
            diags.push(message::machine::missing_kind(name, span));
            None
        }
    };
    let Some(kind) = kind else {
        // Which fields a machine has depends on its kind; without one, each
        // field is checked against what either kind takes, so a misspelt
        // field shows in the same run as the kind.
        let mut all = ROBOT_FIELDS.to_vec();
        all.extend(CNC_FIELDS.iter().filter(|k| !ROBOT_FIELDS.contains(k)));
        let f = Fields::block(
            env,
            stmts,
            &all,
            CNC_BLOCKS,
            format!("machine `{name}`"),
            span,
            diags,
        );
        if let Some((inner, ls)) = f.nested("limits") {
            Fields::block(env, inner, LIMIT_AXES, &[], "limits".into(), ls, diags);
        }
        return None;
    };
    if kind == "robot" {
        let f = Fields::block(
            env,
            stmts,
            ROBOT_FIELDS,
            ROBOT_BLOCKS,
            format!("robot `{name}`"),
            span,
            diags,
        );
        let mut at = Vec::new();
        spans(&f, ROBOT_FIELDS, "", &mut at);
        let r = robot(name, &f, diags);
        let taken: Vec<_> = r
            .iter()
            .flat_map(|r| {
                [
                    (r.laser_out as usize, false, "the laser", f.span("laser")),
                    (
                        r.power_out as usize,
                        true,
                        "the laser power",
                        f.span("power_output"),
                    ),
                ]
            })
            .collect();
        let c = cell::read(env, &f, cell::KUKA, None, &taken, diags);
        let (mut r, c) = (r?, c?);
        at.extend(c.spans);
        r.cell = c.cell;
        Some((Machine::Robot(r), at))
    } else {
        let f = Fields::block(
            env,
            stmts,
            CNC_FIELDS,
            CNC_BLOCKS,
            format!("CNC `{name}`"),
            span,
            diags,
        );
        let limits = match f.nested("limits") {
            Some((inner, ls)) => {
                let l = Fields::block(env, inner, LIMIT_AXES, &[], "limits".into(), ls, diags);
                Some(l)
            }
            None => None,
        };
        let mut at = Vec::new();
        spans(&f, CNC_FIELDS, "", &mut at);
        if let Some(l) = &limits {
            spans(l, LIMIT_AXES, "limits.", &mut at);
        }
        let c = cnc(name, &f, limits.as_ref(), diags);
        let profile = c
            .as_ref()
            .map_or("linuxcnc", |c| c.dialect.profile.as_str())
            .to_string();
        let outputs = if profile == "linuxcnc" {
            cell::LINUXCNC
        } else {
            cell::OTHER_CNC
        };
        let lines = cell::cnc_lines(&f, &profile, diags);
        let cell = cell::read(env, &f, outputs, lines.clone(), &[], diags);
        let (mut c, cell) = (c?, cell?);
        lines?;
        at.extend(cell.spans);
        c.cell = cell.cell;
        Some((Machine::Cnc(c), at))
    }
}

fn frame_ref(f: &Fields<'_>, key: &str, diags: &mut Diagnostics) -> Option<FrameRef> {
    let v = f.value(key, None, diags);
    let v = match v {
        None if f.has(key) => return None,
        None => {
            return Some(FrameRef {
                index: 1,
                value: None,
            })
        }
        Some(v) => v,
    };
    match &v.value {
        Value::Call(c) if c.func == "frame" => {
            let a = Fields::call(
                c,
                &["index"],
                &["index", "x", "y", "z", "a", "b", "c"],
                diags,
            );
            let index = a.count("index", 1, 32, Some("1"), diags);
            let mut g = |k: &str, d: Dim| {
                let limit = if d == Dim::ANGLE {
                    MAX_ANGLE_DEG.to_radians()
                } else {
                    MAX_FRAME_MM
                };
                match a.quantity(k, d, None, diags) {
                    Some((v, span)) if v.abs() > limit => {
                        let angle = d == Dim::ANGLE;
                        let shown = if angle { v.to_degrees() } else { v };
                        diags.push(message::machine::frame_out_of_range(
                            k,
                            shown,
                            angle,
                            span,
                            MAX_FRAME_MM,
                            MAX_ANGLE_DEG,
                        ));
                        None
                    }
                    Some((v, _)) => Some(v),
                    None if a.has(k) => None,
                    None => Some(0.0),
                }
            };
            let (x, y, z) = (
                g("x", Dim::LENGTH),
                g("y", Dim::LENGTH),
                g("z", Dim::LENGTH),
            );
            let (aa, b, c) = (g("a", Dim::ANGLE), g("b", Dim::ANGLE), g("c", Dim::ANGLE));
            Some(FrameRef {
                index: index?.0 as u16,
                value: Some(Pose {
                    x: x?,
                    y: y?,
                    z: z?,
                    a: aa?.to_degrees(),
                    b: b?.to_degrees(),
                    c: c?.to_degrees(),
                }),
            })
        }
        _ => {
            let n = fields::count(v, key, 1, 32, diags)?;
            Some(FrameRef {
                index: n as u16,
                value: None,
            })
        }
    }
}

fn or_default<T>(f: &Fields<'_>, key: &str, got: Option<T>, default: T) -> Option<T> {
    match got {
        Some(x) => Some(x),
        None if f.has(key) => None,
        None => Some(default),
    }
}

fn robot(name: &str, f: &Fields<'_>, diags: &mut Diagnostics) -> Option<Robot> {
    let tool = frame_ref(f, "tool", diags);
    let base = frame_ref(f, "base", diags);
    let beam = f.symbol("beam", &["x", "-x", "y", "-y", "z", "-z"], None, diags);
    let beam = or_default(
        f,
        "beam",
        beam.map(|(b, _)| match b.as_str() {
            "x" => ToolAxis::PlusX,
            "-x" => ToolAxis::MinusX,
            "y" => ToolAxis::PlusY,
            "-y" => ToolAxis::MinusY,
            "-z" => ToolAxis::MinusZ,
            _ => ToolAxis::PlusZ,
        }),
        ToolAxis::PlusZ,
    );
    let laser = f.count("laser", 1, 4096, Some("1"), diags);
    let anout = f.count("power_output", 1, 32, Some("1"), diags);
    let full = f.positive("full_scale", Dim::POWER, Some("4000 W"), diags);
    let vmax = f
        .positive("max_speed", Dim::SPEED, Some("250 mm/s"), diags)
        .and_then(|(v, span)| {
            if v <= ROBOT_VEL_CP_MAX {
                return Some((v, span));
            }
            diags.push(message::machine::robot_speed_too_high(
                v,
                span,
                ROBOT_VEL_CP_MAX,
            ));
            None
        });
    let clearance = f
        .positive("clearance", Dim::LENGTH, None, diags)
        .map(|c| c.0);
    let clearance = or_default(f, "clearance", clearance, 10.0);
    let lines = f
        .count("module_lines", 10, 100_000, None, diags)
        .map(|c| c.0);
    let lines = or_default(f, "module_lines", lines, 2000);
    let home = match f.value("home", None, diags) {
        None if f.has("home") => None,
        None => Some([0.0, -90.0, 90.0, 0.0, 0.0, 0.0]),
        Some(v) => match &v.value {
            Value::List(items) if items.len() == 6 => {
                let mut out = [0.0; 6];
                let mut ok = true;
                for (i, it) in items.iter().enumerate() {
                    match fields::quantity(it, Dim::ANGLE, "home", diags) {
                        Some(a) if a.to_degrees().abs() <= MAX_ANGLE_DEG => out[i] = a.to_degrees(),
                        Some(a) => {
                            diags.push(message::machine::home_axis_out_of_range(
                                i + 1,
                                a.to_degrees(),
                                it.span,
                                MAX_ANGLE_DEG,
                            ));
                            ok = false;
                        }
                        None => ok = false,
                    }
                }
                ok.then_some(out)
            }
            other => {
                diags.push(message::machine::home_not_six_angles(
                    v.span,
                    &other.describe(),
                ));
                None
            }
        },
    };
    let sensor = height_sensor(f, 1, kuka::MAX_ANIN, diags);
    Some(Robot {
        height_sensor: sensor?,
        name: name.to_string(),
        tool: tool?,
        base: base?,
        beam: beam?,
        laser_out: laser?.0 as u16,
        power_out: anout?.0 as u16,
        full_scale_power: Power(full?.0).watts(),
        max_speed: vmax?.0,
        home: home?,
        max_points_per_module: lines?,
        clearance: clearance?,
        cell: Default::default(),
    })
}

fn cnc(
    name: &str,
    f: &Fields<'_>,
    limits: Option<&Fields<'_>>,
    diags: &mut Diagnostics,
) -> Option<Cnc> {
    let axes = f.count("axes", 3, 5, Some("5"), diags);
    let axes = match axes {
        Some((4, s)) => {
            diags.push(message::machine::four_axes(s));
            None
        }
        a => a.map(|a| a.0 as u8),
    };
    let kin = f.symbol("kinematics", &["xyz", "head_ac", "head_bc"], None, diags);
    let kin_span = kin.as_ref().map(|k| k.1);
    let kin = kin.map(|(k, _)| match k.as_str() {
        "head_ac" => Kinematics::HeadAc,
        "head_bc" => Kinematics::HeadBc,
        _ => Kinematics::Xyz,
    });
    let kin = match (axes, kin) {
        (Some(3), None) if !f.has("kinematics") => Some(Kinematics::Xyz),
        (Some(5), None) if !f.has("kinematics") => Some(Kinematics::HeadAc),
        (Some(a), Some(k)) if (a == 3) != (k == Kinematics::Xyz) => {
            diags.push(message::machine::kinematics_mismatch(
                kin_name(k),
                a,
                kin_span,
                f.span("axes"),
            ));
            None
        }
        (_, k) => k,
    };
    let profile = f.symbol("dialect", dialect::PROFILES, None, diags);
    let mut d = match profile {
        Some((p, _)) => dialect::profile(&p),
        None if f.has("dialect") => None,
        None => dialect::profile("linuxcnc"),
    };
    let mut text_ok = true;
    if let Some(d) = d.as_mut() {
        for (key, slot) in [
            ("laser_on", &mut d.laser_on),
            ("laser_off", &mut d.laser_off),
            ("tcp_on", &mut d.tcp_on),
            ("tcp_off", &mut d.tcp_off),
            ("dwell", &mut d.dwell),
        ] {
            if let Some((t, span)) = f.text(key, None, diags) {
                let ok = match key {
                    "laser_on" | "laser_off" => program_text::switch(&t, key, span, diags),
                    "dwell" => program_text::dwell(&t, span, diags),
                    _ => program_text::line(&t, key, span, diags),
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
        if let Some((s, _)) = f.positive("s_per_watt", Dim::NONE, None, diags) {
            d.s_per_watt = s;
        }
        if let Some((u, _)) = f.symbol("feed_units", &["mm_per_min", "mm_per_s"], None, diags) {
            d.feed = if u == "mm_per_s" {
                FeedUnit::MmPerS
            } else {
                FeedUnit::MmPerMin
            };
        }
        if let Some((n, _)) = f.count("s_decimals", 0, 4, None, diags) {
            d.s_decimals = n;
        }
        for key in ["preamble", "postamble"] {
            if let Some(v) = f.value(key, None, diags) {
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
                let lines = lines.map(|l| {
                    let ok = l
                        .iter()
                        .filter(|(t, span)| !program_text::line(t, key, *span, diags))
                        .count()
                        == 0;
                    text_ok &= ok;
                    l.into_iter().map(|(t, _)| t).collect::<Vec<_>>()
                });
                match lines {
                    Some(l) if key == "preamble" => d.preamble = l,
                    Some(l) => {
                        if !program_text::ends_program(&l) {
                            diags.push(message::machine::postamble_without_end(v.span));
                            text_ok = false;
                        }
                        d.postamble = l;
                    }
                    None => diags.push(message::machine::lines_not_texts(key, v.span)),
                }
            }
        }
    }
    let vmax = f.positive("max_speed", Dim::SPEED, Some("100 mm/s"), diags);
    let clearance = f
        .positive("clearance", Dim::LENGTH, None, diags)
        .map(|c| c.0);
    let clearance = or_default(f, "clearance", clearance, 10.0);
    let mut lim = AxisLimits {
        x: [-1000.0, 1000.0],
        y: [-1000.0, 1000.0],
        z: [-1000.0, 1000.0],
        tilt: [-110.0, 110.0],
        rotary: [-360.0, 360.0],
    };
    let mut ok = true;
    if let Some(l) = limits {
        for (key, dim, slot) in [
            ("x", Dim::LENGTH, &mut lim.x),
            ("y", Dim::LENGTH, &mut lim.y),
            ("z", Dim::LENGTH, &mut lim.z),
        ] {
            match l.range(key, dim, None, diags) {
                Some((r, _)) => *slot = r,
                None => ok &= !l.has(key),
            }
        }
        let tilt_key = if kin == Some(Kinematics::HeadBc) {
            "b"
        } else {
            "a"
        };
        let other = if tilt_key == "a" { "b" } else { "a" };
        if kin == Some(Kinematics::Xyz) {
            // A vertical nozzle: no rotary axis to bound.
            for key in ["a", "b", "c"] {
                if let Some(s) = l.span(key) {
                    diags.push(message::machine::no_rotary_axes(key, s));
                    ok = false;
                }
            }
        } else if let Some(s) = l.span(other) {
            diags.push(message::machine::no_such_head_axis(other, tilt_key, s));
            ok = false;
        }
        for (key, slot) in [(tilt_key, &mut lim.tilt), ("c", &mut lim.rotary)] {
            match l.range(key, Dim::ANGLE, None, diags) {
                Some((r, _)) => *slot = [r[0].to_degrees(), r[1].to_degrees()],
                None => ok &= !l.has(key),
            }
        }
    }
    let placement = placement(f, diags);
    let sensor = height_sensor(f, 0, dialect::MAX_ANALOG_INPUT, diags);
    if !ok || !text_ok {
        return None;
    }
    Some(Cnc {
        height_sensor: sensor?,
        name: name.to_string(),
        axes: axes?,
        kinematics: kin?,
        dialect: d?,
        limits: lim,
        placement: placement?,
        max_speed: vmax?.0,
        clearance: clearance?,
        cell: Default::default(),
    })
}

/// `work_offset = 1` (G54 … 6: G59) and `origin = [x, y, z]`: where the part
/// sits on the machine.
fn placement(f: &Fields<'_>, diags: &mut Diagnostics) -> Option<Placement> {
    let offset = f
        .count("work_offset", 1, 6, None, diags)
        .map(|(n, _)| n as u8);
    let offset = or_default(f, "work_offset", offset, 0);
    let origin = match f.value("origin", None, diags) {
        None if f.has("origin") => None,
        None => Some([0.0; 3]),
        Some(v) => match &v.value {
            Value::List(items) if items.len() == 3 => {
                let c: Vec<_> = ["x", "y", "z"]
                    .iter()
                    .zip(items)
                    .map(|(k, it)| fields::quantity(it, Dim::LENGTH, k, diags))
                    .collect();
                match c[..] {
                    [Some(x), Some(y), Some(z)] => Some([x, y, z]),
                    _ => None,
                }
            }
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

/// Longest delay of a height reading lmdc plans, s.
const MAX_SENSOR_DELAY_S: f64 = 10.0;

/// `height_input = n`, `height_full_scale = L`, `height_delay = t`: the
/// analog input a closed height loop reads (seed 004). `Some(None)` when the
/// machine declares none, `None` when a field is wrong (reported).
fn height_sensor(
    f: &Fields<'_>,
    lowest: usize,
    highest: usize,
    diags: &mut Diagnostics,
) -> Option<Option<HeightSensor>> {
    let input = f.count("height_input", lowest, highest, None, diags);
    let scale = f.positive("height_full_scale", Dim::LENGTH, None, diags);
    let delay = match f.quantity("height_delay", Dim::TIME, None, diags) {
        Some((t, _)) if (0.0..=MAX_SENSOR_DELAY_S).contains(&t) => Some(t),
        Some((t, at)) => {
            diags.push(message::field::time_out_of_range(
                "height_delay",
                t,
                MAX_SENSOR_DELAY_S,
                at,
            ));
            None
        }
        None if f.has("height_delay") => None,
        None => Some(0.0),
    };
    if input.is_none() && !f.has("height_input") {
        for key in ["height_full_scale", "height_delay"] {
            if let Some(at) = f.span(key) {
                diags.push(message::machine::sensor_without_input(key, at));
            }
        }
        return (!f.has("height_full_scale") && !f.has("height_delay")).then_some(None);
    }
    if input.is_some() && !f.has("height_full_scale") {
        diags.push(message::machine::sensor_without_full_scale(
            f.span("height_input"),
        ));
    }
    Some(Some(HeightSensor {
        input: input?.0 as u16,
        full_scale: scale?.0,
        delay: delay?,
    }))
}

fn kin_name(k: Kinematics) -> &'static str {
    match k {
        Kinematics::Xyz => "xyz",
        Kinematics::HeadAc => "head_ac",
        Kinematics::HeadBc => "head_bc",
    }
}
