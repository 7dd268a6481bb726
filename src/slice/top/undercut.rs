//! How far a build direction must tilt to build a target's overhang
//! (docs/repair.md, *Overhangs*): the refusal says it, since a repair shop
//! with a tilting head or table asks first whether its machine could.
//!
//! Layers laid along a direction `d` stand on each other along `d`: a
//! line along `d` must meet the target above the scan in one piece, from
//! the scan up, or its upper piece is laid on nothing. The vertical line
//! at the refused point meets it in two (the overhang, and the part under
//! it). For the overhang's underside there, `u`, a direction builds it
//! when the line through `u` runs down inside the target until it reaches
//! the scan, and up from `u` leaves the target once. The directions tried
//! are [`Direction::tried`]'s, as `direction = auto` tries them; the first
//! that builds it is the least tilt, to their step.

use super::direction::{Direction, MAX_TILT};
use crate::sema::model::{Top, TopExtrusion};

/// How far above the refused point's top the line up is followed, mm.
const ABOVE: f64 = 20.0;

/// The step along the line, mm: a corner of the target the line clips by
/// more than this is seen.
const STEP: f64 = 0.02;

/// The least tilt from vertical (deg) and the direction it tilts toward
/// (deg from +x, counter-clockwise) that builds the overhang whose
/// underside is at `under` over `p`, under a top at `top`; `None` when none
/// within [`MAX_TILT`] does, or `ex`'s target is no mesh or solid on a scan.
pub fn least_tilt(ex: &TopExtrusion, p: [f64; 2], under: f64, top: f64) -> Option<[f64; 2]> {
    let scan = &ex.base.as_ref()?.surface;
    if !matches!(ex.top, Top::Mesh(_) | Top::Solid(_)) {
        return None;
    }
    let inside = |q: [f64; 3]| ex.top.contains(q);
    let u = [p[0], p[1], under];
    Direction::tried(0.0, MAX_TILT, false).find_map(|dir| {
        let d = dir.vector();
        let built =
            stands(&inside, &|q| scan.at(q), u, d) && leaves_once(&inside, u, d, top + ABOVE);
        built.then_some(dir.pair())
    })
}

/// Whether the line from `u` down along `−d` stays in the target until it
/// reaches the scan (`scan`: its height, where it has one).
fn stands(
    inside: &impl Fn([f64; 3]) -> bool,
    scan: &impl Fn([f64; 2]) -> Option<f64>,
    u: [f64; 3],
    d: [f64; 3],
) -> bool {
    let mut t = STEP;
    loop {
        let q = [u[0] - t * d[0], u[1] - t * d[1], u[2] - t * d[2]];
        match scan([q[0], q[1]]) {
            Some(b) if q[2] <= b => return true,
            // Off the scan: nothing known to stand on.
            None => return false,
            Some(_) if !inside(q) => return false,
            Some(_) => {}
        }
        t += STEP;
    }
}

/// Whether the line from `u` up along `d` leaves the target once and does
/// not enter it again below `ceiling`.
fn leaves_once(inside: &impl Fn([f64; 3]) -> bool, u: [f64; 3], d: [f64; 3], ceiling: f64) -> bool {
    let length = (ceiling - u[2]) / d[2];
    let mut left = false;
    let mut t = STEP;
    while t < length {
        let q = [u[0] + t * d[0], u[1] + t * d[1], u[2] + t * d[2]];
        if !inside(q) {
            left = true;
        } else if left {
            return false;
        }
        t += STEP;
    }
    true
}
