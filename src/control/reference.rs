//! The paper's numbers, reproduced or not: the gains' units, the totals,
//! Table 2's final speeds, Table 1 on the first layer, the transitions.

use super::analysis::{Finding, Severity};
use super::paper::*;
use super::*;
use crate::units::{Angle, Length, Speed};
use std::num::NonZeroUsize;

fn layers() -> NonZeroUsize {
    NonZeroUsize::new(LAYERS).unwrap()
}

fn speeds() -> Vec<Speed> {
    SPEED_MM_S.iter().map(|&v| Speed(v)).collect()
}

/// A plant calibrated to Table 1 with `drift` per layer, run with `c`.
fn run(c: &Controller, drift: f64) -> Vec<Total> {
    let plant = Plant::calibrated(Length(TARGET_MM), &speeds(), drift).unwrap();
    simulate(c, &plant, &speeds(), layers()).unwrap().totals()
}

#[test]
fn gains_per_m_s_build_29_90_mm_on_every_segment() {
    // 0.1 %/layer: by layer 130 a segment at its start speed lays 13 % high.
    for drift in [0.0, 0.001, -0.001, 0.002] {
        for t in run(&controller().unwrap(), drift) {
            assert!((t.target.0 - 29.90).abs() < 1e-9);
            assert!(t.error().0.abs() < 0.1, "drift {drift}: {t:?}");
            // A ramp in the plant leaves the total a constant v·δ/|kI| high
            // once the loop follows it (the two integrators of eq. 6 follow a
            // ramp in speed with a constant Σ).
            let v0 = SPEED_MM_S[t.segment];
            let offset = v0 * drift / 0.35;
            assert!((t.error().0 - offset).abs() < 0.01, "drift {drift}: {t:?}");
        }
    }
    // With no drift a calibrated plant is on target from the first layer.
    for t in run(&controller().unwrap(), 0.0) {
        assert!(t.error().0.abs() < 1e-9);
        assert!((t.final_speed.0 - SPEED_MM_S[t.segment]).abs() < 1e-9);
    }
}

#[test]
fn gains_read_per_mm_s_cannot_hold_the_height() {
    let printed = controller_with(
        SpeedPerLength::from_mm_s_per_mm(KP_PRINTED),
        SpeedPerLength::from_mm_s_per_mm(KI_PRINTED),
    )
    .unwrap();
    // The same 0.1 % drift: the speed moves by 0.03 mm/s and every segment
    // ends 1.8 mm or more too high (Σ 0.23·0.001·i over 130 layers ≈ 1.93).
    for t in run(&printed, 0.001) {
        assert!(t.error().0 > 1.8, "{t:?}");
        assert!((t.final_speed.0 - SPEED_MM_S[t.segment]).abs() < 0.05);
    }
    let a = analyse(&printed, &speeds(), layers()).unwrap();
    assert!(!a.is_ok());
    match &a.findings[0] {
        Finding::Slow {
            worst,
            settling,
            residual,
            per_metre,
            ..
        } => {
            assert_eq!(worst.segment, Some(4));
            assert!(*settling > 1e5 && *residual > 0.99 && *per_metre);
        }
        f => panic!("{f:?}"),
    }
    assert_eq!(
        a.findings[0].to_string(),
        "the loop is so slow it never settles: segment 5 (13 mm/s) needs ~147406 layers to \
         bring an error down to 2 % (spectral radius 0.999973) but the build has 130; 99.656 % \
         of an error is still there after the last layer"
    );
    let help = a.findings[0].help().unwrap();
    assert!(help.contains("kp = -0.003 m/s/mm"), "{help}");
    assert!(
        help.contains("(-3 (mm/s)/mm and -0.35 (mm/s)/mm)"),
        "{help}"
    );
}

