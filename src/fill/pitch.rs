//! The strip each deposit of a layer fills, from the layer's own geometry.
//!
//! A layer rises `A/pitch` where a move passes ([`crate::deposit`]): the
//! pitch is the width of the strip the move's metal fills. Which tracks
//! overlap is decided here from where they lie, not from the slicing's
//! settings: two contours a bead apart are two walls one bead wide, a
//! contour whose loop comes back within a bead of itself (a fin narrower
//! than two beads) overlaps itself, and the last raster track may lie
//! closer to its neighbour (the closing line) or farther from the contour
//! than the offset.
//!
//! Every deposit is sampled along its centre line (every half bead width,
//! at least once a move). At each sample the nearest centre line of
//! another deposit is looked for on either side: its nearest point, beside
//! the sample (within half a bead along the sample's direction, or up to a
//! bead along where it lies at least as far across); the deposit's own
//! line counts where it comes back (more than two bead widths along it
//! away, or turned back by more than 120°: a fin's other side). Only a
//! neighbour within 20° of the sample's direction runs alongside it. A side
//! whose nearest neighbour lies within a bead width `w` at distance `s`
//! fills `s/2` there (the boundary between two beads is halfway). A side
//! with none within a bead is an edge:
//!
//! Deposits that cross beside it, or end beside its middle (within the
//! fill's offset of their end: a raster track's end, extended to fill the
//! staircase a curved edge leaves), are the front of a fill, not
//! neighbours alongside: on a side with only such ends the fill goes on.
//!
//! - on a deposit with no neighbour at all it fills `w/2` (a wall one bead
//!   wide: pitch `w`);
//! - on the edge of a fill at least three deposits across it fills half
//!   the fill's offset, as a track inside would (the documented convention
//!   of the deposit model: the outermost track of a filled layer fills its
//!   pitch like one inside; the band between it and the faces is the
//!   report's, not the plan's), so a filled layer's tracks all fill their
//!   offset, and a closing raster line `c` from its neighbour `(c + d)/2`;
//! - on a deposit whose one neighbour has no further neighbour (a layer
//!   two deposits across: two overlapped contours, a fin's loop) it fills
//!   `w/2`, the bead's own half: their metal spreads over their two beads.
//!
//! A move's pitch is the mean of its samples'. Two neighbours farther
//! apart than a bead (and nearer than two), running parallel, leave a
//! strip between them no bead covers: the widest such gap, found along at
//! least two bead widths of a deposit, is reported ([`Apart`]). The cost is linear in the samples
//! (a uniform grid of the deposits' moves, a bead wide).

/// One deposit of a layer: a track, or a link laid with the laser on,
/// as the polyline its centre follows, in mm.
#[derive(Clone, Copy, Debug)]
pub struct Strand<'a> {
    /// The centre line.
    pub points: &'a [[f64; 2]],
    /// The continuous deposit it is part of: tracks linked with the laser
    /// on and their links are one chain (numbered in the order they come).
    pub chain: usize,
}

/// What [`strips`] finds.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Strips {
    /// Each strand's moves' pitches, mm (one a move: `points.len() − 1`).
    pub pitch: Vec<Vec<f64>>,
    /// The widest gap between two neighbouring deposits, if any are farther
    /// apart than the bead is wide.
    pub apart: Option<Apart>,
}

/// Two neighbouring deposits farther apart than the bead is wide.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Apart {
    /// A point of the one deposit where the gap is widest, mm.
    pub at: [f64; 2],
    /// How far apart their centre lines are there, mm.
    pub apart: f64,
    /// How long the deposit runs so far from its neighbour, mm.
    pub length: f64,
}

/// Most samples a layer gets: the step grows beyond it (a part's layers
/// share [`STRIP_SAMPLES`]).
pub const MAX_STRIP_SAMPLES: usize = 50_000;

/// Samples a whole part's layers share, so that the cost stays linear in
/// the layers however fine the bead (every layer gets at least
/// [`MIN_STRIP_SAMPLES`], and every move one).
pub const STRIP_SAMPLES: usize = 2_000_000;

