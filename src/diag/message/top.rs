//! What the slicer says about a variable top: its layer count, its
//! footprint, its tracks and the segments that follow it.

use crate::diag::{Code, Diagnostic, Diagnostics};
use crate::geometry::target::TurnedFrame;
use crate::slice::variable::layers::{NoLayerCount, OutOfRange, MAX_LAYERS};
use crate::slice::variable::segments::{SegmentError, MAX_SEGMENTS};
use crate::span::Span;
use crate::units::{short, Length, Speed};

fn at(p: [f64; 2]) -> String {
    format!("({}, {}) mm", short(p[0]), short(p[1]))
}

fn p3(p: [f64; 3]) -> String {
    format!("({}, {}, {}) mm", short(p[0]), short(p[1]), short(p[2]))
}

/// A point of a variable top's footprint (mm, in the frame the fill is
/// planned in) as its messages name it: `(x, y) mm`, or, for a fill
/// planned turned so its build direction is up, the part's point that its
/// line along the direction stands for, on the finished face's height:
/// `(x, y, z) mm`.
pub(crate) fn spot(turned: Option<&TurnedFrame>, p: [f64; 2]) -> String {
    match turned {
        None => at(p),
        Some(t) => p3(t.footprint(p)),
    }
}

/// A height `z` (mm) over the footprint point `p`, in the frame the fill
/// is planned in: `z mm`, or, planned turned, the part's point there:
/// `(x, y, z) mm` (a height along the build direction is a point on its
/// line).
pub(crate) fn height(turned: Option<&TurnedFrame>, p: [f64; 2], z: f64) -> String {
    match turned {
        None => format!("{} mm", short(z)),
        Some(t) => p3(t.point([p[0], p[1], z])),
    }
}

/// The spans a top's messages point at, and the frame its points are in.
#[derive(Clone, Copy)]
pub struct TopAt<'a> {
    /// The top.
    pub top: Span,
    /// The footprint, or the wall's path.
    pub shape: Span,
    /// What `shape` is: `footprint` or `path`.
    pub what: &'static str,
    /// Set when the fill is planned turned: its points go back into the
    /// part.
    pub turned: Option<&'a TurnedFrame>,
}

/// The top needs more than [`MAX_LAYERS`] layers of at most `h_max`.
pub fn too_many_layers(high: Length, needed: f64, h_max: Length, top: Span) -> Diagnostic {
    Diagnostic::error(
        Code::TooManyPoints,
        format!(
            "the top reaches {high}: {} layers of at most {h_max}, more than {MAX_LAYERS}",
            short(needed.ceil()),
        ),
    )
    .label(top, "the top")
    .help("check the top's unit and numbers")
}

/// A number as a fix prints it: `decimals` decimals, trailing zeros dropped.
/// `value` is the number read back from that text, the one the fix was
/// checked with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Decimal {
    /// The value printed.
    pub value: f64,
    /// Its decimals.
    pub decimals: usize,
}

impl std::fmt::Display for Decimal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let d = self.decimals;
        let s = format!("{:.d$}", self.value);
        let s = if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.')
        } else {
            &s
        };
        f.write_str(if s == "-0" { "0" } else { s })
    }
}

/// A change of the top that lets a layer count lay it, with the count
/// (`layers = auto`'s, or the declared one).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TopFix {
    /// `edges(…)` with this `to` (`to`) or `from`, mm, the other kept.
    Edge {
        /// Whether the value is `to`.
        to: bool,
        /// The value, mm.
        value: Decimal,
        /// The layer count.
        layers: u32,
    },
    /// `plane(…)` with this `height`, mm, the slopes kept.
    Height {
        /// The value, mm.
        value: Decimal,
        /// The layer count.
        layers: u32,
    },
    /// `plane(…)` with this slope along x (`axis` 0) or y, in %, the height
    /// and the other slope kept.
    Slope {
        /// 0: `slope_x`, 1: `slope_y`.
        axis: usize,
        /// The slope, %.
        percent: Decimal,
        /// The layer count.
        layers: u32,
    },
    /// A top written as an expression, at most this high where the tracks
    /// run (its lowest kept), mm.
    High {
        /// The height, mm.
        at_most: Decimal,
        /// The layer count.
        layers: u32,
    },
    /// A flat top on a scan from `from` to `to`, mm, each laid in
    /// `layers` layers.
    Flat {
        /// The lowest, mm.
        from: Decimal,
        /// The highest, mm.
        to: Decimal,
        /// The layer count.
        layers: u32,
    },
    /// At least this high where the tracks run lowest (its highest kept), mm.
    Low {
        /// The height, mm.
        at_least: Decimal,
        /// The layer count.
        layers: u32,
    },
}

