//! `wall NAME { along, beads, side, height, bead, ends, direction }`: a wall
//! laid along an open path, and its pairing with `slicing planar { … }` into
//! a [`Build::Wall`](crate::sema::model::Build::Wall).
//!
//! The path is `polyline(points = […])`, `arc(centre, radius, from, to)` or
//! `chain([…])` of them, each piece starting where the one before ends. It
//! is checked here as a path (at least two points, no piece of no length,
//! no crossing) and, once the bead and its offset are known, as the path of
//! a wall that wide (no bend tighter than the wall reaches to its inside,
//! no face that runs into itself): [`OpenPath::wall_fault`].

use crate::diag::message::{self, wall::PathSpans};
use crate::diag::Diagnostics;
use crate::geometry::open_path::OpenPath;
use crate::geometry::profile::Vertex;
use crate::sema::eval::Env;
use crate::sema::fields::Fields;
use crate::sema::model::{
    Bead, Extent, OpenWall, PlanarSlicing, ScanBase, Top, VariableSlicing, WallEnds, WallOnScan,
    WallSide,
};
use crate::sema::schema::wall::{
    fields as wall, path, CHAIN, LEAD, MAX_PATH_POINTS, POLYLINE, WALL,
};
use crate::sema::slicing::planar::PlanarSpec;
use crate::sema::solid::extrude::Scope;
use crate::sema::solid::profile::point;
use crate::sema::value::{Call, Spanned, Value};
use crate::span::Span;
use crate::syntax::ast::{Body, Expr, Stmt};
use crate::units::{Length, Speed};

/// Pieces of a chain this far apart (mm) meet.
const MEET: f64 = 1e-3;

/// A wall block as written.
pub struct Written {
    name: String,
    path: OpenPath,
    pieces: Vec<Span>,
    along_span: Span,
    beads: usize,
    side: WallSide,
    height: Option<(Length, Span)>,
    /// `on = scan(…)` and where, if written.
    on: Option<(ScanBase, Span)>,
    /// `top = …` and where, if written.
    top: Option<(Top, Span)>,
    ends: WallEnds,
    one_way: bool,
    span: Span,
}

impl Written {
    /// The scanned part it is built on, when it is read.
    pub fn scan(&self) -> Option<&ScanBase> {
        self.on.as_ref().map(|(b, _)| b)
    }
}

/// Reads a wall block; returns it and its bead model, each when it is
/// right.
pub fn read<'a>(
    env: &mut Env<'a>,
    name: &str,
    stmts: &'a [Stmt],
    span: Span,
    scope: &Scope<'_, 'a>,
    diags: &mut Diagnostics,
) -> (Option<Written>, Option<Bead>) {
    let f = Fields::block(env, stmts, &WALL, format!("wall `{name}`"), span, diags);
    let on = on(env, &f, (name, scope), diags);
    let along = f.value(&wall::ALONG, diags).and_then(|v| {
        let (points, pieces) = path_value(v, diags)?;
        match OpenPath::new(&points) {
            Ok(p) => match p.self_intersection() {
                None => Some((p, pieces, v.span)),
                Some(at) => {
                    let spans = PathSpans {
                        along: v.span,
                        pieces: &pieces,
                    };
                    diags.push(message::wall::path_fault(
                        crate::geometry::open_path::PathFault::Crosses { at },
                        &spans,
                    ));
                    None
                }
            },
            Err(fault) => {
                let spans = PathSpans {
                    along: v.span,
                    pieces: &pieces,
                };
                diags.push(message::wall::path_fault(fault, &spans));
                None
            }
        }
    });
    // `top` is a function of the position, tried at the path's start.
    let top = match f.expr(&wall::TOP) {
        None => Some(None),
        Some(e) => {
            let at = along.as_ref().map_or([0.0; 2], |(p, _, _)| p.start());
            read_top(env, e, (name, at), scope, diags).map(|t| Some((t, e.span)))
        }
    };
    let count = f.count_or_default(&wall::BEADS, diags);
    let side = f.word_or_default(&wall::SIDE, diags).map(|w| match w {
        "left" => WallSide::Left,
        "right" => WallSide::Right,
        _ => WallSide::Centre,
    });
    let height = f.optional(
        &wall::HEIGHT,
        f.quantity(&wall::HEIGHT, diags)
            .map(|(h, sp)| (Length(h), sp)),
    );
    let ends = ends(&f, diags);
    let one_way = f
        .word_or_default(&wall::DIRECTION, diags)
        .map(|w| w == "one_way");
    let bead = crate::sema::process::bead::named(
        f.value(&wall::BEAD, diags),
        wall::BEAD.key,
        "the wall",
        scope.beads,
        scope.declared,
        diags,
    );
    let rise = rise(height, on, top, span, diags);
    let written = match (along, count, side, rise, ends, one_way) {
        (
            Some((path, pieces, along_span)),
            Some(beads),
            Some(side),
            Some((height, on, top)),
            Some(ends),
            Some(one_way),
        ) => Some(Written {
            name: name.to_string(),
            path,
            pieces,
            along_span,
            beads,
            side,
            height,
            on,
            top,
            ends,
            one_way,
            span,
        }),
        _ => None,
    };
    (written, bead)
}

