//! A repair's target given as a solid of the language (`top = NAME`,
//! docs/repair.md, *A target solid*): the part as designed, whose highest
//! surface over each point is the finished surface, the surface a nozzle
//! coming down would meet.
//!
//! - An extrusion of a fixed shape to a height stands on the plate: over a
//!   point of its shape its top is the height, exactly, and a vertical
//!   line meets nothing else above the plate.
//! - An extrusion of a mesh is the mesh's highest face
//!   ([`Highest`], exact).
//! - A loft is known exactly point by point: the station whose plane
//!   holds a point (for a straight spine its height over the length, for
//!   an arc its angle about the bend axis), and there whether the point
//!   lies within the section's outline (the blend's radius in the twisted
//!   section frame). Down a vertical line its surface is found by
//!   sampling that test every [`STEP`] (or at [`MAX_LINE_SAMPLES`] over
//!   a taller loft) and bisecting each change to
//!   [`RESOLUTION`], far under the 0.001 mm programs are written to; a
//!   line that starts inside, at the loft's highest station of a straight
//!   spine, has its top there exactly. A piece of the loft thinner than
//!   the step along a vertical line can be missed.

use super::mesh::highest::Highest;
use super::region::Region;
use super::section::{Morph, Section};
use super::spine::Spine;
use super::LoftGeometry;
use nalgebra::Point3;

mod tessellate;

/// How far apart (mm) a vertical line is tested against a loft before
/// its changes are bisected.
pub const STEP: f64 = 0.05;

/// How closely (mm) a loft's surface is found along a vertical line.
pub const RESOLUTION: f64 = 1e-9;

/// The most samples down one vertical line: a loft taller than
/// `STEP · MAX_LINE_SAMPLES` (100 mm) is sampled more coarsely, so a
/// repair under a tall designed part (a 7 m bend took minutes a line
/// set) costs a bounded time per point of the footprint.
pub const MAX_LINE_SAMPLES: f64 = 2000.0;

/// A solid whose highest surface over each point is a repair's finished
/// surface.
#[derive(Debug)]
pub enum Target {
    /// An extrusion of `region` from the plate up to `height` (mm).
    Prism {
        /// Its shape, seen from above.
        region: Region,
        /// Its height, mm.
        height: f64,
    },
    /// An extrusion of a mesh: the mesh's faces.
    Mesh(Highest),
    /// A loft.
    Loft(LoftTarget),
    /// A target mesh or solid turned so a tilted build direction is up
    /// (docs/repair.md, *Undercuts*).
    Turned(Turned),
}

impl Target {
    /// The height of the solid's highest surface over `p` (mm), if any of
    /// it is over `p`.
    pub fn at(&self, p: [f64; 2]) -> Option<f64> {
        match self {
            Target::Prism { region, height } => region.contains(p).then_some(*height),
            Target::Mesh(m) => m.at(p),
            Target::Loft(l) => l.crossings(p, f64::NEG_INFINITY, true).first().copied(),
            Target::Turned(t) => t.crossings(p, f64::NEG_INFINITY, true).first().copied(),
        }
    }

    /// Whether `q` (mm) lies in the solid, its faces included: a mesh's
    /// when the vertical line up from `q` crosses its faces an odd number
    /// of times.
    pub fn contains(&self, q: [f64; 3]) -> bool {
        match self {
            Target::Prism { region, height } => {
                (0.0..=*height).contains(&q[2]) && region.contains([q[0], q[1]])
            }
            Target::Mesh(m) => mesh_contains(m, q),
            Target::Loft(l) => l.contains(q),
            Target::Turned(t) => t.contains_turned(q),
        }
    }

    /// The most samples of its inside test one vertical line takes: a
    /// loft's or a turned target's walk (`march`); 1 for a prism or a
    /// mesh, whose crossings are found from their faces.
    pub fn line_samples(&self) -> f64 {
        let walk = |[lo, hi]: [f64; 2]| {
            let n = ((hi - lo) / STEP).ceil();
            if n.is_finite() {
                n.clamp(1.0, MAX_LINE_SAMPLES)
            } else {
                MAX_LINE_SAMPLES
            }
        };
        match self {
            Target::Prism { .. } | Target::Mesh(_) => 1.0,
            Target::Loft(l) => walk(l.z),
            Target::Turned(t) => walk(t.z),
        }
    }

