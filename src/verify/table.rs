//! Rules of the rotary axes in machine coordinates: how fast the axes move
//! while the part turns under the nozzle, and a tilting table's C axis,
//! which must follow a whole layer without unwinding.
//!
//! A move's time is the plan's (its part-frame length at its path speed,
//! [`table::machine_feed`]); in that time a table's linear axes go the
//! machine chord between the inverse kinematics of its ends, and every
//! rotary axis its angle change. Positions and angles against the travel
//! are [`super::machine::Travel`]'s.

use super::rule::{MachineCx, PlanRule, Worst};
use crate::diag::message::verify::table as says;
use crate::diag::Diagnostics;
use crate::ir::MachineField;
use crate::ir::{Kinematics, Machine, RotaryTable};
use crate::plan::kinematics::{Rotary, LIMIT_TOL_DEG};
use crate::plan::{table, Move, MoveKind, Speed, Visit, Where};

/// `lmd::axis-speed`: a feed move whose machine axes must go faster than
/// the machine does: a table's linear axes beyond `max_speed`, a rotary
/// axis beyond `rotary_speed`.
pub(super) struct AxisSpeed {
    kin: Kinematics,
    /// A table's axes (its linear axes' speed is checked).
    table: Option<RotaryTable>,
    origin: [f64; 3],
    max_speed: f64,
    rotary_speed: Option<f64>,
    /// The last move's part point, machine point and angles.
    last: Option<([f64; 3], [f64; 3], Rotary)>,
    /// Linear, tilt, C.
    found: [Option<Worst>; 3],
}

impl Visit for AxisSpeed {
    fn motion(&mut self, m: &Move) {
        let at = match &self.table {
            Some(t) => table::written(self.kin, t, self.origin, m.to, m.axes),
            None => m.to,
        };
        let last = self.last.replace((m.to, at, m.axes));
        let (Speed::Feed(v), Some((part, machine, r))) = (m.speed, last) else {
            return;
        };
        let turn = (m.axes.tilt - r.tilt, m.axes.c - r.c);
        let chord = table::distance(machine, at);
        let f = table::machine_feed(v as f64, table::distance(part, m.to), chord, turn);
        if f.time <= 0.0 {
            return;
        }
        // A little over the limit is the F word's rounding (0.1 mm/min).
        let over = |s: f64, max: f64| s > max * (1.0 + 1e-6);
        if self.table.is_some() && over(chord / f.time, self.max_speed) {
            Worst::hit(
                &mut self.found[0],
                chord / f.time,
                self.max_speed,
                m.source(),
            );
        }
        if let Some(max) = self.rotary_speed {
            for (i, d) in [(1, turn.0), (2, turn.1)] {
                let s = d.abs() / f.time;
                if over(s, max) {
                    Worst::hit(&mut self.found[i], s, max, m.source());
                }
            }
        }
    }
}

impl<'p> PlanRule<'p> for AxisSpeed {
    fn new(cx: &MachineCx<'p>) -> Option<Self> {
        let Machine::Cnc(c) = cx.machine else {
            return None;
        };
        let kin = c.effective_kinematics();
        let table = c.table.filter(|_| kin.is_table());
        (table.is_some() || (kin != Kinematics::Xyz && c.rotary_speed.is_some())).then_some(
            AxisSpeed {
                kin,
                table,
                origin: c.placement.origin,
                max_speed: c.max_speed,
                rotary_speed: c.rotary_speed,
                last: None,
                found: [None; 3],
            },
        )
    }

    fn report(self, cx: &MachineCx<'p>, out: &mut Diagnostics) {
        let tilt = self.kin.tilt_letter().unwrap_or('A');
        for (i, w) in self.found.iter().enumerate() {
            let Some(w) = w else { continue };
            let (axis, field) = match i {
                0 => ("X Y Z".to_string(), MachineField::MaxSpeed),
                1 => (tilt.to_string(), MachineField::RotarySpeed),
                _ => ("C".to_string(), MachineField::RotarySpeed),
            };
            out.push(says::axis_speed(
                cx.machine.name(),
                &axis,
                w,
                cx.origin.at(field),
            ));
        }
    }
}

/// `lmd::c-unwind`: a run the C axis must follow without unwinding, along
/// which it turns further than its travel: a tilting table's layer, or a
/// tilting head's paths from one retract to the next (it unwinds there).
pub(super) struct CUnwind {
    range: [f64; 2],
    /// A head (runs end at a retract), not a table (runs are layers).
    head: bool,
    /// The C angles of the run under way (its points' moves).
    run: Option<[f64; 2]>,
    /// Where the run's C was furthest from its start.
    at: Where,
    found: Option<Worst>,
}

impl CUnwind {
    fn end_run(&mut self) {
        if let Some([lo, hi]) = self.run.take() {
            let width = self.range[1] - self.range[0];
            if hi - lo > width + 2.0 * LIMIT_TOL_DEG {
                Worst::hit(&mut self.found, hi - lo, width, self.at);
            }
        }
    }
}

impl Visit for CUnwind {
    fn layer(&mut self, _index: usize, _layer: &crate::ir::Layer) {
        self.end_run();
    }

    fn motion(&mut self, m: &Move) {
        if self.head && m.kind == MoveKind::Retract {
            self.end_run();
        }
        // The run's own points: the moves into it still carry the angles
        // the last one ended at.
        if !matches!(m.at, Where::Point { .. }) {
            return;
        }
        let c = m.axes.c;
        match &mut self.run {
            None => self.run = Some([c, c]),
            Some(r) => {
                if c < r[0] || c > r[1] {
                    self.at = m.at;
                }
                *r = [r[0].min(c), r[1].max(c)];
            }
        }
    }
}

impl<'p> PlanRule<'p> for CUnwind {
    fn new(cx: &MachineCx<'p>) -> Option<Self> {
        let Machine::Cnc(c) = cx.machine else {
            return None;
        };
        let kin = c.effective_kinematics();
        (kin != Kinematics::Xyz).then_some(CUnwind {
            range: c.limits.rotary,
            head: !kin.is_table(),
            run: None,
            at: Where::End,
            found: None,
        })
    }

    fn report(mut self, cx: &MachineCx<'p>, out: &mut Diagnostics) {
        self.end_run();
        let Some(w) = self.found else { return };
        out.push(says::c_unwind(
            cx.machine.name(),
            &w,
            (self.range, self.head),
            cx.origin.at(MachineField::Limit('C')),
        ));
    }
}
