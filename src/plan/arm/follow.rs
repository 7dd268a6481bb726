//! A robot's arm following its plan move by move ([`Follow`]).

use super::chain::Chain;
use super::{Joints, Solver};
use crate::ir::Robot;
use crate::plan::kinematics::Rotary;
use crate::plan::orient::Orienter;
use crate::plan::positioner::Kin;
use crate::plan::{Move, MoveKind, Where};
use nalgebra::{Isometry3, Matrix3, Rotation3, UnitQuaternion, Vector3};
use std::sync::{Arc, Mutex, PoisonError};

/// Where a pose [`Follow`] solves lies: a move's target, or a pose along
/// the LIN to it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Along {
    /// The move's target.
    pub at: Where,
    /// How far along the LIN the pose is (1: at its end).
    pub way: f64,
}

impl std::fmt::Display for Along {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.way < 1.0 {
            write!(f, "{:.0} % of the way along the LIN to ", self.way * 100.0)?;
        }
        write!(f, "{}", self.at)
    }
}

/// One move of a plan solved by [`Follow`] (or a pose along it).
#[derive(Clone, Copy, Debug)]
pub struct Solved {
    /// The move (`to` the pose's position, for a pose along it).
    pub m: Move,
    /// How far along the move the pose is (1: its target).
    pub way: f64,
    /// The focus at its end as the solver takes it: in the base, or in the
    /// robot's frame through a positioner.
    pub to: [f64; 3],
    /// The tool's axes at its end (columns, as `to`).
    pub rot: Matrix3<f64>,
    /// The axis angles it ends at; `None` where the arm cannot reach.
    pub joints: Option<Joints>,
    /// The wrist centre in the robot's frame (what [`Solver::status_at`]
    /// reads).
    pub wrist: Vector3<f64>,
}

/// A robot's arm following its plan move by move: each pose — the focus
/// where the plan puts it, the tool turned as the KRL writer turns it
/// ([`crate::plan::orient`]) — solved to the axis angles nearest the move
/// before (from `home` for the first). What the verifier's arm rules check
/// and what the preview plots: one way of solving a plan, in one place.
///
/// A LIN is followed between its ends too: the controller moves the focus
/// along the straight line and turns the tool steadily from one orientation
/// to the next, and a pose on the way can be out of reach, past a limit or
/// singular while both ends are not. So a move longer than [`LIN_STEP_MM`],
/// or turning the tool by more than [`LIN_STEP_DEG`], is followed through
/// poses that far apart (each a sub-move of the same move: the rules name
/// the move). The move from home ([`MoveKind::FromHome`]) is a PTP, which
/// the controller interpolates in the axes, not along a line; the move back
/// home has no pose to solve.
///
/// Moves are buffered and solved [`CHUNK`] at a time, in order, each
/// from the one before (`plan::arm::chain`: continued from the last solution
/// where that is provably what the closed form's nearest would be). A full
/// chunk is solved on a thread of its own while the next one is buffered:
/// [`Follow::push`] hands it over and gives back the chunk before it;
/// [`Follow::take`] waits for everything pushed.
pub struct Follow {
    solver: Arc<Solver>,
    /// The running choice; held by the thread solving a chunk.
    chain: Arc<Mutex<Chain>>,
    /// The thread solving the last full chunk.
    solving: Option<std::thread::JoinHandle<Vec<Solved>>>,
    /// Poses pushed so far.
    pushed: u64,
    orient: Orienter,
    /// A positioner carrying the base, and its angles and pose last seen.
    mount: Option<(Kin, Rotary, Isometry3<f64>)>,
    normal: Option<[f32; 3]>,
    /// The tool's axes at the last normal, and as a quaternion.
    rot: (Matrix3<f64>, UnitQuaternion<f64>),
    moves: Vec<(Move, f64)>,
    poses: Vec<Pose6>,
    /// The last move's focus, tool and positioner axes (`None` before the
    /// first move).
    last: Option<([f64; 3], UnitQuaternion<f64>, Rotary)>,
    /// Whether LINs are followed between their ends.
    between: bool,
}

