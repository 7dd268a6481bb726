//! `seam = …` of `slicing planar` (and of `slicing normal`, which takes the
//! directions only): where each contour loop starts and ends,
//! and how that moves from layer to layer, and `link = …` of `raster(…)`.
//! A seam on the same spot of every layer stacks its start/stop defects into
//! a seam line up the part; moving it spreads them out.

use crate::diag::{message, Diagnostics};
use crate::sema::fields::{self, Fields};
use crate::sema::model::{LinkMode, SeamRule};
use crate::sema::schema::slicing::{planar, raster, RANDOM, ROTATING, STAGGERED};
use crate::sema::suggest::did_you_mean;
use crate::sema::value::{Call, Spanned, Value};
use crate::units::{Angle, Dim, Length};

/// Reads `seam = …`: `lowest`, `sharpest_corner`, an angle,
/// `rotating(step, from)` or `random(seed)` (or `random`, seed 0).
pub fn read(v: &Spanned, diags: &mut Diagnostics) -> Option<SeamRule> {
    match &v.value {
        Value::Symbol(s) if s == "lowest" => Some(SeamRule::Lowest),
        Value::Symbol(s) if s == "sharpest_corner" => Some(SeamRule::SharpestCorner),
        Value::Symbol(s) if s == "random" => Some(SeamRule::Random { seed: 0 }),
        Value::Quantity(_) => {
            fields::quantity(v, Dim::ANGLE, "seam", diags).map(|a| SeamRule::Toward(Angle(a)))
        }
        Value::Call(c) if c.func == "rotating" => rotating(c, diags),
        Value::Call(c) if c.func == "staggered" => {
            let f = Fields::call(c, &STAGGERED, diags);
            f.quantity(&raster::SHIFT, diags)
                .map(|(d, _)| SeamRule::Staggered { shift: Length(d) })
        }
        Value::Call(c) if c.func == "random" => {
            let f = Fields::call(c, &RANDOM, diags);
            f.count_or_default(&raster::SEED, diags)
                .map(|n| SeamRule::Random { seed: n as u64 })
        }
        other => {
            let near = match other {
                // The words `seam` takes besides an angle and the calls.
                Value::Symbol(w) => {
                    let words = planar::SEAM.kind.words().unwrap_or_default();
                    did_you_mean(w, words.iter().copied())
                }
                Value::Call(c) => did_you_mean(&c.func, ["rotating", "random", "staggered"]),
                _ => None,
            };
            diags.push(message::solid::bad_seam(other.got(), v.span, near));

            None
        }
    }
}

fn rotating(c: &Call, diags: &mut Diagnostics) -> Option<SeamRule> {
    let f = Fields::call(c, &ROTATING, diags);
    let step = f.quantity_or_default(&raster::STEP, diags).map(Angle);
    let from = f.quantity_or_default(&raster::FROM, diags).map(Angle);
    Some(SeamRule::Rotating {
        from: from?,
        step: step?,
    })
}

/// Reads `link = none | laser_on | laser_off`.
pub fn link(v: &Spanned, diags: &mut Diagnostics) -> Option<LinkMode> {
    let Some(words) = raster::LINK.kind.words() else {
        unreachable!("`link` takes words")
    };
    match fields::word(v, raster::LINK.key, words, diags)? {
        "laser_on" => Some(LinkMode::LaserOn),
        "laser_off" => Some(LinkMode::LaserOff),
        _ => Some(LinkMode::None),
    }
}

impl SeamRule {
    /// Whether the seam moves from layer to layer (a spiral layer change,
    /// going on from where the layer ended, cannot take one).
    pub fn moves(&self) -> bool {
        matches!(
            self,
            SeamRule::Rotating { .. } | SeamRule::Random { .. } | SeamRule::Staggered { .. }
        )
    }

    /// The direction (rad from +x) the seam of layer `k` (from 0) lies
    /// farthest in, or `None` for a rule that is not a direction.
    pub fn direction(&self, k: usize) -> Option<f64> {
        match *self {
            SeamRule::Lowest | SeamRule::SharpestCorner | SeamRule::Staggered { .. } => None,
            SeamRule::Toward(a) => Some(a.0),
            SeamRule::Rotating { from, step } => {
                // Reduced per layer so that a thousand layers lose no digit.
                let turn = (step.0 * k as f64).rem_euclid(std::f64::consts::TAU);
                Some((from.0 + turn).rem_euclid(std::f64::consts::TAU))
            }
            SeamRule::Random { seed } => {
                let x = splitmix64(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ k as u64);
                // The top 53 bits as a fraction of a turn.
                Some((x >> 11) as f64 / (1u64 << 53) as f64 * std::f64::consts::TAU)
            }
        }
    }
}

/// SplitMix64's output function: a fixed, well-mixed hash of one word, so the
/// seams are the same on every platform and in every version.
fn splitmix64(x: u64) -> u64 {
    let mut z = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::TAU;

    #[test]
    fn rotating_seams_turn_by_the_step() {
        let r = SeamRule::Rotating {
            from: Angle::from_deg(0.0),
            step: Angle::from_deg(90.0),
        };
        let deg: Vec<f64> = (0..5)
            .map(|k| r.direction(k).unwrap().to_degrees().round())
            .collect();
        assert_eq!(deg, [0.0, 90.0, 180.0, 270.0, 0.0]);
    }

    #[test]
    fn random_seams_are_fixed_by_the_seed_and_spread() {
        let a = SeamRule::Random { seed: 7 };
        let b = SeamRule::Random { seed: 8 };
        let da: Vec<f64> = (0..200).map(|k| a.direction(k).unwrap()).collect();
        let again: Vec<f64> = (0..200).map(|k| a.direction(k).unwrap()).collect();
        assert_eq!(da, again);
        assert_ne!(
            da[..10],
            (0..10).map(|k| b.direction(k).unwrap()).collect::<Vec<_>>()[..]
        );
        assert!(da.iter().all(|d| (0.0..TAU).contains(d)));
        // Every quarter turn gets some of 200 draws.
        for q in 0..4 {
            let lo = q as f64 * TAU / 4.0;
            assert!(
                da.iter()
                    .filter(|&&d| d >= lo && d < lo + TAU / 4.0)
                    .count()
                    > 25
            );
        }
    }
}