impl TopFix {
    /// The fix in words; `declared` is the file's layer count, if declared.
    fn words(&self, declared: Option<u32>) -> String {
        let count = |n: u32| match declared {
            Some(d) if d != n => format!("with `layers = {n}`"),
            _ => format!("{n} layers"),
        };
        match *self {
            TopFix::Edge { to, value, layers } => {
                let (set, kept) = if to { ("to", "from") } else { ("from", "to") };
                format!("`{set} = {value} mm` (keeping `{kept}`: {})", count(layers))
            }
            TopFix::Height { value, layers } => {
                format!(
                    "`height = {value} mm` (keeping the slopes: {})",
                    count(layers)
                )
            }
            TopFix::Slope {
                axis,
                percent,
                layers,
            } => {
                let set = if axis == 0 { "slope_x" } else { "slope_y" };
                format!(
                    "`{set} = {percent} %` (keeping the rest: {})",
                    count(layers)
                )
            }
            TopFix::High { at_most, layers } => format!(
                "a top at most {at_most} mm high where the tracks run highest ({layers} layers)"
            ),
            TopFix::Flat { from, to, layers } if from.value == to.value => {
                format!("`top = {from} mm` ({})", count(layers))
            }
            TopFix::Flat { from, to, layers } => {
                format!("a top from {from} to {to} mm ({})", count(layers))
            }
            TopFix::Low { at_least, layers } => {
                format!("at least {at_least} mm where they run lowest ({layers} layers)")
            }
        }
    }
}

/// A bead model as the layer-count messages name it, with the heights a
/// bead would need to reach (each checked to fit).
pub struct CountBead<'a> {
    /// Its name.
    pub name: &'a str,
    /// Where its heights are declared.
    pub heights: Span,
    /// Where its speeds are declared.
    pub speeds: Span,
    /// A lowest height that fits, mm, if one does.
    pub low: Option<Decimal>,
    /// A highest height that fits, mm, if one does.
    pub high: Option<Decimal>,
    /// The speed (mm/s) at which the model lays `low` as the tracks stack
    /// it, if it gives one that fits.
    pub speed_for_low: Option<f64>,
    /// The speed for `high`, likewise.
    pub speed_for_high: Option<f64>,
}

/// No whole number of layers lays every point of the top (lowest at
/// `low_at`, highest at `high_at`, both where the tracks run, named in
/// the part when the fill is planned `turned`) within the bead's heights;
/// `fixes` are the changes of the top that would work, `declared` the
/// file's layer count if it declares one.
pub fn no_count(
    e: &NoLayerCount,
    [low_at, high_at]: [[f64; 2]; 2],
    fixes: &[TopFix],
    bead: &CountBead,
    declared: Option<u32>,
    top: Span,
    turned: Option<&TurnedFrame>,
) -> Diagnostic {
    let (lo, hi) = (e.top.low(), e.top.high());
    let (h_lo, h_hi) = (e.bead.low(), e.bead.high());
    let name = bead.name;
    let message = if e.most == 0 {
        format!(
            "where the tracks run the top is {lo} .. {hi} high; its lowest point is below the thinnest layer bead `{name}` lays ({h_lo})"
        )
    } else if e.ratio_needed() > e.ratio_available() {
        format!(
            "where the tracks run the top is {lo} .. {hi} high (ratio {}); bead `{name}` lays {h_lo} .. {h_hi} (ratio {}): no number of layers lays both ends within it",
            short(e.ratio_needed()),
            short(e.ratio_available())
        )
    } else {
        format!(
            "where the tracks run the top is {lo} .. {hi} high (ratio {}); bead `{name}` lays {h_lo} .. {h_hi} (ratio {}), but no whole number of layers fits both ends: the highest point needs at least {} layers, the lowest allows at most {}",
            short(e.ratio_needed()),
            short(e.ratio_available()),
            e.fewest,
            e.most
        )
    };
    let speed_note = |v: Option<f64>, dir: &str| match v {
        Some(v) => format!(" (speeds {dir} {}, if the model holds that far)", Speed(v)),
        None => String::new(),
    };
    let mut fixes: Vec<String> = fixes.iter().map(|f| f.words(declared)).collect();
    // The bead's fixes are for `layers = auto`'s count.
    let auto = match declared {
        Some(_) => " (with `layers = auto`)",
        None => "",
    };
    if let Some(low) = bead.low {
        fixes.push(format!(
            "a bead that lays down to {low} mm{}{auto}",
            speed_note(bead.speed_for_low, "up to")
        ));
    }
    if let Some(high) = bead.high {
        fixes.push(format!(
            "one that lays up to {high} mm{}{auto}",
            speed_note(bead.speed_for_high, "down to")
        ));
    }
    let d = Diagnostic::error(Code::NoLayerCount, message)
        .label(
            top,
            format!(
                "where the tracks run: {hi} at {}, {lo} at {}",
                spot(turned, high_at),
                spot(turned, low_at)
            ),
        )
        .label(bead.heights, format!("the bead lays {h_lo} .. {h_hi}"))
        .label(bead.speeds, "over these speeds");
    if fixes.is_empty() {
        return d.help("no change of the top or the bead's reach that keeps the rest lets a count fit: a flatter top, or a bead map spanning more");
    }
    d.help(format!("this would work: {}", fixes.join("; or ")))
}

