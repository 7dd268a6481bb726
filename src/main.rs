//! The `lmdc` binary. Everything but the command line lives in the library.

mod cli;

use clap::Parser;
use std::process::ExitCode;

#[global_allocator]
static ALLOC: cli::timings::Counting = cli::timings::Counting;

/// Stack of the thread that compiles. The parser and the evaluator bound their
/// recursion to fit a 2 MiB test thread in a debug build
/// ([`lmdc::syntax::MAX_EXPR_DEPTH`], [`lmdc::syntax::MAX_NESTING`]); the
/// binary gives itself 32 times that margin, which costs nothing until used.
const STACK: usize = 64 << 20;

fn main() -> ExitCode {
    let parsed = match cli::Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            // --help and --version are not errors.
            let code = if e.use_stderr() { cli::EXIT_USAGE } else { 0 };
            let _ = e.print();
            return ExitCode::from(code);
        }
    };
    let worker = std::thread::Builder::new()
        .name("lmdc".into())
        .stack_size(STACK)
        .spawn(move || cli::run(parsed));
    match worker.map(|w| w.join()) {
        Ok(Ok(code)) => ExitCode::from(code),
        // A panic has printed its message; say what it means for the user.
        Ok(Err(_)) => {
            eprintln!("error: lmdc stopped on an internal error (a bug: please report it with the input file)");
            ExitCode::from(101)
        }
        Err(e) => {
            eprintln!("error: cannot start lmdc's worker thread: {e}");
            ExitCode::from(cli::EXIT_USAGE)
        }
    }
}
