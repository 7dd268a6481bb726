//! `lmd::deposit`: the plan's own bead model must lay the layers it plans.
//! Layer by layer, every laser-on point's rise is predicted from its speed
//! across the normal, its powder and the strip it fills
//! ([`crate::deposit`]: `A/pitch`) and compared with its layer height:
//!
//! - each point within `rise_tolerance` of it (a few per cent: the scatter
//!   of a calibration and the speed resolution a program writes at);
//! - the layers' errors, each layer's mean over its deposited length, added
//!   up over the layers within `max_drift`: an error small on each layer
//!   still lifts the nozzle away from the part (or into it) layer after
//!   layer, and a standoff off by more than about half a millimetre changes
//!   how much powder the melt pool catches.
//!
//! One diagnostic, with the worst point, how many miss, the whole plan's
//! share and where the drift passes its bound.

use super::rule::{ProgramCx, ProgramRule};
use crate::diag::message::check::deposit::{DepositMiss, Drift, WorstPoint};
use crate::diag::{message, Diagnostics, Worst};
use crate::ir::{Point, Program};
use crate::plan::Where;
use crate::units::{Length, MassFlow, Speed};

/// The rule.
pub(super) struct DepositRule;

impl ProgramRule for DepositRule {
    fn check(cx: &ProgramCx<'_>, out: &mut Diagnostics) {
        if let Some(miss) = check(cx.program) {
            let o = &cx.program.origins;
            out.push(message::check::deposit::deposit_miss(
                &miss,
                o.bead_speed,
                o.slicing,
            ));
        }
    }
}

/// What a point lays by the model, mm.
fn predicted(d: &crate::deposit::Deposit, pt: &Point, next: Option<&Point>) -> f64 {
    let v = Speed(pt.speed_across(next));
    let powder = MassFlow(pt.powder as f64 / 60.0);
    d.rise(v, Length(pt.pitch as f64), Some(powder)).0
}

/// The ground a move covers (across the normal), mm: what a layer's mean
/// is weighted by.
fn ground(pt: &Point, next: Option<&Point>) -> f64 {
    let Some(q) = next else { return 0.0 };
    let d = [
        q.pos[0] - pt.pos[0],
        q.pos[1] - pt.pos[1],
        q.pos[2] - pt.pos[2],
    ];
    let n = pt.normal.map(f64::from);
    let along = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
    (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - along * along)
        .max(0.0)
        .sqrt()
}

/// Everything the rule finds in `p`, or `None` when the plan lays what it
/// plans (or has no bead model to predict with).
pub(crate) fn check(p: &Program) -> Option<DepositMiss> {
    let bead = p.bead?;
    let d = bead.deposit();
    let tol = p.limits.rise_tolerance;
    let mut worst: Option<Worst> = None;
    let mut worst_point: Option<WorstPoint> = None;
    let (mut checked, mut laid, mut planned) = (0u64, 0.0, 0.0);
    let mut drift = Drift::default();
    let mut accumulated = 0.0;
    for (li, layer) in p.layers.iter().enumerate() {
        let (mut len_sum, mut err_sum) = (0.0, 0.0);
        for (pi, path) in layer.paths.iter().enumerate() {
            for (k, pt) in path.points.iter().enumerate() {
                if !pt.laser_on || pt.pitch <= 0.0 || pt.layer_height <= 0.0 {
                    continue;
                }
                let next = path.points.get(k + 1);
                let rise = predicted(&d, pt, next);
                let h = pt.layer_height as f64;
                let len = ground(pt, next);
                checked += 1;
                len_sum += len;
                err_sum += len * (rise - h);
                laid += len * rise;
                planned += len * h;
                let ratio = rise / h;
                if (ratio - 1.0).abs() > tol {
                    let at = Where::Point {
                        layer: li,
                        path: pi,
                        point: k,
                    };
                    let before = worst.map(|w| w.at);
                    let limit = if ratio > 1.0 { 1.0 + tol } else { 1.0 - tol };
                    Worst::hit(&mut worst, ratio, limit, at);
                    if worst.map(|w| w.at) != before {
                        worst_point = Some(WorstPoint {
                            planned: h,
                            rise,
                            speed: pt.speed_across(next),
                            pitch: pt.pitch as f64,
                            needs: d.speed_for(Length(h), Length(pt.pitch as f64)).0,
                            style: pt.style,
                        });
                    }
                }
            }
        }
        if len_sum > 0.0 {
            accumulated += err_sum / len_sum;
            drift.add(li, accumulated, p.limits.max_drift);
        }
    }
    drift.layers = p.layers.len();
    drift.limit = p.limits.max_drift;
    if worst.is_none() && drift.passed.is_none() {
        return None;
    }
    Some(DepositMiss {
        worst,
        point: worst_point,
        checked,
        share: if planned > 0.0 { laid / planned } else { 1.0 },
        tolerance: tol,
        drift,
    })
}
