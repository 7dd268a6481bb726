//! What the verifier says about a ring's height loop and the machines that
//! run it.

use crate::control::{self, Finding, Severity};
use crate::diag::{Code, Diagnostic};
use crate::span::Span;
use crate::target::gcode::MAX_ANALOG_INPUT;
use crate::target::kuka::MAX_ADVANCE;
use crate::units::{short, short_up};
use std::fmt::Display;

/// The declared loop cannot be analysed at all (a degenerate value).
pub fn loop_cannot_run(why: &dyn Display, control: Span) -> Diagnostic {
    Diagnostic::error(
        Code::OutOfRange,
        format!("the height loop cannot run: {why}"),
    )
    .label(control, "control")
}

/// Where the fields a finding of the loop's analysis is about are written.
#[derive(Clone, Copy, Debug)]
pub struct LoopFields {
    /// `kp = …`.
    pub kp: Span,
    /// `ki = …`.
    pub ki: Span,
    /// `clamp = …`.
    pub clamp: Span,
    /// `layers = …` of the slicing block.
    pub layers: Span,
}

/// One finding of the loop's analysis, at the fields it is about.
pub fn loop_finding(f: &Finding, o: &LoopFields) -> Diagnostic {
    let (code, labels): (Code, Vec<(_, &str)>) = match f {
        Finding::Sign { gain, .. } => (
            Code::GainSign,
            vec![(
                match gain {
                    control::analysis::Gain::Proportional => o.kp,
                    control::analysis::Gain::Integral => o.ki,
                },
                "gain",
            )],
        ),
        Finding::Unstable { .. } => (Code::UnstableLoop, vec![(o.kp, "kp"), (o.ki, "ki")]),
        Finding::UnstableAtClamp { .. } => (Code::UnstableLoop, vec![(o.clamp, "clamp")]),
        Finding::Slow { .. } => (
            Code::SlowLoop,
            vec![(o.kp, "kp"), (o.ki, "ki"), (o.layers, "layers")],
        ),
    };
    let mut d = match f.severity() {
        Severity::Error => Diagnostic::error(code, f.to_string()),
        Severity::Warning => Diagnostic::warning(code, f.to_string()),
    };
    for (at, text) in labels {
        d = d.label(at, text);
    }
    match f.help() {
        Some(h) => d.help(h),
        None => d,
    }
}

/// A closed loop asked of a G-code dialect or a robot controller
/// (`what`: `dialect`, `controller`) that cannot run one.
pub fn loop_dialect(
    name: &str,
    profile: &dyn Display,
    what: &str,
    dialect: Span,
    run: Span,
) -> Diagnostic {
    Diagnostic::error(
        Code::LoopDialect,
        format!(
            "the height loop is to run on machine `{name}`, and a closed loop is not supported on the {profile} {what}"
        ),
    )
    .label(dialect, what.to_string())
    .label(run, "the loop runs on the machine")
    .help("`run = schedule` writes an open-loop speed schedule (the loop run against the declared plant) that every dialect runs; a closed loop runs on LinuxCNC and KUKA robots")
}

/// A loop on a tilting table whose program is written in machine coordinates.
pub fn loop_on_table_machine(name: &str, output: Span, run: Span) -> Diagnostic {
    Diagnostic::error(
        Code::LoopDialect,
        format!(
            "the height loop is to run on machine `{name}`, whose table's program is written in machine coordinates: the loop's program writes part coordinates"
        ),
    )
    .label(output, "machine coordinates")
    .label(run, "the loop runs on the machine")
    .help("`table_output = tcp` runs the loop under the control's transform; or `run = schedule` for an open-loop schedule")
}

/// A loop on a robot whose part turns on a positioner.
pub fn loop_on_positioner(name: &str, positioner: Span, run: Span) -> Diagnostic {
    Diagnostic::error(
        Code::LoopDialect,
        format!(
            "the height loop is to run on robot `{name}`, whose part turns on a positioner: the loop's program writes no E1 and E2"
        ),
    )
    .label(positioner, "the positioner")
    .label(run, "the loop runs on the machine")
    .help("`run = schedule` writes an open-loop speed schedule, with E1 and E2 on every motion; or build the ring without the positioner")
}

/// A loop on a machine that declares no height sensor.
pub fn no_height_sensor(name: &str, block: Span, run: Span) -> Diagnostic {
    Diagnostic::error(
        Code::HeightSensor,
        format!("machine `{name}` declares no height sensor for the loop to read"),
    )
    .label(block, "no `height_input`")
    .label(run, "the loop runs on the machine")
    .help("declare the analog input the sensor's segment mean arrives on: `height_input = 3` and `height_full_scale = 2 mm` (the height at 1.0); or `run = schedule` for an open-loop schedule")
}

