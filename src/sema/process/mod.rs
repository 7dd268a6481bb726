//! `process { powder, defocus, power, power_range, speed, min_layer_time, dwell }`;
//! a ring's process is only `powder` and `power_range`, the rest being per
//! segment in its table.

pub mod bead;
pub mod calibration;
pub mod control;
pub mod style;
pub mod thermal;

use crate::diag::{message, Diagnostics};
use crate::ir::Heat;
use crate::sema::eval::Env;
use crate::sema::fields::Fields;
use crate::sema::model::{within, PowerSchedule, Process};
use crate::sema::schema::process::{self as schema, ramp, PROCESS, RAMP, RING_PROCESS};
use crate::sema::statement::{shape_error, single, Statements};
use crate::sema::value::{Spanned, Value};
use crate::span::Span;
use crate::syntax::ast::{Body, Stmt};
use crate::units::{Length, MassFlow, Power, Speed};

/// The process block as read: the whole of it when every field is right, and
/// the parts other checks use on their own, so that a wrong field does not
/// hide a mistake elsewhere that only needs another one.
#[derive(Default)]
pub struct Read {
    /// Every value, when each one is right.
    pub process: Option<Process>,
    /// The laser's range, if known.
    pub laser: Option<Laser>,
    /// The scan speed: `Some(None)` when not written, `None` when wrong.
    pub speed: Option<Option<(Speed, Span)>>,
    /// The powder feed and where it is written, if right.
    pub powder: Option<(MassFlow, Span)>,
}

/// The powers the laser may give: `power_range`, or the scheduled powers
/// when no range is declared.
#[derive(Clone, Copy, Debug)]
pub struct Laser {
    /// Lowest and highest power.
    pub range: [Power; 2],
    /// `power_range = …`, if declared.
    pub range_span: Option<Span>,
    /// `power = …` (the block when it is missing).
    pub power_span: Span,
}

impl Laser {
    /// Whether the laser can give `p`.
    pub fn covers(&self, p: Power) -> bool {
        within(p.0, self.range[0].0, self.range[1].0)
    }
}

/// The file's `process { … }` statement. `ring` is `Some` when the solid is a
/// ring: its table's powers and where they are written, when right.
pub fn statement<'a>(
    env: &mut Env<'a>,
    st: &Statements<'a>,
    ring: Option<Option<([Power; 2], Span)>>,
    diags: &mut Diagnostics,
) -> Read {
    let Some(s) = single(
        st.get("process"),
        "process",
        "process { powder = 45.9 g/min  power = 2100 W }",
        diags,
    ) else {
        return Read::default();
    };
    match (&s.name, &s.body) {
        (None, Body::Block(stmts, _)) => match ring {
            Some(powers) => read_ring(env, stmts, s.span, powers, diags),
            None => read(env, stmts, s.span, diags),
        },
        _ => {
            diags.push(shape_error(
                s,
                "process { … }",
                "process { power = 2100 W }",
            ));
            Read::default()
        }
    }
}

/// Reads a ring's process block: powder and the laser's range; the
/// "schedule" the range is checked against is the table's powers.
fn read_ring<'a>(
    env: &mut Env<'a>,
    stmts: &'a [Stmt],
    span: Span,
    powers: Option<([Power; 2], Span)>,
    diags: &mut Diagnostics,
) -> Read {
    let f = Fields::block(env, stmts, &RING_PROCESS, "process".into(), span, diags);
    let mut ok = true;
    for field in RING_PROCESS.refused {
        if let Some(at) = f.span(field) {
            diags.push(message::bead::not_for_a_ring(field.key, at));
            ok = false;
        }
    }
    let powder = f
        .quantity(&schema::POWDER, diags)
        .map(|(m, sp)| (MassFlow(m), sp));
    let range = f.range(&schema::POWER_RANGE, diags);
    let laser = match (range, powers) {
        (Some(([a, b], rs)), Some(([lo, hi], ps))) => {
            if lo.0 < a || hi.0 > b {
                diags.push(message::bead::ring_powers_out_of_range(
                    lo,
                    hi,
                    Power(a),
                    Power(b),
                    ps,
                    rs,
                ));
                ok = false;
            }
            Some(Laser {
                range: [Power(a), Power(b)],
                range_span: Some(rs),
                power_span: ps,
            })
        }
        (None, Some((r, ps))) if !f.has(&schema::POWER_RANGE) => Some(Laser {
            range: r,
            range_span: None,
            power_span: ps,
        }),
        _ => None,
    };
    let process = match (powder, laser) {
        (Some((powder, powder_span)), Some(l)) if ok => Some(Process {
            heat: Heat::default(),
            thermal: None,
            speed: None,
            powder,
            powder_span,
            defocus: Length(0.0),
            // The points carry each segment's power; this is the laser's top.
            power: PowerSchedule::Constant(l.range[1]),
            power_range: l.range,
            power_span: l.power_span,
            power_range_span: l.range_span,
        }),
        _ => None,
    };
    Read {
        process,
        laser,
        speed: Some(None),
        powder,
    }
}

