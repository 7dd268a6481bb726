//! `lmd::overhang`: a wall's layer must not lean out over the one below by
//! more than the bead can carry. The lean is measured from the nozzle's
//! axis (each point's build direction), as the step across it to the
//! nearest bead of the layer below over the layer's height there: a cone
//! built with a vertical nozzle leans by its half-angle, the same cone with
//! the nozzle following the wall (`nozzle = wall`) by nothing.
//!
//! The limit is the file's `max_overhang`, and a layer past it is an
//! error. Without one, a layer leaning more than
//! [`DEFAULT_OVERHANG`](crate::deposit::DEFAULT_OVERHANG) (45°) or stepping
//! more than half a bead is warned: the melt pool may run off the edge
//! there, and the file says nothing of what its bead carries. Farther than
//! ¾ of a bead is [`super::stacking`]'s (one report for one fault).
//! Only walls one bead wide (a loft's layers) are checked here: a filled
//! planar layer leaning in is carried by the layer below, so its lean is
//! measured against the layer below's region by the planar slicer
//! (`slice::planar`), which knows it.
//! The places checked and their nearest distances are
//! [`super::stacking`]'s.

use super::rule::{ProgramCx, ProgramRule, Worst};
use super::stacking::{nearest, samples, FAR, REACH};
use crate::deposit::{DEFAULT_OVERHANG, DEFAULT_OVERHANG_STEP};
use crate::diag::message::verify::OverhangFix;
use crate::diag::{message, Diagnostics};
use crate::ir::{Kinematics, Machine, PathKind, Program};
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
    let declared = p.limits.max_overhang.map(f64::to_radians);
    // Without `max_overhang`: 45°, or a step of half a bead on a thick layer.
    let limit_at = |h: f64| {
        declared.unwrap_or_else(|| {
            (DEFAULT_OVERHANG.to_radians()).min((DEFAULT_OVERHANG_STEP * w).atan2(h))
        })
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
            let limit = limit_at(h);
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
        declared: declared.is_some(),
        bead: w,
        tilting: p
            .machines
            .iter()
            .find(|m| tilts(m))
            .map(|m| m.name().to_string()),
    };
    out.push(message::verify::overhang(&f, &fix, p.origins.slicing));
}

/// Whether `m` can tilt its nozzle with a wall: a robot, or a CNC's tilting
/// head (a tilting table keeps the nozzle vertical and turns the part,
/// which `nozzle = wall` also builds).
fn tilts(m: &Machine) -> bool {
    match m {
        Machine::Robot(_) => true,
        Machine::Cnc(c) => c.kinematics != Kinematics::Xyz,
    }
}
