//! The model of a solid with a variable top: a planar footprint
//! built up to a top surface `H(x, y)` that need not be parallel to the
//! substrate, and `slicing variable { … }`, which builds it in layers that
//! each lay the same fraction `H/N` of the local height.

use super::{Measure, Shape};
pub use crate::geometry::target::TurnedFrame;
use crate::span::Span;
use crate::syntax::ast::Expr;
use crate::units::Length;
use std::num::NonZeroU32;

/// An axis of the footprint's plane.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    /// Along x.
    X,
    /// Along y.
    Y,
}

impl Axis {
    /// The axis as written: `x` or `y`.
    pub fn name(self) -> &'static str {
        match self {
            Axis::X => "x",
            Axis::Y => "y",
        }
    }

    /// Its unit direction in the plane.
    pub fn unit(self) -> [f64; 2] {
        match self {
            Axis::X => [1.0, 0.0],
            Axis::Y => [0.0, 1.0],
        }
    }

    /// The other axis of the plane.
    pub fn across(self) -> Axis {
        match self {
            Axis::X => Axis::Y,
            Axis::Y => Axis::X,
        }
    }
}

/// The height of the finished part above the substrate at every point of the
/// footprint, as the file gives it.
#[derive(Clone, Debug)]
pub enum Top {
    /// `plane(at, height, slope_x, slope_y)`: `height` at `at`, rising by
    /// `slope_x` per unit of x and `slope_y` per unit of y.
    Plane {
        /// The point the height is given at.
        at: [Length; 2],
        /// The height there.
        height: Length,
        /// Rise per unit run along x and y (dimensionless).
        slope: [f64; 2],
    },
    /// `edges(along, from, to)`: `from` on the footprint's extreme edge at
    /// the low end of the axis, `to` on the one at its high end, linear in
    /// between (and the same across the axis).
    Edges {
        /// The axis the top rises along.
        along: Axis,
        /// Height at the footprint's lowest coordinate along the axis.
        from: Length,
        /// Height at its highest.
        to: Length,
    },
    /// Any expression of the position builtins `x` and `y`, evaluated at
    /// every point the slicer samples ([`crate::sema::TopHeights`]).
    Expr(TopExpr),
    /// `mesh(file, units, turn, at)`: the part as designed, its highest
    /// face over each point (docs/repair.md, *A target mesh*).
    Mesh(TopMesh),
    /// `NAME`: a solid of the file, not built, its highest surface over
    /// each point (docs/repair.md, *A target solid*).
    Solid(TopSolid),
}

/// A top given as a solid of the file: its name and its surface.
#[derive(Clone, Debug)]
pub struct TopSolid {
    /// The solid's name.
    pub name: String,
    /// Its highest surface over each point.
    pub surface: std::sync::Arc<crate::geometry::target::Target>,
}

/// A top given as a mesh: its file and its upper surface, placed.
#[derive(Clone, Debug)]
pub struct TopMesh {
    /// The file, as written.
    pub path: String,
    /// The highest face over each point.
    pub surface: std::sync::Arc<crate::geometry::mesh::highest::Highest>,
}

impl Top {
    /// Its one height, mm, when it is flat: a plane without slope, or
    /// `edges(…)` from and to the same height.
    pub fn flat(&self) -> Option<f64> {
        match self {
            Top::Plane { height, slope, .. } if *slope == [0.0; 2] => Some(height.0),
            Top::Edges { from, to, .. } if from == to => Some(from.0),
            _ => None,
        }
    }

    /// The top at `p` (mm) when it is a mesh or a solid: `Some(None)`
    /// where none of it is over `p`; `None` for any other top.
    pub fn mesh_at(&self, p: [f64; 2]) -> Option<Option<f64>> {
        match self {
            Top::Mesh(m) => Some(m.surface.at(p)),
            Top::Solid(s) => Some(s.surface.at(p)),
            _ => None,
        }
    }

    /// Whether `q` (mm) lies in the top when it is a target mesh or solid
    /// (the part as designed); `false` for any other top, which has no
    /// inside.
    pub fn contains(&self, q: [f64; 3]) -> bool {
        match self {
            Top::Mesh(m) => crate::geometry::target::mesh_contains(&m.surface, q),
            Top::Solid(s) => s.surface.contains(q),
            _ => false,
        }
    }
}

/// A top written as an expression of `x` and `y`, kept as the user wrote it
/// with the file's constants, like a profile that follows the layer.
#[derive(Clone, Debug)]
pub struct TopExpr {
    /// The expression.
    pub expr: Expr,
    /// Every `let` of the file: name, where it is declared, its expression.
    pub constants: Vec<(String, Span, Expr)>,
}

