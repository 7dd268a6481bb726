//! What the slicer says about layers it cannot make or fill, and what it
//! found worth a look in those it made.

use crate::diag::{Code, Diagnostic};
use crate::fill::pitch::Apart;
use crate::fill::{FillError, Gap};
use crate::span::Span;
use crate::units::{short, Length, Speed};

/// `"s"` unless `n` is 1.
fn plural(n: usize) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}

/// The fill of all layers together needs more than `max` points.
pub fn too_many_fill_points(max: usize, slicing: Span) -> Diagnostic {
    Diagnostic::error(
        Code::TooManyPoints,
        format!("the fill needs more than {max} points"),
    )
    .label(slicing, "slicing")
    .help("use fewer layers or a larger chord error")
}

/// What [`too_many_planned_points`] says: a planar plan's layers, the
/// raster's spacing and the fewest points its raster and contours lay.
pub struct PointBudget {
    /// How many layers.
    pub layers: usize,
    /// The raster lines' spacing.
    pub offset: Length,
    /// The fewest points the raster and the contours lay over all layers.
    pub least: f64,
    /// The contours' part of it.
    pub contours: f64,
    /// The most a plan may hold.
    pub max: usize,
}

/// A planar plan whose raster and contours lay at least `b.least` points,
/// more than a plan may hold, found before any layer is filled.
pub fn too_many_planned_points(b: PointBudget, slicing: Span) -> Diagnostic {
    let share = b.max as f64 / b.least;
    let layers = (b.layers as f64 * share).floor();
    let message = if b.contours > 0.0 {
        format!(
            "the contours and raster of these {} layers, lines {} apart, lay at least {:.0} points ({:.0} of them the contours'), more than the {} a plan may hold",
            b.layers, b.offset, b.least, b.contours, b.max
        )
    } else {
        format!(
            "the raster of these {} layers, lines {} apart, lays at least {:.0} points, more than the {} a plan may hold",
            b.layers, b.offset, b.least, b.max
        )
    };
    // The raster's points go as one over its spacing; the contours' do not.
    let raster = b.least - b.contours;
    let room = b.max as f64 - b.contours;
    let spacing = if raster > 0.0 && room > 0.0 {
        format!(
            ", or lines about {} apart (`offset`)",
            Length(b.offset.0 * raster / room)
        )
    } else {
        ", or fewer contours or a larger chord error".to_string()
    };
    Diagnostic::error(Code::TooManyPoints, message)
        .label(slicing, "slicing")
        .help(format!(
            "at most {layers:.0} layers of this profile fit{spacing}; or a smaller profile"
        ))
}

/// The spans a fill's findings point at: the extruded shape and the slicing.
#[derive(Clone, Copy)]
pub struct FillAt {
    /// The shape extruded.
    pub shape: Span,
    /// The slicing statement.
    pub slicing: Span,
}

/// A spot farther than a bead width from every track, on `layers` layers
/// (the first on layer `k`, from 0).
pub fn fill_gap(layers: usize, k: usize, g: &Gap, w: f64, at: FillAt) -> Diagnostic {
    Diagnostic::error(
        Code::FillGap,
        format!(
            "the tracks leave a spot unfilled on {} layer{}: on layer {}, ({}, {}) mm is {} from the nearest track, more than the bead width {}",
            layers,
            plural(layers),
            k + 1,
            short(g.at[0]),
            short(g.at[1]),
            Length(g.distance),
            Length(w)
        ),
    )
    .label(at.shape, "this shape")
    .label(at.slicing, "fill")
    .help("raster lines miss parts of a profile narrower than the offset, and line ends reach at most `extend` past their neighbours: a smaller offset, a larger `extend`, a contour pass or another raster angle fills them")
}

/// Neighbouring tracks farther apart than the bead `w` on `layers` layers
/// (the widest, `a`, on layer `k`).
pub fn tracks_apart(layers: usize, k: usize, a: &Apart, w: f64, at: FillAt) -> Diagnostic {
    Diagnostic::error(
        Code::FillGap,
        format!(
            "neighbouring tracks run farther apart than the bead is wide on {} layer{}: on layer {}, at ({}, {}) mm, {} apart over {}, leaving a strip {} wide that neither {} bead covers",
            layers,
            plural(layers),
            k + 1,
            short(a.at[0]),
            short(a.at[1]),
            Length(a.apart),
            Length(a.length),
            Length(a.apart - w),
            Length(w)
        ),
    )
    .label(at.shape, "this shape")
    .label(at.slicing, "fill")
    .help(format!(
        "a raster's last track lies up to an offset and a half from the contour where the profile is not a whole number of offsets wide, and contours round a narrow part may run more than a bead apart: tracks at most {} apart close the strip (a smaller offset, another raster angle, a contour less or more)",
        Length(w)
    ))
}

