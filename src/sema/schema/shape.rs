//! The shape calls: the sections (`circle(…)`, …), an outline's
//! `arc(to, radius, turn)` piece, `region(…)`, `place(…)` and
//! `bolt_circle(…)`.

use super::Bound::{Any, NonNegative, Positive};
use super::DefaultValue::{Described, Quantity as DefaultQuantity, Word as DefaultWord};
use super::Kind::{self, Call, Count, Either, List, Point, Quantity, Shape, Word};
use super::Need::{Default, Optional, Required, RequiredUnless};
use super::{Block, Field, Len};
use crate::units::Dim;

/// Most holes one region may have (a bolt circle's count included): every
/// pair of holes whose boxes overlap is tested on every layer, so the bound
/// keeps that work to well under a second whatever the holes are.
pub const MAX_HOLES: usize = 1000;

/// Most sides of a polygon.
pub const MAX_SIDES: usize = 1000;

const LENGTH: Kind = Quantity(Dim::LENGTH, Positive);

/// The section constructors.
pub static SECTIONS: &[&Block] = &[
    &CIRCLE,
    &ELLIPSE,
    &SQUARE,
    &RECTANGLE,
    &ROUNDED_RECTANGLE,
    &POLYGON,
];

/// The arguments of the sections.
pub mod section {
    use super::*;

    /// `circle(diameter = …)`.
    pub static DIAMETER: Field = Field::new(
        "diameter",
        LENGTH,
        RequiredUnless("60 mm", "`radius` is given"),
        "the circle's diameter",
    );
    /// `circle(radius = …)`.
    pub static RADIUS: Field =
        Field::new("radius", LENGTH, Optional, "the circle's radius, instead");
    /// `width = …` of an ellipse or a rectangle.
    pub static WIDTH: Field = Field::new("width", LENGTH, Required("60 mm"), "the size along x");
    /// `height = …` of an ellipse or a rectangle.
    pub static HEIGHT: Field = Field::new("height", LENGTH, Required("40 mm"), "the size along y");
    /// `square(side = …)`.
    pub static SIDE: Field = Field::new("side", LENGTH, Required("60 mm"), "the square's side");
    /// `rounded_rectangle(radius = …)`.
    pub static CORNER_RADIUS: Field = Field::new(
        "radius",
        Quantity(Dim::LENGTH, NonNegative),
        Required("5 mm"),
        "the corners' radius, at most half the shorter side",
    );
    /// `polygon(sides = …)`.
    pub static SIDES: Field = Field::new(
        "sides",
        Count(3, MAX_SIDES),
        Required("6"),
        "how many sides; a vertex lies on +x",
    );
    /// `polygon(circumradius = …)`.
    pub static CIRCUMRADIUS: Field = Field::new(
        "circumradius",
        LENGTH,
        RequiredUnless("30 mm", "`side` is given"),
        "the radius through the vertices",
    );
    /// `polygon(side = …)`.
    pub static POLYGON_SIDE: Field =
        Field::new("side", LENGTH, Optional, "the side's length, instead");
}

/// `circle(diameter)` or `circle(radius = …)`.
pub static CIRCLE: Block = Block::new(
    "circle",
    "circle(diameter)",
    "a circle, by its diameter or radius",
    &[&section::DIAMETER, &section::RADIUS],
)
.positional(1);

/// `ellipse(width, height)`.
pub static ELLIPSE: Block = Block::new(
    "ellipse",
    "ellipse(width, height)",
    "an ellipse, its width along x",
    &[&section::WIDTH, &section::HEIGHT],
)
.positional(2);

/// `square(side)`.
pub static SQUARE: Block =
    Block::new("square", "square(side)", "a square", &[&section::SIDE]).positional(1);

/// `rectangle(width, height)`.
pub static RECTANGLE: Block = Block::new(
    "rectangle",
    "rectangle(width, height)",
    "a rectangle, its width along x",
    &[&section::WIDTH, &section::HEIGHT],
)
.positional(2);

/// `rounded_rectangle(width, height, radius)`.
pub static ROUNDED_RECTANGLE: Block = Block::new(
    "rounded_rectangle",
    "rounded_rectangle(width, height, radius)",
    "a rectangle with rounded corners",
    &[&section::WIDTH, &section::HEIGHT, &section::CORNER_RADIUS],
)
.positional(3);

