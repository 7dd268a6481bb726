//! An open path of lines and circular arcs: the centre line (or a face) of
//! a wall that does not close on itself — a rib along an edge, a lip along
//! a mould's damaged edge, a fin on a shaft (`wall NAME { along = … }`).
//!
//! Like a [`Profile`](super::profile::Profile) it keeps arcs exact:
//! offsets go through `cavalier_contours` (an open polyline's parallel
//! offset, arcs kept as arcs, round joins outside a corner and trimmed
//! inside), and the measurements — length, distance, flattening, the
//! directions at its ends — come from its exact segments. What makes a
//! path unfit to lay a wall along is a [`PathFault`], which the caller
//! words.

use super::profile::{Segment, Vertex, LINE_BULGE, MAX_COORDINATE};
use cavalier_contours::core::Control;
use cavalier_contours::polyline::{
    PlineIntersect, PlineOffsetOptions, PlineSelfIntersectOptions, PlineSource, PlineSourceMut,
    PlineVertex, Polyline,
};

/// A piece shorter than this (mm) has no length: two points written the
/// same, or an arc that turns by nothing.
pub const MIN_PIECE: f64 = 1e-6;

/// How far (mm) an offset's ends may lie from where the path's ends,
/// moved square to it, put them: further, and the offset lost a piece of
/// its own (it collapsed there).
const END_TOLERANCE: f64 = 1e-3;

/// Why a path cannot carry a wall.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PathFault {
    /// Fewer than two points: no piece at all.
    TooFewPoints,
    /// Piece `piece` (from 0) has no length.
    ZeroLength {
        /// The piece, from 0.
        piece: usize,
    },
    /// A coordinate is not a finite number, or is beyond what the offset
    /// engine takes ([`MAX_COORDINATE`]).
    NotFinite,
    /// Two pieces cross or touch (or the path runs back over itself) at
    /// `at`.
    Crosses {
        /// Where, mm.
        at: [f64; 2],
    },
    /// Arc `piece` bends at `radius`, tighter than the wall reaches to its
    /// inside (`reach`): the beads and the face on that side would collapse
    /// into its centre.
    ArcTooTight {
        /// The arc, from 0.
        piece: usize,
        /// Its radius, mm.
        radius: f64,
        /// How far the wall reaches to the arc's inside, mm.
        reach: f64,
    },
    /// The wall's face `reach` to one side of the path runs into itself (a
    /// sharp bend whose inside eats a whole piece, or two stretches of the
    /// path closer than the wall is wide), first near `at`, where the
    /// face comes within `apart` of the path at `other` (when found).
    Collapses {
        /// Near where, on the path, mm.
        at: [f64; 2],
        /// The face's signed distance from the path, mm (positive: left).
        reach: f64,
        /// The point of another stretch of the path the face comes too
        /// close to, and how close, mm.
        other: Option<([f64; 2], f64)>,
    },
}

/// An open path: vertices, each with the bulge of the piece that leaves it
/// (the last one's is 0).
#[derive(Clone, Debug, PartialEq)]
pub struct OpenPath {
    vertices: Vec<Vertex>,
    /// For each piece, the piece of the path as written it is part of (an
    /// arc of more than a half circle is split in two here).
    written: Vec<usize>,
}

