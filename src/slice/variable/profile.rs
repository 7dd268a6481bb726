//! The target top along one track, `H(x)`: a polyline through sampled
//! points. A top given as a plane is exactly a polyline of its two ends; any
//! other expression is sampled (the slicer samples at its point spacing, so
//! the segmentation sees what the path will see).
//!
//! The one computation on it: the constant height that best replaces `H`
//! over an interval in the L1 sense (eq. 7 with its absolute value) — the
//! median of `H`'s values weighted by length — and the area between the two.

use super::input::{finite, Invalid, Positive};
use crate::units::Length;

/// `H(x)` along a track: points at strictly increasing `x`, finite heights.
#[derive(Clone, Debug, PartialEq)]
pub struct TrackProfile {
    x: Vec<f64>,
    h: Vec<f64>,
}

/// One straight piece of the profile within an interval: heights `u` → `v`
/// over a run `len > 0`.
#[derive(Clone, Copy, Debug)]
struct Piece {
    u: f64,
    v: f64,
    len: f64,
}

impl Piece {
    /// The length of the piece where the height is at most `c`.
    fn below(self, c: f64) -> f64 {
        let (lo, hi) = (self.u.min(self.v), self.u.max(self.v));
        if c >= hi {
            self.len
        } else if c < lo {
            0.0
        } else {
            // lo ≤ c < hi, so hi > lo.
            self.len * (c - lo) / (hi - lo)
        }
    }

    /// `∫ |h − c|` over the piece: a trapezoid, or two triangles when the
    /// piece crosses `c`.
    fn error(self, c: f64) -> f64 {
        let (a, b) = (self.u - c, self.v - c);
        if a * b >= 0.0 {
            self.len * (a + b).abs() / 2.0
        } else {
            // Crosses c at the fraction t = a/(a − b) of its run.
            let t = a / (a - b);
            self.len * (t * a.abs() + (1.0 - t) * b.abs()) / 2.0
        }
    }
}

impl TrackProfile {
    /// A polyline through `points` `(x, H)`: at least two, `x` strictly
    /// increasing, all finite.
    pub fn new(points: impl IntoIterator<Item = (Length, Length)>) -> Result<Self, Invalid> {
        let (mut x, mut h) = (Vec::new(), Vec::new());
        for (i, (px, ph)) in points.into_iter().enumerate() {
            let px = finite("position along the track", px.0)?;
            let ph = finite("top height", ph.0)?;
            if x.last().is_some_and(|&last| px <= last) {
                return Err(Invalid::NotIncreasing {
                    what: "positions along the track",
                    index: i,
                });
            }
            x.push(px);
            h.push(ph);
        }
        if x.len() < 2 {
            return Err(Invalid::Empty {
                what: "the track (fewer than two points)",
            });
        }
        Ok(TrackProfile { x, h })
    }

    /// `f` sampled at `intervals + 1` equally spaced points over `0 ..= length`.
    pub fn sample(
        length: Positive,
        intervals: usize,
        f: impl Fn(Length) -> Length,
    ) -> Result<Self, Invalid> {
        let n = intervals.max(1);
        let l = length.mm();
        TrackProfile::new((0..=n).map(|i| {
            let x = if i == n { l } else { l * i as f64 / n as f64 };
            (Length(x), f(Length(x)))
        }))
    }

    /// Where the track starts.
    pub fn start(&self) -> Length {
        Length(self.x[0])
    }

    /// Its length (> 0).
    pub fn length(&self) -> Length {
        Length(self.x[self.x.len() - 1] - self.x[0])
    }

    /// `H` at `x`, linear between points, the end value beyond the ends.
    pub fn at(&self, x: Length) -> Length {
        let x = x.0;
        let last = self.x.len() - 1;
        if x <= self.x[0] {
            return Length(self.h[0]);
        }
        if x >= self.x[last] {
            return Length(self.h[last]);
        }
        // The first point beyond x; 1 ≤ j ≤ last.
        let j = self.x.partition_point(|&p| p <= x);
        let (x0, x1, h0, h1) = (self.x[j - 1], self.x[j], self.h[j - 1], self.h[j]);
        Length(h0 + (h1 - h0) * (x - x0) / (x1 - x0))
    }

