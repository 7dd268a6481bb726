//! The plan report (`lmdc report`): per layer and in total, how long a
//! machine's program takes, how far it deposits and travels, how much
//! energy and powder it uses and how much metal the bead model says it lays,
//! against the design solid. Its lengths and times are the verifier's
//! summary of the machine's motion plan ([`crate::check::Summary`]), so
//! they are the program's, move by move. `docs/preview.md` writes out every
//! formula.
//!
//! From the verified plan alone ([`Report::of_plan`]) come lengths, times,
//! energy and powder; the bead model, the density and the design solid are
//! in the checked model, which [`Report::new`] reads too.

pub mod bead;
pub mod design;
pub mod text;
mod volume;

use crate::check::{Costs, VerifiedMachine};
use crate::sema::model::Model;
use bead::Beads;
pub use design::Design;
use serde::Serialize;

/// What one layer (or the whole plan) costs, and the metal it lays. Lengths
/// are the tool tip's path; volumes are over the ground (across the normal).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
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
pub struct Row {
    /// 1-based layer number.
    pub layer: usize,
    /// Its costs.
    #[serde(flatten)]
    pub tally: Tally,
}

/// The bead model the volumes come from.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BeadInfo {
    /// Bead width, mm.
    pub width_mm: f64,
    /// How the tracks are spaced, in words.
    pub spacing: String,
    /// The catch efficiency the model declares (mass balance), 0–1.
    pub declared_efficiency: Option<f64>,
}

/// The whole report of one machine's plan.
#[derive(Clone, Debug, PartialEq, Serialize)]
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
    /// Per layer, in build order.
    pub layers: Vec<Row>,
    /// The whole plan.
    pub total: Tally,
    /// Motion and dwell, s.
    pub time_s: f64,
    /// The bead model, when known.
    pub bead: Option<BeadInfo>,
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
}

impl Report {
    /// The report of `machine`'s plan, with the bead model, design solid and
    /// density of `model`; `density` (g/cm³) replaces or supplies the density.
    pub fn new(machine: VerifiedMachine<'_>, model: &Model, density: Option<f64>) -> Report {
        match Beads::of(model) {
            Some(beads) => Self::from_parts(machine, &beads, design::volume(model), density),
            None => {
                let mut r = Self::walk(machine, None);
                r.design = Some(design::volume(model));
                r.density_g_cm3 = density.filter(|d| d.is_finite() && *d > 0.0);
                r
            }
        }
    }

    /// The report of `machine`'s plan laid with `beads`, against `design`;
    /// `density` (g/cm³) replaces or supplies the bead model's.
    pub fn from_parts(
        machine: VerifiedMachine<'_>,
        beads: &Beads,
        design: Design,
        density: Option<f64>,
    ) -> Report {
        let mut r = Self::walk(machine, Some(beads));
        r.bead = Some(BeadInfo {
            width_mm: beads.width,
            spacing: beads.spacing.describe(beads.width),
            declared_efficiency: beads.efficiency(),
        });
        r.density_g_cm3 = density
            .filter(|d| d.is_finite() && *d > 0.0)
            .or(beads.density().map(|d| d * 1000.0));
        if let Some(rho) = r.density_g_cm3.map(|d| d / 1000.0) {
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
        r.design = Some(design);
        r
    }

    /// What the plan alone tells: lengths, times, energy, powder (no
    /// volumes). What the programs' headers summarise.
    pub fn of_plan(machine: VerifiedMachine<'_>) -> Report {
        Self::walk(machine, None)
    }

    fn walk(machine: VerifiedMachine<'_>, beads: Option<&Beads>) -> Report {
        let program = machine.ir();
        let summary = machine.summary();
        let volumes = beads.map(|b| volume::per_layer(program, b));
        let rows: Vec<Tally> = summary
            .layers
            .iter()
            .enumerate()
            .map(|(i, c)| {
                let (bead, stacked) = volumes
                    .as_ref()
                    .and_then(|v| v.get(i).copied())
                    .unwrap_or((0.0, 0.0));
                Tally {
                    costs: *c,
                    bead_volume_mm3: bead,
                    stacked_volume_mm3: stacked,
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
            density_g_cm3: None,
            bead_mass_g: None,
            bead_efficiency: None,
            design: None,
            design_mass_g: None,
            design_efficiency: None,
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
