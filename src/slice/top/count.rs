//! How many layers a variable top is built in (seed 003 eq. 2, through
//! [`crate::slice::variable::layers`]), and, when no count works, the error
//! that says why with the numbers a fix needs — in the voice of the bend's
//! (`lmd::bend-too-tight`): what the top needs, what the bead lays, and what
//! would work.

use super::footprint::Sampled;
use crate::diag::message::{self, top::CountBead};
use crate::diag::Diagnostic;
use crate::sema::model::{Bead, TopExtrusion, VariableSlicing};
use crate::slice::variable::layers::{
    choose_layers, LayerCount, LayerError, NoLayerCount, OutOfRange,
};
use crate::slice::variable::speed::HeightMap;
use crate::slice::variable::HeightRange;
use crate::units::Length;
use std::num::NonZeroU32;

/// The heights the top needs where tracks run, and where its ends are.
#[derive(Clone, Copy, Debug)]
pub struct TopRange {
    /// `H_min .. H_max`.
    pub heights: HeightRange,
    /// Where the top is lowest, mm.
    pub low_at: [f64; 2],
    /// Where it is highest, mm.
    pub high_at: [f64; 2],
}

impl TopRange {
    /// The range of a sampling (whose heights are positive and finite).
    pub fn of(s: &Sampled) -> Option<Self> {
        let heights = HeightRange::new("top", Length(s.low.0), Length(s.high.0)).ok()?;
        Some(TopRange {
            heights,
            low_at: s.low.1,
            high_at: s.high.1,
        })
    }

    /// This range grown to hold `other` as well.
    pub fn union(self, other: TopRange) -> TopRange {
        let low = if other.heights.low().0 < self.heights.low().0 {
            (other.heights.low(), other.low_at)
        } else {
            (self.heights.low(), self.low_at)
        };
        let high = if other.heights.high().0 > self.heights.high().0 {
            (other.heights.high(), other.high_at)
        } else {
            (self.heights.high(), self.high_at)
        };
        TopRange {
            heights: HeightRange::new("top", low.0, high.0).unwrap_or(self.heights),
            low_at: low.1,
            high_at: high.1,
        }
    }

    /// Whether `other` lies within this range.
    pub fn holds(&self, other: &TopRange) -> bool {
        other.heights.low().0 >= self.heights.low().0
            && other.heights.high().0 <= self.heights.high().0
    }
}

/// The layer count: the fewest that lay every point of `top` within the
/// bead's heights, or the declared one if it does; else the error.
pub fn layers(
    top: &TopRange,
    bead: &Bead,
    map: &impl HeightMap,
    ex: &TopExtrusion,
    slicing: &VariableSlicing,
) -> Result<NonZeroU32, Diagnostic> {
    let beads = map.heights();
    let count = match slicing.layers {
        Some((n, _)) => LayerCount::Exactly(n),
        None => LayerCount::Auto,
    };
    choose_layers(top.heights, beads, count).map_err(|e| match e {
        LayerError::NoCount(e) => no_count(&e, top, bead, map, ex),
        LayerError::OutOfRange(e) => out_of_range(&e, bead, slicing),
        LayerError::TooMany { needed } => {
            message::top::too_many_layers(top.heights.high(), needed, beads.high(), ex.top_span)
        }
    })
}

/// No whole number of layers lays every point within the bead's heights.
fn no_count(
    e: &NoLayerCount,
    top: &TopRange,
    bead: &Bead,
    map: &impl HeightMap,
    ex: &TopExtrusion,
) -> Diagnostic {
    // The speed that lays `h` as these tracks stack it.
    let speed = |h: Length, round: fn(f64) -> f64| {
        let v = map.speed_within(h).0;
        // Rounded away from the bead's range, so the speed named is enough.
        (v.is_finite() && v > 0.0).then(|| round(v * 10.0) / 10.0)
    };
    let cb = CountBead {
        name: &bead.name,
        heights: bead.height_span,
        speeds: bead.speed_span,
        speed_for_low: speed(e.bead_low_at_most(), f64::ceil),
        speed_for_high: e.bead_high_at_least().and_then(|h| speed(h, f64::floor)),
    };
    message::top::no_count(e, top.low_at, top.high_at, &cb, ex.top_span)
}

/// A declared count outside the counts that work.
fn out_of_range(e: &OutOfRange, bead: &Bead, slicing: &VariableSlicing) -> Diagnostic {
    message::top::count_outside(e, &bead.name, slicing.layers.map(|l| l.1), bead.height_span)
}
