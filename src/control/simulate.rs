//! The loop run offline against a [`Plant`]: what `lmdc simulate` prints.
//!
//! Every layer lays every segment at the speed the loop chose, the plant
//! says how high it came out, and [`Controller::update`] — the same law the
//! programs will run — chooses the next layer's speed.

use super::invalid::{count, Invalid};
use super::law::Controller;
use super::plant::Plant;
use crate::units::{Length, Speed};
use std::fmt;
use std::num::NonZeroUsize;

/// One segment on one layer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// The layer, from 0.
    pub layer: usize,
    /// The segment, from 0.
    pub segment: usize,
    /// The speed it was laid at.
    pub speed: Speed,
    /// The height it came out (what the sensor reads).
    pub height: Length,
    /// The segment's height after this layer: the sum of its layer heights.
    pub total: Length,
}

/// A segment's total after the last layer, against the target `N·h_r`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Total {
    /// The segment, from 0.
    pub segment: usize,
    /// Its built height.
    pub built: Length,
    /// `N·h_r`.
    pub target: Length,
    /// The speed of its last layer.
    pub final_speed: Speed,
}

impl Total {
    /// `built − target`, the sign of the paper's Table 2.
    pub fn error(&self) -> Length {
        Length(self.built.0 - self.target.0)
    }
}

/// A finished simulation: `layers × segments` samples, layer by layer.
#[derive(Clone, Debug, PartialEq)]
pub struct Simulation {
    segments: usize,
    layers: usize,
    target: Length,
    samples: Vec<Sample>,
}

/// Runs `controller` for `layers` layers against `plant`, segment `j`
/// starting at `start[j]` (which must lie inside the clamp).
pub fn simulate(
    controller: &Controller,
    plant: &Plant,
    start: &[Speed],
    layers: NonZeroUsize,
) -> Result<Simulation, Invalid> {
    let n = plant.segments();
    count("start speeds", start.len(), n)?;
    let mut states = start
        .iter()
        .map(|&v| controller.start("start speed", v))
        .collect::<Result<Vec<_>, _>>()?;
    let mut totals = vec![0.0; n];
    let mut samples = Vec::with_capacity(layers.get().saturating_mul(n));
    for layer in 0..layers.get() {
        for (segment, (state, total)) in states.iter_mut().zip(&mut totals).enumerate() {
            let height = plant.height(segment, layer, state.speed)?;
            *total += height.0;
            samples.push(Sample {
                layer,
                segment,
                speed: state.speed,
                height,
                total: Length(*total),
            });
            *state = controller.update(*state, height)?;
        }
    }
    Ok(Simulation {
        segments: n,
        layers: layers.get(),
        target: controller.target(),
        samples,
    })
}

impl Simulation {
    /// Every sample, layer by layer, segments in order within a layer.
    pub fn samples(&self) -> &[Sample] {
        &self.samples
    }

    /// The sample of `segment` on `layer` (both from 0).
    pub fn at(&self, layer: usize, segment: usize) -> Option<&Sample> {
        if segment >= self.segments {
            return None;
        }
        self.samples
            .get(layer.checked_mul(self.segments)? + segment)
    }

    /// The number of layers.
    pub fn layers(&self) -> usize {
        self.layers
    }

    /// Each segment's total after the last layer, against `N·h_r`.
    pub fn totals(&self) -> Vec<Total> {
        let target = Length(self.target.0 * self.layers as f64);
        let last = self.layers.saturating_sub(1) * self.segments;
        self.samples[last..]
            .iter()
            .map(|s| Total {
                segment: s.segment,
                built: s.total,
                target,
                final_speed: s.speed,
            })
            .collect()
    }

    /// CSV for plotting: a header, then one row per sample with layers and
    /// segments counted from 1 (as the programs' comments count them), lengths
    /// in mm and speeds in mm/s.
    pub fn write_csv(&self, out: &mut impl fmt::Write) -> fmt::Result {
        writeln!(out, "layer,segment,speed_mm_s,height_mm,total_mm,target_mm")?;
        for s in &self.samples {
            writeln!(
                out,
                "{},{},{:.6},{:.6},{:.6},{:.6}",
                s.layer + 1,
                s.segment + 1,
                s.speed.0,
                s.height.0,
                s.total.0,
                self.target.0 * (s.layer + 1) as f64
            )?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::super::gain::SpeedPerLength;
    use super::super::law::Clamp;
    use super::*;

    fn controller(kp: f64, ki: f64) -> Controller {
        Controller::new(
            SpeedPerLength(kp),
            SpeedPerLength(ki),
            Length(0.25),
            Clamp::new(Speed(1.0), Speed(20.0)).unwrap(),
        )
        .unwrap()
    }

    #[test]
    fn two_layers_by_hand() {
        // g = 2.5 mm²/s at 10 mm/s lays 0.25 mm; at 8 mm/s 0.3125 mm.
        let plant = Plant::new(vec![super::super::plant::Deposition(2.5)], 0.0).unwrap();
        let c = controller(-2.0, -0.5);
        let sim = simulate(&c, &plant, &[Speed(8.0)], NonZeroUsize::new(2).unwrap()).unwrap();
        let first = sim.at(0, 0).unwrap();
        assert_eq!(first.speed, Speed(8.0));
        assert!((first.height.0 - 0.3125).abs() < 1e-15);
        // e = −0.0625, Σ = −0.0625: v = 8 + 0.125 + 0.03125 = 8.15625.
        let second = sim.at(1, 0).unwrap();
        assert!((second.speed.0 - 8.15625).abs() < 1e-12);
        assert!((second.total.0 - (0.3125 + 2.5 / 8.15625)).abs() < 1e-12);
        let t = sim.totals()[0];
        assert!((t.target.0 - 0.5).abs() < 1e-15);
        assert!((t.error().0 - (second.total.0 - 0.5)).abs() < 1e-15);
        let mut csv = String::new();
        sim.write_csv(&mut csv).unwrap();
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(
            lines[0],
            "layer,segment,speed_mm_s,height_mm,total_mm,target_mm"
        );
        assert_eq!(lines[1], "1,1,8.000000,0.312500,0.312500,0.250000");
        assert_eq!(lines.len(), 3);
        assert!(sim.at(2, 0).is_none() && sim.at(0, 1).is_none());
    }

    #[test]
    fn mismatched_inputs_are_refused() {
        let plant = Plant::new(vec![super::super::plant::Deposition(2.5)], 0.0).unwrap();
        let c = controller(-2.0, -0.5);
        let one = NonZeroUsize::MIN;
        assert!(simulate(&c, &plant, &[Speed(8.0), Speed(8.0)], one).is_err());
        assert!(simulate(&c, &plant, &[Speed(30.0)], one).is_err());
    }
}
