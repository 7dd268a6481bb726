//! The IR: layer frames and process points. It is the contract between the front end
//! (parse → check → geometry → slicing) and the back ends, serialisable as
//! `<part>.ir.json` (`--emit ir`), documented in `docs/ir.md`.
//!
//! Units: mm, deg (only in machine poses), mm/s, W, g/min. Directions are unit
//! vectors. Process values and directions are stored as `f32` to keep a point at 80
//! bytes (the dense duct has 3.6 M of them); positions stay `f64`.

use crate::bead::{HeightModel, Table, Widths};
use crate::deposit::{Basis, Deposit};
use crate::span::Span;
use crate::units::{Density, Length, MassFlow, Speed};
use serde::{Deserialize, Serialize};

/// The IR format tag.
pub const FORMAT: &str = "lmdc-ir";
/// The IR version of a plan with a bead model ([`VERSION_CALIBRATED`] for
/// a calibrated one, the newest this compiler writes). Version 4 adds the plan's
/// bead model (`bead`) and each point's `pitch` and predicted `rise`, and
/// changes what a layer height is: the rise `A/pitch` the bead model lays
/// where a deposit fills a strip `pitch` wide ([`crate::deposit`]), where
/// older versions planned each point's height as a single bead's. A reader
/// that chose or checked speeds by the old rule would be off by a third on
/// a wall, so every plan with a bead model is version 4 ([`version_for`]).
pub const VERSION: u32 = 4;

/// Version 5: a bead model a version 4 reader would misread — a `power` or
/// `table` model, or widths measured at each speed (`bead.widths`), which
/// change the metal a move lays. Written only for such a plan
/// ([`Bead::needs_calibrated_version`]); every other plan with a bead
/// model is still version 4.
pub const VERSION_CALIBRATED: u32 = 5;

/// Version 6: a calibration plan (`lmdc calibrate`): layers laid on the
/// plate rather than on the layer before them (`Layer::on_plate`, a
/// coupon's first layer), each coupon's first layer labelled with its
/// parameters (`Layer::label`). A version 5 reader would take each
/// coupon for a layer on the one before.
pub const VERSION_COUPONS: u32 = 6;

/// Version 7: a robot with a positioner (`Robot::positioner`): its `base`
/// is where the part's base sits on the positioner's flange, which turns
/// by each layer's E1 and E2. A version 6 reader would take the base as
/// fixed in the cell and put every pose somewhere else.
pub const VERSION_POSITIONER: u32 = 7;

/// Version 8: a plan a version 7 reader would run wrong in another way: a
/// layer's wait that the thermal budget added (`thermal.layers[].added`
/// above 0), which the plan waits and a reader that ignores `thermal`
/// would not, so the layer would start above its interpass limit; or a
/// robot whose `controller` is not KUKA's, which such a reader would
/// write KRL for. Written only for such a plan ([`with_later`]).
pub const VERSION_BUDGET: u32 = 8;

/// Version 9: a plan whose thermal block predicts islands (`cooling =
/// order`, or `thermal.layers[].islands`): a version 8 reader does not
/// know the word `order` for `thermal.cooling`, nor that a layer's
/// interpass limit holds island by island. Written only for such a plan
/// ([`with_later`]).
pub const VERSION_ORDER: u32 = 9;

/// Version 10: a plan that allows several cooling levers at once
/// (`thermal.cooling` a list, `["order", "dwell"]`): a version 9 reader
/// reads one word there. Written only for such a plan ([`with_later`]).
pub const VERSION_LEVERS: u32 = 10;

/// Version 3: a segmented [`Ring`] built in one continuous run, with a
/// height loop that runs on the machine or a fixed speed schedule (a segmented ring's;
/// ignored, the nominal speeds would run open loop), and the machines'
/// `cell`, the gas and powder they switch (ignored, the laser would run
/// without shielding gas or powder). A ring has no bead model (its segments
/// have their own widths): it is still version 3.
pub const VERSION_RING: u32 = 3;

/// The version of a plan with neither a bead model, a ring nor a machine's
/// cell (an IR built by hand). Version 2 (variable-thickness layers, seed
/// 003): `speed` is the path speed, which the bead model is checked against
/// across the normal; a path may climb along the normal (`tangent` then
/// leaves the layer plane); a variable layer's `frame` is the world frame
/// and its `station` is `i/N`. Version 1 files read the same.
pub const VERSION_BASIC: u32 = 2;

/// The lowest version that holds a plan: [`VERSION`] with a bead model,
/// [`VERSION_RING`] with a ring or a machine that switches gas or powder,
/// else [`VERSION_BASIC`].
pub fn version_for(bead: bool, ring: bool, machines: &[Machine]) -> u32 {
    if bead {
        VERSION
    } else if ring || machines.iter().any(|m| !m.cell().is_none()) {
        VERSION_RING
    } else {
        VERSION_BASIC
    }
}

/// `version`, or [`VERSION_POSITIONER`] where a robot of `machines` has a
/// positioner.
pub fn with_positioner(version: u32, machines: &[Machine]) -> u32 {
    let positioned = machines
        .iter()
        .any(|m| matches!(m, Machine::Robot(r) if r.positioner.is_some()));
    if positioned {
        VERSION_POSITIONER
    } else {
        version
    }
}

/// `program`'s version, [`VERSION_LEVERS`] where its thermal block allows
/// several levers, [`VERSION_ORDER`] where it predicts islands, or [`VERSION_BUDGET`] where the thermal budget added a wait or
/// a robot has another controller than KUKA's.
pub fn with_later(program: &Program) -> u32 {
    if program
        .thermal
        .as_ref()
        .is_some_and(|t| t.cooling.levers().len() > 1)
    {
        return VERSION_LEVERS;
    }
    let islands = program.thermal.as_ref().is_some_and(|t| {
        t.cooling.allows(Cooling::Order) || t.layers.iter().any(|l| !l.islands.is_empty())
    });
    if islands {
        return VERSION_ORDER;
    }
    let waits = program
        .thermal
        .as_ref()
        .is_some_and(|t| t.layers.iter().any(|l| l.added > 0.0));
    let controller = program
        .machines
        .iter()
        .any(|m| matches!(m, Machine::Robot(r) if r.controller != Controller::Kuka));
    if waits || controller {
        VERSION_BUDGET
    } else {
        program.version
    }
}

/// A whole compiled plan.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Program {
    /// Always [`FORMAT`].
    pub format: String,
    /// [`version_for`] the plan: 4 with a bead model, 3 for a ring; later
    /// versions for what an older reader would misread ([`with_positioner`],
    /// [`with_later`]).
    pub version: u32,
    /// The part's name (used for file names).
    pub part: String,
    /// Units of every number in this file.
    pub units: Units,
    /// Process limits every laser-on point must respect.
    pub limits: Limits,
    /// The machines to write programs for.
    pub machines: Vec<Machine>,
    /// The style table: the values each style id stands for. Id 0,
    /// the process block's values, is not listed; points carry their values
    /// either way.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub styles: Vec<Style>,
    /// Cooling between layers.
    #[serde(default, skip_serializing_if = "Heat::is_none")]
    pub heat: Heat,
    /// The thermal model's data and each layer's predicted temperatures,
    /// with the waits a `max_interpass` asks (absent: no `thermal` block).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thermal: Option<Thermal>,
    /// Whether each layer's path goes on into the next layer's without the
    /// laser going off: the build is one run of deposit moves (a segmented
    /// ring, or a wall with `layer_change = spiral`).
    #[serde(default, skip_serializing_if = "is_false")]
    pub continuous: bool,
    /// A segmented ring and its height loop.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ring: Option<Ring>,
    /// The bead model the points' speeds were chosen with and their `rise`
    /// predicted by (none on a ring, whose segments have their own widths).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bead: Option<Bead>,
    /// Fixtures and clamps on the plate, which every machine's head keeps
    /// its gap from.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub fixtures: Vec<Fixture>,
    /// Layers in build order.
    pub layers: Vec<Layer>,
    /// Source spans of the declarations the checks refer to; not serialised.
    #[serde(skip)]
    pub origins: Origins,
}

fn is_false(b: &bool) -> bool {
    !*b
}

/// A ring split into segments with their own process, laid in one
/// continuous run: every layer's path has the same points in plan view, and
/// segment `j` owns points `first_point ..= first_point + flat_moves +
/// transition_moves` of every layer's path (the last being the next
/// segment's first), its transition from `transition_point` on. Points hold
/// the nominal plan: the table's speeds (`v / cos γ` over the transitions),
/// layers `layer_height` apart.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Ring {
    /// The nozzle's circle about the origin, mm.
    pub radius: f64,
    /// The transition at the end of each segment, deg.
    pub transition: f64,
    /// The nominal rise per layer, mm (the loop's target).
    pub layer_height: f64,
    /// Moves over each segment's constant part, on every layer.
    pub flat_moves: usize,
    /// Moves over each segment's transition, on every layer.
    pub transition_moves: usize,
    /// The segments from +x counter-clockwise: their table rows.
    pub segments: Vec<RingSegment>,
    /// How the speeds are chosen layer by layer.
    pub run: RingRun,
}

/// One segment's row of the table, and where its points are.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct RingSegment {
    /// Focal plane to working plane, mm (negative: below).
    pub defocus: f64,
    /// Laser power, W.
    pub power: f64,
    /// The bead width the row lays, mm: taken as the spot diameter `D`.
    pub width: f64,
    /// The starting horizontal scan speed, mm/s.
    pub speed: f64,
    /// `E = P/(D·v)` with `D` the width and `v` the starting speed, J/mm².
    pub energy_density: f64,
    /// Its first point's index in every layer's path.
    pub first_point: usize,
    /// Its transition's first point's index.
    pub transition_point: usize,
}

/// How a ring's speeds change from layer to layer.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
#[serde(tag = "mode", rename_all = "snake_case")]
pub enum RingRun {
    /// The height loop runs on the machine: after each layer a segment's
    /// measured height sets its next speed and working plane.
    OnMachine(HeightLoop),
    /// Open loop: the points carry these speeds, chosen offline (by the
    /// loop run against the declared plant, or the table's on every layer
    /// when no loop is declared).
    Schedule {
        /// Horizontal speed per layer and segment, mm/s.
        speeds: Vec<Vec<f64>>,
        /// The loop the speeds were simulated with, if any.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        control: Option<HeightLoop>,
    },
}

impl RingRun {
    /// The declared loop: run on the machine, or simulated for a schedule.
    pub fn control(&self) -> Option<&HeightLoop> {
        match self {
            RingRun::OnMachine(c) => Some(c),
            RingRun::Schedule { control, .. } => control.as_ref(),
        }
    }
}

