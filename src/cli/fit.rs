//! `lmdc fit DATA.csv`: fits bead models to a measurement sheet and prints
//! each fit's R², residuals and measured range, the model the data favour
//! and the `bead { … }` block to paste (docs/calibration.md).

use super::messages::{self, MessageFormat};
use super::{read_sheet, EXIT_PROGRAM, EXIT_USAGE};
use lmdc::bead::fit::{self, Fit, Given, Kind};
use lmdc::bead::sheet::{self, Sheet};
use lmdc::bead::HeightModel;
use lmdc::diag::Diagnostics;
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
        Err(d) => {
            print(&d);
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
            Err(e) => skipped.push((k, fit::diagnose(&e, k, &sheet))),
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
    let out = if a.json {
        let j = Json::new(&sheet, &fits, chosen, &block);
        serde_json::to_string_pretty(&j).unwrap_or_default() + "\n"
    } else {
        report(&name, &sheet, &fits, &skipped, chosen, &block)
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

/// `lmdc fit --json`.
#[derive(Serialize)]
struct Json<'a> {
    coupons: usize,
    unmeasured: usize,
    /// The speeds measured, mm/s.
    range: [f64; 2],
    fits: Vec<JsonFit<'a>>,
    favoured: &'a str,
    bead: &'a str,
}

#[derive(Serialize)]
struct JsonFit<'a> {
    model: &'a str,
    /// As the language writes it.
    text: String,
    r2: f64,
    adjusted_r2: Option<f64>,
    aicc: Option<f64>,
    rms: f64,
    unit: &'a str,
    /// `[line, measured − fitted]`.
    residuals: &'a [(usize, f64)],
}

impl<'a> Json<'a> {
    fn new(sheet: &Sheet, fits: &'a [Fit], chosen: &'a Fit, block: &'a str) -> Json<'a> {
        Json {
            coupons: sheet.coupons.len(),
            unmeasured: sheet.unmeasured,
            range: chosen.range,
            fits: fits
                .iter()
                .map(|f| JsonFit {
                    model: f.kind.name(),
                    text: model_text(f),
                    r2: f.r2,
                    adjusted_r2: f.adjusted_r2(),
                    aicc: f.aicc(),
                    rms: f.rms,
                    unit: f.unit,
                    residuals: &f.residuals,
                })
                .collect(),
            favoured: chosen.kind.name(),
            bead: block,
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
