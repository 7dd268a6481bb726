//! The deposit model: the metal a move lays and how it stacks, in one place
//! for the slicers, the verifier and the report.
//!
//! **What a move lays.** At scan speed `v` (across the build direction: the
//! speed over the ground a layer covers) a bead lays a cross-section `A(v)`
//! per unit of length. A bead model says how high a bead is at `v`; what
//! that height was *measured as* decides the area ([`Basis`]):
//!
//! - a single track on a flat plate (the seeds' maps, the default): `A` is
//!   the circular segment of the bead's width `w` and that height;
//! - the rise per layer of a wall one bead wide: `A = h·w`;
//! - the rise per layer of a filled layer of tracks `d₀` apart: `A = h·d₀`;
//! - `mass_balance`: `A = η·ṁ/(ρ·v)` directly — mass conservation, no
//!   choice to make — with the move's own powder feed `ṁ`.
//!
//! **How it stacks.** Every deposit fills a strip of the layer, its *pitch*
//! `p`: a wall one bead wide fills its width (`p = w`), tracks laid side by
//! side `d` apart fill `d` each (`p = d`), the balanced tracks of a variable
//! layer the mean of their spacings to the neighbours. A layer then rises
//! by `A(v)/p` where the move passes: seed 001's `A/w` for a single track
//! and `A/d` for overlapped ones, the same rule for walls and ducts. A
//! slicer picks each point's speed so that this rise is the layer height it
//! plans ([`Deposit::speed_for`]); the verifier predicts it from the speed
//! the plan gives ([`Deposit::rise`]); the report adds it up. Edge effects
//! (a wall's rounded shoulders, the outermost track of a filled layer) are
//! not modelled: a track at the edge of a layer is taken to fill its pitch
//! like one inside.

use crate::bead::{segment_area, segment_height, HeightModel, Widths};
use crate::units::{Length, MassFlow, Speed};
use serde::{Deserialize, Serialize};

/// How far a run's predicted rise may be from its planned layer height by
/// default, a share of it (`rise_tolerance`): about the scatter of a bead
/// calibration, and what writing a speed to 0.1 mm/s rounds at 7–10 mm/s.
pub const RISE_TOLERANCE: f64 = 0.03;

/// The lean from the nozzle's axis past which a layer leaning out over the
/// one below is warned when the slicing sets no `max_overhang`, deg: the
/// rule of thumb of powder DED (and of FDM), where the melt pool starts to
/// run off the edge without a tilted nozzle or support (`lmd::overhang`).
pub const DEFAULT_OVERHANG: f64 = 45.0;

/// The step across the nozzle, in bead widths, past which a layer is warned
/// by default whatever its lean: a bead half off the one below (thick layers
/// reach it below 45°). `lmd::stacking` refuses ¾ of a width.
pub const DEFAULT_OVERHANG_STEP: f64 = 0.5;

/// How far the layers' mean errors may add up by default, mm (`max_drift`):
/// a standoff off by more than about half a millimetre changes how much
/// powder the melt pool catches.
pub const MAX_DRIFT: f64 = 0.5;

/// What a bead model's heights were measured as.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Basis {
    /// A single track on a flat plate: the bead's own height. Its
    /// cross-section is the circular segment of its width and that height.
    #[default]
    Track,
    /// The rise per layer of a wall one bead wide.
    Wall,
    /// The rise per layer of a filled layer of tracks `offset` apart (mm).
    Layer {
        /// The tracks' offset in the calibration layers, mm.
        offset: f64,
    },
}

impl Basis {
    /// The words the report and the messages use.
    pub fn describe(self) -> String {
        match self {
            Basis::Track => "measured as single tracks".into(),
            Basis::Wall => "measured as the rise of a wall one bead wide".into(),
            Basis::Layer { offset } => format!(
                "measured as the rise of filled layers of tracks {} mm apart",
                crate::numbers::trimmed(offset, 3)
            ),
        }
    }
}

/// A bead model as the deposit sees it: the height map, the bead's width and
/// what the heights were measured as.
#[derive(Clone, Debug, PartialEq)]
pub struct Deposit {
    /// How the measured height follows the speed.
    pub model: HeightModel,
    /// The bead's width: the strip a wall one bead wide fills, and the
    /// chord of its cross-section where no widths were measured.
    pub width: Length,
    /// What the heights are.
    pub basis: Basis,
    /// The widths measured at each speed, where the calibration has them:
    /// the bead's cross-section at a speed is then that speed's width's
    /// (the strips the plan fills stay `width` wide).
    pub widths: Option<Widths>,
}

