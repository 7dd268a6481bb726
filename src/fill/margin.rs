//! Closing tracks along the raster region's margin where the contour
//! beyond it would have no raster track within reach over a bead or more.
//!
//! The raster's lines are spaced from the region's near extreme and closed
//! at its far one ([`super::raster::CLOSING`]); in between, an edge lies
//! wherever the spacing leaves it. Where it runs with the lines, module
//! `edge` closes it. Where it curves through their direction (a rounded
//! tongue's crest, a round hole's crest and flanks, a rounded notch's
//! floor, at any raster angle), the lines ending at it come seldom near
//! the crest, and their ends are extended along the lines, never across:
//! the contour beyond the margin can be left with no track within a bead
//! over a stretch, and the strip between is left unfilled.
//!
//! So every loop of the raster region is walked, every quarter offset. At
//! each place the contour's place is probed: an offset out of the region
//! along the margin's normal (for an arc the region lies outside of, at
//! most to its centre); without contours the raster's ends are the
//! layer's edge, and nothing is laid. Where no
//! raster track as laid (nor a closing track of `edge`) lies within that
//! distance and the closing threshold of it, as the far extreme's rule
//! has it, the place is open. Along each stretch of open places at least
//! that reach long (a bead, with contours), a track is laid on the margin;
//! two stretches shut for less than two offsets between them are one. A
//! shorter stretch is left to the melt pool: a track there would be
//! shorter than a bead, a blob rather than a bead. Linear in the margin's
//! length and its arcs' chords (as many as the contour's), with a binary
//! search a line near each place and the edges' tracks looked up by cell.

use super::clip::{Piece, Pieces};
use super::coverage::distance2;
use super::extend::Laid;
use crate::geometry::profile::MAX_ARC_CHORDS;
use std::collections::HashMap;
use std::f64::consts::{PI, TAU};

/// Most places a layer's margin is probed at: the step grows beyond it.
const MAX_PLACES: f64 = 200_000.0;

/// A place on the margin, with the contour's place beyond it.
#[derive(Clone, Copy)]
struct Place {
    /// On the margin (frame coordinates).
    at: [f64; 2],
    /// Where the contour runs, an offset out.
    probe: [f64; 2],
}

/// What the margin's places are probed against: the raster tracks as laid
/// and the edges' closing tracks, all in the frame.
pub(super) struct Tracks<'a> {
    /// Each line's `s`, sorted.
    pub line_s: &'a [f64],
    /// Each line's intervals as laid.
    pub lines: &'a [Laid],
    /// The closing tracks along edges (module `edge`).
    pub edges: &'a [[[f64; 2]; 2]],
}

/// The closing tracks (polylines, in the raster's frame) along the margin
/// of the raster region (`pieces`) where the contour an `offset` beyond it
/// would lie farther than `offset + threshold` from every track of `laid`,
/// over at least that much; `offset` the lines' spacing and the contours',
/// arcs kept within `chord_error`. In the order of the loops.
pub(super) fn closings(
    pieces: &Pieces,
    laid: &Tracks<'_>,
    [threshold, offset, chord_error]: [f64; 3],
) -> Vec<Vec<[f64; 2]>> {
    let mut out = Vec::new();
    let usable = [threshold, offset, chord_error]
        .iter()
        .all(|v| v.is_finite() && *v > 0.0);
    if !usable || laid.line_s.is_empty() {
        return out;
    }
    let total: f64 = pieces.items.iter().map(length).sum();
    let step = (offset / 4.0).max(total / MAX_PLACES);
    if !(step.is_finite() && step > 0.0) {
        return out;
    }
    let reach = offset + threshold;
    let edges = EdgeCells::new(laid.edges, reach);
    for (l, &(a, b)) in pieces.loops.iter().enumerate() {
        let hole = pieces.holes.get(l).copied().unwrap_or(false);
        let places: Vec<Place> = pieces.items[a..b]
            .iter()
            .flat_map(|p| sample(p, [step, offset, chord_error], hole))
            .collect();
        let open: Vec<bool> = places
            .iter()
            .map(|p| nearest(p.probe, reach, laid, &edges) > reach)
            .collect();
        let mut along = Vec::with_capacity(places.len());
        let mut walked = 0.0;
        for (k, p) in places.iter().enumerate() {
            along.push(walked);
            let next = places[(k + 1) % places.len()].at;
            walked += (next[0] - p.at[0]).hypot(next[1] - p.at[1]);
        }
        // Shut for less than two offsets between two open stretches: one.
        for run in stretches(&open, &along, walked, 2.0 * offset) {
            let track = stretch(&places, run);
            if super::pitch::length(&track) >= reach {
                out.push(simplify(&track, chord_error / 4.0));
            }
        }
    }
    out
}

