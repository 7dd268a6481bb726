//! The declarations other statements refer to by name: constants (`let`),
//! sections, profiles and bead models. Each is checked on its own; one that
//! fails is left out, but its name is kept so that a use of it is not
//! reported a second time as unknown.

use crate::diag::message::{self, statement::Declaration};
use crate::diag::Diagnostics;
use crate::sema::eval::Env;
use crate::sema::model::{Bead, Section};
use crate::sema::process::bead;
use crate::sema::solid::profile;
use crate::sema::solid::section;
use crate::sema::statement::{shape_error, Statements};
use crate::sema::value::Value;
use crate::span::Span;
use crate::syntax::ast::{Body, Expr};
use std::collections::BTreeMap;

/// What a file declares by name.
pub struct Declared<'a> {
    /// `section NAME = …`, those that are right.
    pub sections: BTreeMap<String, (Section, Span)>,
    /// `profile NAME = …`, kept as expressions: they may depend on `layer`.
    pub profiles: BTreeMap<String, (&'a Expr, Span)>,
    /// `bead NAME { … }`, those that are right.
    pub beads: BTreeMap<String, Bead>,
    /// Every section, profile and bead name, including failed ones.
    pub names: Vec<String>,
    /// Every `let`: name, where it is declared, its expression (a profile
    /// that follows the layer is evaluated with them again, layer by layer).
    pub constants: Vec<(String, Span, Expr)>,
    /// The solids read as the part as designed, once each
    /// ([`crate::sema::solid::extrude::Scope::targets`]).
    pub targets: crate::sema::solid::extrude::Targets,
}

/// Declares and evaluates every constant (so errors in unused ones are
/// reported too), then reads the sections, profiles and bead models.
pub fn read<'a>(env: &mut Env<'a>, st: &Statements<'a>, diags: &mut Diagnostics) -> Declared<'a> {
    let constants = constants(env, st, diags);
    let sections = sections(env, st, diags);
    let profiles = profiles(env, st, diags);
    let beads = beads(env, st, diags);
    let names = ["section", "profile", "bead"]
        .iter()
        .flat_map(|k| st.get(k))
        .filter_map(|s| s.name.as_ref().map(|n| n.node.clone()))
        .collect();
    Declared {
        sections,
        profiles,
        beads,
        names,
        targets: Default::default(),
        constants,
    }
}

/// The `let` statements, declared in `env` (what a calibration file reads
/// of the declarations).
pub(super) fn constants<'a>(
    env: &mut Env<'a>,
    st: &Statements<'a>,
    diags: &mut Diagnostics,
) -> Vec<(String, Span, Expr)> {
    let mut out = Vec::new();
    for s in st.get("let") {
        match (&s.name, &s.body) {
            (Some(n), Body::Assign(e)) => {
                if let Some(prev) = env.declare(&n.node, n.span, e) {
                    diags.push(message::statement::duplicate_name(
                        &n.node,
                        Declaration::Constant,
                        n.span,
                        prev,
                    ));
                } else {
                    out.push((n.node.clone(), n.span, e.clone()));
                }
            }
            _ => diags.push(shape_error(s, "let NAME = value", "let R1 = 250 mm")),
        }
    }
    env.eval_all(diags);
    out
}

fn sections<'a>(
    env: &mut Env<'a>,
    st: &Statements<'a>,
    diags: &mut Diagnostics,
) -> BTreeMap<String, (Section, Span)> {
    let mut sections: BTreeMap<String, (Section, Span)> = BTreeMap::new();
    let mut seen: BTreeMap<&str, Span> = BTreeMap::new();
    for s in st.get("section") {
        let (Some(n), Body::Assign(e)) = (&s.name, &s.body) else {
            diags.push(shape_error(
                s,
                "section NAME = shape(…)",
                "section inlet = circle(diameter = 60 mm)",
            ));
            continue;
        };
        let sec = section_value(env, &n.node, e, diags);
        // A second declaration is a mistake of its own, whatever either value.
        if let Some(&prev) = seen.get(n.node.as_str()) {
            diags.push(message::statement::duplicate_name(
                &n.node,
                Declaration::Section,
                n.span,
                prev,
            ));
            continue;
        }
        seen.insert(&n.node, n.span);
        if let Some(sec) = sec {
            sections.insert(n.node.clone(), (sec, n.span));
        }
    }
    sections
}

/// The value of `section name = e`: a shape that does not follow the layer.
fn section_value(
    env: &mut Env<'_>,
    name: &str,
    e: &Expr,
    diags: &mut Diagnostics,
) -> Option<Section> {
    let before = env.layer_reads();
    let v = env.eval(e, diags)?;
    if env.layer_reads() > before {
        diags.push(message::statement::section_follows_layer(name, e.span));
        return None;
    }
    match &v.value {
        Value::Call(c) if section::SHAPES.contains(&c.func.as_str()) => section::read(c, diags),
        other => {
            diags.push(message::statement::section_not_shape(
                name,
                &other.describe(),
                v.span,
                section::SHAPES,
            ));

            None
        }
    }
}

fn profiles<'a>(
    env: &mut Env<'a>,
    st: &Statements<'a>,
    diags: &mut Diagnostics,
) -> BTreeMap<String, (&'a Expr, Span)> {
    let mut profiles: BTreeMap<String, (&Expr, Span)> = BTreeMap::new();
    // Profiles and sections share names: `profile = NAME` takes either.
    let mut seen: BTreeMap<&str, Span> = BTreeMap::new();
    for s in st.get("section") {
        if let Some(n) = &s.name {
            seen.entry(&n.node).or_insert(n.span);
        }
    }
    for s in st.get("profile") {
        let (Some(n), Body::Assign(e)) = (&s.name, &s.body) else {
            diags.push(shape_error(
                s,
                "profile NAME = outline(…)",
                "profile tooth = outline([0 mm, 0 mm], [40 mm, 0 mm], [40 mm, 20 mm])",
            ));
            continue;
        };
        // Checked once here (at layer 0); the slicer evaluates it per layer.
        let ok = env
            .eval(e, diags)
            .and_then(|v| profile::shape(&v, &format!("profile `{}`", n.node), diags))
            .is_some();
        if let Some(&prev) = seen.get(n.node.as_str()) {
            diags.push(message::statement::duplicate_name(
                &n.node,
                Declaration::Profile,
                n.span,
                prev,
            ));
            continue;
        }
        seen.insert(&n.node, n.span);
        if ok {
            profiles.insert(n.node.clone(), (e, n.span));
        }
    }
    profiles
}

fn beads<'a>(
    env: &mut Env<'a>,
    st: &Statements<'a>,
    diags: &mut Diagnostics,
) -> BTreeMap<String, Bead> {
    let mut beads = BTreeMap::new();
    let mut seen: BTreeMap<&str, Span> = BTreeMap::new();
    for s in st.get("bead") {
        let (Some(n), Body::Block(stmts, _)) = (&s.name, &s.body) else {
            diags.push(shape_error(
                s,
                "bead NAME { … }",
                "bead wall { width = 6 mm … }",
            ));
            continue;
        };
        let b = bead::read(env, &n.node, stmts, s.span, diags);
        if let Some(&prev) = seen.get(n.node.as_str()) {
            diags.push(message::statement::duplicate_name(
                &n.node,
                Declaration::Bead,
                n.span,
                prev,
            ));
            continue;
        }
        seen.insert(&n.node, n.span);
        if let Some(b) = b {
            beads.insert(n.node.clone(), b);
        }
    }
    beads
}
