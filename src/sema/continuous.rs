//! `slicing continuous { layers, layer_height, step }` (seed 004): a ring's
//! layers laid in one run, each rising `layer_height` inside the last
//! transition of the layer below, the points at most `step` apart.

use super::eval::Env;
use super::fields::Fields;
use super::model::MAX_LAYERS;
use crate::diag::{message, Diagnostics};
use crate::span::Span;
use crate::syntax::ast::Stmt;
use crate::units::{Angle, Dim, Length};
use std::num::NonZeroUsize;

/// Fields of `slicing continuous { … }`.
pub const FIELDS: &[&str] = &["layers", "layer_height", "step"];

/// The step when none is written.
pub const DEFAULT_STEP_DEG: f64 = 1.0;

/// The largest step: a 10° chord of a ring sags 0.4 % of its radius inside
/// the circle (0.15 mm on 40 mm), about what a bead's edge forgives.
pub const MAX_STEP_DEG: f64 = 10.0;

/// `slicing continuous { … }` as read.
#[derive(Clone, Debug)]
pub struct ContinuousSpec {
    /// Layers to build.
    pub layers: NonZeroUsize,
    /// Where `layers` is written.
    pub layers_span: Span,
    /// The nominal rise per layer.
    pub layer_height: Length,
    /// Where it is written.
    pub layer_height_span: Span,
    /// Points at most this far apart.
    pub step: Angle,
}

/// Reads a `slicing continuous { … }` block.
pub fn read<'a>(
    env: &mut Env<'a>,
    stmts: &'a [Stmt],
    span: Span,
    diags: &mut Diagnostics,
) -> Option<ContinuousSpec> {
    let f = Fields::block(
        env,
        stmts,
        FIELDS,
        &[],
        "continuous slicing".into(),
        span,
        diags,
    );
    let layers = f.count("layers", 1, MAX_LAYERS, Some("130"), diags);
    let h = f.positive("layer_height", Dim::LENGTH, Some("0.23 mm"), diags);
    let step = match f.positive("step", Dim::ANGLE, None, diags) {
        Some((s, at)) if s.to_degrees() > MAX_STEP_DEG => {
            diags.push(message::solid::ring_step_too_large(
                s.to_degrees(),
                MAX_STEP_DEG,
                at,
            ));

            None
        }
        Some((s, _)) => Some(Angle(s)),
        None if f.has("step") => None,
        None => Some(Angle::from_deg(DEFAULT_STEP_DEG)),
    };
    let (layers, layers_span) = layers?;
    Some(ContinuousSpec {
        layers: NonZeroUsize::new(layers)?,
        layers_span,
        layer_height: Length(h?.0),
        layer_height_span: h?.1,
        step: step?,
    })
}