    /// The box (mm) the solid lies within, lowest corner and highest;
    /// `None` when it has no finite box.
    pub fn bounds(&self) -> Option<[[f64; 3]; 2]> {
        let b = match self {
            Target::Prism { region, height } => {
                let [lo, hi] = region.bounds()?;
                [[lo[0], lo[1], 0.0], [hi[0], hi[1], *height]]
            }
            Target::Mesh(m) => m.bounds(),
            Target::Loft(l) => l.bounds,
            Target::Turned(t) => {
                let [lo, hi] = t.z;
                let [a, b] = t.xy;
                [[a[0], a[1], lo], [b[0], b[1], hi]]
            }
        };
        b.iter().flatten().all(|v| v.is_finite()).then_some(b)
    }

    /// The heights where the vertical line over `p` crosses the solid's
    /// surface above `z` (mm), highest first: from the top down it enters
    /// and leaves the solid in turn, so three or more mean the solid leaves
    /// and enters again above `z` (an overhang, a cavity).
    pub fn crossings_above(&self, p: [f64; 2], z: f64) -> Vec<f64> {
        match self {
            Target::Prism { region, height } if region.contains(p) => {
                [*height, 0.0].into_iter().filter(|&h| h > z).collect()
            }
            Target::Prism { .. } => Vec::new(),
            Target::Mesh(m) => m.crossings_above(p, z),
            Target::Loft(l) => l.crossings(p, z, false),
            Target::Turned(t) => t.crossings(p, z, false),
        }
    }
}

/// Whether `q` lies in a mesh: an odd number of its faces above it.
pub fn mesh_contains(m: &Highest, q: [f64; 3]) -> bool {
    m.crossings_above([q[0], q[1]], q[2]).len() % 2 == 1
}

/// A fill planned in a frame turned so that its build direction is up
/// (`direction = auto`, docs/repair.md, *Undercuts*): what a process
/// engineer reads in a refusal is the part's coordinates, so the
/// planner's points are named back in the part.
#[derive(Clone, Debug)]
pub struct TurnedFrame {
    /// From the planning frame back into the part.
    pub back: nalgebra::Rotation3<f64>,
    /// The finished face's highest point over the footprint in the part,
    /// mm: a line that meets no target is named where it crosses this
    /// height.
    pub face: f64,
    /// The target as planned (turned so the build direction is up): each
    /// point of the turned footprint is the line along the direction
    /// through a point of the finished face, where it enters the target.
    pub target: std::sync::Arc<Target>,
}

impl TurnedFrame {
    /// The part's point at `p` (mm, in the planning frame).
    pub fn point(&self, p: [f64; 3]) -> [f64; 3] {
        let q = self.back * nalgebra::Vector3::from(p);
        [q.x, q.y, q.z]
    }

    /// The planning frame's point (or direction) at the part's `p`: what
    /// [`TurnedFrame::point`] turns back.
    pub fn planned(&self, p: [f64; 3]) -> [f64; 3] {
        let q = self.back.inverse() * nalgebra::Vector3::from(p);
        [q.x, q.y, q.z]
    }

    /// The part's point that the planning frame's footprint point `p`
    /// (mm) stands for: where its vertical line, the build direction's
    /// line in the part, enters the target from above (the finished face
    /// the file's footprint is drawn on), or crosses the face's highest
    /// point's height where it meets no target.
    pub fn footprint(&self, p: [f64; 2]) -> [f64; 3] {
        if let Some(h) = self.target.at(p).filter(|h| h.is_finite()) {
            return self.point([p[0], p[1], h]);
        }
        // The part's z along the turned vertical through p is
        // r₂₀·x + r₂₁·y + r₂₂·z, r₂₂ the direction's z (> 0 within 85°).
        let r = self.back.matrix();
        let z = (self.face - r[(2, 0)] * p[0] - r[(2, 1)] * p[1]) / r[(2, 2)];
        self.point([p[0], p[1], z])
    }
}

/// What a turned target turns: a target mesh or a target solid.
#[derive(Debug)]
pub enum Inner {
    /// `top = mesh(…)`.
    Mesh(std::sync::Arc<Highest>),
    /// `top = NAME`.
    Solid(std::sync::Arc<Target>),
}

impl Inner {
    fn contains(&self, q: [f64; 3]) -> bool {
        match self {
            Inner::Mesh(m) => mesh_contains(m, q),
            Inner::Solid(t) => t.contains(q),
        }
    }

