//! What the slicer says about a loft along a spine: whether a layer count
//! keeps every layer within the bead's heights around a bend, how many points
//! its layers need, and where the seam sits.

use crate::diag::{plural, Code, Diagnostic};
use crate::span::Span;
use crate::units::{short, Angle, Length, Speed};

/// A bead model's heights, with where they are declared.
#[derive(Clone, Copy)]
pub struct Heights {
    /// h_min and h_max.
    pub range: [Length; 2],
    /// Where they are declared.
    pub span: Span,
}

/// The section reaches `inward` toward the bend centre, past the radius;
/// `need` is the radius the bead's heights would need, when one does.
pub fn section_past_centre(
    inward: f64,
    radius: Length,
    need: Option<f64>,
    spine: Span,
    section: Span,
) -> Diagnostic {
    Diagnostic::error(
        Code::BendTooTight,
        format!(
            "the section reaches {} toward the bend centre, past the bend radius {}",
            Length(inward),
            radius
        ),
    )
    .label(spine, "bend radius")
    .label(section, "section")
    .help(match need {
        Some(need) => format!(
            "the bend radius must exceed {}; with this bead model's height range, use a bend radius of at least {}",
            Length(inward),
            Length(need)
        ),
        None => format!(
            "the bend radius must exceed {} (and more for the bead model's height range)",
            Length(inward)
        ),
    })
}

/// No whole number of layers gives `what` ("layer height(s)") within the heights.
pub fn no_layer_count(what: &str, heights: Heights, spine: Span) -> Diagnostic {
    Diagnostic::error(
        Code::NoLayerCount,
        format!(
            "no whole number of layers gives {what} within {} .. {}",
            heights.range[0], heights.range[1]
        ),
    )
    .label(spine, "spine")
    .label(heights.span, "allowed heights")
    .help("change the spine's length or widen the bead's height range")
}

/// `n` declared layers run `lo .. hi` high, outside the bead's heights;
/// `counts` are the layer counts that would fit (`None`: none does).
pub fn layer_count_outside(
    n: usize,
    what: &str,
    [lo, hi]: [f64; 2],
    counts: Option<[f64; 2]>,
    heights: Heights,
    layers: Option<Span>,
) -> Diagnostic {
    let fix = match counts {
        Some([a, b]) if a == b => format!("use {a} layers, or `layers = auto`"),
        Some([a, b]) => format!("use between {a} and {b} layers, or `layers = auto`"),
        None => "no layer count works for this bend and bead model".to_string(),
    };
    Diagnostic::error(
        Code::LayerHeight,
        format!(
            "with {n} layer{} the {what} run {} .. {}, outside the bead's {} .. {}",
            plural(n as u64),
            Length(lo),
            Length(hi),
            heights.range[0],
            heights.range[1]
        ),
    )
    .label_opt(layers, "layer count")
    .label(heights.span, "allowed heights")
    .help(fix)
}

/// A bend too tight for the bead's heights: its numbers and what would fix it.
pub struct TooTight {
    /// The bend radius, mm.
    pub radius: f64,
    /// The section's reach toward and away from the bend centre, mm.
    pub inward: f64,
    /// Its reach away from the centre, mm.
    pub outward: f64,
    /// The outer/inner height ratio the bend needs.
    pub q_need: f64,
    /// The bead's h_max/h_min.
    pub q_have: f64,
    /// The bead's heights.
    pub heights: Heights,
    /// The spine and the bead's speed range.
    pub spine: Span,
    /// Where the bead's speeds are declared.
    pub speeds: Span,
    /// A bend radius that works, if one was found, mm.
    pub radius_fits: Option<f64>,
    /// A top speed of a bead model spanning the ratio, mm/s, if one was
    /// found.
    pub speed_fits: Option<f64>,
    /// The largest section, in % of the declared sizes, that fits, if one
    /// was found.
    pub scale_percent: Option<f64>,
    /// Whether every larger radius, faster top speed and smaller section
    /// works too (`layers = auto`); a declared count fits a band of them.
    pub at_least: bool,
}

