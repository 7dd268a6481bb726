//! What lmdc says about a `ring` (its segments and table) and the
//! `control height` loop that corrects it layer by layer.

use crate::control::{Invalid, SpeedPerLength};
use crate::diag::{Code, Diagnostic};
use crate::span::Span;
use crate::units::{short, Dim, Length, Quantity, Speed};
use std::fmt;

/// The ring's radius, segments and transition (at `at`) cannot be laid out
/// (`e` says why).
pub fn ring_layout(e: &Invalid, at: Span, segments: usize) -> Diagnostic {
    let d = Diagnostic::error(
        Code::OutOfRange,
        format!("the ring cannot be laid out: {e}"),
    )
    .label(at, "transition");
    match e {
        Invalid::TransitionTooLong { segment_deg, .. } => d.help(format!(
            "a transition must be shorter than its segment: 360°/{segments} = {}°",
            short(*segment_deg)
        )),
        _ => d,
    }
}

/// The ring block `what` (at `span`) has no `table`.
pub fn ring_needs_table(what: &str, span: Span) -> Diagnostic {
    Diagnostic::error(Code::MissingField, format!("{what} needs a `table`"))
        .label(span, "`table` is missing")
        .help("add `table { defocus = [...]  power = [...]  width = [...]  speed = [...] }`, one entry per segment")
}

/// A table entry `key` is not a list (`got` describes what it is; `example`
/// is a list of the right kind).
pub fn table_not_a_list(key: &str, at: Span, got: &str, example: &str) -> Diagnostic {
    Diagnostic::error(
        Code::Type,
        format!("`{key}` is a list with one value per segment"),
    )
    .label(at, format!("this is {got}"))
    .help(format!("write `{key} = {example}`"))
}

/// A value of the table's `key` list is zero or below (`shown` is it, with
/// its unit).
pub fn table_not_positive(key: &str, at: Span, shown: &str) -> Diagnostic {
    Diagnostic::error(
        Code::NotPositive,
        format!("every `{key}` of the table must be greater than zero"),
    )
    .label(at, format!("this is {shown}"))
}

/// A per-segment list of the wrong length.
pub fn table_length(
    key: &str,
    found: usize,
    at: Span,
    segments: usize,
    seg_at: Span,
) -> Diagnostic {
    Diagnostic::error(
        Code::TableLength,
        format!(
            "`{key}` has {found} entr{} for {segments} segments",
            if found == 1 { "y" } else { "ies" }
        ),
    )
    .label(
        at,
        format!("{found} entr{}", if found == 1 { "y" } else { "ies" }),
    )
    .label(seg_at, format!("{segments} segments"))
    .help("give one value per segment, from the segment that starts on +x, counter-clockwise")
}

/// The loop's `target` (`t`) differs from the layer height `h` the plan lays.
pub fn target_not_layer_height(t: Length, h: Length, at: Span, layer_at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::ConflictingFields,
        format!("the loop's target {t} is not the layer height {h} the plan lays"),
    )
    .label(at, "target")
    .label(layer_at, "layer height")
    .help("the plan rises `layer_height` a layer and the loop holds each layer to `target`: give them one value (or leave `target` out)")
}

/// The controller cannot be built from the block (`at`); `e` says why.
pub fn loop_cannot_run(e: &Invalid, at: Span) -> Diagnostic {
    Diagnostic::error(Code::OutOfRange, format!("the loop cannot run: {e}")).label(at, "control")
}

/// Segment `segment` (1-based) starts at `speed`, outside the clamp.
pub fn start_outside_clamp(
    segment: usize,
    speed: Speed,
    low: Speed,
    high: Speed,
    speeds_at: Option<Span>,
    clamp_at: Span,
) -> Diagnostic {
    Diagnostic::error(
        Code::OutOfRange,
        format!("segment {segment} starts at {speed}, outside the loop's clamp {low} .. {high}"),
    )
    .label_opt(speeds_at, "the table's speeds")
    .label(clamp_at, "clamp")
    .help("start every segment at a speed the loop may command, or widen the clamp")
}

/// A plant drift of `drift` (a fraction per layer) leaves nothing to lay by
/// layer `layers`.
pub fn drift_exhausts_plant(drift: f64, layers: usize, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::OutOfRange,
        format!(
            "a drift of {} % a layer leaves the plant nothing to lay by layer {layers}",
            short(drift * 100.0)
        ),
    )
    .label(at, "plant")
    .help(format!(
        "a drift above {} % a layer",
        short(-100.0 / (layers - 1).max(1) as f64)
    ))
}

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
    } else if q.dim == SpeedPerLength::DIM {
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

impl fmt::Display for Invalid {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Invalid::NotFinite { what } => write!(f, "{what} is not a finite number"),
            Invalid::NotPositive { what, value } => {
                write!(f, "{what} must be greater than zero, not {value}")
            }
            Invalid::Reversed { what, low, high } => {
                write!(f, "{what} runs from {low} down to {high}")
            }
            Invalid::Empty { what } => write!(f, "{what} is empty"),
            Invalid::NoSegment { segment, segments } => {
                write!(f, "there is no segment {segment} (from 0) of {segments}")
            }
            Invalid::TransitionTooLong {
                transition_deg,
                segment_deg,
            } => write!(
                f,
                "a transition of {transition_deg}° leaves nothing of a {segment_deg}° segment"
            ),
            Invalid::Count {
                what,
                found,
                expected,
            } => write!(f, "{what} has {found} entries for {expected} segments"),
            Invalid::OutsideClamp {
                what,
                value,
                low,
                high,
            } => write!(
                f,
                "{what} {value} mm/s lies outside the clamp {low} mm/s .. {high} mm/s"
            ),
            Invalid::NotIncreasing { what, index } => {
                write!(
                    f,
                    "{what}: point {index} does not lie beyond the one before it"
                )
            }
            Invalid::TooLarge { what, value, max } => {
                write!(f, "{what} is {value}, more than the {max} lmdc allows")
            }
        }
    }
}

impl std::error::Error for Invalid {}
