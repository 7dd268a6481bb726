//! `gas { … }` and `powder { … }` in a machine block: the cell's shielding gas
//! valve and powder feeder, and (on a CNC) the lines that switch outputs.
//!
//! ```text
//! gas {
//!   output = 2
//!   pre_flow = 2 s
//!   post_flow = 5 s
//! }
//! powder {
//!   output = 3
//!   arrival = 2.5 s
//!   rate_output = 2
//!   full_scale = 60 g/min
//! }
//! ```
//!
//! The motion plan decides when they switch (`crate::plan`); this module only
//! checks what is declared: outputs in the range the control numbers them,
//! no output used twice, times within reason, and output lines a control can
//! read.

use crate::diag::{message, Diagnostics};
use crate::ir::{Cell, Feeder, Gas, RateOutput};
use crate::sema::eval::Env;
use crate::sema::fields::Fields;
use crate::sema::program_text;
use crate::sema::schema::machine::{self, gas, powder};
use crate::sema::schema::Field;
use crate::span::Span;
use crate::target::outputs::Outputs;

/// A CNC's lines that switch outputs (defaults from the dialect).
pub static CNC_LINES: [&Field; 3] = [
    &machine::OUTPUT_ON,
    &machine::OUTPUT_OFF,
    &machine::ANALOG_OUTPUT,
];

/// The built-in output lines of a G-code dialect: on, off, analog (empty
/// where lmdc knows none).
pub fn dialect_lines(profile: &str) -> [&'static str; 3] {
    match profile {
        // M64/M65/M68 wait for the motion before them to finish (LinuxCNC's
        // task waits for motion on an immediate output), so each switches
        // exactly where the plan stands still.
        "linuxcnc" => ["M64 P{n}", "M65 P{n}", "M68 E{n} Q{v}"],
        _ => ["", "", ""],
    }
}

