//! Whether the gap under a target's underside, over the scan, is wear or
//! air (docs/repair.md, *Overhangs*).
//!
//! A line down through a target that leaves it and meets the scan only
//! lower down passes a gap under the target's underside. A target of the
//! added metal alone stands over the part: its gap is the wear, filled
//! down to the scan. A target that is the part as designed holds the
//! scanned part (the worn pad lies in the pad as designed): its gap is
//! air beside the part, under an overhang of it (the plate beside a
//! leaning boss), which layers laid from the scan up would fill. Which a
//! target is, is read once over the footprint: the part as designed when
//! somewhere under it the scanned surface lies in the target deeper than
//! [`DEPTH`].

use crate::geometry::outline;
use crate::sema::model::{Top, TopExtrusion};

/// How deep the scanned surface must lie in the target for the target to
/// hold it, mm, beyond three times the scan's noise: a target of added
/// metal drawn on the part's nominal face, over a scan of the same face,
/// is not taken to hold it.
pub const DEPTH: f64 = 0.2;

/// Points a side of the grid the footprint is read on.
const SIDE: usize = 48;

/// Chord error of the footprint's outline, mm.
const CHORD_ERROR: f64 = 0.05;

/// A point of the scanned surface (mm) under `ex`'s footprint that lies
/// in its target deeper than [`DEPTH`]: the target is the part as
/// designed. `None` for a target of added metal alone, or a top that is
/// no target on a scan.
pub fn holds_scan(ex: &TopExtrusion) -> Option<[f64; 3]> {
    let scan = &ex.base.as_ref()?.surface;
    if !matches!(ex.top, Top::Mesh(_) | Top::Solid(_)) {
        return None;
    }
    let profile = outline::profile(&ex.shape, CHORD_ERROR);
    let [lo, hi] = profile.bounds()?;
    let depth = DEPTH + 3.0 * scan.stats.noise;
    let at = |k: usize, i: usize| lo[k] + (i as f64 + 0.5) / SIDE as f64 * (hi[k] - lo[k]);
    (0..SIDE * SIDE).find_map(|n| {
        let p = [at(0, n % SIDE), at(1, n / SIDE)];
        if !profile.contains(p) {
            return None;
        }
        let b = scan.at(p)?;
        ex.top
            .contains([p[0], p[1], b - depth])
            .then_some([p[0], p[1], b])
    })
}
