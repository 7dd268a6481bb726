//! `control height { kp, ki, clamp, target, run, plant }`: the PI loop that
//! corrects the speed of each segment of a segmented ring, layer by layer,
//! from its measured height.
//!
//! A gain is a change of speed per mm of height error. Its dimension is
//! 1/time, which cannot tell (mm/s)/mm from (m/s)/mm — 1000 apart, and the
//! paper's "s⁻¹" gains reproduce its results only read as the second — so
//! the checker also reads how the gain is *written*: its units must name a
//! length (`-3 mm/s/mm`, `-0.003 m/s/mm`); a plain number, `Hz` or `s^-1` is
//! refused with both readings spelled out.

use crate::control::{Clamp, SpeedPerLength};
use crate::diag::{message, Diagnostics};
use crate::sema::eval::Env;
use crate::sema::fields::Fields;
use crate::sema::model::LoopRun;
use crate::sema::schema::control::{self as schema, plant, CONTROL, INVERSE_SPEED};
use crate::sema::schema::Field;
use crate::sema::statement::{shape_error, single, Statements};
use crate::sema::value::Value;
use crate::span::Span;
use crate::syntax::ast::{Body, Expr, ExprKind, Stmt};
use crate::units::{Dim, Length, Speed};

/// How deep the spelling of a gain is followed through constants.
const MAX_SPELLING_DEPTH: usize = 32;

/// `control height { … }` as read.
#[derive(Clone, Debug)]
pub struct ControlSpec {
    /// `kP`.
    pub kp: SpeedPerLength,
    /// `kI`.
    pub ki: SpeedPerLength,
    /// The speeds the loop may command.
    pub clamp: Clamp,
    /// `target`, if written (else the layer height).
    pub target: Option<(Length, Span)>,
    /// Where the loop runs.
    pub run: LoopRun,
    /// The plant `lmdc simulate` and a schedule run against.
    pub plant: PlantSpec,
    /// The block.
    pub span: Span,
    /// `kp = …`.
    pub kp_span: Span,
    /// `ki = …`.
    pub ki_span: Span,
    /// `clamp = …`.
    pub clamp_span: Span,
    /// `run = …`, else the block.
    pub run_span: Span,
}

/// `plant = inverse_speed(drift = δ, factors = [...])`.
#[derive(Clone, Debug)]
pub struct PlantSpec {
    /// The drift per layer, a fraction.
    pub drift: f64,
    /// Each segment's deposition relative to the calibration, if given.
    pub factors: Option<(Vec<f64>, Span)>,
    /// Where it is written (the block when not).
    pub span: Span,
}

/// The file's `control` statement: `None` when there is none, `Some(None)`
/// when it is wrong (reported), with the statement's span.
pub fn statement<'a>(
    env: &mut Env<'a>,
    st: &Statements<'a>,
    constants: &[(String, Span, Expr)],
    diags: &mut Diagnostics,
) -> Option<(Option<ControlSpec>, Span)> {
    let stmts = st.get("control");
    if stmts.is_empty() {
        return None;
    }
    let s = single(stmts, "control", "control height { … }", diags)?;
    let spec = match (&s.name, &s.body) {
        (name, Body::Block(inner, _)) if name.as_ref().is_none_or(|n| n.node == "height") => {
            read(env, inner, s.span, constants, diags)
        }
        (Some(n), Body::Block(..)) => {
            diags.push(message::control::control_not_height(&n.node, n.span));
            None
        }
        _ => {
            diags.push(shape_error(
                s,
                "control height { … }",
                "control height { kp = -3 mm/s/mm  ki = -0.35 mm/s/mm  clamp = 1.9 mm/s .. 20 mm/s }",
            ));
            None
        }
    };
    Some((spec, s.span))
}

fn read<'a>(
    env: &mut Env<'a>,
    stmts: &'a [Stmt],
    span: Span,
    constants: &[(String, Span, Expr)],
    diags: &mut Diagnostics,
) -> Option<ControlSpec> {
    let f = Fields::block(env, stmts, &CONTROL, "control".into(), span, diags);
    let kp = gain(env, &f, &schema::KP, span, constants, diags);
    let ki = gain(env, &f, &schema::KI, span, constants, diags);
    let clamp = f.range(&schema::CLAMP, diags).and_then(|([lo, hi], at)| {
        match Clamp::new(Speed(lo), Speed(hi)) {
            Ok(c) => Some((c, at)),
            Err(e) => {
                diags.push(message::control::clamp_cannot_hold(&e, at));
                None
            }
        }
    });
    let target = f.optional(
        &schema::TARGET,
        f.quantity(&schema::TARGET, diags)
            .map(|(t, at)| (Length(t), at)),
    );
    let run = f.word_or_default(&schema::RUN, diags).map(|r| match r {
        "schedule" => LoopRun::Schedule,
        _ => LoopRun::OnMachine,
    });
    let plant = plant(&f, span, diags);
    let (kp, kp_span) = kp?;
    let (ki, ki_span) = ki?;
    let (clamp, clamp_span) = clamp?;
    Some(ControlSpec {
        kp,
        ki,
        clamp,
        target: target?,
        run: run?,
        plant: plant?,
        span,
        kp_span,
        ki_span,
        clamp_span,
        run_span: f.span(&schema::RUN).unwrap_or(span),
    })
}

