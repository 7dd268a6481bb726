//! The checked semantic model: names resolved, units converted to typed values,
//! ranges checked. Geometry and slicing read only this.

pub use crate::bead::HeightModel;
use crate::ir::{Machine, MachineOrigin};
use crate::span::Span;
use crate::syntax::ast::Expr;
use crate::units::{Angle, Length, MassFlow, Power, Speed};

pub use crate::geometry::section::{Morph, Section};
pub use crate::geometry::shape::{Hole, Outline, Placed, RegionShape, Segment, Shape, Turn};
pub use crate::geometry::spine::Spine;

mod calibration;
mod segmented_ring;
mod top;
mod wall;
pub use calibration::{Calibration, Coupon, CouponKind};
pub use segmented_ring::{HeightControl, LoopRun, RingBuild};
pub use top::{
    Axis, Level, ScanBase, Top, TopExpr, TopExtrusion, TopMesh, TopSolid, TurnedFrame,
    VariableSlicing, DEFAULT_TOLERANCE,
};
pub use wall::{OpenWall, WallEnds, WallOnScan, WallSide};

/// A whole checked `.lmd` file.
#[derive(Clone, Debug)]
pub struct Model {
    /// The part's name.
    pub part: String,
    /// The solid and how it is cut into layers.
    pub build: Build,
    /// The bead model the part is built with (none on a ring, whose table
    /// gives each segment's process).
    pub bead: Option<Bead>,
    /// Process values.
    pub process: Process,
    /// Machines to write programs for, with where they and their fields are declared.
    pub machines: Vec<(Machine, MachineOrigin)>,
    /// Fixtures and clamps on the plate (`fixture NAME { … }`), each with
    /// where it is placed (its `at`, else its name).
    pub fixtures: Vec<(crate::ir::Fixture, crate::span::Span)>,
    /// Process styles and how they pass from layer to layer.
    pub styles: Styles,
    /// How closely the bead model must lay the planned layers.
    pub tolerance: Tolerance,
}

/// How closely the plan's bead model must lay the layers it plans
/// (`rise_tolerance`, `max_drift` of the slicing block; `lmd::deposit`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    /// A run's rise may be this share off its planned height.
    pub rise: f64,
    /// The layers' mean errors may add up to this.
    pub drift: Length,
}

impl Default for Tolerance {
    fn default() -> Self {
        Tolerance {
            rise: crate::deposit::RISE_TOLERANCE,
            drift: Length(crate::deposit::MAX_DRIFT),
        }
    }
}

/// The style table, in declaration order, and its inheritance.
#[derive(Clone, Debug, Default)]
pub struct Styles {
    /// Declared styles; id 0 (the process block's values) is not among them.
    pub table: Vec<Style>,
    /// How a layer's styles pass to the next layer's similar tracks, if at all.
    pub inheritance: Option<Inheritance>,
}

/// `style NAME { id, power, speed, powder, colour, when { … } }`: process values
/// that replace the process block's on the tracks its rules pick.
#[derive(Clone, Debug)]
pub struct Style {
    /// Id written into every point (1..=65535; 0 is the process block).
    pub id: u16,
    /// Its name.
    pub name: String,
    /// Laser power, if the style sets it.
    pub power: Option<Power>,
    /// Scan speed, if the style sets it.
    pub speed: Option<Speed>,
    /// Powder feed, if the style sets it.
    pub powder: Option<MassFlow>,
    /// Display colour `#rrggbb`.
    pub colour: String,
    /// Each `when { … }` block: the style applies where all of one block's
    /// conditions hold.
    pub rules: Vec<Vec<StyleCondition>>,
    /// The style block.
    pub span: Span,
}

/// Which tracks a `when { paths = … }` condition picks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PathSelect {
    /// The outermost contour pass.
    OuterContour,
    /// Contour passes inside the outermost one.
    InnerContour,
    /// Any contour pass.
    Contour,
    /// Raster infill tracks.
    Infill,
}

