//! `calibration { … }`: the coupons `lmdc calibrate` lays to measure a
//! bead — a matrix of speeds (and powers, powder feeds), the coupon kind,
//! and the plate they go on.

use super::Bound::Positive;
use super::DefaultValue::{Count as DefaultCount, Described, Word as DefaultWord};
use super::Kind::{Call, Count, Either, List, Name, Point, Quantity, Range, Word};
use super::Need::{Default, Required};
use super::{Block, Field, Len};
use crate::units::Dim;

/// `bead = NAME`.
pub static BEAD: Field = Field::new(
    "bead",
    Name("bead"),
    Required("track"),
    "the bead the coupons lay: its `width` spaces them (its model, the thing measured, is not read)",
);

/// `speeds = …`.
pub static SPEEDS: Field = Field::new(
    "speeds",
    Either(&[
        List(&Quantity(Dim::SPEED, Positive), Len::Any),
        Range(Dim::SPEED),
    ]),
    Required("4 mm/s .. 8.7 mm/s"),
    "the scan speeds: a list, or `from .. to` with `count` speeds evenly apart",
);

/// `count = …`.
pub static COUNT: Field = Field::new(
    "count",
    Count(2, 1000),
    Default(Described("required with a range of `speeds`")),
    "how many speeds a range of `speeds` is split into, both ends included",
);

/// `powers = […]`.
pub static POWERS: Field = Field::new(
    "powers",
    List(&Quantity(Dim::POWER, Positive), Len::Any),
    Default(Described("the process `power`")),
    "the laser powers: every speed is laid at each",
);

/// `powders = […]`.
pub static POWDERS: Field = Field::new(
    "powders",
    List(&Quantity(Dim::MASS_FLOW, Positive), Len::Any),
    Default(Described("the process `powder`")),
    "the powder feeds: every speed and power is laid at each",
);

/// `repeat = …`.
pub static REPEAT: Field = Field::new(
    "repeat",
    Count(1, 100),
    Default(DefaultCount(1)),
    "coupons laid at each combination, so the fit can tell scatter from trend",
);

/// `coupon = …`.
pub static COUPON: Field = Field::new(
    "coupon",
    Either(&[Word(&["track"]), Call(&[&WALL, &PAD])]),
    Default(DefaultWord("track")),
    "what each coupon is: a single `track`, a `wall(layers)` one bead wide, or a `pad(tracks, offset)` of overlapped tracks",
);

/// `length = …`.
pub static LENGTH: Field = Field::new(
    "length",
    Quantity(Dim::LENGTH, Positive),
    Required("30 mm"),
    "each coupon's length, along x",
);

/// `spacing = …`.
pub static SPACING: Field = Field::new(
    "spacing",
    Quantity(Dim::LENGTH, Positive),
    Required("10 mm"),
    "the clear gap between neighbouring coupons, and between the coupons and the plate's edges",
);

/// `layer_height = …`.
pub static LAYER_HEIGHT: Field = Field::new(
    "layer_height",
    Quantity(Dim::LENGTH, Positive),
    Default(Described("the middle of the bead's `height` range")),
    "how far a wall's layers are apart, and the height the programs plan each coupon at",
);

/// `origin = [x, y]`.
pub static ORIGIN: Field = Field::new(
    "origin",
    Point,
    Default(Described("`[0 mm, 0 mm]`")),
    "the plate's corner with the smallest x and y, in the machine's part frame",
);

/// `plate = [x, y]`.
pub static PLATE: Field = Field::new(
    "plate",
    List(&Quantity(Dim::LENGTH, Positive), Len::Exactly(2)),
    Required("[150 mm, 100 mm]"),
    "the plate's size along x and y: the coupons must fit on it",
);

/// `order = …`.
pub static ORDER: Field = Field::new(
    "order",
    Word(&["random", "sorted"]),
    Default(DefaultWord("random")),
    "the order the coupons are laid and placed in: `random`, shuffled by `seed` (a drifting plate temperature or powder then is no speed effect), or `sorted` by powder, power and speed",
);

/// `seed = …`.
pub static SEED: Field = Field::new(
    "seed",
    Count(0, 1_000_000),
    Default(DefaultCount(1)),
    "the shuffle of `order = random`: the same seed lays the same order, on every machine and lmdc version",
);

/// `calibration { … }`.
pub static CALIBRATION: Block = Block::new(
    "calibration",
    "calibration { … }",
    "coupons to measure a bead on (`lmdc calibrate`; docs/calibration.md)",
    &[
        &BEAD,
        &SPEEDS,
        &COUNT,
        &POWERS,
        &POWDERS,
        &REPEAT,
        &ORDER,
        &SEED,
        &COUPON,
        &LENGTH,
        &SPACING,
        &LAYER_HEIGHT,
        &ORIGIN,
        &PLATE,
    ],
);

/// The arguments of the coupon kinds.
pub mod coupon {
    use super::*;

    /// `wall(layers = …)`.
    pub static LAYERS: Field = Field::new(
        "layers",
        Count(2, 100),
        Required("3"),
        "the wall's layers, each `layer_height` above the one below",
    );
    /// `pad(tracks = …)`.
    pub static TRACKS: Field = Field::new(
        "tracks",
        Count(2, 100),
        Required("5"),
        "the pad's tracks, side by side",
    );
    /// `pad(offset = …)`.
    pub static OFFSET: Field = Field::new(
        "offset",
        Quantity(Dim::LENGTH, Positive),
        Required("1.6 mm"),
        "how far apart the pad's tracks are, centre to centre",
    );
}

/// `wall(layers)`.
pub static WALL: Block = Block::new(
    "wall",
    "wall(layers)",
    "a short wall one bead wide: the same track laid `layers` times, one on the other",
    &[&coupon::LAYERS],
)
.positional(1);

/// `pad(tracks, offset)`.
pub static PAD: Block = Block::new(
    "pad",
    "pad(tracks, offset)",
    "a pad of `tracks` overlapped tracks `offset` apart, in one layer",
    &[&coupon::TRACKS, &coupon::OFFSET],
);
