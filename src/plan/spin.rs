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
//! [`SAMPLES`](super::arm::clearance::SAMPLES) moves spread over the plan;
//! the verifier then checks every move with it, as with a declared `spin`.

use super::arm::clearance::{clearance, sample};
use super::arm::Follow;
use super::Plan;
use crate::ir::{Machine, Program, Spin};

/// The turns tried, deg apart.
pub const STEP: f64 = 15.0;

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