/// A piece's length (mm).
fn length(p: &Piece) -> f64 {
    match p.arc {
        None => (p.hi[0] - p.lo[0]).hypot(p.hi[1] - p.lo[1]),
        Some((c, r, _)) => r * span(p, c).abs(),
    }
}

/// The angles (rad) of an arc piece's `lo` and `hi` about its centre `c`,
/// on the piece's side of the centre.
fn angles(p: &Piece, c: [f64; 2]) -> (f64, f64) {
    let side = p.arc.map_or(1.0, |(_, _, s)| s);
    let angle = |q: [f64; 2]| {
        let a = (q[1] - c[1]).atan2(q[0] - c[0]);
        // The left half runs through ±π: keep it in (0, 2π) there.
        if side < 0.0 && a < 0.0 {
            a + TAU
        } else {
            a
        }
    };
    (angle(p.lo), angle(p.hi))
}

/// The signed angle an arc piece sweeps from `lo` to `hi`.
fn span(p: &Piece, c: [f64; 2]) -> f64 {
    let (a, b) = angles(p, c);
    (b - a).clamp(-PI, PI)
}

/// The piece's places every `step` or less (an arc's within the chord
/// error of it), in the loop's direction of travel, its far end left to
/// the next piece; each with its probe an `offset` out of the region (a
/// loop that is a `hole` has the region on its right).
fn sample(p: &Piece, [step, offset, chord_error]: [f64; 3], hole: bool) -> Vec<Place> {
    let length = length(p);
    let (from, to) = if p.rising { (p.lo, p.hi) } else { (p.hi, p.lo) };
    let Some((c, r, _)) = p.arc else {
        if length <= 0.0 {
            // A point: no direction to probe out of.
            return Vec::new();
        }
        let n = (length / step).ceil().max(1.0) as usize;
        let (dx, dy) = (to[0] - from[0], to[1] - from[1]);
        // Out of the region: right of travel round an outer loop, left
        // round a hole.
        let out = if hole { -offset } else { offset } / length;
        let normal = [out * dy, -out * dx];
        return (0..n)
            .map(|k| {
                let f = k as f64 / n as f64;
                let at = [from[0] + f * dx, from[1] + f * dy];
                Place {
                    at,
                    probe: [at[0] + normal[0], at[1] + normal[1]],
                }
            })
            .collect();
    };
    let (lo, hi) = angles(p, c);
    let (a0, a1) = if p.rising { (lo, hi) } else { (hi, lo) };
    // Places close enough that the chords between them stay within the
    // chord error (the track follows them), as many as the contour's own
    // flattening takes at most.
    let turn = if chord_error < r {
        ((a1 - a0).abs() / (2.0 * (1.0 - chord_error / r).acos())).min(MAX_ARC_CHORDS as f64)
    } else {
        0.0
    };
    let n = (length / step).max(turn).ceil().max(1.0) as usize;
    // Out of the region: away from the centre of a convex arc, toward it
    // (at most to it) of a concave one.
    let out = if p.convex { offset } else { -offset.min(r) };
    (0..n)
        .map(|k| {
            let phi = a0 + k as f64 / n as f64 * (a1 - a0);
            let radial = [phi.cos(), phi.sin()];
            let at = [c[0] + r * radial[0], c[1] + r * radial[1]];
            Place {
                at,
                probe: [at[0] + out * radial[0], at[1] + out * radial[1]],
            }
        })
        .collect()
}

/// The runs of `open` places (first and last index, the last possibly
/// before the first where a run wraps round the loop's start), two runs
/// with at most `bridge` mm of shut margin between them made one (`along`:
/// each place's distance along the loop, `round` the loop's length). A
/// loop open everywhere has no raster near it at all: nothing to close
/// against.
fn stretches(open: &[bool], along: &[f64], round: f64, bridge: f64) -> Vec<(usize, usize)> {
    let n = open.len();
    let Some(shut) = open.iter().position(|o| !o) else {
        return Vec::new();
    };
    let mut runs: Vec<(usize, usize)> = Vec::new();
    let mut run: Option<usize> = None;
    for k in 1..=n {
        let i = (shut + k) % n;
        match (open[i], run) {
            (true, None) => run = Some(i),
            (false, Some(first)) => {
                runs.push((first, (i + n - 1) % n));
                run = None;
            }
            _ => {}
        }
    }
    // Runs come in order from `shut`; join across short shut gaps (the
    // last and the first too, round the loop).
    let gap = |a: (usize, usize), b: (usize, usize)| (along[b.0] - along[a.1]).rem_euclid(round);
    let mut out: Vec<(usize, usize)> = Vec::new();
    for r in runs {
        match out.last_mut() {
            Some(last) if gap(*last, r) <= bridge => last.1 = r.1,
            _ => out.push(r),
        }
    }
    if out.len() >= 2 && gap(out[out.len() - 1], out[0]) <= bridge {
        let last = out.pop().expect("two runs");
        out[0].0 = last.0;
    }
    out
}

