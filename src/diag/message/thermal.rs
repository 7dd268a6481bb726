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

/// A share `key` (`absorptivity`, `emissivity`) not above 0 or above 1.
pub fn share_range(key: &str, value: f64, at: Span) -> Diagnostic {
    let (what, help) = if key == "emissivity" {
        (
            "a share of a black body's radiation",
            "an oxidised metal gives off 0.4–0.6 of it, e.g. `emissivity = 0.5`",
        )
    } else {
        (
            "a share of the laser's power",
            "blown-powder DED takes up 0.3–0.5 of the power, e.g. `absorptivity = 0.35`",
        )
    };
    Diagnostic::error(
        Code::OutOfRange,
        format!("`{key}` is {what}: above 0 and at most 1"),
    )
    .label(at, format!("this is {}", short(value)))
    .help(help)
}

/// A `thermal` block with no `material` that does not declare every
/// property the model takes.
pub fn no_material(missing: &[&str], at: Span) -> Diagnostic {
    let list = missing
        .iter()
        .map(|k| format!("`{k}`"))
        .collect::<Vec<_>>()
        .join(", ");
    Diagnostic::error(
        Code::MissingField,
        format!("`thermal` without `material` must declare the alloy's properties itself: {list} missing"),
    )
    .label(at, "no `material` here")
    .help("name one of lmdc's alloys (`material = ss316l`, `ti64`, `in718` or `ph17_4`), its properties overridden by any declared here; or declare `conductivity`, `density`, `heat_capacity`, `emissivity` and `absorptivity` (docs/thermal.md, *Alloys*)")
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

/// `cooling = []`: no lever to keep the limit with.
pub fn no_levers(at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Type,
        "`cooling` names the levers lmdc may pull to keep `max_interpass`: at least one",
    )
    .label(at, "this list is empty")
    .help("e.g. `cooling = [order, dwell]`: the islands' order first, then the least wait; or leave `cooling` out for waits alone")
}

/// `cooling` names the lever `word` a second time (`first`: where it is
/// named first).
pub fn lever_twice(word: &str, at: Span, first: Span) -> Diagnostic {
    Diagnostic::error(
        Code::BadChoice,
        format!("`cooling` names `{word}` twice"),
    )
    .label(at, "named again here")
    .label(first, "first named here")
    .help(format!(
        "each lever is allowed once, and lmdc pulls them in the order that costs the least time whatever the list's order (the islands' order, then the power, then the wait): remove this `{word}`"
    ))
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
    /// The levers allowed to keep the limit (`dwell`, `power`, `order`), as
    /// written.
    pub cooling: &'a [&'a str],
    /// The longest wait lmdc plans, s.
    pub longest: f64,
    /// The wait that would keep the layer within the limit, s, if known.
    pub needs: Option<f64>,
    /// Whether laying the layer's islands coolest first would keep it.
    pub by_order: bool,
    /// The plate's preheat, °C, where the layer is the first: nothing
    /// waits before it, so only the preheat or the islands laid before
    /// this one in the layer make it start too hot.
    pub first_layer: Option<f64>,
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
    if let Some(preheat) = o.first_layer {
        let why = if o.interpass <= preheat + 1e-6 {
            format!("the plate is preheated to {} °C", short(o.interpass))
        } else {
            // A later island of the first layer, warmed through the plate
            // by the ones laid before it: no lever waits within a layer.
            format!(
                "the plate starts at {} °C, and the islands laid before this one in the first layer warm the plate under it to {} °C (nothing waits before the first layer)",
                short(preheat),
                short(o.interpass)
            )
        };
        return d.label(at, "the limit").help(format!(
            "{why}: lower `preheat`, or raise `max_interpass` to at least {} degC",
            short_up(o.interpass)
        ));
    }
    let raise = format!(
        "raise `max_interpass` to at least {} degC",
        short_up(o.interpass)
    );
    let fix = match o.cooling {
        [one] => one_lever(&o, one, &raise),
        _ => levers_fix(&o, &raise),
    };
    d.label(at, format!("predicted {}", predicted(&o)))
        .help(fix)
}

/// How the refused prediction was made: with the most each allowed lever
/// gives, in the order lmdc pulls them.
fn predicted(o: &Overheat<'_>) -> String {
    let mut how = Vec::new();
    let allows = |w: &str| o.cooling.contains(&w);
    if allows("order") {
        how.push("with the layer's islands in the order that starts each the coolest (the one that has cooled longest first)".to_string());
    }
    match (allows("power"), o.floor) {
        (true, Some(w)) => how.push(format!(
            "with the layer before at {} W, the least the laser's range and the bead's measured powers allow",
            short(w)
        )),
        (true, None) => how.push("at the least power the laser's range and the bead's measured powers allow".to_string()),
        _ => {}
    }
    if allows("dwell") {
        how.push(format!(
            "after the longest wait lmdc plans ({} s)",
            short(o.longest)
        ));
    } else if o.cooling == ["order"] || o.cooling.len() > 1 {
        // Without `dwell` a list waits no longer than declared (`cooling =
        // power` alone says so in its fix: allow waits).
        how.push("no wait beyond the declared ones".to_string());
    }
    how.join(", ")
}

/// The fix where `cooling` is one word, `lever`.
fn one_lever(o: &Overheat<'_>, lever: &str, raise: &str) -> String {
    match (lever, o.needs) {
        ("power", Some(w)) => format!(
            "a wait of {} s before the layer would keep it: allow waits (`cooling = dwell`), or {raise}",
            short_up(w)
        ),
        ("power", None) => format!("allow waits (`cooling = dwell`), or {raise}"),
        ("order", needs) => {
            let why = if o.island.is_some() {
                "each island cools only while the others are laid, which is too short here"
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
    }
}

/// The fix where `cooling` names several levers: the lever not allowed
/// that would keep the layer (the order, a wait), written into the list.
fn levers_fix(o: &Overheat<'_>, raise: &str) -> String {
    let with = |w: &str| {
        let mut all: Vec<&str> = o.cooling.to_vec();
        all.push(w);
        format!("`cooling = [{}]`", all.join(", "))
    };
    let allows = |w: &str| o.cooling.contains(&w);
    let mut fixes = Vec::new();
    if !allows("order") && o.by_order {
        fixes.push(format!(
            "allow order ({}): laying the islands coolest first keeps it",
            with("order")
        ));
    }
    match (allows("dwell"), o.needs) {
        (false, Some(w)) => fixes.push(format!(
            "allow dwell ({}): a {} s wait before the layer keeps it",
            with("dwell"),
            short_up(w)
        )),
        (false, None) => fixes.push(format!("allow dwell ({})", with("dwell"))),
        (true, Some(w)) => fixes.push(format!(
            "a wait of {} s would keep it, longer than lmdc plans: lay less heat per layer (a lower power)",
            short_up(w)
        )),
        (true, None) => fixes.push("lay less heat per layer (a lower power)".to_string()),
    }
    fixes.push(raise.to_string());
    fixes.join("; or ")
}
