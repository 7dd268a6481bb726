//! The solid a file builds (`loft`, `extrude` or `ring`), and its pairing
//! with the slicing strategy into a [`Plan`].

pub mod extrude;
pub mod loft;
pub mod mesh;
pub mod profile;
pub mod scan;
pub mod section;
pub mod segmented_ring;
pub mod target;
pub mod top;
pub mod wall;

use crate::diag::message::{self, solid::SlicingMismatch};
use crate::diag::Diagnostics;
use crate::sema::declare::Declared;
use crate::sema::eval::Env;
use crate::sema::model::{Bead, Build, Loft};
use crate::sema::process::control::ControlSpec;
use crate::sema::slicing::variable;
use crate::sema::slicing::{self, Spec};
use crate::sema::statement::{shape_error, Statements};
use crate::span::Span;
use crate::syntax::ast::{Body, Stmt};
use crate::units::{MassFlow, Speed};

/// What kind of solid the file builds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// `loft NAME { … }`, sliced normal to its spine.
    Loft,
    /// `extrude NAME { … }`, sliced in flat layers.
    Extrude,
    /// `extrude NAME { … top = … }`, sliced in variable layers.
    TopExtrude,
    /// `ring NAME { … }`, sliced in one continuous run.
    Ring,
    /// `wall NAME { … }`, a wall along an open path in flat layers.
    Wall,
    /// `wall` with `on = scan(…)`.
    ScanWall,
}

/// The solid as read: its kind when the file has one, the solid when its
/// block is right, and its bead model when that is right (checks that need
/// only the bead go on without the rest).
pub struct Read<'a> {
    /// The first solid statement's kind.
    pub kind: Option<Kind>,
    solid: Option<Solid<'a>>,
    /// The bead model the solid is built with.
    pub bead: Option<Bead>,
}

/// A solid block as read.
enum Solid<'a> {
    Loft(Loft),
    Extrude(extrude::Written<'a>),
    Ring(segmented_ring::Written),
    Wall(wall::Written),
}

impl Read<'_> {
    /// The scanned part an extrusion is built on, when it is read.
    pub fn scan(&self) -> Option<&crate::sema::model::ScanBase> {
        match &self.solid {
            Some(Solid::Extrude(w)) => w.base.as_ref(),
            Some(Solid::Wall(w)) => w.scan(),
            _ => None,
        }
    }

    /// The table's powers and where they are written, when the solid is a
    /// ring whose powers are right.
    pub fn ring_powers(&self) -> Option<([crate::units::Power; 2], Span)> {
        match &self.solid {
            Some(Solid::Ring(w)) => w.powers,
            _ => None,
        }
    }
}

/// What a ring needs besides its solid and slicing: its loop (`Some(None)`
/// when none is declared, `None` when the block is wrong) and the process
/// block's powder feed.
pub struct RingContext {
    /// The `control` block.
    pub control: Option<Option<ControlSpec>>,
    /// The powder feed, if right.
    pub powder: Option<MassFlow>,
}

