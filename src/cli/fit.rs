//! `lmdc fit DATA.csv`: fits bead models to a measurement sheet and prints
//! each fit's R², residuals and measured range, the model the data favour
//! and the `bead { … }` block to paste (docs/calibration.md).

use super::messages::{self, MessageFormat};
use super::{read_sheet, EXIT_PROGRAM, EXIT_USAGE};
use lmdc::bead::fit::{self, Fit, Given, Group, Kind, Pooling};
use lmdc::bead::sheet::{self, Sheet};
use lmdc::bead::HeightModel;
use lmdc::diag::{sheet as says, Diagnostics};
use lmdc::units::{Density, MassFlow};
use serde::Serialize;
use std::fmt::Write as _;
use std::path::Path;

/// What `lmdc fit` was asked.
pub struct Args<'a> {
    /// The measurement sheet.
    pub file: &'a Path,
    /// Only this model (default: every model the sheet allows).
    pub model: Option<Kind>,
    /// What the heights are: `track`, `wall` or `layer`.
    pub kind: &'a str,
    /// The tracks' offset of `--kind layer`, mm.
    pub offset: Option<f64>,
    /// The metal's density, g/cm³ (a mass balance).
    pub density: Option<f64>,
    /// The powder feed, g/min, for coupons whose row has none.
    pub feed: Option<f64>,
    /// JSON instead of text.
    pub json: bool,
}

/// Runs `lmdc fit`; returns the exit code.
pub fn run(a: Args<'_>, (color, format): (bool, MessageFormat)) -> u8 {
    let Some(text) = read_sheet(a.file) else {
        return EXIT_USAGE;
    };
    let basis = match (a.kind, a.offset) {
        ("track" | "wall", None) => a.kind.to_string(),
        ("layer", Some(o)) if o.is_finite() && o > 0.0 => format!("layer(offset = {} mm)", sig(o)),
        ("layer", _) => {
            eprintln!("error: --kind layer needs the tracks' offset in the layers measured: --offset 1.6 (mm)");
            return EXIT_USAGE;
        }
        (_, _) => {
            eprintln!("error: --offset goes with --kind layer");
            return EXIT_USAGE;
        }
    };
    let positive = |x: Option<f64>, what: &str| match x {
        Some(v) if !(v.is_finite() && v > 0.0) => Err(format!(
            "error: --{what} must be a number greater than zero, not {v}"
        )),
        _ => Ok(x),
    };
    let (density, feed) = match (positive(a.density, "density"), positive(a.feed, "feed")) {
        (Ok(d), Ok(f)) => (d, f),
        (Err(e), _) | (_, Err(e)) => {
            eprintln!("{e}");
            return EXIT_USAGE;
        }
    };
    let name = super::shown(a.file);
    let print = |d: &Diagnostics| messages::print(d, a.file, &text, color, format);
    let sheet = match sheet::read(&text) {
        Ok(s) => s,
        Err(faults) => {
            print(&says::faults(&faults));
            return EXIT_PROGRAM;
        }
    };
    let given = Given {
        density: density.map(|d| Density(d / 1000.0)),
        feed: feed.map(|f| MassFlow(f / 60.0)),
    };
    let kinds: Vec<Kind> = a.model.map_or(Kind::ALL.to_vec(), |k| vec![k]);
    let mut fits = Vec::new();
    let mut skipped = Vec::new();
    for k in kinds {
        match fit::fit(&sheet, k, given) {
            Ok(f) => fits.push(f),
            Err(e) => skipped.push((k, says::fault(&e, k, sheet.header))),
        }
    }
    // Asked for one model that cannot be fitted, or none fits: say why.
    if fits.is_empty() || a.model.is_some() && !skipped.is_empty() {
        let mut d = Diagnostics::new();
        skipped
            .into_iter()
            .flat_map(|s| s.1)
            .for_each(|x| d.push(x));
        print(&d);
        return EXIT_PROGRAM;
    }
    let chosen = match a.model {
        Some(_) => &fits[0],
        None => fit::favoured(&fits).unwrap_or(&fits[0]),
    };
    let block = bead_block(chosen, &basis);
    let pooling = fit::pooling(&sheet, chosen, given);
    let out = if a.json {
        let mut j = Json::new(&sheet, (&fits, &skipped), chosen, &block);
        j.groups = pooling.as_ref().map(|p| JsonPooling::new(p, &basis));
        j.power_line = fit::power_line(&sheet, given);
        serde_json::to_string_pretty(&j).unwrap_or_default() + "\n"
    } else {
        let mut s = report(&name, &sheet, &fits, &skipped, chosen, &block);
        if let Some(p) = &pooling {
            pooling_text(&mut s, p, chosen, &basis);
        }
        if let Some(l) = fit::power_line(&sheet, given) {
            power_line_text(&mut s, &l, pooling.as_ref(), chosen.unit);
        }
        s
    };
    print!("{out}");
    0
}