/// A PI loop on each segment's layer height (`control::law`).
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct HeightLoop {
    /// Proportional gain, (mm/s)/mm.
    pub kp: f64,
    /// Integral gain, (mm/s)/mm.
    pub ki: f64,
    /// Target height per layer, mm.
    pub target: f64,
    /// The speeds the loop may command, mm/s.
    pub clamp: [f64; 2],
}

/// A machine's height sensor (what a segmented ring's loop reads): an analog input that holds a
/// segment's mean layer height.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct HeightSensor {
    /// The analog input: `$ANIN[input]` on a robot; on LinuxCNC
    /// `M66 E<input + j>` for segment `j` (from 0).
    pub input: u16,
    /// The height at an input of 1.0, mm.
    pub full_scale: f64,
    /// How long after a segment's end its mean is on the input, s.
    pub delay: f64,
}

/// A bead model, in the IR's units: what the slicer chose the speeds by
/// and the verifier predicts each layer's rise with ([`crate::deposit`]).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Bead {
    /// The bead's width, mm.
    pub width: f64,
    /// How its height follows the speed.
    pub model: BeadModel,
    /// What its heights were measured as.
    pub basis: Basis,
    /// The speeds it holds for, mm/s.
    pub speed: [f64; 2],
    /// The widths measured, `[speed (mm/s), width (mm)]` by speed: the
    /// bead's cross-section at a speed has that speed's width (absent: the
    /// width is `width` at every speed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub widths: Option<Vec<[f64; 2]>>,
    /// The speeds the model was measured over (a table's, a fit's data),
    /// mm/s: a plan that leaves them extrapolates, which the file must
    /// allow (`lmd::extrapolation`). Absent: the model was typed in, and
    /// `speed` is all that is known.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub measured: Option<[f64; 2]>,
    /// How the model was fitted to its data, when the file names them
    /// (`model = fit(…, data = "…")`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fit: Option<BeadFit>,
    /// The nozzle's tilts from vertical the model was measured at, deg
    /// (`tilt`): a deposit tilted more than 5° beyond them is warned
    /// (`lmd::bead-tilt`). Absent: measured with the nozzle vertical.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tilt: Option<[f64; 2]>,
    /// The laser powers the model was measured at, W (`powers`, or a fit's
    /// coupons'): a process at another is warned (`lmd::extrapolation`).
    /// Absent: not known.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub powers: Option<Vec<f64>>,
    /// The powder feeds it was measured at, g/min (`powders`, or a fit's
    /// coupons'). Absent: not known.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub powders: Option<Vec<f64>>,
}

/// A bead model fitted at compile time to measured coupons
/// (`model = fit(linear, data = "coupons.csv")`): where the numbers of
/// [`Bead::model`] come from, and how well they match.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct BeadFit {
    /// The data file as the source names it.
    pub data: String,
    /// The model fitted: `linear`, `power`, `mass_balance` or `table`.
    pub model: String,
    /// How many coupons were fitted.
    pub points: usize,
    /// How many distinct speeds.
    pub speeds: usize,
    /// The share of the measurements' variance the model explains.
    pub r2: f64,
    /// The root mean square of the residuals, in the unit measured (mm for
    /// heights; mm² for areas, g for masses).
    pub rms: f64,
    /// That unit.
    pub unit: String,
}

/// How a bead's height follows the scan speed `v` (mm/s).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum BeadModel {
    /// `h = slope·v + intercept`.
    Linear {
        /// mm per mm/s.
        slope: f64,
        /// mm.
        intercept: f64,
    },
    /// `A = efficiency·feed/(density·v)`.
    MassBalance {
        /// g/min (a point's own `powder` replaces it).
        feed: f64,
        /// 0–1.
        efficiency: f64,
        /// g/cm³.
        density: f64,
    },
    /// One height at one speed.
    Measured {
        /// mm.
        height: f64,
        /// mm/s.
        speed: f64,
    },
    /// `h = height·(v/speed)^exponent`.
    Power {
        /// mm, at `speed`.
        height: f64,
        /// mm/s.
        speed: f64,
        /// < 0.
        exponent: f64,
    },
    /// Heights at speeds, joined by straight lines.
    Table {
        /// mm/s, increasing.
        speed: Vec<f64>,
        /// mm, falling.
        height: Vec<f64>,
    },
}

impl Bead {
    /// The bead as the deposit model reads it.
    pub fn deposit(&self) -> Deposit {
        let model = match &self.model {
            &BeadModel::Linear { slope, intercept } => HeightModel::Linear {
                slope,
                intercept: Length(intercept),
            },
            &BeadModel::MassBalance {
                feed,
                efficiency,
                density,
            } => HeightModel::MassBalance {
                feed: MassFlow(feed / 60.0),
                efficiency,
                density: Density(density / 1000.0),
            },
            &BeadModel::Measured { height, speed } => HeightModel::Measured {
                height: Length(height),
                speed: Speed(speed),
            },
            &BeadModel::Power {
                height,
                speed,
                exponent,
            } => HeightModel::Power {
                height: Length(height),
                speed: Speed(speed),
                exponent,
            },
            // A table the IR holds was a table when it was written; one
            // edited into no table reads as its first point measured (and
            // the verifier finds what that lays).
            BeadModel::Table { speed, height } => match Table::new(speed, height) {
                Ok(t) => HeightModel::Table(t),
                Err(_) => HeightModel::Measured {
                    height: Length(height.first().copied().unwrap_or(f64::NAN)),
                    speed: Speed(speed.first().copied().unwrap_or(f64::NAN)),
                },
            },
        };
        let widths = self.widths.as_ref().and_then(|w| {
            let (v, w): (Vec<f64>, Vec<f64>) = w.iter().map(|p| (p[0], p[1])).unzip();
            Widths::new(&v, &w).ok()
        });
        Deposit {
            model,
            width: Length(self.width),
            basis: self.basis,
            widths,
        }
    }

    /// The IR's form of a deposit model valid over `speeds`.
    pub fn of(d: &Deposit, speeds: [Speed; 2]) -> Bead {
        let model = match &d.model {
            &HeightModel::Linear { slope, intercept } => BeadModel::Linear {
                slope,
                intercept: intercept.0,
            },
            &HeightModel::MassBalance {
                feed,
                efficiency,
                density,
            } => BeadModel::MassBalance {
                feed: feed.g_min(),
                efficiency,
                density: density.0 * 1000.0,
            },
            &HeightModel::Measured { height, speed } => BeadModel::Measured {
                height: height.0,
                speed: speed.0,
            },
            &HeightModel::Power {
                height,
                speed,
                exponent,
            } => BeadModel::Power {
                height: height.0,
                speed: speed.0,
                exponent,
            },
            HeightModel::Table(t) => BeadModel::Table {
                speed: t.speeds().to_vec(),
                height: t.heights().to_vec(),
            },
        };
        Bead {
            width: d.width.0,
            model,
            basis: d.basis,
            speed: [speeds[0].0, speeds[1].0],
            widths: d.widths.as_ref().map(|w| {
                w.speeds()
                    .iter()
                    .zip(w.widths())
                    .map(|(&v, &w)| [v, w])
                    .collect()
            }),
            measured: None,
            fit: None,
            tilt: None,
            powers: None,
            powders: None,
        }
    }

    /// Whether a reader of version 4 would misread it: a model kind or
    /// measured widths it does not know ([`VERSION_CALIBRATED`]).
    pub fn needs_calibrated_version(&self) -> bool {
        self.widths.is_some()
            || matches!(
                self.model,
                BeadModel::Power { .. } | BeadModel::Table { .. }
            )
    }
}

/// Units of the IR's numbers.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Units {
    /// Positions and heights.
    pub length: String,
    /// Angles.
    pub angle: String,
    /// Speeds.
    pub speed: String,
    /// Laser power.
    pub power: String,
    /// Powder feed.
    pub powder: String,
}

impl Default for Units {
    fn default() -> Self {
        Units {
            length: "mm".into(),
            angle: "deg".into(),
            speed: "mm/s".into(),
            power: "W".into(),
            powder: "g/min".into(),
        }
    }
}

/// Limits from the bead model and the process window.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Limits {
    /// Allowed layer height `[h_min, h_max]` in mm.
    pub layer_height: [f64; 2],
    /// Scan speeds the bead model is valid for, mm/s.
    pub speed: [f64; 2],
    /// Laser power range, W.
    pub power: [f64; 2],
    /// The bead's width, mm (0 when unknown: layers are then not checked for
    /// lying on each other).
    #[serde(default)]
    pub bead_width: f64,
    /// How far a point's predicted rise may be from its layer height, as a
    /// fraction of it (`rise_tolerance`; docs/ir.md, *The deposit*).
    #[serde(default = "default_rise_tolerance")]
    pub rise_tolerance: f64,
    /// How far the layers' mean error may add up, mm (`max_drift`).
    #[serde(default = "default_max_drift")]
    pub max_drift: f64,
    /// The most a wall's layer may lean out over the one below, from the
    /// nozzle's axis, deg (`max_overhang`; absent: only what
    /// `lmd::stacking` holds, docs/ir.md).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_overhang: Option<f64>,
}

// The defaults of the deposit tolerances, re-exported for readers of the IR.
pub use crate::deposit::{MAX_DRIFT, RISE_TOLERANCE};

fn default_rise_tolerance() -> f64 {
    RISE_TOLERANCE
}

fn default_max_drift() -> f64 {
    MAX_DRIFT
}

/// How long a layer must take, so it can cool before the next is laid on it.
/// The motion plan dwells at a safe position after a layer that would be
/// quicker (docs/ir.md).
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Heat {
    /// Least time from one layer's start to the next's, s (0: none).
    pub min_layer_time: f64,
    /// Dwell after every layer but the last, s (0: none).
    pub dwell: f64,
}

impl Heat {
    /// Whether nothing is asked.
    pub fn is_none(&self) -> bool {
        self.min_layer_time <= 0.0 && self.dwell <= 0.0
    }
}

impl Program {
    /// The wait before layer `i` that the thermal budget added to, s, which
    /// the motion plan keeps (0: none added; the plan then waits what the
    /// declared `dwell` and `min_layer_time` ask, by its own layer times).
    pub fn thermal_wait(&self, i: usize) -> f64 {
        self.thermal
            .as_ref()
            .and_then(|t| t.layers.get(i))
            .filter(|l| l.added > 0.0)
            .map_or(0.0, |l| l.wait)
    }

