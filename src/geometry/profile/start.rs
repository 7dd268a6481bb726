//! Where a closed loop starts (its seam) and how it is placed: the extreme
//! point in a direction, the sharpest corner, a loop that starts at a given
//! point of one of its pieces, and rigid motions. All exact: a seam on an arc
//! is a point of the arc, not of its flattening.

use super::{same, Profile, Segment, Vertex};
use std::f64::consts::{PI, TAU};

/// Points whose reach in the seam direction differs by less than this (mm)
/// are level: the first of them in the loop's order wins.
const LEVEL: f64 = 1e-9;

/// Corners turning by less than this (rad) are no corners: a line meeting an
/// arc along its tangent turns by rounding only.
const MIN_TURN: f64 = 1e-6;

impl Profile {
    /// The point of the loop farthest in the direction `angle` (rad, from +x
    /// counter-clockwise), exact on arcs, with the index of the piece it lies
    /// on. Of several level points (a straight edge across the direction) the
    /// first in the loop's order from vertex 0. `None` for a loop without
    /// pieces or with numbers that are not finite.
    pub fn support(&self, angle: f64) -> Option<(usize, [f64; 2])> {
        if !self.is_finite() || !angle.is_finite() {
            return None;
        }
        let (s, c) = angle.sin_cos();
        let reach = |p: [f64; 2]| p[0] * c + p[1] * s;
        let mut best: Option<(usize, [f64; 2], f64)> = None;
        for (i, seg) in self.segments().enumerate() {
            let mut consider = |p: [f64; 2]| {
                let r = reach(p);
                if best.is_none_or(|b| r > b.2 + LEVEL) {
                    best = Some((i, p, r));
                }
            };
            consider(seg.from());
            if let Segment::Arc { centre, radius, .. } = seg {
                if seg.sweeps(angle) {
                    consider([centre[0] + radius * c, centre[1] + radius * s]);
                }
            }
        }
        best.map(|(i, p, _)| (i, p))
    }

    /// The vertex where the direction of travel turns the most (either way),
    /// if any turns by more than a rounding error: a smooth loop (a circle) has
    /// none. Of equal turns the first in the loop's order.
    pub fn sharpest_corner(&self) -> Option<(usize, [f64; 2])> {
        let segs: Vec<Segment> = self.segments().collect();
        let n = segs.len();
        let mut best: Option<(usize, f64)> = None;
        for i in 0..n {
            let incoming = segs[(i + n - 1) % n].end_tangent();
            let outgoing = segs[i].start_tangent();
            let turn = ((outgoing - incoming + PI).rem_euclid(TAU) - PI).abs();
            if turn > MIN_TURN && best.is_none_or(|b| turn > b.1 + MIN_TURN) {
                best = Some((i, turn));
            }
        }
        best.map(|(i, _)| (i, segs[i].from()))
    }

    /// The same loop starting at `at`, a point of piece `piece` (as
    /// [`Profile::support`] gives them): the piece is split there, an arc into
    /// two arcs of the same circle. A point on a vertex just rotates the
    /// vertices. An index out of range gives the loop unchanged.
    pub fn starting_at(&self, piece: usize, at: [f64; 2]) -> Profile {
        let n = self.vertices.len();
        if piece >= n || n < 2 {
            return self.clone();
        }
        let seg = Segment::new(
            self.vertices[piece].pos(),
            self.vertices[(piece + 1) % n].pos(),
            self.vertices[piece].bulge,
        );
        let mut out: Vec<Vertex> = Vec::with_capacity(n + 1);
        let head = if same(seg.from(), at) {
            piece
        } else if same(seg.to(), at) {
            (piece + 1) % n
        } else {
            // Split: `at` starts the loop with the rest of the piece, and the
            // piece's first part closes it.
            let (first, rest) = split_bulges(&seg, at);
            out.push(Vertex::arc(at[0], at[1], rest));
            for k in 1..n {
                out.push(self.vertices[(piece + k) % n]);
            }
            let v = self.vertices[piece];
            out.push(Vertex::arc(v.x, v.y, first));
            return Profile { vertices: out };
        };
        out.extend((0..n).map(|k| self.vertices[(head + k) % n]));
        Profile { vertices: out }
    }

