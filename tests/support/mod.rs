//! The test suite's shared helpers, declared once for every file of
//! `tests/suite.rs` (the separate test programs include the ones they need
//! with `#[path]`).

pub mod data;
pub mod duct;
pub mod example;
pub mod expected;
#[path = "../gcode_common.rs"]
pub mod gcode_common;
pub mod ir_moves;
// The G-code helpers bring the fixtures along (their own programs include
// gcode_common alone).
pub use gcode_common::fixture;
pub mod krl_check;
pub mod krl_parser;
pub mod krl_run;
pub mod m66;
pub mod png;
pub mod rapid_check;
pub mod ring;
pub mod rs274;
pub mod schema;
pub mod skip;
pub mod three_mf;
