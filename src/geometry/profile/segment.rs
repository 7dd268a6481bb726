//! One piece of a profile: a straight line or a circular arc from one vertex
//! to the next, with the exact measurements the rest of the crate needs
//! (distance, bounds, tangents, flattening).

use std::f64::consts::TAU;

/// Bulges at most this large (in magnitude) are straight lines. Over a 100 mm
/// chord such an arc sits 50 nm off the line, far below any bead; treating it
/// as a line spares the arc formulas a radius near infinity.
pub const LINE_BULGE: f64 = 1e-9;

/// Most chords an arc is flattened into, whatever chord error is asked for, so
/// that a tiny chord error cannot make millions of points. A half circle in
/// 1024 chords stays within 1.2e-6 of its radius.
pub const MAX_ARC_CHORDS: usize = 1024;

/// A line or an arc between two vertices of a profile.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Segment {
    /// A straight line.
    Line {
        /// Start point.
        from: [f64; 2],
        /// End point.
        to: [f64; 2],
    },
    /// A circular arc.
    Arc {
        /// Start point.
        from: [f64; 2],
        /// End point.
        to: [f64; 2],
        /// Centre of the circle.
        centre: [f64; 2],
        /// Radius of the circle.
        radius: f64,
        /// Angle of `from` seen from the centre, rad (from +x, counter-clockwise).
        start: f64,
        /// Signed swept angle, rad: positive counter-clockwise.
        sweep: f64,
    },
}

impl Segment {
    /// The segment from `from` to `to` with the given bulge (`tan(sweep/4)`).
    pub fn new(from: [f64; 2], to: [f64; 2], bulge: f64) -> Segment {
        // A NaN bulge gives a line (whose NaN-free numbers stay usable)
        // rather than an arc full of NaN.
        if bulge.is_nan() || bulge.abs() <= LINE_BULGE {
            return Segment::Line { from, to };
        }
        let sweep = 4.0 * bulge.atan();
        let (dx, dy) = (to[0] - from[0], to[1] - from[1]);
        // The centre sits on the chord's perpendicular bisector, to the left
        // of the chord for a counter-clockwise arc; `k` is its distance from
        // the chord's midpoint in chord lengths.
        let k = (1.0 - bulge * bulge) / (4.0 * bulge);
        let centre = [
            (from[0] + to[0]) / 2.0 - dy * k,
            (from[1] + to[1]) / 2.0 + dx * k,
        ];
        let radius = dx.hypot(dy) * (1.0 + bulge * bulge) / (4.0 * bulge.abs());
        let start = (from[1] - centre[1]).atan2(from[0] - centre[0]);
        Segment::Arc {
            from,
            to,
            centre,
            radius,
            start,
            sweep,
        }
    }

    /// Start point.
    pub fn from(&self) -> [f64; 2] {
        match *self {
            Segment::Line { from, .. } | Segment::Arc { from, .. } => from,
        }
    }

    /// End point.
    pub fn to(&self) -> [f64; 2] {
        match *self {
            Segment::Line { to, .. } | Segment::Arc { to, .. } => to,
        }
    }

    /// Whether the direction `phi` (rad, seen from the centre) lies within
    /// the arc's sweep; always false for a line.
    pub fn sweeps(&self, phi: f64) -> bool {
        match *self {
            Segment::Line { .. } => false,
            Segment::Arc { start, sweep, .. } => {
                let along = if sweep > 0.0 {
                    (phi - start).rem_euclid(TAU)
                } else {
                    (start - phi).rem_euclid(TAU)
                };
                along <= sweep.abs()
            }
        }
    }

    /// Exact distance from `p` to the segment.
    pub fn distance(&self, p: [f64; 2]) -> f64 {
        let dist = |a: [f64; 2]| (p[0] - a[0]).hypot(p[1] - a[1]);
        match *self {
            Segment::Line { from, to } => {
                let (dx, dy) = (to[0] - from[0], to[1] - from[1]);
                let len2 = dx * dx + dy * dy;
                if len2.is_nan() || len2 <= 0.0 {
                    return dist(from);
                }
                let t = (((p[0] - from[0]) * dx + (p[1] - from[1]) * dy) / len2).clamp(0.0, 1.0);
                dist([from[0] + t * dx, from[1] + t * dy])
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
                // At the centre every point of the arc is `radius` away.
                if rc == 0.0 || self.sweeps(vy.atan2(vx)) {
                    (rc - radius).abs()
                } else {
                    dist(from).min(dist(to))
                }
            }
        }
    }

    /// Direction of travel at the start, rad.
    pub fn start_tangent(&self) -> f64 {
        self.chord_angle() - self.sweep() / 2.0
    }

    /// Direction of travel at the end, rad.
    pub fn end_tangent(&self) -> f64 {
        self.chord_angle() + self.sweep() / 2.0
    }

    fn chord_angle(&self) -> f64 {
        let (a, b) = (self.from(), self.to());
        (b[1] - a[1]).atan2(b[0] - a[0])
    }

    fn sweep(&self) -> f64 {
        match *self {
            Segment::Line { .. } => 0.0,
            Segment::Arc { sweep, .. } => sweep,
        }
    }

    /// Twice the signed area between the segment and the origin (the
    /// shoelace term), plus twice the circular segment an arc adds.
    pub fn double_area(&self) -> f64 {
        let (a, b) = (self.from(), self.to());
        let chord = a[0] * b[1] - b[0] * a[1];
        match *self {
            Segment::Line { .. } => chord,
            Segment::Arc { radius, sweep, .. } => chord + radius * radius * (sweep - sweep.sin()),
        }
    }

    /// The point on the arc's circle at angle `phi`.
    fn on_circle(centre: [f64; 2], radius: f64, phi: f64) -> [f64; 2] {
        let (s, c) = phi.sin_cos();
        [centre[0] + radius * c, centre[1] + radius * s]
    }

