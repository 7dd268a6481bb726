//! A robot arm's axes along the plan, for the page's joint plot: every
//! move solved by [`crate::plan::arm::Follow`] — the verifier's own way, so
//! the plot shows the angles the arm rules checked — and kept per layer as
//! each axis's lowest and highest angle. Linear in moves, and a page holds
//! 12 numbers a layer however many moves the plan has (every move counts,
//! whatever the page's decimation keeps).
//!
//! The same walk hangs the arm's links on the axes at the moves the page's
//! slider shows ([`Links`]): the frames' origins of its forward kinematics
//! ([`crate::plan::arm::Solver::joint_points`], as the collision check
//! hangs its capsules on them), in the part's coordinates, at most
//! [`POSES`] moves — a forward kinematics each, beside the solving every
//! move costs anyway.

use crate::ir::{Layer, Machine, Robot};
use crate::plan::arm::{frame, Follow, Solved};
use crate::plan::kinematics::Rotary;
use crate::plan::positioner::Kin;
use crate::plan::{Move, Visit};
use nalgebra::{Isometry3, Point3};
use serde::Serialize;

/// Most moves the page carries the arm's links at (36 bytes each): past
/// it, every k-th kept move's.
pub const POSES: usize = 10_000;

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
    /// The arm's links at the moves the page poses (`None`: its base has
    /// no value, or no move is posed).
    pub links: Option<Links>,
}

/// The arm's links at some of the page's moves, in the part's
/// coordinates (on a positioner they turn with the part).
#[derive(Serialize)]
pub struct Links {
    /// The links' radii, mm, as the collision check takes them (the upper
    /// arm's, the forearm's, the wrist's; `None`: an `opw(…)` arm without
    /// `arm_links`, whose links are not checked: drawn as lines).
    pub radii: Option<[f64; 3]>,
    /// The page's moves posed, ascending.
    pub moves: Vec<usize>,
    /// `[min, max]` of the points' x, y, z.
    pub ranges: [[f64; 2]; 3],
    /// Each posed move's six frame origins (A1 at the shoulder's height,
    /// A2, A3, past the forearm's offset, the wrist centre, the flange),
    /// x y z each a 16-bit fraction of its range, little-endian, base64.
    pub points: String,
}

/// The links being gathered: the moves wanted, and the points found.
struct Hang {
    /// `(plan move index, page move index)` of each move to pose,
    /// ascending.
    want: Vec<(usize, usize)>,
    next: usize,
    /// The part's base in the robot's frame, and the positioner.
    base: Isometry3<f64>,
    kin: Option<Kin>,
    home: [f64; 6],
    got: Vec<(usize, [[f64; 3]; 6])>,
}

impl Hang {
    /// The page's move index if the plan's move `index` is wanted.
    fn wanted(&mut self, index: usize) -> Option<usize> {
        while self.want.get(self.next).is_some_and(|w| w.0 < index) {
            self.next += 1;
        }
        let w = self.want.get(self.next).filter(|w| w.0 == index)?;
        Some(w.1)
    }

    /// Keeps the frames' origins `points` (in the robot's frame) for the
    /// page's move `kept`, in the part's coordinates with the positioner
    /// at `axes` (the collision check's frames, `verify::arm::links`).
    fn hang(&mut self, kept: usize, points: [[f64; 3]; 6], axes: Rotary) {
        let part = match &self.kin {
            Some(k) => k.part([axes.tilt, axes.c]),
            None => self.base,
        };
        let inv = part.inverse();
        let p = points.map(|p| {
            let q = inv * Point3::from(p);
            [q.x, q.y, q.z]
        });
        if p.iter().flatten().all(|v| v.is_finite()) {
            self.got.push((kept, p));
        }
    }

