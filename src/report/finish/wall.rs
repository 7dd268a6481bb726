//! The finish of a wall on a scan (docs/repair.md, *A wall on a scan*):
//! its beads run through the same points on every layer (each lays the
//! same share of the gap), so every laser-on move of the last layer has a
//! move under it on each layer below, with the same middle. At each such
//! middle the predicted face is the scanned surface there plus what every
//! layer's move raises it by (`A/pitch` at the move's speed,
//! [`crate::ir::Point::predicted_rise`]), against the wall's flat top.

use super::{first_layer, Finish, Sample};
use crate::ir::Program;
use crate::sema::model::WallOnScan;
use std::collections::BTreeMap;

/// A move's middle, to a nanometre: the same on every layer, whichever
/// way the bead runs (`(a + b)/2` is `(b + a)/2` in floating point).
fn key(a: [f64; 3], b: [f64; 3]) -> ([i64; 2], [f64; 2]) {
    let m = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
    (m.map(|c| (c * 1e6).round() as i64), m)
}

/// The finish of `program`, the plan of the wall `on`, with every place
/// it looked at; `None` for a plan without a bead or a layer.
pub(super) fn sampled(program: &Program, on: &WallOnScan) -> Option<(Finish, Vec<Sample>)> {
    let d = program.bead.as_ref()?.deposit();
    let mut raised: BTreeMap<[i64; 2], f64> = BTreeMap::new();
    for path in program.layers.iter().flat_map(|l| &l.paths) {
        for w in path.points.windows(2).filter(|w| w[0].laser_on) {
            let (k, _) = key(w[0].pos, w[1].pos);
            *raised.entry(k).or_default() += w[0].predicted_rise(&d, Some(&w[1]));
        }
    }
    let last = program.layers.last()?;
    let top = on.top.0;
    let mut f = Finish {
        points: 0,
        below_mm: 0.0,
        below_at: [0.0; 2],
        above_mm: 0.0,
        above_at: [0.0; 2],
        rms_mm: 0.0,
        first_layer_mm: first_layer(&program.layers[0])?,
        along: None,
    };
    let mut squares = 0.0;
    let mut samples = Vec::new();
    for path in &last.paths {
        for w in path.points.windows(2).filter(|w| w[0].laser_on) {
            let (k, at) = key(w[0].pos, w[1].pos);
            let Some(base) = on.base.surface.at(at) else {
                continue;
            };
            let off = base + raised.get(&k).copied().unwrap_or(0.0) - top;
            samples.push(Sample { at, top, off });
            f.points += 1;
            squares += off * off;
            if -off > f.below_mm {
                (f.below_mm, f.below_at) = (-off, at);
            }
            if off > f.above_mm {
                (f.above_mm, f.above_at) = (off, at);
            }
        }
    }
    (f.points > 0).then(|| {
        f.rms_mm = (squares / f.points as f64).sqrt();
        (f, samples)
    })
}