impl Deposit {
    /// The model fed `powder`: a mass balance lays in proportion to the
    /// feed, so a plan fed otherwise than the model was fitted at picks its
    /// speeds for the feed it runs (the checker warns that the fit may not
    /// hold there, `lmd::powder-mismatch`). Other models do not know the
    /// feed.
    pub fn fed(mut self, powder: MassFlow) -> Deposit {
        if let HeightModel::MassBalance { ref mut feed, .. } = self.model {
            *feed = powder;
        }
        self
    }

    /// The cross-section laid per mm at speed `v` (across the build
    /// direction), mm²; `powder` is the move's own feed where a
    /// mass-balance model should use it instead of the one it declares.
    pub fn area(&self, v: Speed, powder: Option<MassFlow>) -> f64 {
        let w = self.width_at(v).0;
        match self.model {
            HeightModel::MassBalance {
                feed,
                efficiency,
                density,
            } => efficiency * powder.unwrap_or(feed).0 / (density.0 * v.0),
            ref m => {
                let h = m.height_at(v, Length(w)).0;
                match self.basis {
                    Basis::Track => segment_area(w, h),
                    Basis::Wall => h * w,
                    Basis::Layer { offset } => h * offset,
                }
            }
        }
    }

    /// The bead's width at `v`: the width measured there, or the one
    /// declared.
    pub fn width_at(&self, v: Speed) -> Length {
        match &self.widths {
            Some(w) => Length(w.at(v.0)),
            None => self.width,
        }
    }

    /// How much a layer rises where a move at `v` fills a strip `pitch`
    /// wide: `A(v)/p`.
    pub fn rise(&self, v: Speed, pitch: Length, powder: Option<MassFlow>) -> Length {
        Length(self.area(v, powder) / pitch.0)
    }

    /// The speed at which a move filling a strip `pitch` wide raises its
    /// layer by `rise` (with the model's own powder feed). A `measured`
    /// model knows one speed: it is that speed whatever the rise.
    pub fn speed_for(&self, rise: Length, pitch: Length) -> Speed {
        let a = rise.0 * pitch.0;
        let w = self.width;
        match self.model {
            HeightModel::MassBalance {
                feed,
                efficiency,
                density,
            } => Speed(efficiency * feed.0 / (density.0 * a)),
            HeightModel::Measured { speed, .. } => speed,
            _ if self.widths.is_some() => self.speed_laying(a),
            ref m => {
                let h = match self.basis {
                    Basis::Track => segment_height(w.0, a),
                    Basis::Wall => a / w.0,
                    Basis::Layer { offset } => a / offset,
                };
                m.speed_for(Length(h), w)
            }
        }
    }

