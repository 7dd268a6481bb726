//! Bands: the set of points within a half-width of some centre lines, and how
//! much of a track's length lies inside them — exactly, from the capsule
//! intervals of each track segment, not by sampling.

use super::capsule::{capsule_interval, dist, finite, point_segment_dist, P};
use super::grid::{Seg, SegmentGrid};
use super::StyleId;

/// Centre lines (each tagged with a style) and a half-width, indexed for queries.
#[derive(Debug)]
pub(crate) struct Bands {
    segs: Vec<Seg>,
    grid: SegmentGrid,
    half_width: f64,
    /// The tags present, sorted, when the half-width is so large (its square
    /// overflows) that every band is the whole plane; empty otherwise.
    everywhere: Vec<StyleId>,
}

/// How much of a track lies in the bands: its total length, and per tag the
/// length inside the union of that tag's bands.
#[derive(Debug, Default)]
pub(crate) struct Coverage {
    /// Length of the track's finite segments.
    pub total: f64,
    /// `(tag, covered length)`, sorted by tag, only tags that cover something.
    pub covered: Vec<(StyleId, f64)>,
}

impl Coverage {
    /// Fraction (0..=1) of the track inside the tag's bands; 0 for a track of no
    /// (or overflowing) length, which has nothing to cover.
    pub(crate) fn fraction(&self, tag: StyleId) -> f64 {
        let covered = match self.covered.binary_search_by_key(&tag, |c| c.0) {
            Ok(i) => self.covered[i].1,
            Err(_) => 0.0,
        };
        ratio(covered, self.total)
    }

    fn add(&mut self, tag: StyleId, len: f64) {
        match self.covered.binary_search_by_key(&tag, |c| c.0) {
            Ok(i) => self.covered[i].1 += len,
            Err(i) => self.covered.insert(i, (tag, len)),
        }
    }
}

/// `covered / total` clamped to 0..=1 (rounding can overshoot 1), 0 when it is
/// not a number.
pub(crate) fn ratio(covered: f64, total: f64) -> f64 {
    if total > 0.0 && total.is_finite() {
        let f = covered / total;
        if f.is_nan() {
            0.0
        } else {
            f.clamp(0.0, 1.0)
        }
    } else {
        0.0
    }
}

/// The finite segments of a polyline (with its closing segment when `closed`); a
/// lone finite point is a degenerate segment, so its band is a disc.
pub(crate) fn segments(line: &[P], closed: bool) -> impl Iterator<Item = (P, P)> + '_ {
    let lone = (line.len() == 1).then(|| (line[0], line[0]));
    let close = (closed && line.len() > 1).then(|| (line[line.len() - 1], line[0]));
    line.windows(2)
        .map(|w| (w[0], w[1]))
        .chain(close)
        .chain(lone)
        .filter(|&(a, b)| finite(a) && finite(b))
}

impl Bands {
    /// The bands of half-width `half_width` around `lines` (closed loops when
    /// `closed`). A NaN or negative half-width is no band at all; one so large that
    /// its square overflows (`+inf` included) makes each band the whole plane.
    pub(crate) fn new<'a>(
        lines: impl IntoIterator<Item = (&'a [P], StyleId)>,
        closed: bool,
        half_width: f64,
    ) -> Self {
        let valid = half_width >= 0.0;
        let mut segs: Vec<Seg> = lines
            .into_iter()
            .filter(|_| valid)
            .flat_map(|(line, tag)| segments(line, closed).map(move |(a, b)| Seg { a, b, tag }))
            .collect();
        let mut everywhere = Vec::new();
        if valid && !(half_width * half_width).is_finite() {
            // The capsule arithmetic would overflow; the answer is known anyway.
            everywhere = segs.iter().map(|s| s.tag).collect();
            everywhere.sort_unstable();
            everywhere.dedup();
            segs.clear();
        }
        let half_width = if valid && everywhere.is_empty() {
            half_width
        } else {
            0.0
        };
        let grid = SegmentGrid::new(&segs, half_width);
        Bands {
            segs,
            grid,
            half_width,
            everywhere,
        }
    }

    /// How much of `track` lies in the bands, per tag. Segments with a non-finite
    /// end are skipped (they have no measurable length).
    ///
    /// Cost: per track segment, the grid cells it crosses plus the candidate
    /// segments found there (each one capsule test and a sort of the intervals).
    pub(crate) fn coverage(&self, track: &[P]) -> Coverage {
        let mut cov = Coverage::default();
        let mut cand = Vec::new();
        let mut ivs: Vec<(StyleId, f64, f64)> = Vec::new();
        for (a, b) in segments(track, false) {
            let len = dist(a, b);
            if len.is_nan() || len <= 0.0 {
                continue;
            }
            cov.total += len;
            for &tag in &self.everywhere {
                cov.add(tag, len);
            }
            self.grid.candidates(a, b, &mut cand);
            ivs.clear();
            ivs.extend(cand.iter().filter_map(|&k| {
                let s = &self.segs[k];
                capsule_interval(a, b, s.a, s.b, self.half_width).map(|(t0, t1)| (s.tag, t0, t1))
            }));
            ivs.sort_unstable_by(|x, y| x.0.cmp(&y.0).then(x.1.total_cmp(&y.1)));
            // Union per tag: merge overlapping intervals, sum what is left.
            let mut i = 0;
            while i < ivs.len() {
                let tag = ivs[i].0;
                let (mut lo, mut hi) = (ivs[i].1, ivs[i].2);
                let mut union = 0.0;
                while i < ivs.len() && ivs[i].0 == tag {
                    let (_, s, e) = ivs[i];
                    if s > hi {
                        union += hi - lo;
                        (lo, hi) = (s, e);
                    } else {
                        hi = hi.max(e);
                    }
                    i += 1;
                }
                union += hi - lo;
                cov.add(tag, union * len);
            }
        }
        cov
    }

