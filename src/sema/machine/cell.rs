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
//! checks what is declared: outputs in the range the control numbers them
//! (on an ABB robot, or a signal's name RAPID can use: [`signal`]), no
//! output used twice, times within reason, and output lines a control can
//! read.

use crate::diag::{message, Diagnostics};
use crate::ir::{Cell, Feeder, Gas, RateOutput, Signal};
use crate::sema::eval::Env;
use crate::sema::fields::Fields;
use crate::sema::program_text;
use crate::sema::schema::machine::{self, gas, powder};
use crate::sema::schema::Field;
use crate::sema::value::Value;
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

/// How a machine's outputs are written: by number only (a KUKA robot, a
/// CNC), or also by a signal's name (an ABB robot).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Naming {
    /// A KUKA robot: `$OUT[n]`, `$ANOUT[n]`.
    Kuka,
    /// A CNC: its output lines' `{n}`.
    Cnc,
    /// An ABB robot: `do<n>`, `ao<n>`, or a named signal.
    Abb,
}

/// The names an ABB robot's program uses besides its `lmd_…` data: its
/// routine `main`, ABB's `v200` and `fine`. A signal so named would clash.
const PROGRAM_NAMES: [&str; 3] = ["main", "v200", "fine"];

/// Output `field` of a block (`b`): a whole number from `lo` to `hi`, or on
/// an ABB robot a signal's name in quotes, a RAPID name the program can
/// use. `None` when not written or wrong (reported).
pub fn signal(
    b: &Fields<'_>,
    field: &Field,
    (lo, hi): (usize, usize),
    naming: Naming,
    diags: &mut Diagnostics,
) -> Option<(Signal, Span)> {
    let v = b.value(field, diags)?;
    let Value::Str(name) = &v.value else {
        let n = crate::sema::fields::count(v, field.key, lo, hi, diags)?;
        return Some((Signal::Number(n as u16), v.span));
    };
    if naming != Naming::Abb {
        let robot = naming == Naming::Kuka;
        diags.push(message::machine::signal_name_numbered(
            field.key, v.span, robot,
        ));
        return None;
    }
    let why = rapid_name_fault(name);
    if let Some(why) = why {
        diags.push(message::machine::signal_name_invalid(
            field.key, name, v.span, &why,
        ));
        return None;
    }
    Some((Signal::Name(name.clone()), v.span))
}

/// Why `name` cannot name a signal in an ABB robot's program, if it cannot.
fn rapid_name_fault(name: &str) -> Option<String> {
    let upper = name.to_ascii_uppercase();
    let lower = name.to_ascii_lowercase();
    let count = name.chars().count();
    let first_letter = name.chars().next().is_some_and(|c| c.is_ascii_alphabetic());
    if !first_letter || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        Some("a RAPID name is a letter, then letters, digits and `_`".into())
    } else if count > crate::target::rapid::MAX_NAME {
        Some(format!(
            "it has {count} characters, more than RAPID's {}",
            crate::target::rapid::MAX_NAME
        ))
    } else if crate::target::rapid::RESERVED.contains(&upper.as_str()) {
        Some(format!("`{upper}` is a RAPID reserved word"))
    } else if lower.starts_with("lmd_") || PROGRAM_NAMES.contains(&lower.as_str()) {
        Some(format!(
            "`{name}` is one of the program's own names (`lmd_…`, `main`, `v200`, `fine`)"
        ))
    } else {
        None
    }
}

/// How `s` is spelt in an ABB robot's program (`do3`, `ao2`, a name), in
/// lower case: two outputs spelt alike are the same (RAPID's names are the
/// same in either case, and a number `n` is `do<n>` or `ao<n>` as on a KUKA
/// robot `$OUT[n]` and `$ANOUT[n]` differ by kind).
fn spelt(s: &Signal, analog: bool) -> String {
    crate::target::rapid::signal(s, analog).to_ascii_lowercase()
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
/// outputs the machine already uses (`(output, analog, what)`), which gas and
/// powder must not share. `None` when something is wrong (reported).
pub fn read<'a>(
    env: &mut Env<'a>,
    f: &Fields<'a>,
    (outputs, naming): (Outputs, Naming),
    lines: Option<([String; 3], &str)>,
    taken: &[(Signal, bool, &str, Option<Span>)],
    diags: &mut Diagnostics,
) -> Option<Read> {
    let mut ok = true;
    let mut spans = Vec::new();
    let mut used: Vec<(String, String, Option<Span>)> = taken
        .iter()
        .map(|(n, a, w, s)| (spelt(n, *a), w.to_string(), *s))
        .collect();
    let mut claim = |n: &Signal, analog: bool, what: &str, at: Span, diags: &mut Diagnostics| {
        let key = spelt(n, analog);
        if let Some((_, other, first)) = used.iter().find(|u| u.0 == key) {
            diags.push(message::machine::output_clash(
                what,
                other,
                (analog, n),
                at,
                *first,
            ));
            return false;
        }
        used.push((key, what.to_string(), Some(at)));
        true
    };
    // A block's output `field` (digital, or analog), read and claimed for
    // `what`: the output and where it is written, and whether it is free.
    let mut output =
        |b: &Fields<'_>, field: &Field, analog: bool, what: &str, diags: &mut Diagnostics| {
            let range = if analog {
                outputs.analog
            } else {
                outputs.digital
            };
            let out = signal(b, field, range, naming, diags);
            let free = out
                .as_ref()
                .is_none_or(|(n, s)| claim(n, analog, what, *s, diags));
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
            // Wrong (`None`) without stopping here: the powder is read too.
            let gas = || {
                Some(Gas {
                    output: out?.0,
                    pre_flow: pre?,
                    post_flow: post?,
                })
            };
            gas().map(Some)
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
                    let rate = || {
                        Some(RateOutput {
                            output: n?.0,
                            // g/s (canonical) → g/min
                            full_scale: full?.0 * 60.0,
                        })
                    };
                    rate().map(Some)
                }
            };
            let feeder = || {
                Some(Feeder {
                    output: out?.0,
                    arrival: arrival?,
                    rate: rate?,
                })
            };
            feeder().map(Some)
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
            let needs_analog = cell.powder.as_ref().is_some_and(|p| p.rate.is_some());
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
