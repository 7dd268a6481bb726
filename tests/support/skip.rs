//! Tests that need an external oracle (LinuxCNC's rs274, the KRL parser):
//! under CI a missing oracle fails the test; elsewhere the test says on the
//! terminal that it did not run, and why. Use from an integration test with
//! `#[path = "support/skip.rs"] mod skip;`.
#![allow(dead_code)]

use std::io::Write;

/// Whether the test run is under CI (`CI` set, non-empty, not `false`/`0`).
pub fn in_ci() -> bool {
    match std::env::var("CI") {
        Ok(v) => !(v.is_empty() || v == "false" || v == "0"),
        Err(_) => false,
    }
}

/// `test` cannot run because `missing` is not installed (`install` says how
/// to get it). Under CI this panics: a test CI should run must not pass
/// without running. Elsewhere it writes a line to the terminal — straight to
/// standard error, past the test harness's capture, so that a skip shows in
/// an ordinary `cargo test` run instead of passing silently — and the test
/// returns.
pub fn skip(test: &str, missing: &str, install: &str) {
    if in_ci() {
        panic!("CI is set but {missing} is missing: {install}");
    }
    let _ = writeln!(
        std::io::stderr(),
        "SKIPPED {test}: {missing} is not installed ({install}); under CI this fails"
    );
}
