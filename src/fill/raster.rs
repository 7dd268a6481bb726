//! Raster lines clipped exactly against the raster region.
//!
//! The region is turned so that the lines run along +t; `u` is the
//! coordinate across them (the direction's left normal, +y for 0°). Its
//! boundary is cut into pieces along which `u` only rises — lines, and arcs
//! split at their top and bottom points — so a line at `u = s` crosses a
//! piece at most once, at a `t` found in closed form (`√((r−q)(r+q))` on an
//! arc). The pieces are swept in order of `u`: each line only looks at the
//! pieces that span it.
//!
//! The region is closed: the crossings (a piece counts when
//! `lo.u ≤ s < hi.u`, so a vertex on the line is counted once, or twice at a
//! bottom point, never wrongly) give its inside, and the boundary lying on
//! the line within [`TOLERANCE`] — a straight edge along it, a vertex or an
//! arc's top touching it — is added to that. No nudging: a line exactly on
//! an edge gives the edge.

use super::extend::extend;
use super::{
    spend, too_many_points, Count, FillError, Pattern, RasterSpec, Track, TrackKind, MAX_LINES,
};
use crate::geometry::profile::{Profile, Segment, TOLERANCE};
use std::f64::consts::{FRAC_PI_2, TAU};

/// Lines up to this fraction of an offset past the region's far extreme
/// still count, so that a region exactly `k` offsets wide gets `k + 1` lines
/// despite rounding.
const LINE_SLACK: f64 = 1e-9;

/// More than this many offsets left over past the last line gets a closing
/// line on the far extreme.
pub const CLOSING: f64 = 0.5;

/// An arc's top or bottom this close (rad) to its end is its end: no split.
const ANGLE_EPS: f64 = 1e-12;

/// The raster's frame: `t` along the lines, `u` across.
#[derive(Clone, Copy, Debug)]
struct Frame {
    cos: f64,
    sin: f64,
}

impl Frame {
    fn new(angle_deg: f64) -> Frame {
        let a = angle_deg.rem_euclid(360.0);
        // Exact at right angles, so that a raster along an axis-parallel
        // edge sees that edge exactly parallel.
        let (sin, cos) = match a {
            _ if a == 0.0 || a == 360.0 => (0.0, 1.0),
            _ if a == 90.0 => (1.0, 0.0),
            _ if a == 180.0 => (0.0, -1.0),
            _ if a == 270.0 => (-1.0, 0.0),
            _ => a.to_radians().sin_cos(),
        };
        Frame { cos, sin }
    }

    fn local(&self, p: [f64; 2]) -> [f64; 2] {
        [
            p[0] * self.cos + p[1] * self.sin,
            -p[0] * self.sin + p[1] * self.cos,
        ]
    }

    fn world(&self, q: [f64; 2]) -> [f64; 2] {
        [
            q[0] * self.cos - q[1] * self.sin,
            q[0] * self.sin + q[1] * self.cos,
        ]
    }
}

/// A piece of boundary along which `u` does not fall, in the raster frame.
#[derive(Clone, Copy, Debug)]
struct Piece {
    /// End with the lower `u`, `[t, u]`.
    lo: [f64; 2],
    /// End with the higher `u`.
    hi: [f64; 2],
    /// For an arc: centre, radius and which side of the centre (+1 larger
    /// `t`, -1 smaller) the piece lies on.
    arc: Option<([f64; 2], f64, f64)>,
}

impl Piece {
    fn new(a: [f64; 2], b: [f64; 2], arc: Option<([f64; 2], f64, f64)>) -> Piece {
        let (lo, hi) = if a[1] <= b[1] { (a, b) } else { (b, a) };
        Piece { lo, hi, arc }
    }

    /// Where the line `u = s` crosses, for `lo.u ≤ s < hi.u`.
    fn crossing(&self, s: f64) -> f64 {
        if s == self.lo[1] {
            return self.lo[0];
        }
        match self.arc {
            None => {
                let f = (s - self.lo[1]) / (self.hi[1] - self.lo[1]);
                self.lo[0] + f * (self.hi[0] - self.lo[0])
            }
            Some((c, r, side)) => {
                let q = s - c[1];
                // (r − q)(r + q) rather than r² − q²: exact near a tangent.
                c[0] + side * ((r - q) * (r + q)).max(0.0).sqrt()
            }
        }
    }
}

