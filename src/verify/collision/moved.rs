//! The help for a fixture in the head's way: where to move it, found by
//! making the plan again with it there — its travels rise over it where it
//! now stands, so the plan changes with it — and checking the head along
//! it (docs/collision.md, *What is said*).

use super::super::rule::MachineCx;
use super::Collision;
use crate::diag::message::collision::Moved;
use crate::ir::FixtureShape;

/// Most points a search re-plans in all (a probe walks the whole plan, a
/// few tenths of a second for 50 k points): past it, fewer directions are
/// searched, or none, and the help names no distance. A refused build
/// should not wait much longer than a built one.
const BUDGET: usize = 2_000_000;

/// The probes a direction's search takes at most: a box beyond every
/// focus's reach, then halving to a tenth of a millimetre.
const PROBES: usize = 24;

/// The directions a fixture is moved in: the axis, its sign, as printed.
const DIRECTIONS: [(usize, f64, &str); 4] = [
    (0, -1.0, "−x"),
    (0, 1.0, "+x"),
    (1, -1.0, "−y"),
    (1, 1.0, "+y"),
];

impl Collision<'_> {
    /// Where fixture `i` keeps the head's gap at every pose of the plan
    /// made again with it there: moved along X or Y, its `at` on a tenth of
    /// a millimetre, the least move found in any of the four directions
    /// (searched from where its box lies beyond the head's reach from every
    /// focus, by halving). `None` where no probe keeps it clear or the plan
    /// is too large to make again that often.
    pub(super) fn moved(&self, cx: &MachineCx<'_>, i: usize) -> Option<Moved> {
        let f = self.program.fixtures.get(i)?;
        let points: usize = (self.program.layers.iter())
            .flat_map(|l| &l.paths)
            .map(|p| p.points.len())
            .sum();
        let dirs = (BUDGET / (points.max(1) * PROBES)).min(DIRECTIONS.len());
        // A fixture fixed to the machine moves in its coordinates.
        let fixed = (self.fixed.iter()).find(|x| f.machine.is_some() && x.tilts == f.tilts);
        let (lo, hi, up_z) = fixed.map_or(self.extent, |x| x.extent);
        if dirs == 0 || lo[0].is_nan() || lo[0] > hi[0] {
            return None;
        }
        let tolerance = match &f.shape {
            FixtureShape::Mesh { tolerance, .. } => *tolerance,
            _ => std::f64::consts::SQRT_2,
        };
        let reach = cx.machine.common().head.spread(up_z) + self.head.gap + tolerance + 0.1;
        let (blo, bhi) = f.bounds();
        // Beyond `far`, the box lies farther from every focus than the head
        // reaches sideways: no pose comes near it.
        let mut order: Vec<_> = DIRECTIONS
            .iter()
            .map(|&(k, sign, name)| {
                let far = if sign < 0.0 {
                    bhi[k] - (lo[k] - reach)
                } else {
                    hi[k] + reach - blo[k]
                };
                (far.max(0.1), k, sign, name)
            })
            .collect();
        order.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut best: Option<Moved> = None;
        for &(far, k, sign, name) in order.iter().take(dirs) {
            // Past the first direction found, only a shorter move counts:
            // a direction refused at the best move so far costs one plan,
            // not a dozen.
            let within = best.as_ref().map_or(far, |b| far.min(b.by));
            if let Some(m) = search(cx, i, (k, sign, name), within) {
                if best.as_ref().is_none_or(|b| m.by < b.by) {
                    best = Some(m);
                }
            }
        }
        best
    }
}

/// The least move of fixture `i` along axis `k` (`sign`) within about
/// `far` that keeps it clear, its coordinate on a tenth of a millimetre:
/// found by halving between a move whose probe is refused (or none) and
/// one whose probe is clear, so the tenth before it was refused.
fn search(
    cx: &MachineCx<'_>,
    i: usize,
    (k, sign, name): (usize, f64, &'static str),
    far: f64,
) -> Option<Moved> {
    let at0 = cx.program.fixtures[i].at;
    // The n-th tenth of a millimetre past `at0` along the move.
    let base = if sign < 0.0 {
        (at0[k] * 10.0).ceil()
    } else {
        (at0[k] * 10.0).floor()
    };
    let place = |n: f64| {
        let mut at = at0;
        at[k] = (base + sign * n) / 10.0;
        at
    };
    let mut hi = (far * 10.0).ceil() + 1.0;
    if !probe(cx, i, place(hi)) {
        return None;
    }
    let mut lo = 0.0;
    for _ in 0..PROBES {
        if hi - lo <= 1.0 {
            break;
        }
        let mid = ((lo + hi) / 2.0).floor();
        if probe(cx, i, place(mid)) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let at = place(hi);
    Some(Moved {
        axis: name,
        by: (at[k] - at0[k]).abs(),
        at,
    })
}

/// Whether fixture `i` at `at` keeps the head's gap at every pose of
/// `cx`'s machine's plan made again with it there.
fn probe(cx: &MachineCx<'_>, i: usize, at: [f64; 3]) -> bool {
    let mut program = cx.program.clone();
    program.fixtures[i].at = at;
    let name = cx.machine.name();
    let Some(machine) = program.machines.iter().find(|m| m.name() == name) else {
        return false;
    };
    let moved = MachineCx {
        program: &program,
        machine,
        origin: cx.origin,
    };
    super::head_clear_of(&moved, i)
}
