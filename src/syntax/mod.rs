//! Source text → typed syntax tree ([`ast::File`]).

pub mod ast;
mod parse;

pub use parse::{parse, unit_after, MAX_EXPR_DEPTH, MAX_NESTING};