/// `x` to six significant digits, trailing zeros cut.
fn sig(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let digits = (5 - x.abs().log10().floor() as i32).clamp(0, 12) as usize;
    let s = format!("{x:.digits$}");
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    };
    if s == "-0" {
        "0".into()
    } else {
        s
    }
}

/// The model as the language writes it.
fn model_text(f: &Fit) -> String {
    let list = |xs: &[f64], unit: &str| {
        let v: Vec<String> = xs.iter().map(|x| format!("{} {unit}", sig(*x))).collect();
        format!("[{}]", v.join(", "))
    };
    match &f.model {
        HeightModel::Linear { slope, intercept } => format!(
            "linear(slope = {} mm / (1 mm/s), intercept = {} mm)",
            sig(*slope),
            sig(intercept.0)
        ),
        HeightModel::Power {
            height,
            speed,
            exponent,
        } => format!(
            "power(height = {} mm, speed = {} mm/s, exponent = {})",
            sig(height.0),
            sig(speed.0),
            sig(*exponent)
        ),
        HeightModel::MassBalance {
            feed,
            efficiency,
            density,
        } => format!(
            "mass_balance(feed = {} g/min, efficiency = {}, density = {} g/cm^3)",
            sig(feed.g_min()),
            sig(*efficiency),
            sig(density.0 * 1000.0)
        ),
        HeightModel::Table(t) => {
            let widths = match &f.widths {
                Some(w) if w.speeds() == t.speeds() => {
                    format!(", width = {}", list(w.widths(), "mm"))
                }
                _ => String::new(),
            };
            format!(
                "table(speed = {}, height = {}{widths})",
                list(t.speeds(), "mm/s"),
                list(t.heights(), "mm")
            )
        }
        HeightModel::Measured { height, speed } => {
            format!(
                "measured(height = {} mm, speed = {} mm/s)",
                sig(height.0),
                sig(speed.0)
            )
        }
    }
}

/// The `bead { … }` block of fit `f`, heights measured as `basis`.
fn bead_block(f: &Fit, basis: &str) -> String {
    let mut s = String::from("bead fitted {\n");
    match f.mean_width {
        Some(w) => {
            let range = f.widths.as_ref().map(|w| w.range()).unwrap_or([w, w]);
            let _ = writeln!(
                s,
                "  width = {} mm                // mean measured, {} .. {} mm",
                sig(w),
                sig(range[0]),
                sig(range[1])
            );
        }
        None => {
            s.push_str("  width = 2.4 mm                // not measured: write the bead's width\n")
        }
    }
    let _ = writeln!(
        s,
        "  speed = {} mm/s .. {} mm/s    // the speeds measured",
        sig(f.range[0]),
        sig(f.range[1])
    );
    let _ = writeln!(s, "  model = {}", model_text(f));
    if !matches!(f.model, HeightModel::MassBalance { .. }) {
        let _ = writeln!(s, "  measured_as = {basis}");
    }
    let list = |xs: &[f64], unit: &str| {
        let v: Vec<String> = xs.iter().map(|x| format!("{} {unit}", sig(*x))).collect();
        v.join(", ")
    };
    if !f.powers.is_empty() {
        let _ = writeln!(
            s,
            "  powers = [{}]    // the powers measured",
            list(&f.powers, "W")
        );
    }
    if !f.feeds.is_empty() {
        let _ = writeln!(
            s,
            "  powders = [{}]    // the powder feeds measured",
            list(&f.feeds, "g/min")
        );
    }
    s.push_str("}\n");
    s
}

