//! What lmdc says about a measurement sheet (`lmdc fit`, `model = fit(…,
//! data = "…")`): its spans are bytes of the sheet, which the report draws
//! with its file name, line and column.

use crate::bead::fit::{Fault, Group, Kind, Pooling};
use crate::bead::sheet::SheetFault;
use crate::bead::TableFault;
use crate::diag::{Code, Diagnostic};
use crate::span::Span;
use crate::units::{short, Length, Speed};

/// `d`, a diagnostic about the data file `path` (whose text is `text`),
/// as one about the program, pointing at `at` (where it names the file):
/// the file's line and column lead its message.
pub fn in_data(d: &Diagnostic, path: &str, text: &str, at: Span) -> Diagnostic {
    let place = match d.labels.first() {
        Some(l) => {
            let before = &text[..l.span.start.min(text.len())];
            let line = before.matches('\n').count() + 1;
            let col = before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1;
            format!("{path}:{line}:{col}")
        }
        None => path.to_string(),
    };
    let mut out =
        Diagnostic::error(d.code, format!("{place}: {}", d.message)).label(at, "the data fitted");
    out.help = d.help.clone();
    out
}

/// The data file `path` (named at `at`) cannot be read (`why`).
pub fn unreadable_data(path: &str, why: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Sheet,
        format!("cannot read the data file `{path}`: {why}"),
    )
    .label(at, "this file")
    .help("the path is relative to the folder of the .lmd file")
}

/// A program names a data file where no file can be read (compiled from a
/// text, not a file).
pub fn no_data_reader(at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Sheet,
        "this program is compiled from a text, not a file: there is no folder to read its data from",
    )
    .label(at, "data file")
    .help("compile the .lmd file (`lmdc build FILE.lmd`), or paste the block `lmdc fit` prints")
}

/// Why `kind` cannot be fitted to the sheet whose header is at `header`.
pub fn fault(f: &Fault, kind: Kind, header: Span) -> Vec<Diagnostic> {
    let model = kind.name();
    match f {
        Fault::TooFew {
            points,
            speeds,
            need,
        } => vec![too_few_points(model, *points, *speeds, need, header)],
        Fault::Missing(what @ ("density" | "feed")) => vec![not_given(model, what, header)],
        Fault::Missing(col) => vec![missing_column(model, col, header)],
        Fault::Rising(b) => vec![rising(kind, *b, header)],
        Fault::Efficiency(eta) => vec![efficiency(*eta, header)],
        Fault::Table {
            speeds,
            means,
            faults,
        } => faults
            .iter()
            .map(|(f, rows)| not_falling(f, (speeds, means), rows, header))
            .collect(),
    }
}

/// The mean heights at each speed (`speeds`, `means`) are no table
/// (`fault`): the coupons at the speeds it names are `rows`.
fn not_falling(
    fault: &TableFault,
    (speeds, means): (&[f64], &[f64]),
    rows: &[(usize, Span)],
    header: Span,
) -> Diagnostic {
    let lines: Vec<String> = rows.iter().map(|r| r.0.to_string()).collect();
    let title = match *fault {
        TableFault::NotFalling(i) => format!(
            "the heights must fall as the speed rises: at {} they average {}, not below {} at {} (lines {})",
            Speed(speeds[i]),
            Length(means[i]),
            Length(means[i - 1]),
            Speed(speeds[i - 1]),
            lines.join(", ")
        ),
        _ => "the mean heights at each speed are no table".to_string(),
    };
    let d = Diagnostic::error(Code::BeadTable, title);
    let d = match rows.first() {
        Some(_) => rows
            .iter()
            .fold(d, |d, (line, at)| d.label(*at, format!("line {line}"))),
        None => d.label(header, "header"),
    };
    d.help("a faster scan lays a lower bead: a height that rises with the speed is a measuring slip or noise larger than the step between the speeds; remeasure those coupons, or fit a line or a power law, which average it out")
}

/// The fitted `kind`'s slope (or exponent) `b` is not negative.
fn rising(kind: Kind, b: f64, header: Span) -> Diagnostic {
    let what = match kind {
        Kind::Power => format!("exponent {}", short(b)),
        _ => format!("slope {} mm per mm/s", short(b)),
    };
    Diagnostic::error(
        Code::BeadSlope,
        format!("the coupons' heights do not fall as the speed rises: the fitted {} model has {what}", kind.name()),
    )
    .label(header, "these coupons")
    .help("a faster scan lays a lower bead: check the speed and height columns are not swapped, that the heights are all in one unit, and that the coupons were laid at one power and feed")
}

