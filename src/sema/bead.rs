//! `bead NAME { width, height, speed, model }`: a bead model.

use super::eval::{unknown_name, Env};
use super::fields::Fields;
use super::model::{Bead, HeightModel};
use super::value::{Spanned, Value};
use crate::diag::{message, Diagnostics};
use crate::span::Span;
use crate::syntax::ast::Stmt;
use crate::units::{Density, Dim, Length, MassFlow, Speed};
use std::collections::BTreeMap;

/// Reads a bead block.
pub fn read<'a>(
    env: &mut Env<'a>,
    name: &str,
    stmts: &'a [Stmt],
    span: Span,
    diags: &mut Diagnostics,
) -> Option<Bead> {
    let f = Fields::block(
        env,
        stmts,
        &["width", "height", "speed", "model"],
        &[],
        format!("bead `{name}`"),
        span,
        diags,
    );
    let width = f.positive("width", Dim::LENGTH, Some("6 mm"), diags);
    // A measured bead brings its speed; every other model needs the range.
    let measured = matches!(
        f.value("model", None, &mut Diagnostics::new()).map(|m| &m.value),
        Some(Value::Call(c)) if c.func == "measured"
    );
    let required = (!measured).then_some("7 mm/s .. 10 mm/s");
    let speed = f.range("speed", Dim::SPEED, required, diags);
    let height = f.range("height", Dim::LENGTH, None, diags);
    let declared_height = height.map(|([lo, hi], _)| [Length(lo), Length(hi)]);
    let model = f.value(
        "model",
        Some("mass_balance(feed = 45.9 g/min, efficiency = 0.3, density = 7.9 g/cm^3)"),
        diags,
    );
    let model_span = model.map(|m| m.span);
    // A range that starts at zero or below is wrong whatever the model.
    let speed = speed.filter(|&(range, speed_span)| {
        if range[0] > 0.0 {
            return true;
        }
        diags.push(message::bead::speed_not_positive(speed_span));
        false
    });
    let model = match model.map(|m| &m.value) {
        Some(Value::Call(c)) if c.func == "linear" => {
            let a = Fields::call(c, &[], &["slope", "intercept"], diags);
            let slope = a.quantity("slope", Dim::TIME, Some("-0.135 mm / (1 mm/s)"), diags);
            let b = a.quantity("intercept", Dim::LENGTH, Some("1.82 mm"), diags);
            let slope = slope.filter(|&(slope, at)| {
                if slope < 0.0 {
                    return true;
                }
                diags.push(message::bead::slope_not_negative(slope, at));
                false
            });
            match (slope, b) {
                (Some(slope), Some(b)) => Some(HeightModel::Linear {
                    slope: slope.0,
                    intercept: Length(b.0),
                }),
                _ => None,
            }
        }
        Some(Value::Call(c)) if c.func == "mass_balance" => {
            let a = Fields::call(c, &[], &["feed", "efficiency", "density"], diags);
            let feed = a.positive("feed", Dim::MASS_FLOW, Some("45.9 g/min"), diags);
            let eff = a.positive("efficiency", Dim::NONE, Some("0.3"), diags);
            let rho = a.positive("density", Dim::DENSITY, Some("7.9 g/cm^3"), diags);
            let eff = eff.filter(|&(eff, at)| {
                if eff <= 1.0 {
                    return true;
                }
                diags.push(message::bead::efficiency_range(eff, at));
                false
            });
            match (feed, eff, rho) {
                (Some(feed), Some(eff), Some(rho)) => Some(HeightModel::MassBalance {
                    feed: MassFlow(feed.0),
                    efficiency: eff.0,
                    density: Density(rho.0),
                }),
                _ => None,
            }
        }
        Some(Value::Call(c)) if c.func == "measured" => {
            let a = Fields::call(c, &[], &["height", "speed"], diags);
            let h = a.positive("height", Dim::LENGTH, Some("0.7 mm"), diags);
            let v = a.positive("speed", Dim::SPEED, Some("6 mm/s"), diags);
            match (h, v) {
                (Some(h), Some(v)) => Some(HeightModel::Measured {
                    height: Length(h.0),
                    speed: Speed(v.0),
                }),
                _ => None,
            }
        }
        Some(other) => {
            diags.push(message::bead::unknown_model(
                model_span.unwrap_or(span),
                &other.describe(),
            ));
            None
        }
        None => None,
    };
    let model = model?;
    // A measured bead is valid at the speed it was measured at, unless the file
    // says over which range it holds.
    let speed = match (speed, model) {
        (Some(s), _) => Some(s),
        (None, HeightModel::Measured { speed: v, .. }) if !f.has("speed") => {
            Some(([v.0, v.0], model_span.unwrap_or(span)))
        }
        (None, _) => None,
    };
    let (width, (speed, speed_span)) = (width?, speed?);
    let w = Length(width.0);
    // The model's heights at the ends of its speed range.
    let h_hi = model.height_at(Speed(speed[0]), w).0;
    let h_lo = model.height_at(Speed(speed[1]), w).0;
    if h_lo <= 0.0 || !h_lo.is_finite() || !h_hi.is_finite() {
        diags.push(message::bead::model_height_not_positive(
            Length(h_lo),
            Speed(speed[1]),
            speed_span,
            model_span,
        ));
        return None;
    }
    let (height, height_span) = match (height, model) {
        // Planar layers of a measured bead rise by A/w (one track) up to h (tracks
        // at the flat-top offset A/h): the heights it can build.
        (None, HeightModel::Measured { height: h, .. }) => (
            [crate::bead::planar_lift(w, h, None).0, h.0],
            model_span.unwrap_or(span),
        ),
        (Some(([lo, hi], hs)), HeightModel::Measured { .. }) => ([lo, hi], hs),
        (None, _) => ([h_lo, h_hi], model_span.unwrap_or(span)),
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
    Some(Bead {
        name: name.to_string(),
        width: w,
        model,
        basis: crate::deposit::Basis::Track,
        declared_height,
        feed: None,
        speed: [Speed(speed[0]), Speed(speed[1])],
        height: [Length(height[0]), Length(height[1])],
        span,
        height_span,
        speed_span,
    })
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
