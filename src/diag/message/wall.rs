//! A wall along an open path (`wall NAME { along = … }`): the path's own
//! mistakes (too few points, a piece of no length, a crossing, a bend
//! tighter than the wall reaches, pieces of a chain that do not meet) and
//! the slicing fields that do not apply to it.

use crate::diag::message::value::Got;
use crate::diag::{Code, Diagnostic};
use crate::geometry::open_path::PathFault;
use crate::span::Span;
use crate::units::{short, Length};

/// Where a path's pieces are written, for its faults' labels.
pub struct PathSpans<'a> {
    /// The whole `along = …` value.
    pub along: Span,
    /// Each piece as written (a polyline's piece is its end point).
    pub pieces: &'a [Span],
}

impl PathSpans<'_> {
    fn piece(&self, k: usize) -> Span {
        self.pieces.get(k).copied().unwrap_or(self.along)
    }
}

/// `(x, y) mm`.
fn at(p: [f64; 2]) -> String {
    format!("({}, {}) mm", short(p[0]), short(p[1]))
}

/// What is wrong with the path itself, or with the wall along it.
pub fn path_fault(f: PathFault, spans: &PathSpans<'_>) -> Diagnostic {
    match f {
        PathFault::TooFewPoints => Diagnostic::error(
            Code::Degenerate,
            "a wall's path needs at least two points",
        )
        .label(spans.along, "fewer than two points")
        .help("give the points the wall runs through: `polyline(points = [[0 mm, 0 mm], [40 mm, 0 mm]])`"),
        PathFault::ZeroLength { piece } => Diagnostic::error(
            Code::Degenerate,
            "this piece of the path has no length",
        )
        .label(spans.piece(piece), "same point as the one before")
        .help("drop the repeated point"),
        PathFault::NotFinite => Diagnostic::error(
            Code::TooLarge,
            "the path's points are too far out to offset",
        )
        .label(spans.along, "this path")
        .help("give the points in mm of the part, within 100 m of its origin"),
        PathFault::Crosses { at: p } => Diagnostic::error(
            Code::SelfIntersecting,
            format!("the path crosses or touches itself at {}", at(p)),
        )
        .label(spans.along, "this path")
        .help("a wall along a path must not run over itself: split it into pieces that do not meet, or reorder the points; a wall that closes on itself is an `extrude` with `contours = 1`"),
        PathFault::ArcTooTight {
            piece,
            radius,
            reach,
        } => Diagnostic::error(
            Code::PathBend,
            format!(
                "this arc bends at a radius of {}, and the wall reaches {} to its inside: its beads there would collapse into the arc's centre",
                Length(radius),
                Length(reach)
            ),
        )
        .label(spans.piece(piece), format!("radius {}", Length(radius)))
        .help(format!(
            "bend at a radius of more than {} (the wall's reach to the inside of the bend), or make the wall narrower on that side (fewer `beads`, or `side` away from the bend)",
            Length(reach)
        )),
        PathFault::Collapses {
            at: p,
            reach,
            other,
        } => Diagnostic::error(
            Code::PathBend,
            format!(
                "the wall's face {} to the {} of the path runs into itself near {}{}: a bend there is too sharp for the wall's width, or the path comes back closer than the wall is wide",
                Length(reach.abs()),
                if reach > 0.0 { "left" } else { "right" },
                at(p),
                other.map_or(String::new(), |(q, apart)| format!(
                    ", {} from the path at {}",
                    Length(apart),
                    at(q)
                )),
            ),
        )
        .label(spans.along, "this path")
        .help("round the bend (an `arc(…)` of a radius larger than the wall's reach to its inside), lengthen the pieces there, keep the path's stretches further apart, or make the wall narrower"),
    }
}

