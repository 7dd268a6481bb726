//! What lmdc says about a `bead` model, the `slicing` block and the
//! `process` block: the numbers that decide how each layer is laid.

use crate::bead::TableFault;
use crate::diag::{Code, Diagnostic};
use crate::span::Span;
use crate::units::{short, Length, MassFlow, Power, Speed};

/// A bead's speed range starts at zero or below.
pub fn speed_not_positive(at: Span) -> Diagnostic {
    Diagnostic::error(Code::NotPositive, "scan speeds must be greater than zero")
        .label(at, "the lower end must be > 0")
}

/// A linear bead model's `slope` (mm per mm/s) is not negative.
pub fn slope_not_negative(slope: f64, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::BeadSlope,
        "the slope of a bead's height over speed must be negative",
    )
    .label(at, format!("this is {} mm per mm/s", short(slope)))
    .help("a faster scan lays a lower bead: fit H = slope·v + intercept with slope < 0")
}

/// A power-law bead model's `exponent` is not negative.
pub fn exponent_not_negative(exponent: f64, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::BeadSlope,
        "the exponent of a bead's power law must be negative",
    )
    .label(at, format!("this is {}", short(exponent)))
    .help("a faster scan lays a lower bead: H = height·(v/speed)^exponent with exponent < 0")
}

/// A `table(…)`'s `key` is not a list (`got` describes it).
pub fn table_not_a_list(key: &str, at: Span, got: &str, example: &str) -> Diagnostic {
    Diagnostic::error(
        Code::Type,
        format!("a bead table's `{key}` is a list, one value for each speed measured"),
    )
    .label(at, format!("this is {got}"))
    .help(format!("write `{key} = {example}`"))
}

/// A mass-balance model's catch efficiency `eff` is above 1.
pub fn efficiency_range(eff: f64, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::EfficiencyRange,
        "catch efficiency must lie between 0 and 1",
    )
    .label(
        at,
        format!("this is {} ({} %)", short(eff), short(eff * 100.0)),
    )
    .help("write it as a fraction (0.3) or a percentage (30 %)")
}

/// A bead's `model` is not one of the models lmdc knows (`got` describes it).
pub fn unknown_model(at: Span, got: &str) -> Diagnostic {
    Diagnostic::error(
        Code::BadChoice,
        "a bead model is `linear(…)`, `mass_balance(…)`, `measured(…)`, `power(…)` or `table(…)`",
    )
    .label(at, format!("this is {got}"))
    .help("e.g. `model = linear(slope = -0.135 mm / (1 mm/s), intercept = 1.82 mm)`")
}

/// The bead model gives a height `h` at or below zero (or not finite) at the
/// fast end `v` of its speed range.
pub fn model_height_not_positive(
    h: Length,
    v: Speed,
    speed_at: Span,
    model_at: Option<Span>,
) -> Diagnostic {
    Diagnostic::error(
        Code::InfeasibleBead,
        format!("the bead model gives a height of {h} at {v}"),
    )
    .label(speed_at, "speed range")
    .label_opt(model_at, "model")
    .help("narrow the speed range to where the model gives positive heights")
}

/// The bead model gives a height `h` at `v` taller than any bead a
/// nozzle lays (`most`): a model in the wrong unit.
pub fn model_height_too_tall(
    h: Length,
    v: Speed,
    most: Length,
    speed_at: Span,
    model_at: Span,
) -> Diagnostic {
    Diagnostic::error(
        Code::InfeasibleBead,
        format!("the bead model gives a height of {h} at {v}, more than the {most} lmdc takes for a laid bead"),
    )
    .label(model_at, "model")
    .label(speed_at, "speed range")
    .help("a laser-deposited bead is tenths of a millimetre to a few millimetres high: check the model's numbers and units (`intercept = 0.9 mm`, `slope = -0.03 mm / (1 mm/s)`)")
}

