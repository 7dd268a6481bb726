//! `slicing continuous { layers, layer_height, step }`: a segmented ring's
//! layers laid in one run, each rising `layer_height` inside the last
//! transition of the layer below, the points at most `step` apart.

use crate::diag::{message, Diagnostics};
use crate::sema::eval::Env;
use crate::sema::fields::Fields;
use crate::sema::schema::slicing::{continuous, CONTINUOUS, MAX_STEP_DEG};
use crate::span::Span;
use crate::syntax::ast::Stmt;
use crate::units::{Angle, Length};
use std::num::NonZeroUsize;

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
        &CONTINUOUS,
        "continuous slicing".into(),
        span,
        diags,
    );
    let layers = f.count(&continuous::LAYERS, diags);
    let h = f.quantity(&continuous::LAYER_HEIGHT, diags);
    let step = f.bounded_or_default(
        &continuous::STEP,
        |s, at| message::solid::ring_step_too_large(s.to_degrees(), MAX_STEP_DEG, at),
        diags,
    );
    let (layers, layers_span) = layers?;
    Some(ContinuousSpec {
        layers: NonZeroUsize::new(layers)?,
        layers_span,
        layer_height: Length(h?.0),
        layer_height_span: h?.1,
        step: Angle(step?),
    })
}
