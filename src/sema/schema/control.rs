//! `control height { … }`: the PI loop on the layer height of each segment
//! of a segmented ring, and the plant it is simulated against.

use super::Bound::{Any, Positive};
use super::DefaultValue::{Described, Quantity as DefaultQuantity, Word as DefaultWord};
use super::Kind::{Call, Deferred, List, Quantity, Range, Word};
use super::Need::{Default, Optional, Required};
use super::{Block, Field, Len};
use crate::control::SpeedPerLength;
use crate::units::Dim;

/// `kp = …`.
pub static KP: Field = Field::new(
    "kp",
    Deferred(&Quantity(SpeedPerLength::DIM, Any)),
    Required("-3 mm/s/mm"),
    "the proportional gain, a speed per mm of height error; its units must name a length",
);

/// `ki = …`.
pub static KI: Field = Field::new(
    "ki",
    Deferred(&Quantity(SpeedPerLength::DIM, Any)),
    Required("-0.35 mm/s/mm"),
    "the integral gain, on the segment's total height error",
);

/// `clamp = …`.
pub static CLAMP: Field = Field::new(
    "clamp",
    Range(Dim::SPEED),
    Required("1.9 mm/s .. 20 mm/s"),
    "the speeds the loop may command",
);

/// `target = …`.
pub static TARGET: Field = Field::new(
    "target",
    Quantity(Dim::LENGTH, Positive),
    Default(Described("the slicing's `layer_height`")),
    "the height per layer the loop holds",
);

/// `run = …`.
pub static RUN: Field = Field::new(
    "run",
    Word(&["on_machine", "schedule"]),
    Default(DefaultWord("on_machine")),
    "`on_machine`: the programs measure and correct; `schedule`: open loop, speeds chosen offline",
);

/// `plant = …`.
pub static PLANT: Field = Field::new(
    "plant",
    Call(&[&INVERSE_SPEED]),
    Default(Described("no drift")),
    "what `lmdc simulate` and a schedule run the loop against",
);

/// `control height { … }`.
pub static CONTROL: Block = Block::new(
    "control",
    "control height { … }",
    "a PI loop on each segment's layer height, layer to layer",
    &[&KP, &KI, &CLAMP, &TARGET, &RUN, &PLANT],
);

/// The arguments of `inverse_speed(…)`.
pub mod plant {
    use super::*;

    /// `drift = …`.
    pub static DRIFT: Field = Field::new(
        "drift",
        Quantity(Dim::NONE, Any),
        Default(DefaultQuantity(0.0)),
        "how much more each layer lays than the one before, a fraction",
    );
    /// `factors = […]`.
    pub static FACTORS: Field = Field::new(
        "factors",
        List(&Quantity(Dim::NONE, Positive), Len::PerSegment),
        Optional,
        "each segment's deposition relative to the calibration",
    );
}

/// `inverse_speed(drift, factors)`: a segment lays `h = g·(1 + drift·i)/v`.
pub static INVERSE_SPEED: Block = Block::new(
    "inverse_speed",
    "inverse_speed(drift, factors)",
    "a plant whose segment lays `h = g·(1 + drift·i)/v`, calibrated to the table",
    &[&plant::DRIFT, &plant::FACTORS],
);
