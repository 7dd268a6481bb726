//! Layers must lie on each other: every deposit of a layer needs a bead of the
//! layer below within [`REACH`] of a bead width across the nozzle, or the bead
//! lands beside the part (a twist of 10⁶° moved points 10.9 mm off a 6 mm
//! bead). The reach is the fill's own: a raster layer leaves spots up to ¾ of a
//! bead from every track without a word (`lmd::thin-gap` starts beyond), so
//! the layer on it lands that far from the centre lines below; a bead ¾ of a
//! width off still overlaps the one below by a quarter of its width. Measured across the
//! nozzle (perpendicular to the point's normal), so the layer's own height does
//! not count; the first layer lies on the substrate and is not checked.
//!
//! Linear in the points: each layer becomes chords an eighth of a bead to a
//! search radius long; the layer below's go into a uniform 3-D grid of cells a
//! search radius wide, and the layer's chord starts (at most 1024 a layer,
//! spread over it) ask it for the nearest.

use crate::diag::Worst;
use crate::diag::{message, Diagnostics};
use crate::ir::{Layer, Program};
use crate::plan::Where;

/// Most places of one layer checked (spread over it): a 300 × 200 mm plate
/// lays 30 m of track a layer.
const MAX_SAMPLES: usize = 1024;

/// Most cells of one layer's grid; beyond it the cells grow.
const MAX_CELLS: usize = 1 << 20;

/// How far across the nozzle, in bead widths, a deposit may land from the
/// nearest bead centre line of the layer below.
pub const REACH: f64 = 0.75;

/// Deposits of each layer farther than [`REACH`] from the layer below.
pub(super) fn check(p: &Program, out: &mut Diagnostics) {
    let w = p.limits.bead_width;
    if !(w.is_finite() && w > 0.0) {
        return;
    }
    let half = w * REACH;
    // Within this 3-D distance a segment can be at most `half` across the
    // nozzle with the layer's height along it.
    let reach = (half * half + p.limits.layer_height[1].powi(2)).sqrt() * 1.01;
    let mut found: Option<Worst> = None;
    let mut below = Segments::of(&p.layers[0], w / 8.0, reach);
    for (li, layer) in p.layers.iter().enumerate().skip(1) {
        let here = Segments::of(layer, w / 8.0, reach);
        if !below.segs.is_empty() {
            let grid = Grid::new(&below.segs, reach);
            // Every chord start of this layer (1/8 bead to `reach` apart), at
            // most MAX_SAMPLES of them spread over the layer.
            let stride = here.starts.len().div_ceil(MAX_SAMPLES).max(1);
            for s in here.starts.iter().step_by(stride) {
                let across = grid.nearest_across(&below.segs, s.pos, s.normal, reach);
                if across.is_none_or(|d| d > half) {
                    let at = Where::Point {
                        layer: li,
                        path: s.path,
                        point: s.point,
                    };
                    Worst::hit(&mut found, across.unwrap_or(reach), half, at);
                }
            }
        }
        below = here;
    }
    let Some(f) = found else { return };
    let o = &p.origins;
    out.push(message::check::stacking(
        &f, reach, half, o.slicing, o.spine,
    ));
}

/// Where a chord of a layer starts: a place a deposit of that layer is
/// checked.
struct Start {
    pos: [f64; 3],
    normal: [f64; 3],
    path: usize,
    point: usize,
}

/// A layer's deposited segments (between points, where the laser is on),
/// with runs of points closer than `step` merged into chords: across the
/// nozzle a chord of 1/8 bead over a wall of 30 mm radius strays 0.002 mm.
/// Each chord is at most `longest` (a long raster track split into pieces),
/// so it covers a few grid cells, not a diagonal band of its bounding box.
struct Segments {
    segs: Vec<[[f64; 3]; 2]>,
    starts: Vec<Start>,
}

impl Segments {
    fn of(layer: &Layer, step: f64, longest: f64) -> Self {
        let mut out = Segments {
            segs: Vec::new(),
            starts: Vec::new(),
        };
        for (pi, path) in layer.paths.iter().enumerate() {
            // The chord under way: its start point and where it is in the path.
            let mut start: Option<([f64; 3], usize)> = None;
            for (k, w) in path.points.windows(2).enumerate() {
                let (a, b) = (w[0].pos, w[1].pos);
                if !w[0].laser_on || !a.iter().chain(&b).all(|v| v.is_finite()) {
                    if let Some((s, at)) = start.take() {
                        out.chord(s, a, path, pi, at, longest);
                    }
                    continue;
                }
                let (s, at) = *start.get_or_insert((a, k));
                if dist2(s, b) >= step * step {
                    out.chord(s, b, path, pi, at, longest);
                    start = Some((b, k + 1));
                }
            }
            if let (Some((s, at)), Some(last)) = (start, path.points.last()) {
                if s != last.pos && last.pos.iter().all(|v| v.is_finite()) {
                    out.chord(s, last.pos, path, pi, at, longest);
                }
            }
        }
        out
    }

