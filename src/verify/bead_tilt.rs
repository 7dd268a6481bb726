//! `lmd::bead-tilt`: a bead model holds for the nozzle's tilt it was
//! measured at. Coupons are laid with the nozzle vertical unless the bead
//! says otherwise (`tilt = 0 deg .. 30 deg`); a deposit whose nozzle tilts
//! from vertical (against gravity, in the cell) more than [`SLACK`] beyond
//! those tilts lays a melt pool that runs downhill, and its heights are a
//! guess: a warning, per machine.
//!
//! The tilt is the beam's from straight down in the cell: a robot's or a
//! tilting head's nozzle tilts by its point's build direction (carried
//! through a robot's base frame, and through its positioner's angles for
//! the layer where it has one); a tilting table turns the part under a
//! vertical nozzle, and a 3-axis machine's nozzle is vertical, so neither
//! tilts it.

use super::rule::{MachineCx, PlanRule, Worst};
use crate::diag::message::bead::{bead_tilt, TiltBeyond};
use crate::diag::Diagnostics;
use crate::ir::{Kinematics, Layer, Machine};
use crate::plan::positioner::{lean, Kin};
use crate::plan::{Move, Visit};
use nalgebra::{Rotation3, Vector3};

/// How far beyond the tilts a bead was measured at a deposit may tilt
/// without a word, deg: within a few degrees of vertical a bead lays as it
/// does vertical, and a positioner that keeps a layer's mean normal up
/// leaves its points tilted by that much on a curved layer.
pub const SLACK: f64 = 5.0;

/// How a machine's nozzle stands in the cell.
enum Stand {
    /// Fixed part: the beam tilts by the point's normal, turned by the
    /// robot's base.
    Fixed(Rotation3<f64>),
    /// A robot's positioner turns the part: by its angles, layer by layer.
    Positioner(Kin, Vec<[f64; 2]>),
}

/// `lmd::bead-tilt` of one machine's plan.
pub(super) struct BeadTilt {
    measured: [f64; 2],
    written: bool,
    stand: Stand,
    layer: usize,
    worst: Option<Worst>,
}

impl<'p> PlanRule<'p> for BeadTilt {
    fn new(cx: &MachineCx<'p>) -> Option<Self> {
        let bead = cx.program.bead.as_ref()?;
        let stand = match cx.machine {
            Machine::Cnc(c) if c.kinematics == Kinematics::Xyz || c.kinematics.is_table() => {
                return None
            }
            Machine::Cnc(_) => Stand::Fixed(Rotation3::identity()),
            Machine::Robot(r) => match (Kin::of(r), &r.positioner) {
                (Some(kin), Some(p)) => Stand::Positioner(kin, p.angles.clone()),
                _ => Stand::Fixed(r.base.value.as_ref().map_or(Rotation3::identity(), |b| {
                    crate::plan::arm::frame(b).rotation.to_rotation_matrix()
                })),
            },
        };
        Some(BeadTilt {
            measured: bead.tilt.unwrap_or([0.0, 0.0]),
            written: bead.tilt.is_some(),
            stand,
            layer: 0,
            worst: None,
        })
    }

    fn report(self, cx: &MachineCx<'p>, out: &mut Diagnostics) {
        let Some(w) = self.worst else { return };
        let t = TiltBeyond {
            machine: cx.machine.name(),
            measured: self.measured,
            written: self.written,
            positioner: matches!(self.stand, Stand::Positioner(..)),
        };
        out.push(bead_tilt(&w, &t, cx.program.origins.bead));
    }
}

impl BeadTilt {
    /// How far the beam along `-n` tilts from straight down, deg.
    fn tilt(&self, n: [f64; 3]) -> f64 {
        match &self.stand {
            Stand::Fixed(r) => {
                let v = r * Vector3::from(n);
                (v.x * v.x + v.y * v.y).sqrt().atan2(v.z).to_degrees()
            }
            Stand::Positioner(kin, angles) => {
                let e = angles.get(self.layer).copied().unwrap_or([0.0, 0.0]);
                lean(kin, e, n)
            }
        }
    }
}

impl Visit for BeadTilt {
    fn layer(&mut self, index: usize, _layer: &Layer) {
        self.layer = index;
    }

    fn motion(&mut self, m: &Move) {
        if !m.deposits() {
            return;
        }
        let t = self.tilt(m.normal.map(f64::from));
        let [lo, hi] = self.measured;
        if t > hi + SLACK {
            Worst::hit(&mut self.worst, t, hi, m.at);
        } else if t < lo - SLACK {
            Worst::hit(&mut self.worst, t, lo, m.at);
        }
    }
}
