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

use super::eval::Env;
use super::fields::Fields;
use super::program_text;
use crate::diag::{message, Diagnostics};
use crate::ir::{Cell, Feeder, Gas, RateOutput};
use crate::span::Span;
use crate::syntax::ast::Stmt;
use crate::units::Dim;

/// The fields of a `gas { … }` block.
const GAS_FIELDS: &[&str] = &["output", "pre_flow", "post_flow"];
/// The fields of a `powder { … }` block.
const POWDER_FIELDS: &[&str] = &["output", "arrival", "rate_output", "full_scale"];
/// A CNC's lines that switch outputs (defaults from the dialect).
pub const CNC_LINES: &[&str] = &["output_on", "output_off", "analog_output"];

/// Longest gas or powder time, s: far beyond any cell's, short of a typo's.
const MAX_TIME_S: f64 = 600.0;

/// How a machine's control numbers its outputs.
#[derive(Clone, Copy, Debug)]
pub struct Outputs {
    /// Digital outputs `lo..=hi`.
    pub digital: (usize, usize),
    /// Analog outputs `lo..=hi`.
    pub analog: (usize, usize),
}

/// KUKA: `$OUT[1..4096]`, `$ANOUT[1..32]`.
pub const KUKA: Outputs = Outputs {
    digital: (1, 4096),
    analog: (1, 32),
};

/// LinuxCNC: `motion.digital-out-NN` and `motion.analog-out-NN`, 00–63.
pub const LINUXCNC: Outputs = Outputs {
    digital: (0, 63),
    analog: (0, 63),
};

/// Another G-code control, through the lines the machine block gives.
pub const OTHER_CNC: Outputs = Outputs {
    digital: (0, 9999),
    analog: (0, 9999),
};

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
    /// Where fields the verifier refers to are written (`powder.arrival`, …).
    pub spans: Vec<(String, Span)>,
}

/// Reads `gas { … }` and `powder { … }` of the machine whose fields are `f`.
/// `lines` are the CNC's output lines (`None` on a robot); `taken` the
/// outputs the machine already uses (`(number, analog, what)`), which gas and
/// powder must not share. `None` when something is wrong (reported).
pub fn read<'a>(
    env: &mut Env<'a>,
    f: &Fields<'a>,
    outputs: Outputs,
    lines: Option<[String; 3]>,
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
    // A block's output `key` (digital, or analog), read and claimed for
    // `what`: the number and where it is written, and whether it is free.
    let mut output = |b: &Fields<'_>,
                      key: &str,
                      analog: bool,
                      example: Option<&str>,
                      what: &str,
                      diags: &mut Diagnostics| {
        let (lo, hi) = if analog {
            outputs.analog
        } else {
            outputs.digital
        };
        let out = b.count(key, lo, hi, example, diags);
        let free = out.is_none_or(|(n, s)| claim(n, analog, what, s, diags));
        (out, free)
    };

    let gas = match f.nested("gas") {
        None => Some(None),
        Some((stmts, at)) => {
            let g = block(env, stmts, GAS_FIELDS, "gas", at, diags);
            let (out, claimed) = output(&g, "output", false, Some("2"), "the gas valve", diags);
            ok &= claimed;
            let pre = time(&g, "pre_flow", diags);
            let post = time(&g, "post_flow", diags);
            if let Some((_, s)) = out {
                spans.push(("gas.output".into(), s));
            }
            if let Some(s) = g.span("pre_flow") {
                spans.push(("gas.pre_flow".into(), s));
            }
            Some(Some(Gas {
                output: out?.0 as u16,
                pre_flow: pre?,
                post_flow: post?,
            }))
        }
    };
    let powder = match f.nested("powder") {
        None => Some(None),
        Some((stmts, at)) => {
            let p = block(env, stmts, POWDER_FIELDS, "powder", at, diags);
            let (out, claimed) = output(&p, "output", false, Some("3"), "the powder feeder", diags);
            ok &= claimed;
            let arrival = if p.has("arrival") {
                time(&p, "arrival", diags)
            } else {
                diags.push(message::machine::powder_without_arrival(at));
                None
            };
            if let Some(s) = p.span("arrival") {
                spans.push(("powder.arrival".into(), s));
            }
            let rate = match (p.has("rate_output"), p.has("full_scale")) {
                (false, false) => Some(None),
                (true, false) | (false, true) => {
                    let (has, lacks) = if p.has("rate_output") {
                        ("rate_output", "full_scale")
                    } else {
                        ("full_scale", "rate_output")
                    };
                    diags.push(message::machine::powder_rate_half(has, lacks, p.span(has)));
                    None
                }
                (true, true) => {
                    let (n, claimed) =
                        output(&p, "rate_output", true, None, "the powder feed rate", diags);
                    ok &= claimed;
                    let full = p.positive("full_scale", Dim::MASS_FLOW, None, diags);
                    if let Some((_, s)) = full {
                        spans.push(("powder.full_scale".into(), s));
                    }
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
    if let Some([on, off, analog]) = lines {
        if !cell.is_none() {
            let needs_analog = powder.is_some_and(|p| p.rate.is_some());
            for (key, text, needed) in [
                ("output_on", &on, true),
                ("output_off", &off, true),
                ("analog_output", &analog, needs_analog),
            ] {
                if needed && text.is_empty() {
                    diags.push(message::machine::no_output_line(
                        key,
                        f.span("gas").or(f.span("powder")),
                        f.span("dialect"),
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
    for (i, key) in CNC_LINES.iter().enumerate() {
        let Some((t, span)) = f.text(key, None, diags) else {
            ok &= !f.has(key);
            continue;
        };
        if !program_text::line(&t, key, span, diags) {
            ok = false;
            continue;
        }
        let holes: &[&str] = if *key == "analog_output" {
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

fn block<'a>(
    env: &mut Env<'a>,
    stmts: &'a [Stmt],
    allowed: &[&str],
    what: &str,
    at: Span,
    diags: &mut Diagnostics,
) -> Fields<'a> {
    Fields::block(env, stmts, allowed, &[], format!("`{what}`"), at, diags)
}

/// A time from 0 to [`MAX_TIME_S`] (0 when not written).
fn time(f: &Fields<'_>, key: &str, diags: &mut Diagnostics) -> Option<f64> {
    match f.quantity(key, Dim::TIME, None, diags) {
        Some((t, _)) if (0.0..=MAX_TIME_S).contains(&t) => Some(t),
        Some((t, at)) => {
            diags.push(message::field::time_out_of_range(key, t, MAX_TIME_S, at));
            None
        }
        None if f.has(key) => None,
        None => Some(0.0),
    }
}