/// The fitted catch efficiency `eta` is not in (0, 1].
fn efficiency(eta: f64, header: Span) -> Diagnostic {
    Diagnostic::error(
        Code::EfficiencyRange,
        format!("the fitted catch efficiency is {}, not between 0 and 1", short(eta)),
    )
    .label(header, "these coupons")
    .help("the melt pool cannot catch more powder than is fed: check the `feed` (g/min), the density (g/cm³) and the area (mm²) or mass and length of the coupons")
}

/// `what` (`density`, `feed`), which model `model` needs, was not given.
fn not_given(model: &str, what: &str, header: Span) -> Diagnostic {
    let (flag, arg) = match what {
        "density" => ("--density 7.9", "density = 7.9 g/cm^3"),
        _ => ("--feed 12", "feed = 12 g/min"),
    };
    Diagnostic::error(
        Code::TooFewPoints,
        format!("a {model} model needs the {what}, which the sheet does not give"),
    )
    .label(header, "header")
    .help(format!(
        "give it: `lmdc fit … {flag}`, or `fit({model}, data = \"…\", {arg})`{}",
        if what == "feed" {
            ", or a `feed (g/min)` column"
        } else {
            ""
        }
    ))
}

/// Every mistake `faults` found in a measurement sheet, in order.
pub fn sheet(faults: &[SheetFault]) -> crate::diag::Diagnostics {
    let mut out = crate::diag::Diagnostics::new();
    for f in faults {
        out.push(match f {
            SheetFault::Empty(at) => empty_sheet(*at),
            SheetFault::NoSpeedColumn(at) => no_speed_column(*at),
            SheetFault::ExtraCell { line, at, columns } => extra_cell(*line, *at, *columns),
            SheetFault::NoSpeed { line, at } => no_speed(*line, *at),
            SheetFault::NotANumber(c, t, at) => not_a_number(c.name(), t, *at),
            SheetFault::NotPositive(c, t, at) => not_positive_cell(c.name(), t, *at),
            SheetFault::DuplicateColumn(c, at, first) => duplicate_column(c.name(), *at, *first),
            SheetFault::MissingUnit(c, at) => missing_unit(c.name(), c.units()[0].0, *at),
            SheetFault::WrongUnit(c, unit, at) => {
                let units: Vec<&str> = c.units().iter().map(|u| u.0).collect();
                wrong_unit(c.name(), unit, &units, *at)
            }
        });
    }
    out
}

/// The sheet holds no row at all.
fn empty_sheet(at: Span) -> Diagnostic {
    Diagnostic::error(Code::Sheet, "the measurement sheet is empty")
        .label(at, "no header, no coupons")
        .help("the first line names the columns with their units: `id,speed (mm/s),width (mm),height (mm)`; one coupon a line follows")
}

/// The header (at `at`) has no `speed` column.
fn no_speed_column(at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Sheet,
        "the measurement sheet has no `speed` column: every model is a function of the scan speed",
    )
    .label(at, "header")
    .help("add a column `speed (mm/s)` with each coupon's scan speed")
}

/// Line `line` has more cells than the header's `n`; the first extra at `at`.
fn extra_cell(line: usize, at: Span, n: usize) -> Diagnostic {
    Diagnostic::error(
        Code::Sheet,
        format!("line {line} has more cells than the header's {n}"),
    )
    .label(at, "no column for this")
    .help("name the column in the header, or put a comma inside a cell in double quotes: \"flat, good\"")
}

/// A measured row (line `line`) has no speed.
fn no_speed(line: usize, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Sheet,
        format!("the coupon on line {line} is measured but has no speed"),
    )
    .label(at, "this row")
    .help("fill in the scan speed the coupon was laid at")
}

/// A cell of column `col` (`text`, at `at`) is not a number.
fn not_a_number(col: &str, text: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Sheet,
        format!("a `{col}` cell must be a number, not `{text}`"),
    )
    .label(at, "not a number")
    .help("write the number alone, with a point as the decimal mark (1.25), its unit in the header; leave the cell empty where nothing was measured")
}

/// A cell of column `col` (`text`, at `at`) is zero or below.
fn not_positive_cell(col: &str, text: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Sheet,
        format!("a `{col}` must be greater than zero, not {text}"),
    )
    .label(at, "≤ 0")
    .help("leave the cell empty where nothing was measured (a coupon that laid no bead is not a bead of height 0: drop its speed from the model)")
}

