//! A ring's rules (seed 004): its height loop, analysed before anything is
//! built (signs, stability at every segment's speed, settling against the
//! layers: [`control::analyse`], whose findings carry the numbers and the
//! wording), and what each machine must offer to run it — transitions within
//! its `max_speed` at the loop's top speed, a sensor input, a control that
//! can run the loop.

use crate::control::{self, analyse, Finding, Severity, SpeedPerLength};
use crate::diag::{Code, Diagnostic, Diagnostics};
use crate::ir::{Machine, MachineOrigin, Program, Ring, RingOrigins, RingRun};
use crate::target::gcode::{LOOP_PROFILE, MAX_ANALOG_INPUT};
use crate::target::kuka::MAX_ADVANCE;
use crate::units::{short, Angle, Length, Speed};
use std::num::NonZeroUsize;

/// The declared loop as the control module's checked type, or why not.
pub fn controller(r: &Ring) -> Option<Result<control::Controller, control::Invalid>> {
    let c = r.run.control()?;
    Some(
        control::Clamp::new(Speed(c.clamp[0]), Speed(c.clamp[1])).and_then(|clamp| {
            control::Controller::new(
                SpeedPerLength::from_mm_s_per_mm(c.kp),
                SpeedPerLength::from_mm_s_per_mm(c.ki),
                Length(c.target),
                clamp,
            )
        }),
    )
}

/// The loop's analysis: every finding as a diagnostic.
pub(super) fn check_loop(p: &Program, out: &mut Diagnostics) {
    let Some(r) = &p.ring else { return };
    let o = p.origins.ring.unwrap_or_default();
    let c = match controller(r) {
        None => return,
        Some(Ok(c)) => c,
        Some(Err(e)) => {
            out.push(
                Diagnostic::error(Code::OutOfRange, format!("the height loop cannot run: {e}"))
                    .label(o.control, "control"),
            );
            return;
        }
    };
    let speeds: Vec<Speed> = r.segments.iter().map(|s| Speed(s.speed)).collect();
    let Some(layers) = NonZeroUsize::new(p.layers.len()) else {
        return;
    };
    match analyse(&c, &speeds, layers) {
        Ok(a) => {
            for f in &a.findings {
                out.push(finding(f, &o));
            }
        }
        Err(e) => out.push(
            Diagnostic::error(Code::OutOfRange, format!("the height loop cannot run: {e}"))
                .label(o.control, "control"),
        ),
    }
}