/// How a wall rises, as written.
type Rise = (
    Option<(Length, Span)>,
    Option<(ScanBase, Span)>,
    Option<(Top, Span)>,
);

/// `top = e` of the wall `own`, tried at `at` (mm), a point of its path:
/// any top an extrusion takes, a solid of the file named too. A top that
/// does not depend on the position is read as the flat height it is.
fn read_top<'a>(
    env: &mut Env<'a>,
    e: &Expr,
    (own, at): (&str, [f64; 2]),
    scope: &Scope<'_, 'a>,
    diags: &mut Diagnostics,
) -> Option<Top> {
    // `top = NAME`: a solid of the file as the target.
    if let Some(t) = crate::sema::solid::target::named_top(env, e, own, scope, diags) {
        return t;
    }
    let reads = env.position_reads();
    let top = crate::sema::solid::top::read(env, e, at, scope.constants, diags)?;
    match top {
        Top::Expr(x) if env.position_reads() == reads => {
            // A constant: its value, so the help can name flat tops.
            let h = x.evaluator().at(at[0], at[1], &mut Diagnostics::new())?;
            Some(Top::Plane {
                at: [Length(0.0); 2],
                height: h,
                slope: [0.0; 2],
            })
        }
        t => Some(t),
    }
}

/// `height`, `on` and `top` (each `Some(None)` when not written, `None`
/// when wrong), when they go together: a wall on a scan rises to its
/// `top`, one on the plate by its `height` (or the slicing's `layers`).
fn rise(
    height: Option<Option<(Length, Span)>>,
    on: Option<Option<(ScanBase, Span)>>,
    top: Option<Option<(Top, Span)>>,
    span: Span,
    diags: &mut Diagnostics,
) -> Option<Rise> {
    let (height, on, top) = (height?, on?, top?);
    match (&height, &on, &top) {
        (Some((_, h)), Some((_, o)), _) => {
            diags.push(message::wall::height_on_scan(*h, *o));
            None
        }
        (_, None, Some((_, t))) => {
            diags.push(message::wall::top_without_scan(*t, span));
            None
        }
        (_, Some((_, o)), None) => {
            diags.push(message::scan::needs_top(*o));
            None
        }
        _ => Some((height, on, top)),
    }
}

/// `on = scan(…)` and where: `Some(None)` when not written, `None` when
/// written wrong (reported). A nominal named as a solid is read through
/// the extrusions' scope, as an extrusion's is.
fn on<'a>(
    env: &mut Env<'a>,
    f: &Fields<'_>,
    (own, scope): (&str, &Scope<'_, 'a>),
    diags: &mut Diagnostics,
) -> Option<Option<(ScanBase, Span)>> {
    let Some(v) = f.value(&wall::ON, diags) else {
        return (!f.has(&wall::ON)).then_some(None);
    };
    let Value::Call(c) = &v.value else {
        return None;
    };
    let data = env.data.clone();
    let mut solid = |n: &str, at: Span, diags: &mut Diagnostics| {
        crate::sema::solid::target::nominal(env, n, at, own, scope, diags)
    };
    crate::sema::solid::scan::read(c, v.span, (data.as_ref(), &mut solid), None, diags)
        .map(|(base, _)| Some((base, v.span)))
}

