//! What the verifier's pass over a machine's plan remembers (naga's
//! `ModuleInfo`): the moves, what each layer costs, the files the program
//! goes to. The writers' headers and `lmdc report` read it from the
//! [`super::VerifiedMachine`] instead of walking the plan again.
//!
//! Times are the program's at its programmed speeds, rapids at the machine's
//! `max_speed`; accelerations are not modelled.

use crate::ir::{Kinematics, Layer, Machine, Program};
use crate::plan::kinematics::{flips, Rotary};
use crate::plan::{Move, Speed, Visit};
use serde::Serialize;

/// What one layer of a plan (or the whole plan) costs. Lengths are the tool
/// tip's path.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Costs {
    /// Length of the deposit moves (laser on), mm.
    pub deposit_mm: f64,
    /// Length of every other move (approach, retract, travel), mm.
    pub travel_mm: f64,
    /// Time of every move at its programmed speed, rapids at the machine's
    /// `max_speed`, s.
    pub motion_s: f64,
    /// Cooling waits the plan makes after this layer, s.
    pub dwell_s: f64,
    /// Time the laser is on, s.
    pub laser_on_s: f64,
    /// Laser energy, `Σ P·t` over the deposit moves, J.
    pub energy_j: f64,
    /// Powder fed while the laser is on, `Σ ṁ·t`, g.
    pub powder_g: f64,
}

impl Costs {
    /// Motion and dwell together, s.
    pub fn time_s(&self) -> f64 {
        self.motion_s + self.dwell_s
    }

    /// Adds `o` in.
    pub fn add(&mut self, o: &Costs) {
        self.deposit_mm += o.deposit_mm;
        self.travel_mm += o.travel_mm;
        self.motion_s += o.motion_s;
        self.dwell_s += o.dwell_s;
        self.laser_on_s += o.laser_on_s;
        self.energy_j += o.energy_j;
        self.powder_g += o.powder_g;
    }
}

/// A machine's plan, summed up by the verifier's pass over it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Summary {
    /// Moves in the plan (a KRL program has one LIN per move).
    pub moves: u64,
    /// Per layer of the IR, in build order.
    pub layers: Vec<Costs>,
    /// The whole plan.
    pub total: Costs,
    /// The files the machine's program is written to.
    pub files: Vec<String>,
    /// Rapid moves are timed at this speed (the machine's `max_speed`), mm/s.
    pub rapid_mm_s: f64,
    /// The layers (from 0) in which a tilting head's or table's tilt goes
    /// over to its other side: a table where a layer needs the other
    /// branch of the axes' two solutions, a head where its nozzle passes
    /// through vertical ([`crate::plan::kinematics::run_start`]).
    pub branch_changes: Vec<usize>,
    /// The closest each body came to each thing of the cell
    /// ([`super::approach`]): the head's, then the arm's links'.
    pub approaches: Vec<super::approach::Approach>,
}

/// The speed a machine's rapid moves are timed at: its `max_speed`.
pub fn rapid_speed(m: &Machine) -> f64 {
    m.common().max_speed
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// A [`Visit`] that adds every move of a plan into its layer's [`Costs`].
pub(super) struct Summarize<'p> {
    program: &'p Program,
    rapid: f64,
    layer: usize,
    at: Option<[f64; 3]>,
    moves: u64,
    rows: Vec<Costs>,
    /// A CNC with rotary axes: the axes the last move ended at.
    tilting: Option<Rotary>,
    branch_changes: Vec<usize>,
}

impl<'p> Summarize<'p> {
    pub fn new(program: &'p Program, machine: &Machine) -> Self {
        Summarize {
            program,
            rapid: rapid_speed(machine),
            layer: 0,
            at: None,
            moves: 0,
            rows: vec![Costs::default(); program.layers.len()],
            tilting: match machine {
                Machine::Cnc(c) if c.effective_kinematics() != Kinematics::Xyz => {
                    Some(Rotary::default())
                }
                _ => None,
            },
            branch_changes: Vec::new(),
        }
    }

    /// The summary, with the files the program goes to.
    pub fn finish(self, files: impl FnOnce(u64) -> Vec<String>) -> Summary {
        let mut total = Costs::default();
        for r in &self.rows {
            total.add(r);
        }
        Summary {
            moves: self.moves,
            files: files(self.moves),
            layers: self.rows,
            total,
            rapid_mm_s: self.rapid,
            branch_changes: self.branch_changes,
            approaches: Vec::new(),
        }
    }
}

impl Visit for Summarize<'_> {
    fn layer(&mut self, index: usize, _: &Layer) {
        self.layer = index;
    }

    /// A cooling wait belongs to the layer that cools: the plan dwells
    /// before the next layer begins.
    fn dwell(&mut self, seconds: f64) {
        if let Some(r) = self.rows.get_mut(self.layer) {
            r.dwell_s += seconds.max(0.0);
        }
    }

    #[inline]
    fn motion(&mut self, m: &Move) {
        self.moves += 1;
        if let Some(was) = self.tilting.replace(m.axes) {
            if flips(was, m.axes) && self.branch_changes.last() != Some(&self.layer) {
                self.branch_changes.push(self.layer);
            }
        }
        // The first move starts wherever the machine stands: no length.
        let d = self.at.replace(m.to).map_or(0.0, |from| dist(from, m.to));
        let v = match m.speed {
            Speed::Feed(v) => v as f64,
            Speed::Rapid => self.rapid,
        };
        let t = if v > 0.0 && v.is_finite() { d / v } else { 0.0 };
        let powder = m
            .deposits()
            .then(|| m.source().point(self.program))
            .flatten();
        let Some(row) = self.rows.get_mut(self.layer) else {
            return;
        };
        row.motion_s += t;
        if m.deposits() {
            row.deposit_mm += d;
            row.laser_on_s += t;
            row.energy_j += m.power as f64 * t;
            if let Some(p) = powder {
                row.powder_g += p.powder as f64 / 60.0 * t;
            }
        } else {
            row.travel_mm += d;
        }
    }
}