/// `extrude NAME { profile, size, bead, top }`: a footprint built up to its
/// top.
#[derive(Clone, Debug)]
pub struct TopExtrusion {
    /// Its name.
    pub name: String,
    /// The footprint (one shape: a top cannot sit on a profile that changes
    /// with the layer).
    pub shape: Shape,
    /// Whether the footprint is the outer face or the tracks' centre line.
    pub measure: Measure,
    /// The top surface.
    pub top: Top,
    /// The extrude block.
    pub span: Span,
    /// The profile's declaration.
    pub profile_span: Span,
    /// Where the shape itself is written.
    pub shape_span: Span,
    /// The `top = …` field.
    pub top_span: Span,
    /// `on = scan(…)`: the measured surface the layers start on, if any
    /// (then `top` is the finished surface's height above z = 0, not
    /// above the base).
    pub base: Option<ScanBase>,
    /// Set when this is the footprint turned so that a tilted build
    /// direction is up (`direction = auto`): how the points its messages
    /// name go back into the part. `None` for the part as the file gives it.
    pub turned: Option<TurnedFrame>,
}

/// A scan a repair is built on (`on = scan(…)`).
#[derive(Clone, Debug)]
pub struct ScanBase {
    /// The file, as written.
    pub path: String,
    /// Its surface seen from above, placed.
    pub surface: std::sync::Arc<crate::geometry::scan::HeightField>,
    /// Its best fit to its nominal, when it was registered to one (boxed:
    /// most scans have none).
    pub registration: Option<Box<crate::ir::Registration>>,
    /// Its faces, placed as the surface is, when it has faces (a mesh):
    /// `direction = auto` asks them what a line meets beside a flank.
    pub faces: Option<std::sync::Arc<crate::geometry::scan::Faces>>,
    /// Where `scan(…)` is written.
    pub span: Span,
}

/// `slicing variable { layers, scan, offset, segments { tolerance, min_length } }`.
#[derive(Clone, Debug)]
pub struct VariableSlicing {
    /// `layers = N` and where; `None`: `auto`, the fewest that work.
    pub layers: Option<(NonZeroU32, Span)>,
    /// The tracks' direction; `None`: `auto`, the axis the top rises more
    /// along (the paper's rule).
    pub scan: Option<Axis>,
    /// A fixed centre distance between tracks and where it is declared;
    /// `None`: `balanced`, each pair spaced so that unequal beads meet level.
    pub offset: Option<(Length, Span)>,
    /// `level = …`: on a scan, levelling passes up to a height, then
    /// regular layers (docs/repair.md, *Levelling*).
    pub level: Level,
    /// `follow = surface` and where: on a scan, the nozzle along the
    /// scanned surface's normal (docs/repair.md, *Following the surface*);
    /// `None`: vertical.
    pub follow: Option<Span>,
    /// `direction = auto` and where: on a scan, the fill planned along the
    /// least tilted build direction that builds the target's overhangs
    /// (docs/repair.md, *Undercuts*); `None`: `vertical`, the layers laid
    /// from above.
    pub direction: Option<Span>,
    /// `E_H`: the largest mean |height error| of the finished top along a
    /// track that constant-speed segments may leave.
    pub tolerance: Length,
    /// The shortest constant-speed segment; `None`: the bead width.
    pub min_length: Option<Length>,
    /// `finish_tolerance = …` and where: the most the predicted finished
    /// face may depart from the top (`lmd::finish`); `None`: reported,
    /// not held.
    pub finish_tolerance: Option<(Length, Span)>,
    /// The slicing block.
    pub span: Span,
    /// `tolerance = …`, if written.
    pub tolerance_span: Option<Span>,
    /// `min_length = …`, if written.
    pub min_length_span: Option<Span>,
}

/// How a repair's layers start on the scan (`level = …`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Level {
    /// `none`: every layer lays the same fraction of the top less the scan.
    None,
    /// `auto`: levelling up to the scan's highest point under the tracks.
    Auto(Span),
    /// A height above the part's `z = 0`: levelling passes fill the wear up
    /// to it, regular layers go on from it to the top.
    At(Length, Span),
}

impl Level {
    /// Where it is written, unless `none`.
    pub fn span(self) -> Option<Span> {
        match self {
            Level::None => None,
            Level::Auto(s) | Level::At(_, s) => Some(s),
        }
    }
}

/// The `segments` tolerance when none is written: a tenth of a millimetre of
/// mean height error along a track, about the flatness the paper reports
/// (116 µm).
pub const DEFAULT_TOLERANCE: Length = Length(0.1);
