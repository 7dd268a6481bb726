//! Bead physics: the height model (how a bead's height follows the scan
//! speed, and the inverse the slicer needs: the speed that lays a given
//! height), the bead's cross-section, and how planar layers rise. The checker
//! builds a [`HeightModel`] from a `bead` block; the slicer and the checks use
//! these functions. Nothing here knows about the language.

pub mod fit;
pub mod sheet;
mod table;

pub use table::{Table, TableFault, Widths};

use crate::units::{Density, Length, MassFlow, Speed};

/// How bead height follows scan speed.
#[derive(Clone, Debug, PartialEq)]
pub enum HeightModel {
    /// `H = slope · v + intercept`: the linear bead map, fitted to measured
    /// beads.
    Linear {
        /// mm per mm/s (a time).
        slope: f64,
        /// mm.
        intercept: Length,
    },
    /// Deposited area from the powder caught: `A = η·ṁ/(ρ·v)`; the bead is a
    /// circular segment of chord `width` and that area.
    MassBalance {
        /// Powder feed.
        feed: MassFlow,
        /// Catch efficiency η (0–1).
        efficiency: f64,
        /// Density of the deposited metal.
        density: Density,
    },
    /// A bead measured at one process point: this height at this speed (seed
    /// 001's 0.7 mm at 6 mm/s).
    Measured {
        /// Bead height.
        height: Length,
        /// The scan speed it was measured at.
        speed: Speed,
    },
    /// A power law through a reference point, `H = height·(v/speed)^exponent`:
    /// fitted in log space to coupons whose height falls off ever more slowly
    /// with speed.
    Power {
        /// The height at `speed`.
        height: Length,
        /// The reference speed.
        speed: Speed,
        /// How the height scales with the speed (< 0).
        exponent: f64,
    },
    /// Heights measured at several speeds, joined by straight lines
    /// (piecewise linear, falling with the speed).
    Table(Table),
}

/// Area of a circular segment of chord `w` and height `h` (mm, mm²): the
/// cross-section of a bead (seed 001 eq. 6). Valid for `0 ≤ h < w`; heights
/// above `w/2` are major segments.
pub fn segment_area(w: f64, h: f64) -> f64 {
    if h <= 0.0 {
        return 0.0;
    }
    let half = w / 2.0;
    let r = (half * half + h * h) / (2.0 * h);
    let theta = 2.0 * half.atan2(r - h);
    0.5 * r * r * theta - half * (r - h)
}

/// The height of the circular segment of chord `w` whose area is `area`, found by
/// bisection (the area grows monotonically with the height). Capped at `w`.
pub fn segment_height(w: f64, area: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, w);
    if area <= 0.0 {
        return 0.0;
    }
    if segment_area(w, hi) <= area {
        return hi;
    }
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if segment_area(w, mid) < area {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo < 1e-12 {
            break;
        }
    }
    0.5 * (lo + hi)
}

impl HeightModel {
    /// Bead height at scan speed `v` for a bead of width `w`.
    pub fn height_at(&self, v: Speed, w: Length) -> Length {
        match *self {
            HeightModel::Power {
                height,
                speed,
                exponent,
            } => Length(height.0 * (v.0 / speed.0).powf(exponent)),
            HeightModel::Table(ref t) => Length(t.height_at(v.0)),
            HeightModel::Linear { slope, intercept } => Length(slope * v.0 + intercept.0),
            HeightModel::MassBalance {
                feed,
                efficiency,
                density,
            } => {
                let area = efficiency * feed.0 / (density.0 * v.0);
                Length(segment_height(w.0, area))
            }
            HeightModel::Measured { height, .. } => height,
        }
    }

    /// The scan speed that lays a bead of height `h` and width `w`.
    pub fn speed_for(&self, h: Length, w: Length) -> Speed {
        match *self {
            HeightModel::Power {
                height,
                speed,
                exponent,
            } => Speed(speed.0 * (h.0 / height.0).powf(1.0 / exponent)),
            HeightModel::Table(ref t) => Speed(t.speed_for(h.0)),
            HeightModel::Linear { slope, intercept } => Speed((h.0 - intercept.0) / slope),
            HeightModel::MassBalance {
                feed,
                efficiency,
                density,
            } => Speed(efficiency * feed.0 / (density.0 * segment_area(w.0, h.0))),
            HeightModel::Measured { speed, .. } => speed,
        }
    }

