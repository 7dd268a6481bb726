//! Mistakes of the command line and the files it names: reports without a
//! place in the source, printed as `error: …` or, with `--message-format
//! json`, as diagnostic objects with empty `spans`, so a CI job reads every
//! failure the same way.

use crate::diag::{Code, Diagnostic};
use crate::overrides::SetError;
use crate::pipeline::{NoSuchMachine, UsageError};

/// The command line does not parse, or an option's value is unusable;
/// `text` is the parser's explanation.
pub fn usage(text: &str) -> Diagnostic {
    Diagnostic::error(Code::Usage, text.trim())
        .help("`lmdc --help` lists the commands, `lmdc COMMAND --help` their options")
}

/// An option's value lmdc cannot use.
pub fn bad_value(option: &str, value: &str, want: &str) -> Diagnostic {
    Diagnostic::error(
        Code::Usage,
        format!("`{option} {value}`: {option} must be {want}"),
    )
}

/// The command does not apply to this (valid) file.
pub fn nothing_to_do(file: &str, command: &str, why: &str) -> Diagnostic {
    Diagnostic::error(
        Code::Usage,
        format!("{file} has nothing to {command}: {why}"),
    )
}

/// The source cannot be read.
pub fn unreadable(file: &str, why: &str) -> Diagnostic {
    Diagnostic::error(Code::Unreadable, format!("cannot read {file}: {why}"))
}

/// `--machine` names no machine of the file.
pub fn no_such_machine(e: &NoSuchMachine) -> Diagnostic {
    Diagnostic::error(Code::NoSuchMachine, e.to_string()).help(format!(
        "give one of {} to --machine, or leave --machine out for every machine",
        e.declared
    ))
}

/// A `--set` the file cannot take.
pub fn bad_set(e: &SetError) -> Diagnostic {
    let help = match e {
        SetError::UnknownName { .. } => {
            "--set replaces the value of a top-level `let NAME = …` of the file"
        }
        SetError::Unit { .. } => "give the value in a unit of the same kind as the file's",
        SetError::BadValue { .. } => {
            "give one value of the language, with its unit: `--set R1=300mm`, `--set S=\"7 mm/s .. 9 mm/s\"`"
        }
        SetError::Twice(_) => "give each name once",
    };
    Diagnostic::error(Code::BadSet, e.to_string()).help(help)
}

/// What the pipeline refused before compiling.
pub fn refused(e: &UsageError) -> Diagnostic {
    match e {
        UsageError::Machine(m) => no_such_machine(m),
        UsageError::Set(s) => bad_set(s),
    }
}

/// An output cannot be written; `what` says which and why.
pub fn output(what: &str) -> Diagnostic {
    Diagnostic::error(Code::Output, what)
}

/// `--deny-warnings` or `--deny` (`how`, as written) with `n` warnings
/// reported that they fail and nothing allows.
pub fn denied_warnings(n: usize, how: &str) -> Diagnostic {
    Diagnostic::error(
        Code::DeniedWarnings,
        format!(
            "{n} warning{} and {how}: nothing is written",
            if n == 1 { "" } else { "s" }
        ),
    )
    .help(format!(
        "fix what the warnings say; or, where one is expected, say so in the file with its \
         reason, `allow \"lmd::CODE\" = \"why\"`, or build with --allow CODE; or without {how}"
    ))
}

/// The same code given to `--allow` and `--deny`.
pub fn allow_and_deny(code: &str) -> Diagnostic {
    Diagnostic::error(
        Code::Usage,
        format!("{code} is both allowed and denied on the command line"),
    )
    .help("give it to --allow or to --deny, not both")
}