/// Spots no bead reaches on `layers` layers (the farthest on layer `k`).
pub fn thin_gap(layers: usize, k: usize, g: &Gap, w: f64, at: FillAt) -> Diagnostic {
    Diagnostic::warning(
        Code::ThinGap,
        format!(
            "no bead reaches some spots on {} layer{}: the farthest, on layer {}, is ({}, {}) mm, {} from the nearest track centre line (a bead reaches {})",
            layers,
            plural(layers),
            k + 1,
            short(g.at[0]),
            short(g.at[1]),
            Length(g.distance),
            Length(w / 2.0)
        ),
    )
    .label(at.shape, "this shape")
    .label(at.slicing, "fill")
    .help("often the strip the raster leaves at its far edge when the profile is not a whole number of offsets wide; a contour pass, a width of whole offsets, or a smaller offset closes it")
}

/// A contour pass whose sides run `thickness` apart on layer `k`.
pub fn contour_sliver(k: usize, thickness: f64, w: f64, at: FillAt) -> Diagnostic {
    Diagnostic::warning(
        Code::Overlap,
        format!(
            "a contour pass on layer {} is a sliver whose sides run {} apart, {:.0} % of the {} bead: it piles up",
            k + 1,
            Length(thickness),
            100.0 * thickness / w,
            Length(w)
        ),
    )
    .label(at.shape, "this shape")
    .label(at.slicing, "contours")
    .help("the profile narrows to less than the passes need there; fewer contours, or a raster for the middle")
}

/// A style that no track of any layer takes.
pub fn unused_style(name: &str, style: Span) -> Diagnostic {
    Diagnostic::warning(
        Code::Unused,
        format!("style `{name}` picks no track on any layer"),
    )
    .label(style, "never applied")
    .help("an earlier style may take its tracks first (the first style in the file wins), or no track meets its `when`")
}

/// Fewer contour passes than asked fit on layer `k`.
pub fn few_contours(passes: usize, asked: usize, k: usize, slicing: Span) -> Diagnostic {
    Diagnostic::warning(
        Code::FewContours,
        format!(
            "only {passes} of the {asked} contour passes fit inside the profile on layer {}",
            k + 1
        ),
    )
    .label(slicing, "contours")
    .help("the profile is narrower there than the passes need; fewer contours, or a raster inside them")
}

/// `count` tracks shorter than a bead (the first on layer `first`).
pub fn short_tracks(count: usize, w: f64, first: usize, slicing: Span) -> Diagnostic {
    Diagnostic::warning(
        Code::ShortTrack,
        format!(
            "{} track{} shorter than the bead width {} (first on layer {})",
            count,
            if count == 1 { " is" } else { "s are" },
            Length(w),
            first + 1
        ),
    )
    .label(slicing, "fill")
    .help(
        "short tracks overheat and pile up: a slower or cooler style, or a profile without slivers",
    )
}

/// Where a layer's fill failed: the layer (from 0), whether its profile
/// changes from layer to layer, and the spans of the shape, the profile and
/// the fill.
pub struct FillLayer {
    /// The layer, from 0.
    pub k: usize,
    /// Whether the profile changes with `layer` (the error then says the
    /// builtin's value).
    pub varies: bool,
    /// The outline's shape.
    pub shape: Span,
    /// The profile extruded.
    pub profile: Span,
    /// The slicing statement.
    pub slicing: Span,
}