    /// Exact bounding box `[min, max]`.
    pub fn bounds(&self) -> [[f64; 2]; 2] {
        let (a, b) = (self.from(), self.to());
        let mut lo = [a[0].min(b[0]), a[1].min(b[1])];
        let mut hi = [a[0].max(b[0]), a[1].max(b[1])];
        if let Segment::Arc { centre, radius, .. } = *self {
            // The circle's extreme points, where the arc passes them.
            for k in 0..4 {
                let phi = f64::from(k) * TAU / 4.0;
                if self.sweeps(phi) {
                    let q = Self::on_circle(centre, radius, phi);
                    for i in 0..2 {
                        lo[i] = lo[i].min(q[i]);
                        hi[i] = hi[i].max(q[i]);
                    }
                }
            }
        }
        [lo, hi]
    }

    /// How many chords flatten this segment within `chord_error` (at most
    /// [`MAX_ARC_CHORDS`]; a chord error that is not a positive number gets
    /// the most).
    pub fn chords(&self, chord_error: f64) -> usize {
        match *self {
            Segment::Line { .. } => 1,
            Segment::Arc { radius, sweep, .. } => {
                if chord_error.is_nan() || chord_error <= 0.0 {
                    return MAX_ARC_CHORDS;
                }
                let ratio = chord_error / radius;
                // A chord spanning angle α sits r(1 − cos(α/2)) inside the arc.
                let step = if ratio >= 2.0 {
                    TAU
                } else {
                    2.0 * (1.0 - ratio).acos()
                };
                let n = (sweep.abs() / step).ceil();
                if n.is_nan() {
                    MAX_ARC_CHORDS
                } else {
                    // `as` saturates; the clamp bounds the count either way.
                    (n as usize).clamp(1, MAX_ARC_CHORDS)
                }
            }
        }
    }

    /// Appends the start point and the points inside the segment that flatten
    /// it within `chord_error` (the end point is the next segment's start).
    pub fn flatten_into(&self, chord_error: f64, out: &mut Vec<[f64; 2]>) {
        out.push(self.from());
        if let Segment::Arc {
            centre,
            radius,
            start,
            sweep,
            ..
        } = *self
        {
            let n = self.chords(chord_error);
            for k in 1..n {
                let phi = start + sweep * (k as f64 / n as f64);
                out.push(Self::on_circle(centre, radius, phi));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn half_circle_bulge_gives_centre_radius_and_sweep() {
        let s = Segment::new([1.0, 0.0], [-1.0, 0.0], 1.0);
        let Segment::Arc {
            centre,
            radius,
            start,
            sweep,
            ..
        } = s
        else {
            panic!("bulge 1 is an arc")
        };
        assert!(centre[0].abs() < 1e-15 && centre[1].abs() < 1e-15);
        assert!((radius - 1.0).abs() < 1e-15);
        assert!(start.abs() < 1e-15);
        assert!((sweep - PI).abs() < 1e-15);
        // Counter-clockwise from (1, 0): heads up, arrives heading down.
        assert!((s.start_tangent() - PI / 2.0).abs() < 1e-12);
        assert!((s.end_tangent() - 3.0 * PI / 2.0).abs() < 1e-12);
    }

    #[test]
    fn quarter_arc_clockwise_has_centre_on_the_right() {
        // Clockwise quarter circle from (0, 1) to (1, 0) about the origin.
        let b = -(PI / 8.0).tan();
        let Segment::Arc { centre, radius, .. } = Segment::new([0.0, 1.0], [1.0, 0.0], b) else {
            panic!("an arc")
        };
        assert!(
            centre[0].abs() < 1e-12 && centre[1].abs() < 1e-12,
            "{centre:?}"
        );
        assert!((radius - 1.0).abs() < 1e-12);
    }

    #[test]
    fn arc_distance_inside_and_outside_the_sweep() {
        let s = Segment::new([1.0, 0.0], [-1.0, 0.0], 1.0); // upper half circle
        assert!((s.distance([0.0, 3.0]) - 2.0).abs() < 1e-12);
        assert!((s.distance([0.0, 0.0]) - 1.0).abs() < 1e-12);
        // Below the diameter the nearest points are the ends.
        assert!((s.distance([1.0, -2.0]) - 2.0).abs() < 1e-12);
    }

    #[test]
    fn arc_bounds_include_the_top() {
        let s = Segment::new([1.0, 0.0], [-1.0, 0.0], 1.0);
        let [lo, hi] = s.bounds();
        assert!((hi[1] - 1.0).abs() < 1e-12 && lo[1].abs() < 1e-12);
        assert!((lo[0] + 1.0).abs() < 1e-12 && (hi[0] - 1.0).abs() < 1e-12);
    }

    #[test]
    fn flattening_meets_the_chord_error_and_is_bounded() {
        let s = Segment::new([10.0, 0.0], [-10.0, 0.0], 1.0);
        let mut pts = Vec::new();
        s.flatten_into(0.01, &mut pts);
        pts.push(s.to());
        for w in pts.windows(2) {
            let mid = [(w[0][0] + w[1][0]) / 2.0, (w[0][1] + w[1][1]) / 2.0];
            assert!(s.distance(mid) <= 0.01 + 1e-12);
        }
        assert!(s.chords(1e-300) == MAX_ARC_CHORDS);
        assert!(s.chords(f64::NAN) == MAX_ARC_CHORDS);
        assert!(s.chords(100.0) == 1);
    }

    #[test]
    fn nan_bulge_is_a_line() {
        assert!(matches!(
            Segment::new([0.0, 0.0], [1.0, 0.0], f64::NAN),
            Segment::Line { .. }
        ));
    }
}
