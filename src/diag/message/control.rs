//! What lmdc says about the `control height` block and the loop it declares:
//! its gains, clamp and plant, and what the compile-time analysis finds
//! ([`Finding`]'s wording).

use crate::control::analysis::{Gain, SegmentLoop, NEVER_SETTLES};
use crate::control::linear::SETTLED;
use crate::control::Finding;
use crate::diag::{Code, Diagnostic};
use crate::invalid::Invalid;
use crate::span::Span;
use crate::units::{short, Dim, Quantity};
use std::fmt;

/// `control` names a quantity other than the height.
pub fn control_not_height(name: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::BadChoice,
        format!("lmdc controls the layer height, not `{name}`"),
    )
    .label(at, "controlled quantity")
    .help("write `control height { … }`")
}

/// The clamp's range (at `at`) cannot be a clamp; `e` says why.
pub fn clamp_cannot_hold(e: &Invalid, at: Span) -> Diagnostic {
    Diagnostic::error(Code::OutOfRange, format!("the clamp cannot hold: {e}"))
        .label(at, "clamp")
        .help("the speeds the loop may command, low .. high, both above zero")
}

/// The control block (`block`) lacks the gain `key`.
pub fn missing_gain(key: &str, block: Span, example: &str) -> Diagnostic {
    Diagnostic::error(Code::MissingField, format!("control needs `{key}`"))
        .label(block, format!("`{key}` is missing"))
        .help(format!(
            "add `{key} = {example}`: a speed per mm of height error"
        ))
}

/// The gain `key` is not a quantity at all (`got` describes what it is).
pub fn gain_not_a_quantity(key: &str, at: Span, got: &str, example: &str) -> Diagnostic {
    Diagnostic::error(
        Code::GainUnit,
        format!("`{key}` must be a speed per length (mm/s/mm)"),
    )
    .label(at, format!("this is {got}"))
    .help(format!("write `{key} = {example}`"))
}

/// What is wrong with a gain's unit, both readings spelled out: no unit, a
/// unit per second that names no length (`units` as written), or another
/// dimension.
pub fn gain_unit(key: &str, q: Quantity, at: Span, units: &[String]) -> Diagnostic {
    let n = short(q.value);
    let readings = format!(
        "write `{key} = {n} mm/s/mm` ({n} (mm/s)/mm), or — if the number is per (m/s)/mm, as KUKA's \
         $VEL.CP counts speed and as the paper's -0.003 \"s⁻¹\" reproduces its results — `{key} = {n} m/s/mm` \
         ({} (mm/s)/mm)",
        short(q.value * 1000.0)
    );
    let (message, label) = if q.dim == Dim::NONE {
        (
            format!("`{key}` has no unit: a gain is a change of speed per mm of height error"),
            "a plain number".to_string(),
        )
    } else if q.dim == Dim::SPEED.per(Dim::LENGTH) {
        (
            format!(
                "`{key}` is written per second ({}): (mm/s)/mm and (m/s)/mm are both 1/s, 1000 apart",
                units.join(", ")
            ),
            "which speed per which length?".to_string(),
        )
    } else {
        (
            format!(
                "`{key}` must be a speed per length (mm/s/mm), not {}",
                q.dim.describe()
            ),
            q.dim.describe(),
        )
    };
    Diagnostic::error(Code::GainUnit, message)
        .label(at, label)
        .help(readings)
}

/// A plant factor is not a plain number above zero (`got` describes it).
pub fn plant_factor(at: Span, got: &str) -> Diagnostic {
    Diagnostic::error(
        Code::ExpectedNumber,
        "a plant factor is a plain number above zero",
    )
    .label(at, format!("this is {got}"))
    .help("1.1 lays 10 % more than the calibration, 0.9 10 % less")
}

/// The plant's `factors` is not a list (`got` describes it).
pub fn factors_not_a_list(at: Span, got: &str) -> Diagnostic {
    Diagnostic::error(Code::Type, "`factors` is a list, one per segment")
        .label(at, format!("this is {got}"))
        .help("e.g. `factors = [1.0, 0.9, …]`")
}

