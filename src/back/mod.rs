//! Back ends: verified IR → machine programs. They read only the IR (and the
//! [`Verified`] proof that it passed the checks), render the
//! program's shape through tera templates and write the per-point lines with a
//! tight fixed-precision loop (see ARCHITECTURE.md for why).

pub mod context;
pub mod fixed;
pub(crate) mod fmt;
pub mod gcode;
pub mod krl;
pub mod templates;

use crate::check::Verified;
use crate::diag::Diagnostics;
use crate::ir::Machine;
use std::io::{self, Write};
pub use templates::Templates;

/// Where a back end writes its files. The compiler core does no file I/O itself:
/// the CLI supplies a sink that writes temporary files and renames them into place
/// only when every program was emitted, tests use [`MemorySink`].
pub trait Sink {
    /// Opens a new output file called `name` (a bare file name, no directories).
    fn create(&mut self, name: &str) -> io::Result<Box<dyn Write + '_>>;
}

/// A sink that discards everything: emitting into it runs every back-end
/// check (axis limits, analog range, …) without writing (`lmdc check`).
#[derive(Default, Debug)]
pub struct NullSink;

impl Sink for NullSink {
    fn create(&mut self, _name: &str) -> io::Result<Box<dyn Write + '_>> {
        Ok(Box::new(io::sink()))
    }
}

/// A sink that keeps files in memory, in creation order.
#[derive(Default, Debug)]
pub struct MemorySink {
    /// `(name, contents)` pairs.
    pub files: Vec<(String, Vec<u8>)>,
}

impl MemorySink {
    /// The contents of the file called `name`, as text.
    pub fn text(&self, name: &str) -> Option<String> {
        self.files
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, b)| String::from_utf8_lossy(b).into_owned())
    }
}

struct MemFile<'a> {
    buf: &'a mut Vec<u8>,
}

impl Write for MemFile<'_> {
    fn write(&mut self, b: &[u8]) -> io::Result<usize> {
        self.buf.extend_from_slice(b);
        Ok(b.len())
    }
    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

impl Sink for MemorySink {
    fn create(&mut self, name: &str) -> io::Result<Box<dyn Write + '_>> {
        self.files.push((name.to_string(), Vec::new()));
        let last = self.files.len() - 1;
        Ok(Box::new(MemFile {
            buf: &mut self.files[last].1,
        }))
    }
}

/// Why a back end could not emit a program.
#[derive(Debug, thiserror::Error)]
pub enum EmitError {
    /// The plan cannot run on this machine (axis limits, missing axes, …).
    #[error("the plan does not fit machine")]
    Program(Diagnostics),
    /// A template failed to render.
    #[error("template error: {0}")]
    Template(String),
    /// Writing failed.
    #[error(transparent)]
    Io(#[from] io::Error),
}

/// Emits the program(s) for machine number `index` of the verified IR.
pub fn emit(
    program: &Verified,
    index: usize,
    templates: &Templates,
    sink: &mut dyn Sink,
) -> Result<(), EmitError> {
    match program.ir().machines.get(index) {
        Some(Machine::Robot(r)) => krl::emit(program, index, r, templates, sink),
        Some(Machine::Cnc(c)) => gcode::emit(program, index, c, templates, sink),
        None => Err(EmitError::Template(format!("no machine number {index}"))),
    }
}

/// A path joins the previous one (no transition between them) when it starts
/// within this distance (mm) of where the previous one ended ...
pub const JOIN_MM: f64 = 1e-3;

/// ... with a normal whose components differ by at most this (about 0.0006°).
pub const JOIN_NORMAL: f32 = 1e-5;

/// Whether a path starting at `next` joins one that ended with its focus at
/// `focus` and normal `normal`: same place, same nozzle direction, so motion goes
/// on without retracting. Both back ends decide joins by this rule.
pub fn joins(focus: [f64; 3], normal: [f32; 3], next: &crate::ir::Point) -> bool {
    let f = next.focus();
    let d2 = (0..3).map(|i| (f[i] - focus[i]).powi(2)).sum::<f64>();
    d2 <= JOIN_MM * JOIN_MM && (0..3).all(|i| (next.normal[i] - normal[i]).abs() <= JOIN_NORMAL)
}

/// A file-name-safe identifier from `text`: letters, digits and `_`, starting with
/// a letter, lower case, at most `max` characters.
pub fn identifier(text: &str, max: usize) -> String {
    let mut s: String = text
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '_'
            }
        })
        .collect();
    if !s.starts_with(|c: char| c.is_ascii_alphabetic()) {
        s.insert(0, 'p');
    }
    s.truncate(max);
    s
}

/// The stem of a program's file name: `identifier(part_machine)`, at most `max`
/// characters. The part's name is shortened first; a machine name too long to
/// keep whole keeps its start and gets a hash of the whole name, so two
/// machines of one part keep distinct names.
pub fn program_stem(part: &str, machine: &str, max: usize) -> String {
    let mut full = identifier(&format!("{part}_{machine}"), usize::MAX);
    if full.len() <= max {
        return full;
    }
    // identifier() maps char for char, so the tail is "_" + the machine's name.
    let tail = machine.chars().count() + 1;
    if tail + 1 < max {
        return format!("{}{}", &full[..max - tail], &full[full.len() - tail..]);
    }
    // `p_` + the machine's start + `_` + 4 hex digits of its whole name.
    const HASHED: usize = 1 + 1 + 1 + 4;
    if max <= HASHED {
        full.truncate(max);
        return full;
    }
    let head: String = full[full.len() - tail + 1..]
        .chars()
        .take(max - HASHED)
        .collect();
    format!(
        "{}_{head}_{:04x}",
        &full[..1],
        fnv1a(machine.as_bytes()) & 0xffff
    )
}

/// 32-bit FNV-1a: a stable hash, the same on every machine and release.
fn fnv1a(bytes: &[u8]) -> u32 {
    bytes.iter().fold(0x811c_9dc5, |h: u32, &b| {
        (h ^ u32::from(b)).wrapping_mul(0x0100_0193)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stems_keep_the_machine() {
        assert_eq!(program_stem("bent tube", "mill5", 24), "bent_tube_mill5");
        let s = program_stem("a very long part name indeed", "mill5", 24);
        assert_eq!(s.len(), 24);
        assert!(s.ends_with("_mill5"), "{s}");
        assert_eq!(program_stem("42", "m", 24), "p42_m");
        let s = program_stem("x", "a machine with a very long name", 24);
        assert_eq!(s.len(), 24);
        assert!(program_stem("part", "kr60", 19).len() <= 19);
    }

    #[test]
    fn long_machine_names_stay_distinct() {
        let a = program_stem("bracket", "cnc_with_a_rather_long_name_1", 24);
        let b = program_stem("bracket", "cnc_with_a_rather_long_name_2", 24);
        assert_ne!(a, b);
        for s in [&a, &b] {
            assert_eq!(s.len(), 24, "{s}");
            assert!(s.starts_with("b_cnc_with_a_rath"), "{s}");
        }
        let k = program_stem("very_long_part_name", "a_seventeen_chars", 19);
        assert!(k.len() <= 19 && k.contains("a_seventeen"), "{k}");
    }
}
