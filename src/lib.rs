#![doc = include_str!("../ARCHITECTURE.md")]
#![warn(missing_docs)]

pub mod back;
pub mod bead;
pub mod control;
pub mod deposit;
pub mod diag;
pub mod fill;
pub mod geometry;
pub mod invalid;
pub mod ir;
pub mod lower;
pub mod numbers;
pub mod overrides;
pub mod pipeline;
pub mod plan;
pub mod preview;
pub mod provenance;
pub mod report;
pub mod sema;
pub mod slice;
pub mod span;
pub mod style;
pub mod syntax;
pub mod target;
pub mod units;
pub mod verify;
