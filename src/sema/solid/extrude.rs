//! `extrude NAME { profile, height, size, bead }`: a profile built up in flat
//! layers, and its pairing with `slicing planar { … }` into a [`Build::Block`]:
//! the scan speed checked against the bead model, the track offset derived
//! where it is `auto` and checked against the bead's width, the height given
//! once (a layer count or a height), and the profile kept as a shape or, when
//! it follows `layer`, as the expression the slicer evaluates on each layer
//! ([`crate::slice::layers`] decides the layers).
//!
//! [`Build::Block`]: crate::sema::model::Build::Block

use crate::bead::{flat_top_offset, MIN_OFFSET_RATIO};
use crate::diag::message::{self, solid::BeadSpeeds};
use crate::diag::Diagnostics;
use crate::sema::eval::{unknown_name, Env};
use crate::sema::fields::Fields;
use crate::sema::model::ScanBase;
use crate::sema::model::{
    Bead, Extent, Extrusion, HeightModel, LayerProfile, Measure, PlanarSlicing, ProfileExpr, Shape,
    Top,
};
use crate::sema::schema::solid::{extrude, scan_section, EXTRUDE, SCAN_SECTION};
use crate::sema::slicing::planar::PlanarSpec;
use crate::sema::solid::profile;
use crate::sema::solid::scan::Cut;
use crate::sema::solid::top;
use crate::sema::value::{Spanned, Value};
use crate::span::Span;
use crate::syntax::ast::{Body, Expr, Stmt};
use crate::units::{Length, Speed};
use std::collections::BTreeMap;

/// What an extrusion may refer to.
pub struct Scope<'s, 'a> {
    /// `section NAME = …`
    pub sections: &'s BTreeMap<String, (crate::sema::model::Section, Span)>,
    /// `profile NAME = …`, kept as expressions: they may depend on `layer`.
    pub profiles: &'s BTreeMap<String, (&'a Expr, Span)>,
    /// `bead NAME { … }`
    pub beads: &'s BTreeMap<String, Bead>,
    /// Every name declared, including failed ones (no second report).
    pub declared: &'s [String],
    /// Every `let` of the file, kept with a `top` written as an expression.
    pub constants: &'s [(String, Span, Expr)],
    /// The file's named statements a `top = NAME` may name (solids) or
    /// mistake for one (sections, profiles, beads).
    pub statements: &'s [&'a Stmt],
    /// The solids already read as the part as designed, by name: a solid
    /// named by both `top` and `register` is read once, its mistakes
    /// reported once.
    pub targets: &'s Targets,
}

/// The solids read as the part as designed, by name (`None`: refused).
pub type Targets =
    std::cell::RefCell<BTreeMap<String, Option<std::sync::Arc<crate::geometry::target::Target>>>>;

/// Where an extrusion's shape comes from.
#[derive(Clone, Debug)]
pub(in crate::sema) enum Source<'a> {
    /// One shape.
    Fixed(Shape),
    /// A profile's expression (it may follow the layer).
    Expr(&'a Expr),
    /// A mesh, cut on every layer.
    Mesh(crate::sema::model::MeshSolid),
}

/// An extrude block as written.
pub struct Written<'a> {
    pub(in crate::sema) name: String,
    pub(in crate::sema) source: Source<'a>,
    height: Option<(Length, Span)>,
    /// `top = …` and where, if written (then there is no `height`).
    pub(in crate::sema) top: Option<(Top, Span)>,
    /// `on = scan(…)`, if written (only with `top`).
    pub(in crate::sema) base: Option<crate::sema::model::ScanBase>,
    pub(in crate::sema) measure: Measure,
    pub(in crate::sema) span: Span,
    pub(in crate::sema) profile_span: Span,
}