/// A declared layer count outside the counts that lay the top's heights.
pub struct CountOutside<'a> {
    /// The count, the heights it lays and the counts that lay them.
    pub e: &'a OutOfRange,
    /// The bead's name.
    pub bead: &'a str,
    /// The counts among them whose tracks can lay their layers, as runs
    /// `[first, last]` (those nearest the declared count, when many).
    pub runs: &'a [[u32; 2]],
    /// The count `layers = auto` takes, when it is one of them.
    pub auto: Option<u32>,
    /// The layer count's declaration.
    pub layers: Option<Span>,
    /// The bead's heights.
    pub heights: Span,
}

/// A declared layer count outside the counts that work.
pub fn count_outside(c: &CountOutside) -> Diagnostic {
    let e = c.e;
    let n = e.layers.get();
    let counts: Vec<String> = c
        .runs
        .iter()
        .map(|&[a, b]| match b - a {
            0 => format!("{a}"),
            1 => format!("{a} or {b}"),
            _ => format!("between {a} and {b}"),
        })
        .collect();
    let auto = match c.auto {
        Some(a) => format!(", or `layers = auto` ({a})"),
        None => String::new(),
    };
    let help = if counts.is_empty() {
        format!(
            "{} to {} layers lay these heights, but at none of them can every track lay its layer at its spacing: `layers = auto` says why",
            e.range.fewest(),
            e.range.most()
        )
    } else {
        format!("use {} layers{auto}", counts.join(", or "))
    };
    Diagnostic::error(
        Code::LayerHeight,
        format!(
            "{n} layers lay {} .. {} where the tracks run, outside the {} .. {} bead `{}` lays",
            e.heights.low(),
            e.heights.high(),
            e.bead.low(),
            e.bead.high(),
            c.bead
        ),
    )
    .label_opt(c.layers, "layer count")
    .label(c.heights, "the bead's heights")
    .help(help)
}

/// The footprint's outline crosses itself at `p` (named in the part when
/// the fill is planned `turned`).
pub fn footprint_crosses(p: [f64; 2], shape: Span, turned: Option<&TurnedFrame>) -> Diagnostic {
    Diagnostic::error(
        Code::SelfIntersecting,
        format!("the footprint crosses itself at {}", spot(turned, p)),
    )
    .label(shape, "this outline's edges cross")
    .help("reorder the outline's points so its edges do not cross")
}

/// The footprint encloses no area.
pub fn footprint_empty(shape: Span) -> Diagnostic {
    Diagnostic::error(Code::FillEmpty, "the footprint encloses nothing").label(shape, "footprint")
}

/// The footprint is narrower across the tracks (along `axis`) than a bead.
pub fn footprint_too_narrow(across: f64, axis: &str, width: f64, shape: Span) -> Diagnostic {
    Diagnostic::error(
        Code::FillEmpty,
        format!(
            "the footprint is {} across the tracks (along {axis}), narrower than the {} bead",
            Length(across),
            Length(width)
        ),
    )
    .label(shape, "footprint")
    .help("a variable-top part is at least one bead wide: widen the footprint, or use a narrower bead")
}

/// The footprint needs more than `max` tracks a layer.
pub fn too_many_tracks(max: usize, shape: Span) -> Diagnostic {
    Diagnostic::error(
        Code::TooManyPoints,
        format!("the footprint needs more than {max} tracks a layer"),
    )
    .label(shape, "footprint")
    .help("check the footprint's size and unit")
}