/// A gain: a quantity of 1/time whose units name a length.
fn gain(
    env: &mut Env<'_>,
    f: &Fields<'_>,
    field: &Field,
    block: Span,
    constants: &[(String, Span, Expr)],
    diags: &mut Diagnostics,
) -> Option<(SpeedPerLength, Span)> {
    let (key, example) = (field.key, f.example(field));
    let Some(e) = f.expr(field) else {
        diags.push(message::control::missing_gain(key, block, example));
        return None;
    };
    let at = f.span(field).unwrap_or(e.span);
    let v = env.eval(e, diags)?;
    let q = match v.value {
        Value::Quantity(q) => q,
        other => {
            diags.push(message::control::gain_not_a_quantity(
                key,
                v.span,
                &other.describe(),
                example,
            ));
            return None;
        }
    };
    let mut units = Vec::new();
    spelled_units(e, constants, 0, &mut units);
    let names_length = units.iter().any(|u| names_a_length(u));
    if q.dim == SpeedPerLength::DIM && names_length {
        return SpeedPerLength::from_quantity(q).map(|g| (g, at));
    }
    diags.push(message::control::gain_unit(key, q, v.span, &units));
    None
}

/// The unit texts written in `e`, following constants by name.
fn spelled_units(
    e: &Expr,
    constants: &[(String, Span, Expr)],
    depth: usize,
    out: &mut Vec<String>,
) {
    if depth > MAX_SPELLING_DEPTH {
        return;
    }
    match &e.kind {
        ExprKind::Number { unit: Some(u), .. } => out.push(u.node.clone()),
        ExprKind::Number { unit: None, .. } | ExprKind::Str(_) => {}
        ExprKind::Ident(name) => {
            if let Some((_, _, c)) = constants.iter().find(|(n, _, _)| n == name) {
                spelled_units(c, constants, depth + 1, out);
            }
        }
        ExprKind::Call { args, .. } => {
            for a in args {
                spelled_units(&a.value, constants, depth + 1, out);
            }
        }
        ExprKind::List(items) => {
            for i in items {
                spelled_units(i, constants, depth + 1, out);
            }
        }
        ExprKind::Unary { expr, .. } => spelled_units(expr, constants, depth + 1, out),
        ExprKind::Binary { lhs, rhs, .. } => {
            spelled_units(lhs, constants, depth + 1, out);
            spelled_units(rhs, constants, depth + 1, out);
        }
    }
}

/// Whether a unit text names a length (`mm/s/mm`, `m/s/mm`; not `Hz`, `s^-1`).
fn names_a_length(unit: &str) -> bool {
    unit.split(['/', '*', '·'])
        .map(|f| f.split('^').next().unwrap_or(""))
        .any(|a| matches!(a, "mm" | "cm" | "m" | "um" | "µm" | "in"))
}

/// `plant = inverse_speed(drift = …, factors = […])`, else no drift.
fn plant(f: &Fields<'_>, block: Span, diags: &mut Diagnostics) -> Option<PlantSpec> {
    let Some(v) = f.value(&schema::PLANT, diags) else {
        return (!f.has(&schema::PLANT)).then_some(PlantSpec {
            drift: 0.0,
            factors: None,
            span: block,
        });
    };
    let Value::Call(c) = &v.value else {
        diags.push(message::control::plant_shape(v.span, &v.value.describe()));
        return None;
    };
    if c.func != "inverse_speed" {
        diags.push(message::control::plant_shape(
            c.func_span,
            &format!("`{}(…)`", c.func),
        ));
        return None;
    }
    let a = Fields::call(c, &INVERSE_SPEED, diags);
    let drift = a.quantity_or_default(&plant::DRIFT, diags);
    let factors = match a.value(&plant::FACTORS, diags) {
        None if a.has(&plant::FACTORS) => None,
        None => Some(None),
        Some(fv) => match &fv.value {
            Value::List(items) => {
                let xs: Vec<Option<f64>> = items
                    .iter()
                    .map(|i| match &i.value {
                        Value::Quantity(q)
                            if q.dim == Dim::NONE && q.value > 0.0 && q.value.is_finite() =>
                        {
                            Some(q.value)
                        }
                        other => {
                            diags.push(message::control::plant_factor(i.span, &other.describe()));
                            None
                        }
                    })
                    .collect();
                xs.into_iter()
                    .collect::<Option<Vec<f64>>>()
                    .map(|x| Some((x, fv.span)))
            }
            other => {
                diags.push(message::control::factors_not_a_list(
                    fv.span,
                    &other.describe(),
                ));
                None
            }
        },
    };
    Some(PlantSpec {
        drift: drift?,
        factors: factors?,
        span: v.span,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_gains_unit_must_name_a_length() {
        assert!(names_a_length("mm/s/mm"));
        assert!(names_a_length("m/s/mm"));
        assert!(names_a_length("mm/s^1/mm"));
        assert!(!names_a_length("Hz"));
        assert!(!names_a_length("s^-1"));
        assert!(!names_a_length("ms^-1"));
        assert!(!names_a_length("%"));
    }
}
