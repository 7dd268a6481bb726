//! A robot's two-axis positioner (issue 22 item 2): the part turns on E1
//! (tilt) and E2 (rotate) under a nozzle that stays vertical.
//!
//! The KRL is read back here with a forward kinematics of the test's own
//! (nalgebra's axis-angle rotations, not the library's): each motion's
//! `X Y Z A B C` in the coupled base, turned by the written E1 and E2 into
//! the robot's frame, must be the IR's point of the part turned by the
//! IR's angles for its layer, to the resolution the numbers are printed
//! at; the nozzle must point straight down on every deposit of the
//! example; and the limit error must carry the angle computed here from
//! the layer's normals.

use lmdc::back::{MemorySink, Templates};
use lmdc::diag::Code;
use lmdc::ir::{Machine, Positioner, Robot};
use nalgebra::{Isometry3, Point3, Rotation3, Translation3, UnitQuaternion, Vector3};
use std::collections::BTreeMap;

/// The example: the seed-000 duct on a KR 60 HA with a positioner.
const EXAMPLE: &str = "examples/duct_positioner.lmd";

/// Half the last printed digit of positions and angles (3 decimals).
const HALF: f64 = 0.0005;

fn build(src: &str) -> lmdc::verify::Verified {
    lmdc::pipeline::compile(src, &mut ())
        .program
        .unwrap_or_else(|| panic!("compiles"))
}

fn krl(p: &lmdc::verify::Verified) -> BTreeMap<String, String> {
    let mut sink = MemorySink::default();
    let m = p.machine(0).expect("a verified robot");
    lmdc::back::emit(m, &Templates::builtin().unwrap(), &mut sink).unwrap();
    sink.files
        .into_iter()
        .map(|(n, b)| (n, String::from_utf8(b).unwrap()))
        .collect()
}

fn robot(p: &lmdc::verify::Verified) -> &Robot {
    match &p.ir().machines[0] {
        Machine::Robot(r) => r,
        _ => panic!("a robot"),
    }
}

/// `key <number>` in a KRL aggregate.
fn field(agg: &str, key: &str) -> f64 {
    agg.split(['{', ',', '}'])
        .find_map(|p| p.trim().strip_prefix(key)?.strip_prefix(' '))
        .and_then(|v| v.trim().parse().ok())
        .unwrap_or_else(|| panic!("no {key} in {agg}"))
}

/// A motion of the KRL: `X Y Z`, `A B C`, E1 E2, whether the laser is on
/// during it.
struct Motion {
    xyz: [f64; 3],
    abc: [f64; 3],
    e: [f64; 2],
    laser: bool,
}

/// Every LIN and PTP of the modules, in order (the modules' names sort in
/// their order).
fn motions(files: &BTreeMap<String, String>) -> Vec<Motion> {
    let mut out = Vec::new();
    let mut laser = false;
    for (_, text) in files
        .iter()
        .filter(|(n, _)| n.contains("_m0") && n.ends_with(".src"))
    {
        for l in text.lines() {
            if l.starts_with("TRIGGER WHEN DISTANCE=0") && l.contains("$OUT[1]=") {
                laser = l.ends_with("TRUE");
            }
            if !(l.starts_with("LIN {X") || l.starts_with("PTP {X")) {
                continue;
            }
            let agg = &l[..l.find('}').unwrap() + 1];
            out.push(Motion {
                xyz: [field(agg, "X"), field(agg, "Y"), field(agg, "Z")],
                abc: [field(agg, "A"), field(agg, "B"), field(agg, "C")],
                e: [field(agg, "E1"), field(agg, "E2")],
                laser,
            });
        }
    }
    out
}

/// KUKA's frame `X Y Z A B C`: `Rz(A)·Ry(B)·Rx(C)`, built from three
/// axis-angle turns.
fn kuka(xyz: [f64; 3], abc: [f64; 3]) -> Isometry3<f64> {
    let r = |axis: Vector3<f64>, deg: f64| Rotation3::new(axis * deg.to_radians());
    let rot = r(Vector3::z(), abc[0]) * r(Vector3::y(), abc[1]) * r(Vector3::x(), abc[2]);
    Isometry3::from_parts(
        Translation3::new(xyz[0], xyz[1], xyz[2]),
        UnitQuaternion::from_rotation_matrix(&rot),
    )
}

