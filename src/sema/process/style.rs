//! `style NAME { … when { … } }` and `inheritance { band, hit }`: the
//! style table, the rules that pick a style's tracks, and checks of every
//! style's values against the bead model and the laser.

use crate::diag::message::style::{StyleBead, Unstyled};
use crate::diag::message::{self, statement::Declaration};
use crate::diag::Diagnostics;
use crate::sema::eval::Env;
use crate::sema::fields::Fields;
use crate::sema::model::{Bead, Inheritance, PathSelect, Style, StyleCondition, Styles};
use crate::sema::process::Laser;
use crate::sema::schema::style::{self as schema, values, when, INHERITANCE, STYLE, WHEN};
use crate::sema::schema::{DefaultValue, Need};
use crate::sema::slicing::planar::PlanarSpec;
use crate::sema::statement::{single_optional, Statements};
use crate::sema::value::Value;
use crate::span::{Span, Spanned};
use crate::syntax::ast::{Body, Stmt};
use crate::units::{Angle, Dim, Length, MassFlow, Power, Speed};
use std::collections::BTreeMap;

/// Colours of styles that do not give one (the "tab10" palette).
const PALETTE: [&str; 10] = [
    "#d62728", "#1f77b4", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
    "#bcbd22", "#17becf",
];

/// Most styles a table holds: ids are 1 ..= 65535.
const MAX_STYLES: usize = u16::MAX as usize;

/// A style as read, before the checks that need the bead and the process.
pub struct Written {
    style: Style,
    power_span: Option<Span>,
    speed_span: Option<Span>,
    /// Whether every field read without error; incomplete styles are still
    /// checked against the bead and the laser, so all errors show at once.
    complete: bool,
}

/// Reads every `style` statement, giving ids in declaration order to those
/// without one.
pub fn read<'a>(env: &mut Env<'a>, stmts: &[&'a Stmt], diags: &mut Diagnostics) -> Vec<Written> {
    let mut out: Vec<Written> = Vec::new();
    let mut names: BTreeMap<String, Span> = BTreeMap::new();
    let mut ids: BTreeMap<u16, Span> = BTreeMap::new();
    let mut auto: Vec<usize> = Vec::new();
    if stmts.len() > MAX_STYLES {
        diags.push(message::style::too_many_styles(
            stmts.len(),
            MAX_STYLES,
            stmts[MAX_STYLES].span,
        ));
        return Vec::new();
    }
    for (i, s) in stmts.iter().enumerate() {
        let (Some(n), Body::Block(body, _)) = (&s.name, &s.body) else {
            diags.push(message::statement::statement_shape(
                "style",
                s.span,
                "style NAME { … }",
                "style edge { power = 1300 W  when { paths = outer_contour } }",
            ));
            continue;
        };
        // The name goes into comments of every program: a word, nothing a
        // control could read as code.
        let word = n
            .node
            .starts_with(|c: char| c.is_ascii_alphabetic() || c == '_')
            && n.node
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_');
        if !word {
            diags.push(message::style::bad_style_name(&n.node, n.span));
        }
        if let Some(prev) = names.insert(n.node.clone(), n.span) {
            diags.push(message::statement::duplicate_name(
                &n.node,
                Declaration::Style,
                n.span,
                prev,
            ));
        }
        let (mut w, id_written) = style(env, s, n, body, i, &mut ids, diags);
        w.complete &= word;
        if !id_written {
            auto.push(out.len());
        }
        out.push(w);
    }
    // The lowest ids no style claims, in declaration order (at most
    // MAX_STYLES styles, so there are enough).
    let mut free = (1..=u16::MAX).filter(|k| !ids.contains_key(k));
    for i in auto {
        out[i].style.id = free.next().unwrap_or(0);
    }
    out
}

