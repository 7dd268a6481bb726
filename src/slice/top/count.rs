//! How many layers a variable top is built in (seed 003 eq. 2, through
//! [`crate::slice::variable::layers`]), and, when no count works, the error
//! that says why with the numbers a fix needs — in the voice of the bend's
//! (`lmd::bend-too-tight`): what the top needs, what the bead lays, and what
//! would work.

use super::footprint::Sampled;
use crate::diag::{Code, Diagnostic};
use crate::sema::model::{Bead, TopExtrusion, VariableSlicing};
use crate::slice::variable::layers::{
    choose_layers, LayerCount, LayerError, NoLayerCount, OutOfRange, MAX_LAYERS,
};
use crate::slice::variable::HeightRange;
use crate::units::{short, Length, Speed};
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
    beads: HeightRange,
    ex: &TopExtrusion,
    slicing: &VariableSlicing,
) -> Result<NonZeroU32, Diagnostic> {
    let count = match slicing.layers {
        Some((n, _)) => LayerCount::Exactly(n),
        None => LayerCount::Auto,
    };
    choose_layers(top.heights, beads, count).map_err(|e| match e {
        LayerError::NoCount(e) => no_count(&e, top, bead, ex),
        LayerError::OutOfRange(e) => out_of_range(&e, bead, slicing),
        LayerError::TooMany { needed } => Diagnostic::error(
            Code::TooManyPoints,
            format!(
                "the top reaches {}: {} layers of at most {}, more than {MAX_LAYERS}",
                top.heights.high(),
                short(needed.ceil()),
                bead.height[1]
            ),
        )
        .label(ex.top_span, "the top")
        .help("check the top's unit and numbers"),
    })
}

fn at(p: [f64; 2]) -> String {
    format!("({}, {}) mm", short(p[0]), short(p[1]))
}

/// No whole number of layers lays every point within the bead's heights.
fn no_count(e: &NoLayerCount, top: &TopRange, bead: &Bead, ex: &TopExtrusion) -> Diagnostic {
    let (lo, hi) = (e.top.low(), e.top.high());
    let (h_lo, h_hi) = (e.bead.low(), e.bead.high());
    let name = &bead.name;
    let message = if e.most == 0 {
        format!(
            "where the tracks run the top is {lo} .. {hi} high; its lowest point is below the thinnest layer bead `{name}` lays ({h_lo})"
        )
    } else if e.ratio_needed() > e.ratio_available() {
        format!(
            "where the tracks run the top is {lo} .. {hi} high (ratio {}); bead `{name}` lays {h_lo} .. {h_hi} (ratio {}): no number of layers lays both ends within it",
            short(e.ratio_needed()),
            short(e.ratio_available())
        )
    } else {
        format!(
            "where the tracks run the top is {lo} .. {hi} high (ratio {}); bead `{name}` lays {h_lo} .. {h_hi} (ratio {}), but no whole number of layers fits both ends: the highest point needs at least {} layers, the lowest allows at most {}",
            short(e.ratio_needed()),
            short(e.ratio_available()),
            e.fewest,
            e.most
        )
    };
    let mut fixes = Vec::new();
    if let Some(h) = e.top_high_at_most() {
        fixes.push(format!(
            "the top at most {h} where it is highest ({} layers)",
            e.most
        ));
    }
    if let Some(h) = e.top_low_at_least() {
        fixes.push(format!(
            "at least {h} where it is lowest ({} layers)",
            e.fewest
        ));
    }
    let low = e.bead_low_at_most();
    fixes.push(format!(
        "a bead that lays down to {low}{}",
        speed_note(bead, low, "up to", f64::ceil)
    ));
    if let Some(high) = e.bead_high_at_least() {
        fixes.push(format!(
            "one that lays up to {high}{}",
            speed_note(bead, high, "down to", f64::floor)
        ));
    }
    Diagnostic::error(Code::NoLayerCount, message)
        .label(
            ex.top_span,
            format!("{hi} at {}, {lo} at {}", at(top.high_at), at(top.low_at)),
        )
        .label(bead.height_span, format!("the bead lays {h_lo} .. {h_hi}"))
        .label(bead.speed_span, "over these speeds")
        .help(format!("this would work: {}", fixes.join("; or ")))
}

/// " (speeds up to 8.8 mm/s, if it holds that far)": the speed at which the
/// bead model would lay `h`, rounded away from its range.
fn speed_note(bead: &Bead, h: Length, dir: &str, round: fn(f64) -> f64) -> String {
    let v = bead.model.speed_for(h, bead.width).0;
    if v.is_finite() && v > 0.0 {
        format!(
            " (speeds {dir} {}, if the model holds that far)",
            Speed(round(v * 10.0) / 10.0)
        )
    } else {
        String::new()
    }
}

/// A declared count outside the counts that work.
fn out_of_range(e: &OutOfRange, bead: &Bead, slicing: &VariableSlicing) -> Diagnostic {
    let n = e.layers.get();
    Diagnostic::error(
        Code::LayerHeight,
        format!(
            "{n} layers lay {} .. {} where the tracks run, outside the {} .. {} bead `{}` lays",
            e.heights.low(),
            e.heights.high(),
            e.bead.low(),
            e.bead.high(),
            bead.name
        ),
    )
    .label_opt(slicing.layers.map(|l| l.1), "layer count")
    .label(bead.height_span, "the bead's heights")
    .help(format!(
        "use between {} and {} layers, or `layers = auto` ({})",
        e.range.fewest(),
        e.range.most(),
        e.range.fewest()
    ))
}
