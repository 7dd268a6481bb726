//! A robot's arm (docs/robots.md): the catalogue against the cited
//! ROS-Industrial URDFs, forward ∘ inverse kinematics on random reachable
//! poses, the KRL's first pose solved back onto the axes lmdc reports, the
//! G-code's first move the safe lift (rs274), and every error example of
//! the arm exiting 1 with its numbers.

use crate::support::rs274::{self, CanonCall};
use lmdc::back::{MemorySink, Templates};
use lmdc::ir::{Arm, Machine};
use lmdc::plan::arm::Solver;
use lmdc::target::arm::{Model, CATALOGUE};
use nalgebra::{Isometry3, Rotation3, Translation3, UnitQuaternion, Vector3};
use proptest::prelude::*;
use std::collections::BTreeMap;

fn arm_of(m: &Model) -> Arm {
    m.arm(0.0, 5.0)
}

/// A joint of a URDF: origin `xyz` (m) from its parent, turning about `axis`.
struct Joint {
    xyz: [f64; 3],
    axis: [f64; 3],
    limit: [f64; 2],
    speed: f64,
}

const fn j(xyz: [f64; 3], axis: [f64; 3], limit: [f64; 2], speed: f64) -> Joint {
    Joint {
        xyz,
        axis,
        limit,
        speed,
    }
}

const Z_DOWN: [f64; 3] = [0.0, 0.0, -1.0];
const Y: [f64; 3] = [0.0, 1.0, 0.0];
const X_BACK: [f64; 3] = [-1.0, 0.0, 0.0];
const Z: [f64; 3] = [0.0, 0.0, 1.0];
const X: [f64; 3] = [1.0, 0.0, 0.0];

/// Each catalogue arm's URDF, as ros-industrial/kuka_experimental writes it
/// (`<joint_a1…a6>`: origin, axis, `<limit lower upper velocity>` in deg and
/// deg/s; then `tool0` at `xyz`, turned `rpy = 0 90° 0` from `link_6`), or
/// ros-industrial/abb_experimental (`<joint_1…6>`, likewise; `tool0` turned
/// `rpy = 0 90° 0` from `flange`, which is `link_6`).
fn urdf(key: &str) -> ([Joint; 6], [f64; 3]) {
    match key {
        // kuka_kr6_support/urdf/kr6r900_2_macro.xacro
        "kr6_r900_2" => (
            [
                j([0.0, 0.0, 0.400], Z_DOWN, [-170.0, 170.0], 360.0),
                j([0.025, 0.0, 0.0], Y, [-190.0, 45.0], 300.0),
                j([0.455, 0.0, 0.0], Y, [-120.0, 156.0], 360.0),
                j([0.0, 0.0, 0.025], X_BACK, [-185.0, 185.0], 450.0),
                j([0.420, 0.0, 0.0], Y, [-120.0, 120.0], 450.0),
                j([0.090, 0.0, 0.0], X_BACK, [-350.0, 350.0], 540.0),
            ],
            [0.0; 3],
        ),
        // kuka_kr16_support/urdf/kr16_2_macro.xacro
        "kr16_2" => (
            [
                j([0.0, 0.0, 0.675], Z_DOWN, [-185.0, 185.0], 156.0),
                j([0.26, 0.0, 0.0], Y, [-155.0, 35.0], 156.0),
                j([0.68, 0.0, 0.0], Y, [-130.0, 154.0], 156.0),
                j([0.67, 0.0, -0.035], X_BACK, [-350.0, 350.0], 330.0),
                j([0.0, 0.0, 0.0], Y, [-130.0, 130.0], 330.0),
                j([0.0, 0.0, 0.0], X_BACK, [-350.0, 350.0], 615.0),
            ],
            [0.158, 0.0, 0.0],
        ),
        // kuka_kr60_support/urdf/kr60ha_macro.xacro
        "kr60ha" => (
            [
                j([0.0, 0.0, 0.0], Z_DOWN, [-185.0, 185.0], 128.0),
                j([0.35, 0.0, 0.815], Y, [-135.0, 35.0], 102.0),
                j([0.85, 0.0, 0.0], Y, [-120.0, 158.0], 128.0),
                j([0.465, 0.0, 0.145], X_BACK, [-350.0, 350.0], 260.0),
                j([0.355, 0.0, 0.0], Y, [-119.0, 119.0], 245.0),
                j([0.17, 0.0, 0.0], X_BACK, [-350.0, 350.0], 322.0),
            ],
            [0.0; 3],
        ),
        // kuka_kr150_support/urdf/kr150_r3100-2_macro.xacro
        "kr150_r3100_2" => (
            [
                j([0.0, 0.0, 0.645], Z_DOWN, [-185.0, 185.0], 105.0),
                j([0.33, 0.0, 0.0], Y, [-140.0, -5.0], 107.0),
                j([1.350, 0.0, 0.0], Y, [-120.0, 168.0], 114.0),
                j([1.420, 0.0, 0.115], X_BACK, [-350.0, 350.0], 190.0),
                j([0.0, 0.0, 0.0], Y, [-125.0, 125.0], 180.0),
                j([0.215, 0.0, 0.0], X_BACK, [-350.0, 350.0], 260.0),
            ],
            [0.0; 3],
        ),
        _ => abb_urdf(key),
    }
}

