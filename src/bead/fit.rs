//! Bead models fitted to measured coupons ([`super::sheet`]) by least
//! squares: a line `H = a·v + b`, a power law `H = c·v^b` (a line in log
//! space), a mass balance's catch efficiency `η` (from each coupon's
//! cross-section or mass, through the origin) and a table of the mean
//! height at each speed. Each fit says how far each coupon lies from it and
//! how much of the data's scatter it explains (R²).

use super::sheet::{Column, Coupon, Sheet};
use super::{HeightModel, Table, TableFault, Widths};
use crate::units::{Density, Length, MassFlow, Speed};

/// The models lmdc fits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// `linear(slope, intercept)`.
    Linear,
    /// `power(height, speed, exponent)`.
    Power,
    /// `mass_balance(feed, efficiency, density)`.
    MassBalance,
    /// `table(speed, height, width)`.
    Table,
}

impl Kind {
    /// Every model, in the order `lmdc fit` prints them.
    pub const ALL: [Kind; 4] = [Kind::Linear, Kind::Power, Kind::MassBalance, Kind::Table];

    /// Its name in the language.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Linear => "linear",
            Kind::Power => "power",
            Kind::MassBalance => "mass_balance",
            Kind::Table => "table",
        }
    }

    /// The model called `name`.
    pub fn of(name: &str) -> Option<Kind> {
        Kind::ALL.into_iter().find(|k| k.name() == name)
    }

    /// How many numbers it fits from `speeds` distinct speeds.
    fn parameters(self, speeds: usize) -> usize {
        match self {
            Kind::Linear | Kind::Power => 2,
            Kind::MassBalance => 1,
            Kind::Table => speeds,
        }
    }
}

/// What a mass balance needs besides the sheet: the metal's density and
/// the feed of coupons whose row has none.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Given {
    /// The metal's density, g/mm³.
    pub density: Option<Density>,
    /// The powder feed, g/min, where the sheet has no `feed`.
    pub feed: Option<MassFlow>,
}

/// Why a model cannot be fitted to a sheet.
#[derive(Clone, Debug, PartialEq)]
pub enum Fault {
    /// Fewer coupons or speeds than the model needs (`need` says how many).
    TooFew {
        /// Coupons usable.
        points: usize,
        /// Distinct speeds among them.
        speeds: usize,
        /// What the model needs, in words.
        need: &'static str,
    },
    /// The sheet lacks what the model is fitted to (a column's name, or
    /// `density` / `feed` not given).
    Missing(&'static str),
    /// The heights fitted rise with the speed (a line's slope or a power
    /// law's exponent, this, is not negative): no speed is the one for a
    /// height, and no bead does that.
    Rising(f64),
    /// The catch efficiency fitted, this, is not between 0 and 1.
    Efficiency(f64),
    /// The mean heights at each speed are no table.
    Table {
        /// The speeds measured, mm/s.
        speeds: Vec<f64>,
        /// The mean height at each, mm.
        means: Vec<f64>,
        /// Each fault, with the rows (line, span) of the coupons at the two
        /// speeds it names.
        faults: Vec<(TableFault, Vec<(usize, crate::span::Span)>)>,
    },
}

/// A model fitted to a sheet.
#[derive(Clone, Debug, PartialEq)]
pub struct Fit {
    /// Which model.
    pub kind: Kind,
    /// The model with the fitted numbers.
    pub model: HeightModel,
    /// The slowest and fastest speed measured, mm/s.
    pub range: [f64; 2],
    /// The coupons used: their line and how far each lies from the model
    /// (measured − fitted), in [`Fit::unit`].
    pub residuals: Vec<(usize, f64)>,
    /// The share of the measurements' scatter the model explains.
    pub r2: f64,
    /// The root mean square residual, in [`Fit::unit`].
    pub rms: f64,
    /// What was fitted: `mm` (heights), `mm²` (areas) or `g` (masses).
    pub unit: &'static str,
    /// How many distinct speeds.
    pub speeds: usize,
    /// The widths measured, by speed (their mean at each), where the sheet
    /// has them.
    pub widths: Option<Widths>,
    /// The mean width measured, mm.
    pub mean_width: Option<f64>,
    /// The laser powers the coupons fitted were laid at, W, increasing
    /// (empty where the sheet has none).
    pub powers: Vec<f64>,
    /// The powder feeds they were laid at, g/min, increasing (empty where
    /// the sheet has none).
    pub feeds: Vec<f64>,
}

/// What a program says of a model it fitted when compiled: where the
/// numbers come from and how well they match (the IR's `bead.fit`, the
/// report's).
#[derive(Clone, Debug, PartialEq)]
pub struct Summary {
    /// The data file as the program names it.
    pub data: String,
    /// The model fitted.
    pub kind: Kind,
    /// How many coupons.
    pub points: usize,
    /// At how many distinct speeds.
    pub speeds: usize,
    /// R².
    pub r2: f64,
    /// RMS residual, in `unit`.
    pub rms: f64,
    /// `mm`, `mm²` or `g`.
    pub unit: &'static str,
}

impl Fit {
    /// The summary of this fit to the data file `data`.
    pub fn summary(&self, data: &str) -> Summary {
        Summary {
            data: data.to_string(),
            kind: self.kind,
            points: self.residuals.len(),
            speeds: self.speeds,
            r2: self.r2,
            rms: self.rms,
            unit: self.unit,
        }
    }