/// Reads an extrude block; returns it and its bead model, each when it is
/// right (the bead is known even when the block is not).
pub fn read<'a>(
    env: &mut Env<'a>,
    name: &str,
    stmts: &'a [Stmt],
    span: Span,
    scope: &Scope<'_, 'a>,
    diags: &mut Diagnostics,
) -> (Option<Written<'a>>, Option<Bead>) {
    // `top` is a function of the position: read by `top::read`, not as a value.
    let f = Fields::block(
        env,
        stmts,
        &EXTRUDE,
        format!("extrude `{name}`"),
        span,
        diags,
    );
    let profile = f.value(&extrude::PROFILE, diags);
    let profile_span = profile.map(|p| p.span).unwrap_or(span);
    let data = env.data.clone();
    // A section of the scan is cut while the scan is read.
    let cut = profile.and_then(|v| scan_section(v, diags));
    let mut solid = |n: &str, at: Span, diags: &mut Diagnostics| {
        crate::sema::solid::target::nominal(env, n, at, name, scope, diags)
    };
    let on = on(&f, (data.as_ref(), &mut solid), cut.flatten(), diags);
    let mut source = match (profile, cut) {
        (Some(v), Some(z)) => z.and_then(|z| from_scan(v.span, z, on.as_ref(), diags)),
        _ => profile.and_then(|v| source(v, scope, data.as_ref(), diags)),
    };
    // A profile written inline that follows the layer is evaluated per layer,
    // like a named one.
    if let Some(Source::Fixed(_)) = source {
        let inline = stmts
            .iter()
            .find_map(|s| match (&s.body, s.kind.node.as_str()) {
                (Body::Assign(e), key) if key == extrude::PROFILE.key => Some(e),
                _ => None,
            });
        if let Some(e) = inline.filter(|e| env.depends_on_layer(e)) {
            source = Some(Source::Expr(e));
        }
    }
    let height = f.optional(
        &extrude::HEIGHT,
        f.quantity(&extrude::HEIGHT, diags)
            .map(|(h, sp)| (Length(h), sp)),
    );
    let top = match f.expr(&extrude::TOP) {
        None => Some(None),
        Some(e) => {
            read_top(env, e, (name, source.as_ref()), scope, diags).map(|t| Some((t, e.span)))
        }
    };
    if let (Some(hs), Some(ts)) = (f.span(&extrude::HEIGHT), f.span(&extrude::TOP)) {
        diags.push(message::solid::height_and_top(hs, ts));
    }
    let height = height.filter(|_| !(f.has(&extrude::HEIGHT) && f.has(&extrude::TOP)));
    let base = on.map(|o| o.map(|(b, _)| b));
    if let (Some(on), None) = (f.span(&extrude::ON), f.span(&extrude::TOP)) {
        diags.push(message::scan::needs_top(on));
    }
    let measure = crate::sema::solid::loft::measure(&f, &extrude::SIZE, diags);
    let bead = crate::sema::process::bead::named(
        f.value(&extrude::BEAD, diags),
        extrude::BEAD.key,
        "the layers",
        scope.beads,
        scope.declared,
        diags,
    );
    let written = match (source, height, top, measure, base) {
        (Some(source), Some(height), Some(top), Some(measure), Some(base)) => Some(Written {
            name: name.to_string(),
            source,
            height,
            top,
            base,
            measure,
            span,
            profile_span,
        }),
        _ => None,
    };
    (written, bead)
}

/// `on = scan(…)`, with its section at `z` when the profile asks for one:
/// `Some(None)` when not written, `None` when written wrong (reported).
fn on(
    f: &Fields<'_>,
    read: (
        Option<&crate::sema::DataReader>,
        crate::sema::solid::scan::SolidNamed<'_>,
    ),
    z: Option<f64>,
    diags: &mut Diagnostics,
) -> Option<Option<(ScanBase, Cut)>> {
    let Some(v) = f.value(&extrude::ON, diags) else {
        return (!f.has(&extrude::ON)).then_some(None);
    };
    match &v.value {
        Value::Call(c) => crate::sema::solid::scan::read(c, v.span, read, z, diags).map(Some),
        _ => None,
    }
}

/// `profile = scan_section(z)`: `Some(Some(z))`, or `Some(None)` when its
/// height is written wrong (reported); `None` for any other profile.
fn scan_section(v: &Spanned, diags: &mut Diagnostics) -> Option<Option<f64>> {
    match &v.value {
        Value::Call(c) if c.func == SCAN_SECTION.name => {
            let f = Fields::call(c, &SCAN_SECTION, diags);
            Some(f.quantity(&scan_section::Z, diags).map(|q| q.0))
        }
        _ => None,
    }
}

