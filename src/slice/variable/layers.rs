//! How many layers (seed 003 eq. 2). Every layer lays `H/N` at a point whose
//! top is at `H`, so `N` must satisfy, at every deposited point,
//! `H/N ≤ h_max` and `H/N ≥ h_min`:
//!
//! `⌈H_max / h_max⌉ ≤ N ≤ ⌊H_min / h_min⌋`.
//!
//! The paper prints the second condition as `H_SB/N ≤ h_min`, which would let
//! the lowest point be laid in layers thinner than the bead can lay. A count
//! exists only if the bead's height ratio `h_max/h_min` is at least the top's
//! `H_max/H_min` (necessary, not sufficient: `N` must also be whole).

use super::input::HeightRange;
use super::{ceil_slack, floor_slack};
use crate::units::Length;
use std::num::NonZeroU32;

/// Most layers a plan may have. Seed 002's wing blank has ~3000; a count past
/// this is a unit mistake, and stops the arithmetic before `u32` saturates.
pub const MAX_LAYERS: u32 = 100_000;

/// The layer count a file asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LayerCount {
    /// The fewest layers that work (fewer layers, less time).
    Auto,
    /// Exactly this many (zero cannot be written).
    Exactly(NonZeroU32),
}

/// The layer counts that lay every point within the bead's heights:
/// `fewest ..= most`, never empty.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LayerRange {
    fewest: NonZeroU32,
    most: NonZeroU32,
}

impl LayerRange {
    /// `⌈H_max / h_max⌉`.
    pub fn fewest(self) -> NonZeroU32 {
        self.fewest
    }

    /// `⌊H_min / h_min⌋` (at least [`fewest`](Self::fewest)).
    pub fn most(self) -> NonZeroU32 {
        self.most
    }

    /// Whether `n` layers work.
    pub fn contains(self, n: NonZeroU32) -> bool {
        (self.fewest..=self.most).contains(&n)
    }
}

/// Why no layer count can be used.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LayerError {
    /// No whole number of layers fits the top into the bead's heights.
    NoCount(NoLayerCount),
    /// The declared count lays heights outside the bead's range.
    OutOfRange(OutOfRange),
    /// The fewest layers that would work are more than [`MAX_LAYERS`].
    TooMany {
        /// `H_max / h_max`.
        needed: f64,
    },
}

/// No `N` exists: `⌈H_max/h_max⌉ > ⌊H_min/h_min⌋`. Carries the numbers a
/// diagnostic needs, and what would fix it (each fix alone suffices).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NoLayerCount {
    /// The heights the top needs, `H_min .. H_max`.
    pub top: HeightRange,
    /// The heights the bead lays, `h_min .. h_max`.
    pub bead: HeightRange,
    /// `⌈H_max / h_max⌉`: the fewest layers the highest point allows.
    pub fewest: u32,
    /// `⌊H_min / h_min⌋`: the most layers the lowest point allows (may be 0).
    pub most: u32,
}

impl NoLayerCount {
    /// `H_max / H_min`, the ratio a bead map must span (necessary).
    pub fn ratio_needed(&self) -> f64 {
        self.top.ratio()
    }

    /// `h_max / h_min`, the ratio this bead spans.
    pub fn ratio_available(&self) -> f64 {
        self.bead.ratio()
    }

    /// A lower high end: keeping the lowest point, the highest may be at most
    /// `most · h_max` (then `most` layers work). `None` when that is below the
    /// lowest point itself — it lies between what `most` and `most + 1`
    /// layers can lay (or below one bead), and no high end fixes that.
    pub fn top_high_at_most(&self) -> Option<Length> {
        let high = self.most as f64 * self.bead.high().0;
        (self.most > 0 && high >= self.top.low().0).then_some(Length(high))
    }

    /// A higher low end: keeping the highest point, the lowest must be at
    /// least `fewest · h_min` (then `fewest` layers work). `None` when that is
    /// above the highest point itself, which then lies between what
    /// `fewest − 1` and `fewest` layers can lay.
    pub fn top_low_at_least(&self) -> Option<Length> {
        let low = self.fewest as f64 * self.bead.low().0;
        (low <= self.top.high().0).then_some(Length(low))
    }

