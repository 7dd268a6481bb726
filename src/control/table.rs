//! The per-segment process table (the paper's Table 1) and the energy
//! density each row delivers.

use super::invalid::{finite, positive, Invalid};
use crate::units::{short, Length, Power, Speed};
use std::fmt;

/// One segment's process values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SegmentProcess {
    /// Focal plane to working plane, negative below (Table 1's "D").
    pub defocus: Length,
    /// Laser power.
    pub power: Power,
    /// The bead width the row is matched to lay, ≈ the spot diameter there.
    pub width: Length,
    /// The starting scan speed (horizontal).
    pub speed: Speed,
}

/// The energy a segment puts into each mm² of track, J/mm².
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
pub struct EnergyDensity(pub f64);

impl EnergyDensity {
    /// In J/mm².
    pub fn j_mm2(self) -> f64 {
        self.0
    }
}

impl fmt::Display for EnergyDensity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} J/mm^2", short(self.0))
    }
}

impl SegmentProcess {
    /// `E = P/(D·v)` (seed 004 eq. 10) with `D` the spot diameter, taken as
    /// the row's width: the paper sets the width with the spot (§2.2, Fig. 2)
    /// and gives no spot diameters, and Table 1's "D" is the defocus, which is
    /// not a diameter. Speeds are the horizontal (table) speed, which the
    /// transitions keep.
    pub fn energy_density(&self) -> EnergyDensity {
        EnergyDensity(self.power.watts() / (self.width.0 * self.speed.0))
    }
}

/// A checked table: at least one row; every value finite; width, speed and
/// power positive (the laser never goes off on a ring).
#[derive(Clone, Debug, PartialEq)]
pub struct SegmentTable {
    rows: Vec<SegmentProcess>,
}

impl SegmentTable {
    /// Checks every row.
    pub fn new(rows: Vec<SegmentProcess>) -> Result<Self, Invalid> {
        if rows.is_empty() {
            return Err(Invalid::Empty {
                what: "segment table",
            });
        }
        for r in &rows {
            finite("segment defocus", r.defocus.0)?;
            positive("segment power", r.power.0)?;
            positive("segment width", r.width.0)?;
            positive("segment speed", r.speed.0)?;
        }
        Ok(SegmentTable { rows })
    }

    /// The rows, segment 0 first.
    pub fn rows(&self) -> &[SegmentProcess] {
        &self.rows
    }

    /// The number of rows.
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    /// Never true (a table has at least one row); for clippy's sake.
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// The starting speeds, one per segment.
    pub fn speeds(&self) -> Vec<Speed> {
        self.rows.iter().map(|r| r.speed).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn energy_density_of_table_1s_ends() {
        let row = |p: f64, w: f64, v: f64| SegmentProcess {
            defocus: Length(-8.0),
            power: Power::from_watts(p),
            width: Length(w),
            speed: Speed(v),
        };
        // 1200 W / (6.25 mm · 4 mm/s) = 48 J/mm²; 650 / (2.5 · 13) = 20.
        assert!((row(1200.0, 6.25, 4.0).energy_density().0 - 48.0).abs() < 1e-9);
        assert!((row(650.0, 2.5, 13.0).energy_density().0 - 20.0).abs() < 1e-9);
        assert_eq!(
            row(650.0, 2.5, 13.0).energy_density().to_string(),
            "20 J/mm^2"
        );
        assert!(SegmentTable::new(vec![]).is_err());
        assert!(SegmentTable::new(vec![row(0.0, 2.5, 13.0)]).is_err());
        assert!(SegmentTable::new(vec![row(650.0, 2.5, f64::NAN)]).is_err());
    }
}
