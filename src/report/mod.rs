//! The plan report (`lmdc report`): per layer and in total, how long a
//! machine's program takes, how far it deposits and travels, how much
//! energy and powder it uses and how much metal the bead model says it lays,
//! against the design solid. Its lengths and times are the verifier's
//! summary of the machine's motion plan ([`crate::verify::Summary`]), so
//! they are the program's, move by move. `docs/preview.md` writes out every
//! formula.
//!
//! From the verified plan alone ([`Report::of_plan`]) come lengths, times,
//! energy and powder; the bead model, the density and the design solid are
//! in the checked model, which [`Report::new`] reads too.

pub mod coverage;
pub mod design;
pub mod finish;
pub mod heat;
pub mod text;
mod volume;

use crate::ir::{BeadModel, Program};
use crate::sema::model::Model;
use crate::verify::{Costs, VerifiedMachine};
pub use design::Design;
use serde::Serialize;

/// What one layer (or the whole plan) costs, and the metal it lays. Lengths
/// are the tool tip's path; volumes are over the ground (across the normal).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Tally {
    /// Lengths, times, energy and powder.
    #[serde(flatten)]
    pub costs: Costs,
    /// Volume the bead model lays, mm³ (0 when the model is not known).
    pub bead_volume_mm3: f64,
    /// Volume the layers stack up, height × track spacing × length, mm³.
    pub stacked_volume_mm3: f64,
}

impl Tally {
    /// Motion and dwell together, s.
    pub fn time_s(&self) -> f64 {
        self.costs.time_s()
    }

    fn add(&mut self, o: &Tally) {
        self.costs.add(&o.costs);
        self.bead_volume_mm3 += o.bead_volume_mm3;
        self.stacked_volume_mm3 += o.stacked_volume_mm3;
    }
}

impl std::ops::Deref for Tally {
    type Target = Costs;

    fn deref(&self) -> &Costs {
        &self.costs
    }
}

/// One layer's row.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Row {
    /// 1-based layer number.
    pub layer: usize,
    /// Its costs.
    #[serde(flatten)]
    pub tally: Tally,
}

/// The bead model the volumes come from (the plan's, as the IR carries it).
#[derive(Clone, Debug, PartialEq, Serialize)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct BeadInfo {
    /// Bead width, mm.
    pub width_mm: f64,
    /// What its heights were measured as, in words.
    pub measured_as: String,
    /// The strips the deposits fill (their pitch), in words.
    pub spacing: String,
    /// The catch efficiency the model declares (mass balance), 0–1.
    pub declared_efficiency: Option<f64>,
    /// The model with its numbers, as the IR states it.
    pub model: crate::ir::BeadModel,
    /// The speeds it was measured over (a table's, a fit's data), mm/s.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub measured: Option<[f64; 2]>,
    /// How it was fitted, when the program fitted it to data.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fit: Option<crate::ir::BeadFit>,
}

/// What the bead model lays against what the plan stacks, over the layers.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct DepositCheck {
    /// What the bead lays over what the plan stacks, the whole plan.
    pub bead_over_stacked: f64,
    /// The layer (1-based) whose share is farthest from 1, and its share.
    pub worst_layer: usize,
    /// Its share.
    pub worst_share: f64,
    /// The layers' mean errors (rise − planned height) added up after the
    /// last layer, mm.
    pub drift_mm: f64,
    /// The largest sum by size on the way, mm.
    pub worst_drift_mm: f64,
    /// The tolerance of each run of a layer (`rise_tolerance`), 0–1.
    pub rise_tolerance: f64,
    /// The bound on the sum (`max_drift`), mm.
    pub max_drift_mm: f64,
}

/// How the speeds the machine reaches were modelled: the deposit rule's
/// assumptions ([`crate::plan::profile`]). The report's times are the
/// programmed speeds' in any case.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Reached {
    /// The machine's declared path acceleration, mm/s² (`None`: the
    /// programmed speeds are taken as reached, and nothing was checked).
    pub acceleration_mm_s2: Option<f64>,
    /// The corner blending the profile assumes, mm.
    pub blending_mm: f64,
    /// Where that blending comes from.
    pub blending_from: &'static str,
    /// Whether runs of deposits start on lead-ins and end with lead-outs.
    pub leads: bool,
}

impl Reached {
    /// What the plan of `machine` assumes.
    fn of(machine: VerifiedMachine<'_>) -> Reached {
        let m = machine.machine();
        let (blending_mm, blending_from) = crate::target::blending(m);
        Reached {
            acceleration_mm_s2: m.common().acceleration,
            blending_mm,
            blending_from,
            leads: machine.plan().leads(),
        }
    }
}