/// The region's boundary as pieces monotone in `u`.
fn pieces(region: &[Profile], frame: &Frame) -> Vec<Piece> {
    let mut out = Vec::new();
    for profile in region {
        let v = profile.vertices();
        let n = v.len();
        if n < 2 {
            continue;
        }
        for i in 0..n {
            let (a, b) = (v[i], v[(i + 1) % n]);
            // Turning keeps an arc's bulge: it preserves orientation.
            let seg = Segment::new(frame.local([a.x, a.y]), frame.local([b.x, b.y]), a.bulge);
            split(&seg, &mut out);
        }
    }
    out
}

/// Cuts a segment at the top and bottom points of its circle.
fn split(seg: &Segment, out: &mut Vec<Piece>) {
    let Segment::Arc {
        from,
        to,
        centre,
        radius,
        start,
        sweep,
    } = *seg
    else {
        out.push(Piece::new(seg.from(), seg.to(), None));
        return;
    };
    let along = |phi: f64| {
        if sweep > 0.0 {
            (phi - start).rem_euclid(TAU)
        } else {
            (start - phi).rem_euclid(TAU)
        }
    };
    let mut cuts: Vec<(f64, [f64; 2])> = Vec::with_capacity(4);
    cuts.push((0.0, from));
    for (phi, u) in [
        (FRAC_PI_2, centre[1] + radius),
        (-FRAC_PI_2, centre[1] - radius),
    ] {
        let a = along(phi);
        if a > ANGLE_EPS && a < sweep.abs() - ANGLE_EPS {
            cuts.push((a, [centre[0], u]));
        }
    }
    cuts.push((sweep.abs(), to));
    cuts.sort_by(|x, y| x.0.total_cmp(&y.0));
    for w in cuts.windows(2) {
        let mid = start + sweep.signum() * (w[0].0 + w[1].0) / 2.0;
        let side = if mid.cos() >= 0.0 { 1.0 } else { -1.0 };
        out.push(Piece::new(w[0].1, w[1].1, Some((centre, radius, side))));
    }
}

/// The raster tracks over `region` (the loops the raster fills), in travel
/// order; `points_left` is the layer's point budget, spent here.
pub(super) fn tracks(
    region: &[Profile],
    spec: &RasterSpec,
    points_left: &mut u64,
) -> Result<Vec<Track>, FillError> {
    let frame = Frame::new(spec.angle_deg);
    let pieces = pieces(region, &frame);
    let Some(s_min) = pieces.iter().map(|p| p.lo[1]).reduce(f64::min) else {
        return Ok(Vec::new());
    };
    let s_max = pieces.iter().map(|p| p.hi[1]).fold(s_min, f64::max);
    let d = spec.offset;
    let count = ((s_max - s_min) / d + LINE_SLACK).floor() + 1.0;
    if count > MAX_LINES as f64 {
        return Err(FillError::TooManyLines(Count {
            // `as` saturates: a count beyond u64 reads as u64::MAX.
            wanted: count as u64,
            max: MAX_LINES,
        }));
    }
    let count = count as usize;
    // When more than half an offset is left beyond the last whole-offset
    // line, one more line on the far extreme keeps that edge from coming
    // up short by up to an offset (the last two lines are then closer).
    let closing = s_max - (s_min + (count - 1) as f64 * d) > CLOSING * d;
    let count = count + usize::from(closing);
    // Each line's `s`; the last may sit a hair past `s_max`, so clamp it
    // back onto the extreme it is meant to touch.
    let line_s = |n: usize| (s_min + n as f64 * d).min(s_max);

    // The lines each piece may touch, one either side to spare rounding.
    let last = count - 1;
    let range = |p: &Piece| {
        let first = ((p.lo[1] - TOLERANCE - s_min) / d).ceil() - 1.0;
        let end = ((p.hi[1] + TOLERANCE - s_min) / d).floor() + 1.0;
        (first.max(0.0) as usize, (end.max(0.0) as usize).min(last))
    };
    let ranges: Vec<(usize, usize)> = pieces.iter().map(range).collect();
    let visits: u64 = ranges
        .iter()
        .map(|&(a, b)| (b + 1).saturating_sub(a) as u64)
        .sum();
    // Every visit may yield a track end: check the budget before the work.
    if visits > *points_left {
        return Err(too_many_points(*points_left, visits));
    }

    let mut order: Vec<usize> = (0..pieces.len()).collect();
    order.sort_by_key(|&i| ranges[i].0);
    let mut next = 0;
    let mut active: Vec<usize> = Vec::new();
    let mut lines: Vec<Vec<[f64; 2]>> = Vec::with_capacity(count);
    let mut scratch = Scratch::default();
    for n in 0..count {
        while next < order.len() && ranges[order[next]].0 <= n {
            active.push(order[next]);
            next += 1;
        }
        active.retain(|&i| ranges[i].1 >= n);
        let s = line_s(n);
        lines.push(scratch.clip(active.iter().map(|&i| &pieces[i]), s));
    }

    let lines = extend(&lines, spec.extend);
    let mut out = Vec::new();
    let mut forward = true;
    for (n, line) in lines.iter().enumerate() {
        if line.is_empty() {
            continue;
        }
        let s = line_s(n);
        spend(points_left, 2 * line.len())?;
        let track = |a: f64, b: f64| Track {
            kind: TrackKind::Infill,
            points: vec![frame.world([a, s]), frame.world([b, s])],
        };
        if forward {
            out.extend(line.iter().map(|&[a, b]| track(a, b)));
        } else {
            out.extend(line.iter().rev().map(|&[a, b]| track(b, a)));
        }
        if spec.pattern == Pattern::Serpentine {
            forward = !forward;
        }
    }
    Ok(out)
}

