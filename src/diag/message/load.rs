//! A robot tool's load (`load = load(…)`, KUKA's `$LOAD`): a value out of
//! its range, a list that is not three values, and a robot that declares
//! none (`lmd::load-unchecked`).

use crate::diag::{Code, Diagnostic};
use crate::span::Span;

/// The example every message about a load shows.
const EXAMPLE: &str = "`load = load(mass = 12 kg, cog = [0 mm, 0 mm, 150 mm])`";

/// A robot that declares no load: its program takes the controller's
/// `LOAD_DATA[index]` (the tool's number), which lmdc cannot check; `at` is
/// its `tool` (`written`) or the robot.
pub fn unchecked(machine: &str, index: u16, at: Span, written: bool) -> Diagnostic {
    let label = if written {
        format!("tool {index}: its load is not declared")
    } else {
        format!("tool {index} (the default): its load is not declared")
    };
    Diagnostic::warning(
        Code::LoadUnchecked,
        format!(
            "robot `{machine}` declares no tool load: its program sets `$LOAD = LOAD_DATA[{index}]`, whatever load data the controller holds for tool {index}"
        ),
    )
    .label(at, label)
    .help(format!(
        "declare the tool's load so the program sets it: {EXAMPLE}, the mass of all the flange carries and its centre of gravity in the flange's frame (from KUKA's load data determination or the nozzle's drawing); the controller plans the motion and watches for collisions with it"
    ))
}

/// `key` of `load(…)` (mass, a centre of gravity's coordinate, a moment of
/// inertia) at `shown` (with its unit), outside `range` (`from 0 to 2000
/// kg*m^2`).
pub fn out_of_range(key: &str, shown: &str, range: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::OutOfRange,
        format!("a tool load's `{key}` of {shown} is out of range: a tool's load takes {range}"),
    )
    .label(at, "not a tool's load")
    .help(format!(
        "write the load of the tool on the flange, in its units: {EXAMPLE}; `inertia` in kg*m^2 (`[0.2 kg*m^2, 0.2 kg*m^2, 0.05 kg*m^2]`)"
    ))
}

/// `key` of `load(…)` is not a list of three values of its kind (`what`).
pub fn not_three(key: &str, what: &str, at: Span, got: &str) -> Diagnostic {
    Diagnostic::error(
        Code::Type,
        format!("a tool load's `{key}` is three {what}, `[x, y, z]`"),
    )
    .label(at, format!("this is {got}"))
    .help(format!("e.g. {EXAMPLE}"))
}

/// `load = …` written as something other than `load(…)`.
pub fn not_a_load(at: Span, got: &str) -> Diagnostic {
    Diagnostic::error(
        Code::Type,
        "a robot's `load` is the tool's load data, `load(mass = …, cog = […])`",
    )
    .label(at, format!("this is {got}"))
    .help(format!(
        "e.g. {EXAMPLE}: the mass and the centre of gravity in the flange's frame; KUKA's `LOAD_DATA[n]` is the tool's number's and needs no index"
    ))
}