/// Two pieces of a `chain(…)` do not meet.
pub fn chain_gap(gap: Length, end: [f64; 2], before: Span, next: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Degenerate,
        format!(
            "the pieces of this chain do not meet: this one starts {gap} from where the one before ends, at {}",
            at(end)
        ),
    )
    .label(next, "starts elsewhere")
    .label(before, "ends here")
    .help("start each piece where the one before ends (an arc starts at its `from` angle on its circle)")
}

/// An arc whose `from` and `to` are the same angle, or a turn or more
/// apart.
pub fn arc_sweep(sweep_deg: f64, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Degenerate,
        format!(
            "this arc turns by {}°: a path's arc turns by more than nothing and less than a whole turn",
            short(sweep_deg)
        ),
    )
    .label(at, "from `from` to `to`")
    .help("e.g. `arc(centre = [0 mm, 0 mm], radius = 10 mm, from = 0 deg, to = 90 deg)`, counter-clockwise; `from = 90 deg` and `to = 0 deg`, clockwise")
}

/// A value where a path belongs.
pub fn not_a_path(got: Got<'_>, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::ExpectedShape,
        "a wall's path is `polyline(points = […])`, `arc(centre, radius, from, to)` or `chain([…])` of them",
    )
    .label(at, format!("this is {}", got.describe()))
    .help("e.g. `along = polyline(points = [[0 mm, 0 mm], [40 mm, 0 mm], [40 mm, 25 mm]])`")
}

/// A path of more points than lmdc takes.
pub fn too_many_points(max: usize, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::TooLarge,
        format!("this path has more than {max} points"),
    )
    .label(at, "this path")
    .help("describe long curves by `arc(…)` pieces rather than many points")
}

/// A field of the slicing block that means nothing for a wall along a
/// path.
pub fn slicing_field(key: &str, at: Span, wall: Span) -> Diagnostic {
    Diagnostic::error(
        Code::ConflictingFields,
        format!("`{key}` does not apply to a wall along a path"),
    )
    .label(at, format!("`{key}`"))
    .label(wall, "a wall along a path: its beads follow the path")
    .help(match key {
        // Planned under an extrusion's footprint, not along a path.
        "direction" => "drop `direction`: lmdc fills along a tilted build direction under an extrusion's footprint only; a lip over an overhang can be drawn as a thin `outline(…)` extruded on the scan".to_string(),
        _ => format!(
            "drop `{key}`: the wall's beads are set by its `beads`, `side`, `ends` and `direction`"
        ),
    })
}

/// A wall's `top` without `on = scan(…)`.
pub fn top_without_scan(top: Span, wall: Span) -> Diagnostic {
    Diagnostic::error(
        Code::ConflictingFields,
        "`top` is the finished height of a wall built on a scan, and this wall is not built on one",
    )
    .label(top, "`top`")
    .label(wall, "built on the plate")
    .help("give a wall on the plate its `height = …` (or `layers` in the slicing block), or build it on a part with `on = scan(file = …)`")
}

/// A wall on a scan given `height` (its layer count is the slicing's
/// `layers`).
pub fn height_on_scan(height: Span, on: Span) -> Diagnostic {
    Diagnostic::error(
        Code::ConflictingFields,
        "a wall on a scan rises to its `top`: its height differs along it, from the scanned surface up",
    )
    .label(height, "a height")
    .label(on, "built on a scan")
    .help("drop `height` and write `top = …`: the finished top above the part's z = 0 (the layer count goes in the slicing block's `layers`)")
}

/// Neither a layer count nor the wall's height is given.
pub fn no_height(at: Span) -> Diagnostic {
    Diagnostic::error(Code::MissingField, "how tall is the wall?")
        .label(at, "no `height`")
        .help("add `height = 12 mm` here, or `layers = 16` to the slicing block")
}

/// A plan of more points than lmdc keeps: `layers` layers of `per_layer`
/// points each, against the most a plan and a layer may hold.
pub fn too_many_plan_points(
    layers: usize,
    per_layer: usize,
    [plan, layer]: [usize; 2],
    at: Span,
) -> Diagnostic {
    Diagnostic::error(
        Code::TooManyPoints,
        format!(
            "this wall would take {layers} layers of {per_layer} points: a plan may hold {plan} points, a layer {layer}"
        ),
    )
    .label(at, "this wall")
    .help("a coarser `chord_error`, fewer beads or a lower wall")
}

