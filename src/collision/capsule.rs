//! Capsules — a segment and a radius, what a robot's arm links are taken as
//! (docs/collision.md, *The arm*) — and their distances to the solids of
//! the cell: a box, an upright cylinder, a disc (a positioner's faceplate).
//!
//! A point's distance to each solid is closed-form. Along a segment it is
//! a convex function of the segment's parameter (the distance to a convex
//! set is convex, and a segment is an affine map), so its least is found
//! by golden-section search: no mesh, no library, a few dozen evaluations.

use super::head::{add, dot, scale, sub};

/// A segment with a radius: everything within `r` of the segment `a`–`b`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Capsule {
    /// One end of its axis, mm.
    pub a: [f64; 3],
    /// The other end, mm.
    pub b: [f64; 3],
    /// Its radius, mm.
    pub r: f64,
}

/// The distance from `p` to the segment `a`–`b`.
pub fn segment_point(a: [f64; 3], b: [f64; 3], p: [f64; 3]) -> f64 {
    let ab = sub(b, a);
    let len2 = dot(ab, ab);
    let t = if len2 > 0.0 {
        (dot(sub(p, a), ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let q = sub(add(a, scale(ab, t)), p);
    dot(q, q).sqrt()
}

/// The distance from `p` to the box `lo`–`hi` (0 inside).
pub fn box_point(lo: [f64; 3], hi: [f64; 3], p: [f64; 3]) -> f64 {
    let d: [f64; 3] = std::array::from_fn(|k| (lo[k] - p[k]).max(p[k] - hi[k]).max(0.0));
    dot(d, d).sqrt()
}

/// The distance from a point `h` along an axis and `rho` from it to the
/// solid cylinder between `h0` and `h1` along that axis of radius `r`
/// (0 inside).
pub fn cylinder_point(h: f64, rho: f64, [h0, h1]: [f64; 2], r: f64) -> f64 {
    let dh = (h0 - h).max(h - h1).max(0.0);
    let dr = (rho - r).max(0.0);
    dh.hypot(dr)
}

/// The least of `f` over the segment `a`–`b`, and the point there: `f` is
/// a point's distance to a convex solid, convex along the segment, so a
/// golden-section search finds it (to within 10⁻⁹ of the segment's length).
pub fn least_along(a: [f64; 3], b: [f64; 3], f: impl Fn([f64; 3]) -> f64) -> (f64, [f64; 3]) {
    let at = |t: f64| add(a, scale(sub(b, a), t));
    let g = (5f64.sqrt() - 1.0) / 2.0;
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    let mut x1 = hi - g * (hi - lo);
    let mut x2 = lo + g * (hi - lo);
    let (mut f1, mut f2) = (f(at(x1)), f(at(x2)));
    while hi - lo > 1e-9 {
        if f1 <= f2 {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - g * (hi - lo);
            f1 = f(at(x1));
        } else {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + g * (hi - lo);
            f2 = f(at(x2));
        }
    }
    // The ends too: a flat stretch at the least (inside the solid) or a
    // least at an end is found exactly.
    [(f1, at(x1)), (f(a), a), (f(b), b)]
        .into_iter()
        .min_by(|x, y| x.0.total_cmp(&y.0))
        .unwrap_or((f1, at(x1)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn closed_forms_at_known_points() {
        assert!((segment_point([0.0; 3], [10.0, 0.0, 0.0], [5.0, 3.0, 4.0]) - 5.0).abs() < 1e-12);
        assert!((segment_point([0.0; 3], [10.0, 0.0, 0.0], [13.0, 4.0, 0.0]) - 5.0).abs() < 1e-12);
        assert_eq!(box_point([0.0; 3], [1.0; 3], [0.5; 3]), 0.0);
        assert!((box_point([0.0; 3], [1.0; 3], [4.0, 5.0, 0.5]) - 5.0).abs() < 1e-12);
        assert_eq!(cylinder_point(5.0, 1.0, [0.0, 10.0], 2.0), 0.0);
        assert!((cylinder_point(13.0, 6.0, [0.0, 10.0], 2.0) - 5.0).abs() < 1e-12);
    }

    proptest! {
        /// The search's least over a segment against the segment sampled
        /// every 1/20000 of it: never above it, never below it by more
        /// than the sampling's step allows.
        #[test]
        fn the_search_finds_the_sampled_least(
            a in prop::array::uniform3(-50.0f64..50.0),
            b in prop::array::uniform3(-50.0f64..50.0),
            lo in prop::array::uniform3(-20.0f64..0.0),
            size in prop::array::uniform3(1.0f64..30.0),
        ) {
            let hi: [f64; 3] = std::array::from_fn(|k| lo[k] + size[k]);
            let f = |p: [f64; 3]| box_point(lo, hi, p);
            let (got, at) = least_along(a, b, f);
            prop_assert!((f(at) - got).abs() < 1e-12);
            let n = 20_000;
            let len = super::super::head::dist(a, b);
            let sampled = (0..=n)
                .map(|k| f(add(a, scale(sub(b, a), k as f64 / n as f64))))
                .fold(f64::INFINITY, f64::min);
            prop_assert!(got <= sampled + 1e-6, "{got} vs {sampled}");
            prop_assert!(got >= sampled - len / n as f64 - 1e-6, "{got} vs {sampled}");
        }
    }
}
