//! How far inside its rules an arm follows a plan: on a sample of the
//! plan's moves, each axis's distance inside its limits less the margin and
//! each LIN's distance outside the singularity threshold. What `spin = auto`
//! ([`crate::plan::spin`]) and a base that brings the part within reach
//! ([`super::reach`]) are chosen by.

use super::{Follow, Joints, Solved};
use crate::ir::{Program, Robot, Spin};
use crate::plan::{Move, Plan};

/// About how many moves a choice looks at.
pub const SAMPLES: usize = 4000;

/// About [`SAMPLES`] of the plan's moves, evenly spread, the first and the
/// last among them: one walk, spaced by the IR's point count (a move a point,
/// and a few more a path), no copy of the whole plan.
pub fn sample(program: &Program, plan: &Plan<'_>) -> Vec<Move> {
    let points: usize = program
        .layers
        .iter()
        .flat_map(|l| &l.paths)
        .map(|p| p.points.len())
        .sum();
    let every = points.div_ceil(SAMPLES).max(1);
    let mut moves = Vec::with_capacity(SAMPLES + 1);
    let mut last = None;
    let mut k = 0usize;
    plan.walk(&mut |m: &Move| {
        if k.is_multiple_of(every) {
            moves.push(*m);
            last = None;
        } else {
            last = Some(*m);
        }
        k += 1;
    });
    moves.extend(last);
    moves
}

/// How far inside the arm's rules `robot` follows `moves` with the tool
/// turned by `deg`, deg: the least over the moves of each axis's distance
/// inside its limits less the margin and, on the LINs (every move but the
/// first), of the distance outside the singularity threshold. Negative
/// where a rule breaks; −∞ where a pose is out of reach or the
/// configuration changes on a LIN.
pub fn clearance(robot: &Robot, deg: f64, moves: &[Move]) -> f64 {
    let mut turned = robot.clone();
    turned.spin = Spin::Declared { deg };
    // The moves are picked across the plan: nothing lies between them.
    let Some(mut follow) = Follow::new(&turned).map(Follow::ends_only) else {
        return f64::NEG_INFINITY;
    };
    let mut solved: Vec<Solved> = Vec::with_capacity(moves.len());
    for m in moves {
        if let Some(done) = follow.push(m) {
            solved.extend(done);
        }
    }
    solved.extend(follow.take());
    let solver = follow.solver();
    let arm = solver.arm();
    let mut least = f64::INFINITY;
    let mut status: Option<u8> = None;
    for s in &solved {
        let Some(j) = s.joints else {
            return f64::NEG_INFINITY;
        };
        least = least.min(inside_limits(&j, &arm.limits, arm.margin));
        let st = solver.status_at(&j, &s.wrist);
        if let Some(before) = status {
            if before != st {
                return f64::NEG_INFINITY;
            }
            let near = solver.singular(&j, &s.wrist).into_iter();
            least = least.min(near.fold(f64::INFINITY, f64::min) - arm.singularity);
        }
        status = Some(st);
    }
    least
}

/// The least distance of the axes `j` inside `limits` less `margin`, deg.
fn inside_limits(j: &Joints, limits: &[[f64; 2]; 6], margin: f64) -> f64 {
    j.iter()
        .zip(limits)
        .map(|(a, [lo, hi])| (a - (lo + margin)).min((hi - margin) - a))
        .fold(f64::INFINITY, f64::min)
}
