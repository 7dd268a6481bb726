//! `bead NAME { width, height, speed, model }`: a bead model, and the three
//! models it may be (`linear(…)`, `mass_balance(…)`, `measured(…)`,
//! `power(…)`, `table(…)`).

use super::Bound::{Any, Negative, Positive, PositiveUpTo};
use super::DefaultValue::{Described, Word as DefaultWord};
use super::Kind::{Call, Either, List, Quantity, Range, Text, Word};
use super::Need::{Default, Required, RequiredUnless};
use super::{Block, Field, Len};
use crate::units::Dim;

/// `width = 6 mm`.
pub static WIDTH: Field = Field::new(
    "width",
    Quantity(Dim::LENGTH, Positive),
    Required("6 mm"),
    "the bead's width",
);

/// `height = lo .. hi`.
pub static HEIGHT: Field = Field::new(
    "height",
    Range(Dim::LENGTH),
    Default(Described("the model's heights over `speed`")),
    "the layer heights allowed, narrowing the model's",
);

/// `speed = lo .. hi`.
pub static SPEED: Field = Field::new(
    "speed",
    Range(Dim::SPEED),
    RequiredUnless(
        "7 mm/s .. 10 mm/s",
        "the model is `measured(…)`, `table(…)` or `fit(…)`, whose speeds are the ones measured",
    ),
    "the scan speeds the model is valid for (within the speeds measured, unless `extrapolate = allow`)",
);

/// `model = …`.
pub static MODEL: Field = Field::new(
    "model",
    Call(&[&LINEAR, &MASS_BALANCE, &MEASURED, &POWER, &TABLE, &FIT]),
    Required("mass_balance(feed = 45.9 g/min, efficiency = 0.3, density = 7.9 g/cm^3)"),
    "how the bead's height follows the scan speed",
);

/// `measured_as = …`.
pub static MEASURED_AS: Field = Field::new(
    "measured_as",
    Either(&[Word(&["track", "wall"]), Call(&[&LAYER])]),
    Default(DefaultWord("track")),
    "what the model's heights are: a single track's (`track`), the rise per layer of a wall one bead wide (`wall`) or of filled layers (`layer(offset)`)",
);

/// `tilt = …`.
pub static TILT: Field = Field::new(
    "tilt",
    Range(Dim::ANGLE),
    Default(Described("`0 deg .. 0 deg`: measured with the nozzle vertical")),
    "the nozzle's tilts from vertical the model was measured at; a deposit tilted more than 5° beyond them is warned (`lmd::bead-tilt`)",
);

/// `powers = […]`.
pub static POWERS: Field = Field::new(
    "powers",
    List(&Quantity(Dim::POWER, Positive), Len::Any),
    Default(Described("a `fit(…)`'s coupons' powers; else not known")),
    "the laser powers the model was measured at: a process at another power is warned (`lmd::extrapolation`)",
);

/// `powders = […]`.
pub static POWDERS: Field = Field::new(
    "powders",
    List(&Quantity(Dim::MASS_FLOW, Positive), Len::Any),
    Default(Described("a `fit(…)`'s coupons' feeds; else not known")),
    "the powder feeds the model was measured at: a process at another feed is warned (`lmd::extrapolation`)",
);

/// `extrapolate = …`.
pub static EXTRAPOLATE: Field = Field::new(
    "extrapolate",
    Word(&["refuse", "allow"]),
    Default(DefaultWord("refuse")),
    "whether `speed` may reach beyond the speeds a `table(…)` or `fit(…)` measured (`allow`: a warning says how far; the model is extended)",
);

/// `bead NAME { … }`.
pub static BEAD: Block = Block::new(
    "bead",
    "bead NAME { … }",
    "a bead model: how high a track of it is at each scan speed",
    &[
        &WIDTH,
        &HEIGHT,
        &SPEED,
        &MODEL,
        &MEASURED_AS,
        &TILT,
        &POWERS,
        &POWDERS,
        &EXTRAPOLATE,
    ],
);

