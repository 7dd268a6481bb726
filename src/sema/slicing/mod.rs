//! The `slicing STRATEGY { … }` statement: `slicing normal { layers, points |
//! chord_error, seam }` is read here; `planar`, `variable` and `continuous`
//! by `crate::sema::slicing::planar`, `crate::sema::slicing::variable` and `crate::sema::slicing::continuous`.

pub mod continuous;
pub mod planar;
pub mod seam;
pub mod shared;
pub mod variable;

use crate::diag::{message, Diagnostics};
use crate::sema::eval::Env;
use crate::sema::fields::Fields;
use crate::sema::model::Tolerance;
use crate::sema::model::{LayerChange, Resolution, SeamRule, Slicing};
use crate::sema::schema::slicing::{self as schema, normal};
use crate::sema::statement::{shape_error, single, Statements};
use crate::sema::suggest::did_you_mean;
use crate::sema::value::Value;
use crate::span::{Span, Spanned};
use crate::syntax::ast::{Body, Stmt};
use crate::units::{Angle, Length};

/// Strategies the language knows.
pub const STRATEGIES: &[&str] = &["normal", "planar", "variable", "continuous"];

/// A slicing block as written, before the solid is known.
#[derive(Clone, Debug)]
pub enum Spec {
    /// `slicing normal { … }`
    Normal(Slicing),
    /// `slicing planar { … }`
    Planar(crate::sema::slicing::planar::PlanarSpec),
    /// `slicing variable { … }`
    Variable(crate::sema::slicing::variable::VariableSpec),
    /// `slicing continuous { … }`
    Continuous(crate::sema::slicing::continuous::ContinuousSpec),
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
pub(in crate::sema) fn statement<'a>(
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

/// The fields of a block whose strategy is wrong or missing: checked against
/// what any strategy takes, so a misspelt field is reported in the same
/// run as the strategy.
fn any_strategy<'a>(env: &mut Env<'a>, stmts: &'a [Stmt], span: Span, diags: &mut Diagnostics) {
    Fields::block(env, stmts, &schema::ANY, "slicing".into(), span, diags);
}

impl Spec {
    /// How closely the bead model must lay the layers (the defaults for a
    /// ring, which has none).
    pub fn tolerance(&self) -> Tolerance {
        match self {
            Spec::Normal(s) => s.tolerance,
            Spec::Planar(p) => p.tolerance,
            Spec::Variable(v) => v.tolerance,
            Spec::Continuous(_) => Tolerance::default(),
        }
    }
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
            return Some(Spec::Variable(crate::sema::slicing::variable::read(
                env, stmts, span, diags,
            )))
        }
        Some(s) if s.node == "continuous" => {
            return crate::sema::slicing::continuous::read(env, stmts, span, diags)
                .map(Spec::Continuous)
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
    normal(env, stmts, span, diags).map(Spec::Normal)
}

/// Reads `slicing normal { … }`.
fn normal<'a>(
    env: &mut Env<'a>,
    stmts: &'a [Stmt],
    span: Span,
    diags: &mut Diagnostics,
) -> Option<Slicing> {
    let f = Fields::block(env, stmts, &schema::NORMAL, "slicing".into(), span, diags);
    let layers = match f.value(&normal::LAYERS, diags) {
        None if f.has(&normal::LAYERS) => None,
        None => Some(None),
        Some(v) if v.value == Value::Symbol("auto".into()) => Some(None),
        Some(_) => f.count(&normal::LAYERS, diags).map(|(n, _)| Some(n)),
    };
    let resolution = match (f.has(&normal::POINTS), f.has(&normal::CHORD_ERROR)) {
        (true, true) => {
            diags.push(message::bead::points_and_chord_error(
                f.span(&normal::POINTS),
                f.span(&normal::CHORD_ERROR),
            ));
            None
        }
        (false, true) => f
            .quantity(&normal::CHORD_ERROR, diags)
            .map(|(e, _)| Resolution::ChordError(Length(e))),
        (_, false) => f
            .count_or_default(&normal::POINTS, diags)
            .map(Resolution::Count),
    };
    let seam = match f.value(&normal::SEAM, diags) {
        Some(v) => seam::read(v, diags).and_then(|rule| match rule {
            SeamRule::Lowest | SeamRule::SharpestCorner => {
                diags.push(message::bend::planar_seam_on_a_wall(v.span));
                None
            }
            rule => Some(rule),
        }),
        None if f.has(&normal::SEAM) => None,
        None => f
            .quantity_or_default(&normal::SEAM, diags)
            .map(|a| SeamRule::Toward(Angle(a))),
    };
    let tolerance = shared::tolerance(&f, diags);
    let nozzle = f.word_or_default(&normal::NOZZLE, diags);
    let overhang = f.optional(
        &normal::MAX_OVERHANG,
        f.quantity(&normal::MAX_OVERHANG, diags).map(|(a, _)| a),
    );
    let layer_change = shared::layer_change(&f, diags);
    if let (Some(LayerChange::Spiral { .. }), Some(rule)) = (layer_change, seam) {
        if rule.moves() {
            diags.push(message::bend::spiral_seam_moves(
                f.span(&normal::LAYER_CHANGE).unwrap_or(span),
                f.span(&normal::SEAM).unwrap_or(span),
            ));
            return None;
        }
    }
    Some(Slicing {
        layers: layers?,
        resolution: resolution?,
        seam: seam?,
        tolerance: tolerance?,
        span,
        layers_span: f.span(&normal::LAYERS),
        seam_span: f.span(&normal::SEAM),
        follow_wall: nozzle? == "wall",
        max_overhang: overhang?,
        layer_change: layer_change?,
        layer_change_span: f.span(&normal::LAYER_CHANGE),
    })
}
