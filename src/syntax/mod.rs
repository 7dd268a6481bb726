//! Source text → typed syntax tree ([`ast::File`]).

pub mod ast;
mod parse;

pub use parse::{parse, MAX_EXPR_DEPTH, MAX_NESTING};