/// The ABB arms' URDFs (ros-industrial/abb_experimental, commit 20b9cf8),
/// limits and speeds in deg and deg/s as written (`${radians(…)}`) or, where
/// written in rad to three decimals, the degrees they round
/// ([`URDF_RAD_DEG`]).
fn abb_urdf(key: &str) -> ([Joint; 6], [f64; 3]) {
    match key {
        // abb_irb2600_support/urdf/irb2600_12_165_macro.xacro (rad: ±3.14159,
        // −2.705…1.658, −2.705…1.309, ±6.981, ±2.094, ±6.981; 3.054, 6.283, 8.727)
        "irb2600_12_165" => (
            [
                j([0.0, 0.0, 0.445], Z, [-180.0, 180.0], 175.0),
                j([0.15, 0.0, 0.0], Y, [-155.0, 95.0], 175.0),
                j([0.0, 0.0, 0.7], Y, [-155.0, 75.0], 175.0),
                j([0.0, 0.0, 0.115], X, [-400.0, 400.0], 360.0),
                j([0.795, 0.0, 0.0], Y, [-120.0, 120.0], 360.0),
                j([0.085, 0.0, 0.0], X, [-400.0, 400.0], 500.0),
            ],
            [0.0; 3],
        ),
        // abb_irb4600_support/urdf/irb4600_60_205_macro.xacro (rad: ±3.141,
        // −1.570…2.617, −3.141…1.308, ±6.981, −2.181…2.094, ±6.981;
        // 3.054, 4.363, 6.283)
        "irb4600_60_205" => (
            [
                j([0.0, 0.0, 0.495], Z, [-180.0, 180.0], 175.0),
                j([0.175, 0.0, 0.0], Y, [-90.0, 150.0], 175.0),
                j([0.0, 0.0, 0.9], Y, [-180.0, 75.0], 175.0),
                j([0.0, 0.0, 0.175], X, [-400.0, 400.0], 250.0),
                j([0.960, 0.0, 0.0], Y, [-125.0, 120.0], 250.0),
                j([0.135, 0.0, 0.0], X, [-400.0, 400.0], 360.0),
            ],
            [0.0; 3],
        ),
        // abb_irb4600_support/urdf/irb4600_40_255_macro.xacro
        "irb4600_40_255" => (
            [
                j([0.0, 0.0, 0.495], Z, [-180.0, 180.0], 175.0),
                j([0.175, 0.0, 0.0], Y, [-90.0, 150.0], 175.0),
                j([0.0, 0.0, 1.095], Y, [-180.0, 75.0], 175.0),
                j([0.0, 0.0, 0.175], X, [-400.0, 400.0], 250.0),
                j([1.270, 0.0, 0.0], Y, [-125.0, 120.0], 250.0),
                j([0.135, 0.0, 0.0], X, [-400.0, 400.0], 360.0),
            ],
            [0.0; 3],
        ),
        // abb_irb6700_support/urdf/irb6700_200_260_macro.xacro (speeds as
        // ABB's product specification, abb_experimental#124)
        "irb6700_200_260" => (
            [
                j([0.0, 0.0, 0.78], Z, [-170.0, 170.0], 110.0),
                j([0.32, 0.0, 0.0], Y, [-65.0, 85.0], 110.0),
                j([0.0, 0.0, 1.125], Y, [-180.0, 70.0], 110.0),
                j([0.0, 0.0, 0.2], X, [-300.0, 300.0], 190.0),
                j([1.1425, 0.0, 0.0], Y, [-130.0, 130.0], 150.0),
                j([0.2, 0.0, 0.0], X, [-360.0, 360.0], 210.0),
            ],
            [0.0; 3],
        ),
        _ => panic!("no URDF for {key}"),
    }
}

/// The URDFs written in rad to three decimals (IRB 2600, IRB 4600-60/2.05)
/// give each limit and speed within this of the whole degrees the
/// catalogue takes (the most: 4600-60/2.05's A2 2.617 rad, 149.943°), deg.
const URDF_RAD_DEG: f64 = 0.06;

/// The flange (`tool0`) by the URDF's chain at axis angles `q` (deg), mm.
fn urdf_flange(key: &str, q: &[f64; 6]) -> Isometry3<f64> {
    let (joints, tool0) = urdf(key);
    let mut t = Isometry3::identity();
    for (jt, a) in joints.iter().zip(q) {
        let axis = nalgebra::Unit::new_normalize(Vector3::from(jt.axis));
        let origin = Translation3::from(Vector3::from(jt.xyz) * 1000.0);
        t *= Isometry3::from_parts(
            origin,
            UnitQuaternion::from_axis_angle(&axis, a.to_radians()),
        );
    }
    let tool = Isometry3::from_parts(
        Translation3::from(Vector3::from(tool0) * 1000.0),
        UnitQuaternion::from_euler_angles(0.0, 90f64.to_radians(), 0.0),
    );
    t * tool
}

fn angles() -> impl Strategy<Value = [f64; 6]> {
    prop::array::uniform6(-1.0f64..1.0)
}

/// A point of the catalogue arm's range: `u` in [-1, 1] spread over each
/// axis's limits.
fn within(m: &Model, u: &[f64; 6]) -> [f64; 6] {
    std::array::from_fn(|i| {
        let [lo, hi] = m.limits[i];
        (lo + hi) / 2.0 + u[i] * (hi - lo) / 2.0
    })
}

#[test]
fn catalogue_limits_and_speeds_are_the_urdfs() {
    for m in CATALOGUE {
        let (joints, _) = urdf(m.key);
        for (i, jt) in joints.iter().enumerate() {
            assert_eq!(m.limits[i], jt.limit, "{} A{}", m.key, i + 1);
            assert_eq!(m.speeds[i], jt.speed, "{} A{}", m.key, i + 1);
        }
    }
}

