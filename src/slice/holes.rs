//! The errors of a layer whose holes do not make a region: a hole that
//! crosses, touches or lies outside the outline, two holes that cross or
//! touch, a hole inside another. Each names the holes (numbered from 1 in
//! the order written, a bolt circle's in its order) and points at where
//! they are written; all of a layer's are reported together.

use crate::diag::{Code, Diagnostic};
use crate::geometry::region::{Fault, Region, MAX_FAULTS};
use crate::sema::model::{RegionShape, Shape};
use crate::span::Span;
use crate::units::short;

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
        out.push(
            Diagnostic::error(
                Code::Hole,
                format!("these are the first {MAX_FAULTS} faults of the holes; there may be more"),
            )
            .label(written.outline_span, "this region's holes")
            .help("fix these and check again"),
        );
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
    let span = |h: usize| r.holes.get(h).map(|h| h.span);
    let on = if layer.varies {
        format!(" on layer {} (layer = {})", layer.k + 1, layer.k)
    } else {
        String::new()
    };
    let at = |p: [f64; 2]| format!("({}, {}) mm", short(p[0]), short(p[1]));
    let d = match f {
        Fault::Outline { .. } => return None,
        Fault::HoleItself { hole, at: p } => Diagnostic::error(
            Code::Hole,
            format!("hole {} crosses itself at {}{on}", hole + 1, at(p)),
        )
        .label_opt(span(hole), format!("hole {}", hole + 1))
        .help("reorder the hole's points so its edges do not cross"),
        Fault::HoleOutline { hole, at: p } => Diagnostic::error(
            Code::Hole,
            format!(
                "hole {} crosses or touches the outline at {}{on}: no metal would be left between them",
                hole + 1,
                at(p)
            ),
        )
        .label_opt(span(hole), format!("hole {}", hole + 1))
        .label(r.outline_span, "the outline")
        .help("a hole lies inside the outline with metal all round it: move it in or make it smaller; an opening that reaches the edge is a notch, drawn as part of the outline"),
        Fault::HoleOutside { hole } => Diagnostic::error(
            Code::Hole,
            format!("hole {} lies outside the outline{on}", hole + 1),
        )
        .label_opt(span(hole), format!("hole {}", hole + 1))
        .label(r.outline_span, "the outline")
        .help("a hole is an opening in the part: place it inside the outline, in the outline's coordinates (`place(circle(…), at = [x, y])`), or drop it"),
        Fault::Holes { hole, other, at: p } => {
            let d = Diagnostic::error(
                Code::Hole,
                format!(
                    "holes {} and {} cross or touch at {}{on}: no metal would be left between them",
                    hole + 1,
                    other + 1,
                    at(p)
                ),
            );
            pair(d, span(hole), span(other), hole, other)
                .help("move the holes apart or make them smaller; overlapping openings are one hole, drawn as one outline")
        }
        Fault::HoleInHole { hole, other } => {
            let d = Diagnostic::error(
                Code::Hole,
                format!("hole {} lies inside hole {}{on}", hole + 1, other + 1),
            );
            pair(d, span(hole), span(other), hole, other).help(format!(
                "hole {} is open already: drop hole {} (metal inside a hole would be an island, a part of its own)",
                other + 1,
                hole + 1
            ))
        }
    };
    Some(d)
}

/// Labels two holes: one label when they are written in one place (a bolt
/// circle), else one each.
fn pair(d: Diagnostic, a: Option<Span>, b: Option<Span>, ha: usize, hb: usize) -> Diagnostic {
    if a == b {
        d.label_opt(a, format!("holes {} and {}", ha + 1, hb + 1))
    } else {
        d.label_opt(a, format!("hole {}", ha + 1))
            .label_opt(b, format!("hole {}", hb + 1))
    }
}
