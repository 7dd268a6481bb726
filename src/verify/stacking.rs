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
//! Each layer's deposits become chords an eighth of a bead to a search radius
//! long, and at most [`MAX_SAMPLES`] chord starts, spread over the layer, are
//! checked. They go into a small grid; the layer below's chords are walked
//! through it once, each sample keeping its nearest. Memory stays bounded by
//! the samples, whatever the track length (a 5 m plate lays 15 km of track a
//! layer), and time is linear in the points and in the track length over the
//! grid's cell, which grows with the part.

use super::rule::{ProgramCx, ProgramRule, Worst};
use crate::diag::message::verify::StackingFix;
use crate::diag::{message, Diagnostics};
use crate::ir::{Layer, Path, PathKind, Program};
use crate::plan::Where;

/// Most places of one layer checked (spread over it): a 300 × 200 mm plate
/// lays 30 m of track a layer.
const MAX_SAMPLES: usize = 1024;

/// Most cells of the samples' grid; beyond it the cells grow. About four
/// cells a sample: a chord piece looks at a few samples, and a large part is
/// walked in few pieces.
const MAX_CELLS: usize = 4 * MAX_SAMPLES;

/// Most pieces one chord is counted in when samples are spread over it.
const MAX_PIECES: f64 = 1e6;

/// How far across the nozzle, in bead widths, a deposit may land from the
/// nearest bead centre line of the layer below.
pub const REACH: f64 = 0.75;

/// `lmd::stacking`: deposits of each layer farther than [`REACH`] from the
/// layer below.
pub(super) struct Stacking;

impl ProgramRule for Stacking {
    fn check(cx: &ProgramCx<'_>, out: &mut Diagnostics) {
        check(cx.program, out);
    }
}

/// How far, in bead widths, the distance of a deposit beyond the reach is
/// searched for (a cone's step, a twist's jump) before it is "more than".
pub(super) const FAR: f64 = 64.0;

fn check(p: &Program, out: &mut Diagnostics) {
    let w = p.limits.bead_width;
    if !(w.is_finite() && w > 0.0) {
        return;
    }
    let half = w * REACH;
    let h_max = p.limits.layer_height[1];
    // Within this 3-D distance a segment can be at most `half` across the
    // nozzle with the layer's height along it.
    let reach = (half * half + h_max.powi(2)).sqrt() * 1.01;
    let far = (FAR * w).max(reach);
    let step = w / 8.0;
    let mut found: Option<Worst> = None;
    // The layer height and the path's kind at the worst place.
    let mut there = (0.0, PathKind::Wall);
    for (li, pair) in p.layers.windows(2).enumerate() {
        let (below, here) = (&pair[0], &pair[1]);
        if here.on_plate {
            continue;
        }
        let samples = samples(here, step, reach);
        if samples.is_empty() {
            continue;
        }
        let Some(best) = nearest(below, &samples, step, [reach, far], h_max) else {
            continue;
        };
        for (s, best) in samples.iter().zip(&best) {
            if best.is_none_or(|d| d > half) {
                let at = Where::Point {
                    layer: li + 1,
                    path: s.path,
                    point: s.point,
                };
                Worst::hit(&mut found, best.unwrap_or(far), half, at);
                if found.is_some_and(|f| f.at == at) {
                    let path = &here.paths[s.path];
                    there = (path.points[s.point].layer_height as f64, path.kind);
                }
            }
        }
    }
    let Some(f) = found else { return };
    let o = &p.origins;
    let fix = fix(p, &f, there, half, far);
    out.push(message::verify::stacking(&f, &fix, o.slicing, o.spine));
}

/// What would land the worst deposit on the layer below. Every step
/// between layers is about the layer height times the wall's lean: a loft's
/// layers all thin as its count grows (its stations are `i/N`), so `N·d/½w`
/// layers step at most `½w`, when the bead lays layers that thin; a lean
/// of at most `atan(½w/h)` steps that little at the layers it has.
fn fix(p: &Program, f: &Worst, (h, kind): (f64, PathKind), half: f64, far: f64) -> StackingFix {
    let d = (f.value < far).then_some(f.value);
    let n = p.layers.len();
    let h_min = p.limits.layer_height[0];
    // The thinnest layer laid, which more layers thin in proportion.
    let thinnest = p
        .layers
        .iter()
        .flat_map(|l| &l.paths)
        .flat_map(|path| &path.points)
        .filter(|pt| pt.laser_on)
        .map(|pt| pt.layer_height as f64)
        .fold(f64::INFINITY, f64::min);
    let most = (n as f64 * thinnest / h_min * (1.0 - 1e-4)).floor();
    let layers = match (d, p.origins.spine) {
        (Some(d), Some(_)) if h > 0.0 && h_min > 0.0 => {
            let need = (n as f64 * d / half * (1.0 + 1e-9)).ceil();
            (need <= most).then_some(need as usize)
        }
        _ => None,
    };
    StackingFix {
        height: h,
        step: d,
        half,
        layers,
        raster: kind == PathKind::Infill,
    }
}

