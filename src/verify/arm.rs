//! A robot's arm along its plan (`lmd::reach`, `lmd::joint-limit`,
//! `lmd::singular-lin`, `lmd::configuration-flip`, `lmd::joint-speed`):
//! every move's pose — the focus where the plan puts it, the tool turned as
//! the KRL writer turns it ([`crate::plan::orient`]) — solved to axis
//! angles continuing from the move before (from `home` for the first), so
//! the program keeps one configuration. The plan's first move is the PTP
//! from home ([`crate::plan::MoveKind::FromHome`]) and its last the PTP
//! back; every move between is a LIN, where a singular pose or a change of
//! configuration stops the controller. Poses are checked where each move
//! ends and along each LIN every [`crate::plan::arm::LIN_STEP_MM`] and
//! [`crate::plan::arm::LIN_STEP_DEG`] of turn ([`Follow`]): a pose between
//! the ends of a LIN can break a rule its ends keep.

use super::rule::{MachineCx, PlanRule};
use crate::diag::message::verify::arm::{self as msg, ArmAt, Flip, Singular};
use crate::diag::message::words::Words;
use crate::diag::Diagnostics;
use crate::ir::Machine;
use crate::ir::MachineField::{Arm, Base, Home, Singularity, Tool};
use crate::plan::arm::{Along, Follow, Joints, Solved};
use crate::plan::kinematics::Rotary;
use crate::plan::{Move, Speed, Visit};
use nalgebra::Vector3;

mod fix;
pub(crate) mod links;
pub(crate) mod ptp;
mod reach;

/// The worst pose of a kind, where it lies (a move's target, or on its way).
type Worst = crate::diag::Worst<Along>;

/// The arm rules of one robot.
pub(super) struct ArmRule<'p> {
    /// The arm following the plan (`plan::arm`, as the preview plots it).
    follow: Follow,
    /// The last solution, its Status, and where the last move ended.
    prev: Joints,
    status: u8,
    last: Option<[f64; 3]>,
    /// A part beyond reach, found before any pose is solved: the plan is
    /// then not followed.
    quick: Option<crate::plan::arm::reach::Beyond>,
    reach: Option<Worst>,
    /// The arm's reach, mm.
    span: [f64; 2],
    limits: [Option<Worst>; 6],
    /// The worst pose near each singularity, in [`Singular::ALL`]'s order
    /// (as [`crate::plan::arm::Solver::singular`] measures them).
    singular: [Option<Worst>; 3],
    flip: Option<(Worst, Flip)>,
    speed: [Option<(Worst, f64)>; 6],
    /// The links against the faceplate and the fixtures (`lmd::collision`).
    links: Option<links::Links<'p>>,
    /// Home: the arm's axes and the positioner's.
    home: ptp::End,
    /// The PTP from home's end (its axes, the move it reaches, the focus
    /// there), once solved.
    first: Option<(ptp::End, crate::plan::Where, [f64; 3])>,
    /// The last pose solved: its axes and focus.
    end: Option<(ptp::End, [f64; 3])>,
    /// A help's probe: the fixture whose first hit by a link ends the walk.
    stop_at: Option<usize>,
    /// The moves told so far.
    moves: usize,
}

