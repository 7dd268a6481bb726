//! The functions of expressions besides `min` and `max`: `sin`, `cos`,
//! `tan` of an angle; `asin`, `acos` of a plain number and `atan2(y, x)`
//! of two values of one kind, giving angles; `sqrt` of a value whose unit
//! has even powers (`sqrt(9 mm^2)` is `3 mm`); `abs` of anything. Units are
//! checked as for the operators: `sin(30)` is an error that asks for
//! `30 deg`, and a value outside a function's domain (`asin(2)`,
//! `sqrt(-1 mm^2)`, `tan(90 deg)`) is `lmd::domain`.

use crate::diag::{message, Diagnostics};
use crate::sema::value::{CallArg, Value};
use crate::span::Span;
use crate::units::{Dim, Quantity};

/// The functions this module computes.
pub const FUNCTIONS: [&str; 8] = ["sin", "cos", "tan", "asin", "acos", "atan2", "sqrt", "abs"];

/// `func(args)` at `span`, or `None` after reporting why not.
pub fn call(func: &str, span: Span, args: &[CallArg], diags: &mut Diagnostics) -> Option<Value> {
    let arity = if func == "atan2" { 2 } else { 1 };
    if args.len() != arity || args.iter().any(|a| a.name.is_some()) {
        diags.push(message::value::math_arity(func, arity, span));
        return None;
    }
    let mut qs = Vec::with_capacity(arity);
    for a in args {
        match &a.value.value {
            Value::Quantity(q) => qs.push((*q, a.value.span)),
            other => {
                diags.push(message::value::math_not_number(
                    func,
                    other.got(),
                    a.value.span,
                ));
                return None;
            }
        }
    }
    let (q, at) = qs[0];
    let want = |dim: Dim, diags: &mut Diagnostics| {
        (q.dim == dim)
            .then_some(q.value)
            .ok_or_else(|| diags.push(message::value::math_unit(func, dim, q.dim, at)))
            .ok()
    };
    let out = match func {
        "sin" | "cos" | "tan" => {
            let a = want(Dim::ANGLE, diags)?;
            let v = match func {
                "sin" => a.sin(),
                "cos" => a.cos(),
                _ => {
                    // A right angle, to the float noise of `90 deg` in rad.
                    if a.cos().abs() < 1e-12 {
                        diags.push(message::value::math_domain(func, "a right angle", at));
                        return None;
                    }
                    a.tan()
                }
            };
            Quantity {
                value: v,
                dim: Dim::NONE,
            }
        }
        "asin" | "acos" => {
            let v = want(Dim::NONE, diags)?;
            if !(-1.0..=1.0).contains(&v) {
                diags.push(message::value::math_outside_one(func, v, at));
                return None;
            }
            let a = if func == "asin" { v.asin() } else { v.acos() };
            Quantity {
                value: a,
                dim: Dim::ANGLE,
            }
        }
        "atan2" => {
            let (x, x_at) = qs[1];
            if x.dim != q.dim {
                diags.push(message::value::min_max_units_differ(
                    func, q.dim, x.dim, x_at,
                ));
                return None;
            }
            Quantity {
                value: q.value.atan2(x.value),
                dim: Dim::ANGLE,
            }
        }
        "sqrt" => {
            let d = q.dim;
            if [d.l, d.m, d.t, d.a].iter().any(|e| e % 2 != 0) {
                diags.push(message::value::math_sqrt_unit(q.dim, at));
                return None;
            }
            if q.value < 0.0 {
                diags.push(message::value::math_domain(func, "a negative value", at));
                return None;
            }
            Quantity {
                value: q.value.sqrt(),
                dim: Dim::new(d.l / 2, d.m / 2, d.t / 2, d.a / 2),
            }
        }
        _ => Quantity {
            value: q.value.abs(),
            dim: q.dim,
        },
    };
    Some(Value::Quantity(out))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diag::Code;
    use crate::sema::value::Spanned;

    fn q(value: f64, dim: Dim) -> CallArg {
        CallArg {
            name: None,
            value: Spanned {
                value: Value::Quantity(Quantity { value, dim }),
                span: Span::new(0, 1),
            },
        }
    }

    fn run(func: &str, args: &[CallArg]) -> Result<Quantity, Vec<Code>> {
        let mut d = Diagnostics::new();
        match call(func, Span::new(0, 1), args, &mut d) {
            Some(Value::Quantity(q)) => Ok(q),
            _ => Err(d.iter().map(|d| d.code).collect()),
        }
    }

    #[test]
    fn values_and_units() {
        let deg = std::f64::consts::PI / 180.0;
        let near = |a: Quantity, v: f64, dim: Dim| (a.value - v).abs() < 1e-12 && a.dim == dim;
        assert!(near(
            run("sin", &[q(30.0 * deg, Dim::ANGLE)]).unwrap(),
            0.5,
            Dim::NONE
        ));
        assert!(near(
            run("cos", &[q(60.0 * deg, Dim::ANGLE)]).unwrap(),
            0.5,
            Dim::NONE
        ));
        assert!(near(
            run("tan", &[q(45.0 * deg, Dim::ANGLE)]).unwrap(),
            1.0,
            Dim::NONE
        ));
        assert!(near(
            run("asin", &[q(0.5, Dim::NONE)]).unwrap(),
            30.0 * deg,
            Dim::ANGLE
        ));
        assert!(near(
            run("acos", &[q(0.5, Dim::NONE)]).unwrap(),
            60.0 * deg,
            Dim::ANGLE
        ));
        let at2 = run("atan2", &[q(-3.0, Dim::LENGTH), q(-3.0, Dim::LENGTH)]).unwrap();
        assert!(near(at2, -135.0 * deg, Dim::ANGLE));
        let area = Dim::LENGTH.powi(2);
        assert!(near(
            run("sqrt", &[q(9.0, area)]).unwrap(),
            3.0,
            Dim::LENGTH
        ));
        assert!(near(
            run("abs", &[q(-2.5, Dim::SPEED)]).unwrap(),
            2.5,
            Dim::SPEED
        ));
    }

    #[test]
    fn wrong_kinds_and_domains_are_errors() {
        assert_eq!(
            run("sin", &[q(30.0, Dim::NONE)]),
            Err(vec![Code::UnitMismatch])
        );
        assert_eq!(run("asin", &[q(2.0, Dim::NONE)]), Err(vec![Code::Domain]));
        assert_eq!(
            run("acos", &[q(0.5, Dim::LENGTH)]),
            Err(vec![Code::UnitMismatch])
        );
        assert_eq!(
            run("sqrt", &[q(4.0, Dim::LENGTH)]),
            Err(vec![Code::UnitMismatch])
        );
        assert_eq!(run("sqrt", &[q(-4.0, Dim::NONE)]), Err(vec![Code::Domain]));
        let right = std::f64::consts::FRAC_PI_2;
        assert_eq!(run("tan", &[q(right, Dim::ANGLE)]), Err(vec![Code::Domain]));
        assert_eq!(
            run("atan2", &[q(1.0, Dim::LENGTH), q(1.0, Dim::TIME)]),
            Err(vec![Code::UnitMismatch])
        );
        assert_eq!(run("cos", &[]), Err(vec![Code::Argument]));
        assert_eq!(
            run("abs", &[q(1.0, Dim::NONE), q(1.0, Dim::NONE)]),
            Err(vec![Code::Argument])
        );
    }
}