/// A `table(…)` (at `at`) is no table: `fault` says why, its entries
/// counted from 0; `what` names the list checked against the speeds
/// ("heights", "widths"), `speeds` and `values` its lists (mm/s, mm).
pub fn table_fault(
    fault: &TableFault,
    what: &str,
    (speeds, values): (&[f64], &[f64]),
    at: Span,
) -> Diagnostic {
    // "height 2 (1.3 mm at 6 mm/s)": the entry as the user counts them.
    let entry = |i: usize| match (speeds.get(i), values.get(i)) {
        (Some(&v), Some(&h)) => format!("{} {} ({} at {})", what, i + 1, Length(h), Speed(v)),
        _ => format!("{} {}", what, i + 1),
    };
    let (title, help) = match *fault {
        TableFault::TooFew(n) => (
            format!("a bead table needs two speeds or more; this one has {n}"),
            "measure the bead at two speeds at least (or use `measured(height, speed)` for one)".to_string(),
        ),
        TableFault::Lengths { speeds, other } => (
            format!("the table has {speeds} speeds and {other} {what}s: one for each speed"),
            format!("give one {what} for each speed"),
        ),
        TableFault::NotPositive(i) => (
            format!("{} of the table is not greater than zero", entry(i)),
            "speeds, heights and widths are all greater than zero".to_string(),
        ),
        TableFault::SpeedOrder(i) => (
            format!(
                "the table's speeds must increase: speed {} ({}) is not above speed {} ({})",
                i + 1,
                Speed(speeds[i]),
                i,
                Speed(speeds[i - 1])
            ),
            "list the speeds from slowest to fastest, each once (average repeated coupons first)".to_string(),
        ),
        TableFault::NotFalling(i) => (
            format!(
                "the table's {what}s must fall as the speed rises: {} is not below {}",
                entry(i),
                entry(i - 1)
            ),
            "a faster scan lays a lower bead; a height that rises with the speed is a measuring slip or noise larger than the step: remeasure, or drop the speed".to_string(),
        ),
    };
    Diagnostic::error(Code::BeadTable, title)
        .label(at, "this table")
        .help(help)
}

/// The bead's `speed` range (at `at`) leaves `measured`, the speeds its
/// model was measured at, by `outside` (below, above; mm/s); a warning
/// when the file allows it (`allowed`), the model at `model_at`.
pub fn extrapolation(
    speeds: [Speed; 2],
    measured: [Speed; 2],
    outside: [f64; 2],
    allowed: bool,
    at: Span,
    model_at: Span,
) -> Diagnostic {
    let [v0, v1] = speeds;
    let [m0, m1] = measured;
    let far = match outside {
        [b, a] if b > 0.0 && a > 0.0 => format!("{} below and {} above", Speed(b), Speed(a)),
        [b, _] if b > 0.0 => format!("{} below", Speed(b)),
        [_, a] => format!("{} above", Speed(a)),
    };
    let title = format!(
        "the bead's speeds {v0} .. {v1} reach {far} the speeds it was measured at, {m0} .. {m1}"
    );
    if allowed {
        Diagnostic::warning(Code::Extrapolation, title)
            .label(at, "extrapolated")
            .label(model_at, "measured here")
            .help("`extrapolate = allow`: the heights outside are the end pieces extended, a guess; measure coupons there to know them")
    } else {
        Diagnostic::error(Code::Extrapolation, title)
            .label(at, "speed range")
            .label(model_at, "measured here")
            .help(format!(
                "narrow `speed` to {m0} .. {m1} (or leave it out), measure coupons at the speeds you need, or write `extrapolate = allow` to use the model outside what was measured"
            ))
    }
}

/// The allowed heights `allowed` do not overlap `laid`, what the model lays
/// over the speed range `speeds`.
pub fn heights_do_not_overlap(
    allowed: [Length; 2],
    speeds: [Speed; 2],
    laid: [Length; 2],
    heights_at: Span,
    speed_at: Span,
) -> Diagnostic {
    let ([lo, hi], [v0, v1], [h_lo, h_hi]) = (allowed, speeds, laid);
    Diagnostic::error(
        Code::InfeasibleBead,
        format!(
            "the allowed heights {lo} .. {hi} do not overlap what the model lays at {v0} .. {v1} ({h_lo} .. {h_hi})"
        ),
    )
    .label(heights_at, "allowed heights")
    .label(speed_at, "speed range")
    .help("widen the speed range or the height range so that they overlap")
}

/// The field `key`, which names the bead model `what` is built with, is not
/// a name (`got` describes it).
pub fn bead_not_a_name(key: &str, what: &str, at: Span, got: &str) -> Diagnostic {
    Diagnostic::error(
        Code::ExpectedName,
        format!("`{key}` names the bead model {what} is built with"),
    )
    .label(at, format!("this is {got}"))
    .help(format!(
        "declare `bead my_bead {{ … }}` and write `{key} = my_bead`"
    ))
}

