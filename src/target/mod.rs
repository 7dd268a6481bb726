//! What lmdc knows about the controllers it writes for: the names they accept,
//! the resolution they are written at, the limits they enforce and the G-code
//! dialects. Plain data and pure functions, read by the checker (to refuse a
//! declaration a controller cannot take), the verifier (to check a plan against
//! it) and the back ends (to write it) alike — like [`units`](crate::units) and
//! the bead physics, it belongs to no single stage.

pub mod gcode;
pub mod kuka;
pub mod names;

/// `v` rounded to `decimals` digits (half away from zero): the value a control
/// reads where a program writes `v` with that many decimals.
pub fn written(v: f64, decimals: usize) -> f64 {
    let s = 10f64.powi(decimals.min(9) as i32);
    (v * s).round() / s
}