impl<'p> PlanRule<'p> for ArmRule<'p> {
    fn new(cx: &MachineCx<'p>) -> Option<Self> {
        let Machine::Robot(r) = cx.machine else {
            return None;
        };
        Some(ArmRule {
            follow: Follow::new(r)?,
            prev: r.home,
            status: 0,
            last: None,
            quick: crate::plan::arm::reach::beyond(cx.program, r),
            reach: None,
            span: [0.0; 2],
            limits: [None; 6],
            singular: [None; 3],
            flip: None,
            speed: [None; 6],
            links: links::Links::new(cx, r),
            home: (
                r.home,
                r.positioner
                    .as_ref()
                    .map_or_else(Rotary::default, |p| Rotary {
                        tilt: p.home[0],
                        c: p.home[1],
                    }),
            ),
            first: None,
            end: None,
            stop_at: None,
            moves: 0,
        })
    }

    fn settled(&self) -> bool {
        self.quick.is_some()
    }

    fn report(mut self, cx: &MachineCx<'p>, out: &mut Diagnostics) {
        let Machine::Robot(r) = cx.machine else {
            return;
        };
        self.flush();
        let arm = self.follow.solver().arm();
        let model = arm.model.as_deref().and_then(crate::target::arm::model);
        let name = model.map_or("opw(…) arm", |m| m.name);
        let up = self.follow.solver().upright();
        let at = ArmAt {
            machine: &r.name,
            arm: name,
            declared: cx.origin.at(Arm),
            base: cx.origin.at(Base),
            tool: cx.origin.at(Tool),
            words: Words::of(r.controller),
        };
        for (i, (h, lim)) in r.home.iter().zip(arm.limits).enumerate() {
            if *h < lim[0] || *h > lim[1] {
                out.push(msg::home_limit(&at, cx.origin.at(Home), i, *h, lim, up));
            }
        }
        if let Some(b) = self.quick {
            out.push(reach::quick(cx, &at, &b));
            return;
        }
        if let Some(w) = self.reach {
            out.push(reach::report(cx, &at, &w, self.span));
        }
        for (i, w) in self.limits.iter().enumerate() {
            if let Some(w) = w {
                out.push(msg::joint_limit(&at, i, w, arm.margin));
            }
        }
        let sing = cx.origin.written(Singularity);
        for (w, kind) in self.singular.into_iter().zip(Singular::ALL) {
            if let Some(w) = w {
                out.push(msg::singular_lin(&at, kind, &w, sing));
            }
        }
        if let Some((w, flip)) = &self.flip {
            out.push(msg::configuration_flip(&at, w, flip));
        }
        for (i, s) in self.speed.iter().enumerate() {
            if let Some((w, v)) = s {
                out.push(msg::joint_speed(&at, i, w, *v));
            }
        }
        if let Some(l) = &self.links {
            let fixes = self.link_fixes(cx, l);
            l.report(cx, self.home_keeping(l), &fixes, out);
        }
    }
}

impl ArmRule<'_> {
    /// Whether the arm followed the plan keeping every rule: every pose
    /// reached, within the axes' limits, no singular LIN, one
    /// configuration, the axes within their speeds, the links clear.
    fn clean(&self) -> bool {
        self.quick.is_none()
            && self.reach.is_none()
            && self.limits.iter().all(Option::is_none)
            && self.singular.iter().all(Option::is_none)
            && self.flip.is_none()
            && self.speed.iter().all(Option::is_none)
            && self.links.as_ref().is_none_or(links::Links::clear)
    }

    /// By target of `l`, the change its help names, where a search finds
    /// one ([`fix`]).
    fn link_fixes(
        &self,
        cx: &MachineCx<'_>,
        l: &links::Links<'_>,
    ) -> Vec<Option<crate::diag::message::collision::LinkFix>> {
        use crate::diag::message::collision::LinkFix;
        let wanted = l.searches();
        let mut fixes = vec![None; wanted.iter().map(|w| w.0 + 1).max().unwrap_or(0)];
        let mut searches = fix::Searches::of(cx);
        let tool_angled = fix::tool_off_beam(cx.machine);
        for (k, what) in wanted {
            fixes[k] = match what {
                links::Search::Fixture(i) => searches.fixture(cx, i).map(LinkFix::Moved),
                links::Search::Base => searches.base(cx),
                links::Search::Spin if tool_angled => searches.spin(cx),
                links::Search::Spin => None,
            };
        }
        fixes
    }

    /// The closest approaches of the arm's links to the cell.
    pub(super) fn approaches(&self) -> Vec<crate::verify::approach::Approach> {
        self.links
            .as_ref()
            .map_or_else(Vec::new, links::Links::approaches)
    }

    /// A `home` whose PTPs keep the gap, where a PTP does not and one is
    /// found ([`ptp::home_keeping`]).
    fn home_keeping(&self, l: &links::Links<'_>) -> Option<(Joints, ptp::HomeFrom)> {
        let ((first, at, focus), (last, end)) = (self.first?, self.end?);
        if !l.ptp_hit() {
            return None;
        }
        ptp::home_keeping(
            l,
            self.follow.solver(),
            (self.home, first, last),
            (at, focus, end),
        )
    }
}

impl Visit for ArmRule<'_> {
    fn motion(&mut self, m: &Move) {
        self.moves += 1;
        if self.quick.is_some() {
            return;
        }
        if m.kind == crate::plan::MoveKind::Home {
            // Everything before is solved first: the PTP starts where the
            // last move ended.
            self.flush();
            if let (Some(l), Some((last, focus))) = (&mut self.links, self.end) {
                let home = (self.home.0, m.axes);
                let at = (crate::plan::Where::End, focus);
                ptp::check(l, self.follow.solver(), (home, last), true, at);
            }
            return;
        }
        if let Some(done) = self.follow.push(m) {
            self.follow_up(done);
        }
    }

    fn done(&self) -> bool {
        self.stop_at
            .is_some_and(|i| self.links.as_ref().is_some_and(|l| l.fixture_hit(i)))
    }
}

