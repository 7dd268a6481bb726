//! `loft NAME { from, to, spine, twist, morph, size, wall }`: a solid swept from
//! one section to another along a spine, built as a single-bead wall.

use super::eval::{unknown_name, Env};
use super::fields::Fields;
use super::model::{Bead, Loft, Measure, Morph, Section, Spine};
use super::section;
use super::value::{Spanned, Value};
use crate::diag::{message, Diagnostics};
use crate::span::Span;
use crate::syntax::ast::Stmt;
use crate::units::{Angle, Dim, Length};
use std::collections::BTreeMap;

/// Declared sections and beads, by name.
pub struct Scope<'s> {
    /// `section NAME = …`
    pub sections: &'s BTreeMap<String, (Section, Span)>,
    /// `bead NAME { … }`
    pub beads: &'s BTreeMap<String, Bead>,
    /// Every name declared, including those whose declaration had errors (so
    /// a use of them is not reported a second time as unknown).
    pub declared: &'s [String],
}

/// Reads a loft block; returns the loft and its wall's bead model, each when
/// it is right (the bead is known even when the loft is not, so what depends
/// only on the bead is still checked).
pub fn read<'a>(
    env: &mut Env<'a>,
    name: &str,
    stmts: &'a [Stmt],
    span: Span,
    scope: &Scope<'_>,
    diags: &mut Diagnostics,
) -> (Option<Loft>, Option<Bead>) {
    let f = Fields::block(
        env,
        stmts,
        &["from", "to", "spine", "twist", "morph", "size", "wall"],
        &[],
        format!("loft `{name}`"),
        span,
        diags,
    );
    let from = f
        .value("from", Some("circle(diameter = 60 mm)"), diags)
        .and_then(|v| section_value(v, scope, diags));
    let to = f
        .value("to", Some("square(side = 60 mm)"), diags)
        .and_then(|v| section_value(v, scope, diags));
    let spine = f
        .value("spine", Some("arc(radius = 250 mm, angle = 45 deg)"), diags)
        .and_then(|v| spine_value(v, diags));
    let twist = f
        .quantity("twist", Dim::ANGLE, None, diags)
        .map(|t| Angle(t.0))
        .or(if f.has("twist") {
            None
        } else {
            Some(Angle(0.0))
        });
    let measure = match f.symbol("size", &["centre", "center", "outer"], None, diags) {
        Some((s, _)) if s == "outer" => Some(Measure::Outer),
        Some(_) => Some(Measure::Centre),
        None if f.has("size") => None,
        None => Some(Measure::Centre),
    };
    let morph = f.symbol("morph", &["superellipse", "radial"], None, diags);
    let bead = super::bead::named(
        f.value("wall", Some("my_bead"), diags),
        "wall",
        "the wall",
        scope.beads,
        scope.declared,
        diags,
    );
    let family = |s: &Section| {
        matches!(
            s,
            Section::Circle { .. } | Section::Ellipse { .. } | Section::Rectangle { .. }
        )
    };
    // The morph needs only the two ends.
    let morph = match (from, to, morph) {
        (_, _, Some((m, _))) if m == "radial" => Some(Morph::Radial),
        (Some(from), Some(to), Some((_, ms))) => {
            if family(&from) && family(&to) {
                Some(Morph::Superellipse)
            } else {
                diags.push(message::shape::superellipse_ends(ms));
                None
            }
        }
        (Some(from), Some(to), None) if !f.has("morph") => Some(if family(&from) && family(&to) {
            Morph::Superellipse
        } else {
            Morph::Radial
        }),
        _ => None,
    };
    let (
        Some(from),
        Some(to),
        Some((spine, spine_span)),
        Some(twist),
        Some(measure),
        Some(b),
        Some(morph),
    ) = (from, to, spine, twist, measure, bead.as_ref(), morph)
    else {
        return (None, bead);
    };
    let spans = [f.span("from").unwrap_or(span), f.span("to").unwrap_or(span)];
    let (from, to) = match measure {
        Measure::Centre => (from, to),
        Measure::Outer => {
            let mut ok = true;
            let mut shrink = |s: Section, at: Span| match s.inset(Length(b.width.0 / 2.0)) {
                Some(s) => s,
                None => {
                    ok = false;
                    diags.push(message::shape::section_too_small(b.width, at));
                    s
                }
            };
            let r = (shrink(from, spans[0]), shrink(to, spans[1]));
            if !ok {
                return (None, bead);
            }
            r
        }
    };
    let loft = Loft {
        name: name.to_string(),
        from,
        to,
        spine,
        twist,
        morph,
        measure,
        span,
        spine_span,
        section_spans: spans,
    };
    (Some(loft), bead)
}

fn section_value(v: &Spanned, scope: &Scope<'_>, diags: &mut Diagnostics) -> Option<Section> {
    match &v.value {
        Value::Symbol(s) => match scope.sections.get(s) {
            Some((sec, _)) => Some(*sec),
            None if scope.declared.contains(s) => None,
            None => {
                let names: Vec<&str> = scope.sections.keys().map(String::as_str).collect();
                diags.push(unknown_name(s, v.span, "section", &names));
                None
            }
        },
        Value::Call(c) if section::SHAPES.contains(&c.func.as_str()) => section::read(c, diags),
        other => {
            diags.push(message::shape::expected_section(
                other,
                v.span,
                section::SHAPES,
            ));
            None
        }
    }
}

fn spine_value(v: &Spanned, diags: &mut Diagnostics) -> Option<(Spine, Span)> {
    let spine = match &v.value {
        Value::Call(c) if c.func == "line" => {
            let f = Fields::call(c, &["length"], &["length"], diags);
            Spine::Line {
                length: Length(f.positive("length", Dim::LENGTH, Some("100 mm"), diags)?.0),
            }
        }
        Value::Call(c) if c.func == "arc" => {
            let f = Fields::call(c, &[], &["radius", "angle"], diags);
            let r = f.positive("radius", Dim::LENGTH, Some("250 mm"), diags);
            let a = f.positive("angle", Dim::ANGLE, Some("45 deg"), diags);
            let (a, aspan) = a?;
            if a > std::f64::consts::PI * 1.5 {
                diags.push(message::shape::bend_too_far(Angle(a), aspan));
                return None;
            }
            Spine::Arc {
                radius: Length(r?.0),
                angle: Angle(a),
            }
        }
        other => {
            diags.push(message::shape::not_a_spine(other, v.span));

            return None;
        }
    };
    Some((spine, v.span))
}
