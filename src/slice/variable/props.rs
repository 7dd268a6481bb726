//! Property tests of the whole module against the formulas, written out
//! again here independently of the code under test: the layer-count bounds
//! by brute force over every count, the segment error by dense sampling and
//! a sampled median, the overlap balance with the circular segment's area
//! in its `acos` form (checked against the paper's corrected eq. 3).

use super::input::{HeightRange, Positive};
use super::layers::{choose_layers, layer_height, layer_range, layer_top, LayerCount, LayerError};
use super::overlap::{lay_tracks, recursion, CrossSection};
use super::profile::TrackProfile;
use super::segments::{equal_segments, segment, SegmentSpec};
use crate::units::Length;
use proptest::prelude::*;
use std::num::{NonZeroU32, NonZeroUsize};

fn range(lo: f64, hi: f64) -> HeightRange {
    HeightRange::new("test", Length(lo), Length(hi)).unwrap()
}

/// Whether `n` layers lay every point of `tops` within `h_min ..= h_max`
/// (with the checks' 1e-9 slack).
fn fits(tops: &[f64], n: u32, h_min: f64, h_max: f64) -> bool {
    tops.iter().all(|&t| {
        let h = t / n as f64;
        h >= h_min * (1.0 - 1e-9) && h <= h_max * (1.0 + 1e-9)
    })
}

