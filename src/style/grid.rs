//! A uniform grid over segments, so "which segments come within `reach` of this
//! one?" looks at a few cells instead of every segment: the band and inheritance
//! queries become near-linear in points instead of quadratic.
//!
//! Memory is linear in the number `n` of segments for any input. The cell count
//! is at most about `3·(2n + 16)`. A segment lands in at most
//! `4·(|dx| + |dy|)/c + 9` cells (`|dy|/c + 3` rows; within a row, its part in a
//! slab `3c` high, widened by the slack, crossing ≤ `x-extent/c + 3` cells, and
//! each x is in at most 4 slabs), and the cell size `c` is at least an eighth of
//! the mean `|dx| + |dy|`, so there are at most ~41 entries per segment on
//! average. Degenerate extents (all points equal, or coordinates so large that
//! the extent overflows) fall back to one cell holding everything: still
//! correct, just a linear scan.
//!
//! The cell size is also at least the query reach (the band's half-width), so a
//! query segment looks at `O(1 + length/c)` cells.

use super::capsule::{finite, P};
use super::StyleId;

/// One segment of a band's centre lines and the style (or group) it belongs to.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Seg {
    /// First end.
    pub a: P,
    /// Second end (equal to `a` for a lone point: the band is then a disc).
    pub b: P,
    /// Which line group (style) the segment belongs to.
    pub tag: StyleId,
}

/// Most cells a grid may have, whatever the segment count.
const MAX_CELLS: usize = 1 << 24;

/// Segments bucketed by the cells they cross (compressed rows: cell `k` holds
/// `items[start[k]..start[k + 1]]`).
#[derive(Debug)]
pub(crate) struct SegmentGrid {
    origin: P,
    cell: f64,
    nx: usize,
    ny: usize,
    /// Distance a query looks around its segment.
    reach: f64,
    /// Rounding allowance added to every rasterisation, so a segment exactly at
    /// `reach` is never lost to a cell border.
    slack: f64,
    /// One cell holding all segments (degenerate or overflowing extents).
    single: bool,
    start: Vec<usize>,
    items: Vec<usize>,
}

/// The cells `k` of an axis (origin `o`, size `c`, `n` cells) whose span meets
/// `[lo, hi]`; cells past either end are clamped to the last one.
fn span(o: f64, c: f64, n: usize, lo: f64, hi: f64) -> Option<(usize, usize)> {
    let top = o + n as f64 * c;
    if !(hi >= o && lo <= top) {
        return None;
    }
    // Truncation is floor for the non-negative values left after `max` (and
    // cheaper: without SSE4.1, `floor` is a libm call); `as usize` saturates and
    // `max` maps NaN to 0, so the casts cannot misbehave.
    let k = |x: f64| (((x - o) / c).max(0.0) as usize).min(n - 1);
    Some((k(lo), k(hi)))
}

