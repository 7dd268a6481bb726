//! Slicing: the semantic model's solid → layers of process points (the IR's
//! layers). Reads the model and the geometry built from it.

mod budget;
pub mod calibration;
pub mod feasibility;
mod holes;
pub mod layers;
mod mesh;
pub mod normal;
pub mod planar;
mod section_points;
pub mod segmented_ring;
pub mod spiral;
pub mod styling;
pub mod top;
pub mod variable;
pub mod wall;

use crate::diag::message::{self, bend::LayerAt, bend::SeamAdvice};
use crate::diag::Diagnostics;
use crate::ir::Layer;
use crate::sema::model::MAX_POINTS;
use crate::sema::model::{
    Bead, Build, LayerChange, Loft, Model, Resolution, SeamRule, Slicing, Spine,
};
use crate::span::Span;
use crate::units::short;
use section_points::Spacing;

/// Most points a plan may hold (80 bytes each in the IR, so at most ~1.6 GB):
/// 20 M is over five times the dense benchmark duct, and bounds memory for any
/// input.
pub const MAX_TOTAL_POINTS: usize = 20_000_000;

/// `Ok` when `layers` of `per_layer` points each are within the plan's
/// point budget ([`MAX_TOTAL_POINTS`]); else the error, at `span` (the
/// slicing, or the field that asks for the points).
pub(crate) fn within_points(per_layer: usize, layers: u32, span: Span) -> Result<(), Diagnostics> {
    if per_layer.saturating_mul(layers as usize) > MAX_TOTAL_POINTS {
        let d = message::top::too_many_points(layers, per_layer, MAX_TOTAL_POINTS, span);
        return Err(d.into());
    }
    Ok(())
}

/// Points of a planar track closer than this (mm) are one point.
pub const DISTINCT: f64 = 1e-6;

/// `points` with each run of points closer than [`DISTINCT`] kept as its
/// first: what a planar track keeps.
pub fn dedup_points(points: &mut Vec<[f64; 2]>) {
    points.dedup_by(|b, a| (b[0] - a[0]).hypot(b[1] - a[1]) <= DISTINCT);
}

/// Slices the model's solid. Returns the layers and their diagnostics
/// (warnings, and errors that leave every layer made, such as a spot left
/// unfilled), or the errors when there are no layers to go on with.
pub fn slice(model: &Model) -> Result<(Vec<Layer>, Diagnostics), Diagnostics> {
    if let Build::Ring(r) = &model.build {
        return segmented_ring::build(r).map(|(layers, _)| (layers, Diagnostics::new()));
    }
    // The checker builds every other plan with its bead model.
    let Some(bead) = &model.bead else {
        return Err(message::internal::no_bead_in_slicing().into());
    };
    match &model.build {
        Build::Duct { loft, slicing } => duct(model, bead, loft, slicing),
        Build::Block { extrusion, slicing } => planar::slice(model, bead, extrusion, slicing),
        Build::Variable { extrusion, slicing } => top::slice(model, bead, extrusion, slicing),
        Build::Ring(r) => segmented_ring::build(r).map(|(layers, _)| (layers, Diagnostics::new())),
        Build::Calibration(c) => Ok((calibration::build(c, &model.process), Diagnostics::new())),
        Build::Wall {
            wall,
            extent,
            slicing,
        } => wall::slice(model, bead, wall, *extent, slicing),
        Build::ScanWall {
            wall,
            on,
            slicing,
            pitch,
        } => wall::slice_on_scan(model, bead, wall, on, slicing, *pitch),
    }
}

