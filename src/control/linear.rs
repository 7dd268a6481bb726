//! The loop linearised at one operating speed, and what its two eigenvalues
//! say: stable or not, how fast it settles.
//!
//! With `h = g/v`, `dh/dv = −g/v² = −h/v`, so near an operating point where
//! the segment lays the target (`h = h_r` at speed `v`) a speed change `δv`
//! changes the error by `δe = (h_r/v)·δv`. Substituting the law
//! `δv_{i+1} = δv_i + kP·e_i + kI·Σ_i` gives, with the dimensionless loop
//! gains `p = kP·h_r/v` and `q = kI·h_r/v`,
//!
//! ```text
//! e_{i+1} = (1 + p)·e_i + q·Σ_i
//! Σ_{i+1} = Σ_i + e_{i+1} = (1 + p)·e_i + (1 + q)·Σ_i
//! ```
//!
//! so the state `(e, Σ)` evolves by `A = [[1+p, q], [1+p, 1+q]]` with trace
//! `2 + p + q` and determinant `1 + p`. The loop is stable iff the spectral
//! radius `ρ(A) < 1`; by Jury's test that is `−2 < p < 0`, `q < 0` and
//! `2p + q > −4`. An error's envelope shrinks like `ρⁱ`, so it falls to 2 % of
//! its start after `ln 0.02 / ln ρ` layers: the settling time. (The constant in
//! front of `ρⁱ`, large when the eigenvalues nearly coincide, is left out: it
//! moves the count by a few layers, not by the orders of magnitude the check is
//! for.)

use super::gain::SpeedPerLength;
use crate::units::{Length, Speed};

/// The fraction of a starting error the settling time counts down to.
pub const SETTLED: f64 = 0.02;

/// A complex number, for the eigenvalues.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Complex {
    /// Real part.
    pub re: f64,
    /// Imaginary part.
    pub im: f64,
}

impl Complex {
    /// The modulus.
    pub fn abs(self) -> f64 {
        self.re.hypot(self.im)
    }
}

/// The loop's dimensionless gains at one operating speed: `p = kP·h_r/v`,
/// `q = kI·h_r/v`. `p = −0.1` means a layer 0.01 mm too high makes the next
/// layer's speed lay 0.001 mm less.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoopGains {
    /// `p = kP·h_r/v`.
    pub proportional: f64,
    /// `q = kI·h_r/v`.
    pub integral: f64,
}

impl LoopGains {
    /// The gains of `kp`, `ki` about a segment that lays `target` at `speed`.
    /// `h_r/v` is `−dh/dv` there: the slower the segment, the stronger the loop.
    pub fn at(kp: SpeedPerLength, ki: SpeedPerLength, target: Length, speed: Speed) -> Self {
        let b = target.0 / speed.0;
        LoopGains {
            proportional: kp.0 * b,
            integral: ki.0 * b,
        }
    }

    /// Both gains times `c`.
    pub fn scaled(self, c: f64) -> Self {
        LoopGains {
            proportional: self.proportional * c,
            integral: self.integral * c,
        }
    }

    /// The matrix `A` of the error recurrence on `(e, Σ)`.
    pub fn matrix(self) -> [[f64; 2]; 2] {
        let (p, q) = (self.proportional, self.integral);
        [[1.0 + p, q], [1.0 + p, 1.0 + q]]
    }

    /// The eigenvalues `1 + μ` of `A`, from `μ² − (p+q)·μ − q = 0`: the
    /// characteristic polynomial shifted by one, so that gains of 10⁻⁵ do not
    /// vanish in `λ ≈ 1` (the form `tr² − 4·det` cancels them away).
    pub fn eigenvalues(self) -> [Complex; 2] {
        let [m1, m2] = self.shifted_roots();
        [
            Complex {
                re: 1.0 + m1.re,
                im: m1.im,
            },
            Complex {
                re: 1.0 + m2.re,
                im: m2.im,
            },
        ]
    }

