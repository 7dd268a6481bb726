//! The shape of a verifier rule (Fornjot's `ValidationCheck`, naga's
//! validator). Two kinds, one trait each:
//!
//! - a [`PlanRule`] follows one machine's motion plan as a [`Visit`]or and
//!   reports what it found at the end;
//! - a [`ProgramRule`] looks at the whole program: the IR's points, the
//!   layers on each other, a ring's loop, and (after the plans) what the
//!   machines would write.
//!
//! Every rule reports each kind of violation once — how many, and the worst
//! ([`Worst`]) — so one run shows everything to fix. The rules are listed in
//! one place, [`super::rules`]; adding one is a type and a line there.

use super::summary::Summary;
use crate::diag::Diagnostics;
use crate::ir::{Machine, MachineOrigin, Program};
use crate::plan::{Visit, Where};

/// A rule's worst violation, at a move of the plan.
pub(crate) type Worst = crate::diag::Worst<Where>;

/// What a rule over one machine's plan sees besides the moves.
#[derive(Clone, Copy)]
pub(crate) struct MachineCx<'p> {
    /// The program the plan builds.
    pub program: &'p Program,
    /// The machine whose plan it is.
    pub machine: &'p Machine,
    /// Where the machine and its fields were declared.
    pub origin: &'p MachineOrigin,
}

/// A rule over one machine's motion plan: it follows the plan in the
/// verifier's single pass over it and reports what it found.
pub(crate) trait PlanRule<'p>: Visit + Sized {
    /// The rule for `cx`'s machine, or `None` where it does not apply (a tilt
    /// rule on a robot, gas timing on a cell without gas).
    fn new(cx: &MachineCx<'p>) -> Option<Self>;

    /// Every kind of violation found, once each.
    fn report(self, cx: &MachineCx<'p>, out: &mut Diagnostics);

    /// Whether the rule knows what it reports before following the plan
    /// (a part beyond the arm's reach): a walk that only such rules would
    /// follow is not taken.
    fn settled(&self) -> bool {
        false
    }
}

/// What a rule over the whole program sees.
#[derive(Clone, Copy)]
pub(crate) struct ProgramCx<'p> {
    /// The program.
    pub program: &'p Program,
    /// The summaries of the machines' plans, by machine index: empty for the
    /// rules that run before or beside the plans.
    pub plans: &'p [(usize, Summary)],
}

/// A rule over the whole program.
pub(crate) trait ProgramRule {
    /// Checks `cx`, reporting every kind of violation once.
    fn check(cx: &ProgramCx<'_>, out: &mut Diagnostics);
}
