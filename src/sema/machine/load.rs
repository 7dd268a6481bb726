//! A robot's `load = load(…)`: the tool's mass, centre of gravity and
//! inertia, which the program sets as KUKA's `$LOAD` (docs/robots.md).

use crate::diag::{message, Diagnostics};
use crate::ir::Load;
use crate::sema::fields::{self, Fields};
use crate::sema::schema::machine::{load as l, LOAD, LOAD_DATA, MAX_LOAD_KG};
use crate::sema::schema::{Bound, Field, Kind};
use crate::sema::value::Value;
use crate::span::Span;
use crate::units::{Dim, Inertia, Mass};

/// The lightest load lmdc writes, kg: a gram, the last of `$LOAD.M`'s
/// three decimals.
pub const MIN_LOAD_KG: f64 = 0.001;

/// The load of the robot block `f`: `Some(None)` when it declares none,
/// `None` when it is written wrong (reported).
pub(super) fn read(f: &Fields<'_>, diags: &mut Diagnostics) -> Option<Option<Load>> {
    let v = match f.value(&LOAD, diags) {
        None if f.has(&LOAD) => return None,
        None => return Some(None),
        Some(v) => v,
    };
    let Value::Call(c) = &v.value else {
        diags.push(message::load::not_a_load(v.span, &v.value.describe()));
        return None;
    };
    if c.func != LOAD_DATA.name {
        diags.push(message::load::not_a_load(v.span, &v.value.describe()));
        return None;
    }
    let a = Fields::call(c, &LOAD_DATA, diags);
    let mass = a
        .bounded(&l::MASS, |q, at| out_of_range(&l::MASS, q, at), diags)
        .and_then(|(m, at)| {
            // A load the program's three decimals of a kilogram would write
            // as 0 is no tool's.
            if Mass(m).kg() >= MIN_LOAD_KG {
                return Some(m);
            }
            diags.push(out_of_range(&l::MASS, m, at));
            None
        });
    let cog = three(&a, &l::COG, diags);
    let inertia = match a.has(&l::INERTIA) {
        true => three(&a, &l::INERTIA, diags),
        false => Some([0.0; 3]),
    };
    let axes = match a.has(&l::INERTIA_AXES) {
        true => three(&a, &l::INERTIA_AXES, diags),
        false => Some([0.0; 3]),
    };
    Some(Some(Load {
        mass: Mass(mass?).kg(),
        cog: cog?,
        inertia_axes: axes?.map(f64::to_degrees),
        inertia: inertia?.map(|j| Inertia(j).kg_m2()),
    }))
}

/// Three quantities of `field`'s dimension within its bound (canonical
/// units); every item out of range is reported.
fn three(a: &Fields<'_>, field: &Field, diags: &mut Diagnostics) -> Option<[f64; 3]> {
    let v = a.value(field, diags)?;
    let (Some((dim, bound)), Value::List(items)) = (item_kind(field), &v.value) else {
        return not_three(field, v.span, &v.value.describe(), diags);
    };
    if items.len() != 3 {
        return not_three(field, v.span, &v.value.describe(), diags);
    }
    let mut out = [0.0; 3];
    let mut ok = true;
    for (o, it) in out.iter_mut().zip(items) {
        match fields::quantity(it, dim, field.key, diags) {
            Some(q) if inside(q, bound) => *o = q,
            Some(q) => {
                diags.push(out_of_range(field, q, it.span));
                ok = false;
            }
            None => ok = false,
        }
    }
    ok.then_some(out)
}

/// The dimension and bound of each item of a list field.
fn item_kind(field: &Field) -> Option<(Dim, Bound)> {
    match &field.kind {
        Kind::List(k, _) => k.quantity(),
        _ => None,
    }
}

/// Whether `q` keeps `bound` (the bounds the load's lists have).
fn inside(q: f64, bound: Bound) -> bool {
    match bound {
        Bound::Magnitude(max) => q.abs() <= max,
        Bound::ZeroUpTo(max) => (0.0..=max).contains(&q),
        _ => true,
    }
}

fn not_three(field: &Field, at: Span, got: &str, diags: &mut Diagnostics) -> Option<[f64; 3]> {
    let what = match field.kind.dim() {
        Some(Dim::LENGTH) => "lengths",
        Some(Dim::ANGLE) => "angles",
        _ => "moments of inertia",
    };
    diags.push(message::load::not_three(field.key, what, at, got));
    None
}

/// `q` (canonical units) of `field` outside its bound.
fn out_of_range(field: &Field, q: f64, at: Span) -> crate::diag::Diagnostic {
    let (dim, bound) = item_kind(field)
        .or(field.kind.quantity())
        .unwrap_or((Dim::NONE, Bound::Any));
    let range = match field == &l::MASS {
        true => format!(
            "from {} to {}",
            Mass(MIN_LOAD_KG * 1000.0),
            Mass(MAX_LOAD_KG * 1000.0)
        ),
        false => bound.describe(dim),
    };
    message::load::out_of_range(field.key, &fields::shown(q, dim), &range, at)
}