/// One finding of the analysis, at the fields it is about.
fn finding(f: &Finding, o: &RingOrigins) -> Diagnostic {
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

/// What machine `m` must offer to run the ring's loop.
pub(super) fn check_machine(
    p: &Program,
    m: &Machine,
    origin: &MachineOrigin,
    out: &mut Diagnostics,
) {
    let Some(r) = &p.ring else { return };
    let RingRun::OnMachine(law) = &r.run else {
        // A schedule is plain speeds: the machine rules check them.
        return;
    };
    let o = p.origins.ring.unwrap_or_default();
    transitions(r, law.clamp[1], m, origin, &o, out);
    let name = m.name();
    let sensor = match m {
        Machine::Robot(rb) => rb.height_sensor,
        Machine::Cnc(c) => {
            if c.dialect.profile != LOOP_PROFILE {
                out.push(
                    Diagnostic::error(
                        Code::LoopDialect,
                        format!(
                            "the height loop is to run on machine `{name}`, and a closed loop is not supported on the {} dialect",
                            c.dialect.profile
                        ),
                    )
                    .label(origin.at("dialect"), "dialect")
                    .label(o.run, "the loop runs on the machine")
                    .help("`run = schedule` writes an open-loop speed schedule (the loop run against the declared plant) that every dialect runs; a closed loop runs on LinuxCNC and KUKA robots"),
                );
            }
            c.height_sensor
        }
    };
    let Some(s) = sensor else {
        out.push(
            Diagnostic::error(
                Code::HeightSensor,
                format!("machine `{name}` declares no height sensor for the loop to read"),
            )
            .label(origin.block, "no `height_input`")
            .label(o.run, "the loop runs on the machine")
            .help("declare the analog input the sensor's segment mean arrives on: `height_input = 3` and `height_full_scale = 2 mm` (the height at 1.0); or `run = schedule` for an open-loop schedule"),
        );
        return;
    };
    if let Machine::Robot(_) = m {
        robot_timing(r, law.clamp[1], s, name, origin, &o, out);
    }
    if let Machine::Cnc(_) = m {
        let last = s.input as usize + r.segments.len() - 1;
        if last > MAX_ANALOG_INPUT {
            out.push(
                Diagnostic::error(
                    Code::HeightSensor,
                    format!(
                        "LinuxCNC reads segment j's height on input `height_input + j`: {} segments from input {} reach M66 E{last}, past E{MAX_ANALOG_INPUT}",
                        r.segments.len(),
                        s.input
                    ),
                )
                .label(origin.at("height_input"), "first input")
                .help(format!(
                    "a first input of at most {}",
                    MAX_ANALOG_INPUT + 1 - r.segments.len().min(MAX_ANALOG_INPUT + 1)
                )),
            );
        }
    }
}

/// On a robot, segment `j`'s update runs as a trigger `delay` after the
/// segment's last move, in the main run, while the advance run reads up to
/// [`MAX_ADVANCE`] moves ahead. The first to read what it sets is segment
/// `j − 1`'s transition on the next layer (it climbs to segment `j`'s new
/// height), `(n − 2)·per + flat` moves after the update's move: the update
/// must land before the advance run gets there. One segment never can: it
/// starts again where it ends.
fn robot_timing(
    r: &Ring,
    top: f64,
    s: crate::ir::HeightSensor,
    name: &str,
    origin: &MachineOrigin,
    o: &RingOrigins,
    out: &mut Diagnostics,
) {
    let n = r.segments.len();
    let per = r.flat_moves + r.transition_moves;
    let arc = r.radius * r.transition.to_radians();
    let mu = std::f64::consts::TAU / n as f64;
    // The shortest move, horizontally (its path is no shorter).
    let flat_len = r.radius * (mu - r.transition.to_radians()) / r.flat_moves.max(1) as f64;
    let shortest = flat_len.min(arc / r.transition_moves.max(1) as f64);
    // The fastest the robot may run: a transition at the clamp's top.
    let fastest = (0..n)
        .map(|j| {
            let next = &r.segments[(j + 1) % n];
            let extra = if j + 1 == n { r.layer_height } else { 0.0 };
            let rise = next.defocus - r.segments[j].defocus + extra;
            control::ring::path_speed(Speed(top), Length(rise), Length(arc)).0
        })
        .fold(top, f64::max);
    let during_delay = (s.delay * fastest / shortest).ceil();
    // Moves between the update's move and the first that reads its values,
    // less those the advance run may be ahead, less one for the
    // approximation at the trigger's move.
    let room = (n as f64 - 2.0) * per as f64 + r.flat_moves as f64 - MAX_ADVANCE as f64 - 1.0;
    if room >= during_delay {
        return;
    }
    let message = if n == 1 {
        format!(
            "a ring of one segment cannot run its loop on robot `{name}`: the segment starts again where it ends, before its measurement can change its speed and height"
        )
    } else {
        format!(
            "on robot `{name}` a segment's update could land after the robot has read the values it sets: it runs {} ms after the segment's end (up to {} moves of {} mm at {} mm/s), and the next reader comes {} moves later, of which the advance run may read {} ahead",
            short(s.delay * 1000.0),
            during_delay,
            short(shortest),
            short(fastest),
            (n - 2) * per + r.flat_moves,
            MAX_ADVANCE
        )
    };
    out.push(
        Diagnostic::error(Code::LoopTiming, message)
            .label(origin.at("height_delay"), "height_delay")
            .label(o.ring, "ring")
            .help("more segments, fewer or longer moves (a larger `step`), a shorter `height_delay`, or `run = schedule`; LinuxCNC, which stops to read, has no such limit"),
    );
}

/// Every transition at the clamp's top speed within the machine's
/// `max_speed`: on the machine the loop may drive any segment up to it.
fn transitions(
    r: &Ring,
    top: f64,
    m: &Machine,
    origin: &MachineOrigin,
    o: &RingOrigins,
    out: &mut Diagnostics,
) {
    let max = match m {
        Machine::Robot(rb) => rb.max_speed,
        Machine::Cnc(c) => c.max_speed,
    };
    let arc = r.radius * r.transition.to_radians();
    // The transitions of the plan: the defocus steps, and the layer change.
    let n = r.segments.len();
    let worst = (0..n)
        .map(|j| {
            let next = &r.segments[(j + 1) % n];
            let extra = if j + 1 == n { r.layer_height } else { 0.0 };
            let rise = next.defocus - r.segments[j].defocus + extra;
            let v = control::ring::path_speed(Speed(top), Length(rise), Length(arc)).0;
            (j, rise, v)
        })
        .fold(None, |best: Option<(usize, f64, f64)>, c| match best {
            Some(b) if b.2 >= c.2 => Some(b),
            _ => Some(c),
        });
    let Some((j, rise, v)) = worst else { return };
    if v <= max {
        return;
    }
    let gamma = (rise / arc).atan();
    let clamp_fits = max * gamma.cos();
    let mut help = format!("a clamp up to {} mm/s", short(clamp_fits));
    if top < max {
        // v·√(1 + (rise/arc)²) ≤ max ⇔ arc ≥ |rise| / √((max/v)² − 1).
        let arc_fits = rise.abs() / ((max / top).powi(2) - 1.0).sqrt();
        let deg = Angle(arc_fits / r.radius).deg();
        help.push_str(&format!(", a transition of at least {}°", short_up(deg)));
    }
    help.push_str(", or a higher max_speed");
    let next = if j + 1 == n {
        "1 of the next layer".to_string()
    } else {
        (j + 2).to_string()
    };
    out.push(
        Diagnostic::error(
            Code::TransitionSpeed,
            format!(
                "the transition from segment {} to {next} ({} mm over {} mm, γ = {}°) runs at {} mm/s at the clamp's {} mm/s, over {}'s max_speed {} mm/s",
                j + 1,
                short(rise),
                short(arc),
                short(gamma.to_degrees().abs()),
                short(v),
                short(top),
                m.name(),
                short(max)
            ),
        )
        .label(origin.at("max_speed"), "max_speed")
        .label(o.clamp, "the loop may command up to here")
        .label(o.transition, "transition")
        .help(help),
    );
}

/// `x` rounded up to what `short` prints, so the advice is enough.
fn short_up(x: f64) -> String {
    let p = 10f64.powi(2);
    short((x * p).ceil() / p)
}
