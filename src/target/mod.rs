//! What lmdc knows about the controllers it writes for: the names they accept,
//! the resolution they are written at, the limits they enforce and the G-code
//! dialects. Plain data and pure functions, read by the checker (to refuse a
//! declaration a controller cannot take), the verifier (to check a plan against
//! it) and the back ends (to write it) alike — like [`units`](crate::units) and
//! the bead physics, it belongs to no single stage.

pub mod arm;
pub mod gcode;
pub mod kuka;
pub mod names;
pub mod outputs;
pub mod rapid;

use crate::ir::Machine;

/// The corner blending a machine's program runs with, mm, and where that
/// number comes from (for the report and the messages).
pub fn blending(m: &Machine) -> (f64, &'static str) {
    if let Some(d) = m.common().blending {
        return (d, "declared");
    }
    match m {
        Machine::Robot(_) => (kuka::APO_CDIS_MM, "the `$APO.CDIS` lmdc writes"),
        Machine::Cnc(c) => match gcode::preamble_blending(&c.dialect.preamble) {
            Some(d) => (d, "set by the preamble"),
            // An unknown mode is taken as the worst: an exact stop.
            None => (0.0, "none known: an exact stop at every corner"),
        },
    }
}

/// `v` rounded to `decimals` digits (half away from zero): the value a control
/// reads where a program writes `v` with that many decimals.
pub fn written(v: f64, decimals: usize) -> f64 {
    let s = 10f64.powi(decimals.min(9) as i32);
    (v * s).round() / s
}

/// The least step of a position every program writes, mm: KRL's and
/// G-code's X Y Z have three decimals ([`kuka::POS_DECIMALS`],
/// [`gcode::POS_DECIMALS`]), and their angles as many in degrees. A move
/// shorter than this prints as no move, or as a step of one digit the part
/// does not make (`X-14.646` then `X-14.647` for 0.3 µm).
pub const POSITION_STEP: f64 = 1e-3;
// The step is the one both back ends print at.
const _: () = assert!(kuka::POS_DECIMALS == 3 && gcode::POS_DECIMALS == 3);

/// Whether two nozzle directions (unit vectors) lie within a printed step
/// of a degree ([`POSITION_STEP`]) of each other: a move between them
/// turns the nozzle by less than its program can say.
pub fn same_direction(a: [f32; 3], b: [f32; 3]) -> bool {
    // The angle by its sine: near 0 an f32 normal's dot with itself can be
    // 1 − 6e-8, whose arc cosine is 0.02°.
    let [a, b] = [a, b].map(|n| n.map(f64::from));
    let cross = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    let dot: f64 = (0..3).map(|i| a[i] * b[i]).sum();
    let sin = cross.iter().map(|c| c * c).sum::<f64>().sqrt();
    dot > 0.0 && sin < POSITION_STEP.to_radians()
}

/// How far a written power or speed may be from the planned one, relative: a
/// program says a value only when its printed resolution gets within this.
pub const WRITE_TOLERANCE: f64 = 0.005;

/// The largest magnitude any number is written with (in its own unit: mm, deg,
/// mm/min, S units, …). Far beyond any machine; the formatters are exact below it.
pub const MAX_WRITTEN: f64 = 1e9;

/// Whether `planned` can be written with `decimals` decimals: `None` when it
/// cannot (too large, or rounds to 0 from a positive value, or moves by more
/// than [`WRITE_TOLERANCE`]); else the value (as written where it matters).
pub fn quantised(planned: f64, decimals: usize) -> Option<f64> {
    if !planned.is_finite() || planned.abs() >= MAX_WRITTEN {
        return None;
    }
    // Where half a printed unit is within the tolerance, rounding cannot
    // fail: the common case, decided without rounding.
    const HALF_UNIT: [f64; 10] = [0.5, 5e-2, 5e-3, 5e-4, 5e-5, 5e-6, 5e-7, 5e-8, 5e-9, 5e-10];
    if planned.abs() * WRITE_TOLERANCE >= HALF_UNIT[decimals.min(9)] {
        return Some(planned);
    }
    let w = written(planned, decimals);
    let ok = planned == 0.0 || (w != 0.0 && (w - planned).abs() <= WRITE_TOLERANCE * planned.abs());
    ok.then_some(w)
}
