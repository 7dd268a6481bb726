//! G-code back end (placeholder until implemented).

pub mod kinematics;

use super::{EmitError, Sink, Templates};
use crate::check::Verified;
use crate::ir::Cnc;

/// Writes the G-code program(s) for `cnc`.
pub fn emit(
    _p: &Verified,
    _index: usize,
    _cnc: &Cnc,
    _t: &Templates,
    _sink: &mut dyn Sink,
) -> Result<(), EmitError> {
    Err(EmitError::Template(
        "G-code back end not implemented".into(),
    ))
}