    /// R² adjusted for the numbers fitted: `None` when the model has as
    /// many numbers as coupons (a table of one coupon a speed explains
    /// everything and says nothing).
    pub fn adjusted_r2(&self) -> Option<f64> {
        let n = self.residuals.len();
        let p = self.kind.parameters(self.speeds);
        (n > p).then(|| 1.0 - (1.0 - self.r2) * (n as f64 - 1.0) / (n - p) as f64)
    }

    /// The small-sample Akaike criterion of the fit, what [`favoured`]
    /// compares (lower is better): `n·ln(1 − R²) + 2k + 2k(k+1)/(n−k−1)`
    /// for `k` numbers fitted to `n` coupons. `1 − R²` is the residuals'
    /// share of the scatter, so models fitted to areas and to heights
    /// compare alike; a table's one number a speed costs what it buys.
    /// `None` with too few coupons for the penalty (`n ≤ k + 1`).
    pub fn aicc(&self) -> Option<f64> {
        let n = self.residuals.len();
        let k = self.kind.parameters(self.speeds) + 1;
        (n > k + 1).then(|| {
            let (nf, kf) = (n as f64, k as f64);
            nf * (1.0 - self.r2).max(1e-15).ln()
                + 2.0 * kf
                + 2.0 * kf * (kf + 1.0) / (nf - kf - 1.0)
        })
    }
}

/// Fits `kind` to the coupons of `sheet`.
pub fn fit(sheet: &Sheet, kind: Kind, given: Given) -> Result<Fit, Fault> {
    let with = |c: Column| -> Vec<&Coupon> {
        sheet
            .coupons
            .iter()
            .filter(|k| k.get(c).is_some())
            .collect()
    };
    let heights = with(Column::Height);
    match kind {
        Kind::Linear | Kind::Power | Kind::Table if !sheet.has(Column::Height) => {
            Err(Fault::Missing("height"))
        }
        Kind::Linear => line_fit(sheet, &heights, false),
        Kind::Power => line_fit(sheet, &heights, true),
        Kind::Table => table_fit(sheet, &heights),
        Kind::MassBalance => mass_balance(sheet, given),
    }
}

/// The model the data favour among `fits`: the lowest [`Fit::aicc`]
/// (the first of equals, in the order of [`Kind::ALL`]).
pub fn favoured(fits: &[Fit]) -> Option<&Fit> {
    fits.iter()
        .filter_map(|f| f.aicc().map(|a| (f, a)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(f, _)| f)
}

/// The least-squares line through `(x, y)`: `(slope, intercept)`.
pub fn least_squares(x: &[f64], y: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = x.iter().map(|a| (a - mx) * (a - mx)).sum();
    let slope = sxy / sxx;
    (slope, my - slope * mx)
}

/// How many distinct speeds `coupons` were laid at.
fn distinct(coupons: &[&Coupon]) -> Vec<f64> {
    let mut v: Vec<f64> = coupons.iter().map(|c| c.speed()).collect();
    v.sort_by(f64::total_cmp);
    v.dedup();
    v
}

/// A line (or, `log`, a power law as a line in log space) through the
/// heights of `coupons`.
fn line_fit(sheet: &Sheet, coupons: &[&Coupon], log: bool) -> Result<Fit, Fault> {
    let speeds = distinct(coupons);
    if speeds.len() < 2 {
        return Err(Fault::TooFew {
            points: coupons.len(),
            speeds: speeds.len(),
            need: "coupons at two speeds or more",
        });
    }
    let f = |x: f64| if log { x.ln() } else { x };
    let x: Vec<f64> = coupons.iter().map(|c| f(c.speed())).collect();
    let y: Vec<f64> = coupons.iter().map(|c| f(height(c))).collect();
    let (slope, intercept) = least_squares(&x, &y);
    let range = [speeds[0], speeds[speeds.len() - 1]];
    let model = if log {
        // The reference speed: the geometric mean of the range, to 0.1
        // mm/s, where the height is least uncertain and reads plainly.
        let v = ((range[0] * range[1]).sqrt() * 10.0).round() / 10.0;
        HeightModel::Power {
            height: Length(intercept.exp() * v.powf(slope)),
            speed: Speed(v),
            exponent: slope,
        }
    } else {
        HeightModel::Linear {
            slope,
            intercept: Length(intercept),
        }
    };
    if slope >= 0.0 {
        return Err(Fault::Rising(slope));
    }
    let kind = if log { Kind::Power } else { Kind::Linear };
    Ok(finish(sheet, kind, model, coupons, speeds.len()))
}

/// The table of the mean height at each speed.
fn table_fit(sheet: &Sheet, coupons: &[&Coupon]) -> Result<Fit, Fault> {
    let speeds = distinct(coupons);
    if speeds.len() < 2 {
        return Err(Fault::TooFew {
            points: coupons.len(),
            speeds: speeds.len(),
            need: "coupons at two speeds or more",
        });
    }
    let at = |v: f64| coupons.iter().filter(move |c| c.speed() == v);
    let means: Vec<f64> = speeds
        .iter()
        .map(|&v| {
            let hs: Vec<f64> = at(v).map(|c| height(c)).collect();
            hs.iter().sum::<f64>() / hs.len() as f64
        })
        .collect();
    let table = Table::new(&speeds, &means).map_err(|faults| Fault::Table {
        speeds: speeds.clone(),
        means: means.clone(),
        faults: faults
            .into_iter()
            .map(|f| {
                let i = match f {
                    TableFault::NotFalling(i) | TableFault::SpeedOrder(i) => i,
                    _ => 0,
                };
                // The coupons at the two speeds that disagree.
                let lines = [i.saturating_sub(1), i]
                    .iter()
                    .flat_map(|&k| at(speeds[k]).map(|c| (c.line, c.span)))
                    .collect();
                (f, lines)
            })
            .collect(),
    })?;
    let n = speeds.len();
    Ok(finish(
        sheet,
        Kind::Table,
        HeightModel::Table(table),
        coupons,
        n,
    ))
}

/// The catch efficiency `η` through the origin: each coupon's area against
/// `ṁ/(ρ·v)`, or its mass against `ṁ·L/v`.
fn mass_balance(sheet: &Sheet, given: Given) -> Result<Fit, Fault> {
    let density = given.density.ok_or(Fault::Missing("density"))?;
    let by_mass = !sheet.has(Column::Area) && sheet.has(Column::Mass);
    let (measured, unit) = match (sheet.has(Column::Area), by_mass) {
        (true, _) => (Column::Area, "mm²"),
        (false, true) => (Column::Mass, "g"),
        (false, false) => return Err(Fault::Missing("area")),
    };
    if by_mass && !sheet.has(Column::Length) {
        return Err(Fault::Missing("length"));
    }
    let feed = |c: &Coupon| c.get(Column::Feed).or(given.feed.map(|f| f.g_min()));
    if !sheet.has(Column::Feed) && given.feed.is_none() {
        return Err(Fault::Missing("feed"));
    }
    let coupons: Vec<&Coupon> = sheet
        .coupons
        .iter()
        .filter(|c| c.get(measured).is_some() && feed(c).is_some())
        .filter(|c| !by_mass || c.get(Column::Length).is_some())
        .collect();
    if coupons.is_empty() {
        return Err(Fault::TooFew {
            points: 0,
            speeds: 0,
            need: "one coupon with its feed and its area or mass",
        });
    }
    // The model's prediction per unit of η.
    let x = |c: &Coupon| {
        let per_s = feed(c).unwrap_or(0.0) / 60.0;
        match by_mass {
            false => per_s / (density.0 * c.speed()),
            true => per_s * c.get(Column::Length).unwrap_or(0.0) / c.speed(),
        }
    };
    let sxy: f64 = coupons
        .iter()
        .map(|c| x(c) * c.get(measured).unwrap_or(0.0))
        .sum();
    let sxx: f64 = coupons.iter().map(|c| x(c) * x(c)).sum();
    let eta = sxy / sxx;
    if !(eta > 0.0 && eta <= 1.0) {
        return Err(Fault::Efficiency(eta));
    }
    let model = HeightModel::MassBalance {
        // The feed the block states: the one given, or the coupons' mean
        // (g/min → g/s).
        feed: given.feed.unwrap_or(MassFlow(mean(&coupons, feed) / 60.0)),
        efficiency: eta,
        density,
    };
    let fitted: Vec<f64> = coupons.iter().map(|c| eta * x(c)).collect();
    let measured: Vec<f64> = coupons
        .iter()
        .map(|c| c.get(measured).unwrap_or(0.0))
        .collect();
    let speeds = distinct(&coupons);
    let mut f = finish(sheet, Kind::MassBalance, model, &coupons, speeds.len());
    (f.residuals, f.r2, f.rms) = scatter(&coupons, &measured, &fitted);
    f.unit = unit;
    Ok(f)
}

/// The mean of `f` over `coupons` (those that have it).
fn mean(coupons: &[&Coupon], f: impl Fn(&Coupon) -> Option<f64>) -> f64 {
    let v: Vec<f64> = coupons.iter().filter_map(|c| f(c)).collect();
    v.iter().sum::<f64>() / v.len().max(1) as f64
}

fn height(c: &Coupon) -> f64 {
    c.get(Column::Height).unwrap_or(f64::NAN)
}

/// The fit of `model` to the heights of `coupons`: residuals, R², RMS, the
/// measured range and widths.
fn finish(
    sheet: &Sheet,
    kind: Kind,
    model: HeightModel,
    coupons: &[&Coupon],
    speeds: usize,
) -> Fit {
    let measured: Vec<f64> = coupons.iter().map(|c| height(c)).collect();
    // The width does not enter a height model's heights.
    let fitted: Vec<f64> = coupons
        .iter()
        .map(|c| model.height_at(Speed(c.speed()), Length(1.0)).0)
        .collect();
    let (residuals, r2, rms) = scatter(coupons, &measured, &fitted);
    let vs: Vec<f64> = coupons.iter().map(|c| c.speed()).collect();
    let range = vs
        .iter()
        .fold([f64::INFINITY, f64::NEG_INFINITY], |[a, b], &v| {
            [a.min(v), b.max(v)]
        });
    let (widths, mean_width) = widths(sheet);
    let values = |col: Column| {
        let mut v: Vec<f64> = coupons.iter().filter_map(|c| c.get(col)).collect();
        v.sort_by(f64::total_cmp);
        v.dedup();
        v
    };
    Fit {
        powers: values(Column::Power),
        feeds: values(Column::Feed),
        kind,
        model,
        range,
        residuals,
        r2,
        rms,
        unit: "mm",
        speeds,
        widths,
        mean_width,
    }
}

/// Residuals (measured − fitted, by the coupon's line), R² and RMS.
#[allow(clippy::type_complexity)]
fn scatter(coupons: &[&Coupon], measured: &[f64], fitted: &[f64]) -> (Vec<(usize, f64)>, f64, f64) {
    let n = measured.len() as f64;
    let m = measured.iter().sum::<f64>() / n;
    let res: Vec<f64> = measured.iter().zip(fitted).map(|(a, b)| a - b).collect();
    let ss_res: f64 = res.iter().map(|r| r * r).sum();
    let ss_tot: f64 = measured.iter().map(|y| (y - m) * (y - m)).sum();
    // Every coupon alike: the model explains all when it hits them.
    let r2 = if ss_tot > 0.0 {
        1.0 - ss_res / ss_tot
    } else if ss_res <= 1e-24 {
        1.0
    } else {
        0.0
    };
    let residuals = coupons.iter().map(|c| c.line).zip(res).collect();
    (residuals, r2, (ss_res / n).sqrt())
}

/// The mean width at each speed where the sheet measured widths, and the
/// mean of all of them.
fn widths(sheet: &Sheet) -> (Option<Widths>, Option<f64>) {
    let with: Vec<&Coupon> = sheet
        .coupons
        .iter()
        .filter(|c| c.get(Column::Width).is_some())
        .collect();
    if with.is_empty() {
        return (None, None);
    }
    let speeds = distinct(&with);
    let means: Vec<f64> = speeds
        .iter()
        .map(|&v| {
            mean(&with, |c| {
                (c.speed() == v).then(|| c.get(Column::Width)).flatten()
            })
        })
        .collect();
    let all = mean(&with, |c| c.get(Column::Width));
    (Widths::new(&speeds, &means).ok(), Some(all))
}

/// The distinct values of `col` among the coupons of `sheet`, increasing.
pub fn values(sheet: &Sheet, col: Column) -> Vec<f64> {
    let mut v: Vec<f64> = sheet.coupons.iter().filter_map(|c| c.get(col)).collect();
    v.sort_by(f64::total_cmp);
    v.dedup();
    v
}

/// Coupons laid at one laser power and one powder feed (either `None`
/// where the sheet has no such column or the cell is empty).
#[derive(Clone, Debug, PartialEq)]
pub struct Group {
    /// The power, W.
    pub power: Option<f64>,
    /// The powder feed, g/min.
    pub feed: Option<f64>,
    /// The lines of its coupons in the file.
    pub lines: Vec<usize>,
}

impl Group {
    /// The coupons of `sheet` in this group, as a sheet of their own.
    pub fn sheet(&self, sheet: &Sheet) -> Sheet {
        let mut s = sheet.clone();
        s.coupons.retain(|c| self.lines.contains(&c.line));
        s
    }
}

/// The groups of coupons of `sheet` by power and powder feed, by power
/// then feed (one group when every coupon was laid at one of each).
pub fn groups(sheet: &Sheet) -> Vec<Group> {
    let same = |a: Option<f64>, b: Option<f64>| match (a, b) {
        (Some(a), Some(b)) => (a - b).abs() <= 1e-9 * a.abs().max(b.abs()),
        (a, b) => a.is_none() && b.is_none(),
    };
    let mut out: Vec<Group> = Vec::new();
    for c in &sheet.coupons {
        let (p, f) = (c.get(Column::Power), c.get(Column::Feed));
        match out.iter_mut().find(|g| same(g.power, p) && same(g.feed, f)) {
            Some(g) => g.lines.push(c.line),
            None => out.push(Group {
                power: p,
                feed: f,
                lines: vec![c.line],
            }),
        }
    }
    let key = |x: Option<f64>| x.unwrap_or(f64::NEG_INFINITY);
    out.sort_by(|a, b| {
        key(a.power)
            .total_cmp(&key(b.power))
            .then(key(a.feed).total_cmp(&key(b.feed)))
    });
    out
}

/// How a pooled fit's residuals fall in one group.
#[derive(Clone, Debug, PartialEq)]
pub struct Residuals {
    /// Their mean, in the fit's unit.
    pub mean: f64,
    /// How many are below zero (the model over the coupon).
    pub negative: usize,
    /// How many are above zero.
    pub positive: usize,
}

/// What fitting each group on its own says of a fit pooled over them.
#[derive(Clone, Debug, PartialEq)]
pub struct Pooling {
    /// Each group, the pooled fit's residuals in it, and the model fitted
    /// to it alone (or why it could not be).
    pub groups: Vec<(Group, Residuals, Result<Fit, Fault>)>,
    /// The small-sample Akaike criterion of the pooled fit and of the
    /// groups fitted apart (one residual scatter, every group's numbers),
    /// when the coupons are enough for both.
    pub aicc: Option<[f64; 2]>,
}

impl Pooling {
    /// Whether pooling hides a factor: fitting each group apart explains
    /// the coupons better for the numbers it takes (the lower AICc, the
    /// criterion [`favoured`] picks models by).
    pub fn hides(&self) -> bool {
        self.aicc.is_some_and(|[pooled, apart]| apart < pooled)
    }
}

/// `pooled` (a fit over every coupon of `sheet`) against the same model
/// fitted to each group of coupons apart; `None` when the sheet holds one
/// group.
pub fn pooling(sheet: &Sheet, pooled: &Fit, given: Given) -> Option<Pooling> {
    let groups = groups(sheet);
    if groups.len() < 2 {
        return None;
    }
    let mut out = Vec::new();
    for g in groups {
        let rs: Vec<f64> = pooled
            .residuals
            .iter()
            .filter(|r| g.lines.contains(&r.0))
            .map(|r| r.1)
            .collect();
        let residuals = Residuals {
            mean: rs.iter().sum::<f64>() / rs.len().max(1) as f64,
            negative: rs.iter().filter(|&&r| r < 0.0).count(),
            positive: rs.iter().filter(|&&r| r > 0.0).count(),
        };
        let alone = fit(&g.sheet(sheet), pooled.kind, given);
        out.push((g, residuals, alone));
    }
    let aicc = aicc_apart(pooled, &out);
    Some(Pooling { groups: out, aicc })
}

/// The AICc of `pooled` and of its groups fitted apart, each as
/// `n·ln(SS/n) + 2k + 2k(k+1)/(n−k−1)` over the same coupons (`k` the
/// numbers fitted and the scatter): `None` where a group could not be
/// fitted or the coupons are too few.
fn aicc_apart(pooled: &Fit, groups: &[(Group, Residuals, Result<Fit, Fault>)]) -> Option<[f64; 2]> {
    let ss = |f: &Fit| f.residuals.iter().map(|r| r.1 * r.1).sum::<f64>();
    let n = pooled.residuals.len();
    let mut apart = (0.0, 0usize, 0usize);
    for (_, _, f) in groups {
        let f = f.as_ref().ok()?;
        apart.0 += ss(f);
        apart.1 += f.kind.parameters(f.speeds);
        apart.2 += f.residuals.len();
    }
    // Every coupon in a group, else the two do not compare.
    if apart.2 != n {
        return None;
    }
    let crit = |ss: f64, k: usize| {
        let (nf, kf) = (n as f64, k as f64);
        (n > k + 1).then(|| {
            nf * (ss / nf).max(1e-300).ln() + 2.0 * kf + 2.0 * kf * (kf + 1.0) / (nf - kf - 1.0)
        })
    };
    let p = pooled.kind.parameters(pooled.speeds) + 1;
    Some([crit(ss(pooled), p)?, crit(apart.0, apart.1 + 1)?])
}

/// A mass balance whose catch efficiency is a line in the laser power,
/// `η(P) = η₀ + s·(P − P₀)`, fitted by least squares to coupons laid at two
/// powers or more (the power as a variable, where pooling hides it).
#[derive(Clone, Debug, PartialEq)]
pub struct PowerLine {
    /// The reference power `P₀`, W: the coupons' mean, to 10 W.
    pub power: f64,
    /// `η₀`, the efficiency at `P₀`.
    pub efficiency: f64,
    /// `s`, the efficiency's change per watt.
    pub slope: f64,
    /// The powers measured, W, increasing, and `η` at each.
    pub at: Vec<(f64, f64)>,
    /// R² of the areas or masses, as [`Fit::r2`].
    pub r2: f64,
    /// The RMS residual, in [`Fit::unit`].
    pub rms: f64,
    /// Its small-sample Akaike criterion over the same coupons as
    /// [`Pooling::aicc`] (three numbers: `η₀`, `s` and the scatter).
    pub aicc: Option<f64>,
}

/// [`PowerLine`] fitted to the coupons of `sheet` that have a power, with
/// `given` as [`fit`] takes it; `None` unless they were laid at two powers
/// or more and the mass balance fits.
pub fn power_line(sheet: &Sheet, given: Given) -> Option<PowerLine> {
    let density = given.density?;
    let by_mass = !sheet.has(Column::Area) && sheet.has(Column::Mass);
    let measured = if by_mass { Column::Mass } else { Column::Area };
    let feed = |c: &Coupon| c.get(Column::Feed).or(given.feed.map(|f| f.g_min()));
    let coupons: Vec<&Coupon> = sheet
        .coupons
        .iter()
        .filter(|c| c.get(measured).is_some() && feed(c).is_some())
        .filter(|c| c.get(Column::Power).is_some())
        .filter(|c| !by_mass || c.get(Column::Length).is_some())
        .collect();
    let powers = {
        let mut v: Vec<f64> = coupons
            .iter()
            .filter_map(|c| c.get(Column::Power))
            .collect();
        v.sort_by(f64::total_cmp);
        v.dedup();
        v
    };
    if powers.len() < 2 {
        return None;
    }
    let x = |c: &Coupon| {
        let per_s = feed(c).unwrap_or(0.0) / 60.0;
        match by_mass {
            false => per_s / (density.0 * c.speed()),
            true => per_s * c.get(Column::Length).unwrap_or(0.0) / c.speed(),
        }
    };
    let p0 = (mean(&coupons, |c| c.get(Column::Power)) / 10.0).round() * 10.0;
    let d = |c: &Coupon| c.get(Column::Power).unwrap_or(p0) - p0;
    // Normal equations of y = a·x + b·x·d.
    let (mut sxx, mut sxxd, mut sxxdd, mut sxy, mut sxyd) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for c in &coupons {
        let (xi, di, yi) = (x(c), d(c), c.get(measured).unwrap_or(0.0));
        sxx += xi * xi;
        sxxd += xi * xi * di;
        sxxdd += xi * xi * di * di;
        sxy += xi * yi;
        sxyd += xi * yi * di;
    }
    let det = sxx * sxxdd - sxxd * sxxd;
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let a = (sxy * sxxdd - sxyd * sxxd) / det;
    let b = (sxx * sxyd - sxxd * sxy) / det;
    let measured_v: Vec<f64> = coupons
        .iter()
        .map(|c| c.get(measured).unwrap_or(0.0))
        .collect();
    let fitted: Vec<f64> = coupons.iter().map(|c| x(c) * (a + b * d(c))).collect();
    let (residuals, r2, rms) = scatter(&coupons, &measured_v, &fitted);
    let n = residuals.len();
    let ss: f64 = residuals.iter().map(|r| r.1 * r.1).sum();
    let k = 3.0;
    let nf = n as f64;
    let aicc = (nf > k + 1.0)
        .then(|| nf * (ss / nf).max(1e-300).ln() + 2.0 * k + 2.0 * k * (k + 1.0) / (nf - k - 1.0));
    let at = powers.iter().map(|&p| (p, a + b * (p - p0))).collect();
    Some(PowerLine {
        power: p0,
        efficiency: a,
        slope: b,
        at,
        r2,
        rms,
        aicc,
    })
}

#[cfg(test)]
mod tests {
    use super::super::sheet;
    use super::*;

    #[test]
    fn a_line_through_exact_points_is_that_line() {
        let h = |v: f64| -0.135 * v + 1.82;
        let text: String = std::iter::once("speed (mm/s),height (mm)\n".to_string())
            .chain([4.0, 5.5, 7.0, 8.7].map(|v| format!("{v},{}\n", h(v))))
            .collect();
        let s = sheet::read(&text).unwrap();
        let f = fit(&s, Kind::Linear, Given::default()).unwrap();
        let HeightModel::Linear { slope, intercept } = f.model else {
            panic!("{:?}", f.model)
        };
        assert!((slope + 0.135).abs() < 1e-12 && (intercept.0 - 1.82).abs() < 1e-12);
        assert!((f.r2 - 1.0).abs() < 1e-12 && f.rms < 1e-12);
        assert_eq!(f.range, [4.0, 8.7]);
    }
}