/// The closed region's intervals along lines of direction `angle_deg` placed
/// by the caller: for each `s` of `at` (the coordinate along the direction's
/// left normal: +y for 0°, −x for 90°), the intervals of the coordinate
/// along the line (x for 0°, y for 90°), sorted and disjoint. The same exact
/// clip as the raster's, for slicers that space their lines themselves
/// (seed 003's unequal-height tracks). Linear in pieces × lines.
pub fn intervals_at(region: &[Profile], angle_deg: f64, at: &[f64]) -> Vec<Vec<[f64; 2]>> {
    let pieces = pieces(region, &Frame::new(angle_deg));
    let mut scratch = Scratch::default();
    at.iter()
        .map(|&s| {
            let near = pieces
                .iter()
                .filter(|p| p.lo[1] - TOLERANCE <= s && s <= p.hi[1] + TOLERANCE);
            scratch.clip(near, s)
        })
        .collect()
}

/// Points of `region` on a square grid of pitch `h` (rows along x), at most
/// `max` of them — the pitch grows until they fit. Used to look for gaps.
pub(super) fn samples(region: &[Profile], h: f64, max: usize) -> Vec<[f64; 2]> {
    let frame = Frame::new(0.0);
    let pieces = pieces(region, &frame);
    let Some(lo) = pieces.iter().map(|p| p.lo[1]).reduce(f64::min) else {
        return Vec::new();
    };
    let hi = pieces.iter().map(|p| p.hi[1]).fold(lo, f64::max);
    let (t_lo, t_hi) = pieces
        .iter()
        .flat_map(|p| [p.lo[0], p.hi[0]])
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), t| {
            (a.min(t), b.max(t))
        });
    // Arcs bulge past their ends; one pitch of margin either way covers
    // the bounding box estimate for the budget only.
    let cells = ((hi - lo) / h + 1.0) * ((t_hi - t_lo) / h + 1.0);
    let h = if cells.is_finite() && cells > max as f64 {
        h * (cells / max as f64).sqrt()
    } else {
        h
    };
    if !(h.is_finite() && h > 0.0) {
        return Vec::new();
    }
    let mut out = Vec::new();
    let mut scratch = Scratch::default();
    let rows = ((hi - lo) / h).floor() as usize + 1;
    for r in 0..rows.min(max) {
        // Rows sit half a pitch in, so a row never runs along an edge.
        let s = lo + (r as f64 + 0.5) * h;
        if s > hi {
            break;
        }
        for [a, b] in scratch.clip(pieces.iter(), s) {
            let n = ((b - a) / h).floor() as usize + 1;
            for k in 0..n {
                if out.len() >= max {
                    return out;
                }
                let t = (a + (k as f64 + 0.5) * h).min(b);
                out.push(frame.world([t, s]));
            }
        }
    }
    out
}

/// Buffers reused from line to line.
#[derive(Default)]
struct Scratch {
    crossings: Vec<f64>,
    intervals: Vec<[f64; 2]>,
}

