//! What the checker says about the style table (`style NAME { … when { … } }`),
//! the rules that pick a style's tracks, `inheritance { band, hit }`, and each
//! style's values against the bead model and the laser.

use crate::diag::message::value::Got;
use crate::diag::{Code, Diagnostic};
use crate::span::Span;
use crate::units::{short, Length, Power, Speed};

/// A file has more styles than a table may hold (`max`).
pub fn too_many_styles(count: usize, max: usize, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::TooManyStyles,
        format!("{count} styles are more than the {max} a table may hold"),
    )
    .label(at, "one too many")
    .help("style ids are 1 ..= 65535 (0 is the process block)")
}

/// A style's name is not a word.
pub fn bad_style_name(name: &str, at: Span) -> Diagnostic {
    Diagnostic::error(Code::StyleName, format!("`{name}` is not a style name"))
        .label(at, "not a name")
        .help("a style's name is a word of letters, digits and `_`, e.g. `style outer_edge { … }`")
}

/// Two styles ask for the same id.
pub fn duplicate_id(id: u16, at: Span, prev: Span) -> Diagnostic {
    Diagnostic::error(Code::DuplicateId, format!("style id {id} is used twice"))
        .label(at, "second use")
        .label(prev, "first use")
        .help("give every style its own id")
}

/// A style (`what`) sets neither power, speed nor powder.
pub fn no_process_value(what: &str, at: Span) -> Diagnostic {
    Diagnostic::warning(Code::Unused, format!("{what} sets no process value"))
        .label(at, "its tracks get the process block's values")
        .help("give it `power`, `speed` or both")
}

/// A style's colour is not `#rrggbb`.
pub fn bad_colour(colour: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::BadChoice,
        format!("`{colour}` is not a colour `#rrggbb`"),
    )
    .label(at, "not a colour")
    .help("write six hex digits, e.g. `colour = \"#d62728\"`")
}

/// A style (`what`) has no `when` block.
pub fn picks_no_tracks(what: &str, at: Span) -> Diagnostic {
    Diagnostic::error(Code::MissingField, format!("{what} picks no tracks"))
        .label(at, "no `when { … }` block")
        .help("add a rule, e.g. `when { paths = outer_contour }`; several `when` blocks pick the tracks any of them picks")
}

/// A rule's `corner_angle` (`deg` degrees) is not in (0°, 180°].
pub fn corner_angle_range(deg: f64, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::CornerAngle,
        "`corner_angle` must be more than 0 deg and at most 180 deg",
    )
    .label(at, format!("this is {} deg", short(deg)))
    .help("a corner's angle is how far the boundary turns there")
}

/// A rule's `corner_angle` is given without `near_corner`.
pub fn corner_angle_unused(at: Span) -> Diagnostic {
    Diagnostic::warning(
        Code::Unused,
        "`corner_angle` does nothing without `near_corner`",
    )
    .label(at, "unused")
    .help("add `near_corner = 3 mm` or remove `corner_angle`")
}

/// A rule's `layers` is a range of plain numbers `lo .. hi` that are not
/// layer numbers in order.
pub fn bad_layers_range(lo: f64, hi: f64, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::LayersRange,
        "`layers` must be a range of layer numbers `first .. last`, counted from 1",
    )
    .label(at, format!("this is {} .. {}", short(lo), short(hi)))
    .help("e.g. `layers = 1 .. 3` for the first three layers")
}

/// A rule's `layers` is not a range of plain numbers.
pub fn layers_not_range(got: Got<'_>, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::ExpectedRange,
        "`layers` must be a range of layer numbers",
    )
    .label(at, format!("this is {}", got.describe()))
    .help("e.g. `layers = 1 .. 3` for the first three layers")
}

/// A `when` block is written empty.
pub fn empty_rule(at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::MissingField,
        "an empty `when` block picks every track",
    )
    .label(at, "no condition")
    .help("set values for every track in `process`; here say which tracks, e.g. `paths = infill`")
}

/// A rule asks for tracks shorter than `below` and at least `above` long.
pub fn lengths_exclude(below: Length, above: Length, at: Span) -> Diagnostic {
    Diagnostic::warning(
        Code::Unused,
        format!("no track is shorter than {below} and at least {above} long"),
    )
    .label(at, "this `when` block picks nothing")
    .help("for tracks shorter than one length or longer than another, write two `when` blocks")
}

/// An `inheritance` statement is not written as a block without a name.
pub fn inheritance_shape(at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Syntax,
        "an `inheritance` statement is written `inheritance { band = …  hit = … }`",
    )
    .label(at, "not in that shape")
    .help("e.g. `inheritance { band = 0.8 mm  hit = 99 % }`")
}

/// `hit` (the share `h`) is not in (0 %, 100 %].
pub fn hit_range(h: f64, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::HitRange,
        "`hit` is the share of a track inside the band: more than 0 % and at most 100 %",
    )
    .label(at, format!("this is {} %", short(h * 100.0)))
    .help("the paper uses 99 %")
}