/// The text report: the sheet, each fit, the favoured one's block, the
/// residuals.
fn report(
    name: &str,
    sheet: &Sheet,
    fits: &[Fit],
    skipped: &[(Kind, Vec<lmdc::diag::Diagnostic>)],
    chosen: &Fit,
    block: &str,
) -> String {
    let mut s = String::new();
    let speeds = fits.iter().map(|f| f.speeds).max().unwrap_or(0);
    let _ = writeln!(
        s,
        "{name}: {} coupons measured at {speeds} speeds, {} .. {} mm/s{}",
        sheet.coupons.len(),
        sig(chosen.range[0]),
        sig(chosen.range[1]),
        match sheet.unmeasured {
            0 => String::new(),
            n => format!(" ({n} rows not measured yet)"),
        }
    );
    let _ = writeln!(
        s,
        "\n{:<14}{:>10}{:>12}{:>10}{:>15}",
        "model", "R²", "adj. R²", "AICc", "RMS"
    );
    for f in fits {
        let adj = f
            .adjusted_r2()
            .map_or("—".to_string(), |a| format!("{a:.6}"));
        let aicc = f.aicc().map_or("—".to_string(), |a| format!("{a:.1}"));
        let _ = writeln!(
            s,
            "{:<14}{:>10.6}{:>12}{:>10}{:>11} {}",
            f.kind.name(),
            f.r2,
            adj,
            aicc,
            sig(f.rms),
            f.unit
        );
    }
    for (k, why) in skipped {
        let first = why.first().map_or(String::new(), |d| d.message.clone());
        let _ = writeln!(s, "{:<14}not fitted: {first}", k.name());
    }
    if fits.len() > 1 {
        let _ = writeln!(
            s,
            "\nthe data favour: {} (lowest AICc: the best fit for the numbers it takes)",
            chosen.kind.name()
        );
    }
    let _ = writeln!(s, "\n{block}");
    let _ = write!(
        s,
        "residuals, measured − fitted:\n{:>6}{:>10}",
        "line", "speed"
    );
    for f in fits {
        let _ = write!(s, "{:>20}", format!("{} ({})", f.kind.name(), f.unit));
    }
    s.push('\n');
    for c in &sheet.coupons {
        let _ = write!(s, "{:>6}{:>10}", c.line, sig(c.speed()));
        for f in fits {
            let r = f.residuals.iter().find(|r| r.0 == c.line);
            let _ = write!(s, "{:>20}", r.map_or("—".to_string(), |r| sig(r.1)));
        }
        s.push('\n');
    }
    s
}

/// The words for a group: `1200 W, 12 g/min` (what the sheet says of it).
fn group_name(g: &Group) -> String {
    let mut parts = Vec::new();
    if let Some(p) = g.power {
        parts.push(format!("{} W", sig(p)));
    }
    if let Some(f) = g.feed {
        parts.push(format!("{} g/min", sig(f)));
    }
    if parts.is_empty() {
        "no power or feed".to_string()
    } else {
        parts.join(", ")
    }
}

/// What the groups differ in: `the power`, `the powder feed` or both.
fn factor(p: &Pooling) -> &'static str {
    let differ = |f: fn(&Group) -> Option<f64>| {
        let first = f(&p.groups[0].0);
        p.groups.iter().any(|g| f(&g.0) != first)
    };
    match (differ(|g| g.power), differ(|g| g.feed)) {
        (true, true) => "the power and the powder feed",
        (false, true) => "the powder feed",
        _ => "the power",
    }
}

/// The text of the groups: each fitted apart, the pooled residuals in each,
/// and whether pooling hides what they differ in.
fn pooling_text(s: &mut String, p: &Pooling, pooled: &Fit, basis: &str) {
    let kind = pooled.kind.name();
    let _ = writeln!(
        s,
        "\nthe sheet holds {} groups of coupons, by power and powder feed; {kind} fitted to each apart:",
        p.groups.len()
    );
    for (g, _, f) in &p.groups {
        match f {
            Ok(f) => {
                let _ = writeln!(
                    s,
                    "  {:<22}{:>3} coupons  R² {:.6}  RMS {} {}  {}",
                    group_name(g),
                    g.lines.len(),
                    f.r2,
                    sig(f.rms),
                    f.unit,
                    model_text(f)
                );
            }
            Err(_) => {
                let _ = writeln!(
                    s,
                    "  {:<22}{:>3} coupons  not fitted: too few for {kind} on their own",
                    group_name(g),
                    g.lines.len()
                );
            }
        }
    }
    let by: Vec<String> = p
        .groups
        .iter()
        .map(|(g, r, _)| {
            format!(
                "{}: mean {}{} {}, {} of {} negative, {} positive",
                group_name(g),
                if r.mean > 0.0 { "+" } else { "" },
                sig(r.mean),
                pooled.unit,
                r.negative,
                g.lines.len(),
                r.positive
            )
        })
        .collect();
    let _ = writeln!(
        s,
        "the pooled {kind}'s residuals by group: {}",
        by.join("; ")
    );
    match p.aicc {
        Some([pooled_aicc, apart]) if p.hides() => {
            let _ = writeln!(
                s,
                "pooling hides {}: the groups fitted apart explain the coupons better for the numbers they take (AICc {:.1} against {:.1} pooled); build with the block of the power and feed the part runs at (below)",
                factor(p),
                apart,
                pooled_aicc
            );
        }
        Some([pooled_aicc, apart]) => {
            let _ = writeln!(
                s,
                "pooling hides nothing the coupons show: the groups fitted apart do not explain them better for the numbers they take (AICc {:.1} against {:.1} pooled)",
                apart, pooled_aicc
            );
        }
        None => {
            let _ = writeln!(
                s,
                "too few coupons to tell whether pooling hides {}",
                factor(p)
            );
        }
    }
    for (g, _, f) in &p.groups {
        if let Ok(f) = f {
            let _ = writeln!(s, "\n// the coupons at {}", group_name(g));
            s.push_str(&bead_block(f, basis));
        }
    }
}