    /// Whether the plan stops to cool between layers: a declared dwell or
    /// minimum layer time, or a wait the thermal budget added.
    pub fn cools(&self) -> bool {
        !self.heat.is_none()
            || self
                .thermal
                .as_ref()
                .is_some_and(|t| t.layers.iter().any(|l| l.added > 0.0))
    }
}

/// How a plan keeps its interpass limit.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum Cooling {
    /// The least wait before each layer that keeps it.
    #[default]
    Dwell,
    /// The least power reduction of the layer before, within the bead's
    /// measured powers and the laser's range.
    Power,
    /// Each layer's islands laid in the order that starts each the
    /// coolest, no wait beyond the declared ones.
    Order,
}

impl Cooling {
    /// The word the language and the IR write it as.
    pub fn word(self) -> &'static str {
        match self {
            Cooling::Dwell => "dwell",
            Cooling::Power => "power",
            Cooling::Order => "order",
        }
    }
}

/// The levers a plan may pull to keep its interpass limit: one, written as
/// its word (`"order"`), or several, as a list (`["order", "dwell"]`,
/// version 10), each at most once. lmdc pulls them in the order that
/// costs the least time whatever the list's order: the islands' order,
/// then the power, then the wait (docs/thermal.md, *The budget*).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Eq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
#[serde(untagged)]
pub enum Levers {
    /// One lever.
    One(Cooling),
    /// Several, as written.
    Several(Vec<Cooling>),
}

impl Default for Levers {
    fn default() -> Levers {
        Levers::One(Cooling::Dwell)
    }
}

impl Levers {
    /// The levers `list` names: one as its word, several as a list (an
    /// empty list: the default).
    pub fn of(list: &[Cooling]) -> Levers {
        match list {
            [] => Levers::default(),
            [one] => Levers::One(*one),
            many => Levers::Several(many.to_vec()),
        }
    }

    /// The levers, as written.
    pub fn levers(&self) -> &[Cooling] {
        match self {
            Levers::One(c) => std::slice::from_ref(c),
            Levers::Several(v) => v,
        }
    }

    /// Whether `lever` is allowed.
    pub fn allows(&self, lever: Cooling) -> bool {
        self.levers().contains(&lever)
    }

    /// As the source writes it: `order`, `[order, dwell]`.
    pub fn written(&self) -> String {
        let words: Vec<&str> = self.levers().iter().map(|c| c.word()).collect();
        match self {
            Levers::One(c) => c.word().to_string(),
            Levers::Several(_) => format!("[{}]", words.join(", ")),
        }
    }
}

/// The thermal model's data (docs/thermal.md) and what it predicts of each
/// layer.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Thermal {
    /// The alloy, as `material = …` names it (`KEY, with declared
    /// properties` over it; `declared material`: no alloy).
    pub material: String,
    /// Thermal conductivity, W/(m·K).
    pub conductivity: f64,
    /// Density, kg/m³.
    pub density: f64,
    /// Specific heat capacity, J/(kg·K).
    pub heat_capacity: f64,
    /// The surface's emissivity.
    pub emissivity: f64,
    /// The share of the laser's power the part takes up.
    pub absorptivity: f64,
    /// Heat transfer coefficient to the cell's gas, W/(m²·K).
    pub heat_transfer: f64,
    /// The plate's length, width and thickness, mm.
    pub plate: [f64; 3],
    /// The plate's temperature when the build starts, °C.
    pub preheat: f64,
    /// The cell's gas and walls, °C.
    pub ambient: f64,
    /// The interpass temperature no layer starts above, °C (absent:
    /// predicted, not limited).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_interpass: Option<f64>,
    /// How the limit may be kept.
    pub cooling: Levers,
    /// `cooling` with another lever than `dwell`: what `cooling = dwell`
    /// would add to the waits to keep the limit with the islands in the
    /// slicer's order, s (absent: waits alone, no limit, or waits of at
    /// most an hour would not keep it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dwell_alone: Option<f64>,
    /// Each layer's prediction, in layer order.
    pub layers: Vec<LayerHeat>,
}

/// One layer's predicted temperatures (docs/thermal.md).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct LayerHeat {
    /// Where the layer starts: its first deposit point, mm.
    pub at: [f64; 3],
    /// When, s from the build's start (deposits and waits; rapid moves
    /// between paths counted as instant, so the part is taken to cool
    /// less than it does).
    pub time: f64,
    /// The temperature of the top of the part there and then, °C: the
    /// layer below's (the plate's under the first).
    pub interpass: f64,
    /// The layer's own temperature when it is laid, °C: the hottest it is
    /// as a whole (not the melt pool's).
    pub peak: f64,
    /// The wait before the layer, s: the declared `dwell` or
    /// `min_layer_time`'s, or longer where `max_interpass` asks; the
    /// motion plan waits at least this.
    pub wait: f64,
    /// What `max_interpass` added to the wait, s.
    pub added: f64,
    /// The share of its declared power the layer is laid at (`cooling =
    /// power`; absent: 1).
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub power: f64,
    /// A layer of several islands: each island's prediction, in the order
    /// they are laid (absent: a layer of one piece, whose figures are the
    /// layer's).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub islands: Vec<IslandHeat>,
    /// Whether the budget laid the islands in another order than the
    /// slicer's (`cooling` with `order`; absent: the slicer's).
    #[serde(default, skip_serializing_if = "is_false")]
    pub reordered: bool,
}

/// One island of a layer of several: its predicted temperatures
/// (docs/thermal.md, *Islands*).
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct IslandHeat {
    /// Where the island starts: its first deposit point, mm.
    pub at: [f64; 3],
    /// When, s from the build's start.
    pub time: f64,
    /// The temperature of the top of the island below it there and then
    /// (the plate's under the first layer), °C.
    pub interpass: f64,
    /// The island's own temperature when it is laid, °C.
    pub peak: f64,
}

fn one() -> f64 {
    1.0
}

fn is_one(x: &f64) -> bool {
    *x == 1.0
}

/// One layer: deposited on the plane at `station` of the spine (a planar
/// layer on the plane `z = station·height`; a variable layer on the planned
/// top of the layer below, `station` being its fraction `i/N` of the top).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Layer {
    /// 0-based build order.
    pub index: usize,
    /// Position along the spine of the plane this layer is deposited on (0 = start
    /// section, 1 = end section).
    pub station: f64,
    /// The section frame at that station.
    pub frame: Frame,
    /// Paths in deposition order.
    pub paths: Vec<Path>,
    /// A line the programs write as a comment before the layer: a
    /// calibration coupon's id and parameters (empty: none).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub label: String,
    /// Whether the layer is laid on the plate rather than on the layer
    /// before it (a calibration coupon's first layer): `lmd::stacking` does
    /// not look for the layer before it underneath.
    #[serde(default, skip_serializing_if = "is_false")]
    pub on_plate: bool,
}

/// A right-handed orthonormal frame.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Frame {
    /// Origin, mm.
    pub origin: [f64; 3],
    /// Section reference direction (carries the twist).
    pub x: [f64; 3],
    /// `z × x`.
    pub y: [f64; 3],
    /// Build direction: the layer plane's normal (the beam points along −z).
    pub z: [f64; 3],
}

impl Frame {
    /// The part's own axes at its origin: a flat layer's frame.
    pub const PART: Frame = Frame {
        origin: [0.0; 3],
        x: [1.0, 0.0, 0.0],
        y: [0.0, 1.0, 0.0],
        z: [0.0, 0.0, 1.0],
    };
}

/// What a path is for.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq, Eq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum PathKind {
    /// A bead of a wall: a loft's single bead following the section, or a
    /// bead of a wall along an open path.
    Wall,
    /// A contour pass of a filled solid.
    Contour,
    /// A raster infill track.
    Infill,
    /// A laser-off move between deposits.
    Travel,
    /// A laser-off lead onto a deposit's first point or on from its last
    /// (a wall along an open path with `ends = lead(…)`): the nozzle runs
    /// it at its points' speed, so it is at speed where the laser switches
    /// on and brakes after it switched off ([`crate::plan`]).
    Lead,
}

/// A polyline of process points.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Path {
    /// What the path is.
    pub kind: PathKind,
    /// The points, in order.
    pub points: Vec<Point>,
}

/// One process point: where the bead is laid, how the nozzle stands, and the
/// process values from this point to the next.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Point {
    /// Deposit point on the working plane, mm.
    pub pos: [f64; 3],
    /// Unit build direction; the beam points along −normal.
    pub normal: [f32; 3],
    /// Unit direction of travel (it climbs out of the layer plane where a
    /// variable layer follows the layer below).
    pub tangent: [f32; 3],
    /// Local height of this layer here, mm.
    pub layer_height: f32,
    /// Path speed from this point to the next (the nozzle's focus's speed
    /// along the path), mm/s. The bead model holds for the deposit point's
    /// speed across the normal ([`Point::speed_across`]).
    pub speed: f32,
    /// Laser power, W.
    pub power: f32,
    /// Powder feed, g/min.
    pub powder: f32,
    /// Distance of the focal plane from the working plane, mm (negative: focus
    /// below the surface).
    pub defocus: f32,
    /// Whether the laser is on while moving to the next point.
    pub laser_on: bool,
    /// The process style of this point (0: the process block's values).
    #[serde(default)]
    pub style: u16,
    /// The width of the strip of its layer this point's deposit fills, mm:
    /// the bead's width on a wall one bead wide, the offset of overlapped
    /// tracks, the mean spacing to the neighbouring tracks in a balanced
    /// variable layer (0: not known, as on a ring). The deposit model's rise
    /// here is `A/pitch` (docs/ir.md, *The deposit*).
    #[serde(default)]
    pub pitch: f32,
    /// How much the layer rises here by the plan's bead model, at this
    /// point's speed across the normal and its powder feed, mm (0 where the
    /// laser is off or no bead model is known): what `layer_height` plans.
    #[serde(default)]
    pub rise: f32,
}

/// One row of the style table.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Style {
    /// The id points carry.
    pub id: u16,
    /// Its name in the source.
    pub name: String,
    /// Laser power, W, if the style sets it.
    pub power: Option<f64>,
    /// Scan speed, mm/s, if the style sets it.
    pub speed: Option<f64>,
    /// Powder feed, g/min, if the style sets it.
    pub powder: Option<f64>,
    /// Display colour `#rrggbb`.
    pub colour: String,
}

/// A machine to write a program for.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum Machine {
    /// An industrial robot programmed in KRL.
    Robot(Robot),
    /// A CNC programmed in G-code.
    Cnc(Cnc),
}