impl ArmRule<'_> {
    /// Solves the moves still buffered and follows them in order.
    pub(super) fn flush(&mut self) {
        let rest = self.follow.take();
        self.follow_up(rest);
    }

    /// Follows solved moves in order.
    fn follow_up(&mut self, solved: Vec<Solved>) {
        for s in solved {
            let at = Along {
                at: s.m.at,
                way: s.way,
            };
            self.step(&s, at, s.joints);
        }
    }

    /// One move reaching axis angles `j` (none: out of reach).
    fn step(&mut self, s: &Solved, at: Along, j: Option<Joints>) {
        let (m, wrist) = (&s.m, &s.wrist);
        // A PTP (from home) keeps only its end's rules; every other move
        // is a LIN.
        let lin = !m.kind.ptp();
        let Some(j) = j else {
            let (d, span) = self.follow.solver().reach(s.to, &s.rot);
            self.span = span;
            let edge = if d > span[1] { span[1] } else { span[0] };
            Worst::hit(&mut self.reach, d, edge, at);
            self.last = Some(m.to);
            return;
        };
        self.limits(&j, at);
        if let Some(l) = &mut self.links {
            let solver = self.follow.solver();
            if m.kind == crate::plan::MoveKind::FromHome {
                let first = ((j, m.axes), m.at, m.to);
                ptp::check(l, solver, (self.home, first.0), false, (m.at, m.to));
                self.first = Some(first);
            }
            l.check(solver, &j, m.axes, links::Place::Move(at), m.to);
        }
        self.end = Some(((j, m.axes), m.to));
        let status = self.follow.solver().status_at(&j, wrist);
        if lin {
            self.lin(&j, wrist, status, m, at);
        }
        self.prev = j;
        self.status = status;
        self.last = Some(m.to);
    }
}

impl ArmRule<'_> {
    /// Each axis within its limits less the margin.
    fn limits(&mut self, j: &Joints, at: Along) {
        let arm = self.follow.solver().arm();
        for (i, a) in j.iter().enumerate() {
            let [lo, hi] = arm.limits[i];
            let (lo, hi) = (lo + arm.margin, hi - arm.margin);
            if *a < lo {
                Worst::hit(&mut self.limits[i], *a, lo, at);
            } else if *a > hi {
                Worst::hit(&mut self.limits[i], *a, hi, at);
            }
        }
    }

    /// What a LIN to `j` must keep: away from singularities, one
    /// configuration, the axes within their speeds.
    fn lin(&mut self, j: &Joints, wrist: &Vector3<f64>, to: u8, m: &Move, at: Along) {
        let solver = self.follow.solver();
        let thr = solver.arm().singularity;
        let near = solver.singular(j, wrist);
        for (slot, d) in self.singular.iter_mut().zip(near) {
            if d < thr {
                Worst::hit(slot, d, thr, at);
            }
        }
        let from = self.status;
        if from != to {
            let mut slot = self.flip.map(|f| f.0);
            Worst::hit(&mut slot, 1.0, 0.0, at);
            // The first change is reported: its Status and `confdata`.
            let keep = self.flip.map_or_else(
                || Flip {
                    status: [from, to],
                    confdata: [solver.confdata(&self.prev), solver.confdata(j)],
                },
                |f| f.1,
            );
            self.flip = slot.map(|w| (w, keep));
        }
        let (Speed::Feed(v), Some(last)) = (m.speed, self.last) else {
            return;
        };
        let d = (0..3)
            .map(|i| (m.to[i] - last[i]).powi(2))
            .sum::<f64>()
            .sqrt();
        if d <= 0.0 || v <= 0.0 {
            return;
        }
        let t = d / v as f64;
        let speeds = self.follow.solver().arm().speeds;
        for i in 0..6 {
            let rate = (j[i] - self.prev[i]).abs() / t;
            if rate > speeds[i] {
                let mut slot = self.speed[i].map(|s| s.0);
                let worse = slot.is_none_or(|w| rate > w.value);
                Worst::hit(
                    &mut slot,
                    rate,
                    speeds[i],
                    Along {
                        at: m.source(),
                        ..at
                    },
                );
                let speed = match (worse, self.speed[i]) {
                    (false, Some((_, s))) => s,
                    _ => v as f64,
                };
                self.speed[i] = slot.map(|w| (w, speed));
            }
        }
    }
}