/// The whole report of one machine's plan.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Report {
    /// Always `"report"`: the JSON stream of `--message-format json` carries
    /// diagnostics too.
    #[serde(rename = "type")]
    pub kind: &'static str,
    /// The part.
    pub part: String,
    /// The machine whose plan was followed.
    pub machine: String,
    /// Rapid moves are timed at this speed (the machine's `max_speed`), mm/s.
    pub rapid_mm_s: f64,
    /// How the speeds the machine reaches were modelled.
    pub reached: Reached,
    /// Per layer, in build order.
    pub layers: Vec<Row>,
    /// The whole plan.
    pub total: Tally,
    /// Motion and dwell, s.
    pub time_s: f64,
    /// The bead model, when known.
    pub bead: Option<BeadInfo>,
    /// What it lays against what the plan stacks, when known.
    pub deposit: Option<DepositCheck>,
    /// Density of the deposit, g/cm³, when known (a mass-balance bead model
    /// declares it; `--density` gives it).
    pub density_g_cm3: Option<f64>,
    /// Mass the bead model lays, g.
    pub bead_mass_g: Option<f64>,
    /// Share of the powder fed that the bead model's deposit holds: the catch
    /// efficiency it implies.
    pub bead_efficiency: Option<f64>,
    /// The design solid.
    pub design: Option<Design>,
    /// Design mass, g.
    pub design_mass_g: Option<f64>,
    /// Share of the powder fed the design solid needs caught.
    pub design_efficiency: Option<f64>,
    /// The plan's stacked volume over the design's: the strips its
    /// deposits fill times its layer heights, where strips that overlap
    /// count twice (so it says nothing of where the design is not filled:
    /// see `design_missing`).
    pub design_filled: Option<f64>,
    /// What of the design the deposits' strips cover, and what they leave
    /// (the band at the faces, hollows left on purpose, the rest), for an
    /// extrusion in flat layers.
    pub design_missing: Option<coverage::Missing>,
    /// A variable top's finished surface as the bead model predicts it,
    /// against the top (docs/repair.md, *The report*).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub finish: Option<finish::Finish>,
    /// The layers (from 1) in which a tilting head's or table's tilt goes
    /// over to its other side (the other of the axes' two solutions for a
    /// nozzle direction): a table only retracted, where a layer needs it
    /// within the stops; a head through vertical, C staying where it is
    /// (docs/ir.md, *Rotary axes with stops*). Empty where it keeps one
    /// side throughout.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub branch_changes: Vec<usize>,
    /// The closest each body the machine carries came to each thing of the
    /// cell, where the collision checks measured it (docs/collision.md,
    /// *Closest approaches*).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub approaches: Vec<crate::verify::approach::Approach>,
    /// A repair's scan moved onto its nominal by a best fit: the move found
    /// and how well it fits (docs/repair.md, *Registration*).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub registration: Option<crate::ir::Registration>,
    /// Each layer's predicted interpass and peak temperatures, and what
    /// keeping `max_interpass` cost (docs/thermal.md); absent without a
    /// `thermal` block.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub thermal: Option<heat::Heat>,
}

impl Report {
    /// The report of `machine`'s plan, against the design solid of `model`;
    /// `density` (g/cm³) replaces or supplies the density.
    pub fn new(machine: VerifiedMachine<'_>, model: &Model, density: Option<f64>) -> Report {
        // A fill along a tilted build direction (`direction = auto`) has
        // that direction as every layer's frame z.
        let along = machine
            .ir()
            .layers
            .first()
            .map(|l| l.frame.z)
            .filter(|&z| z != [0.0, 0.0, 1.0]);
        let mut r = Self::from_parts(machine, design::volume(model, along), density);
        if let (Some(v), Some(_)) = (r.design_volume(), &r.bead) {
            r.design_missing =
                coverage::missing(model, machine.ir()).map(|m| m.scaled(v, r.density_g_cm3));
        }
        r.finish = finish::of(machine.ir(), model);
        r
    }

    /// The report of `machine`'s plan against `design`; `density` (g/cm³)
    /// replaces or supplies the bead model's.
    pub fn from_parts(
        machine: VerifiedMachine<'_>,
        design: Design,
        density: Option<f64>,
    ) -> Report {
        let program = machine.ir();
        let mut r = Self::walk(machine);
        r.bead = program.bead.as_ref().map(|b| BeadInfo {
            width_mm: b.width,
            measured_as: b.basis.describe(),
            spacing: spacing(program, b.width),
            declared_efficiency: match b.model {
                BeadModel::MassBalance { efficiency, .. } => Some(efficiency),
                _ => None,
            },
            model: b.model.clone(),
            measured: b.measured,
            fit: b.fit.clone(),
        });
        let declared = program.bead.as_ref().and_then(|b| match b.model {
            BeadModel::MassBalance { density, .. } => Some(density),
            _ => None,
        });
        r.density_g_cm3 = density.filter(|d| d.is_finite() && *d > 0.0).or(declared);
        if let Some(rho) = r
            .density_g_cm3
            .map(|d| d / 1000.0)
            .filter(|_| r.bead.is_some())
        {
            let powder = r.total.powder_g;
            let share = |m: f64| (powder > 0.0).then(|| m / powder);
            let bead = rho * r.total.bead_volume_mm3;
            r.bead_mass_g = Some(bead);
            r.bead_efficiency = share(bead);
            if let Design::Known { volume_mm3, .. } = design {
                r.design_mass_g = Some(rho * volume_mm3);
                r.design_efficiency = share(rho * volume_mm3);
            }
        }
        if let (Design::Known { volume_mm3, .. }, Some(_)) = (&design, &r.bead) {
            r.design_filled = (*volume_mm3 > 0.0).then(|| r.total.stacked_volume_mm3 / volume_mm3);
        }
        r.design = Some(design);
        r
    }

