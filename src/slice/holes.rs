//! The errors of a layer whose holes do not make a region: a hole that
//! crosses, touches or lies outside the outline, two holes that cross or
//! touch, a hole inside another. Each names the holes (numbered from 1 in
//! the order written, a bolt circle's in its order) and points at where
//! they are written; all of a layer's are reported together.

use crate::diag::{message, Diagnostic};
use crate::geometry::region::{Fault, Region, MAX_FAULTS};
use crate::sema::model::{RegionShape, Shape};

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
    let Some(written) = region_shape(shape) else {
        return Vec::new();
    };
    if written.holes.is_empty() {
        return Vec::new();
    }
    let faults = region.faults();
    let capped = faults.len() >= MAX_FAULTS;
    let mut out: Vec<Diagnostic> = faults
        .into_iter()
        .filter_map(|f| diagnostic(f, written, layer))
        .collect();
    if capped {
        out.push(message::hole::more_faults(written.outline_span));
    }
    out
}

/// The `region(…)` a shape is, placed or not.
fn region_shape(s: &Shape) -> Option<&RegionShape> {
    match s {
        Shape::Region(r) => Some(r),
        Shape::Placed(p) => region_shape(&p.shape),
        _ => None,
    }
}

fn diagnostic(f: Fault, r: &RegionShape, layer: &Layer) -> Option<Diagnostic> {
    message::hole::fault(
        f,
        |h| r.holes.get(h).map(|h| h.span),
        r.outline_span,
        layer.k,
        layer.varies,
    )
}
