#![doc = include_str!("../ARCHITECTURE.md")]
#![warn(missing_docs)]

pub mod back;
pub mod check;
pub mod diag;
pub mod ir;
pub mod span;
pub mod syntax;
pub mod units;