/// The URDFs written in rad: each number within [`URDF_RAD_DEG`] of the
/// degrees the catalogue and the table above take.
#[test]
// The URDFs' own numbers (3.14159, 6.283 …), not approximations of π to fix.
#[allow(clippy::approx_constant)]
fn urdf_radians_round_to_the_catalogues_degrees() {
    for (key, rad) in [
        (
            "irb2600_12_165",
            [
                [-3.14159, 3.14159, 3.054],
                [-2.705, 1.658, 3.054],
                [-2.705, 1.309, 3.054],
                [-6.981, 6.981, 6.283],
                [-2.094, 2.094, 6.283],
                [-6.981, 6.981, 8.727],
            ],
        ),
        (
            "irb4600_60_205",
            [
                [-3.141, 3.141, 3.054],
                [-1.570, 2.617, 3.054],
                [-3.141, 1.308, 3.054],
                [-6.981, 6.981, 4.363],
                [-2.181, 2.094, 4.363],
                [-6.981, 6.981, 6.283],
            ],
        ),
    ] {
        let m = lmdc::target::arm::model(key).unwrap();
        for (i, [lo, hi, v]) in rad.iter().enumerate() {
            let near = |deg: f64, r: f64| (deg - r.to_degrees()).abs() < URDF_RAD_DEG;
            assert!(
                near(m.limits[i][0], *lo) && near(m.limits[i][1], *hi),
                "{key} A{}",
                i + 1
            );
            assert!(near(m.speeds[i], *v), "{key} A{}", i + 1);
        }
    }
}

/// The arms rs-opw-kinematics ships from the same ROS-Industrial files (its
/// ABB sets in ABB's convention, as `irb2400_10` has it).
#[test]
fn catalogue_opw_sets_are_the_crates() {
    use rs_opw_kinematics::parameters::opw_kinematics::Parameters;
    for (key, p) in [
        ("kr6_r900_2", Parameters::kuka_kr6_r900_2()),
        ("kr150_r3100_2", Parameters::kuka_kr150_r3100_2()),
        ("irb2600_12_165", Parameters::irb2600_12_165()),
        ("irb4600_60_205", Parameters::irb4600_60_205()),
        ("irb4600_40_255", Parameters::irb4600_40_255()),
    ] {
        let a = arm_of(lmdc::target::arm::model(key).unwrap());
        let theirs = [p.a1, p.a2, p.b, p.c1, p.c2, p.c3, p.c4].map(|x| x * 1000.0);
        for (o, t) in a.opw.iter().zip(theirs) {
            assert!((o - t).abs() < 1e-9, "{key}: {:?} vs {theirs:?}", a.opw);
        }
        assert_eq!(a.signs, p.sign_corrections, "{key}");
        for (o, t) in a.offsets.iter().zip(p.offsets) {
            assert!((o.to_radians() - t).abs() < 1e-12, "{key}");
        }
    }
}

/// The IRB 4600-60/2.05 at its calibration position (every axis 0) puts
/// the axes where a calibration study outside ROS-Industrial does
/// (Ssz990220/Kinematic_Param_Calibration, `init_kine_param.m`: the axes'
/// points 175/495, 175/1395, 175/1570, 1135/1570, 1270/1570 mm, x/z): the
/// wrist centre 1135 mm ahead and 1570 mm up, the flange 1270 mm ahead,
/// facing forward.
#[test]
fn irb4600_at_zero_is_where_a_second_source_has_it() {
    let m = lmdc::target::arm::model("irb4600_60_205").unwrap();
    let s = Solver::with(arm_of(m), Isometry3::identity(), Isometry3::identity());
    let p = s.joint_points(&[0.0; 6]);
    for (got, want) in [
        (p[1], [175.0, 495.0]),
        (p[2], [175.0, 1395.0]),
        (p[3], [175.0, 1570.0]),
        (p[4], [1135.0, 1570.0]),
        (p[5], [1270.0, 1570.0]),
    ] {
        assert!(
            (got[0] - want[0]).abs() < 1e-6
                && got[1].abs() < 1e-6
                && (got[2] - want[1]).abs() < 1e-6,
            "{got:?} vs {want:?}"
        );
    }
    let z = s.forward_flange(&[0.0; 6]).rotation * Vector3::z();
    assert!((z - Vector3::x()).norm() < 1e-9, "{z:?}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Each arm's OPW parameters put the flange where the URDF's chain of
    /// joint origins and axes does, at any axis angles.
    #[test]
    fn catalogue_opw_is_the_urdfs_chain(u in angles()) {
        for m in CATALOGUE {
            let q = within(m, &u);
            let s = Solver::with(arm_of(m), Isometry3::identity(), Isometry3::identity());
            let ours = s.forward_flange(&q);
            let theirs = urdf_flange(m.key, &q);
            let d = (ours.translation.vector - theirs.translation.vector).norm();
            prop_assert!(d < 1e-6, "{} at {q:?}: {d} mm", m.key);
            prop_assert!(ours.rotation.angle_to(&theirs.rotation) < 1e-9, "{} at {q:?}", m.key);
        }
    }

    /// forward ∘ inverse = identity: a pose the arm reaches (the flange at
    /// random axis angles, with a base and tool) is solved back to axis
    /// angles whose pose is the same, the angles themselves when the last
    /// ones are given and the wrist is not singular.
    #[test]
    fn forward_inverse_is_identity(u in angles(), t in prop::array::uniform3(-200.0f64..200.0)) {
        for m in CATALOGUE {
            let q = within(m, &u);
            let base = Isometry3::from_parts(Translation3::new(t[0], t[1], 0.0), UnitQuaternion::from_euler_angles(0.0, 0.0, 0.3));
            let tool = Isometry3::from_parts(Translation3::new(0.0, t[2] / 4.0, 300.0), UnitQuaternion::from_euler_angles(0.0, 0.2, 0.0));
            let s = Solver::with(arm_of(m), base, tool);
            let (to, rot) = s.forward(&q);
            let sols = s.solve(to, &rot, &q);
            prop_assert!(!sols.is_empty(), "{} at {q:?}: no solution", m.key);
            for j in &sols {
                let (p, r) = s.forward(j);
                let d = (0..3).map(|i| (p[i] - to[i]).powi(2)).sum::<f64>().sqrt();
                prop_assert!(d < 1e-6, "{}: {d} mm", m.key);
                let q = |m| UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(m));
                let dr = q(r).angle_to(&q(rot));
                prop_assert!(dr < 1e-6, "{}: {dr} rad", m.key);
            }
            if q[4].abs() > 1.0 {
                let first = sols[0];
                let wrap = |a: f64| (a + 180.0).rem_euclid(360.0) - 180.0;
                for i in 0..6 {
                    prop_assert!(wrap(first[i] - q[i]).abs() < 1e-6, "{} A{}: {first:?} vs {q:?}", m.key, i + 1);
                }
            }
        }
    }
}

