//! `slicing normal { layers, points | chord_error, seam }`.

use super::fields::Fields;
use super::model::{Resolution, Slicing};
use super::value::{Env, Value};
use crate::diag::{Diagnostic, Diagnostics};
use crate::span::{Span, Spanned};
use crate::syntax::ast::Stmt;
use crate::units::{Angle, Dim, Length};

/// Strategies the language knows (more come with planar fills).
pub const STRATEGIES: &[&str] = &["normal"];

/// Most layers and points per layer a plan may have: 10⁸ points in all keeps
/// memory bounded (the IR holds 72 bytes a point).
pub const MAX_LAYERS: usize = 100_000;
/// See [`MAX_LAYERS`].
pub const MAX_POINTS: usize = 100_000;

/// Reads a slicing block.
pub fn read<'a>(
    env: &mut Env<'a>,
    strategy: Option<&Spanned<String>>,
    stmts: &'a [Stmt],
    span: Span,
    diags: &mut Diagnostics,
) -> Option<Slicing> {
    match strategy {
        Some(s) if STRATEGIES.contains(&s.node.as_str()) => {}
        Some(s) => {
            diags.push(
                Diagnostic::error(
                    "lmd::bad-choice",
                    format!("lmdc does not know the slicing strategy `{}`", s.node),
                )
                .label(s.span, "unknown strategy")
                .help("use `slicing normal { … }`: continuous gradual slicing normal to the spine (planar for a straight spine)"),
            );
            return None;
        }
        None => {
            diags.push(
                Diagnostic::error("lmd::syntax", "name the slicing strategy")
                    .label(span, "which strategy?")
                    .help("write `slicing normal { … }`"),
            );
            return None;
        }
    }
    let f = Fields::block(
        env,
        stmts,
        &["layers", "points", "chord_error", "seam"],
        &[],
        "slicing".into(),
        span,
        diags,
    );
    let layers = match f.value("layers", None, diags) {
        None if f.has("layers") => return None,
        None => Some(None),
        Some(v) if v.value == Value::Symbol("auto".into()) => Some(None),
        Some(_) => f
            .count("layers", 1, MAX_LAYERS, None, diags)
            .map(|(n, _)| Some(n)),
    };
    let resolution = match (f.has("points"), f.has("chord_error")) {
        (true, true) => {
            diags.push(
                Diagnostic::error(
                    "lmd::duplicate",
                    "give either `points` or `chord_error`, not both",
                )
                .label_opt(f.span("points"), "points")
                .label_opt(f.span("chord_error"), "chord error"),
            );
            None
        }
        (false, true) => f
            .positive("chord_error", Dim::LENGTH, None, diags)
            .map(|(e, _)| Resolution::ChordError(Length(e))),
        (true, false) => f
            .count("points", 8, MAX_POINTS, None, diags)
            .map(|(n, _)| Resolution::Count(n)),
        (false, false) => Some(Resolution::Count(360)),
    };
    let seam = match f.quantity("seam", Dim::ANGLE, None, diags) {
        Some((a, _)) => Some(Angle(a)),
        None if f.has("seam") => None,
        None => Some(Angle::from_deg(90.0)),
    };
    Some(Slicing {
        layers: layers?,
        resolution: resolution?,
        seam: seam?,
        span,
        layers_span: f.span("layers"),
        seam_span: f.span("seam"),
    })
}
