//! What lmdc says about a `ring` (its segments and table), its pairing with
//! the loop, and why a number cannot be planned at all ([`Invalid`]).

use crate::diag::{Code, Diagnostic};
use crate::invalid::Invalid;
use crate::span::Span;
use crate::units::{short, Length, Speed};
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

/// A ring of `radius` whose widest bead (`width`) reaches its centre.
pub fn ring_too_small(radius: Length, width: Length, at: Span, widths: Span) -> Diagnostic {
    Diagnostic::error(
        Code::RingTooSmall,
        format!(
            "a ring of radius {radius} cannot carry a bead {width} wide: its inner face would cross the centre"
        ),
    )
    .label(at, "radius")
    .label(widths, "the widest bead")
    .help(format!(
        "a radius of more than {}, or narrower beads",
        Length(width.0 / 2.0)
    ))
}

/// Ring segments, `length` long each, shorter than their beads are wide
/// (`count` of them, beads up to `width`).
pub fn short_segments(count: usize, length: Length, width: Length, at: Span) -> Diagnostic {
    let (segments, are, beads) = if count == 1 {
        ("1 segment", "is", "its bead")
    } else {
        ("segments", "are", "their beads")
    };
    let lead = if count == 1 {
        segments.to_string()
    } else {
        format!("{count} {segments}")
    };
    Diagnostic::warning(
        Code::ShortTrack,
        format!(
            "{lead} of the ring, {length} long, {are} shorter than {beads} are wide (up to {width})"
        ),
    )
    .label(at, "ring")
    .help("short segments overheat and pile up, and their transitions climb steeply: a larger radius or fewer segments")
}
