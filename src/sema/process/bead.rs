//! `bead NAME { width, height, speed, model }`: a bead model.

use crate::bead::fit::{self, Given, Kind, Summary};
use crate::bead::sheet::Column;
use crate::bead::{sheet, Table, TableFault, Widths};
use crate::deposit::Basis;
use crate::diag::{message, Diagnostics};
use crate::sema::data::Data;
use crate::sema::eval::{unknown_name, Env};
use crate::sema::fields::{self, Fields};
use crate::sema::model::{Bead, HeightModel};
use crate::sema::schema::bead::{
    self as schema, model as args, BEAD, FIT, LAYER, LINEAR, MASS_BALANCE, MEASURED, POWER, TABLE,
};
use crate::sema::schema::Field;
use crate::sema::suggest::did_you_mean;
use crate::sema::value::{Spanned, Value};
use crate::span::Span;
use crate::syntax::ast::Stmt;
use crate::units::{Density, Length, MassFlow, Power, Speed};
use std::collections::BTreeMap;

/// Reads a bead block.
pub fn read<'a>(
    env: &mut Env<'a>,
    name: &str,
    stmts: &'a [Stmt],
    span: Span,
    diags: &mut Diagnostics,
) -> Option<Bead> {
    let f = Fields::block(env, stmts, &BEAD, format!("bead `{name}`"), span, diags);
    let width = f.quantity(&schema::WIDTH, diags);
    // A measured bead brings its speed, a table its speeds; every other
    // model needs the range.
    let measured = matches!(
        f.value(&schema::MODEL, &mut Diagnostics::new()).map(|m| &m.value),
        Some(Value::Call(c)) if ["measured", "table", "fit"].contains(&c.func.as_str())
    );
    let speed = f.range(&schema::SPEED, diags);
    if !measured {
        f.require(&schema::SPEED, diags);
    }
    let height = f.range(&schema::HEIGHT, diags);
    let tilt = tilt(&f, diags);
    let declared_height = height.map(|([lo, hi], _)| [Length(lo), Length(hi)]);
    let model = f.value(&schema::MODEL, diags);
    let model_span = model.map(|m| m.span);
    // A range that starts at zero or below is wrong whatever the model.
    let speed = speed.filter(|&(range, speed_span)| {
        if range[0] > 0.0 {
            return true;
        }
        diags.push(message::bead::speed_not_positive(speed_span));
        false
    });
    let read = height_model(model, span, env.data.as_ref(), diags);
    let (model, widths, measured_speeds, fit, at) = match read {
        Some(r) => (Some(r.model), r.widths, r.measured, r.fit, r.at),
        None => (None, None, None, None, At::default()),
    };
    // Internal units: a fit's powers in W, its feeds in g/min.
    let fit_powers = at
        .powers
        .map(|v| v.into_iter().map(|w| Power::from_watts(w).0).collect());
    let fit_feeds = at.feeds.map(|v| v.into_iter().map(|g| g / 60.0).collect());
    let powers = measured_at(&f, &schema::POWERS, fit_powers, model_span, diags)
        .map(|o| o.map(|(v, s)| (v.into_iter().map(Power).collect(), s)));
    let powders = measured_at(&f, &schema::POWDERS, fit_feeds, model_span, diags)
        .map(|o| o.map(|(v, s)| (v.into_iter().map(MassFlow).collect(), s)));
    let basis = basis(&f, model.as_ref(), model_span, diags);
    let (model, basis) = (model?, basis?);
    let model_span = model_span.unwrap_or(span);
    // A measured bead is valid at the speed it was measured at, unless the file
    // says over which range it holds.
    let speed = match (speed, &model) {
        (Some(s), _) => Some(s),
        (None, HeightModel::Measured { speed: v, .. }) if !f.has(&schema::SPEED) => {
            Some(([v.0, v.0], model_span))
        }
        (None, _) if !f.has(&schema::SPEED) => measured_speeds.map(|r| (r, model_span)),
        (None, _) => None,
    };
    let (width, (speed, speed_span)) = (width?, speed?);
    if let Some(m) = measured_speeds {
        let allow = f.word_or_default(&schema::EXTRAPOLATE, diags) == Some("allow");
        extrapolation(speed, m, allow, (speed_span, model_span), diags)?;
    }
    let w = Length(width.0);
    let deposit = crate::deposit::Deposit {
        model: model.clone(),
        width: w,
        basis,
        widths: widths.clone(),
    };
    let (height, height_span) = heights(&deposit, speed, height, (speed_span, model_span), diags)?;
    Some(Bead {
        name: name.to_string(),
        width: w,
        model,
        basis,
        widths,
        measured: measured_speeds.map(|[lo, hi]| [Speed(lo), Speed(hi)]),
        fit,
        declared_height,
        tilt: tilt?,
        powers: powers?,
        powders: powders?,
        feed: None,
        speed: [Speed(speed[0]), Speed(speed[1])],
        height,
        span,
        height_span,
        speed_span,
    })
}