#[test]
fn the_papers_loop_is_stable_but_its_fast_segments_settle_late() {
    let a = analyse(&controller().unwrap(), &speeds(), layers()).unwrap();
    assert!(a.is_ok());
    for l in &a.segments {
        // Complex pairs of modulus √(1 − 3·0.23/v).
        let v = SPEED_MM_S[l.segment.unwrap()];
        assert!((l.radius - (1.0 - 0.69 / v).sqrt()).abs() < 1e-12);
    }
    // 4 mm/s settles in 41 layers, 13 mm/s in 144 of the build's 130 — yet
    // only ρ¹³⁰ = 2.887 % of an error is left then, within the 5 % band
    // (SETTLED_ENOUGH): no finding on the published loop.
    let rho13 = (1.0 - 0.69 / 13.0f64).sqrt();
    let worst = a.segments.iter().find(|l| l.segment == Some(4)).unwrap();
    assert!((worst.settling.unwrap() - 0.02f64.ln() / rho13.ln()).abs() < 1e-9);
    assert!(worst.settling.unwrap() > 130.0);
    let residual = rho13.powi(130);
    assert!((residual - 0.02887).abs() < 5e-5, "{residual}");
    assert!((worst.gains.residual_after(130) - residual).abs() < 1e-12);
    assert!(a.findings.is_empty(), "{:?}", a.findings);
    // With 110 layers ρ¹¹⁰ = 5.0 %… and 100 layers 6.6 %: the warning, with
    // the gains that settle in time.
    let short = analyse(
        &controller().unwrap(),
        &speeds(),
        NonZeroUsize::new(100).unwrap(),
    )
    .unwrap();
    assert!(rho13.powi(100) > super::analysis::SETTLED_ENOUGH);
    assert_eq!(short.findings.len(), 1);
    let f = &short.findings[0];
    assert_eq!(f.severity(), Severity::Warning);
    assert!(
        f.to_string().starts_with(
            "segment 5 (13 mm/s) settles in ~144 layers (to 2 %), but the build has 100"
        ),
        "{f}"
    );
    assert!(f
        .help()
        .unwrap()
        .contains("settle within 100 layers at every segment"));
    // The slowest loop the clamp allows, 1.9 mm/s, is still stable.
    assert!((a.clamp_low.radius - (1.0 - 0.69 / 1.9f64).sqrt()).abs() < 1e-12);
}

#[test]
fn an_unstable_loop_names_its_worst_segment_and_the_stable_gains() {
    let c = controller_with(SpeedPerLength(-40.0), SpeedPerLength(-5.0)).unwrap();
    let a = analyse(&c, &speeds(), layers()).unwrap();
    let f = &a.findings[0];
    assert_eq!(f.severity(), Severity::Error);
    // p = −40·0.23/4 = −2.3 < −2 at the 4 mm/s ends: λ = ... ρ = 1.471.
    assert_eq!(
        f.to_string(),
        "unstable: loop gain kP·h_r/v = -2.3, kI·h_r/v = -0.2875 at segment 1 (4 mm/s): \
         spectral radius 1.471 (2 of 10 segments unstable)"
    );
    // 4 / (2·2.3 + 0.2875) = 0.8184.
    assert_eq!(
        f.help().unwrap(),
        "gains below ×0.8184 of these are stable at every segment: kp above -32.737 (mm/s)/mm, \
         ki above -4.092 (mm/s)/mm"
    );
    // 2|kP| + |kI| = 42 < 4·v/h_r = 69.6 at 4 mm/s, > 33 at the clamp's 1.9:
    // p = −2.421 < −2 there, λ = −1.569; stable below ×4/(2·2.421 + 0.2421) = ×0.7867.
    let c = controller_with(SpeedPerLength(-20.0), SpeedPerLength(-2.0)).unwrap();
    let a = analyse(&c, &speeds(), layers()).unwrap();
    assert!(a.is_ok());
    assert_eq!(
        a.findings[0].to_string(),
        "the loop is stable at every segment's speed but not if a segment slows to the \
         clamp's 1.9 mm/s: spectral radius 1.569 there"
    );
    assert_eq!(
        a.findings[0].help().unwrap(),
        "gains below ×0.7867 of these are stable there, or raise the clamp's low speed"
    );
    let positive = controller_with(SpeedPerLength(3.0), SpeedPerLength(-0.35)).unwrap();
    let a = analyse(&positive, &speeds(), layers()).unwrap();
    assert_eq!(a.findings.len(), 1);
    assert!(matches!(a.findings[0], Finding::Sign { .. }));
}

