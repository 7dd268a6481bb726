//! Each pose's axis angles chosen, in order, nearest the pose before's.
//!
//! rs-opw-kinematics' closed form finds all eight solutions of a pose and
//! checks each with forward kinematics: about 1.2 µs a pose, which on the
//! dense duct's four million poses is most of the build. Consecutive poses
//! of a plan lie a fraction of a millimetre apart, and the solution wanted
//! is the one nearest the last. So a pose is first *continued* from the
//! last solution: Newton steps on the crate's own forward kinematics (the
//! Jacobian taken from it by differences, kept while the arm moves little),
//! until the crate's forward kinematics puts the flange on the pose to
//! 10⁻⁸ mm and 10⁻¹⁰ rad and the next step would move no axis by more than
//! 10⁻¹¹ rad. The result is kept only where it is provably the
//! solution the closed form's nearest would be: it lies less than
//! [`MAX_STEP`] from the last, and less than half as far as the nearest
//! other solution of the pose can lie ([`Solver::separation`]: the other
//! shoulder, the other elbow, the flipped wrist). Anything else — the
//! first move, a pose after one out of reach, a pose near a singularity, a
//! step the iteration does not settle — is solved by the closed form, as
//! before. The two ways choose the same angles (tested to 10⁻⁶°); the
//! closed form stays the authority.

use super::{Joints, Solver};
use nalgebra::{Isometry3, Matrix3, Matrix6, Vector3, Vector6};

/// The most a continued solution may lie from the last, deg (the sum of
/// the axes' turns, the measure [`Solver::nearest`] ranks by).
pub const MAX_STEP: f64 = 1.0;
/// |A5| below which a pose is left to the closed form, deg: at the wrist
/// singularity A4 and A6 are split by the move before ([`Solver::solve`]).
const WRIST_DEG: f64 = 1e-3;
/// Newton steps tried before the closed form takes over.
const ITERATIONS: usize = 4;
/// How near the flange must come to the pose, mm and rad.
const TOL_MM: f64 = 1e-8;
const TOL_RAD: f64 = 1e-10;
/// How near the axes must come to the pose's solution, rad: the next
/// Newton step's size. Near the wrist singularity a pose residual within
/// [`TOL_RAD`] still leaves A4 and A6 loose by about TOL_RAD / sin A5
/// (10⁻⁶° at A5 = 0.2°), so convergence is judged on the axes as well.
const TOL_Q: f64 = 1e-11;
/// The axis step of the Jacobian's differences, rad.
const H: f64 = 1e-6;
/// How far the axes may move from where the Jacobian was taken before it
/// is taken again, rad (its error slows each step by about this ratio).
const JACOBIAN_RANGE: f64 = 0.005;

/// The running choice: the last solution and where it puts the flange.
pub(super) struct Chain {
    prev: Joints,
    /// The flange at `prev` (forward kinematics): where continuing starts.
    /// `None` before the first solution, or when poses are not consecutive.
    at: Option<Isometry3<f64>>,
    /// No pose solved yet: the next is the PTP from home.
    first: bool,
    /// Whether poses follow each other (a plan's moves in order) and may be
    /// continued; picked poses are each solved in closed form.
    continuing: bool,
    /// The Jacobian's inverse, and the angles (rad) it was taken at.
    jacobian: Option<([f64; 6], Matrix6<f64>)>,
    /// Poses continued, and poses solved in closed form.
    pub counts: [u64; 2],
}

impl Chain {
    /// A chain starting at `home`.
    pub fn new(home: Joints, continuing: bool) -> Chain {
        Chain {
            prev: home,
            at: None,
            first: true,
            continuing,
            jacobian: None,
            counts: [0; 2],
        }
    }

    /// Poses are picked, not consecutive: each is solved in closed form.
    pub fn picked(&mut self) {
        self.continuing = false;
        self.at = None;
    }

    /// The axis angles of the tool at `to` with axes `rot` nearest the last
    /// solution's (the first: as the KRL writer solves the PTP from home),
    /// `None` out of reach; and the pose's wrist centre.
    pub fn next(
        &mut self,
        s: &Solver,
        to: [f64; 3],
        rot: &Matrix3<f64>,
    ) -> (Option<Joints>, Vector3<f64>) {
        let f = s.flange(to, rot);
        let wrist = s.wrist(&f);
        if let Some((j, at)) = self.continued(s, &f, &wrist) {
            self.prev = j;
            self.at = Some(at);
            self.counts[0] += 1;
            return (Some(j), wrist);
        }
        self.counts[1] += 1;
        let sols = s.solutions(&f);
        let joints = match (self.first, s.nearest(&sols, &self.prev)) {
            (false, Some(j)) => Some(j),
            _ if sols.is_empty() => None,
            _ => s.home_solution(to, rot, &self.prev),
        };
        self.first = false;
        if let Some(j) = joints {
            self.prev = j;
            self.at = if self.continuing {
                s.flange_rad(&j.map(f64::to_radians))
            } else {
                None
            };
        }
        (joints, wrist)
    }

