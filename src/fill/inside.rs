//! Whether a polyline between two neighbouring raster lines stays inside a
//! closed region (the links' safety check), exactly: a segment is cut where
//! it meets the boundary's lines and true arcs, and each part between two
//! such points is inside or outside as a whole, which its midpoint tells
//! (by parity on its own line, or lying on the boundary).
//!
//! The region's pieces are indexed by strip (the band between raster lines
//! `k` and `k + 1`), so a check reads only the pieces near its strip. The
//! index holds each piece once per strip it reaches: linear in pieces plus
//! strips crossed, and refused beyond [`MAX_INDEX`] entries (the layer then
//! keeps its tracks unlinked). Checks spend a budget of piece tests,
//! [`MAX_WORK`] a layer, for the same reason.

use super::clip::{Piece, Pieces};
use crate::geometry::profile::TOLERANCE;

/// Most (strip, piece) entries the index may hold.
const MAX_INDEX: usize = 8_000_000;

/// Most piece tests the checks of one layer may make.
const MAX_WORK: u64 = 50_000_000;

/// Segment parameters closer than this are one point.
const SAME_T: f64 = 1e-12;

/// The region's pieces by strip.
pub(super) struct Inside<'a> {
    pieces: &'a [Piece],
    /// Pieces near strip `k`: `items[starts[k]..starts[k + 1]]`.
    starts: Vec<usize>,
    items: Vec<u32>,
    work: u64,
}

