//! The 2-D shapes a planar layer is made of, as the checker builds them
//! from the language: sections, outlines of lines and arcs, placed shapes,
//! regions with holes and a mesh section's islands. Pure data: the
//! [`outline`](super::outline) module turns them into exact profiles.

use super::section::Section;
use crate::span::Span;
use crate::units::{Angle, Length};

/// Which way an arc turns, seen along the outline.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Turn {
    /// Counter-clockwise: a convex corner of a counter-clockwise outline.
    Left,
    /// Clockwise.
    Right,
}

/// A piece of an outline, from the end of the previous one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Segment {
    /// A straight line to a point.
    Line {
        /// End point `[x, y]`.
        to: [Length; 2],
    },
    /// The shorter circular arc of a radius to a point.
    Arc {
        /// End point `[x, y]`.
        to: [Length; 2],
        /// Radius.
        radius: Length,
        /// Which way it turns.
        turn: Turn,
    },
}

/// A closed outline of lines and arcs; it closes with a line back to `start`.
#[derive(Clone, Debug, PartialEq)]
pub struct Outline {
    /// First point.
    pub start: [Length; 2],
    /// The pieces after it.
    pub segments: Vec<Segment>,
}

/// A 2-D shape to extrude.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A parametric section, centred on the origin.
    Section(Section),
    /// An outline of lines and arcs.
    Outline(Outline),
    /// A shape turned about the origin, then moved: `place(…)`.
    Placed(Box<Placed>),
    /// An outline with holes: `region(…)`.
    Region(Box<RegionShape>),
    /// Separate islands on one layer, each an outline or a region: a mesh's
    /// section (never written in a file). The planar slicer fills each on
    /// its own and visits them nearest first.
    Islands(Vec<Shape>),
}

impl Shape {
    /// Whether the shape has holes (only a [`Shape::Region`], placed or not).
    pub fn has_holes(&self) -> bool {
        match self {
            Shape::Section(_) | Shape::Outline(_) => false,
            Shape::Placed(p) => p.shape.has_holes(),
            Shape::Region(r) => !r.holes.is_empty(),
            Shape::Islands(v) => v.iter().any(Shape::has_holes),
        }
    }

    /// The pieces of all its outlines (an ellipse's flattening counts as 8):
    /// the work an offset of it does.
    pub fn pieces(&self) -> usize {
        match self {
            Shape::Outline(o) => o.segments.len() + 1,
            Shape::Section(_) => 8,
            Shape::Placed(p) => p.shape.pieces(),
            Shape::Region(r) => {
                r.outline.pieces() + r.holes.iter().map(|h| h.shape.pieces()).sum::<usize>()
            }
            Shape::Islands(v) => v.iter().map(Shape::pieces).sum(),
        }
    }
}

/// `place(shape, at = [x, y], turn = a)`: the shape turned by `turn` about
/// the origin (counter-clockwise), then moved by `at`.
#[derive(Clone, Debug, PartialEq)]
pub struct Placed {
    /// What is placed.
    pub shape: Shape,
    /// Rotation about the origin, counter-clockwise.
    pub turn: Angle,
    /// Where the shape's origin goes.
    pub at: [Length; 2],
}

/// `region(outline = …, holes = […])`: a planar profile with openings.
#[derive(Clone, Debug, PartialEq)]
pub struct RegionShape {
    /// The outer outline (without holes of its own).
    pub outline: Shape,
    /// Where the outline is written.
    pub outline_span: Span,
    /// The holes, in the order written (a bolt circle's in its order).
    pub holes: Vec<Hole>,
}

/// One hole of a [`RegionShape`].
#[derive(Clone, Debug, PartialEq)]
pub struct Hole {
    /// Its outline (without holes of its own).
    pub shape: Shape,
    /// Where it is written (a bolt circle's holes share its span).
    pub span: Span,
}
