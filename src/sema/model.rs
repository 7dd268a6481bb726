//! The checked semantic model: names resolved, units converted to typed values,
//! ranges checked. Geometry and slicing read only this.

use crate::ir::Machine;
use crate::span::Span;
use crate::units::{Angle, Density, Length, MassFlow, Power, Speed};

/// A whole checked `.lmd` file.
#[derive(Clone, Debug)]
pub struct Model {
    /// The part's name.
    pub part: String,
    /// The solid and how it is built.
    pub loft: Loft,
    /// The bead model the wall is built with.
    pub bead: Bead,
    /// How the solid is cut into layers.
    pub slicing: Slicing,
    /// Process values.
    pub process: Process,
    /// Machines to write programs for, with their declaration spans.
    pub machines: Vec<(Machine, Span)>,
}

/// A parametric section shape, sizes in mm, centred on its frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Section {
    /// `circle(diameter)`
    Circle {
        /// Radius.
        r: Length,
    },
    /// `ellipse(width, height)`: semi-axes along x and y.
    Ellipse {
        /// Semi-axis along x.
        a: Length,
        /// Semi-axis along y.
        b: Length,
    },
    /// `square(side)`, `rectangle(width, height)`: half sides.
    Rectangle {
        /// Half width (x).
        a: Length,
        /// Half height (y).
        b: Length,
    },
    /// `rounded_rectangle(width, height, radius)`.
    RoundedRectangle {
        /// Half width (x).
        a: Length,
        /// Half height (y).
        b: Length,
        /// Corner radius.
        r: Length,
    },
    /// `polygon(sides, circumradius | side)`: a vertex on +x.
    Polygon {
        /// Number of sides.
        n: u32,
        /// Circumradius.
        r: Length,
    },
}

/// Where the section's size is measured.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Measure {
    /// The size is the bead's centre line (the path).
    Centre,
    /// The size is the outer face of the wall: the path runs half a bead width
    /// inside.
    Outer,
}

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

/// How the section changes from the start to the end shape.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Morph {
    /// Superellipse whose exponent and semi-axes move linearly between the ends
    /// (circle/ellipse/square/rectangle ends only).
    Superellipse,
    /// Linear blend of the polar radius at each angle.
    Radial,
}

/// A loft built as a single-bead wall.
#[derive(Clone, Debug)]
pub struct Loft {
    /// The loft's name.
    pub name: String,
    /// Start section.
    pub from: Section,
    /// End section.
    pub to: Section,
    /// Centre line.
    pub spine: Spine,
    /// Rotation of the end section relative to the start, about the spine.
    pub twist: Angle,
    /// Morph between the sections.
    pub morph: Morph,
    /// Where section sizes are measured.
    pub measure: Measure,
    /// Spans: the whole loft, the spine, the sections' declarations.
    pub span: Span,
    /// The spine expression.
    pub spine_span: Span,
    /// `from` and `to` values.
    pub section_spans: [Span; 2],
}

/// How bead height follows scan speed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum HeightModel {
    /// `H = slope · v + intercept` (seed 003's fitted map).
    Linear {
        /// mm per mm/s (a time).
        slope: f64,
        /// mm.
        intercept: Length,
    },
    /// Deposited area from the powder caught: `A = η·ṁ/(ρ·v)`; the bead is a
    /// circular segment of chord `width` and that area.
    MassBalance {
        /// Powder feed.
        feed: MassFlow,
        /// Catch efficiency η (0–1).
        efficiency: f64,
        /// Density of the deposited metal.
        density: Density,
    },
}

/// A bead model.
#[derive(Clone, Debug)]
pub struct Bead {
    /// Its name.
    pub name: String,
    /// Bead width.
    pub width: Length,
    /// Height model.
    pub model: HeightModel,
    /// Speeds the model is valid for.
    pub speed: [Speed; 2],
    /// Allowed layer heights: the declared range, narrowed to what the model
    /// reaches over its speed range.
    pub height: [Length; 2],
    /// Spans: whole bead, its height range (or the model when not declared), its
    /// speed range.
    pub span: Span,
    /// `height = …`
    pub height_span: Span,
    /// `speed = …`
    pub speed_span: Span,
}

/// How many points a layer gets.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Resolution {
    /// `points = k`
    Count(usize),
    /// `chord_error = e`
    ChordError(Length),
}

/// Slicing strategy.
#[derive(Clone, Debug)]
pub struct Slicing {
    /// `None`: the smallest feasible count.
    pub layers: Option<usize>,
    /// Points per layer.
    pub resolution: Resolution,
    /// Angle of the start/stop point in the section frame, from its x axis.
    pub seam: Angle,
    /// Spans.
    pub span: Span,
    /// `layers = …`, if written.
    pub layers_span: Option<Span>,
    /// `seam = …`, if written.
    pub seam_span: Option<Span>,
}

/// Laser power over the layers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PowerSchedule {
    /// The same power on every layer.
    Constant(Power),
    /// Linear from `from` on layer 0 to `to` on layer `layers`, then `to`.
    Ramp {
        /// Power on the first layer.
        from: Power,
        /// Power from layer `layers` on.
        to: Power,
        /// Ramp length in layers.
        layers: usize,
    },
}

impl PowerSchedule {
    /// Power on layer `i` (0-based).
    pub fn at(&self, i: usize) -> Power {
        match *self {
            PowerSchedule::Constant(p) => p,
            PowerSchedule::Ramp { from, to, layers } => {
                let t = if layers == 0 {
                    1.0
                } else {
                    (i as f64 / layers as f64).min(1.0)
                };
                Power(from.0 + (to.0 - from.0) * t)
            }
        }
    }
}

/// Process values.
#[derive(Clone, Debug)]
pub struct Process {
    /// Powder feed.
    pub powder: MassFlow,
    /// Focal plane relative to the working plane (negative: below).
    pub defocus: Length,
    /// Power schedule.
    pub power: PowerSchedule,
    /// Allowed laser power.
    pub power_range: [Power; 2],
    /// `power = …`
    pub power_span: Span,
}

impl Section {
    /// The section offset inward by `d` (for sizes measured at the wall's outer
    /// face: the bead's centre line runs `w/2` inside). Exact for every shape but
    /// the ellipse, whose offset curve is not an ellipse (its semi-axes shrink by
    /// `d`). `None` if nothing is left.
    pub fn inset(self, d: Length) -> Option<Section> {
        let d = d.0;
        let pos = |x: f64| (x > 1e-9).then_some(Length(x));
        Some(match self {
            Section::Circle { r } => Section::Circle { r: pos(r.0 - d)? },
            Section::Ellipse { a, b } => Section::Ellipse {
                a: pos(a.0 - d)?,
                b: pos(b.0 - d)?,
            },
            Section::Rectangle { a, b } => Section::Rectangle {
                a: pos(a.0 - d)?,
                b: pos(b.0 - d)?,
            },
            Section::RoundedRectangle { a, b, r } => Section::RoundedRectangle {
                a: pos(a.0 - d)?,
                b: pos(b.0 - d)?,
                r: Length((r.0 - d).max(0.0)),
            },
            Section::Polygon { n, r } => {
                // Moving each side in by d moves the vertices in by d / cos(π/n).
                let dr = d / (std::f64::consts::PI / n as f64).cos();
                Section::Polygon {
                    n,
                    r: pos(r.0 - dr)?,
                }
            }
        })
    }
}