    /// The roots `μ` of `μ² − s·μ − q = 0`, `s = p + q`.
    fn shifted_roots(self) -> [Complex; 2] {
        let (p, q) = (self.proportional, self.integral);
        let s = p + q;
        let disc = s * s + 4.0 * q;
        if disc < 0.0 {
            let im = (-disc).sqrt() / 2.0;
            let re = s / 2.0;
            return [Complex { re, im }, Complex { re, im: -im }];
        }
        // The larger root without cancellation, the smaller from the
        // product of the roots, −q.
        let big = (s + s.signum() * disc.sqrt()) / 2.0;
        let small = if big == 0.0 { 0.0 } else { -q / big };
        [Complex { re: big, im: 0.0 }, Complex { re: small, im: 0.0 }]
    }

    /// `ln ρ(A)`, accurate when `ρ` is within 10⁻⁶ of 1 (weak gains).
    pub fn log_radius(self) -> f64 {
        let [m1, m2] = self.shifted_roots();
        if m1.im != 0.0 {
            // A complex pair: |λ|² = det = 1 + p (> 0 whenever the pair is complex).
            return 0.5 * self.proportional.ln_1p();
        }
        let log_abs = |m: f64| {
            if m > -1.0 {
                m.ln_1p()
            } else {
                (-1.0 - m).ln()
            }
        };
        log_abs(m1.re).max(log_abs(m2.re))
    }

    /// `ρ(A)`, the largest eigenvalue modulus.
    pub fn spectral_radius(self) -> f64 {
        self.log_radius().exp()
    }

    /// `ρ(A) < 1`: an error dies away.
    pub fn is_stable(self) -> bool {
        self.log_radius() < 0.0
    }

    /// Layers until an error's envelope `ρⁱ` falls to [`SETTLED`] of its
    /// start; `None` when the loop is not stable. At least 1.
    pub fn settling_layers(self) -> Option<f64> {
        let l = self.log_radius();
        (l < 0.0).then(|| (SETTLED.ln() / l).max(1.0))
    }

    /// The fraction of a starting error's envelope left after `layers` layers, `ρᴺ`.
    pub fn residual_after(self, layers: usize) -> f64 {
        (self.log_radius() * layers as f64).exp()
    }

    /// For negative gains, the factor `c` such that `c·(p, q)` is stable iff
    /// `c` lies below it: `4 / (2|p| + |q|)` (Jury's third condition; the first,
    /// `c·|p| < 2`, then holds too). `None` when a gain is not negative: no
    /// scaling makes such a loop stable.
    pub fn stability_limit(self) -> Option<f64> {
        let (p, q) = (self.proportional, self.integral);
        (p < 0.0 && q < 0.0).then(|| 4.0 / (-2.0 * p - q))
    }