/// A layer whose fill failed.
pub fn fill_error(e: &FillError, l: &FillLayer) -> Diagnostic {
    let k = l.k;
    match e {
        FillError::SelfIntersecting { at } => Diagnostic::error(
            Code::SelfIntersecting,
            format!(
                "the profile crosses itself at ({}, {}) mm on layer {}{}",
                short(at[0]),
                short(at[1]),
                k + 1,
                // The builtin's value, for a profile that follows it.
                if l.varies {
                    format!(" (layer = {k})")
                } else {
                    String::new()
                }
            ),
        )
        .label(l.shape, "this outline's edges cross")
        .label_opt(
            (l.profile != l.shape).then_some(l.profile),
            "extruded here",
        )
        .help("reorder the outline's points so its edges do not cross; if its numbers use `layer`, check them at that layer"),
        FillError::Empty => Diagnostic::error(
            Code::FillEmpty,
            format!("no track fits in the profile on layer {}", k + 1),
        )
        .label(l.profile, "profile")
        .label(l.slicing, "fill")
        .help("the profile is narrower than the bead and its contour passes; make it larger or use fewer contours"),
        other => Diagnostic::error(
            Code::Fill,
            format!("layer {} cannot be filled: {other}", k + 1),
        )
        .label(l.profile, "profile")
        .label(l.slicing, "fill"),
    }
}

/// The profile, which follows `layer`, is not a shape on layer `k`; the
/// profile's own errors follow this one.
pub fn profile_invalid_on_layer(k: usize, profile: Span) -> Diagnostic {
    Diagnostic::error(
        Code::ProfileLayer,
        format!(
            "the profile is not a valid shape on layer {} (layer = {k})",
            k + 1
        ),
    )
    .label(profile, "profile")
    .help("see the error below; the profile's numbers change with `layer`")
}

/// A height that needs more than `max` layers of `lift`.
pub fn too_many_layers(height: Length, lift: Length, max: usize, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::TooManyPoints,
        format!("{height} in layers of {lift} is more than {max} layers"),
    )
    .label(at, "height")
}

/// `n` whole layers of `lift` build `built`, not the `height` asked for.
pub fn height_rounded(n: usize, lift: Length, built: f64, height: Length, at: Span) -> Diagnostic {
    Diagnostic::warning(
        Code::HeightRounded,
        format!(
            "{n} layers of {lift} build {}: the {height} asked for and {} more",
            Length(built),
            Length(built - height.0)
        ),
    )
    .label(at, "height")
    .help("layers come whole: give `layers` in the slicing block instead, or a height that is a multiple of the layer height")
}

/// A profile whose pieces over all layers pass `max`.
pub fn too_much_profile(max: usize, profile: Span) -> Diagnostic {
    Diagnostic::error(
        Code::TooManyPoints,
        format!("the profile's pieces over all layers come to more than {max}"),
    )
    .label(profile, "profile")
    .help("fewer layers, or an outline of fewer pieces (an arc is one piece)")
}

/// How a layer's rise follows from its bead, in words.
fn lift_rule(overlapped: bool) -> &'static str {
    if overlapped {
        "A/d: the bead's cross-section A spread over the track offset d"
    } else {
        "A/w: one track a layer, its cross-section A spread over its width w"
    }
}

/// A bead model's name and the heights it lays, with where they are declared.
pub struct BeadHeights<'a> {
    /// The bead's name.
    pub name: &'a str,
    /// h_min and h_max.
    pub height: [Length; 2],
    /// Where the heights are declared.
    pub span: Span,
}

/// A declared layer height outside the bead's heights; the tracks lay `laid`.
pub fn declared_height_outside(
    l: Length,
    laid: Length,
    bead: &BeadHeights,
    at: Span,
) -> Diagnostic {
    Diagnostic::error(
        Code::LayerHeight,
        format!(
            "layers {} high are outside the {} .. {} bead `{}` can lay",
            l, bead.height[0], bead.height[1], bead.name
        ),
    )
    .label(at, "declared layer height")
    .label(bead.span, "the bead's heights")
    .help(format!(
        "`layer_height = auto` gives {laid}, what these tracks lay"
    ))
}

/// A declared layer height that is not what the tracks lay: the standoff
/// drifts by the difference every layer.
pub fn lift_mismatch(l: Length, laid: Length, overlapped: bool, at: Span) -> Diagnostic {
    Diagnostic::warning(
        Code::LiftMismatch,
        format!(
            "layers {} high, but these tracks lay {} a layer ({}): the standoff changes by {} a layer",
            l,
            laid,
            lift_rule(overlapped),
            Length((laid.0 - l.0).abs()),
        ),
    )
    .label(at, "declared layer height")
    .help(format!(
        "`layer_height = auto` uses {laid}; keep a declared height only if the process is controlled to it"
    ))
}

