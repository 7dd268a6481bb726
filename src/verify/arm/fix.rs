//! The helps for an arm's link too close (docs/collision.md, *What is
//! said*): each a number the file can take, found by changing it in a copy
//! of the program and following the arm along the plan made again, with
//! the same checks the refusal came from, at every pose.
//!
//! - A fixture in a link's way: moved along X or Y, the least move in the
//!   four directions (doubling from 10 mm, then halving to a tenth of a
//!   millimetre) whose plan — its travels rise over the fixture where it
//!   now stands — keeps the links and the head clear of it.
//! - The arm folded back onto itself: the part stood farther from the
//!   arm's foot along the horizontal line from the foot to the base
//!   (doubling from 10 mm, halving to a millimetre), every arm rule kept at
//!   every pose — reach, the axes' limits, the singularities, one
//!   configuration, the axes' speeds, the links clear of everything.
//! - The tool, angled on its flange, down at the part's plane: the tool
//!   turned about the beam (`spin`), nearest the turn used first, 15° at a
//!   time each way, then halved to a tenth of a degree, every arm rule kept.
//!
//! A probe makes the whole plan again: the searches stop once they have
//! made [`BUDGET`] points again in all, and the help then names no number.
//! A fixture's probe stops following the arm at the path after a link
//! first meets the fixture (the probe is refused whatever follows), and
//! is charged the moves it followed; a probe starts only where a whole
//! plan's worth is left.

use super::ArmRule;
use crate::diag::message::collision::{LinkFix, Moved};
use crate::ir::{Machine, Program, Spin};
use crate::plan::Plan;
use crate::verify::rule::{MachineCx, PlanRule};

/// Most points the searches of one report make again in all.
const BUDGET: usize = 1_000_000;

/// The directions a fixture is moved in: the axis, its sign, as printed.
const DIRECTIONS: [(usize, f64, &str); 4] = [
    (0, -1.0, "−x"),
    (0, 1.0, "+x"),
    (1, -1.0, "−y"),
    (1, 1.0, "+y"),
];

/// What is left of the budget, and what one probe costs at most (the
/// plan's points).
struct Budget {
    left: usize,
    each: usize,
}

impl Budget {
    fn of(program: &Program) -> Budget {
        let points: usize = (program.layers.iter())
            .flat_map(|l| &l.paths)
            .map(|p| p.points.len())
            .sum();
        Budget {
            left: BUDGET,
            each: points.max(1),
        }
    }

    /// Takes one probe's worth: whether there was.
    fn take(&mut self) -> bool {
        self.spend(self.each)
    }

    /// Takes `points`' worth where a probe's whole worth is left: whether
    /// it was.
    fn spend(&mut self, points: usize) -> bool {
        if self.left < self.each {
            return false;
        }
        self.left -= points.min(self.left);
        true
    }
}

/// The least `n` in `1..=most` whose probe is clear: from `first`, grown
/// by `grow` until a probe is clear, then halved between the last refused
/// (or none: the file as it is, refused) and it, so `n − 1` was found
/// refused. With `most_first`, `most` is probed first (a direction that
/// cannot beat a move found already costs one probe). `None` where none up
/// to `most` is, or a probe is over the budget (`clear` gives `None`).
fn least(
    (first, most, most_first): (u32, u32, bool),
    grow: impl Fn(u32) -> u32,
    mut clear: impl FnMut(u32) -> Option<bool>,
) -> Option<u32> {
    if most == 0 || (most_first && !clear(most)?) {
        return None;
    }
    let (mut lo, mut n) = (0, first.clamp(1, most));
    while !clear(n)? {
        if n >= most {
            return None;
        }
        lo = n;
        n = grow(n).min(most);
    }
    let mut hi = n;
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if clear(mid)? {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Some(hi)
}

/// `cx`'s machine's arm rule in `program` (a changed copy of `cx`'s),
/// having followed the plan made again.
fn follow<'p>(program: &'p Program, cx: &MachineCx<'p>) -> Option<ArmRule<'p>> {
    follow_until(program, cx, None)
}

/// [`follow`], stopped at the path after a link first meets fixture
/// `stop_at` where given (a probe that has met what refuses it).
fn follow_until<'p>(
    program: &'p Program,
    cx: &MachineCx<'p>,
    stop_at: Option<usize>,
) -> Option<ArmRule<'p>> {
    let name = cx.machine.name();
    let machine = program.machines.iter().find(|m| m.name() == name)?;
    let there = MachineCx {
        program,
        machine,
        origin: cx.origin,
    };
    let mut rule = ArmRule::new(&there)?;
    rule.stop_at = stop_at;
    Plan::new(program, machine).walk(&mut rule);
    rule.flush();
    Some(rule)
}