impl Machine {
    /// What the machine has whatever its kind: name, speed, clearance, cell
    /// and height sensor.
    pub fn common(&self) -> &MachineCommon {
        match self {
            Machine::Robot(r) => &r.common,
            Machine::Cnc(c) => &c.common,
        }
    }

    /// The same, to change (a check's help tries another head).
    pub fn common_mut(&mut self) -> &mut MachineCommon {
        match self {
            Machine::Robot(r) => &mut r.common,
            Machine::Cnc(c) => &mut c.common,
        }
    }

    /// The machine's name from the source.
    pub fn name(&self) -> &str {
        &self.common().name
    }

    /// The gas and powder it switches.
    pub fn cell(&self) -> &Cell {
        &self.common().cell
    }
}

/// What every machine has, whatever its kind: the fields a robot's and a
/// CNC's blocks share (one entry each in the language's machine table).
/// A [`Robot`] and a [`Cnc`] dereference to theirs, so `robot.max_speed`
/// reads it; the IR's JSON keeps each field where it always was among the
/// kind's own.
#[derive(Clone, Debug, PartialEq)]
pub struct MachineCommon {
    /// Name from the source; the program is named after the part and this.
    pub name: String,
    /// Highest path speed (a CNC's feed), mm/s.
    pub max_speed: f64,
    /// Distance the nozzle backs off along the normal between paths that do not
    /// join, mm.
    pub clearance: f64,
    /// The cell's shielding gas and powder feeder, if the program switches them.
    pub cell: Cell,
    /// The height sensor a closed loop reads, if the cell has one.
    pub height_sensor: Option<HeightSensor>,
    /// The path acceleration (and deceleration) the control plans with,
    /// mm/s² (`None`: not declared, and the programmed speeds are taken as
    /// reached; docs/ir.md, *The speed the machine reaches*).
    pub acceleration: Option<f64>,
    /// How far before (and after) a corner the control may leave the path
    /// to round it, mm (`None`: what the program sets by default,
    /// [`crate::target::blending`]).
    pub blending: Option<f64>,
    /// How the program starts and stops a bead.
    pub ramp: Ramp,
    /// What it carries along the beam, for the collision checks.
    pub head: Head,
}

/// What a machine carries along the beam (docs/collision.md): solids of
/// revolution about the beam, stacked from the nozzle's tip up, each kept
/// `gap` away from the plate, the fixtures and the part as it grows.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Head {
    /// The nozzle tip's distance from the laser focus, up the beam, mm: the
    /// tool's own geometry (a larger defocus below the surface brings the
    /// tip nearer the part).
    pub standoff: f64,
    /// From the tip up.
    pub bodies: Vec<HeadBody>,
    /// The least distance kept between the head and anything else, mm.
    pub gap: f64,
    /// Whether the machine declared it (else lmdc's typical coaxial nozzle,
    /// [`Head::typical`], and the warning `lmd::head-unchecked`).
    pub declared: bool,
}

/// One solid of a [`Head`]: a frustum about the beam (a cylinder where its
/// two diameters are equal).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct HeadBody {
    /// What it is (`nozzle`, `body`, `housing`), for the messages.
    pub name: String,
    /// Its length along the beam, mm.
    pub length: f64,
    /// Its diameters at its lower and upper ends, mm.
    pub diameters: [f64; 2],
}

impl Head {
    /// A typical coaxial DED nozzle, for a machine that declares no head: a
    /// conical nozzle 45 mm long from a 12 mm tip to 40 mm, on a body 60 mm
    /// across and 100 mm long, its tip 15 mm above the focus; a gap of 2 mm.
    /// Not any one product: the size of the discrete-jet and annular
    /// nozzles of 1–4 kW cells (docs/collision.md).
    pub fn typical() -> Head {
        Head {
            standoff: 15.0,
            bodies: vec![
                HeadBody {
                    name: "nozzle".into(),
                    length: 45.0,
                    diameters: [12.0, 40.0],
                },
                HeadBody {
                    name: "body".into(),
                    length: 100.0,
                    diameters: [60.0, 60.0],
                },
            ],
            gap: 2.0,
            declared: false,
        }
    }
}

impl Default for Head {
    fn default() -> Self {
        Head::typical()
    }
}

impl Head {
    /// The ends of its solids, from the tip up: each `(s, r)`, `s` up the
    /// beam from the focus and `r` the radius there, mm.
    fn rims(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        let mut s = self.standoff;
        self.bodies.iter().flat_map(move |b| {
            let rims = [
                (s, b.diameters[0] / 2.0),
                (s + b.length, b.diameters[1] / 2.0),
            ];
            s += b.length;
            rims
        })
    }

    /// How far above its focus the head's lowest point lies (mm, negative
    /// below it) with its beam's Z component `up_z` (the cosine of its
    /// tilt): a solid of revolution reaches lowest on the rim of one of its
    /// ends, at `s·cos θ − r·sin θ`.
    pub fn lowest_above_focus(&self, up_z: f64) -> f64 {
        let c = up_z.clamp(-1.0, 1.0);
        let across = (1.0 - c * c).sqrt();
        self.rims()
            .map(|(s, r)| s * c - r * across)
            .fold(f64::INFINITY, f64::min)
    }

    /// At most how far the head reaches sideways from the vertical line
    /// through its focus (mm) with its beam's Z component `up_z`: a rim's
    /// centre lies `s·sin θ` off it, its points `r` farther at most.
    pub fn spread(&self, up_z: f64) -> f64 {
        let c = up_z.clamp(-1.0, 1.0);
        let across = (1.0 - c * c).sqrt();
        self.rims()
            .map(|(s, r)| s.abs() * across + r)
            .fold(0.0, f64::max)
    }
}

/// A fixture or clamp (`fixture NAME { … }`): what the head and the arm
/// must keep their gap from. On the plate, in the part's coordinates (it
/// turns with a table or a positioner); or, with `machine`, fixed to that
/// machine, in its own coordinates (docs/collision.md).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Fixture {
    /// Its name from the source.
    pub name: String,
    /// Its shape.
    pub shape: FixtureShape,
    /// The centre of its bottom face, mm: in the part's coordinates, or
    /// in its machine's.
    pub at: [f64; 3],
    /// The machine it is fixed to (`machine = NAME`), by name: `at` is in
    /// that machine's coordinates (a CNC's at every rotary axis 0, a
    /// robot's own frame), it does not turn with the part, and only that
    /// machine's plan is checked against it. Absent: on the plate.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub machine: Option<String>,
    /// Fixed to its machine's tilt axis (`turns_with = tilt`): a table's
    /// cradle or trunnion, turning with A or B and not with C; a
    /// positioner's tilting arm, with E1 and not E2. `at` is where it
    /// stands with every rotary axis at 0.
    #[serde(default, skip_serializing_if = "is_false")]
    pub tilts: bool,
    /// The scanned part's best fit to its nominal (`scan(register = …)`):
    /// how it was moved and how well it fits. Absent: placed as declared,
    /// or not a scan.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub registration: Option<Registration>,
}

/// How a scan was moved onto its nominal by a best fit, and how well it
/// fits (`scan(register = …, fit_tolerance = …)`, docs/repair.md,
/// *Registration*).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Registration {
    /// The nominal's file, or the name of the solid of the file it is
    /// (`register = NAME`), as the source writes it.
    pub nominal: String,
    /// The shift the fit found after the declared placement, mm (with
    /// `turned`, about the part's origin: `p ↦ R·p + moved`).
    pub moved: [f64; 3],
    /// The turn the fit found after the declared placement, deg: about x,
    /// then y, then z, as `turn` is written.
    pub turned: [f64; 3],
    /// The whole placement, declared and fitted together: the `turn` (deg)
    /// that places the scan so without `register`…
    pub turn: [f64; 3],
    /// …and the `at` (mm).
    pub at: [f64; 3],
    /// RMS distance to the nominal of the points the fit keeps, mm.
    pub rms: f64,
    /// The farthest kept point's distance, mm.
    pub max: f64,
    /// The share of the fitted points kept (the rest: worn, stray), 0–1.
    pub inliers: f64,
    /// The points fitted (every k-th of the scan's, at most 50 000).
    pub points: usize,
    /// The iterations the fit took.
    pub iterations: usize,
    /// `fit_tolerance`: the most `rms` may be, mm.
    pub tolerance: f64,
}

/// The name the part a repair builds on goes by among the fixtures
/// (`extrude { on = scan(…) }`, docs/repair.md): its estimated surface is an
/// obstacle as a mesh fixture is. Not a name a file can give a fixture (it
/// has a space), so it never meets a declared one.
pub const SCANNED_PART: &str = "scanned part";

impl Fixture {
    /// Whether this is the scanned part a repair builds on.
    pub fn is_scan(&self) -> bool {
        self.name == SCANNED_PART
    }

    /// Whether the plan of machine `name` meets it, and how: `Some(false)`
    /// on the plate (the part's coordinates), `Some(true)` fixed to that
    /// machine, `None` fixed to another one.
    pub fn fixed_to(&self, name: &str) -> Option<bool> {
        match &self.machine {
            None => Some(false),
            Some(m) if m == name => Some(true),
            Some(_) => None,
        }
    }

    /// How the messages and the report name it: `fixture NAME`, or `the
    /// scanned part`.
    pub fn label(&self) -> String {
        if self.is_scan() {
            "the scanned part".into()
        } else {
            format!("fixture {}", self.name)
        }
    }

    /// The box round it, mm: its least and greatest X, Y and Z.
    pub fn bounds(&self) -> ([f64; 3], [f64; 3]) {
        let [x, y, z] = self.at;
        let (half, height) = match &self.shape {
            FixtureShape::Box { size } => ([size[0] / 2.0, size[1] / 2.0], size[2]),
            FixtureShape::Cylinder { diameter, length } => ([diameter / 2.0; 2], *length),
            FixtureShape::Mesh { min, max, .. } => {
                return (
                    [x + min[0], y + min[1], z + min[2]],
                    [x + max[0], y + max[1], z + max[2]],
                )
            }
        };
        (
            [x - half[0], y - half[1], z],
            [x + half[0], y + half[1], z + height],
        )
    }
}