/// A pose as the solver takes it: the focus, the tool's axes.
type Pose6 = ([f64; 3], Matrix3<f64>);
/// A chunk: its moves (with how far along each its pose lies) and poses.
type Job = (Vec<(Move, f64)>, Vec<Pose6>);

/// Moves solved together, on a thread beside the one pushing them.
pub const CHUNK: usize = 4096;

/// The farthest apart two poses followed along a LIN lie, mm.
pub const LIN_STEP_MM: f64 = 5.0;
/// The most the tool turns between two poses followed along a LIN, deg.
pub const LIN_STEP_DEG: f64 = 2.0;

impl Follow {
    /// The follower of `robot`'s arm, when [`Solver::new`] has one.
    pub fn new(robot: &Robot) -> Option<Follow> {
        Some(Follow {
            solver: Arc::new(Solver::new(robot)?),
            chain: Arc::new(Mutex::new(Chain::new(robot.home, true))),
            solving: None,
            pushed: 0,
            orient: Orienter::for_robot(robot),
            mount: Kin::of(robot).map(|k| {
                let at = k.part([0.0, 0.0]);
                (k, Rotary::default(), at)
            }),
            normal: None,
            rot: (Matrix3::identity(), UnitQuaternion::identity()),
            moves: Vec::with_capacity(CHUNK),
            poses: Vec::with_capacity(CHUNK),
            last: None,
            between: true,
        })
    }

    /// The same follower solving only the moves pushed, none between:
    /// for moves picked from a plan, not consecutive ones
    /// ([`crate::plan::spin`]).
    pub fn ends_only(mut self) -> Follow {
        self.between = false;
        lock(&self.chain).picked();
        self
    }

    /// How many poses were continued from the one before, and how many
    /// solved in closed form, so far (`plan::arm::chain`).
    pub fn counts(&self) -> [u64; 2] {
        lock(&self.chain).counts
    }

    /// The solver.
    pub fn solver(&self) -> &Solver {
        &self.solver
    }

    /// Poses pushed so far (moves and the poses along the LINs to them).
    pub fn pushed(&self) -> u64 {
        self.pushed
    }

