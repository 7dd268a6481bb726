#![doc = include_str!("../ARCHITECTURE.md")]
#![warn(missing_docs)]

pub mod diag;
pub mod span;
pub mod syntax;
pub mod units;