    /// A bead map reaching lower: with `h_max` kept, `h_min` down to
    /// `H_min / fewest` lets `fewest` layers work.
    pub fn bead_low_at_most(&self) -> Length {
        Length(self.top.low().0 / self.fewest as f64)
    }

    /// A bead map reaching higher: with `h_min` kept, `h_max` up to
    /// `H_max / most` lets `most` layers work. `None` when `most` is 0.
    pub fn bead_high_at_least(&self) -> Option<Length> {
        (self.most > 0).then(|| Length(self.top.high().0 / self.most as f64))
    }
}

/// A declared count outside [`LayerRange`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OutOfRange {
    /// The declared count.
    pub layers: NonZeroU32,
    /// The layer heights it would lay, `H_min/N .. H_max/N`.
    pub heights: HeightRange,
    /// The heights the bead lays.
    pub bead: HeightRange,
    /// The counts that work.
    pub range: LayerRange,
}

/// The layer counts for which every point of the top lays a height the bead
/// can lay.
pub fn layer_range(top: HeightRange, bead: HeightRange) -> Result<LayerRange, LayerError> {
    let needed = top.high().0 / bead.high().0;
    let fewest = ceil_slack(needed).max(1.0);
    if fewest > MAX_LAYERS as f64 {
        return Err(LayerError::TooMany { needed });
    }
    // `as` saturates, and `most` only bounds a declared count from above.
    let most = floor_slack(top.low().0 / bead.low().0).min(u32::MAX as f64) as u32;
    let fewest = fewest as u32;
    match (NonZeroU32::new(fewest), NonZeroU32::new(most)) {
        (Some(f), Some(m)) if f <= m => Ok(LayerRange { fewest: f, most: m }),
        _ => Err(LayerError::NoCount(NoLayerCount {
            top,
            bead,
            fewest,
            most,
        })),
    }
}

/// The layer count: the fewest that work for [`LayerCount::Auto`], the
/// declared one if it works.
pub fn choose_layers(
    top: HeightRange,
    bead: HeightRange,
    count: LayerCount,
) -> Result<NonZeroU32, LayerError> {
    let range = layer_range(top, bead)?;
    match count {
        LayerCount::Auto => Ok(range.fewest),
        LayerCount::Exactly(n) if range.contains(n) => Ok(n),
        LayerCount::Exactly(n) => Err(LayerError::OutOfRange(OutOfRange {
            layers: n,
            heights: HeightRange::new(
                "layer heights",
                layer_height(top.low(), n),
                layer_height(top.high(), n),
            )
            .unwrap_or(top),
            bead,
            range,
        })),
    }
}

/// The height every layer lays where the top is at `top`: `H / N`.
pub fn layer_height(top: Length, layers: NonZeroU32) -> Length {
    Length(top.0 / layers.get() as f64)
}