impl Scratch {
    /// The closed region's intervals on the line `u = s`, sorted, disjoint.
    fn clip<'a>(&mut self, pieces: impl Iterator<Item = &'a Piece>, s: f64) -> Vec<[f64; 2]> {
        self.crossings.clear();
        self.intervals.clear();
        for p in pieces {
            if p.lo[1] <= s && s < p.hi[1] {
                self.crossings.push(p.crossing(s));
            }
            // The boundary on the line (within tolerance) is in the region.
            if p.lo[1] >= s - TOLERANCE && p.hi[1] <= s + TOLERANCE {
                let (a, b) = (p.lo[0], p.hi[0]);
                self.intervals.push([a.min(b), a.max(b)]);
            } else {
                for end in [p.lo, p.hi] {
                    if (end[1] - s).abs() <= TOLERANCE {
                        self.intervals.push([end[0], end[0]]);
                    }
                }
            }
        }
        self.crossings.sort_by(f64::total_cmp);
        // Closed loops cross a line an even number of times under the
        // half-open rule; inside lies between the 1st and 2nd, 3rd and 4th…
        for c in self.crossings.chunks_exact(2) {
            self.intervals.push([c[0], c[1]]);
        }
        self.intervals.sort_by(|x, y| x[0].total_cmp(&y[0]));
        let mut merged: Vec<[f64; 2]> = Vec::new();
        for &i in &self.intervals {
            match merged.last_mut() {
                Some(m) if i[0] <= m[1] + TOLERANCE => m[1] = m[1].max(i[1]),
                _ => merged.push(i),
            }
        }
        merged
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::profile::Vertex;

    fn clip_all(region: &[Profile], angle: f64, s: f64) -> Vec<[f64; 2]> {
        let ps = pieces(region, &Frame::new(angle));
        Scratch::default().clip(ps.iter(), s)
    }

    #[test]
    fn frame_is_exact_at_right_angles_and_round_trips() {
        let f = Frame::new(90.0);
        assert_eq!(f.local([3.0, 4.0]), [4.0, -3.0]);
        assert_eq!(f.world([4.0, -3.0]), [3.0, 4.0]);
        assert_eq!(Frame::new(-360.0).local([3.0, 4.0]), [3.0, 4.0]);
        let g = Frame::new(33.0);
        let q = g.world(g.local([3.0, 4.0]));
        assert!((q[0] - 3.0).abs() < 1e-14 && (q[1] - 4.0).abs() < 1e-14);
    }

    #[test]
    fn a_full_circle_splits_into_four_monotone_quarters() {
        let ps = pieces(&[Profile::circle(2.0)], &Frame::new(0.0));
        assert_eq!(ps.len(), 4);
        for p in &ps {
            assert!(p.lo[1] <= p.hi[1]);
            assert!(p.hi[1] - p.lo[1] > 1.9);
        }
    }

    #[test]
    fn lines_through_edges_vertices_and_tangents() {
        let sq = [Profile::rectangle(4.0, 2.0)];
        assert_eq!(clip_all(&sq, 0.0, 0.0), vec![[0.0, 4.0]]);
        assert_eq!(clip_all(&sq, 0.0, 2.0), vec![[0.0, 4.0]]);
        assert_eq!(clip_all(&sq, 0.0, 1.0), vec![[0.0, 4.0]]);
        assert_eq!(clip_all(&sq, 0.0, 2.5), Vec::<[f64; 2]>::new());
        let c = [Profile::circle(1.0)];
        assert_eq!(clip_all(&c, 0.0, -1.0), vec![[0.0, 0.0]]);
        assert_eq!(clip_all(&c, 0.0, 1.0), vec![[0.0, 0.0]]);
        let mid = clip_all(&c, 0.0, 0.6);
        assert_eq!(mid.len(), 1);
        assert!((mid[0][0] + 0.8).abs() < 1e-15 && (mid[0][1] - 0.8).abs() < 1e-15);
        // A diamond's top and bottom vertices.
        let diamond = [Profile::new(vec![
            Vertex::line(0.0, -1.0),
            Vertex::line(1.0, 0.0),
            Vertex::line(0.0, 1.0),
            Vertex::line(-1.0, 0.0),
        ])];
        assert_eq!(clip_all(&diamond, 0.0, 1.0), vec![[0.0, 0.0]]);
        assert_eq!(clip_all(&diamond, 0.0, -1.0), vec![[0.0, 0.0]]);
        assert_eq!(clip_all(&diamond, 0.0, 0.0), vec![[-1.0, 1.0]]);
    }
}