/// `polygon(sides, circumradius)` or `polygon(sides, side = …)`.
pub static POLYGON: Block = Block::new(
    "polygon",
    "polygon(sides, circumradius)",
    "a regular polygon, a vertex on +x, by its circumradius or side",
    &[
        &section::SIDES,
        &section::CIRCUMRADIUS,
        &section::POLYGON_SIDE,
    ],
)
.positional(2);

/// The arguments of an outline's arc and of the region calls.
pub mod piece {
    use super::*;

    /// `arc(to = …)`.
    pub static TO: Field = Field::new(
        "to",
        Point,
        Required("[40 mm, 20 mm]"),
        "where the arc ends",
    );
    /// `arc(radius = …)`.
    pub static RADIUS: Field = Field::new(
        "radius",
        LENGTH,
        Required("10 mm"),
        "the arc's radius, at least half its chord: the shorter arc is taken",
    );
    /// `arc(turn = …)`.
    pub static TURN: Field = Field::new(
        "turn",
        Word(&["left", "right"]),
        Default(DefaultWord("left")),
        "`left` turns counter-clockwise, `right` clockwise",
    );
    /// `region(outline = …)`.
    pub static OUTLINE: Field = Field::new(
        "outline",
        Shape,
        Required("circle(diameter = 120 mm)"),
        "the outer edge, a shape without holes",
    );
    /// `region(holes = […])`.
    pub static HOLES: Field = Field::new(
        "holes",
        List(&Either(&[Shape, Call(&[&BOLT_CIRCLE])]), Len::Any),
        Optional,
        "the openings, each a shape without holes, or a bolt circle of them",
    );
    /// `place(shape = …)`.
    pub static PLACED: Field = Field::new(
        "shape",
        Shape,
        Required("circle(diameter = 12 mm)"),
        "the shape placed (a section is centred on the origin until placed)",
    );
    /// `at = [x, y]` of `place` and `bolt_circle`.
    pub static AT: Field = Field::new(
        "at",
        Point,
        Default(Described("`[0 mm, 0 mm]`")),
        "where the origin is moved to",
    );
    /// `place(turn = …)`.
    pub static PLACE_TURN: Field = Field::new(
        "turn",
        Quantity(Dim::ANGLE, Any),
        Default(DefaultQuantity(0.0)),
        "the turn about the origin (counter-clockwise), before moving",
    );
    /// `bolt_circle(shape = …)`.
    pub static HOLE: Field = Field::new(
        "shape",
        Shape,
        Required("circle(diameter = 12 mm)"),
        "the hole copied round the circle",
    );
    /// `bolt_circle(count = …)`.
    pub static COUNT: Field = Field::new(
        "count",
        Count(1, MAX_HOLES),
        Required("6"),
        "how many copies",
    );
    /// `bolt_circle(diameter = …)`.
    pub static PITCH: Field = Field::new(
        "diameter",
        LENGTH,
        Required("85 mm"),
        "the pitch circle's diameter, as a drawing gives it",
    );
    /// `bolt_circle(from = …)`.
    pub static FROM: Field = Field::new(
        "from",
        Quantity(Dim::ANGLE, Any),
        Default(DefaultQuantity(0.0)),
        "the first copy's angle; each is turned with the pattern",
    );
}

/// `arc(to, radius, turn)`: a piece of an `outline(…)`.
pub static ARC: Block = Block::new(
    "outline_arc",
    "arc(to, radius, turn)",
    "a piece of an `outline(…)`: the shorter arc to a point",
    &[&piece::TO, &piece::RADIUS, &piece::TURN],
);

/// `region(outline, holes)`: a profile with openings.
pub static REGION: Block = Block::new(
    "region",
    "region(outline, holes)",
    "a profile with openings",
    &[&piece::OUTLINE, &piece::HOLES],
)
.positional(1);

/// `place(shape, at, turn)`: a shape turned, then moved.
pub static PLACE: Block = Block::new(
    "place",
    "place(shape, at, turn)",
    "a shape turned about the origin, then moved",
    &[&piece::PLACED, &piece::AT, &piece::PLACE_TURN],
)
.positional(1);

/// `bolt_circle(shape, count, diameter, from, at)`, in a hole list.
pub static BOLT_CIRCLE: Block = Block::new(
    "bolt_circle",
    "bolt_circle(shape, count, diameter, from, at)",
    "in a hole list: copies of a hole on a pitch circle",
    &[
        &piece::HOLE,
        &piece::COUNT,
        &piece::PITCH,
        &piece::FROM,
        &piece::AT,
    ],
)
.positional(1);