/// A fixture's shape: a box or a cylinder standing on its bottom face, or
/// a mesh placed by its own origin.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
#[serde(tag = "shape", rename_all = "snake_case")]
pub enum FixtureShape {
    /// A box, its sides along X, Y and Z, mm.
    Box {
        /// Along X, Y and Z, mm.
        size: [f64; 3],
    },
    /// An upright cylinder, mm.
    Cylinder {
        /// mm.
        diameter: f64,
        /// Its height, mm.
        length: f64,
    },
    /// A triangle mesh from a file (`mesh(file = …)`), its own origin at
    /// the fixture's `at`: scaled to mm and turned as declared. Its
    /// triangles are not in the IR (a file may hold millions): the file,
    /// its units and turn say how to read it again, the box where it is.
    Mesh {
        /// The file as the source names it.
        file: String,
        /// What one unit of its coordinates is (`mm`, `cm`, `m`, `in`).
        units: String,
        /// Its turns about x, then y, then z, degrees.
        turn: [f64; 3],
        /// The least corner of the box round it, from `at`, mm.
        min: [f64; 3],
        /// The greatest corner of the box round it, from `at`, mm.
        max: [f64; 3],
        /// How far at most a point of its surface lies from the sample the
        /// collision checks stand it for, mm (docs/collision.md).
        tolerance: f64,
        /// Its surface as samples from `at`, `[x, y, z, radius]` in mm
        /// ([`crate::collision::surface`]): beside the IR, not in it.
        #[serde(skip)]
        samples: MeshSamples,
    },
}

/// A mesh fixture's samples, shared (a program and its copies hold one).
#[derive(Clone, Default)]
pub struct MeshSamples(pub std::sync::Arc<Vec<[f64; 4]>>);

impl PartialEq for MeshSamples {
    fn eq(&self, other: &Self) -> bool {
        std::sync::Arc::ptr_eq(&self.0, &other.0) || self.0 == other.0
    }
}

impl std::fmt::Debug for MeshSamples {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} samples", self.0.len())
    }
}

/// How a machine's program starts and stops a bead, where the nozzle speeds
/// up from rest and slows down to it while the powder keeps flowing
/// (`ramp = …`).
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum Ramp {
    /// The laser switches where the nozzle stands: each run of deposits
    /// starts from rest and ends at rest.
    #[default]
    None,
    /// A laser-off lead-in along the path's first direction, `v²/2a` long,
    /// brings the nozzle up to speed where the laser switches on (without
    /// stopping); a lead-out after the last deposit lets it slow down with
    /// the laser off ([`crate::plan`]).
    Lead,
}

impl Ramp {
    /// Whether it is the default (left out of the IR's JSON).
    pub fn is_none(&self) -> bool {
        *self == Ramp::None
    }
}

/// A pose `X Y Z A B C` (mm, deg; KUKA ZYX Euler: R = Rz(A)·Ry(B)·Rx(C)).
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Pose {
    /// mm
    pub x: f64,
    /// mm
    pub y: f64,
    /// mm
    pub z: f64,
    /// deg, about Z
    pub a: f64,
    /// deg, about the new Y
    pub b: f64,
    /// deg, about the new X
    pub c: f64,
}

/// A frame on the controller: an index into its table, and optionally a value the
/// program sets.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct FrameRef {
    /// `TOOL_DATA[n]` / `BASE_DATA[n]`.
    pub index: u16,
    /// Value written by the program, if declared in the source.
    pub value: Option<Pose>,
}

/// A robot tool's load (`load = load(…)`), as KUKA's `LOAD_DATA[n]` holds
/// it and the main program sets it (`$LOAD`): the mass, where its centre of
/// gravity is and how its principal axes of inertia are turned, in the
/// flange's frame (`$FLANGE`), and its principal moments of inertia.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Load {
    /// Mass, kg (`M`).
    pub mass: f64,
    /// Centre of gravity in the flange's frame, mm (`CM` X, Y, Z).
    pub cog: [f64; 3],
    /// The principal axes of inertia turned from the flange's, KUKA A, B,
    /// C, deg (`CM` A, B, C).
    pub inertia_axes: [f64; 3],
    /// Principal moments of inertia about the centre of gravity, kg·m²
    /// (`J` X, Y, Z); all 0: a point mass.
    pub inertia: [f64; 3],
}

/// An axis of the tool frame, with a sign.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq, Eq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum ToolAxis {
    /// +X
    PlusX,
    /// −X
    MinusX,
    /// +Y
    PlusY,
    /// −Y
    MinusY,
    /// +Z
    PlusZ,
    /// −Z
    MinusZ,
}

/// A KUKA robot cell.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
#[serde(from = "wire::Robot", into = "wire::Robot")]
pub struct Robot {
    /// Name, speed, clearance, cell and height sensor.
    pub common: MachineCommon,
    /// The controller its program is written for: KRL for KUKA, RAPID for
    /// ABB.
    pub controller: Controller,
    /// Tool (TCP at the laser focus).
    pub tool: FrameRef,
    /// The tool's load, when the robot declares it: the program sets it
    /// (`$LOAD`); none: the controller's `LOAD_DATA[n]` of the tool's index.
    pub load: Option<Load>,
    /// Base the part is programmed in.
    pub base: FrameRef,
    /// Which tool axis the beam travels along.
    pub beam: ToolAxis,
    /// `$OUT[n]` that switches the laser on (ABB: `do<n>`, or the named
    /// signal).
    pub laser_out: Signal,
    /// `$ANOUT[n]` that sets the power (ABB: `ao<n>`, or the named signal).
    pub power_out: Signal,
    /// Power at `$ANOUT = 1.0`, W.
    pub full_scale_power: f64,
    /// Axis angles of the home position, deg.
    pub home: [f64; 6],
    /// Most motion lines in one sub-program module.
    pub max_points_per_module: usize,
    /// The arm, when the robot declares it: its reach, axis limits,
    /// singularities and axis speeds are then checked on every move.
    pub arm: Option<Box<Arm>>,
    /// The tool's turn about the beam (`spin`): free for a coaxial nozzle,
    /// declared or chosen by lmdc ([`crate::plan::spin`]).
    pub spin: Spin,
    /// A two-axis positioner that turns the part (KUKA external axes E1,
    /// E2, mathematically coupled): `base` is then where the part's base
    /// sits on its flange, and every pose is in that moving base.
    pub positioner: Option<Box<Positioner>>,
}

/// The controller a robot's program is written for (`controller = …`).
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "lowercase")]
pub enum Controller {
    /// A KUKA KR C4/C5 (KSS 8.x): KRL.
    #[default]
    Kuka,
    /// An ABB IRC5 or OmniCore: RAPID (docs/rapid.md).
    Abb,
}

impl Controller {
    /// KUKA's, the default (left out of the IR's JSON).
    pub fn is_kuka(&self) -> bool {
        *self == Controller::Kuka
    }
}

/// An output a machine switches or sets: by number (KUKA's `$OUT[n]` and
/// `$ANOUT[n]`, ABB's `do<n>` and `ao<n>`, a G-code output line's `{n}`),
/// or, on an ABB robot, by the signal's name in the controller's I/O
/// configuration (`doLaserOn`, a RAPID identifier). The IR's JSON writes a
/// number as a number and a name as a text.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
#[serde(untagged)]
pub enum Signal {
    /// The output's number.
    Number(u16),
    /// The signal's name (ABB only).
    Name(String),
}

impl Signal {
    /// The output's number; `None` for a named signal, which only an ABB
    /// robot has (sema refuses a name elsewhere).
    pub fn number(&self) -> Option<u16> {
        match self {
            Signal::Number(n) => Some(*n),
            Signal::Name(_) => None,
        }
    }
}

impl std::fmt::Display for Signal {
    /// The number, or the name.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Signal::Number(n) => write!(f, "{n}"),
            Signal::Name(s) => f.write_str(s),
        }
    }
}

/// A robot's two-axis positioner (`positioner { … }`): a tilt axis (KUKA's
/// E1) fixed in the robot's frame (`$ROBROOT`, taken as `$WORLD`), carrying
/// a rotate axis (E2) whose flange carries the part's base. Every axis is
/// given at E1 = E2 = 0; an angle turns right-handed about its direction.
/// The flange's frame: its origin on the rotate axis at `rotate.point`, Z
/// along `rotate.direction`, X along the tilt axis (made square to Z).
/// Lengths mm, angles deg.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Positioner {
    /// E1: the tilt axis.
    pub tilt: PositionerAxis,
    /// E2: the rotate axis, at E1 = 0.
    pub rotate: PositionerAxis,
    /// How the angles are chosen.
    pub keep: Keep,
    /// E1 and E2 at home, deg: where the program starts (the PTP from home)
    /// and ends (the PTP back), with the arm at its `home`.
    #[serde(default)]
    pub home: [f64; 2],
    /// Each layer's E1 and E2, deg, in layer order (constant over a
    /// layer): chosen by [`crate::plan::positioner`] after lowering.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub angles: Vec<[f64; 2]>,
    /// The faceplate's diameter, mm: a disc on E2's flange, its face where
    /// the part's base sits, [`FACEPLATE_THICKNESS_MM`] thick behind it,
    /// which the arm's links keep their gap from (docs/collision.md);
    /// `None`: not declared, not checked.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub faceplate: Option<f64>,
}

/// How thick a positioner's faceplate is taken to be, mm.
pub const FACEPLATE_THICKNESS_MM: f64 = 40.0;

/// One axis of a [`Positioner`].
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct PositionerAxis {
    /// Its direction in the robot's frame, unit.
    pub direction: [f64; 3],
    /// A point of it in the robot's frame, mm.
    pub point: [f64; 3],
    /// Its software limits, deg.
    pub limits: [f64; 2],
    /// Its top speed, deg/s.
    pub speed: f64,
}

/// How a positioner's angles are chosen for each layer.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
#[serde(tag = "keep", rename_all = "snake_case")]
pub enum Keep {
    /// The layer's mean normal turned straight up (the nozzle vertical).
    Vertical,
    /// The angles kept while the layer's mean normal is within `deg` of
    /// straight up; beyond, turned straight up again.
    Cone {
        /// deg.
        deg: f64,
    },
    /// These angles for every layer, deg.
    Fixed {
        /// E1, deg.
        e1: f64,
        /// E2, deg.
        e2: f64,
    },
}

/// The tool's turn about the beam axis, deg, added to the turn lmdc carries
/// from normal to normal ([`crate::plan::orient`]): 0 keeps that turn.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
#[serde(tag = "from", rename_all = "snake_case")]
pub enum Spin {
    /// `spin = auto` (the default): 0°, or the turn lmdc chose where 0°
    /// breaks an arm rule.
    Auto {
        /// deg.
        deg: f64,
    },
    /// Declared in the file (`spin = 30 deg`): used as written.
    Declared {
        /// deg.
        deg: f64,
    },
}