    fn bounds(&self) -> Option<[[f64; 3]; 2]> {
        let b = match self {
            Inner::Mesh(m) => m.bounds(),
            Inner::Solid(t) => t.bounds()?,
        };
        b.iter().flatten().all(|v| v.is_finite()).then_some(b)
    }
}

/// A target seen along a tilted build direction: the part's coordinates
/// turned by `rot` so the direction is up. Its surface along a vertical
/// line of the turned frame is found as a loft's is: the inside test
/// (turned back into the part) every [`STEP`] (at most
/// [`MAX_LINE_SAMPLES`] times a line), each change bisected to
/// [`RESOLUTION`]. A piece thinner than the step along the line can be
/// missed.
#[derive(Debug)]
pub struct Turned {
    inner: Inner,
    /// Part to turned frame.
    rot: nalgebra::Rotation3<f64>,
    /// The turned heights (mm) it lies within.
    z: [f64; 2],
    /// Its turned extent in x and y (mm).
    xy: [[f64; 2]; 2],
}

impl Turned {
    /// `inner` turned by `rot`; `None` when it has no finite box.
    pub fn new(inner: Inner, rot: nalgebra::Rotation3<f64>) -> Option<Turned> {
        let [lo, hi] = inner.bounds()?;
        let (mut a, mut b) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for k in 0..8 {
            let c = [
                if k & 1 == 0 { lo[0] } else { hi[0] },
                if k & 2 == 0 { lo[1] } else { hi[1] },
                if k & 4 == 0 { lo[2] } else { hi[2] },
            ];
            let t = rot * nalgebra::Vector3::from(c);
            for i in 0..3 {
                a[i] = a[i].min(t[i]);
                b[i] = b[i].max(t[i]);
            }
        }
        // A face at the box's very top is inside at the start of a walk.
        Some(Turned {
            inner,
            rot,
            z: [a[2] - STEP, b[2] + STEP],
            xy: [[a[0], a[1]], [b[0], b[1]]],
        })
    }

    /// Whether the turned point `q` lies in the target.
    fn contains_turned(&self, q: [f64; 3]) -> bool {
        let p = self.rot.inverse() * nalgebra::Vector3::from(q);
        self.inner.contains([p.x, p.y, p.z])
    }

    /// The turned heights where the vertical line over `p` crosses the
    /// surface above `z`, highest first; only the first when `first`.
    fn crossings(&self, p: [f64; 2], z: f64, first: bool) -> Vec<f64> {
        let [x, y] = self.xy;
        if !(p[0] >= x[0] && p[0] <= y[0] && p[1] >= x[1] && p[1] <= y[1]) {
            return Vec::new();
        }
        let inside = |h: f64| self.contains_turned([p[0], p[1], h]);
        march([self.z[0].max(z), self.z[1]], false, first, inside)
    }
}

/// A loft as a target: its sections as written are its faces.
#[derive(Debug)]
pub struct LoftTarget {
    geometry: LoftGeometry,
    /// The heights (mm) every point of the loft lies within.
    z: [f64; 2],
    /// A box (mm) it lies within: the heights, and x and y within its
    /// sections' reach of the spine (a bent spine's run added).
    bounds: [[f64; 3]; 2],
}

/// Why a loft cannot be a target.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LoftFault {
    /// Its sections reach the bend's axis or past it (`radius` of the
    /// bend, `reach` of the sections, mm): its stations' planes meet
    /// inside it.
    Tight {
        /// The bend's radius, mm.
        radius: f64,
        /// The farthest any section reaches from the spine, mm.
        reach: f64,
    },
}

impl LoftTarget {
    /// The loft from `from` to `to` (faces as given) along `spine`, the end
    /// turned by `twist` (rad).
    pub fn new(
        from: Section,
        to: Section,
        morph: Morph,
        spine: Spine,
        twist: f64,
    ) -> Result<Self, LoftFault> {
        let geometry = LoftGeometry::new(from, to, morph, spine, twist);
        let reach = geometry.blend.max_radius();
        let z = match spine {
            Spine::Line { length } => [0.0, length.0],
            Spine::Arc { radius, angle } => {
                if reach >= radius.0 {
                    return Err(LoftFault::Tight {
                        radius: radius.0,
                        reach,
                    });
                }
                arc_heights(&geometry, radius.0 * angle.0.abs() + reach * angle.0.abs())
            }
        };
        let run = match spine {
            Spine::Line { .. } => 0.0,
            Spine::Arc { radius, angle } => radius.0 * angle.0.abs(),
        };
        let r = reach + run;
        let bounds = [[-r, -reach, z[0]], [r, reach, z[1]]];
        Ok(LoftTarget {
            geometry,
            z,
            bounds,
        })
    }

