//! The `slicing STRATEGY { … }` statement: `slicing normal { layers, points |
//! chord_error, seam }` is read here; `planar`, `variable` and `continuous`
//! by `super::planar`, `super::variable` and `super::continuous`.

use super::eval::Env;
use super::fields::Fields;
use super::model::{Resolution, Slicing, MAX_LAYERS, MAX_POINTS};
use super::planar;
use super::statement::{shape_error, single, Statements};
use super::suggest::did_you_mean;
use super::value::Value;
use crate::diag::{message, Diagnostics};
use crate::span::{Span, Spanned};
use crate::syntax::ast::{Body, Stmt};
use crate::units::{Angle, Dim, Length};

/// Strategies the language knows.
pub const STRATEGIES: &[&str] = &["normal", "planar", "variable", "continuous"];

/// A slicing block as written, before the solid is known.
#[derive(Clone, Debug)]
pub enum Spec {
    /// `slicing normal { … }`
    Normal(Slicing),
    /// `slicing planar { … }`
    Planar(super::planar::PlanarSpec),
    /// `slicing variable { … }`
    Variable(super::variable::VariableSpec),
    /// `slicing continuous { … }`
    Continuous(super::continuous::ContinuousSpec),
}

/// The slicing statement as read: the strategy named (when it is one lmdc
/// knows) and the block when every field is right.
pub struct Read<'s> {
    /// The `slicing` statement, if there is one.
    pub stmt: Option<&'s Stmt>,
    /// `normal` or `planar`, if written so.
    pub strategy: Option<&'s str>,
    /// The block, when every field is right.
    pub spec: Option<Spec>,
}

/// The file's `slicing STRATEGY { … }` statement.
pub(super) fn statement<'a>(
    env: &mut Env<'a>,
    st: &Statements<'a>,
    diags: &mut Diagnostics,
) -> Read<'a> {
    let stmt = single(
        st.get("slicing"),
        "slicing",
        "slicing normal { layers = auto }",
        diags,
    );
    let Some(s) = stmt else {
        return Read {
            stmt,
            strategy: None,
            spec: None,
        };
    };
    let strategy = s
        .name
        .as_ref()
        .map(|n| n.node.as_str())
        .filter(|n| STRATEGIES.contains(n));
    let spec = match &s.body {
        Body::Block(stmts, _) => read(env, s.name.as_ref(), stmts, s.span, diags),
        _ => {
            diags.push(shape_error(
                s,
                "slicing STRATEGY { … }",
                "slicing normal { layers = auto }",
            ));
            None
        }
    };
    Read {
        stmt,
        strategy,
        spec,
    }
}

/// Fields of `slicing normal { … }`.
const NORMAL_FIELDS: &[&str] = &["layers", "points", "chord_error", "seam"];

/// The fields of a block whose strategy is wrong or missing: checked against
/// what either strategy takes, so a misspelt field is reported in the same
/// run as the strategy.
fn any_strategy<'a>(env: &mut Env<'a>, stmts: &'a [Stmt], span: Span, diags: &mut Diagnostics) {
    let mut all: Vec<&str> = NORMAL_FIELDS.to_vec();
    for k in planar::FIELDS
        .iter()
        .chain(super::variable::FIELDS)
        .chain(super::continuous::FIELDS)
    {
        if !all.contains(k) {
            all.push(k);
        }
    }
    Fields::block(
        env,
        stmts,
        &all,
        super::variable::BLOCKS,
        "slicing".into(),
        span,
        diags,
    );
}

/// Reads a slicing block.
fn read<'a>(
    env: &mut Env<'a>,
    strategy: Option<&Spanned<String>>,
    stmts: &'a [Stmt],
    span: Span,
    diags: &mut Diagnostics,
) -> Option<Spec> {
    match strategy {
        Some(s) if s.node == "planar" => {
            return planar::read(env, stmts, span, diags).map(Spec::Planar)
        }
        Some(s) if s.node == "variable" => {
            return Some(Spec::Variable(super::variable::read(
                env, stmts, span, diags,
            )))
        }
        Some(s) if s.node == "continuous" => {
            return super::continuous::read(env, stmts, span, diags).map(Spec::Continuous)
        }
        Some(s) if STRATEGIES.contains(&s.node.as_str()) => {}
        Some(s) => {
            let suggestion = did_you_mean(&s.node, STRATEGIES.iter().copied());
            diags.push(message::bead::unknown_strategy(&s.node, s.span, suggestion));
            any_strategy(env, stmts, span, diags);
            return None;
        }
        None => {
            diags.push(message::bead::unnamed_strategy(span));
            any_strategy(env, stmts, span, diags);
            return None;
        }
    }
    let f = Fields::block(
        env,
        stmts,
        NORMAL_FIELDS,
        &[],
        "slicing".into(),
        span,
        diags,
    );
    let layers = match f.value("layers", None, diags) {
        None if f.has("layers") => None,
        None => Some(None),
        Some(v) if v.value == Value::Symbol("auto".into()) => Some(None),
        Some(_) => f
            .count("layers", 1, MAX_LAYERS, None, diags)
            .map(|(n, _)| Some(n)),
    };
    let resolution = match (f.has("points"), f.has("chord_error")) {
        (true, true) => {
            diags.push(message::bead::points_and_chord_error(
                f.span("points"),
                f.span("chord_error"),
            ));
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
    Some(Spec::Normal(Slicing {
        layers: layers?,
        resolution: resolution?,
        seam: seam?,
        span,
        layers_span: f.span("layers"),
        seam_span: f.span("seam"),
    }))
}
