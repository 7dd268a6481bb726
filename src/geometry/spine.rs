//! The spine: the centre line a loft's sections are swept along, and the frame
//! it carries at each station.

use crate::units::{Angle, Length};
use nalgebra::{Point3, Vector3};

/// The spine the sections are swept along.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Spine {
    /// A straight line along +Z.
    Line {
        /// Length.
        length: Length,
    },
    /// An arc that starts along +Z and bends toward +X about an axis parallel to Y.
    Arc {
        /// Bend radius of the centre line.
        radius: Length,
        /// Bend angle.
        angle: Angle,
    },
}

/// Where the spine is at a station, and its frame before twist.
#[derive(Clone, Copy, Debug)]
pub struct SpineFrame {
    /// Point on the centre line, mm.
    pub origin: Point3<f64>,
    /// Unit tangent: the build direction (layer normal).
    pub tangent: Vector3<f64>,
    /// Unit direction toward the bend centre (for a line: +X). The section's x
    /// axis before twist.
    pub inward: Vector3<f64>,
}

impl SpineFrame {
    /// `tangent × inward`: the section's y axis before twist.
    pub fn side(&self) -> Vector3<f64> {
        self.tangent.cross(&self.inward)
    }
}

/// The frame at station `s` (0 = start, 1 = end). The spine starts at the origin
/// heading +Z; an arc bends toward +X about an axis parallel to Y through
/// `(R, 0, 0)`.
pub fn frame(spine: &Spine, s: f64) -> SpineFrame {
    match *spine {
        Spine::Line { length } => SpineFrame {
            origin: Point3::new(0.0, 0.0, length.0 * s),
            tangent: Vector3::z(),
            inward: Vector3::x(),
        },
        Spine::Arc { radius, angle } => {
            let r = radius.0;
            let (sin, cos) = (angle.0 * s).sin_cos();
            SpineFrame {
                origin: Point3::new(r - r * cos, 0.0, r * sin),
                tangent: Vector3::new(sin, 0.0, cos),
                inward: Vector3::new(cos, 0.0, -sin),
            }
        }
    }
}

/// The spine's length, mm.
pub fn length(spine: &Spine) -> f64 {
    match *spine {
        Spine::Line { length } => length.0,
        Spine::Arc { radius, angle } => radius.0 * angle.0,
    }
}