/// `layer(offset)` of `measured_as`.
pub static LAYER: Block = Block::new(
    "layer",
    "layer(offset)",
    "the rise per layer of filled layers of tracks `offset` apart",
    &[&model::OFFSET],
);

/// The arguments of the models.
pub mod model {
    use super::*;

    /// `linear(slope = …)`.
    pub static SLOPE: Field = Field::new(
        "slope",
        Quantity(Dim::TIME, Negative),
        Required("-0.135 mm / (1 mm/s)"),
        "the height's change per speed, a length per speed (a time)",
    );
    /// `linear(intercept = …)`.
    pub static INTERCEPT: Field = Field::new(
        "intercept",
        Quantity(Dim::LENGTH, Any),
        Required("1.82 mm"),
        "the height at zero speed",
    );
    /// `mass_balance(feed = …)`.
    pub static FEED: Field = Field::new(
        "feed",
        Quantity(Dim::MASS_FLOW, Positive),
        Required("45.9 g/min"),
        "the powder feed the model was fitted at",
    );
    /// `mass_balance(efficiency = …)`.
    pub static EFFICIENCY: Field = Field::new(
        "efficiency",
        Quantity(Dim::NONE, PositiveUpTo(1.0)),
        Required("0.3"),
        "the share of the powder the melt pool catches",
    );
    /// `mass_balance(density = …)`.
    pub static DENSITY: Field = Field::new(
        "density",
        Quantity(Dim::DENSITY, Positive),
        Required("7.9 g/cm^3"),
        "the metal's density",
    );
    /// `measured(height = …)`.
    pub static HEIGHT: Field = Field::new(
        "height",
        Quantity(Dim::LENGTH, Positive),
        Required("0.7 mm"),
        "the single track's measured height",
    );
    /// `layer(offset = …)` of `measured_as`.
    pub static OFFSET: Field = Field::new(
        "offset",
        Quantity(Dim::LENGTH, Positive),
        Required("1.6 mm"),
        "the tracks' offset in the layers measured",
    );
    /// `power(height = …)`.
    pub static REF_HEIGHT: Field = Field::new(
        "height",
        Quantity(Dim::LENGTH, Positive),
        Required("1.0 mm"),
        "the height at the reference speed",
    );
    /// `power(speed = …)`.
    pub static REF_SPEED: Field = Field::new(
        "speed",
        Quantity(Dim::SPEED, Positive),
        Required("6 mm/s"),
        "the reference speed",
    );
    /// `power(exponent = …)`.
    pub static EXPONENT: Field = Field::new(
        "exponent",
        Quantity(Dim::NONE, Negative),
        Required("-0.5"),
        "how the height scales with the speed: `H = height·(v/speed)^exponent`, < 0",
    );
    /// `table(speed = […])`.
    pub static SPEEDS: Field = Field::new(
        "speed",
        List(&Quantity(Dim::SPEED, Positive), Len::Any),
        Required("[4 mm/s, 6 mm/s, 8.7 mm/s]"),
        "the speeds measured, increasing",
    );
    /// `table(height = […])`.
    pub static HEIGHTS: Field = Field::new(
        "height",
        List(&Quantity(Dim::LENGTH, Positive), Len::Any),
        Required("[1.28 mm, 1.01 mm, 0.65 mm]"),
        "the heights measured at those speeds, falling",
    );
    /// `table(width = […])`.
    pub static WIDTHS: Field = Field::new(
        "width",
        List(&Quantity(Dim::LENGTH, Positive), Len::Any),
        Default(Described("the bead's `width` at every speed")),
        "the widths measured at those speeds: the bead's cross-section at a speed has that speed's width",
    );
    /// `fit(model = …)`.
    pub static FIT_MODEL: Field = Field::new(
        "model",
        Word(&["linear", "power", "mass_balance", "table"]),
        Required("linear"),
        "the model fitted to the data",
    );
    /// `fit(data = …)`.
    pub static DATA: Field = Field::new(
        "data",
        Text,
        Required("\"coupons.csv\""),
        "the measurement sheet, a path relative to the .lmd file (docs/calibration.md)",
    );
    /// `fit(density = …)`.
    pub static FIT_DENSITY: Field = Field::new(
        "density",
        Quantity(Dim::DENSITY, Positive),
        super::super::Need::Optional,
        "the metal's density (a `mass_balance` fit)",
    );
    /// `fit(feed = …)`.
    pub static FIT_FEED: Field = Field::new(
        "feed",
        Quantity(Dim::MASS_FLOW, Positive),
        super::super::Need::Optional,
        "the powder feed of coupons whose row has none (a `mass_balance` fit)",
    );
    /// `fit(power = …)`.
    pub static FIT_POWER: Field = Field::new(
        "power",
        Quantity(Dim::POWER, Positive),
        super::super::Need::Optional,
        "fit only the coupons laid at this laser power (a sheet of several powers)",
    );
    /// `fit(powder = …)`.
    pub static FIT_POWDER: Field = Field::new(
        "powder",
        Quantity(Dim::MASS_FLOW, Positive),
        super::super::Need::Optional,
        "fit only the coupons laid at this powder feed (a sheet of several feeds)",
    );
    /// `measured(speed = …)`.
    pub static SPEED: Field = Field::new(
        "speed",
        Quantity(Dim::SPEED, Positive),
        Required("6 mm/s"),
        "the speed it was laid at",
    );
}

