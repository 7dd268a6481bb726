//! The exact clip of lines against a region's loops, shared by the raster,
//! the extension's hole limit, the links and the gap samples.
//!
//! The region is turned so that the lines run along +t; `u` is the
//! coordinate across them (the direction's left normal, +y for 0°). Its
//! boundary is cut into pieces along which `u` only rises — lines, and arcs
//! split at their top and bottom points — so a line at `u = s` crosses a
//! piece at most once, at a `t` found in closed form (`√((r−q)(r+q))` on an
//! arc).
//!
//! The region is closed: the crossings (a piece counts when
//! `lo.u ≤ s < hi.u`, so a vertex on the line is counted once, or twice at a
//! bottom point, never wrongly) give its inside by parity — so holes need no
//! orientation, only that no two loops cross — and the boundary lying on
//! the line within [`TOLERANCE`] — a straight edge along it, a vertex or an
//! arc's top touching it — is added to that. No nudging: a line exactly on
//! an edge gives the edge.

use crate::geometry::profile::{Profile, Segment, TOLERANCE};
use std::f64::consts::{FRAC_PI_2, TAU};

/// An arc's top or bottom this close (rad) to its end is its end: no split.
const ANGLE_EPS: f64 = 1e-12;

/// The raster's frame: `t` along the lines, `u` across.
#[derive(Clone, Copy, Debug)]
pub(super) struct Frame {
    cos: f64,
    sin: f64,
}

impl Frame {
    pub(super) fn new(angle_deg: f64) -> Frame {
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

    pub(super) fn local(&self, p: [f64; 2]) -> [f64; 2] {
        [
            p[0] * self.cos + p[1] * self.sin,
            -p[0] * self.sin + p[1] * self.cos,
        ]
    }

    pub(super) fn world(&self, q: [f64; 2]) -> [f64; 2] {
        [
            q[0] * self.cos - q[1] * self.sin,
            q[0] * self.sin + q[1] * self.cos,
        ]
    }
}

/// A piece of boundary along which `u` does not fall, in the raster frame.
#[derive(Clone, Copy, Debug)]
pub(super) struct Piece {
    /// End with the lower `u`, `[t, u]`.
    pub lo: [f64; 2],
    /// End with the higher `u`.
    pub hi: [f64; 2],
    /// For an arc: centre, radius and which side of the centre (+1 larger
    /// `t`, -1 smaller) the piece lies on.
    pub arc: Option<([f64; 2], f64, f64)>,
    /// The loop it belongs to (its place among the loops given).
    pub loop_id: u32,
    /// Whether the loop runs along it from `lo` to `hi`.
    pub rising: bool,
    /// For an arc: whether the region lies inside its circle (a convex edge).
    pub convex: bool,
}

impl Piece {
    /// Where the line `u = s` crosses, for `lo.u ≤ s < hi.u`.
    pub fn crossing(&self, s: f64) -> f64 {
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

    /// Whether the line `u = s` crosses it (the half-open rule).
    pub fn spans(&self, s: f64) -> bool {
        self.lo[1] <= s && s < self.hi[1]
    }

    /// Exact distance from `p` (frame coordinates) to the piece.
    pub fn distance(&self, p: [f64; 2]) -> f64 {
        let d = |a: [f64; 2]| (p[0] - a[0]).hypot(p[1] - a[1]);
        match self.arc {
            None => {
                let (dx, dy) = (self.hi[0] - self.lo[0], self.hi[1] - self.lo[1]);
                let len2 = dx * dx + dy * dy;
                if len2.is_nan() || len2 <= 0.0 {
                    return d(self.lo);
                }
                let f =
                    (((p[0] - self.lo[0]) * dx + (p[1] - self.lo[1]) * dy) / len2).clamp(0.0, 1.0);
                d([self.lo[0] + f * dx, self.lo[1] + f * dy])
            }
            Some((c, r, side)) => {
                let (vx, vy) = (p[0] - c[0], p[1] - c[1]);
                let rc = vx.hypot(vy);
                if rc == 0.0 {
                    return r;
                }
                // The nearest point of the circle, if it is on this piece.
                let q = [c[0] + r * vx / rc, c[1] + r * vy / rc];
                if q[1] >= self.lo[1] && q[1] <= self.hi[1] && (q[0] - c[0]) * side >= 0.0 {
                    (rc - r).abs()
                } else {
                    d(self.lo).min(d(self.hi))
                }
            }
        }
    }
}

/// The boundary of some loops as pieces monotone in `u`, with the range of
/// pieces each loop has (in the loop's order of travel).
#[derive(Clone, Debug, Default)]
pub(super) struct Pieces {
    pub items: Vec<Piece>,
    /// `items[loops[i].0 .. loops[i].1]` are loop `i`'s pieces.
    pub loops: Vec<(usize, usize)>,
    /// Whether loop `i` is a hole (the region on its right: every loop
    /// runs counter-clockwise).
    pub holes: Vec<bool>,
}

impl Pieces {
    /// The pieces of `loops` (each with whether it is a hole) in `frame`.
    pub fn new<'a>(loops: impl IntoIterator<Item = (&'a Profile, bool)>, frame: &Frame) -> Pieces {
        let mut out = Pieces::default();
        for (id, (profile, hole)) in loops.into_iter().enumerate() {
            let start = out.items.len();
            let v = profile.vertices();
            let n = v.len();
            if n >= 2 {
                for i in 0..n {
                    let (a, b) = (v[i], v[(i + 1) % n]);
                    // Turning keeps an arc's bulge: it preserves orientation.
                    let seg =
                        Segment::new(frame.local([a.x, a.y]), frame.local([b.x, b.y]), a.bulge);
                    // Every loop is stored counter-clockwise: the region is
                    // inside a left-turning arc of an outer loop, outside one
                    // of a hole.
                    split(&seg, id as u32, (a.bulge > 0.0) != hole, &mut out.items);
                }
            }
            out.loops.push((start, out.items.len()));
            out.holes.push(hole);
        }
        out
    }

