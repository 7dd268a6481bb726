//! Most integration tests, as modules of one binary (Cargo.toml says why).
//! Run one file's tests with `cargo test --release --test suite <file>::`.

// The support modules are declared once, here; each file uses what it needs
// from `crate::support`.
mod support;

mod all_errors;
mod arm;
mod atomic_output;
mod budgets;
mod calibrate;
mod cases;
mod cell_io;
mod cli;
mod cli_ci;
mod codes;
mod collision;
mod deposit;
mod diagnostics;
mod duct_geometry;
mod editor_grammar;
mod fill;
mod first_use;
mod fit;
mod fixture_sanity;
mod fmt;
mod gcode_kinematics;
mod gcode_program;
mod gcode_rs274;
mod heat;
mod help_parses;
mod holes;
mod holes_ir;
mod krl_parser;
mod krl_program;
mod laser_timing;
mod library;
mod lsp;
mod machine_checks;
mod mesh;
mod message_format;
mod overhang;
mod placement;
mod plan_lines;
mod planar;
mod positioner;
mod preview;
mod program_text;
mod progress;
mod reach;
mod report;
mod ring;
mod ring_krl;
mod ring_rs274;
mod robustness;
mod rs274_smoke;
mod safe_motion;
mod schemas;
mod section_points;
mod spiral;
mod stacking;
mod style;
mod table;
mod typos;
mod variable_errors;
mod variable_rs274;
mod variable_top;