/// Column `col` (at `at`) is named twice, first at `first`.
fn duplicate_column(col: &str, at: Span, first: Span) -> Diagnostic {
    Diagnostic::error(
        Code::SheetUnits,
        format!("the sheet has two `{col}` columns"),
    )
    .label(at, "again")
    .label(first, "first")
    .help("keep one, or rename the other (lmdc skips columns it does not know)")
}

/// Column `col` (at `at`) has no unit; `unit` is the one lmdc uses.
fn missing_unit(col: &str, unit: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::SheetUnits,
        format!("the `{col}` column does not say its unit"),
    )
    .label(at, "which unit?")
    .help(format!(
        "write the unit in brackets in the header: `{col} ({unit})`"
    ))
}

/// Column `col` (at `at`) is in `unit`, which lmdc does not convert.
fn wrong_unit(col: &str, unit: &str, units: &[&str], at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::SheetUnits,
        format!("lmdc does not read a `{col}` in `{unit}`"),
    )
    .label(at, "this unit")
    .help(format!(
        "convert the column to one of: {}",
        units
            .iter()
            .map(|u| format!("`{col} ({u})`"))
            .collect::<Vec<_>>()
            .join(", ")
    ))
}

/// The sheet (its header at `at`) has `n` coupons measured at `speeds`
/// distinct speeds, fewer than model `model` needs (`need`, in words).
pub fn too_few_points(model: &str, n: usize, speeds: usize, need: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::TooFewPoints,
        format!(
            "a {model} model needs {need}; the sheet has {n} coupon{} measured at {speeds} speed{}",
            if n == 1 { "" } else { "s" },
            if speeds == 1 { "" } else { "s" }
        ),
    )
    .label(at, "these columns")
    .help("measure more coupons (three speeds or more across the range you will build at), or choose a model the data can fix")
}

/// The sheet (header at `at`) lacks the column `col` model `model` fits.
pub fn missing_column(model: &str, col: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::TooFewPoints,
        format!("a {model} model is fitted to `{col}`, which the sheet does not have"),
    )
    .label(at, "header")
    .help(format!(
        "add a `{col}` column with the measurements, or choose another model"
    ))
}

/// The `n` coupons of a calibration block, each `footprint` mm wide and
/// `length` long with `spacing` between them and around them, need
/// `need` mm (x, y) where the plate is `plate`.
pub fn coupons_off_plate(
    n: usize,
    [length, footprint, spacing]: [f64; 3],
    need: [f64; 2],
    plate: [f64; 2],
    at: Span,
) -> Diagnostic {
    let mm = |v: f64| Length(v).to_string();
    Diagnostic::error(
        Code::CouponsPlate,
        format!(
            "{n} coupons of {} × {} with {} between them need {} × {}; the plate is {} × {}",
            mm(length),
            mm(footprint),
            mm(spacing),
            mm(need[0]),
            mm(need[1]),
            mm(plate[0]),
            mm(plate[1])
        ),
    )
    .label(at, "the plate")
    .help("lay fewer coupons (fewer speeds, powers, powders or `repeat`), make them shorter or closer (`length`, `spacing`), or declare a larger plate")
}

/// `speeds` is neither a list of speeds nor a range.
pub fn speeds_not_a_list(got: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Type,
        format!("`speeds` must be a list of speeds or a range, not {got}"),
    )
    .label(at, "not a list or a range")
    .help("write `speeds = [4 mm/s, 6 mm/s, 8 mm/s]`, or `speeds = 4 mm/s .. 8 mm/s` with `count = 5`")
}

/// `what` (`speeds`, `powers`, `powders`) is an empty list.
pub fn empty_list(what: &str, at: Span) -> Diagnostic {
    Diagnostic::error(Code::CountRange, format!("`{what}` lists no value"))
        .label(at, "empty")
        .help(format!("give `{what}` at least one value, or leave it out"))
}

/// The process power is a ramp, which gives no one power to lay the
/// coupons at.
pub fn ramp_without_powers(at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Unsupported,
        "the process power is a ramp: a coupon is laid at one power",
    )
    .label(at, "a ramp")
    .help("give the calibration block its powers: `powers = [1000 W]`")
}

/// A calibration file that also declares a part to build (`what`: the
/// statement).
pub fn calibration_with_part(what: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Unsupported,
        format!("a file with a `calibration` block lays coupons, not a part: it takes no `{what}`"),
    )
    .label(at, "not in a calibration file")
    .help("keep the calibration in a file of its own (`part`, `bead`, `process`, `machine` and `calibration`), and the part in another")
}

