//! The plant the simulation runs the loop against: what height a segment lays
//! at a given speed on a given layer.
//!
//! The model is the paper's own statement (§4): with defocus, power and feed
//! fixed, "the layer height is inversely proportional to the scan speed". So
//! segment `j` on layer `i` (from 0) lays
//!
//! ```text
//! h = g_j · (1 + δ·i) / v
//! ```
//!
//! `g_j` (mm²/s, a height times a speed) is the segment's deposition; `δ` a
//! slow drift per layer (the part heats up, the nozzle fouls) common to all
//! segments. [`Plant::calibrated`] sets `g_j = h_r·v_j` so that each segment's
//! Table-1 speed lays the target: Table 1 *is* the result of single-track
//! matching at those speeds (§4), so this is what the paper's cell was set up
//! to do. A mass balance (`A = η·ṁ/(ρ·v)` over the width) needs a catch
//! efficiency the paper does not give, and with one η for all segments it
//! contradicts Table 1 (`v·w` is 25 mm²/s on segment 1 and 38.5 on segment 4
//! at the same 6 g/min), so it would put the loop off target from layer 1 for
//! a reason the paper's cell did not have. [`Plant::scaled`] adds a
//! per-segment mismatch for what the calibration misses.

use super::invalid::{count, finite, positive, Invalid};
use crate::units::{Length, Speed};

/// A segment's deposition: the bead height times the scan speed, mm²/s. At a
/// speed `v` the segment lays `g / v`.
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
pub struct Deposition(pub f64);

impl Deposition {
    /// The height laid at `v`.
    pub fn height_at(self, v: Speed) -> Length {
        Length(self.0 / v.0)
    }
}

/// `h = g_j·(1 + δ·i)/v` per segment, deterministic.
#[derive(Clone, Debug, PartialEq)]
pub struct Plant {
    deposition: Vec<Deposition>,
    drift: f64,
}

impl Plant {
    /// One deposition per segment (each finite and positive) and the drift
    /// `δ` per layer (finite; negative is a plant that lays less and less).
    pub fn new(deposition: Vec<Deposition>, drift: f64) -> Result<Self, Invalid> {
        if deposition.is_empty() {
            return Err(Invalid::Empty { what: "plant" });
        }
        for g in &deposition {
            positive("plant deposition", g.0)?;
        }
        finite("plant drift", drift)?;
        Ok(Plant { deposition, drift })
    }

    /// The plant on which each of `speeds` lays exactly `target` on the first
    /// layer: `g_j = h_r·v_j`.
    pub fn calibrated(target: Length, speeds: &[Speed], drift: f64) -> Result<Self, Invalid> {
        let h = positive("target layer height", target.0)?;
        let g = speeds
            .iter()
            .map(|v| positive("calibration speed", v.0).map(|v| Deposition(h * v)))
            .collect::<Result<Vec<_>, _>>()?;
        Plant::new(g, drift)
    }

    /// The same plant with segment `j`'s deposition times `factors[j]` (each
    /// finite and positive): the part of the real cell the calibration missed.
    pub fn scaled(&self, factors: &[f64]) -> Result<Self, Invalid> {
        count("plant factors", factors.len(), self.deposition.len())?;
        let g = self
            .deposition
            .iter()
            .zip(factors)
            .map(|(g, &f)| positive("plant factor", f).map(|f| Deposition(g.0 * f)))
            .collect::<Result<Vec<_>, _>>()?;
        Plant::new(g, self.drift)
    }

    /// The number of segments.
    pub fn segments(&self) -> usize {
        self.deposition.len()
    }

    /// Segment `j`'s deposition before drift.
    pub fn deposition(&self, segment: usize) -> Option<Deposition> {
        self.deposition.get(segment).copied()
    }

    /// The drift `δ` per layer.
    pub fn drift(&self) -> f64 {
        self.drift
    }

    /// The height segment `segment` lays on layer `layer` (from 0) at `speed`.
    /// A segment that does not exist, a speed ≤ 0 or a drift that has taken
    /// the deposition to zero by this layer is [`Invalid`].
    pub fn height(&self, segment: usize, layer: usize, speed: Speed) -> Result<Length, Invalid> {
        let g = self.deposition(segment).ok_or(Invalid::NoSegment {
            segment,
            segments: self.deposition.len(),
        })?;
        let v = positive("simulated speed", speed.0)?;
        let g = positive(
            "plant deposition after drift",
            g.0 * (1.0 + self.drift * layer as f64),
        )?;
        Ok(Length(g / v))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn calibrated_plant_lays_the_target_at_the_start_speeds() {
        let p = Plant::calibrated(Length(0.23), &[Speed(4.0), Speed(13.0)], 0.001).unwrap();
        assert_eq!(p.deposition(0), Some(Deposition(0.92)));
        assert!((p.height(1, 0, Speed(13.0)).unwrap().0 - 0.23).abs() < 1e-15);
        // Twice as fast, half as high; 100 layers of 0.1 % drift: 10 % higher.
        assert!((p.height(0, 0, Speed(8.0)).unwrap().0 - 0.115).abs() < 1e-15);
        assert!((p.height(0, 100, Speed(4.0)).unwrap().0 - 0.253).abs() < 1e-12);
    }

    #[test]
    fn degenerate_plants_are_refused() {
        assert!(Plant::new(vec![], 0.0).is_err());
        assert!(Plant::new(vec![Deposition(-1.0)], 0.0).is_err());
        assert!(Plant::new(vec![Deposition(1.0)], f64::NAN).is_err());
        let p = Plant::new(vec![Deposition(1.0)], -0.01).unwrap();
        assert!(p.height(0, 99, Speed(1.0)).is_ok());
        assert!(p.height(0, 100, Speed(1.0)).is_err());
        assert!(p.height(1, 0, Speed(1.0)).is_err());
        assert!(p.height(0, 0, Speed(0.0)).is_err());
        assert!(p.scaled(&[1.0, 2.0]).is_err());
        assert!(p.scaled(&[0.0]).is_err());
    }
}
