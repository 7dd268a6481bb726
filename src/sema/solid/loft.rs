//! `loft NAME { from, to, spine, twist, morph, size, wall }`: a solid swept from
//! one section to another along a spine, built as a single-bead wall.

use crate::diag::{message, Diagnostics};
use crate::sema::eval::{unknown_name, Env};
use crate::sema::fields::Fields;
use crate::sema::model::{Bead, Loft, Measure, Morph, Section, Spine};
use crate::sema::schema::solid::{loft, spine, ARC, LINE, LOFT};
use crate::sema::schema::Field;
use crate::sema::solid::section;
use crate::sema::value::{Spanned, Value};
use crate::span::Span;
use crate::syntax::ast::Stmt;
use crate::units::{Angle, Length};
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
    let f = Fields::block(env, stmts, &LOFT, format!("loft `{name}`"), span, diags);
    let from = f
        .value(&loft::FROM, diags)
        .and_then(|v| section_value(v, scope, diags));
    let to = f
        .value(&loft::TO, diags)
        .and_then(|v| section_value(v, scope, diags));
    let spine = f
        .value(&loft::SPINE, diags)
        .and_then(|v| spine_value(v, diags));
    let twist = f.quantity_or_default(&loft::TWIST, diags).map(Angle);
    let measure = measure(&f, &loft::SIZE, diags);
    let morph = f.word(&loft::MORPH, diags);
    let bead = crate::sema::process::bead::named(
        f.value(&loft::WALL, diags),
        loft::WALL.key,
        "the wall",
        scope.beads,
        scope.declared,
        diags,
    );
    let morph = morph_between(&f, from, to, morph, diags);
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
    let spans = [
        f.span(&loft::FROM).unwrap_or(span),
        f.span(&loft::TO).unwrap_or(span),
    ];
    let Some((from, to)) = measured_sections(from, to, measure, b, spans, diags) else {
        return (None, bead);
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

/// `size = centre | center | outer` (`f` the block's `size` field).
pub(in crate::sema) fn measure(
    fields: &Fields<'_>,
    f: &Field,
    diags: &mut Diagnostics,
) -> Option<Measure> {
    match fields.word_or_default(f, diags)? {
        "outer" => Some(Measure::Outer),
        _ => Some(Measure::Centre),
    }
}

/// The morph between two sections: as written (`morph`), else the
/// superellipse where both ends are of its family, else radial. It needs
/// only the two ends.
pub(in crate::sema) fn morph_between(
    f: &Fields<'_>,
    from: Option<Section>,
    to: Option<Section>,
    morph: Option<(&str, Span)>,
    diags: &mut Diagnostics,
) -> Option<Morph> {
    let family = |s: &Section| {
        matches!(
            s,
            Section::Circle { .. } | Section::Ellipse { .. } | Section::Rectangle { .. }
        )
    };
    match (from, to, morph) {
        (_, _, Some(("radial", _))) => Some(Morph::Radial),
        (Some(from), Some(to), Some((_, ms))) => {
            if family(&from) && family(&to) {
                Some(Morph::Superellipse)
            } else {
                diags.push(message::shape::superellipse_ends(ms));
                None
            }
        }
        (Some(from), Some(to), None) if !f.has(&loft::MORPH) => {
            Some(if family(&from) && family(&to) {
                Morph::Superellipse
            } else {
                Morph::Radial
            })
        }
        _ => None,
    }
}

/// The sections as the wall's centre line: `size = outer` sections shrunk
/// by half the bead's width (each declared at `spans`).
fn measured_sections(
    from: Section,
    to: Section,
    measure: Measure,
    b: &Bead,
    spans: [Span; 2],
    diags: &mut Diagnostics,
) -> Option<(Section, Section)> {
    match measure {
        Measure::Centre => Some((from, to)),
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
            ok.then_some(r)
        }
    }
}

pub(in crate::sema) fn section_value(
    v: &Spanned,
    scope: &Scope<'_>,
    diags: &mut Diagnostics,
) -> Option<Section> {
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
                other.got(),
                v.span,
                section::SHAPES,
            ));
            None
        }
    }
}

pub(in crate::sema) fn spine_value(v: &Spanned, diags: &mut Diagnostics) -> Option<(Spine, Span)> {
    let spine = match &v.value {
        Value::Call(c) if c.func == "line" => {
            let f = Fields::call(c, &LINE, diags);
            Spine::Line {
                length: Length(f.quantity(&spine::LENGTH, diags)?.0),
            }
        }
        Value::Call(c) if c.func == "arc" => {
            let f = Fields::call(c, &ARC, diags);
            let r = f.quantity(&spine::RADIUS, diags);
            let (a, _) = f.bounded(
                &spine::ANGLE,
                |a, at| message::shape::bend_too_far(Angle(a), at),
                diags,
            )?;
            Spine::Arc {
                radius: Length(r?.0),
                angle: Angle(a),
            }
        }
        other => {
            diags.push(message::shape::not_a_spine(other.got(), v.span));

            return None;
        }
    };
    Some((spine, v.span))
}
