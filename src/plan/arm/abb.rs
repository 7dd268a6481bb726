//! ABB's configuration data of a solution (`confdata`: `cf1, cf4, cf6,
//! cfx` of a `robtarget`), from the same solutions the verifier checks.
//!
//! ABB's rule (*Technical reference manual – RAPID Instructions, Functions
//! and Data types*, `confdata`, for serial six-axis arms): `cf1`, `cf4`,
//! `cf6` are the quadrants of axes 1, 4 and 6 — 0 for 0°…90°, 1 for
//! 90°…180°, −1 for −90°…0°, −2 for −180°…−90°, and on past ±180° — and
//! `cfx` picks one of eight configurations by where the wrist centre is and
//! how axis 5 bends:
//!
//! | `cfx` | wrist centre to axis 1 | wrist centre to the lower arm | axis 5 |
//! |---|---|---|---|
//! | 0 | in front of | in front of | positive |
//! | 1 | in front of | in front of | negative |
//! | 2 | in front of | behind | positive |
//! | 3 | in front of | behind | negative |
//! | 4 | behind | in front of | positive |
//! | 5 | behind | in front of | negative |
//! | 6 | behind | behind | positive |
//! | 7 | behind | behind | negative |
//!
//! that is `cfx = 4·(behind axis 1) + 2·(behind the lower arm) + (axis 5
//! negative)`. ABB's lower arm is the link from axis 2 to axis 3 (KUKA's
//! and OPW's upper arm, `c2`).

use super::{Joints, Solver};
use nalgebra::Vector3;

impl Solver {
    /// ABB's `[cf1, cf4, cf6, cfx]` of the solution `j` (the controller's
    /// axis angles, deg; the module's table): `cf1`, `cf4`, `cf6` the
    /// quadrants `⌊angle / 90°⌋` of axes 1, 4 and 6 (−1 for −90°…0°);
    /// `cfx` = 4·(wrist centre behind axis 1) + 2·(wrist centre behind the
    /// lower arm) + (axis 5 negative, below 0°).
    ///
    /// Against KUKA's Status and Turn ([`Self::status`], [`Self::turn`]):
    /// behind axis 1 is Status bit 0 (the same test, [`Self::behind_a1`]);
    /// behind the lower arm is Status bit 1 *clear* (A3 short of its stretch
    /// angle, the forearm folded back over the lower arm: an ABB arm's usual
    /// configuration has the wrist in front, `cfx` bit 1 clear, where a
    /// KUKA's has Status bit 1 set); axis 5 negative is Status bit 2 but for
    /// A5 = 0 (KUKA counts 0 as its bit set, ABB as positive). The quadrants
    /// say more than Turn's signs: which quarter turn, so A4 and A6 at ±360°
    /// apart are told apart (Turn says only the sign). The lower arm side is
    /// read off the arm's geometry as ABB defines it — the wrist centre on
    /// the forward side of the line through axes 2 and 3, in the arm's
    /// plane — not off axis 3's angle, so no convention is assumed.
    pub fn confdata(&self, j: &Joints) -> [i32; 4] {
        let quadrant = |a: f64| (a / 90.0).floor() as i32;
        let p = self.joint_points(j);
        let w = Vector3::from(p[4]);
        let cfx = 4 * i32::from(self.behind_a1(j, &w))
            + 2 * i32::from(self.behind_lower_arm(j, &p))
            + i32::from(j[4] < 0.0);
        [quadrant(j[0]), quadrant(j[3]), quadrant(j[5]), cfx]
    }