    /// The loop turned by `angle` (rad, counter-clockwise) about the origin,
    /// then moved by `by`. A rigid motion keeps every bulge.
    pub fn placed(&self, angle: f64, by: [f64; 2]) -> Profile {
        let (s, c) = angle.sin_cos();
        Profile {
            vertices: self
                .vertices
                .iter()
                .map(|v| Vertex {
                    x: v.x * c - v.y * s + by[0],
                    y: v.x * s + v.y * c + by[1],
                    bulge: v.bulge,
                })
                .collect(),
        }
    }
}

/// The bulges of the two parts of `seg` split at `at` (a point on it).
fn split_bulges(seg: &Segment, at: [f64; 2]) -> (f64, f64) {
    match *seg {
        Segment::Line { .. } => (0.0, 0.0),
        Segment::Arc {
            centre,
            start,
            sweep,
            ..
        } => {
            let phi = (at[1] - centre[1]).atan2(at[0] - centre[0]);
            // The part of the sweep up to `at`, in the arc's own sense.
            let along = if sweep > 0.0 {
                (phi - start).rem_euclid(TAU)
            } else {
                -(start - phi).rem_euclid(TAU)
            };
            let along = along.clamp(sweep.min(0.0), sweep.max(0.0));
            ((along / 4.0).tan(), ((sweep - along) / 4.0).tan())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: [f64; 2], b: [f64; 2]) -> bool {
        (a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12
    }

    #[test]
    fn a_circle_is_reached_exactly_in_every_direction() {
        let c = Profile::circle(2.0);
        for k in 0..16 {
            let a = k as f64 * TAU / 16.0 + 0.1;
            let (_, p) = c.support(a).unwrap();
            assert!(close(p, [2.0 * a.cos(), 2.0 * a.sin()]), "{a}: {p:?}");
        }
    }

    #[test]
    fn a_level_edge_gives_its_first_point() {
        let r = Profile::rectangle(4.0, 2.0);
        // Downwards: the bottom edge, run left to right; its first point.
        assert_eq!(r.support(-PI / 2.0), Some((0, [0.0, 0.0])));
        assert_eq!(r.support(0.0), Some((1, [4.0, 0.0])));
    }

    #[test]
    fn starting_on_an_arc_keeps_the_circle_and_the_area() {
        let c = Profile::circle(3.0);
        let (i, p) = c.support(1.0).unwrap();
        let s = c.starting_at(i, p);
        assert!(close([s.vertices()[0].x, s.vertices()[0].y], p));
        assert!((s.area() - c.area()).abs() < 1e-12);
        for q in s.polyline(0.01) {
            assert!(((q[0].hypot(q[1])) - 3.0).abs() < 1e-12);
        }
        // On a vertex: a rotation.
        let r = Profile::rectangle(4.0, 2.0);
        let t = r.starting_at(1, [4.0, 0.0]);
        assert_eq!(t.vertices()[0], Vertex::line(4.0, 0.0));
        assert_eq!(t.vertices().len(), 4);
    }

    #[test]
    fn the_sharpest_corner_and_none_on_a_circle() {
        let tri = Profile::new(vec![
            Vertex::line(0.0, 0.0),
            Vertex::line(10.0, 0.0),
            Vertex::line(0.0, 1.0),
        ]);
        // The corner at (10, 0) turns by 180° − 5.7°.
        assert_eq!(tri.sharpest_corner(), Some((1, [10.0, 0.0])));
        assert_eq!(Profile::circle(1.0).sharpest_corner(), None);
    }

    #[test]
    fn placing_turns_then_moves() {
        let r = Profile::rectangle(2.0, 1.0).placed(PI / 2.0, [10.0, 0.0]);
        let v = r.vertices();
        assert!(close([v[1].x, v[1].y], [10.0, 2.0]));
        assert!((r.area() - 2.0).abs() < 1e-12);
    }
}