/// The test's forward kinematics: the part's base in the robot's frame at
/// `e`, from the IR's positioner and base (`T₁(E1)·T₂(E2)·F₀·B`).
fn part_base(p: &Positioner, base: [f64; 6], e: [f64; 2]) -> Isometry3<f64> {
    let turn = |dir: [f64; 3], at: [f64; 3], deg: f64| -> Isometry3<f64> {
        let d = Vector3::from(dir).normalize();
        let at = Vector3::from(at);
        Translation3::from(at) * UnitQuaternion::new(d * deg.to_radians()) * Translation3::from(-at)
    };
    let z = Vector3::from(p.rotate.direction).normalize();
    let t = Vector3::from(p.tilt.direction);
    let x = (t - z * t.dot(&z)).normalize();
    let flange = Isometry3::from_parts(
        Translation3::from(Vector3::from(p.rotate.point)),
        UnitQuaternion::from_rotation_matrix(&Rotation3::from_basis_unchecked(&[
            x,
            z.cross(&x),
            z,
        ])),
    );
    let b = kuka([base[0], base[1], base[2]], [base[3], base[4], base[5]]);
    let t1 = turn(p.tilt.direction, p.tilt.point, e[0]);
    let t2 = turn(p.rotate.direction, p.rotate.point, e[1]);
    t1 * t2 * flange * b
}

/// The IR's deposit targets in order (the focus of every point whose
/// predecessor lays metal) with their layer.
fn deposits(ir: &lmdc::ir::Program) -> Vec<([f64; 3], usize)> {
    let mut out = Vec::new();
    for (li, l) in ir.layers.iter().enumerate() {
        for p in &l.paths {
            for w in p.points.windows(2) {
                if w[0].laser_on {
                    out.push((w[1].focus(), li));
                }
            }
        }
    }
    out
}

/// Distance of `w` from the axis through `at` along `dir`.
fn from_axis(w: &Point3<f64>, dir: [f64; 3], at: [f64; 3]) -> f64 {
    let d = Vector3::from(dir).normalize();
    let v = w.coords - Vector3::from(at);
    (v - d * d.dot(&v)).norm()
}

/// The example's KRL turned into the robot's frame by its own E1 and E2,
/// then back into the part by the IR's angles for the layer: the IR's
/// path, to the printed resolution (the positions' half digit, and the
/// angles' half digit at the point's distance from each axis); its E1 and
/// E2 are the IR's to the printed digit; the nozzle (the tool's +Z, the
/// beam) points straight down within 1° on every deposit.
#[test]
fn the_written_axes_rebuild_the_part_and_keep_the_nozzle_vertical() {
    let p = build(&std::fs::read_to_string(EXAMPLE).unwrap());
    let r = robot(&p);
    let pos = r.positioner.as_deref().expect("a positioner");
    let b = r.base.value.expect("a base on the flange");
    let base = [b.x, b.y, b.z, b.a, b.b, b.c];
    let moves: Vec<_> = motions(&krl(&p)).into_iter().filter(|m| m.laser).collect();
    let want = deposits(p.ir());
    assert_eq!(moves.len(), want.len(), "one LIN a deposit");
    assert_eq!(pos.angles.len(), p.ir().layers.len());
    let mut worst_tilt = 0.0f64;
    for (m, (focus, layer)) in moves.iter().zip(&want) {
        let ir_e = pos.angles[*layer];
        for i in 0..2 {
            assert!(
                (m.e[i] - ir_e[i]).abs() <= HALF + 1e-9,
                "E{}: {:?} vs {ir_e:?}",
                i + 1,
                m.e
            );
        }
        let pose = kuka(m.xyz, m.abc);
        let world = part_base(pos, base, m.e) * pose;
        let w = world * Point3::origin();
        let back = part_base(pos, base, ir_e).inverse() * w;
        let tol = HALF * 3f64.sqrt()
            + (HALF.to_radians())
                * (from_axis(&w, pos.tilt.direction, pos.tilt.point)
                    + from_axis(&w, pos.rotate.direction, pos.rotate.point))
            + 1e-9;
        let d = (back.coords - Vector3::from(*focus)).norm();
        assert!(
            d <= tol,
            "layer {}: {back:?} vs {focus:?} ({d} > {tol})",
            layer + 1
        );
        // The beam, the tool's +Z, in the robot's frame.
        let beam = world.rotation * Vector3::z();
        let tilt = beam.angle(&-Vector3::z()).to_degrees();
        worst_tilt = worst_tilt.max(tilt);
    }
    assert!(
        worst_tilt < 1.0,
        "the nozzle leans {worst_tilt}° from vertical"
    );
    // The duct bends by 45°: the positioner really turns it.
    let e1 = pos.angles.iter().map(|e| e[0].abs()).fold(0.0, f64::max);
    assert!(e1 > 40.0, "E1 reaches {e1}°");
}

