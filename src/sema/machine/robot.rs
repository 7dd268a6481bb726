//! `machine NAME { kind = robot … }`: a KUKA robot, programmed in KRL.

use super::{common, height_sensor, motion, Written};
use crate::diag::message::words::Words;
use crate::diag::{message, Diagnostics};
use crate::ir::{Arm, Controller, FrameRef, Machine, Pose, Robot, Signal, Spin, ToolAxis};
use crate::sema::eval::Env;
use crate::sema::fields::{self, Fields};
use crate::sema::machine::cell;
use crate::sema::schema::machine::ARM_LINKS;
use crate::sema::schema::machine::{
    frame, opw, ARM, BASE, BEAM, CLEARANCE, CONTROLLER, FRAME, FULL_SCALE, HOME, JOINT_MARGIN,
    KIND, LASER, MAX_ANGLE_DEG, MAX_FRAME_MM, MAX_SPEED, MODULE_LINES, OPW, POSITIONER_BLOCK,
    POWER_OUTPUT, ROBOT, SINGULARITY, SPIN, TOOL,
};
use crate::sema::schema::Field;
use crate::sema::value::Value;
use crate::span::Span;
use crate::syntax::ast::Stmt;
use crate::target::kuka;
use crate::units::Power;

/// Reads a robot's block: the robot, and where its fields are written.
pub(super) fn read<'a>(
    env: &mut Env<'a>,
    name: &str,
    stmts: &'a [Stmt],
    span: Span,
    diags: &mut Diagnostics,
) -> Option<(Machine, Written)> {
    let f = Fields::block(env, stmts, &ROBOT, format!("robot `{name}`"), span, diags);
    let mut at: Written = f.written().collect();
    let controller = f.word_or_default(&CONTROLLER, diags).map(|c| match c {
        "abb" => Controller::Abb,
        _ => Controller::Kuka,
    });
    let naming = match controller {
        Some(Controller::Abb) => cell::Naming::Abb,
        _ => cell::Naming::Kuka,
    };
    let r = robot(name, &f, (controller, naming), diags);
    let taken: Vec<_> = r
        .iter()
        .flat_map(|r| {
            [
                (r.laser_out.clone(), false, "the laser", f.span(&LASER)),
                (
                    r.power_out.clone(),
                    true,
                    "the laser power",
                    f.span(&POWER_OUTPUT),
                ),
            ]
        })
        .collect();
    let outputs = (crate::target::outputs::KUKA, naming);
    let c = cell::read(env, &f, outputs, None, &taken, diags);
    let positioner = super::positioner::read(env, &f, &mut at, diags);
    let head = super::head::read(env, &f, name, &mut at, diags);
    let (mut r, c, positioner, head) = (r?, c?, positioner?, head?);
    if let (Some(_), None) = (&positioner, r.base.value) {
        let block = f.span(&POSITIONER_BLOCK).unwrap_or(span);
        diags.push(message::positioner::needs_base(block, f.span(&BASE)));
        return None;
    }
    at.extend(c.spans);
    r.common.cell = c.cell;
    r.common.head = head;
    r.positioner = positioner.map(Box::new);
    Some((Machine::Robot(r), at))
}

