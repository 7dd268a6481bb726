//! A robot's arm: the tool poses of the plan solved to axis angles A1–A6
//! with rs-opw-kinematics (closed-form inverse kinematics of an arm with an
//! ortho-parallel base and a spherical wrist), and what the controllers
//! call the solution's configuration: KUKA's Status and Turn, ABB's
//! `confdata` (`abb.rs`).
//!
//! Frames, as on the controller: a pose `P` (the laser focus, `X Y Z A B C`
//! in `$BASE`) is reached with the flange at `BASE · P · TOOL⁻¹` in the
//! robot's own frame (`$ROBROOT`, taken as `$WORLD`); the solver's `tool0` is
//! KUKA's `$FLANGE` or ABB's `tool0` and its joints are the controller's
//! axis angles, in the arm's offsets and signs ([`crate::target::arm`]):
//! an axis angle is `(θ + offset)·sign` of the solver's OPW angle `θ`.
//! Nothing here assumes one maker's convention: where an axis's direction
//! matters (A1's forward, A3's stretch) it is read through the arm's
//! offsets and signs. Angles here are degrees.

use crate::ir::{Arm, Pose, Robot};
use nalgebra::{Isometry3, Matrix3, Rotation3, Translation3, UnitQuaternion, Vector3};
use rs_opw_kinematics::glam::{DQuat, DVec3};
use rs_opw_kinematics::kinematic_traits::{Kinematics, Pose as OpwPose};
use rs_opw_kinematics::kinematics_impl::OPWKinematics;
use rs_opw_kinematics::parameters::opw_kinematics::Parameters;

/// Axis angles A1–A6, deg.
pub type Joints = [f64; 6];

/// A robot's arm with its base and tool: solves tool poses to axis angles.
#[derive(Clone, Debug)]
pub struct Solver {
    kin: OPWKinematics,
    arm: Arm,
    base: Isometry3<f64>,
    tool_inv: Isometry3<f64>,
    /// A3's axis angle where the arm is stretched (the wrist centre
    /// farthest from A2), deg, with the arm's offset and sign: KUKA's φ of
    /// Status bit 1, and where the two elbow solutions of a pose meet (and
    /// 180° on, folded).
    stretch: f64,
}

