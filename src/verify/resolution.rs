//! Values as the program writes them. A power, speed or position is written only
//! when the machine's settings let the program say it: within
//! [`WRITE_TOLERANCE`] of the plan, never rounded to 0, never too large to print
//! (the formatters would otherwise have to write *something*). Each rule names
//! the setting that would fix it.

use super::rule::{MachineCx, PlanRule, Worst};
use crate::diag::message::verify::machine::SpeedWord;
use crate::diag::{message, Diagnostics};
use crate::ir::Machine;
use crate::ir::MachineField as Field;
use crate::plan::kinematics::Rotary;
use crate::plan::{Move, MoveKind, Speed, Visit};
use crate::target::same_direction;
use crate::target::{gcode, kuka, quantised, written, MAX_WRITTEN, POSITION_STEP};

/// `lmd::resolution`: powers and speeds one machine cannot write, and
/// positions too large to.
pub(super) struct Resolution<'p> {
    machine: &'p Machine,
    /// Planned value and how it would be written (0 if it could not be).
    speed: Option<Worst>,
    power: Option<Worst>,
    /// The smallest positive power and speed planned (what the help sizes
    /// the settings for).
    least_power: f64,
    least_speed: f64,
    position: Option<Worst>,
    /// The last speed and power (f32 bits) found writable: most moves repeat them.
    speed_ok: u32,
    power_ok: u32,
}

impl<'p> PlanRule<'p> for Resolution<'p> {
    fn new(cx: &MachineCx<'p>) -> Option<Self> {
        Some(Resolution {
            machine: cx.machine,
            speed: None,
            power: None,
            least_power: f64::INFINITY,
            least_speed: f64::INFINITY,
            position: None,
            // NaN bits: no planned value (all finite) matches them.
            speed_ok: u32::MAX,
            power_ok: u32::MAX,
        })
    }

    fn report(self, cx: &MachineCx<'p>, out: &mut Diagnostics) {
        let (machine, o) = (cx.machine, cx.origin);
        let speeds = cx.program.origins.bead_speed;
        let has = |f: Field| o.written(f).is_some();
        if let Some(w) = self.position {
            out.push(message::verify::machine::position_too_large(
                machine.name(),
                &w,
                o.at(Field::Name),
            ));
        }
        if let Some(w) = self.speed {
            // The setting that decides how F is written, if declared.
            let field = match machine {
                Machine::Cnc(_) if has(Field::FeedUnits) => Field::FeedUnits,
                _ => Field::Name,
            };
            let word = match machine {
                Machine::Cnc(c) => SpeedWord::F {
                    unit: c.dialect.feed.text(),
                    per_mm_s: c.dialect.feed.per_mm_s(),
                    decimals: gcode::f_decimals(c.dialect.feed),
                },
                Machine::Robot(_) => SpeedWord::VelCp,
            };
            out.push(message::verify::machine::speed_unwritable(
                machine.name(),
                word,
                &w,
                self.least_speed,
                o.at(field),
                speeds,
            ));
        }
        if let Some(w) = self.power {
            let d = match machine {
                Machine::Cnc(c) => {
                    let field = if has(Field::SDecimals) {
                        Field::SDecimals
                    } else {
                        Field::SPerWatt
                    };
                    message::verify::machine::cnc_power_unwritable(
                        &c.name,
                        c.dialect.s_per_watt,
                        c.dialect.s_decimals,
                        &w,
                        self.least_power,
                        o.at(field),
                    )
                }
                Machine::Robot(r) => message::verify::machine::robot_power_unwritable(
                    (&r.name, message::words::Words::of(r.controller)),
                    &r.power_out,
                    r.full_scale_power,
                    &w,
                    o.at(Field::FullScale),
                ),
            };
            out.push(d);
        }
    }
}

