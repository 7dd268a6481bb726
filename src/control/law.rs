//! The control law, in one place: [`LAW`] lists its steps in the order they
//! run, [`Controller::update`] runs them for the simulation, and the code
//! generators write the same steps, in the same order, into KRL and G-code
//! (each matches on [`Step`], so a step added here cannot be left out there).
//!
//! Per segment `j`, from layer `i` to `i + 1` (seed 004 eq. 6 and eq. 3):
//!
//! ```text
//! e_i     = h_r − h_i                     height error of the layer just built
//! Σ_i     = Σ_{m≤i} e_m                   = N·h_r − built height: the total error
//! v_{i+1} = clamp(v_i + kP·e_i + kI·Σ_i, v_min, v_max)
//! z_{i+1} = z_i + h_i                     the next working plane (eq. 3)
//! ```
//!
//! `Σ` is not clamped (no anti-windup): it *is* the segment's total-height
//! error, and making the total converge is the point of the integral term.

use super::gain::SpeedPerLength;
use super::invalid::{finite, positive, Invalid};
use crate::units::{Length, Speed};

/// The speeds the loop may command, `low < high`, both finite and positive.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Clamp {
    low: Speed,
    high: Speed,
}

impl Clamp {
    /// Checks `0 < low < high`.
    pub fn new(low: Speed, high: Speed) -> Result<Self, Invalid> {
        let lo = positive("clamp's low speed", low.0)?;
        let hi = positive("clamp's high speed", high.0)?;
        if lo >= hi {
            return Err(Invalid::Reversed {
                what: "speed clamp",
                low: lo,
                high: hi,
            });
        }
        Ok(Clamp { low, high })
    }

    /// `v_min`.
    pub fn low(self) -> Speed {
        self.low
    }

    /// `v_max`: the top speed, at which the verifier checks the transitions.
    pub fn high(self) -> Speed {
        self.high
    }

    /// `v` limited to `low ..= high`.
    pub fn apply(self, v: Speed) -> Speed {
        Speed(v.0.clamp(self.low.0, self.high.0))
    }

    /// Whether `v` lies in `low ..= high`.
    pub fn contains(self, v: Speed) -> bool {
        v.0 >= self.low.0 && v.0 <= self.high.0
    }
}

/// One step of the law. The programs hold the measured height `h` and the
/// error `e` in locals, and `Σ`, `v` and `z` per segment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Step {
    /// `e = h_r − h`: the error of the layer just measured.
    Error,
    /// `Σ = Σ + e`.
    Sum,
    /// `v = v + kP·e + kI·Σ`.
    Speed,
    /// `v = v_min` where `v < v_min`.
    ClampLow,
    /// `v = v_max` where `v > v_max`.
    ClampHigh,
    /// `z = z + h`: the segment's working plane rises by what it laid.
    Plane,
}

/// The law's steps, in the order every copy of it runs them.
pub const LAW: [Step; 6] = [
    Step::Error,
    Step::Sum,
    Step::Speed,
    Step::ClampLow,
    Step::ClampHigh,
    Step::Plane,
];

/// What the loop remembers for one segment between layers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoopState {
    /// The speed the segment is laid at on this layer.
    pub speed: Speed,
    /// `Σ e` over the layers built so far: the target total minus the built
    /// total.
    pub error_sum: Length,
    /// The segment's working plane: the sum of the heights it laid (0 on the
    /// substrate).
    pub plane: Length,
}

/// A declared PI loop on layer height: gains, target height per layer, clamp.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Controller {
    kp: SpeedPerLength,
    ki: SpeedPerLength,
    target: Length,
    clamp: Clamp,
}

impl Controller {
    /// Checks that the gains are finite and the target positive. Signs and
    /// stability are *not* checked here: a wrong sign is a legal loop that
    /// [`analyse`](super::analysis::analyse) reports, with numbers.
    pub fn new(
        kp: SpeedPerLength,
        ki: SpeedPerLength,
        target: Length,
        clamp: Clamp,
    ) -> Result<Self, Invalid> {
        finite("kp", kp.0)?;
        finite("ki", ki.0)?;
        positive("target layer height", target.0)?;
        Ok(Controller {
            kp,
            ki,
            target,
            clamp,
        })
    }

    /// The proportional gain `kP`.
    pub fn kp(&self) -> SpeedPerLength {
        self.kp
    }

    /// The integral gain `kI`.
    pub fn ki(&self) -> SpeedPerLength {
        self.ki
    }

