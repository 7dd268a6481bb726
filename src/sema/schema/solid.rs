//! The solids: `loft NAME { … }` and its spines, `extrude NAME { … }` and
//! the sugar of its `top`, and `ring NAME { … }` (a segmented ring) with its
//! `table { … }`.

use super::shape::SECTIONS;
use super::Bound::{Any, Positive, PositiveUpTo};
use super::DefaultValue::{Described, Quantity as DefaultQuantity, Word as DefaultWord};
use super::Kind::{
    self, Block as Nested, Call, Count, Deferred, Either, Layered, List, Name, Point, Quantity,
    Shape, Text, Word,
};
use super::Need::{Default, Optional, Required};
use super::{Block, Field, Len};
use crate::units::Dim;

/// Most segments a ring may have.
pub const MAX_SEGMENTS: usize = 1000;

/// The transition when none is written: the paper's 2°.
pub const DEFAULT_TRANSITION_DEG: f64 = 2.0;

/// Steepest slope of a plane top, deg from the horizontal (its tangent
/// grows without bound toward 90°).
pub const MAX_SLOPE_DEG: f64 = 89.0;

/// The largest bend of an arc spine, rad: three quarters of a turn.
pub const MAX_BEND: f64 = std::f64::consts::PI * 1.5;

/// How a section's size is measured.
const SIZE: Kind = Word(&["centre", "center", "outer"]);

/// A section: a name or a section call.
const SECTION: Kind = Either(&[Name("section"), Call(SECTIONS)]);

/// The fields of `loft NAME { … }`.
pub mod loft {
    use super::*;

    /// `from = …`.
    pub static FROM: Field = Field::new(
        "from",
        SECTION,
        Required("circle(diameter = 60 mm)"),
        "the start section",
    );
    /// `to = …`.
    pub static TO: Field = Field::new(
        "to",
        SECTION,
        Required("square(side = 60 mm)"),
        "the end section",
    );
    /// `spine = …`.
    pub static SPINE: Field = Field::new(
        "spine",
        Call(&[&LINE, &ARC]),
        Required("arc(radius = 250 mm, angle = 45 deg)"),
        "the centre line the sections sweep along, from the origin heading +Z",
    );
    /// `twist = …`.
    pub static TWIST: Field = Field::new(
        "twist",
        Quantity(Dim::ANGLE, Any),
        Default(DefaultQuantity(0.0)),
        "the end section's turn about the spine, reached linearly",
    );
    /// `morph = …`.
    pub static MORPH: Field = Field::new(
        "morph",
        Word(&["superellipse", "radial"]),
        Default(Described(
            "`superellipse` between circles, ellipses and rectangles, else `radial`",
        )),
        "how the section changes from one end to the other",
    );
    /// `size = …`.
    pub static SIZE: Field = Field::new(
        "size",
        super::SIZE,
        Default(DefaultWord("centre")),
        "whether the sizes are the wall's centre line or its outer face",
    );
    /// `wall = …`.
    pub static WALL: Field = Field::new(
        "wall",
        Name("bead"),
        Required("my_bead"),
        "the bead model of the single-bead wall",
    );
}

/// `loft NAME { … }`: a solid swept along a spine, built as a one-bead wall.
pub static LOFT: Block = Block::new(
    "loft",
    "loft NAME { … }",
    "a solid swept from one section to another along a spine, built as a one-bead wall",
    &[
        &loft::FROM,
        &loft::TO,
        &loft::SPINE,
        &loft::TWIST,
        &loft::MORPH,
        &loft::SIZE,
        &loft::WALL,
    ],
);

/// The arguments of the spines.
pub mod spine {
    use super::*;

    /// `line(length = …)`.
    pub static LENGTH: Field = Field::new(
        "length",
        Quantity(Dim::LENGTH, Positive),
        Required("100 mm"),
        "how far it goes straight up",
    );
    /// `arc(radius = …)`.
    pub static RADIUS: Field = Field::new(
        "radius",
        Quantity(Dim::LENGTH, Positive),
        Required("250 mm"),
        "the bend radius, toward +X",
    );
    /// `arc(angle = …)`.
    pub static ANGLE: Field = Field::new(
        "angle",
        Quantity(Dim::ANGLE, PositiveUpTo(MAX_BEND)),
        Required("45 deg"),
        "how far it bends",
    );
}

/// `line(length)`: a straight spine.
pub static LINE: Block = Block::new(
    "line",
    "line(length)",
    "a straight spine",
    &[&spine::LENGTH],
)
.positional(1);