/// The powers or feeds the model was measured at (`field`, internal
/// units): as written, else what its fit's coupons were laid at (`fit`,
/// said at `model`); `Some(None)` when neither says.
fn measured_at(
    f: &Fields<'_>,
    field: &Field,
    fit: Option<Vec<f64>>,
    model: Option<Span>,
    diags: &mut Diagnostics,
) -> Option<Option<(Vec<f64>, Span)>> {
    if f.has(field) {
        let at = f.span(field).unwrap_or_else(|| f.block_span());
        return list(f, field, diags).map(|v| Some((v, at)));
    }
    Some(fit.filter(|v| !v.is_empty()).zip(model))
}

/// `tilt = lo .. hi`: the nozzle's tilts the model was measured at, rad,
/// within 0° .. 90° and increasing; `Some(None)` when not written.
fn tilt(f: &Fields<'_>, diags: &mut Diagnostics) -> Option<Option<([f64; 2], Span)>> {
    if !f.has(&schema::TILT) {
        return Some(None);
    }
    let ([lo, hi], at) = f.range(&schema::TILT, diags)?;
    if !(0.0..=90.0_f64.to_radians() * (1.0 + 1e-9)).contains(&lo)
        || !(lo..=90.0_f64.to_radians() * (1.0 + 1e-9)).contains(&hi)
    {
        diags.push(message::bead::bad_tilt([lo, hi], at));
        return None;
    }
    Some(Some(([lo, hi], at)))
}

/// What the model's heights were measured as (`measured_as = …`; a single
/// track when not written).
fn basis(
    f: &Fields<'_>,
    model: Option<&HeightModel>,
    model_span: Option<Span>,
    diags: &mut Diagnostics,
) -> Option<Basis> {
    let Some(v) = f.value(&schema::MEASURED_AS, diags) else {
        return (!f.has(&schema::MEASURED_AS)).then_some(Basis::Track);
    };
    let basis = match &v.value {
        Value::Symbol(s) if s == "track" => Basis::Track,
        Value::Symbol(s) if s == "wall" => Basis::Wall,
        Value::Call(c) if c.func == "layer" => {
            let a = Fields::call(c, &LAYER, diags);
            Basis::Layer {
                offset: a.quantity(&args::OFFSET, diags)?.0,
            }
        }
        other => {
            let near = match other {
                Value::Symbol(w) => did_you_mean(w, ["track", "wall", "layer"]),
                Value::Call(c) => did_you_mean(&c.func, ["layer"]),
                _ => None,
            };
            diags.push(message::bead::bad_measured_as(
                v.span,
                &other.describe(),
                near,
            ));
            return None;
        }
    };
    if let (Some(HeightModel::MassBalance { .. }), Some(m)) = (model, model_span) {
        diags.push(message::bead::measured_as_with_mass_balance(v.span, m));
        return None;
    }
    Some(basis)
}