/// `ends = stop | lead(length)`.
fn ends(f: &Fields<'_>, diags: &mut Diagnostics) -> Option<WallEnds> {
    match f.value(&wall::ENDS, diags) {
        Some(v) => match &v.value {
            Value::Call(c) if c.func == "lead" => {
                let args = Fields::call(c, &LEAD, diags);
                args.quantity(&path::LENGTH, diags)
                    .map(|(l, _)| WallEnds::Lead(Length(l)))
            }
            _ => f
                .word_or_default(&wall::ENDS, diags)
                .map(|_| WallEnds::Stop),
        },
        None if f.has(&wall::ENDS) => None,
        None => Some(WallEnds::Stop),
    }
}

/// The path's vertices and, for each piece, where it is written; `None`
/// after reporting what is wrong.
fn path_value(v: &Spanned, diags: &mut Diagnostics) -> Option<(Vec<Vertex>, Vec<Span>)> {
    let mut out = Pieces::default();
    match &v.value {
        Value::Call(c) if c.func == "chain" => {
            let f = Fields::call(c, &CHAIN, diags);
            let list = f.value(&path::PIECES, diags)?;
            let Value::List(items) = &list.value else {
                diags.push(message::wall::not_a_path(list.value.got(), list.span));
                return None;
            };
            let mut ok = true;
            for item in items {
                ok &= piece(item, &mut out, diags).is_some();
            }
            if !ok {
                return None;
            }
        }
        _ => piece(v, &mut out, diags)?,
    }
    if out.vertices.len() > MAX_PATH_POINTS {
        diags.push(message::wall::too_many_points(MAX_PATH_POINTS, v.span));
        return None;
    }
    Some((out.vertices, out.spans))
}

/// A path as it is read, piece by piece.
#[derive(Default)]
struct Pieces {
    vertices: Vec<Vertex>,
    /// Where each piece (from one vertex to the next) is written.
    spans: Vec<Span>,
    /// The last piece as written (a polyline or an arc), for a gap's label.
    last: Option<Span>,
}

impl Pieces {
    /// Goes on from the path so far with `vertices` (written at `spans`,
    /// one for each piece, the whole piece at `whole`): its first vertex
    /// must be where the path ends.
    fn push(
        &mut self,
        vertices: Vec<Vertex>,
        spans: Vec<Span>,
        whole: Span,
        diags: &mut Diagnostics,
    ) -> Option<()> {
        let Some(first) = vertices.first().copied() else {
            return Some(());
        };
        if let (Some(end), Some(before)) = (self.vertices.last_mut(), self.last) {
            let gap = (first.x - end.x).hypot(first.y - end.y);
            if gap > MEET || gap.is_nan() {
                diags.push(message::wall::chain_gap(
                    Length(gap),
                    [end.x, end.y],
                    before,
                    whole,
                ));
                return None;
            }
            // The piece goes on from the end point with its own bend.
            end.bulge = first.bulge;
            self.vertices.extend(vertices.into_iter().skip(1));
        } else {
            self.vertices.extend(vertices);
        }
        self.spans.extend(spans);
        self.last = Some(whole);
        Some(())
    }
}

/// Reads one piece — a polyline or an arc — onto `out`.
fn piece(v: &Spanned, out: &mut Pieces, diags: &mut Diagnostics) -> Option<()> {
    match &v.value {
        Value::Call(c) if c.func == "polyline" => {
            let (vertices, spans) = polyline(c, v.span, diags)?;
            out.push(vertices, spans, v.span, diags)
        }
        Value::Call(c) if c.func == "arc" => {
            let vertices = arc(c, diags)?;
            out.push(vertices, vec![v.span], v.span, diags)
        }
        other => {
            diags.push(message::wall::not_a_path(other.got(), v.span));
            None
        }
    }
}

