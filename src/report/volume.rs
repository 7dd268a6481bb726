//! The metal each layer's deposit moves lay, from the plan's own deposit
//! model ([`crate::deposit`]), as the IR carries it: a deposit move runs
//! from an IR point whose laser is on to the next point of its path, over
//! the ground `len` (across the normal), filling a strip `pitch` wide.
//!
//! - **bead**: what the bead model lays, `A·len = rise·pitch·len` (the
//!   point's predicted `rise` at its speed and powder);
//! - **stacked**: what the plan stacks there, the layer's height along the
//!   move (the mean of its ends') times `pitch·len`.
//!
//! Where the two differ the layers do not rise as planned: the verifier
//! refuses a plan whose runs differ by more than `rise_tolerance` or whose
//! layers' mean errors add up past `max_drift` (`lmd::deposit`). Sums over
//! the IR's points in the plan's order, without following the plan again
//! (its lengths and times come from the verifier's summary).

use crate::ir::{Layer, Program};

/// What one layer lays and stacks.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Laid {
    /// What the bead model lays, mm³.
    pub bead: f64,
    /// What the plan stacks, mm³.
    pub stacked: f64,
    /// The layer's mean error (rise − planned height) over its deposited
    /// ground, mm.
    pub mean_error: f64,
}

/// Each layer's volumes.
pub fn per_layer(program: &Program) -> Vec<Laid> {
    program.layers.iter().map(layer).collect()
}

fn layer(layer: &Layer) -> Laid {
    let mut out = Laid::default();
    let (mut ground, mut error) = (0.0, 0.0);
    for path in &layer.paths {
        for w in path.points.windows(2) {
            let (from, to) = (&w[0], &w[1]);
            if !from.laser_on || from.pitch <= 0.0 {
                continue;
            }
            let len = from.ground_to(Some(to));
            let h = 0.5 * (from.layer_height as f64 + to.layer_height as f64);
            let (rise, pitch) = (from.rise as f64, from.pitch as f64);
            out.bead += rise * pitch * len;
            out.stacked += h * pitch * len;
            ground += len;
            error += (rise - h) * len;
        }
    }
    if ground > 0.0 {
        out.mean_error = error / ground;
    }
    out
}