impl OpenPath {
    /// The path through `vertices`, in order; each vertex's bulge is the
    /// piece that leaves it (`tan(sweep/4)`, positive counter-clockwise).
    /// Refuses fewer than two points, a coordinate that is not finite (or
    /// too large) and a piece of no length. Arcs of more than a half circle
    /// are split in two; pieces keep their number as written in faults.
    pub fn new(vertices: &[Vertex]) -> Result<OpenPath, PathFault> {
        if vertices.len() < 2 {
            return Err(PathFault::TooFewPoints);
        }
        let finite = |v: &Vertex| {
            [v.x, v.y, v.bulge].iter().all(|c| c.is_finite())
                && v.x.abs() <= MAX_COORDINATE
                && v.y.abs() <= MAX_COORDINATE
        };
        if !vertices.iter().all(finite) {
            return Err(PathFault::NotFinite);
        }
        let mut out = Vec::with_capacity(vertices.len() + 1);
        let mut written = Vec::with_capacity(vertices.len());
        for (i, w) in vertices.windows(2).enumerate() {
            let (a, b) = (w[0], w[1]);
            let bulge = if a.bulge.abs() <= LINE_BULGE {
                0.0
            } else {
                a.bulge
            };
            let chord = (b.x - a.x).hypot(b.y - a.y);
            if chord < MIN_PIECE {
                return Err(PathFault::ZeroLength { piece: i });
            }
            if bulge.abs() > 1.0 {
                // More than a half circle: split at its middle, each half
                // a quarter of the sweep's bulge.
                let Segment::Arc {
                    centre,
                    radius,
                    start,
                    sweep,
                    ..
                } = Segment::new([a.x, a.y], [b.x, b.y], bulge)
                else {
                    return Err(PathFault::NotFinite);
                };
                let mid = start + sweep / 2.0;
                let half = (sweep / 8.0).tan();
                out.push(Vertex::arc(a.x, a.y, half));
                out.push(Vertex::arc(
                    centre[0] + radius * mid.cos(),
                    centre[1] + radius * mid.sin(),
                    half,
                ));
                written.extend([i, i]);
            } else {
                out.push(Vertex::arc(a.x, a.y, bulge));
                written.push(i);
            }
        }
        let last = vertices[vertices.len() - 1];
        out.push(Vertex::line(last.x, last.y));
        Ok(OpenPath {
            vertices: out,
            written,
        })
    }

    /// The vertices (the last one's bulge is 0).
    pub fn vertices(&self) -> &[Vertex] {
        &self.vertices
    }