    /// Buffers a move (and the poses along a LIN to it). When a chunk is
    /// full, hands it to a thread to solve and gives back the chunk before
    /// it, solved and chosen in order.
    pub fn push(&mut self, m: &Move) -> Option<Vec<Solved>> {
        if m.kind == MoveKind::Home {
            // Back to the home axes: no pose to solve.
            return None;
        }
        if self.normal != Some(m.normal) {
            // As the writer does: the tool turns only where the normal changes.
            self.normal = Some(m.normal);
            let rot = self.orient.rotation(m.normal);
            let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(rot));
            self.rot = (rot, q);
        }
        let q = self.rot.1;
        // A PTP (from home) is interpolated in the axes: no line to follow.
        let lin = self.between && !m.kind.ptp();
        if let Some((from, q0, axes)) = self.last.filter(|_| lin) {
            let d = (0..3)
                .map(|i| (m.to[i] - from[i]).powi(2))
                .sum::<f64>()
                .sqrt();
            // The tool's turn, and a positioner's axes' (E1, E2).
            let turn = q0
                .angle_to(&q)
                .to_degrees()
                .max((m.axes.tilt - axes.tilt).abs())
                .max((m.axes.c - axes.c).abs());
            // A move of exactly k steps (a 10 mm retract) has k − 1 poses
            // between its ends, whatever its last bit.
            let n = ((d / LIN_STEP_MM).max(turn / LIN_STEP_DEG) - 1e-9).ceil();
            // A move of millimetres has no pose between; a runaway count
            // (a non-finite or absurd length) is refused by the other rules.
            let n = if n.is_finite() {
                n.min(1e5) as usize
            } else {
                1
            };
            for k in 1..n {
                let t = k as f64 / n as f64;
                let lerp = |a: f64, b: f64| a + t * (b - a);
                let sub = Move {
                    to: std::array::from_fn(|i| lerp(from[i], m.to[i])),
                    axes: Rotary {
                        tilt: lerp(axes.tilt, m.axes.tilt),
                        c: lerp(axes.c, m.axes.c),
                    },
                    ..*m
                };
                let turned = q0.try_slerp(&q, t, 1e-12).unwrap_or(q);
                let pose = self.pose(&sub, *turned.to_rotation_matrix().matrix());
                self.moves.push((sub, t));
                self.poses.push(pose);
                self.pushed += 1;
            }
        }
        self.last = Some((m.to, q, m.axes));
        self.moves.push((*m, 1.0));
        let pose = self.pose(m, self.rot.0);
        self.poses.push(pose);
        self.pushed += 1;
        if self.moves.len() < CHUNK {
            return None;
        }
        let job = Arc::new((
            std::mem::replace(&mut self.moves, Vec::with_capacity(CHUNK)),
            std::mem::replace(&mut self.poses, Vec::with_capacity(CHUNK)),
        ));
        // The chunk continues from the last pose of the one before: that one
        // is finished first.
        let before = self.joined();
        let (solver, chain, theirs) = (
            Arc::clone(&self.solver),
            Arc::clone(&self.chain),
            Arc::clone(&job),
        );
        let spawned = std::thread::Builder::new()
            .name("arm".into())
            .spawn(move || solve(&solver, &mut lock(&chain), &theirs));
        match spawned {
            Ok(thread) => self.solving = Some(thread),
            // No thread to be had: solved here, now.
            Err(_) => {
                let mut out = before;
                out.extend(solve(&self.solver, &mut lock(&self.chain), &job));
                return Some(out);
            }
        }
        Some(before)
    }

    /// The chunk solving in the background, solved (none: nothing).
    fn joined(&mut self) -> Vec<Solved> {
        match self.solving.take() {
            Some(t) => t.join().unwrap_or_else(|e| std::panic::resume_unwind(e)),
            None => Vec::new(),
        }
    }

    /// The pose of `m` as the solver takes it: the tool turned `rot`, at
    /// the focus, through the positioner at the move's angles.
    fn pose(&mut self, m: &Move, rot: Matrix3<f64>) -> Pose6 {
        let Some((kin, at, part)) = self.mount.as_mut() else {
            return (m.to, rot);
        };
        if *at != m.axes {
            *at = m.axes;
            *part = kin.part([m.axes.tilt, m.axes.c]);
        }
        let p = *part * nalgebra::Point3::from(m.to);
        let r = part.rotation.to_rotation_matrix().into_inner() * rot;
        ([p.x, p.y, p.z], r)
    }

    /// Every move pushed and not yet given back, solved and chosen in order.
    pub fn take(&mut self) -> Vec<Solved> {
        let mut out = self.joined();
        let job = (
            std::mem::take(&mut self.moves),
            std::mem::take(&mut self.poses),
        );
        out.extend(solve(&self.solver, &mut lock(&self.chain), &job));
        out
    }
}

/// The chain, whoever held it last (a thread that panicked passes its
/// panic on when joined).
fn lock(chain: &Mutex<Chain>) -> std::sync::MutexGuard<'_, Chain> {
    chain.lock().unwrap_or_else(PoisonError::into_inner)
}

/// Each pose of `job` solved in order, from where `chain` stands.
fn solve(solver: &Solver, chain: &mut Chain, job: &Job) -> Vec<Solved> {
    let (moves, poses) = job;
    moves
        .iter()
        .zip(poses)
        .map(|(&(m, way), &(to, rot))| {
            let (joints, wrist) = chain.next(solver, to, &rot);
            Solved {
                m,
                way,
                to,
                rot,
                joints,
                wrist,
            }
        })
        .collect()
}
