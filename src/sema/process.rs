//! `process { powder, defocus, power, power_range }`.

use super::fields::Fields;
use super::model::{PowerSchedule, Process};
use super::value::{Env, Value};
use crate::diag::{Code, Diagnostic, Diagnostics};
use crate::span::Span;
use crate::syntax::ast::Stmt;
use crate::units::{Dim, Length, MassFlow, Power, Speed};

/// Reads the process block.
pub fn read<'a>(
    env: &mut Env<'a>,
    stmts: &'a [Stmt],
    span: Span,
    diags: &mut Diagnostics,
) -> Option<Process> {
    let f = Fields::block(
        env,
        stmts,
        &["powder", "defocus", "power", "power_range", "speed"],
        &[],
        "process".into(),
        span,
        diags,
    );
    let powder = f.positive("powder", Dim::MASS_FLOW, Some("45.9 g/min"), diags);
    let defocus = match f.quantity("defocus", Dim::LENGTH, None, diags) {
        Some((d, _)) => Some(Length(d)),
        None if f.has("defocus") => None,
        None => Some(Length(0.0)),
    };
    let power_v = f.value("power", Some("2100 W"), diags);
    let power_span = power_v.map(|p| p.span).unwrap_or(span);
    let power = match power_v.map(|v| &v.value) {
        Some(Value::Call(c)) if c.func == "ramp" => {
            let a = Fields::call(c, &[], &["from", "to", "layers"], diags);
            let from = a.positive("from", Dim::POWER, Some("4000 W"), diags);
            let to = a.positive("to", Dim::POWER, Some("2100 W"), diags);
            let n = a.count("layers", 1, 1_000_000, Some("20"), diags);
            Some(PowerSchedule::Ramp {
                from: Power(from?.0),
                to: Power(to?.0),
                layers: n?.0,
            })
        }
        Some(_) => f
            .positive("power", Dim::POWER, None, diags)
            .map(|(p, _)| PowerSchedule::Constant(Power(p))),
        None => None,
    };
    let range = f.range("power_range", Dim::POWER, None, diags);
    let power = power?;
    let (lo, hi) = match power {
        PowerSchedule::Constant(p) => (p.0, p.0),
        PowerSchedule::Ramp { from, to, .. } => (from.0.min(to.0), from.0.max(to.0)),
    };
    let power_range_span = range.map(|r| r.1);
    let power_range = match range {
        Some(([a, b], rs)) => {
            if lo < a || hi > b {
                diags.push(
                    Diagnostic::error(
                        Code::OutOfRange,
                        format!(
                            "the power schedule reaches {} .. {}, outside the laser's range {} .. {}",
                            Power(lo), Power(hi), Power(a), Power(b)
                        ),
                    )
                    .label(power_span, "power")
                    .label(rs, "allowed range")
                    .help("keep the scheduled powers inside `power_range`"),
                );
                return None;
            }
            [Power(a), Power(b)]
        }
        None if f.has("power_range") => return None,
        None => [Power(lo), Power(hi)],
    };
    let speed = f
        .positive("speed", Dim::SPEED, None, diags)
        .map(|(v, sp)| (Speed(v), sp));
    if f.has("speed") && speed.is_none() {
        return None;
    }
    Some(Process {
        speed,
        powder: MassFlow(powder?.0),
        powder_span: powder?.1,
        defocus: defocus?,
        power,
        power_range,
        power_span,
        power_range_span,
    })
}