/// What would make the tracks lay an allowed height.
pub enum LiftFix {
    /// Overlapped tracks: offsets in this range (mm), for the cross-section A (mm²).
    Offsets {
        /// The offsets, mm.
        range: [f64; 2],
        /// The bead's cross-section, mm².
        area: f64,
    },
    /// One track a layer of a measured bead: only overlap.
    Measured,
    /// One track a layer: scan speeds in this range (mm/s).
    Speeds([f64; 2]),
    /// One track a layer, and no speed in the bead's range does it.
    NoSpeed,
}

/// `layer_height = auto` gives a rise `laid` outside the bead's heights;
/// `slicing` is what sets the tracks (the offset when overlapped).
pub fn derived_height_outside(
    laid: Length,
    overlapped: bool,
    bead: &BeadHeights,
    slicing: Span,
    fix: &LiftFix,
) -> Diagnostic {
    let [lo, hi] = bead.height;
    let overlap = "or overlap tracks (contours > 1 or a raster) so the layer rises by A/d";
    let help = match fix {
        LiftFix::Offsets { range, area } => format!(
            "tracks {} .. {} apart lay an allowed height (A/d with A = {} mm²)",
            Length(range[0]),
            Length(range[1]),
            short(*area)
        ),
        LiftFix::Measured => {
            format!("a measured bead has the one height it was measured with; {overlap}")
        }
        LiftFix::Speeds([a, b]) => format!(
            "one track a layer rises by A/w: scan at {} .. {} for that, {overlap}",
            Speed(*a),
            Speed(*b)
        ),
        LiftFix::NoSpeed => {
            format!("no speed in the bead's range lays an allowed A/w; {overlap}")
        }
    };
    Diagnostic::error(
        Code::LayerHeight,
        format!(
            "these tracks lay {} a layer ({}), outside the {} .. {} bead `{}` allows",
            laid,
            lift_rule(overlapped),
            lo,
            hi,
            bead.name
        ),
    )
    .label(
        slicing,
        if overlapped {
            "track offset"
        } else {
            "one track a layer"
        },
    )
    .label(bead.span, "the bead's heights")
    .help(help)
}

/// A ring whose plan would pass the point budget.
pub fn ring_too_large(why: &dyn std::fmt::Display, layers: Span, ring: Span) -> Diagnostic {
    Diagnostic::error(
        Code::TooManyPoints,
        format!("the ring's plan is too large: {why}"),
    )
    .label(layers, "layers")
    .label(ring, "ring")
    .help("use a larger `step`, or fewer layers")
}

/// A style whose `when` asks for layer `layer`, past the part's `layers`.
pub fn style_layer_past_end(
    name: &str,
    layer: impl std::fmt::Display,
    layers: usize,
    style: Span,
) -> Diagnostic {
    Diagnostic::warning(
        Code::Unused,
        format!("style `{name}` asks for layer {layer}, but the part has {layers}"),
    )
    .label(style, "a `when` block that picks nothing")
    .help("layers count from 1 to the last, as in the programs' layer comments")
}

/// `layer_change = spiral` on planar layers that are not one bead wide.
pub fn spiral_not_a_wall(change: Span, contours: usize, infill: bool) -> Diagnostic {
    let what = if infill {
        "an infill".to_string()
    } else {
        format!("{contours} contour passes")
    };
    Diagnostic::error(
        Code::ConflictingFields,
        format!(
            "a spiral layer change climbs round one loop into the next layer, but these layers are {what}"
        ),
    )
    .label(change, "each layer climbs into the next here")
    .help(
        "a spiral is for a wall one bead wide: `contours = 1` and no `infill`; \
         or keep `layer_change = lift`",
    )
}

/// `layer_change = spiral` on a planar wall whose layer `k` (from 0) is not the one
/// loop the layer below climbed into: `loops` loops (a hole or an island
/// adds one), or a profile that changes from layer to layer.
pub fn spiral_needs_one_loop(k: usize, loops: usize, change: Span, profile: Span) -> Diagnostic {
    let why = if loops == 1 {
        "its profile changes from layer to layer, so the climb would not end where the next layer starts".to_string()
    } else {
        format!(
            "layer {} has {loops} loops (holes or islands), and a climb goes on into one",
            k + 1
        )
    };
    Diagnostic::error(
        Code::ConflictingFields,
        format!("a spiral layer change needs one loop, the same on every layer: {why}"),
    )
    .label(change, "each layer climbs into the next here")
    .label(profile, "this profile")
    .help(
        "slice the part as a loft (`slicing normal`, which climbs between changing sections) \
         or keep `layer_change = lift`",
    )
}
