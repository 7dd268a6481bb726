//! Normal → rotary angles: the angles reproduce the normal, the choice among the
//! equivalent solutions is the nearest one, and C stays continuous along real paths.

use crate::support::gcode_common as common;
use common::fixture::*;
use common::*;
use lmdc::ir::*;
use lmdc::plan::kinematics::{direction, follow, run_start, Rotary};
use proptest::prelude::*;

const HEADS: [Kinematics; 2] = [Kinematics::HeadAc, Kinematics::HeadBc];

/// The formulas of the issue, written out independently of the library.
fn t_of(kin: Kinematics, tilt: f64, c: f64) -> [f64; 3] {
    let (t, c) = (tilt.to_radians(), c.to_radians());
    match kin {
        Kinematics::HeadAc => [t.sin() * c.sin(), -t.sin() * c.cos(), t.cos()],
        Kinematics::HeadBc => [t.sin() * c.cos(), t.sin() * c.sin(), t.cos()],
        _ => unreachable!("heads only"),
    }
}

fn unit(theta: f64, phi: f64) -> [f64; 3] {
    let (t, p) = (theta.to_radians(), phi.to_radians());
    [t.sin() * p.cos(), t.sin() * p.sin(), t.cos()]
}

fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
    (0..3).all(|i| (a[i] - b[i]).abs() <= tol)
}

fn cost(a: Rotary, b: Rotary) -> f64 {
    (a.tilt - b.tilt).abs() + (a.c - b.c).abs()
}

proptest! {
    #[test]
    fn angles_reproduce_the_normal(
        theta in 0.0f64..90.0,
        phi in 0.0f64..360.0,
        prev_tilt in -120.0f64..120.0,
        prev_c in -1000.0f64..1000.0,
    ) {
        let n = unit(theta, phi);
        let prev = Rotary { tilt: prev_tilt, c: prev_c };
        for kin in HEADS {
            let r = follow(kin, n, prev);
            let t = t_of(kin, r.tilt, r.c);
            // Vertical within VERTICAL_DEG counts as vertical: 1e-5 rad off at most.
            prop_assert!(close(t, n, 1e-5), "{kin:?} {r:?}: {t:?} vs {n:?}");
            prop_assert!(close(direction(kin, r), t, 1e-12));
            // The angles, rounded as printed, still give the normal to 1e-4.
            let printed = |v: f64| (v * 1000.0).round() / 1000.0;
            prop_assert!(close(t_of(kin, printed(r.tilt), printed(r.c)), n, 1e-4));
        }
    }

    #[test]
    fn the_nearest_equivalent_solution_wins(
        theta in 0.01f64..90.0,
        phi in 0.0f64..360.0,
        prev_tilt in -90.0f64..90.0,
        prev_c in -1000.0f64..1000.0,
    ) {
        let n = unit(theta, phi);
        let prev = Rotary { tilt: prev_tilt, c: prev_c };
        for kin in HEADS {
            let r = follow(kin, n, prev);
            // Every equivalent solution: ±tilt, C + 180° with −tilt, whole turns.
            for k in -5..=5 {
                for (tilt, c) in [(r.tilt, r.c), (-r.tilt, r.c + 180.0)] {
                    let other = Rotary { tilt, c: c + 360.0 * k as f64 };
                    prop_assert!(close(t_of(kin, other.tilt, other.c), n, 1e-9));
                    prop_assert!(
                        cost(prev, r) <= cost(prev, other) + 1e-9,
                        "{kin:?}: from {prev:?} chose {r:?}, but {other:?} is closer"
                    );
                }
            }
        }
    }

    #[test]
    fn repositioning_finds_a_solution_inside_the_limits(
        theta in 0.01f64..90.0,
        phi in 0.0f64..360.0,
        prev_c in -2000.0f64..2000.0,
    ) {
        let n = unit(theta, phi);
        let prev = Rotary { tilt: 0.0, c: prev_c };
        for kin in HEADS {
            // A one-sided head with one turn of C: one solution is always
            // inside, for a run of this one direction.
            let r = run_start(kin, std::iter::once(n), prev, [[0.0, 120.0], [-180.0, 180.0]]);
            prop_assert!(r.tilt >= 0.0 && r.c >= -180.0 && r.c <= 180.0, "{r:?}");
            prop_assert!(close(t_of(kin, r.tilt, r.c), n, 1e-9));
        }
    }
}