    /// The last solution continued to the flange `target`, and where it
    /// puts the flange; `None` where the closed form must decide.
    fn continued(
        &mut self,
        s: &Solver,
        target: &Isometry3<f64>,
        wrist: &Vector3<f64>,
    ) -> Option<(Joints, Isometry3<f64>)> {
        let from = self.at?;
        let mut q = self.prev.map(f64::to_radians);
        let inverse = self.jacobian(s, &q)?;
        let mut e = error(target, &from);
        for k in 0..ITERATIONS {
            let dq = inverse * e;
            for (a, d) in q.iter_mut().zip(dq.iter()) {
                *a += d;
            }
            let f = s.flange_rad(&q)?;
            e = error(target, &f);
            if e.fixed_rows::<3>(0).norm() < TOL_MM
                && e.fixed_rows::<3>(3).norm() < TOL_RAD
                && (inverse * e).amax() < TOL_Q
            {
                if k >= 2 {
                    // Slow to settle: the Jacobian is stale.
                    self.jacobian = None;
                }
                return self.guarded(s, q, wrist).map(|j| (j, f));
            }
        }
        self.jacobian = None;
        None
    }

    /// The Jacobian's inverse near `q` (rad): the one kept, or a new one.
    fn jacobian(&mut self, s: &Solver, q: &[f64; 6]) -> Option<Matrix6<f64>> {
        if let Some((at, m)) = &self.jacobian {
            if at
                .iter()
                .zip(q)
                .all(|(a, b)| (a - b).abs() < JACOBIAN_RANGE)
            {
                return Some(*m);
            }
        }
        let f0 = s.flange_rad(q)?;
        let mut m = Matrix6::zeros();
        for i in 0..6 {
            let mut p = *q;
            p[i] += H;
            m.set_column(i, &(error(&s.flange_rad(&p)?, &f0) / H));
        }
        let inverse = m.try_inverse()?;
        self.jacobian = Some((*q, inverse));
        Some(inverse)
    }

    /// `q` (rad) in degrees as [`Solver::nearest`] gives a solution, where
    /// it is provably the nearest: a small step from the last, much smaller
    /// than the way to any other solution, off the wrist singularity.
    fn guarded(&self, s: &Solver, q: [f64; 6], wrist: &Vector3<f64>) -> Option<Joints> {
        let j = s.within_turn(q.map(f64::to_degrees));
        let step: f64 = j.iter().zip(&self.prev).map(|(a, b)| (a - b).abs()).sum();
        // Another solution q' lies at least `separation` from j, so at least
        // separation − step from the last: farther than j when 2·step is less.
        let ok = step < MAX_STEP
            && j[4].abs() > WRIST_DEG
            && 2.0 * step + 1e-9 < s.separation(&j, wrist);
        ok.then_some(j)
    }
}

