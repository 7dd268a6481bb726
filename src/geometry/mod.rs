//! Geometry of the solid: sections, their morph, the spine and the twisted
//! section frames, with nalgebra poses. Its types are its own (the
//! checker builds them from the language), so it reads no stage.

pub mod mesh;
pub mod open_path;
pub mod outline;
pub mod profile;
pub mod region;
pub mod scan;
pub mod section;
pub mod shape;
pub mod spine;
pub mod target;

use nalgebra::{Point3, Vector3};
use section::{Blend, Morph, Section};
use spine::{Spine, SpineFrame};

/// A section frame: where the section at a station sits and how it is turned.
#[derive(Clone, Copy, Debug)]
pub struct SectionFrame {
    /// The untwisted spine frame.
    pub spine: SpineFrame,
    /// Twist angle at this station, rad.
    pub twist: f64,
    /// Section x axis (carries the twist).
    pub x: Vector3<f64>,
    /// Section y axis: `z × x`.
    pub y: Vector3<f64>,
}

impl SectionFrame {
    /// The build direction.
    pub fn z(&self) -> Vector3<f64> {
        self.spine.tangent
    }

    /// The point at section coordinates `(u, v)`.
    pub fn at(&self, u: f64, v: f64) -> Point3<f64> {
        self.spine.origin + self.x * u + self.y * v
    }
}

/// A loft's geometry, ready to be evaluated at any station and angle.
#[derive(Clone, Copy, Debug)]
pub struct LoftGeometry {
    /// The spine.
    pub spine: Spine,
    /// Section outlines.
    pub blend: Blend,
    /// Total twist, rad.
    pub twist: f64,
}

impl LoftGeometry {
    /// The geometry of a loft from `from` to `to` along `spine`, the end
    /// turned by `twist` (rad) about it.
    pub fn new(from: Section, to: Section, morph: Morph, spine: Spine, twist: f64) -> Self {
        LoftGeometry {
            spine,
            blend: Blend::new(from, to, morph),
            twist,
        }
    }

    /// The section frame at station `s`.
    pub fn frame(&self, s: f64) -> SectionFrame {
        let sp = spine::frame(&self.spine, s);
        let twist = self.twist * s;
        let (sin, cos) = twist.sin_cos();
        let side = sp.side();
        let x = sp.inward * cos + side * sin;
        let y = sp.tangent.cross(&x);
        SectionFrame {
            spine: sp,
            twist,
            x,
            y,
        }
    }

    /// The outline point at station `s`, angle `theta` in the section frame, with
    /// its section coordinates.
    pub fn point(&self, f: &SectionFrame, s: f64, theta: f64) -> (Point3<f64>, [f64; 2]) {
        let r = self.blend.radius(s, theta);
        let (sin, cos) = theta.sin_cos();
        let (u, v) = (r * cos, r * sin);
        (f.at(u, v), [u, v])
    }

    /// Distance from the bend axis of the point at section coordinates `uv` on
    /// frame `f` (for a straight spine: `None`, there is no bend axis).
    pub fn bend_distance(&self, f: &SectionFrame, uv: [f64; 2]) -> Option<f64> {
        match self.spine {
            Spine::Line { .. } => None,
            Spine::Arc { radius, .. } => {
                // Component of the offset toward the bend centre.
                let (sin, cos) = f.twist.sin_cos();
                let inward = uv[0] * cos - uv[1] * sin;
                Some(radius.0 - inward)
            }
        }
    }
}

/// Halving between `good` (where `ok` holds) and `bad` (where it does not)
/// until they are within `tol`: the last value found to hold, the nearest
/// `bad` — the largest clear diameter, the least clear raise.
pub fn bisect(mut good: f64, mut bad: f64, tol: f64, ok: impl Fn(f64) -> bool) -> f64 {
    while (bad - good).abs() > tol {
        let mid = (good + bad) / 2.0;
        // Far from zero the ends can be one float apart and still wider
        // than `tol`: nothing lies between them.
        if mid == good || mid == bad {
            break;
        }
        if ok(mid) {
            good = mid;
        } else {
            bad = mid;
        }
    }
    good
}
