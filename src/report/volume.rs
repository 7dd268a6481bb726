//! The metal each layer's deposit moves lay, two ways ([`Beads`]): a
//! deposit move runs from an IR point whose laser is on to the next point of
//! its path, so the volumes are a sum over the IR's points, in the plan's
//! order, without following the plan again (its lengths and times come from
//! the verifier's summary).

use super::bead::Beads;
use crate::ir::{Layer, Point, Program};

/// Bead and stacked volume of each layer, mm³.
pub fn per_layer(program: &Program, beads: &Beads) -> Vec<(f64, f64)> {
    program.layers.iter().map(|l| layer(l, beads)).collect()
}

fn layer(layer: &Layer, beads: &Beads) -> (f64, f64) {
    // The layer lays one track: one path deposits.
    let depositing = layer
        .paths
        .iter()
        .filter(|p| p.points.iter().any(|q| q.laser_on))
        .count();
    let single = depositing <= 1;
    let mut sum = (0.0, 0.0);
    for path in &layer.paths {
        for w in path.points.windows(2) {
            if w[0].laser_on {
                let (b, s) = volumes(&w[0], &w[1], beads, single);
                sum.0 += b;
                sum.1 += s;
            }
        }
    }
    sum
}

/// The volumes (bead, stacked) the move from `from` to `to` lays, mm³.
fn volumes(from: &Point, to: &Point, beads: &Beads, single: bool) -> (f64, f64) {
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
    let s = beads.stacked(from.layer_height as f64, a, single);
    (a * across, s * across)
}
