//! `lmdc preview`: compiles like `check` and writes the plan preview of one
//! machine as a single HTML file (docs/preview.md).

use super::messages;
use super::progress::Progress;
use super::{read_source, shown, Common, EXIT_PROGRAM, EXIT_USAGE};
use lmdc::diag::usage;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Runs `lmdc preview`; returns the exit code.
pub fn run(
    file: &Path,
    machine: Option<&str>,
    out: Option<&Path>,
    common: &Common,
    mut progress: Progress,
) -> u8 {
    let Some(source) = read_source(file) else {
        return EXIT_USAGE;
    };
    let options = common.options(file, machine);
    let (compiled, model) =
        match lmdc::pipeline::compile_with_model(&source, &options, &mut progress) {
            Ok(c) => c,
            Err(e) => return messages::fail(file, usage::refused(&e)),
        };
    let (color, format) = (common.color, common.format);
    progress.print(|| messages::print(&compiled.diagnostics, file, &source, color, format));
    if let Some(code) = common.denied(file, &compiled.diagnostics) {
        return code;
    }
    // A plan refused by its arm alone is drawn with those errors (and the
    // run still fails); any other error leaves nothing to draw.
    let (page, part, code) = match (&compiled.program, &compiled.refused) {
        (Some(program), _) => {
            // The first machine checked: the one named, else the first declared.
            let Some(m) = program.machines().next() else {
                eprintln!("error: the file declares no machine whose plan could be shown");
                return EXIT_PROGRAM;
            };
            let overlay = model
                .as_ref()
                .and_then(|model| lmdc::pipeline::repair_overlay(m.ir(), model));
            let page = lmdc::preview::html_with(m, overlay.as_ref());
            (page, &program.ir().part, 0)
        }
        (None, Some(refused)) => match lmdc::preview::refused_html(refused) {
            Some(page) => (page, &refused.ir().part, EXIT_PROGRAM),
            None => return EXIT_PROGRAM,
        },
        (None, None) => return EXIT_PROGRAM,
    };
    progress.finish();
    let path: PathBuf = match out {
        Some(p) => p.to_path_buf(),
        None => Path::new("out").join(format!(
            "{}.preview.html",
            lmdc::target::names::windows_safe(&lmdc::back::identifier(part, 64))
        )),
    };
    match write_atomically(&path, page.as_bytes()) {
        Ok(()) if code != 0 => {
            eprintln!(
                "wrote {}: the refused plan, its arm's errors marked (no program is written for it)",
                shown(&path)
            );
            code
        }
        Ok(()) => {
            eprintln!("wrote {}", shown(&path));
            0
        }
        Err(e) => {
            let why = format!("writing {}: {e}", shown(&path));
            messages::fail(file, usage::output(&why))
        }
    }
}

/// Writes `bytes` to a temporary file beside `path` and renames it into
/// place: a reader never sees half a page.
fn write_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    std::fs::create_dir_all(dir)?;
    let mut tmp = tempfile::NamedTempFile::new_in(dir)?;
    tmp.write_all(bytes)?;
    tmp.flush()?;
    // A page to open and share: readable as any file the user writes
    // (temporary files start private).
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        tmp.as_file()
            .set_permissions(std::fs::Permissions::from_mode(0o644))?;
    }
    tmp.persist(path).map_err(|e| e.error)?;
    Ok(())
}