/// Whether the bead's `speed` range (`speed`, at `spans.0`) stays within
/// `measured`, the speeds its model was measured at (at `spans.1`): an
/// error when it leaves them, a warning when the file allows it (`allow`);
/// `None` on the error.
fn extrapolation(
    speed: [f64; 2],
    measured: [f64; 2],
    allow: bool,
    (speed_span, model_span): (Span, Span),
    diags: &mut Diagnostics,
) -> Option<()> {
    let below = measured[0] - speed[0];
    let above = speed[1] - measured[1];
    let slack = 1e-9 * measured[1];
    if below <= slack && above <= slack {
        return Some(());
    }
    diags.push(message::bead::extrapolation(
        speed.map(Speed),
        measured.map(Speed),
        [below.max(0.0), above.max(0.0)],
        allow,
        speed_span,
        model_span,
    ));
    allow.then_some(())
}

/// `table(speed, height, width)`: the heights (and widths) measured at
/// each speed, or every fault of them.
fn table(
    c: &crate::sema::value::Call,
    at: Span,
    diags: &mut Diagnostics,
) -> Option<(Table, Option<Widths>)> {
    let a = Fields::call(c, &TABLE, diags);
    let speeds = list(&a, &args::SPEEDS, diags);
    let heights = list(&a, &args::HEIGHTS, diags);
    let widths = a.has(&args::WIDTHS).then(|| list(&a, &args::WIDTHS, diags));
    let (speeds, heights) = (speeds?, heights?);
    let faults = |fs: Vec<TableFault>, what: &str, values: &[f64], diags: &mut Diagnostics| {
        for f in fs {
            diags.push(message::bead::table_fault(&f, what, (&speeds, values), at));
        }
    };
    let table = Table::new(&speeds, &heights).map_err(|fs| faults(fs, "height", &heights, diags));
    let widths = match widths {
        None => Ok(None),
        Some(None) => Err(()),
        Some(Some(w)) => match Widths::new(&speeds, &w) {
            // One width for each speed: a table's shape is the heights'.
            Ok(w) if w.speeds().len() == speeds.len() => Ok(Some(w)),
            Ok(_) => Err(()),
            Err(fs) => {
                let fs = fs
                    .into_iter()
                    .filter(|f| {
                        matches!(f, TableFault::Lengths { .. } | TableFault::NotPositive(_))
                    })
                    .collect();
                faults(fs, "width", &w, diags);
                Err(())
            }
        },
    };
    Some((table.ok()?, widths.ok()?))
}

/// One list of quantities of a `table(…)`: every entry of the field's
/// dimension, each one reported where it is not.
fn list(a: &Fields<'_>, field: &Field, diags: &mut Diagnostics) -> Option<Vec<f64>> {
    let dim = field.kind.dim().expect("a table's lists are of quantities");
    let v = a.value(field, diags)?;
    let Value::List(items) = &v.value else {
        diags.push(message::bead::table_not_a_list(
            field.key,
            v.span,
            &v.value.describe(),
            a.example(field),
        ));
        return None;
    };
    let read: Vec<Option<f64>> = items
        .iter()
        .map(|it| fields::quantity(it, dim, field.key, diags))
        .collect();
    read.into_iter().collect()
}

/// What `model = …` says: the height model, and where it was measured,
/// the widths and speeds measured and the fit that gave it.
struct Read {
    model: HeightModel,
    widths: Option<Widths>,
    measured: Option<[f64; 2]>,
    fit: Option<Summary>,
    at: At,
}

/// The powers (W) and feeds (g/min) a fit's coupons were laid at.
#[derive(Default)]
struct At {
    powers: Option<Vec<f64>>,
    feeds: Option<Vec<f64>>,
}

