//! How diagnostics leave the command: drawn for people on stderr, or as JSON
//! lines on stdout (`--message-format json`, docs/diagnostics.md), where a
//! CI job reads them without scraping text. stdout holds nothing else but
//! JSON then (the report's object), so the stream parses line by line; the
//! human lines (`ok: …`, `wrote …`) stay on stderr.

use clap::ValueEnum;
use lmdc::diag::json::Encoder;
use lmdc::diag::{render, Diagnostics};
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
