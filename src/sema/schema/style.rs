//! `style NAME { … when { … } }` and `inheritance { … }`: process styles.

use super::Bound::{Positive, Within};
use super::DefaultValue::{Described, Quantity as DefaultQuantity};
use super::Kind::{Blocks, Count, Quantity, Range, Text, Word};
use super::Need::{Default, Optional, Required};
use super::{Block, Field};
use crate::units::Dim;

/// Corners that turn by at least this much are sharp unless `corner_angle`
/// says, deg.
pub const DEFAULT_CORNER_DEG: f64 = 45.0;

/// The paths a rule may pick.
pub const PATHS: &[&str] = &["outer_contour", "inner_contour", "contour", "infill"];

/// The fields of `style NAME { … }`: its values and its rules.
pub mod values {
    use super::*;

    /// `id = …`.
    pub static ID: Field = Field::new(
        "id",
        Count(1, u16::MAX as usize),
        Default(Described(
            "the lowest no style claims, in declaration order",
        )),
        "the id the points carry; 0 is the process block",
    );
    /// `power = …`.
    pub static POWER: Field = Field::new(
        "power",
        Quantity(Dim::POWER, Positive),
        Optional,
        "the laser power of its tracks; left out: the process block's",
    );
    /// `speed = …`.
    pub static SPEED: Field = Field::new(
        "speed",
        Quantity(Dim::SPEED, Positive),
        Optional,
        "the scan speed of its tracks; left out: the process block's",
    );
    /// `powder = …`.
    pub static POWDER: Field = Field::new(
        "powder",
        Quantity(Dim::MASS_FLOW, Positive),
        Optional,
        "the powder feed of its tracks, programmed through the feeder's rate output (refused on a machine without one)",
    );
    /// `colour = …`.
    pub static COLOUR: Field = Field::new(
        "colour",
        Text,
        Default(Described("a palette colour")),
        "`#rrggbb`, for viewers of the IR",
    );
    /// `when { … }`.
    pub static WHEN: Field = Field::new(
        "when",
        Blocks(&super::WHEN),
        Optional,
        "a rule picking its tracks; several: any of them",
    );
}

/// `style NAME { … }`: process values for the tracks its rules pick.
pub static STYLE: Block = Block::new(
    "style",
    "style NAME { … }",
    "process values for the tracks its rules pick",
    &[
        &values::ID,
        &values::POWER,
        &values::SPEED,
        &values::POWDER,
        &values::COLOUR,
        &values::WHEN,
    ],
);

/// The conditions of `when { … }`.
pub mod when {
    use super::*;

    /// `paths = …`.
    pub static PATHS: Field = Field::new(
        "paths",
        Word(super::PATHS),
        Optional,
        "picks the tracks of these passes",
    );
    /// `shorter_than = …`.
    pub static SHORTER_THAN: Field = Field::new(
        "shorter_than",
        Quantity(Dim::LENGTH, Positive),
        Optional,
        "picks a track shorter than this",
    );
    /// `longer_than = …`.
    pub static LONGER_THAN: Field = Field::new(
        "longer_than",
        Quantity(Dim::LENGTH, Positive),
        Optional,
        "picks a track at least this long",
    );
    /// `near_boundary = …`.
    pub static NEAR_BOUNDARY: Field = Field::new(
        "near_boundary",
        Quantity(Dim::LENGTH, Positive),
        Optional,
        "picks a track all of which lies within this of the layer's profile",
    );
    /// `near_corner = …`.
    pub static NEAR_CORNER: Field = Field::new(
        "near_corner",
        Quantity(Dim::LENGTH, Positive),
        Optional,
        "picks a track passing within this of a sharp corner of the profile",
    );
    /// `corner_angle = …`.
    pub static CORNER_ANGLE: Field = Field::new(
        "corner_angle",
        Quantity(Dim::ANGLE, Within(std::f64::consts::PI)),
        Default(DefaultQuantity(crate::sema::schema::deg(
            DEFAULT_CORNER_DEG,
        ))),
        "with `near_corner`: how far the profile turns at a sharp corner",
    );
    /// `layers = …`.
    pub static LAYERS: Field = Field::new(
        "layers",
        Range(Dim::NONE),
        Optional,
        "picks the tracks of layers a to b, counted from 1",
    );
}

/// `when { … }`: all its conditions must hold.
pub static WHEN: Block = Block::new(
    "when",
    "when { … }",
    "a style's rule: all its conditions must hold",
    &[
        &when::PATHS,
        &when::SHORTER_THAN,
        &when::LONGER_THAN,
        &when::NEAR_BOUNDARY,
        &when::NEAR_CORNER,
        &when::CORNER_ANGLE,
        &when::LAYERS,
    ],
);

/// `band = …`.
pub static BAND: Field = Field::new(
    "band",
    Quantity(Dim::LENGTH, Positive),
    Required("0.8 mm"),
    "the half-width of the band round a styled track",
);

/// `hit = …`.
pub static HIT: Field = Field::new(
    "hit",
    Quantity(Dim::NONE, Within(1.0)),
    Required("99 %"),
    "the share of a track's length that must lie in the band",
);

/// `inheritance { … }`: how a track no rule picks takes the style below it.
pub static INHERITANCE: Block = Block::new(
    "inheritance",
    "inheritance { … }",
    "how a track no rule picks takes the style of the layer below",
    &[&BAND, &HIT],
);
