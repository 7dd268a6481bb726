//! `process { … }`: the process values, a ring's process block (only
//! `powder` and `power_range`: its table gives the rest per segment), and
//! `ramp(…)`.

use super::Bound::{Any, Positive, PositiveUpTo, Within, ZeroUpTo};
use super::DefaultValue::{Described, Quantity as DefaultQuantity, Word as DefaultWord};
use super::Kind::{Block as Nested, Call, Count, Either, List, Quantity, Range, Word};
use super::Need::{Default, Optional, Required, RequiredUnless};
use super::{Block, Field, Len};
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
        &THERMAL_BLOCK,
    ],
);

/// `thermal { … }`.
pub static THERMAL_BLOCK: Field = Field::new(
    "thermal",
    Nested(&THERMAL),
    Optional,
    "the alloy and the plate, from which lmdc predicts each layer's interpass temperature, and the limit it keeps it within (docs/thermal.md); none: no prediction",
);

/// `thermal { material, absorptivity, heat_transfer, plate, preheat,
/// max_interpass, cooling }`.
pub static THERMAL: Block = Block::new(
    "thermal",
    "thermal { material = ss316l  max_interpass = 200 degC }",
    "the thermal model's data and the interpass temperature the plan keeps (docs/thermal.md)",
    &[
        &thermal::MATERIAL,
        &thermal::CONDUCTIVITY,
        &thermal::DENSITY,
        &thermal::HEAT_CAPACITY,
        &thermal::EMISSIVITY,
        &thermal::ABSORPTIVITY,
        &thermal::HEAT_TRANSFER,
        &thermal::PLATE,
        &thermal::PREHEAT,
        &thermal::MAX_INTERPASS,
        &thermal::COOLING,
    ],
);

/// The fields of `thermal { … }`.
pub mod thermal {
    use super::*;

    /// The hottest preheat or limit lmdc takes, °C: above any alloy's
    /// interpass range, short of a typo's.
    pub const MAX_TEMPERATURE: f64 = 1000.0;

    /// `material = ss316l`.
    pub static MATERIAL: Field = Field::new(
        "material",
        Word(crate::thermal::alloy::KEYS),
        RequiredUnless(
            "ss316l",
            "`conductivity`, `density`, `heat_capacity`, `emissivity` and `absorptivity` are all given",
        ),
        "the alloy, whose conductivity, density, heat capacity, emissivity and absorptivity the model takes (docs/thermal.md, *Alloys*); each field of these that is given overrides the alloy's",
    );
    /// `conductivity = 45 W/m/degC`.
    pub static CONDUCTIVITY: Field = Field::new(
        "conductivity",
        Quantity(Dim::CONDUCTIVITY, Positive),
        Default(Described("the alloy's")),
        "the thermal conductivity of the part and the plate (the mean over 20–800 °C)",
    );
    /// `density = 7850 kg/m^3`.
    pub static DENSITY: Field = Field::new(
        "density",
        Quantity(Dim::DENSITY, Positive),
        Default(Described("the alloy's")),
        "the density of the part and the plate",
    );
    /// `heat_capacity = 600 J/kg/degC`.
    pub static HEAT_CAPACITY: Field = Field::new(
        "heat_capacity",
        Quantity(Dim::HEAT_CAPACITY, Positive),
        Default(Described("the alloy's")),
        "the specific heat capacity of the part and the plate (the mean over 20–800 °C)",
    );
    /// `emissivity = 0.5`.
    pub static EMISSIVITY: Field = Field::new(
        "emissivity",
        Quantity(Dim::NONE, Within(1.0)),
        Default(Described("the alloy's")),
        "the share of a black body's radiation the part's surface gives off (0.4–0.6 oxidised)",
    );
    /// `absorptivity = 0.35`.
    pub static ABSORPTIVITY: Field = Field::new(
        "absorptivity",
        Quantity(Dim::NONE, Within(1.0)),
        Default(Described("the alloy's")),
        "the share of the laser's power the part takes up: the model's least certain number, which a calibration build should fit",
    );
    /// `heat_transfer = 20 W/m^2/degC`.
    pub static HEAT_TRANSFER: Field = Field::new(
        "heat_transfer",
        Quantity(Dim::HEAT_TRANSFER, Positive),
        Default(Described("20 W/m^2/degC")),
        "the heat transfer coefficient from the part to the cell's gas (convection; radiation is added from the alloy's emissivity)",
    );
    /// `plate = [200 mm, 200 mm, 20 mm]`.
    pub static PLATE: Field = Field::new(
        "plate",
        List(
            &Quantity(Dim::LENGTH, PositiveUpTo(super::super::collision::MAX_SIZE_MM)),
            Len::Exactly(3),
        ),
        Default(Described("[200 mm, 200 mm, 20 mm]")),
        "the plate's length, width and thickness, the part standing in its middle: the heat sink under the first layers",
    );
    /// `preheat = 25 degC`.
    pub static PREHEAT: Field = Field::new(
        "preheat",
        Quantity(Dim::TEMPERATURE, Within(MAX_TEMPERATURE)),
        Default(Described("25 degC, the cell's")),
        "the plate's temperature when the build starts (the cell's gas and walls are at 25 °C)",
    );
    /// `max_interpass = 200 degC`.
    pub static MAX_INTERPASS: Field = Field::new(
        "max_interpass",
        Quantity(Dim::TEMPERATURE, Within(MAX_TEMPERATURE)),
        Optional,
        "the hottest a layer may be where and when the next starts on it: lmdc plans the cooling that keeps every layer within it, or refuses the plan; none: predicted, not limited",
    );
    /// The levers `cooling` names.
    pub const LEVERS: &[&str] = &["dwell", "power", "order"];
    /// `cooling = dwell`, `cooling = [order, dwell]`.
    pub static COOLING: Field = Field::new(
        "cooling",
        Either(&[Word(LEVERS), List(&Word(LEVERS), Len::Any)]),
        Default(DefaultWord("dwell")),
        "how lmdc may keep `max_interpass`, one lever or a list of them: `order`, each layer's islands laid in the order that starts each the coolest; `power`, the least power reduction within the bead's measured powers and the laser's range, the speeds and so the layers unchanged; `dwell`, the least wait before each layer that does. With several, the order first and the power next (neither costs time), then the least wait for what is still too hot",
    );
}

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