    /// The target height per layer `h_r`.
    pub fn target(&self) -> Length {
        self.target
    }

    /// The speed clamp.
    pub fn clamp(&self) -> Clamp {
        self.clamp
    }

    /// The same loop with both gains multiplied by `factor` (for hints).
    pub fn with_gains_scaled(&self, factor: f64) -> Controller {
        Controller {
            kp: self.kp.scaled(factor),
            ki: self.ki.scaled(factor),
            ..*self
        }
    }

    /// The state of a segment before its first layer: its start speed (which
    /// must lie inside the clamp, or the first update would jump) and no error.
    pub fn start(&self, what: &'static str, speed: Speed) -> Result<LoopState, Invalid> {
        let v = finite(what, speed.0)?;
        if !self.clamp.contains(speed) {
            return Err(Invalid::OutsideClamp {
                what,
                value: v,
                low: self.clamp.low.0,
                high: self.clamp.high.0,
            });
        }
        Ok(LoopState {
            speed,
            error_sum: Length(0.0),
            plane: Length(0.0),
        })
    }

    /// The law: the state for the next layer after this layer's segment came
    /// out `measured` high. A non-finite reading is refused rather than
    /// turned into a NaN speed.
    pub fn update(&self, state: LoopState, measured: Length) -> Result<LoopState, Invalid> {
        let h = finite("measured height", measured.0)?;
        let mut e = 0.0;
        let LoopState {
            speed: Speed(mut v),
            error_sum: Length(mut sum),
            plane: Length(mut z),
        } = state;
        for step in LAW {
            match step {
                Step::Error => e = self.target.0 - h,
                Step::Sum => sum += e,
                Step::Speed => v += self.kp.of(Length(e)).0 + self.ki.of(Length(sum)).0,
                Step::ClampLow => v = v.max(self.clamp.low.0),
                Step::ClampHigh => v = v.min(self.clamp.high.0),
                Step::Plane => z += h,
            }
        }
        Ok(LoopState {
            speed: Speed(v),
            error_sum: Length(sum),
            plane: Length(z),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn paper() -> Controller {
        Controller::new(
            SpeedPerLength::from_m_s_per_mm(-0.003),
            SpeedPerLength::from_m_s_per_mm(-0.00035),
            Length(0.23),
            Clamp::new(Speed(1.9), Speed(20.0)).unwrap(),
        )
        .unwrap()
    }

    #[test]
    fn one_step_of_eq_6() {
        let c = paper();
        let s = c.start("start", Speed(13.0)).unwrap();
        // 0.03 mm too high: e = −0.03, Σ = −0.03,
        // v = 13 + (−3)(−0.03) + (−0.35)(−0.03) = 13.1005.
        let s = c.update(s, Length(0.26)).unwrap();
        assert!((s.error_sum.0 + 0.03).abs() < 1e-12);
        assert!((s.speed.0 - 13.1005).abs() < 1e-12);
        // Back on target: e = 0, the integral alone keeps pushing: +0.0105.
        let s = c.update(s, Length(0.23)).unwrap();
        assert!((s.speed.0 - 13.111).abs() < 1e-12);
        // The working plane rose by both layers.
        assert!((s.plane.0 - 0.49).abs() < 1e-12);
    }

    #[test]
    fn the_clamp_holds_and_the_sum_does_not_wind_down() {
        let c = paper();
        let s = c.start("start", Speed(2.0)).unwrap();
        // 1 mm too low: 2 + (−3)(1) + (−0.35)(1) < 1.9.
        let s = c.update(s, Length(-0.77)).unwrap();
        assert_eq!(s.speed, Speed(1.9));
        assert!((s.error_sum.0 - 1.0).abs() < 1e-12);
        assert!(c.update(s, Length(f64::NAN)).is_err());
    }

    #[test]
    fn degenerate_loops_are_refused() {
        assert!(Clamp::new(Speed(20.0), Speed(1.9)).is_err());
        assert!(Clamp::new(Speed(0.0), Speed(1.9)).is_err());
        assert!(Clamp::new(Speed(2.0), Speed(2.0)).is_err());
        let clamp = Clamp::new(Speed(1.9), Speed(20.0)).unwrap();
        let k = SpeedPerLength(-3.0);
        assert!(Controller::new(SpeedPerLength(f64::NAN), k, Length(0.23), clamp).is_err());
        assert!(Controller::new(k, k, Length(0.0), clamp).is_err());
        assert!(matches!(
            paper().start("start", Speed(25.0)),
            Err(Invalid::OutsideClamp { .. })
        ));
    }
}
