//! `slicing planar { layer_height, layers, contours, offset, infill,
//! chord_error, seam }`: flat layers, their tracks (contours and a raster
//! infill) and how far each layer rises (declared, or `auto` from the bead).

use super::eval::Env;
use super::fields::{self, Fields};
use super::model::{LinkMode, Pattern, Raster, SeamRule, MAX_LAYERS};
use super::seam;
use super::value::{Call, Spanned as SpannedValue, Value};
use crate::diag::{message, Diagnostics};
use crate::span::Span;
use crate::syntax::ast::Stmt;
use crate::units::{Angle, Dim, Length};

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

/// Fields of `slicing planar { … }`.
pub const FIELDS: &[&str] = &[
    "layer_height",
    "layers",
    "contours",
    "offset",
    "infill",
    "chord_error",
    "seam",
];

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

/// Reads `slicing planar { … }`.
pub fn read<'a>(
    env: &mut Env<'a>,
    stmts: &'a [Stmt],
    span: Span,
    diags: &mut Diagnostics,
) -> Option<PlanarSpec> {
    let f = Fields::block(
        env,
        stmts,
        FIELDS,
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
