//! What the checker and the lowering say about `process { thermal { … } }`
//! and the interpass limit (docs/thermal.md).

use crate::diag::message::value::Got;
use crate::diag::{Code, Diagnostic};
use crate::span::Span;
use crate::units::{short, short_up};

/// A temperature `key` (`preheat`, `max_interpass`) not above 0 °C or
/// beyond `max` °C.
pub fn temperature_range(key: &str, value: f64, max: f64, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::OutOfRange,
        format!("`{key}` must be above 0 °C and at most {} °C", short(max)),
    )
    .label(at, format!("this is {} °C", short(value)))
    .help("temperatures are written in degC, e.g. `max_interpass = 200 degC`")
}

/// `absorptivity` not above 0 or above 1.
pub fn absorptivity_range(value: f64, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::OutOfRange,
        "`absorptivity` is a share of the laser's power: above 0 and at most 1",
    )
    .label(at, format!("this is {}", short(value)))
    .help("blown-powder DED takes up 0.3–0.5 of the power, e.g. `absorptivity = 0.35`")
}

/// `plate` is not three lengths above zero.
pub fn plate_not_three(got: Got<'_>, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Type,
        "`plate` is three lengths above zero: the plate's length, width and thickness",
    )
    .label(at, format!("this is {}", got.describe()))
    .help("e.g. `plate = [200 mm, 200 mm, 20 mm]`")
}

/// What a refused interpass limit would need.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Overheat<'a> {
    /// The layer, 1-based as people count.
    pub layer: usize,
    /// Its predicted interpass temperature after the most cooling allowed, °C.
    pub interpass: f64,
    /// The limit, °C.
    pub limit: f64,
    /// How the limit is kept (`dwell`, `power`).
    pub cooling: &'a str,
    /// The longest wait lmdc plans, s.
    pub longest: f64,
    /// The wait that would keep the layer within the limit, s, if known.
    pub needs: Option<f64>,
    /// Whether it is the plate's preheat that is above the limit (the
    /// first layer).
    pub preheat: bool,
    /// The least power the layer before may be laid at, W (`cooling =
    /// power`).
    pub floor: Option<f64>,
    /// Where the island that starts too hot starts, mm, in a layer of
    /// several.
    pub island: Option<[f64; 3]>,
}

/// No allowed cooling keeps a layer within `max_interpass`.
pub fn interpass(o: Overheat<'_>, at: Span) -> Diagnostic {
    let which = match o.island {
        Some([x, y, _]) => format!(
            "the island of layer {} at ({} mm, {} mm)",
            o.layer,
            short(x),
            short(y)
        ),
        None => format!("layer {}", o.layer),
    };
    let d = Diagnostic::error(
        Code::Interpass,
        format!(
            "{which} would start at {} °C, above `max_interpass` ({} °C)",
            short(o.interpass),
            short(o.limit)
        ),
    );
    if o.preheat {
        return d
            .label(at, "the limit")
            .help(format!(
                "the plate is preheated to {} °C: lower `preheat`, or raise `max_interpass` to at least {} degC",
                short(o.interpass),
                short_up(o.interpass)
            ));
    }
    let how = match (o.cooling, o.floor) {
        ("power", Some(w)) => format!(
            "with the layer before at {} W, the least the laser's range and the bead's measured powers allow",
            short(w)
        ),
        ("power", None) => "at the least power the laser's range and the bead's measured powers allow".to_string(),
        ("order", _) => "with the layer's islands in the order that starts each the coolest (the one that has cooled longest first), no wait beyond the declared ones".to_string(),
        _ => format!("after the longest wait lmdc plans ({} s)", short(o.longest)),
    };
    let raise = format!(
        "raise `max_interpass` to at least {} degC",
        short_up(o.interpass)
    );
    let fix = match (o.cooling, o.needs) {
        ("power", Some(w)) => format!(
            "a wait of {} s before the layer would keep it: allow waits (`cooling = dwell`), or {raise}",
            short_up(w)
        ),
        ("power", None) => format!("allow waits (`cooling = dwell`), or {raise}"),
        ("order", needs) => {
            let why = if o.island.is_some() {
                "each island cools only while the others are laid, too short here"
            } else {
                "a layer of one piece has no order to choose"
            };
            let wait = needs.map_or(String::new(), |w| {
                format!(": a wait of {} s before the layer would keep it", short_up(w))
            });
            format!("{why}{wait}; allow waits (`cooling = dwell`), or {raise}")
        }
        (_, Some(w)) => format!(
            "a wait of {} s would keep it, longer than lmdc plans: {raise}, or lay less heat per layer (a lower power)",
            short_up(w)
        ),
        (_, None) => format!("{raise}, or lay less heat per layer (a lower power)"),
    };
    d.label(at, format!("predicted {how}")).help(fix)
}