/// One condition of a `when` block.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StyleCondition {
    /// `paths = …`
    Paths(PathSelect),
    /// `shorter_than = L`: the track is shorter than L.
    ShorterThan(Length),
    /// `longer_than = L`: the track is at least L long.
    LongerThan(Length),
    /// `near_boundary = L`: all of the track lies within L of the layer's
    /// boundary.
    NearBoundary(Length),
    /// `near_corner = L`: the track passes within L of a corner that turns by at
    /// least `corner_angle`.
    NearCorner(Length, Angle),
    /// `layers = a .. b`: layers a to b, counted from 1 as the programs do.
    Layers(usize, usize),
}

/// `inheritance { band, hit }`: a track inherits the style of the
/// previous layer's tracks of that style when at least `hit` of its length lies
/// within `band` of them.
#[derive(Clone, Copy, Debug)]
pub struct Inheritance {
    /// Half-width of the band around a styled track (the paper's R/2).
    pub band: Length,
    /// Share of a track's length that must lie inside the band, 0–1.
    pub hit: f64,
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

impl Loft {
    /// The loft's geometry, ready to be evaluated at any station.
    pub fn geometry(&self) -> crate::geometry::LoftGeometry {
        let (from, to) = (self.from, self.to);
        crate::geometry::LoftGeometry::new(from, to, self.morph, self.spine, self.twist.0)
    }
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
    /// What the model's heights were measured as.
    pub basis: crate::deposit::Basis,
    /// Speeds the model is valid for.
    pub speed: [Speed; 2],
    /// Allowed layer heights: the declared range, narrowed to what the model
    /// reaches over its speed range.
    pub height: [Length; 2],
    /// The widths measured at each speed (a `table(…)` with `width`), which
    /// the deposit model takes over the one `width`.
    pub widths: Option<crate::bead::Widths>,
    /// The speeds the model was measured over (a table's, a fit's data),
    /// when known.
    pub measured: Option<[Speed; 2]>,
    /// The fit that gave the model (`fit(…, data = "…")`).
    pub fit: Option<crate::bead::fit::Summary>,
    /// The `height = …` range as declared, if it is.
    pub declared_height: Option<[Length; 2]>,
    /// The nozzle's tilts from vertical the model was measured at (`tilt`),
    /// rad, and where they are written; `None`: vertical.
    pub tilt: Option<([f64; 2], Span)>,
    /// The laser powers the model was measured at (`powers`, or a fit's
    /// coupons'), and where they are said; `None`: not known.
    pub powers: Option<(Vec<crate::units::Power>, Span)>,
    /// The powder feeds it was measured at (`powders`, or a fit's
    /// coupons'), and where they are said; `None`: not known.
    pub powders: Option<(Vec<MassFlow>, Span)>,
    /// The process's powder feed, which a mass-balance model lays by
    /// ([`crate::deposit::Deposit::fed`]); `None` until the process is read.
    pub feed: Option<crate::units::MassFlow>,
    /// Spans: whole bead, its height range (or the model when not declared), its
    /// speed range.
    pub span: Span,
    /// `height = …`
    pub height_span: Span,
    /// `speed = …`
    pub speed_span: Span,
}

/// Whether `x` lies in `lo ..= hi`, with the one rounding slack every range
/// rule allows, the checker's and the verifier's alike
/// ([`in_range`](crate::units::in_range)).
pub fn within(x: f64, lo: f64, hi: f64) -> bool {
    crate::units::in_range(x, [lo, hi])
}

impl Bead {
    /// The bead as the deposit model reads it.
    pub fn deposit(&self) -> crate::deposit::Deposit {
        let d = crate::deposit::Deposit {
            model: self.model.clone(),
            width: self.width,
            basis: self.basis,
            widths: self.widths.clone(),
        };
        match self.feed {
            Some(f) => d.fed(f),
            None => d,
        }
    }

    /// Whether the model holds at scan speed `v`.
    pub fn covers_speed(&self, v: Speed) -> bool {
        within(v.0, self.speed[0].0, self.speed[1].0)
    }