    /// The model's name as the language writes it: `linear`, `table`, ….
    pub fn kind(&self) -> &'static str {
        match self {
            HeightModel::Linear { .. } => "linear",
            HeightModel::MassBalance { .. } => "mass_balance",
            HeightModel::Measured { .. } => "measured",
            HeightModel::Power { .. } => "power",
            HeightModel::Table(_) => "table",
        }
    }
}

/// Tracks closer than this share of the bead width pile up instead of
/// levelling (overlap above 70 %; seed 001 levels at about 27–33 %).
pub const MIN_OFFSET_RATIO: f64 = 0.3;

/// How much a planar layer rises: a single track adds its cross-section `A` spread
/// over its width (`A/w`); tracks laid side by side at offset `d` add `A` every
/// `d` (`A/d`) — seed 001's eq. 6 and the reason its fixed lift of `A/w`
/// undershot on overlapped layers. `offset` is `None` for a single track.
pub fn planar_lift(w: Length, h: Length, offset: Option<Length>) -> Length {
    let a = segment_area(w.0, h.0);
    Length(a / offset.map_or(w.0, |d| d.0))
}

/// The offset between tracks that keeps an overlapped layer flat: each track
/// fills the strip `d` wide at the bead's height, `d = A/h`.
pub fn flat_top_offset(w: Length, h: Length) -> Length {
    Length(segment_area(w.0, h.0) / h.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn semicircle_area_and_inverse() {
        // h = w/2 is a half disc.
        let a = segment_area(6.0, 3.0);
        assert!((a - std::f64::consts::PI * 9.0 / 2.0).abs() < 1e-9);
        assert!((segment_height(6.0, a) - 3.0).abs() < 1e-9);
    }

    #[test]
    fn flat_segment_matches_parabola() {
        // For h ≪ w the segment is close to a parabola: A ≈ 2/3·w·h.
        let a = segment_area(6.0, 0.01);
        assert!((a / (2.0 / 3.0 * 6.0 * 0.01) - 1.0).abs() < 1e-4);
    }

    #[test]
    fn seed_003_linear_map() {
        let m = HeightModel::Linear {
            slope: -0.135,
            intercept: Length(1.82),
        };
        let w = Length(3.0);
        assert!((m.height_at(Speed(4.0), w).0 - 1.28).abs() < 1e-9);
        assert!((m.height_at(Speed(8.7), w).0 - 0.6455).abs() < 1e-9);
        assert!((m.speed_for(Length(1.28), w).0 - 4.0).abs() < 1e-9);
    }

    #[test]
    fn a_power_law_passes_its_reference_point_and_inverts() {
        let m = HeightModel::Power {
            height: Length(1.0),
            speed: Speed(6.0),
            exponent: -0.5,
        };
        let w = Length(2.4);
        assert!((m.height_at(Speed(6.0), w).0 - 1.0).abs() < 1e-12);
        // Four times the speed, half the height.
        assert!((m.height_at(Speed(24.0), w).0 - 0.5).abs() < 1e-12);
        assert!((m.speed_for(Length(0.5), w).0 - 24.0).abs() < 1e-9);
    }

    #[test]
    fn seed_001_lifts() {
        // DOMAIN.md: w 2.2 mm, h 0.7 mm → A ≈ 1.1056 mm², A/w ≈ 0.5025 mm,
        // A/d ≈ 0.691 mm at d = 1.6 mm, flat top at d = A/h ≈ 1.58 mm.
        let (w, h) = (Length(2.2), Length(0.7));
        assert!((segment_area(2.2, 0.7) - 1.1056).abs() < 5e-4);
        assert!((planar_lift(w, h, None).0 - 0.5025).abs() < 5e-4);
        assert!((planar_lift(w, h, Some(Length(1.6))).0 - 0.691).abs() < 5e-4);
        assert!((flat_top_offset(w, h).0 - 1.58).abs() < 5e-3);
    }
}
