//! `top = …` in an extrusion: the height of the finished part above
//! the substrate at every point of the footprint. Two forms of sugar say what
//! labs build — `edges(along, from, to)` (heights on the footprint's two
//! extreme edges, linear between) and `plane(at, height, slope_x, slope_y)` —
//! a mesh of the part as designed (`mesh(…)`, its highest face over each
//! point), and any other expression is a function of the position builtins `x` and
//! `y`, checked here at one point of the footprint and evaluated by the
//! slicer at every point it samples ([`TopHeights`]).

use crate::diag::{message, Diagnostics};
use crate::sema::eval::Env;
use crate::sema::fields::{self, Fields};
use crate::sema::model::{Axis, Shape, Top, TopExpr};
use crate::sema::schema::solid::{top, EDGES, MAX_SLOPE_DEG, MESH, PLANE};
use crate::sema::schema::Field;
use crate::sema::value::Value;
use crate::span::Span;
use crate::syntax::ast::{Expr, ExprKind};
use crate::units::{Dim, Length};

/// The sugar forms a top may be written in.
pub const SUGAR: [&str; 2] = ["edges", "plane"];

/// Reads a `top` expression; `at` is a point of the footprint (mm) where an
/// expression of `x` and `y` is tried, so that its unit and arithmetic are
/// checked before slicing; `constants` are the file's, kept with it.
pub fn read(
    env: &mut Env<'_>,
    expr: &Expr,
    at: [f64; 2],
    constants: &[(String, Span, Expr)],
    diags: &mut Diagnostics,
) -> Option<Top> {
    if let ExprKind::Call { func, .. } = &expr.kind {
        if func.node == MESH.name {
            let v = env.eval(expr, diags)?;
            let Value::Call(c) = &v.value else {
                return None;
            };
            return target(c, v.span, env.data.clone().as_ref(), diags);
        }
        if SUGAR.contains(&func.node.as_str()) {
            // Evaluated as any call: `along = x` stays the word `x`.
            let before = env.layer_reads();
            let v = env.eval(expr, diags)?;
            if env.layer_reads() > before {
                diags.push(message::solid::top_follows_layer(expr.span));
                return None;
            }
            let Value::Call(c) = &v.value else {
                return None;
            };
            return if c.func == "edges" {
                edges(c, diags)
            } else {
                plane(c, diags)
            };
        }
    }
    let before = (env.layer_reads(), env.position_reads());
    let mut inner = Diagnostics::new();
    let v = env.at_position(at[0], at[1], |env| env.eval(expr, &mut inner));
    // Arithmetic that fails at this point of the footprint: say where.
    let at_point =
        env.position_reads() > before.1 && inner.iter().any(message::value::is_arithmetic_failure);
    if at_point {
        diags.push(message::solid::top_fails_at_point(at, expr.span));
    }
    diags.extend(inner);
    let v = v?;
    if env.layer_reads() > before.0 {
        diags.push(message::solid::top_follows_layer(expr.span));
        return None;
    }
    fields::quantity(&v, Dim::LENGTH, "top", diags)?;
    Some(Top::Expr(TopExpr {
        expr: expr.clone(),
        constants: constants.to_vec(),
    }))
}

/// `edges(along = x, from = 20 mm, to = 36 mm)`.
fn edges(c: &crate::sema::value::Call, diags: &mut Diagnostics) -> Option<Top> {
    let a = Fields::call(c, &EDGES, diags);
    let along = a.word(&top::ALONG, diags);
    let from = a.quantity(&top::FROM, diags);
    let to = a.quantity(&top::TO, diags);
    let (along, from, to) = (along?, from?, to?);
    Some(Top::Edges {
        along: if along.0 == "x" { Axis::X } else { Axis::Y },
        from: Length(from.0),
        to: Length(to.0),
    })
}