/// The profile `scan_section(z)` (written at `at`) from the scan `on`
/// read with its section.
fn from_scan<'a>(
    at: Span,
    z: f64,
    on: Option<&Option<(ScanBase, Cut)>>,
    diags: &mut Diagnostics,
) -> Option<Source<'a>> {
    match on? {
        None => {
            diags.push(message::scan::section_without_scan(at));
            None
        }
        Some((_, Some(Ok(islands)))) => Some(Source::Fixed(crate::geometry::mesh::shape_of(
            islands.clone(),
            at,
        ))),
        Some((b, Some(Err(fault)))) => {
            diags.push(message::scan::section(&b.path, z, fault, at, b.span));
            None
        }
        // Asked for, so cut.
        Some((_, None)) => None,
    }
}

/// Reads `top = e` over the footprint `source` (tried at a point of it).
fn read_top<'a>(
    env: &mut Env<'a>,
    e: &Expr,
    (own, source): (&str, Option<&Source<'_>>),
    scope: &Scope<'_, 'a>,
    diags: &mut Diagnostics,
) -> Option<Top> {
    // `top = NAME`: a solid of the file as the target.
    if let Some(t) = crate::sema::solid::target::named_top(env, e, own, scope, diags) {
        return t;
    }
    let shape = match source {
        Some(Source::Fixed(s)) => Some(s.clone()),
        Some(Source::Expr(p)) => {
            // Only for a point to try the top at: errors of the
            // profile itself are reported where it is assembled.
            let mut scratch = Diagnostics::new();
            env.eval(p, &mut scratch)
                .and_then(|v| profile::shape(&v, "a profile", &mut scratch))
        }
        Some(Source::Mesh(_)) | None => None,
    };
    let at = crate::sema::solid::top::reference_point(shape.as_ref());
    top::read(env, e, at, scope.constants, diags)
}

pub(in crate::sema) fn source<'a>(
    v: &Spanned,
    scope: &Scope<'_, 'a>,
    data: Option<&crate::sema::DataReader>,
    diags: &mut Diagnostics,
) -> Option<Source<'a>> {
    match &v.value {
        Value::Call(c) if c.func == "mesh" => {
            crate::sema::solid::mesh::read(c, v.span, data, diags).map(Source::Mesh)
        }
        Value::Symbol(n) => {
            if let Some((e, _)) = scope.profiles.get(n) {
                Some(Source::Expr(e))
            } else if let Some((s, _)) = scope.sections.get(n) {
                Some(Source::Fixed(Shape::Section(*s)))
            } else if scope.declared.contains(n) {
                None
            } else {
                let names: Vec<&str> = scope
                    .profiles
                    .keys()
                    .chain(scope.sections.keys())
                    .map(String::as_str)
                    .collect();
                diags.push(unknown_name(n, v.span, "profile or section", &names));
                None
            }
        }
        _ => profile::shape(v, "`profile`", diags).map(Source::Fixed),
    }
}

/// The scan speed of planar layers: `process { speed }`, else the speed a
/// measured bead model was measured at.
pub(in crate::sema) fn scan_speed(
    speed: Option<(Speed, Span)>,
    bead: &Bead,
    at: Span,
    diags: &mut Diagnostics,
) -> Option<Speed> {
    match (speed, &bead.model) {
        (Some((v, sp)), _) => {
            if !bead.covers_speed(v) {
                let measured = matches!(bead.model, HeightModel::Measured { .. });
                diags.push(message::solid::scan_speed_outside_bead(
                    v,
                    sp,
                    &BeadSpeeds {
                        name: &bead.name,
                        speed: bead.speed,
                        at: bead.speed_span,
                        measured,
                    },
                ));
                return None;
            }
            Some(v)
        }
        (None, HeightModel::Measured { speed, .. }) => Some(*speed),
        (None, _) => {
            diags.push(message::solid::no_scan_speed(at));
            None
        }
    }
}

