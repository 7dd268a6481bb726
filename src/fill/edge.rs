//! Closing tracks along the raster region's edges that run with the lines.
//!
//! The raster's lines are spaced from the region's near extreme and closed
//! at its far one ([`super::raster::CLOSING`]), but an edge inside that
//! range running along the lines — a notch's side, a step of the outline,
//! a straight hole's side, or any edge a few degrees off the lines — is
//! wherever the spacing leaves it: the nearest line beside it may lie up to
//! an offset away, and with the contour another offset beyond, the strip
//! between them is wider than the bead (`lmd::fill-gap`). Lines crossing
//! an edge at a steeper angle end at it and are extended into the
//! staircase; these cross it seldom (every `offset / sin(angle)`), and
//! between two crossings the wedge beside it is the gap.
//!
//! So along every straight edge within [`PARALLEL_DEG`] of the lines (a run
//! of pieces along one line counting as one edge), the
//! nearest line on the region's side is looked up every quarter offset;
//! where it runs alongside (its interval as laid covers that place) farther
//! than the closing threshold from the edge, over at least
//! [`MIN_LENGTH`] offsets, a track is laid on the edge, as the closing line
//! is laid on the far extreme. Linear in the edges' length, plus two
//! inside tests (each linear in the region's vertices) for each edge near
//! the lines' direction.

use super::clip::{Frame, Pieces};
use super::extend::Laid;
use crate::geometry::region::Region;

/// Edges within this of the lines' direction (deg) may need a closing
/// track: between two lines that cross such an edge (every
/// `offset / sin(angle)`, 24 mm at 5° for a 2.1 mm offset) the wedge
/// beside it is wider than the bead over more than two offsets; across a
/// steeper edge the lines' ends, extended, fill the staircase.
pub const PARALLEL_DEG: f64 = 5.0;

/// A stretch shorter than this many offsets gets no track (a laser on for
/// less than a bead lays a blob; the gap check looks along two beads).
const MIN_LENGTH: f64 = 2.0;

/// A line this many offsets outside an edge, alongside it, lays along the
/// edge.
const HAIR: f64 = 0.1;

/// Most places an edge is sampled at.
const MAX_SAMPLES: f64 = 100_000.0;

/// How far off the edge (mm) its region side is tested.
const SIDE_PROBE: f64 = 1e-4;

/// The closing tracks (start and end, in the raster's frame) along `region`'s
/// straight edges that run within [`PARALLEL_DEG`] of the lines at
/// `line_s` (their intervals as laid, `lines`, each with the interval it
/// grew from), where the nearest line on
/// the region's side lies more than `threshold` from the edge (at least
/// [`HAIR`] offsets: a bead no wider than the offset would put the track
/// on the line); `offset` the lines' spacing, `extend` the most their ends
/// grow. In the order of the edges along the loops.
pub(super) fn closings(
    region: &Region,
    (pieces, frame): (&Pieces, &Frame),
    (line_s, lines): (&[f64], &[Laid]),
    [threshold, offset, extend]: [f64; 3],
) -> Vec<[[f64; 2]; 2]> {
    let mut out = Vec::new();
    let usable = offset.is_finite() && offset > 0.0 && threshold.is_finite();
    if line_s.is_empty() || !usable {
        return out;
    }
    let threshold = threshold.max(HAIR * offset);
    // A line outside the edge, alongside it, lays along it within this: a
    // hair, or as far as an end grown along an edge off the lines gets.
    let hair = (HAIR * offset).max(extend * PARALLEL_DEG.to_radians().sin());
    let tan = PARALLEL_DEG.to_radians().tan();
    for p in straight_edges(pieces) {
        let (dt, du) = (p.hi[0] - p.lo[0], p.hi[1] - p.lo[1]);
        let len = dt.hypot(du);
        let long = len.is_finite() && len >= MIN_LENGTH * offset;
        if !long || du > tan * dt.abs() {
            continue;
        }
        let at = |f: f64| [p.lo[0] + f * dt, p.lo[1] + f * du];
        let mid = at(0.5);
        let inside = |du: f64| region.contains(frame.world([mid[0], mid[1] + du]));
        let side = match (inside(SIDE_PROBE), inside(-SIDE_PROBE)) {
            (true, false) => 1.0,
            (false, true) => -1.0,
            // A slit or a sliver: the region on both sides or neither.
            _ => continue,
        };
        // Every quarter offset, but a bounded count an edge.
        let n = (len / (offset / 4.0)).ceil().min(MAX_SAMPLES) as usize;
        let far = |q: [f64; 2]| {
            // A line a hair outside the edge (an edge off the lines'
            // direction, touched at its end by the extreme line) lays along
            // it too.
            let along = gap_beside(q, -side, line_s, lines).is_some_and(|g| g <= hair);
            !along && gap_beside(q, side, line_s, lines).is_some_and(|g| g > threshold)
        };
        // Each sample stands for 1/n of the edge, around its middle.
        let mut run: Option<usize> = None;
        for k in 0..=n {
            let open = k < n && far(at((k as f64 + 0.5) / n as f64));
            match (open, run) {
                (true, None) => run = Some(k),
                (false, Some(first)) => {
                    run = None;
                    let (a, b) = (first as f64 / n as f64, k as f64 / n as f64);
                    if (b - a) * len >= MIN_LENGTH * offset {
                        out.push([at(a), at(b)]);
                    }
                }
                _ => {}
            }
        }
    }
    out
}