/// The balanced spacing has no stretch that closes on the far edge.
pub fn no_closure(top: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Fill,
        "no uniform stretch of the balanced spacing lands the last track half a bead inside the far edge",
    )
    .label(top, "the top")
    .help("the top's thickness ratio across the tracks is far outside what a bead map spans: give `offset = …` a length, or a flatter top across")
}

/// The `tracks` balanced tracks were stretched by the factor `s` to close;
/// `fits` is the footprint width across the tracks (mm) that needs no
/// stretch with as many tracks.
pub fn stretched(tracks: usize, s: f64, fits: f64, slicing: Span, shape: Span) -> Diagnostic {
    let (how, speed, strips) = if s > 1.0 {
        ("stretched", "slower", "wider")
    } else {
        ("squeezed", "faster", "narrower")
    };
    Diagnostic::warning(
        Code::OverlapStretch,
        format!(
            "the {tracks} tracks are {how} by {} % to reach half a bead inside both edges: they are scanned about that much {speed} to fill their {strips} strips, and the beads meet less evenly than the balance lays them",
            short(((s - 1.0) * 100.0).abs())
        ),
    )
    .label(slicing, "offset = balanced")
    .label(shape, "footprint")
    .help(format!(
        "a footprint about {} mm wide across the tracks fits the balanced spacing of {tracks} tracks; or declare `offset = …`",
        short((fits * 100.0).round() / 100.0)
    ))
}

/// `n` layers of `per_layer` points pass `max`.
pub fn too_many_points(n: u32, per_layer: usize, max: usize, slicing: Span) -> Diagnostic {
    Diagnostic::error(
        Code::TooManyPoints,
        format!("{n} layers × {per_layer} points is more than {max} points"),
    )
    .label(slicing, "slicing")
    .help("a larger `tolerance` makes fewer segments; a smaller part fewer tracks")
}

/// `count` tracks shorter than the bead width `w`, on every layer.
pub fn short_tracks(count: usize, w: f64, slicing: Span) -> Diagnostic {
    Diagnostic::warning(
        Code::ShortTrack,
        format!(
            "{count} track{} shorter than the bead width {} (on every layer)",
            if count == 1 { " is" } else { "s are" },
            Length(w)
        ),
    )
    .label(slicing, "tracks")
    .help("short tracks overheat and pile up: a footprint without narrow ends, or tracks along its longer side (`scan`)")
}

/// A state the checker's checks should have made impossible.
pub fn internal(what: &str) -> Diagnostics {
    Diagnostic::error(
        Code::NonFinite,
        format!("variable slicing cannot go on: {what}"),
    )
    .help("this is a bug in lmdc for this input; please report it with the .lmd file")
    .into()
}

/// What is wrong with the top at a point where a track runs.
pub enum BadTop {
    /// A height, not above the substrate.
    NotPositive(f64),
    /// Not a finite number.
    NotFinite,
    /// Its expression failed there (the errors follow).
    Failed,
    /// A target mesh with no face over the point.
    OffTarget,
    /// A target solid of the file (named) with no part over the point.
    OffSolid(String),
}

/// The top is not a positive height at `p` (and at `more` other points);
/// `inner` holds what failed when it could not be computed.
pub fn bad_top(p: [f64; 2], more: usize, bad: BadTop, inner: bool, at: TopAt<'_>) -> Diagnostic {
    let p = spot(at.turned, p);
    let others = match more {
        0 => String::new(),
        1 => " (and at 1 other point sampled)".to_string(),
        n => format!(" (and at {n} other points sampled)"),
    };
    let message = match bad {
        BadTop::NotPositive(h) => format!(
            "the top is {} at {p}, where a track runs{others}: every deposited point needs a height above the substrate",
            Length(h)
        ),
        BadTop::NotFinite => format!("the top is not a finite number at {p}{others}"),
        BadTop::Failed => format!("the top cannot be computed at {p}{others}"),
        BadTop::OffTarget => {
            format!("the target mesh has no face over {p}, where a track runs{others}")
        }
        BadTop::OffSolid(ref name) => format!(
            "the target solid `{name}` has no part over {p}, where a track runs{others}"
        ),
    };
    let what = at.what;
    let help = if matches!(bad, BadTop::OffTarget) {
        format!("a target mesh is the part as designed, and its faces must cover the {what} seen from above: check its `at` and `turn`, or keep the {what} within it")
    } else if matches!(bad, BadTop::OffSolid(_)) {
        format!("a target solid is the part as designed, and seen from above it must cover the {what}: make its shape reach over the {what}, or keep the {what} within it")
    } else if inner {
        "the top is the finished part's height above the substrate, computed at every point a track runs through: the error below says what failed there".to_string()
    } else {
        format!("the top is the finished part's height above the substrate: make it positive over the whole {what}")
    };
    Diagnostic::error(Code::TopHeight, message)
        .label(at.top, "the top")
        .label(at.shape, format!("the {what}"))
        .help(help)
}