/// Each sample's nearest distance across the nozzle to `below`'s deposits:
/// within `reach` in one walk, then, for those not settled there, searched
/// twice as far each time up to `far` (`None`: not within it). `None` when
/// `below` lays nothing. A segment `r` away in 3-D lies at least
/// `√(r² − h²)` across (`h` the thickest layer), so a distance up to that is
/// the nearest.
pub(super) fn nearest(
    below: &Layer,
    samples: &[Start],
    step: f64,
    [reach, far]: [f64; 2],
    h: f64,
) -> Option<Vec<Option<f64>>> {
    let settled = |r: f64, d: Option<f64>| d.is_some_and(|d| d * d + h * h <= r * r);
    let mut grid = Grid::new(samples, reach);
    let mut deposits = false;
    chords(below, step, |a, b, _, _| {
        deposits = true;
        grid.walk(a, b, reach, samples);
    });
    if !deposits {
        return None;
    }
    let mut best = grid.best;
    let mut left: Vec<usize> = (0..samples.len())
        .filter(|&k| !settled(reach, best[k]))
        .collect();
    let mut r = reach;
    while !left.is_empty() && r < far {
        r = (2.0 * r).min(far);
        let these: Vec<Start> = left.iter().map(|&k| samples[k]).collect();
        let mut grid = Grid::new(&these, r);
        chords(below, step, |a, b, _, _| grid.walk(a, b, r, &these));
        let mut next = Vec::new();
        for (j, &k) in left.iter().enumerate() {
            if grid.best[j].is_some() {
                best[k] = grid.best[j];
            }
            if !settled(r, grid.best[j]) {
                next.push(k);
            }
        }
        left = next;
    }
    Some(best)
}

/// A place a deposit of a layer is checked: where a chord piece starts.
#[derive(Clone, Copy)]
pub(super) struct Start {
    pos: [f64; 3],
    normal: [f64; 3],
    /// The path, in its layer.
    pub path: usize,
    /// The point the chord starts at, in its path.
    pub point: usize,
}

/// Calls `f(a, b, path, point)` with each chord of `layer`'s deposits (between
/// points where the laser is on), runs of points closer than `step` merged:
/// across the nozzle a chord of 1/8 bead over a wall of 30 mm radius strays
/// 0.002 mm. `point` is where the chord starts in path `path`.
fn chords(layer: &Layer, step: f64, mut f: impl FnMut([f64; 3], [f64; 3], usize, usize)) {
    for (pi, path) in layer.paths.iter().enumerate() {
        // The chord under way: its start point and where it is in the path.
        let mut start: Option<([f64; 3], usize)> = None;
        for (k, w) in path.points.windows(2).enumerate() {
            let (a, b) = (w[0].pos, w[1].pos);
            if !w[0].laser_on || !a.iter().chain(&b).all(|v| v.is_finite()) {
                if let Some((s, at)) = start.take() {
                    f(s, a, pi, at);
                }
                continue;
            }
            let (s, at) = *start.get_or_insert((a, k));
            if dist2(s, b) >= step * step {
                f(s, b, pi, at);
                start = Some((b, k + 1));
            }
        }
        if let (Some((s, at)), Some(last)) = (start, path.points.last()) {
            if s != last.pos && last.pos.iter().all(|v| v.is_finite()) {
                f(s, last.pos, pi, at);
            }
        }
    }
}

/// How many pieces of at most `longest` the chord `a`–`b` is cut into.
fn pieces(a: [f64; 3], b: [f64; 3], longest: f64) -> usize {
    (dist2(a, b).sqrt() / longest).ceil().clamp(1.0, MAX_PIECES) as usize
}

/// The places of `layer` checked: the starts of its chords cut into pieces of
/// at most `longest`, every k-th so that at most [`MAX_SAMPLES`] remain. Two
/// passes over the chords (count, then pick), so the pieces are never stored.
pub(super) fn samples(layer: &Layer, step: f64, longest: f64) -> Vec<Start> {
    let mut total = 0usize;
    chords(layer, step, |a, b, _, _| {
        total = total.saturating_add(pieces(a, b, longest))
    });
    let stride = total.div_ceil(MAX_SAMPLES).max(1);
    let mut out = Vec::with_capacity(total.div_ceil(stride));
    // Index of the chord's first piece among all the layer's pieces.
    let mut first = 0usize;
    chords(layer, step, |a, b, pi, at| {
        let n = pieces(a, b, longest);
        let normal = normal_at(&layer.paths[pi], at);
        // The first piece of this chord whose index is a multiple of `stride`.
        let mut k = (stride - first % stride) % stride;
        while k < n {
            let t = k as f64 / n as f64;
            out.push(Start {
                pos: [0, 1, 2].map(|i| a[i] + t * (b[i] - a[i])),
                normal,
                path: pi,
                point: at,
            });
            k += stride;
        }
        first += n;
    });
    out
}

