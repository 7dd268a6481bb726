//! The free angle about the nozzle axis (`spin = auto`): a coaxial powder
//! nozzle lays the same bead however the tool is turned about its beam, so
//! that turn is lmdc's to choose where the turn it carries from normal to
//! normal ([`crate::plan::orient`]) breaks one of the arm's rules.
//!
//! The rule, documented in docs/robots.md: 0° is kept when the arm follows
//! the plan with it — every pose reached, every axis inside its limits less
//! the margin, every LIN away from the singular configurations, no change
//! of configuration. Otherwise each turn in steps of [`STEP`] is tried and
//! the one with the largest clearance is kept (the least, over the plan, of
//! each axis's distance inside its margin and each LIN's distance outside
//! the singularity threshold; ties to the smaller turn), if it does better
//! than 0°. One turn for the whole program: the tool turns with the normal
//! as before, smoothly, only offset. The choice is made on about
//! [`SAMPLES`] moves spread over the plan; the verifier then checks every
//! move with it, as with a declared `spin`.

use super::arm::{Follow, Joints, Solved};
use super::{Move, Plan};
use crate::ir::{Machine, Program, Robot, Spin};

/// The turns tried, deg apart.
pub const STEP: f64 = 15.0;
/// About how many moves the choice looks at.
pub const SAMPLES: usize = 4000;

/// Chooses the spin of every robot of `program` whose `spin` is `auto` and
/// whose arm lmdc can solve; other machines are left as they are.
pub fn choose(program: &mut Program) {
    for i in 0..program.machines.len() {
        let Machine::Robot(r) = &program.machines[i] else {
            continue;
        };
        // A part the arm cannot reach is refused without solving a pose.
        let refused = || super::arm::reach::beyond(program, r).is_some();
        if !matches!(r.spin, Spin::Auto { .. }) || Follow::new(r).is_none() || refused() {
            continue;
        }
        let deg = best(program, &program.machines[i]);
        if let Machine::Robot(r) = &mut program.machines[i] {
            r.spin = Spin::Auto { deg };
        }
    }
}

/// The turn to use for `machine` (a robot with a solvable arm).
fn best(program: &Program, machine: &Machine) -> f64 {
    let Machine::Robot(robot) = machine else {
        return 0.0;
    };
    let moves = sample(program, &Plan::new(program, machine));
    let zero = clearance(robot, 0.0, &moves);
    if zero >= 0.0 {
        return 0.0;
    }
    let steps = (180.0 / STEP) as i32;
    let mut best = (zero, 0.0);
    // −165 … 180: every turn once, the smaller first among equals.
    let mut turns: Vec<f64> = (1 - steps..=steps).map(|k| k as f64 * STEP).collect();
    turns.sort_by(|a, b| a.abs().total_cmp(&b.abs()).then(b.total_cmp(a)));
    for deg in turns {
        let c = clearance(robot, deg, &moves);
        if c > best.0 {
            best = (c, deg);
        }
    }
    best.1
}

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