/// Fewest samples a layer's step is chosen for.
pub const MIN_STRIP_SAMPLES: usize = 2_000;

/// The gap [`strips`] looks for reaches this many bead widths: beyond, the
/// coverage check finds the spot (`fill::gap`).
const REACH: f64 = 2.0;

/// A neighbour of the deposit's own line must lie this many bead widths
/// along it away (else it is the line itself bending).
const OWN: f64 = 2.0;

/// A neighbour runs alongside where its direction is within 20° of the
/// sample's (either way): the cosine. (Raster tracks meeting a contour at
/// a steeper angle end at it: the front of the fill.)
const ALONG: f64 = 0.94;

/// Two neighbours run parallel where their directions are within 1°: the
/// cosine. A strip between them is a gap; where they part at a steeper
/// angle (two contours round a web between a hole and the outline), the
/// wedge is the melt pool's to fill, and `fill::gap` finds a spot too
/// wide.
const PARALLEL: f64 = 0.99985;

/// Neighbours farther apart than the bead by more than this share of it
/// leave a strip unfilled ([`Apart`]): a few per cent is the melt pool's
/// to close, and the scatter of a flattened curve's chords.
const APART: f64 = 0.02;

/// A point of a deposit's centre line, standing for the piece of it
/// `weight` long around it.
#[derive(Clone, Copy)]
struct Sample {
    at: [f64; 2],
    dir: [f64; 2],
    chain: usize,
    /// Arc length along its chain, mm.
    arc: f64,
    weight: f64,
    strand: usize,
    step: usize,
}

/// One move of a deposit, and its samples.
#[derive(Clone, Copy)]
struct Move {
    a: [f64; 2],
    b: [f64; 2],
    chain: usize,
    /// Arc length along its chain where it starts, mm.
    arc: f64,
    len: f64,
    /// Its samples: `first .. first + count`.
    first: usize,
    count: usize,
}

/// The nearest neighbour on one side: its distance, the move it lies on
/// and how far along (0–1).
type Side = Option<(f64, usize, f64)>;

/// A sample's nearest neighbours running alongside it, left and right,
/// and whether other deposits end or cross beside it within a bead on
/// each side (raster tracks ending at a contour: the front of a fill).
#[derive(Clone, Copy, Default)]
struct Sides {
    along: [Side; 2],
    ends: [bool; 2],
    /// Whether the nearest neighbour alongside runs parallel (within 1°):
    /// a strip between the two, not a wedge where they part.
    parallel: [bool; 2],
}