/// Reads the file's one solid; a missing one and each one after the first
/// are reported.
pub fn read<'a>(
    env: &mut Env<'a>,
    st: &Statements<'a>,
    decl: &Declared<'a>,
    diags: &mut Diagnostics,
) -> Read<'a> {
    let (solids, statements) = to_build(st, decl);
    let Some((s, rest)) = solids.split_first() else {
        diags.push(none_to_build(&statements));
        return Read {
            kind: None,
            solid: None,
            bead: None,
        };
    };
    for extra in rest {
        diags.push(message::solid::second_solid(extra.kind.span, s.kind.span));
    }
    let (kind, solid, bead) = match (s.kind.node.as_str(), &s.name, &s.body) {
        ("loft", Some(n), Body::Block(stmts, _)) => {
            let scope = loft::Scope {
                sections: &decl.sections,
                beads: &decl.beads,
                declared: &decl.names,
            };
            let (l, b) = loft::read(env, &n.node, stmts, s.span, &scope, diags);
            (Kind::Loft, l.map(Solid::Loft), b)
        }
        ("extrude", Some(n), Body::Block(stmts, _)) => {
            let scope = extrude_scope(decl, &statements);
            let (w, b) = extrude::read(env, &n.node, stmts, s.span, &scope, diags);
            // Whether it has a top decides its slicing, even when the top is wrong.
            let kind = if stmts.iter().any(|s| s.kind.node == "top") {
                Kind::TopExtrude
            } else {
                Kind::Extrude
            };
            (kind, w.map(Solid::Extrude), b)
        }
        ("ring", Some(n), Body::Block(stmts, _)) => {
            let w = segmented_ring::read(env, &n.node, stmts, s.span, diags);
            (Kind::Ring, Some(Solid::Ring(w)), None)
        }
        ("wall", Some(n), Body::Block(stmts, _)) => {
            let scope = extrude_scope(decl, &statements);
            let (w, b) = wall::read(env, &n.node, stmts, s.span, &scope, diags);
            // Whether it is on a scan decides its slicing, even when the scan is wrong.
            let kind = if stmts.iter().any(|s| s.kind.node == "on") {
                Kind::ScanWall
            } else {
                Kind::Wall
            };
            (kind, w.map(Solid::Wall), b)
        }
        ("wall", _, _) => {
            diags.push(shape_error(
                s,
                "wall NAME { … }",
                "wall rib { along = polyline(points = [[0 mm, 0 mm], [40 mm, 0 mm]])  bead = my_bead  height = 12 mm }",
            ));
            (Kind::Wall, None, None)
        }
        ("ring", _, _) => {
            diags.push(shape_error(
                s,
                "ring NAME { … }",
                "ring wall { radius = 40 mm  segments = 10  table { … } }",
            ));
            (Kind::Ring, None, None)
        }
        ("loft", _, _) => {
            diags.push(shape_error(
                s,
                "loft NAME { … }",
                "loft duct { from = inlet … }",
            ));
            (Kind::Loft, None, None)
        }
        _ => {
            diags.push(shape_error(
                s,
                "extrude NAME { … }",
                "extrude tooth { profile = tooth  bead = track }",
            ));
            (Kind::Extrude, None, None)
        }
    };
    Read {
        kind: Some(kind),
        solid,
        bead,
    }
}

/// What an extrusion (or a wall on a scan naming its nominal) may refer to.
fn extrude_scope<'s, 'a>(
    decl: &'s Declared<'a>,
    statements: &'s [&'a Stmt],
) -> extrude::Scope<'s, 'a> {
    extrude::Scope {
        sections: &decl.sections,
        profiles: &decl.profiles,
        beads: &decl.beads,
        declared: &decl.names,
        constants: &decl.constants,
        statements,
        targets: &decl.targets,
    }
}

/// The solid statements to build, in source order, and the named
/// statements a `top = NAME` may name or mistake for a solid. A solid a
/// `top` names is the part as designed, read as the target where it is
/// named: it is not built.
fn to_build<'a>(st: &Statements<'a>, decl: &Declared<'a>) -> (Vec<&'a Stmt>, Vec<&'a Stmt>) {
    let mut solids: Vec<&Stmt> = target::SOLIDS
        .iter()
        .flat_map(|k| st.get(k))
        .copied()
        .collect();
    solids.sort_by_key(|s| s.span.start);
    let targets = target::named(&solids, &decl.constants);
    let statements: Vec<&Stmt> = ["section", "profile", "bead"]
        .iter()
        .flat_map(|k| st.get(k))
        .chain(solids.iter())
        .copied()
        .collect();
    solids.retain(|s| {
        s.name
            .as_ref()
            .is_none_or(|n| !targets.contains(n.node.as_str()))
    });
    (solids, statements)
}

/// Why there is no solid to build: none written, or every one named by
/// another as the part as designed (a cycle of `register`s or `top`s).
fn none_to_build(statements: &[&Stmt]) -> crate::diag::Diagnostic {
    let named: Vec<(&str, Span)> = statements
        .iter()
        .filter(|s| target::SOLIDS.contains(&s.kind.node.as_str()))
        .filter_map(|s| s.name.as_ref().map(|n| (n.node.as_str(), n.span)))
        .collect();
    if named.is_empty() {
        message::solid::missing_solid()
    } else {
        message::target::every_solid_named(&named)
    }
}