    /// The pieces, in order.
    pub fn segments(&self) -> impl Iterator<Item = Segment> + '_ {
        self.vertices
            .windows(2)
            .map(|w| Segment::new([w[0].x, w[0].y], [w[1].x, w[1].y], w[0].bulge))
    }

    /// The path's length, mm (exact: arcs by their radius and sweep).
    pub fn length(&self) -> f64 {
        self.segments().map(|s| segment_length(&s)).sum()
    }

    /// The first point.
    pub fn start(&self) -> [f64; 2] {
        let v = self.vertices[0];
        [v.x, v.y]
    }

    /// The last point.
    pub fn end(&self) -> [f64; 2] {
        let v = self.vertices[self.vertices.len() - 1];
        [v.x, v.y]
    }

    /// The unit direction of travel at the start.
    pub fn start_direction(&self) -> [f64; 2] {
        let a = self.segments().next().map_or(0.0, |s| s.start_tangent());
        [a.cos(), a.sin()]
    }

    /// The unit direction of travel at the end.
    pub fn end_direction(&self) -> [f64; 2] {
        let a = self.segments().last().map_or(0.0, |s| s.end_tangent());
        [a.cos(), a.sin()]
    }

    /// The same path run the other way.
    pub fn reversed(&self) -> OpenPath {
        let n = self.vertices.len();
        let vertices = (0..n)
            .rev()
            .map(|i| {
                // The piece that left vertex i − 1 now leaves vertex i,
                // turning the other way.
                let bulge = if i > 0 {
                    -self.vertices[i - 1].bulge
                } else {
                    0.0
                };
                Vertex::arc(self.vertices[i].x, self.vertices[i].y, bulge)
            })
            .collect();
        let written = self.written.iter().rev().copied().collect();
        OpenPath { vertices, written }
    }

    /// The exact distance from `p` to the path, mm.
    pub fn distance(&self, p: [f64; 2]) -> f64 {
        self.segments()
            .map(|s| s.distance(p))
            .fold(f64::INFINITY, f64::min)
    }

    /// The points that follow the path within `chord_error`: every vertex,
    /// and arcs flattened between them; the last point is the path's end.
    pub fn flatten(&self, chord_error: f64) -> Vec<[f64; 2]> {
        let mut out = Vec::with_capacity(self.vertices.len());
        for s in self.segments() {
            s.flatten_into(chord_error, &mut out);
        }
        out.push(self.end());
        out
    }

    /// How many points [`OpenPath::flatten`] gives at `chord_error`.
    pub fn points(&self, chord_error: f64) -> usize {
        self.segments()
            .map(|s| s.chords(chord_error))
            .sum::<usize>()
            + 1
    }

    fn to_pline(&self) -> Polyline<f64> {
        let mut pl = Polyline::new();
        for v in &self.vertices {
            pl.add(v.x, v.y, v.bulge);
        }
        pl
    }

    /// Where two pieces that do not follow each other cross or touch, or
    /// neighbours fold back over each other; `None` for a simple path.
    pub fn self_intersection(&self) -> Option<[f64; 2]> {
        let options = PlineSelfIntersectOptions {
            pos_equal_eps: super::profile::TOLERANCE,
            ..Default::default()
        };
        let mut found = None;
        let _: Control<()> = self.to_pline().visit_self_intersects_opt(
            &mut |i: PlineIntersect<f64>| {
                let p = match i {
                    PlineIntersect::Basic(b) => b.point,
                    PlineIntersect::Overlapping(o) => o.point1,
                };
                found = Some([p.x, p.y]);
                Control::Break(())
            },
            &options,
        );
        found
    }

    /// The path moved `d` square to itself (positive: to the left of the
    /// direction of travel), arcs kept as arcs, round outside a corner and
    /// trimmed inside; `None` where it does not come out as one path from
    /// the start moved by `d` to the end moved by `d` (it collapsed).
    pub fn offset(&self, d: f64) -> Option<OpenPath> {
        if d == 0.0 {
            return Some(self.clone());
        }
        if !d.is_finite() {
            return None;
        }
        let options = PlineOffsetOptions::default();
        let pieces = self.to_pline().parallel_offset_opt(d, &options);
        let [pl] = &pieces[..] else {
            return None;
        };
        let vertices: Vec<Vertex> = pl
            .iter_vertexes()
            .map(|v: PlineVertex<f64>| Vertex::arc(v.x, v.y, v.bulge))
            .collect();
        let moved = |p: [f64; 2], dir: [f64; 2]| [p[0] - d * dir[1], p[1] + d * dir[0]];
        let want = [
            moved(self.start(), self.start_direction()),
            moved(self.end(), self.end_direction()),
        ];
        let got = [vertices.first()?, vertices.last()?].map(|v| [v.x, v.y]);
        let near = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]) <= END_TOLERANCE;
        if !(near(got[0], want[0]) && near(got[1], want[1])) {
            return None;
        }
        // Pieces the engine left shorter than a point are dropped.
        let mut kept: Vec<Vertex> = Vec::with_capacity(vertices.len());
        for v in vertices {
            match kept.last_mut() {
                Some(last) if (last.x - v.x).hypot(last.y - v.y) < MIN_PIECE => {
                    last.bulge = v.bulge;
                }
                _ => kept.push(v),
            }
        }
        let path = OpenPath::new(&kept).ok()?;
        path.self_intersection().is_none().then_some(path)
    }

    /// Whether a wall reaching `left` to the left of the path and `right`
    /// to its right (both ≥ 0, mm) can be laid along it: no arc tighter
    /// than the wall's reach to its inside, and each face an offset that
    /// does not run into itself. The first fault found.
    pub fn wall_fault(&self, left: f64, right: f64) -> Option<PathFault> {
        for (k, s) in self.segments().enumerate() {
            if let Segment::Arc { radius, sweep, .. } = s {
                // The centre lies to the left of a counter-clockwise arc.
                let reach = if sweep > 0.0 { left } else { right };
                if reach >= radius {
                    return Some(PathFault::ArcTooTight {
                        piece: self.written[k],
                        radius,
                        reach,
                    });
                }
            }
        }
        for reach in [left, -right] {
            if reach != 0.0 && self.offset(reach).is_none() {
                let (at, other) = match self.too_close(reach) {
                    Some((at, other, apart)) => (at, Some((other, apart))),
                    None => (self.collapse_near(reach), None),
                };
                return Some(PathFault::Collapses { at, reach, other });
            }
        }
        None
    }

    /// Near where the face `reach` from the path first fails: the path's
    /// point nearest to where the longest offset piece that starts right
    /// ends (the path's start when none does).
    fn collapse_near(&self, reach: f64) -> [f64; 2] {
        let pieces = self
            .to_pline()
            .parallel_offset_opt(reach, &PlineOffsetOptions::default());
        let start = self.start();
        let moved = [
            start[0] - reach * self.start_direction()[1],
            start[1] + reach * self.start_direction()[0],
        ];
        let first = pieces.iter().find(|pl| {
            pl.iter_vertexes()
                .next()
                .is_some_and(|v| (v.x - moved[0]).hypot(v.y - moved[1]) <= END_TOLERANCE)
        });
        let Some(end) = first.and_then(|pl| pl.iter_vertexes().next_back()) else {
            return start;
        };
        self.nearest([end.x, end.y])
    }

    /// The first point of the path (sampled along it) whose point on the
    /// face `reach` from it lies closer than `|reach|` to a piece of the
    /// path that is neither its own nor a neighbour of it: that point,
    /// the nearest point of the other piece and how far the face point is
    /// from it.
    fn too_close(&self, reach: f64) -> Option<([f64; 2], [f64; 2], f64)> {
        let segments: Vec<Segment> = self.segments().collect();
        let length = self.length();
        let step = (reach.abs() / 4.0).max(length / 4000.0);
        if !(step > 0.0 && step.is_finite()) {
            return None;
        }
        for (k, s) in segments.iter().enumerate() {
            let n = (segment_length(s) / step).ceil().clamp(1.0, 4000.0) as usize;
            for i in 0..=n {
                let (q, dir) = point_along(s, i as f64 / n as f64);
                let f = [q[0] - reach * dir[1], q[1] + reach * dir[0]];
                let found = segments
                    .iter()
                    .enumerate()
                    .filter(|(m, _)| m.abs_diff(k) > 1)
                    .map(|(_, o)| (o.distance(f), o))
                    .find(|(d, _)| *d < reach.abs() * (1.0 - 1e-6));
                if let Some((apart, o)) = found {
                    return Some((q, foot(o, f), apart));
                }
            }
        }
        None
    }

    /// The path's point nearest to `p` (its vertex or the foot on a line;
    /// on an arc, the nearer end where the foot is off it).
    fn nearest(&self, p: [f64; 2]) -> [f64; 2] {
        let mut best = (f64::INFINITY, self.start());
        for s in self.segments() {
            let q = foot(&s, p);
            let d = (q[0] - p[0]).hypot(q[1] - p[1]);
            if d < best.0 {
                best = (d, q);
            }
        }
        best.1
    }

    /// The piece as written that piece `k` (of [`OpenPath::segments`]) is
    /// part of.
    pub fn written_piece(&self, k: usize) -> usize {
        self.written.get(k).copied().unwrap_or(k)
    }
}