/// `plate` does not have two sizes.
pub fn plate_not_two(n: usize, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Type,
        format!("`plate` is the plate's size along x and y, two lengths, not {n}"),
    )
    .label(at, "two lengths")
    .help("write `plate = [150 mm, 100 mm]`")
}

/// A calibration matrix of `n` coupons, more than `max`.
pub fn too_many_coupons(n: usize, max: usize, at: Span) -> Diagnostic {
    let n = if n == usize::MAX {
        "more than can be counted".to_string()
    } else {
        n.to_string()
    };
    Diagnostic::error(
        Code::CountRange,
        format!("this calibration lays {n} coupons; lmdc lays at most {max}"),
    )
    .label(at, "speeds × powers × powders × repeat")
    .help("give fewer speeds, powers, powder feeds or a smaller `repeat`")
}

/// A group of coupons as a sheet says it: `1200 W, 12 g/min`.
pub fn group_name(g: &Group) -> String {
    let mut parts = Vec::new();
    if let Some(p) = g.power {
        parts.push(format!("{} W", short(p)));
    }
    if let Some(f) = g.feed {
        parts.push(format!("{} g/min", short(f)));
    }
    if parts.is_empty() {
        "no power or feed".to_string()
    } else {
        parts.join(", ")
    }
}

/// `fit(…, power = …)` or `powder = …` (`column`, `x` in W or g/min,
/// written at `at`) selects no coupon of `path`, whose coupons were laid at
/// `all`.
pub fn no_coupons_at(column: &str, x: f64, all: &[f64], path: &str, at: Span) -> Diagnostic {
    let (unit, key) = if column == "power" {
        ("W", "power")
    } else {
        ("g/min", "powder")
    };
    let laid: Vec<String> = all
        .iter()
        .map(|v| format!("{} {unit}", short(*v)))
        .collect();
    let laid = if laid.is_empty() {
        format!("it has no `{column}` column")
    } else {
        format!("its coupons were laid at {}", laid.join(", "))
    };
    Diagnostic::error(
        Code::TooFewPoints,
        format!("`{path}` has no coupon laid at {} {unit}: {laid}", short(x)),
    )
    .label(at, format!("the coupons at this {column}"))
    .help(format!(
        "fit the coupons at a {column} the sheet has (`{key} = …`), or lay coupons at {} {unit} and measure them",
        short(x)
    ))
}

/// One `fit(…)` (`f`) pooled over coupons of `path` laid at several powers
/// or feeds that fitting each group apart explains better (`p`); `at`
/// names the file.
pub fn pooled_fit(p: &Pooling, f: &crate::bead::fit::Fit, path: &str, at: Span) -> Diagnostic {
    let residuals: Vec<String> = p
        .groups
        .iter()
        .map(|(g, r, _)| {
            format!(
                "{}{} {} at {} ({} of {} below)",
                if r.mean > 0.0 { "+" } else { "" },
                short(r.mean),
                f.unit,
                group_name(g),
                r.negative,
                g.lines.len()
            )
        })
        .collect();
    let differ = |get: fn(&Group) -> Option<f64>| {
        let first = get(&p.groups[0].0);
        p.groups.iter().any(|g| get(&g.0) != first)
    };
    let (power, feed) = (differ(|g| g.power), differ(|g| g.feed));
    let select: Vec<String> = p
        .groups
        .iter()
        .map(|(g, _, _)| {
            let mut a = Vec::new();
            if let (true, Some(w)) = (power, g.power) {
                a.push(format!("power = {} W", short(w)));
            }
            if let (true, Some(m)) = (feed, g.feed) {
                a.push(format!("powder = {} g/min", short(m)));
            }
            format!("`{}`", a.join(", "))
        })
        .collect();
    let apart = p.aicc.map_or(String::new(), |[pooled, apart]| {
        format!(" (AICc {:.1} against {:.1} pooled)", apart, pooled)
    });
    Diagnostic::warning(
        Code::PooledFit,
        format!(
            "`{path}` holds coupons laid at {} groups of power and powder feed, and one {} pooled over them hides the difference: its residuals average {}; each group fitted apart explains the coupons better{apart}",
            p.groups.len(),
            f.kind.name(),
            residuals.join(", ")
        ),
    )
    .label(at, "these coupons")
    .help(format!(
        "fit the coupons laid at the power and feed the part runs at: {} in `fit(…)`; `lmdc fit {path}` prints every group's fit",
        select.join(" or ")
    ))
}
