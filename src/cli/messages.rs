//! How diagnostics leave the command: drawn for people on stderr, or as JSON
//! lines on stdout (`--message-format json`, docs/diagnostics.md), where a
//! CI job reads them without scraping text. stdout holds nothing else but
//! JSON then (the report's object), so the stream parses line by line; the
//! human lines (`ok: …`, `wrote …`) stay on stderr.

use clap::ValueEnum;
use lmdc::diag::json::Encoder;
use lmdc::diag::{render, Diagnostic, Diagnostics};
use std::io::Write;
use std::path::Path;

/// `--message-format`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum MessageFormat {
    /// Drawn with the source lines, on stderr.
    Human,
    /// One JSON object per diagnostic per line, on stdout.
    Json,
}

/// Prints `d` about `source` (read from `file`) in `format`.
pub fn print(d: &Diagnostics, file: &Path, source: &str, color: bool, format: MessageFormat) {
    if d.is_empty() {
        return;
    }
    let name = file.display().to_string();
    match format {
        MessageFormat::Human => eprint!("{}", render(d, &name, source, color)),
        MessageFormat::Json => {
            let enc = Encoder::new(&name, source);
            let mut out = std::io::stdout().lock();
            for one in d.iter() {
                // A closed stdout (a pipe into `head`) is not lmdc's error.
                if writeln!(out, "{}", enc.line(one)).is_err() {
                    return;
                }
            }
            let _ = out.flush();
        }
    }
}

/// The format of this run, set once by [`set_format`] before anything is
/// printed: the command line's usage errors are printed from everywhere in
/// the CLI, each in the format the user asked for.
static FORMAT: std::sync::OnceLock<MessageFormat> = std::sync::OnceLock::new();

/// Sets the format of every usage error of this run.
pub fn set_format(format: MessageFormat) {
    let _ = FORMAT.set(format);
}

/// Prints a usage or file error (a report with no place in the source) in
/// this run's format; `file` is the file it is about, as given ("" when
/// none). Returns the exit code it calls for.
pub fn fail(file: &Path, d: Diagnostic) -> u8 {
    let name = file.display().to_string();
    match FORMAT.get().copied().unwrap_or(MessageFormat::Human) {
        MessageFormat::Human => {
            eprintln!("error: {}", lmdc::diag::sanitize(&d.message));
            if let Some(h) = &d.help {
                eprintln!("  help: {}", lmdc::diag::sanitize(h));
            }
        }
        MessageFormat::Json => {
            let line = Encoder::new(&name, "").line(&d);
            let mut out = std::io::stdout().lock();
            let _ = writeln!(out, "{line}").and_then(|()| out.flush());
        }
    }
    match d.code {
        lmdc::diag::Code::DeniedWarnings => super::EXIT_PROGRAM,
        _ => super::EXIT_USAGE,
    }
}

/// Prints `d` in this run's format, without colour (`lmdc fmt`, which has
/// no place to be told otherwise).
pub fn print_default(d: &Diagnostics, file: &Path, source: &str) {
    let format = FORMAT.get().copied().unwrap_or(MessageFormat::Human);
    print(d, file, source, false, format);
}