    /// The straight pieces of the profile within `a ..= b`.
    fn pieces(&self, a: f64, b: f64) -> Vec<Piece> {
        let mut cuts = vec![a];
        cuts.extend(self.x.iter().copied().filter(|&p| p > a && p < b));
        cuts.push(b);
        cuts.windows(2)
            .filter(|w| w[1] > w[0])
            .map(|w| Piece {
                u: self.at(Length(w[0])).0,
                v: self.at(Length(w[1])).0,
                len: w[1] - w[0],
            })
            .collect()
    }

    /// The constant height that replaces `H` over `a ..= b` with the least
    /// area between them, and that area `∫ₐᵇ |H − c| dx`. The minimiser of an
    /// L1 distance is a median: `c` with half the interval's length at or
    /// below it. On a straight piece the heights are spread evenly, so the
    /// median is the mean — the value at the interval's midpoint.
    pub fn best_constant(&self, a: Length, b: Length) -> (Length, f64) {
        let (a, b) = (a.0.min(b.0), a.0.max(b.0));
        let pieces = self.pieces(a, b);
        if pieces.is_empty() {
            return (self.at(Length(a)), 0.0);
        }
        let half = pieces.iter().map(|p| p.len).sum::<f64>() / 2.0;
        let below = |c: f64| pieces.iter().map(|p| p.below(c)).sum::<f64>();
        let mut marks: Vec<f64> = pieces.iter().flat_map(|p| [p.u, p.v]).collect();
        marks.sort_by(f64::total_cmp);
        marks.dedup();
        // `below` grows with c, linearly between marks, with steps at the
        // heights of flat pieces. Find the first mark where it reaches half.
        let j = marks.partition_point(|&m| below(m) < half);
        let c = match j {
            0 => marks[0],
            j if j >= marks.len() => marks[marks.len() - 1],
            j => {
                let (m0, m1) = (marks[j - 1], marks[j]);
                let (f0, fmid) = (below(m0), below(0.5 * (m0 + m1)));
                // Its value just below m1, past any step at m1.
                let f1 = f0 + 2.0 * (fmid - f0);
                if f1 > f0 && f1 >= half {
                    m0 + (half - f0) / (f1 - f0) * (m1 - m0)
                } else {
                    m1
                }
            }
        };
        let area = pieces.iter().map(|p| p.error(c)).sum();
        (Length(c), area)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(l: f64, h0: f64, h1: f64) -> TrackProfile {
        TrackProfile::new([(Length(0.0), Length(h0)), (Length(l), Length(h1))]).unwrap()
    }

    #[test]
    fn on_a_straight_piece_the_midpoint_is_best() {
        // H from 10 to 20 over 100: over 20 .. 60 the midpoint height is 14,
        // and the area is two triangles 20 long and 2 high: 2·(20·2/2) = 40.
        let p = line(100.0, 10.0, 20.0);
        let (c, area) = p.best_constant(Length(20.0), Length(60.0));
        assert!((c.0 - 14.0).abs() < 1e-12);
        assert!((area - 40.0).abs() < 1e-9);
        // Any other constant does worse.
        for d in [-0.5, -0.01, 0.01, 0.5] {
            let other: f64 = p.pieces(20.0, 60.0).iter().map(|q| q.error(14.0 + d)).sum();
            assert!(other > area);
        }
    }

    #[test]
    fn a_flat_step_is_its_own_median() {
        // 0 over the first 3/4, 4 over the last 1/4 (a steep ramp between):
        // the median is 0, the area that of the high quarter.
        let p = TrackProfile::new([
            (Length(0.0), Length(0.0)),
            (Length(75.0), Length(0.0)),
            (Length(75.000001), Length(4.0)),
            (Length(100.0), Length(4.0)),
        ])
        .unwrap();
        let (c, area) = p.best_constant(Length(0.0), Length(100.0));
        assert!(c.0.abs() < 1e-9);
        assert!((area - 100.0).abs() < 1e-4);
    }

    #[test]
    fn bad_tracks_are_refused() {
        assert!(TrackProfile::new([(Length(0.0), Length(1.0))]).is_err());
        assert!(
            TrackProfile::new([(Length(0.0), Length(1.0)), (Length(0.0), Length(2.0))]).is_err()
        );
        assert!(
            TrackProfile::new([(Length(0.0), Length(1.0)), (Length(1.0), Length(f64::NAN))])
                .is_err()
        );
    }
}