    /// The smallest factor `c` by which both gains must be multiplied for the
    /// loop to settle within `layers` layers, if any does (below the
    /// stability limit). May be below 1 (the loop is faster than needed).
    pub fn scale_to_settle(self, layers: usize) -> Option<f64> {
        let limit = self.stability_limit()?;
        let settles = |c: f64| {
            self.scaled(c)
                .settling_layers()
                .is_some_and(|n| n <= layers as f64)
        };
        // ρ(c) falls from 1 as c grows from 0, reaches a least value and rises
        // to 1 at the limit: walk up a fine geometric grid to the first
        // factor that settles, then bisect back to the crossing.
        const STEPS: i32 = 3000;
        let ratio = 1e-9_f64.powf(1.0 / STEPS as f64);
        let mut below = 0.0;
        for k in (0..STEPS).rev() {
            let c = limit * ratio.powi(k + 1);
            if settles(c) {
                let mut hi = c;
                let mut lo = below;
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if settles(mid) {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                return Some(hi);
            }
            below = c;
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn paper_at(v: f64) -> LoopGains {
        LoopGains::at(
            SpeedPerLength(-3.0),
            SpeedPerLength(-0.35),
            Length(0.23),
            Speed(v),
        )
    }

    #[test]
    fn the_papers_loop_at_13_mm_s() {
        let g = paper_at(13.0);
        // p = −3·0.23/13, q = −0.35·0.23/13.
        assert!((g.proportional + 0.053_076_923).abs() < 1e-8);
        assert!((g.integral + 0.006_192_308).abs() < 1e-8);
        // (p+q)² + 4q < 0: a complex pair of modulus √(1+p).
        let rho = (1.0 + g.proportional).sqrt();
        assert!((g.spectral_radius() - rho).abs() < 1e-12);
        assert!((rho - 0.973_100).abs() < 1e-6);
        // ln 0.02 / ln ρ = 143.5 layers.
        let n = g.settling_layers().unwrap();
        assert!((n - 0.02f64.ln() / rho.ln()).abs() < 1e-9);
        assert!((n - 143.46).abs() < 0.01, "{n}");
        // At 4 mm/s the loop is 13/4 times stronger: ρ = √(1 − 0.69/4), 41 layers.
        let n4 = paper_at(4.0).settling_layers().unwrap();
        assert!((n4 - 0.02f64.ln() / (0.5 * (1.0 - 0.69 / 4.0f64).ln())).abs() < 1e-9);
        assert!((n4 - 41.32).abs() < 0.01, "{n4}");
    }

    #[test]
    fn the_papers_gains_read_per_mm_s_need_a_hundred_thousand_layers() {
        let g = LoopGains::at(
            SpeedPerLength(-0.003),
            SpeedPerLength(-0.00035),
            Length(0.23),
            Speed(13.0),
        );
        assert!(g.is_stable());
        // ρ = √(1 − 5.3·10⁻⁵): 1.47·10⁵ layers; 1 − ρ¹³⁰ is only 0.34 %.
        let n = g.settling_layers().unwrap();
        assert!((n / 147_000.0 - 1.0).abs() < 0.01, "{n}");
        assert!(g.residual_after(130) > 0.99);
    }

    #[test]
    fn eigenvalues_solve_the_characteristic_polynomial() {
        for g in [paper_at(4.0), paper_at(1.9), paper_at(13.0)]
            .into_iter()
            .chain([
                LoopGains {
                    proportional: -1.5,
                    integral: -0.9,
                },
                LoopGains {
                    proportional: -2.5,
                    integral: -0.1,
                },
                LoopGains {
                    proportional: 0.2,
                    integral: -0.1,
                },
            ])
        {
            let [[a, b], [c, d]] = g.matrix();
            let (tr, det) = (a + d, a * d - b * c);
            assert!((det - (1.0 + g.proportional)).abs() < 1e-12);
            for l in g.eigenvalues() {
                // λ² − tr·λ + det = 0, in complex arithmetic.
                let re = l.re * l.re - l.im * l.im - tr * l.re + det;
                let im = 2.0 * l.re * l.im - tr * l.im;
                assert!(re.abs() < 1e-12 && im.abs() < 1e-12, "{g:?}");
            }
            let rho = g.eigenvalues().iter().map(|l| l.abs()).fold(0.0, f64::max);
            assert!((rho - g.spectral_radius()).abs() < 1e-12);
        }
    }

    #[test]
    fn the_stability_limit_is_where_the_radius_reaches_one() {
        let g = paper_at(4.0);
        // 4 / (2·0.1725 + 0.020125) = 10.95.
        let c = g.stability_limit().unwrap();
        assert!((c - 4.0 / (2.0 * 0.1725 + 0.020125)).abs() < 1e-9);
        assert!(g.scaled(c * 0.999).is_stable());
        assert!(!g.scaled(c * 1.001).is_stable());
        assert!((g.scaled(c).spectral_radius() - 1.0).abs() < 1e-9);
        assert_eq!(
            LoopGains {
                proportional: 0.1,
                integral: -0.1
            }
            .stability_limit(),
            None
        );
    }

    #[test]
    fn the_scale_to_settle_is_the_crossing() {
        let g = paper_at(13.0);
        // Complex regime: ρ = √(1 + c·p) = 0.02^(1/130) ⇒ c = (0.02^(2/130) − 1)/p.
        let want = (0.02f64.powf(2.0 / 130.0) - 1.0) / g.proportional;
        let c = g.scale_to_settle(130).unwrap();
        assert!((c - want).abs() < 1e-6, "{c} vs {want}");
        assert!(c > 1.0 && c < 1.2);
        assert!(paper_at(4.0).scale_to_settle(130).unwrap() < 1.0);
        // A loop with no integral can never settle its total.
        let p_only = LoopGains {
            proportional: -0.5,
            integral: 0.0,
        };
        assert!(!p_only.is_stable());
        assert_eq!(p_only.scale_to_settle(130), None);
    }
}