    /// The piece after (`forward`) or before piece `i` along its loop.
    pub fn neighbour(&self, i: usize, forward: bool) -> usize {
        let (a, b) = self.loops[self.items[i].loop_id as usize];
        if forward {
            if i + 1 < b {
                i + 1
            } else {
                a
            }
        } else if i > a {
            i - 1
        } else {
            b - 1
        }
    }

    /// The lowest and highest `u` of all pieces, if any.
    pub fn extent(&self) -> Option<(f64, f64)> {
        let lo = self.items.iter().map(|p| p.lo[1]).reduce(f64::min)?;
        let hi = self.items.iter().map(|p| p.hi[1]).fold(lo, f64::max);
        Some((lo, hi))
    }
}

/// Cuts a segment at the top and bottom points of its circle.
fn split(seg: &Segment, loop_id: u32, convex: bool, out: &mut Vec<Piece>) {
    let piece = |a: [f64; 2], b: [f64; 2], arc| {
        let rising = a[1] <= b[1];
        let (lo, hi) = if rising { (a, b) } else { (b, a) };
        Piece {
            lo,
            hi,
            arc,
            loop_id,
            rising,
            convex,
        }
    };
    let Segment::Arc {
        from,
        to,
        centre,
        radius,
        start,
        sweep,
    } = *seg
    else {
        out.push(piece(seg.from(), seg.to(), None));
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
        out.push(piece(w[0].1, w[1].1, Some((centre, radius, side))));
    }
}

/// Buffers reused from line to line.
#[derive(Default)]
pub(super) struct Scratch {
    crossings: Vec<(f64, u32)>,
    intervals: Vec<[f64; 2]>,
}