impl Visit for Resolution<'_> {
    #[inline]
    fn motion(&mut self, m: &Move) {
        let machine = self.machine;
        if !m.to.iter().all(|v| v.abs() < MAX_WRITTEN)
            || m.axes.tilt.abs() >= MAX_WRITTEN
            || m.axes.c.abs() >= MAX_WRITTEN
        {
            let worst = m.to.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            Worst::hit(&mut self.position, worst, MAX_WRITTEN, m.at);
        }
        let v = match (m.speed, machine) {
            (Speed::Feed(v), _) if v.to_bits() == self.speed_ok => None,
            (Speed::Feed(v), _) => Some((v as f64, v.to_bits())),
            (Speed::Rapid, Machine::Robot(r)) => Some((r.max_speed, u32::MAX)),
            (Speed::Rapid, Machine::Cnc(_)) => None, // G0 has no F
        };
        if let Some((v, bits)) = v {
            let (scale, decimals) = speed_word(machine);
            if quantised(v * scale, decimals).is_some() {
                self.speed_ok = bits;
            } else {
                self.least_speed = self.least_speed.min(v);
                let w = written(v * scale, decimals) / scale;
                Worst::hit(&mut self.speed, v, w, m.source());
            }
        }
        if m.deposits() && m.power > 0.0 && m.power.to_bits() != self.power_ok {
            let p = m.power as f64;
            let (scale, decimals) = power_word(machine);
            if quantised(p * scale, decimals).is_some() {
                self.power_ok = m.power.to_bits();
            } else {
                self.least_power = self.least_power.min(p);
                let w = written(p * scale, decimals) / scale;
                Worst::hit(&mut self.power, p, w, m.source());
            }
        }
    }
}

/// The speed word's scale (per mm/s) and decimals.
fn speed_word(m: &Machine) -> (f64, usize) {
    match m {
        Machine::Cnc(c) => (c.dialect.feed.per_mm_s(), gcode::f_decimals(c.dialect.feed)),
        Machine::Robot(_) => (1e-3, kuka::VEL_DECIMALS),
    }
}

/// The power word's scale (per W) and decimals.
fn power_word(m: &Machine) -> (f64, usize) {
    match m {
        Machine::Cnc(c) => (c.dialect.s_per_watt, c.dialect.s_decimals),
        Machine::Robot(r) => (1.0 / r.full_scale_power, kuka::ANOUT_DECIMALS),
    }
}

/// `lmd::short-move`: moves shorter than the step positions are written
/// at ([`POSITION_STEP`]) where the nozzle stands as it did: each prints
/// as no move or a step of one digit. Lowering merges them inside a path,
/// so what is found here is a path of one place or a plan's own move.
pub(super) struct ShortMoves {
    /// The last move's target, nozzle direction and rotary axes.
    last: Option<([f64; 3], [f32; 3], Rotary)>,
    found: Option<Worst>,
}

impl<'p> PlanRule<'p> for ShortMoves {
    fn new(_cx: &MachineCx<'p>) -> Option<Self> {
        Some(ShortMoves {
            last: None,
            found: None,
        })
    }

    fn report(self, cx: &MachineCx<'p>, out: &mut Diagnostics) {
        if let Some(w) = self.found {
            out.push(message::verify::machine::short_moves(
                cx.machine.name(),
                &w,
                cx.origin.at(Field::Name),
            ));
        }
    }
}

impl Visit for ShortMoves {
    #[inline]
    fn motion(&mut self, m: &Move) {
        // A lift writes Z alone, and home is axis angles: neither's `to` is
        // where the program leaves the nozzle. A PTP from home comes from
        // axis angles too.
        if matches!(m.kind, MoveKind::Lift | MoveKind::Home) {
            self.last = None;
            return;
        }
        let last = self.last.replace((m.to, m.normal, m.axes));
        let (Some((to, normal, axes)), false) = (last, m.kind == MoveKind::FromHome) else {
            return;
        };
        let d2: f64 = (0..3).map(|i| (m.to[i] - to[i]).powi(2)).sum();
        if d2 >= POSITION_STEP * POSITION_STEP {
            return;
        }
        // A turn of the nozzle or the axes in place is a move of its own.
        let turned = (m.axes.tilt - axes.tilt).abs() >= POSITION_STEP
            || (m.axes.c - axes.c).abs() >= POSITION_STEP
            || !same_direction(normal, m.normal);
        if !turned {
            Worst::hit(&mut self.found, d2.sqrt(), POSITION_STEP, m.at);
        }
    }
}