fn build(path: &str) -> lmdc::verify::Verified {
    let src = std::fs::read_to_string(path).unwrap();
    lmdc::pipeline::compile(&src, &mut ())
        .program
        .unwrap_or_else(|| panic!("{path} compiles"))
}

fn files(p: &lmdc::verify::Verified, index: usize) -> BTreeMap<String, String> {
    let mut sink = MemorySink::default();
    let m = p.machine(index).expect("a verified machine");
    lmdc::back::emit(m, &Templates::builtin().unwrap(), &mut sink).unwrap();
    sink.files
        .into_iter()
        .map(|(n, b)| (n, String::from_utf8(b).unwrap()))
        .collect()
}

/// `key <number>` in a KRL aggregate.
fn field(agg: &str, key: &str) -> f64 {
    agg.split(['{', ',', '}'])
        .find_map(|p| p.trim().strip_prefix(key)?.strip_prefix(' '))
        .and_then(|v| v.trim().parse().ok())
        .unwrap_or_else(|| panic!("no {key} in {agg}"))
}

/// Each example built on a declared arm: the KRL's first motion is a PTP
/// with Status and Turn, and the axis solution of its pose (through the
/// IR's arm, base and tool) with that Status and Turn is the one lmdc
/// writes beside it.
#[test]
fn krl_first_pose_solves_back_to_the_reported_axes() {
    let mut checked = 0;
    for path in [
        "examples/sprocket_tooth.lmd",
        "examples/wedge.lmd",
        "examples/flange.lmd",
    ] {
        let p = build(path);
        for (i, m) in p.ir().machines.iter().enumerate() {
            let Machine::Robot(r) = m else { continue };
            assert!(r.arm.is_some(), "{path}: the example declares its arm");
            let f = files(&p, i);
            let module = f
                .iter()
                .find(|(n, _)| n.ends_with("_m001.src"))
                .map(|(_, t)| t)
                .unwrap();
            let first = module
                .lines()
                .find(|l| l.starts_with("LIN ") || l.starts_with("PTP "))
                .unwrap();
            assert!(first.starts_with("PTP {X "), "{path}: {first}");
            let (agg, comment) = first.split_once(" ; from home, axes ").unwrap();
            let pos = [field(agg, "X"), field(agg, "Y"), field(agg, "Z")];
            let abc = [field(agg, "A"), field(agg, "B"), field(agg, "C")];
            let (st, tu) = (field(agg, "S") as u8, field(agg, "T") as u8);
            let reported: Vec<f64> = comment
                .split_whitespace()
                .skip(1)
                .step_by(2)
                .map(|v| v.parse().unwrap())
                .collect();
            let s = Solver::new(r).unwrap();
            let rot = *Rotation3::from_euler_angles(
                abc[2].to_radians(),
                abc[1].to_radians(),
                abc[0].to_radians(),
            )
            .matrix();
            let sols = s.solve(pos, &rot, &r.home);
            let matching: Vec<_> = sols
                .iter()
                .filter(|j| s.status(j) == st && Solver::turn(j) == tu)
                .collect();
            assert!(
                !matching.is_empty(),
                "{path}: no solution with S {st} T {tu}"
            );
            let near = matching
                .iter()
                .any(|j| j.iter().zip(&reported).all(|(a, b)| (a - b).abs() < 0.01));
            assert!(near, "{path}: {matching:?} vs reported {reported:?}");
            checked += 1;
        }
    }
    assert!(checked >= 3);
}

/// The part's highest point: the highest focus of the IR, mm.
fn highest_focus(p: &lmdc::verify::Verified) -> f64 {
    p.ir()
        .layers
        .iter()
        .flat_map(|l| &l.paths)
        .flat_map(|p| &p.points)
        .map(|pt| pt.focus()[2])
        .fold(f64::NEG_INFINITY, f64::max)
}