impl SegmentGrid {
    /// Buckets `segs` (all with finite ends) for queries that look `reach` (finite,
    /// ≥ 0) around a segment.
    pub(crate) fn new(segs: &[Seg], reach: f64) -> Self {
        let n = segs.len();
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        let mut extent = 0.0;
        for s in segs {
            for p in [s.a, s.b] {
                debug_assert!(finite(p));
                for k in 0..2 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
            extent += (s.b[0] - s.a[0]).abs() + (s.b[1] - s.a[1]).abs();
        }
        let (w, h) = (hi[0] - lo[0], hi[1] - lo[1]);
        let max_cells = (2 * n + 16).min(MAX_CELLS);
        let k = max_cells as f64;
        let cell = reach
            .max((w * h / k).sqrt())
            .max(w.max(h) / k)
            .max(extent / (8.0 * n.max(1) as f64));
        let scale = lo[0]
            .abs()
            .max(lo[1].abs())
            .max(hi[0].abs())
            .max(hi[1].abs());
        let mut grid = SegmentGrid {
            origin: lo,
            cell,
            nx: 1,
            ny: 1,
            reach,
            slack: 1e-9 * (scale + cell + reach),
            single: true,
            start: vec![0, n],
            items: (0..n).collect(),
        };
        let fits = cell > 0.0 && cell.is_finite() && w.is_finite() && h.is_finite();
        if n == 0 || !fits || !grid.slack.is_finite() {
            return grid;
        }
        grid.single = false;
        // ⌊w/c⌋ + 1 cells cover [lo, hi] whole (the cast truncates: floor for
        // w/c ≥ 0); the cap only guards rounding.
        grid.nx = ((w / cell) as usize + 1).min(max_cells);
        grid.ny = ((h / cell) as usize + 1).min(max_cells);
        if grid.nx * grid.ny > 3 * max_cells + 1 {
            // Unreachable by the choice of `cell`, but memory must stay bounded.
            grid.single = true;
            grid.nx = 1;
            grid.ny = 1;
            return grid;
        }
        let cells = grid.nx * grid.ny;
        let mut start = vec![0usize; cells + 1];
        for s in segs {
            grid.for_cells(s.a, s.b, grid.slack, |c| start[c + 1] += 1);
        }
        for c in 0..cells {
            start[c + 1] += start[c];
        }
        let mut items = vec![0usize; start[cells]];
        let mut next = start.clone();
        for (i, s) in segs.iter().enumerate() {
            grid.for_cells(s.a, s.b, grid.slack, |c| {
                items[next[c]] = i;
                next[c] += 1;
            });
        }
        grid.start = start;
        grid.items = items;
        grid
    }

    /// Calls `f` with every cell that a point within `r` of segment `ab` can lie in:
    /// row by row, the part of `ab` whose `y` is within `r` of the row, widened by
    /// `r` in `x`.
    fn for_cells(&self, a: P, b: P, r: f64, mut f: impl FnMut(usize)) {
        if self.single {
            f(0);
            return;
        }
        let (o, c) = (self.origin, self.cell);
        let Some((j0, j1)) = span(o[1], c, self.ny, a[1].min(b[1]) - r, a[1].max(b[1]) + r) else {
            return;
        };
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        for j in j0..=j1 {
            let y0 = o[1] + j as f64 * c - r;
            let y1 = y0 + c + 2.0 * r;
            let (x0, x1) = if dy == 0.0 {
                (a[0].min(b[0]), a[0].max(b[0]))
            } else {
                let (t0, t1) = ((y0 - a[1]) / dy, (y1 - a[1]) / dy);
                let (t0, t1) = (t0.min(t1).max(0.0), t0.max(t1).min(1.0));
                if t0.is_nan() || t1.is_nan() || t0 > t1 {
                    continue;
                }
                let (xa, xb) = (a[0] + t0 * dx, a[0] + t1 * dx);
                (xa.min(xb), xa.max(xb))
            };
            if let Some((i0, i1)) = span(o[0], c, self.nx, x0 - r, x1 + r) {
                for i in i0..=i1 {
                    f(j * self.nx + i);
                }
            }
        }
    }

    /// The indices (sorted, once each) of the segments that may come within
    /// `reach` of segment `ab` (a point when `a == b`), into `out`.
    pub(crate) fn candidates(&self, a: P, b: P, out: &mut Vec<usize>) {
        out.clear();
        self.for_cells(a, b, self.reach + self.slack, |c| {
            out.extend_from_slice(&self.items[self.start[c]..self.start[c + 1]]);
        });
        out.sort_unstable();
        out.dedup();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::style::capsule::point_segment_dist;

    fn seg(a: P, b: P) -> Seg {
        Seg { a, b, tag: 0 }
    }

    /// Every segment within reach is a candidate (the grid never loses one), and
    /// far ones are pruned.
    #[test]
    fn candidates_are_complete_and_pruned() {
        // A 40×40 lattice of short segments, 1 mm apart.
        let mut segs = Vec::new();
        for i in 0..40 {
            for j in 0..40 {
                let (x, y) = (i as f64, j as f64);
                segs.push(seg([x, y], [x + 0.5, y + 0.3]));
            }
        }
        let grid = SegmentGrid::new(&segs, 1.0);
        assert!(!grid.single);
        let mut out = Vec::new();
        for q in [
            [10.2, 10.7],
            [0.0, 0.0],
            [39.5, 39.3],
            [-0.9, 5.0],
            [20.0, 41.0],
        ] {
            grid.candidates(q, q, &mut out);
            for (i, s) in segs.iter().enumerate() {
                if point_segment_dist(q, s.a, s.b) <= 1.0 {
                    assert!(out.contains(&i), "{q:?} lost segment {i}");
                }
            }
            assert!(out.len() < 60, "{q:?}: {} candidates", out.len());
        }
        // Far away: nothing.
        grid.candidates([100.0, 100.0], [120.0, 90.0], &mut out);
        assert!(out.is_empty());
    }

    /// Long diagonal segments: entries stay linear in the segment count.
    #[test]
    fn long_segments_stay_linear() {
        let segs: Vec<Seg> = (0..500)
            .map(|i| {
                let o = i as f64 * 0.4;
                seg([o, 0.0], [o + 200.0, 200.0])
            })
            .collect();
        let grid = SegmentGrid::new(&segs, 0.5);
        assert!(grid.items.len() <= 41 * segs.len(), "{}", grid.items.len());
        let mut out = Vec::new();
        grid.candidates([100.0, 50.0], [100.0, 50.0], &mut out);
        for (i, s) in segs.iter().enumerate() {
            if point_segment_dist([100.0, 50.0], s.a, s.b) <= 0.5 {
                assert!(out.contains(&i));
            }
        }
    }

    #[test]
    fn degenerate_extents_use_one_cell() {
        let segs = vec![seg([1.0, 1.0], [1.0, 1.0]); 3];
        let grid = SegmentGrid::new(&segs, 0.0);
        let mut out = Vec::new();
        grid.candidates([5.0, 5.0], [5.0, 5.0], &mut out);
        assert_eq!(out, vec![0, 1, 2]);
        let huge = vec![
            seg([-1e308, 0.0], [1e308, 0.0]),
            seg([0.0, -1e308], [0.0, 1e308]),
        ];
        let grid = SegmentGrid::new(&huge, 1.0);
        grid.candidates([0.0, 0.0], [1.0, 1.0], &mut out);
        assert_eq!(out, vec![0, 1]);
        let grid = SegmentGrid::new(&[], 1.0);
        grid.candidates([0.0, 0.0], [1.0, 1.0], &mut out);
        assert!(out.is_empty());
    }
}
