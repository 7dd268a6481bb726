//! `slicing planar { layer_height, layers, contours, offset, infill,
//! chord_error, seam }`: flat layers, their tracks (contours and a raster
//! infill) and how far each layer rises (declared, or `auto` from the bead).

use crate::diag::{message, Diagnostics};
use crate::sema::eval::Env;
use crate::sema::fields::Fields;
use crate::sema::model::{LayerChange, LinkMode, Pattern, Raster, SeamRule};
use crate::sema::model::{PlanarSlicing, Tolerance};
use crate::sema::schema::slicing::{normal, planar, raster, PLANAR, RASTER};
use crate::sema::schema::Field;
use crate::sema::slicing::seam;
use crate::sema::value::{Call, Spanned as SpannedValue, Value};
use crate::span::Span;
use crate::syntax::ast::Stmt;
use crate::units::{Angle, Length, Speed};

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
    /// `rise_tolerance` and `max_drift`.
    pub tolerance: Tolerance,
    /// `max_overhang = …`, if written (rad).
    pub max_overhang: Option<f64>,
    /// `layer_change = …`: how a one-bead wall goes on to the next layer.
    pub layer_change: LayerChange,
    /// `layer_change = …`, if written.
    pub layer_change_span: Option<Span>,
    /// The block.
    pub span: Span,
}

impl PlanarSpec {
    /// Whether a layer is more than one track wide, so that it rises by `A/d`
    /// rather than `A/w`.
    pub fn overlapped(&self) -> bool {
        self.infill.is_some() || self.contours > 1
    }

    /// The slicing with its `auto`s settled: the tracks `offset` apart
    /// (`derived` when it was `auto`), at `speed`, `contours` of them and
    /// `infill`, whose rasters' `extend` defaults to the offset.
    pub fn into_slicing(
        self,
        (offset, derived): (Length, bool),
        speed: Speed,
        contours: usize,
        infill: Option<(Raster, Option<Length>)>,
    ) -> PlanarSlicing {
        PlanarSlicing {
            contours,
            offset,
            offset_derived: derived,
            infill: infill.map(|(mut r, extend)| {
                r.extend = extend.unwrap_or(offset);
                r
            }),
            chord_error: self.chord_error,
            seam: self.seam,
            speed,
            lift: self.lift,
            span: self.span,
            offset_span: self.offset.map(|o| o.1),
            tolerance: self.tolerance,
            max_overhang: self.max_overhang,
            layer_change: self.layer_change,
            layer_change_span: self.layer_change_span,
        }
    }
}

/// `key = auto` or a length: `Some(None)` for auto (or when not written).
fn auto_or_length(
    f: &Fields<'_>,
    field: &Field,
    diags: &mut Diagnostics,
) -> Option<Option<(Length, Span)>> {
    match f.value(field, diags) {
        None if f.has(field) => None,
        None => Some(None),
        Some(v) if v.value == Value::Symbol("auto".into()) => Some(None),
        Some(_) => f
            .quantity(field, diags)
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
    let f = Fields::block(env, stmts, &PLANAR, "planar slicing".into(), span, diags);
    let lift = auto_or_length(&f, &planar::LAYER_HEIGHT, diags);
    let offset = auto_or_length(&f, &planar::OFFSET, diags);
    let layers = match f.value(&planar::LAYERS, diags) {
        None if f.has(&planar::LAYERS) => None,
        None => Some(None),
        Some(v) if v.value == Value::Symbol("auto".into()) => Some(None),
        Some(_) => f.count(&planar::LAYERS, diags).map(Some),
    };
    let infill = match f.value(&planar::INFILL, diags) {
        None if f.has(&planar::INFILL) => None,
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
    let contours = match f.count(&planar::CONTOURS, diags) {
        Some((n, sp)) => Some((n, Some(sp))),
        None if f.has(&planar::CONTOURS) => None,
        // With an infill the raster alone fills the layer (a raster-filled
        // solid); without one the profile alone is a wall.
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
    let chord_error = f
        .quantity_or_default(&planar::CHORD_ERROR, diags)
        .map(Length);
    let seam = match f.value(&planar::SEAM, diags) {
        Some(v) => seam::read(v, diags),
        None if f.has(&planar::SEAM) => None,
        None => Some(SeamRule::Lowest),
    };
    let layer_change = super::shared::layer_change(&f, diags);
    let layer_change = match (layer_change, seam, contours, &infill) {
        (Some(LayerChange::Spiral { .. }), Some(rule), _, _) if rule.moves() => {
            diags.push(message::bend::spiral_seam_moves(
                f.span(&normal::LAYER_CHANGE).unwrap_or(span),
                f.span(&planar::SEAM).unwrap_or(span),
            ));
            None
        }
        (Some(LayerChange::Spiral { .. }), _, Some(c), Some(i)) if c != 1 || i.is_some() => {
            diags.push(message::slicing::spiral_not_a_wall(
                f.span(&normal::LAYER_CHANGE).unwrap_or(span),
                c,
                i.is_some(),
            ));
            None
        }
        (change, ..) => change,
    };
    Some(PlanarSpec {
        lift: lift?,
        layers: layers?,
        contours: contours?,
        offset: offset?,
        infill: infill?,
        chord_error: chord_error?,
        seam: seam?,
        tolerance: super::shared::tolerance(&f, diags)?,
        max_overhang: f.optional(
            &normal::MAX_OVERHANG,
            f.quantity(&normal::MAX_OVERHANG, diags).map(|(a, _)| a),
        )?,
        layer_change: layer_change?,
        layer_change_span: f.span(&normal::LAYER_CHANGE),
        span,
    })
}

fn raster(c: &Call, diags: &mut Diagnostics) -> Option<(Raster, Option<Length>)> {
    let a = Fields::call(c, &RASTER, diags);
    let angle = a.quantity_or_default(&raster::ANGLE, diags).map(Angle);
    let rotate = a.quantity_or_default(&raster::ROTATE, diags).map(Angle);
    let pattern = a.word_or_default(&raster::PATTERN, diags).map(|p| match p {
        "one_way" => Pattern::OneWay,
        _ => Pattern::Serpentine,
    });
    let extend = match a.value(&raster::EXTEND, diags) {
        None if a.has(&raster::EXTEND) => None,
        None => Some(None),
        Some(v) if v.value == Value::Symbol("auto".into()) => Some(None),
        Some(_) => a
            .bounded(
                &raster::EXTEND,
                |_, at| message::bead::negative_extend(at),
                diags,
            )
            .map(|(e, _)| Some(Length(e))),
    };
    let link = match a.value(&raster::LINK, diags) {
        Some(v) => seam::link(v, diags),
        None if a.has(&raster::LINK) => None,
        None => Some(LinkMode::None),
    };
    // A link turns the nozzle back into the next track: one-way tracks all
    // start on the same side, and no edge leads from one's end to the next.
    if let (Some(Pattern::OneWay), Some(LinkMode::LaserOn | LinkMode::LaserOff)) = (pattern, link) {
        diags.push(message::bead::one_way_linked(
            a.span(&raster::LINK),
            a.span(&raster::PATTERN),
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
