//! `lmdc report`: compiles like `check` and prints the plan report of each
//! checked machine (text, or one JSON object a machine with `--json`).

use super::messages;
use super::progress::Progress;
use super::{read_source, Common, EXIT_PROGRAM, EXIT_USAGE};
use lmdc::diag::usage;
use lmdc::pipeline;
use lmdc::report::{text, Report};
use std::io::Write;
use std::path::Path;

/// What `lmdc report` was asked.
pub struct Args<'a> {
    /// The .lmd file.
    pub file: &'a Path,
    /// Only this machine.
    pub machine: Option<&'a str>,
    /// JSON instead of text.
    pub json: bool,
    /// Density of the deposit, g/cm³, for bead models that declare none.
    pub density: Option<f64>,
}

/// Runs `lmdc report`; returns the exit code.
pub fn run(a: Args<'_>, common: &Common, mut progress: Progress) -> u8 {
    let Some(source) = read_source(a.file) else {
        return EXIT_USAGE;
    };
    if let Some(d) = a.density {
        if !(d.is_finite() && d > 0.0) {
            let d = usage::bad_value("--density", &d.to_string(), "a positive number of g/cm³");
            return messages::fail(a.file, d);
        }
    }
    let options = common.options(a.file, a.machine);
    let (compiled, model) = match pipeline::compile_with_model(&source, &options, &mut progress) {
        Ok(c) => c,
        Err(e) => return messages::fail(a.file, usage::refused(&e)),
    };
    progress.finish();
    let (color, format) = (common.color, common.format);
    messages::print(&compiled.diagnostics, a.file, &source, color, format);
    if let Some(code) = common.denied(a.file, &compiled.diagnostics) {
        return code;
    }
    let (Some(program), Some(model)) = (compiled.program, model) else {
        return EXIT_PROGRAM;
    };
    let mut out = std::io::stdout().lock();
    for (i, m) in program.machines().enumerate() {
        let r = Report::new(m, &model, a.density);
        let written = if a.json {
            serde_json::to_string(&r)
                .map_err(std::io::Error::other)
                .and_then(|s| writeln!(out, "{s}"))
        } else {
            let sep = if i > 0 { "\n" } else { "" };
            write!(out, "{sep}{}", text::render(&r))
        };
        if written.is_err() {
            // stdout closed (piped into `head`): nothing more to say.
            return 0;
        }
    }
    let _ = out.flush();
    0
}
