//! Back ends: a verified machine's motion plan → its program. They only *write*
//! the plan ([`crate::plan`]) — where the nozzle goes and when the laser
//! switches is decided there, for every back end alike — rendering the
//! program's shape through tera templates and the per-move lines with a tight
//! fixed-precision loop (see ARCHITECTURE.md for why). They take a
//! [`VerifiedMachine`], so a plan that has not passed the checks cannot reach
//! them, and cannot fail on a limit.

pub mod cell;
pub mod context;
pub(crate) mod fmt;
pub mod gcode;
pub mod height_loop;
pub mod krl;
pub mod module_stream;
pub mod rapid;
pub mod templates;

use crate::ir::Machine;
pub use crate::target::names::identifier;
use crate::verify::VerifiedMachine;
use std::io::{self, Write};
pub use templates::Templates;

/// Where a back end writes its files. The compiler core does no file I/O itself:
/// the CLI supplies a sink that writes temporary files and renames them into place
/// only when every program was emitted, tests use [`MemorySink`].
pub trait Sink {
    /// Opens a new output file called `name` (a bare file name, no directories).
    fn create(&mut self, name: &str) -> io::Result<Box<dyn Write + '_>>;
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

/// Why a back end could not write a program. A verified plan always fits its
/// machine: what remains are the templates and the disk.
#[derive(Debug, thiserror::Error)]
pub enum EmitError {
    /// A template failed to render.
    #[error("template error: {0}")]
    Template(String),
    /// Writing failed.
    #[error(transparent)]
    Io(#[from] io::Error),
}

/// Writes the program(s) of a verified machine.
pub fn emit(
    m: VerifiedMachine<'_>,
    templates: &Templates,
    sink: &mut dyn Sink,
) -> Result<(), EmitError> {
    match m.machine() {
        Machine::Robot(r) if r.controller == crate::ir::Controller::Abb => {
            rapid::emit(m, r, templates, sink)
        }
        Machine::Robot(r) => krl::emit(m, r, templates, sink),
        Machine::Cnc(c) => gcode::emit(m, c, templates, sink),
    }
}
