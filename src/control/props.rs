//! Property tests against the formulas, written out again here: the
//! linearised analysis against the nonlinear simulation (stable ⇔ converges),
//! against Jury's test and nalgebra's eigenvalues; the ring's points against
//! `v / cos γ` measured from the points themselves; no panic on any input.

use super::linear::LoopGains;
use super::*;
use crate::units::{Angle, Length, Power, Speed};
use nalgebra::Matrix2;
use proptest::prelude::*;
use std::f64::consts::TAU;
use std::num::NonZeroUsize;

/// A loop gain: mostly negative, log-uniform over three decades, sometimes
/// positive or zero.
fn gain(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    prop_oneof![
        8 => (lo.ln()..hi.ln()).prop_map(|x: f64| -x.exp()),
        1 => (lo.ln()..hi.ln()).prop_map(|x: f64| x.exp()),
        1 => Just(0.0),
    ]
}

/// Whether one segment, started 1 % off its operating speed, ends on it:
/// speed, layer height and total all within 10⁻⁷ of where they should be.
fn converges(kp: f64, ki: f64, target: f64, v: f64, offset: f64) -> bool {
    let layers = 4000;
    let c = Controller::new(
        SpeedPerLength(kp),
        SpeedPerLength(ki),
        Length(target),
        Clamp::new(Speed(v / 4.0), Speed(v * 4.0)).unwrap(),
    )
    .unwrap();
    let plant = Plant::new(vec![Deposition(target * v)], 0.0).unwrap();
    let start = [Speed(v * (1.0 + offset))];
    let sim = simulate(&c, &plant, &start, NonZeroUsize::new(layers).unwrap()).unwrap();
    let last = sim.at(layers - 1, 0).unwrap();
    (last.speed.0 / v - 1.0).abs() < 1e-7
        && (last.height.0 / target - 1.0).abs() < 1e-7
        && (last.total.0 / (target * layers as f64) - 1.0).abs() < 1e-7
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// The compile-time check agrees with the nonlinear loop: a loop the
    /// linearisation calls stable converges from a small offset, one it calls
    /// unstable does not (away from ρ = 1, where 4000 layers cannot tell).
    #[test]
    fn stable_iff_the_simulation_converges(
        p in gain(0.05, 5.0),
        ratio in 0.01..3.0f64,
        ki_sign in prop_oneof![8 => Just(1.0), 1 => Just(-1.0), 1 => Just(0.0)],
        target in 0.1..1.0f64,
        v in 2.0..18.0f64,
        offset in prop_oneof![-0.01..-0.001f64, 0.001..0.01f64],
    ) {
        // Gains in (mm/s)/mm from the dimensionless p = kP·h_r/v, q = kI·h_r/v.
        let q = -ki_sign * ratio * p.abs().max(0.05);
        let kp = p * v / target;
        let ki = q * v / target;
        let g = LoopGains::at(SpeedPerLength(kp), SpeedPerLength(ki), Length(target), Speed(v));
        let rho = g.spectral_radius();
        prop_assume!((rho - 1.0).abs() > 0.02);
        prop_assert_eq!(g.is_stable(), converges(kp, ki, target, v, offset), "p {} q {} ρ {}", p, q, rho);
    }

    /// ρ < 1 ⇔ Jury's conditions −2 < p < 0, q < 0, 2p + q > −4; and the
    /// eigenvalues are nalgebra's.
    #[test]
    fn the_radius_agrees_with_jury_and_nalgebra(p in -6.0..1.0f64, q in -6.0..1.0f64) {
        let g = LoopGains { proportional: p, integral: q };
        let jury = p > -2.0 && p < 0.0 && q < 0.0 && 2.0 * p + q > -4.0;
        let rho = g.spectral_radius();
        prop_assume!((rho - 1.0).abs() > 1e-9);
        prop_assert_eq!(g.is_stable(), jury);
        let m = Matrix2::new(1.0 + p, q, 1.0 + p, 1.0 + q);
        let theirs = m.complex_eigenvalues();
        let mut ours: Vec<(f64, f64)> = g.eigenvalues().iter().map(|l| (l.re, l.im)).collect();
        let mut them: Vec<(f64, f64)> = theirs.iter().map(|l| (l.re, l.im)).collect();
        ours.sort_by(|a, b| a.partial_cmp(b).unwrap());
        them.sort_by(|a, b| a.partial_cmp(b).unwrap());
        for (a, b) in ours.iter().zip(&them) {
            prop_assert!((a.0 - b.0).abs() < 1e-7 && (a.1 - b.1).abs() < 1e-7, "{:?} vs {:?}", ours, them);
        }
        if let Some(n) = g.settling_layers() {
            // The envelope ρⁿ is 2 % at the settling time.
            prop_assert!((rho.powf(n) - 0.02).abs() < 1e-9 || n == 1.0);
        }
    }

    /// Every point of any layer lies on the ring in angular order, every
    /// transition move runs at v / cos γ measured from its own end points, the
    /// constant parts at the layer's speeds, the laser always on, and the last
    /// point is where the next layer starts.
    #[test]
    fn a_layer_keeps_the_horizontal_speed(
        r in 5.0..200.0f64,
        n in 1usize..24,
        t_frac in 0.01..0.5f64,
        step_deg in 0.2..10.0f64,
        rows in prop::collection::vec((-10.0..0.0f64, 100.0..2000.0f64, 1.0..8.0f64, 1.0..20.0f64, 0.0..30.0f64), 24),
        next in prop::option::of(0.0..40.0f64),
    ) {
        let mu = 360.0 / n as f64;
        let ring = Ring::new(Length(r), n, Angle::from_deg(mu * t_frac)).unwrap();
        let rows = &rows[..n];
        let table = SegmentTable::new(rows.iter().map(|&(d, p, w, v, _)| SegmentProcess {
            defocus: Length(d), power: Power::from_watts(p), width: Length(w), speed: Speed(v),
        }).collect()).unwrap();
        let speeds: Vec<Speed> = rows.iter().map(|row| Speed(row.3 * 1.1)).collect();
        let base: Vec<Length> = rows.iter().map(|row| Length(row.4)).collect();
        let spec = LayerSpec { speeds: &speeds, base: &base, next_start: next.map(Length) };
        let pts = ring.layer(&table, &spec, Angle::from_deg(step_deg)).unwrap();
        let arc_at = |p: &RingPoint| p.pos[1].atan2(p.pos[0]).rem_euclid(TAU);
        for w in pts.windows(2) {
            let (a, b) = (&w[0], &w[1]);
            let (ta, mut tb) = (arc_at(a), arc_at(b));
            if tb <= ta { tb += TAU; }
            let dtheta = tb - ta;
            prop_assert!(dtheta > 0.0 && dtheta <= step_deg.to_radians() * (1.0 + 1e-9) + 1e-12);
            let v = speeds[a.segment].0;
            if a.transition {
                let tan_g = (b.focus_z() - a.focus_z()) / (r * dtheta);
                prop_assert!((a.speed.0 - v / (1.0 / (1.0 + tan_g * tan_g).sqrt())).abs() < 1e-6 * v * (1.0 + tan_g.abs()));
            } else {
                prop_assert_eq!(a.speed.0, v);
                prop_assert_eq!(a.defocus, Length(rows[a.segment].0));
                prop_assert_eq!(a.pos[2], base[a.segment].0);
            }
            prop_assert!((a.pos[0].hypot(a.pos[1]) - r).abs() < 1e-9 * r);
            prop_assert!(a.laser_on);
        }
        let end = pts.last().unwrap();
        match next {
            Some(z) => {
                prop_assert!((end.pos[2] - z).abs() < 1e-12);
                prop_assert_eq!(end.defocus, table.rows()[0].defocus);
            }
            None => prop_assert_eq!(end.pos[2], base[n - 1].0),
        }
        prop_assert!((arc_at(end) - 0.0).abs() < 1e-9 || (arc_at(end) - TAU).abs() < 1e-9);
    }

    /// The simulation's totals are the sums of its heights and its speeds stay
    /// inside the clamp, whatever the gains.
    #[test]
    fn totals_add_up_and_speeds_stay_clamped(
        kp in -50.0..50.0f64, ki in -20.0..20.0f64, drift in -0.003..0.01f64,
        factors in prop::collection::vec(0.5..2.0f64, 10),
    ) {
        let c = paper::controller_with(SpeedPerLength(kp), SpeedPerLength(ki)).unwrap();
        let speeds = paper::table1().unwrap().speeds();
        let plant = Plant::calibrated(Length(0.23), &speeds, drift).unwrap().scaled(&factors).unwrap();
        let sim = simulate(&c, &plant, &speeds, NonZeroUsize::new(130).unwrap()).unwrap();
        let mut sums = [0.0; 10];
        for s in sim.samples() {
            sums[s.segment] += s.height.0;
            prop_assert!((s.total.0 - sums[s.segment]).abs() < 1e-9);
            prop_assert!(s.speed.0 >= 1.9 && s.speed.0 <= 20.0);
            prop_assert!(s.height.0 > 0.0);
        }
    }

    /// Garbage in, a typed error out — never a panic.
    #[test]
    fn no_input_panics(
        r in any::<f64>(), n in any::<usize>(), t in any::<f64>(), step in any::<f64>(),
        lo in any::<f64>(), hi in any::<f64>(), kp in any::<f64>(), target in any::<f64>(),
        v in any::<f64>(), layers in 1usize..5,
    ) {
        let _ = Ring::new(Length(r), n % 5000, Angle(t)).map(|ring| {
            let table = paper::table1().unwrap();
            let _ = ring.first_layer(&table, Length(target), Angle(step));
            let _ = ring.fastest_transition(&table, Length(target), Speed(v));
        });
        if let Ok(clamp) = Clamp::new(Speed(lo), Speed(hi)) {
            if let Ok(c) = Controller::new(SpeedPerLength(kp), SpeedPerLength(kp), Length(target), clamp) {
                let _ = analyse(&c, &[Speed(v)], NonZeroUsize::new(layers).unwrap());
                if let Ok(plant) = Plant::calibrated(Length(target), &[Speed(v)], 0.0) {
                    let _ = simulate(&c, &plant, &[Speed(v)], NonZeroUsize::new(layers).unwrap());
                }
            }
        }
    }
}
