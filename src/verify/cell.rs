//! The cell's gas and powder along a machine's motion plan: at every laser
//! start the gas must have flowed its `pre_flow` and the powder its `arrival`
//! time since the feeder started or changed rate; with a rate output, every
//! deposit's powder feed must be the rate set and within the output's full
//! scale.
//!
//! Time is counted as the plan's feed moves at their speeds plus its dwells;
//! rapid moves count as instant, so the real time is never shorter than the
//! one checked.

use super::rule::{MachineCx, PlanRule, Worst};
use crate::diag::{message, Diagnostics};
use crate::ir::MachineField;
use crate::ir::{Cell, MachineOrigin, Program};
use crate::plan::{Io, Move, Speed, Visit};

/// Slack on times, s: the plan waits exactly the declared times, which sums
/// of move times may miss by rounding.
const TIME_SLACK_S: f64 = 1e-6;

/// `lmd::powder-arrival` and `lmd::powder-rate`: the gas and powder timing
/// and the feed-rate output along one plan, on machines that switch them.
pub(super) struct CellRule<'p> {
    program: &'p Program,
    cell: Cell,
    /// Plan time so far, s.
    t: f64,
    at: Option<[f64; 3]>,
    gas_since: Option<f64>,
    powder_since: Option<f64>,
    rate: Option<f32>,
    /// Laser starts with too little gas time: the shortest wait.
    gas_short: Option<Worst>,
    /// Laser starts before the powder arrived.
    powder_short: Option<Worst>,
    /// Deposits at another feed than the rate output is set to.
    rate_differs: Option<Worst>,
    /// Rates beyond the output's full scale.
    rate_over: Option<Worst>,
    /// Deposits of a style with a powder feed of its own on a machine
    /// whose feeder has no rate output: the feed (as its value) and the
    /// style's id (as its limit).
    unfed: Option<Worst>,
}

impl<'p> CellRule<'p> {
    /// The rule for a machine with `cell`, or `None` when it switches
    /// nothing and no style feeds powder of its own.
    fn with(program: &'p Program, cell: &Cell) -> Option<Self> {
        let styled = program.styles.iter().any(|s| s.powder.is_some());
        (!cell.is_none() || styled).then(|| CellRule {
            program,
            cell: cell.clone(),
            t: 0.0,
            at: None,
            gas_since: None,
            powder_since: None,
            rate: None,
            gas_short: None,
            powder_short: None,
            rate_differs: None,
            rate_over: None,
            unfed: None,
        })
    }

    /// Reports what was found, at the fields that declare the times.
    fn report_at(self, name: &str, o: &MachineOrigin, out: &mut Diagnostics) {
        use message::verify::cell;
        if let (Some(w), Some(g)) = (self.gas_short, self.cell.gas) {
            out.push(cell::gas_too_short(
                name,
                &w,
                g.pre_flow,
                o.at(MachineField::GasPreFlow),
            ));
        }
        if let (Some(w), Some(p)) = (self.powder_short, &self.cell.powder) {
            out.push(cell::powder_too_early(
                name,
                &w,
                p.arrival,
                o.at(MachineField::PowderArrival),
            ));
        }
        let full = self.cell.powder.as_ref().and_then(|p| p.rate.as_ref());
        if let Some(w) = self.rate_differs {
            out.push(cell::rate_changes_in_path(
                name,
                &w,
                o.at(MachineField::PowderFullScale),
            ));
        }
        if let Some(w) = self.unfed {
            let style = self
                .program
                .styles
                .iter()
                .find(|s| f64::from(s.id) == w.limit);
            out.push(cell::style_powder_unfed(
                name,
                &w,
                style.map_or("", |s| s.name.as_str()),
                o.block,
            ));
        }
        if let (Some(w), Some(r)) = (self.rate_over, full) {
            out.push(cell::rate_over_full_scale(
                name,
                &w,
                r.full_scale,
                o.at(MachineField::PowderFullScale),
            ));
        }
    }
}

impl<'p> PlanRule<'p> for CellRule<'p> {
    fn new(cx: &MachineCx<'p>) -> Option<Self> {
        Self::with(cx.program, cx.machine.cell())
    }

    fn report(self, cx: &MachineCx<'p>, out: &mut Diagnostics) {
        self.report_at(cx.machine.name(), cx.origin, out);
    }
}