/// Reads the fields of style `name` (the `i`th), its id recorded in `ids`;
/// and whether an id is written (or wrong: then none is given).
fn style<'a>(
    env: &mut Env<'a>,
    s: &Stmt,
    name: &Spanned<String>,
    body: &'a [Stmt],
    i: usize,
    ids: &mut BTreeMap<u16, Span>,
    diags: &mut Diagnostics,
) -> (Written, bool) {
    let what = format!("style `{}`", name.node);
    let f = Fields::block(env, body, &STYLE, what.clone(), s.span, diags);
    // `Some(None)`: no id written; one is given once every explicit id
    // is known, so it never takes an id a later style asks for.
    let id = f.optional(
        &values::ID,
        f.count(&values::ID, diags).map(|(id, sp)| {
            let id = id as u16;
            if let Some(prev) = ids.get(&id) {
                diags.push(message::style::duplicate_id(id, sp, *prev));
            }
            ids.insert(id, sp);
            id
        }),
    );
    let power = f.optional(&values::POWER, f.quantity(&values::POWER, diags));
    let speed = f.optional(&values::SPEED, f.quantity(&values::SPEED, diags));
    let powder = f.optional(&values::POWDER, f.quantity(&values::POWDER, diags));
    if [&values::POWER, &values::SPEED, &values::POWDER]
        .iter()
        .all(|v| !f.has(v))
    {
        diags.push(message::style::no_process_value(&what, name.span));
    }
    let colour = colour(&f, i, diags);
    let blocks = f.nested_all(&values::WHEN);
    if blocks.is_empty() {
        diags.push(message::style::picks_no_tracks(&what, s.span));
    }
    let rules: Vec<Option<Vec<StyleCondition>>> = blocks
        .iter()
        .map(|(stmts, sp)| rule(env, stmts, *sp, &what, diags))
        .collect();
    let complete = id.is_some()
        && power.is_some()
        && speed.is_some()
        && powder.is_some()
        && colour.is_some()
        && !blocks.is_empty()
        && rules.iter().all(Option::is_some);
    let (power, speed, powder) = (power.flatten(), speed.flatten(), powder.flatten());
    let written = Written {
        style: Style {
            id: id.flatten().unwrap_or(0),
            name: name.node.clone(),
            power: power.map(|(p, _)| Power(p)),
            speed: speed.map(|(v, _)| Speed(v)),
            powder: powder.map(|(m, _)| MassFlow(m)),
            colour: colour.unwrap_or_default(),
            rules: rules.into_iter().flatten().collect(),
            span: s.span,
        },
        power_span: power.map(|p| p.1),
        speed_span: speed.map(|v| v.1),
        complete,
    };
    (written, id != Some(None))
}

/// `colour = "#rrggbb"`, else the palette's `i`th; `None` when wrong.
fn colour(f: &Fields<'_>, i: usize, diags: &mut Diagnostics) -> Option<String> {
    match f.text(&values::COLOUR, diags) {
        Some((c, sp)) => {
            if is_colour(&c) {
                Some(c.to_ascii_lowercase())
            } else {
                diags.push(message::style::bad_colour(&c, sp));
                None
            }
        }
        None if f.has(&values::COLOUR) => None,
        None => Some(PALETTE[i % PALETTE.len()].to_string()),
    }
}

fn is_colour(c: &str) -> bool {
    c.len() == 7 && c.starts_with('#') && c[1..].chars().all(|h| h.is_ascii_hexdigit())
}

/// A `when { … }` block of `what`: its conditions, `None` when one is
/// wrong or the block picks nothing.
fn rule<'a>(
    env: &mut Env<'a>,
    stmts: &'a [Stmt],
    span: Span,
    what: &str,
    diags: &mut Diagnostics,
) -> Option<Vec<StyleCondition>> {
    let f = Fields::block(
        env,
        stmts,
        &WHEN,
        format!("a `when` block of {what}"),
        span,
        diags,
    );
    let mut out = Vec::new();
    let mut ok = paths(&f, &mut out, diags);
    for (field, make) in [
        (
            &when::SHORTER_THAN,
            StyleCondition::ShorterThan as fn(Length) -> _,
        ),
        (&when::LONGER_THAN, StyleCondition::LongerThan),
        (&when::NEAR_BOUNDARY, StyleCondition::NearBoundary),
    ] {
        match f.quantity(field, diags) {
            Some((l, _)) => out.push(make(Length(l))),
            None => ok &= !f.has(field),
        }
    }
    ok &= corner(&f, &mut out, diags);
    ok &= layers(&f, &mut out, diags);
    // Only a block written empty picks every track; one whose conditions
    // all failed has said why already.
    if ok && out.is_empty() && stmts.is_empty() {
        diags.push(message::style::empty_rule(span));
        return None;
    }
    if out.is_empty() {
        return None;
    }
    let length = |pick: fn(&StyleCondition) -> Option<f64>| out.iter().find_map(pick);
    if let (Some(below), Some(above)) = (
        length(|c| match c {
            StyleCondition::ShorterThan(l) => Some(l.0),
            _ => None,
        }),
        length(|c| match c {
            StyleCondition::LongerThan(l) => Some(l.0),
            _ => None,
        }),
    ) {
        if below <= above {
            diags.push(message::style::lengths_exclude(
                Length(below),
                Length(above),
                span,
            ));
        }
    }
    ok.then_some(out)
}

