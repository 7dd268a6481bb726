//! `style NAME { … when { … } }` and `inheritance { band, hit }` (seed 002): the
//! style table, the rules that pick a style's tracks, and checks of every
//! style's values against the bead model and the laser.

use super::eval::Env;
use super::fields::{self, Fields};
use super::model::{Bead, Inheritance, PathSelect, Style, StyleCondition, Styles};
use super::planar::PlanarSpec;
use super::process::Laser;
use super::statement::{single_optional, Statements};
use super::value::Value;
use crate::diag::message::style::{StyleBead, Unstyled};
use crate::diag::message::{self, statement::Declaration};
use crate::diag::Diagnostics;
use crate::span::Span;
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

/// Corners that turn by at least this much are sharp unless `corner_angle` says.
const DEFAULT_CORNER: f64 = 45.0;

const PATHS: &[&str] = &["outer_contour", "inner_contour", "contour", "infill"];

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
        let what = format!("style `{}`", n.node);
        let f = Fields::block_with_repeats(
            env,
            body,
            &["id", "power", "speed", "powder", "colour"],
            &[],
            &["when"],
            what.clone(),
            s.span,
            diags,
        );
        // `Some(None)`: no id written; one is given once every explicit id
        // is known, so it never takes an id a later style asks for.
        let id = match f.count("id", 1, u16::MAX as usize, None, diags) {
            Some((id, sp)) => {
                let id = id as u16;
                if let Some(prev) = ids.get(&id) {
                    diags.push(message::style::duplicate_id(id, sp, *prev));
                }
                ids.insert(id, sp);
                Some(Some(id))
            }
            None if f.has("id") => None,
            None => Some(None),
        };
        let power = f.optional("power", f.positive("power", Dim::POWER, None, diags));
        let speed = f.optional("speed", f.positive("speed", Dim::SPEED, None, diags));
        let powder = f.optional("powder", f.positive("powder", Dim::MASS_FLOW, None, diags));
        if let Some(Some((_, sp))) = powder {
            // Seed 002's table reserves the field too: feeders are not switched
            // track by track.
            diags.push(message::style::powder_not_programmed(&what, sp));
        }
        if !f.has("power") && !f.has("speed") && !f.has("powder") {
            diags.push(message::style::no_process_value(&what, n.span));
        }
        let colour = match f.text("colour", None, diags) {
            Some((c, sp)) => {
                if is_colour(&c) {
                    Some(c.to_ascii_lowercase())
                } else {
                    diags.push(message::style::bad_colour(&c, sp));
                    None
                }
            }
            None if f.has("colour") => None,
            None => Some(PALETTE[i % PALETTE.len()].to_string()),
        };
        let blocks = f.nested_all("when");
        if blocks.is_empty() {
            diags.push(message::style::picks_no_tracks(&what, s.span));
        }
        let rules: Vec<Option<Vec<StyleCondition>>> = blocks
            .iter()
            .map(|(stmts, sp)| rule(env, stmts, *sp, &what, diags))
            .collect();
        let complete = word
            && id.is_some()
            && power.is_some()
            && speed.is_some()
            && powder.is_some()
            && colour.is_some()
            && !blocks.is_empty()
            && rules.iter().all(Option::is_some);
        let (power, speed, powder) = (power.flatten(), speed.flatten(), powder.flatten());
        if id == Some(None) {
            auto.push(out.len());
        }
        out.push(Written {
            style: Style {
                id: id.flatten().unwrap_or(0),
                name: n.node.clone(),
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
        });
    }
    // The lowest ids no style claims, in declaration order (at most
    // MAX_STYLES styles, so there are enough).
    let mut free = (1..=u16::MAX).filter(|k| !ids.contains_key(k));
    for i in auto {
        out[i].style.id = free.next().unwrap_or(0);
    }
    out
}