/// The G-code's first move is the safe lift: rs274's first traverse moves
/// Z alone (X and Y stay where the machine stands, 0 in rs274), to above
/// every point of the part; the program ends at that height.
#[test]
fn gcode_starts_and_ends_at_the_safe_height() {
    if rs274::find_rs274().is_none() {
        crate::support::skip::skip(
            "gcode_starts_and_ends_at_the_safe_height",
            "rs274",
            "bash .ci/install-rs274.sh",
        );
        return;
    }
    let p = build("examples/sprocket_tooth.lmd");
    let top = highest_focus(&p);
    for (i, m) in p.ir().machines.iter().enumerate() {
        let Machine::Cnc(c) = m else { continue };
        let text: String = files(&p, i).into_values().collect();
        let calls = rs274::interpret_source(&text).unwrap();
        let body = rs274::program_body(&calls);
        let moves: Vec<(f64, f64, f64)> = body
            .iter()
            .filter_map(|c| match *c {
                CanonCall::Traverse { x, y, z, .. } | CanonCall::Feed { x, y, z, .. } => {
                    Some((x, y, z))
                }
                _ => None,
            })
            .collect();
        let (x, y, z) = moves[0];
        assert!(matches!(
            body.iter()
                .find(|c| matches!(c, CanonCall::Traverse { .. } | CanonCall::Feed { .. })),
            Some(CanonCall::Traverse { .. })
        ));
        assert_eq!((x, y), (0.0, 0.0), "the first move lifts Z alone");
        assert!(
            (z - (top + c.clearance)).abs() < 1e-3,
            "lifts to {z}, want {}",
            top + c.clearance
        );
        let last = moves.last().unwrap();
        assert!(
            (last.2 - z).abs() < 1e-3,
            "ends at {}, not the safe height {z}",
            last.2
        );
    }
}

/// A declared `safe_height` must clear the part: below its highest point
/// plus the clearance it is refused, with those numbers and the height that
/// would do; at that height or above, the program lifts to exactly it.
#[test]
fn a_safe_height_below_the_part_is_refused_and_one_above_is_kept() {
    let p = build("examples/sprocket_tooth.lmd");
    let top = highest_focus(&p);
    let clearance = 5.0;
    let with = |safe: f64| {
        crate::support::example::edited(
            "sprocket_tooth.lmd",
            &[(
                "machine mill3 {\n  kind = cnc\n",
                &format!("machine mill3 {{\n  kind = cnc\n  safe_height = {safe} mm\n"),
            )],
        )
    };
    let low = top + clearance - 0.05;
    let c = lmdc::pipeline::compile(&with(low), &mut ());
    assert!(c.program.is_none());
    let d: Vec<_> = c
        .diagnostics
        .iter()
        .filter(|d| d.code == lmdc::diag::Code::SafeHeight)
        .collect();
    assert_eq!(d.len(), 1, "{:?}", c.diagnostics);
    let m = &d[0].message;
    assert!(
        m.contains(&format!("safe_height of {} mm", lmdc::units::short(low))),
        "{m}"
    );
    assert!(
        m.contains(&format!(
            "highest point is at Z {} mm",
            lmdc::units::short(top)
        )),
        "{m}"
    );
    let help = d[0].help.as_deref().unwrap();
    let advised: f64 = help
        .split("at least ")
        .nth(1)
        .and_then(|t| t.split(" mm").next())
        .and_then(|t| t.parse().ok())
        .unwrap_or_else(|| panic!("{help}"));
    assert!(
        advised >= top + clearance && advised < top + clearance + 0.1,
        "{help}"
    );
    // The advice, followed as printed, builds; and a higher one is where
    // the program starts and ends.
    for safe in [advised, top + 40.0] {
        let c = lmdc::pipeline::compile(&with(safe), &mut ());
        let p = c.program.unwrap_or_else(|| panic!("{:?}", c.diagnostics));
        let i = p
            .ir()
            .machines
            .iter()
            .position(|m| m.name() == "mill3")
            .unwrap();
        let text: String = files(&p, i).into_values().collect();
        let zs: Vec<f64> = text
            .lines()
            .filter(|l| l.starts_with("G0") || l.starts_with("G1"))
            .filter_map(|l| l.split_whitespace().find_map(|w| w.strip_prefix('Z')))
            .map(|z| z.parse().unwrap())
            .collect();
        let want = (safe * 1000.0).round() / 1000.0;
        assert_eq!(zs.first(), Some(&want), "starts at the safe height {safe}");
        assert_eq!(zs.last(), Some(&want), "ends at the safe height {safe}");
    }
}

/// ramp_wall on a KR 60 HA whose A6 turns only ±135° (an `opw(…)` arm),
/// with `spin` as given (`None`: not written, `auto`).
fn narrow_wrist(spin: Option<&str>) -> String {
    let arm =
        "arm = opw(a1 = 350 mm, a2 = -145 mm, c1 = 815 mm, c2 = 850 mm, c3 = 820 mm, c4 = 170 mm,
    limits = [-185 deg .. 185 deg, -135 deg .. 35 deg, -120 deg .. 158 deg,
              -350 deg .. 350 deg, -119 deg .. 119 deg, -135 deg .. 135 deg],
    speeds = [128 deg/s, 102 deg/s, 128 deg/s, 260 deg/s, 245 deg/s, 322 deg/s])";
    let spin = spin.map_or(String::new(), |s| format!("\n  spin = {s}"));
    crate::support::example::edited(
        "ramp_wall.lmd",
        &[("arm = kr60ha ", &format!("{arm}{spin} //"))],
    )
}

