//! The errors of a layer whose holes do not make a region: a hole that
//! crosses, touches or lies outside the outline, two holes that cross or
//! touch, a hole inside another. Each names the holes (numbered from 1 in
//! the order written, a bolt circle's in its order) and points at where
//! they are written; all of a layer's are reported together.

use crate::diag::{message, Diagnostic};
use crate::geometry::region::Region;
use crate::sema::model::Shape;

/// Which layer, for the message: `None` when the profile is the same on
/// every layer (then the fault is on all of them).
pub(super) struct Layer {
    /// The layer, from 0.
    pub k: usize,
    /// Whether the profile follows `layer` (the message then says which).
    pub varies: bool,
}

/// The diagnostics for the faults of `region` (made from `shape`) that
/// concern its holes; the outline's own crossing is the fill's to report.
pub(super) fn faults(region: &Region, shape: &Shape, layer: &Layer) -> Vec<Diagnostic> {
    message::hole::region_faults(region, shape, layer.k, layer.varies)
}
