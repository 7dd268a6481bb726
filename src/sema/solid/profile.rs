//! `profile NAME = outline(…)` (or any section shape): the 2-D shape an
//! extrusion's layers follow. An outline is a start point, then points (straight
//! lines to them) and `arc(to = …, radius = …, turn = left|right)` pieces; it
//! closes with a line back to the start. Its numbers may use `layer`, so the
//! profile can change from layer to layer (a sprocket tooth's corner arc
//! that grows a track offset a layer).
//!
//! Besides, planar profiles with holes and placed shapes (a region is a
//! shape whose outline and holes are shapes: one reader, recursive):
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
use crate::diag::{message, Diagnostics};
use crate::sema::eval::Env;
use crate::sema::fields::{self, Fields};
use crate::sema::model::{Hole, Outline, Placed, ProfileExpr, RegionShape, Segment, Shape, Turn};
use crate::sema::schema::shape::{piece, ARC, BOLT_CIRCLE, PLACE, REGION};
use crate::sema::solid::section;
use crate::sema::value::{Call, Spanned, Value};
use crate::span::Span;
use crate::syntax::ast::Expr;
use crate::units::{Angle, Dim, Length};

/// The shapes a profile can be, besides the section shapes.
pub const OUTLINE: &str = "outline";

/// Most pieces an outline may have.
pub const MAX_SEGMENTS: usize = 10_000;

/// Reads a profile value: `outline(…)`, a section shape, `place(…)` of
/// one, or `region(…)` (see [`region`]).
pub fn shape(v: &Spanned, what: &str, diags: &mut Diagnostics) -> Option<Shape> {
    match &v.value {
        Value::Call(c) if c.func == OUTLINE => outline(c, diags).map(Shape::Outline),
        Value::Call(c) if section::SHAPES.contains(&c.func.as_str()) => {
            section::read(c, diags).map(Shape::Section)
        }
        Value::Call(c) if c.func == "region" => region(c, diags),
        Value::Call(c) if c.func == "place" => place(c, diags),
        Value::Call(c) if c.func == "bolt_circle" => {
            diags.push(message::shape::bolt_circle_not_shape(what, v.span));
            None
        }
        // A name leading back to its own shape, reported as it was
        // written out (`crate::sema::named_shape`).
        Value::Symbol(name) if name == crate::sema::named_shape::REPORTED => None,
        // Profiles and sections were written out where they are named.
        Value::Symbol(name) => {
            diags.push(message::shape::named_shape(what, name, v.span, None));
            None
        }
        other => {
            diags.push(message::shape::not_a_shape(
                what,
                other.got(),
                v.span,
                section::SHAPES,
            ));
            None
        }
    }
}

fn outline(c: &Call, diags: &mut Diagnostics) -> Option<Outline> {
    let mut start = None;
    let mut segments = Vec::new();
    let mut ok = true;
    let mut last: Option<[Length; 2]> = None;
    if c.args.len() > MAX_SEGMENTS {
        diags.push(message::shape::too_many_pieces(MAX_SEGMENTS, c.func_span));
        return None;
    }
    for a in &c.args {
        if let Some((_, s)) = &a.name {
            diags.push(message::shape::named_piece(*s));
            ok = false;
            continue;
        }
        let v = &a.value;
        let seg = match &v.value {
            Value::List(_) => point(v, diags).map(|to| Segment::Line { to }),
            Value::Call(arc) if arc.func == "arc" && start.is_some() => arc_piece(arc, diags),
            other => {
                let first = start.is_none();
                diags.push(message::shape::bad_piece(first, other.got(), v.span));
                None
            }
        };
        let Some(seg) = seg else {
            ok = false;
            continue;
        };
        let to = match seg {
            Segment::Line { to } | Segment::Arc { to, .. } => to,
        };
        if start.is_none() {
            start = Some(to);
        } else {
            if last == Some(to) {
                diags.push(message::shape::zero_length_piece(v.span));
                ok = false;
            }
            if let (Segment::Arc { radius, .. }, Some(from)) = (seg, last) {
                let chord = ((to[0].0 - from[0].0).powi(2) + (to[1].0 - from[1].0).powi(2)).sqrt();
                if radius.0 * 2.0 < chord * (1.0 - 1e-9) {
                    diags.push(message::shape::arc_too_small(radius, Length(chord), v.span));
                    ok = false;
                }
            }
            segments.push(seg);
        }
        last = Some(to);
    }
    let Some(start) = start else {
        // `outline()`: nothing was said about it yet.
        if ok {
            diags.push(message::shape::too_few_corners(c.func_span));
        }
        return None;
    };
    let arcs = segments.iter().any(|s| matches!(s, Segment::Arc { .. }));
    if ok && segments.len() < 2 && !arcs {
        diags.push(message::shape::too_few_corners(c.func_span));
        return None;
    }
    // Straight pieces whose corners all lie on one line enclose nothing (the
    // fill would call it a crossing, at a corner).
    if ok && !arcs && on_one_line(start, &segments) {
        diags.push(message::shape::no_area(c.func_span));
        return None;
    }
    ok.then_some(Outline { start, segments })
}