impl<'a> Inside<'a> {
    /// The index of `region` over the strips between the lines at `s`
    /// (sorted), each widened by `margin`; `None` when it would be too large.
    pub fn new(region: &'a Pieces, s: &[f64], margin: f64) -> Option<Inside<'a>> {
        let strips = s.len().saturating_sub(1);
        let range = |p: &Piece| {
            let first = s.partition_point(|&x| x < p.lo[1] - margin).max(1) - 1;
            let last = s.partition_point(|&x| x <= p.hi[1] + margin);
            (first, last.min(strips))
        };
        let ranges: Vec<(usize, usize)> = region.items.iter().map(range).collect();
        let total: usize = ranges.iter().map(|&(a, b)| b.saturating_sub(a)).sum();
        if total > MAX_INDEX {
            return None;
        }
        let mut starts = vec![0usize; strips + 1];
        for &(a, b) in &ranges {
            for k in a..b {
                starts[k + 1] += 1;
            }
        }
        for k in 1..starts.len() {
            starts[k] += starts[k - 1];
        }
        let mut fill = starts.clone();
        let mut items = vec![0u32; total];
        for (i, &(a, b)) in ranges.iter().enumerate() {
            for slot in &mut fill[a..b] {
                items[*slot] = i as u32;
                *slot += 1;
            }
        }
        Some(Inside {
            pieces: &region.items,
            starts,
            items,
            work: MAX_WORK,
        })
    }

    /// Whether every segment of `path` (frame coordinates, within strip
    /// `strip` and its margin) lies in the closed region.
    pub fn path(&mut self, path: &[[f64; 2]], strip: usize) -> bool {
        let Some(near) = self
            .starts
            .get(strip..strip + 2)
            .map(|r| &self.items[r[0]..r[1]])
        else {
            return false;
        };
        let cost = near.len() as u64 * path.len() as u64 * 2;
        if cost > self.work {
            return false;
        }
        self.work -= cost;
        path.windows(2)
            .all(|w| segment(self.pieces, near, w[0], w[1]))
    }
}

/// Whether the segment `a`–`b` lies in the closed region whose pieces near
/// it are `near`.
fn segment(pieces: &[Piece], near: &[u32], a: [f64; 2], b: [f64; 2]) -> bool {
    let d = [b[0] - a[0], b[1] - a[1]];
    let mut ts = vec![0.0, 1.0];
    for &i in near {
        meets(&pieces[i as usize], a, d, &mut ts);
    }
    ts.sort_by(f64::total_cmp);
    let at = |t: f64| [a[0] + t * d[0], a[1] + t * d[1]];
    point(pieces, near, a)
        && point(pieces, near, b)
        && ts
            .windows(2)
            .filter(|w| w[1] - w[0] > SAME_T)
            .all(|w| point(pieces, near, at((w[0] + w[1]) / 2.0)))
}

/// Whether `p` is inside the closed region or on its boundary.
fn point(pieces: &[Piece], near: &[u32], p: [f64; 2]) -> bool {
    let tol = TOLERANCE * (1.0 + p[0].abs().max(p[1].abs()) * 1e-3);
    let mut odd = false;
    for &i in near {
        let piece = &pieces[i as usize];
        if piece.distance(p) <= tol {
            return true;
        }
        if piece.spans(p[1]) && piece.crossing(p[1]) < p[0] {
            odd = !odd;
        }
    }
    odd
}

/// Pushes to `ts` the parameters in (0, 1) where `a + t·d` meets `piece`.
fn meets(piece: &Piece, a: [f64; 2], d: [f64; 2], ts: &mut Vec<f64>) {
    let cross = |x: [f64; 2], y: [f64; 2]| x[0] * y[1] - x[1] * y[0];
    let mut push = |t: f64| {
        if t > 0.0 && t < 1.0 {
            ts.push(t);
        }
    };
    match piece.arc {
        None => {
            let e = [piece.hi[0] - piece.lo[0], piece.hi[1] - piece.lo[1]];
            let den = cross(d, e);
            if den == 0.0 || !den.is_finite() {
                // Parallel: the parts' midpoints tell on or off the edge.
                return;
            }
            let w = [piece.lo[0] - a[0], piece.lo[1] - a[1]];
            let (t, v) = (cross(w, e) / den, cross(w, d) / den);
            if (-1e-12..=1.0 + 1e-12).contains(&v) {
                push(t);
            }
        }
        Some((c, r, side)) => {
            let f = [a[0] - c[0], a[1] - c[1]];
            let qa = d[0] * d[0] + d[1] * d[1];
            if qa == 0.0 {
                return;
            }
            let qb = 2.0 * (f[0] * d[0] + f[1] * d[1]);
            let qc = (f[0] * f[0] + f[1] * f[1]) - r * r;
            let disc = qb * qb - 4.0 * qa * qc;
            // NaN as well as negative: no crossing.
            if disc.is_nan() || disc < 0.0 {
                return;
            }
            let root = disc.sqrt();
            for t in [(-qb - root) / (2.0 * qa), (-qb + root) / (2.0 * qa)] {
                let x = [a[0] + t * d[0], a[1] + t * d[1]];
                let on = x[1] >= piece.lo[1] - TOLERANCE
                    && x[1] <= piece.hi[1] + TOLERANCE
                    && (x[0] - c[0]) * side >= -TOLERANCE;
                if on {
                    push(t);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fill::clip::Frame;
    use crate::geometry::profile::Profile;

    #[test]
    fn segments_in_and_out_of_a_square_with_a_hole() {
        let outer = Profile::rectangle(10.0, 10.0);
        let hole = Profile::circle(2.0).placed(0.0, [5.0, 5.0]);
        let ps = Pieces::new([(&outer, false), (&hole, true)], &Frame::new(0.0));
        let s = [0.0, 10.0];
        let mut inside = Inside::new(&ps, &s, 0.1).unwrap();
        assert!(inside.path(&[[1.0, 1.0], [9.0, 1.0]], 0));
        // Along the bottom edge: on the boundary is in.
        assert!(inside.path(&[[0.0, 0.0], [10.0, 0.0]], 0));
        // Through the hole.
        assert!(!inside.path(&[[1.0, 5.0], [9.0, 5.0]], 0));
        // Tangent to the hole's top: touching is in.
        assert!(inside.path(&[[1.0, 7.0], [9.0, 7.0]], 0));
        // A chord of the hole's circle from edge point to edge point: out.
        let p = [5.0 - 2.0, 5.0];
        let q = [5.0, 5.0 + 2.0];
        assert!(!inside.path(&[p, q], 0));
        // Leaving the square.
        assert!(!inside.path(&[[9.0, 1.0], [11.0, 1.0]], 0));
    }
}
