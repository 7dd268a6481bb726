//! KUKA KRL back end (placeholder until implemented).
use super::{EmitError, Sink, Templates};
use crate::check::Verified;
use crate::ir::Robot;

/// Writes the KRL program(s) for `robot`.
pub fn emit(
    _p: &Verified,
    _index: usize,
    _robot: &Robot,
    _t: &Templates,
    _sink: &mut dyn Sink,
) -> Result<(), EmitError> {
    Err(EmitError::Template("KRL back end not implemented".into()))
}