fn normal_at(path: &Path, at: usize) -> [f64; 3] {
    path.points[at].normal.map(|v| v as f64)
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

/// The point of segment `a`–`b` nearest to `p`.
fn closest(a: [f64; 3], b: [f64; 3], p: [f64; 3]) -> [f64; 3] {
    let d = sub(b, a);
    let len2 = dot(d, d);
    let t = if len2 > 0.0 {
        (dot(sub(p, a), d) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    [a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2]]
}

/// The samples by cell (a dense grid over their bounding box, counting
/// sort), and each sample's nearest distance across the nozzle so far.
struct Grid {
    origin: [f64; 3],
    cell: f64,
    dims: [usize; 3],
    start: Vec<u32>,
    items: Vec<u32>,
    best: Vec<Option<f64>>,
}

impl Grid {
    fn new(samples: &[Start], reach: f64) -> Self {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for s in samples {
            for i in 0..3 {
                lo[i] = lo[i].min(s.pos[i]);
                hi[i] = hi[i].max(s.pos[i]);
            }
        }
        // At least the search radius, so a piece's neighbourhood is a few cells.
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
            items: vec![0; samples.len()],
            best: vec![None; samples.len()],
        };
        let cells: Vec<usize> = samples.iter().map(|s| g.cell_of(s.pos)).collect();
        for &c in &cells {
            g.start[c + 1] += 1;
        }
        for i in 1..g.start.len() {
            g.start[i] += g.start[i - 1];
        }
        let mut next = g.start.clone();
        for (k, &c) in cells.iter().enumerate() {
            g.items[next[c] as usize] = k as u32;
            next[c] += 1;
        }
        g
    }

    /// The cell index along axis `i` of coordinate `v`, unclamped.
    #[inline]
    fn axis(&self, i: usize, v: f64) -> f64 {
        ((v - self.origin[i]) / self.cell).floor()
    }

    #[inline]
    fn cell_of(&self, p: [f64; 3]) -> usize {
        let at = |i: usize| (self.axis(i, p[i]).max(0.0) as usize).min(self.dims[i] - 1);
        (at(0) * self.dims[1] + at(1)) * self.dims[2] + at(2)
    }

    /// Offers the segment `a`–`b` of the layer below to every sample within
    /// `reach` of it, in pieces at most a cell long (so each looks at a few
    /// cells, however long and slanted the segment).
    fn walk(&mut self, a: [f64; 3], b: [f64; 3], reach: f64, samples: &[Start]) {
        let n = pieces(a, b, self.cell);
        let along = |t: f64| [0, 1, 2].map(|i| a[i] + t * (b[i] - a[i]));
        'pieces: for k in 0..n {
            let (p, q) = (along(k as f64 / n as f64), along((k + 1) as f64 / n as f64));
            let mut range = [(0usize, 0usize); 3];
            for (i, r) in range.iter_mut().enumerate() {
                let lo = self.axis(i, p[i].min(q[i]) - reach);
                let hi = self.axis(i, p[i].max(q[i]) + reach);
                if hi < 0.0 || lo > (self.dims[i] - 1) as f64 {
                    // The piece's neighbourhood misses the samples' box.
                    continue 'pieces;
                }
                *r = (lo.max(0.0) as usize, (hi as usize).min(self.dims[i] - 1));
            }
            for x in range[0].0..=range[0].1 {
                for y in range[1].0..=range[1].1 {
                    for z in range[2].0..=range[2].1 {
                        let c = (x * self.dims[1] + y) * self.dims[2] + z;
                        let (from, to) = (self.start[c] as usize, self.start[c + 1] as usize);
                        for &k in &self.items[from..to] {
                            let s = &samples[k as usize];
                            let d = sub(s.pos, closest(p, q, s.pos));
                            let d2 = dot(d, d);
                            if d2 > reach * reach {
                                continue;
                            }
                            let along = dot(d, s.normal);
                            let across = (d2 - along * along).max(0.0).sqrt();
                            let best = &mut self.best[k as usize];
                            if best.is_none_or(|b| across < b) {
                                *best = Some(across);
                            }
                        }
                    }
                }
            }
        }
    }
}
