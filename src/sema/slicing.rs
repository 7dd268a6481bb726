//! `slicing normal { layers, points | chord_error, seam }` and
//! `slicing planar { layer_height, layers, contours, offset, infill, chord_error }`;
//! `slicing variable { … }` is read by `sema::variable`.

use super::eval::Env;
use super::fields::{self, Fields};
use super::model::{LinkMode, Pattern, Raster, Resolution, SeamRule, Slicing};
use super::seam;
use super::statement::{shape_error, single, Statements};
use super::suggest::did_you_mean;
use super::value::{Call, Spanned as SpannedValue, Value};
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
    Planar(PlanarSpec),
    /// `slicing variable { … }`
    Variable(super::variable::VariableSpec),
    /// `slicing continuous { … }`
    Continuous(super::continuous::ContinuousSpec),
}

/// `slicing planar { … }` as written: the lift and offset may be `auto`, to be
/// derived from the bead model.
#[derive(Clone, Debug)]
pub struct PlanarSpec {
    /// `layer_height`, or `None` for auto.
    pub lift: Option<(Length, Span)>,
    /// `layers`, if given.
    pub layers: Option<(usize, Span)>,
    /// Contour passes.
    pub contours: usize,
    /// `offset`, or `None` for auto (flat top).
    pub offset: Option<(Length, Span)>,
    /// The infill; its `extend` is `None` for auto (= the offset).
    pub infill: Option<(Raster, Option<Length>)>,
    /// Chord error of flattened arcs.
    pub chord_error: Length,
    /// Where contour loops start, layer by layer.
    pub seam: SeamRule,
    /// The block.
    pub span: Span,
}

impl PlanarSpec {
    /// Whether a layer is more than one track wide, so that it rises by `A/d`
    /// rather than `A/w`.
    pub fn overlapped(&self) -> bool {
        self.infill.is_some() || self.contours > 1
    }
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

/// Most layers and points per layer a plan may have: 10⁸ points in all keeps
/// memory bounded (the IR holds 72 bytes a point).
pub const MAX_LAYERS: usize = 100_000;
/// See [`MAX_LAYERS`].
pub const MAX_POINTS: usize = 100_000;

/// Fields of `slicing normal { … }`.
const NORMAL_FIELDS: &[&str] = &["layers", "points", "chord_error", "seam"];

/// Fields of `slicing planar { … }`.
const PLANAR_FIELDS: &[&str] = &[
    "layer_height",
    "layers",
    "contours",
    "offset",
    "infill",
    "chord_error",
    "seam",
];

/// The fields of a block whose strategy is wrong or missing: checked against
/// what either strategy takes, so a misspelt field is reported in the same
/// run as the strategy.
fn any_strategy<'a>(env: &mut Env<'a>, stmts: &'a [Stmt], span: Span, diags: &mut Diagnostics) {
    let mut all: Vec<&str> = NORMAL_FIELDS.to_vec();
    for k in PLANAR_FIELDS
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
        Some(s) if s.node == "planar" => return planar(env, stmts, span, diags).map(Spec::Planar),
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

/// Most contour passes a layer may have.
pub const MAX_CONTOURS: usize = 1000;

fn auto_or_length(
    f: &Fields<'_>,
    key: &str,
    diags: &mut Diagnostics,
) -> Option<Option<(Length, Span)>> {
    match f.value(key, None, diags) {
        None if f.has(key) => None,
        None => Some(None),
        Some(v) if v.value == Value::Symbol("auto".into()) => Some(None),
        Some(_) => f
            .positive(key, Dim::LENGTH, None, diags)
            .map(|(l, sp)| Some((Length(l), sp))),
    }
}

fn planar<'a>(
    env: &mut Env<'a>,
    stmts: &'a [Stmt],
    span: Span,
    diags: &mut Diagnostics,
) -> Option<PlanarSpec> {
    let f = Fields::block(
        env,
        stmts,
        PLANAR_FIELDS,
        &[],
        "planar slicing".into(),
        span,
        diags,
    );
    let lift = auto_or_length(&f, "layer_height", diags);
    let offset = auto_or_length(&f, "offset", diags);
    let layers = match f.value("layers", None, diags) {
        None if f.has("layers") => None,
        None => Some(None),
        Some(v) if v.value == Value::Symbol("auto".into()) => Some(None),
        Some(_) => f.count("layers", 1, MAX_LAYERS, None, diags).map(Some),
    };
    let infill = match f.value("infill", None, diags) {
        None if f.has("infill") => None,
        None => Some(None),
        Some(v) if v.value == Value::Symbol("none".into()) => Some(None),
        Some(SpannedValue {
            value: Value::Call(c),
            ..
        }) if c.func == "raster" => raster(c, diags).map(Some),
        Some(v) => {
            diags.push(message::bead::bad_infill(v.span, &v.value.describe()));
            None
        }
    };
    let contours = match f.count("contours", 0, MAX_CONTOURS, None, diags) {
        Some((n, sp)) => Some((n, Some(sp))),
        None if f.has("contours") => None,
        // A raster alone fills seed 001's layers; a profile alone is a wall.
        None => infill.map(|i| (if i.is_some() { 0 } else { 1 }, None)),
    };
    // Nothing to deposit: known once both are.
    let contours = match (contours, &infill) {
        (Some((0, Some(sp))), Some(None)) => {
            diags.push(message::bead::nothing_deposited(sp));
            None
        }
        (c, _) => c.map(|c| c.0),
    };
    let chord_error = match f.positive("chord_error", Dim::LENGTH, None, diags) {
        Some((e, _)) => Some(Length(e)),
        None if f.has("chord_error") => None,
        None => Some(Length(0.05)),
    };
    let seam = match f.value("seam", None, diags) {
        Some(v) => seam::read(v, diags),
        None if f.has("seam") => None,
        None => Some(SeamRule::Lowest),
    };
    Some(PlanarSpec {
        lift: lift?,
        layers: layers?,
        contours: contours?,
        offset: offset?,
        infill: infill?,
        chord_error: chord_error?,
        seam: seam?,
        span,
    })
}