/// `linear(slope, intercept)`: the linear bead map `H = slope·v + intercept`.
pub static LINEAR: Block = Block::new(
    "linear",
    "linear(slope, intercept)",
    "a bead map fitted as a line, `H = slope·v + intercept`",
    &[&model::SLOPE, &model::INTERCEPT],
);

/// `mass_balance(feed, efficiency, density)`: the metal caught per length.
pub static MASS_BALANCE: Block = Block::new(
    "mass_balance",
    "mass_balance(feed, efficiency, density)",
    "the metal the melt pool catches per length, as a circular segment of the bead's width",
    &[&model::FEED, &model::EFFICIENCY, &model::DENSITY],
);

/// `power(height, speed, exponent)`: a power law through a reference point.
pub static POWER: Block = Block::new(
    "power",
    "power(height, speed, exponent)",
    "a power law through a reference point, `H = height·(v/speed)^exponent` (what `lmdc fit` fits in log space)",
    &[&model::REF_HEIGHT, &model::REF_SPEED, &model::EXPONENT],
);

/// `table(speed, height, width)`: heights measured at several speeds.
pub static TABLE: Block = Block::new(
    "bead_table",
    "table(speed, height, width)",
    "heights (and widths) measured at several speeds, joined by straight lines; the heights must fall as the speed rises",
    &[&model::SPEEDS, &model::HEIGHTS, &model::WIDTHS],
);

/// `fit(model, data, density, feed, power, powder)`: a model fitted at
/// compile time to a measurement sheet.
pub static FIT: Block = Block::new(
    "fit",
    "fit(model, data, density, feed, power, powder)",
    "a model fitted when the file is compiled to the coupons of a measurement sheet (`lmdc fit` prints the same fit)",
    &[
        &model::FIT_MODEL,
        &model::DATA,
        &model::FIT_DENSITY,
        &model::FIT_FEED,
        &model::FIT_POWER,
        &model::FIT_POWDER,
    ],
)
.positional(2);

/// `measured(height, speed)`: one track measured at one process point.
pub static MEASURED: Block = Block::new(
    "measured",
    "measured(height, speed)",
    "one track measured at one process point",
    &[&model::HEIGHT, &model::SPEED],
);