/// The pitch of every move of `strands` with a bead `w` wide (at most
/// `max_samples` samples; `w` itself everywhere when `w` is not a
/// positive length), and the widest gap between neighbours whose middle
/// is `inside` the part.
pub fn strips(
    strands: &[Strand<'_>],
    [w, offset]: [f64; 2],
    max_samples: usize,
    inside: impl Fn([f64; 2]) -> bool,
) -> Strips {
    let flat = |w: f64| Strips {
        pitch: strands
            .iter()
            .map(|s| vec![w; s.points.len().saturating_sub(1)])
            .collect(),
        apart: None,
    };
    let total: f64 = strands.iter().map(|s| length(s.points)).sum();
    if !(w.is_finite() && w > 0.0 && total.is_finite()) {
        return flat(w);
    }
    let step = (w / 2.0).max(total / max_samples.max(1) as f64);
    let (samples, moves, chains) = sample(strands, step);
    let grid = Grid::new(&moves, w);
    let near = Near {
        samples: &samples,
        moves: &moves,
        chains: &chains,
        w,
        offset: if offset > 0.0 && offset <= w {
            offset
        } else {
            w
        },
    };
    let mut seen = vec![usize::MAX; moves.len()];
    let sides: Vec<Sides> = samples
        .iter()
        .enumerate()
        .map(|(i, p)| grid.sides(&near, (i, p), &mut seen))
        .collect();
    let mut pitch: Vec<Vec<(f64, f64)>> = strands
        .iter()
        .map(|s| vec![(0.0, 0.0); s.points.len().saturating_sub(1)])
        .collect();
    let mut gaps = Gaps::new(strands.len(), w);
    for (i, p) in samples.iter().enumerate() {
        let f = near.filled(&sides, i);
        let m = &mut pitch[p.strand][p.step];
        m.0 += f * p.weight;
        m.1 += p.weight;
        gaps.sample(&moves, p, &sides[i], &inside);
    }
    Strips {
        pitch: pitch
            .into_iter()
            .map(|moves| {
                moves
                    .into_iter()
                    .map(|(sum, len)| if len > 0.0 { sum / len } else { w })
                    .collect()
            })
            .collect(),
        apart: gaps.widest(),
    }
}

/// The length of a polyline (mm).
pub(crate) fn length(points: &[[f64; 2]]) -> f64 {
    points
        .windows(2)
        .map(|m| (m[1][0] - m[0][0]).hypot(m[1][1] - m[0][1]))
        .sum()
}

/// Each chain's length, and whether it closes on itself (a contour loop).
#[derive(Clone, Copy, Default)]
struct Chain {
    length: f64,
    closed: bool,
}

/// Samples every move of `strands` about every `step` mm, at least once
/// (the middles of equal pieces); the moves; and the chains.
fn sample(strands: &[Strand<'_>], step: f64) -> (Vec<Sample>, Vec<Move>, Vec<Chain>) {
    let chains = strands.iter().map(|s| s.chain + 1).max().unwrap_or(0);
    let mut arc = vec![0.0; chains];
    let mut ends: Vec<Option<[[f64; 2]; 2]>> = vec![None; chains];
    let (mut samples, mut moves) = (Vec::new(), Vec::new());
    for (si, s) in strands.iter().enumerate() {
        let c = s.chain;
        let (Some(&a), Some(&b)) = (s.points.first(), s.points.last()) else {
            continue;
        };
        ends[c] = Some([ends[c].map_or(a, |e| e[0]), b]);
        for (j, m) in s.points.windows(2).enumerate() {
            let d = [m[1][0] - m[0][0], m[1][1] - m[0][1]];
            let len = d[0].hypot(d[1]);
            if len.is_nan() || len <= 1e-12 {
                continue;
            }
            let n = (len / step).ceil().max(1.0) as usize;
            let dir = [d[0] / len, d[1] / len];
            moves.push(Move {
                a: m[0],
                b: m[1],
                chain: c,
                arc: arc[c],
                len,
                first: samples.len(),
                count: n,
            });
            for k in 0..n {
                let t = (k as f64 + 0.5) / n as f64;
                samples.push(Sample {
                    at: [m[0][0] + d[0] * t, m[0][1] + d[1] * t],
                    dir,
                    chain: c,
                    arc: arc[c] + t * len,
                    weight: len / n as f64,
                    strand: si,
                    step: j,
                });
            }
            arc[c] += len;
        }
    }
    let chains = (0..chains)
        .map(|c| Chain {
            length: arc[c],
            closed: ends[c].is_some_and(|[a, b]| (a[0] - b[0]).hypot(a[1] - b[1]) <= 1e-9),
        })
        .collect();
    (samples, moves, chains)
}

/// What the rule reads: the samples, the moves, the chains and the bead's
/// width.
struct Near<'a> {
    samples: &'a [Sample],
    moves: &'a [Move],
    chains: &'a [Chain],
    w: f64,
    /// The fill's offset: the strip of a deposit the fill's ends reach on
    /// both sides.
    offset: f64,
}

impl Near<'_> {
    /// What sample `i` fills across, by its sides (the module's rule).
    fn filled(&self, sides: &[Sides], i: usize) -> f64 {
        let w = self.w;
        let here = &sides[i];
        let near = |s: Side| s.filter(|&(d, _, _)| d <= w);
        // An edge on side `e`, with the neighbour on the other side at `s`:
        // the fill goes on where deposits end beside it, or past the
        // neighbour.
        let edge = |e: usize, s: f64, m: usize, t: f64| {
            if here.ends[e] || self.beyond(sides, i, m, t) {
                0.5 * (s + self.offset)
            } else {
                0.5 * (s + w)
            }
        };
        match (near(here.along[0]), near(here.along[1])) {
            (Some((l, _, _)), Some((r, _, _))) => 0.5 * (l + r),
            (Some((s, m, t)), None) => edge(1, s, m, t),
            (None, Some((s, m, t))) => edge(0, s, m, t),
            // Only ends beside it: the front of a fill whose tracks end at
            // it, as far from it as their offset.
            (None, None) if here.ends.iter().any(|&e| e) => self.offset,
            (None, None) => w,
        }
    }

    /// Whether sample `p`'s neighbour, `t` along move `m`, has a neighbour
    /// of its own (or ends) on its side away from `p`: a fill going on
    /// past it. (Where `p` lies ahead of it, as a contour beyond a raster
    /// track's end, either of its sides goes on past it.)
    fn beyond(&self, sides: &[Sides], p: usize, m: usize, t: f64) -> bool {
        let mv = &self.moves[m];
        let q = mv.first + ((t * mv.count as f64) as usize).min(mv.count - 1);
        let (a, b) = (&self.samples[p], &self.samples[q]);
        let d = [a.at[0] - b.at[0], a.at[1] - b.at[1]];
        let across = -d[0] * b.dir[1] + d[1] * b.dir[0];
        let ahead = (d[0] * b.dir[0] + d[1] * b.dir[1]).abs();
        let on =
            |k: usize| sides[q].ends[k] || sides[q].along[k].is_some_and(|(s, _, _)| s <= self.w);
        if across.abs() < ahead {
            on(0) || on(1)
        } else if across > 0.0 {
            on(1)
        } else {
            on(0)
        }
    }

    /// Whether the point `t` along move `m` lies within the fill's offset
    /// of its deposit's end: where a raster track's end was extended to
    /// fill the staircase a curved edge leaves (seed 001's `ΔX ≤ d`),
    /// whose metal fills that corner rather than a neighbour's strip.
    fn near_end(&self, chain: usize, arc: f64) -> bool {
        let c = self.chains.get(chain).copied().unwrap_or_default();
        !c.closed && arc.min(c.length - arc) < self.offset
    }

    /// Whether a point `t` along move `m`, on `p`'s own chain, is that
    /// chain coming back beside `p` rather than `p`'s line going on: far
    /// along it, or turned back.
    fn comes_back(&self, p: &Sample, m: &Move, t: f64) -> bool {
        let mut along = (m.arc + t * m.len - p.arc).abs();
        let c = self.chains.get(p.chain).copied().unwrap_or_default();
        if c.closed {
            along = along.min(c.length - along);
        }
        let dir = [(m.b[0] - m.a[0]) / m.len, (m.b[1] - m.a[1]) / m.len];
        along > OWN * self.w || p.dir[0] * dir[0] + p.dir[1] * dir[1] < -0.5
    }
}