fn robot(
    name: &str,
    f: &Fields<'_>,
    (controller, naming): (Option<Controller>, cell::Naming),
    diags: &mut Diagnostics,
) -> Option<Robot> {
    let tool = frame_ref(f, &TOOL, diags);
    let load = super::load::read(f, diags);
    let base = frame_ref(f, &BASE, diags);
    let beam = f.word_or_default(&BEAM, diags).map(|b| match b {
        "x" => ToolAxis::PlusX,
        "-x" => ToolAxis::MinusX,
        "y" => ToolAxis::PlusY,
        "-y" => ToolAxis::MinusY,
        "-z" => ToolAxis::MinusZ,
        _ => ToolAxis::PlusZ,
    });
    let outs = crate::target::outputs::KUKA;
    let laser = cell::signal(f, &LASER, outs.digital, naming, diags);
    let anout = cell::signal(f, &POWER_OUTPUT, outs.analog, naming, diags);
    // Numbered, the two are `do<n>` and `ao<n>`: named, they must differ.
    let anout = match (&laser, anout) {
        (Some((l @ Signal::Name(a), on)), Some((Signal::Name(b), at)))
            if a.eq_ignore_ascii_case(&b) =>
        {
            let d = message::machine::output_clash(
                "the laser power",
                "the laser",
                (true, l),
                at,
                Some(*on),
            );
            diags.push(d);
            None
        }
        (_, anout) => anout,
    };
    let full = f.quantity(&FULL_SCALE, diags);
    let top = match controller {
        Some(Controller::Abb) => crate::target::rapid::V_TCP_MAX,
        _ => kuka::VEL_CP_MAX,
    };
    let vmax = f.quantity(&MAX_SPEED, diags).and_then(|(v, span)| {
        if v <= top {
            return Some((v, span));
        }
        diags.push(message::machine::robot_speed_too_high(v, span, top));
        None
    });
    let clearance = f.quantity_or_default(&CLEARANCE, diags);
    let lines = f.count_or_default(&MODULE_LINES, diags);
    let home = home(f, controller, diags);
    let arm = controller.and_then(|c| arm(f, c, diags));
    let spin = spin(f, diags);
    let moves = motion(f, diags);
    let sensor = height_sensor(f, 1, kuka::MAX_ANIN, diags);
    if controller == Some(Controller::Abb) {
        abb_frames(f, tool.as_ref(), base.as_ref(), load.as_ref(), diags);
    } else if let (Some(None), Some(t)) = (&load, &tool) {
        // The tool whose load data it is, or the robot's `kind = robot`.
        let written = f.span(&TOOL);
        let at = written.or(f.span(&KIND)).unwrap_or(f.block_span());
        diags.push(message::load::unchecked(
            name,
            t.index,
            at,
            written.is_some(),
        ));
    }
    Some(Robot {
        common: common(name, vmax.map(|v| v.0), clearance, sensor, moves)?,
        controller: controller?,
        tool: tool?,
        load: load?,
        base: base?,
        beam: beam?,
        laser_out: laser?.0,
        power_out: anout?.0,
        full_scale_power: Power(full?.0).watts(),
        home: home?,
        max_points_per_module: lines?,
        arm: arm?.map(Box::new),
        spin: spin?,
        positioner: None,
    })
}

/// An ABB robot's program declares its `tooldata` and `wobjdata` in full
/// (RAPID has no numbered tables to fall back on, and a `tooldata` holds
/// its load): a tool, base or load left to the controller is refused.
fn abb_frames(
    f: &Fields<'_>,
    tool: Option<&FrameRef>,
    base: Option<&FrameRef>,
    load: Option<&Option<crate::ir::Load>>,
    diags: &mut Diagnostics,
) {
    let at = |field: &Field| {
        f.span(field)
            .or(f.span(&CONTROLLER))
            .unwrap_or(f.block_span())
    };
    if let Some(FrameRef { value: None, .. }) = tool {
        diags.push(message::machine::abb_needs(
            "tool",
            at(&TOOL),
            "`tool = frame(1, z = 350 mm)`: the laser focus from the flange, which the program's `tooldata` holds",
        ));
    }
    if let Some(FrameRef { value: None, .. }) = base {
        diags.push(message::machine::abb_needs(
            "base",
            at(&BASE),
            "`base = frame(1, x = 1200 mm, y = 0 mm, z = 400 mm)`: where the part's origin sits from the robot's base frame, which the program's `wobjdata` holds",
        ));
    }
    if let Some(None) = load {
        diags.push(message::machine::abb_needs(
            "load",
            at(&TOOL),
            "`load = load(mass = 12 kg, cog = [0 mm, 0 mm, 120 mm])`: the mass of all the flange carries and its centre of gravity, which the program's `tooldata` holds (ABB's controller refuses a tool without mass)",
        ));
    }
}

/// `spin = auto | angle`.
fn spin(f: &Fields<'_>, diags: &mut Diagnostics) -> Option<Spin> {
    match f.value(&SPIN, diags) {
        None if f.has(&SPIN) => None,
        None => Some(Spin::default()),
        Some(v) if v.value == Value::Symbol("auto".into()) => Some(Spin::default()),
        Some(_) => f.quantity(&SPIN, diags).map(|(a, _)| Spin::Declared {
            deg: a.to_degrees(),
        }),
    }
}

