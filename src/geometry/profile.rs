//! A closed 2-D profile of lines and circular arcs: the outline of a planar
//! layer. Offsets are exact (arcs stay arcs) through `cavalier_contours`;
//! the measurements (area, distance, bounds, flattening) are computed here
//! from the segments.
//!
//! Lengths are in mm like the rest of the crate; the tolerances below assume
//! that scale.

mod segment;
mod start;

pub use segment::{Segment, LINE_BULGE, MAX_ARC_CHORDS};

use cavalier_contours::core::math::Vector2;
use cavalier_contours::core::Control;
use cavalier_contours::polyline::{
    PlineIntersect, PlineOffsetOptions, PlineSelfIntersectOptions, PlineSource, PlineSourceMut,
    PlineVertex, Polyline, TouchingLoopBehavior,
};

/// Points closer than this are one point; a point this close to the boundary
/// is on it.
pub const TOLERANCE: f64 = 1e-9;

/// A point where the closed polylines `p` (indexed by `index`, when it has
/// one) and `q` cross or touch, if they do: where a region's loops, or a
/// mesh section's, meet.
pub fn meet(
    p: &Polyline<f64>,
    index: Option<&cavalier_contours::static_aabb2d_index::StaticAABB2DIndex<f64>>,
    q: &Polyline<f64>,
) -> Option<[f64; 2]> {
    let options = cavalier_contours::polyline::FindIntersectsOptions {
        pline1_aabb_index: index,
        pos_equal_eps: TOLERANCE,
    };
    let found = p.find_intersects_opt(q, &options);
    found
        .basic_intersects
        .first()
        .map(|i| [i.point.x, i.point.y])
        .or_else(|| {
            found
                .overlapping_intersects
                .first()
                .map(|o| [o.point1.x, o.point1.y])
        })
}

/// Largest coordinate handed to `cavalier_contours`. Beyond it squared
/// distances lose every digit that matters (and eventually overflow), so such
/// profiles are neither offset nor tested for self-intersection.
pub const MAX_COORDINATE: f64 = 1e12;

/// Offset loops smaller than this (mm²) are slivers left where the offset
/// closes up, not room for a track.
pub(crate) const MIN_LOOP_AREA: f64 = 1e-9;

/// A corner of a profile and the bend of the piece that leaves it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vertex {
    /// x, mm.
    pub x: f64,
    /// y, mm.
    pub y: f64,
    /// `tan(swept angle / 4)` of the arc from this vertex to the next:
    /// positive counter-clockwise, 0 a straight line, 1 a half circle.
    pub bulge: f64,
}

impl Vertex {
    /// A vertex followed by a straight line.
    pub fn line(x: f64, y: f64) -> Vertex {
        Vertex { x, y, bulge: 0.0 }
    }

    /// A vertex followed by an arc of the given bulge.
    pub fn arc(x: f64, y: f64, bulge: f64) -> Vertex {
        Vertex { x, y, bulge }
    }

    fn pos(&self) -> [f64; 2] {
        [self.x, self.y]
    }
}

/// A closed loop of lines and arcs, counter-clockwise.
#[derive(Clone, Debug)]
pub struct Profile {
    vertices: Vec<Vertex>,
}

impl Profile {
    /// The closed loop through `vertices` (the last connects to the first).
    ///
    /// Normalises: a vertex within [`TOLERANCE`] of the one before it (or the
    /// last of the first) is dropped, keeping the bulge of the piece that
    /// follows; bulges within [`LINE_BULGE`] of 0 become lines; arcs of more
    /// than a half circle are split in two (the offset engine takes at most
    /// half circles); a clockwise loop is reversed.
    pub fn new(vertices: Vec<Vertex>) -> Profile {
        let mut kept: Vec<Vertex> = Vec::with_capacity(vertices.len());
        for mut v in vertices {
            if v.bulge.abs() <= LINE_BULGE {
                v.bulge = 0.0;
            }
            match kept.last_mut() {
                Some(last) if same(last.pos(), v.pos()) => last.bulge = v.bulge,
                _ => kept.push(v),
            }
        }
        while kept.len() > 1 && same(kept[0].pos(), kept[kept.len() - 1].pos()) {
            kept.pop();
        }
        let mut split = Vec::with_capacity(kept.len());
        for (i, v) in kept.iter().enumerate() {
            let next = kept[(i + 1) % kept.len()];
            if v.bulge.abs() > 1.0 && kept.len() > 1 {
                split.extend(halve(*v, next));
            } else {
                split.push(*v);
            }
        }
        let mut p = Profile { vertices: split };
        if p.signed_area() < 0.0 {
            p.reverse();
        }
        p
    }