/// The kind of solid or layers that has no styles.
#[derive(Clone, Copy, Debug)]
pub enum Unstyled {
    /// A loft: one track a layer.
    Loft,
    /// A ring: its table sets each segment's process.
    Ring,
    /// Variable layers: speeds from the bead model.
    Variable,
    /// A wall along an open path: the same beads every layer.
    Wall,
}

/// Styles are declared for a solid or layers that have none.
pub fn styles_unsupported(kind: Unstyled, at: Span) -> Diagnostic {
    let (message, help) = match kind {
        Unstyled::Loft => (
            "styles pick tracks of planar layers; a loft's wall is one track a layer",
            "schedule the wall's power in `process` (e.g. `power = ramp(…)`)",
        ),
        Unstyled::Wall => (
            "styles pick tracks of filled planar layers; a wall along a path lays the same beads on every layer",
            "schedule the wall's power in `process` (e.g. `power = ramp(…)`)",
        ),
        Unstyled::Ring => (
            "styles pick tracks of planar layers; a ring's table sets each segment's process",
            "remove the style and give the segments their values in the ring's `table`",
        ),
        Unstyled::Variable => (
            "styles pick tracks of planar layers; variable layers take every speed from the bead model",
            "remove the style: each segment's speed lays its height, and the power is the process block's (`power = ramp(…)` schedules it over the layers)",
        ),
    };
    Diagnostic::error(Code::Unsupported, message)
        .label(at, "style")
        .help(help)
}

/// `inheritance` is given but no style.
pub fn inheritance_without_styles(at: Span) -> Diagnostic {
    Diagnostic::warning(Code::Unused, "inheritance without styles does nothing")
        .label(at, "no style to inherit")
        .help("declare `style NAME { … }` or remove `inheritance`")
}

/// Raster tracks turn `turn` degrees a layer, so they inherit no style.
pub fn raster_turns_away(turn: f64, at: Span) -> Diagnostic {
    Diagnostic::warning(
        Code::Unused,
        format!(
            "raster tracks turn {} deg a layer, so they cross the layer below's styled tracks and do not inherit their styles",
            short(turn)
        ),
    )
    .label(at, "inheritance")
    .help("inheritance follows tracks laid the same way as the layer below: rotate by 0 or 180 deg, or pick the tracks by rules on every layer")
}

/// The bead model a style's speed is checked against.
pub struct StyleBead<'a> {
    /// Its name.
    pub name: &'a str,
    /// The speeds it holds for, and where they are written.
    pub speed: ([Speed; 2], Span),
    /// The heights it allows, and where they are written.
    pub height: ([Length; 2], Span),
}

/// A style's speed `v` is outside the bead model's speeds.
pub fn style_speed_outside_bead(
    style: &str,
    v: Speed,
    at: Span,
    bead: &StyleBead<'_>,
) -> Diagnostic {
    let [lo, hi] = bead.speed.0;
    Diagnostic::error(
        Code::StyleSpeed,
        format!(
            "style `{style}` scans at {v}, outside the {lo} .. {hi} bead `{}` is valid for",
            bead.name
        ),
    )
    .label(at, "style speed")
    .label(bead.speed.1, "bead model's speeds")
    .help("choose a speed the bead model covers, or measure the bead at this speed")
}

/// A style's speed `v` lays a bead `h` high, outside the allowed heights.
pub fn style_height_outside_bead(
    style: &str,
    v: Speed,
    h: Length,
    at: Span,
    bead: &StyleBead<'_>,
) -> Diagnostic {
    let [lo, hi] = bead.height.0;
    Diagnostic::error(
        Code::StyleSpeed,
        format!(
            "style `{style}` scans at {v}, where bead `{}` is {h} high: outside its allowed {lo} .. {hi}",
            bead.name
        ),
    )
    .label(at, "style speed")
    .label(bead.height.1, "allowed heights")
    .help("a speed whose bead height lies in the allowed range keeps the layer level")
}

/// A style's power `p` is outside the laser's range `range`, written at
/// `range_at` (`None`: the range is the process power alone, at `power_at`).
pub fn style_power_outside_laser(
    style: &str,
    p: Power,
    at: Span,
    range: [Power; 2],
    range_at: Option<Span>,
    power_at: Span,
) -> Diagnostic {
    let [lo, hi] = range;
    Diagnostic::error(
        Code::StylePower,
        format!("style `{style}` sets {p}, outside the laser's range {lo} .. {hi}"),
    )
    .label(at, "style power")
    .label(
        range_at.unwrap_or(power_at),
        match range_at {
            Some(_) => "the laser's range",
            None => "the range is this power alone",
        },
    )
    .help(match range_at {
        Some(_) => "widen `power_range` if the laser allows it, or change the style's power",
        None => "declare the laser's range in `process`, e.g. `power_range = 1000 W .. 3000 W`",
    })
}
