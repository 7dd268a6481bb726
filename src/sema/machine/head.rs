//! A machine's `head { … }`: the solids it carries along the beam, for the
//! collision checks (docs/collision.md). A machine without one is checked
//! with a typical coaxial nozzle, and `lmd::head-unchecked` says so.

use super::Written;
use crate::diag::{message, Diagnostic, Diagnostics};
use crate::ir::{Head, HeadBody};
use crate::sema::eval::Env;
use crate::sema::fields::Fields;
use crate::sema::schema::collision::{self as c, CYLINDER, FRUSTUM, HEAD, HEAD_BLOCK, MAX_SIZE_MM};
use crate::sema::schema::machine::KIND;
use crate::sema::schema::Field;
use crate::sema::value::Value;
use crate::span::Span;

/// The head of the machine block `f` (named `machine`), its fields' spans
/// added to `at`; `None` when it is written wrong (reported).
pub(super) fn read<'a>(
    env: &mut Env<'a>,
    f: &Fields<'a>,
    machine: &str,
    at: &mut Written,
    diags: &mut Diagnostics,
) -> Option<Head> {
    let Some((stmts, span)) = f.nested(&HEAD_BLOCK) else {
        let at = f.span(&KIND).unwrap_or(f.block_span());
        diags.push(message::collision::head_unchecked(machine, at));
        return Some(Head::typical());
    };
    let b = Fields::block(env, stmts, &HEAD, "`head`".into(), span, diags);
    at.extend(b.written());
    let standoff = b.bounded(&c::STANDOFF, too_large(&c::STANDOFF), diags);
    let nozzle = solid(&b, &c::NOZZLE, diags);
    let body = solid(&b, &c::BODY, diags);
    let housing = solid(&b, &c::HOUSING, diags);
    let gap = b.bounded_or_default(&c::GAP, too_large(&c::GAP), diags);
    let bodies: Vec<HeadBody> = [nozzle?, body?, housing?].into_iter().flatten().collect();
    Some(Head {
        standoff: standoff?.0,
        bodies,
        gap: gap?,
        declared: true,
    })
}

/// The report of a length beyond what lmdc takes.
fn too_large(field: &'static Field) -> impl FnOnce(f64, Span) -> Diagnostic {
    move |q, at| {
        let bound = format!("up to {} m", MAX_SIZE_MM / 1000.0);
        message::field::too_large(
            field.key,
            &bound,
            &format!("{} mm", crate::units::short(q)),
            at,
        )
    }
}

/// The solid `field` names, `frustum(…)` or `cylinder(…)`: `Some(None)`
/// when it is not written, `None` when written wrong (reported).
fn solid(b: &Fields<'_>, field: &Field, diags: &mut Diagnostics) -> Option<Option<HeadBody>> {
    let v = match b.value(field, diags) {
        None if b.has(field) => return None,
        None => return Some(None),
        Some(v) => v,
    };
    let Value::Call(call) = &v.value else {
        diags.push(message::collision::not_a_solid(
            field.key,
            v.span,
            &v.value.describe(),
        ));
        return None;
    };
    let (length, diameters) = if call.func == FRUSTUM.name {
        let a = Fields::call(call, &FRUSTUM, diags);
        let length = a.bounded(&c::LENGTH, too_large(&c::LENGTH), diags);
        let tip = a.bounded(&c::TIP, too_large(&c::TIP), diags);
        let top = a.bounded(&c::TOP, too_large(&c::TOP), diags);
        (length?.0, [tip?.0, top?.0])
    } else if call.func == CYLINDER.name {
        let a = Fields::call(call, &CYLINDER, diags);
        let length = a.bounded(&c::LENGTH, too_large(&c::LENGTH), diags);
        let d = a.bounded(&c::DIAMETER, too_large(&c::DIAMETER), diags);
        (length?.0, [d?.0; 2])
    } else {
        diags.push(message::collision::not_a_solid(
            field.key,
            v.span,
            &v.value.describe(),
        ));
        return None;
    };
    Some(Some(HeadBody {
        name: field.key.to_string(),
        length,
        diameters,
    }))
}