/// The planned top of layer `layer` (from 0) where the part's top is at
/// `top`: `H·(layer+1)/N`, exactly `H` on the last layer. Layer `i` is laid
/// on the planned top of layer `i − 1` (0 on the substrate).
pub fn layer_top(top: Length, layers: NonZeroU32, layer: u32) -> Length {
    let n = layers.get();
    if layer + 1 >= n {
        top
    } else {
        Length(top.0 * (layer + 1) as f64 / n as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn range(lo: f64, hi: f64) -> HeightRange {
        HeightRange::new("test", Length(lo), Length(hi)).unwrap()
    }

    fn nz(n: u32) -> NonZeroU32 {
        NonZeroU32::new(n).unwrap()
    }

    #[test]
    fn whole_quotients_are_not_rounded_up() {
        let r = layer_range(range(6.0, 6.0), range(0.6, 1.2)).unwrap();
        assert_eq!(r.fewest().get(), 5);
        // 8.4 / 1.2 is 7.000000000000001 in floating point: still 7 layers.
        let r = layer_range(range(8.4, 8.4), range(0.6, 1.2)).unwrap();
        assert_eq!(r.fewest().get(), 7);
        // and 0.7/0.1 = 6.999999999999999 still allows 7.
        let r = layer_range(range(0.7, 0.7), range(0.1, 0.7)).unwrap();
        assert_eq!(r.most().get(), 7);
    }

    #[test]
    fn seed_003_bead() {
        // h = 0.6455 .. 1.28 mm (ratio 1.983).
        let bead = range(0.6455, 1.28);
        // A top from 12 to 20 mm: ⌈20/1.28⌉ = 16 ≤ N ≤ ⌊12/0.6455⌋ = 18.
        let r = layer_range(range(12.0, 20.0), bead).unwrap();
        assert_eq!((r.fewest().get(), r.most().get()), (16, 18));
        assert_eq!(
            choose_layers(range(12.0, 20.0), bead, LayerCount::Auto),
            Ok(nz(16))
        );
        // The paper's inequality as printed (H_min/N ≤ h_min) would accept 20
        // layers, which lays 0.6 mm at the low end: below h_min.
        let Err(LayerError::OutOfRange(e)) =
            choose_layers(range(12.0, 20.0), bead, LayerCount::Exactly(nz(20)))
        else {
            panic!("20 layers must be refused")
        };
        assert!((e.heights.low().0 - 0.6).abs() < 1e-12);
        assert_eq!(e.range, r);
    }

    #[test]
    fn a_ratio_of_two_is_beyond_the_seed_003_bead() {
        // A wall rising 10 → 20 mm needs ratio 2 > 1.983: ⌈20/1.28⌉ = 16 >
        // ⌊10/0.6455⌋ = 15.
        let Err(LayerError::NoCount(e)) = layer_range(range(10.0, 20.0), range(0.6455, 1.28))
        else {
            panic!("no count should exist")
        };
        assert_eq!((e.fewest, e.most), (16, 15));
        assert!((e.ratio_needed() - 2.0).abs() < 1e-12);
        assert!((e.ratio_available() - 1.98296).abs() < 1e-5);
        // Each fix alone makes a count exist.
        assert!((e.top_high_at_most().unwrap().0 - 19.2).abs() < 1e-9);
        assert!((e.top_low_at_least().unwrap().0 - 10.328).abs() < 1e-9);
        assert!((e.bead_low_at_most().0 - 0.625).abs() < 1e-9);
        assert!((e.bead_high_at_least().unwrap().0 - 4.0 / 3.0).abs() < 1e-9);
    }

    #[test]
    fn a_point_below_one_bead_has_no_high_end_fix() {
        let Err(LayerError::NoCount(e)) = layer_range(range(0.5, 3.0), range(0.6, 1.2)) else {
            panic!()
        };
        assert_eq!(e.most, 0);
        assert_eq!(e.top_high_at_most(), None);
        assert_eq!(e.bead_high_at_least(), None);
    }

    #[test]
    fn a_top_between_two_counts_is_fixed_by_the_bead_alone() {
        // 2.5 mm everywhere with 0.9 .. 1.2 mm beads: 2 layers lay at most
        // 2.4, 3 at least 2.7. No top fix keeps the other end; the bead
        // needs h_min ≤ 2.5/3 or h_max ≥ 2.5/2.
        let Err(LayerError::NoCount(e)) = layer_range(range(2.5, 2.5), range(0.9, 1.2)) else {
            panic!()
        };
        assert_eq!((e.fewest, e.most), (3, 2));
        assert_eq!((e.top_high_at_most(), e.top_low_at_least()), (None, None));
        assert!((e.bead_low_at_most().0 - 2.5 / 3.0).abs() < 1e-12);
        assert_eq!(e.bead_high_at_least(), Some(Length(1.25)));
    }

    #[test]
    fn absurd_counts_are_refused() {
        assert!(matches!(
            layer_range(range(1e9, 1e9), range(0.5, 1.0)),
            Err(LayerError::TooMany { .. })
        ));
    }

    #[test]
    fn the_last_layer_ends_on_the_top() {
        let n = nz(3);
        assert_eq!(layer_top(Length(0.3), n, 2), Length(0.3));
        assert!((layer_top(Length(0.3), n, 0).0 - 0.1).abs() < 1e-15);
    }
}
