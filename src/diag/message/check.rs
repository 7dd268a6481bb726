//! What the verifier says about a plan and the machines that build it.

use crate::diag::{Code, Diagnostic};
use crate::span::Span;

/// Two machines would write a file of the same name (`file`).
pub fn name_clash(
    first: &str,
    second: &str,
    file: &str,
    first_block: Option<Span>,
    second_block: Option<Span>,
) -> Diagnostic {
    Diagnostic::error(
        Code::NameClash,
        format!("machines `{first}` and `{second}` would both write {file}"),
    )
    .label_opt(second_block, "second machine")
    .label_opt(first_block, "first machine")
    .help("file names keep letters, digits and `_` of the part's and the machine's names: give the machines names that differ there")
}

/// A solid reached lowering without a bead model (sema should have refused it).
pub fn no_bead_in_lowering() -> Diagnostic {
    Diagnostic::error(
        Code::NonFinite,
        "internal error: a solid without a bead model reached lowering; please report it",
    )
}
