//! The layers of a planar plan: how far each one rises (the declared
//! `layer_height`, or what the tracks lay: `A/d` overlapped, `A/w` one track),
//! how many there are (declared, or the extrusion's height in whole layers),
//! and the profile on each (evaluated layer by layer when it follows `layer`).
//! The checker has checked every declaration; what is decided here depends on
//! all of them together.

use crate::diag::message::{self, slicing::BeadHeights, slicing::LiftFix};
use crate::diag::Diagnostics;
use crate::sema::model::MAX_LAYERS;
use crate::sema::model::{
    Bead, Extent, Extrusion, HeightModel, LayerProfile, Measure, PlanarSlicing, Shape,
};
use crate::span::Span;
use crate::units::Length;

/// A declared layer height this far (relative) from what the tracks lay is
/// reported.
const LIFT_TOLERANCE: f64 = 0.02;

/// A height this far (relative) from a whole number of layers is reported.
const HEIGHT_TOLERANCE: f64 = 0.01;

use super::budget::MAX_PROFILE_WORK;

/// The layers an extrusion is built in.
pub struct Layers {
    /// The profile of every layer, in build order.
    pub shapes: Vec<Shape>,
    /// How far every layer rises.
    pub lift: Length,
    /// The strip each track fills (the offset of overlapped tracks, else
    /// the bead's width): the layer rises `A/pitch` ([`crate::deposit`]).
    pub pitch: Length,
    /// Whether the lift was derived from the bead model (`layer_height = auto`).
    pub lift_derived: bool,
}

impl Layers {
    /// Whether the profile differs from layer to layer.
    pub fn varies(&self) -> bool {
        self.shapes.windows(2).any(|w| w[0] != w[1])
    }
}

/// Decides the layers of `extrusion` sliced by `slicing` with `bead`; `None`
/// after reporting why there are none. Warnings (a declared lift the tracks
/// do not lay, a height rounded up) go to `diags` too.
pub fn plan(
    bead: &Bead,
    extrusion: &Extrusion,
    slicing: &PlanarSlicing,
    diags: &mut Diagnostics,
) -> Option<Layers> {
    let width = bead.width;
    let (lift, pitch, lift_derived) = lift(bead, slicing, diags)?;
    // A mesh is held to the plan's limits from its size first: read in
    // the wrong unit, it would be refused only after it is cut.
    let inset = match extrusion.measure {
        Measure::Outer => width.0 / 2.0,
        Measure::Centre => 0.0,
    };
    let band = super::budget::band(slicing, inset);
    if let LayerProfile::Mesh(m) = &extrusion.profile {
        let planned = match extrusion.extent {
            Extent::Layers(n, _) => n as f64,
            Extent::Height(height, _) => layer_count(height, lift),
        };
        super::mesh::plausible(m, (planned, lift), (slicing, band), diags)?;
        super::mesh::wide_enough(m, inset, width, diags)?;
    }
    let n = match extrusion.extent {
        Extent::Layers(n, _) => n,
        Extent::Height(height, at) => whole_layers(height, at, lift, diags)?,
    };
    let shapes = match &extrusion.profile {
        LayerProfile::Fixed(s) => {
            within_budget(s.pieces().saturating_mul(n), extrusion.profile_span, diags)?;
            vec![s.clone(); n]
        }
        LayerProfile::PerLayer(p) => {
            let mut shapes = p.evaluator();
            let mut out = Vec::with_capacity(n.min(1 << 16));
            let mut total = 0usize;
            for k in 0..n {
                let mut scratch = Diagnostics::new();
                match shapes.at(k, k as f64 * lift.0, &mut scratch) {
                    Some(s) if !scratch.has_errors() => {
                        total = total.saturating_add(s.pieces());
                        within_budget(total, extrusion.profile_span, diags)?;
                        out.push(s);
                    }
                    _ => {
                        diags.push(message::slicing::profile_invalid_on_layer(
                            k,
                            extrusion.profile_span,
                        ));
                        diags.extend(scratch);
                        return None;
                    }
                }
            }
            out
        }
        LayerProfile::Mesh(m) => super::mesh::shapes(m, (n, lift), (slicing, band), diags)?,
    };
    Some(Layers {
        shapes,
        lift,
        pitch,
        lift_derived,
    })
}

/// How far each layer rises, the strip each track fills (the offset of
/// overlapped tracks, else the bead's width: the layer rises `A/pitch`
/// at the process speed, [`crate::deposit`]) and whether the lift was
/// derived (`layer_height = auto`); `None` after reporting a lift the bead
/// does not stack.
pub(super) fn lift(
    bead: &Bead,
    slicing: &PlanarSlicing,
    diags: &mut Diagnostics,
) -> Option<(Length, Length, bool)> {
    let overlapped = slicing.overlapped();
    let pitch = if overlapped {
        slicing.offset
    } else {
        bead.width
    };
    let laid = bead.deposit().rise(slicing.speed, pitch, None);
    match slicing.lift {
        Some((l, at)) => declared_lift((l, at), laid, (overlapped, pitch), slicing, bead, diags)
            .map(|l| (l, pitch, false)),
        None => {
            derived_lift(laid, (overlapped, pitch), slicing, bead, diags).map(|l| (l, pitch, true))
        }
    }
}

