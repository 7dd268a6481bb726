//! Slicing: the semantic model's solid → layers of process points (the IR's
//! layers). Reads the model and the geometry built from it.

pub mod feasibility;
mod holes;
pub mod layers;
pub mod normal;
pub mod planar;
pub mod segmented_ring;
pub mod styling;
pub mod top;
pub mod variable;

use crate::diag::message::{self, bend::SeamAdvice};
use crate::diag::Diagnostics;
use crate::geometry::LoftGeometry;
use crate::ir::Layer;
use crate::sema::model::MAX_POINTS;
use crate::sema::model::{Bead, Build, Loft, Model, Resolution, Slicing, Spine};
use crate::units::short;

/// Most points a plan may hold (80 bytes each in the IR, so at most ~1.6 GB):
/// 20 M is over five times the dense benchmark duct, and bounds memory for any
/// input.
pub const MAX_TOTAL_POINTS: usize = 20_000_000;

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
    let geo = LoftGeometry::new(loft);
    let (layers, step) =
        feasibility::choose_layers(loft, &geo, bead, slicing).map_err(Diagnostics::from)?;
    let k = match slicing.resolution {
        Resolution::Count(k) => k,
        Resolution::ChordError(e) => {
            // Chord error of polar sampling on the largest radius; a multiple of
            // 8 puts a point on every corner of a square section.
            let r = geo.blend.max_radius();
            let dth = 2.0 * (1.0 - (e.0 / r).min(1.0)).acos();
            let k = (std::f64::consts::TAU / dth).ceil().max(8.0);
            let k = ((k / 8.0).ceil() * 8.0).min(1e12) as usize;
            if k > MAX_POINTS {
                return Err(
                    message::bend::too_many_layer_points(e, k, MAX_POINTS, slicing.span).into(),
                );
            }
            k
        }
    };
    if layers.saturating_mul(k + 1) > MAX_TOTAL_POINTS {
        return Err(message::bend::too_many_duct_points(
            layers,
            k + 1,
            MAX_TOTAL_POINTS,
            slicing.span,
        )
        .into());
    }
    let plan = normal::Setup {
        seam: slicing.seam.0,
        layers,
        step,
        k,
    };
    let mut out = Vec::with_capacity(layers);
    let mut seam_hits = Vec::new();
    let mut scan = normal::SeamScan::new(k);
    for i in 0..layers {
        let (layer, seam) = normal::layer(model, bead, &geo, &plan, i, &mut scan);
        if let Some(x) = seam {
            if !(normal::SEAM_EXTREME..=1.0 - normal::SEAM_EXTREME).contains(&x) {
                seam_hits.push(i);
            }
        }
        out.push(layer);
    }
    if let (Some(first), Spine::Arc { .. }) = (seam_hits.first(), loft.spine) {
        let seam = slicing.seam;
        warnings.push(message::bend::seam_at_bend_extreme(
            seam_hits.len(),
            *first,
            seam.0,
            &seam_advice(&scan, seam.0, k, seam_hits.len()),
            slicing.seam_span.unwrap_or(slicing.span),
            loft.spine_span,
        ));
    }
    Ok((out, warnings))
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