/// The robot of `cx`'s machine in `program`.
fn robot<'a>(program: &'a mut Program, cx: &MachineCx<'_>) -> Option<&'a mut crate::ir::Robot> {
    let name = cx.machine.name();
    program.machines.iter_mut().find_map(|m| match m {
        Machine::Robot(r) if r.name == name => Some(r),
        _ => None,
    })
}

/// Where fixture `i` keeps the arm's links and the head clear at every
/// pose of the plan made again with it there (module docs).
fn fixture_moved(cx: &MachineCx<'_>, i: usize, budget: &mut Budget) -> Option<Moved> {
    let at0 = cx.program.fixtures.get(i)?.at;
    let mut best: Option<Moved> = None;
    for &(k, sign, name) in &DIRECTIONS {
        // On tenths of a millimetre from where it stands.
        let base = if sign < 0.0 {
            (at0[k] * 10.0).ceil()
        } else {
            (at0[k] * 10.0).floor()
        };
        let place = |n: u32| {
            let mut at = at0;
            at[k] = (base + sign * f64::from(n)) / 10.0;
            at
        };
        let most = best
            .as_ref()
            .map_or(20_000, |b| ((b.by * 10.0).round() as u32).saturating_sub(1));
        let clear = |n: u32| {
            if budget.left < budget.each {
                return None;
            }
            let mut program = cx.program.clone();
            program.fixtures[i].at = place(n);
            let (clear, walked) = fixture_clear(cx, &program, i);
            budget.spend(walked);
            Some(clear)
        };
        let found = least((100, most, best.is_some()), |n| n * 2, clear);
        if let Some(n) = found {
            let at = place(n);
            best = Some(Moved {
                axis: name,
                by: (at[k] - at0[k]).abs(),
                at,
            });
        } else if budget.left < budget.each {
            break;
        }
    }
    best
}

/// Whether fixture `i` of `program` is clear of the arm's links and the
/// head at every pose of its plan, and the moves followed to find out
/// (the walk stops at the path after a link first meets it).
fn fixture_clear(cx: &MachineCx<'_>, program: &Program, i: usize) -> (bool, usize) {
    let Some(rule) = follow_until(program, cx, Some(i)) else {
        return (false, usize::MAX);
    };
    let walked = rule.moves;
    if rule.links.as_ref().is_some_and(|l| l.fixture_hit(i)) {
        return (false, walked);
    }
    let name = cx.machine.name();
    let Some(machine) = program.machines.iter().find(|m| m.name() == name) else {
        return (false, walked);
    };
    let there = MachineCx {
        program,
        machine,
        origin: cx.origin,
    };
    (crate::verify::collision::head_clear_of(&there, i), walked)
}

/// A base farther from the arm's foot along the horizontal line to it
/// from which the arm follows the plan keeping every rule: how far, mm,
/// and the base (module docs). Only without a positioner.
fn base_moved(cx: &MachineCx<'_>, budget: &mut Budget) -> Option<LinkFix> {
    let Machine::Robot(r) = cx.machine else {
        return None;
    };
    if r.positioner.is_some() {
        return None;
    }
    let b0 = r.base.value?;
    let len = b0.x.hypot(b0.y);
    let (ux, uy) = if len > 1e-9 {
        (b0.x / len, b0.y / len)
    } else {
        (1.0, 0.0)
    };
    let place = |n: u32| {
        let tenth = |v: f64| (v * 10.0).round() / 10.0;
        let mut b = b0;
        b.x = tenth(b0.x + ux * f64::from(n));
        b.y = tenth(b0.y + uy * f64::from(n));
        b
    };
    let clear = |n: u32| {
        if !budget.take() {
            return None;
        }
        let mut program = cx.program.clone();
        robot(&mut program, cx)?.base.value = Some(place(n));
        Some(follow(&program, cx).is_some_and(|rule| rule.clean()))
    };
    let n = least((10, 3000, false), |n| n * 2, clear)?;
    let b = place(n);
    Some(LinkFix::Base {
        by: f64::from(n),
        index: r.base.index,
        pose: [b.x, b.y, b.z, b.a, b.b, b.c],
    })
}