/// The crate's pose of the flange `f`.
fn opw_pose(f: &Isometry3<f64>) -> OpwPose {
    let (t, q) = (f.translation.vector, f.rotation.into_inner().coords);
    OpwPose::from_parts(
        DVec3::new(t.x, t.y, t.z),
        DQuat::from_xyzw(q.x, q.y, q.z, q.w),
    )
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
        Some(Solver::with(*arm, base, tool))
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
            // The closed form's θ3 = ±t − atan2(a2, c3) on the model; an
            // axis angle is (θ + offset)·sign.
            stretch: ((-a2).atan2(c3).to_degrees() + arm.offsets[2]) * f64::from(arm.signs[2]),
            arm,
            base,
            tool_inv: tool.inverse(),
        }
    }

    /// The arm.
    pub fn arm(&self) -> &Arm {
        &self.arm
    }

    /// A3's stretch angle, deg (an axis angle, in the arm's convention).
    pub fn stretch(&self) -> f64 {
        self.stretch
    }

    /// The solver's OPW angles `θ` of the axis angles `j`, deg: `j` is
    /// `(θ + offset)·sign` (a sign is ±1, its own inverse).
    pub fn theta(&self, j: &Joints) -> [f64; 6] {
        std::array::from_fn(|i| j[i] * f64::from(self.arm.signs[i]) - self.arm.offsets[i])
    }

    /// The axis angles of the solver's OPW angles `theta`, deg.
    pub fn axes(&self, theta: &[f64; 6]) -> Joints {
        std::array::from_fn(|i| (theta[i] + self.arm.offsets[i]) * f64::from(self.arm.signs[i]))
    }

    /// The arm upright in its own axis angles ([`crate::target::arm::upright`]):
    /// KUKA's home, ABB's zero.
    pub fn upright(&self) -> Joints {
        crate::target::arm::upright(&self.arm.offsets, &self.arm.signs)
    }

    /// The direction the arm faces at axis angles `j`: the horizontal unit
    /// vector from A1's axis towards A2's, in the robot's frame (OPW's A1
    /// turns about +Z; the arm's sign and offset say how its A1 does).
    pub fn facing(&self, j: &Joints) -> Vector3<f64> {
        let t = (j[0] * f64::from(self.arm.signs[0]) - self.arm.offsets[0]).to_radians();
        Vector3::new(t.cos(), t.sin(), 0.0)
    }

    /// Whether A3 is at or past its stretch angle, folding the forearm
    /// forward of the upper arm (OPW's θ3 at or above its stretched value):
    /// KUKA's Status bit 1, the wrist centre *in front of* the lower arm
    /// in ABB's `cfx` where the arm is not folded past 180°.
    pub fn elbow_forward(&self, j: &Joints) -> bool {
        (j[2] - self.stretch) * f64::from(self.arm.signs[2]) >= 0.0
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

    /// `j` with A1, A2, A3 and A5 in the one turn centred on the middle of
    /// their limits: these axes turn less than a full turn, so the angle in
    /// that turn is the only one they can take (the solver keeps every axis
    /// in the turn nearest the last). Centred on the limits, not on 0°: a
    /// KUKA A2 of −185° (limits −190°…45°) is in range, its 175° is not.
    pub fn within_turn(&self, mut j: Joints) -> Joints {
        for i in [0, 1, 2, 4] {
            let [lo, hi] = self.arm.limits[i];
            let low = (lo + hi) / 2.0 - 180.0;
            j[i] -= 360.0 * ((j[i] - low) / 360.0).floor();
        }
        j
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
        let pose = opw_pose(&f);
        let prev = prev.map(f64::to_radians);
        let sols = self
            .kin
            .inverse_continuing(&pose, &prev)
            .into_iter()
            .map(|j| self.within_turn(j.map(f64::to_degrees)))
            .collect();
        (sols, self.wrist(&f))
    }

    /// The axis angles the PTP from home takes for the tool at `to` with
    /// axes `rot` (`None` out of reach): of every solution (A4 and A6 in
    /// the turn nearest `home`'s), the one whose axes differ least from
    /// `home` in sum. Two equally near (within 10⁻⁹°: the wrist flipped or
    /// not, A6 at +180° or −180° from home) are told apart so the choice
    /// never depends on the solver's order: the wrist not flipped first
    /// (A5 ≥ 0, Status bit 2 clear), then by the axes in order, the lower
    /// angle first (A6 −180° before +180°). The KRL writer's `S` and `T`
    /// and the verifier's first pose are both this one.
    pub fn home_solution(&self, to: [f64; 3], rot: &Matrix3<f64>, home: &Joints) -> Option<Joints> {
        let dist = |j: &Joints| -> f64 { j.iter().zip(home).map(|(a, b)| (a - b).abs()).sum() };
        self.solve(to, rot, home).into_iter().min_by(|a, b| {
            let (da, db) = (dist(a), dist(b));
            if (da - db).abs() > 1e-9 {
                return da.total_cmp(&db);
            }
            let flipped = |j: &Joints| j[4] < 0.0;
            if flipped(a) != flipped(b) {
                return flipped(a).cmp(&flipped(b));
            }
            a.iter()
                .zip(b)
                .map(|(x, y)| x.total_cmp(y))
                .find(|o| o.is_ne())
                .unwrap_or(std::cmp::Ordering::Equal)
        })
    }

    /// Every solution for the flange at `f` (in the robot's frame), in no
    /// order: what [`Self::nearest`] picks from.
    pub fn solutions(&self, f: &Isometry3<f64>) -> Vec<Joints> {
        let mut sols = self.kin.inverse(&opw_pose(f));
        for j in &mut sols {
            *j = j.map(f64::to_degrees);
        }
        sols
    }

    /// The flange in the robot's frame at axis angles `q` in radians, as
    /// the solver's forward kinematics puts it; `None` where it cannot.
    pub fn flange_rad(&self, q: &[f64; 6]) -> Option<Isometry3<f64>> {
        let p = self.kin.try_forward(q).ok()?;
        let (t, r) = (p.translation, p.rotation);
        Some(Isometry3::from_parts(
            Translation3::new(t.x, t.y, t.z),
            UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(r.w, r.x, r.y, r.z)),
        ))
    }

    /// The least distance from the solution `j`, whose wrist centre is `w`,
    /// to any other solution of the same pose, deg, in the measure
    /// [`Self::nearest`] ranks by: every other solution turns A1 to the other
    /// shoulder (180° less twice the angle the shoulder offset `b` makes at
    /// the wrist centre's distance from A1), or A3 to the other elbow (twice
    /// A3's distance from where the two elbows meet, stretched or folded), or
    /// flips the wrist (A4 and A6 by 180° each). 0 within 1 mm of A1's axis,
    /// where A1 is free.
    pub fn separation(&self, j: &Joints, w: &Vector3<f64>) -> f64 {
        let b = self.arm.opw[2];
        let r2 = w.x * w.x + w.y * w.y - b * b;
        if r2 < 1.0 {
            return 0.0;
        }
        let shoulder = 180.0 - 2.0 * b.abs().atan2(r2.sqrt()).to_degrees();
        let u = ((j[2] - self.stretch + 180.0).rem_euclid(360.0) - 180.0).abs();
        let elbow = 2.0 * u.min(180.0 - u);
        shoulder.min(elbow).min(360.0)
    }

    /// Of `sols` (from [`Self::solutions`]), the one nearest `prev` (the
    /// sum of the axes' differences, as the solver sorts), every axis in the
    /// turn nearest `prev`'s, A1, A2, A3 and A5 in their one turn
    /// ([`Self::within_turn`]). `None`
    /// where there is none, or where the pose is at the wrist singularity
    /// (A5 within 10⁻⁶° of 0): A4 and A6 are then split by the move before,
    /// which only [`Self::solve_at`] does.
    pub fn nearest(&self, sols: &[Joints], prev: &Joints) -> Option<Joints> {
        let mut best: Option<(f64, Joints)> = None;
        for s in sols {
            if s[4].abs() < 1e-6 {
                return None;
            }
            let mut j = *s;
            for i in 0..6 {
                j[i] = prev[i] + ((j[i] - prev[i] + 180.0).rem_euclid(360.0) - 180.0);
            }
            let j = self.within_turn(j);
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

    /// The origins of the arm's frames at axis angles `j`, in the robot's
    /// frame, as the solver's forward kinematics chains them: A1 at the
    /// shoulder's height, the A2 axis (the shoulder), the A3 axis (the
    /// elbow), the forearm's start past its offset `a2`, the wrist centre
    /// and the flange. The collision checks hang the arm's links on them
    /// ([`crate::collision::arm`]).
    pub fn joint_points(&self, j: &Joints) -> [[f64; 3]; 6] {
        let poses = self.kin.forward_with_joint_poses(&j.map(f64::to_radians));
        poses.map(|p| [p.translation.x, p.translation.y, p.translation.z])
    }

    /// The tool's frame (its origin the focus) in the robot's frame at
    /// axis angles `j`: where the collision checks hang the head.
    pub fn tcp(&self, j: &Joints) -> Isometry3<f64> {
        self.forward_flange(j) * self.tool_inv.inverse()
    }

    /// [`Self::joint_points`] and [`Self::tcp`] from one pass of the
    /// forward kinematics (the collision checks ask both at every pose).
    pub fn joint_frames(&self, j: &Joints) -> ([[f64; 3]; 6], Isometry3<f64>) {
        let poses = self.kin.forward_with_joint_poses(&j.map(f64::to_radians));
        let (t, q) = (poses[5].translation, poses[5].rotation);
        let flange = Isometry3::from_parts(
            Translation3::new(t.x, t.y, t.z),
            UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q.w, q.x, q.y, q.z)),
        );
        let points = poses.map(|p| [p.translation.x, p.translation.y, p.translation.z]);
        (points, flange * self.tool_inv.inverse())
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
        let [a1, _, _, c1, ..] = self.arm.opw;
        let w = self.wrist(&self.flange(to, rot));
        let h = (w.x * w.x + w.y * w.y).sqrt();
        let d = ((h - a1).powi(2) + (w.z - c1).powi(2)).sqrt();
        (d, self.span())
    }

    /// The nearest and farthest the arm puts the wrist centre from the A2
    /// axis, mm: the upper arm and the forearm folded and stretched.
    pub fn span(&self) -> [f64; 2] {
        let [_, a2, _, _, c2, c3, _] = self.arm.opw;
        let fore = (c3 * c3 + a2 * a2).sqrt();
        [(c2 - fore).abs(), c2 + fore]
    }

    /// How far the solution `j`, whose wrist centre is `w`, is from each
    /// singular configuration a LIN must keep clear of, deg: the wrist
    /// (|A5|), the stretched arm (A3 from φ), and the overhead
    /// ([`Self::overhead`]).
    pub fn singular(&self, j: &Joints, w: &Vector3<f64>) -> [f64; 3] {
        [j[4].abs(), (j[2] - self.stretch).abs(), self.overhead(w)]
    }

    /// How far the wrist centre `w` (robot's frame) is from A1's axis, as
    /// an angle seen from the shoulder's height on that axis, deg: 0 at the
    /// overhead singularity (the wrist centre on the axis, where A1 turns
    /// freely and spins near it). A shoulder offset `b` moves the singular
    /// line to `b` from the axis.
    pub fn overhead(&self, w: &Vector3<f64>) -> f64 {
        let [_, _, b, c1, ..] = self.arm.opw;
        let r = (w.x * w.x + w.y * w.y - b * b).max(0.0).sqrt();
        r.atan2((w.z - c1).abs()).to_degrees()
    }

    /// KUKA's Status of a solution: bit 0 the wrist centre behind A1
    /// (overhead), bit 1 A3 at or past its stretch angle
    /// ([`Self::elbow_forward`]), bit 2 A5 ≤ 0. On an arm of another maker
    /// it is still what the verifier tells configurations apart by (a LIN
    /// that changes it changes configuration); ABB's own is
    /// [`Self::confdata`].
    pub fn status(&self, j: &Joints) -> u8 {
        self.status_at(j, &self.wrist(&self.forward_flange(j)))
    }

    /// [`Self::status`] of a solution whose wrist centre is `w` (from
    /// [`Self::solve_at`]: no forward kinematics).
    pub fn status_at(&self, j: &Joints, w: &Vector3<f64>) -> u8 {
        u8::from(self.behind_a1(j, w))
            | (u8::from(self.elbow_forward(j)) << 1)
            | (u8::from(j[4] <= 0.0) << 2)
    }

    /// Whether the wrist centre `w` (robot's frame) of the solution `j` is
    /// behind A1's axis: on the other side of it from where the arm faces
    /// ([`Self::facing`]) — KUKA's Status bit 0, ABB's `cfx` bit 2.
    pub fn behind_a1(&self, j: &Joints, w: &Vector3<f64>) -> bool {
        let f = self.facing(j);
        w.x * f.x + w.y * f.y < 0.0
    }

    /// KUKA's Turn: bit `i` set where axis `i + 1` is negative.
    pub fn turn(j: &Joints) -> u8 {
        j.iter()
            .enumerate()
            .fold(0, |t, (i, a)| t | (u8::from(*a < 0.0) << i))
    }
}