/// A straight edge of the region in the frame: its ends with the lower and
/// the higher `u`.
struct Edge {
    lo: [f64; 2],
    hi: [f64; 2],
}

/// Pieces whose ends lie this close (mm) to the line of the run before
/// them, and that go on the same way, go on along it.
const COLLINEAR: f64 = 1e-6;

/// The region's straight edges: each run of consecutive straight pieces of
/// a loop that lie along one line, as one edge (a side drawn with points
/// along it, or a mesh's section, comes in pieces each shorter than the
/// [`MIN_LENGTH`] a closing track needs).
fn straight_edges(pieces: &Pieces) -> Vec<Edge> {
    let mut out = Vec::new();
    for &(a, b) in &pieces.loops {
        let items = &pieces.items[a..b];
        let n = items.len();
        let travel = |k: usize| {
            let p = &items[k % n];
            let ends = if p.rising { (p.lo, p.hi) } else { (p.hi, p.lo) };
            p.arc.is_none().then_some(ends)
        };
        let along = |run: ([f64; 2], [f64; 2]), k: usize| {
            travel(k).is_some_and(|(from, to)| {
                let (dx, dy) = (run.1[0] - run.0[0], run.1[1] - run.0[1]);
                let len = dx.hypot(dy);
                let off = |q: [f64; 2]| ((q[0] - run.0[0]) * dy - (q[1] - run.0[1]) * dx) / len;
                let ahead = (to[0] - from[0]) * dx + (to[1] - from[1]) * dy > 0.0;
                len > 0.0 && ahead && off(from).abs() <= COLLINEAR && off(to).abs() <= COLLINEAR
            })
        };
        // Start where a run starts: after a piece the one at `k` does not
        // go on from (a loop all along one line is degenerate: none).
        let Some(start) = (0..n).find(|&k| {
            travel(k).is_some() && !travel(k + n - 1).is_some_and(|prev| along(prev, k))
        }) else {
            continue;
        };
        let mut k = start;
        while k < start + n {
            let Some(mut run) = travel(k) else {
                k += 1;
                continue;
            };
            k += 1;
            while k < start + n && along(run, k) {
                run.1 = travel(k).map_or(run.1, |t| t.1);
                k += 1;
            }
            let (lo, hi) = if run.0[1] <= run.1[1] {
                run
            } else {
                (run.1, run.0)
            };
            out.push(Edge { lo, hi });
        }
    }
    out
}

/// How far from `q` (frame coordinates, on an edge) the nearest line on
/// the region's `side` (+1: higher `u`) lies, when that line runs alongside
/// `q` (one of its intervals covers `q`'s `t`); `None` when none does.
fn gap_beside(q: [f64; 2], side: f64, line_s: &[f64], lines: &[Laid]) -> Option<f64> {
    // A line on the edge, to rounding, is beside it.
    let slack = 1e-9 * (1.0 + q[1].abs());
    let k = if side > 0.0 {
        line_s.partition_point(|&s| s < q[1] - slack)
    } else {
        line_s
            .partition_point(|&s| s <= q[1] + slack)
            .checked_sub(1)?
    };
    let s = *line_s.get(k)?;
    let alongside = lines
        .get(k)?
        .iter()
        .any(|&(_, [a, b])| a - slack <= q[0] && q[0] <= b + slack);
    alongside.then_some((s - q[1]).abs())
}