/// The mass balance with the power as a variable: its line, its `η` at
/// each power measured, and its AICc beside the pooled and apart fits'.
fn power_line_text(s: &mut String, l: &fit::PowerLine, p: Option<&Pooling>, unit: &str) {
    let at: Vec<String> =
        l.at.iter()
            .map(|(w, e)| format!("{} at {} W", sig(*e), sig(*w)))
            .collect();
    let aicc = match (l.aicc, p.and_then(|p| p.aicc)) {
        (Some(a), Some([pooled, apart])) => {
            format!(", AICc {a:.1} against {pooled:.1} pooled and {apart:.1} apart")
        }
        _ => String::new(),
    };
    let _ = writeln!(
        s,
        "\nmass_balance with the power as a variable: efficiency = {} + {} /W·(P − {} W) (R² {:.6}, RMS {} {unit}{aicc}): {}; a part at a power P between them takes `mass_balance(…, efficiency = …)` at P, with `powers = [P]` (docs/calibration.md)",
        sig(l.efficiency),
        sig(l.slope),
        sig(l.power),
        l.r2,
        sig(l.rms),
        at.join(", ")
    );
}

/// `lmdc fit --json`: every number at full precision (docs/fit.schema.json).
#[derive(Serialize)]
struct Json<'a> {
    coupons: usize,
    unmeasured: usize,
    /// The speeds measured, mm/s.
    range: [f64; 2],
    fits: Vec<JsonFit<'a>>,
    /// The models asked for that could not be fitted, and why.
    not_fitted: Vec<NotFitted>,
    favoured: &'a str,
    bead: &'a str,
    /// The coupons by power and powder feed, where the sheet holds several
    /// groups: the favoured model fitted to each apart.
    #[serde(skip_serializing_if = "Option::is_none")]
    groups: Option<JsonPooling>,
    /// A mass balance whose efficiency is a line in the power, where the
    /// coupons were laid at two powers or more.
    #[serde(skip_serializing_if = "Option::is_none", serialize_with = "power_line")]
    power_line: Option<fit::PowerLine>,
}

/// `power_line` as `{power, efficiency, slope, at: [[W, η]…], r2, rms, aicc}`.
fn power_line<S: serde::Serializer>(l: &Option<fit::PowerLine>, s: S) -> Result<S::Ok, S::Error> {
    let v = l.as_ref().map(|l| {
        serde_json::json!({
            "power": l.power,
            "efficiency": l.efficiency,
            "slope": l.slope,
            "at": l.at,
            "r2": l.r2,
            "rms": l.rms,
            "aicc": l.aicc,
        })
    });
    serde::Serialize::serialize(&v, s)
}

/// `lmdc fit --json`'s groups.
#[derive(Serialize)]
struct JsonPooling {
    /// Whether fitting each group apart explains the coupons better for
    /// the numbers it takes (lower AICc).
    pooling_hides: bool,
    /// The AICc pooled and apart.
    aicc: Option<[f64; 2]>,
    groups: Vec<JsonGroup>,
}

#[derive(Serialize)]
struct JsonGroup {
    /// W.
    power: Option<f64>,
    /// g/min.
    feed: Option<f64>,
    coupons: usize,
    /// The pooled fit's mean residual in the group.
    pooled_mean_residual: f64,
    pooled_negative: usize,
    pooled_positive: usize,
    /// The model fitted to the group alone, as the language writes it.
    text: Option<String>,
    r2: Option<f64>,
    rms: Option<f64>,
    bead: Option<String>,
}

