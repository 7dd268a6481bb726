//! Section shapes: `circle(diameter = 60 mm)`, `square(side = 60 mm)`, …

use crate::diag::{message, Diagnostics};
use crate::sema::fields::Fields;
use crate::sema::model::Section;
use crate::sema::schema::shape::{
    section, CIRCLE, ELLIPSE, POLYGON, RECTANGLE, ROUNDED_RECTANGLE, SQUARE,
};
use crate::sema::schema::Field;
use crate::sema::value::Call;
use crate::span::Span;
use crate::units::Length;

/// The section constructors the language knows.
pub const SHAPES: &[&str] = &[
    "circle",
    "ellipse",
    "square",
    "rectangle",
    "rounded_rectangle",
    "polygon",
];

/// Reads a section constructor call.
pub fn read(call: &Call, diags: &mut Diagnostics) -> Option<Section> {
    match call.func.as_str() {
        "circle" => {
            let f = Fields::call(call, &CIRCLE, diags);
            if !one_of(&f, &section::DIAMETER, &section::RADIUS, diags) {
                return None;
            }
            let r = if f.has(&section::RADIUS) {
                f.quantity(&section::RADIUS, diags)?.0
            } else {
                required(&f, &section::DIAMETER, diags)?.0 / 2.0
            };
            Some(Section::Circle { r: Length(r) })
        }
        "ellipse" => {
            let f = Fields::call(call, &ELLIPSE, diags);
            let (a, b) = sides(&f, diags);
            Some(Section::Ellipse { a: a?, b: b? })
        }
        "square" => {
            let f = Fields::call(call, &SQUARE, diags);
            let s = f.quantity(&section::SIDE, diags)?.0 / 2.0;
            Some(Section::Rectangle {
                a: Length(s),
                b: Length(s),
            })
        }
        "rectangle" => {
            let f = Fields::call(call, &RECTANGLE, diags);
            let (a, b) = sides(&f, diags);
            Some(Section::Rectangle { a: a?, b: b? })
        }
        "rounded_rectangle" => rounded_rectangle(call, diags),
        "polygon" => polygon(call, diags),
        _ => None,
    }
}

/// Half the `width` and `height` of an ellipse or a rectangle.
fn sides(f: &Fields<'_>, diags: &mut Diagnostics) -> (Option<Length>, Option<Length>) {
    let a = f.quantity(&section::WIDTH, diags);
    let b = f.quantity(&section::HEIGHT, diags);
    (a.map(|a| Length(a.0 / 2.0)), b.map(|b| Length(b.0 / 2.0)))
}

/// A field required when the other way of giving the size is not written.
fn required(f: &Fields<'_>, field: &Field, diags: &mut Diagnostics) -> Option<(f64, Span)> {
    let q = f.quantity(field, diags);
    f.require(field, diags);
    q
}

fn rounded_rectangle(call: &Call, diags: &mut Diagnostics) -> Option<Section> {
    let f = Fields::call(call, &ROUNDED_RECTANGLE, diags);
    let (a, b) = sides(&f, diags);
    // A negative radius is wrong whatever the sides.
    let r = f.bounded(
        &section::CORNER_RADIUS,
        |r, rs| message::shape::corner_radius(Length(r), None, rs),
        diags,
    );
    let (a, b, (r, rs)) = (a?.0, b?.0, r?);
    if r > a.min(b) {
        diags.push(message::shape::corner_radius(
            Length(r),
            Some(Length(a.min(b))),
            rs,
        ));
        return None;
    }
    Some(Section::RoundedRectangle {
        a: Length(a),
        b: Length(b),
        r: Length(r),
    })
}

fn polygon(call: &Call, diags: &mut Diagnostics) -> Option<Section> {
    let f = Fields::call(call, &POLYGON, diags);
    let n = f.count(&section::SIDES, diags);
    if !one_of(&f, &section::CIRCUMRADIUS, &section::POLYGON_SIDE, diags) {
        return None;
    }
    let r = if f.has(&section::POLYGON_SIDE) {
        let s = f.quantity(&section::POLYGON_SIDE, diags);
        let n = n?.0;
        Some(s?.0 / (2.0 * (std::f64::consts::PI / n as f64).sin()))
    } else {
        required(&f, &section::CIRCUMRADIUS, diags).map(|x| x.0)
    };
    Some(Section::Polygon {
        n: n?.0 as u32,
        r: Length(r?),
    })
}

/// Whether at most one of two arguments that give the same size is written;
/// reports both when both are.
fn one_of(f: &Fields<'_>, a: &Field, b: &Field, diags: &mut Diagnostics) -> bool {
    if !(f.has(a) && f.has(b)) {
        return true;
    }
    diags.push(message::shape::either_not_both(
        a.key,
        f.span(a),
        b.key,
        f.span(b),
    ));

    false
}