/// Every LIN and PTP pose of a robot's KRL modules: position and `A B C`.
fn krl_poses(files: &BTreeMap<String, String>) -> Vec<([f64; 3], [f64; 3])> {
    let mut poses = Vec::new();
    for (_, text) in files
        .iter()
        .filter(|(n, _)| n.contains("_m0") && n.ends_with(".src"))
    {
        for l in text
            .lines()
            .filter(|l| l.starts_with("LIN {X") || l.starts_with("PTP {X"))
        {
            let agg = &l[..l.find('}').unwrap() + 1];
            poses.push((
                [field(agg, "X"), field(agg, "Y"), field(agg, "Z")],
                [field(agg, "A"), field(agg, "B"), field(agg, "C")],
            ));
        }
    }
    poses
}

fn rotation(abc: [f64; 3]) -> nalgebra::Matrix3<f64> {
    *Rotation3::from_euler_angles(
        abc[2].to_radians(),
        abc[1].to_radians(),
        abc[0].to_radians(),
    )
    .matrix()
}

/// The tool turned about the beam (`spin`, docs/robots.md): where 0° takes
/// A6 past its limit, a pinned 0° is refused with the axis and its angle,
/// and `auto` turns the tool in steps of 15° until the arm follows the
/// plan. The written program, solved back through the IR's arm pose by pose
/// (an independent walk of the KRL text), keeps A6 inside its limits, and
/// the beam still points along −normal.
#[test]
fn spin_auto_turns_the_tool_where_zero_breaks_a_limit() {
    let pinned = lmdc::pipeline::compile(&narrow_wrist(Some("0 deg")), &mut ());
    assert!(pinned.program.is_none());
    let d = pinned
        .diagnostics
        .iter()
        .find(|d| d.code == lmdc::diag::Code::JointLimit)
        .expect("a joint-limit error at 0°");
    assert!(
        d.message.contains("A6") && d.message.contains("-180°"),
        "{}",
        d.message
    );

    for spin in [None, Some("auto")] {
        let src = narrow_wrist(spin);
        let p = lmdc::pipeline::compile(&src, &mut ())
            .program
            .unwrap_or_else(|| panic!("{spin:?} compiles"));
        let (i, r) = p
            .ir()
            .machines
            .iter()
            .enumerate()
            .find_map(|(i, m)| match m {
                Machine::Robot(r) => Some((i, r)),
                _ => None,
            })
            .unwrap();
        let lmdc::ir::Spin::Auto { deg } = r.spin else {
            panic!("{:?}", r.spin)
        };
        assert!(
            deg != 0.0 && deg % 15.0 == 0.0 && deg.abs() <= 180.0,
            "{deg}"
        );
        let s = Solver::new(r).unwrap();
        let poses = krl_poses(&files(&p, i));
        assert!(poses.len() > 1000, "{}", poses.len());
        let mut prev = r.home;
        for (pos, abc) in &poses {
            let rot = rotation(*abc);
            let j = s.solve(*pos, &rot, &prev)[0];
            assert!(j[5].abs() <= 133.0 + 1e-6, "A6 {} at {pos:?} {abc:?}", j[5]);
            // The beam (+Z of the tool) points down onto ramp_wall's flat layers.
            assert!((rot.column(2).z + 1.0).abs() < 1e-6, "{abc:?}");
            prev = j;
        }
    }
}

/// A declared `spin` is used as written: every pose of the program is the
/// unturned one turned by it about the beam, and the IR says it was
/// declared.
#[test]
fn a_declared_spin_turns_every_pose_by_it() {
    let plain = crate::support::example::edited("ramp_wall.lmd", &[]);
    let turned = crate::support::example::edited(
        "ramp_wall.lmd",
        &[("arm = kr60ha ", "spin = -40 deg\n  arm = kr60ha ")],
    );
    let build = |src: &str| lmdc::pipeline::compile(src, &mut ()).program.unwrap();
    let (a, b) = (build(&plain), build(&turned));
    let robot = |p: &lmdc::verify::Verified| {
        p.ir()
            .machines
            .iter()
            .position(|m| matches!(m, Machine::Robot(_)))
            .unwrap()
    };
    let Machine::Robot(r) = &b.ir().machines[robot(&b)] else {
        unreachable!()
    };
    assert_eq!(r.spin, lmdc::ir::Spin::Declared { deg: -40.0 });
    let (pa, pb) = (
        krl_poses(&files(&a, robot(&a))),
        krl_poses(&files(&b, robot(&b))),
    );
    assert_eq!(pa.len(), pb.len());
    for ((xa, ra), (xb, rb)) in pa.iter().zip(&pb) {
        assert_eq!(xa, xb);
        // R_b = R_a · Rz(−40°): the tool's own Z is the beam.
        let want =
            rotation(*ra) * Rotation3::from_axis_angle(&Vector3::z_axis(), (-40f64).to_radians());
        let diff = (want - rotation(*rb)).abs().max();
        assert!(diff < 1e-4, "{ra:?} → {rb:?}: {diff}");
    }
}

/// The nozzle 80° off the flange's axis (examples/errors/arm_joint_limit.lmd):
/// pinned at 0° A5 bends past its limit; with `auto` lmdc turns the tool
/// about the beam, which swings the wrist, until every axis fits — and the
/// program it writes, solved back, keeps A5 inside.
#[test]
fn an_angled_tool_is_turned_until_the_wrist_fits() {
    let pinned = std::fs::read_to_string("examples/errors/arm_joint_limit.lmd").unwrap();
    assert!(lmdc::pipeline::compile(&pinned, &mut ()).program.is_none());
    let auto = pinned.replacen("  spin = 0 deg\n", "", 1);
    assert_ne!(auto, pinned);
    let p = lmdc::pipeline::compile(&auto, &mut ())
        .program
        .expect("with spin = auto the duct builds");
    let Machine::Robot(r) = &p.ir().machines[0] else {
        panic!("a robot")
    };
    assert!(
        matches!(r.spin, lmdc::ir::Spin::Auto { deg } if deg != 0.0),
        "{:?}",
        r.spin
    );
    let s = Solver::new(r).unwrap();
    let [lo, hi] = r.arm.as_ref().unwrap().limits[4];
    let mut prev = r.home;
    for (pos, abc) in krl_poses(&files(&p, 0)) {
        let j = s.solve(pos, &rotation(abc), &prev)[0];
        assert!(
            j[4] >= lo + 2.0 - 1e-6 && j[4] <= hi - 2.0 + 1e-6,
            "A5 {}",
            j[4]
        );
        prev = j;
    }
}

