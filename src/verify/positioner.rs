//! A robot's positioner (`lmd::positioner-limit`, `lmd::positioner-speed`):
//! each layer's E1 and E2, and its home, inside the axes' limits, and on
//! every line the angles' change within the axes' speeds: a deposit that
//! runs on into the next layer, and the laser-off lines between layers,
//! which the plan slows to the axes ([`crate::plan::held_to_axes`]). The
//! PTPs from and back home move at the controller's PTP speeds. The arm's own rules see the
//! poses through the positioner ([`crate::plan::arm::Follow`]).

use super::rule::{MachineCx, PlanRule, Worst};
use crate::diag::message::positioner as says;
use crate::diag::Diagnostics;
use crate::ir::MachineField;
use crate::ir::{Machine, Positioner};
use crate::plan::{Move, Speed, Visit, JOIN_MM};

/// `lmd::positioner-limit` and `lmd::positioner-speed` of one robot.
pub(super) struct PositionerRule {
    positioner: Positioner,
    /// The robot's rapid, mm/s.
    rapid: f64,
    /// Where the last move ended and its angles.
    last: Option<([f64; 3], [f64; 2])>,
    speed: [Option<Worst>; 2],
}

impl Visit for PositionerRule {
    fn motion(&mut self, m: &Move) {
        let e = [m.axes.tilt, m.axes.c];
        let last = self.last.replace((m.to, e));
        let Some((from, was)) = last.filter(|_| !m.kind.ptp()) else {
            // A PTP (from and back home) moves the axes at the controller's
            // PTP speeds, within their own.
            return;
        };
        let d = (0..3)
            .map(|i| (m.to[i] - from[i]).powi(2))
            .sum::<f64>()
            .sqrt();
        let v = match m.speed {
            Speed::Feed(v) => v as f64,
            // A rapid line of no length turns the axes alone, at their own
            // speeds; a longer one at the robot's rapid.
            Speed::Rapid if d <= JOIN_MM => return,
            Speed::Rapid => self.rapid,
        };
        let axes = [&self.positioner.tilt, &self.positioner.rotate];
        for i in 0..2 {
            let turn = (e[i] - was[i]).abs();
            if turn <= 1e-9 {
                continue;
            }
            // A turn of the part under a standing nozzle takes no time at
            // the path speed: any turn is too fast.
            let rate = if d > 0.0 && v > 0.0 {
                turn / (d / v)
            } else {
                f64::INFINITY
            };
            // Within a speed's single-precision digits is within it.
            if rate > axes[i].speed * (1.0 + 1e-6) {
                Worst::hit(
                    &mut self.speed[i],
                    rate.min(1e12),
                    axes[i].speed,
                    m.source(),
                );
            }
        }
    }
}

impl<'p> PlanRule<'p> for PositionerRule {
    fn new(cx: &MachineCx<'p>) -> Option<Self> {
        let Machine::Robot(r) = cx.machine else {
            return None;
        };
        Some(PositionerRule {
            positioner: *r.positioner.clone()?,
            rapid: r.max_speed,
            last: None,
            speed: [None; 2],
        })
    }

    fn report(self, cx: &MachineCx<'p>, out: &mut Diagnostics) {
        let name = cx.machine.name();
        let p = &self.positioner;
        let keep = cx
            .origin
            .written(MachineField::PositionerKeep)
            .or(cx.origin.written(MachineField::Positioner));
        let fields = [
            (&p.tilt, MachineField::TiltLimits, MachineField::TiltSpeed),
            (
                &p.rotate,
                MachineField::RotateLimits,
                MachineField::RotateSpeed,
            ),
        ];
        for (i, (axis, limits, _)) in fields.iter().enumerate() {
            let mut worst: Option<crate::diag::Worst<usize>> = None;
            for (layer, e) in p.angles.iter().enumerate() {
                let [lo, hi] = axis.limits;
                let a = e[i];
                if a < lo - 1e-9 {
                    crate::diag::Worst::hit(&mut worst, a, lo, layer + 1);
                } else if a > hi + 1e-9 {
                    crate::diag::Worst::hit(&mut worst, a, hi, layer + 1);
                }
            }
            if let Some(w) = worst {
                let declared = cx.origin.written(*limits);
                out.push(says::limit(name, i, &w, axis.limits, declared, keep));
            }
            let [lo, hi] = axis.limits;
            let home = p.home[i];
            if home < lo - 1e-9 || home > hi + 1e-9 {
                let at = cx
                    .origin
                    .written(MachineField::PositionerHome)
                    .or(cx.origin.written(*limits));
                out.push(says::home_limit(name, i, home, axis.limits, at));
            }
        }
        for (i, w) in self.speed.iter().enumerate() {
            if let Some(w) = w {
                out.push(says::speed(name, i, w, cx.origin.written(fields[i].2)));
            }
        }
    }
}
