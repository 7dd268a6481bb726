//! What the checker says about the solid a file builds and how it is laid:
//! its pairing with a slicing strategy, an extrusion's height, top, scan
//! speed and track offset, variable and continuous layers, and seams.

use crate::diag::message::value::Got;
use crate::diag::{Code, Diagnostic};
use crate::span::Span;
use crate::units::{short, Angle, Length, Speed};

/// The file has no `loft`, `extrude` or `ring`.
pub fn missing_solid() -> Diagnostic {
    Diagnostic::error(
        Code::MissingSolid,
        "the file does not describe a solid to build",
    )
    .label(Span::new(0, 0), "no `loft`, `extrude` or `ring` here")
    .help("add `loft NAME { from = …  to = …  spine = …  wall = BEAD }`, `extrude NAME { profile = …  bead = BEAD }` or `ring NAME { radius = …  segments = …  table { … } }`")
}

/// The file has a second solid.
pub fn second_solid(at: Span, first: Span) -> Diagnostic {
    Diagnostic::error(Code::SecondSolid, "lmdc builds one solid per file")
        .label(at, "second solid")
        .label(first, "first solid")
        .help("put each part in its own file")
}

/// A solid and a slicing strategy that do not go together.
#[derive(Clone, Copy, Debug)]
pub enum SlicingMismatch<'a> {
    /// A loft sliced with the named strategy (`planar` or `variable`).
    Loft(&'a str),
    /// An extrusion sliced `normal`.
    ExtrusionNormal,
    /// An extrusion without a `top` sliced `variable`.
    ExtrusionVariable,
    /// An extrusion with a `top` sliced `normal`.
    TopExtrusionNormal,
    /// An extrusion with a `top` sliced `planar`.
    TopExtrusionPlanar,
    /// A ring sliced with the named strategy (not `continuous`).
    Ring(&'a str),
    /// A loft or an extrusion sliced `continuous`.
    Continuous,
    /// A wall along a path sliced with the named strategy (not `planar`).
    Wall(&'a str),
    /// A wall on a scan sliced other than `variable`.
    ScanWall(&'a str),
}

/// The solid and the slicing strategy (written at `at`) do not go together.
pub fn slicing_mismatch(m: SlicingMismatch<'_>, at: Span) -> Diagnostic {
    let (message, help) = match m {
        SlicingMismatch::Loft(s) => (
            format!("{s} slicing does not build a loft"),
            "slice a loft with `slicing normal { … }`",
        ),
        SlicingMismatch::ExtrusionNormal => (
            "normal slicing does not build an extrusion".to_string(),
            "slice an extrusion with `slicing planar { … }`",
        ),
        SlicingMismatch::ExtrusionVariable => (
            "variable slicing builds an extrusion up to its `top`, and this one has none".to_string(),
            "add `top = …` to the extrusion (e.g. `top = edges(along = x, from = 20 mm, to = 36 mm)`), or slice it with `slicing planar { … }`",
        ),
        SlicingMismatch::TopExtrusionNormal => (
            "normal slicing does not build an extrusion".to_string(),
            "slice an extrusion with a `top` with `slicing variable { … }`",
        ),
        SlicingMismatch::Ring(s) => (
            format!("{s} slicing does not build a ring"),
            "slice a ring with `slicing continuous { layers = …  layer_height = … }`",
        ),
        SlicingMismatch::Continuous => (
            "continuous slicing builds a ring".to_string(),
            "slice a loft with `slicing normal { … }`, an extrusion with `slicing planar { … }` (or `variable` with a `top`)",
        ),
        SlicingMismatch::Wall(s) => (
            format!("{s} slicing does not build a wall along a path"),
            "slice a wall along a path with `slicing planar { … }`: flat layers, one bead height apart (or, built on a scan with `on = scan(…)`, `slicing variable { … }`)",
        ),
        SlicingMismatch::ScanWall(s) => (
            format!("{s} slicing does not build a wall on a scan"),
            "slice a wall on a scan with `slicing variable { … }`: its layers start on the scanned surface and each lays the same share of the height left to its top",
        ),
        SlicingMismatch::TopExtrusionPlanar => (
            "planar slicing lays flat layers of one height, and this extrusion has a `top`".to_string(),
            "slice it with `slicing variable { … }`, or give it `height = …` instead of `top`",
        ),
    };
    Diagnostic::error(Code::BadChoice, message)
        .label(at, "slicing")
        .help(help)
}

/// An extrusion has both a `height` and a `top`.
pub fn height_and_top(height: Span, top: Span) -> Diagnostic {
    Diagnostic::error(
        Code::ConflictingFields,
        "give the extrusion a `height` or a `top`, not both",
    )
    .label(height, "height: flat layers")
    .label(top, "top: the finished part's height at every point")
    .help("a `top` is built with `slicing variable { … }`, a `height` with `slicing planar { … }`")
}

/// The bead a scan speed is checked against.
pub struct BeadSpeeds<'a> {
    /// The bead model's name.
    pub name: &'a str,
    /// The speeds it holds for (both the one it was measured at, if measured).
    pub speed: [Speed; 2],
    /// Where they are written.
    pub at: Span,
    /// Whether it was measured at one speed.
    pub measured: bool,
}

/// The scan speed `v` (at `at`) is not one the bead model holds for.
pub fn scan_speed_outside_bead(v: Speed, at: Span, bead: &BeadSpeeds<'_>) -> Diagnostic {
    let [lo, hi] = bead.speed;
    let name = bead.name;
    Diagnostic::error(
        Code::ScanSpeed,
        if bead.measured {
            format!("the scan speed {v} is not the {lo} bead `{name}` was measured at")
        } else {
            format!("the scan speed {v} is outside the {lo} .. {hi} bead `{name}` is valid for")
        },
    )
    .label(at, "scan speed")
    .label(bead.at, "the bead model's speeds")
    .help(if bead.measured {
        "a measured bead holds at its own speed: scan at that speed, or measure the bead at this one".to_string()
    } else {
        format!("scan at {lo} .. {hi}, or fit the bead model over the speed you need")
    })
}

/// Planar layers have no scan speed (none in the process block, and the bead
/// was not measured at one).
pub fn no_scan_speed(at: Span) -> Diagnostic {
    Diagnostic::error(Code::MissingField, "planar layers need a scan speed")
        .label(at, "the speed of these layers' tracks is not given")
        .help("add `speed = 6 mm/s` to the process block")
}

/// Both a layer count and an extrusion height are given.
pub fn layers_and_height(layers: Span, height: Span) -> Diagnostic {
    Diagnostic::error(
        Code::ConflictingFields,
        "give the layer count or the height, not both",
    )
    .label(layers, "layers")
    .label(height, "height")
    .help("the other follows from the layer height")
}

/// Neither a layer count nor an extrusion height is given.
pub fn no_height(at: Span) -> Diagnostic {
    Diagnostic::error(Code::MissingField, "how tall is the extrusion?")
        .label(at, "no `height`")
        .help("add `height = 24 mm` here, or `layers = 35` to the slicing block")
}

/// Tracks `d` apart leave gaps with a bead `width` wide (`flat` is the
/// flat-top offset, if known).
pub fn offset_gaps(
    d: Length,
    width: Length,
    at: Span,
    bead: Span,
    flat: Option<Length>,
) -> Diagnostic {
    Diagnostic::error(
        Code::FillGap,
        format!("tracks {d} apart leave gaps: the bead is {width} wide"),
    )
    .label(at, "track offset")
    .label(bead, "bead model")
    .help(match flat {
        Some(f) => {
            format!("use an offset of at most the bead width; {f} keeps the top flat (d = A/h)")
        }
        None => "use an offset of at most the bead width".to_string(),
    })
}

/// Tracks `d` apart overlap so much that a layer of a bead `width` wide
/// piles up (`flat` is the flat-top offset, if known).
pub fn offset_piles_up(d: Length, width: Length, at: Span, flat: Option<Length>) -> Diagnostic {
    Diagnostic::error(
        Code::Overlap,
        format!(
            "tracks {d} apart overlap by {:.0} % of the {width} bead: the layer piles up",
            100.0 * (1.0 - d.0 / width.0),
        ),
    )
    .label(at, "track offset")
    .help(match flat {
        Some(f) => {
            format!("overlaps of about 33 % keep tracks level; d = A/h = {f} gives a flat top")
        }
        None => "overlaps of about 33 % keep tracks level".to_string(),
    })
}

/// The top fails to compute at the point `[x, y]` (mm) of the footprint.
pub fn top_fails_at_point(p: [f64; 2], at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::TopHeight,
        format!(
            "the top cannot be computed at ({}, {}) mm, a point of the footprint",
            short(p[0]),
            short(p[1])
        ),
    )
    .label(at, "the top")
    .help("the top is the finished part's height at every point of the footprint: the error below says what fails there")
}

/// A `top` reads `layer` or `layer_z`.
pub fn top_follows_layer(at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::LayerOutsideProfile,
        "`top` uses `layer` or `layer_z`: the top is one surface for every layer",
    )
    .label(at, "depends on the layer")
    .help("each layer lays the same fraction of the top: write the finished part's height, a function of `x` and `y`")
}

