//! A robot arm's axes along the plan, for the page's joint plot: every
//! move solved by [`crate::plan::arm::Follow`] — the verifier's own way, so
//! the plot shows the angles the arm rules checked — and kept per layer as
//! each axis's lowest and highest angle. Linear in moves, and a page holds
//! 12 numbers a layer however many moves the plan has (every move counts,
//! whatever the page's decimation keeps).

use crate::ir::{Layer, Machine};
use crate::plan::arm::{Follow, Solved};
use crate::plan::{Move, Visit};
use serde::Serialize;

/// What the page says about the arm.
#[derive(Serialize)]
pub struct Arm {
    /// The arm's name (the catalogue's, or `opw(…) arm`).
    pub name: String,
    /// Each axis's `[lowest, highest]` angle, deg.
    pub limits: [[f64; 2]; 6],
    /// The margin the verifier keeps from them (`lmd::joint-limit`), deg.
    pub margin: f64,
    /// How near A5 = 0 and A3's stretch angle a LIN may go
    /// (`lmd::singular-lin`), deg.
    pub singularity: f64,
    /// A3's stretch angle, deg.
    pub stretch: f64,
    /// Every layer's `[[lowest, highest]; 6]` axis angles, deg, over its
    /// moves the arm reaches (`None`: none). Moves before the first layer
    /// (the PTP from home) count with the first.
    pub layers: Vec<Option<[[f64; 2]; 6]>>,
    /// Moves the arm cannot reach (a plan that built has none).
    pub unreachable: usize,
}

/// Follows the plan and keeps each layer's ranges.
struct Collect {
    follow: Follow,
    /// The layer of each buffered pose.
    pending: Vec<usize>,
    layer: usize,
    arm: Arm,
}

impl Collect {
    /// Counts solved poses with the layers they were pushed in (the oldest
    /// pending ones: poses come back in order).
    fn collect(&mut self, solved: Vec<Solved>) {
        let layers: Vec<usize> = self.pending.drain(..solved.len()).collect();
        for (s, layer) in solved.iter().zip(layers) {
            self.add(s, layer);
        }
    }

    fn flush(&mut self) {
        let solved = self.follow.take();
        self.collect(solved);
    }

    fn add(&mut self, s: &Solved, layer: usize) {
        let Some(j) = s.joints else {
            self.arm.unreachable += 1;
            return;
        };
        let slot = &mut self.arm.layers[layer];
        let r = slot.get_or_insert([[f64::INFINITY, f64::NEG_INFINITY]; 6]);
        for (r, a) in r.iter_mut().zip(j) {
            *r = [r[0].min(a), r[1].max(a)];
        }
    }
}

impl Visit for Collect {
    fn layer(&mut self, index: usize, _: &Layer) {
        self.layer = index.min(self.arm.layers.len().saturating_sub(1));
    }

    fn motion(&mut self, m: &Move) {
        let before = self.follow.pushed();
        let done = self.follow.push(m);
        // The move, and the poses along a LIN to it, count with its layer.
        let added = (self.follow.pushed() - before) as usize;
        self.pending.extend(std::iter::repeat_n(self.layer, added));
        if let Some(done) = done {
            self.collect(done);
        }
    }
}

/// The arm's axes along `plan`, when `machine` is a robot with an arm lmdc
/// can solve and a part not beyond its reach (refused from its points, its
/// poses are not solved: there is nothing to plot).
pub fn of(machine: &Machine, plan: &crate::plan::Plan<'_>, layers: usize) -> Option<Arm> {
    let Machine::Robot(r) = machine else {
        return None;
    };
    if crate::plan::arm::reach::beyond(plan.program(), r).is_some() {
        return None;
    }
    let follow = Follow::new(r)?;
    let a = follow.solver().arm();
    let arm = Arm {
        name: a
            .model
            .as_deref()
            .and_then(crate::target::arm::model)
            .map_or("opw(…) arm", |m| m.name)
            .to_string(),
        limits: a.limits,
        margin: a.margin,
        singularity: a.singularity,
        stretch: follow.solver().stretch(),
        layers: vec![None; layers.max(1)],
        unreachable: 0,
    };
    let mut c = Collect {
        follow,
        pending: Vec::new(),
        layer: 0,
        arm,
    };
    plan.walk(&mut c);
    c.flush();
    Some(c.arm)
}