/// `paths = …`: whether it is right or not written.
fn paths(f: &Fields<'_>, out: &mut Vec<StyleCondition>, diags: &mut Diagnostics) -> bool {
    match f.word(&when::PATHS, diags) {
        Some((p, _)) => {
            out.push(StyleCondition::Paths(match p {
                "outer_contour" => PathSelect::OuterContour,
                "inner_contour" => PathSelect::InnerContour,
                "contour" => PathSelect::Contour,
                _ => PathSelect::Infill,
            }));
            true
        }
        None => !f.has(&when::PATHS),
    }
}

/// `near_corner = …` and `corner_angle = …`: whether both are right or not
/// written.
fn corner(f: &Fields<'_>, out: &mut Vec<StyleCondition>, diags: &mut Diagnostics) -> bool {
    let corner = f.quantity(&when::NEAR_CORNER, diags);
    let mut ok = corner.is_some() || !f.has(&when::NEAR_CORNER);
    let angle = match f.bounded(
        &when::CORNER_ANGLE,
        |a, at| message::style::corner_angle_range(a.to_degrees(), at),
        diags,
    ) {
        Some((a, sp)) => {
            if corner.is_none() && !f.has(&when::NEAR_CORNER) {
                diags.push(message::style::corner_angle_unused(sp));
            }
            Some(Angle(a))
        }
        None => {
            ok &= !f.has(&when::CORNER_ANGLE);
            None
        }
    };
    if let Some((d, _)) = corner {
        out.push(StyleCondition::NearCorner(
            Length(d),
            angle.unwrap_or(Angle(default_corner())),
        ));
    }
    ok
}

/// The sharp corner's angle when `corner_angle` is not written.
fn default_corner() -> f64 {
    match when::CORNER_ANGLE.need {
        Need::Default(DefaultValue::Quantity(a)) => a,
        _ => unreachable!("`corner_angle` has a default"),
    }
}

/// `layers = a .. b`: whether it is right or not written.
fn layers(f: &Fields<'_>, out: &mut Vec<StyleCondition>, diags: &mut Diagnostics) -> bool {
    let Some(v) = f.value(&when::LAYERS, diags) else {
        return !f.has(&when::LAYERS);
    };
    match &v.value {
        Value::Range(a, b) if a.dim == Dim::NONE && b.dim == Dim::NONE => {
            let whole = |x: f64| x.fract() == 0.0 && (1.0..=1e6).contains(&x);
            if whole(a.value) && whole(b.value) && a.value <= b.value {
                out.push(StyleCondition::Layers(a.value as usize, b.value as usize));
                true
            } else {
                diags.push(message::style::bad_layers_range(a.value, b.value, v.span));
                false
            }
        }
        other => {
            diags.push(message::style::layers_not_range(other.got(), v.span));
            false
        }
    }
}

/// The `inheritance` statement as read.
pub struct InheritanceRead {
    /// Band and hit, when the statement is right.
    pub value: Option<Inheritance>,
    /// The statement, if the file has one.
    pub span: Option<Span>,
}

/// The file's `inheritance { band, hit }` statement, if any (at most one).
pub fn inheritance_statement<'a>(
    env: &mut Env<'a>,
    st: &Statements<'a>,
    diags: &mut Diagnostics,
) -> InheritanceRead {
    let stmt = single_optional(st.get("inheritance"), "inheritance", diags);
    InheritanceRead {
        value: stmt.and_then(|s| inheritance(env, s, diags)),
        span: stmt.map(|s| s.span),
    }
}

/// Reads `inheritance { band, hit }`.
fn inheritance<'a>(
    env: &mut Env<'a>,
    stmt: &'a Stmt,
    diags: &mut Diagnostics,
) -> Option<Inheritance> {
    let (None, Body::Block(stmts, _)) = (&stmt.name, &stmt.body) else {
        diags.push(message::style::inheritance_shape(stmt.span));
        return None;
    };
    let f = Fields::block(
        env,
        stmts,
        &INHERITANCE,
        "inheritance".into(),
        stmt.span,
        diags,
    );
    let band = f.quantity(&schema::BAND, diags);
    let hit = f.bounded(&schema::HIT, message::style::hit_range, diags);
    Some(Inheritance {
        band: Length(band?.0),
        hit: hit?.0,
    })
}