    /// Whether `h` is an allowed layer height.
    pub fn covers_height(&self, h: Length) -> bool {
        within(h.0, self.height[0].0, self.height[1].0)
    }

    /// The layer heights this bead stacks where each deposit fills a strip
    /// `pitch` wide ([`crate::deposit`]): its rises `A/pitch` over its
    /// speeds, narrowed to the declared `height`. A bead measured at one
    /// speed rises `A/pitch` whatever the pitch it is given: its allowed
    /// heights are the declared ones or `A/w .. h`, a lone track's to that
    /// of tracks at the flat-top offset.
    pub fn heights(&self, pitch: Length) -> [Length; 2] {
        if let HeightModel::Measured { .. } = self.model {
            return self.height;
        }
        let [lo, hi] = self.deposit().rises(self.speed, pitch);
        match self.declared_height {
            Some([a, b]) => [Length(lo.0.max(a.0)), Length(hi.0.min(b.0))],
            None => [lo, hi],
        }
    }

    /// Whether `h` is a layer height this bead stacks at `pitch`.
    pub fn stacks(&self, h: Length, pitch: Length) -> bool {
        let [lo, hi] = self.heights(pitch);
        within(h.0, lo.0, hi.0)
    }
}

impl Process {
    /// Whether the laser can give `p`.
    pub fn covers_power(&self, p: Power) -> bool {
        within(p.0, self.power_range[0].0, self.power_range[1].0)
    }
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
    /// Where each layer starts and stops: an angle in the section frame
    /// (from its x axis), turning or drawn layer by layer.
    pub seam: SeamRule,
    /// Spans.
    pub span: Span,
    /// `layers = …`, if written.
    pub layers_span: Option<Span>,
    /// `seam = …`, if written.
    pub seam_span: Option<Span>,
    /// `rise_tolerance` and `max_drift`.
    pub tolerance: Tolerance,
    /// `nozzle = wall`: the build direction follows the wall's lean.
    pub follow_wall: bool,
    /// `max_overhang = …`, if written (rad).
    pub max_overhang: Option<f64>,
    /// `layer_change = …`: how each layer goes on to the next.
    pub layer_change: LayerChange,
    /// `layer_change = …`, if written.
    pub layer_change_span: Option<Span>,
}

/// How a one-bead wall goes from one layer to the next: `layer_change = …`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LayerChange {
    /// The laser goes off, the nozzle lifts and comes down at the next
    /// layer's start.
    Lift,
    /// The end of each loop climbs to the next layer's start with the laser
    /// on, and the next layer goes on from there: over its last `length`,
    /// or over the whole loop (`None`: a helix of constant pitch).
    Spiral {
        /// How much of the loop's end climbs (`None`: all of it).
        length: Option<Length>,
    },
}

impl LayerChange {
    /// Whether layers go on into each other with the laser on.
    pub fn is_spiral(self) -> bool {
        matches!(self, LayerChange::Spiral { .. })
    }
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
    /// Scan speed of planar layers (`speed = …`), and where it was declared.
    pub speed: Option<(Speed, Span)>,
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
    /// `power_range = …`, if declared.
    pub power_range_span: Option<Span>,
    /// `powder = …`
    pub powder_span: Span,
    /// Cooling between layers (`min_layer_time`, `dwell`).
    pub heat: crate::ir::Heat,
    /// The thermal model's data and limit (`thermal { … }`), its layers
    /// empty, and where a refused limit is reported.
    pub thermal: Option<(crate::ir::Thermal, Span)>,
}

