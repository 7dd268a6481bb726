//! What the robot program tests (tests/krl_program.rs, tests/rapid_program.rs)
//! read from an IR to compare a program's trace with: its deposits, the
//! tool's beam axis, and distances.

use lmdc::ir::{Point, Program, ToolAxis};

/// The tool's beam axis as (index of the tool frame's axis, sign).
pub fn beam_axis(b: ToolAxis) -> (usize, f64) {
    match b {
        ToolAxis::PlusX => (0, 1.0),
        ToolAxis::MinusX => (0, -1.0),
        ToolAxis::PlusY => (1, 1.0),
        ToolAxis::MinusY => (1, -1.0),
        ToolAxis::PlusZ => (2, 1.0),
        ToolAxis::MinusZ => (2, -1.0),
    }
}

/// The distance from `a` to `b`.
pub fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt()
}

/// Every IR deposit (a segment whose start has the laser on), in order.
pub fn deposits(p: &Program) -> Vec<(Point, Point)> {
    p.layers
        .iter()
        .flat_map(|l| &l.paths)
        .flat_map(|path| path.points.windows(2))
        .filter(|w| w[0].laser_on)
        .map(|w| (w[0], w[1]))
        .collect()
}