/// A top plane's `at` is not a point.
pub fn top_at_not_point(got: Got<'_>, at: Span) -> Diagnostic {
    Diagnostic::error(Code::ExpectedPoint, "`at` is a point `[x, y]`, two lengths")
        .label(at, format!("this is {}", got.describe()))
        .help("e.g. `at = [0 mm, 0 mm]`")
}

/// A top plane's slope `key` is an angle of 89° or more.
pub fn slope_too_steep(key: &str, angle: Angle, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::OutOfRange,
        format!("`{key}` must be less than 89 deg from the horizontal"),
    )
    .label(at, format!("this is {angle}"))
    .help("a top that steep is a wall: slice it with `slicing normal` or `planar`")
}

/// A process `speed` is given to variable layers (`bead` is the bead's name,
/// if known).
pub fn speed_with_variable(bead: Option<&str>, speed: Span, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::SpeedFromBead,
        match bead {
            Some(b) => format!(
                "variable layers take their speeds from bead `{b}`: a process `speed` does not apply"
            ),
            None => "variable layers take their speeds from the bead model: a process `speed` does not apply".to_string(),
        },
    )
    .label(speed, "process speed")
    .label(at, "variable slicing")
    .help("remove `speed` from the process block: each segment of a track is laid at the speed the bead model gives for its height")
}

