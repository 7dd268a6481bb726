//! What a gas or powder event sets on a robot's cell, for the robot back
//! ends to write in their own words.

use crate::ir::{Robot, Signal};
use crate::plan::Io;

/// One output a cell event sets.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CellOut<'a> {
    /// Digital output `n` on or off; `what` it switches (`gas`, `powder`).
    Switch {
        /// The output: its number, or on an ABB robot its signal's name.
        n: &'a Signal,
        /// On or off.
        on: bool,
        /// What it switches.
        what: &'static str,
    },
    /// The feeder's rate: analog output `n` at `fraction` of full scale,
    /// for `g_min` g/min.
    Rate {
        /// The output: its number, or on an ABB robot its signal's name.
        n: &'a Signal,
        /// The fraction of full scale.
        fraction: f64,
        /// The rate, g/min.
        g_min: f32,
    },
}

/// The outputs `event` sets on `robot`'s cell, in order: a feeder's rate
/// before the feeder switches on.
pub fn outputs<'a>(robot: &'a Robot, event: Io) -> Vec<CellOut<'a>> {
    let cell = &robot.cell;
    let mut out = Vec::new();
    let rate = |out: &mut Vec<CellOut<'a>>, g_min: f32| {
        if let Some(r) = cell.powder.as_ref().and_then(|p| p.rate.as_ref()) {
            out.push(CellOut::Rate {
                n: &r.output,
                fraction: g_min as f64 / r.full_scale,
                g_min,
            });
        }
    };
    let switch = |n, on: bool, what: &'static str| CellOut::Switch { n, on, what };
    match (event, &cell.gas, &cell.powder) {
        (Io::GasOn, Some(g), _) => out.push(switch(&g.output, true, "gas")),
        (Io::GasOff, Some(g), _) => out.push(switch(&g.output, false, "gas")),
        (Io::PowderOn(r), _, Some(p)) => {
            rate(&mut out, r);
            out.push(switch(&p.output, true, "powder"));
        }
        (Io::PowderRate(r), _, Some(_)) => rate(&mut out, r),
        (Io::PowderOff, _, Some(p)) => out.push(switch(&p.output, false, "powder")),
        _ => {}
    }
    out
}