    /// What the plan alone tells: lengths, times, energy, powder, and the
    /// metal its bead model lays. What the programs' headers summarise.
    pub fn of_plan(machine: VerifiedMachine<'_>) -> Report {
        Self::walk(machine)
    }

    fn walk(machine: VerifiedMachine<'_>) -> Report {
        let program = machine.ir();
        let summary = machine.summary();
        let laid = program.bead.as_ref().map(|_| volume::per_layer(program));
        let rows: Vec<Tally> = summary
            .layers
            .iter()
            .enumerate()
            .map(|(i, c)| {
                let l = laid
                    .as_ref()
                    .and_then(|v| v.get(i).copied())
                    .unwrap_or_default();
                Tally {
                    costs: *c,
                    bead_volume_mm3: l.bead,
                    stacked_volume_mm3: l.stacked,
                }
            })
            .collect();
        let mut total = Tally::default();
        for r in &rows {
            total.add(r);
        }
        Report {
            kind: "report",
            part: program.part.clone(),
            machine: machine.machine().name().to_string(),
            rapid_mm_s: summary.rapid_mm_s,
            reached: Reached::of(machine),
            layers: rows
                .iter()
                .enumerate()
                .map(|(i, t)| Row {
                    layer: i + 1,
                    tally: *t,
                })
                .collect(),
            total,
            time_s: total.time_s(),
            bead: None,
            deposit: laid.map(|l| check(program, &l, &total)),
            density_g_cm3: None,
            bead_mass_g: None,
            bead_efficiency: None,
            design: None,
            design_mass_g: None,
            design_efficiency: None,
            design_filled: None,
            design_missing: None,
            finish: None,
            branch_changes: summary.branch_changes.iter().map(|l| l + 1).collect(),
            approaches: summary.approaches.clone(),
            registration: program
                .fixtures
                .iter()
                .find(|f| f.is_scan())
                .and_then(|f| f.registration.clone()),
            thermal: heat::Heat::of(program),
        }
    }

    /// The design volume, if known, mm³.
    pub fn design_volume(&self) -> Option<f64> {
        match &self.design {
            Some(Design::Known { volume_mm3, .. }) => Some(*volume_mm3),
            _ => None,
        }
    }
}

/// The layers' shares and their errors added up.
fn check(program: &Program, laid: &[volume::Laid], total: &Tally) -> DepositCheck {
    let share = |bead: f64, stacked: f64| if stacked > 0.0 { bead / stacked } else { 1.0 };
    let (mut worst_layer, mut worst_share) = (1, 1.0f64);
    let (mut drift, mut worst_drift) = (0.0f64, 0.0f64);
    for (i, l) in laid.iter().enumerate() {
        let s = share(l.bead, l.stacked);
        if (s - 1.0).abs() > (worst_share - 1.0).abs() {
            (worst_layer, worst_share) = (i + 1, s);
        }
        drift += l.mean_error;
        if drift.abs() > worst_drift.abs() {
            worst_drift = drift;
        }
    }
    DepositCheck {
        bead_over_stacked: share(total.bead_volume_mm3, total.stacked_volume_mm3),
        worst_layer,
        worst_share,
        drift_mm: drift,
        worst_drift_mm: worst_drift,
        rise_tolerance: program.limits.rise_tolerance,
        max_drift_mm: program.limits.max_drift,
    }
}

/// The strips the deposits fill, in words: one bead wide, tracks one
/// distance apart, or a range of them.
fn spacing(program: &Program, width: f64) -> String {
    let (lo, hi) = program
        .layers
        .iter()
        .flat_map(|l| &l.paths)
        .flat_map(|p| &p.points)
        .filter(|q| q.laser_on && q.pitch > 0.0)
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), q| {
            (lo.min(q.pitch as f64), hi.max(q.pitch as f64))
        });
    let t = |x: f64| crate::numbers::trimmed(x, 3);
    if lo > hi {
        "no deposit".into()
    } else if hi - lo <= 1e-6 * hi && (hi - width).abs() <= 1e-6 * width {
        format!("one bead wide ({} mm)", t(width))
    } else if hi - lo <= 1e-6 * hi {
        format!("tracks {} mm apart", t(hi))
    } else {
        format!("tracks {} .. {} mm apart", t(lo), t(hi))
    }
}