/// How far the flange `at` is from `target`: the translation (mm) and the
/// turn (rad, about the robot's axes) from one to the other.
fn error(target: &Isometry3<f64>, at: &Isometry3<f64>) -> Vector6<f64> {
    let dp = target.translation.vector - at.translation.vector;
    let d = (target.rotation * at.rotation.inverse()).into_inner();
    // The shorter way round; the rotation vector exact to the smallest turn.
    let (w, v) = if d.w < 0.0 {
        (-d.w, -d.imag())
    } else {
        (d.w, d.imag())
    };
    let n = v.norm();
    let r = if n < 1e-12 {
        2.0 * v
    } else {
        v * (2.0 * n.atan2(w) / n)
    };
    Vector6::new(dp.x, dp.y, dp.z, r.x, r.y, r.z)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::target::arm::CATALOGUE;
    use proptest::prelude::*;

    fn solver(key: &str, base: Isometry3<f64>) -> Solver {
        let arm = crate::target::arm::model(key).unwrap().arm(0.0, 5.0);
        Solver::with(arm, base, Isometry3::identity())
    }

    /// Each pose of `path` (axis angles, deg, turned to poses by forward
    /// kinematics) solved by a continuing chain and by the closed form
    /// alone; asserts they choose the same, gives how many were continued.
    fn both(s: &Solver, path: &[Joints]) -> u64 {
        let home = s.upright();
        let (mut fast, mut closed) = (Chain::new(home, true), Chain::new(home, false));
        for j in path {
            let (to, rot) = s.forward(j);
            let (a, wa) = fast.next(s, to, &rot);
            let (b, wb) = closed.next(s, to, &rot);
            assert!((wa - wb).norm() < 1e-9);
            match (a, b) {
                (Some(a), Some(b)) => {
                    for i in 0..6 {
                        assert!((a[i] - b[i]).abs() < 1e-6, "at {j:?}: {a:?} vs {b:?}");
                    }
                }
                (a, b) => assert_eq!(a.is_some(), b.is_some(), "at {j:?}"),
            }
        }
        assert_eq!(closed.counts[0], 0);
        fast.counts[0]
    }

    /// Along a smooth path of small steps, nearly every pose is continued,
    /// and each chooses what the closed form chooses, for every arm.
    #[test]
    fn smooth_paths_are_continued() {
        for m in CATALOGUE {
            let s = solver(m.key, Isometry3::identity());
            let up = s.upright();
            let path: Vec<Joints> = (0..2000)
                .map(|k| super::super::tests::winding(&up, k as f64 / 100.0))
                .collect();
            let continued = both(&s, &path);
            assert!(continued >= 1990, "{}: {continued} of 2000", m.key);
        }
    }

    /// Across the wrist singularity (A5 through 0) and the stretched elbow,
    /// the chain leaves the poses near them to the closed form and still
    /// chooses what it chooses.
    #[test]
    fn singularities_go_to_the_closed_form() {
        let s = solver("kr60ha", Isometry3::identity());
        let phi = s.stretch();
        let path: Vec<Joints> = (0..400)
            .map(|k| {
                let t = k as f64 / 100.0 - 2.0;
                [10.0, -60.0, phi + 3.0 * t, 30.0, 5.0 * t, 20.0]
            })
            .collect();
        let continued = both(&s, &path);
        assert!(continued > 0 && continued < 400, "{continued}");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        /// Every other solution of a pose lies at least `separation` from a
        /// solution, in the measure the nearest is chosen by (each axis in
        /// the turn nearest): the bound the chain's guard stands on. Arms
        /// with an A3 offset or sign, and a shoulder offset b, included.
        #[test]
        fn separation_is_a_lower_bound(
            arm in 0..CATALOGUE.len(),
            j in prop::array::uniform6(-175.0f64..175.0),
            offset3 in prop::sample::select(vec![0.0, -90.0, 30.0]),
            sign3 in prop::sample::select(vec![1i8, -1]),
            b in prop::sample::select(vec![0.0, 40.0, -120.0]),
        ) {
            let mut a = crate::target::arm::model(CATALOGUE[arm].key).unwrap().arm(0.0, 5.0);
            a.offsets[2] = offset3;
            a.signs[2] = sign3;
            a.opw[2] = b;
            let s = Solver::with(a, Isometry3::identity(), Isometry3::identity());
            let f = s.forward_flange(&j);
            let sep = s.separation(&j, &s.wrist(&f));
            let mut own = 0;
            for o in s.solutions(&f) {
                let d: f64 = (0..6)
                    .map(|i| ((o[i] - j[i] + 180.0).rem_euclid(360.0) - 180.0).abs())
                    .sum();
                if d < 1e-6 {
                    own += 1;
                } else {
                    prop_assert!(d >= sep - 1e-6, "{o:?} is {d} from {j:?}, bound {sep}");
                }
            }
            prop_assert!(own >= 1, "the pose's own solution is among them");
        }

        /// Random paths, steps from a hundredth of a degree to tens of
        /// degrees, anywhere in the axes' ranges: the chain chooses what
        /// the closed form chooses at every pose.
        #[test]
        fn chain_is_the_closed_form(
            arm in 0..CATALOGUE.len(),
            start in prop::array::uniform6(-170.0f64..170.0),
            dirs in prop::collection::vec(prop::array::uniform6(-1.0f64..1.0), 1..4),
            scale in prop::sample::select(vec![0.01, 0.1, 1.0, 10.0]),
            base_x in -200.0f64..200.0,
        ) {
            let base = Isometry3::translation(base_x, 0.0, 0.0);
            let s = solver(CATALOGUE[arm].key, base);
            // The upper arm and the forearm kept as KUKA's A2 −140°…0° and
            // A3 −110°…150° keep them, in the solver's angles.
            let mut t = s.theta(&start);
            t[1] = t[1].clamp(-50.0, 90.0);
            t[2] = t[2].clamp(-110.0, 150.0);
            let mut j = s.axes(&t);
            let mut path = Vec::new();
            for d in &dirs {
                for _ in 0..60 {
                    for i in 0..6 {
                        j[i] += d[i] * scale;
                    }
                    path.push(j);
                }
            }
            both(&s, &path);
        }
    }
}