/// What the style checks need from the rest of the file, each part when it
/// is known: a style is checked against what is there, so a mistake
/// elsewhere does not hide one in the style table.
pub struct Context<'c> {
    /// Whether the solid is a loft, whose wall is one track a layer.
    pub loft: bool,
    /// Whether the solid is a wall along an open path.
    pub wall: bool,
    /// Whether the layers are variable, whose speeds come from
    /// the bead model.
    pub variable: bool,
    /// Whether the solid is a segmented ring, whose table sets each
    /// segment's process.
    pub ring: bool,
    /// `slicing planar { … }`, if read.
    pub planar: Option<&'c PlanarSpec>,
    /// The bead model the part is built with.
    pub bead: Option<&'c Bead>,
    /// The laser's power range.
    pub laser: Option<&'c Laser>,
}

/// Checks each style's values against the bead model (speed range, and the
/// bead height that speed gives) and the laser's power range, and what the
/// plan makes of the table (a loft has no tracks to style; a raster that
/// turns away from the tracks it would inherit from), and makes the table.
pub fn assemble(
    written: Vec<Written>,
    inheritance: &InheritanceRead,
    cx: &Context<'_>,
    diags: &mut Diagnostics,
) -> Option<Styles> {
    for (unstyled, kind) in [
        (cx.loft, Unstyled::Loft),
        (cx.ring, Unstyled::Ring),
        (cx.wall, Unstyled::Wall),
        (cx.variable, Unstyled::Variable),
    ] {
        if let (true, Some(first)) = (unstyled, written.first()) {
            diags.push(message::style::styles_unsupported(kind, first.style.span));
            return None;
        }
    }
    let mut ok = written.iter().all(|w| w.complete);
    for w in &written {
        ok &= values_fit(w, cx.bead, cx.laser, diags);
    }
    match inheritance.span {
        Some(sp) if written.is_empty() => {
            diags.push(message::style::inheritance_without_styles(sp))
        }
        Some(sp) => {
            // The band runs along a styled track; a track turned across it
            // covers at most a band's width of its length.
            let turn = cx
                .planar
                .and_then(|s| s.infill)
                .map_or(0.0, |(r, _)| r.rotate.deg().rem_euclid(180.0));
            if turn > 1e-9 && 180.0 - turn > 1e-9 {
                diags.push(message::style::raster_turns_away(turn, sp));
            }
        }
        None => {}
    }
    // A failed `inheritance` statement was reported where it was read.
    ok &= inheritance.span.is_none() || inheritance.value.is_some();
    ok.then(|| Styles {
        table: written.into_iter().map(|w| w.style).collect(),
        inheritance: inheritance.value,
    })
}

/// Whether a style's speed (and the bead height it gives) and power are ones
/// the bead model and the laser allow; reports those that are not.
fn values_fit(
    w: &Written,
    bead: Option<&Bead>,
    laser: Option<&Laser>,
    diags: &mut Diagnostics,
) -> bool {
    let s = &w.style;
    let mut ok = true;
    if let (Some(v), Some(sp), Some(bead)) = (s.speed, w.speed_span, bead) {
        let h = bead.model.height_at(v, bead.width);
        let b = StyleBead {
            name: &bead.name,
            speed: (bead.speed, bead.speed_span),
            height: (bead.height, bead.height_span),
        };
        if !bead.covers_speed(v) {
            diags.push(message::style::style_speed_outside_bead(&s.name, v, sp, &b));
            ok = false;
        } else if !bead.covers_height(h) {
            diags.push(message::style::style_height_outside_bead(
                &s.name, v, h, sp, &b,
            ));
            ok = false;
        }
    }
    if let (Some(p), Some(sp), Some(laser)) = (s.power, w.power_span, laser) {
        if !laser.covers(p) {
            diags.push(message::style::style_power_outside_laser(
                &s.name,
                p,
                sp,
                laser.range,
                laser.range_span,
                laser.power_span,
            ));

            ok = false;
        }
    }
    ok
}
