//! `machine NAME { kind = robot | cnc, … }`: the cells lmdc writes programs for.
//! A machine is plain data, so the checked declaration is already the IR's
//! [`Machine`]. What either kind has (the height sensor, the cell's gas and
//! powder) is read here; [`robot`] and [`cnc`] read the rest.

pub mod cell;
mod cnc;
pub mod fixture;
mod head;
mod load;
pub mod origin;
mod positioner;
mod robot;
pub mod statements;

use super::eval::Env;
use super::fields::{self, Fields};
use super::schema::machine::{
    self as schema, ACCELERATION, BLENDING, HEIGHT_DELAY, HEIGHT_FULL_SCALE, HEIGHT_INPUT, LIMITS,
    LIMITS_BLOCK, MACHINE, MAX_BLENDING_MM, RAMP,
};
use super::schema::Field;
use crate::diag::{message, Diagnostics};
use crate::ir::{Cell, HeightSensor, Machine, MachineCommon, Ramp};
use crate::span::Span;
use crate::syntax::ast::{Body, Stmt};

/// The fields of a machine, each with where it is written: what the checks
/// point at ([`crate::ir::MachineOrigin`]).
pub type Written = Vec<(&'static Field, Span)>;

/// Reads a machine block: the machine, and where its fields are written.
pub fn read<'a>(
    env: &mut Env<'a>,
    name: &str,
    stmts: &'a [Stmt],
    span: Span,
    diags: &mut Diagnostics,
) -> Option<(Machine, Written)> {
    match kind(env, name, stmts, span, diags) {
        Some("robot") => robot::read(env, name, stmts, span, diags),
        Some(_) => cnc::read(env, name, stmts, span, diags),
        None => {
            // Which fields a machine has depends on its kind; without one, each
            // field is checked against what either kind takes, so a misspelt
            // field shows in the same run as the kind.
            let what = format!("machine `{name}`");
            let f = Fields::block(env, stmts, &MACHINE, what, span, diags);
            limits_block(env, &f, diags);
            None
        }
    }
}

/// `kind = robot | cnc`, when written right.
fn kind<'a>(
    env: &mut Env<'a>,
    name: &str,
    stmts: &'a [Stmt],
    span: Span,
    diags: &mut Diagnostics,
) -> Option<&'static str> {
    let kind_stmt = stmts.iter().find(|s| s.kind.node == schema::KIND.key);
    match kind_stmt.map(|s| &s.body) {
        // Evaluated quietly: reading the block reports its errors.
        Some(Body::Assign(e)) => {
            let v = env.eval(e, &mut Diagnostics::new())?;
            let words = schema::KIND.kind.words()?;
            fields::word(&v, schema::KIND.key, words, diags)
        }
        Some(_) => None,
        None => {
            diags.push(message::machine::missing_kind(name, span));
            None
        }
    }
}

/// The fields of `limits { … }`, if the block has one.
fn limits_block<'a>(
    env: &mut Env<'a>,
    f: &Fields<'a>,
    diags: &mut Diagnostics,
) -> Option<Fields<'a>> {
    let (inner, at) = f.nested(&LIMITS_BLOCK)?;
    Some(Fields::block(
        env,
        inner,
        &LIMITS,
        "limits".into(),
        at,
        diags,
    ))
}

/// The part of a machine either kind has, from what its reader read (each
/// reads them in its own order); its cell is added with the gas and powder.
fn common(
    name: &str,
    max_speed: Option<f64>,
    clearance: Option<f64>,
    height_sensor: Option<Option<HeightSensor>>,
    motion: Option<Motion>,
) -> Option<MachineCommon> {
    let motion = motion?;
    Some(MachineCommon {
        name: name.to_string(),
        max_speed: max_speed?,
        clearance: clearance?,
        cell: Cell::default(),
        height_sensor: height_sensor?,
        acceleration: motion.acceleration,
        blending: motion.blending,
        ramp: motion.ramp,
        head: crate::ir::Head::typical(),
    })
}

/// How a machine moves along a path and starts and stops a bead: its
/// `acceleration`, `blending` and `ramp`.
struct Motion {
    acceleration: Option<f64>,
    blending: Option<f64>,
    ramp: Ramp,
}

/// Reads `acceleration`, `blending` and `ramp` (a lead is sized by the
/// acceleration: `ramp = lead` needs one).
fn motion(f: &Fields<'_>, diags: &mut Diagnostics) -> Option<Motion> {
    let acceleration = f.quantity(&ACCELERATION, diags).map(|q| q.0);
    let blending = f
        .bounded(
            &BLENDING,
            |mm, at| message::machine::blending_out_of_range(mm, at, MAX_BLENDING_MM),
            diags,
        )
        .map(|q| q.0);
    let ramp = match f.word_or_default(&RAMP, diags)? {
        "lead" => Ramp::Lead,
        _ => Ramp::None,
    };
    let acceleration = f.optional(&ACCELERATION, acceleration)?;
    let blending = f.optional(&BLENDING, blending)?;
    if ramp == Ramp::Lead && acceleration.is_none() && !f.has(&ACCELERATION) {
        diags.push(message::machine::lead_without_acceleration(
            f.span(&RAMP),
            f.block_span(),
        ));
        return None;
    }
    Some(Motion {
        acceleration,
        blending,
        ramp,
    })
}

/// `height_input = n`, `height_full_scale = L`, `height_delay = t`: the
/// analog input a closed height loop reads, `n` within
/// `lowest..=highest`. `Some(None)` when the machine declares none, `None`
/// when a field is wrong (reported).
fn height_sensor(
    f: &Fields<'_>,
    lowest: usize,
    highest: usize,
    diags: &mut Diagnostics,
) -> Option<Option<HeightSensor>> {
    let input = f.count_in(&HEIGHT_INPUT, lowest, highest, diags);
    let scale = f.quantity(&HEIGHT_FULL_SCALE, diags);
    let delay = f.quantity_or_default(&HEIGHT_DELAY, diags);
    if input.is_none() && !f.has(&HEIGHT_INPUT) {
        for field in [&HEIGHT_FULL_SCALE, &HEIGHT_DELAY] {
            if let Some(at) = f.span(field) {
                diags.push(message::machine::sensor_without_input(field.key, at));
            }
        }
        return (!f.has(&HEIGHT_FULL_SCALE) && !f.has(&HEIGHT_DELAY)).then_some(None);
    }
    if input.is_some() && !f.has(&HEIGHT_FULL_SCALE) {
        diags.push(message::machine::sensor_without_full_scale(
            f.span(&HEIGHT_INPUT),
        ));
    }
    Some(Some(HeightSensor {
        input: input?.0 as u16,
        full_scale: scale?.0,
        delay: delay?,
    }))
}
