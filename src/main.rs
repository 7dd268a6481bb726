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
            if !e.use_stderr() {
                let _ = e.print();
                return ExitCode::from(0);
            }
            if asks_for_json() {
                cli::messages::set_format(cli::messages::MessageFormat::Json);
                let text = e.to_string();
                // clap's first line says it; the rest is usage for people.
                let first = text.lines().next().unwrap_or_default();
                let first = first.strip_prefix("error: ").unwrap_or(first);
                let d = lmdc::diag::usage::usage(first);
                return ExitCode::from(cli::messages::fail(std::path::Path::new(""), d));
            }
            let _ = e.print();
            return ExitCode::from(cli::EXIT_USAGE);
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

/// Whether the command line asks for `--message-format json`, read before
/// clap has parsed it (it failed to): a CI job that asked for JSON gets its
/// usage errors as JSON too.
fn asks_for_json() -> bool {
    let args: Vec<std::ffi::OsString> = std::env::args_os().collect();
    args.iter().any(|a| a == "--message-format=json")
        || args
            .windows(2)
            .any(|w| w[0] == "--message-format" && w[1] == "json")
}