/// The turn about the beam nearest the one used from which the arm
/// follows the plan keeping every rule (module docs).
fn spin_turned(cx: &MachineCx<'_>, budget: &mut Budget) -> Option<LinkFix> {
    let Machine::Robot(r) = cx.machine else {
        return None;
    };
    let s0 = match r.spin {
        Spin::Auto { deg } | Spin::Declared { deg } => deg,
    };
    let mut best: Option<(u32, f64)> = None;
    for sign in [1.0, -1.0] {
        // Tenths of a degree from the turn used, either way.
        let turn = |n: u32| {
            let s = s0 + sign * f64::from(n) / 10.0;
            let s = (s + 180.0).rem_euclid(360.0) - 180.0;
            (s * 10.0).round() / 10.0
        };
        let most = best.map_or(1800, |b| b.0.saturating_sub(1));
        let clear = |n: u32| {
            if !budget.take() {
                return None;
            }
            let mut program = cx.program.clone();
            robot(&mut program, cx)?.spin = Spin::Declared { deg: turn(n) };
            Some(follow(&program, cx).is_some_and(|rule| rule.clean()))
        };
        let step = 150;
        if let Some(n) = least((step, most, best.is_some()), |n| n + step, clear) {
            best = Some((n, turn(n)));
        }
    }
    best.map(|(_, deg)| LinkFix::Spin { deg, from: s0 })
}

/// Whether `machine`'s tool holds the flange off the beam's line (a tool
/// angled on it): a turn about the beam then moves the flange.
pub(super) fn tool_off_beam(machine: &Machine) -> bool {
    let Machine::Robot(r) = machine else {
        return false;
    };
    let Some(tool) = r.tool.value.as_ref() else {
        return false;
    };
    let t = crate::plan::arm::frame(tool);
    // The flange in the tool's frame, and the beam's line through the TCP.
    let f = t.inverse().translation.vector;
    let u = super::links::beam(r.beam);
    (f - u * f.dot(&u)).norm() > 1.0
}

/// The searches a report's links ask for, under one budget.
pub(super) struct Searches {
    budget: Budget,
}

impl Searches {
    /// For `cx`'s program.
    pub(super) fn of(cx: &MachineCx<'_>) -> Searches {
        Searches {
            budget: Budget::of(cx.program),
        }
    }

    /// [`fixture_moved`].
    pub(super) fn fixture(&mut self, cx: &MachineCx<'_>, i: usize) -> Option<Moved> {
        fixture_moved(cx, i, &mut self.budget)
    }

    /// [`base_moved`].
    pub(super) fn base(&mut self, cx: &MachineCx<'_>) -> Option<LinkFix> {
        base_moved(cx, &mut self.budget)
    }

    /// [`spin_turned`].
    pub(super) fn spin(&mut self, cx: &MachineCx<'_>) -> Option<LinkFix> {
        spin_turned(cx, &mut self.budget)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A probe is charged what it followed, and none starts once less
    /// than a whole plan's worth is left.
    #[test]
    fn a_probe_is_charged_what_it_followed() {
        let mut b = Budget {
            left: 1000,
            each: 300,
        };
        assert!(b.spend(40) && b.left == 960);
        assert!(b.take() && b.left == 660);
        assert!(b.spend(usize::MAX) && b.left == 0);
        assert!(!b.spend(1) && !b.take());
        let mut short = Budget {
            left: 299,
            each: 300,
        };
        assert!(!short.spend(10) && short.left == 299);
    }

    /// The least clear count, found by growing and halving: the one before
    /// it refused; none past `most`, and none once the budget is out.
    #[test]
    fn the_least_clear_count_is_found_and_the_one_before_refused() {
        for (edge, grow) in [(37u32, 2u32), (1, 2), (1000, 2), (37, 0)] {
            let mut probes = 0;
            let got = least(
                (10, 2000, false),
                |n| if grow == 0 { n + 15 } else { n * grow },
                |n| {
                    probes += 1;
                    Some(n >= edge)
                },
            );
            assert_eq!(got, Some(edge), "{edge}");
            assert!(probes < 150, "{probes}");
        }
        assert_eq!(least((10, 30, false), |n| n * 2, |n| Some(n >= 31)), None);
        assert_eq!(least((10, 30, true), |n| n * 2, |n| Some(n >= 31)), None);
        let mut left = 3;
        let out = least(
            (10, 3000, false),
            |n| n * 2,
            |n| {
                left -= 1;
                (left >= 0).then_some(n >= 500)
            },
        );
        assert_eq!(out, None);
    }
}
