//! `follow = surface` (docs/repair.md, *Following the surface*): on a
//! tilting machine the layers that lie on a curved scan are laid with the
//! nozzle along the normal of the surface they lie on, as a bead is
//! measured on a coupon, instead of straight down on a slope.
//!
//! Layer `i` of `N` (or levelling pass `k` of the `n` a place takes) lies
//! on `B + f·(top − B)`, `f = i/N`: over a flat top (or the flat level a
//! levelling fills to) its slope is `(1 − f)·∇B`, and its build direction
//! is that surface's normal, `(−(1 − f)·∇B, 1)` made unit. The first layer
//! is on the scan's own normal; each next one is nearer vertical, and the
//! layers above the level are vertical. `∇B` is the slope of a plane
//! fitted to the scan's robust surface estimate ([`HeightField`]) over a
//! bead's width either way: the powder spot and the beads beside it, what
//! the bead lies on. A finer slope is noise to the nozzle, and near
//! vertical a noisy normal's direction would swing a head's C axis.
//!
//! The tilt is capped at the least of the bead's measured `tilt` (its
//! heights hold there) and each tilting CNC's tilt axis (the larger of its
//! limits' ends: the C axis turns the other way round). A robot's arm has
//! no such single limit; reach and singularities are its verifier's.
//!
//! A tilted nozzle lays a bead whose thickness is along its axis. Where the
//! surface slopes by `α` along the track and the normal tilts by `θ`, the
//! layer's thickness along the normal is `h·cos θ` for a vertical rise `h`,
//! the strip it fills, measured in the surface across the track, is
//! `p·cos α / cos θ` for tracks `p` apart, and the metal per length
//! along the path that raises it by `h` is the bead map's at pitch `p` for
//! `h·cos α` ([`Tilted`]).

use crate::diag::{message, Diagnostics};
use crate::geometry::scan::HeightField;
use crate::ir::{Kinematics, Machine};
use crate::sema::model::{Bead, Model, TopExtrusion, VariableSlicing};
use nalgebra::{Matrix3, Vector3};

/// The most cells either way the slope is fitted over: a coarse scan's
/// cell, or a wide bead, still fits over at most 17 × 17 samples.
const MAX_HALF_WINDOW: f64 = 8.0;

/// A layer's nozzle along the scan's normal, up to `max_tan`.
#[derive(Clone, Copy, Debug)]
pub struct Follow<'m> {
    surface: &'m HeightField,
    /// How far either way the slope is fitted over, mm: a bead's width.
    reach: f64,
    /// `tan` of the largest tilt from the planning frame's vertical.
    max_tan: f64,
    /// Planned turned (along a tilted build direction): the part's
    /// vertical in the planning frame, and `cos` of the largest tilt from
    /// it. What the head reaches is the nozzle's whole tilt in the part,
    /// the direction's and the surface's together.
    part: Option<([f64; 3], f64)>,
}

/// What a tilted point lays: its build direction and the factors its
/// layer height, pitch and target height take (all 1 when vertical).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tilted {
    /// The unit build direction.
    pub normal: [f64; 3],
    /// `cos θ`: vertical thickness to thickness along the normal.
    pub along_normal: f64,
    /// `cos α`: the surface's slope along the track, what the bead map's
    /// height at pitch `p` is scaled by.
    pub along_track: f64,
}

impl Tilted {
    /// Straight down.
    pub const VERTICAL: Tilted = Tilted {
        normal: [0.0, 0.0, 1.0],
        along_normal: 1.0,
        along_track: 1.0,
    };

    /// The strip the point fills, measured in its surface, for tracks `p`
    /// apart.
    pub fn pitch(&self, p: f64) -> f64 {
        p * self.along_track / self.along_normal
    }
}

/// Whether the nozzle can follow the scan when `follow = surface`: every
/// refusal, a bead measured vertical and each machine whose nozzle stays
/// vertical (the part built on a scan is sema's check).
pub fn check(model: &Model, bead: &Bead, slicing: &VariableSlicing) -> Result<(), Diagnostics> {
    let Some(at) = slicing.follow else {
        return Ok(());
    };
    let mut out = Diagnostics::new();
    if bead.tilt.is_none() {
        out.push(message::scan::follow_untilted_bead(
            &bead.name, at, bead.span,
        ));
    }
    for (m, origin) in &model.machines {
        if let Machine::Cnc(c) = m {
            if c.effective_kinematics() == Kinematics::Xyz {
                let axes = origin.at(crate::ir::MachineField::Axes);
                out.push(message::scan::follow_on_vertical_machine(
                    m.name(),
                    at,
                    axes,
                ));
            }
        }
    }
    if out.is_empty() {
        Ok(())
    } else {
        Err(out)
    }
}

