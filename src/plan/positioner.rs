//! A robot's two-axis positioner: where it puts the part, and the angles
//! each layer is built at.
//!
//! The positioner is KUKA's mathematically coupled external kinematics: E1
//! turns about the tilt axis, fixed in the robot's frame (`$ROBROOT`, taken
//! as `$WORLD`); E2 turns about the rotate axis, carried by E1; the part's
//! base (`BASE_DATA[n]`, the robot's `base`) sits on E2's flange. With the
//! angles `e = (E1, E2)` the part's base is, in the robot's frame,
//!
//! ```text
//! P(e) = T₁(E1) · T₂(E2) · F₀ · B
//! ```
//!
//! where `Tᵢ(θ)` turns by `θ` right-handed about axis `i` through its point
//! (both given at E1 = E2 = 0), `F₀` is the flange at zero (origin on the
//! rotate axis at its point, Z along it, X along the tilt axis made square
//! to Z) and `B` the base on the flange. A program's poses are in that
//! moving base, as the controller's `$BASE` of a coupled kinematics takes
//! them; the arm reaches `P(e) · pose`.
//!
//! The angles are constant over a layer and chosen here, after lowering
//! ([`choose`]): a layer's mean normal `n` turned by `P(e)`'s rotation
//! points straight up where `T₁(E1)·T₂(E2)·m = +Z` with `m = F₀·B·n` —
//! Paden and Kahan's second subproblem: the vector `c = T₂(E2)·m` lies on
//! the cone about the rotate axis through `m` and on the cone about the
//! tilt axis through +Z; the two cones meet in (up to) two such vectors,
//! the positioner's two solutions ([`solutions`]). Of them, each with E2
//! by whole turns, the one inside both axes' limits nearest the layer
//! before is taken ([`Kin::solve`]), so E2 never unwinds further than the
//! normals ask and stays inside its travel where it can.

use crate::ir::{Keep, Machine, Pose, Positioner, Program};
use crate::plan::arm::frame;
use nalgebra::{Isometry3, Point3, Rotation3, Translation3, Unit, UnitQuaternion, Vector3};

/// An axis as a unit direction and a point of it, mm.
pub type AxisLine = ([f64; 3], [f64; 3]);

/// The positioner's kinematics with the part's base on its flange.
#[derive(Clone, Debug)]
pub struct Kin {
    tilt: (Unit<Vector3<f64>>, Vector3<f64>),
    rotate: (Unit<Vector3<f64>>, Vector3<f64>),
    /// The flange at zero, times the base on it.
    flange_base: Isometry3<f64>,
    limits: [[f64; 2]; 2],
}

/// `T(θ)`: a turn by `deg` about the axis along `dir` through `point`.
fn about(dir: &Unit<Vector3<f64>>, point: &Vector3<f64>, deg: f64) -> Isometry3<f64> {
    let r = UnitQuaternion::from_axis_angle(dir, deg.to_radians());
    Translation3::from(*point) * r * Translation3::from(-*point)
}

/// The flange's frame at E1 = E2 = 0 for `p`: origin at the rotate axis's
/// point, Z along it, X along the tilt axis made square to Z.
pub fn flange_zero(p: &Positioner) -> Isometry3<f64> {
    let z = Vector3::from(p.rotate.direction).normalize();
    let t = Vector3::from(p.tilt.direction);
    let x = (t - z * t.dot(&z)).normalize();
    let y = z.cross(&x);
    let r = Rotation3::from_basis_unchecked(&[x, y, z]);
    Isometry3::from_parts(
        Translation3::from(Vector3::from(p.rotate.point)),
        UnitQuaternion::from_rotation_matrix(&r),
    )
}

impl Kin {
    /// The kinematics of `p` with the part's base `base` on its flange.
    pub fn new(p: &Positioner, base: &Pose) -> Kin {
        let axis = |a: &crate::ir::PositionerAxis| {
            (
                Unit::new_normalize(Vector3::from(a.direction)),
                Vector3::from(a.point),
            )
        };
        Kin {
            tilt: axis(&p.tilt),
            rotate: axis(&p.rotate),
            flange_base: flange_zero(p) * frame(base),
            limits: [p.tilt.limits, p.rotate.limits],
        }
    }

    /// The kinematics of `robot`'s positioner, when it has one and a base
    /// with a value.
    pub fn of(robot: &crate::ir::Robot) -> Option<Kin> {
        Some(Kin::new(
            robot.positioner.as_ref()?,
            robot.base.value.as_ref()?,
        ))
    }

