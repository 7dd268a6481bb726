//! Whether every track can lay its layer at the pitch the layout gives it:
//! a track that fills a strip `p` wide must lay `h·p` per mm to raise the
//! layer by `h` ([`crate::deposit`]), at a speed within the bead's range.
//! A balanced layout stretched (or squeezed) to close on the far edge moves
//! its tracks apart (or together), and the speeds follow; where they leave
//! the bead's range at one layer count, the next count's thinner layers may
//! fit.

use super::footprint::Footprint;
use super::tracks::Track;
use crate::diag::message::top::{Unfillable, UnfillableTrack};
use crate::diag::Diagnostic;
use crate::sema::model::{Axis, Bead, TopExtrusion, VariableSlicing};
use crate::units::Length;
use std::num::NonZeroU32;

/// Relative slack on the bead's speed range.
const SLACK: f64 = 1e-9;

/// The track farthest outside the bead's speeds at `n` layers, if any is.
pub fn unfillable(tracks: &[Track], n: NonZeroU32, bead: &Bead) -> Option<UnfillableTrack> {
    let d = bead.deposit();
    let [lo, hi] = [bead.speed[0].0, bead.speed[1].0];
    let mut worst: Option<(f64, UnfillableTrack)> = None;
    for t in tracks {
        // Every point's height, as the count keeps every point's within the
        // bead's (the segments' heights lie between them).
        for (j, &top) in t.h.iter().enumerate() {
            let h = top / n.get() as f64;
            let v = d.speed_for(Length(h), Length(t.pitch)).0;
            let off = if v < lo * (1.0 - SLACK) {
                lo / v
            } else if v > hi * (1.0 + SLACK) {
                v / hi
            } else {
                continue;
            };
            if worst.as_ref().is_none_or(|w| off > w.0) {
                let (slow, fast) = (
                    d.rise(bead.speed[1], Length(t.pitch), None).0,
                    d.rise(bead.speed[0], Length(t.pitch), None).0,
                );
                worst = Some((
                    off,
                    UnfillableTrack {
                        across: t.c,
                        along: t.t[j],
                        pitch: t.pitch,
                        height: h,
                        speed: v,
                        rises: [slow, fast],
                    },
                ));
            }
        }
    }
    worst.map(|w| w.1)
}

/// The layer count nearest `n` at which every track of this layout can lay
/// its layers: each segment of top `H` over a strip `p` needs `H/N` within
/// what the bead raises `p` over its speeds, so `N` lies within
/// `⌈H/rise_max⌉ .. ⌊H/rise_min⌋`; `None` when the tracks' ranges do not
/// meet.
pub fn nearest(tracks: &[Track], n: NonZeroU32, bead: &Bead) -> Option<NonZeroU32> {
    let d = bead.deposit();
    let [lo, hi] = [bead.speed[0], bead.speed[1]];
    let (mut first, mut last) = (1.0f64, f64::INFINITY);
    for t in tracks {
        let p = Length(t.pitch);
        let (least, most) = (d.rise(hi, p, None).0, d.rise(lo, p, None).0);
        // Every point's height within the strip's range, as the count keeps
        // them within the bead's (the segments' heights lie between).
        for &top in &t.h {
            first = first.max((top / most * (1.0 - SLACK)).ceil());
            last = last.min((top / least * (1.0 + SLACK)).floor());
        }
    }
    if first > last || !last.is_finite() {
        return None;
    }
    let c = (n.get() as f64).clamp(first, last).min(u32::MAX as f64);
    NonZeroU32::new(c as u32)
}

/// No layer count lets the tracks (along `scan`) lay their layers.
pub fn report(
    miss: &UnfillableTrack,
    n: NonZeroU32,
    bead: &Bead,
    slicing: &VariableSlicing,
    ex: &TopExtrusion,
    scan: Axis,
) -> Diagnostic {
    let through = ex
        .turned
        .as_ref()
        .map(|f| f.footprint(Footprint::point(scan, miss.along, miss.across)));
    crate::diag::message::top::unfillable(&Unfillable {
        through,
        track: *miss,
        layers: n.get(),
        bead: &bead.name,
        speeds: [bead.speed[0].0, bead.speed[1].0],
        width: bead.width.0,
        declared: slicing.layers.is_some(),
        spans: [slicing.span, ex.shape_span, bead.speed_span],
    })
}