impl Default for Spin {
    fn default() -> Self {
        Spin::Auto { deg: 0.0 }
    }
}

impl Spin {
    /// The turn, deg.
    pub fn deg(&self) -> f64 {
        match self {
            Spin::Auto { deg } | Spin::Declared { deg } => *deg,
        }
    }

    /// `auto` at 0°: what lmdc writes when nothing was declared or chosen.
    pub fn is_default(&self) -> bool {
        *self == Spin::default()
    }
}

/// A robot's arm (`arm = …`): its kinematics in the OPW convention (an
/// ortho-parallel base and a spherical wrist; docs/robots.md), so a reader
/// can solve the program's poses to axis angles as lmdc does, its limits
/// and the margins lmdc checked them with. Lengths mm, angles deg.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Arm {
    /// The catalogue's key (`kr16_2`); none for an arm declared by its
    /// parameters.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub model: Option<String>,
    /// OPW `a1, a2, b, c1, c2, c3, c4`, mm.
    pub opw: [f64; 7],
    /// The solver's angle at each axis's zero, deg.
    pub offsets: [f64; 6],
    /// Each axis's direction against the solver's, ±1.
    pub signs: [i8; 6],
    /// A1–A6's limits, deg.
    pub limits: [[f64; 2]; 6],
    /// A1–A6's top speeds, deg/s.
    pub speeds: [f64; 6],
    /// How far inside its limits every axis must stay, deg.
    pub margin: f64,
    /// How far from a singular configuration (A5 = 0, the arm stretched) a
    /// LIN must stay, deg.
    pub singularity: f64,
    /// The radii of its links as the collision checks take them — the
    /// upper arm, the forearm, the wrist — mm: the robot's own
    /// (`arm_links`), else the catalogue's
    /// ([`crate::target::arm::Model::links`]); `None`: an `opw(…)` arm
    /// without `arm_links`, whose links are not checked.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub links: Option<[f64; 3]>,
    /// The radius of its column (the foot up to A2, taking in A1's and
    /// A2's drives) as the collision checks take it, mm: the catalogue's
    /// ([`crate::target::arm::Model::column`]); `None`: an `opw(…)` arm,
    /// whose column is not known.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub column: Option<f64>,
}

/// The cell's shielding gas and powder feeder as a machine switches them
/// (`gas { … }` and `powder { … }` in a machine block). The motion plan places
/// the switching ([`crate::plan::Io`]); the back ends write it.
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Cell {
    /// The shielding gas valve.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gas: Option<Gas>,
    /// The powder feeder.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub powder: Option<Feeder>,
    /// G-code only: the line that switches digital output `{n}` on ...
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub output_on: String,
    /// ... and off ...
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub output_off: String,
    /// ... and the line that sets analog output `{n}` to `{v}` (a fraction of
    /// its full scale).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub analog_output: String,
}

impl Cell {
    /// Whether the program switches neither gas nor powder.
    pub fn is_none(&self) -> bool {
        self.gas.is_none() && self.powder.is_none()
    }
}

/// A shielding gas valve on a digital output.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Gas {
    /// The output that opens it (`$OUT[n]`; ABB: `do<n>` or a signal's
    /// name; G-code: the output line's `{n}`).
    pub output: Signal,
    /// How long the gas flows before the laser first starts, s.
    pub pre_flow: f64,
    /// How long it flows on after the laser last stops, s.
    pub post_flow: f64,
}

/// A powder feeder on a digital output, with its rate on an analog one where
/// the cell has it.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Feeder {
    /// The output that starts it.
    pub output: Signal,
    /// Time from starting it (or changing its rate) until the powder arrives
    /// at the nozzle, s.
    pub arrival: f64,
    /// The analog output that sets the feed rate, if any.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rate: Option<RateOutput>,
}

/// An analog output that sets the powder feed rate.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct RateOutput {
    /// `$ANOUT[n]`; ABB: `ao<n>` or a signal's name; G-code: the analog
    /// line's `{n}`.
    pub output: Signal,
    /// The feed rate at 1.0, g/min.
    pub full_scale: f64,
}

/// How a CNC's axes move the nozzle relative to the part.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq, Eq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum Kinematics {
    /// X Y Z only: the nozzle always points down (−Z).
    Xyz,
    /// Tilting head: A about X, then C about Z. Tool-tip (TCP) programming.
    HeadAc,
    /// Tilting head: B about Y, then C about Z. Tool-tip (TCP) programming.
    HeadBc,
    /// Tilting table: the part turns on C, which an A trunnion (about X)
    /// tilts; the nozzle stays vertical. Axes as [`Cnc::table`] declares.
    TableAc,
    /// Tilting table: the part turns on C, which a B trunnion (about Y)
    /// tilts; the nozzle stays vertical.
    TableBc,
}

impl Kinematics {
    /// Whether the part turns (a tilting table) rather than the head.
    pub fn is_table(self) -> bool {
        matches!(self, Kinematics::TableAc | Kinematics::TableBc)
    }

    /// The tilt axis's letter: `A` (about X) or `B` (about Y); `None` on
    /// [`Kinematics::Xyz`].
    pub fn tilt_letter(self) -> Option<char> {
        match self {
            Kinematics::HeadAc | Kinematics::TableAc => Some('A'),
            Kinematics::HeadBc | Kinematics::TableBc => Some('B'),
            Kinematics::Xyz => None,
        }
    }

    /// The word the language and the programs' headers use for it.
    pub fn word(self) -> &'static str {
        match self {
            Kinematics::Xyz => "xyz",
            Kinematics::HeadAc => "head_ac",
            Kinematics::HeadBc => "head_bc",
            Kinematics::TableAc => "table_ac",
            Kinematics::TableBc => "table_bc",
        }
    }
}

/// How a tilting table's axes sit on the machine, and what its program
/// writes (`docs/gcode.md`, "Tilting tables"). Every point is in machine
/// coordinates with the rotary axes at 0, as LinuxCNC's `xyzac-trt-kins`
/// and `xyzbc-trt-kins` take them (`x-rot-point` … `z-offset`).
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct RotaryTable {
    /// A point of the C axis (which is parallel to Z at tilt 0), mm.
    pub c_axis: [f64; 3],
    /// A point of the tilt axis (parallel to X for A, to Y for B), mm.
    pub tilt_axis: [f64; 3],
    /// Part coordinates and angles under the control's transform, or
    /// machine coordinates computed by lmdc.
    pub output: TableOutput,
}

/// What a tilting table's program writes.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum TableOutput {
    /// Part coordinates and the rotary angles, with the control's
    /// tool-tip/work-piece transform on (LinuxCNC trt kinematics, TRAORI,
    /// `#RTCP`).
    #[default]
    Tcp,
    /// Machine coordinates: lmdc turns every point by the table's angles
    /// about its axes; the control interpolates the axes linearly.
    Machine,
}

/// Dialect details of a CNC control, from a built-in profile and overrides.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Dialect {
    /// Profile name (`linuxcnc`, `fagor8070`, `sinumerik840d`, `m20`).
    pub profile: String,
    /// Line(s) that switch the laser on.
    pub laser_on: String,
    /// Line(s) that switch the laser off.
    pub laser_off: String,
    /// S word value per watt (S = power · s_per_watt).
    pub s_per_watt: f64,
    /// Decimals of the S word.
    pub s_decimals: usize,
    /// Lines at the start of the program (after the header comment).
    pub preamble: Vec<String>,
    /// Lines at the end of the program.
    pub postamble: Vec<String>,
    /// A dwell: the line with `{s}` where the seconds go.
    #[serde(default = "default_dwell")]
    pub dwell: String,
    /// Line that switches tool-tip control on for 5-axis moves (empty if none).
    pub tcp_on: String,
    /// Line that switches it off.
    pub tcp_off: String,
    /// Comment delimiters: `(`…`)` or `;`.
    pub comment: CommentStyle,
    /// Use `G00`/`G01` rather than `G0`/`G1`.
    pub padded_g: bool,
    /// File extension of the program, without the dot (`ngc`, `mpf`, `nc`).
    pub extension: String,
    /// Unit of the F word.
    #[serde(default)]
    pub feed: FeedUnit,
}

fn default_dwell() -> String {
    "G4 P{s}".into()
}

/// What the control's F word measures.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum FeedUnit {
    /// mm/min (G94 on most controls).
    #[default]
    MmPerMin,
    /// mm/s (the `m20` control: `F10` is 10 mm/s).
    MmPerS,
}

impl FeedUnit {
    /// F per mm/s of speed.
    pub fn per_mm_s(self) -> f64 {
        match self {
            FeedUnit::MmPerMin => 60.0,
            FeedUnit::MmPerS => 1.0,
        }
    }

    /// The unit as written in comments.
    pub fn text(self) -> &'static str {
        match self {
            FeedUnit::MmPerMin => "mm/min",
            FeedUnit::MmPerS => "mm/s",
        }
    }
}

/// How comments are written.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq, Eq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum CommentStyle {
    /// `(text)`
    Parens,
    /// `; text`
    Semicolon,
}

/// A CNC cell.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
#[serde(from = "wire::Cnc", into = "wire::Cnc")]
pub struct Cnc {
    /// Name, feed, clearance, cell and height sensor.
    pub common: MachineCommon,
    /// 3 or 5.
    pub axes: u8,
    /// Axis arrangement.
    pub kinematics: Kinematics,
    /// Control dialect.
    pub dialect: Dialect,
    /// Travel limits of X Y Z (mm) and the rotary axes (deg): `[min, max]`,
    /// in machine coordinates.
    pub limits: AxisLimits,
    /// Where the part sits on the machine.
    pub placement: Placement,
    /// The height (Z, part coordinates, mm) the first move lifts to before
    /// the other axes move and the program ends at (`None`: the part's
    /// highest point plus the clearance, [`crate::plan`]).
    pub safe_height: Option<f64>,
    /// A tilting table's axes and output (`None` unless the kinematics is
    /// a table's).
    pub table: Option<RotaryTable>,
    /// The rotary axes' top speed, deg/s (`None`: not checked).
    pub rotary_speed: Option<f64>,
}

impl Cnc {
    /// The kinematics its program is written for: a machine declared with
    /// fewer than five axes has no rotary axes, whatever its kinematics
    /// says.
    pub fn effective_kinematics(&self) -> Kinematics {
        if self.axes >= 5 {
            self.kinematics
        } else {
            Kinematics::Xyz
        }
    }
}

impl std::ops::Deref for Robot {
    type Target = MachineCommon;

