//! Variable-thickness layers (seed 003, Xin et al. 2020): the physics and the
//! maths, as pure functions of numbers — nothing here reads the semantic model
//! or writes IR, so the slicer and the checks can both call it.
//!
//! A solid whose top `H(x, y)` is not parallel to the substrate is built in
//! `N` layers that each lay the same *fraction* of the local height, `H/N`.
//! Four questions follow, one module each:
//!
//! | module | question | the paper | what we changed |
//! |---|---|---|---|
//! | [`layers`] | how many layers | eq. 2 | `⌊min H / h_min⌋` (the paper prints `≤`); exact at whole numbers |
//! | [`speed`] | which speed lays `H/N` | eq. 1, 8 | the map gives the *horizontal* speed; the path speed is `v_h·√(1+s²)` |
//! | [`segments`] | where the speed may change along a track | eq. 7 | `∫|H − H_seg|` (the paper drops the absolute value); each segment at its L1-best height |
//! | [`overlap`] | how far apart tracks of unequal height sit | eq. 4–6 | `C·(h_k+h_{k+1}) = A_k+A_{k+1}` (no factor 2); a closure rule for the far edge |
//!
//! [`input`] holds the checked input types: every function takes values that
//! cannot be NaN, negative or empty, and degenerate numbers become an
//! [`Invalid`] at the boundary instead of a panic or a NaN deep inside.
//! [`crate::slice::top`] applies it to a model and writes IR; the language
//! is `docs/language.md`'s *Variable slicing*.

pub mod input;
pub mod layers;
pub mod overlap;
pub mod profile;
pub mod segments;
pub mod speed;

#[cfg(test)]
mod props;

pub use input::{HeightRange, Invalid, Positive};

/// Relative slack on comparisons of heights and on rounding quotients to whole
/// numbers: tighter than the checks' [`RANGE_SLACK`](crate::units::RANGE_SLACK),
/// so a plan this module accepts is one the checks accept.
pub const SLACK: f64 = 1e-9;

/// `⌈q⌉`, except that a quotient within [`SLACK`] of a whole number is that
/// number: `8.4 / 1.2` is `7.000000000000001` in floating point, and an 8.4 mm
/// top with 1.2 mm beads is 7 layers, not 8.
pub(crate) fn ceil_slack(q: f64) -> f64 {
    let r = q.round();
    if (q - r).abs() <= SLACK * r.abs().max(1.0) {
        r
    } else {
        q.ceil()
    }
}

/// `⌊q⌋` with the same slack as [`ceil_slack`].
pub(crate) fn floor_slack(q: f64) -> f64 {
    let r = q.round();
    if (q - r).abs() <= SLACK * r.abs().max(1.0) {
        r
    } else {
        q.floor()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounding_is_exact_at_whole_numbers() {
        assert_eq!(ceil_slack(6.0 / 1.2), 5.0);
        assert_eq!(8.4 / 1.2, 7.000000000000001);
        assert_eq!(ceil_slack(8.4 / 1.2), 7.0);
        assert_eq!(floor_slack(0.7 / 0.1), 7.0); // 6.999999999999999
        assert_eq!(ceil_slack(5.01), 6.0);
        assert_eq!(floor_slack(4.99), 4.0);
    }
}
