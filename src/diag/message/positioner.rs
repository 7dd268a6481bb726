//! What lmdc says about a robot's positioner (`positioner { … }`): axes
//! that cannot turn a part, and the verifier's findings on E1 and E2.

use crate::diag::{plural, Code, Diagnostic, Worst};
use crate::span::Span;
use crate::units::short;
use std::fmt::Display;

/// An axis direction (`key`) that is not three numbers.
pub fn direction_not_three(key: &str, at: Span, got: &str) -> Diagnostic {
    Diagnostic::error(
        Code::ExpectedPoint,
        format!("`{key}` is the axis's direction in the robot's frame: three numbers `[x, y, z]`"),
    )
    .label(at, format!("this is {got}"))
    .help(format!(
        "e.g. `{key} = [1, 0, 0]` for an axis along the robot's X; the length does not matter"
    ))
}

/// A positioner's `home` that is not two angles.
pub fn home_not_two_angles(at: Span, got: &str) -> Diagnostic {
    Diagnostic::error(
        Code::ExpectedPoint,
        "a positioner's `home` is E1 and E2 at home: two angles `[e1, e2]`".to_string(),
    )
    .label(at, format!("this is {got}"))
    .help("e.g. `home = [0 deg, 0 deg]`, the default".to_string())
}

/// An axis direction (`key`) of no length.
pub fn zero_direction(key: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::PositionerAxes,
        format!("`{key}` has no length: an axis needs a direction to turn about"),
    )
    .label(at, "[0, 0, 0]")
    .help(format!(
        "give the direction the axis turns about (a positive angle turns right-handed about it), e.g. `{key} = [0, 0, 1]`"
    ))
}

/// The tilt and rotate axes are parallel (within `angle` degrees).
pub fn parallel_axes(tilt: Span, rotate: Span, angle: f64) -> Diagnostic {
    Diagnostic::error(
        Code::PositionerAxes,
        format!(
            "the positioner's tilt and rotate axes are {}° apart: parallel axes cannot tilt the part, only turn it",
            short(angle)
        ),
    )
    .label(tilt, "E1 turns about this")
    .label(rotate, "E2 turns about this, at E1 = 0")
    .help("a two-axis positioner tilts about one axis and rotates the part about another square to it at E1 = 0: e.g. `tilt_axis = [1, 0, 0]`, `rotate_axis = [0, 0, 1]`")
}

/// Limits (`key`) whose low end is not below the high one.
pub fn reversed_limits(key: &str, at: Span, lo: f64, hi: f64) -> Diagnostic {
    Diagnostic::error(
        Code::PositionerAxes,
        format!(
            "`{key}` runs from {}° to {}°: the low end must be below the high one",
            short(lo),
            short(hi)
        ),
    )
    .label(at, "these limits")
    .help(format!(
        "the axis's software limits, low first: e.g. `{key} = -90 deg .. 90 deg`"
    ))
}

/// A positioner on a robot whose `base` is only an index.
pub fn needs_base(block: Span, base: Option<Span>) -> Diagnostic {
    Diagnostic::error(
        Code::PositionerAxes,
        "a positioner needs `base = frame(…)`: where the part's base sits on its flange",
    )
    .label(block, "the positioner")
    .label_opt(base, "only an index into the controller's table")
    .help("declare the base on the flange the program sets (the flange: origin on the rotate axis at `rotate_point`, Z along `rotate_axis`, X along `tilt_axis`), e.g. `base = frame(1, z = 20 mm)` for the part 20 mm above the flange's centre")
}

/// The name of a positioner axis: `E1 (tilt)` or `E2 (rotate)`.
fn axis(i: usize) -> &'static str {
    if i == 0 {
        "E1 (tilt)"
    } else {
        "E2 (rotate)"
    }
}

/// A layer's angle of positioner axis `i` outside its `limits`; the worst
/// is at a layer (`w.at`, 1-based).
pub fn limit(
    machine: &str,
    i: usize,
    w: &Worst<usize>,
    limits: [f64; 2],
    declared: Option<Span>,
    keep: Option<Span>,
) -> Diagnostic {
    Diagnostic::error(
        Code::PositionerLimit,
        format!(
            "the positioner's {} of robot `{machine}` would stand at {}° for layer {}, outside its limits {}° .. {}° ({} layer{} outside)",
            axis(i),
            short(w.value),
            w.at,
            short(limits[0]),
            short(limits[1]),
            w.count,
            plural(w.count)
        ),
    )
    .label_opt(declared, "limits declared here")
    .label_opt(keep, "the angles this asks for")
    .help(if i == 0 {
        "the tilt that brings the layer's normal up is beyond the axis: turn the part on the flange (`base`) so its layers lean less, or let them lean (`keep = cone(…)`, `keep = fixed(…)`)"
    } else {
        "E2 would have to wind further than it can: widen `rotate_limits` if the axis turns further, or turn the part on the flange (`base`) so its layers wind less"
    })
}

/// A positioner's home angle `home` of axis `i` outside its `limits`.
pub fn home_limit(
    machine: &str,
    i: usize,
    home: f64,
    limits: [f64; 2],
    at: Option<Span>,
) -> Diagnostic {
    Diagnostic::error(
        Code::PositionerLimit,
        format!(
            "the positioner's {} of robot `{machine}` is at {}° at home, outside its limits {}° .. {}°: the program starts and ends there",
            axis(i),
            short(home),
            short(limits[0]),
            short(limits[1]),
        ),
    )
    .label_opt(at, "declared here")
    .help("set the positioner's `home = [e1, e2]` to the angles it stands at between programs, inside its limits")
}

/// A feed move on which positioner axis `i` turns faster than `w.limit`.
pub fn speed(
    machine: &str,
    i: usize,
    w: &Worst<impl Display>,
    declared: Option<Span>,
) -> Diagnostic {
    Diagnostic::error(
        Code::PositionerSpeed,
        format!(
            "the positioner's {} of robot `{machine}` would have to turn at {} °/s, beyond its {} °/s, at {} ({} move{} too fast)",
            axis(i),
            short(w.value),
            short(w.limit),
            w.at,
            w.count,
            plural(w.count)
        ),
    )
    .label_opt(declared, "top speed declared here")
    .help("the positioner turns between layers while the nozzle deposits (layers that join without a travel): lower the scan speed there, or keep the angles (`keep = cone(…)`) so it turns less often")
}