/// `plant` is not `inverse_speed(…)` (`what` describes what it is).
pub fn plant_shape(at: Span, what: &str) -> Diagnostic {
    Diagnostic::error(Code::BadChoice, "the plant is `inverse_speed(…)`")
        .label(at, format!("this is {what}"))
        .help("`plant = inverse_speed(drift = 0.1 %)`: each segment lays h = g·(1 + drift·layer)/v, calibrated so that its table speed lays the target; `factors = […]` scales each segment's g")
}

impl Finding {
    /// What would fix it, with numbers.
    pub fn help(&self) -> Option<String> {
        match self {
            Finding::Sign { .. } => Some(
                "both gains must be negative: the bead height falls as the speed rises \
                 (h ∝ 1/v), so a layer below the target must slow its segment down"
                    .into(),
            ),
            Finding::Unstable { kp, ki, limit, .. } => Some(format!(
                "gains below ×{} of these are stable at every segment: kp above {}, ki above {}",
                short(*limit),
                kp.scaled(*limit),
                ki.scaled(*limit)
            )),
            Finding::UnstableAtClamp { limit, .. } => limit.map(|c| {
                format!(
                    "gains below ×{} of these are stable there, or raise the clamp's low speed",
                    short(c)
                )
            }),
            Finding::Slow {
                kp,
                ki,
                scale,
                per_metre,
                layers,
                ..
            } => {
                if *per_metre {
                    Some(format!(
                        "if the gains were meant per (m/s)/mm, as KUKA's $VEL.CP counts speed, \
                         write kp = {} m/s/mm and ki = {} m/s/mm ({} and {})",
                        short(kp.0),
                        short(ki.0),
                        kp.scaled(1000.0),
                        ki.scaled(1000.0)
                    ))
                } else {
                    scale.map(|c| {
                        format!(
                            "×{} of these gains (kp = {}, ki = {}) settle within {} layers at every segment",
                            short(c),
                            kp.scaled(c),
                            ki.scaled(c),
                            layers
                        )
                    })
                }
            }
        }
    }
}

fn at(l: &SegmentLoop) -> String {
    match l.segment {
        Some(j) => format!("segment {} ({})", j + 1, l.speed),
        None => format!("the clamp's low speed ({})", l.speed),
    }
}

impl fmt::Display for Finding {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Finding::Sign { gain, value } => {
                let (name, why) = match gain {
                    Gain::Proportional => (
                        "kp",
                        if value.0 == 0.0 {
                            "the integral alone swings the speed back and forth without ever settling"
                        } else {
                            "a layer that comes out too low would speed its segment up and come out lower still"
                        },
                    ),
                    Gain::Integral => (
                        "ki",
                        if value.0 == 0.0 {
                            "nothing corrects the total height: errors of past layers stay in the part"
                        } else {
                            "a segment whose total falls behind would be sped up and fall further behind"
                        },
                    ),
                };
                let sign = if value.0 == 0.0 { "zero" } else { "positive" };
                write!(f, "{name} = {value} is {sign}: {why}")
            }
            Finding::Unstable {
                worst, count, of, ..
            } => write!(
                f,
                "unstable: loop gain kP·h_r/v = {}, kI·h_r/v = {} at {}: spectral radius {} \
                 ({count} of {of} segments unstable)",
                short(worst.gains.proportional),
                short(worst.gains.integral),
                at(worst),
                short(worst.radius)
            ),
            Finding::UnstableAtClamp { at: l, .. } => write!(
                f,
                "the loop is stable at every segment's speed but not if a segment slows to the \
                 clamp's {}: spectral radius {} there",
                l.speed,
                short(l.radius)
            ),
            Finding::Slow {
                worst,
                settling,
                layers,
                residual,
                ..
            } => {
                let n = format!("{:.0}", settling.ceil());
                let left = short(residual * 100.0);
                if *residual > NEVER_SETTLES {
                    write!(
                        f,
                        "the loop is so slow it never settles: {} needs ~{n} layers to bring an \
                         error down to {} % (spectral radius {:.6}) but the build has {layers}; \
                         {left} % of an error is still there after the last layer",
                        at(worst),
                        short(SETTLED * 100.0),
                        worst.radius
                    )
                } else {
                    write!(
                        f,
                        "{} settles in ~{n} layers (to {} %), but the build has {layers}: \
                         {left} % of a starting error remains after the last layer",
                        at(worst),
                        short(SETTLED * 100.0)
                    )
                }
            }
        }
    }
}
