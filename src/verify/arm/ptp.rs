//! The PTPs from and back to a robot's home (docs/collision.md, *The
//! arm*): the controller moves every axis at once, each by its share of
//! the way at every moment (a synchronised PTP: the axes start and stop
//! together), so the arm's path is the straight line in the axes from one
//! end's angles to the other's — A1–A6 and, on a positioner, E1 and E2,
//! which the KRL writes on the same PTP. It is followed every
//! [`PTP_STEP_DEG`] of the axis that moves most, and each pose checked as
//! [`Links::check`] does, the head too.

use super::links::{Links, Place};
use crate::collision::head::Pose;
use crate::plan::arm::{Joints, Solver};
use crate::plan::kinematics::Rotary;
use crate::plan::Where;

/// The most any axis turns between two poses followed along a PTP, deg.
pub const PTP_STEP_DEG: f64 = 2.0;

/// One end of a PTP: the arm's axis angles and the positioner's.
pub(crate) type End = (Joints, Rotary);

/// The poses along the PTP from `a` to `b`, every [`PTP_STEP_DEG`] of the
/// axis that moves most: how far along (0 and 1 its ends, both included)
/// and the axes there.
pub(crate) fn path(a: End, b: End) -> Vec<(f64, End)> {
    let most = (0..6)
        .map(|i| (b.0[i] - a.0[i]).abs())
        .chain([(b.1.tilt - a.1.tilt).abs(), (b.1.c - a.1.c).abs()])
        .fold(0.0f64, f64::max);
    let n = (most / PTP_STEP_DEG).ceil();
    // A runaway count (a non-finite angle) is refused by the other rules.
    let n = if n.is_finite() {
        n.clamp(1.0, 1e5) as usize
    } else {
        1
    };
    (0..=n)
        .map(|k| {
            let t = k as f64 / n as f64;
            let lerp = |x: f64, y: f64| x + t * (y - x);
            let j = std::array::from_fn(|i| lerp(a.0[i], b.0[i]));
            let e = Rotary {
                tilt: lerp(a.1.tilt, b.1.tilt),
                c: lerp(a.1.c, b.1.c),
            };
            (t, (j, e))
        })
        .collect()
}

/// Checks the PTP from `home` to `first` (the move to `at`, its focus
/// `focus`) or, with `back`, from `first` (the last pose) back to `home`:
/// every pose along it but the plan's own (checked as a move), against
/// everything [`Links::check`] checks, the head too — on the way back,
/// against the finished part.
pub(crate) fn check(
    links: &mut Links<'_>,
    solver: &Solver,
    (home, first): (End, End),
    back: bool,
    (at, focus): (Where, [f64; 3]),
) {
    let steps = if back {
        path(first, home)
    } else {
        path(home, first)
    };
    let poses: Vec<Pose> = steps
        .iter()
        .map(|(_, (j, e))| links.head_pose(solver, j, *e))
        .collect();
    links.build_material(back, &poses);
    for (t, (j, e)) in steps {
        // The plan's pose at the PTP's end is checked as its move.
        let plan_end = if back { t == 0.0 } else { t == 1.0 };
        if plan_end {
            continue;
        }
        let place = Place::Ptp { back, way: t, at };
        links.check(solver, &j, e, place, focus);
    }
}

/// A `home` whose PTPs keep the gap, for the help, and how it was
/// found ([`HomeFrom`]): the first pose's A1 and wrist with the upper arm
/// as at `home` and the forearm as there, then raised 30° and 60° more
/// (A3 less, by its sign), else the first pose's own axes, rounded to a tenth of a
/// degree — each within the axes' limits and tried on both PTPs with
/// `links`' checks; `None` where none keeps it.
pub(crate) fn home_keeping(
    links: &Links<'_>,
    solver: &Solver,
    (home, first, last): (End, End, End),
    (at, focus, end_focus): (Where, [f64; 3], [f64; 3]),
) -> Option<(Joints, HomeFrom)> {
    let round = |j: Joints| j.map(|a| (a * 10.0).round() / 10.0);
    let f = first.0;
    // Raising the forearm is A3 less on KUKA's and ABB's arms, more on an
    // arm whose A3 turns the other way.
    let sign3 = f64::from(solver.arm().signs[2]);
    let raised = |up: f64| round([f[0], home.0[1], home.0[2] - up * sign3, f[3], f[4], f[5]]);
    let limits = solver.arm().limits;
    let margin = solver.arm().margin;
    [
        (raised(0.0), HomeFrom::Raised(0)),
        (raised(30.0), HomeFrom::Raised(30)),
        (raised(60.0), HomeFrom::Raised(60)),
        (round(f), HomeFrom::First),
    ]
    .into_iter()
    .find(|(h, _)| {
        let inside = h
            .iter()
            .zip(limits)
            .all(|(a, [lo, hi])| *a >= lo + margin && *a <= hi - margin);
        if !inside {
            return false;
        }
        let mut probe = links.fresh();
        let new_home = (*h, home.1);
        check(&mut probe, solver, (new_home, first), false, (at, focus));
        check(
            &mut probe,
            solver,
            (new_home, last),
            true,
            (Where::End, end_focus),
        );
        !probe.ptp_hit()
    })
}

pub(crate) use crate::diag::message::collision::HomeFrom;

#[cfg(test)]
mod tests {
    use super::*;

    /// The path's steps: no axis turns more than the step between two
    /// poses, both ends are in it, and the axes move together (each by
    /// the same share of its way).
    #[test]
    fn the_path_is_a_line_in_the_axes() {
        let a = (
            [0.0, -90.0, 90.0, 0.0, 0.0, 0.0],
            Rotary { tilt: 0.0, c: 0.0 },
        );
        let b = (
            [31.0, -60.0, 70.0, 10.0, 45.0, -5.0],
            Rotary { tilt: 50.0, c: 3.0 },
        );
        let p = path(a, b);
        // E1 moves most: 50° in 25 steps.
        assert_eq!(p.len(), 26);
        assert_eq!(p[0].1 .0, a.0);
        assert_eq!(p[25].1 .0, b.0);
        for w in p.windows(2) {
            for i in 0..6 {
                assert!((w[1].1 .0[i] - w[0].1 .0[i]).abs() <= PTP_STEP_DEG + 1e-12);
            }
            assert!((w[1].1 .1.tilt - w[0].1 .1.tilt).abs() <= PTP_STEP_DEG + 1e-12);
        }
        let (t, (j, _)) = p[5];
        for ((x, x0), x1) in j.iter().zip(a.0).zip(b.0) {
            if (x1 - x0).abs() > 0.0 {
                assert!(((x - x0) / (x1 - x0) - t).abs() < 1e-12);
            }
        }
        // No move: one step, both ends.
        assert_eq!(path(a, a).len(), 2);
    }
}