    /// Whether `q` lies in the loft (its faces included).
    pub fn contains(&self, q: [f64; 3]) -> bool {
        let Some(s) = self.station(q) else {
            return false;
        };
        let f = self.geometry.frame(s);
        let d = Point3::from(q) - f.spine.origin;
        let (u, v) = (d.dot(&f.x), d.dot(&f.y));
        let r = u.hypot(v);
        r <= 1e-12 || r <= self.geometry.blend.radius(s, v.atan2(u)) + 1e-9
    }

    /// The station (0..1) whose plane holds `q`, if `q` is between the
    /// end sections' planes.
    fn station(&self, q: [f64; 3]) -> Option<f64> {
        let s = match self.geometry.spine {
            Spine::Line { length } => q[2] / length.0,
            Spine::Arc { radius, angle } => {
                // The stations' planes all hold the bend axis, parallel to
                // y through (R, 0, 0); the spine leaves it along -x.
                (q[2].atan2(radius.0 - q[0])) / angle.0
            }
        };
        (-1e-12..=1.0 + 1e-12)
            .contains(&s)
            .then_some(s.clamp(0.0, 1.0))
    }

    /// The heights where the vertical line over `p` crosses the loft's
    /// surface above `z`, highest first; only the first when `first`.
    fn crossings(&self, p: [f64; 2], z: f64, first: bool) -> Vec<f64> {
        let [lo, hi] = self.z;
        let lo = lo.max(z);
        let bottom = lo == self.z[0];
        march([lo, hi], bottom, first, |h| self.contains([p[0], p[1], h]))
    }
}

/// The heights where `inside` changes down `[lo, hi]`, highest first
/// (only the first when `first`): `hi` when it starts inside, each change
/// between samples bisected, and `lo` when it is still inside there and
/// `lo` is the solid's `bottom`. The samples are [`STEP`] apart, or
/// [`MAX_LINE_SAMPLES`] over the line where that is wider, so the work
/// per line is bounded whatever the solid's height.
fn march([lo, hi]: [f64; 2], bottom: bool, first: bool, inside: impl Fn(f64) -> bool) -> Vec<f64> {
    let mut out = Vec::new();
    if hi <= lo || !(hi - lo).is_finite() {
        return out;
    }
    let n = ((hi - lo) / STEP).ceil().clamp(1.0, MAX_LINE_SAMPLES) as usize;
    let at = |k: usize| hi - (hi - lo) * k as f64 / n as f64;
    let mut was = inside(hi);
    if was {
        out.push(hi);
        if first {
            return out;
        }
    }
    for k in 1..=n {
        let h = at(k);
        let is = inside(h);
        if is != was {
            // The end inside is the one kept: the height found is in the solid.
            let (good, bad) = if was { (at(k - 1), h) } else { (h, at(k - 1)) };
            out.push(super::bisect(good, bad, RESOLUTION, &inside));
            if first {
                return out;
            }
        }
        was = is;
    }
    // Inside down to the loft's lowest height: its bottom.
    if was && bottom {
        out.push(lo);
    }
    out
}

