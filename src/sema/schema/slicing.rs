//! `slicing STRATEGY { … }`: the four strategies' fields, `raster(…)` of a
//! planar infill, the seam calls, and `segments { … }` of variable slicing.

use super::Bound::{Any, NonNegative, Positive, PositiveUpTo};
use super::DefaultValue::{
    Count as DefaultCount, Described, Quantity as DefaultQuantity, Word as DefaultWord,
};
use super::Kind::{self, Block as Nested, Call, Count, Either, Quantity, Word};
use super::Need::{Default, Optional, Required};
use super::{Block, Field};
use crate::sema::model::{MAX_LAYERS, MAX_POINTS};
use crate::units::Dim;

/// The strategies, in the order messages list them.
pub static STRATEGIES: &[&Block] = &[&NORMAL, &PLANAR, &VARIABLE, &CONTINUOUS];

/// Most contour passes a layer may have.
pub const MAX_CONTOURS: usize = 1000;

/// The step of a continuous ring when none is written, deg.
pub const DEFAULT_STEP_DEG: f64 = 1.0;

/// The largest step, deg: a 10° chord of a ring sags 0.4 % of its radius
/// inside the circle (0.15 mm on 40 mm), about what a bead's edge forgives.
pub const MAX_STEP_DEG: f64 = 10.0;

/// The golden angle (deg): a seam turned by it every layer never comes back
/// to the same direction, and any run of layers spreads its seams evenly.
pub const GOLDEN_ANGLE_DEG: f64 = 137.507_764_050_037_85;

/// A layer count, or `auto`.
const LAYERS: Kind = Either(&[Word(&["auto"]), Count(1, MAX_LAYERS)]);

/// `rise_tolerance = …`, of every strategy with a bead model.
pub static RISE_TOLERANCE: Field = Field::new(
    "rise_tolerance",
    Quantity(Dim::NONE, PositiveUpTo(1.0)),
    Default(DefaultQuantity(crate::deposit::RISE_TOLERANCE)),
    "how far a run's rise by the bead model may be from the layer height it plans, a share of it (`lmd::deposit`)",
);

/// `max_drift = …`, of every strategy with a bead model.
pub static MAX_DRIFT: Field = Field::new(
    "max_drift",
    Quantity(Dim::LENGTH, Positive),
    Default(DefaultQuantity(crate::deposit::MAX_DRIFT)),
    "how far the layers' mean errors may add up over the build (`lmd::deposit`)",
);

/// The fields of `slicing normal { … }`.
pub mod normal {
    use super::*;

    /// `layers = …`.
    pub static LAYERS: Field = Field::new(
        "layers",
        super::LAYERS,
        Default(DefaultWord("auto")),
        "how many layers; `auto`: the fewest whose thickest point the bead can lay",
    );
    /// `points = …`.
    pub static POINTS: Field = Field::new(
        "points",
        Count(8, MAX_POINTS),
        Default(DefaultCount(360)),
        "points per layer, at equal angles from the seam, plus the corners; or `chord_error`",
    );
    /// `chord_error = …`.
    pub static CHORD_ERROR: Field = Field::new(
        "chord_error",
        Quantity(Dim::LENGTH, Positive),
        Optional,
        "instead of `points`: no chord further than this from the section, every corner a point",
    );
    /// `seam = …`.
    pub static SEAM: Field = Field::new(
        "seam",
        Either(&[
            Word(&["random"]),
            Quantity(Dim::ANGLE, Any),
            Call(&[&ROTATING, &RANDOM, &STAGGERED]),
        ]),
        Default(DefaultQuantity(crate::sema::schema::deg(90.0))),
        "where each layer starts and stops, an angle in the section frame, layer by layer; `staggered(shift)`: `shift` along its loop past the layer below's start",
    );
    /// `nozzle = …`.
    pub static NOZZLE: Field = Field::new(
        "nozzle",
        Word(&["spine", "wall"]),
        Default(DefaultWord("spine")),
        "the build direction: along the spine, or `wall`: tilted with the wall's lean, in the plane of its normal (5-axis or robot)",
    );
    /// `layer_change = …`.
    pub static LAYER_CHANGE: Field = Field::new(
        "layer_change",
        Either(&[Word(&["lift", "spiral"]), Call(&[&SPIRAL])]),
        Default(DefaultWord("lift")),
        "how a layer goes on to the next: `lift` (laser off, up, laser on at the next start), or `spiral`: the loop's end climbs to the next layer with the laser on, and the next goes on without a stop",
    );
    /// `spiral(length = …)`.
    pub static LENGTH: Field = Field::new(
        "length",
        Quantity(Dim::LENGTH, Positive),
        Default(Described("the whole loop: a helix of constant pitch")),
        "how much of the end of each layer's loop climbs to the next layer",
    );
    /// `max_overhang = …`.
    pub static MAX_OVERHANG: Field = Field::new(
        "max_overhang",
        Quantity(Dim::ANGLE, Positive),
        Default(Described("a warning past 45° or a step of half the bead; `lmd::stacking` refuses ¾ bead")),
        "the most a wall's layer (or a planar layer's contour) may lean out over the one below, from the nozzle's axis; past it, an error (`lmd::overhang`)",
    );
}

