//! The `fixture NAME { shape = …  at = […] }` statements: the clamps and
//! fixtures on the plate, in the part's coordinates, which every machine's
//! head keeps its gap from (docs/collision.md).

use crate::diag::{message, Diagnostics};
use crate::ir::{Fixture, FixtureShape};
use crate::sema::eval::Env;
use crate::sema::fields::{self, Fields};
use crate::sema::schema::collision::{self as c, BOX, CYLINDER, FIXTURE, MAX_SIZE_MM};
use crate::sema::statement::{shape_error, Statements};
use crate::sema::value::Value;
use crate::span::Span;
use crate::units::Dim;
use std::collections::BTreeMap;

/// Every fixture that is written right, with where it is placed (its
/// `at`, else its name): what a collision with it points at.
pub fn read<'a>(
    env: &mut Env<'a>,
    st: &Statements<'a>,
    diags: &mut Diagnostics,
) -> Vec<(Fixture, Span)> {
    let mut out = Vec::new();
    let mut seen = BTreeMap::new();
    for s in st.get("fixture") {
        let (Some(n), crate::syntax::ast::Body::Block(stmts, _)) = (&s.name, &s.body) else {
            diags.push(shape_error(s, "fixture NAME { … }", FIXTURE.syntax));
            continue;
        };
        if let Some(&prev) = seen.get(n.node.as_str()) {
            diags.push(message::collision::duplicate_fixture(&n.node, n.span, prev));
            continue;
        }
        seen.insert(n.node.as_str(), n.span);
        let f = Fields::block(
            env,
            stmts,
            &FIXTURE,
            format!("fixture `{}`", n.node),
            s.span,
            diags,
        );
        let shape = shape(&f, diags);
        let placed = f.span(&c::AT).unwrap_or(n.span);
        let at = at(&f, diags);
        if let (Some(shape), Some(at)) = (shape, at) {
            let fixture = Fixture {
                name: n.node.clone(),
                shape,
                at,
            };
            out.push((fixture, placed));
        }
    }
    out
}

/// `shape = box(size = […]) | cylinder(length, diameter)`.
fn shape(f: &Fields<'_>, diags: &mut Diagnostics) -> Option<FixtureShape> {
    let v = f.value(&c::SHAPE, diags)?;
    let Value::Call(call) = &v.value else {
        diags.push(message::collision::not_a_shape(v.span, &v.value.describe()));
        return None;
    };
    if call.func == BOX.name {
        let a = Fields::call(call, &BOX, diags);
        let v = a.value(&c::SIZE, diags)?;
        let size = three(v, c::SIZE.key, diags)?;
        if let Some(bad) = size.iter().find(|s| !(*s > &0.0 && **s <= MAX_SIZE_MM)) {
            diags.push(message::collision::bad_size(v.span, *bad, MAX_SIZE_MM));
            return None;
        }
        return Some(FixtureShape::Box { size });
    }
    if call.func == CYLINDER.name {
        let a = Fields::call(call, &CYLINDER, diags);
        let out = |q: f64, at| message::collision::bad_size(at, q, MAX_SIZE_MM);
        let length = a.bounded(&c::LENGTH, out, diags);
        let diameter = a.bounded(&c::DIAMETER, out, diags);
        return Some(FixtureShape::Cylinder {
            diameter: diameter?.0,
            length: length?.0,
        });
    }
    diags.push(message::collision::not_a_shape(v.span, &v.value.describe()));
    None
}

/// `at = [x, y, z]` (default the origin).
fn at(f: &Fields<'_>, diags: &mut Diagnostics) -> Option<[f64; 3]> {
    match f.value(&c::AT, diags) {
        None if f.has(&c::AT) => None,
        None => Some([0.0; 3]),
        Some(v) => three(v, c::AT.key, diags),
    }
}

/// Three lengths `[x, y, z]`.
fn three(v: &crate::sema::value::Spanned, key: &str, diags: &mut Diagnostics) -> Option<[f64; 3]> {
    let items = match &v.value {
        Value::List(items) if items.len() == 3 => items,
        other => {
            diags.push(message::collision::not_three(
                key,
                v.span,
                &other.describe(),
            ));
            return None;
        }
    };
    let mut out = [0.0; 3];
    let mut ok = true;
    for (o, it) in out.iter_mut().zip(items) {
        match fields::quantity(it, Dim::LENGTH, key, diags) {
            Some(q) => *o = q,
            None => ok = false,
        }
    }
    ok.then_some(out)
}
