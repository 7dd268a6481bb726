//! The control module's degenerate inputs: [`crate::invalid`], shared with
//! the slicer.

pub use crate::invalid::Invalid;
pub(crate) use crate::invalid::{count, finite, positive};