impl Scratch {
    /// The closed region's intervals on the line `u = s` over the pieces
    /// `which` of `pieces`, sorted, disjoint.
    pub fn clip(
        &mut self,
        pieces: &[Piece],
        which: impl Iterator<Item = usize>,
        s: f64,
    ) -> Vec<[f64; 2]> {
        self.crossings.clear();
        self.intervals.clear();
        for i in which {
            let p = &pieces[i];
            if p.spans(s) {
                self.crossings.push((p.crossing(s), i as u32));
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
        self.crossings.sort_by(|a, b| a.0.total_cmp(&b.0));
        // Closed loops cross a line an even number of times under the
        // half-open rule; inside lies between the 1st and 2nd, 3rd and 4th…
        for c in self.crossings.chunks_exact(2) {
            self.intervals.push([c[0].0, c[1].0]);
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

    /// The piece whose crossing of the last clipped line is exactly at `t`,
    /// if exactly one is: where an interval's end meets the boundary.
    pub fn crossing_at(&self, t: f64) -> Option<u32> {
        let k = self.crossings.partition_point(|c| c.0 < t);
        match self.crossings.get(k..k + 2) {
            Some([a, b]) if a.0 == t && b.0 == t => None,
            _ => self.crossings.get(k).filter(|c| c.0 == t).map(|c| c.1),
        }
    }

    /// Each loop's own inside on the line `u = s`, as if it alone were
    /// given (no parity between loops: grown holes may overlap), merged.
    pub fn clip_each(
        &mut self,
        pieces: &[Piece],
        which: impl Iterator<Item = usize>,
        s: f64,
    ) -> Vec<[f64; 2]> {
        self.crossings.clear();
        for i in which {
            let p = &pieces[i];
            if p.spans(s) {
                self.crossings.push((p.crossing(s), p.loop_id));
            }
        }
        self.crossings
            .sort_by(|a, b| a.1.cmp(&b.1).then(a.0.total_cmp(&b.0)));
        let mut out: Vec<[f64; 2]> = Vec::new();
        for run in self.crossings.chunk_by(|a, b| a.1 == b.1) {
            out.extend(run.chunks_exact(2).map(|c| [c[0].0, c[1].0]));
        }
        out.sort_by(|x, y| x[0].total_cmp(&y[0]));
        let mut merged: Vec<[f64; 2]> = Vec::new();
        for i in out {
            match merged.last_mut() {
                Some(m) if i[0] <= m[1] => m[1] = m[1].max(i[1]),
                _ => merged.push(i),
            }
        }
        merged
    }
}

/// For each of the sorted line positions `s`, the pieces that may touch
/// it: calls `each(n, active)` line after line. Linear in pieces plus the
/// lines each spans.
pub(super) fn sweep(pieces: &[Piece], s: &[f64], mut each: impl FnMut(usize, &[usize])) {
    if s.is_empty() {
        return;
    }
    let last = s.len() - 1;
    let range = |p: &Piece| {
        let first = s.partition_point(|&x| x < p.lo[1] - TOLERANCE);
        let end = s.partition_point(|&x| x <= p.hi[1] + TOLERANCE);
        (first, end.min(last + 1))
    };
    let ranges: Vec<(usize, usize)> = pieces.iter().map(range).collect();
    let mut order: Vec<usize> = (0..pieces.len())
        .filter(|&i| ranges[i].0 < ranges[i].1)
        .collect();
    order.sort_by_key(|&i| ranges[i].0);
    let mut next = 0;
    let mut active: Vec<usize> = Vec::new();
    for n in 0..s.len() {
        while next < order.len() && ranges[order[next]].0 <= n {
            active.push(order[next]);
            next += 1;
        }
        active.retain(|&i| ranges[i].1 > n);
        each(n, &active);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::profile::Vertex;

    fn clip_all(region: &[Profile], angle: f64, s: f64) -> Vec<[f64; 2]> {
        let ps = Pieces::new(region.iter().map(|p| (p, false)), &Frame::new(angle));
        Scratch::default().clip(&ps.items, 0..ps.items.len(), s)
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
        let ps = Pieces::new([(&Profile::circle(2.0), false)], &Frame::new(0.0));
        assert_eq!(ps.items.len(), 4);
        for p in &ps.items {
            assert!(p.lo[1] <= p.hi[1]);
            assert!(p.hi[1] - p.lo[1] > 1.9);
            assert!(p.convex);
        }
        assert_eq!(ps.neighbour(3, true), 0);
        assert_eq!(ps.neighbour(0, false), 3);
        let hole = Pieces::new([(&Profile::circle(2.0), true)], &Frame::new(0.0));
        assert!(hole.items.iter().all(|p| !p.convex));
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

    #[test]
    fn a_hole_splits_the_line_by_parity_and_its_edge_stays() {
        let outer = Profile::rectangle(10.0, 10.0);
        let hole = Profile::circle(2.0).placed(0.0, [5.0, 5.0]);
        let ps = Pieces::new([(&outer, false), (&hole, true)], &Frame::new(0.0));
        let mut sc = Scratch::default();
        let got = sc.clip(&ps.items, 0..ps.items.len(), 5.0);
        assert_eq!(got, vec![[0.0, 3.0], [7.0, 10.0]]);
        // The end at the hole is a crossing of one of its pieces.
        let p = sc.crossing_at(3.0).expect("a crossing");
        assert_eq!(ps.items[p as usize].loop_id, 1);
        // Tangent to the hole's top: the touch point is inside the region.
        assert_eq!(
            sc.clip(&ps.items, 0..ps.items.len(), 7.0),
            vec![[0.0, 10.0]]
        );
    }

    #[test]
    fn overlapping_loops_clipped_each_by_itself_merge() {
        let a = Profile::circle(2.0);
        let b = Profile::circle(2.0).placed(0.0, [3.0, 0.0]);
        let ps = Pieces::new([(&a, true), (&b, true)], &Frame::new(0.0));
        let got = Scratch::default().clip_each(&ps.items, 0..ps.items.len(), 0.0);
        assert_eq!(got, vec![[-2.0, 5.0]]);
    }

    #[test]
    fn the_sweep_hands_each_line_the_pieces_spanning_it() {
        let ps = Pieces::new([(&Profile::rectangle(4.0, 2.0), false)], &Frame::new(0.0));
        let mut seen = Vec::new();
        sweep(&ps.items, &[-1.0, 0.0, 1.0, 2.0, 3.0], |n, active| {
            seen.push((n, active.len()))
        });
        assert_eq!(seen, vec![(0, 0), (1, 3), (2, 2), (3, 3), (4, 0)]);
    }
}