/// `slicing normal { … }`: layers normal to a loft's spine.
pub static NORMAL: Block = Block::new(
    "normal",
    "slicing normal { … }",
    "layers normal to a loft's spine",
    &[
        &normal::LAYERS,
        &normal::POINTS,
        &normal::CHORD_ERROR,
        &normal::SEAM,
        &normal::NOZZLE,
        &normal::LAYER_CHANGE,
        &normal::MAX_OVERHANG,
        &RISE_TOLERANCE,
        &MAX_DRIFT,
    ],
);

/// The fields of `slicing planar { … }`.
pub mod planar {
    use super::*;

    /// `layer_height = …`.
    pub static LAYER_HEIGHT: Field = Field::new(
        "layer_height",
        Either(&[Word(&["auto"]), Quantity(Dim::LENGTH, Positive)]),
        Default(DefaultWord("auto")),
        "how far each layer rises; `auto`: what the tracks lay",
    );
    /// `layers = …`.
    pub static LAYERS: Field = Field::new(
        "layers",
        super::LAYERS,
        Optional,
        "how many layers, or `height` in the extrusion",
    );
    /// `contours = …`.
    pub static CONTOURS: Field = Field::new(
        "contours",
        Count(0, MAX_CONTOURS),
        Default(Described("1 without infill, else 0")),
        "contour passes round each layer",
    );
    /// `offset = …`.
    pub static OFFSET: Field = Field::new(
        "offset",
        Either(&[Word(&["auto"]), Quantity(Dim::LENGTH, Positive)]),
        Default(DefaultWord("auto")),
        "the distance between neighbouring tracks; `auto`: A/h, a flat top",
    );
    /// `infill = …`.
    pub static INFILL: Field = Field::new(
        "infill",
        Either(&[Word(&["none"]), Call(&[&RASTER])]),
        Default(DefaultWord("none")),
        "parallel tracks inside the contours",
    );
    /// `chord_error = …`.
    pub static CHORD_ERROR: Field = Field::new(
        "chord_error",
        Quantity(Dim::LENGTH, Positive),
        Default(DefaultQuantity(0.05)),
        "arcs are flattened within this",
    );
    /// `seam = …`.
    pub static SEAM: Field = Field::new(
        "seam",
        Either(&[
            Word(&["lowest", "sharpest_corner", "random"]),
            Quantity(Dim::ANGLE, Any),
            Call(&[&ROTATING, &RANDOM, &STAGGERED]),
        ]),
        Default(DefaultWord("lowest")),
        "where each contour loop starts and ends, layer by layer",
    );
}

/// `slicing planar { … }`: flat, filled layers.
pub static PLANAR: Block = Block::new(
    "planar",
    "slicing planar { … }",
    "flat layers of contours and a raster infill",
    &[
        &planar::LAYER_HEIGHT,
        &planar::LAYERS,
        &planar::CONTOURS,
        &planar::OFFSET,
        &planar::INFILL,
        &planar::CHORD_ERROR,
        &planar::SEAM,
        &normal::LAYER_CHANGE,
        &normal::MAX_OVERHANG,
        &RISE_TOLERANCE,
        &MAX_DRIFT,
    ],
);

/// The arguments of `raster(…)` and of the seam calls.
pub mod raster {
    use super::*;