/// LinuxCNC's analog inputs end before the last segment's (`last`).
pub fn too_many_inputs(segments: usize, first: u16, last: usize, declared: Span) -> Diagnostic {
    Diagnostic::error(
        Code::HeightSensor,
        format!(
            "LinuxCNC reads segment j's height on input `height_input + j`: {segments} segments from input {first} reach M66 E{last}, past E{MAX_ANALOG_INPUT}"
        ),
    )
    .label(declared, "first input")
    .help(format!(
        "a first input of at most {}",
        MAX_ANALOG_INPUT + 1 - segments.min(MAX_ANALOG_INPUT + 1)
    ))
}

/// Why a robot's segment update could land after the advance run read it.
pub enum LateUpdate {
    /// One segment starts again where it ends.
    OneSegment,
    /// The update's delay spans more moves than there are before the reader.
    TooLate {
        /// The sensor's delay, s.
        delay: f64,
        /// Moves the robot may make during the delay.
        during_delay: f64,
        /// The shortest move, mm.
        shortest: f64,
        /// The fastest speed the robot may run, mm/s.
        fastest: f64,
        /// Moves between the update and the first that reads it.
        between: usize,
    },
}

/// A robot's loop update that could land after the values were read.
pub fn loop_timing(name: &str, why: &LateUpdate, delay: Span, ring: Span) -> Diagnostic {
    let message = match why {
        LateUpdate::OneSegment => format!(
            "a ring of one segment cannot run its loop on robot `{name}`: the segment starts again where it ends, before its measurement can change its speed and height"
        ),
        LateUpdate::TooLate {
            delay,
            during_delay,
            shortest,
            fastest,
            between,
        } => format!(
            "on robot `{name}` a segment's update could land after the robot has read the values it sets: it runs {} ms after the segment's end (up to {} moves of {} mm at {} mm/s), and the next reader comes {} moves later, of which the advance run may read {} ahead",
            short(delay * 1000.0),
            during_delay,
            short(*shortest),
            short(*fastest),
            between,
            MAX_ADVANCE
        ),
    };
    Diagnostic::error(Code::LoopTiming, message)
        .label(delay, "height_delay")
        .label(ring, "ring")
        .help("more segments, fewer or longer moves (a larger `step`), a shorter `height_delay`, or `run = schedule`; LinuxCNC, which stops to read, has no such limit")
}

/// The steepest transition of a ring, at the loop's top speed, beyond a
/// machine's `max_speed`.
pub struct FastTransition<'a> {
    /// The machine.
    pub machine: &'a str,
    /// Its `max_speed`, mm/s.
    pub max: f64,
    /// The transition's segment (from 0) and how many there are.
    pub segment: usize,
    /// How many segments the ring has.
    pub segments: usize,
    /// The rise over the transition, mm, and its arc, mm.
    pub rise: f64,
    /// The transition's arc, mm.
    pub arc: f64,
    /// The path speed there, mm/s.
    pub speed: f64,
    /// The clamp's top speed, mm/s.
    pub top: f64,
    /// The transition (deg) that would fit, when a longer one can.
    pub transition_fits: Option<f64>,
    /// The ring radius (mm) whose transition arc would fit, at the declared
    /// transition angle.
    pub radius_fits: Option<f64>,
    /// Where the machine's max_speed, the clamp and the transition are declared.
    pub spans: [Span; 3],
}

/// A ring's transition that the loop could drive past a machine's max_speed.
pub fn transition_speed(t: &FastTransition) -> Diagnostic {
    let (j, n) = (t.segment, t.segments);
    let gamma = (t.rise / t.arc).atan();
    let mut help = format!("a clamp up to {} mm/s", short(t.max * gamma.cos()));
    if let Some(deg) = t.transition_fits {
        help.push_str(&format!(", a transition of at least {}°", short_up(deg)));
    }
    if let Some(r) = t.radius_fits {
        help.push_str(&format!(
            ", a ring radius of at least {} mm (a longer transition arc)",
            short_up(r)
        ));
    }
    help.push_str(&format!(
        ", or a max_speed of at least {} mm/s",
        short_up(t.speed)
    ));
    let next = if j + 1 == n {
        "1 of the next layer".to_string()
    } else {
        (j + 2).to_string()
    };
    Diagnostic::error(
        Code::TransitionSpeed,
        format!(
            "the transition from segment {} to {next} ({} mm over {} mm, γ = {}°) runs at {} mm/s at the clamp's {} mm/s, over {}'s max_speed {} mm/s",
            j + 1,
            short(t.rise),
            short(t.arc),
            short(gamma.to_degrees().abs()),
            short(t.speed),
            short(t.top),
            t.machine,
            short(t.max)
        ),
    )
    .label(t.spans[0], "max_speed")
    .label(t.spans[1], "the loop may command up to here")
    .label(t.spans[2], "transition")
    .help(help)
}