mod abb;
mod chain;
pub mod clearance;
mod follow;
pub mod reach;

pub use follow::{Along, Follow, Solved, CHUNK, LIN_STEP_DEG, LIN_STEP_MM};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::target::arm::CATALOGUE;

    fn solver(key: &str) -> Solver {
        let arm = crate::target::arm::model(key).unwrap().arm(0.0, 5.0);
        Solver::with(arm, Isometry3::identity(), Isometry3::identity())
    }

    /// Upright — KUKA's home (A2 −90°, A3 90°, the rest 0), ABB's zero —
    /// the flange faces forward: `$POS_ACT` reads `A 0, B 90, C 0`, at the
    /// upper arm's top plus the forearm and the wrist ahead.
    #[test]
    fn home_faces_forward() {
        for m in CATALOGUE {
            let s = solver(m.key);
            assert_eq!(s.upright(), m.upright());
            let f = s.forward_flange(&s.upright());
            let [a1, a2, _, c1, c2, c3, c4] = s.arm.opw;
            let t = f.translation.vector;
            assert!((t.x - (a1 + c3 + c4)).abs() < 1e-6, "{} x {}", m.key, t.x);
            assert!(t.y.abs() < 1e-6);
            assert!((t.z - (c1 + c2 - a2)).abs() < 1e-6, "{} z {}", m.key, t.z);
            let z = f.rotation * Vector3::z();
            assert!((z - Vector3::x()).norm() < 1e-9, "{} flange z {z:?}", m.key);
        }
    }

    /// An axis whose limits reach past ±180° (the KR 6 R900-2's A2,
    /// −190°…45°) is solved in its limits: a pose with A2 at −185° comes
    /// back at −185°, not at the 175° of the same turn outside them.
    #[test]
    fn a_limit_past_a_half_turn_keeps_its_angle() {
        let s = solver("kr6_r900_2");
        let j = [10.0, -185.0, 100.0, 20.0, 40.0, 30.0];
        let f = s.forward_flange(&j);
        let all: Vec<Joints> = s
            .solutions(&f)
            .into_iter()
            .map(|q| s.within_turn(q))
            .collect();
        let near = s.nearest(&all, &j).unwrap();
        for i in 0..6 {
            assert!((near[i] - j[i]).abs() < 1e-6, "{near:?}");
        }
        let tcp = s.forward(&j);
        let solved = s.solve(tcp.0, &tcp.1, &j);
        assert!((solved[0][1] + 185.0).abs() < 1e-6, "{solved:?}");
    }

    /// The PTP from home to a tool pointing straight down ahead of the arm:
    /// from the upright home (A4 = A5 = A6 = 0) the wrist reaches it either
    /// unflipped (A5 > 0, A6 a half turn, +180° or −180° as near) or
    /// flipped (A5 < 0, A4 a half turn), all four equally near. The rule
    /// takes A5 > 0 and A6 = −180°, whatever order the solver gives.
    #[test]
    fn the_ptp_from_home_breaks_ties_by_the_stated_rule() {
        for m in CATALOGUE {
            let s = solver(m.key);
            let home = s.upright();
            let [a1, _, _, c1, c2, c3, c4] = s.arm.opw;
            let to = [a1 + 0.6 * (c3 + c4), 0.0, c1 + 0.3 * c2 - c4];
            // The flange's Z straight down, its X ahead: A6 a half turn from home.
            let rot = Matrix3::new(1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, -1.0);
            let all = s.solve(to, &rot, &home);
            let j = s.home_solution(to, &rot, &home).unwrap();
            assert!(
                j[4] > 0.0 && (j[5] + 180.0).abs() < 1e-6 && j[3].abs() < 1e-6,
                "{} {j:?}",
                m.key
            );
            // Tied with a flipped wrist: the rule, not the order, decided.
            let dist = |q: &Joints| q.iter().zip(&home).map(|(a, b)| (a - b).abs()).sum::<f64>();
            assert!(
                all.iter()
                    .any(|q| q[4] < 0.0 && (dist(q) - dist(&j)).abs() < 1e-6),
                "{} {all:?}",
                m.key
            );
        }
    }

    /// φ, the stretch angle, is where the wrist centre is farthest from A2.
    #[test]
    fn stretch_is_farthest() {
        for m in CATALOGUE {
            let s = solver(m.key);
            let dist = |a3: f64| {
                let mut j = s.upright();
                j[2] = a3;
                let f = s.forward_flange(&j);
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

    /// A path of axis angles away from the wrist singularity, A4 and A6
    /// winding past ±180° as `t` grows (start at 0), from the arm's upright
    /// pose `up` ([`Solver::upright`]).
    pub(super) fn winding(up: &Joints, t: f64) -> Joints {
        let d = [
            5.0 + t,
            10.0 + t,
            10.0 - t,
            170.0 + 3.0 * t,
            40.0,
            170.0 + 4.0 * t,
        ];
        std::array::from_fn(|i| up[i] + d[i])
    }

    /// Picking the nearest of every solution is what solving each from the
    /// one before does, along a path away from the wrist singularity, A4
    /// and A6 winding past ±180°.
    #[test]
    fn nearest_is_continuing() {
        for m in CATALOGUE {
            let s = solver(m.key);
            let up = s.upright();
            let mut prev = winding(&up, 0.0);
            for k in 0..200 {
                let t = k as f64 / 20.0;
                let (to, rot) = s.forward(&winding(&up, t));
                let a = s.nearest(&s.solutions(&s.flange(to, &rot)), &prev).unwrap();
                let b = s.solve(to, &rot, &prev)[0];
                for i in 0..6 {
                    assert!((a[i] - b[i]).abs() < 1e-6, "{}: {a:?} vs {b:?}", m.key);
                }
                prev = a;
            }
            assert!(prev[3] > 180.0 && prev[5] > 180.0, "{prev:?}");
        }
    }
}
