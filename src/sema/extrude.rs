//! `extrude NAME { profile, height, size, bead }`: a profile built up in flat
//! layers, and its assembly with `slicing planar { … }` into a [`Plan::Block`]:
//! the lift and track offset derived from the bead model where they are `auto`,
//! the layer count, and the profile evaluated on every layer.
//!
//! [`Plan::Block`]: super::model::Plan::Block

use super::fields::Fields;
use super::model::{Bead, Extrusion, HeightModel, Measure, PlanarSlicing, Process, Shape};
use super::profile;
use super::slicing::{PlanarSpec, MAX_LAYERS};
use super::value::{unknown_name, Env, Spanned, Value};
use crate::bead::{flat_top_offset, planar_lift, MIN_OFFSET_RATIO};
use crate::diag::{Code, Diagnostic, Diagnostics};
use crate::span::Span;
use crate::syntax::ast::{Body, Expr, Stmt};
use crate::units::{short, Dim, Length, Speed};
use std::collections::BTreeMap;

/// What an extrusion may refer to.
pub struct Scope<'s, 'a> {
    /// `section NAME = …`
    pub sections: &'s BTreeMap<String, (super::model::Section, Span)>,
    /// `profile NAME = …`, kept as expressions: they may depend on `layer`.
    pub profiles: &'s BTreeMap<String, (&'a Expr, Span)>,
    /// `bead NAME { … }`
    pub beads: &'s BTreeMap<String, Bead>,
    /// Every name declared, including failed ones (no second report).
    pub declared: &'s [String],
}

/// Where an extrusion's shape comes from.
#[derive(Clone, Debug)]
enum Source<'a> {
    Fixed(Shape),
    Expr(&'a Expr),
}

/// An extrude block as written.
pub struct Written<'a> {
    name: String,
    source: Source<'a>,
    height: Option<(Length, Span)>,
    measure: Measure,
    /// The bead model it is built with.
    pub bead: Bead,
    span: Span,
    profile_span: Span,
}

/// Reads an extrude block.
pub fn read<'a>(
    env: &mut Env<'a>,
    name: &str,
    stmts: &'a [Stmt],
    span: Span,
    scope: &Scope<'_, 'a>,
    diags: &mut Diagnostics,
) -> Option<Written<'a>> {
    let f = Fields::block(
        env,
        stmts,
        &["profile", "height", "size", "bead"],
        &[],
        format!("extrude `{name}`"),
        span,
        diags,
    );
    let profile = f.value("profile", Some("my_profile"), diags);
    let profile_span = profile.map(|p| p.span).unwrap_or(span);
    let mut source = profile.and_then(|v| source(v, scope, diags));
    // A profile written inline that follows the layer is evaluated per layer,
    // like a named one.
    if let Some(Source::Fixed(_)) = source {
        let inline = stmts
            .iter()
            .find_map(|s| match (&s.body, s.kind.node.as_str()) {
                (Body::Assign(e), "profile") => Some(e),
                _ => None,
            });
        if let Some(e) = inline.filter(|e| env.depends_on_layer(e)) {
            source = Some(Source::Expr(e));
        }
    }
    let height = match f.positive("height", Dim::LENGTH, None, diags) {
        Some((h, sp)) => Some(Some((Length(h), sp))),
        None if f.has("height") => None,
        None => Some(None),
    };
    let measure = match f.symbol("size", &["centre", "center", "outer"], None, diags) {
        Some((s, _)) if s == "outer" => Some(Measure::Outer),
        Some(_) => Some(Measure::Centre),
        None if f.has("size") => None,
        None => Some(Measure::Centre),
    };
    let bead = super::bead::named(
        f.value("bead", Some("my_bead"), diags),
        "bead",
        "the layers",
        scope.beads,
        scope.declared,
        diags,
    );
    Some(Written {
        name: name.to_string(),
        source: source?,
        height: height?,
        measure: measure?,
        bead: bead?,
        span,
        profile_span,
    })
}