/// A solid with the slicing strategy that builds it: each strategy takes the
/// solids it can slice, so a mismatch cannot reach the slicer.
#[derive(Clone, Debug)]
pub enum Build {
    /// A thin-walled loft, sliced normal to its spine.
    Duct {
        /// The loft.
        loft: Loft,
        /// Normal slicing.
        slicing: Slicing,
    },
    /// A profile extruded and built in flat, filled layers.
    Block {
        /// The extrusion, its profile evaluated for every layer.
        extrusion: Extrusion,
        /// Planar slicing and the fill.
        slicing: PlanarSlicing,
    },
    /// A footprint built up to a variable top in layers of variable
    /// thickness.
    Variable {
        /// The footprint and its top.
        extrusion: TopExtrusion,
        /// Variable slicing.
        slicing: VariableSlicing,
    },
    /// A segmented ring laid in one continuous run, with its height loop.
    Ring(RingBuild),
    /// Coupons to measure a bead on (`calibration { … }`).
    Calibration(Calibration),
    /// A wall along an open path, built in flat layers.
    Wall {
        /// The wall and its path.
        wall: OpenWall,
        /// How tall: a layer count or a height.
        extent: Extent,
        /// Planar slicing: the layer height, the beads' offset, the chord
        /// error.
        slicing: PlanarSlicing,
    },
    /// A wall along an open path built on a scanned part, in layers of
    /// variable thickness from the scan up to its top.
    ScanWall {
        /// The wall and its path.
        wall: OpenWall,
        /// The scanned part and the top.
        on: WallOnScan,
        /// Variable slicing: the layer count, the segments' tolerance.
        slicing: VariableSlicing,
        /// The beads' pitch across the wall (the strip each fills).
        pitch: Length,
    },
}

/// The ways of a contour loop's seam (where it starts and ends) from layer
/// to layer: `seam = …` in `slicing planar`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SeamRule {
    /// At the loop's point with the smallest `(y, x)`, the same on every
    /// layer.
    Lowest,
    /// Farthest in one direction (from +x, counter-clockwise).
    Toward(Angle),
    /// Farthest in a direction that turns by `step` every layer from `from`.
    Rotating {
        /// The direction on the first layer.
        from: Angle,
        /// Added every layer.
        step: Angle,
    },
    /// Farthest in a direction drawn for each layer from a fixed seed: the
    /// same file always gives the same seams.
    Random {
        /// The seed.
        seed: u64,
    },
    /// At the loop's sharpest corner (a corner hides the seam).
    SharpestCorner,
    /// Layer `k`'s seam `k·shift` along the loop (the way the nozzle goes)
    /// from the lowest point, wrapping round: the starts climb the part on a
    /// slant, a fixed distance apart.
    Staggered {
        /// How far each layer's seam moves along the loop (mm).
        shift: Length,
    },
}

/// Whether neighbouring raster tracks are joined at their ends along the
/// edge: `link = …` in `raster(…)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LinkMode {
    /// Every track its own: laser off, retract, approach.
    None,
    /// Linked with the laser on: the nozzle turns along the edge depositing.
    LaserOn,
    /// Linked with the laser off: the nozzle moves along the edge at the
    /// layer's height, without lifting.
    LaserOff,
}

/// `extrude NAME { profile, height, size, bead }`: what the checker knows of
/// an extrusion. How many layers it has and how far each rises is the
/// slicer's decision ([`crate::slice::layers`]).
#[derive(Clone, Debug)]
pub struct Extrusion {
    /// Its name.
    pub name: String,
    /// The profile: one shape, or one that follows the layer.
    pub profile: LayerProfile,
    /// How tall it is: a layer count or a height.
    pub extent: Extent,
    /// Whether the profile's size is the outer face or the bead centre line.
    pub measure: Measure,
    /// The extrude block.
    pub span: Span,
    /// The profile's declaration.
    pub profile_span: Span,
    /// Where the shape itself is written: the profile's `outline(…)` (or the
    /// section), for errors about the shape.
    pub shape_span: Span,
}

/// An extrusion's profile.
#[derive(Clone, Debug)]
pub enum LayerProfile {
    /// The same shape on every layer.
    Fixed(Shape),
    /// A profile whose numbers use `layer` or `layer_z`: the slicer evaluates
    /// it on each layer ([`ProfileExpr::evaluator`]).
    PerLayer(ProfileExpr),
    /// A mesh's section on each layer (`mesh(…)`).
    Mesh(MeshSolid),
}

