//! The help for a head's body that runs into the part beside it, where
//! raising the head does not help: the slimmer body that keeps the gap,
//! checked by following the plan again with it (docs/collision.md, *What
//! is said*).
//!
//! The poses found too close each say how far the body's radii must
//! shrink to clear the lump nearest it there; a body that slim may meet
//! another lump, at another pose, that the wider body's nearer lumps hid.
//! So the plan is followed again with the body as the help would declare
//! it, and narrowed again by what that finds, until the part is clear.

use super::super::rule::MachineCx;
use super::Collision;
use crate::diag::message::collision::Narrower;
use crate::plan::Plan;

/// Most rounds of narrowing and checking.
const ROUNDS: usize = 6;

/// Most points a search follows in all (each round walks the whole plan).
const BUDGET: usize = 2_000_000;

impl Collision<'_> {
    /// Body `body` as declared, narrowed until the plan followed again
    /// with it keeps its gap from the part everywhere, its diameters
    /// floored to the tenth printed; `None` where no narrowing was found
    /// to (the part along its axis, another body on the part, past the
    /// rounds or the budget).
    pub(super) fn narrowed(&self, cx: &MachineCx<'_>, body: usize) -> Option<Narrower> {
        let points: usize = (self.program.layers.iter())
            .flat_map(|l| &l.paths)
            .map(|p| p.points.len())
            .sum();
        let rounds = (BUDGET / points.max(1)).min(ROUNDS);
        let declared = cx.machine.common().head.bodies.get(body)?;
        let mut k = self.narrow.get(body).copied().flatten()?;
        for _ in 0..rounds {
            let diameters = declared.diameters.map(|d| (d * k * 10.0).floor() / 10.0);
            if diameters[1] <= 0.0 {
                return None;
            }
            let mut program = self.program.clone();
            let name = cx.machine.name();
            let m = program.machines.iter_mut().find(|m| m.name() == name)?;
            m.common_mut().head.bodies[body].diameters = diameters;
            let machine = program.machines.iter().find(|m| m.name() == name)?;
            let probe = MachineCx {
                program: &program,
                machine,
                origin: cx.origin,
            };
            let mut rule = Collision::against(&probe, None)?;
            Plan::new(&program, machine).walk(&mut rule);
            match &rule.worst[2] {
                None => {
                    return Some(Narrower {
                        length: declared.length,
                        diameters,
                    })
                }
                Some(w) if w.at.body == body => {
                    // Relative to the diameters tried, as printed.
                    let tried = diameters[1] / declared.diameters[1];
                    k = tried * rule.narrow.get(body).copied().flatten()?;
                }
                // Another body on the part: slimming this one is not
                // the fix.
                Some(_) => return None,
            }
        }
        None
    }
}