/// A track whose height tolerance needs segments shorter than min_length:
/// the worst track's numbers and the tolerance that works on every track.
pub struct TooShortSegments {
    /// The declared tolerance.
    pub tolerance: Length,
    /// The minimum segment length (declared, or the bead width).
    pub min_length: Length,
    /// Whether `min_length` was declared.
    pub min_declared: bool,
    /// The worst track's length.
    pub length: Length,
    /// The worst track's place across the scan (axis name, mm), when there are several.
    pub place: Option<(&'static str, f64)>,
    /// For a fill planned turned, the part's point at the worst track's
    /// middle, named instead of its place in the turned frame.
    pub through: Option<[f64; 3]>,
    /// How many tracks fail, of how many.
    pub failing: usize,
    /// How many tracks a layer has.
    pub tracks: usize,
    /// The worst track's error.
    pub error: SegmentError,
    /// The tolerance that works on every track, mm.
    pub fix: f64,
    /// The segments the worst track gets at that tolerance, if it was tried.
    pub fix_segments: Option<usize>,
    /// Where the tolerance, the minimum length and the top are.
    pub spans: [Span; 3],
}

/// Segments shorter than the controller's minimum (`lmd::segments-too-short`).
pub fn segments_too_short(t: &TooShortSegments) -> Diagnostic {
    let (tol, min_length, length) = (t.tolerance, t.min_length, t.length);
    let place = match (t.through, t.place) {
        (Some(p), _) => format!(" through {}", p3(p)),
        (None, Some((axis, c))) => format!(" at {axis} = {} mm", short(c)),
        (None, None) => String::new(),
    };
    let others = match t.failing {
        1 => String::new(),
        n => format!(" ({n} of the {} tracks need segments that short)", t.tracks),
    };
    let message = match t.error {
        SegmentError::TooShort(e) => match e.needed {
            Some((m, len)) => format!(
                "a height tolerance of {tol} needs {m} segments of {len} on the {length} track{place}, shorter than min_length {min_length}{others}"
            ),
            None => format!(
                "a height tolerance of {tol} needs more than {MAX_SEGMENTS} segments on the {length} track{place}, shorter than min_length {min_length}{others}"
            ),
        },
        SegmentError::TooMany { .. } => format!(
            "a height tolerance of {tol} needs more than {MAX_SEGMENTS} segments on the {length} track{place}{others}"
        ),
    };
    let works = match t.fix_segments {
        Some(m) => format!(
            "`tolerance = {} mm` works ({m} segments of {} on that track)",
            short(t.fix),
            Length(length.0 / m as f64)
        ),
        None => format!("`tolerance = {} mm` works", short(t.fix)),
    };
    Diagnostic::error(Code::SegmentsTooShort, message)
        .label(t.spans[0], format!("tolerance {tol}"))
        .label(
            t.spans[1],
            if t.min_declared {
                format!("min_length {min_length}")
            } else {
                format!("min_length: the bead width {min_length}")
            },
        )
        .label(t.spans[2], "the top the segments follow")
        .help(format!(
            "{works}, or a lower `min_length` if the controller can change speed that often"
        ))
}

/// A track of a variable layer that no speed of the bead lets fill its
/// strip.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UnfillableTrack {
    /// Its line across the scan axis, mm.
    pub across: f64,
    /// The point along it where the speed is farthest outside the bead's,
    /// mm along the scan axis.
    pub along: f64,
    /// The strip it fills, mm.
    pub pitch: f64,
    /// The layer height it must lay there, mm.
    pub height: f64,
    /// The speed that would lay it, mm/s.
    pub speed: f64,
    /// What it raises over the bead's speeds (fastest, slowest), mm.
    pub rises: [f64; 2],
}

/// What [`unfillable`] says.
#[derive(Clone, Copy, Debug)]
pub struct Unfillable<'a> {
    /// The worst track.
    pub track: UnfillableTrack,
    /// The layer count it was found at (the last one tried).
    pub layers: u32,
    /// The bead's name.
    pub bead: &'a str,
    /// Its speeds, mm/s.
    pub speeds: [f64; 2],
    /// Its width, mm.
    pub width: f64,
    /// Whether the count was declared.
    pub declared: bool,
    /// For a fill planned turned, the part's point of the track where its
    /// speed is farthest out, named instead of its line in the turned
    /// frame.
    pub through: Option<[f64; 3]>,
    /// The slicing block, the footprint, the bead's speeds.
    pub spans: [Span; 3],
}