/// Pairs the solid with its slicing: a loft is sliced normal to its spine,
/// an extrusion in flat layers (reported whenever both kinds are known, even
/// if a block has other mistakes). `speed` is the process block's scan speed
/// (`Some(None)` when not written, `None` when wrong). Returns the plan, if
/// every part of it is right, and the bead model.
pub fn build(
    env: &mut Env<'_>,
    solid: Read<'_>,
    slicing: slicing::Read<'_>,
    speed: Option<Option<(Speed, Span)>>,
    decl: &Declared<'_>,
    ring_cx: RingContext,
    diags: &mut Diagnostics,
) -> (Option<Build>, Option<Bead>) {
    let bead = solid.bead;
    if mismatch(solid.kind, slicing.strategy, slicing.stmt, diags) {
        return (None, bead);
    }
    let side_ok = match (&slicing.spec, slicing.strategy, slicing.stmt) {
        (spec, Some("variable"), Some(s)) => {
            let offset = match spec {
                Some(Spec::Variable(v)) => v.offset(),
                _ => None,
            };
            variable::side_checks(bead.as_ref(), speed, offset, s.span, diags)
        }
        _ => true,
    };
    let plan = match (solid.solid, slicing.spec, &bead) {
        (Some(Solid::Loft(loft)), Some(Spec::Normal(slicing)), _) => {
            Some(Build::Duct { loft, slicing })
        }
        (Some(Solid::Extrude(w)), Some(Spec::Planar(spec)), Some(b)) if w.top.is_none() => {
            extrude::assemble(env, w, b, spec, speed, &decl.constants, diags)
                .map(|(extrusion, slicing)| Build::Block { extrusion, slicing })
        }
        (Some(Solid::Extrude(w)), Some(Spec::Variable(spec)), Some(_)) if w.top.is_some() => {
            variable::assemble(env, w, spec, diags)
                .filter(|_| side_ok)
                .map(|(extrusion, slicing)| Build::Variable { extrusion, slicing })
        }
        (Some(Solid::Wall(w)), Some(Spec::Planar(spec)), Some(b)) if w.scan().is_none() => {
            wall::assemble(w, b, spec, (slicing.stmt, speed), diags).map(
                |(wall, extent, slicing)| Build::Wall {
                    wall,
                    extent,
                    slicing,
                },
            )
        }
        (Some(Solid::Wall(w)), Some(Spec::Variable(spec)), Some(b)) if w.scan().is_some() => {
            wall::assemble_on_scan(w, b, spec, slicing.stmt, diags)
                .filter(|_| side_ok)
                .map(|(wall, on, slicing, pitch)| Build::ScanWall {
                    wall,
                    on,
                    slicing,
                    pitch,
                })
        }
        (Some(Solid::Ring(w)), Some(Spec::Continuous(spec)), _) => {
            segmented_ring::assemble(w, spec, ring_cx.control, ring_cx.powder, diags)
                .map(Build::Ring)
        }
        // A part that failed, reported where it was read.
        _ => None,
    };
    (plan, bead)
}

/// Reports a solid and a strategy that do not go together, when both are
/// known; whether it did.
fn mismatch(
    kind: Option<Kind>,
    strategy: Option<&str>,
    stmt: Option<&Stmt>,
    diags: &mut Diagnostics,
) -> bool {
    let m = match (kind, strategy) {
        (Some(Kind::Loft), Some(s @ ("planar" | "variable"))) => SlicingMismatch::Loft(s),
        (Some(Kind::Extrude), Some("normal")) => SlicingMismatch::ExtrusionNormal,
        (Some(Kind::Extrude), Some("variable")) => SlicingMismatch::ExtrusionVariable,
        (Some(Kind::TopExtrude), Some("normal")) => SlicingMismatch::TopExtrusionNormal,
        (Some(Kind::Ring), Some(s @ ("normal" | "planar" | "variable"))) => {
            SlicingMismatch::Ring(s)
        }
        (Some(Kind::Loft | Kind::Extrude | Kind::TopExtrude), Some("continuous")) => {
            SlicingMismatch::Continuous
        }
        (Some(Kind::TopExtrude), Some("planar")) => SlicingMismatch::TopExtrusionPlanar,
        (Some(Kind::Wall), Some(s @ ("normal" | "variable" | "continuous"))) => {
            SlicingMismatch::Wall(s)
        }
        (Some(Kind::ScanWall), Some(s @ ("normal" | "planar" | "continuous"))) => {
            SlicingMismatch::ScanWall(s)
        }
        _ => return false,
    };
    let at = stmt.map(|s| s.span).unwrap_or(Span::new(0, 0));
    diags.push(message::solid::slicing_mismatch(m, at));
    true
}