/// A bend whose outer/inner height ratio no layer count fits.
pub fn too_tight(t: &TooTight) -> Diagnostic {
    let [h_min, h_max] = t.heights.range;
    let (least, most, up_to) = if t.at_least {
        ("at least ", "at most ", "up to ")
    } else {
        ("", "", "up to ")
    };
    let mut fixes = Vec::new();
    if let Some(r_need) = t.radius_fits {
        fixes.push(format!("a bend radius of {least}{}", Length(r_need)));
    }
    if let Some(v) = t.speed_fits {
        fixes.push(format!(
            "a bead model that spans the ratio (e.g. speeds {up_to}{} if it holds that far)",
            Speed(v)
        ));
    }
    if let Some(p) = t.scale_percent {
        fixes.push(format!(
            "a section {most}{}% of the declared size",
            short(p)
        ));
    }
    let help = if fixes.is_empty() {
        "no bend radius, speed range or section size alone fits this bead model".to_string()
    } else {
        format!("this would work: {}", fixes.join("; or "))
    };
    let (q_need, q_have) = (t.q_need, t.q_have);
    let d = apart(q_need, q_have);
    Diagnostic::error(
        Code::BendTooTight,
        if q_need > q_have {
            format!(
                "outer/inner layer height ratio {q_need:.d$} needs h_max/h_min ≥ {q_need:.d$}; this bead model gives {q_have:.d$}"
            )
        } else {
            format!(
                "outer/inner layer height ratio {:.2} is within the bead model's {:.2}, but no whole number of layers keeps every height within {} .. {}",
                q_need, q_have, h_min, h_max
            )
        },
    )
    .label(
        t.spine,
        format!(
            "bend radius {}: layers are {q_need:.d$}× thicker at the outside ({} from the bend axis) than at the inside ({})",
            Length(t.radius),
            Length(t.radius + t.outward),
            Length(t.radius - t.inward)
        ),
    )
    .label(
        t.heights.span,
        format!("h_max/h_min = {} / {} = {q_have:.d$}", h_max, h_min),
    )
    .label(t.speeds, "speed range")
    .help(help)
}

/// Decimals (2 to 6) that print `need` above `have` when it is: at two a
/// ratio of 1.4135 and one of 1.4080 both read 1.41.
fn apart(need: f64, have: f64) -> usize {
    (2..=6)
        .find(|&d| need <= have || format!("{need:.d$}") != format!("{have:.d$}"))
        .unwrap_or(6)
}

/// Where a layer is: its number (from 1), or how far along the loft its
/// section lies (a share, for a check made before the layers are counted).
#[derive(Clone, Copy)]
pub enum LayerAt {
    /// Layer number, from 1.
    Layer(usize),
    /// A share of the way along the loft.
    Along(f64),
}

/// A chord error that needs more than `max` points on a layer (`at`).
pub fn too_many_layer_points(
    chord_error: Length,
    max: usize,
    at: LayerAt,
    slicing: Span,
) -> Diagnostic {
    let on = match at {
        LayerAt::Layer(n) => format!("layer {n}"),
        LayerAt::Along(s) if s <= 0.0 => "the first layer".to_string(),
        LayerAt::Along(s) if s >= 1.0 => "the last layer".to_string(),
        LayerAt::Along(s) => format!("the layer {}% along the loft", short(s * 100.0)),
    };
    Diagnostic::error(
        Code::TooManyPoints,
        format!(
            "a chord error of {chord_error} needs more than {max} points on {on} \
             (its section's outline)"
        ),
    )
    .label(slicing, "slicing")
    .help("allow a larger chord error")
}

/// `points = k` and the section's corners between them make `k` points a
/// layer, more than `max`.
pub fn too_many_section_points(k: usize, max: usize, slicing: Span) -> Diagnostic {
    Diagnostic::error(
        Code::TooManyPoints,
        format!("the points a layer asks for and the section's corners make {k}, more than {max}"),
    )
    .label(slicing, "slicing")
    .help("ask for fewer points a layer")
}

/// `layers` layers of `points` points each pass `max`; `chord`: the points
/// are placed by a chord error (else counted, `points = k`).
pub fn too_many_duct_points(
    layers: usize,
    points: usize,
    max: usize,
    chord: bool,
    slicing: Span,
) -> Diagnostic {
    // The fewest points a layer can have: a section's eight seeds and the
    // closing point.
    let fits = max / layers.max(1);
    let help = if fits < 9 {
        format!(
            "even 8 points a layer pass it: fewer layers ({} at most), a bead that lays more a layer",
            max / 9
        )
    } else if chord {
        format!("a larger chord error, for at most {fits} points a layer")
    } else {
        format!("at most `points = {}` a layer", fits - 1)
    };
    Diagnostic::error(
        Code::TooManyPoints,
        format!("{layers} layers × {points} points is more than the {max} points a plan may hold"),
    )
    .label(slicing, "slicing")
    .help(help)
}

/// The most layers a wall may have: a plan's limit on layers, or fewer
/// when its limit on points comes first.
pub struct WallLimit {
    /// The most layers.
    pub layers: usize,
    /// When the points limit it: the points a layer has, the most a plan
    /// may hold, and how a layer would have few enough, if it can.
    pub points: Option<(usize, usize, Option<Fewer>)>,
}

/// How a layer would have fewer points.
pub enum Fewer {
    /// A larger chord error.
    ChordError,
    /// `points = k`.
    Points(usize),
}

