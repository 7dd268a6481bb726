//! The wording of every diagnostic lmdc reports, in one module (Gleam's
//! `error.rs`). The rules decide *whether* something is wrong and compute the
//! numbers and places a fix needs; a function here turns them into the finished
//! report — its sentence, the text under each label and the help. A complaint
//! about a message is answered here alone: no rule holds a sentence, and
//! [`Diagnostic`](super::Diagnostic)'s builders are private to [`crate::diag`]
//! so none can.
//!
//! One file per area of the language, named for it; each function is named
//! for the mistake it reports.

pub mod bead;
pub mod bend;
pub mod calib;
pub mod collision;
pub mod control;
pub mod field;
pub mod fill;
pub mod hole;
pub mod internal;
pub mod load;
pub mod machine;
pub mod mesh;
pub mod positioner;
pub mod scan;
pub mod segmented_ring;
pub mod shape;
pub mod slicing;
pub mod solid;
pub mod statement;
pub mod style;
pub mod syntax;
pub mod target;
pub mod thermal;
pub mod top;
pub mod usage;
pub mod value;
pub mod verify;
pub mod wall;
pub mod words;