fn is_colour(c: &str) -> bool {
    c.len() == 7 && c.starts_with('#') && c[1..].chars().all(|h| h.is_ascii_hexdigit())
}

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
        &[
            "paths",
            "shorter_than",
            "longer_than",
            "near_boundary",
            "near_corner",
            "corner_angle",
            "layers",
        ],
        &[],
        format!("a `when` block of {what}"),
        span,
        diags,
    );
    let mut ok = true;
    let mut out = Vec::new();
    match f.symbol("paths", PATHS, None, diags) {
        Some((p, _)) => out.push(StyleCondition::Paths(match p.as_str() {
            "outer_contour" => PathSelect::OuterContour,
            "inner_contour" => PathSelect::InnerContour,
            "contour" => PathSelect::Contour,
            _ => PathSelect::Infill,
        })),
        None => ok &= !f.has("paths"),
    }
    let mut length = |key: &str, make: fn(Length) -> StyleCondition, out: &mut Vec<_>| match f
        .positive(key, Dim::LENGTH, None, diags)
    {
        Some((l, _)) => out.push(make(Length(l))),
        None => ok &= !f.has(key),
    };
    length("shorter_than", StyleCondition::ShorterThan, &mut out);
    length("longer_than", StyleCondition::LongerThan, &mut out);
    length("near_boundary", StyleCondition::NearBoundary, &mut out);
    let corner = f.positive("near_corner", Dim::LENGTH, None, diags);
    ok &= corner.is_some() || !f.has("near_corner");
    let angle = match f.quantity("corner_angle", Dim::ANGLE, None, diags) {
        Some((a, sp)) if !(a > 0.0 && a <= std::f64::consts::PI) => {
            diags.push(message::style::corner_angle_range(a.to_degrees(), sp));
            ok = false;
            None
        }
        Some((a, sp)) => {
            if corner.is_none() && !f.has("near_corner") {
                diags.push(message::style::corner_angle_unused(sp));
            }
            Some(Angle(a))
        }
        None => {
            ok &= !f.has("corner_angle");
            None
        }
    };
    if let Some((d, _)) = corner {
        out.push(StyleCondition::NearCorner(
            Length(d),
            angle.unwrap_or(Angle::from_deg(DEFAULT_CORNER)),
        ));
    }
    if let Some(v) = f.value("layers", None, diags) {
        match &v.value {
            Value::Range(a, b) if a.dim == Dim::NONE && b.dim == Dim::NONE => {
                let whole = |x: f64| x.fract() == 0.0 && (1.0..=1e6).contains(&x);
                if whole(a.value) && whole(b.value) && a.value <= b.value {
                    out.push(StyleCondition::Layers(a.value as usize, b.value as usize));
                } else {
                    diags.push(message::style::bad_layers_range(a.value, b.value, v.span));
                    ok = false;
                }
            }
            other => {
                diags.push(message::style::layers_not_range(other, v.span));
                ok = false;
            }
        }
    } else {
        ok &= !f.has("layers");
    }
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
        &["band", "hit"],
        &[],
        "inheritance".into(),
        stmt.span,
        diags,
    );
    let band = f.positive("band", Dim::LENGTH, Some("0.8 mm"), diags);
    let hit = match f.value("hit", Some("99 %"), diags) {
        Some(v) => match fields::quantity(v, Dim::NONE, "hit", diags) {
            Some(h) if h > 0.0 && h <= 1.0 => Some(h),
            Some(h) => {
                diags.push(message::style::hit_range(h, v.span));
                None
            }
            None => None,
        },
        None => None,
    };
    Some(Inheritance {
        band: Length(band?.0),
        hit: hit?,
    })
}

/// What the style checks need from the rest of the file, each part when it
/// is known: a style is checked against what is there, so a mistake
/// elsewhere does not hide one in the style table.
pub struct Context<'c> {
    /// Whether the solid is a loft, whose wall is one track a layer.
    pub loft: bool,
    /// Whether the layers are variable (seed 003), whose speeds come from
    /// the bead model.
    pub variable: bool,
    /// Whether the solid is a ring (seed 004), whose table sets each
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