    fn deref(&self) -> &MachineCommon {
        &self.common
    }
}

impl std::ops::DerefMut for Robot {
    fn deref_mut(&mut self) -> &mut MachineCommon {
        &mut self.common
    }
}

impl std::ops::Deref for Cnc {
    type Target = MachineCommon;

    fn deref(&self) -> &MachineCommon {
        &self.common
    }
}

impl std::ops::DerefMut for Cnc {
    fn deref_mut(&mut self) -> &mut MachineCommon {
        &mut self.common
    }
}

/// The machines as the IR's JSON writes them (docs/ir.md): each kind's
/// fields flat, the common ones where they always were, so the common part
/// changes no file.
mod wire {
    use super::{
        AxisLimits, Cell, Dialect, FrameRef, HeightSensor, Kinematics, MachineCommon, Placement,
        Ramp, RotaryTable, ToolAxis,
    };
    use serde::{Deserialize, Serialize};

    /// A robot's fields in the file's order.
    #[derive(Serialize, Deserialize)]
    #[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
    pub(super) struct Robot {
        /// Name from the source; the program is named after the part and this.
        name: String,
        /// The controller its program is written for (absent: KUKA).
        #[serde(default, skip_serializing_if = "super::Controller::is_kuka")]
        controller: super::Controller,
        /// Tool (TCP at the laser focus).
        tool: FrameRef,
        /// The tool's load, when declared (absent: the controller's
        /// `LOAD_DATA[n]`).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        load: Option<super::Load>,
        /// Base the part is programmed in.
        base: FrameRef,
        /// Which tool axis the beam travels along.
        beam: ToolAxis,
        /// `$OUT[n]` that switches the laser on (ABB: `do<n>`, or a
        /// signal's name).
        laser_out: super::Signal,
        /// `$ANOUT[n]` that sets the power (ABB: `ao<n>`, or a signal's
        /// name).
        power_out: super::Signal,
        /// Power at `$ANOUT = 1.0`, W.
        full_scale_power: f64,
        /// Highest path speed (a CNC's feed), mm/s.
        max_speed: f64,
        /// Axis angles of the home position, deg.
        home: [f64; 6],
        /// Most motion lines in one sub-program module.
        max_points_per_module: usize,
        /// The arm, when the robot declares it: its reach, axis limits,
        /// singularities and axis speeds are then checked on every move.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        arm: Option<super::Arm>,
        /// The tool's turn about the beam, declared or chosen, deg (absent:
        /// `auto` at 0°, the turn carried from normal to normal).
        #[serde(default, skip_serializing_if = "super::Spin::is_default")]
        spin: super::Spin,
        /// A two-axis positioner turning the part (E1, E2), with each
        /// layer's angles; `base` is then on its flange.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        positioner: Option<Box<super::Positioner>>,
        /// Distance the nozzle backs off along the normal between paths that do not
        /// join, mm.
        clearance: f64,
        /// The cell's shielding gas and powder feeder, if the program switches them.
        #[serde(default, skip_serializing_if = "Cell::is_none")]
        cell: Cell,
        /// The height sensor a closed loop reads, if the cell has one.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        height_sensor: Option<HeightSensor>,
        /// The path acceleration (and deceleration) the control plans with,
        /// mm/s² (absent: not declared, and the programmed speeds are taken as reached).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        acceleration: Option<f64>,
        /// How far before (and after) a corner the control may leave the path
        /// to round it, mm (absent: what the program sets by default).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        blending: Option<f64>,
        /// How the program starts and stops a bead.
        #[serde(default, skip_serializing_if = "Ramp::is_none")]
        ramp: Ramp,
        /// What it carries along the beam (absent: lmdc's typical nozzle).
        #[serde(default)]
        head: super::Head,
    }

    /// A CNC's fields in the file's order.
    #[derive(Serialize, Deserialize)]
    #[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
    pub(super) struct Cnc {
        /// Name from the source; the program is named after the part and this.
        name: String,
        /// 3 or 5.
        axes: u8,
        /// Axis arrangement.
        kinematics: Kinematics,
        /// Control dialect.
        dialect: Dialect,
        /// Travel limits of X Y Z (mm) and the rotary axes (deg): `[min, max]`,
        /// in machine coordinates.
        limits: AxisLimits,
        /// Where the part sits on the machine.
        #[serde(default)]
        placement: Placement,
        /// The height (Z, part coordinates, mm) the first move lifts to before
        /// the other axes move and the program ends at (absent: the part's
        /// highest point plus the clearance).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        safe_height: Option<f64>,
        /// A tilting table's axes and how the program is written (absent:
        /// the head tilts, or no rotary axes).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        table: Option<RotaryTable>,
        /// The rotary axes' top speed, deg/s (absent: not checked).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        rotary_speed: Option<f64>,
        /// Highest path speed (a CNC's feed), mm/s.
        max_speed: f64,
        /// Distance the nozzle backs off along the normal between paths that do not
        /// join, mm.
        clearance: f64,
        /// The cell's shielding gas and powder feeder, if the program switches them.
        #[serde(default, skip_serializing_if = "Cell::is_none")]
        cell: Cell,
        /// The height sensor a closed loop reads, if the cell has one.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        height_sensor: Option<HeightSensor>,
        /// The path acceleration (and deceleration) the control plans with,
        /// mm/s² (absent: not declared, and the programmed speeds are taken as reached).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        acceleration: Option<f64>,
        /// How far before (and after) a corner the control may leave the path
        /// to round it, mm (absent: what the program sets by default).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        blending: Option<f64>,
        /// How the program starts and stops a bead.
        #[serde(default, skip_serializing_if = "Ramp::is_none")]
        ramp: Ramp,
        /// What it carries along the beam (absent: lmdc's typical nozzle).
        #[serde(default)]
        head: super::Head,
    }

    impl From<Robot> for super::Robot {
        fn from(r: Robot) -> Self {
            super::Robot {
                controller: r.controller,
                common: MachineCommon {
                    name: r.name,
                    max_speed: r.max_speed,
                    clearance: r.clearance,
                    cell: r.cell,
                    height_sensor: r.height_sensor,
                    acceleration: r.acceleration,
                    blending: r.blending,
                    ramp: r.ramp,
                    head: r.head,
                },
                tool: r.tool,
                load: r.load,
                base: r.base,
                beam: r.beam,
                laser_out: r.laser_out,
                power_out: r.power_out,
                full_scale_power: r.full_scale_power,
                home: r.home,
                max_points_per_module: r.max_points_per_module,
                arm: r.arm.map(Box::new),
                spin: r.spin,
                positioner: r.positioner,
            }
        }
    }

    impl From<super::Robot> for Robot {
        fn from(r: super::Robot) -> Self {
            let c = r.common;
            Robot {
                name: c.name,
                controller: r.controller,
                tool: r.tool,
                load: r.load,
                base: r.base,
                beam: r.beam,
                laser_out: r.laser_out,
                power_out: r.power_out,
                full_scale_power: r.full_scale_power,
                max_speed: c.max_speed,
                home: r.home,
                max_points_per_module: r.max_points_per_module,
                arm: r.arm.map(|a| *a),
                spin: r.spin,
                positioner: r.positioner,
                clearance: c.clearance,
                cell: c.cell,
                height_sensor: c.height_sensor,
                acceleration: c.acceleration,
                blending: c.blending,
                ramp: c.ramp,
                head: c.head,
            }
        }
    }

    impl From<Cnc> for super::Cnc {
        fn from(c: Cnc) -> Self {
            super::Cnc {
                common: MachineCommon {
                    name: c.name,
                    max_speed: c.max_speed,
                    clearance: c.clearance,
                    cell: c.cell,
                    height_sensor: c.height_sensor,
                    acceleration: c.acceleration,
                    blending: c.blending,
                    ramp: c.ramp,
                    head: c.head,
                },
                axes: c.axes,
                kinematics: c.kinematics,
                dialect: c.dialect,
                limits: c.limits,
                placement: c.placement,
                safe_height: c.safe_height,
                table: c.table,
                rotary_speed: c.rotary_speed,
            }
        }
    }

    impl From<super::Cnc> for Cnc {
        fn from(c: super::Cnc) -> Self {
            let m = c.common;
            Cnc {
                name: m.name,
                axes: c.axes,
                kinematics: c.kinematics,
                dialect: c.dialect,
                limits: c.limits,
                placement: c.placement,
                safe_height: c.safe_height,
                table: c.table,
                rotary_speed: c.rotary_speed,
                max_speed: m.max_speed,
                clearance: m.clearance,
                cell: m.cell,
                height_sensor: m.height_sensor,
                acceleration: m.acceleration,
                blending: m.blending,
                ramp: m.ramp,
                head: m.head,
            }
        }
    }
}

/// Where a part sits on a CNC: the program is written in part coordinates
/// under a work offset whose value is the part's origin in machine
/// coordinates; the axis limits apply to program position + origin.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Placement {
    /// 1–6: `G54`–`G59` is selected at the start; 0: none is written (the
    /// control's active one is used).
    pub work_offset: u8,
    /// The part's origin in machine coordinates, mm (the work offset's value).
    pub origin: [f64; 3],
}

/// Axis travel limits.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct AxisLimits {
    /// mm
    pub x: [f64; 2],
    /// mm
    pub y: [f64; 2],
    /// mm
    pub z: [f64; 2],
    /// deg: the tilt axis (A or B)
    pub tilt: [f64; 2],
    /// deg: the C axis
    pub rotary: [f64; 2],
}

/// Where in the source the things the checks talk about were declared, so an
/// infeasible IR can be reported at the lines responsible. Not serialised (spans
/// would make every IR snapshot churn when text moves).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Origins {
    /// The bead model's height range.
    pub bead_height: Option<Span>,
    /// The bead model's speed range.
    pub bead_speed: Option<Span>,
    /// The bead's `tilt` where written, else its block.
    pub bead: Option<Span>,
    /// The laser power declaration.
    pub power: Option<Span>,
    /// The spine (bend radius).
    pub spine: Option<Span>,
    /// A variable-top solid's `top`.
    pub top: Option<Span>,
    /// The slicing block.
    pub slicing: Option<Span>,
    /// A segmented ring's declarations.
    pub ring: Option<RingOrigins>,
    /// Each machine's declaration, by index in [`Program::machines`].
    pub machines: Vec<MachineOrigin>,
    /// Where each fixture is placed (its `at`, else its name), by index in
    /// [`Program::fixtures`].
    pub fixtures: Vec<Span>,
}