    /// Forward kinematics: the part's base in the robot's frame with the
    /// positioner at `e` (E1, E2; deg).
    pub fn part(&self, e: [f64; 2]) -> Isometry3<f64> {
        about(&self.tilt.0, &self.tilt.1, e[0])
            * about(&self.rotate.0, &self.rotate.1, e[1])
            * self.flange_base
    }

    /// The two turns (E1's axis, then E2's: unit direction and a point)
    /// and the flange at zero times the base, whose product is
    /// [`Kin::part`].
    pub fn parts(&self) -> ([AxisLine; 2], Isometry3<f64>) {
        let turn = |(d, p): &(Unit<Vector3<f64>>, Vector3<f64>)| ([d.x, d.y, d.z], [p.x, p.y, p.z]);
        ([turn(&self.tilt), turn(&self.rotate)], self.flange_base)
    }

    /// The part's base in the frame of the tilting arm (E1's body, as it
    /// stands in the robot's frame at E1 = 0) with the positioner at `e`:
    /// what turns with E1 and not with E2 sees the part there.
    pub fn part_on_tilt(&self, e: [f64; 2]) -> Isometry3<f64> {
        about(&self.rotate.0, &self.rotate.1, e[1]) * self.flange_base
    }

    /// A point `to` of the part (in its base) in the robot's frame at `e`.
    pub fn point(&self, e: [f64; 2], to: [f64; 3]) -> [f64; 3] {
        let p = self.part(e) * Point3::from(to);
        [p.x, p.y, p.z]
    }

    /// Inverse kinematics: the angles that turn the part's direction `n`
    /// (in its base) straight up, nearest `prev` among the solutions inside
    /// both axes' limits (nearest `prev` outside them where none is inside;
    /// the verifier reports the limit). Where `n` cannot be turned up (the
    /// axes' cones do not meet), the solution that turns it nearest up.
    pub fn solve(&self, n: [f64; 3], prev: [f64; 2]) -> [f64; 2] {
        let m = self.flange_base.rotation * Vector3::from(n);
        let mut best: Option<(bool, f64, [f64; 2])> = None;
        for e in solutions(&self.tilt.0, &self.rotate.0, &m, prev) {
            let e = self.wound_into_limits(e, prev);
            let inside = (0..2).all(|i| e[i] >= self.limits[i][0] && e[i] <= self.limits[i][1]);
            let cost = (e[0] - prev[0]).abs() + (e[1] - prev[1]).abs();
            let better = match best {
                None => true,
                Some((bi, bc, _)) => (inside && !bi) || (inside == bi && cost < bc - 1e-9),
            };
            if better {
                best = Some((inside, cost, e));
            }
        }
        best.map_or(prev, |b| b.2)
    }

    /// `e` with E1 in the turn nearest `prev`'s and E2 moved by whole turns
    /// into its limits where it can go (else left nearest `prev`).
    fn wound_into_limits(&self, e: [f64; 2], prev: [f64; 2]) -> [f64; 2] {
        let mut out = [near(e[0], prev[0]), near(e[1], prev[1])];
        for (i, v) in out.iter_mut().enumerate() {
            let [lo, hi] = self.limits[i];
            if *v < lo {
                let up = *v + 360.0 * ((lo - *v) / 360.0).ceil();
                if up <= hi {
                    *v = up;
                }
            } else if *v > hi {
                let down = *v - 360.0 * ((*v - hi) / 360.0).ceil();
                if down >= lo {
                    *v = down;
                }
            }
        }
        out
    }
}

/// `a + k·360°` nearest `reference`.
fn near(a: f64, reference: f64) -> f64 {
    a + 360.0 * ((reference - a) / 360.0).round()
}

/// The angle, deg, that turns `a` onto `b` about the unit `w` (both
/// projected square to it); `None` where either lies along `w`.
fn turn_about(w: &Vector3<f64>, a: &Vector3<f64>, b: &Vector3<f64>) -> Option<f64> {
    let pa = a - w * w.dot(a);
    let pb = b - w * w.dot(b);
    if pa.norm() < 1e-9 || pb.norm() < 1e-9 {
        return None;
    }
    Some(w.dot(&pa.cross(&pb)).atan2(pa.dot(&pb)).to_degrees())
}