/// Azimuth of `n` in the head's C convention, deg (`None` when vertical).
fn azimuth(kin: Kinematics, n: [f64; 3]) -> Option<f64> {
    if n[0].hypot(n[1]) < 1e-9 {
        return None;
    }
    Some(match kin {
        Kinematics::HeadAc => n[0].atan2(-n[1]).to_degrees(),
        _ => n[1].atan2(n[0]).to_degrees(),
    })
}

/// The least C travel any solution needs between directions `a` and `b`: their
/// azimuth difference, or its supplement when flipping the tilt is shorter.
fn required_c(kin: Kinematics, a: [f64; 3], b: [f64; 3]) -> f64 {
    match (azimuth(kin, a), azimuth(kin, b)) {
        (Some(x), Some(y)) => {
            let d = (y - x).rem_euclid(360.0);
            let d = d.min(360.0 - d);
            d.min(180.0 - d)
        }
        _ => 0.0,
    }
}

/// One layer with two paths: the inside of a cone walked twice round (normals lean
/// outwards by 30°, turning with the path), then a straight path whose normal tips
/// from −25° through vertical to +25°.
fn cone(kin: Kinematics) -> Program {
    let pt = |pos: [f64; 3], n: [f64; 3]| Point {
        pos,
        normal: [n[0] as f32, n[1] as f32, n[2] as f32],
        tangent: [1.0, 0.0, 0.0],
        layer_height: 0.5,
        speed: 8.0,
        power: 2000.0,
        powder: 10.0,
        defocus: -2.0,
        laser_on: true,
        style: 0,
        pitch: 0.0,
        rise: 0.0,
    };
    let turns: Vec<Point> = (0..=720)
        .map(|i| {
            let th = (i as f64).to_radians();
            let pos = [40.0 * th.cos(), 40.0 * th.sin(), 0.0];
            pt(pos, unit(30.0, i as f64))
        })
        .collect();
    let tip: Vec<Point> = (0..=50)
        .map(|i| {
            let a = -25.0 + i as f64;
            pt([i as f64, 60.0, 0.0], unit(a, 0.0))
        })
        .collect();
    let mut machine = cnc5_with(kin);
    machine.limits.rotary = [-10000.0, 10000.0];
    let mut p = bent_tube(1, 4, 0.0, vec![Machine::Cnc(machine)]);
    p.layers[0].paths = vec![
        Path {
            kind: PathKind::Wall,
            points: turns,
        },
        Path {
            kind: PathKind::Wall,
            points: tip,
        },
    ];
    p
}

#[test]
fn c_follows_the_path_without_jumps() {
    for kin in HEADS {
        let ir = cone(kin);
        let v = verified(ir.clone());
        let (_, text) = emit(&v, 0);
        let tilt_letter = if kin == Kinematics::HeadAc { 'A' } else { 'B' };
        let word = |l: &str, c: char| -> f64 {
            l.split_whitespace()
                .find(|w| w.starts_with(c))
                .unwrap_or_else(|| panic!("no {c} in {l}"))[1..]
                .parse()
                .unwrap()
        };
        // Deposit lines in order, with the IR normals they reach.
        let g1: Vec<(f64, f64)> = text
            .lines()
            .filter(|l| l.starts_with("G1 "))
            .map(|l| (word(l, tilt_letter), word(l, 'C')))
            .collect();
        let paths = &ir.layers[0].paths;
        // Each path: an approach to point 0, then points 1.. .
        let normals: Vec<[f64; 3]> = paths
            .iter()
            .flat_map(|p| p.points.iter())
            .map(|p| p.normal.map(|v| v as f64))
            .collect();
        assert_eq!(g1.len(), normals.len(), "one G1 per point");
        let mut c_total = 0.0;
        for i in 1..g1.len() {
            if i == paths[0].points.len() {
                continue; // the transition to the second path may turn freely
            }
            let dc = (g1[i].1 - g1[i - 1].1).abs();
            let need = required_c(kin, normals[i - 1], normals[i]);
            assert!(
                dc <= need + 2e-3,
                "{kin:?} line {i}: C moves {dc}° where {need}° would do"
            );
            if i < paths[0].points.len() {
                c_total += g1[i].1 - g1[i - 1].1;
            }
        }
        // Two full turns, wound up rather than jumping back.
        assert!(
            (c_total - 720.0).abs() < 1e-2,
            "{kin:?}: C turned {c_total}°"
        );
        // Through the vertical the tilt changes sign while C holds still.
        let tip = &g1[paths[0].points.len()..];
        assert!(tip.first().unwrap().0 * tip.last().unwrap().0 < 0.0);
        assert!(tip.iter().all(|t| t.1 == tip[0].1), "{kin:?}: {tip:?}");
    }
}
