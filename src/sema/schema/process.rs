//! `process { … }`: the process values, a ring's process block (only
//! `powder` and `power_range`: its table gives the rest per segment), and
//! `ramp(…)`.

use super::Bound::{Any, Positive, ZeroUpTo};
use super::DefaultValue::{Described, Quantity as DefaultQuantity};
use super::Kind::{Call, Count, Either, Quantity, Range};
use super::Need::{Default, Optional, Required};
use super::{Block, Field};
use crate::units::Dim;

/// Longest interlayer time lmdc plans, s (an hour).
pub const MAX_DWELL_S: f64 = 3600.0;

/// `powder = …`.
pub static POWDER: Field = Field::new(
    "powder",
    Quantity(Dim::MASS_FLOW, Positive),
    Required("45.9 g/min"),
    "the powder feed",
);

/// `defocus = …`.
pub static DEFOCUS: Field = Field::new(
    "defocus",
    Quantity(Dim::LENGTH, Any),
    Default(DefaultQuantity(0.0)),
    "the focal plane's distance from the working plane (negative: below); the program's TCP is the focus",
);

/// `power = …`.
pub static POWER: Field = Field::new(
    "power",
    Either(&[Quantity(Dim::POWER, Positive), Call(&[&RAMP])]),
    Required("2100 W"),
    "the laser power, or a ramp over the first layers",
);

/// `power_range = …`.
pub static POWER_RANGE: Field = Field::new(
    "power_range",
    Range(Dim::POWER),
    Default(Described("the powers scheduled (a ring: its table's)")),
    "the laser's range, which every power is checked against",
);

/// `speed = …`.
pub static SPEED: Field = Field::new(
    "speed",
    Quantity(Dim::SPEED, Positive),
    Optional,
    "planar layers: the scan speed (else a `measured` bead's); other layers take theirs from the bead",
);

/// `min_layer_time = …`.
pub static MIN_LAYER_TIME: Field = Field::new(
    "min_layer_time",
    Quantity(Dim::TIME, ZeroUpTo(MAX_DWELL_S)),
    Default(DefaultQuantity(0.0)),
    "the least time from a layer's start to the next's: a quicker layer waits",
);

/// `dwell = …`.
pub static DWELL: Field = Field::new(
    "dwell",
    Quantity(Dim::TIME, ZeroUpTo(MAX_DWELL_S)),
    Default(DefaultQuantity(0.0)),
    "a pause after every layer but the last",
);

/// `process { … }`.
pub static PROCESS: Block = Block::new(
    "process",
    "process { … }",
    "the process values",
    &[
        &POWDER,
        &DEFOCUS,
        &POWER,
        &POWER_RANGE,
        &SPEED,
        &MIN_LAYER_TIME,
        &DWELL,
    ],
);

/// A ring's `process { … }`: its table gives the power, defocus and speed
/// of each segment, and its layers run on without a stop (why each is
/// refused: `diag::message::bead::not_for_a_ring`).
pub static RING_PROCESS: Block =
    Block::new("ring_process", "process { … }",
 "a ring's process block: its table gives the power, defocus and speed of each segment, and its layers run on without a stop", &[&POWDER, &POWER_RANGE])
        .refusing(&[&POWER, &DEFOCUS, &SPEED, &MIN_LAYER_TIME, &DWELL])
        .with_examples(&[(&POWDER, "6 g/min")]);

/// The arguments of `ramp(…)`.
pub mod ramp {
    use super::*;

    /// `from = …`.
    pub static FROM: Field = Field::new(
        "from",
        Quantity(Dim::POWER, Positive),
        Required("4000 W"),
        "the power on the first layer",
    );
    /// `to = …`.
    pub static TO: Field = Field::new(
        "to",
        Quantity(Dim::POWER, Positive),
        Required("2100 W"),
        "the power it reaches, and then holds",
    );
    /// `layers = …`.
    pub static LAYERS: Field = Field::new(
        "layers",
        Count(1, 1_000_000),
        Required("20"),
        "how many layers later it reaches `to`",
    );
}

/// `ramp(from, to, layers)`: a power going linearly from one to the other.
pub static RAMP: Block = Block::new(
    "ramp",
    "ramp(from, to, layers)",
    "a power going linearly from one value to another over the first layers",
    &[&ramp::FROM, &ramp::TO, &ramp::LAYERS],
);