/// `compile_then` runs its work beside the arm's checks (told they are
/// still running) and gives it back only when they pass; where the other
/// rules already fail it is not run at all.
#[test]
fn work_beside_the_arm_is_kept_only_when_the_arm_passes() {
    let pinned = std::fs::read_to_string("examples/errors/arm_joint_limit.lmd").unwrap();
    let auto = pinned.replace("spin = 0 deg", "spin = auto");
    // The same cell slower than its bead: an error of a rule that is not
    // the arm's (lmd::machine-speed).
    let slow = auto.replace("max_speed = 250 mm/s", "max_speed = 5 mm/s");
    assert_ne!(slow, auto);
    let run = |src: &str| {
        let mut told = None;
        let options = lmdc::pipeline::Options::default();
        let (c, made) = lmdc::pipeline::compile_then(src, &options, &mut (), |v, _| {
            told = Some(v.machines().count());
            "staged"
        })
        .unwrap();
        let codes: Vec<String> = c.diagnostics.iter().map(|d| d.code.to_string()).collect();
        (c.program.is_some(), made, told, codes)
    };
    let (ok, made, told, codes) = run(&auto);
    assert!(ok && made == Some("staged") && told == Some(1), "{codes:?}");
    let (ok, made, told, codes) = run(&pinned);
    assert!(!ok && made.is_none() && told == Some(1), "{codes:?}");
    assert!(codes.iter().any(|c| c == "lmd::joint-limit"), "{codes:?}");
    let (ok, made, told, codes) = run(&slow);
    assert!(!ok && made.is_none() && told.is_none(), "{codes:?}");
    assert_eq!(codes, ["lmd::machine-speed"]);
}

/// A LIN is followed between its ends (`plan::arm::Follow`): a 100 mm move
/// that also tilts the tool by 20° is solved at 5 mm steps, each pose on the
/// straight line and turned its share of the way, and each solution puts the
/// tool there (forward kinematics).
#[test]
fn a_long_lin_is_followed_between_its_ends() {
    use lmdc::plan::arm::{Follow, LIN_STEP_MM};
    use lmdc::plan::{Move, MoveKind, Speed, Where};
    let p = build("examples/ramp_wall.lmd");
    let robot = p
        .ir()
        .machines
        .iter()
        .find_map(|m| match m {
            Machine::Robot(r) if r.arm.is_some() => Some(r),
            _ => None,
        })
        .expect("the ramp wall's robot declares an arm");
    let first = p.ir().layers[0].paths[0].points[0].pos;
    let start: [f64; 3] = std::array::from_fn(|i| first[i] + if i == 2 { 20.0 } else { 0.0 });
    let end = [start[0] + 60.0, start[1] + 80.0, start[2]];
    let tilt = 20f64.to_radians();
    let mv = |to: [f64; 3], normal: [f32; 3], point: usize| Move {
        kind: MoveKind::Travel,
        to,
        normal,
        axes: Default::default(),
        speed: Speed::Feed(50.0),
        power: 0.0,
        at: Where::Point {
            layer: 0,
            path: 0,
            point,
        },
    };
    let mut follow = Follow::new(robot).unwrap();
    follow.push(&mv(start, [0.0, 0.0, 1.0], 0));
    follow.push(&mv(end, [tilt.sin() as f32, 0.0, tilt.cos() as f32], 1));
    let solved = follow.take();
    let n = (100.0 / LIN_STEP_MM) as usize;
    assert_eq!(solved.len(), 1 + n, "the start, then {n} poses to the end");
    let beam = |j: &[f64; 6]| {
        let (_, rot) = follow.solver().forward(j);
        Vector3::new(rot[(0, 2)], rot[(1, 2)], rot[(2, 2)])
    };
    let b0 = beam(&solved[0].joints.unwrap());
    for (k, s) in solved.iter().enumerate().skip(1) {
        let t = k as f64 / n as f64;
        assert!((s.way - t).abs() < 1e-12, "pose {k}: {}", s.way);
        let j = s.joints.expect("reachable");
        let (pos, _) = follow.solver().forward(&j);
        for i in 0..3 {
            let want = start[i] + t * (end[i] - start[i]);
            assert!((pos[i] - want).abs() < 1e-6, "pose {k} axis {i}: {pos:?}");
            assert!((s.m.to[i] - want).abs() < 1e-9);
        }
        let turned = b0.angle(&beam(&j)).to_degrees();
        assert!(
            (turned - 20.0 * t).abs() < 1e-6,
            "pose {k}: turned {turned}°"
        );
    }
    assert_eq!(
        solved[n].m.at,
        solved[n - 1].m.at,
        "poses on the way name the move"
    );
    let along = lmdc::plan::arm::Along {
        at: solved[5].m.at,
        way: solved[5].way,
    };
    assert_eq!(
        along.to_string(),
        "25 % of the way along the LIN to layer 1, path 1, point 2"
    );
}