/// `polyline(points = […])`: its vertices, and each piece's span (its end
/// point's).
fn polyline(c: &Call, at: Span, diags: &mut Diagnostics) -> Option<(Vec<Vertex>, Vec<Span>)> {
    let f = Fields::call(c, &POLYLINE, diags);
    let list = f.value(&path::POINTS, diags)?;
    let Value::List(items) = &list.value else {
        diags.push(message::shape::not_a_point(list.value.got(), list.span));
        return None;
    };
    if items.len() > MAX_PATH_POINTS {
        diags.push(message::wall::too_many_points(MAX_PATH_POINTS, at));
        return None;
    }
    let mut vertices = Vec::with_capacity(items.len());
    let mut ok = true;
    for item in items {
        match point(item, diags) {
            Some(p) => vertices.push(Vertex::line(p[0].0, p[1].0)),
            None => ok = false,
        }
    }
    let spans = items.iter().skip(1).map(|i| i.span).collect();
    if vertices.len() < 2 && ok {
        let spans = PathSpans {
            along: list.span,
            pieces: &[],
        };
        diags.push(message::wall::path_fault(
            crate::geometry::open_path::PathFault::TooFewPoints,
            &spans,
        ));
        return None;
    }
    ok.then_some((vertices, spans))
}

/// `arc(centre, radius, from, to)`: its two vertices, the first with the
/// bulge of the turn.
fn arc(c: &Call, diags: &mut Diagnostics) -> Option<Vec<Vertex>> {
    let f = Fields::call(c, &crate::sema::schema::wall::ARC, diags);
    let centre = f.value(&path::CENTRE, diags).and_then(|v| point(v, diags));
    let radius = f.quantity(&path::RADIUS, diags);
    let from = f.quantity(&path::FROM, diags);
    let to = f.quantity(&path::TO, diags);
    let (centre, (r, _), (a, a_at), (b, b_at)) = (centre?, radius?, from?, to?);
    let sweep = b - a;
    let turn = std::f64::consts::TAU;
    // A whole turn ends where it starts: a closed loop, not a path.
    if sweep == 0.0 || sweep.abs() >= turn * (1.0 - 1e-9) || !sweep.is_finite() {
        diags.push(message::wall::arc_sweep(
            sweep.to_degrees(),
            a_at.join(b_at),
        ));
        return None;
    }
    let [cx, cy] = [centre[0].0, centre[1].0];
    let on = |phi: f64| [cx + r * phi.cos(), cy + r * phi.sin()];
    let (p, q) = (on(a), on(b));
    Some(vec![
        Vertex::arc(p[0], p[1], (sweep / 4.0).tan()),
        Vertex::line(q[0], q[1]),
    ])
}

/// How tall the wall is: `layers` in the slicing block or `height` in the
/// wall block, exactly one of them.
fn extent(w: &Written, spec: &PlanarSpec, diags: &mut Diagnostics) -> Option<Extent> {
    match (spec.layers, w.height) {
        (Some((n, ls)), None) => Some(Extent::Layers(n, ls)),
        (None, Some((h, hs))) => Some(Extent::Height(h, hs)),
        (Some((_, ls)), Some((_, hs))) => {
            diags.push(message::solid::layers_and_height(ls, hs));
            None
        }
        (None, None) => {
            diags.push(message::wall::no_height(w.span));
            None
        }
    }
}

/// The slicing fields that mean nothing for a wall along a path, where
/// written in `slicing`.
const NOT_FOR_A_WALL: &[&str] = &["contours", "infill", "seam", "layer_change"];

/// The slicing statement and the process block's speed (`Some(None)` when
/// not written, `None` when wrong) a wall is assembled with.
type Context<'s> = (Option<&'s Stmt>, Option<Option<(Speed, Span)>>);

/// Joins a wall with its planar slicing and its bead: the speed checked
/// against the bead, the beads' offset (`auto`: the flat-top offset `A/h`)
/// checked against its width, and the path against the wall's width.
pub fn assemble(
    w: Written,
    bead: &Bead,
    spec: PlanarSpec,
    (slicing, speed): Context<'_>,
    diags: &mut Diagnostics,
) -> Option<(OpenWall, Extent, PlanarSlicing)> {
    let ok = no_fields(NOT_FOR_A_WALL, slicing, w.span, diags);
    let extent = extent(&w, &spec, diags);
    let width = bead.width;
    let v = speed.and_then(|s| super::extrude::scan_speed(s, bead, spec.span, diags));
    let flat = v.map(|v| crate::bead::flat_top_offset(width, bead.model.height_at(v, width)));
    let offset_ok = match spec.offset {
        Some((d, at)) if w.beads > 1 => super::extrude::declared_offset(d, at, bead, flat, diags),
        _ => true,
    };
    let (Some(v), Some(flat), true, true) = (v, flat, offset_ok, ok) else {
        return None;
    };
    let (offset, offset_derived) = match spec.offset {
        Some((d, _)) => (d, false),
        None => (flat, true),
    };
    let extent = extent?;
    let wall = open_wall(w, width, offset, diags)?.0;
    // One contour a bead: a wall one bead wide rises A/w, beads side by
    // side A/offset ([`PlanarSlicing::overlapped`]).
    let slicing = spec.into_slicing((offset, offset_derived), v, wall.beads, None);
    Some((wall, extent, slicing))
}