impl Visit for CellRule<'_> {
    fn laser_on(&mut self, next: &Move) {
        let at = next.source();
        if let Some(g) = &self.cell.gas {
            let waited = self.gas_since.map_or(0.0, |s| self.t - s);
            if waited + TIME_SLACK_S < g.pre_flow || self.gas_since.is_none() {
                Worst::hit(&mut self.gas_short, waited, g.pre_flow, at);
            }
        }
        if let Some(p) = &self.cell.powder {
            let waited = self.powder_since.map_or(0.0, |s| self.t - s);
            if waited + TIME_SLACK_S < p.arrival || self.powder_since.is_none() {
                Worst::hit(&mut self.powder_short, waited, p.arrival, at);
            }
        }
    }

    fn motion(&mut self, m: &Move) {
        if let (Speed::Feed(v), Some(from)) = (m.speed, self.at) {
            let d = (0..3)
                .map(|i| (m.to[i] - from[i]).powi(2))
                .sum::<f64>()
                .sqrt();
            self.t += d / v as f64;
        }
        self.at = Some(m.to);
        if !m.deposits() {
            return;
        }
        let Some(full) = self.cell.powder.as_ref().and_then(|p| p.rate.as_ref()) else {
            // No rate output: the feeder gives the rate it is set to, and a
            // style's own feed would be credited without being fed.
            let point = m.source().point(self.program);
            if let Some(p) = point.filter(|p| p.style != 0) {
                let own = self.program.styles.iter().find(|s| s.id == p.style);
                if own.is_some_and(|s| s.powder.is_some()) {
                    let at = m.source();
                    Worst::hit(&mut self.unfed, f64::from(p.powder), f64::from(p.style), at);
                }
            }
            return;
        };
        let Some(feed) = m.source().point(self.program).map(|p| p.powder) else {
            return;
        };
        if let Some(r) = self.rate {
            if (feed - r).abs() > 1e-4 * feed.abs().max(r.abs()) {
                Worst::hit(&mut self.rate_differs, feed as f64, r as f64, m.source());
            }
        }
        if feed as f64 > full.full_scale * (1.0 + 1e-9) {
            Worst::hit(
                &mut self.rate_over,
                feed as f64,
                full.full_scale,
                m.source(),
            );
        }
    }

    fn dwell(&mut self, seconds: f64) {
        self.t += seconds;
    }

    fn io(&mut self, event: Io) {
        match event {
            Io::GasOn => self.gas_since = Some(self.t),
            Io::GasOff => self.gas_since = None,
            Io::PowderOn(r) | Io::PowderRate(r) => {
                self.powder_since = Some(self.t);
                self.rate = Some(r);
            }
            Io::PowderOff => {
                self.powder_since = None;
                self.rate = None;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diag::Code;
    use crate::ir::{Feeder, Gas};
    use crate::plan::{MoveKind, Where};

    fn program() -> Program {
        serde_json::from_str(
            r#"{"format":"lmdc-ir","version":2,"part":"t","units":{"length":"mm","angle":"deg","speed":"mm/s","power":"W","powder":"g/min"},
            "limits":{"layer_height":[0.1,1],"speed":[1,20],"power":[0,4000],"bead_width":3},
            "machines":[],"layers":[]}"#,
        )
        .unwrap()
    }

    fn cell() -> Cell {
        Cell {
            gas: Some(Gas {
                output: crate::ir::Signal::Number(2),
                pre_flow: 2.0,
                post_flow: 1.0,
            }),
            powder: Some(Feeder {
                output: crate::ir::Signal::Number(3),
                arrival: 3.0,
                rate: None,
            }),
            ..Cell::default()
        }
    }

    fn deposit() -> Move {
        Move {
            kind: MoveKind::Deposit,
            to: [10.0, 0.0, 0.0],
            normal: [0.0, 0.0, 1.0],
            axes: Default::default(),
            speed: Speed::Feed(10.0),
            power: 1000.0,
            at: Where::Point {
                layer: 0,
                path: 0,
                point: 1,
            },
        }
    }

    #[test]
    fn a_start_before_the_powder_arrives_is_found_with_the_time_waited() {
        let p = program();
        let mut r = CellRule::with(&p, &cell()).unwrap();
        r.io(Io::GasOn);
        r.io(Io::PowderOn(10.0));
        r.dwell(2.5);
        r.laser_on(&deposit());
        assert!(r.gas_short.is_none(), "2.5 s of gas is more than 2 s");
        let w = r.powder_short.unwrap();
        assert_eq!((w.count, w.value, w.limit), (1, 2.5, 3.0));
        let mut d = Diagnostics::new();
        r.report_at("m", &MachineOrigin::default(), &mut d);
        let codes: Vec<Code> = d.iter().map(|d| d.code).collect();
        assert_eq!(codes, [Code::PowderArrival]);
    }

    #[test]
    fn feed_moves_count_toward_the_wait_and_a_stop_restarts_it() {
        let p = program();
        let mut r = CellRule::with(&p, &cell()).unwrap();
        r.io(Io::GasOn);
        r.io(Io::PowderOn(10.0));
        let mut m = deposit();
        m.kind = MoveKind::Approach;
        m.to = [0.0; 3];
        r.motion(&m);
        // 30 mm at 10 mm/s: 3 s.
        m.to = [30.0, 0.0, 0.0];
        r.motion(&m);
        r.laser_on(&deposit());
        assert!(r.powder_short.is_none() && r.gas_short.is_none());
        r.io(Io::PowderOff);
        r.laser_on(&deposit());
        assert_eq!(r.powder_short.unwrap().count, 1, "no powder at all");
    }
}