/// Warning: bead `bead` is modelled at `feed` of powder, while the process
/// feeds `powder`.
pub fn powder_mismatch(
    bead: &str,
    feed: MassFlow,
    powder: MassFlow,
    process_at: Span,
    bead_at: Span,
) -> Diagnostic {
    Diagnostic::warning(
        Code::PowderMismatch,
        format!(
            "bead `{}` is modelled at {} of powder, the process feeds {}: the beads will not be the heights planned",
            bead, feed, powder
        ),
    )
    .label(process_at, "process feed")
    .label(bead_at, "bead model")
    .help("use one feed in both, or refit the bead model at the process feed")
}

/// The slicing strategy `name` is not one lmdc knows; `suggestion` is a
/// close known one, if any.
pub fn unknown_strategy(name: &str, at: Span, suggestion: Option<&str>) -> Diagnostic {
    let d = Diagnostic::error(
        Code::BadChoice,
        format!("lmdc does not know the slicing strategy `{name}`"),
    )
    .label(at, "unknown strategy");
    match suggestion {
        Some(m) => d.help(format!("did you mean `slicing {m} {{ … }}`?")),
        None => d.help("use `slicing normal { … }` (continuous gradual slicing normal to a loft's spine), `slicing planar { … }` (flat filled layers of an extrusion), `slicing variable { … }` (layers that follow an extrusion's `top`) or `slicing continuous { … }` (a ring's layers in one run)"),
    }
}

/// A `slicing` block (at `at`) without a strategy name.
pub fn unnamed_strategy(at: Span) -> Diagnostic {
    Diagnostic::error(Code::Syntax, "name the slicing strategy")
        .label(at, "which strategy?")
        .help("write `slicing normal { … }`")
}

/// Both `points` and `chord_error` are given.
pub fn points_and_chord_error(points: Option<Span>, chord: Option<Span>) -> Diagnostic {
    Diagnostic::error(
        Code::ConflictingFields,
        "give either `points` or `chord_error`, not both",
    )
    .label_opt(points, "points")
    .label_opt(chord, "chord error")
}

/// `infill` is neither `raster(…)` nor `none` (`got` describes it).
pub fn bad_infill(at: Span, got: &str) -> Diagnostic {
    Diagnostic::error(Code::BadChoice, "an infill is `raster(…)` or `none`")
        .label(at, format!("this is {got}"))
        .help("e.g. `infill = raster(angle = 0 deg, pattern = serpentine)`")
}

/// `contours = 0` (at `at`) and no infill: nothing would be deposited.
pub fn nothing_deposited(at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::NothingDeposited,
        "a layer with no contour and no infill deposits nothing",
    )
    .label(at, "no contour")
    .help("add `infill = raster(…)` or at least one contour")
}

/// A raster's `extend` is negative.
pub fn negative_extend(at: Span) -> Diagnostic {
    Diagnostic::error(Code::NotPositive, "`extend` cannot be negative")
        .label(at, "negative")
        .help("0 mm keeps tracks where they meet the boundary")
}

/// One-way raster tracks are asked to be linked.
pub fn one_way_linked(link: Option<Span>, pattern: Option<Span>) -> Diagnostic {
    Diagnostic::error(
        Code::ConflictingFields,
        "one-way tracks cannot be linked: each starts on the side the last one started",
    )
    .label_opt(link, "link")
    .label_opt(pattern, "one way")
    .help("link serpentine tracks (`pattern = serpentine`), or drop `link`")
}

/// A ring's process block gives `key`, which a ring takes per segment or
/// not at all.
pub fn not_for_a_ring(key: &str, at: Span) -> Diagnostic {
    let why = match key {
        "power" => "each segment's power is in the ring's table: `table { power = [...] }`",
        "defocus" => "each segment's defocus is in the ring's table: `table { defocus = [...] }`",
        "speed" => "each segment's speed is in the ring's table, and the height loop changes it",
        "min_layer_time" => {
            "a ring is laid in one run with the laser on: there is no stop between layers to cool in"
        }
        _ => "a ring is laid in one run with the laser on: there is no stop between layers to dwell in",
    };
    Diagnostic::error(
        Code::Unsupported,
        format!("a ring's process has no `{key}`"),
    )
    .label(at, "not for a ring")
    .help(why)
}

