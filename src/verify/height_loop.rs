//! A segmented ring's rules: its height loop, analysed before anything is
//! built (signs, stability at every segment's speed, settling against the
//! layers: [`control::analyse`], whose findings carry the numbers and the
//! wording), and what each machine must offer to run it — transitions within
//! its `max_speed` at the loop's top speed, a sensor input, a control that
//! can run the loop.

use super::rule::{MachineCx, PlanRule, ProgramCx, ProgramRule};
use crate::control::{self, analyse, SpeedPerLength};
use crate::diag::message::verify::height_loop::{
    self as says, FastTransition, LateUpdate, LoopFields,
};
use crate::diag::Diagnostics;
use crate::ir::MachineField;
use crate::ir::{Machine, MachineOrigin, Program, Ring, RingOrigins, RingRun};
use crate::plan::{Move, Visit};
use crate::target::gcode::{LOOP_PROFILE, MAX_ANALOG_INPUT};
use crate::target::kuka::MAX_ADVANCE;
use crate::units::{Angle, Length, Speed};
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

/// `lmd::gain-sign`, `lmd::unstable-loop`, `lmd::slow-loop`: the loop's
/// analysis, every finding as a diagnostic.
pub(super) struct LoopAnalysis;

impl ProgramRule for LoopAnalysis {
    fn check(cx: &ProgramCx<'_>, out: &mut Diagnostics) {
        check_loop(cx.program, out);
    }
}

fn check_loop(p: &Program, out: &mut Diagnostics) {
    let Some(r) = &p.ring else { return };
    let o = p.origins.ring.unwrap_or_default();
    let c = match controller(r) {
        None => return,
        Some(Ok(c)) => c,
        Some(Err(e)) => {
            out.push(says::loop_cannot_run(&e, o.control));
            return;
        }
    };
    let speeds: Vec<Speed> = r.segments.iter().map(|s| Speed(s.speed)).collect();
    let Some(layers) = NonZeroUsize::new(p.layers.len()) else {
        return;
    };
    match analyse(&c, &speeds, layers) {
        Ok(a) => {
            let fields = LoopFields {
                kp: o.kp,
                ki: o.ki,
                clamp: o.clamp,
                layers: o.layers,
            };
            for f in &a.findings {
                out.push(says::loop_finding(f, &fields));
            }
        }
        Err(e) => out.push(says::loop_cannot_run(&e, o.control)),
    }
}

/// `lmd::transition-speed`, `lmd::loop-dialect`, `lmd::height-sensor`,
/// `lmd::loop-timing`: what a machine must offer to run the ring's loop. It
/// reads the declarations, not the moves.
pub(super) struct LoopOnMachine;

impl Visit for LoopOnMachine {
    fn motion(&mut self, _: &Move) {}
}

impl<'p> PlanRule<'p> for LoopOnMachine {
    fn new(cx: &MachineCx<'p>) -> Option<Self> {
        cx.program.ring.as_ref().map(|_| LoopOnMachine)
    }

    fn report(self, cx: &MachineCx<'p>, out: &mut Diagnostics) {
        check_machine(cx.program, cx.machine, cx.origin, out);
    }
}

fn check_machine(p: &Program, m: &Machine, origin: &MachineOrigin, out: &mut Diagnostics) {
    let Some(r) = &p.ring else { return };
    let RingRun::OnMachine(law) = &r.run else {
        // A schedule is plain speeds: the machine rules check them.
        return;
    };
    let o = p.origins.ring.unwrap_or_default();
    transitions(r, law.clamp[1], m, origin, &o, out);
    let name = m.name();
    if let Machine::Cnc(c) = m {
        if crate::plan::table::machine_output(c).is_some() {
            out.push(says::loop_on_table_machine(
                name,
                origin.at(MachineField::TableOutput),
                o.run,
            ));
        }
        if c.dialect.profile != LOOP_PROFILE {
            out.push(says::loop_dialect(
                name,
                &c.dialect.profile,
                "dialect",
                origin.at(MachineField::Dialect),
                o.run,
            ));
        }
    }
    if let Machine::Robot(rb) = m {
        if rb.controller == crate::ir::Controller::Abb {
            let at = origin.at(MachineField::Controller);
            out.push(says::loop_dialect(name, &"ABB", "controller", at, o.run));
        }
        if rb.positioner.is_some() {
            let at = origin.at(MachineField::Positioner);
            out.push(says::loop_on_positioner(name, at, o.run));
        }
    }
    let Some(s) = m.common().height_sensor else {
        out.push(says::no_height_sensor(name, origin.block, o.run));
        return;
    };
    if let Machine::Robot(_) = m {
        robot_timing(r, law.clamp[1], s, name, origin, &o, out);
    }
    if let Machine::Cnc(_) = m {
        let last = s.input as usize + r.segments.len() - 1;
        if last > MAX_ANALOG_INPUT {
            out.push(says::too_many_inputs(
                r.segments.len(),
                s.input,
                last,
                origin.at(MachineField::HeightInput),
            ));
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
            control::geometry::path_speed(Speed(top), Length(rise), Length(arc)).0
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
    let why = if n == 1 {
        LateUpdate::OneSegment
    } else {
        LateUpdate::TooLate {
            delay: s.delay,
            during_delay,
            shortest,
            fastest,
            between: (n - 2) * per + r.flat_moves,
        }
    };
    out.push(says::loop_timing(
        name,
        &why,
        origin.at(MachineField::HeightDelay),
        o.ring,
    ));
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
    let max = m.common().max_speed;
    let arc = r.radius * r.transition.to_radians();
    // The transitions of the plan: the defocus steps, and the layer change.
    let n = r.segments.len();
    let worst = (0..n)
        .map(|j| {
            let next = &r.segments[(j + 1) % n];
            let extra = if j + 1 == n { r.layer_height } else { 0.0 };
            let rise = next.defocus - r.segments[j].defocus + extra;
            let v = control::geometry::path_speed(Speed(top), Length(rise), Length(arc)).0;
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
    // v·√(1 + (rise/arc)²) ≤ max ⇔ arc ≥ |rise| / √((max/v)² − 1).
    let arc_fits = (top < max).then(|| rise.abs() / ((max / top).powi(2) - 1.0).sqrt());
    let transition_fits = arc_fits.map(|a| Angle(a / r.radius).deg());
    // The same arc at the declared transition angle: a larger ring.
    let radius_fits = arc_fits.map(|a| a / r.transition.to_radians());
    out.push(says::transition_speed(&FastTransition {
        machine: m.name(),
        max,
        segment: j,
        segments: n,
        rise,
        arc,
        speed: v,
        top,
        transition_fits,
        radius_fits,
        spans: [origin.at(MachineField::MaxSpeed), o.clamp, o.transition],
    }));
}