/// Reads the process block.
fn read<'a>(env: &mut Env<'a>, stmts: &'a [Stmt], span: Span, diags: &mut Diagnostics) -> Read {
    let f = Fields::block(env, stmts, &PROCESS, "process".into(), span, diags);
    // Every field is read before any is combined with another.
    let powder = f
        .quantity(&schema::POWDER, diags)
        .map(|(m, sp)| (MassFlow(m), sp));
    let defocus = f.quantity_or_default(&schema::DEFOCUS, diags).map(Length);
    let power_v = f.value(&schema::POWER, diags);
    let power_span = power_v.map(|p| p.span).unwrap_or(span);
    let power = power_v.and_then(|v| power_schedule(&f, v, diags));
    let range = f.range(&schema::POWER_RANGE, diags);
    let heat = heat(&f, diags);
    let thermal = thermal::read(env, &f, diags);
    let speed = f.optional(
        &schema::SPEED,
        f.quantity(&schema::SPEED, diags)
            .map(|(v, sp)| (Speed(v), sp)),
    );
    let laser = laser(&f, power, range, power_span, diags);
    let process = match (powder, defocus, power, laser, speed, heat, thermal) {
        (
            Some((powder, powder_span)),
            Some(defocus),
            Some(power),
            Some(l),
            Some(speed),
            Some(heat),
            Some(thermal),
        ) => Some(Process {
            heat,
            thermal,
            speed,
            powder,
            powder_span,
            defocus,
            power,
            power_range: l.range,
            power_span,
            power_range_span: l.range_span,
        }),
        _ => None,
    };
    Read {
        process,
        laser,
        speed,
        powder,
    }
}

/// `power = …` written as `v`: a constant power or a `ramp(…)`.
fn power_schedule(f: &Fields<'_>, v: &Spanned, diags: &mut Diagnostics) -> Option<PowerSchedule> {
    match &v.value {
        Value::Call(c) if c.func == "ramp" => {
            let a = Fields::call(c, &RAMP, diags);
            let from = a.quantity(&ramp::FROM, diags);
            let to = a.quantity(&ramp::TO, diags);
            let n = a.count(&ramp::LAYERS, diags);
            Some(PowerSchedule::Ramp {
                from: Power(from?.0),
                to: Power(to?.0),
                layers: n?.0,
            })
        }
        _ => f
            .quantity(&schema::POWER, diags)
            .map(|(p, _)| PowerSchedule::Constant(Power(p))),
    }
}

/// `min_layer_time` and `dwell`; `None` when one is wrong (reported).
fn heat(f: &Fields<'_>, diags: &mut Diagnostics) -> Option<Heat> {
    // Both are read, so that both are reported.
    let min_layer_time = f.quantity_or_default(&schema::MIN_LAYER_TIME, diags);
    let dwell = f.quantity_or_default(&schema::DWELL, diags);
    Some(Heat {
        min_layer_time: min_layer_time?,
        dwell: dwell?,
    })
}

/// The laser's range (`range`, declared at `power_range`, else the
/// scheduled powers'), and a schedule outside a declared range reported.
fn laser(
    f: &Fields<'_>,
    power: Option<PowerSchedule>,
    range: Option<([f64; 2], Span)>,
    power_span: Span,
    diags: &mut Diagnostics,
) -> Option<Laser> {
    // The scheduled powers, and the laser's range: declared, else theirs.
    let scheduled = power.map(|p| match p {
        PowerSchedule::Constant(p) => (p.0, p.0),
        PowerSchedule::Ramp { from, to, .. } => (from.0.min(to.0), from.0.max(to.0)),
    });
    let laser = match (range, scheduled) {
        (Some(([a, b], rs)), _) => Some(Laser {
            range: [Power(a), Power(b)],
            range_span: Some(rs),
            power_span,
        }),
        (None, _) if f.has(&schema::POWER_RANGE) => None,
        (None, Some((lo, hi))) => Some(Laser {
            range: [Power(lo), Power(hi)],
            range_span: None,
            power_span,
        }),
        (None, None) => None,
    };
    // A schedule outside the laser's range is reported here, at the
    // declarations; the process is kept, so that the machine checks still run
    // in this run (the verifier's own point-power rule then says nothing more:
    // see `pipeline`).
    if let (Some(l), Some((lo, hi)), Some(rs)) =
        (laser, scheduled, laser.and_then(|l| l.range_span))
    {
        let [a, b] = l.range;
        if lo < a.0 || hi > b.0 {
            diags.push(message::bead::schedule_out_of_range(
                Power(lo),
                Power(hi),
                a,
                b,
                power_span,
                rs,
            ));
        }
    }
    laser
}