/// The layers that build `height`: whole ones, at least as tall as asked
/// (machining takes off the rest).
pub(super) fn whole_layers(
    height: Length,
    at: Span,
    lift: Length,
    diags: &mut Diagnostics,
) -> Option<usize> {
    let n = layer_count(height, lift);
    if n > MAX_LAYERS as f64 {
        diags.push(message::slicing::too_many_layers(
            height, lift, MAX_LAYERS, at,
        ));
        return None;
    }
    let n = (n as usize).max(1);
    let built = n as f64 * lift.0;
    if (built - height.0).abs() > HEIGHT_TOLERANCE * height.0 {
        diags.push(message::slicing::height_rounded(n, lift, built, height, at));
    }
    Some(n)
}

/// How many layers of `lift` build `height` (whole ones, not fewer than
/// it needs).
fn layer_count(height: Length, lift: Length) -> f64 {
    // Float noise (a mesh's f32 coordinates in inches) is no extra layer.
    crate::units::whole_count(height.0 / lift.0)
}

fn within_budget(total: usize, at: Span, diags: &mut Diagnostics) -> Option<()> {
    if total <= MAX_PROFILE_WORK {
        return Some(());
    }
    diags.push(message::slicing::too_much_profile(MAX_PROFILE_WORK, at));
    None
}

/// A declared layer height: within the bead's heights (else an error), and
/// reported when it is not what the tracks lay (`laid`).
fn declared_lift(
    (l, at): (Length, Span),
    laid: Length,
    (overlapped, pitch): (bool, Length),
    slicing: &PlanarSlicing,
    bead: &Bead,
    diags: &mut Diagnostics,
) -> Option<Length> {
    if !bead.stacks(l, pitch) {
        diags.push(message::slicing::declared_height_outside(
            l,
            laid,
            &heights(bead, pitch),
            at,
        ));
        return None;
    }
    // The nozzle rises by the declared height, the part by what its tracks
    // lay: a difference adds up layer after layer (seed 001's fixed lift
    // undershot and needed an extra lift every 3 layers).
    // Beyond the deposit's tolerance the verifier refuses the plan
    // (`lmd::deposit`, with the fix): below it the drift is a warning.
    let drift = laid.0 - l.0;
    if drift.abs() > LIFT_TOLERANCE * laid.0 && drift.abs() <= slicing.tolerance.rise * l.0 {
        diags.push(message::slicing::lift_mismatch(l, laid, overlapped, at));
    }
    Some(l)
}

/// `layer_height = auto`: what the tracks lay, if the bead allows it; if not,
/// the error names the offsets (or speeds) that would.
fn derived_lift(
    laid: Length,
    (overlapped, pitch): (bool, Length),
    slicing: &PlanarSlicing,
    bead: &Bead,
    diags: &mut Diagnostics,
) -> Option<Length> {
    if bead.stacks(laid, pitch) {
        return Some(laid);
    }
    let [lo, hi] = bead.heights(pitch);
    let width = bead.width;
    let fix = if overlapped {
        let a = laid.0 * slicing.offset.0;
        LiftFix::Offsets {
            range: [a / hi.0, a / lo.0],
            area: a,
        }
    } else {
        wall_fix(bead, width, lo, hi)
    };
    let at = if overlapped {
        slicing.offset_span.unwrap_or(slicing.span)
    } else {
        slicing.span
    };
    diags.push(message::slicing::derived_height_outside(
        laid,
        overlapped,
        &heights(bead, pitch),
        at,
        &fix,
    ));
    None
}

/// The heights the bead stacks at `pitch`, for the messages.
fn heights(bead: &Bead, pitch: Length) -> BeadHeights<'_> {
    BeadHeights {
        name: &bead.name,
        height: bead.heights(pitch),
        span: bead.height_span,
    }
}

/// What makes a one-track layer rise by an allowed height: the scan speeds at
/// which `A/w` lies in `lo .. hi` (within the bead's speed range), or overlap.
fn wall_fix(bead: &Bead, w: Length, lo: Length, hi: Length) -> LiftFix {
    if let HeightModel::Measured { .. } = bead.model {
        return LiftFix::Measured;
    }
    // The speed at which a lone track rises r.
    let deposit = bead.deposit();
    let speed = |r: Length| deposit.speed_for(r, w).0;
    let (a, b) = (speed(lo), speed(hi));
    let (a, b) = (a.min(b).max(bead.speed[0].0), a.max(b).min(bead.speed[1].0));
    if a.is_finite() && b.is_finite() && a <= b {
        LiftFix::Speeds([a, b])
    } else {
        LiftFix::NoSpeed
    }
}
