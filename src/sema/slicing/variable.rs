//! `slicing variable { layers, scan, offset, segments { tolerance, min_length } }`
//! (variable layers), and its pairing with an extrusion that has a `top` into a
//! [`Build::Variable`]: the speeds come from the bead model, so the process
//! block gives none and the bead must map heights to speeds; a declared
//! track offset is checked against the bead's width. How many layers, where
//! the tracks run and where their speed changes is the slicer's decision
//! ([`crate::slice::top`]).
//!
//! [`Build::Variable`]: crate::sema::model::Build::Variable

use crate::diag::{message, Diagnostics};
use crate::sema::eval::Env;
use crate::sema::fields::Fields;
use crate::sema::model::Tolerance;
use crate::sema::model::{
    Axis, Bead, HeightModel, Level, Shape, TopExtrusion, VariableSlicing, DEFAULT_TOLERANCE,
};
use crate::sema::schema::slicing::{variable, SEGMENTS, VARIABLE};
use crate::sema::solid::extrude::{declared_offset, Source, Written};
use crate::sema::solid::profile;
use crate::sema::value::Value;
use crate::span::Span;
use crate::syntax::ast::Stmt;
use crate::units::{Length, Speed};
use std::num::NonZeroU32;

/// `slicing variable { … }` as read: the whole block when every field is
/// right, and its declared offset on its own (checked against the bead
/// whatever else is wrong).
#[derive(Clone, Debug)]
pub struct VariableSpec {
    slicing: Option<VariableSlicing>,
    offset: Option<(Length, Span)>,
    /// `rise_tolerance` and `max_drift` (the defaults where wrong: reported).
    pub tolerance: Tolerance,
}

impl VariableSpec {
    /// The declared track offset, if any.
    pub fn offset(&self) -> Option<(Length, Span)> {
        self.offset
    }

    /// The slicing, when every field of it is right.
    pub fn into_slicing(self) -> Option<VariableSlicing> {
        self.slicing
    }
}

/// Reads a `slicing variable { … }` block.
pub fn read<'a>(
    env: &mut Env<'a>,
    stmts: &'a [Stmt],
    span: Span,
    diags: &mut Diagnostics,
) -> VariableSpec {
    let f = Fields::block(
        env,
        stmts,
        &VARIABLE,
        "variable slicing".into(),
        span,
        diags,
    );
    let layers = match f.value(&variable::LAYERS, diags) {
        None if f.has(&variable::LAYERS) => None,
        None => Some(None),
        Some(v) if v.value == Value::Symbol("auto".into()) => Some(None),
        Some(_) => f
            .count(&variable::LAYERS, diags)
            .map(|(n, sp)| NonZeroU32::new(n as u32).map(|n| (n, sp))),
    };
    let scan = f.word_or_default(&variable::SCAN, diags).map(|s| match s {
        "x" => Some(Axis::X),
        "y" => Some(Axis::Y),
        _ => None,
    });
    let offset = match f.value(&variable::OFFSET, diags) {
        None if f.has(&variable::OFFSET) => None,
        None => Some(None),
        Some(v) if v.value == Value::Symbol("balanced".into()) => Some(None),
        Some(_) => f
            .quantity(&variable::OFFSET, diags)
            .map(|(d, sp)| Some((Length(d), sp))),
    };
    let level = match f.value(&variable::LEVEL, diags) {
        None if f.has(&variable::LEVEL) => None,
        None => Some(Level::None),
        Some(v) if v.value == Value::Symbol("none".into()) => Some(Level::None),
        Some(v) if v.value == Value::Symbol("auto".into()) => Some(Level::Auto(v.span)),
        Some(_) => f
            .quantity(&variable::LEVEL, diags)
            .map(|(z, sp)| Level::At(Length(z), sp)),
    };
    let follow = chosen(&f, &variable::FOLLOW, "surface", diags);
    let finish = f.quantity(&variable::FINISH_TOLERANCE, diags);
    let finish = f.optional(&variable::FINISH_TOLERANCE, finish);
    let direction = chosen(&f, &variable::DIRECTION, "auto", diags);
    let segments = segments(env, &f, diags);
    let declared = offset.flatten();
    let slicing = match (
        segments,
        layers,
        scan,
        offset,
        level,
        (follow, direction, finish),
    ) {
        (
            Some((tolerance, min_length)),
            Some(layers),
            Some(scan),
            Some(offset),
            Some(level),
            (Some(follow), Some(direction), Some(finish)),
        ) => Some(VariableSlicing {
            layers,
            scan,
            offset,
            level,
            follow,
            direction,
            tolerance: tolerance.map_or(DEFAULT_TOLERANCE, |t| Length(t.0)),
            min_length: min_length.map(|m| Length(m.0)),
            finish_tolerance: finish.map(|(t, at)| (Length(t), at)),
            span,
            tolerance_span: tolerance.map(|t| t.1),
            min_length_span: min_length.map(|m| m.1),
        }),
        _ => None,
    };
    VariableSpec {
        slicing,
        offset: declared,
        tolerance: super::shared::tolerance(&f, diags).unwrap_or_default(),
    }
}

