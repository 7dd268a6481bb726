//! A 5-axis CNC's rotary axes along the plan, for the page's angle plot:
//! the tilt axis (A or B) and C of every move, kept per layer as each
//! axis's lowest and highest angle — on a tilting table, the angles the
//! table turns the part to, layer by layer. The angles are the plan's, the
//! ones the program writes and the verifier checks against the limits.
//! A robot's two-axis positioner is plotted the same way: E1 (tilt) and E2
//! (rotate), the angles it turns the part to, layer by layer.

use crate::ir::{Layer, Machine};
use crate::plan::{Move, Visit};
use serde::Serialize;

/// What the page says about the rotary axes.
#[derive(Serialize)]
pub struct Rotary {
    /// The kinematics' word (`head_ac`, `table_bc`, …; `positioner` for a
    /// robot's).
    pub kinematics: &'static str,
    /// The axes' names: the tilt axis's, then `C` (`E1`, `E2`).
    pub axes: [String; 2],
    /// Each axis's `[lowest, highest]` travel, deg.
    pub limits: [[f64; 2]; 2],
    /// Every layer's `[[lowest, highest]; 2]` angles, deg, over its moves
    /// (`None`: none). The program's first moves count with the first layer.
    pub layers: Vec<Option<[[f64; 2]; 2]>>,
}

impl Visit for Rotary {
    fn layer(&mut self, _: usize, _: &Layer) {
        self.layers.push(None);
    }

    fn motion(&mut self, m: &Move) {
        if self.layers.is_empty() {
            self.layers.push(None);
        }
        let slot = self.layers.last_mut().expect("a layer");
        let r = slot.get_or_insert([[f64::INFINITY, f64::NEG_INFINITY]; 2]);
        for (r, a) in r.iter_mut().zip([m.axes.tilt, m.axes.c]) {
            *r = [r[0].min(a), r[1].max(a)];
        }
    }
}

/// The rotary axes along `plan`, when `machine` is a CNC that has them or a
/// robot with a positioner.
pub fn of(machine: &Machine, plan: &crate::plan::Plan<'_>) -> Option<Rotary> {
    let mut r = match machine {
        Machine::Cnc(c) => {
            let kin = c.effective_kinematics();
            let tilt = kin.tilt_letter()?;
            Rotary {
                kinematics: kin.word(),
                axes: [tilt.to_string(), "C".into()],
                limits: [c.limits.tilt, c.limits.rotary],
                layers: Vec::new(),
            }
        }
        Machine::Robot(robot) => {
            let p = robot.positioner.as_deref()?;
            Rotary {
                kinematics: "positioner",
                axes: ["E1".into(), "E2".into()],
                limits: [p.tilt.limits, p.rotate.limits],
                layers: Vec::new(),
            }
        }
    };
    plan.walk(&mut r);
    Some(r)
}
