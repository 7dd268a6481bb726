//! Planar slicing of an extrusion: flat layers `lift` apart, each filled with
//! contour passes and raster tracks (seed 001).

use crate::diag::{Diagnostic, Diagnostics};
use crate::ir::Layer;
use crate::sema::model::{Extrusion, Model, PlanarSlicing};

/// Slices an extrusion into filled planar layers.
pub fn slice(
    _model: &Model,
    _extrusion: &Extrusion,
    slicing: &PlanarSlicing,
) -> Result<(Vec<Layer>, Diagnostics), Diagnostics> {
    Err(
        Diagnostic::error("lmd::unsupported", "planar slicing is not built yet")
            .label(slicing.span, "planar")
            .into(),
    )
}