#[test]
fn table_2_final_speeds_need_a_per_segment_plant() {
    // A drift common to every segment moves every speed the same way; Table 2
    // has five segments faster at the end and five slower.
    let up = run(&controller().unwrap(), 0.001);
    let paper_up: Vec<bool> = (0..10)
        .map(|j| FINAL_SPEED_MM_S[j] > SPEED_MM_S[j])
        .collect();
    assert_eq!(paper_up.iter().filter(|&&u| u).count(), 5);
    let agree = up
        .iter()
        .filter(|t| (t.final_speed.0 > SPEED_MM_S[t.segment]) == paper_up[t.segment])
        .count();
    assert_eq!(agree, 5);
    // A plant that really laid g_j = h_r·v_final (the calibration missing by
    // −10 % … +31 %, the substrate's unevenness the paper names) ends within
    // 2 % of every Table 2 speed, in the right direction; but it builds every
    // total to within 0.05 mm of 29.90, where the paper's are 0.98 mm short
    // to 0.06 mm over: the integral closes the total on any plant h ∝ 1/v, so
    // those shortfalls came from outside this model (a sensor reading other
    // than the real height, say).
    let factors: Vec<f64> = (0..10)
        .map(|j| FINAL_SPEED_MM_S[j] / SPEED_MM_S[j])
        .collect();
    let plant = Plant::calibrated(Length(TARGET_MM), &speeds(), 0.0)
        .unwrap()
        .scaled(&factors)
        .unwrap();
    let sim = simulate(&controller().unwrap(), &plant, &speeds(), layers()).unwrap();
    for t in sim.totals() {
        let paper = FINAL_SPEED_MM_S[t.segment];
        assert!((t.final_speed.0 / paper - 1.0).abs() < 0.02, "{t:?}");
        assert_eq!(t.final_speed.0 > SPEED_MM_S[t.segment], paper_up[t.segment]);
        assert!(t.error().0.abs() < 0.05, "{t:?}");
    }
    let paper_errors: Vec<f64> = TOTAL_MM.iter().map(|t| t - 29.90).collect();
    assert!(paper_errors.iter().any(|e| *e < -0.9));
}

fn ring() -> Ring {
    Ring::new(Length(RADIUS_MM), 10, transition()).unwrap()
}

#[test]
fn the_first_layer_lays_table_1() {
    let table = table1().unwrap();
    let points = ring()
        .first_layer(&table, Length(TARGET_MM), Angle::from_deg(1.0))
        .unwrap();
    for p in points.iter().filter(|p| !p.transition) {
        let j = p.segment;
        assert_eq!(p.speed.0, SPEED_MM_S[j]);
        assert_eq!(p.defocus.0, DEFOCUS_MM[j]);
        assert!((p.power.watts() - POWER_W[j]).abs() < 1e-9);
        assert_eq!(p.pos[2], 0.0);
        // Eq. 2: the nozzle of layer 1 at Z0 + (j − 1) up to n/2, then back
        // down; Z0 here is the first segment's focus, −8 mm.
        let j1 = j + 1;
        let steps = if j1 <= 5 { j1 - 1 } else { 10 - j1 };
        assert_eq!(p.focus_z(), -8.0 + steps as f64);
        // Inside the segment's 34°, on the 40 mm circle.
        let theta = p.pos[1].atan2(p.pos[0]).rem_euclid(std::f64::consts::TAU);
        let deg = theta.to_degrees();
        assert!(deg >= 36.0 * j as f64 - 1e-9 && deg <= 36.0 * j as f64 + 34.0 + 1e-9);
        assert!((p.pos[0].hypot(p.pos[1]) - 40.0).abs() < 1e-12);
    }
    assert!(points.iter().all(|p| p.laser_on));
    // 34 moves of 1° and 2 of 1° per segment, and the end point.
    assert_eq!(points.len(), 10 * 36 + 1);
    let end = points.last().unwrap();
    assert!((end.pos[0] - 40.0).abs() < 1e-9 && end.pos[1].abs() < 1e-9);
    assert!((end.pos[2] - 0.23).abs() < 1e-12);
    assert_eq!(end.defocus.0, -8.0);
}