/// Gaps wider than the bead between neighbours, summed strand by strand.
struct Gaps {
    w: f64,
    length: Vec<f64>,
    widest: Vec<Option<([f64; 2], f64)>>,
}

impl Gaps {
    fn new(strands: usize, w: f64) -> Self {
        Gaps {
            w,
            length: vec![0.0; strands],
            widest: vec![None; strands],
        }
    }

    /// Notes `p`'s sides: one whose nearest neighbour alongside lies beyond
    /// a bead (but within the reach), and no deposit ends within a bead,
    /// leaves a strip no bead covers, where the
    /// strip's middle is in the part (`inside`: two islands' contours
    /// across the gap between them are no gap).
    fn sample(
        &mut self,
        moves: &[Move],
        p: &Sample,
        sides: &Sides,
        inside: &impl Fn([f64; 2]) -> bool,
    ) {
        // A side where other deposits end within a bead is filled by them.
        let wide = (0..2)
            .filter(|&k| sides.parallel[k] && !sides.ends[k])
            .filter_map(|k| sides.along[k].as_ref())
            .filter(|&&(s, _, _)| s > self.w * (1.0 + APART))
            .filter(|&&(_, m, t)| {
                let q = at(&moves[m], t);
                inside([0.5 * (p.at[0] + q[0]), 0.5 * (p.at[1] + q[1])])
            })
            .map(|&(s, _, _)| s)
            .fold(None, |m: Option<f64>, s| Some(m.map_or(s, |m| m.max(s))));
        if let Some(s) = wide {
            self.length[p.strand] += p.weight;
            let w = &mut self.widest[p.strand];
            if w.is_none_or(|(_, o)| s > o) {
                *w = Some((p.at, s));
            }
        }
    }