/// The angles `(E1, E2)` with `T₁(E1)·T₂(E2)·m = +Z` (directions: the
/// axes' rotations alone), `w1` the tilt axis, `w2` the rotate axis at
/// zero: two solutions, one where they coincide, and where the cones do
/// not meet the one that brings `m` nearest up. An angle left free (`m`
/// along `w2`, or +Z along `w1`) keeps `prev`'s.
pub fn solutions(
    w1: &Unit<Vector3<f64>>,
    w2: &Unit<Vector3<f64>>,
    m: &Vector3<f64>,
    prev: [f64; 2],
) -> Vec<[f64; 2]> {
    let m = m.normalize();
    let up = Vector3::z();
    let (w1, w2) = (w1.into_inner(), w2.into_inner());
    let k = w1.dot(&w2);
    let cross = w1.cross(&w2);
    let det = k * k - 1.0;
    if det.abs() < 1e-12 {
        return vec![prev];
    }
    let alpha = (k * w2.dot(&m) - w1.dot(&up)) / det;
    let beta = (k * w1.dot(&up) - w2.dot(&m)) / det;
    let g2 = (1.0 - alpha * alpha - beta * beta - 2.0 * alpha * beta * k) / cross.norm_squared();
    let gamma = g2.max(0.0).sqrt();
    let mut out = Vec::with_capacity(2);
    for g in [gamma, -gamma] {
        let c = w1 * alpha + w2 * beta + cross * g;
        // T₂(E2)·m = c, then T₁(E1)·c = up.
        let e2 = turn_about(&w2, &m, &c).unwrap_or(prev[1]);
        let e1 = turn_about(&w1, &c, &up).unwrap_or(prev[0]);
        out.push([e1, e2]);
        if gamma < 1e-12 {
            break;
        }
    }
    out
}

/// A layer's mean normal: its laser-on points' normals summed (every
/// point's where none deposits, the layer's build direction where it has
/// none).
fn mean_normal(layer: &crate::ir::Layer) -> [f64; 3] {
    let mut sum = [0.0f64; 3];
    let mut any = false;
    for deposits in [true, false] {
        for p in layer.paths.iter().flat_map(|p| &p.points) {
            if p.laser_on == deposits || !deposits {
                for (s, c) in sum.iter_mut().zip(p.normal) {
                    *s += c as f64;
                }
                any = true;
            }
        }
        if any {
            break;
        }
    }
    let len = (sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]).sqrt();
    if len > 1e-9 {
        sum.map(|c| c / len)
    } else {
        layer.frame.z
    }
}

/// How far `n` (the part's, in its base) leans from straight up with the
/// positioner at `e`, deg.
pub fn lean(kin: &Kin, e: [f64; 2], n: [f64; 3]) -> f64 {
    let v = kin.part(e).rotation * Vector3::from(n);
    (v.x * v.x + v.y * v.y).sqrt().atan2(v.z).to_degrees()
}

/// The angles of every layer of `program` for `p` (with the part's base
/// `base` on its flange), from the positioner's zero.
pub fn angles(program: &Program, p: &Positioner, base: &Pose) -> Vec<[f64; 2]> {
    let kin = Kin::new(p, base);
    let mut prev = [0.0, 0.0];
    program
        .layers
        .iter()
        .map(|layer| {
            let e = match p.keep {
                Keep::Fixed { e1, e2 } => [e1, e2],
                Keep::Vertical => kin.solve(mean_normal(layer), prev),
                Keep::Cone { deg } => {
                    let n = mean_normal(layer);
                    if lean(&kin, prev, n) <= deg {
                        prev
                    } else {
                        kin.solve(n, prev)
                    }
                }
            };
            prev = e;
            e
        })
        .collect()
}