    /// `angle = …`.
    pub static ANGLE: Field = Field::new(
        "angle",
        Quantity(Dim::ANGLE, Any),
        Default(DefaultQuantity(0.0)),
        "the tracks' direction, from +x counter-clockwise",
    );
    /// `rotate = …`.
    pub static ROTATE: Field = Field::new(
        "rotate",
        Quantity(Dim::ANGLE, Any),
        Default(DefaultQuantity(0.0)),
        "how far the direction turns every layer",
    );
    /// `pattern = …`.
    pub static PATTERN: Field = Field::new(
        "pattern",
        Word(&["serpentine", "one_way"]),
        Default(DefaultWord("serpentine")),
        "`serpentine` alternates the tracks' directions, `one_way` keeps them",
    );
    /// `extend = …`.
    pub static EXTEND: Field = Field::new(
        "extend",
        Either(&[Word(&["auto"]), Quantity(Dim::LENGTH, NonNegative)]),
        Default(DefaultWord("auto")),
        "how far a track end may reach past its neighbour's; `auto`: the offset",
    );
    /// `link = …`.
    pub static LINK: Field = Field::new(
        "link",
        Word(&["none", "laser_on", "laser_off"]),
        Default(DefaultWord("none")),
        "whether neighbouring tracks are joined along the edge, and with the laser on or off",
    );
    /// `rotating(step = …)`.
    pub static STEP: Field = Field::new(
        "step",
        Quantity(Dim::ANGLE, Any),
        Default(DefaultQuantity(crate::sema::schema::deg(GOLDEN_ANGLE_DEG))),
        "how far the seam's direction turns every layer (the golden angle)",
    );
    /// `rotating(from = …)`.
    pub static FROM: Field = Field::new(
        "from",
        Quantity(Dim::ANGLE, Any),
        Default(DefaultQuantity(crate::sema::schema::deg(-90.0))),
        "the first layer's direction, from +x",
    );
    /// `staggered(shift = …)`.
    pub static SHIFT: Field = Field::new(
        "shift",
        Quantity(Dim::LENGTH, Positive),
        Required("10 mm"),
        "how far each layer's seam moves along the loop from the one below",
    );
    /// `random(seed = …)`.
    pub static SEED: Field = Field::new(
        "seed",
        Count(0, u32::MAX as usize),
        Default(DefaultCount(0)),
        "the seed the directions are drawn from: the same seed, the same seams",
    );
}

/// `raster(angle, rotate, pattern, extend, link)`: a planar infill.
pub static RASTER: Block = Block::new(
    "raster",
    "raster(angle, rotate, pattern, extend, link)",
    "parallel infill tracks",
    &[
        &raster::ANGLE,
        &raster::ROTATE,
        &raster::PATTERN,
        &raster::EXTEND,
        &raster::LINK,
    ],
);

/// `rotating(step, from)`: a seam that turns layer by layer.
pub static ROTATING: Block = Block::new(
    "rotating",
    "rotating(step, from)",
    "a seam that turns layer by layer",
    &[&raster::STEP, &raster::FROM],
)
.positional(1);

/// `spiral(length)`: a layer change that climbs with the laser on.
pub static SPIRAL: Block = Block::new(
    "spiral",
    "spiral(length)",
    "a layer change that climbs to the next layer over the end of each loop, the laser on",
    &[&normal::LENGTH],
)
.positional(1);

/// `staggered(shift)`: a seam that moves a fixed distance along the loop
/// every layer.
pub static STAGGERED: Block = Block::new(
    "staggered",
    "staggered(shift)",
    "a seam that moves a fixed distance along the loop every layer",
    &[&raster::SHIFT],
)
.positional(1);

/// `random(seed)`: a seam in a direction drawn for each layer.
pub static RANDOM: Block = Block::new(
    "random",
    "random(seed)",
    "a seam in a direction drawn for each layer from a seed",
    &[&raster::SEED],
)
.positional(1);

/// The fields of `slicing variable { … }` and its `segments { … }`.
pub mod variable {
    use super::*;

    /// `layers = …`.
    pub static LAYERS: Field = Field::new(
        "layers",
        super::LAYERS,
        Default(DefaultWord("auto")),
        "how many layers, each laying top/N at every point; `auto`: the fewest",
    );
    /// `scan = …`.
    pub static SCAN: Field = Field::new(
        "scan",
        Word(&["auto", "x", "y"]),
        Default(DefaultWord("auto")),
        "the tracks' direction; `auto`: along the axis the top rises more along",
    );
    /// `offset = …`.
    pub static OFFSET: Field = Field::new(
        "offset",
        Either(&[Word(&["balanced"]), Quantity(Dim::LENGTH, Positive)]),
        Default(DefaultWord("balanced")),
        "the distance between track centres; `balanced`: neighbouring beads meet level",
    );
    /// `level = …`.
    pub static LEVEL: Field = Field::new(
        "level",
        Either(&[Word(&["none", "auto"]), Quantity(Dim::LENGTH, Any)]),
        Default(DefaultWord("none")),
        "on a scan: fill the wear up to this height first (levelling passes, nothing where it is thinner than half the lowest bead), then regular layers to the top; `auto`: the scan's highest point under the tracks; `none`: every layer a fraction of the top less the scan",
    );
    /// `follow = …`.
    pub static FOLLOW: Field = Field::new(
        "follow",
        Word(&["vertical", "surface"]),
        Default(DefaultWord("vertical")),
        "on a scan, with a machine that tilts the nozzle: `surface` lays the layers on the scan with the nozzle along the scanned surface's normal (within the bead's measured `tilt` and the machine's tilt axis), back to vertical as the layers level it; `vertical`: the nozzle straight down",
    );
    /// `direction = …`.
    pub static DIRECTION: Field = Field::new(
        "direction",
        Word(&["vertical", "auto"]),
        Default(DefaultWord("vertical")),
        "on a scan, toward a target mesh or solid that overhangs it: `auto` plans the fill along the least tilted build direction (within the bead's measured `tilt` and the machines' tilt axes) along which every line over the footprint meets the target in one piece above the scan (the footprint, the finished face's outline, projected along it), the nozzle or the part tilted by it; `vertical`: the layers laid from above",
    );
    /// `finish_tolerance = …`.
    pub static FINISH_TOLERANCE: Field = Field::new(
        "finish_tolerance",
        Quantity(Dim::LENGTH, Positive),
        Optional,
        "the most the finished face the plan lays, as its bead model predicts it (`lmdc report`'s finish), may lie below or above the top anywhere; more is refused (`lmd::finish`); without it the finish is reported, not held",
    );
    /// `segments { … }`.
    pub static SEGMENTS: Field = Field::new(
        "segments",
        Nested(&super::SEGMENTS),
        Optional,
        "how a track is cut into stretches of constant speed",
    );
    /// `tolerance = …`.
    pub static TOLERANCE: Field = Field::new(
        "tolerance",
        Quantity(Dim::LENGTH, Positive),
        Default(DefaultQuantity(0.1)),
        "the finished top's mean height error along a track",
    );
    /// `min_length = …`.
    pub static MIN_LENGTH: Field = Field::new(
        "min_length",
        Quantity(Dim::LENGTH, Positive),
        Default(Described("the bead's width")),
        "the shortest stretch of constant speed",
    );
}