/// `mesh(file = "…", …)`: a solid given as a triangle mesh, read, checked
/// closed and manifold, and placed on the plate.
#[derive(Clone, Debug)]
pub struct MeshSolid {
    /// The file, as the program names it.
    pub path: String,
    /// The placed mesh.
    pub mesh: std::sync::Arc<crate::geometry::mesh::Mesh>,
    /// Its highest point (mm): the extrusion's height unless one is written.
    pub top: Length,
    /// The file's unit: mm per file unit (from `units`, or a 3MF's `unit`).
    pub scale: f64,
    /// A 3MF's own name for its unit (`millimeter`, `foot`); `None` for an
    /// STL, whose unit `units` says.
    pub file_unit: Option<&'static str>,
    /// The `mesh(…)` call.
    pub span: Span,
}

/// A profile that follows the layer, kept as the user wrote it: the
/// expression and the file's constants it may use. It was checked on layer 0;
/// another layer may still make it invalid (a negative size, crossing edges),
/// which the slicer reports with that layer.
#[derive(Clone, Debug)]
pub struct ProfileExpr {
    /// The profile's expression.
    pub expr: Expr,
    /// Every `let` of the file: name, where it is declared, its expression.
    pub constants: Vec<(String, Span, Expr)>,
}

/// How tall an extrusion is, as the file says it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Extent {
    /// `layers = n` in the slicing block.
    Layers(usize, Span),
    /// `height = h` in the extrude block: as many whole layers as reach it.
    Height(Length, Span),
}

/// Order of raster tracks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pattern {
    /// Every other track runs back (no travel between tracks).
    Serpentine,
    /// All tracks run the same way.
    OneWay,
}

/// `infill = raster(…)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Raster {
    /// Track direction on the first layer, from +X counter-clockwise.
    pub angle: Angle,
    /// Added to the direction on every layer.
    pub rotate: Angle,
    /// Serpentine or one-way.
    pub pattern: Pattern,
    /// Most a track end is extended where the boundary curves (`ΔX ≤ d`,
    /// [`crate::fill`]).
    pub extend: Length,
    /// Whether neighbouring tracks are linked along the edge.
    pub link: LinkMode,
}

/// `slicing planar { … }`.
#[derive(Clone, Debug)]
pub struct PlanarSlicing {
    /// Contour passes around each layer.
    pub contours: usize,
    /// Offset between neighbouring tracks (contours and raster), mm.
    pub offset: Length,
    /// Whether the offset was derived for a flat top (`offset = auto`, d = A/h).
    pub offset_derived: bool,
    /// The infill, if any.
    pub infill: Option<Raster>,
    /// Largest distance of a flattened arc from the true one.
    pub chord_error: Length,
    /// Where contour loops start on each layer.
    pub seam: SeamRule,
    /// Scan speed of every track.
    pub speed: Speed,
    /// `layer_height`, if declared (`None`: auto, what the tracks lay).
    pub lift: Option<(Length, Span)>,
    /// The slicing block.
    pub span: Span,
    /// The offset's declaration, if written.
    pub offset_span: Option<Span>,
    /// `rise_tolerance` and `max_drift`.
    pub tolerance: Tolerance,
    /// `max_overhang = …`, if written (rad): the contours' lean is checked.
    pub max_overhang: Option<f64>,
    /// `layer_change = …`: how a one-bead wall goes on to the next layer.
    pub layer_change: LayerChange,
    /// `layer_change = …`, if written.
    pub layer_change_span: Option<Span>,
}

impl PlanarSlicing {
    /// Whether a layer is more than one track wide, so that it rises by `A/d`
    /// rather than `A/w`.
    pub fn overlapped(&self) -> bool {
        self.infill.is_some() || self.contours > 1
    }
}

/// Most layers and points per layer a plan may have: 10⁸ points in all keeps
/// memory bounded (the IR holds 80 bytes a point).
pub const MAX_LAYERS: usize = 100_000;
/// See [`MAX_LAYERS`].
pub const MAX_POINTS: usize = 100_000;
