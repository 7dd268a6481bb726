//! What the verifier says about a cell's gas and powder timing.

use crate::diag::{plural, Worst};
use crate::diag::{Code, Diagnostic};
use crate::span::Span;
use crate::units::short;
use std::fmt::Display;

/// The laser would start before the gas flowed its `pre_flow`.
pub fn gas_too_short(
    name: &str,
    w: &Worst<impl Display>,
    pre_flow: f64,
    declared: Span,
) -> Diagnostic {
    Diagnostic::error(
        Code::PowderArrival,
        format!(
            "machine `{name}` would start the laser {} s after opening the gas, short of its pre_flow of {} s, at {} ({} start{})",
            short(w.value),
            short(pre_flow),
            w.at,
            w.count,
            plural(w.count)
        ),
    )
    .label(declared, "pre_flow declared here")
    .help("the melt pool oxidises without shielding: the gas must flow for pre_flow before the laser starts")
}

/// The laser would start before the powder arrived at the nozzle.
pub fn powder_too_early(
    name: &str,
    w: &Worst<impl Display>,
    arrival: f64,
    declared: Span,
) -> Diagnostic {
    Diagnostic::error(
        Code::PowderArrival,
        format!(
            "machine `{name}` would start the laser {} s after starting the powder feeder (or changing its rate), before the powder arrives ({} s), at {} ({} start{})",
            short(w.value),
            short(arrival),
            w.at,
            w.count,
            plural(w.count)
        ),
    )
    .label(declared, "arrival declared here")
    .help("a laser on the bare substrate without powder remelts it instead of building: the plan must wait the powder's arrival time")
}

/// The powder feed changes inside a path while a rate output sets it; `w`
/// holds the new feed and (as its limit) the one set.
pub fn rate_changes_in_path(name: &str, w: &Worst<impl Display>, programmed: Span) -> Diagnostic {
    Diagnostic::error(
        Code::PowderRate,
        format!(
            "machine `{name}`'s powder feed changes from {} to {} g/min inside a path, at {} ({} move{}): the feed-rate output cannot follow (powder takes the arrival time to reach the nozzle)",
            short(w.limit),
            short(w.value),
            w.at,
            w.count,
            plural(w.count)
        ),
    )
    .label(programmed, "the feed rate is programmed")
    .help("keep one powder feed along each path (a style's `powder` applies to whole paths), or set the rate on the feeder and drop `rate_output`")
}

/// Deposits of style `style` (the worst's value its feed, g/min) on a
/// machine whose feeder has no rate output (`machine`: its declaration).
pub fn style_powder_unfed(
    name: &str,
    w: &Worst<impl Display>,
    style: &str,
    machine: Span,
) -> Diagnostic {
    Diagnostic::error(
        Code::PowderRate,
        format!(
            "style `{style}` feeds {} g/min, which machine `{name}` cannot program: its feeder has no rate output, so the style's tracks get whatever rate the feeder is set to, while the plan's speeds and heights count on the style's ({} move{}, the first at {})",
            short(w.value),
            w.count,
            plural(w.count),
            w.at
        ),
    )
    .label(machine, "no rate output for the powder feed")
    .help(format!(
        "give `{name}` a powder feeder with a rate output (`powder {{ output = …  arrival = …  rate_output = …  full_scale = … }}`): the plan then sets each track's feed and waits its arrival; or leave `powder` out of the style"
    ))
}

/// A powder feed beyond the feed-rate output's full scale.
pub fn rate_over_full_scale(
    name: &str,
    w: &Worst<impl Display>,
    full_scale: f64,
    declared: Span,
) -> Diagnostic {
    Diagnostic::error(
        Code::PowderRate,
        format!(
            "machine `{name}` would feed {} g/min, beyond its feed-rate output's full_scale of {} g/min ({} move{})",
            short(w.value),
            short(full_scale),
            w.count,
            plural(w.count)
        ),
    )
    .label(declared, "full scale declared here")
    .help(format!(
        "set `full_scale` to the feeder's rate at full analog output (at least {} g/min), or feed less powder",
        short(w.value)
    ))
}