/// The ring's table powers `lo .. hi` leave the laser's range `a .. b`.
pub fn ring_powers_out_of_range(
    lo: Power,
    hi: Power,
    a: Power,
    b: Power,
    powers_at: Span,
    range_at: Span,
) -> Diagnostic {
    Diagnostic::error(
        Code::PowerSchedule,
        format!("the ring's table reaches {lo} .. {hi}, outside the laser's range {a} .. {b}"),
    )
    .label(powers_at, "the table's powers")
    .label(range_at, "allowed range")
    .help("keep every segment's power inside `power_range`")
}

/// The power schedule reaches `lo .. hi`, outside the laser's range `a .. b`.
pub fn schedule_out_of_range(
    lo: Power,
    hi: Power,
    a: Power,
    b: Power,
    power_at: Span,
    range_at: Span,
) -> Diagnostic {
    Diagnostic::error(
        Code::PowerSchedule,
        if lo == hi {
            // A constant power: no schedule to speak of.
            format!("the power {lo} lies outside the laser's range {a} .. {b}")
        } else {
            format!("the power schedule reaches {lo} .. {hi}, outside the laser's range {a} .. {b}")
        },
    )
    .label(power_at, "power")
    .label(range_at, "allowed range")
    .help("keep the scheduled powers inside `power_range`")
}

/// `measured_as` is none of `track`, `wall`, `layer(offset)` (`got`
/// describes it; `near` a word it may have meant).
pub fn bad_measured_as(at: Span, got: &str, near: Option<&str>) -> Diagnostic {
    let d = Diagnostic::error(
        Code::BadChoice,
        "`measured_as` is `track`, `wall` or `layer(offset = …)`",
    )
    .label(at, format!("this is {got}"));
    match near {
        Some(w) => d.help(format!("did you mean `{w}`?")),
        None => d.help("what the model's heights are: one track on a plate (`track`, the seeds' maps), the rise per layer of a wall one bead wide (`wall`), or of filled layers of tracks `offset` apart (`layer(offset = 1.6 mm)`)"),
    }
}

/// `measured_as` is given with a mass-balance model, which needs none.
pub fn measured_as_with_mass_balance(at: Span, model: Span) -> Diagnostic {
    Diagnostic::error(
        Code::ConflictingFields,
        "a mass balance needs no `measured_as`: it gives the metal caught per length, `A = η·ṁ/(ρ·v)`, whatever was measured",
    )
    .label(at, "measured_as")
    .label(model, "mass balance")
    .help("drop `measured_as`")
}

/// A mass-balance bead whose cross-section at `v` would raise a one-bead
/// wall `rise` a layer, more than its width `w`.
pub fn taller_than_wide(rise: Length, v: Speed, w: Length, model: Span) -> Diagnostic {
    Diagnostic::warning(
        Code::TallBead,
        format!(
            "this mass balance lays so much at {v} that a wall one bead wide would rise {rise} a layer, more than the bead's {w} width"
        ),
    )
    .label(model, "the model")
    .help(
        "a laid bead is a flat cap, a fraction of its width high: check the units of the density (steel is about 7.9 g/cm^3, not kg/m^3), the feed (g/min) and the efficiency (%)",
    )
}

/// A bead's `tilt` range is not within 0° .. 90°, increasing (`tilt`
/// in rad).
pub fn bad_tilt(tilt: [f64; 2], at: Span) -> Diagnostic {
    let deg = |a: f64| short((a.to_degrees() * 1e3).round() / 1e3);
    Diagnostic::error(
        Code::OutOfRange,
        format!(
            "a bead's `tilt` is the nozzle's tilts from vertical it was measured at, from 0° up to 90°, not {}° .. {}°",
            deg(tilt[0]),
            deg(tilt[1])
        ),
    )
    .label(at, "the tilts measured")
    .help("write the tilts of the coupons' nozzle from vertical, the lower first: `tilt = 0 deg .. 30 deg`")
}

/// Where a deposit tilts beyond its bead's measured tilts: the machine, the
/// tilts measured (deg) and whether they were written, and the tilt that
/// would cover every deposit (deg, rounded up).
pub struct TiltBeyond<'a> {
    /// The machine whose plan tilts so.
    pub machine: &'a str,
    /// The tilts the bead was measured at, deg.
    pub measured: [f64; 2],
    /// Whether the bead's `tilt` is written (else: vertical).
    pub written: bool,
    /// Whether the machine is a robot on a positioner (which can turn the
    /// part to bring the nozzle nearer vertical).
    pub positioner: bool,
}