/// `arc(radius, angle)`: a spine bending toward +X.
pub static ARC: Block = Block::new(
    "spine_arc",
    "arc(radius, angle)",
    "a spine bending toward +X",
    &[&spine::RADIUS, &spine::ANGLE],
);

/// The fields of `extrude NAME { … }`.
pub mod extrude {
    use super::*;

    /// `profile = …`.
    pub static PROFILE: Field = Field::new(
        "profile",
        Layered(&Either(&[
            Name("profile or section"),
            Shape,
            Call(&[&MESH, &SCAN_SECTION]),
        ])),
        Required("my_profile"),
        "the shape each layer fills, a `mesh(…)` whose sections the layers fill, or `scan_section(z = …)`: the section of the part scanned in `on`",
    );
    /// `height = …`.
    pub static HEIGHT: Field = Field::new(
        "height",
        Quantity(Dim::LENGTH, Positive),
        Optional,
        "the height, rounded up to whole layers; or `layers` in the slicing block, or `top`",
    );
    /// `size = …`.
    pub static SIZE: Field = Field::new(
        "size",
        super::SIZE,
        Default(DefaultWord("centre")),
        "whether the profile is the track centre line or the outer face",
    );
    /// `bead = …`.
    pub static BEAD: Field = Field::new(
        "bead",
        Name("bead"),
        Required("my_bead"),
        "the bead model of its tracks",
    );
    /// `top = …`.
    pub static TOP: Field = Field::new(
        "top",
        Deferred(&Either(&[
            Quantity(Dim::LENGTH, Positive),
            Call(&[&EDGES, &PLANE, &MESH]),
            Name("solid"),
        ])),
        Optional,
        "the finished part's height at every point, an expression of `x` and `y`; or the part as designed, its highest surface over each point: `mesh(…)`, or the name of an `extrude` or `loft` of the file, which is then not built (docs/repair.md, *A target solid*)",
    );
    /// `on = …`.
    pub static ON: Field = Field::new(
        "on",
        Call(&[&SCAN]),
        Optional,
        "the measured part the layers are built on, `scan(file = …)`; `top` is then the finished surface's height above the part's z = 0 (docs/repair.md)",
    );
}

/// `extrude NAME { … }`: a profile built up in layers.
pub static EXTRUDE: Block = Block::new(
    "extrude",
    "extrude NAME { … }",
    "a profile built up in layers",
    &[
        &extrude::PROFILE,
        &extrude::HEIGHT,
        &extrude::SIZE,
        &extrude::BEAD,
        &extrude::TOP,
        &extrude::ON,
    ],
);

/// The arguments of `mesh(…)`.
pub mod mesh {
    use super::*;

    /// `mesh(file = "…")`.
    pub static FILE: Field = Field::new(
        "file",
        Text,
        Required("\"part.stl\""),
        "the STL (binary or ASCII) or 3MF file, a path relative to the .lmd file",
    );
    /// `mesh(units = …)`.
    pub static UNITS: Field = Field::new(
        "units",
        Word(crate::geometry::mesh::UNITS),
        Default(DefaultWord("mm")),
        "what one unit of an STL's coordinates is (STL files do not say; a 3MF says its own, and `units` may only repeat it)",
    );
    /// `mesh(turn = [rx, ry, rz])`.
    pub static TURN: Field = Field::new(
        "turn",
        List(&Quantity(Dim::ANGLE, Any), Len::Exactly(3)),
        Default(Described("`[0 deg, 0 deg, 0 deg]`")),
        "turns about the x, then the y, then the z axis (right-handed), after scaling and before moving",
    );
    /// `mesh(at = [x, y, z])`.
    pub static AT: Field = Field::new(
        "at",
        List(&Quantity(Dim::LENGTH, Any), Len::Exactly(3)),
        Default(Described("`[0 mm, 0 mm, 0 mm]`")),
        "where the file's origin goes, after turning, in the part's coordinates: a mesh solid's lowest point must come to z = 0 (the plate); a `register` nominal or a `top` target goes where the part is, wherever that is",
    );
}

/// `mesh(file, units, turn, at)`: a solid given as a triangle mesh.
pub static MESH: Block = Block::new(
    "mesh",
    "mesh(file, units, turn, at)",
    "a solid given as an STL or 3MF mesh, sliced in flat layers (its height is the extrusion's unless `height` or `layers` is written); also a repair's nominal (`scan(register = mesh(…))`) and target (`top = mesh(…)`), which are not sliced",
    &[&mesh::FILE, &mesh::UNITS, &mesh::TURN, &mesh::AT],
)
.positional(1);

/// The arguments of `scan(…)`.
pub mod scan {
    use super::*;