/// `fit(model, data, density, feed)`: the model fitted to the data file,
/// read with `data`.
fn fitted(
    c: &crate::sema::value::Call,
    data: Option<&crate::sema::DataReader>,
    diags: &mut Diagnostics,
) -> Option<Read> {
    let a = Fields::call(c, &FIT, diags);
    let kind = a.word(&args::FIT_MODEL, diags);
    let path = a.text(&args::DATA, diags);
    let density = a.quantity(&args::FIT_DENSITY, diags);
    let feed = a.quantity(&args::FIT_FEED, diags);
    let power = a.quantity(&args::FIT_POWER, diags);
    let powder = a.quantity(&args::FIT_POWDER, diags);
    let ((kind, _), (path, at)) = (kind?, path?);
    let kind = Kind::of(kind)?;
    let Some(read) = data else {
        diags.push(message::calib::no_data_reader(at));
        return None;
    };
    let text = read(&path, Data::Sheet)
        .and_then(|b| Data::Sheet.too_long(&b).map_or(Ok(b), Err))
        .and_then(|b| String::from_utf8(b).map_err(|e| not_text(&e)))
        .map_err(|why| diags.push(message::calib::unreadable_data(&path, &why, at)))
        .ok()?;
    let in_data = |ds: Vec<crate::diag::Diagnostic>, diags: &mut Diagnostics| {
        for d in ds {
            diags.push(message::calib::in_data(&d, &path, &text, at));
        }
    };
    let mut sheet = sheet::read(&text)
        .map_err(|fs| in_data(message::calib::sheet(&fs).into_vec(), diags))
        .ok()?;
    let select = [
        power.map(|(p, s)| (Column::Power, Power(p).watts(), s)),
        powder.map(|(p, s)| (Column::Feed, MassFlow(p).g_min(), s)),
    ];
    for (col, x, s) in select.into_iter().flatten() {
        let all = fit::values(&sheet, col);
        sheet
            .coupons
            .retain(|c| c.get(col).is_some_and(|v| (v - x).abs() <= 1e-6 * x));
        if sheet.coupons.is_empty() {
            diags.push(message::calib::no_coupons_at(col.name(), x, &all, &path, s));
            return None;
        }
    }
    let given = Given {
        density: density.map(|d| Density(d.0)),
        feed: feed.map(|f| MassFlow(f.0)),
    };
    let f = fit::fit(&sheet, kind, given)
        .map_err(|e| in_data(message::calib::fault(&e, kind, sheet.header), diags))
        .ok()?;
    if let Some(p) = fit::pooling(&sheet, &f, given).filter(fit::Pooling::hides) {
        diags.push(message::calib::pooled_fit(&p, &f, &path, at));
    }
    Some(Read {
        widths: f.widths.clone(),
        measured: Some(f.range),
        fit: Some(f.summary(&path)),
        at: At {
            powers: Some(f.powers.clone()),
            feeds: Some(f.feeds.clone()),
        },
        model: f.model,
    })
}

/// Why a data file is not text.
fn not_text(e: &std::string::FromUtf8Error) -> String {
    format!(
        "it is not UTF-8 text (invalid byte at offset {})",
        e.utf8_error().valid_up_to()
    )
}

/// The model `model = …` gives, and the widths it measured where it did
/// (`block` is where to point when the value is no model at all and has
/// no span of its own; `data` reads a `fit(…)`'s data file).
fn height_model(
    model: Option<&Spanned>,
    block: Span,
    data: Option<&crate::sema::DataReader>,
    diags: &mut Diagnostics,
) -> Option<Read> {
    let at = model.map_or(block, |m| m.span);
    let m = match &model?.value {
        Value::Call(c) if c.func == "fit" => return fitted(c, data, diags),
        Value::Call(c) if c.func == "table" => {
            let (t, w) = table(c, at, diags)?;
            return Some(Read {
                measured: Some(t.range()),
                model: HeightModel::Table(t),
                widths: w,
                fit: None,
                at: At::default(),
            });
        }
        Value::Call(c) if c.func == "power" => {
            let a = Fields::call(c, &POWER, diags);
            let h = a.quantity(&args::REF_HEIGHT, diags);
            let v = a.quantity(&args::REF_SPEED, diags);
            let e = a.bounded(&args::EXPONENT, message::bead::exponent_not_negative, diags);
            HeightModel::Power {
                height: Length(h?.0),
                speed: Speed(v?.0),
                exponent: e?.0,
            }
        }
        other => one_point_model(other, at, diags)?,
    };
    Some(Read {
        model: m,
        widths: None,
        measured: None,
        fit: None,
        at: At::default(),
    })
}