    /// The speed at which the bead lays the cross-section `a` where its
    /// width follows the speed: the area falls with the speed (a faster
    /// scan lays less metal), so bisection on the speed finds it.
    fn speed_laying(&self, a: f64) -> Speed {
        let area = |v: f64| self.area(Speed(v), None);
        // A bracket around the answer: widen until the area crosses `a`.
        let (mut lo, mut hi) = (1.0, 2.0);
        for _ in 0..200 {
            if area(lo) >= a {
                break;
            }
            lo /= 2.0;
        }
        for _ in 0..200 {
            if area(hi) <= a {
                break;
            }
            hi *= 2.0;
        }
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if area(mid) > a {
                lo = mid;
            } else {
                hi = mid;
            }
            if hi - lo < 1e-12 * hi {
                break;
            }
        }
        Speed(0.5 * (lo + hi))
    }

    /// The rises a strip `pitch` wide gets over the speeds `speeds` (slowest,
    /// fastest): `[rise at the fastest, rise at the slowest]`, since a faster
    /// scan lays less.
    pub fn rises(&self, speeds: [Speed; 2], pitch: Length) -> [Length; 2] {
        [
            self.rise(speeds[1], pitch, None),
            self.rise(speeds[0], pitch, None),
        ]
    }

    /// The height of the bead itself at `v` (a single track's, whatever the
    /// model was measured as: from its area where it was not measured on one
    /// track). What variable layers' balanced layout spaces its tracks by.
    pub fn bead_height(&self, v: Speed) -> Length {
        match (&self.model, self.basis) {
            (HeightModel::MassBalance { .. }, _) | (_, Basis::Wall | Basis::Layer { .. }) => {
                Length(segment_height(self.width_at(v).0, self.area(v, None)))
            }
            (m, Basis::Track) => m.height_at(v, self.width_at(v)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::units::Density;

    fn linear(basis: Basis) -> Deposit {
        Deposit {
            model: HeightModel::Linear {
                slope: -0.135,
                intercept: Length(1.82),
            },
            width: Length(2.4),
            basis,
            widths: None,
        }
    }

    #[test]
    fn a_single_track_lays_its_segment_and_a_wall_rises_by_it_over_the_width() {
        // Seed 001: w 2.2, h 0.7 → A ≈ 1.1056 mm², A/w ≈ 0.5025, A/1.6 ≈ 0.691.
        let d = Deposit {
            model: HeightModel::Measured {
                height: Length(0.7),
                speed: Speed(6.0),
            },
            width: Length(2.2),
            basis: Basis::Track,
            widths: None,
        };
        let a = d.area(Speed(6.0), None);
        assert!((a - segment_area(2.2, 0.7)).abs() < 1e-12);
        assert!((d.rise(Speed(6.0), Length(2.2), None).0 - 0.5025).abs() < 5e-4);
        assert!((d.rise(Speed(6.0), Length(1.6), None).0 - 0.691).abs() < 5e-4);
        // A measured bead knows one speed.
        assert_eq!(d.speed_for(Length(0.5), Length(2.2)), Speed(6.0));
    }

    #[test]
    fn speed_for_inverts_rise_for_every_basis() {
        for basis in [Basis::Track, Basis::Wall, Basis::Layer { offset: 1.9 }] {
            let d = linear(basis);
            for v in [4.0, 5.5, 8.7] {
                for p in [2.4, 1.8] {
                    let r = d.rise(Speed(v), Length(p), None);
                    let back = d.speed_for(r, Length(p));
                    assert!((back.0 - v).abs() < 1e-9, "{basis:?} {v} {p}: {back:?}");
                }
            }
        }
    }

    #[test]
    fn what_the_heights_were_measured_as_decides_the_area() {
        // Seed 003's map at 6 mm/s: H = 1.01 mm.
        let h = 1.82 - 0.135 * 6.0;
        let v = Speed(6.0);
        assert!((linear(Basis::Track).area(v, None) - segment_area(2.4, h)).abs() < 1e-12);
        // Measured on a wall, the height is the rise: A = h·w, rise over w = h.
        let wall = linear(Basis::Wall);
        assert!((wall.area(v, None) - h * 2.4).abs() < 1e-12);
        assert!((wall.rise(v, Length(2.4), None).0 - h).abs() < 1e-12);
        // Measured on layers 2 mm apart: tracks 2 mm apart rise h.
        let layer = linear(Basis::Layer { offset: 2.0 });
        assert!((layer.rise(v, Length(2.0), None).0 - h).abs() < 1e-12);
        // A single-track map on a wall rises A/w: between 2/3 of the bead
        // (a flat segment, a parabola) and π/4 of it (a half disc).
        let track = linear(Basis::Track).rise(v, Length(2.4), None).0;
        assert!((track - segment_area(2.4, h) / 2.4).abs() < 1e-12);
        let share = track / h;
        assert!(
            share > 2.0 / 3.0 && share < std::f64::consts::FRAC_PI_4,
            "{share}"
        );
    }

    #[test]
    fn mass_balance_is_mass_conservation_with_the_moves_own_powder() {
        // The duct: 45.9 g/min, 35 %, 7.9 g/cm³ at 8 mm/s on a 6 mm wall.
        let d = Deposit {
            model: HeightModel::MassBalance {
                feed: MassFlow(45.9 / 60.0),
                efficiency: 0.35,
                density: Density(7.9e-3),
            },
            width: Length(6.0),
            basis: Basis::Track,
            widths: None,
        };
        let feed_mm3_s = 45.9 / 60.0 / 7.9e-3; // g/s over g/mm³
        let a = 0.35 * feed_mm3_s / 8.0;
        assert!((d.area(Speed(8.0), None) - a).abs() < 1e-9 * a);
        assert!((d.rise(Speed(8.0), Length(6.0), None).0 - a / 6.0).abs() < 1e-9);
        // Twice the powder, twice the metal.
        let twice = d.area(Speed(8.0), Some(MassFlow(91.8 / 60.0)));
        assert!((twice / a - 2.0).abs() < 1e-12);
        // The rises over 7–10 mm/s: ratio 10/7 exactly.
        let [lo, hi] = d.rises([Speed(7.0), Speed(10.0)], Length(6.0));
        assert!((hi.0 / lo.0 - 10.0 / 7.0).abs() < 1e-12);
        assert!((d.speed_for(lo, Length(6.0)).0 - 10.0).abs() < 1e-9);
    }
}
