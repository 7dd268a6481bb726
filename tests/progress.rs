//! The progress line: drawn on a terminal for a run longer than a second,
//! never into a pipe or a log, never with `--quiet`. `LMDC_PROGRESS_AFTER_MS=0`
//! draws from the first tick, so a quick example shows it.

use crate::support::skip;

use std::process::Command;

const FILE: &str = "examples/twisted_duct.lmd";

fn drawn(stderr: &[u8]) -> bool {
    let text = String::from_utf8_lossy(stderr);
    text.contains('\r') || text.contains("\x1b[2K") || text.contains(" … ")
}

#[test]
fn nothing_is_drawn_when_stderr_is_not_a_terminal() {
    let o = Command::new(env!("CARGO_BIN_EXE_lmdc"))
        .args(["check", FILE])
        .env("LMDC_PROGRESS_AFTER_MS", "0")
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(0));
    assert!(
        !drawn(&o.stderr),
        "{:?}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(String::from_utf8_lossy(&o.stderr).starts_with("ok: "));
}

/// `script` runs the command on a pseudo-terminal (util-linux, on every
/// Debian); returns what the terminal showed.
fn on_a_terminal(args: &str) -> Option<String> {
    let cmd = format!("{} {args}", env!("CARGO_BIN_EXE_lmdc"));
    let o = Command::new("script")
        .args(["-qec", &cmd, "/dev/null"])
        .env("LMDC_PROGRESS_AFTER_MS", "0")
        .output()
        .ok()?;
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stdout));
    Some(String::from_utf8_lossy(&o.stdout).into_owned())
}

#[test]
fn a_terminal_sees_the_stage_unless_quiet() {
    let Some(text) = on_a_terminal(&format!("check {FILE}")) else {
        skip::skip(
            "a_terminal_sees_the_stage_unless_quiet",
            "script",
            "apt-get install bsdutils",
        );
        return;
    };
    assert!(text.contains("twisted_duct.lmd: "), "{text:?}");
    // The line is cleared before the result is printed.
    assert!(text.contains("\r\x1b[2Kok: "), "{text:?}");
    let quiet = on_a_terminal(&format!("check --quiet {FILE}")).unwrap();
    assert!(quiet.starts_with("ok: "), "{quiet:?}");
    assert!(
        !quiet.contains('…') && !quiet.contains("\x1b[2K"),
        "{quiet:?}"
    );
}