/// No layer count lets every track of a variable layer lay its height at
/// the spacing the layout gives it.
pub fn unfillable(u: &Unfillable<'_>) -> Diagnostic {
    let t = &u.track;
    let [lo, hi] = u.speeds;
    let (dir, near) = if t.speed < lo {
        ("slower than", lo)
    } else {
        ("faster than", hi)
    };
    let track = match u.through {
        Some(p) => format!("through {}", p3(p)),
        None => format!("{} mm across", short(t.across)),
    };
    let counts = if u.declared {
        format!("with the declared {} layers", u.layers)
    } else {
        format!("no layer count fits these tracks: with {} layers", u.layers)
    };
    Diagnostic::error(
        Code::NoLayerCount,
        format!(
            "{counts}, the track {track} fills a strip {} mm wide and must raise its layer {} mm: that needs {} mm/s, {dir} bead `{}` holds ({} mm/s); over its speeds it raises that strip {} .. {} mm",
            short(t.pitch),
            short(t.height),
            short(t.speed),
            u.bead,
            short(near),
            short(t.rises[0]),
            short(t.rises[1]),
        ),
    )
    .label(u.spans[0], "the layers and the tracks' spacing")
    .label(u.spans[1], "footprint")
    .label(u.spans[2], "the bead's speeds")
    .help(format!(
        "the tracks' spacing is set to close on the footprint's far edge: a footprint whose width across the tracks fits the balanced spacing, an `offset` between {} and {} mm, or a bead measured over a wider speed range would lay it",
        short(0.3 * u.width),
        short(u.width)
    ))
}

/// A target mesh with a face between its top and the base at `p`: an
/// overhang (heights `[top, under, base]`, mm), at `more` other points too;
/// `reach` the least tilt that builds it, if one does. Planned `turned`,
/// the points are named in the part and no tilt is searched: the fill is
/// already along its direction.
pub fn undercut(
    p: [f64; 2],
    [top, under, base]: [f64; 3],
    more: usize,
    solid: Option<&str>,
    at: Span,
    reach: Option<[f64; 2]>,
    turned: Option<&TurnedFrame>,
) -> Diagnostic {
    let others = match more {
        0 => String::new(),
        1 => " (and at 1 other point sampled)".to_string(),
        n => format!(" (and at {n} other points sampled)"),
    };
    let (what, under_is) = match solid {
        Some(name) => (format!("target solid `{name}`"), "its underside runs"),
        None => ("target".to_string(), "a face of it runs"),
    };
    let tilt = match (turned, reach) {
        (Some(_), _) => String::new(),
        (None, Some([t, a])) => format!(
            "; along a build direction tilted {}° from vertical toward {}° (from +x, counter-clockwise), the line through the underside here runs in the target down to the scan and leaves it once above: layers laid along it would stand on each other here",
            short(t),
            short(a),
        ),
        (None, None) => "; no build direction within 85° of vertical puts the underside here on metal below it: no tilt builds it".to_string(),
    };
    let help = match (turned, reach) {
        (Some(_), _) => "layers laid along the build direction stand on each other only where its line meets the target in one piece from the scan up, and here it meets it in two: build the part to the overhang's underside, and the overhang in a later step along its own direction",
        (None, Some(_)) => "these layers are laid from above with the nozzle vertical, so they would fill under the overhang: `direction = auto` in `slicing variable` plans the fill along the least tilted direction that builds every point of the footprint, within the bead's measured `tilt` and each machine's tilt axis (docs/repair.md, *Undercuts*); or build the part to the overhang's underside here, and the overhang in a later step with the part tilted",
        (None, None) => "these layers are laid from above with the nozzle vertical, so they would fill under the overhang, and a ledge over a gap stands on nothing from any side: build the part to the ledge's underside, then the ledge on a support or in a later step with the part turned over",
    };
    Diagnostic::error(
        Code::TopHeight,
        format!(
            "the {what} has an overhang over {}{others}: its top is at {}, but {under_is} at {}, above the base at {}{tilt}",
            spot(turned, p),
            height(turned, p, top),
            height(turned, p, under),
            height(turned, p, base)
        ),
    )
    .label(at, "the target")
    .help(help)
}

