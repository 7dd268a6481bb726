//! What the verifier says about the rotary axes in machine coordinates: their
//! speeds, and a tilting table's C axis that would have to unwind inside a
//! layer.

use crate::diag::{plural, Code, Diagnostic, Worst};
use crate::span::Span;
use crate::units::short;
use std::fmt::Display;

/// A machine's axes (`axis`: `X Y Z`, the tilt axis's letter or `C`) would
/// have to move faster than declared (`declared`: `max_speed` or
/// `rotary_speed`).
pub fn axis_speed(name: &str, axis: &str, w: &Worst<impl Display>, declared: Span) -> Diagnostic {
    let linear = axis.len() > 1;
    let (unit, field, help) = if linear {
        (
            "mm/s",
            "max_speed",
            "the table turns the part under the nozzle, so the linear axes move further than \
             the nozzle does along the part (most near the rims, far from the table's axes): \
             lower the scan speeds, or place the part nearer the C axis",
        )
    } else {
        (
            "°/s",
            "rotary_speed",
            "the normals turn fast along the path (a tight bend, points close together where \
             the layer's direction changes): lower the scan speeds there, or raise \
             `rotary_speed` if the axis really turns faster",
        )
    };
    let axes = if linear { "axes" } else { "axis" };
    Diagnostic::error(
        Code::AxisSpeed,
        format!(
            "the {axis} {axes} of machine `{name}` would have to move at {} {unit}, beyond its \
             {field} of {} {unit}, at {} ({} move{} too fast)",
            short(w.value),
            short(w.limit),
            w.at,
            w.count,
            plural(w.count)
        ),
    )
    .label(declared, "limit declared here")
    .help(help)
}

/// A tilting table's C axis would turn through more than its travel
/// (`range`) within one layer.
pub fn c_unwind(
    name: &str,
    w: &Worst<impl Display>,
    (range, head): ([f64; 2], bool),
    declared: Span,
) -> Diagnostic {
    let (within, why) = if head {
        (
            "between two retracts",
            "a head unwinds C only where the nozzle has backed off with the laser off, \
             between paths: declare C's real travel if it turns further (an endless C axis: \
             as wide as the paths wind), or let the nozzle leave the part more often (a \
             continuous program: `layer_change = lift` in the slicing, so each layer is a \
             run of its own)",
        )
    } else {
        (
            "within one layer",
            "a table does not unwind C in the middle of a layer (the part would swing round \
             with the nozzle over it): declare C's real travel if it turns further (an endless \
             C axis: as wide as the layers wind), or build the part so its layers wind less",
        )
    };
    let runs = if head { "run" } else { "layer" };
    Diagnostic::error(
        Code::CUnwind,
        format!(
            "the C axis of machine `{name}` would turn through {}° {within} (up to {}), \
             more than its travel of {}° ({}° .. {}°; {} {runs}{} too wide)",
            short(w.value),
            w.at,
            short(w.limit),
            short(range[0]),
            short(range[1]),
            w.count,
            plural(w.count)
        ),
    )
    .label(declared, "C's travel declared here")
    .help(why)
}