/// `arm = …` with `joint_margin` and `singularity`: `Some(None)` when no arm
/// is declared. An arm whose `base` or `tool` is only an index on the
/// controller cannot be checked: a warning says how to declare them.
fn arm(f: &Fields<'_>, controller: Controller, diags: &mut Diagnostics) -> Option<Option<Arm>> {
    let margin = f.quantity_or_default(&JOINT_MARGIN, diags);
    let singularity = f.quantity_or_default(&SINGULARITY, diags);
    let v = match f.value(&ARM, diags) {
        None if f.has(&ARM) => return None,
        None => return Some(None),
        Some(v) => v,
    };
    let (margin, singularity) = (margin?.to_degrees(), singularity?.to_degrees());
    let mut arm = match &v.value {
        Value::Call(c) if c.func == "opw" => {
            opw_arm(&Fields::call(c, &OPW, diags), controller, diags)?
        }
        _ => {
            let word = fields::word(v, ARM.key, crate::target::arm::KEYS, diags)?;
            let model = crate::target::arm::model(word)?;
            if maker(controller) != model.maker {
                let at = f.span(&CONTROLLER).or(f.span(&KIND));
                diags.push(message::machine::arm_of_other_maker(
                    model.name,
                    controller == Controller::Abb,
                    v.span,
                    at,
                ));
                return None;
            }
            model.arm(0.0, 0.0)
        }
    };
    arm.margin = margin;
    arm.singularity = singularity;
    if let Some(v) = f.value(&ARM_LINKS, diags) {
        arm.links = Some(links(v, diags)?);
    } else if f.has(&ARM_LINKS) {
        return None;
    }
    for (field, what) in [(&BASE, "base"), (&TOOL, "tool")] {
        let declared = f
            .value(field, &mut Diagnostics::default())
            .is_some_and(|v| matches!(&v.value, Value::Call(c) if c.func == "frame"));
        if !declared {
            diags.push(message::machine::arm_unchecked(
                what,
                f.span(field).unwrap_or(v.span),
                v.span,
            ));
        }
    }
    Some(Some(arm))
}

/// `arm_links = [r, r, r]`: three lengths above zero, mm.
fn links(v: &super::super::value::Spanned, diags: &mut Diagnostics) -> Option<[f64; 3]> {
    let items = match &v.value {
        Value::List(items) if items.len() == 3 => items,
        _ => {
            diags.push(message::collision::not_three_links(
                v.span,
                &v.value.describe(),
            ));
            return None;
        }
    };
    let mut out = [0.0; 3];
    let mut ok = true;
    for (o, it) in out.iter_mut().zip(items) {
        match fields::quantity(it, crate::units::Dim::LENGTH, ARM_LINKS.key, diags) {
            Some(r) if r > 0.0 => *o = r,
            Some(_) => {
                diags.push(message::collision::not_three_links(
                    it.span,
                    "a length not above zero",
                ));
                ok = false;
            }
            None => ok = false,
        }
    }
    ok.then_some(out)
}

/// The maker whose arms a controller drives.
fn maker(c: Controller) -> crate::target::arm::Maker {
    match c {
        Controller::Kuka => crate::target::arm::Maker::Kuka,
        Controller::Abb => crate::target::arm::Maker::Abb,
    }
}

/// `opw(…)`: an arm by its parameters, in the controller's axis angles.
fn opw_arm(a: &Fields<'_>, controller: Controller, diags: &mut Diagnostics) -> Option<Arm> {
    let words = Words::of(controller);
    let len = |field: &Field, diags: &mut Diagnostics| match field.need {
        crate::sema::schema::Need::Required(_) => a.quantity(field, diags).map(|q| q.0),
        _ => a.quantity_or_default(field, diags),
    };
    let ps = [
        len(&opw::A1, diags),
        len(&opw::A2, diags),
        len(&opw::B, diags),
        len(&opw::C1, diags),
        len(&opw::C2, diags),
        len(&opw::C3, diags),
        len(&opw::C4, diags),
    ];
    let limits = six(a, &opw::LIMITS, words, diags, |it, diags| match &it.value {
        Value::Range(lo, hi) if lo.dim == crate::units::Dim::ANGLE && lo.value < hi.value => {
            Some([lo.value.to_degrees(), hi.value.to_degrees()])
        }
        _ => {
            diags.push(message::machine::arm_list_item(
                (opw::LIMITS.key, words),
                it.span,
                &it.value.describe(),
                "a range of angles, low first: `-185 deg .. 185 deg`",
            ));
            None
        }
    });
    let speeds = six(
        a,
        &opw::SPEEDS,
        words,
        diags,
        |it, diags| match fields::quantity(
            it,
            crate::units::Dim::ANGULAR_SPEED,
            opw::SPEEDS.key,
            diags,
        ) {
            Some(x) if x > 0.0 => Some(x.to_degrees()),
            Some(_) => {
                diags.push(message::machine::arm_list_item(
                    (opw::SPEEDS.key, words),
                    it.span,
                    &it.value.describe(),
                    "a speed above zero: `156 deg/s`",
                ));
                None
            }
            None => None,
        },
    );
    let mut opw = [0.0; 7];
    for (o, p) in opw.iter_mut().zip(ps) {
        *o = p?;
    }
    // The axis angles are the controller's own: KUKA's or ABB's convention.
    let k = match controller {
        Controller::Kuka => crate::target::arm::KUKA,
        Controller::Abb => crate::target::arm::ABB,
    };
    Some(Arm {
        model: None,
        opw,
        offsets: k.offsets,
        signs: k.signs,
        limits: limits?,
        speeds: speeds?,
        margin: 0.0,
        singularity: 0.0,
        links: None,
        column: None,
    })
}