/// A piece's length: a chord, or an arc's radius times its sweep.
pub fn segment_length(s: &Segment) -> f64 {
    match *s {
        Segment::Line { from, to } => (to[0] - from[0]).hypot(to[1] - from[1]),
        Segment::Arc { radius, sweep, .. } => radius * sweep.abs(),
    }
}

/// The point a share `t` along `s` and the unit direction of travel there.
fn point_along(s: &Segment, t: f64) -> ([f64; 2], [f64; 2]) {
    match *s {
        Segment::Line { from, to } => {
            let (dx, dy) = (to[0] - from[0], to[1] - from[1]);
            let len = dx.hypot(dy).max(f64::MIN_POSITIVE);
            ([from[0] + t * dx, from[1] + t * dy], [dx / len, dy / len])
        }
        Segment::Arc {
            centre,
            radius,
            start,
            sweep,
            ..
        } => {
            let phi = start + t * sweep;
            let (sn, cs) = phi.sin_cos();
            let turn = sweep.signum();
            (
                [centre[0] + radius * cs, centre[1] + radius * sn],
                [-sn * turn, cs * turn],
            )
        }
    }
}

/// The point of `s` nearest to `p`.
fn foot(s: &Segment, p: [f64; 2]) -> [f64; 2] {
    match *s {
        Segment::Line { from, to } => {
            let (dx, dy) = (to[0] - from[0], to[1] - from[1]);
            let len2 = dx * dx + dy * dy;
            if len2 <= 0.0 || len2.is_nan() {
                return from;
            }
            let t = (((p[0] - from[0]) * dx + (p[1] - from[1]) * dy) / len2).clamp(0.0, 1.0);
            [from[0] + t * dx, from[1] + t * dy]
        }
        Segment::Arc {
            from,
            to,
            centre,
            radius,
            ..
        } => {
            let (vx, vy) = (p[0] - centre[0], p[1] - centre[1]);
            let rc = vx.hypot(vy);
            if rc > 0.0 && s.sweeps(vy.atan2(vx)) {
                [centre[0] + radius * vx / rc, centre[1] + radius * vy / rc]
            } else {
                let d = |a: [f64; 2]| (a[0] - p[0]).hypot(a[1] - p[1]);
                if d(from) <= d(to) {
                    from
                } else {
                    to
                }
            }
        }
    }
}

#[cfg(test)]
mod tests;