/// What the block declares, with where.
pub struct Read {
    /// The cell.
    pub cell: Cell,
    /// Where the fields of `gas` and `powder` are written (the verifier
    /// points at `powder::ARRIVAL`, …).
    pub spans: Vec<(&'static Field, Span)>,
}

/// Reads `gas { … }` and `powder { … }` of the machine whose fields are `f`.
/// `lines` are the CNC's output lines (`None` on a robot); `taken` the
/// outputs the machine already uses (`(number, analog, what)`), which gas and
/// powder must not share. `None` when something is wrong (reported).
pub fn read<'a>(
    env: &mut Env<'a>,
    f: &Fields<'a>,
    outputs: Outputs,
    lines: Option<([String; 3], &str)>,
    taken: &[(usize, bool, &str, Option<Span>)],
    diags: &mut Diagnostics,
) -> Option<Read> {
    let mut ok = true;
    let mut spans = Vec::new();
    let mut used: Vec<(usize, bool, String, Option<Span>)> = taken
        .iter()
        .map(|&(n, a, w, s)| (n, a, w.to_string(), s))
        .collect();
    let mut claim = |n: usize, analog: bool, what: &str, at: Span, diags: &mut Diagnostics| {
        if let Some((_, _, other, first)) = used.iter().find(|u| u.0 == n && u.1 == analog) {
            diags.push(message::machine::output_clash(
                what, other, analog, n, at, *first,
            ));
            return false;
        }
        used.push((n, analog, what.to_string(), Some(at)));
        true
    };
    // A block's output `field` (digital, or analog), read and claimed for
    // `what`: the number and where it is written, and whether it is free.
    let mut output =
        |b: &Fields<'_>, field: &Field, analog: bool, what: &str, diags: &mut Diagnostics| {
            let (lo, hi) = if analog {
                outputs.analog
            } else {
                outputs.digital
            };
            let out = b.count_in(field, lo, hi, diags);
            let free = out.is_none_or(|(n, s)| claim(n, analog, what, s, diags));
            (out, free)
        };

    let gas = match f.nested(&machine::GAS_BLOCK) {
        None => Some(None),
        Some((stmts, at)) => {
            let g = Fields::block(env, stmts, &machine::GAS, "`gas`".into(), at, diags);
            let (out, claimed) = output(&g, &gas::OUTPUT, false, "the gas valve", diags);
            ok &= claimed;
            let pre = g.quantity_or_default(&gas::PRE_FLOW, diags);
            let post = g.quantity_or_default(&gas::POST_FLOW, diags);
            spans.extend(g.written());
            Some(Some(Gas {
                output: out?.0 as u16,
                pre_flow: pre?,
                post_flow: post?,
            }))
        }
    };
    let powder = match f.nested(&machine::POWDER_BLOCK) {
        None => Some(None),
        Some((stmts, at)) => {
            let p = Fields::block(env, stmts, &machine::POWDER, "`powder`".into(), at, diags);
            let (out, claimed) = output(&p, &powder::OUTPUT, false, "the powder feeder", diags);
            ok &= claimed;
            let arrival = if p.has(&powder::ARRIVAL) {
                p.quantity(&powder::ARRIVAL, diags).map(|t| t.0)
            } else {
                diags.push(message::machine::powder_without_arrival(at));
                None
            };
            // The feed rate's checks point at its value, not its key.
            spans.extend(p.written().filter(|(f, _)| *f != &powder::FULL_SCALE));
            let rate = match (p.has(&powder::RATE_OUTPUT), p.has(&powder::FULL_SCALE)) {
                (false, false) => Some(None),
                (true, false) | (false, true) => {
                    let (has, lacks) = if p.has(&powder::RATE_OUTPUT) {
                        (&powder::RATE_OUTPUT, &powder::FULL_SCALE)
                    } else {
                        (&powder::FULL_SCALE, &powder::RATE_OUTPUT)
                    };
                    diags.push(message::machine::powder_rate_half(
                        has.key,
                        lacks.key,
                        p.span(has),
                    ));
                    None
                }
                (true, true) => {
                    let (n, claimed) = output(
                        &p,
                        &powder::RATE_OUTPUT,
                        true,
                        "the powder feed rate",
                        diags,
                    );
                    ok &= claimed;
                    let full = p.quantity(&powder::FULL_SCALE, diags);
                    spans.extend(full.map(|(_, s)| (&powder::FULL_SCALE, s)));
                    Some(Some(RateOutput {
                        output: n?.0 as u16,
                        // g/s (canonical) → g/min
                        full_scale: full?.0 * 60.0,
                    }))
                }
            };
            Some(Some(Feeder {
                output: out?.0 as u16,
                arrival: arrival?,
                rate: rate?,
            }))
        }
    };
    let (gas, powder) = (gas?, powder?);
    let mut cell = Cell {
        gas,
        powder,
        ..Cell::default()
    };
    if let Some(([on, off, analog], profile)) = lines {
        if !cell.is_none() {
            let needs_analog = powder.is_some_and(|p| p.rate.is_some());
            for (field, text, needed) in [
                (CNC_LINES[0], &on, true),
                (CNC_LINES[1], &off, true),
                (CNC_LINES[2], &analog, needs_analog),
            ] {
                if needed && text.is_empty() {
                    diags.push(message::machine::no_output_line(
                        field.key,
                        profile,
                        f.span(&machine::GAS_BLOCK)
                            .or(f.span(&machine::POWDER_BLOCK)),
                        f.span(&machine::DIALECT),
                    ));
                    ok = false;
                }
            }
        }
        cell.output_on = on;
        cell.output_off = off;
        cell.analog_output = analog;
    }
    ok.then_some(Read { cell, spans })
}

/// The CNC's output lines: the dialect's, overridden by the machine block's
/// (each one printable line holding `{n}` once, the analog one `{v}` too).
/// `None` when one is wrong (reported).
pub fn cnc_lines(f: &Fields<'_>, profile: &str, diags: &mut Diagnostics) -> Option<[String; 3]> {
    let mut out = dialect_lines(profile).map(String::from);
    let mut ok = true;
    for (i, field) in CNC_LINES.iter().enumerate() {
        let key = field.key;
        let Some((t, span)) = f.text(field, diags) else {
            ok &= !f.has(field);
            continue;
        };
        if !program_text::line(&t, key, span, diags) {
            ok = false;
            continue;
        }
        let holes: &[&str] = if std::ptr::eq(*field, &machine::ANALOG_OUTPUT) {
            &["{n}", "{v}"]
        } else {
            &["{n}"]
        };
        if let Some(h) = holes.iter().find(|h| t.matches(**h).count() != 1) {
            diags.push(message::machine::output_line_hole(
                key,
                h,
                span,
                dialect_lines("linuxcnc")[i],
            ));
            ok = false;
            continue;
        }
        out[i] = t;
    }
    ok.then_some(out)
}
