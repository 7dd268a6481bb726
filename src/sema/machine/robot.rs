//! `machine NAME { kind = robot … }`: a KUKA robot, programmed in KRL.

use super::super::cell;
use super::super::eval::Env;
use super::super::fields::{self, Fields};
use super::super::schema::machine::{
    frame, BASE, BEAM, CLEARANCE, FRAME, FULL_SCALE, HOME, LASER, MAX_ANGLE_DEG, MAX_FRAME_MM,
    MAX_SPEED, MODULE_LINES, POWER_OUTPUT, ROBOT, TOOL,
};
use super::super::schema::Field;
use super::super::value::Value;
use super::{common, height_sensor, motion, Written};
use crate::diag::{message, Diagnostics};
use crate::ir::{FrameRef, Machine, Pose, Robot, ToolAxis};
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
    let r = robot(name, &f, diags);
    let taken: Vec<_> = r
        .iter()
        .flat_map(|r| {
            [
                (r.laser_out as usize, false, "the laser", f.span(&LASER)),
                (
                    r.power_out as usize,
                    true,
                    "the laser power",
                    f.span(&POWER_OUTPUT),
                ),
            ]
        })
        .collect();
    let c = cell::read(env, &f, cell::KUKA, None, &taken, diags);
    let (mut r, c) = (r?, c?);
    at.extend(c.spans);
    r.common.cell = c.cell;
    Some((Machine::Robot(r), at))
}

fn robot(name: &str, f: &Fields<'_>, diags: &mut Diagnostics) -> Option<Robot> {
    let tool = frame_ref(f, &TOOL, diags);
    let base = frame_ref(f, &BASE, diags);
    let beam = f.word_or_default(&BEAM, diags).map(|b| match b {
        "x" => ToolAxis::PlusX,
        "-x" => ToolAxis::MinusX,
        "y" => ToolAxis::PlusY,
        "-y" => ToolAxis::MinusY,
        "-z" => ToolAxis::MinusZ,
        _ => ToolAxis::PlusZ,
    });
    let laser = f.count(&LASER, diags);
    let anout = f.count(&POWER_OUTPUT, diags);
    let full = f.quantity(&FULL_SCALE, diags);
    let vmax = f.quantity(&MAX_SPEED, diags).and_then(|(v, span)| {
        if v <= kuka::VEL_CP_MAX {
            return Some((v, span));
        }
        diags.push(message::machine::robot_speed_too_high(
            v,
            span,
            kuka::VEL_CP_MAX,
        ));
        None
    });
    let clearance = f.quantity_or_default(&CLEARANCE, diags);
    let lines = f.count_or_default(&MODULE_LINES, diags);
    let home = home(f, diags);
    let moves = motion(f, diags);
    let sensor = height_sensor(f, 1, kuka::MAX_ANIN, diags);
    Some(Robot {
        common: common(name, vmax.map(|v| v.0), clearance, sensor, moves)?,
        tool: tool?,
        base: base?,
        beam: beam?,
        laser_out: laser?.0 as u16,
        power_out: anout?.0 as u16,
        full_scale_power: Power(full?.0).watts(),
        home: home?,
        max_points_per_module: lines?,
    })
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
fn home(f: &Fields<'_>, diags: &mut Diagnostics) -> Option<[f64; 6]> {
    let v = match f.value(&HOME, diags) {
        None if f.has(&HOME) => return None,
        None => return Some([0.0, -90.0, 90.0, 0.0, 0.0, 0.0]),
        Some(v) => v,
    };
    let Value::List(items) = &v.value else {
        diags.push(message::machine::home_not_six_angles(
            v.span,
            &v.value.describe(),
        ));
        return None;
    };
    if items.len() != 6 {
        diags.push(message::machine::home_not_six_angles(
            v.span,
            &v.value.describe(),
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