fn source<'a>(v: &Spanned, scope: &Scope<'_, 'a>, diags: &mut Diagnostics) -> Option<Source<'a>> {
    match &v.value {
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
fn scan_speed(process: &Process, bead: &Bead, at: Span, diags: &mut Diagnostics) -> Option<Speed> {
    match (process.speed, bead.model) {
        (Some((v, sp)), _) => {
            let [lo, hi] = bead.speed;
            if !bead.covers_speed(v) {
                let measured = matches!(bead.model, HeightModel::Measured { .. });
                diags.push(
                    Diagnostic::error(
                        Code::OutOfRange,
                        if measured {
                            format!("the scan speed {v} is not the {lo} bead `{}` was measured at", bead.name)
                        } else {
                            format!("the scan speed {v} is outside the {lo} .. {hi} bead `{}` is valid for", bead.name)
                        },
                    )
                    .label(sp, "scan speed")
                    .label(bead.speed_span, "the bead model's speeds")
                    .help(if measured {
                        "a measured bead holds at its own speed: scan at that speed, or measure the bead at this one".to_string()
                    } else {
                        format!("scan at {lo} .. {hi}, or fit the bead model over the speed you need")
                    }),
                );
                return None;
            }
            Some(v)
        }
        (None, HeightModel::Measured { speed, .. }) => Some(speed),
        (None, _) => {
            diags.push(
                Diagnostic::error(Code::MissingField, "planar layers need a scan speed")
                    .label(at, "the speed of these layers' tracks is not given")
                    .help("add `speed = 6 mm/s` to the process block"),
            );
            None
        }
    }
}

/// A declared layer height this far (relative) from what the tracks lay is
/// reported.
const LIFT_TOLERANCE: f64 = 0.02;

/// A height this far (relative) from a whole number of layers is reported.
const HEIGHT_TOLERANCE: f64 = 0.01;

/// Joins an extrusion with its planar slicing: derives what is `auto` and
/// evaluates the profile on every layer.
pub fn assemble(
    env: &mut Env<'_>,
    w: Written<'_>,
    spec: PlanarSpec,
    process: &Process,
    diags: &mut Diagnostics,
) -> Option<(Extrusion, PlanarSlicing)> {
    let bead = &w.bead;
    let width = bead.width;
    let v = scan_speed(process, bead, spec.span, diags)?;
    let h = bead.model.height_at(v, width);
    let overlapped = spec.overlapped();
    let (offset, offset_derived) = match spec.offset {
        Some((d, _)) => (d, false),
        None => (flat_top_offset(width, h), true),
    };
    let offset_at = spec.offset.map(|o| o.1).unwrap_or(spec.span);
    if overlapped && offset.0 > width.0 * (1.0 + 1e-9) {
        diags.push(
            Diagnostic::error(
                Code::FillGap,
                format!(
                    "tracks {} apart leave gaps: the bead is {} wide",
                    offset, width
                ),
            )
            .label(offset_at, "track offset")
            .label(bead.span, "bead model")
            .help(format!(
                "use an offset of at most the bead width; {} keeps the top flat (d = A/h)",
                flat_top_offset(width, h)
            )),
        );
        return None;
    }
    if overlapped && offset.0 < width.0 * MIN_OFFSET_RATIO {
        diags.push(
            Diagnostic::error(
                Code::Overlap,
                format!(
                    "tracks {} apart overlap by {:.0} % of the {} bead: the layer piles up",
                    offset,
                    100.0 * (1.0 - offset.0 / width.0),
                    width
                ),
            )
            .label(offset_at, "track offset")
            .help(format!(
                "overlaps of about 33 % keep tracks level; d = A/h = {} gives a flat top",
                flat_top_offset(width, h)
            )),
        );
        return None;
    }
    let laid = planar_lift(width, h, overlapped.then_some(offset));
    let (lift, lift_derived) = match spec.lift {
        Some((l, at)) => (declared_lift(l, at, laid, overlapped, bead, diags)?, false),
        None => (
            derived_lift(laid, overlapped, offset, offset_at, &spec, bead, diags)?,
            true,
        ),
    };
    let layers = match (spec.layers, w.height) {
        (Some((n, _)), None) => n,
        (None, Some((height, _))) => {
            // Whole layers, at least as tall as asked (machining takes off the rest).
            let n = (height.0 / lift.0 * (1.0 - 1e-9)).ceil();
            if n > MAX_LAYERS as f64 {
                diags.push(
                    Diagnostic::error(
                        Code::TooManyPoints,
                        format!(
                            "{} in layers of {} is more than {MAX_LAYERS} layers",
                            height, lift
                        ),
                    )
                    .label(w.height.map(|h| h.1).unwrap_or(w.span), "height"),
                );
                return None;
            }
            let n = (n as usize).max(1);
            let built = n as f64 * lift.0;
            if (built - height.0).abs() > HEIGHT_TOLERANCE * height.0 {
                diags.push(
                    Diagnostic::warning(
                        Code::HeightRounded,
                        format!(
                            "{n} layers of {} build {}: the {} asked for and {} more",
                            lift,
                            Length(built),
                            height,
                            Length(built - height.0)
                        ),
                    )
                    .label(w.height.map(|h| h.1).unwrap_or(w.span), "height")
                    .help("layers come whole: give `layers` in the slicing block instead, or a height that is a multiple of the layer height"),
                );
            }
            n
        }
        (Some((_, ls)), Some((_, hs))) => {
            diags.push(
                Diagnostic::error(
                    Code::Duplicate,
                    "give the layer count or the height, not both",
                )
                .label(ls, "layers")
                .label(hs, "height")
                .help("the other follows from the layer height"),
            );
            return None;
        }
        (None, None) => {
            diags.push(
                Diagnostic::error(Code::MissingField, "how tall is the extrusion?")
                    .label(w.span, "no `height`")
                    .help("add `height = 24 mm` here, or `layers = 35` to the slicing block"),
            );
            return None;
        }
    };
    let (shapes, shape_span) = match w.source {
        Source::Fixed(s) => {
            within_budget(pieces(&s).saturating_mul(layers), w.profile_span, diags)?;
            (vec![s; layers], w.profile_span)
        }
        Source::Expr(e) => (
            per_layer(env, e, layers, lift.0, w.profile_span, diags)?,
            e.span,
        ),
    };
    Some((
        Extrusion {
            name: w.name,
            layers: shapes,
            measure: w.measure,
            lift,
            lift_derived,
            span: w.span,
            profile_span: w.profile_span,
            shape_span,
        },
        PlanarSlicing {
            contours: spec.contours,
            offset,
            offset_derived,
            infill: spec.infill.map(|(mut r, extend)| {
                r.extend = extend.unwrap_or(offset);
                r
            }),
            chord_error: spec.chord_error,
            speed: v,
            span: spec.span,
            offset_span: spec.offset.map(|o| o.1),
            lift_span: spec.lift.map(|l| l.1),
        },
    ))
}

/// The profile on every layer: evaluated once if it does not use `layer`.
fn per_layer(
    env: &mut Env<'_>,
    e: &Expr,
    layers: usize,
    lift: f64,
    at: Span,
    diags: &mut Diagnostics,
) -> Option<Vec<Shape>> {
    if !env.depends_on_layer(e) {
        let v = env.eval(e, diags)?;
        let s = profile::shape(&v, "a profile", diags)?;
        within_budget(pieces(&s).saturating_mul(layers), at, diags)?;
        return Some(vec![s; layers]);
    }
    let mut out = Vec::with_capacity(layers.min(1 << 16));
    let mut total = 0usize;
    for k in 0..layers {
        let mut scratch = Diagnostics::new();
        let s = env.at_layer(k, k as f64 * lift, |env| {
            let v = env.eval(e, &mut scratch)?;
            profile::shape(&v, "a profile", &mut scratch)
        });
        match s {
            Some(s) if !scratch.has_errors() => {
                total = total.saturating_add(pieces(&s));
                within_budget(total, at, diags)?;
                out.push(s);
            }
            _ => {
                diags.push(
                    Diagnostic::error(
                        Code::ProfileLayer,
                        format!(
                            "the profile is not a valid shape on layer {} (layer = {k})",
                            k + 1
                        ),
                    )
                    .label(at, "profile")
                    .help("see the error below; the profile's numbers change with `layer`"),
                );
                diags.extend(scratch);
                return None;
            }
        }
    }
    Some(out)
}

/// Most outline pieces over all layers: every piece of every layer is offset,
/// clipped and checked, so the work (and the profiles kept) grows with it.
const MAX_PROFILE_WORK: usize = 20_000_000;

/// Pieces of a shape's outline (an ellipse's flattening is bounded apart).
fn pieces(s: &Shape) -> usize {
    match s {
        Shape::Outline(o) => o.segments.len() + 1,
        Shape::Section(_) => 8,
    }
}

fn within_budget(total: usize, at: Span, diags: &mut Diagnostics) -> Option<()> {
    if total <= MAX_PROFILE_WORK {
        return Some(());
    }
    diags.push(
        Diagnostic::error(
            Code::TooManyPoints,
            format!("the profile's pieces over all layers come to more than {MAX_PROFILE_WORK}"),
        )
        .label(at, "profile")
        .help("fewer layers, or an outline of fewer pieces (an arc is one piece)"),
    );
    None
}

/// How a layer's rise follows from its bead, in words.
fn lift_rule(overlapped: bool) -> &'static str {
    if overlapped {
        "A/d: the bead's cross-section A spread over the track offset d"
    } else {
        "A/w: one track a layer, its cross-section A spread over its width w"
    }
}

/// A declared layer height: within the bead's heights (else an error), and
/// reported when it is not what the tracks lay (`laid`).
fn declared_lift(
    l: Length,
    at: Span,
    laid: Length,
    overlapped: bool,
    bead: &Bead,
    diags: &mut Diagnostics,
) -> Option<Length> {
    if !bead.covers_height(l) {
        diags.push(
            Diagnostic::error(
                Code::LayerHeight,
                format!(
                    "layers {} high are outside the {} .. {} bead `{}` can lay",
                    l, bead.height[0], bead.height[1], bead.name
                ),
            )
            .label(at, "declared layer height")
            .label(bead.height_span, "the bead's heights")
            .help(format!(
                "`layer_height = auto` gives {laid}, what these tracks lay"
            )),
        );
        return None;
    }
    // The nozzle rises by the declared height, the part by what its tracks
    // lay: a difference adds up layer after layer (seed 001's fixed lift
    // undershot and needed an extra lift every 3 layers).
    let drift = laid.0 - l.0;
    if drift.abs() > LIFT_TOLERANCE * laid.0 {
        diags.push(
            Diagnostic::warning(
                Code::LiftMismatch,
                format!(
                    "layers {} high, but these tracks lay {} a layer ({}): the standoff changes by {} a layer",
                    l,
                    laid,
                    lift_rule(overlapped),
                    Length(drift.abs()),
                ),
            )
            .label(at, "declared layer height")
            .help(format!(
                "`layer_height = auto` uses {laid}; keep a declared height only if the process is controlled to it"
            )),
        );
    }
    Some(l)
}

/// `layer_height = auto`: what the tracks lay, if the bead allows it; if not,
/// the error names the offsets (or speeds) that would.
fn derived_lift(
    laid: Length,
    overlapped: bool,
    offset: Length,
    offset_at: Span,
    spec: &PlanarSpec,
    bead: &Bead,
    diags: &mut Diagnostics,
) -> Option<Length> {
    if bead.covers_height(laid) {
        return Some(laid);
    }
    let [lo, hi] = bead.height;
    let width = bead.width;
    let a = laid.0 * if overlapped { offset.0 } else { width.0 };
    diags.push(
        Diagnostic::error(
            Code::LayerHeight,
            format!(
                "these tracks lay {} a layer ({}), outside the {} .. {} bead `{}` allows",
                laid,
                lift_rule(overlapped),
                lo,
                hi,
                bead.name
            ),
        )
        .label(
            if overlapped { offset_at } else { spec.span },
            if overlapped {
                "track offset"
            } else {
                "one track a layer"
            },
        )
        .label(bead.height_span, "the bead's heights")
        .help(if overlapped {
            format!(
                "tracks {} .. {} apart lay an allowed height (A/d with A = {} mm²)",
                Length(a / hi.0),
                Length(a / lo.0),
                short(a)
            )
        } else {
            wall_help(bead, width, lo, hi)
        }),
    );
    None
}

/// What makes a one-track layer rise by an allowed height: the scan speeds at
/// which `A/w` lies in `lo .. hi` (within the bead's speed range), or overlap.
fn wall_help(bead: &Bead, w: Length, lo: Length, hi: Length) -> String {
    let overlap = "or overlap tracks (contours > 1 or a raster) so the layer rises by A/d";
    if let HeightModel::Measured { .. } = bead.model {
        return format!("a measured bead has the one height it was measured with; {overlap}");
    }
    // The bead height whose segment area spread over w is the rise r.
    let speed = |r: Length| {
        let h = crate::bead::segment_height(w.0, r.0 * w.0);
        bead.model.speed_for(Length(h), w).0
    };
    let (a, b) = (speed(lo), speed(hi));
    let (a, b) = (a.min(b).max(bead.speed[0].0), a.max(b).min(bead.speed[1].0));
    if a.is_finite() && b.is_finite() && a <= b {
        format!(
            "one track a layer rises by A/w: scan at {} .. {} for that, {overlap}",
            Speed(a),
            Speed(b)
        )
    } else {
        format!("no speed in the bead's range lays an allowed A/w; {overlap}")
    }
}
