//! The finish of a wall on a scan (docs/repair.md, *A wall on a scan*):
//! every bead of a line runs along the same polyline on every layer (its
//! levelling passes through their own points on it), so at the middle of
//! each laser-on move of the last layer the predicted face is the scanned
//! surface there plus what each layer's move through that place raises it
//! by (`A/pitch` at the move's speed,
//! [`crate::ir::Point::predicted_rise`]), against the wall's top there.
//! The moves are found through a grid of cells half a bead wide: linear
//! in the moves.

use super::{first_layer, Finish, Sample, Tally};
use crate::ir::Program;
use crate::sema::model::{OpenWall, WallOnScan};
use std::collections::BTreeMap;

/// Every laser-on move of the plan, seen from above, in a grid of square
/// cells: each move is listed in every cell its box covers.
struct Moves {
    cell: f64,
    /// Per move: its ends (x, y) and the rise it lays.
    moves: Vec<([f64; 2], [f64; 2], f64, usize)>,
    cells: BTreeMap<[i64; 2], Vec<usize>>,
}

impl Moves {
    fn new(program: &Program, d: &crate::deposit::Deposit, cell: f64) -> Moves {
        let mut out = Moves {
            cell,
            moves: Vec::new(),
            cells: BTreeMap::new(),
        };
        for (li, layer) in program.layers.iter().enumerate() {
            for path in &layer.paths {
                for w in path.points.windows(2).filter(|w| w[0].laser_on) {
                    let (a, b) = ([w[0].pos[0], w[0].pos[1]], [w[1].pos[0], w[1].pos[1]]);
                    let rise = w[0].predicted_rise(d, Some(&w[1]));
                    let k = out.moves.len();
                    out.moves.push((a, b, rise, li));
                    let [i0, j0] = out.key([a[0].min(b[0]), a[1].min(b[1])]);
                    let [i1, j1] = out.key([a[0].max(b[0]), a[1].max(b[1])]);
                    for i in i0..=i1 {
                        for j in j0..=j1 {
                            out.cells.entry([i, j]).or_default().push(k);
                        }
                    }
                }
            }
        }
        out
    }

    fn key(&self, p: [f64; 2]) -> [i64; 2] {
        p.map(|c| (c / self.cell).floor() as i64)
    }

    /// What every layer raises the place `p` by: on each layer, the first
    /// move through it (within a micrometre: the beads of one line run
    /// through the same points, and the lines are a pitch apart).
    fn raised(&self, p: [f64; 2]) -> f64 {
        let Some(list) = self.cells.get(&self.key(p)) else {
            return 0.0;
        };
        let mut seen: Vec<usize> = Vec::new();
        let mut sum = 0.0;
        for &k in list {
            let (a, b, rise, layer) = self.moves[k];
            if seen.contains(&layer) || crate::fill::coverage::distance2(p, &[a, b]) > 1e-6 {
                continue;
            }
            seen.push(layer);
            sum += rise;
        }
        sum
    }
}

/// The finish of `program`, the plan of the wall `on`, with every place
/// it looked at; `None` for a plan without a bead or a layer.
pub(super) fn sampled(
    program: &Program,
    wall: &OpenWall,
    on: &WallOnScan,
) -> Option<(Finish, Vec<Sample>)> {
    let d = program.bead.as_ref()?.deposit();
    let cell = (program.limits.bead_width / 2.0).max(0.1);
    let moves = Moves::new(program, &d, cell);
    let last = program.layers.last()?;
    let mut top = crate::slice::wall::top_form(wall, on);
    let mut tally = Tally::new(first_layer(&program.layers[0])?, None);
    for path in &last.paths {
        for w in path.points.windows(2).filter(|w| w[0].laser_on) {
            let at = [
                (w[0].pos[0] + w[1].pos[0]) / 2.0,
                (w[0].pos[1] + w[1].pos[1]) / 2.0,
            ];
            let Some(base) = on.base.surface.at(at) else {
                continue;
            };
            let Ok(top) = top.at(at) else {
                continue;
            };
            tally.add(at, top, base + moves.raised(at) - top);
        }
    }
    tally.done()
}