/// Why no build direction within the machines' tilt builds a target's
/// overhang (`direction = auto`, docs/repair.md, *Undercuts*).
pub struct Untilted<'a> {
    /// A point (mm, in the part) of the line along the best direction
    /// allowed that does not build: where its upper piece starts
    /// ([`LineFault::Again`]), where it leaves the target over a gap
    /// ([`LineFault::Gap`]), where it meets a flank ([`LineFault::Flank`]),
    /// or where it crosses the finished face ([`LineFault::Nothing`]).
    pub at: [f64; 3],
    /// What that line meets.
    pub meets: LineFault,
    /// The most tilt allowed (deg) and what holds it there.
    pub limit: (f64, &'a str),
    /// The least tilt (deg) and its azimuth (deg from +x) that builds
    /// every point, if one within 85° does.
    pub needs: Option<[f64; 2]>,
    /// `direction = auto`.
    pub direction: Span,
    /// `top = …`.
    pub top: Span,
    /// Whether the scan's faces close a solid, asked what a line meets at
    /// a flank: without that a real step reads as a flank too.
    pub faces: bool,
    /// Whether a line failed at a flank in the search.
    pub flanked: bool,
}

/// What a line along a build direction meets that does not build it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LineFault {
    /// The target, left and entered again above the scan.
    Again,
    /// The scan only below a gap under the target, which contains the
    /// scanned part elsewhere: air beside the part as designed.
    Gap,
    /// The scan on a flank steeper than the line: under the edge of a
    /// part that may overhang itself.
    Flank,
    /// None of the target above the scan, or no scan.
    Nothing,
}

/// `direction = auto` finds no build direction within the machines' tilt
/// along which every line over the footprint meets the target in one
/// piece above the scan.
pub fn untilted(u: &Untilted<'_>) -> Diagnostic {
    let (limit, by) = u.limit;
    let needs = match u.needs {
        Some([t, a]) => format!(
            "; the least tilt that builds every point is {}° toward {}° (from +x, counter-clockwise), {}° more than allowed",
            short(t),
            short(a),
            short(t - limit)
        ),
        None => "; no direction within 85° of vertical builds every point".to_string(),
    };
    let help = match u.needs {
        Some(_) => format!(
            "layers laid along a direction stand on each other only where each line along it meets the target in one piece from the scan up; the tilt is held to {}° by {by}: a machine that tilts the nozzle or the part farther (its tilt axis's limits), with the bead's `tilt` measured that far, would build it; or build the part to the overhang's underside and the overhang in a later step with the part tilted",
            short(limit)
        ),
        None => "no one direction builds every point of the footprint (a ledge over a gap, or overhangs leaning different ways): build the part in steps, first up to the overhangs' undersides, then each overhang along its own direction, with its own footprint, on a scan of the part as the steps before left it (docs/repair.md, *Repairs in steps*)".to_string(),
    };
    // Only where a step could be what stops it.
    let help = if u.faces || !u.flanked {
        help
    } else {
        format!("{help}; this scan's faces close no solid (or it has none), so a face of the part steeper than the build direction reads as a flank that may hide an overhang: a closed mesh of the part (a watertight STL, 3MF or PLY with faces) shows a step the lines meet, and lmdc builds on it")
    };
    let meets = match u.meets {
        LineFault::Again => "leaves the target and enters it again above the scan",
        LineFault::Flank if u.faces => "comes under the scanned part where, seen from above, it rises steeper than the line: the scan's faces show no step there that the line meets in the open, so the part leans out over the line (or the scan has a hole there)",
        LineFault::Flank => "meets the scan on a flank steeper than itself (a face of the scanned part steeper than the build direction), below the flank's top edge: the scan, seen from above, does not show whether the part is there or leans out over the line, which would then pass under it",
        LineFault::Gap => "leaves the target there and meets the scan only below, through air beside the part as designed (the target contains the scanned part elsewhere, so a gap under it is no wear)",
        LineFault::Nothing => "meets none of the target above the scan, or runs off the scan",
    };
    let within = if limit < 1.0 {
        format!("the target's overhangs need a tilted build direction, and {by} holds the nozzle vertical: down it")
    } else {
        format!(
            "no build direction within {}° of vertical builds the target's overhangs: along the best of them",
            short(limit)
        )
    };
    Diagnostic::error(
        Code::TopHeight,
        format!(
            "{within} the line through ({}, {}, {}) mm {meets}{needs}",
            short(u.at[0]),
            short(u.at[1]),
            short(u.at[2]),
        ),
    )
    .label(u.direction, "the build direction searched for")
    .label(u.top, "the target")
    .help(help)
}