/// A list of six items of `field`, each read by `item`.
fn six<T: Copy + Default>(
    a: &Fields<'_>,
    field: &Field,
    words: Words,
    diags: &mut Diagnostics,
    item: impl Fn(&crate::sema::value::Spanned, &mut Diagnostics) -> Option<T>,
) -> Option<[T; 6]> {
    let v = a.value(field, diags)?;
    let items = match &v.value {
        Value::List(items) if items.len() == 6 => items,
        other => {
            diags.push(message::machine::arm_list_not_six(
                (field.key, words),
                v.span,
                &other.describe(),
            ));
            return None;
        }
    };
    let mut out = [T::default(); 6];
    let mut ok = true;
    for (o, it) in out.iter_mut().zip(items) {
        match item(it, diags) {
            Some(x) => *o = x,
            None => ok = false,
        }
    }
    ok.then_some(out)
}

/// `tool = …` or `base = …` (`field`): an index into the controller's
/// table, or `frame(index, …)` with the value the program sets.
fn frame_ref(f: &Fields<'_>, field: &Field, diags: &mut Diagnostics) -> Option<FrameRef> {
    let v = match f.value(field, diags) {
        None if f.has(field) => return None,
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
            let a = Fields::call(c, &FRAME, diags);
            let index = a.count(&frame::INDEX, diags);
            let mut g = |field: &Field| {
                let angle = field.kind.dim() == Some(crate::units::Dim::ANGLE);
                let out = |v: f64, at| {
                    let shown = if angle { v.to_degrees() } else { v };
                    message::machine::frame_out_of_range(
                        field.key,
                        shown,
                        angle,
                        at,
                        MAX_FRAME_MM,
                        MAX_ANGLE_DEG,
                    )
                };
                a.bounded_or_default(field, out, diags)
            };
            let (x, y, z) = (g(&frame::X), g(&frame::Y), g(&frame::Z));
            let (aa, b, c) = (g(&frame::A), g(&frame::B), g(&frame::C));
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
            let Some((lo, hi)) = field.kind.count() else {
                unreachable!("`{}` takes an index", field.key)
            };
            let n = fields::count(v, field.key, lo, hi, diags)?;
            Some(FrameRef {
                index: n as u16,
                value: None,
            })
        }
    }
}

/// `home = [a1, …, a6]`: six axis angles, deg.
fn home(
    f: &Fields<'_>,
    controller: Option<Controller>,
    diags: &mut Diagnostics,
) -> Option<[f64; 6]> {
    let v = match f.value(&HOME, diags) {
        None if f.has(&HOME) => return None,
        None if controller == Some(Controller::Abb) => {
            return Some([0.0, 0.0, 0.0, 0.0, 90.0, 0.0])
        }
        None => return Some([0.0, -90.0, 90.0, 0.0, 0.0, 0.0]),
        Some(v) => v,
    };
    let words = Words::of(controller.unwrap_or_default());
    let Value::List(items) = &v.value else {
        diags.push(message::machine::home_not_six_angles(
            v.span,
            &v.value.describe(),
            words,
        ));
        return None;
    };
    if items.len() != 6 {
        diags.push(message::machine::home_not_six_angles(
            v.span,
            &v.value.describe(),
            words,
        ));
        return None;
    }
    let mut out = [0.0; 6];
    let mut ok = true;
    for (i, it) in items.iter().enumerate() {
        match fields::quantity(it, crate::units::Dim::ANGLE, HOME.key, diags) {
            Some(a) if a.to_degrees().abs() <= MAX_ANGLE_DEG => out[i] = a.to_degrees(),
            Some(a) => {
                diags.push(message::machine::home_axis_out_of_range(
                    (i, words),
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