/// Whether every corner of a straight outline lies on the line through its
/// first two distinct corners (within a nanometre per millimetre of extent).
fn on_one_line(start: [Length; 2], segments: &[Segment]) -> bool {
    let corners: Vec<[f64; 2]> = std::iter::once(start)
        .chain(segments.iter().map(|s| match s {
            Segment::Line { to } | Segment::Arc { to, .. } => *to,
        }))
        .map(|p| [p[0].0, p[1].0])
        .collect();
    let a = corners[0];
    let Some(b) = corners.iter().find(|p| **p != a) else {
        return true;
    };
    let d = [b[0] - a[0], b[1] - a[1]];
    let len = d[0].hypot(d[1]);
    corners
        .iter()
        .all(|p| ((p[0] - a[0]) * d[1] - (p[1] - a[1]) * d[0]).abs() <= 1e-6 * len * len)
}

/// A point `[x, y]` of two lengths.
pub(in crate::sema) fn point(v: &Spanned, diags: &mut Diagnostics) -> Option<[Length; 2]> {
    match &v.value {
        Value::List(items) if items.len() == 2 => {
            let x = fields::quantity(&items[0], Dim::LENGTH, "x", diags);
            let y = fields::quantity(&items[1], Dim::LENGTH, "y", diags);
            Some([Length(x?), Length(y?)])
        }
        other => {
            diags.push(message::shape::not_a_point(other.got(), v.span));

            None
        }
    }
}

fn arc_piece(c: &Call, diags: &mut Diagnostics) -> Option<Segment> {
    let f = Fields::call(c, &ARC, diags);
    let to = f.value(&piece::TO, diags).and_then(|v| point(v, diags));
    let radius = f.quantity(&piece::RADIUS, diags);
    let turn = f.word_or_default(&piece::TURN, diags).map(|t| match t {
        "right" => Turn::Right,
        _ => Turn::Left,
    });
    Some(Segment::Arc {
        to: to?,
        radius: Length(radius?.0),
        turn: turn?,
    })
}

/// Evaluates a [`ProfileExpr`] layer after layer: the constants are declared
/// once, and those that use the layer are recomputed on each.
pub struct LayerShapes<'m> {
    env: Env<'m>,
    expr: &'m Expr,
}

impl ProfileExpr {
    /// An evaluator of the profile on any layer.
    pub fn evaluator(&self) -> LayerShapes<'_> {
        LayerShapes {
            env: Env::with_constants(&self.constants),
            expr: &self.expr,
        }
    }
}

impl LayerShapes<'_> {
    /// The profile on layer `layer` (0-based) whose plane is `z` mm above the
    /// first's; `None` after reporting why it is not a shape there.
    pub fn at(&mut self, layer: usize, z: f64, diags: &mut Diagnostics) -> Option<Shape> {
        let expr = self.expr;
        self.env.at_layer(layer, z, |env| {
            let v = env.eval(expr, diags)?;
            shape(&v, "a profile", diags)
        })
    }
}

pub use crate::sema::schema::shape::MAX_HOLES;

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