/// The variable slicing fields a wall on a scan does not plan: `scan` (its
/// beads follow the path) and the tilted build, which lmdc plans under an
/// extrusion's footprint only.
const NOT_FOR_A_SCAN_WALL: &[&str] = &["scan", "direction"];

/// Joins a wall on a scan with its variable slicing (whose side checks
/// were made) and its bead: the beads' pitch (one bead: its width; more:
/// the declared `offset`, else the flat-top offset at the middle of the
/// bead's speeds) and the path checked against the wall's width.
pub fn assemble_on_scan(
    w: Written,
    bead: &Bead,
    spec: crate::sema::slicing::variable::VariableSpec,
    slicing: Option<&Stmt>,
    diags: &mut Diagnostics,
) -> Option<(OpenWall, WallOnScan, VariableSlicing, Length)> {
    let ok = no_fields(NOT_FOR_A_SCAN_WALL, slicing, w.span, diags);
    let declared = spec.offset();
    let (Some(variable), true) = (spec.into_slicing(), ok) else {
        return None;
    };
    let width = bead.width;
    // One bead fills the wall's width, as a flat wall's rises `A/w`; beads
    // side by side fill their pitch.
    let pitch = match declared {
        _ if w.beads == 1 => width,
        Some((d, _)) => d,
        None => {
            let mid = Speed((bead.speed[0].0 + bead.speed[1].0) / 2.0);
            crate::bead::flat_top_offset(width, bead.model.height_at(mid, width))
        }
    };
    let (wall, (on, top)) = open_wall(w, width, pitch, diags)?;
    // Both are there: `rise` refused a wall on a scan without its top.
    let (Some((base, _)), Some((top, top_span))) = (on, top) else {
        return None;
    };
    Some((
        wall,
        WallOnScan {
            base,
            top,
            top_span,
        },
        variable,
        pitch,
    ))
}

/// What a wall rises on and to: `on` and `top`, as read.
type OnTop = (Option<(ScanBase, Span)>, Option<(Top, Span)>);

/// The wall `w` with beads `width` wide `pitch` apart, its path checked
/// against the wall's reach, and what it rises on and to.
fn open_wall(
    w: Written,
    width: Length,
    pitch: Length,
    diags: &mut Diagnostics,
) -> Option<(OpenWall, OnTop)> {
    let wall = OpenWall {
        name: w.name,
        path: w.path,
        pieces: w.pieces,
        along_span: w.along_span,
        beads: w.beads,
        side: w.side,
        ends: w.ends,
        one_way: w.one_way,
        span: w.span,
    };
    let [left, right] = wall.reach(width.0, pitch.0);
    if let Some(fault) = wall.path.wall_fault(left, right) {
        let spans = PathSpans {
            along: wall.along_span,
            pieces: &wall.pieces,
        };
        diags.push(message::wall::path_fault(fault, &spans));
        return None;
    }
    Some((wall, (w.on, w.top)))
}

/// Reports each of `keys` written in the slicing statement `slicing` of
/// the wall at `wall`; whether none is.
fn no_fields(keys: &[&str], slicing: Option<&Stmt>, wall: Span, diags: &mut Diagnostics) -> bool {
    let Some(Body::Block(stmts, _)) = slicing.map(|s| &s.body) else {
        return true;
    };
    let mut ok = true;
    for s in stmts
        .iter()
        .filter(|s| keys.contains(&s.kind.node.as_str()))
    {
        diags.push(message::wall::slicing_field(
            &s.kind.node,
            s.kind.span,
            wall,
        ));
        ok = false;
    }
    ok
}
