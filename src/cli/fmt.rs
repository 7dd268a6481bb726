//! `lmdc fmt`: files rewritten in the canonical layout (atomically, only
//! when it changes them), stdin to stdout, or `--check` for CI.

use super::{messages, read_source, shown, EXIT_PROGRAM, EXIT_USAGE};
use lmdc::diag::{usage, Diagnostics};
use lmdc::fmt::{format, FmtError};
use std::io::{Read, Write};
use std::path::Path;

/// Runs `lmdc fmt`; returns the exit code.
pub fn run(files: &[std::path::PathBuf], check: bool) -> u8 {
    if files.is_empty() {
        return stdin(check);
    }
    let mut worst = 0;
    for f in files {
        worst = worst.max(one(f, check));
    }
    worst
}

/// Formats `source`, printing why not (a syntax error as `check` draws it).
fn formatted(file: &Path, source: &str) -> Result<String, u8> {
    match format(source) {
        Ok(t) => Ok(t),
        Err(FmtError::Syntax(d)) => {
            let mut all = Diagnostics::new();
            all.push(*d);
            messages::print_default(&all, file, source);
            Err(EXIT_PROGRAM)
        }
        Err(FmtError::Changed) => {
            eprintln!(
                "error: formatting {} would change its meaning: left as it is (a bug in lmdc fmt: please report it with the file)",
                shown(file)
            );
            Err(EXIT_PROGRAM)
        }
    }
}

fn one(file: &Path, check: bool) -> u8 {
    let Some(source) = read_source(file) else {
        return EXIT_USAGE;
    };
    let text = match formatted(file, &source) {
        Ok(t) => t,
        Err(code) => return code,
    };
    if text == source {
        return 0;
    }
    if check {
        eprintln!(
            "not formatted: {} (run `lmdc fmt {}`)",
            shown(file),
            shown(file)
        );
        return EXIT_PROGRAM;
    }
    match write_atomically(file, &text) {
        Ok(()) => {
            eprintln!("formatted {}", shown(file));
            0
        }
        Err(e) => {
            let why = format!("writing {}: {e}", shown(file));
            messages::fail(file, usage::output(&why))
        }
    }
}

fn stdin(check: bool) -> u8 {
    let mut bytes = Vec::new();
    let name = Path::new("<stdin>");
    if let Err(e) = std::io::stdin()
        .take(super::MAX_SOURCE + 1)
        .read_to_end(&mut bytes)
    {
        return messages::fail(name, usage::unreadable("stdin", &e.to_string()));
    }
    if bytes.len() as u64 > super::MAX_SOURCE {
        let why = format!("it is larger than {} MB", super::MAX_SOURCE >> 20);
        return messages::fail(name, usage::unreadable("stdin", &why));
    }
    let Ok(source) = String::from_utf8(bytes) else {
        return messages::fail(name, usage::unreadable("stdin", "it is not UTF-8 text"));
    };
    let text = match formatted(name, &source) {
        Ok(t) => t,
        Err(code) => return code,
    };
    if check {
        if text != source {
            eprintln!("not formatted: <stdin>");
            return EXIT_PROGRAM;
        }
        return 0;
    }
    let mut out = std::io::stdout().lock();
    let _ = out.write_all(text.as_bytes()).and_then(|()| out.flush());
    0
}

/// Replaces `path` with `text` through a temporary file beside it, keeping
/// the file's permissions: an editor or a crash never sees half a file.
fn write_atomically(path: &Path, text: &str) -> std::io::Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let perms = std::fs::metadata(path)?.permissions();
    let mut tmp = tempfile::NamedTempFile::new_in(dir)?;
    tmp.write_all(text.as_bytes())?;
    tmp.flush()?;
    tmp.as_file().set_permissions(perms)?;
    tmp.persist(path).map_err(|e| e.error)?;
    Ok(())
}
