//! What the parser says about the text of a file: brackets, strings, numbers
//! and expressions it cannot read.

use crate::diag::{Code, Diagnostic};
use crate::span::Span;

/// The parser produced no file at all (pest's grammar should prevent it).
pub fn empty_parse() -> Diagnostic {
    Diagnostic::error(Code::Syntax, "empty parse")
}

/// A text opened with `"` at `at` reaches the end of its line unclosed.
pub fn unclosed_text(at: Span) -> Diagnostic {
    Diagnostic::error(Code::Syntax, "this text is not closed on its line")
        .label(at, "no closing `\"` before the line ends")
        .help("close the text with `\"` on the same line; a text cannot span lines")
}

/// A comment opened with `/*` at `at` is never closed with `*/`.
pub fn unclosed_comment(at: Span) -> Diagnostic {
    Diagnostic::error(Code::Syntax, "this comment is never closed")
        .label(at, "opened here; no `*/` follows")
        .help("end the comment with `*/`, or use `//` for a comment to the end of the line")
}

/// Brackets nest deeper than `max` (the bracket at `at` is one too many).
pub fn brackets_too_deep(max: usize, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::TooDeep,
        format!("brackets are nested more than {max} deep"),
    )
    .label(at, "this one is too deep")
    .help("split the expression with `let` constants")
}

/// The bracket `open` at `opened` is closed by the wrong bracket `close` at
/// `closed`; `closer` is the one that would match.
pub fn mismatched_bracket(
    open: char,
    opened: Span,
    close: char,
    closed: Span,
    closer: char,
) -> Diagnostic {
    Diagnostic::error(Code::Syntax, format!("`{open}` is closed by `{close}`"))
        .label(opened, format!("this `{open}` …"))
        .label(closed, format!("… is closed here by `{close}`"))
        .help(format!("close `{open}` with `{closer}` first"))
}

/// A closing bracket `close` at `at` has no opening bracket.
pub fn closes_nothing(close: char, at: Span) -> Diagnostic {
    Diagnostic::error(Code::Syntax, format!("`{close}` closes nothing"))
        .label(at, "no matching opening bracket")
        .help("remove it, or add the opening bracket it belongs to")
}

/// The bracket `open` at `at` is still open at the end of the file.
pub fn never_closed(open: char, at: Span, closer: char) -> Diagnostic {
    Diagnostic::error(Code::Syntax, format!("this `{open}` is never closed"))
        .label(at, "opened here")
        .help(format!("add `{closer}` where it should end"))
}

/// pest stopped at `at`, expecting one of `expected` (names of grammar rules,
/// sorted; none when it gave no list); `letter` is the non-ASCII letter it
/// stopped at, if it did.
pub fn syntax_error(at: Span, expected: &[&str], letter: Option<char>) -> Diagnostic {
    let what = match expected.len() {
        0 => "unexpected text".to_string(),
        1 => format!("expected {}", expected[0]),
        _ => {
            let (last, rest) = expected.split_last().unwrap_or((&"", &[]));
            format!("expected {} or {}", rest.join(", "), last)
        }
    };
    let help = match letter {
        Some(c) => format!(
            "names are written with the letters a–z and A–Z, digits and `_`: `{c}` is not one of them"
        ),
        None => "every statement is `name = value` or `kind name { … }`; numbers carry their unit right after them, e.g. `6 mm` or `7 mm/s`".to_string(),
    };
    Diagnostic::error(Code::Syntax, format!("syntax error: {what}"))
        .label(at, what)
        .help(help)
}

/// A statement came out of the grammar without its keyword (should not happen).
pub fn statement_without_name() -> Diagnostic {
    Diagnostic::error(Code::Syntax, "statement without a name")
}

/// An expression at `at` nests `depth` operators and brackets, more than
/// `max`; `operators` of them are at its outer level.
pub fn expression_too_deep(depth: usize, max: usize, operators: usize, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::DeepExpression,
        format!(
            "this expression nests {depth} operators and brackets into one another; lmdc takes at most {max}"
        ),
    )
    .label(at, format!("{operators} operators at its outer level"))
    .help("compute it in steps with `let` constants (`let a = …`, then `let b = a + …`), and write each sign once (`--x` is `x`)")
}

/// The number at `at` does not fit in a finite `f64`.
pub fn number_too_large(at: Span) -> Diagnostic {
    Diagnostic::error(Code::Number, "this number is too large").label(at, "not a finite number")
}

/// A call came out of the grammar without its function name (should not happen).
pub fn call_without_name() -> Diagnostic {
    Diagnostic::error(Code::Syntax, "call without a name")
}

/// The grammar produced an expression of a kind the parser does not know at `at`.
pub fn unexpected_expression(at: Span) -> Diagnostic {
    Diagnostic::error(Code::Syntax, "unexpected expression").label(at, "")
}