impl JsonPooling {
    fn new(p: &Pooling, basis: &str) -> JsonPooling {
        JsonPooling {
            pooling_hides: p.hides(),
            aicc: p.aicc,
            groups: p
                .groups
                .iter()
                .map(|(g, r, f)| {
                    let f = f.as_ref().ok();
                    JsonGroup {
                        power: g.power,
                        feed: g.feed,
                        coupons: g.lines.len(),
                        pooled_mean_residual: r.mean,
                        pooled_negative: r.negative,
                        pooled_positive: r.positive,
                        text: f.map(model_text),
                        r2: f.map(|f| f.r2),
                        rms: f.map(|f| f.rms),
                        bead: f.map(|f| bead_block(f, basis)),
                    }
                })
                .collect(),
        }
    }
}

#[derive(Serialize)]
struct JsonFit<'a> {
    model: &'a str,
    /// The fitted numbers, in the units the schema names.
    parameters: Parameters,
    /// As the language writes it (six significant digits).
    text: String,
    r2: f64,
    adjusted_r2: Option<f64>,
    aicc: Option<f64>,
    rms: f64,
    unit: &'a str,
    residuals: Vec<Residual>,
}

/// A model's fitted numbers: mm, mm/s, s (a slope in mm per mm/s), g/min,
/// g/cm³, and the efficiency as a fraction.
#[derive(Serialize)]
#[serde(untagged)]
enum Parameters {
    Linear {
        slope: f64,
        intercept: f64,
    },
    Power {
        height: f64,
        speed: f64,
        exponent: f64,
    },
    MassBalance {
        feed: f64,
        efficiency: f64,
        density: f64,
    },
    Table {
        speed: Vec<f64>,
        height: Vec<f64>,
        width: Option<Vec<f64>>,
    },
    Measured {
        height: f64,
        speed: f64,
    },
}

/// One coupon's residual: measured − fitted, in the fit's unit.
#[derive(Serialize)]
struct Residual {
    line: usize,
    residual: f64,
}

/// A model that could not be fitted.
#[derive(Serialize)]
struct NotFitted {
    model: &'static str,
    /// What lmdc says of it, as its diagnostics do.
    reason: String,
    help: Option<String>,
}

impl Parameters {
    fn of(f: &Fit) -> Parameters {
        match &f.model {
            HeightModel::Linear { slope, intercept } => Parameters::Linear {
                slope: *slope,
                intercept: intercept.0,
            },
            HeightModel::Power {
                height,
                speed,
                exponent,
            } => Parameters::Power {
                height: height.0,
                speed: speed.0,
                exponent: *exponent,
            },
            HeightModel::MassBalance {
                feed,
                efficiency,
                density,
            } => Parameters::MassBalance {
                feed: feed.g_min(),
                efficiency: *efficiency,
                density: density.0 * 1000.0,
            },
            HeightModel::Table(t) => Parameters::Table {
                speed: t.speeds().to_vec(),
                height: t.heights().to_vec(),
                width: f
                    .widths
                    .as_ref()
                    .filter(|w| w.speeds() == t.speeds())
                    .map(|w| w.widths().to_vec()),
            },
            HeightModel::Measured { height, speed } => Parameters::Measured {
                height: height.0,
                speed: speed.0,
            },
        }
    }
}

impl<'a> Json<'a> {
    fn new(
        sheet: &Sheet,
        (fits, skipped): (&'a [Fit], &[(Kind, Vec<lmdc::diag::Diagnostic>)]),
        chosen: &'a Fit,
        block: &'a str,
    ) -> Json<'a> {
        Json {
            coupons: sheet.coupons.len(),
            unmeasured: sheet.unmeasured,
            range: chosen.range,
            fits: fits
                .iter()
                .map(|f| JsonFit {
                    model: f.kind.name(),
                    parameters: Parameters::of(f),
                    text: model_text(f),
                    r2: f.r2,
                    adjusted_r2: f.adjusted_r2(),
                    aicc: f.aicc(),
                    rms: f.rms,
                    unit: f.unit,
                    residuals: f
                        .residuals
                        .iter()
                        .map(|&(line, residual)| Residual { line, residual })
                        .collect(),
                })
                .collect(),
            not_fitted: skipped
                .iter()
                .map(|(k, d)| NotFitted {
                    model: k.name(),
                    reason: d
                        .iter()
                        .map(|d| d.message.as_str())
                        .collect::<Vec<_>>()
                        .join("; "),
                    help: d.iter().find_map(|d| d.help.clone()),
                })
                .collect(),
            favoured: chosen.kind.name(),
            bead: block,
            groups: None,
            power_line: None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::sig;

    #[test]
    fn six_significant_digits() {
        assert_eq!(sig(-0.135), "-0.135");
        assert_eq!(sig(1.8200000001), "1.82");
        assert_eq!(sig(1234.5678), "1234.57");
        assert_eq!(sig(0.000123456789), "0.000123457");
    }
}