/// Where a ring's declarations are, for the loop's and the transitions'
/// checks.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RingOrigins {
    /// The `ring` block.
    pub ring: Span,
    /// Its `transition`.
    pub transition: Span,
    /// The `control` block.
    pub control: Span,
    /// `kp = …`.
    pub kp: Span,
    /// `ki = …`.
    pub ki: Span,
    /// `clamp = …`.
    pub clamp: Span,
    /// `run = …` (the block when not written).
    pub run: Span,
    /// `layers = …` of the slicing block.
    pub layers: Span,
}

/// A machine's field that a check may point at: the IR's own name for a
/// place in the source, so the verifier needs none of the language's tables.
/// The checker records each field it reads under its key
/// (`sema::schema::machine::ORIGIN_KEYS`); a key is an enum, so a typo
/// cannot compile.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MachineField {
    /// The machine's name (`machine NAME { … }`): what a check points at
    /// when no field declares what it is about.
    Name,
    /// `max_speed`.
    MaxSpeed,
    /// `rotary_speed` (a CNC's rotary axes).
    RotarySpeed,
    /// `acceleration`.
    Acceleration,
    /// `blending`.
    Blending,
    /// `ramp`.
    Ramp,
    /// `axes` (a CNC's axis letters).
    Axes,
    /// `full_scale` (a robot's laser power output).
    FullScale,
    /// `safe_height`.
    SafeHeight,
    /// `feed_units`.
    FeedUnits,
    /// `s_decimals`.
    SDecimals,
    /// `s_per_watt`.
    SPerWatt,
    /// `table_output`.
    TableOutput,
    /// `dialect`.
    Dialect,
    /// `height_input`.
    HeightInput,
    /// `height_delay`.
    HeightDelay,
    /// A robot's `arm`.
    Arm,
    /// A robot's `controller`.
    Controller,
    /// A robot's `base`.
    Base,
    /// A robot's `tool`.
    Tool,
    /// A robot's `home`.
    Home,
    /// A robot's `singularity`.
    Singularity,
    /// One axis of a CNC's `limits { … }`: `X`, `Y`, `Z`, `A`, `B` or `C`.
    Limit(char),
    /// `gas { pre_flow }`.
    GasPreFlow,
    /// `powder { arrival }`.
    PowderArrival,
    /// `powder { full_scale }`.
    PowderFullScale,
    /// The `positioner { … }` block.
    Positioner,
    /// `positioner { keep }`.
    PositionerKeep,
    /// `positioner { home }`.
    PositionerHome,
    /// `positioner { tilt_limits }`.
    TiltLimits,
    /// `positioner { tilt_speed }`.
    TiltSpeed,
    /// `positioner { rotate_limits }`.
    RotateLimits,
    /// `positioner { rotate_speed }`.
    RotateSpeed,
    /// `positioner { faceplate }`.
    Faceplate,
    /// The `head { … }` block: what a collision points at.
    Head,
}

/// Where a machine and the fields the checks refer to were declared.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MachineOrigin {
    /// The whole `machine` block.
    pub block: Span,
    /// The fields given that a check may point at, each by its key.
    pub fields: Vec<(MachineField, Span)>,
}

impl MachineOrigin {
    /// A machine declared at `block`, its fields' spans unknown.
    pub fn new(block: Span) -> Self {
        MachineOrigin {
            block,
            fields: Vec::new(),
        }
    }

    /// Where `field` was given, if it was.
    pub fn written(&self, field: MachineField) -> Option<Span> {
        self.fields
            .iter()
            .find(|(f, _)| *f == field)
            .map(|(_, s)| *s)
    }

    /// Where `field` was given, else the block: what a diagnostic about
    /// the limit that field declares points at.
    pub fn at(&self, field: MachineField) -> Span {
        self.written(field).unwrap_or(self.block)
    }
}

impl Point {
    /// The speed the bead model holds for on the move to `next`: the speed
    /// at which the **deposit point** moves over the ground it covers,
    /// `speed·ground / |Δf|`, where `speed` is the nozzle's (the focus's:
    /// what the program writes), `Δf` the focus's move and `ground` the
    /// deposit points' move across the normal ([`Point::ground_to`]). The
    /// metal lands at the deposit point: where the nozzle is tilted and
    /// defocused, the focus runs on another curve than the deposit (a cone
    /// with the nozzle along its wall: the focus on a circle larger than
    /// the deposit's), and the deposit covers its own ground in the time
    /// the focus takes for its move. A bead map is measured on flat
    /// tracks, and what sets a layer's thickness is the metal laid per
    /// length across the build direction: a path that climbs along the
    /// normal (a variable layer following the planned top of the one
    /// below; a ring's nozzle climbing to the next segment's defocus) runs
    /// `√(1 + s²)` faster than the ground it covers. For a move in the
    /// layer's plane at one defocus and one normal — every planar path —
    /// this is the speed itself; so it is for a path's last point, which
    /// has no move.
    #[inline]
    pub fn speed_across(&self, next: Option<&Point>) -> f64 {
        let v = self.speed as f64;
        let Some(q) = next else { return v };
        let (a, b) = (self.focus(), q.focus());
        let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let len2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        if len2.is_nan() || len2 <= 0.0 {
            return v;
        }
        v * self.ground_to(next) / len2.sqrt()
    }

    /// How much the layer rises on the move to `next` by the deposit model
    /// `d` ([`crate::deposit`]): `A/pitch` at this point's speed across the
    /// normal and its own powder feed, mm. What lowering writes as `rise`
    /// and the verifier predicts.
    pub fn predicted_rise(&self, d: &Deposit, next: Option<&Point>) -> f64 {
        let v = Speed(self.speed_across(next));
        let powder = MassFlow(self.powder as f64 / 60.0);
        d.rise(v, Length(self.pitch as f64), Some(powder)).0
    }

    /// The ground the move to `next` covers, mm: its length across this
    /// point's normal (the deposit points' distance with its component
    /// along the nozzle removed). What a layer holds per unit of, whatever
    /// the slope its path climbs; 0 for a path's last point.
    pub fn ground_to(&self, next: Option<&Point>) -> f64 {
        let Some(q) = next else { return 0.0 };
        let d = [
            q.pos[0] - self.pos[0],
            q.pos[1] - self.pos[1],
            q.pos[2] - self.pos[2],
        ];
        let n = self.normal.map(f64::from);
        let along = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
        (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - along * along)
            .max(0.0)
            .sqrt()
    }

    /// Where the tool centre point goes: the laser focus, `defocus` along the
    /// normal from the deposit point. Both back ends program this point.
    pub fn focus(&self) -> [f64; 3] {
        let d = self.defocus as f64;
        [
            self.pos[0] + d * self.normal[0] as f64,
            self.pos[1] + d * self.normal[1] as f64,
            self.pos[2] + d * self.normal[2] as f64,
        ]
    }
}

impl Program {
    /// The ring and its loop, when the loop runs on the machine: the back
    /// ends then write it as a program that loops over one layer.
    pub fn loop_on_machine(&self) -> Option<(&Ring, &HeightLoop)> {
        let r = self.ring.as_ref()?;
        match &r.run {
            RingRun::OnMachine(l) => Some((r, l)),
            RingRun::Schedule { .. } => None,
        }
    }

    /// Number of points in all layers.
    pub fn point_count(&self) -> usize {
        self.layers
            .iter()
            .flat_map(|l| &l.paths)
            .map(|p| p.points.len())
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(pos: [f64; 3], speed: f32) -> Point {
        Point {
            pos,
            normal: [0.0, 0.0, 1.0],
            tangent: [1.0, 0.0, 0.0],
            layer_height: 1.0,
            speed,
            power: 1000.0,
            powder: 12.0,
            defocus: 0.0,
            laser_on: true,
            style: 0,
            pitch: 0.0,
            rise: 0.0,
        }
    }

    #[test]
    fn a_climbing_move_is_checked_at_the_speed_over_the_ground() {
        // A 3-4-5 climb: 5 mm of path per 4 mm of ground. At 10 mm/s along
        // the path the nozzle crosses the ground at 8 mm/s.
        let a = point([0.0, 0.0, 0.0], 10.0);
        let b = point([4.0, 0.0, 3.0], 10.0);
        assert!((a.speed_across(Some(&b)) - 8.0).abs() < 1e-6);
        // In the layer's plane (every planar and normal-sliced move) it is
        // the speed itself; so is a last point, which has no move.
        let c = point([4.0, 3.0, 0.0], 10.0);
        assert_eq!(a.speed_across(Some(&c)), 10.0);
        assert_eq!(a.speed_across(None), 10.0);
        // A tilted normal: the move in the plane normal to it is unchanged.
        let mut t = point([0.0, 0.0, 0.0], 6.0);
        let s = std::f32::consts::FRAC_1_SQRT_2;
        t.normal = [s, 0.0, s];
        let u = point([-1.0, 2.0, 1.0], 6.0);
        assert!((t.speed_across(Some(&u)) - 6.0).abs() < 1e-5);
    }

    #[test]
    fn a_tilted_defocused_nozzle_lays_at_the_deposit_points_speed() {
        // A cone's top layer with the nozzle along its wall (26.6° in) and
        // the focus 4 mm below: the deposit circles at 20.47 mm, the focus
        // at 20.47 + 4·sin 26.6° = 22.26 mm. The program runs the focus at
        // 5 mm/s; the deposit covers its smaller circle in the same time.
        let (r, tilt, step) = (20.47_f64, 26.565_f64.to_radians(), 0.01_f64);
        let at = |th: f64| {
            let mut p = point([r * th.cos(), r * th.sin(), 0.0], 5.0);
            // The build direction leans in, toward the axis.
            let n = [-tilt.sin() * th.cos(), -tilt.sin() * th.sin(), tilt.cos()];
            p.normal = n.map(|c| c as f32);
            p.defocus = -4.0;
            p
        };
        let (a, b) = (at(0.0), at(step));
        let focus_r = r + 4.0 * tilt.sin();
        assert!((focus_r - 22.26).abs() < 0.01);
        let want = 5.0 * r / focus_r;
        assert!(
            (a.speed_across(Some(&b)) - want).abs() < 1e-4,
            "{} vs {want}",
            a.speed_across(Some(&b))
        );
    }
}

#[cfg(test)]
mod size {
    /// The memory budget of a plan (`slice::MAX_TOTAL_POINTS`, the README's
    /// benchmark) counts 80 bytes a point.
    #[test]
    fn a_point_is_80_bytes() {
        assert_eq!(std::mem::size_of::<super::Point>(), 80);
    }
}
