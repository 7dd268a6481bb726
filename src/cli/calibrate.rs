//! `lmdc calibrate FILE.lmd [-o DIR]`: the coupon programs of a
//! calibration file, one per machine, through the same plan, checks and
//! writers as any part, and the measurement sheet `DIR/<part>.coupons.csv`
//! that `lmdc fit` reads once filled in — all written atomically, nothing
//! on an error.

use super::progress::{self, Progress};
use super::{messages, read_source, shown, sink, write_programs, Common};
use super::{EXIT_PROGRAM, EXIT_USAGE};
use lmdc::back::{Sink, Templates};
use lmdc::diag::usage;
use lmdc::pipeline;
use lmdc::sema::model::Build;
use std::io::Write;
use std::path::Path;

/// Runs `lmdc calibrate` with the shared options (`--set`,
/// `--deny-warnings`, the message format) as `check` and `build` take them;
/// returns the exit code.
pub fn run(file: &Path, out: &Path, common: &Common, mut progress: Progress) -> u8 {
    let (color, format) = (common.color, common.format);
    let templates = match Templates::load(None) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("error: {e}");
            return EXIT_USAGE;
        }
    };
    if let Err(e) = sink::recover(out) {
        eprintln!("error: output directory {}: {e}", shown(out));
        return EXIT_USAGE;
    }
    let Some(source) = read_source(file) else {
        return EXIT_USAGE;
    };
    let options = common.options(file, None);
    let (compiled, model) = match pipeline::compile_with_model(&source, &options, &mut progress) {
        Ok(c) => c,
        Err(e) => return messages::fail(file, usage::refused(&e)),
    };
    progress.print(|| messages::print(&compiled.diagnostics, file, &source, color, format));
    if let Some(code) = common.denied(file, &compiled.diagnostics) {
        return code;
    }
    let (program, model) = match (compiled.program, model) {
        (Some(p), Some(m)) => (p, m),
        _ if !has_calibration(&source) => return no_calibration(file),
        _ => return EXIT_PROGRAM,
    };
    let Build::Calibration(calibration) = &model.build else {
        return no_calibration(file);
    };
    let mut sink = match sink::AtomicDir::new(out) {
        Ok(s) => s,
        Err(e) => {
            eprintln!(
                "error: cannot create the output directory {}: {e}",
                shown(out)
            );
            return EXIT_USAGE;
        }
    };
    let mut quiet = ();
    let mut inner = progress::Both(&mut quiet, &mut progress);
    if let Err(code) = write_programs(&program, &templates, &mut sink, &mut inner, out) {
        return code;
    }
    let part = &program.ir().part;
    let name = format!(
        "{}.coupons.csv",
        lmdc::target::names::windows_safe(&lmdc::back::identifier(part, 64))
    );
    let text = lmdc::slice::calibration::sheet(part, calibration);
    let written = (|| -> std::io::Result<()> {
        let mut w = sink.create(&name)?;
        w.write_all(text.as_bytes())?;
        w.flush()
    })();
    if let Err(e) = written {
        eprintln!("error: writing {name}: {e}");
        return EXIT_USAGE;
    }
    let end = sink.counter().get();
    sink.end_set(
        sink::SetKey {
            part: part.clone(),
            // No machine is called this (a name has no space): the sheet's
            // own set.
            machine: Some("coupons sheet".into()),
        },
        end,
    );
    let paths = match sink.commit() {
        Ok(p) => p,
        Err(e) => {
            eprintln!("error: writing into {}: {e}", shown(out));
            return EXIT_USAGE;
        }
    };
    progress.finish();
    for p in paths {
        eprintln!("wrote {}", shown(&p));
    }
    eprintln!(
        "{} coupons: measure them, fill in the sheet, then `lmdc fit {}`",
        calibration.coupons.len(),
        shown(&out.join(&name))
    );
    0
}

/// Whether the source has a `calibration` statement at all (a file
/// without one gets a usage error, not its part's diagnostics alone).
fn has_calibration(source: &str) -> bool {
    lmdc::syntax::parse(source)
        .map(|f| f.stmts.iter().any(|s| s.kind.node == "calibration"))
        .unwrap_or(true)
}

fn no_calibration(file: &Path) -> u8 {
    eprintln!(
        "error: {} has no `calibration {{ … }}` block: nothing to calibrate (docs/calibration.md)",
        shown(file)
    );
    EXIT_USAGE
}
