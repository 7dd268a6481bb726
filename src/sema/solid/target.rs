//! `top = NAME`: a repair's target given as a solid of the file, the part
//! as designed (docs/repair.md, *A target solid*), and `scan(register =
//! NAME)`: a scan's nominal given so (*Registration*). A solid either
//! names is taken out of the build ([`named`]) and read here: an
//! `extrude` of a shape up to its `height`, an `extrude` of a `mesh(…)`,
//! or a `loft`, its shapes its faces. What builds a solid — its bead, its
//! tracks' `size` — is not needed; what would make it anything but a part
//! standing on the plate (a `top` or `on` of its own, a profile that
//! follows `layer`) is refused, as is a name that is no such solid.

use crate::diag::message::target::{self, Fault, Role};
use crate::diag::Diagnostics;
use crate::geometry::mesh::highest::Highest;
use crate::geometry::region::Region;
use crate::geometry::target::{LoftFault, LoftTarget, Target};
use crate::sema::eval::{unknown_name, Env, LAYER, POSITION, Z};
use crate::sema::fields::Fields;
use crate::sema::model::Shape;
use crate::sema::model::{Top, TopSolid};
use crate::sema::schema::solid::{extrude, loft, scan, EXTRUDE, LOFT, SCAN, SCAN_SECTION};
use crate::sema::solid::extrude::{Scope, Source};
use crate::sema::solid::profile;
use crate::sema::suggest::did_you_mean;
use crate::sema::value::Value;
use crate::span::Span;
use crate::syntax::ast::{Body, ExprKind, Stmt};
use crate::units::Angle;
use std::collections::BTreeSet;
use std::sync::Arc;

/// How finely a target's ellipses are flattened, mm: the programs'
/// resolution.
const CHORD: f64 = 0.001;

/// The statement kinds that are solids.
pub const SOLIDS: [&str; 4] = ["loft", "extrude", "ring", "wall"];

/// The solids some extrusion's `top` or its scan's `register` names (not
/// itself, not a constant): they are the part as designed, not built. A
/// name no solid has, which is no constant or position either, is taken
/// for the solid its "did you mean" offers: the typo is reported where
/// the name is read, and that solid stays out of the build rather than
/// being read as a second part to build.
pub fn named<'a>(
    solids: &[&'a Stmt],
    constants: &[(String, Span, crate::syntax::ast::Expr)],
) -> BTreeSet<&'a str> {
    let name_of = |s: &'a Stmt| s.name.as_ref().map(|n| n.node.as_str());
    let names: BTreeSet<&str> = solids.iter().filter_map(|s| name_of(s)).collect();
    let mut out = BTreeSet::new();
    for s in solids
        .iter()
        .filter(|s| matches!(s.kind.node.as_str(), "extrude" | "wall"))
    {
        let Body::Block(stmts, _) = &s.body else {
            continue;
        };
        for n in stmts.iter().filter_map(part_named) {
            let constant = constants.iter().any(|(c, _, _)| c == n);
            let builtin = POSITION.contains(&n) || n == LAYER || n == Z;
            if constant || builtin || name_of(s) == Some(n) {
                continue;
            }
            let others = names.iter().copied().filter(|m| Some(*m) != name_of(s));
            match names.get(n) {
                Some(m) => {
                    out.insert(*m);
                }
                None => out.extend(did_you_mean(n, others)),
            }
        }
    }
    out
}

/// The name a field of an extrude block gives the part as designed:
/// `top = NAME`, or `on = scan(…, register = NAME)`.
fn part_named(f: &Stmt) -> Option<&str> {
    let Body::Assign(e) = &f.body else {
        return None;
    };
    fn ident(e: &crate::syntax::ast::Expr) -> Option<&str> {
        match &e.kind {
            ExprKind::Ident(n) => Some(n.as_str()),
            _ => None,
        }
    }
    match (f.kind.node.as_str(), &e.kind) {
        (k, _) if k == extrude::TOP.key => ident(e),
        (k, ExprKind::Call { func, args }) if k == extrude::ON.key && func.node == SCAN.name => {
            args.iter()
                .find(|a| {
                    a.name
                        .as_ref()
                        .is_some_and(|n| n.node == scan::REGISTER.key)
                })
                .and_then(|a| ident(&a.value))
        }
        _ => None,
    }
}

/// `top = NAME` in the extrusion `own`, written at `at`: the target when
/// `name` is a solid of the file, `Some(None)` after reporting why it
/// cannot be one (or is no solid); `None` when `name` is a constant or a
/// position, for the expression reader.
pub fn read<'a>(
    env: &mut Env<'a>,
    name: &str,
    at: Span,
    own: &str,
    scope: &Scope<'_, 'a>,
    diags: &mut Diagnostics,
) -> Option<Option<Top>> {
    let builtin = POSITION.contains(&name) || name == LAYER || name == Z;
    if builtin || scope.constants.iter().any(|(c, _, _)| c == name) {
        return None;
    }
    let surface = solid(env, (name, Role::Top), at, own, scope, diags);
    Some(surface.map(|surface| {
        Top::Solid(TopSolid {
            name: name.to_string(),
            surface,
        })
    }))
}