/// A diagnostic of a fill planned along a tilted direction, in the frame
/// turned so the direction is up: its points are named in the part (by
/// the message that names them), its heights, `over` and `under` are
/// along the direction.
pub fn in_turned_frame(mut d: Diagnostic, [tilt, azimuth]: [f64; 2]) -> Diagnostic {
    d.message.push_str(&format!(
        " (planned along the build direction tilted {}° toward {}° from +x, counter-clockwise: heights and depths here are measured along it, points are in the part's coordinates)",
        short(tilt),
        short(azimuth)
    ));
    d
}

/// A repair's predicted finish against its top (`lmd::finish`): the worst
/// place below and above it (mm, and where), its RMS, how many places,
/// and the `finish_tolerance` it is held to.
#[derive(Clone, Copy, Debug)]
pub struct FinishOff {
    /// How far below the top it lies at worst, and where, mm.
    pub below: (f64, [f64; 2]),
    /// How far above it it stands at worst, and where, mm.
    pub above: (f64, [f64; 2]),
    /// The RMS of its departure, mm.
    pub rms: f64,
    /// The places it is predicted at.
    pub points: usize,
    /// `finish_tolerance`, mm.
    pub tolerance: f64,
}

/// Without `finish_tolerance`: the predicted finish falls `below` mm short
/// of the top at `p`, more than the `thinnest` layer the bead lays.
pub fn finish_short(below: f64, p: [f64; 2], thinnest: f64, top: Span) -> Diagnostic {
    Diagnostic::warning(
        Code::Finish,
        format!(
            "the finished face this plan lays is predicted to fall {} mm below the top at ({}, {}) mm, more than the thinnest layer the bead lays ({} mm): the part is left short there",
            short(below),
            short(p[0]),
            short(p[1]),
            short(thinnest)
        ),
    )
    .label(top, "the top")
    .help("where a footprint narrows under a bead's width, or a gap is thinner than a layer, the beads lay less than the top asks: a narrower bead lays it, or leave it as stock; `lmdc report` gives the finish and `lmdc preview` colours it; `finish_tolerance = …` in the slicing refuses such a plan")
}

/// The predicted finish off the top by more than `finish_tolerance`
/// (written at `at`; the top at `top`).
pub fn finish_off(f: &FinishOff, at: Span, top: Span) -> Diagnostic {
    let place = |p: [f64; 2]| format!("({}, {}) mm", short(p[0]), short(p[1]));
    let mut off = Vec::new();
    if f.below.0 > f.tolerance {
        off.push(format!(
            "falls {} mm below the top at {}",
            short(f.below.0),
            place(f.below.1)
        ));
    }
    if f.above.0 > f.tolerance {
        off.push(format!(
            "stands {} mm above the top at {}",
            short(f.above.0),
            place(f.above.1)
        ));
    }
    let mut help = vec!["the face departs from the top where a segment holds one speed over heights that differ along it (a smaller `segments { tolerance }` cuts shorter ones) and where tracks shorter than the bead lay less at their rounded ends (`lmd::short-track`; a narrower bead lays them)".to_string()];
    if f.below.0 > f.tolerance {
        help.push(format!(
            "to machine it back to the design, build to a `top` at least {} mm above the designed face and hold the finish to that stock (`finish_tolerance`): the face then stays above the design everywhere",
            short(f.below.0)
        ));
    }
    help.push(
        "`lmdc report` without `finish_tolerance` gives the finish, and `lmdc preview` colours the face by its departure; a larger `finish_tolerance` allows more"
            .to_string(),
    );
    Diagnostic::error(
        Code::Finish,
        format!(
            "the finished face this plan lays {}, more than the `finish_tolerance` of {} mm (its bead model's surface at {} places along the last layer's tracks, RMS {} mm)",
            off.join(" and "),
            short(f.tolerance),
            f.points,
            short(f.rms)
        ),
    )
    .label(at, "the tolerance")
    .label(top, "the top")
    .help(help.join("; "))
}

/// `finish_tolerance` on a plan whose finish cannot be predicted (no
/// track the prediction reads): it cannot be held.
pub fn finish_unknown(at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Finish,
        "this plan's finish cannot be predicted (no straight track of its last layer to predict it along), so `finish_tolerance` cannot be held",
    )
    .label(at, "the tolerance")
    .help("`lmdc report` gives no finish for this plan either: leave `finish_tolerance` out and check the finished face on the part")
}