    fn finish(mut self, radii: Option<[f64; 3]>) -> Option<Links> {
        if self.got.is_empty() {
            return None;
        }
        self.got.sort_by_key(|g| g.0);
        let mut ranges = [[f64::INFINITY, f64::NEG_INFINITY]; 3];
        for (_, p) in &self.got {
            for q in p {
                for (r, v) in ranges.iter_mut().zip(q) {
                    *r = [r[0].min(*v), r[1].max(*v)];
                }
            }
        }
        let mut bytes = Vec::with_capacity(self.got.len() * 36);
        for (_, p) in &self.got {
            for q in p {
                for (k, v) in q.iter().enumerate() {
                    let q = super::encode::quantise(*v, ranges[k][0], ranges[k][1]);
                    bytes.extend_from_slice(&q.to_le_bytes());
                }
            }
        }
        Some(Links {
            radii,
            moves: self.got.iter().map(|g| g.0).collect(),
            ranges,
            points: super::encode::base64(&bytes),
        })
    }
}

/// Follows the plan and keeps each layer's ranges.
struct Collect {
    follow: Follow,
    /// The layer of each buffered pose, and the page's move it ends where
    /// the page poses that move.
    pending: Vec<(usize, Option<usize>)>,
    layer: usize,
    arm: Arm,
    /// Moves of the plan so far.
    index: usize,
    hang: Option<Hang>,
}

impl Collect {
    /// Counts solved poses with the layers they were pushed in (the oldest
    /// pending ones: poses come back in order).
    fn collect(&mut self, solved: Vec<Solved>) {
        let layers: Vec<(usize, Option<usize>)> = self.pending.drain(..solved.len()).collect();
        for (s, (layer, kept)) in solved.iter().zip(layers) {
            self.add(s, layer);
            if let (Some(kept), Some(j), Some(h)) = (kept, s.joints, self.hang.as_mut()) {
                h.hang(kept, self.follow.solver().joint_points(&j), s.m.axes);
            }
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
        let index = self.index;
        self.index += 1;
        let kept = self.hang.as_mut().and_then(|h| h.wanted(index));
        let before = self.follow.pushed();
        let done = self.follow.push(m);
        // The move, and the poses along a LIN to it, count with its layer;
        // the last pose is the move's end.
        let added = (self.follow.pushed() - before) as usize;
        self.pending
            .extend(std::iter::repeat_n((self.layer, None), added));
        match (self.pending.last_mut(), kept) {
            (Some(last), Some(_)) if added > 0 => last.1 = kept,
            // The PTP home has no pose to solve: the arm is at its home axes.
            (_, Some(kept)) => {
                if let Some(h) = self.hang.as_mut() {
                    let home = h.home;
                    h.hang(kept, self.follow.solver().joint_points(&home), m.axes);
                }
            }
            _ => {}
        }
        if let Some(done) = done {
            self.collect(done);
        }
    }
}

/// The arm's axes along `plan`, when `machine` is a robot with an arm lmdc
/// can solve and a part not beyond its reach (refused from its points, its
/// poses are not solved: there is nothing to plot); and its links at the
/// plan's moves `want` (`(plan move index, page move index)`, ascending).
pub fn of(
    machine: &Machine,
    plan: &crate::plan::Plan<'_>,
    layers: usize,
    want: Vec<(usize, usize)>,
) -> Option<Arm> {
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
        links: None,
    };
    let mut c = Collect {
        follow,
        pending: Vec::new(),
        layer: 0,
        arm,
        index: 0,
        hang: hang(r, want),
    };
    plan.walk(&mut c);
    c.flush();
    let radii = link_radii(r);
    c.arm.links = c.hang.and_then(|h| h.finish(radii));
    Some(c.arm)
}

/// The gatherer of `robot`'s links at `want`, where its base has a value.
fn hang(robot: &Robot, want: Vec<(usize, usize)>) -> Option<Hang> {
    Some(Hang {
        want,
        next: 0,
        base: frame(robot.base.value.as_ref()?),
        kin: Kin::of(robot),
        home: robot.home,
        got: Vec::new(),
    })
}

/// The links' radii the collision check takes: declared, else the
/// catalogue's.
fn link_radii(robot: &Robot) -> Option<[f64; 3]> {
    let arm = robot.arm.as_ref()?;
    arm.links
        .or_else(|| crate::target::arm::model(arm.model.as_deref()?).map(|m| m.links))
}
