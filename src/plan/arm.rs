//! A robot's arm: the tool poses of the plan solved to axis angles A1–A6
//! with rs-opw-kinematics (closed-form inverse kinematics of an arm with an
//! ortho-parallel base and a spherical wrist), and what KUKA's controller
//! calls the solution's configuration (Status and Turn).
//!
//! Frames, as on the controller: a pose `P` (the laser focus, `X Y Z A B C`
//! in `$BASE`) is reached with the flange at `BASE · P · TOOL⁻¹` in the
//! robot's own frame (`$ROBROOT`, taken as `$WORLD`); the solver's `tool0` is
//! KUKA's `$FLANGE` and its joints are KUKA's axis angles
//! ([`crate::target::arm`]). Angles here are degrees.

use crate::ir::{Arm, Pose, Robot};
use crate::plan::kinematics::Rotary;
use crate::plan::orient::Orienter;
use crate::plan::positioner::Kin;
use crate::plan::{Move, Where};
use nalgebra::{Isometry3, Matrix3, Rotation3, Translation3, UnitQuaternion, Vector3};
use rs_opw_kinematics::glam::{DQuat, DVec3};
use rs_opw_kinematics::kinematic_traits::{Kinematics, Pose as OpwPose};
use rs_opw_kinematics::kinematics_impl::OPWKinematics;
use rs_opw_kinematics::parameters::opw_kinematics::Parameters;
use std::sync::Arc;

/// Axis angles A1–A6, deg.
pub type Joints = [f64; 6];

/// A robot's arm with its base and tool: solves tool poses to axis angles.
#[derive(Clone, Debug)]
pub struct Solver {
    kin: OPWKinematics,
    arm: Arm,
    base: Isometry3<f64>,
    tool_inv: Isometry3<f64>,
    /// A3's angle where the arm is stretched (the wrist centre farthest
    /// from A2), deg: KUKA's φ of Status bit 1.
    stretch: f64,
}

/// KUKA's frame `X Y Z A B C` (`R = Rz(A)·Ry(B)·Rx(C)`) as an isometry.
pub fn frame(p: &Pose) -> Isometry3<f64> {
    let r = Rotation3::from_euler_angles(p.c.to_radians(), p.b.to_radians(), p.a.to_radians());
    Isometry3::from_parts(
        Translation3::new(p.x, p.y, p.z),
        UnitQuaternion::from_rotation_matrix(&r),
    )
}

impl Solver {
    /// The solver of `robot`'s arm, when it declares one and the values of
    /// its base and tool (an index alone says nothing lmdc can solve with).
    pub fn new(robot: &Robot) -> Option<Solver> {
        let arm = robot.arm.clone()?;
        let base = frame(&robot.base.value?);
        // On a positioner the base moves: poses come in the robot's frame
        // ([`Follow`], [`crate::plan::positioner::Kin::part`]).
        let base = if robot.positioner.is_some() {
            Isometry3::identity()
        } else {
            base
        };
        let tool = frame(&robot.tool.value?);
        Some(Solver::with(arm, base, tool))
    }

    /// The solver of `arm` with a base and tool frame.
    pub fn with(arm: Arm, base: Isometry3<f64>, tool: Isometry3<f64>) -> Solver {
        let [a1, a2, b, c1, c2, c3, c4] = arm.opw;
        let p = Parameters {
            a1,
            a2,
            b,
            c1,
            c2,
            c3,
            c4,
            offsets: arm.offsets.map(f64::to_radians),
            sign_corrections: arm.signs,
            dof: 6,
        };
        Solver {
            kin: OPWKinematics::new(p),
            stretch: (-a2).atan2(c3).to_degrees(),
            arm,
            base,
            tool_inv: tool.inverse(),
        }
    }

    /// The arm.
    pub fn arm(&self) -> &Arm {
        &self.arm
    }

    /// A3's stretch angle, deg.
    pub fn stretch(&self) -> f64 {
        self.stretch
    }