/// `slicing variable { … }`: layers that follow a sloped top.
pub static VARIABLE: Block = Block::new(
    "variable",
    "slicing variable { … }",
    "layers that follow a sloped top, each a fraction of the local height",
    &[
        &variable::LAYERS,
        &variable::SCAN,
        &variable::OFFSET,
        &variable::LEVEL,
        &variable::FOLLOW,
        &variable::DIRECTION,
        &RISE_TOLERANCE,
        &MAX_DRIFT,
        &variable::FINISH_TOLERANCE,
        &variable::SEGMENTS,
    ],
);

/// `segments { … }` of `slicing variable`.
pub static SEGMENTS: Block = Block::new(
    "segments",
    "segments { … }",
    "how a variable layer's tracks are cut into stretches of constant speed",
    &[&variable::TOLERANCE, &variable::MIN_LENGTH],
);

/// The fields of `slicing continuous { … }`.
pub mod continuous {
    use super::*;

    /// `layers = …`.
    pub static LAYERS: Field = Field::new(
        "layers",
        Count(1, MAX_LAYERS),
        Required("130"),
        "how many layers",
    );
    /// `layer_height = …`.
    pub static LAYER_HEIGHT: Field = Field::new(
        "layer_height",
        Quantity(Dim::LENGTH, Positive),
        Required("0.23 mm"),
        "the nominal rise per layer",
    );
    /// `step = …`.
    pub static STEP: Field = Field::new(
        "step",
        Quantity(
            Dim::ANGLE,
            PositiveUpTo(crate::sema::schema::deg(MAX_STEP_DEG)),
        ),
        Default(DefaultQuantity(crate::sema::schema::deg(DEFAULT_STEP_DEG))),
        "the points are at most this far apart",
    );
}

/// `slicing continuous { … }`: a segmented ring's layers in one run.
pub static CONTINUOUS: Block = Block::new(
    "continuous",
    "slicing continuous { … }",
    "a ring's layers laid in one run",
    &[
        &continuous::LAYERS,
        &continuous::LAYER_HEIGHT,
        &continuous::STEP,
    ],
);

/// A slicing block whose strategy is missing or unknown: what any strategy
/// takes, so a misspelt field shows in the same run as the strategy.
pub static ANY: Block = Block::new(
    "slicing",
    "slicing STRATEGY { … }",
    "a slicing block whose strategy is missing or unknown",
    &[
        &normal::LAYERS,
        &normal::POINTS,
        &normal::CHORD_ERROR,
        &normal::SEAM,
        &normal::NOZZLE,
        &normal::LAYER_CHANGE,
        &normal::MAX_OVERHANG,
        &RISE_TOLERANCE,
        &MAX_DRIFT,
        &planar::LAYER_HEIGHT,
        &planar::CONTOURS,
        &planar::OFFSET,
        &planar::INFILL,
        &variable::SCAN,
        &variable::LEVEL,
        &variable::FOLLOW,
        &variable::DIRECTION,
        &variable::FINISH_TOLERANCE,
        &continuous::STEP,
        &variable::SEGMENTS,
    ],
);