/// The largest tilt from vertical, rad: the bead's measured upper tilt and
/// each tilting CNC's tilt axis reach. `None` unless `follow = surface` and
/// [`check`] holds.
pub fn limit(model: &Model, bead: &Bead, slicing: &VariableSlicing) -> Option<f64> {
    slicing.follow?;
    let (tilt, _) = bead.tilt?;
    let machines = model.machines.iter().filter_map(|(m, _)| match m {
        Machine::Cnc(c) if c.effective_kinematics() != Kinematics::Xyz => {
            let [lo, hi] = c.limits.tilt;
            Some(lo.abs().max(hi.abs()).to_radians())
        }
        _ => None,
    });
    let most = machines.fold(tilt[1].max(0.0), f64::min);
    Some(most.clamp(0.0, 89.0_f64.to_radians()))
}

/// The part's vertical in the frame `ex` is planned in, when it is planned
/// turned (along a tilted build direction): what [`Follow::turned`] holds
/// the nozzle's whole tilt from.
pub fn part_vertical(ex: &TopExtrusion) -> Option<[f64; 3]> {
    Some(ex.turned.as_ref()?.planned([0.0, 0.0, 1.0]))
}

impl<'m> Follow<'m> {
    /// Following `surface` up to `max` rad from vertical, its slope
    /// fitted over `reach` mm either way (a bead's width).
    pub fn new(surface: &'m HeightField, max: f64, reach: f64) -> Self {
        Follow {
            surface,
            reach,
            max_tan: max.tan(),
            part: None,
        }
    }

    /// This following planned turned, the part's vertical `up` (a unit
    /// vector in the planning frame): the nozzle's tilt from it held to
    /// the same largest tilt.
    pub fn turned(mut self, up: Option<[f64; 3]>) -> Self {
        let max = self.max_tan.atan();
        self.part = up.map(|u| (u, max.cos()));
        self
    }

    /// The slope `g` scaled down, its direction kept, until the nozzle
    /// tilts at most the largest tilt from the part's vertical (planned
    /// turned). Unscaled, the nozzle is along the build direction, which
    /// the direction's search holds within the same tilt; the scale is
    /// bisected between the two (the tilt need not grow with it: a slope
    /// toward the part's vertical first brings the nozzle nearer it).
    fn within_reach(&self, g: [f64; 2]) -> [f64; 2] {
        let Some((up, min_cos)) = self.part else {
            return g;
        };
        let cos = |s: f64| {
            let n = [-s * g[0], -s * g[1], 1.0];
            let len = (n[0] * n[0] + n[1] * n[1] + 1.0).sqrt();
            (n[0] * up[0] + n[1] * up[1] + n[2] * up[2]) / len
        };
        if cos(1.0) >= min_cos {
            return g;
        }
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..40 {
            let mid = 0.5 * (lo + hi);
            if cos(mid) >= min_cos {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        g.map(|v| v * lo)
    }

    /// The scan's slope at `p`: the least-squares plane through its
    /// surface sampled every cell over `reach` either way along x and y.
    /// Only samples whose mirror about `p` is on the scan too are taken
    /// (a window symmetric about `p` gives a quadratic surface's slope at
    /// `p` exactly; one cut by the scan's edge, the slope a cell or two
    /// inward); where they do not fix a plane, every sample; flat where
    /// those do not either.
    pub fn gradient(&self, p: [f64; 2]) -> [f64; 2] {
        let c = self.surface.cell();
        let k = (self.reach / c).ceil().clamp(1.0, MAX_HALF_WINDOW) as i32;
        let at = |i: i32, j: i32| self.surface.at([p[0] + i as f64 * c, p[1] + j as f64 * c]);
        [true, false]
            .into_iter()
            .find_map(|mirrored| {
                // z = a + gx·x + gy·y about p: its normal equations.
                let mut m = Matrix3::<f64>::zeros();
                let mut r = Vector3::<f64>::zeros();
                for i in -k..=k {
                    for j in -k..=k {
                        let Some(z) = at(i, j) else { continue };
                        if mirrored && at(-i, -j).is_none() {
                            continue;
                        }
                        let v = Vector3::new(1.0, i as f64 * c, j as f64 * c);
                        m += v * v.transpose();
                        r += v * z;
                    }
                }
                let x = m.lu().solve(&r)?;
                (x[1].is_finite() && x[2].is_finite()).then_some([x[1], x[2]])
            })
            .unwrap_or([0.0, 0.0])
    }

    /// The point at `p` on a layer whose slope is `weight` of the scan's
    /// (`1 − i/N`), its track running along the unit direction `along`
    /// (x–y; either way).
    pub fn at(&self, p: [f64; 2], weight: f64, along: [f64; 2]) -> Tilted {
        let g = self.gradient(p).map(|v| v * weight.clamp(0.0, 1.0));
        let t = g[0].hypot(g[1]);
        // Capped: the slope's direction kept, its tilt the most allowed.
        let g = self.within_reach(if t > self.max_tan {
            g.map(|v| v * self.max_tan / t)
        } else {
            g
        });
        let len = (1.0 + g[0] * g[0] + g[1] * g[1]).sqrt();
        // Along an axis, that slope alone, exactly (the other times 0).
        let along = g[0] * along[0] + g[1] * along[1];
        Tilted {
            normal: [-g[0] / len, -g[1] / len, 1.0 / len],
            along_normal: 1.0 / len,
            along_track: 1.0 / along.hypot(1.0),
        }
    }
}