    /// The flange, in the robot's frame, where the tool's focus is at `to`
    /// with the tool's axes `rot` (columns, in the base).
    pub fn flange(&self, to: [f64; 3], rot: &Matrix3<f64>) -> Isometry3<f64> {
        let tcp = Isometry3::from_parts(
            Translation3::new(to[0], to[1], to[2]),
            UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(*rot)),
        );
        self.base * tcp * self.tool_inv
    }

    /// Every solution for the tool at `to` with axes `rot`, nearest `prev`
    /// first (a wrist singularity resolved towards it, A4 and A6 kept in
    /// the turn nearest it); empty where the arm cannot reach.
    pub fn solve(&self, to: [f64; 3], rot: &Matrix3<f64>, prev: &Joints) -> Vec<Joints> {
        self.solve_at(to, rot, prev).0
    }

    /// [`Self::solve`], and the wrist centre of the pose in the robot's
    /// frame (what [`Self::status_at`] reads).
    pub fn solve_at(
        &self,
        to: [f64; 3],
        rot: &Matrix3<f64>,
        prev: &Joints,
    ) -> (Vec<Joints>, Vector3<f64>) {
        let f = self.flange(to, rot);
        let t = f.translation.vector;
        let q = f.rotation.into_inner().coords;
        let pose = OpwPose::from_parts(
            DVec3::new(t.x, t.y, t.z),
            DQuat::from_xyzw(q.x, q.y, q.z, q.w),
        );
        let prev = prev.map(f64::to_radians);
        let sols = self
            .kin
            .inverse_continuing(&pose, &prev)
            .into_iter()
            .map(|j| {
                let mut j = j.map(f64::to_degrees);
                // A1, A2, A3 and A5 turn less than a full turn: the angle
                // in [−180°, 180°) is the only one they can take (the
                // solver keeps every axis in the turn nearest the last).
                for i in [0, 1, 2, 4] {
                    j[i] -= 360.0 * ((j[i] + 180.0) / 360.0).floor();
                }
                j
            })
            .collect();
        (sols, self.wrist(&f))
    }

    /// Every solution of each pose `(to, rot)`, in no order, with its wrist
    /// centre: the part of [`Self::solve_at`] that does not depend on the
    /// move before, so it can be solved for many moves at once, on `threads`
    /// threads. [`Self::nearest`] then picks what `solve_at` would.
    pub fn solve_many(
        &self,
        poses: &[([f64; 3], Matrix3<f64>)],
        threads: usize,
    ) -> Vec<(Vec<Joints>, Vector3<f64>)> {
        let one = |(to, rot): &([f64; 3], Matrix3<f64>)| {
            let f = self.flange(*to, rot);
            let (t, q) = (f.translation.vector, f.rotation.into_inner().coords);
            let pose = OpwPose::from_parts(
                DVec3::new(t.x, t.y, t.z),
                DQuat::from_xyzw(q.x, q.y, q.z, q.w),
            );
            let mut sols = self.kin.inverse(&pose);
            for j in &mut sols {
                *j = j.map(f64::to_degrees);
            }
            (sols, self.wrist(&f))
        };
        let per = poses.len().div_ceil(threads.max(1)).max(1);
        if threads <= 1 || poses.len() < 64 {
            return poses.iter().map(one).collect();
        }
        std::thread::scope(|s| {
            let parts: Vec<_> = poses
                .chunks(per)
                .map(|c| s.spawn(move || c.iter().map(one).collect::<Vec<_>>()))
                .collect();
            parts
                .into_iter()
                .flat_map(|h| h.join().unwrap_or_default())
                .collect()
        })
    }

    /// Of `sols` (from [`Self::solve_many`]), the one nearest `prev` (the
    /// sum of the axes' differences, as the solver sorts), every axis in the
    /// turn nearest `prev`'s, A1, A2, A3 and A5 in [−180°, 180°). `None`
    /// where there is none, or where the pose is at the wrist singularity
    /// (A5 within 10⁻⁶° of 0): A4 and A6 are then split by the move before,
    /// which only [`Self::solve_at`] does.
    pub fn nearest(sols: &[Joints], prev: &Joints) -> Option<Joints> {
        let mut best: Option<(f64, Joints)> = None;
        for s in sols {
            if s[4].abs() < 1e-6 {
                return None;
            }
            let mut j = *s;
            for i in 0..6 {
                j[i] = prev[i] + ((j[i] - prev[i] + 180.0).rem_euclid(360.0) - 180.0);
            }
            for i in [0, 1, 2, 4] {
                j[i] -= 360.0 * ((j[i] + 180.0) / 360.0).floor();
            }
            let d: f64 = j.iter().zip(prev).map(|(a, b)| (a - b).abs()).sum();
            if best.is_none_or(|(bd, _)| d < bd) {
                best = Some((d, j));
            }
        }
        best.map(|b| b.1)
    }

    /// The flange in the robot's frame at axis angles `j`.
    pub fn forward_flange(&self, j: &Joints) -> Isometry3<f64> {
        let p = self.kin.forward(&j.map(f64::to_radians));
        let (t, q) = (p.translation, p.rotation);
        Isometry3::from_parts(
            Translation3::new(t.x, t.y, t.z),
            UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q.w, q.x, q.y, q.z)),
        )
    }

    /// The tool's focus in the base, and its axes, at axis angles `j`.
    pub fn forward(&self, j: &Joints) -> ([f64; 3], Matrix3<f64>) {
        let tcp = self.base.inverse() * self.forward_flange(j) * self.tool_inv.inverse();
        let t = tcp.translation.vector;
        ([t.x, t.y, t.z], *tcp.rotation.to_rotation_matrix().matrix())
    }

    /// The wrist centre in the robot's frame for a flange `f`.
    fn wrist(&self, f: &Isometry3<f64>) -> Vector3<f64> {
        f.translation.vector - f.rotation * Vector3::z() * self.arm.opw[6]
    }

    /// How far the wrist centre is from the A2 axis where the tool is at
    /// `to` with `rot`, and the nearest and farthest the arm puts it, mm.
    pub fn reach(&self, to: [f64; 3], rot: &Matrix3<f64>) -> (f64, [f64; 2]) {
        let [a1, a2, _, c1, c2, c3, _] = self.arm.opw;
        let w = self.wrist(&self.flange(to, rot));
        let h = (w.x * w.x + w.y * w.y).sqrt();
        let d = ((h - a1).powi(2) + (w.z - c1).powi(2)).sqrt();
        let fore = (c3 * c3 + a2 * a2).sqrt();
        (d, [(c2 - fore).abs(), c2 + fore])
    }

    /// KUKA's Status of a solution: bit 0 the wrist centre behind A1
    /// (overhead), bit 1 A3 at or past its stretch angle, bit 2 A5 ≤ 0.
    pub fn status(&self, j: &Joints) -> u8 {
        self.status_at(j, &self.wrist(&self.forward_flange(j)))
    }

    /// [`Self::status`] of a solution whose wrist centre is `w` (from
    /// [`Self::solve_at`]: no forward kinematics).
    pub fn status_at(&self, j: &Joints, w: &Vector3<f64>) -> u8 {
        // A1 turns about −Z: the arm's forward direction at A1 = θ.
        let t = j[0].to_radians();
        let ahead = w.x * t.cos() - w.y * t.sin();
        u8::from(ahead < 0.0) | (u8::from(j[2] >= self.stretch) << 1) | (u8::from(j[4] <= 0.0) << 2)
    }

    /// KUKA's Turn: bit `i` set where axis `i + 1` is negative.
    pub fn turn(j: &Joints) -> u8 {
        j.iter()
            .enumerate()
            .fold(0, |t, (i, a)| t | (u8::from(*a < 0.0) << i))
    }
}

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
/// the move). The first move is the PTP from home, which the controller
/// interpolates in the axes, not along a line.
///
/// Moves are buffered and solved [`CHUNK`] at a time on two threads
/// ([`Solver::solve_many`]), then chosen in order ([`Solver::nearest`]).
/// A full chunk is solved in the background while the next one is
/// buffered: [`Follow::push`] hands it over and gives back the chunk before
/// it, chosen; [`Follow::take`] waits for everything pushed.
pub struct Follow {
    solver: Arc<Solver>,
    /// The chunk being solved in the background.
    solving: Option<Solving>,
    /// Poses pushed so far.
    pushed: u64,
    orient: Orienter,
    /// A positioner carrying the base, and its angles and pose last seen.
    mount: Option<(Kin, Rotary, Isometry3<f64>)>,
    normal: Option<[f32; 3]>,
    rot: Matrix3<f64>,
    moves: Vec<(Move, f64)>,
    poses: Vec<([f64; 3], Matrix3<f64>)>,
    /// The last move's focus, tool and positioner axes (`None` before the
    /// first move).
    last: Option<([f64; 3], UnitQuaternion<f64>, Rotary)>,
    /// Whether LINs are followed between their ends.
    between: bool,
    /// The last solution (home before the first).
    prev: Joints,
    /// No move solved yet: the next is the PTP from home.
    first: bool,
}

