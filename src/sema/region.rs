//! Planar profiles with holes and placed shapes:
//!
//! - `region(outline = SHAPE, holes = [SHAPE, …])`: a profile with openings;
//! - `place(SHAPE, at = [x, y], turn = a)`: a shape turned about the origin,
//!   then moved (a section is centred on the origin until placed);
//! - `bolt_circle(SHAPE, count = n, diameter = D, from = a, at = [x, y])`,
//!   in a hole list only: `n` copies of the shape on a circle of diameter `D`
//!   about `at` (default the origin), the first at angle `a`, each turned
//!   with the pattern — the way a drawing dimensions bolt holes (pitch circle
//!   diameter).
//!
//! Whether the holes lie inside the outline, apart from each other, is a
//! question of the geometry on each layer: the slicer answers it
//! ([`crate::slice::planar`]).

use super::fields::Fields;
use super::model::{Hole, Placed, RegionShape, Shape};
use super::profile::{point, shape};
use super::schema::shape::{piece, BOLT_CIRCLE, PLACE, REGION};
use super::value::{Call, Spanned, Value};
use crate::diag::{message, Diagnostics};
use crate::span::Span;
use crate::units::{Angle, Length};

pub use super::schema::shape::MAX_HOLES;

/// Reads `region(outline = …, holes = […])`.
pub fn region(c: &Call, diags: &mut Diagnostics) -> Option<Shape> {
    let f = Fields::call(c, &REGION, diags);
    let outline = f
        .value(&piece::OUTLINE, diags)
        .and_then(|v| plain(v, "the outline of a region", diags).map(|s| (s, v.span)));
    let holes = match f.value(&piece::HOLES, diags) {
        None if f.has(&piece::HOLES) => None,
        None => Some(Vec::new()),
        Some(v) => holes(v, diags),
    };
    let (outline, outline_span) = outline?;
    Some(Shape::Region(Box::new(RegionShape {
        outline,
        outline_span,
        holes: holes?,
    })))
}

/// Reads `place(shape, at = [x, y], turn = a)`.
pub fn place(c: &Call, diags: &mut Diagnostics) -> Option<Shape> {
    let f = Fields::call(c, &PLACE, diags);
    let inner = f
        .value(&piece::PLACED, diags)
        .and_then(|v| shape(v, "what `place` places", diags));
    let at = at(&f, diags);
    let turn = f.quantity_or_default(&piece::PLACE_TURN, diags).map(Angle);
    Some(Shape::Placed(Box::new(Placed {
        shape: inner?,
        turn: turn?,
        at: at?,
    })))
}

/// `at = [x, y]`, the origin when not written.
fn at(f: &Fields<'_>, diags: &mut Diagnostics) -> Option<[Length; 2]> {
    match f.value(&piece::AT, diags) {
        Some(v) => point(v, diags),
        None if f.has(&piece::AT) => None,
        None => Some([Length(0.0); 2]),
    }
}

/// A shape that must be one outline: no holes of its own.
fn plain(v: &Spanned, what: &str, diags: &mut Diagnostics) -> Option<Shape> {
    let s = shape(v, what, diags)?;
    if s.has_holes() {
        diags.push(message::shape::holes_in_hole(what, v.span));
        return None;
    }
    Some(s)
}

/// The list of holes, bolt circles expanded.
fn holes(v: &Spanned, diags: &mut Diagnostics) -> Option<Vec<Hole>> {
    let Value::List(items) = &v.value else {
        diags.push(message::shape::holes_not_list(v.value.got(), v.span));
        return None;
    };
    let mut out = Vec::new();
    let mut ok = true;
    for item in items {
        let read = match &item.value {
            Value::Call(c) if c.func == "bolt_circle" => bolt_circle(c, item.span, diags),
            _ => plain(item, "a hole", diags).map(|shape| {
                vec![Hole {
                    shape,
                    span: item.span,
                }]
            }),
        };
        match read {
            Some(h) => out.extend(h),
            None => ok = false,
        }
    }
    if out.len() > MAX_HOLES {
        diags.push(message::shape::too_many_holes(MAX_HOLES, out.len(), v.span));

        return None;
    }
    ok.then_some(out)
}

/// `count` copies of the hole on the pitch circle: copy `k` is the hole
/// moved to `[D/2, 0]`, turned about the origin by `from + k·360°/count` and
/// moved by `at`.
fn bolt_circle(c: &Call, span: Span, diags: &mut Diagnostics) -> Option<Vec<Hole>> {
    let f = Fields::call(c, &BOLT_CIRCLE, diags);
    let at = at(&f, diags);
    let hole = f
        .value(&piece::HOLE, diags)
        .and_then(|v| plain(v, "a bolt circle's hole", diags));
    let count = f.count(&piece::COUNT, diags);
    let diameter = f.quantity(&piece::PITCH, diags);
    let from = f.quantity_or_default(&piece::FROM, diags).map(Angle);
    let (hole, (count, _), (diameter, _), from, at) = (hole?, count?, diameter?, from?, at?);
    let moved = Shape::Placed(Box::new(Placed {
        shape: hole,
        turn: Angle(0.0),
        at: [Length(diameter / 2.0), Length(0.0)],
    }));
    Some(
        (0..count)
            .map(|k| Hole {
                shape: Shape::Placed(Box::new(Placed {
                    shape: moved.clone(),
                    turn: Angle(from.0 + std::f64::consts::TAU * k as f64 / count as f64),
                    at,
                })),
                span,
            })
            .collect(),
    )
}