/// `plane(at = [0 mm, 0 mm], height = 14 mm, slope_x = 8 mm / 60 mm, slope_y = 20 %)`.
fn plane(c: &crate::sema::value::Call, diags: &mut Diagnostics) -> Option<Top> {
    let a = Fields::call(c, &PLANE, diags);
    let at = match a.value(&top::AT, diags) {
        None if a.has(&top::AT) => None,
        None => Some([Length(0.0); 2]),
        Some(v) => point(v, diags),
    };
    let height = a.quantity(&top::HEIGHT, diags);
    let slope_x = slope(&a, &top::SLOPE_X, diags);
    let slope_y = slope(&a, &top::SLOPE_Y, diags);
    Some(Top::Plane {
        at: at?,
        height: Length(height?.0),
        slope: [slope_x?, slope_y?],
    })
}

/// A point `[x, y]` of two lengths.
fn point(v: &crate::sema::value::Spanned, diags: &mut Diagnostics) -> Option<[Length; 2]> {
    match &v.value {
        Value::List(items) if items.len() == 2 => {
            let x = fields::quantity(&items[0], Dim::LENGTH, "x", diags);
            let y = fields::quantity(&items[1], Dim::LENGTH, "y", diags);
            Some([Length(x?), Length(y?)])
        }
        other => {
            diags.push(message::solid::top_at_not_point(other.got(), v.span));
            None
        }
    }
}

/// A slope: a plain number (`8 mm / 60 mm`, `16 %`) or an angle from the
/// horizontal below 90° (its tangent); 0 when not written.
fn slope(a: &Fields<'_>, field: &Field, diags: &mut Diagnostics) -> Option<f64> {
    let key = field.key;
    let Some(v) = a.value(field, diags) else {
        return (!a.has(field)).then_some(0.0);
    };
    if let Value::Quantity(q) = &v.value {
        if q.dim == Dim::ANGLE {
            if q.value.abs() < MAX_SLOPE_DEG.to_radians() {
                return Some(q.value.tan());
            }
            diags.push(message::solid::slope_too_steep(
                key,
                crate::units::Angle(q.value),
                v.span,
            ));

            return None;
        }
    }
    fields::quantity(v, Dim::NONE, key, diags)
}

/// A [`TopExpr`] evaluated point after point: the constants are declared
/// once, and the position builtins read the point asked for.
pub struct TopHeights<'m> {
    env: Env<'m>,
    expr: &'m Expr,
}

impl TopExpr {
    /// An evaluator of the top at any point.
    pub fn evaluator(&self) -> TopHeights<'_> {
        TopHeights {
            env: Env::with_constants(&self.constants),
            expr: &self.expr,
        }
    }
}

impl TopHeights<'_> {
    /// The top at `(x, y)` mm, or `None` after reporting why it has none
    /// there (a division by zero, a number too large). Not checked for
    /// being positive: the caller says where the point is.
    pub fn at(&mut self, x: f64, y: f64, diags: &mut Diagnostics) -> Option<Length> {
        let expr = self.expr;
        let v = self.env.at_position(x, y, |env| env.eval(expr, diags))?;
        fields::quantity(&v, Dim::LENGTH, "top", diags).map(Length)
    }
}

/// A point of `top` the footprint certainly has, to try an expression of the
/// position at: an outline's first point, a section's centre.
pub fn reference_point(shape: Option<&Shape>) -> [f64; 2] {
    match shape {
        Some(Shape::Outline(o)) => [o.start[0].0, o.start[1].0],
        _ => [0.0, 0.0],
    }
}

/// `top = mesh(…)`: the part as designed, its upper faces the finished
/// surface.
fn target(
    c: &crate::sema::value::Call,
    at: Span,
    data: Option<&crate::sema::DataReader>,
    diags: &mut Diagnostics,
) -> Option<Top> {
    let (faces, path) = crate::sema::solid::mesh::placed(c, data, diags)?;
    let Some(surface) = crate::geometry::mesh::highest::Highest::new(faces) else {
        diags.push(message::mesh::no_upper_face(&path, at));
        return None;
    };
    Some(Top::Mesh(crate::sema::model::TopMesh {
        path,
        surface: std::sync::Arc::new(surface),
    }))
}
