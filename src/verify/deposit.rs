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

use super::rule::{ProgramCx, ProgramRule, Worst};
use crate::bead::HeightModel;
use crate::diag::message::verify::deposit::{DepositMiss, Drift, WorstPoint};
use crate::diag::{message, Diagnostics};
use crate::ir::Program;
use crate::plan::Where;
use crate::units::Length;

/// The rule.
pub(super) struct DepositRule;

impl ProgramRule for DepositRule {
    fn check(cx: &ProgramCx<'_>, out: &mut Diagnostics) {
        if let Some(miss) = check(cx.program) {
            let o = &cx.program.origins;
            out.push(message::verify::deposit::deposit_miss(
                &miss,
                o.bead_speed,
                o.slicing,
            ));
        }
    }
}

/// A run of moves at one speed over one strip: a constant-speed segment of
/// a variable layer's track lays one rise over the heights its points plan,
/// so the run is compared as a whole, by its means over its length.
#[derive(Default)]
struct Run {
    len: f64,
    rise: f64,
    planned: f64,
    /// Where it starts, and its first point's numbers.
    at: Option<(Where, WorstPoint)>,
}

/// Everything the rule finds in `p`, or `None` when the plan lays what it
/// plans (or has no bead model to predict with).
pub(crate) fn check(p: &Program) -> Option<DepositMiss<Where>> {
    let bead = p.bead.as_ref()?;
    let d = bead.deposit();
    let mut found = Found {
        tol: p.limits.rise_tolerance,
        strips: [f64::INFINITY, 0.0],
        ..Found::default()
    };
    let mut drift = Drift::default();
    let mut accumulated = 0.0;
    for (li, layer) in p.layers.iter().enumerate() {
        let (mut len_sum, mut err_sum) = (0.0, 0.0);
        for (pi, path) in layer.paths.iter().enumerate() {
            let mut run = Run::default();
            let mut key = None;
            for (k, pt) in path.points.iter().enumerate() {
                let next = path.points.get(k + 1);
                let here = (pt.laser_on && pt.pitch > 0.0 && pt.layer_height > 0.0)
                    .then_some((pt.speed, pt.pitch, pt.powder));
                if here != key {
                    found.close(std::mem::take(&mut run));
                    key = here;
                }
                if here.is_none() {
                    continue;
                }
                let rise = pt.predicted_rise(&d, next);
                // The layer's height along the move: the mean of its ends'.
                let h = match next {
                    Some(q) if q.layer_height > 0.0 => {
                        0.5 * (pt.layer_height as f64 + q.layer_height as f64)
                    }
                    _ => pt.layer_height as f64,
                };
                let len = pt.ground_to(next);
                found.checked += 1;
                let strip = pt.pitch as f64;
                found.strips = [found.strips[0].min(strip), found.strips[1].max(strip)];
                len_sum += len;
                err_sum += len * (rise - h);
                found.laid += len * rise;
                found.planned += len * h;
                run.len += len;
                run.rise += len * rise;
                run.planned += len * h;
                run.at.get_or_insert((
                    Where::Point {
                        layer: li,
                        path: pi,
                        point: k,
                    },
                    WorstPoint {
                        planned: h,
                        rise,
                        speed: pt.speed_across(next),
                        pitch: pt.pitch as f64,
                        needs: (!matches!(d.model, HeightModel::Measured { .. }))
                            .then(|| d.speed_for(Length(h), Length(pt.pitch as f64)).0),
                        style: pt.style,
                    },
                ));
            }
            found.close(run);
        }
        if len_sum > 0.0 {
            accumulated += err_sum / len_sum;
            drift.add(li, accumulated, p.limits.max_drift);
        }
    }
    drift.layers = p.layers.len();
    drift.limit = p.limits.max_drift;
    if found.worst.is_none() && drift.passed.is_none() {
        return None;
    }
    Some(DepositMiss {
        worst: found.worst,
        point: found.point,
        checked: found.checked,
        share: if found.planned > 0.0 {
            found.laid / found.planned
        } else {
            1.0
        },
        tolerance: found.tol,
        drift,
        strips: found.strips,
        style: found
            .point
            .filter(|w| w.style != 0 && w.needs.is_some())
            .map(|w| style_speeds(p, &d, w.style)),
    })
}

