//! `bead NAME { width, height, speed, model }`: a bead model.

use super::eval::{unknown_name, Env};
use super::fields::Fields;
use super::model::{Bead, HeightModel};
use super::schema::bead::{
    self as schema, model as args, BEAD, LAYER, LINEAR, MASS_BALANCE, MEASURED,
};
use super::suggest::did_you_mean;
use super::value::{Spanned, Value};
use crate::deposit::Basis;
use crate::diag::{message, Diagnostics};
use crate::span::Span;
use crate::syntax::ast::Stmt;
use crate::units::{Density, Length, MassFlow, Speed};
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
    // A measured bead brings its speed; every other model needs the range.
    let measured = matches!(
        f.value(&schema::MODEL, &mut Diagnostics::new()).map(|m| &m.value),
        Some(Value::Call(c)) if c.func == "measured"
    );
    let speed = f.range(&schema::SPEED, diags);
    if !measured {
        f.require(&schema::SPEED, diags);
    }
    let height = f.range(&schema::HEIGHT, diags);
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
    let model = height_model(model, span, diags);
    let basis = basis(&f, model, model_span, diags);
    let (model, basis) = (model?, basis?);
    let model_span = model_span.unwrap_or(span);
    // A measured bead is valid at the speed it was measured at, unless the file
    // says over which range it holds.
    let speed = match (speed, model) {
        (Some(s), _) => Some(s),
        (None, HeightModel::Measured { speed: v, .. }) if !f.has(&schema::SPEED) => {
            Some(([v.0, v.0], model_span))
        }
        (None, _) => None,
    };
    let (width, (speed, speed_span)) = (width?, speed?);
    let w = Length(width.0);
    let deposit = crate::deposit::Deposit {
        model,
        width: w,
        basis,
    };
    let (height, height_span) = heights(deposit, speed, height, (speed_span, model_span), diags)?;
    Some(Bead {
        name: name.to_string(),
        width: w,
        model,
        basis,
        declared_height,
        feed: None,
        speed: [Speed(speed[0]), Speed(speed[1])],
        height,
        span,
        height_span,
        speed_span,
    })
}

/// What the model's heights were measured as (`measured_as = …`; a single
/// track when not written).
fn basis(
    f: &Fields<'_>,
    model: Option<HeightModel>,
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

/// The model `model = …` gives (`block` is where to point when the value
/// is no model at all and has no span of its own).
fn height_model(
    model: Option<&Spanned>,
    block: Span,
    diags: &mut Diagnostics,
) -> Option<HeightModel> {
    let at = model.map_or(block, |m| m.span);
    match &model?.value {
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

/// The heights a bead of width `w` lays over its `speed` range (declared at
/// `spans.0`), narrowed to `height` if written: the layer heights allowed,
/// and where they are declared (`spans.1`, the model, when not written).
fn heights(
    deposit: crate::deposit::Deposit,
    speed: [f64; 2],
    height: Option<([f64; 2], Span)>,
    (speed_span, model_span): (Span, Span),
    diags: &mut Diagnostics,
) -> Option<([Length; 2], Span)> {
    let (model, w) = (deposit.model, deposit.width);
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
    let (height, height_span) = match (height, model) {
        // Planar layers of a measured bead rise by A/w (one track) up to its
        // bead's height (tracks at the flat-top offset A/h): the heights it
        // can build.
        (None, HeightModel::Measured { speed: v, .. }) => (
            [deposit.rise(v, w, None).0, deposit.bead_height(v).0],
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
    if let HeightModel::MassBalance { feed, .. } = bead.model {
        if (feed.0 - powder.0).abs() > 0.01 * feed.0 {
            diags.push(message::bead::powder_mismatch(
                &bead.name, feed, powder, at, bead.span,
            ));
        }
    }
}