    /// A circle of radius `r` centred on the origin.
    pub fn circle(r: f64) -> Profile {
        Profile::new(vec![Vertex::arc(r, 0.0, 1.0), Vertex::arc(-r, 0.0, 1.0)])
    }

    /// A `w` × `h` rectangle with its lower left corner on the origin.
    pub fn rectangle(w: f64, h: f64) -> Profile {
        Profile::new(vec![
            Vertex::line(0.0, 0.0),
            Vertex::line(w, 0.0),
            Vertex::line(w, h),
            Vertex::line(0.0, h),
        ])
    }

    /// A `w` × `h` rectangle with its lower left corner on the origin and
    /// corners rounded by quarter circles of radius `r` (at most half the
    /// shorter side).
    pub fn rounded_rectangle(w: f64, h: f64, r: f64) -> Profile {
        let q = (std::f64::consts::PI / 8.0).tan(); // a quarter circle
        Profile::new(vec![
            Vertex::line(r, 0.0),
            Vertex::arc(w - r, 0.0, q),
            Vertex::line(w, r),
            Vertex::arc(w, h - r, q),
            Vertex::line(w - r, h),
            Vertex::arc(r, h, q),
            Vertex::line(0.0, h - r),
            Vertex::arc(0.0, r, q),
        ])
    }

    /// The vertices, counter-clockwise; each one's bulge bends the piece to
    /// the next.
    pub fn vertices(&self) -> &[Vertex] {
        &self.vertices
    }