/// `top = e` when `e` names a solid of the file (`top = NAME`): the
/// target, or `None` inside after reporting why it cannot be one; `None`
/// when `e` is no name of a solid (an expression to read as one).
pub fn named_top<'a>(
    env: &mut Env<'a>,
    e: &crate::syntax::ast::Expr,
    own: &str,
    scope: &Scope<'_, 'a>,
    diags: &mut Diagnostics,
) -> Option<Option<Top>> {
    match &e.kind {
        ExprKind::Ident(n) => read(env, n, e.span, own, scope, diags),
        _ => None,
    }
}

/// `scan(register = NAME)` in the extrusion `own`, written at `at`: the
/// solid `name` of the file as the scan's nominal, `None` after reporting
/// why it cannot be one (a constant is no solid either).
pub fn nominal<'a>(
    env: &mut Env<'a>,
    name: &str,
    at: Span,
    own: &str,
    scope: &Scope<'_, 'a>,
    diags: &mut Diagnostics,
) -> Option<Arc<Target>> {
    solid(env, (name, Role::Nominal), at, own, scope, diags)
}

/// The solid `name` of the file as the part as designed, named for
/// `role` at `at` from the extrusion `own`; `None` after reporting why it
/// cannot be (or is no solid).
fn solid<'a>(
    env: &mut Env<'a>,
    (name, role): (&str, Role),
    at: Span,
    own: &str,
    scope: &Scope<'_, 'a>,
    diags: &mut Diagnostics,
) -> Option<Arc<Target>> {
    let decl = scope
        .statements
        .iter()
        .find(|s| s.name.as_ref().is_some_and(|n| n.node == name));
    let Some(s) = decl else {
        let known: Vec<&str> = solid_names(scope, own);
        diags.push(unknown_name(name, at, "solid", &known));
        return None;
    };
    let kind = s.kind.node.as_str();
    let decl_span = s.name.as_ref().map_or(s.span, |n| n.span);
    if !SOLIDS.contains(&kind) {
        let known = solid_names(scope, own);
        diags.push(target::not_a_solid(name, kind, role, at, decl_span, &known));
        return None;
    }
    if name == own {
        diags.push(target::cannot(name, Fault::Itself, role, at, decl_span));
        return None;
    }
    let Body::Block(stmts, _) = &s.body else {
        // Its shape is reported where the file's solids are read.
        return None;
    };
    if let Some(read) = scope.targets.borrow().get(name) {
        return read.clone();
    }
    let cx = Cx {
        name,
        role,
        at,
        decl: decl_span,
        span: s.span,
    };
    let surface = match kind {
        "extrude" => extrusion(env, stmts, &cx, scope, diags),
        "loft" => lofted(env, stmts, &cx, scope, diags),
        _ => cx.refuse(Fault::Kind(kind), diags),
    };
    let surface = surface.map(Arc::new);
    scope
        .targets
        .borrow_mut()
        .insert(name.to_string(), surface.clone());
    surface
}

/// The solids a top may name: every one but `own`.
fn solid_names<'s>(scope: &'s Scope<'_, '_>, own: &str) -> Vec<&'s str> {
    scope
        .statements
        .iter()
        .filter(|s| SOLIDS.contains(&s.kind.node.as_str()))
        .filter_map(|s| s.name.as_ref().map(|n| n.node.as_str()))
        .filter(|n| *n != own)
        .collect()
}

/// Where a target is named and declared.
struct Cx<'n> {
    name: &'n str,
    /// What names it.
    role: Role,
    /// The `top = NAME` or `register = NAME`.
    at: Span,
    /// The target's name in its declaration.
    decl: Span,
    /// Its block.
    span: Span,
}

impl Cx<'_> {
    fn refuse<T>(&self, fault: Fault<'_>, diags: &mut Diagnostics) -> Option<T> {
        diags.push(target::cannot(
            self.name, fault, self.role, self.at, self.decl,
        ));
        None
    }
}