fn raster(c: &Call, diags: &mut Diagnostics) -> Option<(Raster, Option<Length>)> {
    let a = Fields::call(
        c,
        &[],
        &["angle", "rotate", "pattern", "extend", "link"],
        diags,
    );
    let angle = match a.quantity("angle", Dim::ANGLE, None, diags) {
        Some((x, _)) => Some(Angle(x)),
        None if a.has("angle") => None,
        None => Some(Angle(0.0)),
    };
    let rotate = match a.quantity("rotate", Dim::ANGLE, None, diags) {
        Some((x, _)) => Some(Angle(x)),
        None if a.has("rotate") => None,
        None => Some(Angle(0.0)),
    };
    let pattern = match a.symbol("pattern", &["serpentine", "one_way"], None, diags) {
        Some((p, _)) if p == "one_way" => Some(Pattern::OneWay),
        Some(_) => Some(Pattern::Serpentine),
        None if a.has("pattern") => None,
        None => Some(Pattern::Serpentine),
    };
    let extend = match a.value("extend", None, diags) {
        None if a.has("extend") => None,
        None => Some(None),
        Some(v) if v.value == Value::Symbol("auto".into()) => Some(None),
        Some(v) => fields::quantity(v, Dim::LENGTH, "extend", diags).and_then(|e| {
            if e < 0.0 {
                diags.push(message::bead::negative_extend(v.span));
                None
            } else {
                Some(Some(Length(e)))
            }
        }),
    };
    let link = match a.value("link", None, diags) {
        Some(v) => seam::link(v, diags),
        None if a.has("link") => None,
        None => Some(LinkMode::None),
    };
    // A link turns the nozzle back into the next track: one-way tracks all
    // start on the same side, and no edge leads from one's end to the next.
    if let (Some(Pattern::OneWay), Some(LinkMode::LaserOn | LinkMode::LaserOff)) = (pattern, link) {
        diags.push(message::bead::one_way_linked(
            a.span("link"),
            a.span("pattern"),
        ));
        return None;
    }
    let extend = extend?;
    Some((
        Raster {
            angle: angle?,
            rotate: rotate?,
            pattern: pattern?,
            extend: extend.unwrap_or(Length(0.0)),
            link: link?,
        },
        extend,
    ))
}