    /// The widest gap along a strand that runs at least two bead widths so
    /// far from its neighbour.
    fn widest(self) -> Option<Apart> {
        self.widest
            .into_iter()
            .zip(self.length)
            .filter_map(|(g, len)| {
                g.filter(|_| len >= 2.0 * self.w)
                    .map(|(at, s)| (at, s, len))
            })
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(at, apart, length)| Apart { at, apart, length })
    }
}

/// The point `t` along `m`.
fn at(m: &Move, t: f64) -> [f64; 2] {
    [
        m.a[0] + (m.b[0] - m.a[0]) * t,
        m.a[1] + (m.b[1] - m.a[1]) * t,
    ]
}

/// A uniform grid of the moves, a bead width a cell (larger where the
/// layer is large): each move in every cell its box touches.
struct Grid {
    origin: [f64; 2],
    cell: f64,
    cols: usize,
    rows: usize,
    start: Vec<usize>,
    items: Vec<usize>,
}

/// Most cells the grid has (its cells grow beyond).
const MAX_CELLS: usize = 1 << 20;

impl Grid {
    fn new(moves: &[Move], w: f64) -> Self {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for m in moves {
            for p in [m.a, m.b] {
                for k in 0..2 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
        }
        if moves.is_empty() {
            (lo, hi) = ([0.0; 2], [0.0; 2]);
        }
        let span = [hi[0] - lo[0], hi[1] - lo[1]];
        // About as many cells as moves (at least a bead a cell): a grid
        // finer than the moves costs its cells, not its queries.
        let cells = MAX_CELLS.min(4 * moves.len() + 16) as f64;
        let cell = w.max((span[0] * span[1] / cells).sqrt());
        let cols = ((span[0] / cell).floor() as usize + 1).min(MAX_CELLS);
        let rows = ((span[1] / cell).floor() as usize + 1).min(MAX_CELLS / cols);
        let col = |x: f64| ((((x - lo[0]) / cell).max(0.0)) as usize).min(cols - 1);
        let row = |y: f64| ((((y - lo[1]) / cell).max(0.0)) as usize).min(rows - 1);
        // Each move in the cells it passes through, column by column (not
        // every cell of its box: a long diagonal chord would fill a square
        // of them), counted first and then placed (one list for all cells).
        let visit = |m: &Move, f: &mut dyn FnMut(usize)| {
            let (c0, c1) = (col(m.a[0].min(m.b[0])), col(m.a[0].max(m.b[0])));
            let dx = m.b[0] - m.a[0];
            for c in c0..=c1 {
                let (y0, y1) = if c0 == c1 || dx == 0.0 {
                    (m.a[1], m.b[1])
                } else {
                    let x = |k: usize| lo[0] + k as f64 * cell;
                    let (xa, xb) = (m.a[0].min(m.b[0]), m.a[0].max(m.b[0]));
                    let y = |x: f64| m.a[1] + (m.b[1] - m.a[1]) * ((x - m.a[0]) / dx);
                    (y(x(c).max(xa)), y(x(c + 1).min(xb)))
                };
                for r in row(y0.min(y1))..=row(y0.max(y1)) {
                    f(r * cols + c);
                }
            }
        };
        let mut start = vec![0usize; cols * rows + 1];
        for m in moves {
            visit(m, &mut |k| start[k + 1] += 1);
        }
        for k in 0..cols * rows {
            start[k + 1] += start[k];
        }
        let mut fill = start.clone();
        let mut items = vec![0usize; start[cols * rows]];
        for (i, m) in moves.iter().enumerate() {
            visit(m, &mut |k| {
                items[fill[k]] = i;
                fill[k] += 1;
            });
        }
        Grid {
            origin: lo,
            cell,
            cols,
            rows,
            start,
            items,
        }
    }

    /// `p`'s (sample `i`'s) nearest neighbour on its left and on its
    /// right, within the gap's reach (`seen` marks the moves looked at for
    /// it: a move lies in several cells).
    fn sides(&self, near: &Near<'_>, (i, p): (usize, &Sample), seen: &mut [usize]) -> Sides {
        let w = near.w;
        let reach = REACH * w;
        let span = (reach / self.cell).ceil() as isize;
        let c0 = ((p.at[0] - self.origin[0]) / self.cell) as isize;
        let r0 = ((p.at[1] - self.origin[1]) / self.cell) as isize;
        let normal = [-p.dir[1], p.dir[0]];
        let mut out = Sides::default();
        for r in (r0 - span).max(0)..=(r0 + span).min(self.rows as isize - 1) {
            for c in (c0 - span).max(0)..=(c0 + span).min(self.cols as isize - 1) {
                let k = r as usize * self.cols + c as usize;
                for &j in &self.items[self.start[k]..self.start[k + 1]] {
                    if std::mem::replace(&mut seen[j], i) == i {
                        continue;
                    }
                    let m = &near.moves[j];
                    let t = closest(m, p.at);
                    let q = at(m, t);
                    let d = [q[0] - p.at[0], q[1] - p.at[1]];
                    if d[0] * d[0] + d[1] * d[1] > reach * reach
                        || m.chain == p.chain && !near.comes_back(p, m, t)
                    {
                        continue;
                    }
                    let b = (d[0] * p.dir[0] + d[1] * p.dir[1]).abs();
                    let a = d[0] * normal[0] + d[1] * normal[1];
                    // Beside it: within half a bead along, or farther
                    // along (up to a bead) no more than across.
                    if b > w || (b > w / 2.0 && b > a.abs()) {
                        continue;
                    }
                    // A neighbour on the centre line itself overlaps it
                    // wholly: it counts as a hundredth of a bead away.
                    let s = d[0].hypot(d[1]).max(w / 100.0);
                    let side = usize::from(a < 0.0);
                    let dir = [(m.b[0] - m.a[0]) / m.len, (m.b[1] - m.a[1]) / m.len];
                    // A neighbour's end beside the middle of this one (two
                    // tracks' ends side by side run alongside).
                    let ending =
                        near.near_end(m.chain, m.arc + t * m.len) && !near.near_end(p.chain, p.arc);
                    if (p.dir[0] * dir[0] + p.dir[1] * dir[1]).abs() < ALONG || ending {
                        // Crossing or ending beside it, not alongside.
                        out.ends[side] |= s <= w;
                        continue;
                    }
                    if s > reach {
                        continue;
                    }
                    if out.along[side].is_none_or(|(o, _, _)| s < o) {
                        out.along[side] = Some((s, j, t));
                        out.parallel[side] =
                            (p.dir[0] * dir[0] + p.dir[1] * dir[1]).abs() >= PARALLEL;
                    }
                }
            }
        }
        out
    }
}

/// How far along `m` (0–1) its point nearest `p` lies.
fn closest(m: &Move, p: [f64; 2]) -> f64 {
    let d = [m.b[0] - m.a[0], m.b[1] - m.a[1]];
    let t = ((p[0] - m.a[0]) * d[0] + (p[1] - m.a[1]) * d[1]) / (m.len * m.len);
    t.clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(y: f64, x0: f64, x1: f64) -> Vec<[f64; 2]> {
        vec![[x0, y], [x1, y]]
    }

    fn pitches(lines: &[Vec<[f64; 2]>], [w, offset]: [f64; 2]) -> Strips {
        let strands: Vec<Strand<'_>> = lines
            .iter()
            .enumerate()
            .map(|(i, p)| Strand {
                points: p,
                chain: i,
            })
            .collect();
        strips(&strands, [w, offset], MAX_STRIP_SAMPLES, |_| true)
    }

    fn close(a: f64, b: f64) {
        assert!((a - b).abs() < 1e-9, "{a} != {b}");
    }

    #[test]
    fn a_lone_track_fills_its_bead() {
        let s = pitches(&[line(0.0, 0.0, 50.0)], [3.0, 3.0]);
        close(s.pitch[0][0], 3.0);
        assert_eq!(s.apart, None);
    }

    #[test]
    fn a_fill_of_tracks_fills_its_offset_to_its_edges() {
        // Ten tracks 2 mm apart with a 3 mm bead: every one fills 2 mm,
        // the outermost too (the deposit model's convention).
        let lines: Vec<_> = (0..10).map(|k| line(2.0 * k as f64, 0.0, 40.0)).collect();
        let s = pitches(&lines, [3.0, 2.0]);
        for p in &s.pitch {
            close(p[0], 2.0);
        }
        assert_eq!(s.apart, None);
    }

    #[test]
    fn two_tracks_a_bead_apart_are_two_walls() {
        let s = pitches(&[line(0.0, 0.0, 40.0), line(3.0, 0.0, 40.0)], [3.0, 3.0]);
        close(s.pitch[0][0], 3.0);
        close(s.pitch[1][0], 3.0);
        // Two overlapped tracks spread their metal over their two beads:
        // 1 + 1.5 each.
        let s = pitches(&[line(0.0, 0.0, 40.0), line(2.0, 0.0, 40.0)], [3.0, 2.0]);
        close(s.pitch[0][0], 2.5);
        close(s.pitch[1][0], 2.5);
    }

    #[test]
    fn a_loop_that_comes_back_within_a_bead_overlaps_itself() {
        // A fin 4.5 mm wide, one contour of a 3 mm bead: its loop's long
        // sides run 1.5 mm apart; each fills 0.75 + 1.5 mm.
        let fin = vec![[0.0, 0.0], [40.0, 0.0], [40.0, 1.5], [0.0, 1.5], [0.0, 0.0]];
        let s = pitches(&[fin], [3.0, 3.0]);
        close(s.pitch[0][0], 2.25);
        close(s.pitch[0][2], 2.25);
        // A loop 10 mm wide does not: its sides fill a bead each.
        let wide = vec![
            [0.0, 0.0],
            [40.0, 0.0],
            [40.0, 10.0],
            [0.0, 10.0],
            [0.0, 0.0],
        ];
        let s = pitches(&[wide], [3.0, 3.0]);
        for p in &s.pitch[0] {
            close(*p, 3.0);
        }
    }

    #[test]
    fn a_track_farther_than_a_bead_from_its_neighbour_leaves_a_strip() {
        // Tracks 2.168 mm apart, the last one 3.153 mm from the next (the
        // bracket's raster against its contour, with a 3 mm bead).
        let mut lines: Vec<_> = (0..5).map(|k| line(2.168 * k as f64, 0.0, 40.0)).collect();
        lines.push(line(4.0 * 2.168 + 3.153, 0.0, 40.0));
        let s = pitches(&lines, [3.0, 2.168]);
        let a = s.apart.expect("a strip is left");
        close(a.apart, 3.153);
        assert!(a.length >= 39.0, "{a:?}");
        // The last track of the fill fills its offset (its far side an
        // edge of the fill); the lone one beyond its bead.
        close(s.pitch[4][0], 2.168);
        close(s.pitch[5][0], 3.0);
    }
}