/// The `segments { tolerance, min_length }` block: each field and where,
/// `None` where not written; `None` when either is wrong (reported).
type Segments = (Option<(f64, Span)>, Option<(f64, Span)>);

fn segments<'a>(env: &mut Env<'a>, f: &Fields<'a>, diags: &mut Diagnostics) -> Option<Segments> {
    let Some((inner, at)) = f.nested(&variable::SEGMENTS) else {
        return Some((None, None));
    };
    let s = Fields::block(
        env,
        inner,
        &SEGMENTS,
        "the `segments` block".into(),
        at,
        diags,
    );
    let tolerance = s.quantity(&variable::TOLERANCE, diags);
    let min_length = s.quantity(&variable::MIN_LENGTH, diags);
    match (
        s.optional(&variable::TOLERANCE, tolerance),
        s.optional(&variable::MIN_LENGTH, min_length),
    ) {
        (Some(t), Some(m)) => Some((t, m)),
        _ => None,
    }
}

/// A field of two words read as where `word` (the one that is not the
/// default) is written: `Some(None)` for the default, `None` when wrong.
fn chosen(
    f: &Fields<'_>,
    field: &crate::sema::schema::Field,
    word: &str,
    diags: &mut Diagnostics,
) -> Option<Option<Span>> {
    match f.word(field, diags) {
        None if f.has(field) => None,
        Some((w, at)) if w == word => Some(Some(at)),
        _ => Some(None),
    }
}

/// What variable slicing asks of the rest of the file, checked whenever the
/// strategy is `variable` (whatever else is wrong): no process `speed` (the
/// bead gives them: `speed` is the process block's, `Some(None)` when not
/// written), a bead that maps heights to speeds, and a declared track
/// offset the bead's width allows. Whether all hold.
pub fn side_checks(
    bead: Option<&Bead>,
    speed: Option<Option<(Speed, Span)>>,
    offset: Option<(Length, Span)>,
    at: Span,
    diags: &mut Diagnostics,
) -> bool {
    let mut ok = true;
    if let (Some((d, sp)), Some(b)) = (offset, bead) {
        ok &= declared_offset(d, sp, b, None, diags);
    }
    if let Some(Some((_, sp))) = speed {
        diags.push(message::solid::speed_with_variable(
            bead.map(|b| b.name.as_str()),
            sp,
            at,
        ));
        ok = false;
    }
    if let Some(b) = bead {
        if let HeightModel::Measured { speed, .. } = b.model {
            diags.push(message::solid::measured_bead_with_variable(
                &b.name, speed, b.span, at,
            ));
            ok = false;
        }
    }
    ok
}

/// Joins an extrusion that has a `top` with its variable slicing and its
/// bead (whose [`side_checks`] were made), keeping the footprint as one
/// shape.
pub fn assemble(
    env: &mut Env<'_>,
    w: Written<'_>,
    spec: VariableSpec,
    diags: &mut Diagnostics,
) -> Option<(TopExtrusion, VariableSlicing)> {
    let slicing = spec.slicing?;
    let (top, top_span) = w.top?;
    if let (Some(at), None) = (slicing.level.span(), &w.base) {
        diags.push(message::scan::level_without_scan(at, w.span));
        return None;
    }
    if let (Some(at), None) = (slicing.follow, &w.base) {
        diags.push(message::scan::follow_without_scan(at, w.span));
        return None;
    }
    let (shape, shape_span) = footprint(env, w.source, w.profile_span, diags)?;
    Some((
        TopExtrusion {
            name: w.name,
            shape,
            measure: w.measure,
            top,
            span: w.span,
            profile_span: w.profile_span,
            shape_span,
            top_span,
            base: w.base,
            turned: None,
        },
        slicing,
    ))
}

/// The footprint: one shape without holes. A profile that follows `layer`
/// has no place under a top, whose layers are not planes a profile could be
/// cut at.
fn footprint(
    env: &mut Env<'_>,
    source: Source<'_>,
    profile_span: Span,
    diags: &mut Diagnostics,
) -> Option<(Shape, Span)> {
    let (shape, span) = one_footprint(env, source, profile_span, diags)?;
    if shape.has_holes() {
        // The balanced offsets and the segments assume one strip per track.
        diags.push(message::solid::top_footprint_holes(span));
        return None;
    }
    Some((shape, span))
}

fn one_footprint(
    env: &mut Env<'_>,
    source: Source<'_>,
    profile_span: Span,
    diags: &mut Diagnostics,
) -> Option<(Shape, Span)> {
    match source {
        Source::Fixed(s) => Some((s, profile_span)),
        Source::Expr(e) if env.depends_on_layer(e) => {
            diags.push(message::solid::top_footprint_follows_layer(
                e.span,
                profile_span,
            ));

            None
        }
        Source::Expr(e) => {
            let v = env.eval(e, diags)?;
            Some((profile::shape(&v, "a profile", diags)?, e.span))
        }
        Source::Mesh(m) => {
            diags.push(message::mesh::mesh_with_top(m.span));
            None
        }
    }
}