/// No whole number of layers lays a wall on a scan: what the count needs.
pub struct NoCountOnScan<'a> {
    /// The gaps' range, the bead's heights and the counts each end allows.
    pub e: &'a crate::slice::variable::layers::NoLayerCount,
    /// Where along the wall the gap is least and where greatest.
    pub at: [[f64; 2]; 2],
    /// The wall's top, mm, when it is flat.
    pub top: Option<f64>,
    /// The level the regular layers rise from, mm, when the wear under
    /// the wall was levelled first (`level = …`): the gaps are from it.
    pub level: Option<f64>,
    /// The flat tops nearest it that a count lays (`[lowest, highest]` mm)
    /// and that count, if any.
    pub fix: Option<([f64; 2], u32)>,
    /// The bead's name and where its heights are declared.
    pub bead: (&'a str, Span),
    /// The beads' pitch (the strip each fills), mm.
    pub pitch: f64,
    /// Where the top and the scan are written.
    pub spans: [Span; 2],
}

/// No whole number of layers lays every gap between a wall's scan and its
/// top within the bead's heights (`lmd::no-layer-count`).
pub fn no_count_on_scan(c: &NoCountOnScan<'_>) -> Diagnostic {
    use super::top::spot;
    let e = c.e;
    let (lo, hi) = (e.top.low(), e.top.high());
    let (h_lo, h_hi) = (e.bead.low(), e.bead.high());
    let name = c.bead.0;
    let gaps = match c.level {
        None => format!("along the wall the scanned part lies {lo} .. {hi} below its top"),
        Some(z) => format!(
            "from the level {} mm the wall's regular layers rise {lo} .. {hi} to its top",
            short(z)
        ),
    };
    let message = if e.most == 0 {
        format!("{gaps}; the least is thinner than the thinnest layer bead `{name}` lays ({h_lo})")
    } else if e.ratio_needed() > e.ratio_available() {
        format!(
            "{gaps} (ratio {}); bead `{name}` lays {h_lo} .. {h_hi} a layer (ratio {}): no number of layers lays both",
            short(e.ratio_needed()),
            short(e.ratio_available())
        )
    } else {
        format!(
            "{gaps}; bead `{name}` lays {h_lo} .. {h_hi} a layer, but no whole number of layers fits both: the deepest needs at least {}, the shallowest allows at most {}",
            e.fewest, e.most
        )
    };
    // The ends are hundredths, rounded inward: printed as they are.
    let fix = match c.fix {
        Some(([a, b], n)) if a == b => format!("`top = {a} mm` ({n} layers); or "),
        Some(([a, b], n)) => format!("a top from {a} to {b} mm ({n} layers); or "),
        None => String::new(),
    };
    let [low_at, high_at] = c.at;
    Diagnostic::error(crate::diag::Code::NoLayerCount, message)
        .label(
            c.spans[0],
            format!(
                "{}: {hi} to add at {}, {lo} at {}",
                c.top.map_or("the top".to_string(), |t| format!("{} mm", short(t))),
                spot(None, high_at),
                spot(None, low_at)
            ),
        )
        .label(c.spans[1], "the scan")
        .label(
            c.bead.1,
            format!(
                "the bead lays {h_lo} .. {h_hi} a layer at the beads' pitch, {}",
                Length(c.pitch)
            ),
        )
        .help(match c.level {
            None => format!(
                "this would work: {fix}a bead whose heights span more; or `level = auto` in the slicing block, which fills the wear up to the scan's highest point under the wall first"
            ),
            Some(_) => format!(
                "this would work: {fix}a bead whose heights span more; or another level, from which a whole number of the bead's layers reaches the top"
            ),
        })
}
