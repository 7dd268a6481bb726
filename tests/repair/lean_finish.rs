//! The report's finish of a fill along a tilted build direction
//! (docs/repair.md, *The report*): the leaning slab of
//! [`super::tilted`], its finished face predicted along its lean.

use super::tilted::{shift, slab_and_model, worn, BASE, HEIGHT, LEAN};
use lmdc::ir::{Point, Program};

/// The distance between the line through `p` along the unit `d` and the
/// segment `a`–`b`, mm: in the plane square to `d`, the point's distance
/// to the segment's shadow.
fn line_to_segment(p: [f64; 3], d: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    let dot = |u: [f64; 3], v: [f64; 3]| u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    let across = |u: [f64; 3]| {
        let k = dot(u, d);
        [u[0] - k * d[0], u[1] - k * d[1], u[2] - k * d[2]]
    };
    let (u, v) = (
        across([a[0] - p[0], a[1] - p[1], a[2] - p[2]]),
        across([b[0] - a[0], b[1] - a[1], b[2] - a[2]]),
    );
    let s = if dot(v, v) > 0.0 {
        (-dot(u, v) / dot(v, v)).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let w = [u[0] + s * v[0], u[1] + s * v[1], u[2] + s * v[2]];
    dot(w, w).sqrt()
}

/// How far back along `d` from `p` the worn surface's formula lies, mm
/// (bisected to a micrometre).
fn depth_along(p: [f64; 3], d: [f64; 3]) -> f64 {
    let below = |t: f64| {
        let q = [p[0] - t * d[0], p[1] - t * d[1], p[2] - t * d[2]];
        q[2] <= worn(q[0], q[1])
    };
    let (mut lo, mut hi) = (0.0, 20.0);
    assert!(below(hi) && !below(lo));
    while hi - lo > 1e-6 {
        let mid = 0.5 * (lo + hi);
        if below(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

/// The least and greatest the layers raise the line through `p` along
/// `d` by, mm: in each layer, the laser-on moves the line crosses (two
/// where moves meet), each raising it by its bead model's rise over the
/// nozzle's share along `d`: counted from the IR's points alone.
fn raised(p: &Program, at: [f64; 3], d: [f64; 3]) -> [f64; 2] {
    let deposit = p.bead.as_ref().unwrap().deposit();
    let mut sum = [0.0, 0.0];
    for layer in &p.layers {
        let mut rises: Vec<f64> = Vec::new();
        for path in &layer.paths {
            for w in path.points.windows(2).filter(|w| w[0].laser_on) {
                let (a, b): (&Point, &Point) = (&w[0], &w[1]);
                if line_to_segment(at, d, a.pos, b.pos) < 1e-4 {
                    rises.push(a.predicted_rise(&deposit, Some(b)));
                }
            }
        }
        if !rises.is_empty() {
            sum[0] += rises.iter().copied().fold(f64::INFINITY, f64::min);
            sum[1] += rises.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        }
    }
    sum
}

/// The slab filled along its lean has a finish: measured along the lean,
/// at places on its face (13.5 mm, within its outline), each place's
/// departure what this test counts from the IR's points along the line
/// through it (the rises of the moves it crosses) less the depth along
/// the lean to the worn surface's formula, within the scan's noise. A
/// prediction from above would mix layers: the places' departures here
/// are under 0.35 mm, a third of a layer.
#[test]
fn a_tilted_fills_finish_is_predicted_along_its_lean() {
    let (program, model) = slab_and_model();
    let p = program.ir();
    let (f, samples) = lmdc::report::finish::sampled(p, &model).expect("a tilted fill's finish");
    let lean = LEAN.to_radians();
    let d = [lean.sin(), 0.0, lean.cos()];
    let along = f.along.expect("measured along the lean");
    for k in 0..3 {
        assert!((along[k] - d[k]).abs() < 1e-9, "{along:?}");
    }
    assert_eq!(f.points, samples.len());
    assert!(f.points > 300, "{}", f.points);
    let face = [BASE[0] + shift(), BASE[1] + shift()];
    let mut worst: f64 = 0.0;
    for s in &samples {
        let at = [s.at[0], s.at[1], s.top];
        assert!((s.top - (10.0 + HEIGHT)).abs() < 0.01, "{s:?}");
        assert!(
            at[0] > face[0] && at[0] < face[1] && at[1].abs() < 10.0,
            "{s:?}"
        );
        let [lo, hi] = raised(p, at, d);
        let depth = depth_along(at, d);
        let (lo, hi) = (lo - depth, hi - depth);
        // The scan's noise and its raster, against the formula.
        assert!(
            s.off > lo - 0.05 && s.off < hi + 0.05,
            "{s:?}: {lo} .. {hi}"
        );
        worst = worst.max(s.off.abs());
    }
    assert!((worst - f.below_mm.max(f.above_mm)).abs() < 1e-12);
    assert!(f.rms_mm < 0.15 && worst < 0.35, "{f:?}");
}