    /// Whether `p` lies in some band (distance ≤ half-width to a centre line).
    pub(crate) fn contains(&self, p: P) -> bool {
        if !finite(p) {
            return false;
        }
        if !self.everywhere.is_empty() {
            return true;
        }
        let mut cand = Vec::new();
        self.grid.candidates(p, p, &mut cand);
        cand.iter().any(|&k| {
            let s = &self.segs[k];
            point_segment_dist(p, s.a, s.b) <= self.half_width
        })
    }
}

/// Fraction (0..=1) of the track's length lying within `half_width` of any of
/// `lines` (open polylines in mm; a one-point line is a disc).
///
/// Exact, not sampled: for each track segment `P(t) = A + t(B − A)`, the `t` within
/// `half_width` of a line segment form one interval (the capsule is convex; its
/// rectangle and end discs give closed forms — a quadratic for each disc); the
/// intervals are merged per track segment and their lengths summed.
///
/// A zero-length track (empty, one point, or all points equal) has no length to
/// lie anywhere: the fraction is 0. Segments with a non-finite end are ignored on
/// both sides; a NaN or negative `half_width` is no band (0), one whose square
/// overflows (`+inf`) covers everything. A track length that overflows `f64` gives
/// 0; coordinates so large (≳ 1e150 mm) that squares overflow give some value in
/// 0..=1, never a panic.
///
/// Cost: builds a uniform grid over the lines (O(line segments)), then near-linear
/// in the track's segments for tracks whose segments each meet few line
/// segments. To test many tracks against the same lines, use
/// [`Inheritance`](super::Inheritance), which builds the index once.
pub fn fraction_within(track: &[[f64; 2]], lines: &[&[[f64; 2]]], half_width: f64) -> f64 {
    let bands = Bands::new(lines.iter().map(|l| (*l, 0)), false, half_width);
    bands.coverage(track).fraction(0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn union_of_overlapping_bands_is_counted_once() {
        // Two parallel lines 0.5 apart, band 1: together they cover y ∈ [−1, 1.5],
        // so a perpendicular track from y = −5 to 5 is 2.5/10 inside.
        let l1: &[P] = &[[0.0, 0.0], [10.0, 0.0]];
        let l2: &[P] = &[[0.0, 0.5], [10.0, 0.5]];
        let f = fraction_within(&[[5.0, -5.0], [5.0, 5.0]], &[l1, l2], 1.0);
        assert!((f - 0.25).abs() < 1e-12, "{f}");
    }

    #[test]
    fn tags_are_counted_apart() {
        let l1: &[P] = &[[0.0, 0.0], [10.0, 0.0]];
        let l2: &[P] = &[[0.0, 0.5], [10.0, 0.5]];
        let bands = Bands::new([(l1, 1), (l2, 2)], false, 1.0);
        let cov = bands.coverage(&[[5.0, -5.0], [5.0, 5.0]]);
        assert!((cov.fraction(1) - 0.2).abs() < 1e-12);
        assert!((cov.fraction(2) - 0.2).abs() < 1e-12);
        assert_eq!(cov.fraction(3), 0.0);
    }

    #[test]
    fn closed_loops_include_the_closing_edge() {
        let square: &[P] = &[[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]];
        // Along the left edge (the closing one), 0.5 inside.
        let track = [[0.5, 2.0], [0.5, 8.0]];
        let closed = Bands::new([(square, 0)], true, 1.0);
        assert_eq!(closed.coverage(&track).fraction(0), 1.0);
        let open = Bands::new([(square, 0)], false, 1.0);
        assert_eq!(open.coverage(&track).fraction(0), 0.0);
    }

    #[test]
    fn contains_points() {
        let l: &[P] = &[[0.0, 0.0], [10.0, 0.0]];
        let bands = Bands::new([(l, 0)], false, 1.0);
        assert!(bands.contains([5.0, 1.0]));
        assert!(!bands.contains([5.0, 1.01]));
        assert!(bands.contains([10.6, 0.8]));
        assert!(!bands.contains([f64::NAN, 0.0]));
    }

    #[test]
    fn bad_half_widths() {
        let l: &[P] = &[[0.0, 0.0], [10.0, 0.0]];
        let t = [[1.0, 0.0], [2.0, 0.0]];
        assert_eq!(fraction_within(&t, &[l], f64::NAN), 0.0);
        assert_eq!(fraction_within(&t, &[l], -1.0), 0.0);
        assert_eq!(fraction_within(&t, &[l], f64::INFINITY), 1.0);
        assert_eq!(fraction_within(&t, &[l], 1e200), 1.0);
        assert_eq!(fraction_within(&t, &[], f64::INFINITY), 0.0);
        assert_eq!(fraction_within(&t, &[l], 0.0), 1.0, "on the line itself");
    }
}
