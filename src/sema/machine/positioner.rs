//! A robot's `positioner { … }`: a tilt axis (E1) carrying a rotate axis
//! (E2) whose flange carries the part's base (docs/robots.md).

use super::Written;
use crate::diag::{message, Diagnostics};
use crate::ir::{Keep, Positioner, PositionerAxis};
use crate::sema::eval::Env;
use crate::sema::fields::{self, Fields};
use crate::sema::schema::machine::{positioner as p, CONE, FIXED, POSITIONER, POSITIONER_BLOCK};
use crate::sema::schema::Field;
use crate::sema::value::Value;
use crate::units::Dim;

/// Axes closer than this to parallel (deg) cannot tilt a part.
pub const PARALLEL_DEG: f64 = 1.0;

/// The positioner of the robot block `f`: `Some(None)` when it has none,
/// `None` when it is written wrong (reported). Where its fields are
/// written goes into `at`.
pub(super) fn read<'a>(
    env: &mut Env<'a>,
    f: &Fields<'a>,
    at: &mut Written,
    diags: &mut Diagnostics,
) -> Option<Option<Positioner>> {
    let Some((stmts, span)) = f.nested(&POSITIONER_BLOCK) else {
        return Some(None);
    };
    let b = Fields::block(env, stmts, &POSITIONER, "`positioner`".into(), span, diags);
    at.extend(b.written());
    let tilt = axis(
        &b,
        [
            &p::TILT_AXIS,
            &p::TILT_POINT,
            &p::TILT_LIMITS,
            &p::TILT_SPEED,
        ],
        diags,
    );
    let rotate = axis(
        &b,
        [
            &p::ROTATE_AXIS,
            &p::ROTATE_POINT,
            &p::ROTATE_LIMITS,
            &p::ROTATE_SPEED,
        ],
        diags,
    );
    let keep = keep(&b, diags);
    let home = home(&b, diags);
    let faceplate = b.optional(&p::FACEPLATE, b.quantity(&p::FACEPLATE, diags).map(|q| q.0));
    let (tilt, rotate) = (tilt?, rotate?);
    let dot: f64 = (0..3)
        .map(|i| tilt.direction[i] * rotate.direction[i])
        .sum();
    let apart = dot.abs().clamp(0.0, 1.0).acos().to_degrees();
    if apart < PARALLEL_DEG {
        let s = |k| b.span(k).unwrap_or(span);
        diags.push(message::positioner::parallel_axes(
            s(&p::TILT_AXIS),
            s(&p::ROTATE_AXIS),
            apart,
        ));
        return None;
    }
    Some(Some(Positioner {
        tilt,
        rotate,
        keep: keep?,
        home: home?,
        angles: Vec::new(),
        faceplate: faceplate?,
    }))
}

/// One axis: its direction, point, limits and speed (`[direction, point,
/// limits, speed]`).
fn axis(
    b: &Fields<'_>,
    [dir, point, lim, speed]: [&Field; 4],
    diags: &mut Diagnostics,
) -> Option<PositionerAxis> {
    let direction = three(b, dir, Dim::NONE, diags).and_then(|(d, s)| {
        let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        if n > 1e-9 && n.is_finite() {
            Some(d.map(|c| c / n))
        } else {
            diags.push(message::positioner::zero_direction(dir.key, s));
            None
        }
    });
    let point = three(b, point, Dim::LENGTH, diags).map(|p| p.0);
    let limits = b.range(lim, diags).and_then(|([lo, hi], s)| {
        let (lo, hi) = (lo.to_degrees(), hi.to_degrees());
        if lo < hi {
            Some([lo, hi])
        } else {
            diags.push(message::positioner::reversed_limits(lim.key, s, lo, hi));
            None
        }
    });
    let speed = b.quantity(speed, diags).map(|s| s.0.to_degrees());
    Some(PositionerAxis {
        direction: direction?,
        point: point?,
        limits: limits?,
        speed: speed?,
    })
}

/// A list of three quantities of `dim` (a direction, a point).
fn three(
    b: &Fields<'_>,
    field: &Field,
    dim: Dim,
    diags: &mut Diagnostics,
) -> Option<([f64; 3], crate::span::Span)> {
    list(b, field, dim, diags)
}

/// A list of `N` quantities of `dim`.
fn list<const N: usize>(
    b: &Fields<'_>,
    field: &Field,
    dim: Dim,
    diags: &mut Diagnostics,
) -> Option<([f64; N], crate::span::Span)> {
    let v = b.value(field, diags)?;
    let items = match &v.value {
        Value::List(items) if items.len() == N => items,
        _ => {
            diags.push(wrong(field, v.span, &v.value.describe()));
            return None;
        }
    };
    let mut out = [0.0; N];
    let mut ok = true;
    for (o, it) in out.iter_mut().zip(items) {
        match fields::quantity(it, dim, field.key, diags) {
            Some(q) => *o = q,
            None => ok = false,
        }
    }
    ok.then_some((out, v.span))
}

fn wrong(field: &Field, at: crate::span::Span, got: &str) -> crate::diag::Diagnostic {
    match field.kind.dim() {
        Some(Dim::LENGTH) => message::machine::axis_point_not_a_point(field.key, at, got),
        Some(Dim::ANGLE) => message::positioner::home_not_two_angles(at, got),
        _ => message::positioner::direction_not_three(field.key, at, got),
    }
}

/// `home = [e1, e2]`, deg (default both 0).
fn home(b: &Fields<'_>, diags: &mut Diagnostics) -> Option<[f64; 2]> {
    if !b.has(&p::HOME) {
        return Some([0.0; 2]);
    }
    list(b, &p::HOME, Dim::ANGLE, diags).map(|(e, _)| e.map(f64::to_degrees))
}

/// `keep = vertical | cone(angle) | fixed(e1, e2)`.
fn keep(b: &Fields<'_>, diags: &mut Diagnostics) -> Option<Keep> {
    let v = match b.value(&p::KEEP, diags) {
        None if b.has(&p::KEEP) => return None,
        None => return Some(Keep::Vertical),
        Some(v) => v,
    };
    match &v.value {
        Value::Call(c) if c.func == CONE.name => {
            let a = Fields::call(c, &CONE, diags);
            let out = |q: f64, s| {
                let shown = format!("{}°", crate::units::short(q.to_degrees()));
                message::field::too_large(p::CONE_ANGLE.key, "up to 90°", &shown, s)
            };
            let (deg, _) = a.bounded(&p::CONE_ANGLE, out, diags)?;
            Some(Keep::Cone {
                deg: deg.to_degrees().abs(),
            })
        }
        Value::Call(c) if c.func == FIXED.name => {
            let a = Fields::call(c, &FIXED, diags);
            let mut g = |field: &Field| {
                let out = |q: f64, s| {
                    message::machine::frame_out_of_range(
                        field.key,
                        q.to_degrees(),
                        true,
                        s,
                        crate::sema::schema::machine::MAX_FRAME_MM,
                        crate::sema::schema::machine::MAX_ANGLE_DEG,
                    )
                };
                a.bounded_or_default(field, out, diags)
            };
            let (e1, e2) = (g(&p::E1), g(&p::E2));
            Some(Keep::Fixed {
                e1: e1?.to_degrees(),
                e2: e2?.to_degrees(),
            })
        }
        _ => b.word(&p::KEEP, diags).map(|_| Keep::Vertical),
    }
}