    /// Whether the wrist centre is behind ABB's lower arm (axis 2 to axis
    /// 3) at axis angles `j`, whose frames' origins are `p`
    /// ([`Self::joint_points`]): on the side of the line through the two
    /// axes away from the one the arm faces, seen in the arm's plane.
    fn behind_lower_arm(&self, j: &Joints, p: &[[f64; 3]; 6]) -> bool {
        let f = self.facing(j);
        let along = |v: [f64; 3], o: [f64; 3]| {
            let d = Vector3::new(v[0] - o[0], v[1] - o[1], v[2] - o[2]);
            (d.dot(&f), d.z)
        };
        let (uf, uz) = along(p[2], p[1]);
        let (rf, rz) = along(p[4], p[1]);
        // The lower arm's normal towards its front: up turned to forward.
        rf * uz - rz * uf < 0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::target::arm::CATALOGUE;
    use nalgebra::Isometry3;
    use proptest::prelude::*;

    fn solver(key: &str) -> Solver {
        let arm = crate::target::arm::model(key).unwrap().arm(0.0, 5.0);
        Solver::with(arm, Isometry3::identity(), Isometry3::identity())
    }

    /// Hand-picked axes of an IRB 4600-60/2.05 (stretch at A3 ≈ −79.7°),
    /// each `cfx` of the table, and quadrants either side of 0.
    #[test]
    fn confdata_follows_abbs_table() {
        let s = solver("irb4600_60_205");
        let cases: [(Joints, [i32; 4]); 12] = [
            // Calibration position: everything in front, axis 5 at 0 positive.
            ([0.0; 6], [0, 0, 0, 0]),
            ([-45.0, 10.0, 20.0, -100.0, 30.0, 200.0], [-1, -2, 2, 0]),
            ([100.0, 10.0, 20.0, 90.0, -30.0, -90.0], [1, 1, -1, 1]),
            // Lower arm tilted forward, forearm folded up past the stretch.
            ([0.0, 60.0, -120.0, 0.0, 30.0, 0.0], [0, 0, 0, 2]),
            ([0.0, 60.0, -120.0, 0.0, -30.0, 0.0], [0, 0, 0, 3]),
            // Lower arm tilted back, the wrist centre behind axis 1.
            ([0.0, -80.0, 0.0, 0.0, 30.0, 0.0], [0, 0, 0, 4]),
            ([0.0, -80.0, 0.0, 0.0, -30.0, 0.0], [0, 0, 0, 5]),
            ([0.0, -80.0, -120.0, 0.0, 30.0, 0.0], [0, 0, 0, 6]),
            ([0.0, -80.0, -120.0, 0.0, -30.0, 0.0], [0, 0, 0, 7]),
            // Quadrants: −1 for −90°…0°, −2 for −180°…−90°, past a turn.
            ([-0.5, 0.0, 0.0, -90.5, 30.0, -179.0], [-1, -2, -2, 0]),
            ([179.0, 0.0, 0.0, 359.0, 30.0, 390.0], [1, 3, 4, 0]),
            ([-180.0, 0.0, 0.0, -360.0, 30.0, -400.0], [-2, -4, -5, 0]),
        ];
        for (j, want) in cases {
            assert_eq!(s.confdata(&j), want, "{j:?}");
        }
    }

    /// A solution of the catalogue's arms in range, away from the three
    /// singularities (by `clear` deg), or `None`.
    fn away(s: &Solver, lim: &[[f64; 2]; 6], u: &[f64; 6], clear: f64) -> Option<Joints> {
        let j: Joints = std::array::from_fn(|i| {
            let [lo, hi] = lim[i];
            (lo + hi) / 2.0 + u[i] * (hi - lo) / 2.0
        });
        let w = s.wrist(&s.forward_flange(&j));
        let near = s.singular(&j, &w);
        let folded = (j[2] - s.stretch()).abs() > 180.0 - clear;
        // A1 within a half turn: the solver gives it no other turn.
        let a1 = j[0].abs() < 180.0 - clear;
        (near.iter().all(|d| *d > clear) && !folded && a1).then_some(j)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(128))]

        /// `confdata` tells the solutions of a pose apart: every solution of
        /// the pose a solution reaches (A4 and A6 a turn either way too)
        /// has its own `confdata`, and the one with the solution's own is
        /// the solution.
        #[test]
        fn confdata_tells_the_solutions_of_a_pose_apart(
            arm in 0..CATALOGUE.len(),
            u in prop::array::uniform6(-1.0f64..1.0),
        ) {
            let m = &CATALOGUE[arm];
            let s = solver(m.key);
            let Some(j) = away(&s, &m.limits, &u, 2.0) else { return Ok(()) };
            let f = s.forward_flange(&j);
            let mut sols: Vec<Joints> = Vec::new();
            for q in s.solutions(&f).into_iter().filter(|q| q.iter().all(|a| a.is_finite())) {
                let q = s.within_turn(q);
                for k in 0..9 {
                    let (d4, d6) = (360.0 * f64::from(k / 3 - 1), 360.0 * f64::from(k % 3 - 1));
                    let mut q = q;
                    q[3] += d4;
                    q[5] += d6;
                    let same = |o: &Joints| (0..6).all(|i| (o[i] - q[i]).abs() < 1e-6);
                    if !sols.iter().any(same) {
                        sols.push(q);
                    }
                }
            }
            prop_assert!(sols.len() >= 2, "{}: {sols:?}", m.key);
            for (a, qa) in sols.iter().enumerate() {
                for qb in &sols[a + 1..] {
                    prop_assert_ne!(s.confdata(qa), s.confdata(qb), "{}: {:?} and {:?}", m.key, qa, qb);
                }
            }
            let own: Vec<_> = sols.iter().filter(|q| s.confdata(q) == s.confdata(&j)).collect();
            prop_assert_eq!(own.len(), 1, "{}", m.key);
            for i in 0..6 {
                prop_assert!((own[0][i] - j[i]).abs() < 1e-6, "{}: {:?} vs {:?}", m.key, own[0], j);
            }
        }

        /// `cfx` against KUKA's Status, on every arm of either maker: behind
        /// axis 1 is bit 0, behind the lower arm is bit 1 clear (the arm
        /// not folded past 180° from its stretch), axis 5 negative is bit 2
        /// (A5 not 0).
        #[test]
        fn cfx_is_status_read_abbs_way(
            arm in 0..CATALOGUE.len(),
            u in prop::array::uniform6(-1.0f64..1.0),
        ) {
            let m = &CATALOGUE[arm];
            let s = solver(m.key);
            let Some(j) = away(&s, &m.limits, &u, 0.5) else { return Ok(()) };
            let st = i32::from(s.status(&j));
            let cfx = s.confdata(&j)[3];
            prop_assert_eq!(cfx, 4 * (st & 1) + 2 * (1 - ((st >> 1) & 1)) + ((st >> 2) & 1), "{} at {:?}", m.key, j);
        }
    }
}