/// `layers = auto` builds the wall in `n` layers (the bead lays at most
/// `heights.range[1]` a layer), more than `limit` allows; a bead laying
/// `fits` a layer would build it in as many as it allows (a mass balance's
/// `efficiency`, a share, would). Usually a bead model's number in the
/// wrong unit (an efficiency of 35e-6 %, a density in kg/m³ for g/cm³),
/// or a part far larger than meant.
pub fn too_many_wall_layers(
    n: f64,
    limit: WallLimit,
    fits: Length,
    efficiency: Option<f64>,
    heights: Heights,
    slicing: Span,
) -> Diagnostic {
    let most = limit.layers;
    let (what, fewer) = match limit.points {
        None => (format!("a plan may have at most {most} layers"), None),
        Some((k, max, fewer)) => (
            format!("a plan may hold at most {max} points, {most} layers of its {k} points"),
            match fewer {
                Some(Fewer::ChordError) => Some("a larger chord error".to_string()),
                Some(Fewer::Points(k)) => Some(format!("`points = {k}`")),
                None => None,
            },
        ),
    };
    let efficiency = efficiency.map_or(String::new(), |e| {
        format!(
            " (this mass balance with an efficiency of at least {} %)",
            short(e * 100.0)
        )
    });
    let fewer = fewer.map_or(String::new(), |f| format!("; or fewer points a layer: {f}"));
    let n = if n.is_finite() {
        format!("{n:.0}")
    } else {
        "endless".to_string()
    };
    Diagnostic::error(
        Code::TooManyPoints,
        format!(
            "the wall needs {n} layers: this bead lays at most {} a layer, and {what}",
            heights.range[1]
        ),
    )
    .label(heights.span, "the bead's heights")
    .label(slicing, "the layer count")
    .help(format!(
        "a bead that lays at least {fits} a layer builds it in {most} layers{efficiency}{fewer}; \
         or a smaller part. A bead far off has a number in the wrong unit, most often (an \
         efficiency in %, a density in g/cm^3, a feed in g/min)"
    ))
}

/// `seam = lowest` or `sharpest_corner` on a normal-sliced wall.
pub fn planar_seam_on_a_wall(at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::BadChoice,
        "a wall's seam is an angle, `rotating(…)`, `random(…)` or `staggered(…)`",
    )
    .label(at, "this picks among a planar layer's contour points")
    .help(
        "`lowest` and `sharpest_corner` choose where a flat contour starts; a wall sliced \
         normal to its spine starts at an angle in its section frame, e.g. \
         `seam = rotating(step = 90 deg)` turns it a quarter turn each layer, \
         `staggered(shift = 10 mm)` moves it 10 mm along the loop each layer",
    )
}

/// `layer_change = spiral` with a seam that moves from layer to layer.
pub fn spiral_seam_moves(change: Span, seam: Span) -> Diagnostic {
    Diagnostic::error(
        Code::ConflictingFields,
        "a spiral layer change goes on from where the layer ended, so every layer starts at the same angle: its seam cannot move",
    )
    .label(change, "each layer climbs into the next here")
    .label(seam, "this seam moves from layer to layer")
    .help(
        "give the seam one angle (`seam = 90 deg`: the climb ends there on every layer), \
         or keep `layer_change = lift` to move the seam",
    )
}

/// A better seam, found by sampling the layer at the seam + j·2π/k.
pub enum SeamAdvice {
    /// This angle (deg) keeps off the extremes on every layer.
    Everywhere(String),
    /// This angle (deg) sits there on the fewest layers (that many).
    Fewest(String, usize),
    /// No angle does better: the section turns through them all.
    None,
}

/// The seam sits at the bend's innermost or outermost point on `hits` layers.
pub fn seam_at_bend_extreme(
    hits: usize,
    first: usize,
    seam: f64,
    advice: &SeamAdvice,
    seam_span: Span,
    bend: Span,
) -> Diagnostic {
    let help = match advice {
        SeamAdvice::Everywhere(deg) => format!(
            "start and stop where the layer height is average: `seam = {deg} deg` keeps the seam off the bend's innermost and outermost points on every layer"
        ),
        SeamAdvice::Fewest(deg, n) => format!(
            "no seam keeps off the bend's innermost and outermost points on every layer; `seam = {deg} deg` sits there on the fewest ({n})"
        ),
        SeamAdvice::None => "no other seam angle sits at the bend's innermost or outermost points on fewer layers: the section turns through them all (a twist); accept the seam or change the twist".to_string(),
    };
    Diagnostic::warning(
        Code::SeamAtBendExtreme,
        format!(
            "the seam (laser on/off) sits at the innermost or outermost point of the bend on {} layer{} (first: layer {})",
            hits,
            if hits == 1 { "" } else { "s" },
            first + 1
        ),
    )
    .label(seam_span, format!("seam at {}", Angle(seam)))
    .label(bend, "bend")
    .help(help)
}

#[cfg(test)]
mod tests {
    use super::apart;

    #[test]
    fn ratios_print_apart_when_one_passes_the_other() {
        assert_eq!(apart(2.2366, 1.408), 2);
        // Both read 1.41 at two decimals: three tell them apart.
        assert_eq!(apart(1.4135, 1.4080), 3);
        assert_eq!(apart(1.40801, 1.40800), 5);
        // A need within the bead's ratio needs nothing more.
        assert_eq!(apart(1.2, 1.408), 2);
    }
}