/// A chunk's moves and poses, and the thread solving the poses.
struct Solving {
    moves: Vec<(Move, f64)>,
    poses: Arc<Vec<Pose6>>,
    thread: std::thread::JoinHandle<Vec<Solutions>>,
}

/// A pose as the solver takes it: the focus, the tool's axes.
type Pose6 = ([f64; 3], Matrix3<f64>);
/// A pose's solutions, and its wrist centre.
type Solutions = (Vec<Joints>, Vector3<f64>);

/// Moves solved together: their poses do not depend on each other, only
/// the choice among each one's solutions does (`Solver::nearest`).
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
            solving: None,
            pushed: 0,
            orient: Orienter::for_robot(robot),
            mount: Kin::of(robot).map(|k| {
                let at = k.part([0.0, 0.0]);
                (k, Rotary::default(), at)
            }),
            normal: None,
            rot: Matrix3::identity(),
            moves: Vec::with_capacity(CHUNK),
            poses: Vec::with_capacity(CHUNK),
            last: None,
            between: true,
            prev: robot.home,
            first: true,
        })
    }

    /// The same follower solving only the moves pushed, none between:
    /// for moves picked from a plan, not consecutive ones
    /// ([`crate::plan::spin`]).
    pub fn ends_only(mut self) -> Follow {
        self.between = false;
        self
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
        if self.normal != Some(m.normal) {
            // As the writer does: the tool turns only where the normal changes.
            self.normal = Some(m.normal);
            self.rot = self.orient.rotation(m.normal);
        }
        let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(self.rot));
        if let Some((from, q0, axes)) = self.last.filter(|_| self.between) {
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
        let pose = self.pose(m, self.rot);
        self.poses.push(pose);
        self.pushed += 1;
        if self.moves.len() < CHUNK {
            return None;
        }
        let moves = std::mem::replace(&mut self.moves, Vec::with_capacity(CHUNK));
        let poses = Arc::new(std::mem::replace(
            &mut self.poses,
            Vec::with_capacity(CHUNK),
        ));
        let (solver, theirs) = (Arc::clone(&self.solver), Arc::clone(&poses));
        let spawned = std::thread::Builder::new()
            .name("arm".into())
            .spawn(move || solver.solve_many(&theirs, 2));
        // This chunk is solving before the one before is chosen: the
        // choosing runs beside it.
        let before = match spawned {
            Ok(thread) => self.solving.replace(Solving {
                moves,
                poses,
                thread,
            }),
            // No thread to be had: solved here, now, after the one before.
            Err(_) => {
                let mut out = match self.solving.take() {
                    Some(s) => self.joined(s),
                    None => Vec::new(),
                };
                let solved = self.solver.solve_many(&poses, 2);
                out.extend(self.choose(moves, &poses, solved));
                return Some(out);
            }
        };
        before.map(|s| self.joined(s))
    }

    /// The chunk `s` solved in the background, chosen.
    fn joined(&mut self, s: Solving) -> Vec<Solved> {
        let solved = s
            .thread
            .join()
            .unwrap_or_else(|e| std::panic::resume_unwind(e));
        self.choose(s.moves, &s.poses, solved)
    }

    /// The pose of `m` as the solver takes it: the tool turned `rot`, at
    /// the focus, through the positioner at the move's angles.
    fn pose(&mut self, m: &Move, rot: Matrix3<f64>) -> ([f64; 3], Matrix3<f64>) {
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
        let mut out = match self.solving.take() {
            Some(s) => self.joined(s),
            None => Vec::new(),
        };
        let moves = std::mem::take(&mut self.moves);
        let poses = std::mem::take(&mut self.poses);
        let solved = self.solver.solve_many(&poses, 2);
        out.extend(self.choose(moves, &poses, solved));
        out
    }

    /// Chooses, in order, each pose's solution nearest the one before.
    fn choose(
        &mut self,
        moves: Vec<(Move, f64)>,
        poses: &[Pose6],
        solved: Vec<Solutions>,
    ) -> Vec<Solved> {
        let mut out = Vec::with_capacity(moves.len());
        for (((m, way), &(to, rot)), (sols, wrist)) in moves.into_iter().zip(poses).zip(solved) {
            // The first move (the PTP from home) as the KRL writer solves it,
            // and a pose at the wrist singularity, by the move before.
            let joints = match (self.first, Solver::nearest(&sols, &self.prev)) {
                (false, Some(j)) => Some(j),
                _ if sols.is_empty() => None,
                _ => self.solver.solve(to, &rot, &self.prev).first().copied(),
            };
            if let Some(j) = joints {
                self.prev = j;
            }
            self.first = false;
            out.push(Solved {
                m,
                way,
                to,
                rot,
                joints,
                wrist,
            });
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::target::arm::CATALOGUE;

    fn solver(key: &str) -> Solver {
        let arm = crate::target::arm::model(key).unwrap().arm(0.0, 5.0);
        Solver::with(arm, Isometry3::identity(), Isometry3::identity())
    }

    /// At KUKA's home (A2 −90°, A3 90°, the rest 0) the flange faces
    /// forward: `$POS_ACT` reads `A 0, B 90, C 0`, at the upper arm's top
    /// plus the forearm and the wrist ahead.
    #[test]
    fn home_faces_forward() {
        for m in CATALOGUE {
            let s = solver(m.key);
            let f = s.forward_flange(&[0.0, -90.0, 90.0, 0.0, 0.0, 0.0]);
            let [a1, a2, _, c1, c2, c3, c4] = s.arm.opw;
            let t = f.translation.vector;
            assert!((t.x - (a1 + c3 + c4)).abs() < 1e-6, "{} x {}", m.key, t.x);
            assert!(t.y.abs() < 1e-6);
            assert!((t.z - (c1 + c2 - a2)).abs() < 1e-6, "{} z {}", m.key, t.z);
            let z = f.rotation * Vector3::z();
            assert!((z - Vector3::x()).norm() < 1e-9, "{} flange z {z:?}", m.key);
        }
    }

    /// φ, the stretch angle, is where the wrist centre is farthest from A2.
    #[test]
    fn stretch_is_farthest() {
        for m in CATALOGUE {
            let s = solver(m.key);
            let dist = |a3: f64| {
                let f = s.forward_flange(&[0.0, -90.0, a3, 0.0, 0.0, 0.0]);
                let w = s.wrist(&f);
                let [a1, _, _, c1, ..] = s.arm.opw;
                ((w.x - a1).powi(2) + (w.z - c1).powi(2)).sqrt()
            };
            let phi = s.stretch();
            assert!(
                dist(phi) > dist(phi + 1.0) && dist(phi) > dist(phi - 1.0),
                "{}",
                m.key
            );
            let (_, span) = (0.0, s.reach([0.0; 3], &Matrix3::identity()).1);
            assert!((dist(phi) - span[1]).abs() < 1e-6, "{}", m.key);
        }
    }

    /// Solving many poses at once and picking the nearest is what solving
    /// each from the one before does, along a path away from the wrist
    /// singularity, A4 and A6 winding past ±180°.
    #[test]
    fn many_then_nearest_is_continuing() {
        for m in CATALOGUE {
            let s = solver(m.key);
            let mut prev = [5.0, -80.0, 100.0, 170.0, 40.0, 170.0];
            let poses: Vec<_> = (0..200)
                .map(|k| {
                    let t = k as f64 / 20.0;
                    s.forward(&[
                        5.0 + t,
                        -80.0 + t,
                        100.0 - t,
                        170.0 + 3.0 * t,
                        40.0,
                        170.0 + 4.0 * t,
                    ])
                })
                .collect();
            let many = s.solve_many(&poses, 2);
            for ((to, rot), (sols, _)) in poses.iter().zip(&many) {
                let a = Solver::nearest(sols, &prev).unwrap();
                let b = s.solve(*to, rot, &prev)[0];
                for i in 0..6 {
                    assert!((a[i] - b[i]).abs() < 1e-6, "{}: {a:?} vs {b:?}", m.key);
                }
                prev = a;
            }
            assert!(prev[3] > 180.0 && prev[5] > 180.0, "{prev:?}");
        }
    }
}
