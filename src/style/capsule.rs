//! Exact geometry of one segment against one capsule (a segment's band with round
//! ends): the parameter interval of the segment that lies inside, and point
//! distances. Everything here returns "nothing" rather than NaN, so callers never
//! have to reason about non-finite intermediate values.

/// A 2D point in mm.
pub(crate) type P = [f64; 2];

fn sub(a: P, b: P) -> P {
    [a[0] - b[0], a[1] - b[1]]
}

fn dot(a: P, b: P) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

fn cross(a: P, b: P) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// Whether both coordinates are finite.
pub(crate) fn finite(p: P) -> bool {
    p[0].is_finite() && p[1].is_finite()
}

/// Euclidean distance between two points (`hypot`, so no premature overflow).
pub(crate) fn dist(a: P, b: P) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// Distance from `p` to the segment `cd` (a point when `c == d`).
pub(crate) fn point_segment_dist(p: P, c: P, d: P) -> f64 {
    let u = sub(d, c);
    let l2 = dot(u, u);
    let t = if l2 > 0.0 {
        (dot(sub(p, c), u) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    // `clamp` keeps NaN, and a NaN `t` would make the foot NaN: fall back to `c`.
    let t = if t.is_nan() { 0.0 } else { t };
    dist(p, [c[0] + t * u[0], c[1] + t * u[1]])
}

/// `[lo, hi]` when it is a real, non-empty interval (NaN bounds are not).
fn interval(lo: f64, hi: f64) -> Option<(f64, f64)> {
    (lo <= hi).then_some((lo, hi))
}

/// The `t` with `lo ≤ α + β·t ≤ hi`, intersected with `[0, 1]`.
fn linear(alpha: f64, beta: f64, lo: f64, hi: f64) -> Option<(f64, f64)> {
    if beta == 0.0 {
        // Constant along the segment: all of it or none of it.
        return (lo <= alpha && alpha <= hi).then_some((0.0, 1.0));
    }
    let (t0, t1) = ((lo - alpha) / beta, (hi - alpha) / beta);
    let (t0, t1) = if beta > 0.0 { (t0, t1) } else { (t1, t0) };
    interval(t0.max(0.0), t1.min(1.0))
}

/// The `t ∈ [0, 1]` where `A + t·dir` is within `r` of `centre`: the roots of
/// `|dir|²t² + 2(w·dir)t + |w|² − r² ≤ 0` (w = A − centre), computed in the
/// cancellation-free form (one root from `q`, the other as `c/q`).
fn disc(a: P, dir: P, centre: P, r: f64) -> Option<(f64, f64)> {
    let w = sub(a, centre);
    let qa = dot(dir, dir);
    let qb = dot(w, dir);
    let qc = dot(w, w) - r * r;
    let d = qb * qb - qa * qc;
    if d.is_nan() || d < 0.0 || qa.is_nan() || qa <= 0.0 {
        return None;
    }
    let q = -(qb + qb.signum() * d.sqrt());
    let (t0, t1) = if q == 0.0 {
        // qb = 0 and d = 0, so qc = 0: A touches the circle tangentially.
        (0.0, 0.0)
    } else {
        let (r0, r1) = (q / qa, qc / q);
        (r0.min(r1), r0.max(r1))
    };
    interval(t0.max(0.0), t1.min(1.0))
}

/// The `t ∈ [0, 1]` where `A + t·(B − A)` lies within `r` of the segment `CD` — the
/// capsule around `CD`, a convex set, so the answer is one interval (or none).
///
/// Exact up to rounding: the capsule is the union of the rectangle over `CD`
/// (half-width `r`) and the discs at `C` and `D`; each piece gives an interval of
/// `t` in closed form, and since their union is convex along a line, it is the
/// hull of the pieces. Returns `None` for a degenerate `AB` (no length to cover)
/// and whenever arithmetic overflows into NaN.
pub(crate) fn capsule_interval(a: P, b: P, c: P, d: P, r: f64) -> Option<(f64, f64)> {
    let dir = sub(b, a);
    let len2 = dot(dir, dir);
    if len2.is_nan() || len2 <= 0.0 || r.is_nan() || r < 0.0 {
        return None;
    }
    let mut pieces = [disc(a, dir, c, r), disc(a, dir, d, r), None];
    let u = sub(d, c);
    let l2 = dot(u, u);
    if l2 > 0.0 {
        // The rectangle: projection on CD within [0, |CD|²] (unnormalised),
        // signed distance from the line CD within ±r (scaled by |CD|).
        let w = sub(a, c);
        let rl = r * l2.sqrt();
        pieces[2] = linear(dot(w, u), dot(dir, u), 0.0, l2).and_then(|(s0, s1)| {
            linear(cross(w, u), cross(dir, u), -rl, rl)
                .and_then(|(q0, q1)| interval(s0.max(q0), s1.min(q1)))
        });
    }
    let (lo, hi) = pieces
        .iter()
        .flatten()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &(s, e)| {
            (lo.min(s), hi.max(e))
        });
    interval(lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: (f64, f64), b: (f64, f64)) -> bool {
        (a.0 - b.0).abs() < 1e-12 && (a.1 - b.1).abs() < 1e-12
    }

    #[test]
    fn parallel_inside_is_whole_segment() {
        let i = capsule_interval([0.0, 0.5], [10.0, 0.5], [-1.0, 0.0], [11.0, 0.0], 1.0);
        assert_eq!(i, Some((0.0, 1.0)));
    }

    #[test]
    fn perpendicular_crossing_is_two_r() {
        // From y = −5 to y = 5 across the x axis, band ±1: t ∈ [0.4, 0.6].
        let i = capsule_interval([3.0, -5.0], [3.0, 5.0], [0.0, 0.0], [10.0, 0.0], 1.0).unwrap();
        assert!(close(i, (0.4, 0.6)), "{i:?}");
    }

    #[test]
    fn round_end_adds_the_cap() {
        // Collinear, running past D = (10, 0) with r = 1: covered up to x = 11.
        let i = capsule_interval([5.0, 0.0], [15.0, 0.0], [0.0, 0.0], [10.0, 0.0], 1.0).unwrap();
        assert!(close(i, (0.0, 0.6)), "{i:?}");
        // Offset by 0.6: the cap reaches sqrt(1 − 0.36) = 0.8 past D.
        let i = capsule_interval([5.0, 0.6], [15.0, 0.6], [0.0, 0.0], [10.0, 0.0], 1.0).unwrap();
        assert!(close(i, (0.0, 0.58)), "{i:?}");
    }

    #[test]
    fn degenerate_band_is_a_disc() {
        let i = capsule_interval([-2.0, 0.0], [2.0, 0.0], [0.0, 0.0], [0.0, 0.0], 1.0).unwrap();
        assert!(close(i, (0.25, 0.75)), "{i:?}");
    }

    #[test]
    fn outside_is_none() {
        let i = capsule_interval([0.0, 2.0], [10.0, 2.0], [0.0, 0.0], [10.0, 0.0], 1.0);
        assert_eq!(i, None);
    }

    #[test]
    fn non_finite_gives_none() {
        let n = f64::NAN;
        assert_eq!(
            capsule_interval([n, 0.0], [1.0, 0.0], [0.0, 0.0], [1.0, 0.0], 1.0),
            None
        );
        assert_eq!(
            capsule_interval([0.0, 0.0], [1.0, 0.0], [0.0, 0.0], [1.0, 0.0], n),
            None
        );
        // Overflowing arithmetic may lose the answer but never yields NaN bounds.
        let big = 1e300;
        if let Some((s, e)) =
            capsule_interval([-big, 0.0], [big, 0.0], [0.0, big], [0.0, -big], big)
        {
            assert!(
                (0.0..=1.0).contains(&s) && (s..=1.0).contains(&e),
                "{s} {e}"
            );
        }
    }

    #[test]
    fn point_distance() {
        assert_eq!(point_segment_dist([5.0, 3.0], [0.0, 0.0], [10.0, 0.0]), 3.0);
        assert_eq!(
            point_segment_dist([13.0, 4.0], [0.0, 0.0], [10.0, 0.0]),
            5.0
        );
        assert_eq!(point_segment_dist([3.0, 4.0], [0.0, 0.0], [0.0, 0.0]), 5.0);
    }
}