/// The rise a point lays at the path speed `v`, and the speed across the
/// normal over the path speed (the style's speed is a path speed).
fn rise_at(d: &crate::deposit::Deposit, pt: &crate::ir::Point, across: f64, v: f64) -> f64 {
    let powder = crate::units::MassFlow(pt.powder as f64 / 60.0);
    d.rise(
        crate::units::Speed(v * across),
        Length(pt.pitch as f64),
        Some(powder),
    )
    .0
}

/// The speed in `1e-3 .. 1e5` mm/s at which the decreasing `f` crosses 0.
fn root(f: impl Fn(f64) -> f64) -> f64 {
    let (mut lo, mut hi) = (1e-3f64, 1e5f64);
    for _ in 0..80 {
        let mid = (lo * hi).sqrt();
        if f(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    (lo * hi).sqrt()
}

/// The speeds `style`'s own speed may take: each of its deposits' speeds
/// within the tolerance, and the one that lays its tracks' planned
/// heights on the whole.
fn style_speeds(
    p: &Program,
    d: &crate::deposit::Deposit,
    style: u16,
) -> message::verify::deposit::StyleSpeeds {
    let tol = p.limits.rise_tolerance;
    let mut moves = Vec::new();
    for path in p.layers.iter().flat_map(|l| &l.paths) {
        for (k, pt) in path.points.iter().enumerate() {
            let next = path.points.get(k + 1);
            let len = pt.ground_to(next);
            if pt.style != style || !pt.laser_on || pt.pitch <= 0.0 || len <= 0.0 {
                continue;
            }
            let h = match next {
                Some(q) if q.layer_height > 0.0 => {
                    0.5 * (pt.layer_height as f64 + q.layer_height as f64)
                }
                _ => pt.layer_height as f64,
            };
            let across = if pt.speed > 0.0 {
                pt.speed_across(next) / pt.speed as f64
            } else {
                1.0
            };
            moves.push((pt, across, h, len));
        }
    }
    let (mut lo, mut hi) = (0.0f64, f64::INFINITY);
    let mut strips = [f64::INFINITY, 0.0f64];
    for &(pt, across, h, _) in &moves {
        lo = lo.max(root(|v| rise_at(d, pt, across, v) - h * (1.0 + tol)));
        hi = hi.min(root(|v| rise_at(d, pt, across, v) - h * (1.0 - tol)));
        strips = [
            strips[0].min(pt.pitch as f64),
            strips[1].max(pt.pitch as f64),
        ];
    }
    let even = root(|v| {
        moves
            .iter()
            .map(|&(pt, across, h, len)| len * (rise_at(d, pt, across, v) - h))
            .sum()
    });
    message::verify::deposit::StyleSpeeds {
        style,
        strips,
        fits: (lo <= hi && !moves.is_empty()).then(|| (even.clamp(lo, hi), [lo, hi])),
    }
}

/// The runs off by more than the tolerance, and the plan's totals.
#[derive(Default)]
struct Found {
    tol: f64,
    worst: Option<Worst>,
    point: Option<WorstPoint>,
    checked: u64,
    laid: f64,
    planned: f64,
    /// The narrowest and widest strip of a laser-on point, mm.
    strips: [f64; 2],
}

impl Found {
    /// Compares a finished run's mean rise with its mean planned height.
    fn close(&mut self, run: Run) {
        let Some((at, mut point)) = run.at else {
            return;
        };
        // A run of one point (a last point, no length) is that point.
        let (rise, planned) = if run.len > 0.0 {
            (run.rise / run.len, run.planned / run.len)
        } else {
            (point.rise, point.planned)
        };
        let ratio = rise / planned;
        if (ratio - 1.0).abs() <= self.tol {
            return;
        }
        let before = self.worst.map(|w| w.at);
        let limit = if ratio > 1.0 {
            1.0 + self.tol
        } else {
            1.0 - self.tol
        };
        Worst::hit(&mut self.worst, ratio, limit, at);
        if self.worst.map(|w| w.at) != before {
            point.rise = rise;
            point.planned = planned;
            self.point = Some(point);
        }
    }
}