    /// `scan(file = "…")`.
    pub static FILE: Field = Field::new(
        "file",
        Text,
        Required("\"worn.ply\""),
        "the scan: PLY (points or faces), XYZ/CSV text (a point a line), STL, 3MF or E57, a path relative to the .lmd file",
    );
    /// `scan(units = …)`.
    pub static UNITS: Field = Field::new(
        "units",
        Word(crate::geometry::mesh::UNITS),
        Default(DefaultWord("mm")),
        "what one unit of the scan's coordinates is (a 3MF says its own; an E57 is in metres)",
    );
    /// `scan(at = [x, y, z])`.
    pub static AT: Field = Field::new(
        "at",
        List(&Quantity(Dim::LENGTH, Any), Len::Exactly(3)),
        Default(Described("`[0 mm, 0 mm, 0 mm]`")),
        "where the scan's origin goes in the part's coordinates, after turning",
    );
    /// `scan(cell = …)`.
    pub static CELL: Field = Field::new(
        "cell",
        Quantity(Dim::LENGTH, Positive),
        Default(DefaultQuantity(1.0)),
        "the side of the grid's cells the surface is estimated on (a plane fitted through each cell's points)",
    );
    /// `scan(outlier = …)`.
    pub static OUTLIER: Field = Field::new(
        "outlier",
        Quantity(Dim::LENGTH, Positive),
        Default(DefaultQuantity(0.5)),
        "how far a cell may stand out of its neighbours' median before it is taken for a spike and replaced by it",
    );
    /// `scan(register = mesh(…))` or `scan(register = NAME)`.
    pub static REGISTER: Field = Field::new(
        "register",
        Either(&[Call(&[&MESH]), Name("solid")]),
        Optional,
        "the nominal: the part as designed, a `mesh(…)` placed in the part's coordinates by its own `turn` and `at` (it need not be closed nor stand on the plate), or the name of an `extrude` or `loft` of the file, which is then not built; the scan is moved onto it by a best fit that leaves the worn region out, starting from where the scan's `turn` and `at` put it (docs/repair.md, *Registration*)",
    );
    /// `scan(fit_tolerance = …)`.
    pub static FIT_TOLERANCE: Field = Field::new(
        "fit_tolerance",
        Quantity(Dim::LENGTH, Positive),
        Default(DefaultQuantity(0.1)),
        "with `register`: the most the best fit may leave between the scan and the nominal, as the RMS distance of the points it keeps; more is refused (`lmd::scan-registration`)",
    );
}

/// `scan(file, units, turn, at, cell, outlier, register, fit_tolerance)`:
/// a measured part's surface.
pub static SCAN: Block = Block::new(
    "scan",
    "scan(file, units, turn, at, cell, outlier, register, fit_tolerance)",
    "a measured part's surface seen from above, the base a repair is built on",
    &[
        &scan::FILE,
        &scan::UNITS,
        &mesh::TURN,
        &scan::AT,
        &scan::CELL,
        &scan::OUTLIER,
        &scan::REGISTER,
        &scan::FIT_TOLERANCE,
    ],
)
.positional(1);

/// The arguments of `scan_section(…)`.
pub mod scan_section {
    use super::*;

    /// `scan_section(z = …)`.
    pub static Z: Field = Field::new(
        "z",
        Quantity(Dim::LENGTH, Any),
        Required("36 mm"),
        "the height of the cut, in the part's coordinates (where the scan's placement puts it): below the worn or missing part, where the scan shows the part whole",
    );
}

/// `scan_section(z)`: the section of the scanned part at a height, as a
/// profile.
pub static SCAN_SECTION: Block = Block::new(
    "scan_section",
    "scan_section(z)",
    "the section of the extrusion's scanned part (`on = scan(…)`, with faces) at a height, as its profile: the part continued upward as it is",
    &[&scan_section::Z],
)
.positional(1);

/// The arguments of a top's sugar.
pub mod top {
    use super::*;

    /// A slope: a plain number or an angle from the horizontal.
    const SLOPE: Kind = Either(&[Quantity(Dim::NONE, Any), Quantity(Dim::ANGLE, Any)]);