/// The small duct held 60 mm off A1's axis, 1.1 m up, on a KR 60 HA whose
/// axes turn as far as the model allows (an `opw(…)` arm), with
/// `singularity` as given.
fn overhead_duct(singularity: f64) -> String {
    let arm =
        "arm = opw(a1 = 350 mm, a2 = -145 mm, c1 = 815 mm, c2 = 850 mm, c3 = 820 mm, c4 = 170 mm,
    limits = [-185 deg .. 185 deg, -185 deg .. 185 deg, -185 deg .. 185 deg,
              -350 deg .. 350 deg, -185 deg .. 185 deg, -350 deg .. 350 deg],
    speeds = [5000 deg/s, 5000 deg/s, 5000 deg/s, 5000 deg/s, 5000 deg/s, 5000 deg/s])";
    crate::support::example::edited(
        "errors/arm_singular_lin.lmd",
        &[
            (
                "arm = kr60ha",
                &format!("{arm}\n  singularity = {singularity} deg"),
            ),
            (
                "base = frame(1, x = 1650 mm, y = 12 mm, z = 1810 mm, b = -90 deg)",
                "base = frame(1, x = 60 mm, y = 0 mm, z = 1100 mm)",
            ),
        ],
    )
}

/// The overhead singularity (the wrist centre on A1's axis, where A1
/// spins) is a singular LIN of its own: the angle the wrist centre makes
/// with A1's axis, seen from the shoulder's height, computed here from
/// each pose the arm follows (its flange, less c4 along the flange's z),
/// is what `lmd::singular-lin` reports at its least, with the count of
/// poses below the threshold; below the least angle, the plan passes.
#[test]
fn the_overhead_singularity_is_a_singular_lin() {
    use lmdc::plan::arm::Follow;
    use lmdc::plan::{Move, Plan, Visit};
    let loose = lmdc::pipeline::compile(&overhead_duct(1.0), &mut ());
    let codes: Vec<_> = loose.diagnostics.iter().map(|d| d.code).collect();
    let p = loose.program.unwrap_or_else(|| panic!("{codes:?}"));
    let (machine, robot) = p
        .ir()
        .machines
        .iter()
        .find_map(|m| match m {
            Machine::Robot(r) => Some((m, r)),
            _ => None,
        })
        .unwrap();
    struct Angles(Follow, Vec<lmdc::plan::arm::Solved>);
    impl Visit for Angles {
        fn motion(&mut self, m: &Move) {
            if let Some(done) = self.0.push(m) {
                self.1.extend(done);
            }
        }
    }
    let mut v = Angles(Follow::new(robot).unwrap(), Vec::new());
    Plan::new(p.ir(), machine).walk(&mut v);
    let rest = v.0.take();
    v.1.extend(rest);
    let (c1, c4) = (815.0, 170.0);
    // The first move is the PTP from home: not a LIN.
    let angles: Vec<f64> =
        v.1.iter()
            .skip(1)
            .map(|s| {
                let f = v.0.solver().flange(s.to, &s.rot);
                let w = f.translation.vector - f.rotation * Vector3::z() * c4;
                w.xy().norm().atan2((w.z - c1).abs()).to_degrees()
            })
            .collect();
    let least = angles.iter().copied().fold(f64::INFINITY, f64::min);
    assert!(least > 1.0 && least < 5.0, "{least}");
    let below = angles.iter().filter(|a| **a < 5.0).count();

    let strict = lmdc::pipeline::compile(&overhead_duct(5.0), &mut ());
    assert!(strict.program.is_none());
    let d = strict
        .diagnostics
        .iter()
        .find(|d| d.code == lmdc::diag::Code::SingularLin && d.message.contains("A1's axis"))
        .unwrap_or_else(|| panic!("{:?}", strict.diagnostics));
    let reported: f64 = d
        .message
        .split("centre ")
        .nth(1)
        .unwrap()
        .split('°')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(
        (reported - least).abs() < 1e-3,
        "{reported} vs {least}: {}",
        d.message
    );
    assert!(
        d.message.contains(&format!("({below} poses)")),
        "{below}: {}",
        d.message
    );

    let just_below = lmdc::pipeline::compile(&overhead_duct(least - 0.01), &mut ());
    assert!(just_below.program.is_some(), "{:?}", just_below.diagnostics);
}

/// On a real plan every pose but the first (the PTP from home) is
/// continued from the one before (`plan::arm::chain`): the closed form is
/// left for where it must decide, and the fast path is not silently dead.
#[test]
fn a_plan_is_continued_pose_by_pose() {
    use lmdc::plan::arm::Follow;
    use lmdc::plan::{Move, Plan, Visit};
    let p = build("examples/ramp_wall.lmd");
    let (machine, robot) = p
        .ir()
        .machines
        .iter()
        .find_map(|m| match m {
            Machine::Robot(r) if r.arm.is_some() => Some((m, r)),
            _ => None,
        })
        .expect("the ramp wall's robot declares an arm");
    struct Push(Follow);
    impl Visit for Push {
        fn motion(&mut self, m: &Move) {
            self.0.push(m);
        }
    }
    let mut v = Push(Follow::new(robot).unwrap());
    Plan::new(p.ir(), machine).walk(&mut v);
    let solved = v.0.take().len() as u64;
    let [continued, closed] = v.0.counts();
    assert_eq!(continued + closed, v.0.pushed());
    assert!(solved > 0 && v.0.pushed() > 1000, "{}", v.0.pushed());
    assert_eq!(closed, 1, "{continued} continued, {closed} in closed form");
}
