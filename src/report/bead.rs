//! The metal a deposit move lays, two ways (the physics is written out in
//! `docs/preview.md`, *What the report computes*):
//!
//! - **bead**: the bead model's cross-section at the move's speed across the
//!   normal, `A(v)`: a circular segment of chord `w` and the model's height
//!   at `v` (seed 001 eq. 6); for a mass-balance model directly
//!   `η·ṁ/(ρ·v)` with the move's own powder feed (a style may change it).
//!   This is the metal the bead model predicts.
//! - **stacked**: what the plan assumes each layer adds, its local height
//!   times the spacing of its tracks, `h·s`: a flat layer of tracks `d` apart
//!   rises by `A/d`, so each track lays `h·d`; a single track or a wall one
//!   bead wide lays `h·w`; seed 003's balanced tracks are spaced so that
//!   `h·C = A`. Where the two differ the layers will not rise as planned.
//!
//! Both are per length *across the normal*: what a layer holds per unit of
//! ground, whatever the slope its path climbs (docs/ir.md, *Speeds*).

use crate::bead::{segment_area, HeightModel};
use crate::sema::model::{Model, Plan};

/// How far apart a layer's tracks sit, as far as the volume it adds goes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Spacing {
    /// One track wide (a wall, a single-track layer): the bead's width.
    Width,
    /// Overlapped tracks this far apart, mm.
    Offset(f64),
    /// Seed 003's balanced layout: each pair of tracks is spaced so that the
    /// layer's thickness times the spacing holds the beads, `h·C = A`.
    Balanced,
}

impl Spacing {
    /// Words for the report.
    pub fn describe(self, width: f64) -> String {
        match self {
            Spacing::Width => format!("one bead wide ({} mm)", trim(width)),
            Spacing::Offset(d) => format!("tracks {} mm apart", trim(d)),
            Spacing::Balanced => "balanced tracks (h·C = A)".into(),
        }
    }
}

fn trim(x: f64) -> String {
    crate::numbers::trimmed(x, 3)
}

/// The bead model and track spacing of a part: what turns a move into a
/// volume.
#[derive(Clone, Copy, Debug)]
pub struct Beads {
    /// Bead width, mm.
    pub width: f64,
    /// The bead model.
    pub model: HeightModel,
    /// How far apart the tracks sit.
    pub spacing: Spacing,
}

impl Beads {
    /// The beads of a checked model; `None` for a solid without a bead
    /// model (a ring: its segment table gives the widths).
    pub fn of(model: &Model) -> Option<Beads> {
        let bead = model.bead.as_ref()?;
        let spacing = match &model.plan {
            Plan::Duct { .. } => Spacing::Width,
            Plan::Block { slicing, .. } if slicing.overlapped() => {
                Spacing::Offset(slicing.offset.0)
            }
            Plan::Variable { slicing, .. } => match slicing.offset {
                Some((d, _)) => Spacing::Offset(d.0),
                None => Spacing::Balanced,
            },
            // A single-track layer, and any plan lmdc learns later: one bead
            // wide is what a track without neighbours lays.
            _ => Spacing::Width,
        };
        Some(Beads {
            width: bead.width.0,
            model: bead.model,
            spacing,
        })
    }

    /// Cross-section (mm²) the bead model lays at speed `v` (mm/s, across the
    /// normal) with powder feed `powder` (g/min).
    pub fn area(&self, v: f64, powder: f64) -> f64 {
        if v <= 0.0 || !v.is_finite() {
            return 0.0;
        }
        match self.model {
            HeightModel::MassBalance {
                efficiency,
                density,
                ..
            } => efficiency * (powder / 60.0) / (density.0 * v),
            m => segment_area(
                self.width,
                m.height_at(crate::units::Speed(v), crate::units::Length(self.width))
                    .0,
            ),
        }
    }

    /// Cross-section (mm²) the plan stacks where the layer is `h` thick and
    /// the bead model lays `bead` (mm²); `single`: the layer is one track
    /// (a track without neighbours spreads over its own width whatever the
    /// spacing of wider layers).
    pub fn stacked(&self, h: f64, bead: f64, single: bool) -> f64 {
        if single {
            return h * self.width;
        }
        match self.spacing {
            Spacing::Width => h * self.width,
            Spacing::Offset(d) => h * d,
            Spacing::Balanced => bead,
        }
    }

    /// The density the bead model declares (mass balance), g/mm³.
    pub fn density(&self) -> Option<f64> {
        match self.model {
            HeightModel::MassBalance { density, .. } => Some(density.0),
            _ => None,
        }
    }

    /// The catch efficiency the bead model declares (mass balance), 0–1.
    pub fn efficiency(&self) -> Option<f64> {
        match self.model {
            HeightModel::MassBalance { efficiency, .. } => Some(efficiency),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::units::{Density, Length, MassFlow, Speed};

    #[test]
    fn mass_balance_lays_the_powder_caught() {
        // 45.9 g/min at 35 % into 7.9 g/cm³ at 8 mm/s: A = η·ṁ/(ρ·v).
        let b = Beads {
            width: 6.0,
            model: HeightModel::MassBalance {
                feed: MassFlow(45.9 / 60.0),
                efficiency: 0.35,
                density: Density(7.9e-3),
            },
            spacing: Spacing::Width,
        };
        let a = b.area(8.0, 45.9);
        assert!((a - 0.35 * 0.765 / (7.9e-3 * 8.0)).abs() < 1e-9, "{a}");
        // The model's own height at that speed has the same segment area.
        let h = b.model.height_at(Speed(8.0), Length(6.0)).0;
        assert!((segment_area(6.0, h) - a).abs() < 1e-6);
        assert!((b.stacked(h, a, false) - 6.0 * h).abs() < 1e-12);
    }

    #[test]
    fn a_measured_bead_lays_its_segment_and_tracks_their_spacing() {
        let b = Beads {
            width: 2.2,
            model: HeightModel::Measured {
                height: Length(0.7),
                speed: Speed(6.0),
            },
            spacing: Spacing::Offset(1.6),
        };
        assert!((b.area(6.0, 10.0) - segment_area(2.2, 0.7)).abs() < 1e-12);
        assert!((b.stacked(0.691, 1.1, false) - 0.691 * 1.6).abs() < 1e-12);
        assert_eq!(b.area(0.0, 10.0), 0.0);
        assert_eq!(b.density(), None);
    }
}