/// Chooses each layer's angles for every robot of `program` with a
/// positioner (and a base on it): the one step besides
/// [`super::spin::choose`] that writes into the IR after lowering, before
/// it (the arm sees the poses through the positioner).
pub fn choose(program: &mut Program) {
    for i in 0..program.machines.len() {
        let Machine::Robot(r) = &program.machines[i] else {
            continue;
        };
        let (Some(p), Some(base)) = (&r.positioner, r.base.value) else {
            continue;
        };
        if !p.angles.is_empty() {
            continue;
        }
        let a = angles(program, p, &base);
        if let Machine::Robot(r) = &mut program.machines[i] {
            if let Some(p) = r.positioner.as_mut() {
                p.angles = a;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::PositionerAxis;
    use proptest::prelude::*;

    fn positioner(tilt: [f64; 3], rotate: [f64; 3]) -> Positioner {
        Positioner {
            tilt: PositionerAxis {
                direction: tilt,
                point: [1500.0, 0.0, 600.0],
                limits: [-135.0, 135.0],
                speed: 60.0,
            },
            rotate: PositionerAxis {
                direction: rotate,
                point: [1500.0, 30.0, 750.0],
                limits: [-720.0, 720.0],
                speed: 90.0,
            },
            keep: Keep::Vertical,
            home: [0.0; 2],
            angles: Vec::new(),
            faceplate: None,
        }
    }

    fn base() -> Pose {
        Pose {
            x: 10.0,
            y: -20.0,
            z: 35.0,
            a: 20.0,
            b: -5.0,
            c: 3.0,
        }
    }

    proptest! {
        /// Inverse after forward: for any angles, the normal they turn up
        /// is solved to angles that turn it up too — the same ones or the
        /// other solution — for a square positioner and a skewed one.
        #[test]
        fn inverse_of_forward_turns_the_normal_up(
            e1 in -120.0f64..120.0,
            e2 in -350.0f64..350.0,
            skew in any::<bool>(),
        ) {
            let rotate = if skew { [0.1, -0.2, 1.0] } else { [0.0, 0.0, 1.0] };
            let p = positioner([1.0, 0.3, 0.0], rotate);
            let kin = Kin::new(&p, &base());
            // The part's direction that e turns straight up.
            let n = kin.part([e1, e2]).rotation.inverse() * Vector3::z();
            let got = kin.solve([n.x, n.y, n.z], [e1 + 3.0, e2 - 3.0]);
            prop_assert!(lean(&kin, got, [n.x, n.y, n.z]) < 1e-6, "{got:?}");
            // Nearest the angles it started from: the same solution, or
            // one at least as near (where the normal lies near the rotate
            // axis, E2 barely moves it and solutions crowd together).
            let from = [e1 + 3.0, e2 - 3.0];
            let cost = |e: [f64; 2]| (e[0] - from[0]).abs() + (e[1] - from[1]).abs();
            prop_assert!(cost(got) <= cost([e1, e2]) + 1e-6,
                "{got:?} vs {:?}", [e1, e2]);
        }

        /// Forward kinematics is rigid and puts the base where the axes
        /// turn it: a point on the tilt axis stays put through any E1 at
        /// E2 = 0.
        #[test]
        fn the_tilt_axis_stays_put(e1 in -180.0f64..180.0) {
            let p = positioner([1.0, 0.0, 0.0], [0.0, 0.0, 1.0]);
            let kin = Kin::new(&p, &base());
            let on = [2000.0, 0.0, 600.0];
            let part = kin.part([0.0, 0.0]).inverse() * Point3::from(on);
            let back = kin.point([e1, 0.0], [part.x, part.y, part.z]);
            for i in 0..3 {
                prop_assert!((back[i] - on[i]).abs() < 1e-9, "{back:?}");
            }
        }
    }

    /// The two solutions of a square positioner: E1 = ±tilt, E2 half a
    /// turn apart.
    #[test]
    fn two_solutions_half_a_turn_apart() {
        let w1 = Unit::new_normalize(Vector3::x());
        let w2 = Unit::new_normalize(Vector3::z());
        let m = Vector3::new(0.0, 0.5f64.sin(), 0.5f64.cos());
        let s = solutions(&w1, &w2, &m, [0.0, 0.0]);
        assert_eq!(s.len(), 2);
        let d2 = (s[0][1] - s[1][1]).abs();
        assert!((d2 - 180.0).abs() < 1e-9, "{s:?}");
        assert!((s[0][0] + s[1][0]).abs() < 1e-9, "{s:?}");
        assert!((s[0][0].abs() - 0.5f64.to_degrees()).abs() < 1e-9, "{s:?}");
    }

    /// E2 goes by whole turns into its limits.
    #[test]
    fn e2_is_brought_into_its_limits() {
        let mut p = positioner([1.0, 0.0, 0.0], [0.0, 0.0, 1.0]);
        p.rotate.limits = [-90.0, 270.0];
        let kin = Kin::new(&p, &Pose::default());
        let e = kin.wound_into_limits([10.0, -100.0], [0.0, 0.0]);
        assert!((e[1] - 260.0).abs() < 1e-9, "{e:?}");
    }
}