/// The models of typed-in numbers: `linear`, `mass_balance`, `measured`.
fn one_point_model(value: &Value, at: Span, diags: &mut Diagnostics) -> Option<HeightModel> {
    match value {
        Value::Call(c) if c.func == "linear" => {
            let a = Fields::call(c, &LINEAR, diags);
            let slope = a.bounded(&args::SLOPE, message::bead::slope_not_negative, diags);
            let b = a.quantity(&args::INTERCEPT, diags);
            Some(HeightModel::Linear {
                slope: slope?.0,
                intercept: Length(b?.0),
            })
        }
        Value::Call(c) if c.func == "mass_balance" => {
            let a = Fields::call(c, &MASS_BALANCE, diags);
            let feed = a.quantity(&args::FEED, diags);
            let eff = a.bounded(&args::EFFICIENCY, message::bead::efficiency_range, diags);
            let rho = a.quantity(&args::DENSITY, diags);
            Some(HeightModel::MassBalance {
                feed: MassFlow(feed?.0),
                efficiency: eff?.0,
                density: Density(rho?.0),
            })
        }
        Value::Call(c) if c.func == "measured" => {
            let a = Fields::call(c, &MEASURED, diags);
            let h = a.quantity(&args::HEIGHT, diags);
            let v = a.quantity(&args::SPEED, diags);
            Some(HeightModel::Measured {
                height: Length(h?.0),
                speed: Speed(v?.0),
            })
        }
        other => {
            diags.push(message::bead::unknown_model(at, &other.describe()));
            None
        }
    }
}

/// The tallest bead lmdc takes, mm: ten times a tall laser-deposited
/// bead's 5 mm (a taller one is a model in the wrong unit).
const MAX_BEAD_HEIGHT: f64 = 50.0;

/// The heights a bead of width `w` lays over its `speed` range (declared at
/// `spans.0`), narrowed to `height` if written: the layer heights allowed,
/// and where they are declared (`spans.1`, the model, when not written).
fn heights(
    deposit: &crate::deposit::Deposit,
    speed: [f64; 2],
    height: Option<([f64; 2], Span)>,
    (speed_span, model_span): (Span, Span),
    diags: &mut Diagnostics,
) -> Option<([Length; 2], Span)> {
    let (model, w) = (&deposit.model, deposit.width);
    // The model's heights at the ends of its speed range.
    let h_hi = model.height_at(Speed(speed[0]), w).0;
    let h_lo = model.height_at(Speed(speed[1]), w).0;
    if h_lo <= 0.0 || !h_lo.is_finite() || !h_hi.is_finite() {
        diags.push(message::bead::model_height_not_positive(
            Length(h_lo),
            Speed(speed[1]),
            speed_span,
            Some(model_span),
        ));
        return None;
    }
    // Metres of bead are a model in the wrong unit; the plan's layers,
    // its collision lumps and its machine moves would scale with them.
    if h_hi > MAX_BEAD_HEIGHT {
        diags.push(message::bead::model_height_too_tall(
            Length(h_hi),
            Speed(speed[0]),
            Length(MAX_BEAD_HEIGHT),
            speed_span,
            model_span,
        ));
        return None;
    }
    // A mass balance's bead is a flat cap, a fraction of its width high: a
    // cross-section of more than a square of its width (a one-bead wall
    // rising more than its width a layer) is no bead a nozzle lays, but a
    // density or feed in the wrong unit.
    let area = deposit.area(Speed(speed[0]), None);
    if matches!(model, HeightModel::MassBalance { .. }) && area > w.0 * w.0 {
        diags.push(message::bead::taller_than_wide(
            Length(area / w.0),
            Speed(speed[0]),
            w,
            model_span,
        ));
    }
    let (height, height_span) = match (height, model) {
        // Planar layers of a measured bead rise by A/w (one track) up to its
        // bead's height (tracks at the flat-top offset A/h): the heights it
        // can build.
        (None, HeightModel::Measured { speed: v, .. }) => (
            [deposit.rise(*v, w, None).0, deposit.bead_height(*v).0],
            model_span,
        ),
        (Some(([lo, hi], hs)), HeightModel::Measured { .. }) => ([lo, hi], hs),
        (None, _) => ([h_lo, h_hi], model_span),
        (Some(([lo, hi], hs)), _) => {
            let (elo, ehi) = (lo.max(h_lo), hi.min(h_hi));
            if lo <= 0.0 || elo > ehi {
                diags.push(message::bead::heights_do_not_overlap(
                    [Length(lo), Length(hi)],
                    [Speed(speed[0]), Speed(speed[1])],
                    [Length(h_lo), Length(h_hi)],
                    hs,
                    speed_span,
                ));
                return None;
            }
            ([elo, ehi], hs)
        }
    };
    Some(([Length(height[0]), Length(height[1])], height_span))
}