/// How tall the extrusion is: `layers` in the slicing block or `height` in
/// the extrude block, exactly one of them; a mesh is as tall as it is
/// unless the file builds part of it.
fn extent(w: &Written<'_>, spec: &PlanarSpec, diags: &mut Diagnostics) -> Option<Extent> {
    match (spec.layers, w.height) {
        (Some((n, ls)), None) => Some(Extent::Layers(n, ls)),
        (None, Some((h, hs))) => Some(Extent::Height(h, hs)),
        (Some((_, ls)), Some((_, hs))) => {
            diags.push(message::solid::layers_and_height(ls, hs));
            None
        }
        (None, None) => match &w.source {
            Source::Mesh(m) => Some(Extent::Height(m.top, m.span)),
            _ => {
                diags.push(message::solid::no_height(w.span));
                None
            }
        },
    }
}

/// Whether tracks `d` apart (declared at `at`) neither leave gaps nor pile
/// up with `bead`; `flat` is the flat-top offset, if known, for the help.
pub(in crate::sema) fn declared_offset(
    d: Length,
    at: Span,
    bead: &Bead,
    flat: Option<Length>,
    diags: &mut Diagnostics,
) -> bool {
    let width = bead.width;
    if d.0 > width.0 * (1.0 + 1e-9) {
        diags.push(message::solid::offset_gaps(d, width, at, bead.span, flat));
        return false;
    }
    if d.0 < width.0 * MIN_OFFSET_RATIO {
        diags.push(message::solid::offset_piles_up(d, width, at, flat));

        return false;
    }
    true
}

/// Joins an extrusion with its planar slicing and its bead: checks the scan
/// speed (`speed` as the process block gives it: `Some(None)` when not
/// written, `None` when wrong) and the track offset against
/// the bead, and keeps the profile as a shape or, when it follows the layer,
/// as an expression over the file's `constants`.
pub fn assemble(
    env: &mut Env<'_>,
    w: Written<'_>,
    bead: &Bead,
    spec: PlanarSpec,
    speed: Option<Option<(Speed, Span)>>,
    constants: &[(String, Span, Expr)],
    diags: &mut Diagnostics,
) -> Option<(Extrusion, PlanarSlicing)> {
    // The height is declared once whatever the speed.
    let extent = extent(&w, &spec, diags);
    let width = bead.width;
    // `None` when the process speed is wrong (reported there) or the bead
    // model does not hold at it.
    let v = speed.and_then(|s| scan_speed(s, bead, spec.span, diags));
    let flat = v.map(|v| flat_top_offset(width, bead.model.height_at(v, width)));
    // A declared offset is checked against the bead's width, whatever the
    // speed; the flat-top offset d = A/h never leaves a gap or piles up.
    let offset_ok = match spec.offset {
        Some((d, at)) if spec.overlapped() => declared_offset(d, at, bead, flat, diags),
        _ => true,
    };
    let (Some(v), Some(flat), true) = (v, flat, offset_ok) else {
        return None;
    };
    let (offset, offset_derived) = match spec.offset {
        Some((d, _)) => (d, false),
        None => (flat, true),
    };
    let (profile, shape_span) = match w.source {
        Source::Fixed(s) => (LayerProfile::Fixed(s), w.profile_span),
        Source::Expr(e) if env.depends_on_layer(e) => (
            LayerProfile::PerLayer(ProfileExpr {
                expr: e.clone(),
                constants: constants.to_vec(),
            }),
            e.span,
        ),
        Source::Mesh(m) => {
            let span = m.span;
            (LayerProfile::Mesh(m), span)
        }
        // A named profile that does not follow the layer was checked where
        // it is declared; it is one shape.
        Source::Expr(e) => {
            let v = env.eval(e, diags)?;
            (
                LayerProfile::Fixed(profile::shape(&v, "a profile", diags)?),
                e.span,
            )
        }
    };
    Some((
        Extrusion {
            name: w.name,
            profile,
            extent: extent?,
            measure: w.measure,
            span: w.span,
            profile_span: w.profile_span,
            shape_span,
        },
        {
            let (contours, infill) = (spec.contours, spec.infill);
            spec.into_slicing((offset, offset_derived), v, contours, infill)
        },
    ))
}