/// Normal (continuous gradual) slicing of a loft.
fn duct(
    model: &Model,
    bead: &Bead,
    loft: &Loft,
    slicing: &Slicing,
) -> Result<(Vec<Layer>, Diagnostics), Diagnostics> {
    let mut warnings = Diagnostics::new();
    let geo = loft.geometry();
    let spacing = match slicing.resolution {
        Resolution::Count(k) => Spacing::Count(k),
        Resolution::ChordError(e) => Spacing::Chord {
            error: e.0,
            rise: slicing.tolerance.rise,
        },
    };
    // The points every layer will have, from a few sections: the layers
    // and points are held to the plan's limits before any layer's seam or
    // points are allocated.
    let per_layer = section_points::fewest(&geo, spacing, MAX_POINTS)
        .map_err(|(s, k)| too_many_points(slicing, LayerAt::Along(s), k))?;
    let (layers, step) = feasibility::choose_layers(loft, &geo, bead, slicing, per_layer)
        .map_err(Diagnostics::from)?;
    if layers.saturating_mul(per_layer) > MAX_TOTAL_POINTS {
        return Err(message::bend::too_many_duct_points(
            layers,
            per_layer,
            MAX_TOTAL_POINTS,
            matches!(spacing, Spacing::Chord { .. }),
            slicing.span,
        )
        .into());
    }
    let plan = normal::Setup {
        seam: slicing.seam,
        starts: normal::seam_angles(&geo, slicing.seam, layers),
        layers,
        step,
        spacing,
        max_points: MAX_POINTS,
        follow: slicing.follow_wall,
        rise: slicing.tolerance.rise,
        climb: match slicing.layer_change {
            LayerChange::Lift => None,
            LayerChange::Spiral { length } => Some(length.map_or(f64::INFINITY, |l| l.0)),
        },
    };
    let mut out = Vec::with_capacity(layers);
    let mut seam_hits = Vec::new();
    let mut scan = normal::SeamScan::new(plan.scan_grid());
    let mut total = 0usize;
    for i in 0..layers {
        let (layer, seam) = normal::layer(model, bead, &geo, &plan, i, &mut scan)
            .map_err(|k| too_many_points(slicing, LayerAt::Layer(i + 1), k))?;
        total += layer.paths.iter().map(|p| p.points.len()).sum::<usize>();
        if total > MAX_TOTAL_POINTS {
            let k = layer.paths.iter().map(|p| p.points.len()).sum::<usize>();
            return Err(message::bend::too_many_duct_points(
                layers,
                k,
                MAX_TOTAL_POINTS,
                matches!(spacing, Spacing::Chord { .. }),
                slicing.span,
            )
            .into());
        }
        if let Some(x) = seam {
            if !(normal::SEAM_EXTREME..=1.0 - normal::SEAM_EXTREME).contains(&x) {
                seam_hits.push(i);
            }
        }
        out.push(layer);
    }
    if slicing.layer_change.is_spiral() {
        spiral::join_layers(&mut out);
    }
    if let (Some(first), Spine::Arc { .. }, SeamRule::Toward(seam)) =
        (seam_hits.first(), loft.spine, slicing.seam)
    {
        warnings.push(message::bend::seam_at_bend_extreme(
            seam_hits.len(),
            *first,
            seam.0,
            &seam_advice(&scan, seam.0, plan.scan_grid(), seam_hits.len()),
            slicing.seam_span.unwrap_or(slicing.span),
            loft.spine_span,
        ));
    }
    Ok((out, warnings))
}

/// A layer (`at`) needs `k` points (or more), more than a layer may hold.
fn too_many_points(slicing: &Slicing, at: LayerAt, k: usize) -> Diagnostics {
    match slicing.resolution {
        Resolution::ChordError(e) => {
            message::bend::too_many_layer_points(e, MAX_POINTS, at, slicing.span).into()
        }
        Resolution::Count(_) => {
            message::bend::too_many_section_points(k, MAX_POINTS, slicing.span).into()
        }
    }
}

/// Where to put a seam that sits at the bend's extremes on `hits` layers:
/// the sample angle (the seam + j·2π/k) that does so on the fewest.
fn seam_advice(scan: &normal::SeamScan, seam: f64, k: usize, hits: usize) -> SeamAdvice {
    match scan.best() {
        Some((j, 0)) => SeamAdvice::Everywhere(advised_angle(seam, j, k)),
        Some((j, n)) if n < hits => SeamAdvice::Fewest(advised_angle(seam, j, k), n),
        _ => SeamAdvice::None,
    }
}

/// Sample `j`'s angle, in degrees within 0 ..< 360.
fn advised_angle(seam: f64, j: usize, k: usize) -> String {
    let deg = (seam + j as f64 * std::f64::consts::TAU / k as f64)
        .to_degrees()
        .rem_euclid(360.0);
    short(if deg >= 360.0 - 1e-9 { 0.0 } else { deg })
}
