//! Following a machine's motion plan and adding up what each move costs: the
//! report's numbers come from the moves the program makes, so its times are
//! the program's (at the programmed speeds; accelerations are not modelled).

use super::bead::Beads;
use super::Tally;
use crate::ir::{Machine, Point, Program};
use crate::plan::{Move, Speed, Visit, Where};

/// A [`Visit`] that adds every move of a plan into its layer's [`Tally`].
pub struct Walk<'a> {
    program: &'a Program,
    /// Rapid moves run at the machine's highest speed, mm/s.
    rapid: f64,
    beads: Option<&'a Beads>,
    layer: usize,
    /// The layer lays one track (one path deposits).
    single: bool,
    at: Option<[f64; 3]>,
    /// One per layer of the IR.
    pub rows: Vec<Tally>,
}

/// The speed a machine's rapid moves are timed at: its `max_speed`.
pub fn rapid_speed(m: &Machine) -> f64 {
    m.common().max_speed
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

impl<'a> Walk<'a> {
    /// A walk of `program`'s plan on `machine`, computing volumes when the
    /// bead model is known.
    pub fn new(program: &'a Program, machine: &Machine, beads: Option<&'a Beads>) -> Self {
        Walk {
            program,
            rapid: rapid_speed(machine),
            beads,
            layer: 0,
            single: false,
            at: None,
            rows: vec![Tally::default(); program.layers.len()],
        }
    }

    fn point(&self, w: Where) -> Option<&'a Point> {
        match w {
            Where::Point { layer, path, point } => self
                .program
                .layers
                .get(layer)?
                .paths
                .get(path)?
                .points
                .get(point),
            _ => None,
        }
    }

    /// The volumes (bead, stacked) a deposit move lays, mm³.
    fn volumes(&self, m: &Move, from: &Point) -> (f64, f64) {
        let (Some(beads), Some(to)) = (self.beads, self.point(m.at)) else {
            return (0.0, 0.0);
        };
        let d = [
            to.pos[0] - from.pos[0],
            to.pos[1] - from.pos[1],
            to.pos[2] - from.pos[2],
        ];
        let n = from.normal.map(f64::from);
        let along = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
        let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        // Length over the ground: what a layer holds per unit of (docs/ir.md).
        let across = (len * len - along * along).max(0.0).sqrt();
        if len <= 0.0 {
            return (0.0, 0.0);
        }
        let v = from.speed as f64 * across / len;
        let a = beads.area(v, from.powder as f64);
        let s = beads.stacked(from.layer_height as f64, a, self.single);
        (a * across, s * across)
    }
}

impl Visit for Walk<'_> {
    fn layer(&mut self, index: usize, layer: &crate::ir::Layer) {
        self.layer = index;
        let depositing = layer
            .paths
            .iter()
            .filter(|p| p.points.iter().any(|q| q.laser_on))
            .count();
        self.single = depositing <= 1;
    }

    /// A cooling wait belongs to the layer that cools: the plan dwells
    /// before the next layer begins.
    fn dwell(&mut self, seconds: f64) {
        if let Some(r) = self.rows.get_mut(self.layer) {
            r.dwell_s += seconds.max(0.0);
        }
    }

    fn motion(&mut self, m: &Move) {
        // The first move starts wherever the machine stands: no length.
        let d = self.at.replace(m.to).map_or(0.0, |from| dist(from, m.to));
        let v = match m.speed {
            Speed::Feed(v) => v as f64,
            Speed::Rapid => self.rapid,
        };
        let t = if v > 0.0 && v.is_finite() { d / v } else { 0.0 };
        let source = self.point(m.source()).copied();
        let vols = match (m.deposits(), &source) {
            (true, Some(p)) => self.volumes(m, p),
            _ => (0.0, 0.0),
        };
        let Some(row) = self.rows.get_mut(self.layer) else {
            return;
        };
        row.motion_s += t;
        if m.deposits() {
            row.deposit_mm += d;
            row.laser_on_s += t;
            row.energy_j += m.power as f64 * t;
            if let Some(p) = source {
                row.powder_g += p.powder as f64 / 60.0 * t;
            }
            row.bead_volume_mm3 += vols.0;
            row.stacked_volume_mm3 += vols.1;
        } else {
            row.travel_mm += d;
        }
    }
}