/// Variable layers are built with a bead measured at one speed.
pub fn measured_bead_with_variable(name: &str, speed: Speed, bead: Span, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::BeadMapNeeded,
        format!(
            "bead `{name}` was measured at one speed ({speed}): variable layers change the height through the speed"
        ),
    )
    .label(bead, "measured bead")
    .label(at, "variable slicing")
    .help("fit the bead's height over a speed range: `model = linear(slope = -0.135 mm / (1 mm/s), intercept = 1.82 mm)` with `speed = 4 mm/s .. 8.7 mm/s`")
}

/// A footprint under a `top` has holes.
pub fn top_footprint_holes(at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Unsupported,
        "a footprint with holes cannot carry a `top` (yet)",
    )
    .label(at, "has holes")
    .help("variable layers are laid in straight tracks across one outline: build the part with a flat top (`height` and `slicing planar`), or without the holes")
}

/// A footprint under a `top` follows the layer.
pub fn top_footprint_follows_layer(at: Span, profile: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Unsupported,
        "a footprint that changes with `layer` cannot carry a `top`",
    )
    .label(at, "follows the layer")
    .label(profile, "profile")
    .help("variable layers are not planes a profile could be cut at: give one footprint, and let the top shape the part")
}

/// A continuous slicing's step of `deg` degrees is above `max`.
pub fn ring_step_too_large(deg: f64, max: f64, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::OutOfRange,
        format!(
            "a step of {}° cuts the ring into chords that sag too far inside it",
            short(deg)
        ),
    )
    .label(at, format!("at most {max}°"))
    .help("points at most 1° apart follow a ring closely: `step = 1 deg`")
}

/// A seam is none of the forms it takes (`suggestion` is a close word, if any).
pub fn bad_seam(got: Got<'_>, at: Span, suggestion: Option<&str>) -> Diagnostic {
    let d = Diagnostic::error(
        Code::BadChoice,
        "a seam is `lowest`, `sharpest_corner`, an angle, `rotating(…)` or `random(…)`",
    )
    .label(at, format!("this is {}", got.describe()));
    match suggestion {
        Some(m) => d.help(format!("did you mean `{m}`?")),
        None => d.help("e.g. `seam = rotating(step = 90 deg)` moves the start of every contour a quarter turn each layer"),
    }
}