/// The mean normal of a layer's deposits, from the IR.
fn mean_normal(l: &lmdc::ir::Layer) -> Vector3<f64> {
    let mut s = Vector3::zeros();
    for p in l
        .paths
        .iter()
        .flat_map(|p| &p.points)
        .filter(|p| p.laser_on)
    {
        s += Vector3::new(p.normal[0] as f64, p.normal[1] as f64, p.normal[2] as f64);
    }
    s.normalize()
}

/// E1 held within ±20°: the duct's layers lean up to 45° about the tilt
/// axis, and neither solution (±lean) fits. The error names E1, the worst
/// layer (the last, leaning most) and its angle — the lean of that layer's
/// mean normal computed here — and how many layers lean beyond 20°.
#[test]
fn e1_beyond_its_limits_is_refused_with_the_layer_and_angle() {
    let src = std::fs::read_to_string(EXAMPLE).unwrap().replace(
        "tilt_limits = -90 deg .. 90 deg",
        "tilt_limits = -20 deg .. 20 deg",
    );
    let ok = build(&std::fs::read_to_string(EXAMPLE).unwrap());
    let layers = &ok.ir().layers;
    let lean: Vec<f64> = layers
        .iter()
        .map(|l| mean_normal(l).angle(&Vector3::z()).to_degrees())
        .collect();
    let beyond = lean.iter().filter(|a| **a > 20.0 + 1e-9).count();
    let (worst, at) = lean
        .iter()
        .enumerate()
        .map(|(i, a)| (*a, i + 1))
        .fold((0.0, 0), |b, x| if x.0 > b.0 { x } else { b });
    let c = lmdc::pipeline::compile(&src, &mut ());
    assert!(c.program.is_none());
    let d = c
        .diagnostics
        .iter()
        .find(|d| d.code == Code::PositionerLimit)
        .expect("lmd::positioner-limit");
    let shown = lmdc::units::short(worst);
    assert!(d.message.contains("E1 (tilt)"), "{}", d.message);
    assert!(
        d.message.contains(&format!("at {shown}° for layer {at},")),
        "{} (want {shown}° at layer {at})",
        d.message
    );
    assert!(
        d.message.contains(&format!("({beyond} layers outside)")),
        "{} (want {beyond})",
        d.message
    );
}