/// Random tops: a sampled plane `a + b·x + c·y` over a 60 × 20 mm footprint
/// plus scattered points, so both ramps and arbitrary tops are covered.
fn tops() -> impl Strategy<Value = Vec<f64>> {
    (
        1.0..40.0f64,
        0.0..0.3f64,
        0.0..0.3f64,
        prop::collection::vec(1.0..60.0f64, 0..6),
    )
        .prop_map(|(a, b, c, extra)| {
            let mut v: Vec<f64> = (0..=12)
                .flat_map(|i| (0..=4).map(move |j| a + b * 5.0 * i as f64 + c * 5.0 * j as f64))
                .collect();
            v.extend(extra);
            v
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn layer_counts_meet_the_bounds(tops in tops(), h_min in 0.2..1.5f64, ratio in 1.02..3.0f64) {
        let h_max = h_min * ratio;
        let top = HeightRange::of("top", tops.iter().map(|&t| Length(t))).unwrap();
        let bead = range(h_min, h_max);
        // Every count up to well past the range, by brute force.
        let limit = (top.high().0 / h_min).ceil() as u32 + 2;
        let working: Vec<u32> = (1..=limit).filter(|&n| fits(&tops, n, h_min, h_max)).collect();
        match layer_range(top, bead) {
            Ok(r) => {
                prop_assert_eq!(working.first().copied(), Some(r.fewest().get()));
                prop_assert_eq!(working.last().copied(), Some(r.most().get()));
                prop_assert_eq!(working.len() as u32, r.most().get() - r.fewest().get() + 1);
                let n = choose_layers(top, bead, LayerCount::Auto).unwrap();
                prop_assert_eq!(n, r.fewest());
                for &t in &tops {
                    // Σ of the layer heights at a point is its top.
                    let sum: f64 = (0..n.get()).map(|_| layer_height(Length(t), n).0).sum();
                    prop_assert!((sum - t).abs() <= 1e-6 * t);
                    prop_assert_eq!(layer_top(Length(t), n, n.get() - 1).0, t);
                    // Each layer is laid on the planned top of the one below.
                    for i in 1..n.get() {
                        let d = layer_top(Length(t), n, i).0 - layer_top(Length(t), n, i - 1).0;
                        prop_assert!(bead.contains(Length(d)));
                    }
                }
            }
            Err(LayerError::NoCount(e)) => {
                prop_assert!(working.is_empty(), "{:?} work", working);
                // Each fix alone makes a count exist.
                let ok = |top: HeightRange, bead: HeightRange| layer_range(top, bead).is_ok();
                if let Some(hi) = e.top_high_at_most() {
                    prop_assert!(ok(range(top.low().0, hi.0), bead));
                }
                if let Some(lo) = e.top_low_at_least() {
                    prop_assert!(ok(range(lo.0, top.high().0), bead));
                }
                // A top of one height in a gap between counts has no top fix,
                // but a bead fix always exists.
                prop_assert!(ok(top, range(e.bead_low_at_most().0, h_max)));
                if let Some(hi) = e.bead_high_at_least() {
                    prop_assert!(ok(top, range(h_min, hi.0)));
                }
                // The ratio is necessary: a bead spanning less cannot work.
                if e.ratio_available() < e.ratio_needed() {
                    prop_assert!(working.is_empty());
                }
            }
            Err(other) => prop_assert!(false, "{:?}", other),
        }
    }

    #[test]
    fn a_declared_count_works_exactly_when_it_fits(tops in tops(), h_min in 0.2..1.5f64, ratio in 1.02..3.0f64, n in 1u32..200) {
        let top = HeightRange::of("top", tops.iter().map(|&t| Length(t))).unwrap();
        let n = NonZeroU32::new(n).unwrap();
        let got = choose_layers(top, range(h_min, h_min * ratio), LayerCount::Exactly(n));
        prop_assert_eq!(got.is_ok(), fits(&tops, n.get(), h_min, h_min * ratio));
    }
}

/// `H` at `x` on the polyline `pts`, written again for the tests.
fn interp(pts: &[(f64, f64)], x: f64) -> f64 {
    let j = pts
        .iter()
        .position(|p| p.0 >= x)
        .unwrap_or(pts.len() - 1)
        .max(1);
    let ((x0, h0), (x1, h1)) = (pts[j - 1], pts[j]);
    h0 + (h1 - h0) * ((x - x0) / (x1 - x0)).clamp(0.0, 1.0)
}

/// `E(m)` by sampling each equal segment at `K` midpoints and taking the
/// samples' median as the segment's height: the discrete L1 optimum.
fn sampled_error(pts: &[(f64, f64)], m: usize) -> f64 {
    const K: usize = 400;
    let (x0, l) = (pts[0].0, pts[pts.len() - 1].0 - pts[0].0);
    let mut area = 0.0;
    for j in 0..m {
        let (a, b) = (
            x0 + l * j as f64 / m as f64,
            x0 + l * (j + 1) as f64 / m as f64,
        );
        let mut s: Vec<f64> = (0..K)
            .map(|k| interp(pts, a + (b - a) * (k as f64 + 0.5) / K as f64))
            .collect();
        s.sort_by(f64::total_cmp);
        let med = s[K / 2];
        area += s.iter().map(|h| (h - med).abs()).sum::<f64>() * (b - a) / K as f64;
    }
    area / l
}

/// Random polyline tops: 2–7 points, 1–30 mm apart, heights 1–30 mm.
fn polyline() -> impl Strategy<Value = Vec<(f64, f64)>> {
    prop::collection::vec((1.0..30.0f64, 1.0..30.0f64), 2..7).prop_map(|v| {
        let mut x = 0.0;
        v.into_iter()
            .enumerate()
            .map(|(i, (dx, h))| {
                if i > 0 {
                    x += dx;
                }
                (x, h)
            })
            .collect()
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn the_segment_count_is_the_smallest_that_meets_the_tolerance(pts in polyline(), tol in 0.05..3.0f64) {
        let p = TrackProfile::new(pts.iter().map(|&(x, h)| (Length(x), Length(h)))).unwrap();
        let l = p.length().0;
        let spec = SegmentSpec {
            tolerance: Positive::new("tol", Length(tol)).unwrap(),
            min_length: Positive::new("min", Length(l / 40.0)).unwrap(),
        };
        // Sampling the median costs ~(range)/K of accuracy.
        let slack = 0.01 * tol;
        match segment(&p, spec) {
            Ok(s) => {
                let m = s.segments.len();
                prop_assert!((s.error.0 - sampled_error(&pts, m)).abs() <= slack);
                prop_assert!(sampled_error(&pts, m) <= tol + slack);
                for fewer in 1..m {
                    prop_assert!(sampled_error(&pts, fewer) > tol - slack, "{} of {} meets it", fewer, m);
                }
                // The segments tile the track.
                prop_assert_eq!(s.segments[0].start.0, pts[0].0);
                prop_assert_eq!(s.segments[m - 1].end.0, pts[pts.len() - 1].0);
                prop_assert!(s.segments.windows(2).all(|w| w[0].end == w[1].start));
            }
            Err(super::segments::SegmentError::TooShort(e)) => {
                for m in 1..=e.allowed.get() {
                    prop_assert!(sampled_error(&pts, m) > tol - slack);
                }
                let best = (1..=e.allowed.get()).map(|m| sampled_error(&pts, m)).fold(f64::INFINITY, f64::min);
                prop_assert!((e.workable.0 - best).abs() <= slack);
            }
            Err(other) => prop_assert!(false, "{:?}", other),
        }
    }

    #[test]
    fn a_ramp_needs_a_quarter_of_its_rise_per_tolerance(l in 20.0..200.0f64, h0 in 1.0..30.0f64, rise in -15.0..15.0f64, tol in 0.02..1.0f64) {
        let p = TrackProfile::new([(Length(0.0), Length(h0)), (Length(l), Length(h0 + rise))]).unwrap();
        let m = super::ceil_slack(rise.abs() / (4.0 * tol)).max(1.0) as usize;
        prop_assume!(m <= 400);
        let spec = SegmentSpec {
            tolerance: Positive::new("tol", Length(tol)).unwrap(),
            min_length: Positive::new("min", Length(l / 400.0)).unwrap(),
        };
        let s = segment(&p, spec).unwrap();
        prop_assert_eq!(s.segments.len(), m);
        prop_assert!((s.error.0 - rise.abs() / (4.0 * m as f64)).abs() <= 1e-9 * (1.0 + rise.abs()));
        // The L1-best height of a straight segment is its midpoint value.
        for g in &s.segments {
            let mid = h0 + rise * (g.start.0 + g.end.0) / (2.0 * l);
            prop_assert!((g.height.0 - mid).abs() <= 1e-9 * (1.0 + mid.abs()));
        }
        if m > 1 {
            let fewer = equal_segments(&p, NonZeroUsize::new(m - 1).unwrap());
            prop_assert!(fewer.error.0 > tol);
        }
    }
}

/// The paper's eq. 3, corrected (W the chord, H the height): a circular
/// segment by its `asin` form, right only for `h ≤ W/2`.
fn paper_area(w: f64, h: f64) -> f64 {
    let r = (4.0 * h * h + w * w) / (8.0 * h);
    r * r * (4.0 * h * w / (4.0 * h * h + w * w)).asin() - w * (w * w - 4.0 * h * h) / (16.0 * h)
}

/// The circular segment of chord `w` and height `h` for every `h`:
/// `R²/2·(θ − sin θ)` with the central angle `θ = 2·acos((R − h)/R)`.
fn circular_segment(w: f64, h: f64) -> f64 {
    let r = (4.0 * h * h + w * w) / (8.0 * h);
    let theta = 2.0 * ((r - h) / r).clamp(-1.0, 1.0).acos();
    r * r / 2.0 * (theta - theta.sin())
}

#[test]
fn the_two_area_formulas_agree_where_both_hold() {
    for h in [0.1, 0.6455, 1.0, 1.2] {
        assert!((paper_area(2.4, h) - circular_segment(2.4, h)).abs() < 1e-12);
    }
    // Past W/2 the asin form turns back; seed 003's own h_max = 1.28 mm
    // with W = 2.4 mm is such a height.
    assert!(paper_area(2.4, 1.28) < circular_segment(2.4, 1.28));
    assert!((circular_segment(2.4, 1.2) - std::f64::consts::PI * 1.44 / 2.0).abs() < 1e-12);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn every_pair_of_tracks_balances(w in 1.5..4.0f64, tracks in 1.2..12.0f64, a in 0.15..0.8f64, b in 0.15..0.8f64) {
        let l0 = w * (1.0 + tracks * 0.7);
        let (first, far) = (a * w, b * w);
        let section = CrossSection::new(Length(l0), Length(first), Length(far)).unwrap();
        let bead = Positive::new("w", Length(w)).unwrap();
        // Linear from edge to edge, the edge value beyond.
        let line = |y: f64| first + (far - first) * (y / l0).clamp(0.0, 1.0);

        // The unstretched recursion is eq. 4 itself on every pair.
        let raw = recursion(&section, bead, Length(l0 - w / 2.0));
        for p in raw.windows(2) {
            let (h0, h1) = (line(p[0].0), line(p[1].0));
            let c = p[1].0 - p[0].0;
            let lhs = c * (h0 + h1);
            let rhs = circular_segment(w, h0) + circular_segment(w, h1);
            prop_assert!((lhs - rhs).abs() <= 1e-9 * rhs, "{} vs {}", lhs, rhs);
        }

        // The closed layout: first and last centre half a bead inside the
        // edges, heights on the planned line, one stretch on every pair.
        let t = lay_tracks(&section, bead).unwrap();
        let n = t.centres.len();
        prop_assert!((t.centres[0].0 - w / 2.0).abs() <= 1e-12);
        prop_assert!((t.centres[n - 1].0 - (l0 - w / 2.0)).abs() <= 1e-8 * l0);
        prop_assert!(t.centres.windows(2).all(|c| c[1].0 > c[0].0));
        for (y, h) in t.centres.iter().zip(&t.heights) {
            prop_assert!((h.0 - line(y.0)).abs() <= 1e-12 * (1.0 + h.0));
        }
        for k in 0..n - 1 {
            let c = t.centres[k + 1].0 - t.centres[k].0;
            let (h0, h1) = (t.heights[k].0, t.heights[k + 1].0);
            let lhs = c * (h0 + h1);
            let rhs = t.stretch * (circular_segment(w, h0) + circular_segment(w, h1));
            prop_assert!((lhs - rhs).abs() <= 1e-9 * rhs, "pair {}: {} vs {}", k, lhs, rhs);
        }
        // Of the two counts around the recursion's, the closure stretches by
        // at most about one spacing in n − 1.
        prop_assert!((t.stretch - 1.0).abs() <= 1.2 / (n - 1) as f64, "{} over {}", t.stretch, n - 1);
    }
}