    /// The pieces of the loop, the last one closing it.
    pub fn segments(&self) -> impl Iterator<Item = Segment> + '_ {
        let n = self.vertices.len();
        // A lone vertex is a point, not a loop: no pieces.
        let count = if n < 2 { 0 } else { n };
        (0..count).map(move |i| {
            let (a, b) = (self.vertices[i], self.vertices[(i + 1) % n]);
            Segment::new(a.pos(), b.pos(), a.bulge)
        })
    }

    /// Whether every coordinate and bulge is a finite number.
    pub fn is_finite(&self) -> bool {
        self.vertices
            .iter()
            .all(|v| v.x.is_finite() && v.y.is_finite() && v.bulge.is_finite())
    }

    /// The enclosed area (≥ 0 since the loop is counter-clockwise).
    pub fn area(&self) -> f64 {
        self.signed_area()
    }

    fn signed_area(&self) -> f64 {
        self.segments().map(|s| s.double_area()).sum::<f64>() / 2.0
    }

    /// Exact bounding box `[min, max]` (arcs included); `None` for a profile
    /// without vertices.
    pub fn bounds(&self) -> Option<[[f64; 2]; 2]> {
        if self.vertices.len() == 1 {
            let p = self.vertices[0].pos();
            return Some([p, p]);
        }
        self.segments().map(|s| s.bounds()).reduce(|a, b| {
            [
                [a[0][0].min(b[0][0]), a[0][1].min(b[0][1])],
                [a[1][0].max(b[1][0]), a[1][1].max(b[1][1])],
            ]
        })
    }

    fn reverse(&mut self) {
        let n = self.vertices.len();
        // The piece from v[i] back to v[i-1] is piece i-1 run backwards.
        let old = std::mem::take(&mut self.vertices);
        self.vertices = (0..n)
            .rev()
            .map(|i| Vertex {
                bulge: -old[(i + n - 1) % n].bulge,
                ..old[i]
            })
            .collect();
    }

    /// Whether `cavalier_contours` can be trusted with this profile.
    pub(crate) fn engine_safe(&self) -> bool {
        self.vertices.len() >= 2
            && self.is_finite()
            && self
                .vertices
                .iter()
                .all(|v| v.x.abs() <= MAX_COORDINATE && v.y.abs() <= MAX_COORDINATE)
    }

    /// The loop as `cavalier_contours` takes it (counter-clockwise).
    pub(crate) fn to_pline(&self) -> Polyline<f64> {
        let mut pl = Polyline::new_closed();
        for v in &self.vertices {
            pl.add(v.x, v.y, v.bulge);
        }
        pl
    }

    /// The profile of a closed loop `cavalier_contours` returned (made
    /// counter-clockwise like every profile).
    pub(crate) fn from_pline(pl: &Polyline<f64>) -> Profile {
        Profile::new(
            pl.iter_vertexes()
                .map(|v: PlineVertex<f64>| Vertex::arc(v.x, v.y, v.bulge))
                .collect(),
        )
    }

    /// A point where two pieces that do not follow each other cross or
    /// touch, or where neighbouring pieces fold back over each other; `None`
    /// for a simple loop. A profile that is not finite, or has coordinates
    /// beyond [`MAX_COORDINATE`], also gives `None`: check those first.
    pub fn self_intersection(&self) -> Option<[f64; 2]> {
        if !self.engine_safe() {
            return None;
        }
        let pl = self.to_pline();
        let options = PlineSelfIntersectOptions {
            pos_equal_eps: TOLERANCE,
            ..Default::default()
        };
        let mut found = None;
        let _: Control<()> = pl.visit_self_intersects_opt(
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

    /// The loops at distance `d` inside the profile (outside for negative
    /// `d`). The region may split into several loops or vanish (no loops);
    /// `d = 0` gives a clone. Loops smaller than 1e-9 mm² are dropped. A
    /// profile that is not finite or not simple gives no meaningful result
    /// (none at all when not finite).
    pub fn offset_inward(&self, d: f64) -> Vec<Profile> {
        if d == 0.0 {
            return vec![self.clone()];
        }
        if !d.is_finite() || !self.engine_safe() {
            return Vec::new();
        }
        let options = PlineOffsetOptions {
            // Two loops that touch become two tracks, not one figure eight.
            touching_loop_behavior: TouchingLoopBehavior::Separate,
            ..Default::default()
        };
        // Counter-clockwise, so "left of the direction of travel" is inward.
        self.to_pline()
            .parallel_offset_opt(d, &options)
            .into_iter()
            .filter(|pl| pl.is_closed())
            .map(|pl| Profile::from_pline(&pl))
            .filter(|p| p.area() > MIN_LOOP_AREA)
            .collect()
    }

    /// Whether `p` lies inside or on the boundary (within [`TOLERANCE`]).
    pub fn contains(&self, p: [f64; 2]) -> bool {
        if !(p[0].is_finite() && p[1].is_finite()) || self.vertices.len() < 2 || !self.is_finite() {
            return false;
        }
        if self.distance_to_boundary(p) <= TOLERANCE {
            return true;
        }
        self.to_pline().winding_number(Vector2::new(p[0], p[1])) != 0
    }

    /// Exact distance from `p` to the nearest point of the boundary, arcs
    /// included (infinite for a profile without vertices, NaN for one that is
    /// not finite).
    pub fn distance_to_boundary(&self, p: [f64; 2]) -> f64 {
        if !self.is_finite() {
            return f64::NAN;
        }
        if self.vertices.len() == 1 {
            let v = self.vertices[0];
            return (p[0] - v.x).hypot(p[1] - v.y);
        }
        self.segments()
            .map(|s| s.distance(p))
            .fold(f64::INFINITY, f64::min)
    }

    /// The loop flattened into points, arcs within `chord_error` (but at most
    /// [`MAX_ARC_CHORDS`] chords an arc), starting at the first vertex; the
    /// closing point is not repeated.
    pub fn polyline(&self, chord_error: f64) -> Vec<[f64; 2]> {
        if self.vertices.len() == 1 {
            return vec![self.vertices[0].pos()];
        }
        let mut out = Vec::with_capacity(self.vertices.len());
        for s in self.segments() {
            s.flatten_into(chord_error, &mut out);
        }
        out
    }

    /// The vertices where the direction of travel turns by at least
    /// `min_turn_deg` degrees: sharp corners. Where a line runs into an arc
    /// along its tangent the direction does not jump, so that is no corner.
    pub fn corners(&self, min_turn_deg: f64) -> Vec<[f64; 2]> {
        let segs: Vec<Segment> = self.segments().collect();
        let n = segs.len();
        (0..n)
            .filter(|&i| {
                let incoming = segs[(i + n - 1) % n].end_tangent();
                let outgoing = segs[i].start_tangent();
                let turn = (outgoing - incoming + std::f64::consts::PI)
                    .rem_euclid(std::f64::consts::TAU)
                    - std::f64::consts::PI;
                turn.abs().to_degrees() >= min_turn_deg
            })
            .map(|i| segs[i].from())
            .collect()
    }
}

/// Whether two points are one (within [`TOLERANCE`] on each axis).
fn same(a: [f64; 2], b: [f64; 2]) -> bool {
    (a[0] - b[0]).abs() <= TOLERANCE && (a[1] - b[1]).abs() <= TOLERANCE
}

/// The arc from `v` to `next` as two arcs of half the sweep.
fn halve(v: Vertex, next: Vertex) -> [Vertex; 2] {
    let b = v.bulge;
    // tan(q/2) from tan(q); `hypot` keeps a huge bulge from overflowing.
    let half = b / (1.0 + 1f64.hypot(b));
    let (dx, dy) = (next.x - v.x, next.y - v.y);
    // The arc's midpoint lies a sagitta of b·chord/2 to the right of the
    // chord for a counter-clockwise arc.
    let mid = Vertex::arc(
        (v.x + next.x) / 2.0 + dy * b / 2.0,
        (v.y + next.y) / 2.0 - dx * b / 2.0,
        half,
    );
    [Vertex { bulge: half, ..v }, mid]
}

#[cfg(test)]
mod tests;