/// The bead model a field names (`wall = my_bead`, `bead = my_bead`); `what`
/// says what it builds ("the wall"). Unknown names get a "did you mean";
/// names declared with errors are not reported again.
pub fn named(
    v: Option<&Spanned>,
    key: &str,
    what: &str,
    beads: &BTreeMap<String, Bead>,
    declared: &[String],
    diags: &mut Diagnostics,
) -> Option<Bead> {
    match v {
        Some(Spanned {
            value: Value::Symbol(b),
            span,
        }) => match beads.get(b) {
            Some(bead) => Some(bead.clone()),
            None if declared.contains(b) => None,
            None => {
                let names: Vec<&str> = beads.keys().map(String::as_str).collect();
                diags.push(unknown_name(b, *span, "bead model", &names));
                None
            }
        },
        Some(v) => {
            diags.push(message::bead::bead_not_a_name(
                key,
                what,
                v.span,
                &v.value.describe(),
            ));
            None
        }
        None => None,
    }
}

/// Warns when a mass-balance model was fitted at another powder feed than the
/// process feeds (`powder`, written at `at`): its heights would not be the
/// ones laid.
pub fn check_feed(bead: &Bead, powder: MassFlow, at: Span, diags: &mut Diagnostics) {
    if let HeightModel::MassBalance { feed, .. } = &bead.model {
        if (feed.0 - powder.0).abs() > 0.01 * feed.0 {
            diags.push(message::bead::powder_mismatch(
                &bead.name, *feed, powder, at, bead.span,
            ));
        }
    }
}

/// Warns (`lmd::extrapolation`) where the process (a ramp's last power) or
/// a style (named) runs the laser at a power, or feeds powder, that the
/// bead was not measured at, when its `powers` or `powders` are known:
/// within 1 % of one of them counts. Each value comes with where it is
/// written.
#[allow(clippy::type_complexity)]
pub fn check_measured_at(
    bead: &Bead,
    powers: &[(Power, Span, Option<&str>)],
    powders: &[(MassFlow, Span, Option<&str>)],
    diags: &mut Diagnostics,
) {
    let near = |x: f64, of: f64| (x - of).abs() <= 0.01 * of;
    if let Some((ps, at)) = &bead.powers {
        for &(power, power_at, style) in powers {
            if !ps.iter().any(|p| near(power.0, p.0)) {
                diags.push(message::bead::unmeasured_power(
                    (&bead.name, *at),
                    power,
                    ps,
                    (power_at, style),
                ));
            }
        }
    }
    if let Some((fs, at)) = &bead.powders {
        for &(powder, powder_at, style) in powders {
            if !fs.iter().any(|f| near(powder.0, f.0)) {
                diags.push(message::bead::unmeasured_powder(
                    (&bead.name, *at),
                    powder,
                    fs,
                    (powder_at, style),
                ));
            }
        }
    }
}