/// `keep = fixed(…)` holds the positioner where it is told on every layer,
/// and `cone(…)` turns it only when a layer leaves the cone: every layer is
/// then within the cone of straight up, and the angles change less often
/// than the layers do.
#[test]
fn fixed_and_cone_keep_what_they_say() {
    let text = std::fs::read_to_string(EXAMPLE).unwrap();
    let fixed = build(&text.replace("keep = vertical", "keep = fixed(e1 = 10 deg, e2 = -30 deg)"));
    let pos = robot(&fixed).positioner.as_deref().unwrap();
    let at = |e: &[f64; 2]| (e[0] - 10.0).abs() < 1e-9 && (e[1] + 30.0).abs() < 1e-9;
    assert!(pos.angles.iter().all(at), "{:?}", &pos.angles[..3]);
    let cone = build(&text.replace("keep = vertical", "keep = cone(10 deg)"));
    let r = robot(&cone);
    let pos = r.positioner.as_deref().unwrap();
    let b = r.base.value.unwrap();
    let base = [b.x, b.y, b.z, b.a, b.b, b.c];
    let mut changes = 0;
    for (i, l) in cone.ir().layers.iter().enumerate() {
        let up = part_base(pos, base, pos.angles[i]).rotation * mean_normal(l);
        let lean = up.angle(&Vector3::z()).to_degrees();
        assert!(lean <= 10.0 + 1e-6, "layer {} leans {lean}°", i + 1);
        if i > 0 && pos.angles[i] != pos.angles[i - 1] {
            changes += 1;
        }
    }
    assert!(
        (4..20).contains(&changes),
        "{changes} changes over 281 layers"
    );
    // A cone's angle is how far a layer may lean: from 0 to 90°.
    let bad = lmdc::pipeline::compile(
        &text.replace("keep = vertical", "keep = cone(-5 deg)"),
        &mut (),
    );
    assert!(bad.program.is_none());
    let m: Vec<&str> = bad.diagnostics.iter().map(|d| d.message.as_str()).collect();
    assert!(
        m.iter().any(|m| m.contains("`angle`") && m.contains("90")),
        "{m:?}"
    );
}

/// E2 held within ±45° with the duct's bend axis square to the tilt axis
/// (the base not turned on the flange): every layer that leans needs E2 at
/// ±90° to bring its bend round to the tilt axis — here computed from the
/// bend axis, the duct's Y, turned onto the tilt axis, the robot's X — and
/// neither fits. The error names E2, ±90° and every leaning layer.
#[test]
fn e2_beyond_its_limits_is_refused_with_its_angle() {
    let src = std::fs::read_to_string(EXAMPLE)
        .unwrap()
        .replace("base = frame(1, a = 90 deg)", "base = frame(1)")
        .replace(
            "rotate_limits = -360 deg .. 360 deg",
            "rotate_limits = -45 deg .. 45 deg",
        );
    let ok = build(&std::fs::read_to_string(EXAMPLE).unwrap());
    let leaning = ok
        .ir()
        .layers
        .iter()
        .filter(|l| mean_normal(l).angle(&Vector3::z()) > 1e-9)
        .count();
    // The turn about Z taking the bend axis (Y) onto the tilt axis (X).
    let (bend, tilt) = (Vector3::<f64>::y(), Vector3::<f64>::x());
    let need = bend
        .cross(&tilt)
        .z
        .atan2(bend.dot(&tilt))
        .to_degrees()
        .abs();
    let c = lmdc::pipeline::compile(&src, &mut ());
    let d = c
        .diagnostics
        .iter()
        .find(|d| d.code == Code::PositionerLimit)
        .expect("lmd::positioner-limit");
    assert!(d.message.contains("E2 (rotate)"), "{}", d.message);
    let shown = lmdc::units::short(need);
    assert!(
        d.message.contains(&format!("at {shown}° for layer"))
            || d.message.contains(&format!("at -{shown}° for layer")),
        "{} (want ±{shown}°)",
        d.message
    );
    assert!(
        d.message.contains(&format!("({leaning} layers outside)")),
        "{} (want {leaning})",
        d.message
    );
}

/// A positioner set too far from the robot: the arm cannot reach the part,
/// and the fix names the positioner's place, not a robot base (which, on a
/// positioner, is the part's place on the flange).
#[test]
fn a_positioner_out_of_reach_says_to_bring_it_nearer() {
    let src = std::fs::read_to_string(EXAMPLE)
        .unwrap()
        .replace("tilt_point = [1500 mm,", "tilt_point = [6500 mm,")
        .replace("rotate_point = [1500 mm,", "rotate_point = [6500 mm,");
    assert_eq!(src.matches("6500 mm").count(), 2);
    let c = lmdc::pipeline::compile(&src, &mut ());
    assert!(c.program.is_none());
    let d = c
        .diagnostics
        .iter()
        .find(|d| d.code == Code::Reach)
        .expect("lmd::reach");
    let help = d.help.as_deref().unwrap();
    assert!(
        help.contains("`rotate_point`") && help.contains("positioner"),
        "{help}"
    );
    assert!(!help.contains("frame("), "{help}");
}