/// The heights (mm) a bent loft lies within: its outline's at 129
/// stations and 720 angles, widened by what can lie between them (`sweep`
/// is how far, mm, its farthest point travels from end to end) and a
/// twentieth of its reach for the outline between the angles.
fn arc_heights(geometry: &LoftGeometry, sweep: f64) -> [f64; 2] {
    const STATIONS: usize = 128;
    const ANGLES: usize = 720;
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for k in 0..=STATIONS {
        let s = k as f64 / STATIONS as f64;
        let f = geometry.frame(s);
        for j in 0..ANGLES {
            let theta = std::f64::consts::TAU * j as f64 / ANGLES as f64;
            let z = geometry.point(&f, s, theta).0.z;
            lo = lo.min(z);
            hi = hi.max(z);
        }
    }
    let slack = sweep / STATIONS as f64 + geometry.blend.max_radius() / 20.0 + STEP;
    [lo - slack, hi + slack]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::units::{Angle, Length};

    fn rect(w: f64, h: f64) -> Section {
        Section::Rectangle {
            a: Length(w / 2.0),
            b: Length(h / 2.0),
        }
    }

    /// A box lofted straight up: its top is its length, exactly, inside
    /// it, and nothing is beside it.
    #[test]
    fn a_straight_box_lofts_top_is_its_length_exactly() {
        let spine = Spine::Line {
            length: Length(13.0),
        };
        let l = LoftTarget::new(
            rect(80.0, 40.0),
            rect(80.0, 40.0),
            Morph::Superellipse,
            spine,
            0.0,
        )
        .unwrap();
        let t = Target::Loft(l);
        for p in [[0.0, 0.0], [39.0, -19.0], [-12.3, 7.7]] {
            assert_eq!(t.at(p), Some(13.0), "{p:?}");
            assert_eq!(t.crossings_above(p, 2.0), vec![13.0]);
        }
        assert_eq!(t.at([41.0, 0.0]), None);
        let c = t.crossings_above([1.0, 1.0], -1.0);
        assert_eq!(c.len(), 2);
        assert!(c[1].abs() <= RESOLUTION, "{c:?}");
    }

    /// A cone (a circle of 60 mm to one of 20 mm over 20 mm): its top at
    /// radius r is where the section's radius is r.
    #[test]
    fn a_cones_top_is_where_its_section_reaches_the_point() {
        let spine = Spine::Line {
            length: Length(20.0),
        };
        let circle = |d: f64| Section::Circle { r: Length(d / 2.0) };
        let l = LoftTarget::new(circle(60.0), circle(20.0), Morph::Radial, spine, 0.0).unwrap();
        let t = Target::Loft(l);
        for r in [12.0, 20.0, 29.0] {
            let want = 20.0 * (30.0 - r) / 20.0;
            let got = t.at([r * 0.6, r * 0.8]).unwrap();
            assert!((got - want).abs() <= 2.0 * RESOLUTION, "{r}: {got}");
        }
        assert_eq!(t.at([5.0, 0.0]), Some(20.0));
    }

    /// A box bent along an arc: its top is the end section's plane,
    /// tilted by the bend's angle.
    #[test]
    fn a_bent_boxs_top_is_its_tilted_end() {
        let (r, a) = (2000.0_f64, 0.5_f64.to_radians());
        let spine = Spine::Arc {
            radius: Length(r),
            angle: Angle(a),
        };
        let l = LoftTarget::new(
            rect(80.0, 40.0),
            rect(80.0, 40.0),
            Morph::Superellipse,
            spine,
            0.0,
        )
        .unwrap();
        let t = Target::Loft(l);
        let (xc, zc) = (r - r * a.cos(), r * a.sin());
        for p in [[0.0, 0.0], [25.0, 9.0], [-30.0, -9.0]] {
            let want = zc - a.tan() * (p[0] - xc);
            let got = t.at(p).unwrap();
            assert!(
                (got - want).abs() <= 2.0 * RESOLUTION,
                "{p:?}: {got} vs {want}"
            );
        }
    }

    /// A loft bent tighter than its sections reach is refused.
    #[test]
    fn a_loft_bent_round_its_own_section_is_refused() {
        let spine = Spine::Arc {
            radius: Length(30.0),
            angle: Angle(1.0),
        };
        let got = LoftTarget::new(
            rect(80.0, 40.0),
            rect(80.0, 40.0),
            Morph::Superellipse,
            spine,
            0.0,
        );
        assert!(matches!(got, Err(LoftFault::Tight { .. })));
    }

    /// A box turned 30° about y: along a turned vertical line its top is
    /// where the turned line meets the box's top face, its inside test
    /// the box's, and a line beside it meets nothing.
    #[test]
    fn a_turned_boxs_crossings_are_its_faces_along_the_line() {
        let region = crate::geometry::outline::region(
            &crate::geometry::shape::Shape::Section(rect(40.0, 20.0)),
            0.001,
        );
        let prism = std::sync::Arc::new(Target::Prism {
            region,
            height: 10.0,
        });
        let a = 30.0f64.to_radians();
        let rot = nalgebra::Rotation3::from_axis_angle(&nalgebra::Vector3::y_axis(), -a);
        let t = Target::Turned(Turned::new(Inner::Solid(prism), rot).unwrap());
        // The turned line over (0, 0): back in the part it runs along
        // d = (sin 30°, 0, cos 30°) through the origin, meeting the top
        // (z = 10) at z' = 10 / cos 30° and the plate at 0.
        let c = t.crossings_above([0.0, 0.0], -1.0);
        assert_eq!(c.len(), 2, "{c:?}");
        assert!((c[0] - 10.0 / a.cos()).abs() < 1e-6, "{c:?}");
        assert!(c[1].abs() < 1e-6, "{c:?}");
        assert!((t.at([0.0, 0.0]).unwrap() - c[0]).abs() < 1e-6);
        assert!(t.contains([0.0, 0.0, 5.0]));
        assert!(!t.contains([0.0, 0.0, 12.0]));
        assert_eq!(t.at([0.0, 30.0]), None);
    }

    /// A prism's crossings: its top, then the plate.
    /// A line down a loft takes a sample every 0.05 mm of its height, at
    /// most [`MAX_LINE_SAMPLES`]; a prism's is found from its faces.
    #[test]
    fn a_lofts_line_samples_follow_its_height_up_to_the_cap() {
        let box_of = |length: f64| {
            let spine = Spine::Line {
                length: Length(length),
            };
            let l = LoftTarget::new(
                rect(80.0, 40.0),
                rect(80.0, 40.0),
                Morph::Radial,
                spine,
                0.0,
            );
            Target::Loft(l.unwrap())
        };
        assert_eq!(box_of(13.0).line_samples(), 260.0);
        assert_eq!(box_of(1000.0).line_samples(), MAX_LINE_SAMPLES);
        let prism = Target::Prism {
            region: crate::geometry::outline::region(
                &crate::geometry::shape::Shape::Section(rect(10.0, 10.0)),
                0.001,
            ),
            height: 13.0,
        };
        assert_eq!(prism.line_samples(), 1.0);
    }

    /// Down a line of 1 m, two pieces 200 mm apart: the samples are capped
    /// at [`MAX_LINE_SAMPLES`] (and the bisections of its four changes), and
    /// every change is still found to [`RESOLUTION`].
    #[test]
    fn a_tall_lines_samples_are_bounded_and_its_changes_found() {
        let calls = std::cell::Cell::new(0usize);
        let inside = |h: f64| {
            calls.set(calls.get() + 1);
            (0.0..=400.0).contains(&h) || (600.0..=1000.0).contains(&h)
        };
        let out = march([0.0, 1000.0], true, false, inside);
        assert_eq!(out.len(), 4, "{out:?}");
        for (h, want) in out.iter().zip([1000.0, 600.0, 400.0, 0.0]) {
            assert!((h - want).abs() <= 1e-6, "{h} against {want}");
        }
        // 2001 samples, and at most 31 halvings of a 0.5 mm step per change.
        assert!(calls.get() <= 2001 + 2 * 31, "{} calls", calls.get());
    }

    /// A line of 20 mm keeps the 0.05 mm step: a piece 0.06 mm thick is seen.
    #[test]
    fn a_short_line_sees_a_piece_thicker_than_the_step() {
        let out = march([0.0, 20.0], false, false, |h| (10.0..=10.06).contains(&h));
        assert_eq!(out.len(), 2, "{out:?}");
    }

    /// Ends far from zero, one float apart, end the bisection.
    #[test]
    fn a_bisection_far_from_zero_ends() {
        let good = 1e12_f64;
        let bad = f64::from_bits(good.to_bits() + 1);
        assert_eq!(
            super::super::bisect(good, bad, RESOLUTION, |h| h <= good),
            good
        );
    }

    #[test]
    fn a_prisms_crossings_are_its_top_and_the_plate() {
        let region = crate::geometry::outline::region(
            &crate::geometry::shape::Shape::Section(rect(10.0, 10.0)),
            0.001,
        );
        let t = Target::Prism {
            region,
            height: 7.5,
        };
        assert_eq!(t.at([1.0, 1.0]), Some(7.5));
        assert_eq!(t.at([6.0, 1.0]), None);
        assert_eq!(t.crossings_above([1.0, 1.0], -1.0), vec![7.5, 0.0]);
        assert_eq!(t.crossings_above([1.0, 1.0], 1.0), vec![7.5]);
    }
}