#[test]
fn transitions_run_at_v_over_cos_gamma() {
    let table = table1().unwrap();
    let points = ring()
        .first_layer(&table, Length(TARGET_MM), Angle::from_deg(0.5))
        .unwrap();
    let arc_per_rad = RADIUS_MM;
    let mut seen = 0;
    for w in points.windows(2) {
        let (p, q) = (&w[0], &w[1]);
        if !p.transition {
            continue;
        }
        seen += 1;
        let dtheta =
            (q.pos[1].atan2(q.pos[0]) - p.pos[1].atan2(p.pos[0])).rem_euclid(std::f64::consts::TAU);
        let tan_g = (q.focus_z() - p.focus_z()) / (arc_per_rad * dtheta);
        let cos_g = 1.0 / (1.0 + tan_g * tan_g).sqrt();
        let v = SPEED_MM_S[p.segment];
        assert!((p.speed.0 - v / cos_g).abs() < 1e-9, "{p:?}");
    }
    assert_eq!(seen, 10 * 4);
    // Segments 1→2: a 1 mm rise over 2° of a 40 mm ring at 4 mm/s: 4.92 mm/s.
    let first = points.iter().find(|p| p.transition).unwrap();
    assert!(
        (first.speed.0 - 4.0 * (1.0f64 + (1.0 / (40.0 * 2f64.to_radians())).powi(2)).sqrt()).abs()
            < 1e-12
    );
    assert!((first.speed.0 - 4.920).abs() < 1e-3);
    // The layer change rises by 0.23 mm: 4 mm/s · 1.0135.
    let last = points
        .iter()
        .rev()
        .find(|p| p.transition && p.segment == 9)
        .unwrap();
    assert!((last.speed.0 - 4.0539).abs() < 1e-4);
}

#[test]
fn the_fastest_transition_at_the_clamps_top() {
    let table = table1().unwrap();
    let (t, v) = ring()
        .fastest_transition(&table, Length(TARGET_MM), Speed(CLAMP_MM_S[1]))
        .unwrap();
    // Every 1 mm defocus step at 20 mm/s: 20/cos 35.6° = 24.6 mm/s; a machine
    // whose max_speed is 22 mm/s cannot run it.
    assert_eq!(t.segment, 0);
    assert!((t.rise.0 - 1.0).abs() < 1e-12);
    assert!((v.0 - 24.600).abs() < 1e-3);
    let rises: Vec<f64> = ring()
        .transitions(&table, Length(TARGET_MM))
        .unwrap()
        .iter()
        .map(|t| t.rise.0)
        .collect();
    let want = [1.0, 1.0, 1.0, 1.0, 0.0, -1.0, -1.0, -1.0, -1.0, 0.23];
    for (r, w) in rises.iter().zip(want) {
        assert!((r - w).abs() < 1e-12);
    }
    // Table 1's energy densities: 48 J/mm² at the wide ends, 20 at the narrow middle.
    let e: Vec<f64> = table.rows().iter().map(|r| r.energy_density().0).collect();
    assert!((e[0] - 48.0).abs() < 1e-9 && (e[4] - 20.0).abs() < 1e-9);
    assert!((e[3] - 780.0 / 38.5).abs() < 1e-9);
}

#[test]
fn a_table_of_the_wrong_length_is_refused() {
    let mut rows = table1().unwrap().rows().to_vec();
    rows.pop();
    let nine = SegmentTable::new(rows).unwrap();
    assert_eq!(
        ring().check_table(&nine),
        Err(Invalid::Count {
            what: "segment table",
            found: 9,
            expected: 10
        })
    );
    assert!(ring()
        .first_layer(&nine, Length(TARGET_MM), Angle::from_deg(1.0))
        .is_err());
}