/// Deposits of `t.machine`'s plan whose nozzle tilts from vertical beyond
/// the bead's measured tilts by more than 5°; `w.value` is the worst tilt
/// (deg), `w.limit` the end of the measured range it passes.
pub fn bead_tilt(
    w: &crate::diag::Worst<impl std::fmt::Display>,
    t: &TiltBeyond<'_>,
    bead: Option<Span>,
) -> Diagnostic {
    let deg = |a: f64| short((a * 10.0).round() / 10.0);
    let measured = if t.written {
        format!(
            "the {}° .. {}° its bead was measured at",
            deg(t.measured[0]),
            deg(t.measured[1])
        )
    } else {
        "the vertical nozzle its bead was measured with (no `tilt` in the bead)".to_string()
    };
    let turn = if w.value < w.limit {
        ""
    } else if t.positioner {
        "; or turn the part so the nozzle stands nearer vertical (the positioner's `keep`)"
    } else {
        "; or build it where the part turns under a vertical nozzle (a tilting table, a robot's positioner)"
    };
    let cover = (w.value.max(t.measured[1])).ceil();
    let lo = t.measured[0].min(w.value).floor();
    Diagnostic::warning(
        Code::BeadTilt,
        format!(
            "machine `{}` tilts the nozzle {}° from vertical while it deposits, more than 5° outside {measured}, at {} ({} deposit{}): the bead's heights are not the ones measured there (a tilted melt pool runs downhill)",
            t.machine,
            deg(w.value),
            w.at,
            w.count,
            crate::diag::plural(w.count)
        ),
    )
    .label_opt(bead, if t.written { "the tilts measured" } else { "the bead, measured vertical" })
    .help(format!(
        "lay coupons with the nozzle tilted as this part tilts it, fit the bead to them and say so (`tilt = {} deg .. {cover} deg` in the bead){turn}",
        lo.max(0.0)
    ))
}

/// The process, or style `at.1`, runs the laser at `power` (written at
/// `at.0`), a power bead `bead.0` was not measured at (`measured`, said at
/// `bead.1`).
pub fn unmeasured_power(
    (bead, bead_at): (&str, Span),
    power: Power,
    measured: &[Power],
    (at, style): (Span, Option<&str>),
) -> Diagnostic {
    let list: Vec<String> = measured.iter().map(|p| p.to_string()).collect();
    let who = match style {
        Some(s) => format!("style `{s}` runs"),
        None => "the process runs".to_string(),
    };
    Diagnostic::warning(
        Code::Extrapolation,
        format!(
            "bead `{bead}` was measured at {}, {who} the laser at {power}: how much the melt pool catches changes with the power, and the bead's heights there are a guess",
            list.join(", ")
        ),
    )
    .label(at, if style.is_some() { "the style's power" } else { "the process's power" })
    .label(bead_at, "the powers measured")
    .help(format!(
        "lay coupons at {power} and fit the bead to them (`powers = [{power}]` in the calibration, `fit(…, power = {power})`), or run the laser at a power measured"
    ))
}

/// The process, or style `at.1`, feeds `powder` (written at `at.0`), a
/// feed bead `bead.0` was not measured at (`measured`, said at `bead.1`).
pub fn unmeasured_powder(
    (bead, bead_at): (&str, Span),
    powder: MassFlow,
    measured: &[MassFlow],
    (at, style): (Span, Option<&str>),
) -> Diagnostic {
    let list: Vec<String> = measured.iter().map(|p| p.to_string()).collect();
    let who = match style {
        Some(s) => format!("style `{s}` feeds"),
        None => "the process feeds".to_string(),
    };
    Diagnostic::warning(
        Code::Extrapolation,
        format!(
            "bead `{bead}` was measured at a powder feed of {}, {who} {powder}: how much of it the melt pool catches changes with the feed, and the bead's heights there are a guess",
            list.join(", ")
        ),
    )
    .label(at, if style.is_some() { "the style's feed" } else { "the process's feed" })
    .label(bead_at, "the feeds measured")
    .help(format!(
        "lay coupons at {powder} and fit the bead to them (`powders = [{powder}]` in the calibration, `fit(…, powder = {powder})`), or feed a powder measured"
    ))
}
