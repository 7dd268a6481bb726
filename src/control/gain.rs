//! The controller's gains as a typed quantity: a change of scan speed per mm
//! of height error.
//!
//! The paper prints `kP = −0.00300 s⁻¹`. Dimensionally (mm/s)/mm *is* s⁻¹, so
//! the dimension cannot tell the two readings apart: read as (mm/s)/mm the
//! gains move a speed by a few µm/s a layer and need ~10⁵ layers to settle;
//! read as (m/s)/mm — KUKA's `$VEL.CP` is in m/s — they are −3 (mm/s)/mm and
//! reproduce the paper's Table 2 (`docs/design/seed004.md`). So a gain is its
//! own type, always shown as a speed per length, and the language makes the
//! user write both units (`kp = -3 mm/s/mm`, `kp = -0.003 m/s/mm`).

use crate::units::{short, Dim, Length, Quantity, Speed};
use std::fmt;

/// A change of scan speed per unit of height error, the unit of the PI gains.
/// The value is in (mm/s)/mm, the crate's canonical mm and s (so s⁻¹ in
/// canonical units, like `Hz`).
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd, Default)]
pub struct SpeedPerLength(pub f64);

impl SpeedPerLength {
    /// The dimension: length/time per length, i.e. 1/time.
    pub const DIM: Dim = Dim::new(0, 0, -1, 0);

    /// From (mm/s)/mm.
    pub fn from_mm_s_per_mm(v: f64) -> Self {
        SpeedPerLength(v)
    }

    /// From (m/s)/mm: the reading of the paper's gains that reproduces its
    /// Table 2 (`-0.003` → −3 (mm/s)/mm).
    pub fn from_m_s_per_mm(v: f64) -> Self {
        SpeedPerLength(v * 1000.0)
    }

    /// In (mm/s)/mm.
    pub fn mm_s_per_mm(self) -> f64 {
        self.0
    }

    /// In (m/s)/mm, the unit a KUKA program would hold it in next to `$VEL.CP`.
    pub fn m_s_per_mm(self) -> f64 {
        self.0 / 1000.0
    }

    /// From a checked quantity (`-3 mm/s/mm` evaluates to −3 s⁻¹), if the
    /// dimension matches. Which *spelling* the user wrote (a speed over a
    /// length, not `Hz`) is the checker's business; this only checks the
    /// dimension.
    pub fn from_quantity(q: Quantity) -> Option<Self> {
        (q.dim == Self::DIM).then_some(SpeedPerLength(q.value))
    }

    /// The speed change this gain asks for a height error `e`.
    pub fn of(self, e: Length) -> Speed {
        Speed(self.0 * e.0)
    }

    /// The gain times a plain factor (a hint's "at most ×0.7 of these").
    pub fn scaled(self, factor: f64) -> Self {
        SpeedPerLength(self.0 * factor)
    }
}

impl fmt::Display for SpeedPerLength {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} (mm/s)/mm", short(self.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::units::parse_unit;

    #[test]
    fn the_language_spellings_of_the_papers_gain() {
        // `-0.003 m/s/mm` read left to right is (m/s)/mm: −3 (mm/s)/mm.
        let (f, d) = parse_unit("m/s/mm").unwrap();
        let kp = SpeedPerLength::from_quantity(Quantity {
            value: -0.003 * f,
            dim: d,
        })
        .unwrap();
        assert!((kp.mm_s_per_mm() + 3.0).abs() < 1e-12);
        assert_eq!(kp, SpeedPerLength::from_m_s_per_mm(-0.003));
        let (f, d) = parse_unit("mm/s/mm").unwrap();
        assert_eq!((f, d), (1.0, SpeedPerLength::DIM));
        // A speed is not a gain.
        assert!(SpeedPerLength::from_quantity(Quantity {
            value: 1.0,
            dim: Dim::SPEED
        })
        .is_none());
        assert_eq!(kp.to_string(), "-3 (mm/s)/mm");
        assert!((kp.m_s_per_mm() + 0.003).abs() < 1e-15);
    }

    #[test]
    fn a_gain_turns_a_height_error_into_a_speed_change() {
        // 0.05 mm too low at −3 (mm/s)/mm: 0.15 mm/s slower.
        let dv = SpeedPerLength(-3.0).of(Length(0.05));
        assert!((dv.0 + 0.15).abs() < 1e-12);
    }
}
