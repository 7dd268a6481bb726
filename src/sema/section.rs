//! Section shapes: `circle(diameter = 60 mm)`, `square(side = 60 mm)`, …

use super::fields::Fields;
use super::model::Section;
use super::value::Call;
use crate::diag::{message, Diagnostics};
use crate::units::{Dim, Length};

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
    let l = Dim::LENGTH;
    match call.func.as_str() {
        "circle" => {
            let f = Fields::call(call, &["diameter"], &["diameter", "radius"], diags);
            if !one_of(&f, "diameter", "radius", diags) {
                return None;
            }
            let r = if f.has("radius") {
                f.positive("radius", l, None, diags)?.0
            } else {
                f.positive("diameter", l, Some("60 mm"), diags)?.0 / 2.0
            };
            Some(Section::Circle { r: Length(r) })
        }
        "ellipse" => {
            let f = Fields::call(call, &["width", "height"], &["width", "height"], diags);
            let a = f.positive("width", l, Some("60 mm"), diags);
            let b = f.positive("height", l, Some("40 mm"), diags);
            Some(Section::Ellipse {
                a: Length(a?.0 / 2.0),
                b: Length(b?.0 / 2.0),
            })
        }
        "square" => {
            let f = Fields::call(call, &["side"], &["side"], diags);
            let s = f.positive("side", l, Some("60 mm"), diags)?.0 / 2.0;
            Some(Section::Rectangle {
                a: Length(s),
                b: Length(s),
            })
        }
        "rectangle" => {
            let f = Fields::call(call, &["width", "height"], &["width", "height"], diags);
            let a = f.positive("width", l, Some("60 mm"), diags);
            let b = f.positive("height", l, Some("40 mm"), diags);
            Some(Section::Rectangle {
                a: Length(a?.0 / 2.0),
                b: Length(b?.0 / 2.0),
            })
        }
        "rounded_rectangle" => {
            let f = Fields::call(
                call,
                &["width", "height", "radius"],
                &["width", "height", "radius"],
                diags,
            );
            let a = f.positive("width", l, Some("60 mm"), diags);
            let b = f.positive("height", l, Some("40 mm"), diags);
            let r = f.quantity("radius", l, Some("5 mm"), diags);
            // A negative radius is wrong whatever the sides.
            let r = r.filter(|&(r, rs)| {
                if r >= 0.0 {
                    return true;
                }
                diags.push(message::shape::corner_radius(Length(r), None, rs));
                false
            });
            let (a, b, (r, rs)) = (a?.0 / 2.0, b?.0 / 2.0, r?);
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
        "polygon" => {
            let f = Fields::call(
                call,
                &["sides", "circumradius"],
                &["sides", "circumradius", "side"],
                diags,
            );
            let n = f.count("sides", 3, 1000, Some("6"), diags);
            if !one_of(&f, "circumradius", "side", diags) {
                return None;
            }
            let r = if f.has("side") {
                let s = f.positive("side", l, None, diags);
                let n = n?.0;
                Some(s?.0 / (2.0 * (std::f64::consts::PI / n as f64).sin()))
            } else {
                f.positive("circumradius", l, Some("30 mm"), diags)
                    .map(|x| x.0)
            };
            Some(Section::Polygon {
                n: n?.0 as u32,
                r: Length(r?),
            })
        }
        _ => None,
    }
}

/// Whether at most one of two arguments that give the same size is written;
/// reports both when both are.
fn one_of(f: &Fields<'_>, a: &str, b: &str, diags: &mut Diagnostics) -> bool {
    if !(f.has(a) && f.has(b)) {
        return true;
    }
    diags.push(message::shape::either_not_both(a, f.span(a), b, f.span(b)));

    false
}