/// The margin's places from `run.0` to `run.1` (wrapping round the loop).
fn stretch(places: &[Place], (first, last): (usize, usize)) -> Vec<[f64; 2]> {
    let n = places.len();
    let count = (last + n - first) % n + 1;
    (0..count).map(|k| places[(first + k) % n].at).collect()
}

/// Most places one move of a margin track stands for (bounds the work of
/// [`simplify`]).
const MAX_SKIPPED: usize = 64;

/// `points` without the ones that lie within `tolerance` of the move
/// between their kept neighbours: a straight run becomes one move, an arc
/// stays within the chord error.
fn simplify(points: &[[f64; 2]], tolerance: f64) -> Vec<[f64; 2]> {
    let Some(&first) = points.first() else {
        return Vec::new();
    };
    let mut out = vec![first];
    let mut anchor = 0;
    for j in 2..points.len() {
        let a = points[anchor];
        let fits = j - anchor <= MAX_SKIPPED
            && points[anchor + 1..j]
                .iter()
                .all(|&p| distance2(p, &[a, points[j]]) <= tolerance * tolerance);
        if !fits {
            anchor = j - 1;
            out.push(points[anchor]);
        }
    }
    if points.len() >= 2 {
        out.push(points[points.len() - 1]);
    }
    out
}

/// The edges' closing tracks by the cells of `u` they span (cells as tall
/// as the reach looked within), so a place looks only at those near it:
/// each track is in as many cells as its `u` range spans, a few for an
/// edge within 5° of the lines.
struct EdgeCells<'a> {
    edges: &'a [[[f64; 2]; 2]],
    cell: f64,
    cells: HashMap<i64, Vec<usize>>,
}

impl<'a> EdgeCells<'a> {
    fn new(edges: &'a [[[f64; 2]; 2]], cell: f64) -> Self {
        let mut cells: HashMap<i64, Vec<usize>> = HashMap::new();
        for (i, [a, b]) in edges.iter().enumerate() {
            let (lo, hi) = (a[1].min(b[1]) / cell, a[1].max(b[1]) / cell);
            if !(lo.is_finite() && hi.is_finite()) {
                continue;
            }
            for k in lo.floor() as i64..=hi.floor() as i64 {
                cells.entry(k).or_default().push(i);
            }
        }
        EdgeCells { edges, cell, cells }
    }

    /// The tracks in the cells within one of `u`'s.
    fn near(&self, u: f64) -> impl Iterator<Item = [[f64; 2]; 2]> + '_ {
        let k = (u / self.cell).floor() as i64;
        (k - 1..=k + 1)
            .filter_map(|k| self.cells.get(&k))
            .flatten()
            .map(|&i| self.edges[i])
    }
}

/// The distance from `q` (frame coordinates) to the nearest track of
/// `laid` (its edges' tracks by `edges`), looked for up to `within` away
/// (farther reads as infinite). Each line's intervals are sorted: a binary
/// search a line.
fn nearest(q: [f64; 2], within: f64, laid: &Tracks<'_>, edges: &EdgeCells<'_>) -> f64 {
    let dist = |p: [f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]);
    let mut best = f64::INFINITY;
    let lo = laid.line_s.partition_point(|&s| s < q[1] - within);
    let hi = laid.line_s.partition_point(|&s| s <= q[1] + within);
    for k in lo..hi.min(laid.lines.len()) {
        let s = laid.line_s[k];
        let line = &laid.lines[k];
        let i = line.partition_point(|&(_, [_, b])| b < q[0]);
        for j in [i.checked_sub(1), Some(i)].into_iter().flatten() {
            if let Some(&(_, [a, b])) = line.get(j) {
                best = best.min(dist([q[0].clamp(a, b), s]));
            }
        }
    }
    for [a, b] in edges.near(q[1]) {
        best = best.min(distance2(q, &[a, b]).sqrt());
    }
    best
}
