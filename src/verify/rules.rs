//! Every rule of the verifier, in one place, in the order they report. A
//! new rule is a type implementing [`PlanRule`] or [`ProgramRule`] and one
//! line here.

use super::arm::ArmRule;
use super::bead_tilt::BeadTilt;
use super::bump::DepositBump;
use super::cell::CellRule;
use super::collision::Collision;
use super::deposit::DepositRule;
use super::height_loop::{LoopAnalysis, LoopOnMachine};
use super::machine::{Analog, SafeHeight, SpeedLimit, Tilt, Travel};
use super::names::FileNames;
use super::overhang::Overhang;
use super::positioner::PositionerRule;
use super::process::ProcessRules;
use super::resolution::{Resolution, ShortMoves};
use super::rule::{MachineCx, PlanRule, ProgramCx, ProgramRule};
use super::stacking::Stacking;
use super::table::{AxisSpeed, CUnwind};
use crate::diag::Diagnostics;
use crate::ir::Layer;
use crate::plan::{Io, Move, SegmentEnd, Visit};

/// A rule over the whole program, as the lists hold it.
pub(super) type Check = fn(&ProgramCx<'_>, &mut Diagnostics);

/// Rules over the IR alone, run first: the points' values, the ring's loop.
/// The plans are walked only if every point is finite (a plan through a
/// non-finite point would only repeat that error).
pub(super) const BEFORE_PLANS: &[Check] =
    &[ProcessRules::check, DepositRule::check, LoopAnalysis::check];

/// Rules over the IR that run beside the machines' plans, on a thread of
/// their own.
pub(super) const BESIDE_PLANS: &[Check] = &[Stacking::check, Overhang::check];

/// Rules over what the plans' summaries say the machines would write.
pub(super) const AFTER_PLANS: &[Check] = &[FileNames::check];

/// Declares a set of rules over one machine's plan, each present where it
/// applies, following the plan together in one pass (static dispatch: the
/// pass visits millions of moves).
macro_rules! plan_rules {
    ($(#[$doc:meta])* $set:ident { $($field:ident: $rule:ty),* $(,)? }) => {
        $(#[$doc])*
        pub(super) struct $set<'p> {
            $($field: Option<$rule>,)*
            _p: std::marker::PhantomData<&'p ()>,
        }

        impl<'p> $set<'p> {
            /// The rules that apply to `cx`'s machine.
            pub fn new(cx: &MachineCx<'p>) -> Self {
                $set {
                    $($field: <$rule as PlanRule<'p>>::new(cx),)*
                    _p: std::marker::PhantomData,
                }
            }

            /// Whether any rule of the set applies.
            #[allow(dead_code, reason = "only the slow set is asked")]
            pub fn any(&self) -> bool {
                false $(|| self.$field.is_some())*
            }

            /// Whether every rule of the set that applies knows what it
            /// reports without following the plan.
            #[allow(dead_code, reason = "only the slow set is asked")]
            pub fn settled(&self) -> bool {
                true $(&& self.$field.as_ref().is_none_or(|r| r.settled()))*
            }

            /// What each found.
            pub fn report(self, cx: &MachineCx<'p>, out: &mut Diagnostics) {
                $(if let Some(r) = self.$field {
                    r.report(cx, out);
                })*
            }
        }

        impl Visit for $set<'_> {
            fn layer(&mut self, index: usize, layer: &Layer) {
                $(if let Some(r) = &mut self.$field {
                    r.layer(index, layer);
                })*
            }

            fn laser_on(&mut self, next: &Move) {
                $(if let Some(r) = &mut self.$field {
                    r.laser_on(next);
                })*
            }

            fn laser_off(&mut self) {
                $(if let Some(r) = &mut self.$field {
                    r.laser_off();
                })*
            }

            #[inline]
            fn motion(&mut self, m: &Move) {
                $(if let Some(r) = &mut self.$field {
                    r.motion(m);
                })*
            }

            fn dwell(&mut self, seconds: f64) {
                $(if let Some(r) = &mut self.$field {
                    r.dwell(seconds);
                })*
            }

            fn io(&mut self, event: Io) {
                $(if let Some(r) = &mut self.$field {
                    r.io(event);
                })*
            }

            fn segment_end(&mut self, end: SegmentEnd) {
                $(if let Some(r) = &mut self.$field {
                    r.segment_end(end);
                })*
            }
        }
    };
}

plan_rules! {
    /// Every rule over one machine's plan but the slow ones, in the order
    /// they report.
    PlanRules {
        tilt: Tilt,
        travel: Travel,
        safe: SafeHeight,
        unwind: CUnwind,
        axis_speed: AxisSpeed,
        speed: SpeedLimit<'p>,
        analog: Analog,
        resolution: Resolution<'p>,
        short_moves: ShortMoves,
        cell: CellRule<'p>,
        ring: LoopOnMachine,
        bump: DepositBump<'p>,
        positioner: PositionerRule,
        collision: Collision<'p>,
        bead_tilt: BeadTilt,
    }
}

plan_rules! {
    /// The rules that solve every move of a plan: a robot's arm (inverse
    /// kinematics, seconds on a dense plan). They follow the plan on a walk
    /// of their own, on another thread, beside the other rules — and, in a
    /// build, beside the writers ([`super::verify_with`]).
    SlowRules {
        arm: ArmRule<'p>,
    }
}

impl PlanRules<'_> {
    /// The closest approaches the head's collision rule found.
    pub fn approaches(&self) -> Vec<super::approach::Approach> {
        self.collision
            .as_ref()
            .map_or_else(Vec::new, |c| c.approaches())
    }
}

impl SlowRules<'_> {
    /// Follows the moves the arm still holds: its approaches are then
    /// complete.
    pub fn flush(&mut self) {
        if let Some(a) = &mut self.arm {
            a.flush();
        }
    }

    /// The closest approaches the arm's links came to the cell (after
    /// [`Self::flush`]).
    pub fn approaches(&self) -> Vec<super::approach::Approach> {
        self.arm.as_ref().map_or_else(Vec::new, ArmRule::approaches)
    }
}
