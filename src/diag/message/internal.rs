//! Reports of states the checks before them should have made impossible:
//! each is a bug in lmdc, and says so.

use crate::diag::{Code, Diagnostic};
use crate::span::Span;
use std::fmt::Display;

/// A solid reached lowering without a bead model (sema should have refused it).
pub fn no_bead_in_lowering() -> Diagnostic {
    Diagnostic::error(
        Code::NonFinite,
        "internal error: a solid without a bead model reached lowering; please report it",
    )
}

/// A solid reached the slicer without a bead model (sema should have refused it).
pub fn no_bead_in_slicing() -> Diagnostic {
    Diagnostic::error(
        Code::NonFinite,
        "internal error: a solid without a bead model reached the slicer; please report it",
    )
}

/// A ring the checker let through that cannot be laid out.
pub fn ring_layout(why: &dyn Display, ring: Span) -> Diagnostic {
    Diagnostic::error(
        Code::NonFinite,
        format!("internal error laying out the ring: {why}; please report it"),
    )
    .label(ring, "ring")
}

/// A loop the checker let through that cannot be simulated.
pub fn loop_simulation(why: &dyn Display) -> Diagnostic {
    Diagnostic::error(
        Code::NonFinite,
        format!("internal error simulating the loop: {why}; please report it"),
    )
}