/// The fields of a block a target refuses, and `size = centre`.
fn refused(
    f: &Fields<'_>,
    keys: &[&'static crate::sema::schema::Field],
    size: &crate::sema::schema::Field,
    cx: &Cx<'_>,
    diags: &mut Diagnostics,
) -> bool {
    let mut ok = true;
    for key in keys {
        if let Some(at) = f.span(key) {
            diags.push(target::cannot(
                cx.name,
                Fault::Field(key.key),
                cx.role,
                cx.at,
                at,
            ));
            ok = false;
        }
    }
    if let Some((w, at)) = f.word(size, diags) {
        if w != "outer" {
            diags.push(target::cannot(cx.name, Fault::Centre, cx.role, cx.at, at));
            ok = false;
        }
    }
    ok
}

/// An extrude block as a target: a prism of its shape up to its height,
/// or its mesh.
fn extrusion<'a>(
    env: &mut Env<'a>,
    stmts: &'a [Stmt],
    cx: &Cx<'_>,
    scope: &Scope<'_, 'a>,
    diags: &mut Diagnostics,
) -> Option<Target> {
    let what = format!("extrude `{}`", cx.name);
    let f = Fields::block(env, stmts, &EXTRUDE, what, cx.span, diags);
    let ok = refused(
        &f,
        &[&extrude::TOP, &extrude::ON],
        &extrude::SIZE,
        cx,
        diags,
    );
    // A bead, if written, must still be one (a typo is a typo).
    if f.has(&extrude::BEAD) {
        crate::sema::process::bead::named(
            f.value(&extrude::BEAD, diags),
            extrude::BEAD.key,
            "the layers",
            scope.beads,
            scope.declared,
            diags,
        );
    }
    let v = f.value(&extrude::PROFILE, diags)?;
    let height = f.quantity(&extrude::HEIGHT, diags).map(|h| h.0);
    match &v.value {
        Value::Call(c) if c.func == "mesh" => {
            let (faces, path) =
                crate::sema::solid::mesh::placed(c, env.data.clone().as_ref(), diags)?;
            if f.has(&extrude::HEIGHT) {
                return cx.refuse(Fault::MeshHeight, diags);
            }
            let Some(h) = Highest::new(faces) else {
                diags.push(crate::diag::message::mesh::no_upper_face(&path, v.span));
                return None;
            };
            return ok.then_some(Target::Mesh(h));
        }
        Value::Call(c) if c.func == SCAN_SECTION.name => {
            return cx.refuse(Fault::ScanSection, diags)
        }
        _ => {}
    }
    let inline = stmts.iter().find_map(|s| match &s.body {
        Body::Assign(e) if s.kind.node == extrude::PROFILE.key => Some(e),
        _ => None,
    });
    if inline.is_some_and(|e| env.depends_on_layer(e)) {
        return cx.refuse(Fault::FollowsLayer, diags);
    }
    let shape =
        match crate::sema::solid::extrude::source(v, scope, env.data.clone().as_ref(), diags)? {
            Source::Fixed(s) => s,
            Source::Expr(e) if env.depends_on_layer(e) => {
                return cx.refuse(Fault::FollowsLayer, diags)
            }
            Source::Expr(e) => {
                let v = env.eval(e, diags)?;
                profile::shape(&v, "a profile", diags)?
            }
            Source::Mesh(_) => return None,
        };
    let Some(height) = height else {
        // A target with a top of its own is refused for that alone.
        if !f.has(&extrude::HEIGHT) && !f.has(&extrude::TOP) {
            return cx.refuse(Fault::NoHeight, diags);
        }
        return None;
    };
    let region = crate::geometry::outline::region(&shape, CHORD);
    let holes_ok = holes_checked(&region, &shape, diags);
    (ok && holes_ok).then_some(Target::Prism { region, height })
}

/// Reports the faults of `region`'s holes (made from `shape`) as a built
/// extrusion's are reported (`lmd::hole`): a hole outside the outline or
/// inside another would add faces that are not the part. Whether there
/// are none.
fn holes_checked(region: &Region, shape: &Shape, diags: &mut Diagnostics) -> bool {
    let found = crate::diag::message::hole::region_faults(region, shape, 0, false);
    let ok = found.is_empty();
    for d in found {
        diags.push(d);
    }
    ok
}

/// A loft block as a target: its sections as written are its faces.
fn lofted<'a>(
    env: &mut Env<'a>,
    stmts: &'a [Stmt],
    cx: &Cx<'_>,
    scope: &Scope<'_, 'a>,
    diags: &mut Diagnostics,
) -> Option<Target> {
    use crate::sema::solid::loft as read;
    let what = format!("loft `{}`", cx.name);
    let f = Fields::block(env, stmts, &LOFT, what, cx.span, diags);
    let ok = refused(&f, &[], &loft::SIZE, cx, diags);
    let sc = read::Scope {
        sections: scope.sections,
        beads: scope.beads,
        declared: scope.declared,
    };
    if f.has(&loft::WALL) {
        crate::sema::process::bead::named(
            f.value(&loft::WALL, diags),
            loft::WALL.key,
            "the wall",
            scope.beads,
            scope.declared,
            diags,
        );
    }
    let from = f
        .value(&loft::FROM, diags)
        .and_then(|v| read::section_value(v, &sc, diags));
    let to = f
        .value(&loft::TO, diags)
        .and_then(|v| read::section_value(v, &sc, diags));
    let spine = f
        .value(&loft::SPINE, diags)
        .and_then(|v| read::spine_value(v, diags));
    let twist = f.quantity_or_default(&loft::TWIST, diags).map(Angle);
    let morph = f.word(&loft::MORPH, diags);
    let morph = read::morph_between(&f, from, to, morph, diags);
    let (from, to, (spine, _), twist, morph) = (from?, to?, spine?, twist?, morph?);
    match LoftTarget::new(from, to, morph, spine, twist.0) {
        Ok(l) => ok.then_some(Target::Loft(l)),
        Err(LoftFault::Tight { radius, reach }) => cx.refuse(Fault::Tight(radius, reach), diags),
    }
}