    /// `edges(along = …)`.
    pub static ALONG: Field = Field::new(
        "along",
        Word(&crate::sema::eval::POSITION),
        Required("x"),
        "the axis the top rises along",
    );
    /// `edges(from = …)`.
    pub static FROM: Field = Field::new(
        "from",
        Quantity(Dim::LENGTH, Positive),
        Required("20 mm"),
        "the height on the footprint's edge at the low end of the axis",
    );
    /// `edges(to = …)`.
    pub static TO: Field = Field::new(
        "to",
        Quantity(Dim::LENGTH, Positive),
        Required("36 mm"),
        "the height on the edge at its high end",
    );
    /// `plane(at = …)`.
    pub static AT: Field = Field::new(
        "at",
        Point,
        Default(Described("`[0 mm, 0 mm]`")),
        "the point `height` is given at",
    );
    /// `plane(height = …)`.
    pub static HEIGHT: Field = Field::new(
        "height",
        Quantity(Dim::LENGTH, Any),
        Required("14 mm"),
        "the height at `at`",
    );
    /// `plane(slope_x = …)`.
    pub static SLOPE_X: Field = Field::new(
        "slope_x",
        SLOPE,
        Default(DefaultQuantity(0.0)),
        "the rise per unit of x: a plain number (`16 %`) or an angle below 89 deg",
    );
    /// `plane(slope_y = …)`.
    pub static SLOPE_Y: Field = Field::new(
        "slope_y",
        SLOPE,
        Default(DefaultQuantity(0.0)),
        "the rise per unit of y: a plain number or an angle below 89 deg",
    );
}

/// `edges(along, from, to)`: heights on the footprint's two extreme edges.
pub static EDGES: Block = Block::new(
    "edges",
    "edges(along, from, to)",
    "a top with heights on the footprint's two extreme edges, straight between",
    &[&top::ALONG, &top::FROM, &top::TO],
);

/// `plane(at, height, slope_x, slope_y)`: a sloped plane.
pub static PLANE: Block = Block::new(
    "plane",
    "plane(at, height, slope_x, slope_y)",
    "a sloped plane as a top",
    &[&top::AT, &top::HEIGHT, &top::SLOPE_X, &top::SLOPE_Y],
);

/// The fields of `ring NAME { … }`.
pub mod ring {
    use super::*;

    /// `radius = …`.
    pub static RADIUS: Field = Field::new(
        "radius",
        Quantity(Dim::LENGTH, Positive),
        Required("40 mm"),
        "the nozzle's circle about the origin",
    );
    /// `segments = …`.
    pub static SEGMENTS: Field = Field::new(
        "segments",
        Count(1, MAX_SEGMENTS),
        Required("10"),
        "how many equal segments; the first starts on +x, counter-clockwise",
    );
    /// `transition = …`.
    pub static TRANSITION: Field = Field::new(
        "transition",
        Quantity(Dim::ANGLE, Positive),
        Default(DefaultQuantity(crate::sema::schema::deg(
            DEFAULT_TRANSITION_DEG,
        ))),
        "the end of each segment over which the nozzle moves to the next one's height",
    );
    /// `table { … }`.
    pub static TABLE: Field = Field::new(
        "table",
        Nested(&super::TABLE),
        Required("{ … }"),
        "each segment's process values",
    );
}

/// `ring NAME { … }`: a segmented ring.
pub static RING: Block = Block::new(
    "ring",
    "ring NAME { … }",
    "a ring split into equal segments, each with its own process",
    &[
        &ring::RADIUS,
        &ring::SEGMENTS,
        &ring::TRANSITION,
        &ring::TABLE,
    ],
);

/// The lists of `table { … }`, one entry per segment.
pub mod table {
    use super::*;

    /// `defocus = […]`.
    pub static DEFOCUS: Field = Field::new(
        "defocus",
        List(&Quantity(Dim::LENGTH, Any), Len::PerSegment),
        Required("[-8 mm, -7 mm, …]"),
        "the focal plane's distance from the working plane (negative: below)",
    );
    /// `power = […]`.
    pub static POWER: Field = Field::new(
        "power",
        List(&Quantity(Dim::POWER, Positive), Len::PerSegment),
        Required("[1200 W, 1050 W, …]"),
        "the laser power",
    );
    /// `width = […]`.
    pub static WIDTH: Field = Field::new(
        "width",
        List(&Quantity(Dim::LENGTH, Positive), Len::PerSegment),
        Required("[6.25 mm, 5.55 mm, …]"),
        "the bead width it lays, taken as the spot diameter",
    );
    /// `speed = […]`.
    pub static SPEED: Field = Field::new(
        "speed",
        List(&Quantity(Dim::SPEED, Positive), Len::PerSegment),
        Required("[4 mm/s, 5 mm/s, …]"),
        "the starting horizontal scan speed",
    );
}

/// A ring's `table { … }`.
pub static TABLE: Block = Block::new(
    "table",
    "table { … }",
    "a ring's process values, one entry per segment",
    &[&table::DEFOCUS, &table::POWER, &table::WIDTH, &table::SPEED],
);
