//! `wall NAME { … }`: a wall laid along an open path, and the paths it
//! takes — `polyline(…)`, `arc(…)` and `chain(…)` of them.

use super::Bound::{Any, Positive};
use super::DefaultValue::{Count as DefaultCount, Word as DefaultWord};
use super::Kind::{Call, Count, Deferred, Either, List, Name, Point, Quantity, Word};
use super::Need::{Default, Optional, Required};
use super::{Block, Field, Kind, Len};
use crate::units::Dim;

/// Most beads side by side a wall may have.
pub const MAX_BEADS: usize = 100;

/// Most points a path may have, all its pieces together.
pub const MAX_PATH_POINTS: usize = 10_000;

/// A path: one of the path calls.
const PATH: Kind = Call(&[&POLYLINE, &ARC, &CHAIN]);

/// The fields of `wall NAME { … }`.
pub mod fields {
    use super::*;

    /// `along = …`.
    pub static ALONG: Field = Field::new(
        "along",
        PATH,
        Required("polyline(points = [[0 mm, 0 mm], [40 mm, 0 mm], [40 mm, 25 mm]])"),
        "the open path the wall follows, in the part's x and y",
    );
    /// `beads = …`.
    pub static BEADS: Field = Field::new(
        "beads",
        Count(1, MAX_BEADS),
        Default(DefaultCount(1)),
        "how many beads side by side, the slicing's `offset` apart (each a parallel offset of the path)",
    );
    /// `side = …`.
    pub static SIDE: Field = Field::new(
        "side",
        Word(&["centre", "center", "left", "right"]),
        Default(DefaultWord("centre")),
        "where the wall lies: centred on the path, or on its left or right (the path is then that wall's face), looking along it",
    );
    /// `height = …`.
    pub static HEIGHT: Field = Field::new(
        "height",
        Quantity(Dim::LENGTH, Positive),
        Optional,
        "the height, rounded up to whole layers; or `layers` in the slicing block",
    );
    /// `bead = …`.
    pub static BEAD: Field = Field::new(
        "bead",
        Name("bead"),
        Required("my_bead"),
        "the bead model of its beads",
    );
    /// `ends = …`.
    pub static ENDS: Field = Field::new(
        "ends",
        Either(&[Word(&["stop"]), Call(&[&LEAD])]),
        Default(DefaultWord("stop")),
        "how each bead starts and ends: `stop`, the laser on and off at the path's ends; `lead(length)`, the nozzle running on past them with the laser off",
    );
    /// `on = …`.
    pub static ON: Field = Field::new(
        "on",
        Call(&[&crate::sema::schema::solid::SCAN]),
        Optional,
        "the measured part the wall is built on, `scan(file = …)`: its layers start on the scanned surface and rise to `top` (docs/repair.md, *A wall on a scan*)",
    );
    /// `top = …`.
    pub static TOP: Field = Field::new(
        "top",
        Deferred(&Either(&[
            Quantity(Dim::LENGTH, Positive),
            Call(&[
                &crate::sema::schema::solid::EDGES,
                &crate::sema::schema::solid::PLANE,
                &crate::sema::schema::solid::MESH,
            ]),
            Name("solid"),
        ])),
        Optional,
        "with `on`: the finished wall's top above the part's z = 0 at every point of its path: a height, an expression of `x` and `y`, `plane(…)`, `edges(…)` over the path's extent, or the part as designed (`mesh(…)`, a solid's name) (then there is no `height`)",
    );
    /// `direction = …`.
    pub static DIRECTION: Field = Field::new(
        "direction",
        Word(&["alternate", "one_way"]),
        Default(DefaultWord("alternate")),
        "which way the beads run: `alternate`, each layer the other way (the ends build evenly); `one_way`, always from the path's start, with a travel back",
    );
}

/// `wall NAME { … }`: a wall along an open path.
pub static WALL: Block = Block::new(
    "open_wall",
    "wall NAME { … }",
    "a wall laid along an open path, built in flat layers (or, on a scan, in layers that level it)",
    &[
        &fields::ALONG,
        &fields::BEADS,
        &fields::SIDE,
        &fields::HEIGHT,
        &fields::BEAD,
        &fields::ENDS,
        &fields::DIRECTION,
        &fields::ON,
        &fields::TOP,
    ],
);

/// The arguments of the path calls.
pub mod path {
    use super::*;

    /// `polyline(points = …)`.
    pub static POINTS: Field = Field::new(
        "points",
        List(&Point, Len::Any),
        Required("[[0 mm, 0 mm], [40 mm, 0 mm]]"),
        "the points the path runs through, straight from each to the next (at least two)",
    );
    /// `arc(centre = …)`.
    pub static CENTRE: Field = Field::new(
        "centre",
        Point,
        Required("[0 mm, 0 mm]"),
        "the arc's centre",
    );
    /// `arc(radius = …)`.
    pub static RADIUS: Field = Field::new(
        "radius",
        Quantity(Dim::LENGTH, Positive),
        Required("20 mm"),
        "the arc's radius",
    );
    /// `arc(from = …)`.
    pub static FROM: Field = Field::new(
        "from",
        Quantity(Dim::ANGLE, Any),
        Required("0 deg"),
        "the angle the arc starts at, seen from the centre (from +x, counter-clockwise)",
    );
    /// `arc(to = …)`.
    pub static TO: Field = Field::new(
        "to",
        Quantity(Dim::ANGLE, Any),
        Required("90 deg"),
        "the angle it ends at: counter-clockwise when larger than `from`, clockwise when smaller, less than a turn away",
    );
    /// `chain(pieces = …)`.
    pub static PIECES: Field = Field::new(
        "pieces",
        List(&Call(&[&POLYLINE, &ARC]), Len::Any),
        Required("[polyline(points = [[0 mm, 0 mm], [20 mm, 0 mm]]), arc(centre = [20 mm, 10 mm], radius = 10 mm, from = -90 deg, to = 0 deg)]"),
        "the pieces in order, each starting where the one before ends",
    );
    /// `lead(length = …)`.
    pub static LENGTH: Field = Field::new(
        "length",
        Quantity(Dim::LENGTH, Positive),
        Required("3 mm"),
        "how far the nozzle runs on, laser off, before the path's start and past its end, along its direction there",
    );
}

/// `polyline(points)`: straight pieces through points.
pub static POLYLINE: Block = Block::new(
    "polyline",
    "polyline(points)",
    "an open path of straight pieces through points",
    &[&path::POINTS],
)
.positional(1);

/// `arc(centre, radius, from, to)`: an arc of a circle as a path.
pub static ARC: Block = Block::new(
    "path_arc",
    "arc(centre, radius, from, to)",
    "an open path along an arc of a circle",
    &[&path::CENTRE, &path::RADIUS, &path::FROM, &path::TO],
);

/// `chain(pieces)`: paths one after another.
pub static CHAIN: Block = Block::new(
    "chain",
    "chain(pieces)",
    "an open path of polylines and arcs, each starting where the one before ends",
    &[&path::PIECES],
)
.positional(1);

/// `lead(length)`: a wall's ends run on with the laser off.
pub static LEAD: Block = Block::new(
    "lead",
    "lead(length)",
    "a bead's start and end run on past the path's ends with the laser off, at the bead's speed",
    &[&path::LENGTH],
)
.positional(1);