    /// The chord from `a` (point `at` of path `pi`) to `b`, in pieces of at
    /// most `longest`.
    fn chord(
        &mut self,
        a: [f64; 3],
        b: [f64; 3],
        path: &crate::ir::Path,
        pi: usize,
        at: usize,
        longest: f64,
    ) {
        let n = path.points[at].normal.map(|v| v as f64);
        // Beyond any plate a piece is not split further.
        let pieces = (dist2(a, b).sqrt() / longest).ceil().clamp(1.0, 1e6) as usize;
        let along = |t: f64| [0, 1, 2].map(|i| a[i] + t * (b[i] - a[i]));
        for k in 0..pieces {
            let (from, to) = (
                along(k as f64 / pieces as f64),
                along((k + 1) as f64 / pieces as f64),
            );
            self.segs.push([from, to]);
            self.starts.push(Start {
                pos: from,
                normal: n,
                path: pi,
                point: at,
            });
        }
    }
}

fn dist2(a: [f64; 3], b: [f64; 3]) -> f64 {
    (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The point of segment `s` nearest to `p`.
fn closest(s: &[[f64; 3]; 2], p: [f64; 3]) -> [f64; 3] {
    let d = sub(s[1], s[0]);
    let len2 = dot(d, d);
    let t = if len2 > 0.0 {
        (dot(sub(p, s[0]), d) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    [s[0][0] + t * d[0], s[0][1] + t * d[1], s[0][2] + t * d[2]]
}

/// Segments by cell: a dense grid over their bounding box (counting sort).
struct Grid {
    origin: [f64; 3],
    cell: f64,
    dims: [usize; 3],
    start: Vec<u32>,
    items: Vec<u32>,
}

impl Grid {
    fn new(segs: &[[[f64; 3]; 2]], reach: f64) -> Self {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for s in segs {
            for p in s {
                for i in 0..3 {
                    lo[i] = lo[i].min(p[i]);
                    hi[i] = hi[i].max(p[i]);
                }
            }
        }
        let mut cell = reach.max(1e-9);
        let dims = loop {
            let d =
                [0, 1, 2].map(|i| (((hi[i] - lo[i]) / cell).floor() as usize).saturating_add(1));
            if d.iter()
                .try_fold(1usize, |a, &b| a.checked_mul(b))
                .is_some_and(|n| n <= MAX_CELLS)
            {
                break d;
            }
            cell *= 2.0;
        };
        let mut g = Grid {
            origin: lo,
            cell,
            dims,
            start: vec![0; dims[0] * dims[1] * dims[2] + 1],
            items: Vec::new(),
        };
        // Counting sort: each segment's cell range once, then count per
        // cell, prefix sums, and place.
        let ranges: Vec<([usize; 3], [usize; 3])> = segs
            .iter()
            .map(|s| {
                let (a, b) = (g.index(s[0]), g.index(s[1]));
                (
                    [a[0].min(b[0]), a[1].min(b[1]), a[2].min(b[2])],
                    [a[0].max(b[0]), a[1].max(b[1]), a[2].max(b[2])],
                )
            })
            .collect();
        let mut count = vec![0u32; g.start.len()];
        for &(lo, hi) in &ranges {
            g.for_range(lo, hi, |c| count[c + 1] += 1);
        }
        for i in 1..count.len() {
            count[i] += count[i - 1];
        }
        g.start.clone_from(&count);
        let mut items = vec![0u32; count[count.len() - 1] as usize];
        for (k, &(lo, hi)) in ranges.iter().enumerate() {
            g.for_range(lo, hi, |c| {
                items[count[c] as usize] = k as u32;
                count[c] += 1;
            });
        }
        g.items = items;
        g
    }

    #[inline]
    fn index(&self, p: [f64; 3]) -> [usize; 3] {
        let at = |i: usize| {
            let v = ((p[i] - self.origin[i]) / self.cell).floor();
            (v.max(0.0) as usize).min(self.dims[i] - 1)
        };
        [at(0), at(1), at(2)]
    }

    /// Calls `f` with each cell of the index box `lo ..= hi`.
    #[inline]
    fn for_range(&self, lo: [usize; 3], hi: [usize; 3], mut f: impl FnMut(usize)) {
        for x in lo[0]..=hi[0] {
            for y in lo[1]..=hi[1] {
                for z in lo[2]..=hi[2] {
                    f((x * self.dims[1] + y) * self.dims[2] + z);
                }
            }
        }
    }

    /// The smallest distance across normal `n` from `p` to a segment within
    /// `reach` of it, if any.
    fn nearest_across(
        &self,
        segs: &[[[f64; 3]; 2]],
        p: [f64; 3],
        n: [f64; 3],
        reach: f64,
    ) -> Option<f64> {
        let c = self.index(p);
        let mut best: Option<f64> = None;
        let span = (reach / self.cell).ceil() as usize;
        for x in c[0].saturating_sub(span)..=(c[0] + span).min(self.dims[0] - 1) {
            for y in c[1].saturating_sub(span)..=(c[1] + span).min(self.dims[1] - 1) {
                for z in c[2].saturating_sub(span)..=(c[2] + span).min(self.dims[2] - 1) {
                    let cell = (x * self.dims[1] + y) * self.dims[2] + z;
                    let (a, b) = (self.start[cell] as usize, self.start[cell + 1] as usize);
                    for &k in &self.items[a..b] {
                        let q = closest(&segs[k as usize], p);
                        let d = sub(p, q);
                        if dot(d, d) > reach * reach {
                            continue;
                        }
                        let along = dot(d, n);
                        let across = (dot(d, d) - along * along).max(0.0).sqrt();
                        if best.is_none_or(|b| across < b) {
                            best = Some(across);
                        }
                    }
                }
            }
        }
        best
    }
}
