//! `lmd::overhang`: a wall's layer must not lean out over the one below by
//! more than the bead can carry. The lean is measured from the nozzle's
//! axis (each point's build direction), as the step across it to the
//! nearest bead of the layer below over the layer's height there: a cone
//! built with a vertical nozzle leans by its half-angle, the same cone with
//! the nozzle following the wall (`nozzle = wall`) by nothing.
//!
//! The limit is the file's `max_overhang`. Without one, the limit is what
//! the bead carries at all, a step of ¾ of its width a layer
//! (`atan(3w / 4h)` at the layer's height `h`), which [`super::stacking`]
//! already holds every deposit to and reports with the lean (one report
//! for one fault), so this rule runs only where `max_overhang` is written.
//! Only walls one bead wide (a loft's layers) are checked here: a filled
//! planar layer leaning in is carried by the layer below, so its lean is
//! measured against the layer below's region by the planar slicer
//! (`slice::planar`), which knows it.
//! The places checked and their nearest distances are
//! [`super::stacking`]'s.

use super::rule::{ProgramCx, ProgramRule, Worst};
use super::stacking::{nearest, samples, FAR, REACH};
use crate::diag::message::verify::OverhangFix;
use crate::diag::{message, Diagnostics};
use crate::ir::{PathKind, Program};
use crate::plan::Where;

/// `lmd::overhang`: wall layers leaning out over the layer below by more
/// than the bead carries.
pub(super) struct Overhang;

impl ProgramRule for Overhang {
    fn check(cx: &ProgramCx<'_>, out: &mut Diagnostics) {
        check(cx.program, out);
    }
}

fn check(p: &Program, out: &mut Diagnostics) {
    let w = p.limits.bead_width;
    // The IR holds degrees; the leans below are radians.
    let Some(limit) = p.limits.max_overhang.map(f64::to_radians) else {
        return;
    };
    if !(w.is_finite() && w > 0.0) {
        return;
    }
    let h_max = p.limits.layer_height[1];
    let reach = ((w * REACH).powi(2) + h_max.powi(2)).sqrt() * 1.01;
    let far = (FAR * w).max(reach);
    let step = w / 8.0;
    let mut found: Option<Worst> = None;
    // The step and the layer height at the worst place.
    let mut there = (0.0, 0.0, false);
    for (li, pair) in p.layers.windows(2).enumerate() {
        let (below, here) = (&pair[0], &pair[1]);
        if here.on_plate {
            continue;
        }
        let walls: Vec<_> = samples(here, step, reach)
            .into_iter()
            .filter(|s| here.paths[s.path].kind == PathKind::Wall)
            .collect();
        if walls.is_empty() {
            continue;
        }
        let Some(best) = nearest(below, &walls, step, [reach, far], h_max) else {
            continue;
        };
        for (s, d) in walls.iter().zip(&best) {
            // Farther is off the layer below: lmd::stacking's.
            let Some(d) = d.filter(|&d| d <= w * REACH) else {
                continue;
            };
            let h = here.paths[s.path].points[s.point].layer_height as f64;
            if h.is_nan() || h <= 0.0 {
                continue;
            }
            let lean = d.atan2(h);
            if lean > limit {
                let at = Where::Point {
                    layer: li + 1,
                    path: s.path,
                    point: s.point,
                };
                Worst::hit(&mut found, lean, limit, at);
                if found.is_some_and(|f| f.at == at) {
                    there = (d, h, false);
                }
            }
        }
    }
    let Some(f) = found else { return };
    let fix = OverhangFix {
        step: there.0,
        height: there.1,
        planar: there.2,
    };
    out.push(message::verify::overhang(&f, &fix, p.origins.slicing));
}
