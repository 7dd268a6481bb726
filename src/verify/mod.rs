//! The verifier: every rule the plan must keep, checked once, before anything is
//! written. The result is a [`Verified`] proof the back ends require, so
//! unchecked IR cannot reach them (the idea of naga's validator); a back end
//! takes a [`VerifiedMachine`] and cannot fail on a limit.
//!
//! Every rule has one of two shapes (`rule`): a rule over one machine's motion
//! plan follows it as a visitor, a rule over the whole program looks at the IR
//! (and, after the plans, at what they would write). All are listed in one
//! place, `rules`, and each reports every kind of violation once (how many,
//! and the worst): the process rules over the IR's points (`process`), a
//! ring's loop and what a machine needs to run it (`ring`), the layers on each
//! other (`stacking`), each machine's limits (`machine`, `resolution`, `cell`),
//! the metal laid at the speed each machine really reaches (`bump`) and the
//! files the machines would write (`names`). The machine rules run
//! whatever the process rules found, so one run reports everything.
//!
//! The proof remembers (naga's `ModuleInfo`): the one pass over each plan also
//! sums it up ([`Summary`]: moves, each layer's lengths and times, the files),
//! which the writers' headers and the report read instead of walking the plan
//! again.

pub mod approach;
mod arm;
mod bead_tilt;
mod bump;
mod cell;
mod collision;
mod deposit;
pub mod height_loop;
mod machine;
mod names;
mod overhang;
mod positioner;
mod process;
mod resolution;
mod rule;
mod rules;
mod stacking;
pub mod summary;
mod table;

pub use machine::NEEDS_TILT_DEG;
pub use summary::{Costs, Summary};

use crate::diag::{Code, Diagnostics};
use crate::ir::{Machine, MachineOrigin, Program};
use crate::plan::Plan;
use crate::provenance::Provenance;
use rule::{MachineCx, ProgramCx};

/// IR that passed every check, for the machines it was checked for, with the
/// warnings found on the way and what the pass over each plan summed up.
#[derive(Debug)]
pub struct Verified {
    program: Program,
    /// The machines checked, by index, in declaration order, with their
    /// plans' summaries.
    machines: Vec<(usize, Summary)>,
    warnings: Diagnostics,
    /// The source the program was compiled from, for the programs' headers.
    provenance: Provenance,
}

impl Verified {
    /// The checked IR.
    pub fn ir(&self) -> &Program {
        &self.program
    }

    /// Warnings (the checks passed regardless).
    pub fn warnings(&self) -> &Diagnostics {
        &self.warnings
    }

    /// The machines whose plans were checked, in declaration order.
    pub fn machines(&self) -> impl Iterator<Item = VerifiedMachine<'_>> {
        self.machines
            .iter()
            .map(move |(index, summary)| VerifiedMachine {
                program: &self.program,
                index: *index,
                summary,
                provenance: &self.provenance,
            })
    }

    /// Machine number `index` of the IR, if its plan was checked.
    pub fn machine(&self, index: usize) -> Option<VerifiedMachine<'_>> {
        self.machines().find(|m| m.index == index)
    }

    /// Where the program came from (the pipeline sets it; empty until then).
    pub fn provenance(&self) -> &Provenance {
        &self.provenance
    }

    /// Records where the program came from.
    pub fn set_provenance(&mut self, p: Provenance) {
        self.provenance = p;
    }

    /// Gives the IR back.
    pub fn into_ir(self) -> Program {
        self.program
    }
}

/// A machine whose motion plan passed every check: what a back end writes,
/// with what the check's pass over the plan summed up.
#[derive(Clone, Copy, Debug)]
pub struct VerifiedMachine<'a> {
    program: &'a Program,
    index: usize,
    summary: &'a Summary,
    provenance: &'a Provenance,
}

impl<'a> VerifiedMachine<'a> {
    /// The checked IR.
    pub fn ir(&self) -> &'a Program {
        self.program
    }

    /// The machine's index in the IR's machine list.
    pub fn index(&self) -> usize {
        self.index
    }

    /// The machine.
    pub fn machine(&self) -> &'a Machine {
        &self.program.machines[self.index]
    }

    /// Its motion plan.
    pub fn plan(&self) -> Plan<'a> {
        Plan::new(self.program, self.machine())
    }

    /// What the verifier's pass over the plan summed up: moves, each layer's
    /// lengths and times, the files.
    pub fn summary(&self) -> &'a Summary {
        self.summary
    }

    /// Where the program came from: the headers name it.
    pub fn provenance(&self) -> &'a Provenance {
        self.provenance
    }
}

/// Machine `i`'s plan, followed once by every rule over it and the summary:
/// the rules' diagnostics, and the summary.
fn machine_rules(p: &Program, i: usize) -> (Diagnostics, Option<(usize, Summary)>) {
    let mut d = Diagnostics::new();
    let Some(cx) = machine_cx(p, i) else {
        return (d, None);
    };
    let m = cx.machine;
    let mut walk = (rules::PlanRules::new(&cx), summary::Summarize::new(p, m));
    Plan::new(p, m).walk(&mut walk);
    let (rules, summary) = walk;
    let approaches = rules.approaches();
    rules.report(&cx, &mut d);
    let mut summary = summary.finish(|moves| names::files(p, m, moves));
    summary.approaches = approaches;
    (d, Some((i, summary)))
}

/// Which machines to check and build.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Select {
    /// Every machine the file declares.
    All,
    /// Only the machine with this index.
    One(usize),
}

/// Runs the program rules of `list` over `cx`.
fn run(list: &[rules::Check], cx: &ProgramCx<'_>) -> Diagnostics {
    let mut d = Diagnostics::new();
    for check in list {
        check(cx, &mut d);
    }
    d
}

/// Checks `program` and the plans of the `select`ed machines; returns the proof,
/// or every error and warning found.
pub fn verify(program: Program, select: Select) -> Result<Verified, Diagnostics> {
    verify_with(program, select, Provenance::default(), |_, _| ()).verified
}

/// What [`verify_with`] found.
#[derive(Debug)]
pub struct Outcome<R> {
    /// The proof, or every error and warning found.
    pub verified: Result<Verified, Diagnostics>,
    /// What the caller's work made, when every rule passed.
    pub made: Option<R>,
    /// Where only the slow rules (a robot's arm) failed: the plan every
    /// other rule passed, for a preview to draw with those failures.
    pub refused: Option<Refused>,
}

/// A program every rule passed but the slow ones (a robot's arm): what
/// `lmdc preview` draws with the arm's failures marked. It cannot reach a
/// back end: only the preview reads it.
#[derive(Debug)]
pub struct Refused {
    /// The program, its plans' summaries and the other rules' warnings.
    plan: Verified,
    /// The slow rules' errors (and warnings).
    failures: Diagnostics,
}

impl Refused {
    /// The checked IR.
    pub fn ir(&self) -> &Program {
        self.plan.ir()
    }

    /// What the slow rules found.
    pub fn failures(&self) -> &Diagnostics {
        &self.failures
    }

    /// The machines whose plans the other rules passed (for the preview).
    pub(crate) fn machines(&self) -> impl Iterator<Item = VerifiedMachine<'_>> {
        self.plan.machines()
    }
}

/// [`verify`], running `meanwhile` on the program while the slow rules (a
/// robot's arm: every move solved) are still following the plans, once every
/// other rule has passed; it is told whether any slow rule is running. What
/// `meanwhile` made is given back only if the slow rules pass too: a build writes its programs into a staging folder
/// meanwhile and commits them only then, so a plan the arm cannot follow
/// writes nothing, and the writers run on the core the arm leaves them.
pub fn verify_with<R>(
    program: Program,
    select: Select,
    provenance: Provenance,
    meanwhile: impl FnOnce(&Verified, bool) -> R,
) -> Outcome<R> {
    let machines: Vec<usize> = match select {
        Select::All => (0..program.machines.len()).collect(),
        Select::One(i) => (i < program.machines.len())
            .then_some(i)
            .into_iter()
            .collect(),
    };
    let mut v = Verified {
        program,
        machines: Vec::new(),
        warnings: Diagnostics::new(),
        provenance,
    };
    let (diags, made, failures, found) = std::thread::scope(|s| {
        let p = &v.program;
        let alone = ProgramCx {
            program: p,
            plans: &[],
        };
        let mut diags = run(rules::BEFORE_PLANS, &alone);
        // A plan through non-finite points would only repeat that error.
        if diags.iter().any(|d| d.code == Code::NonFinite) {
            return (diags, None, None, Vec::new());
        }
        // Every rule reads the IR only: the slow rules, the rules beside
        // the plans and each machine's plan run side by side, and report
        // in this fixed order.
        let slow: Vec<_> = machines
            .iter()
            .filter_map(|&i| slow_rules(p, i))
            .map(|(settled, walk)| (settled, s.spawn(walk)))
            .collect();
        let mut found = Vec::new();
        let beside = s.spawn(move || run(rules::BESIDE_PLANS, &alone));
        let walked: Vec<_> = machines
            .iter()
            .map(|&i| s.spawn(move || machine_rules(p, i)))
            .collect();
        diags.extend(joined(beside));
        let mut plans = Vec::new();
        for h in walked {
            let (d, summary) = joined(h);
            diags.extend(d);
            plans.extend(summary);
        }
        let after = ProgramCx {
            program: p,
            plans: &plans,
        };
        diags.extend(run(rules::AFTER_PLANS, &after));
        v.machines = plans;
        // Slow rules that knew their answer without following the plan (a
        // part beyond the arm's reach) are in already: a plan they refuse
        // is not written meanwhile.
        let (settled, slow): (Vec<_>, Vec<_>) = slow.into_iter().partition(|(done, _)| *done);
        let mut failures = Diagnostics::new();
        join_slow(settled, &mut failures, &mut found);
        let mut made = None;
        if !diags.has_errors() && !failures.has_errors() {
            v.warnings = diags.clone();
            made = Some(meanwhile(&v, !slow.is_empty()));
        }
        let passed = !diags.has_errors();
        join_slow(slow, &mut failures, &mut found);
        diags.extend(failures.clone());
        (diags, made, passed.then_some(failures), found)
    });
    // The arm's closest approaches join its plan's summary (the writers,
    // meanwhile, did not read them).
    for (i, near) in found {
        if let Some((_, s)) = v.machines.iter_mut().find(|(m, _)| *m == i) {
            s.approaches.extend(near);
        }
    }
    outcome(v, diags, made, failures)
}

/// The outcome of a verification: `v` with its warnings where `diags`
/// has no error, else the errors (and the plan refused only by the slow
/// rules, with their `failures`).
fn outcome<R>(
    mut v: Verified,
    diags: Diagnostics,
    made: Option<R>,
    failures: Option<Diagnostics>,
) -> Outcome<R> {
    match failures {
        _ if !diags.has_errors() => {
            v.warnings = diags;
            Outcome {
                verified: Ok(v),
                made,
                refused: None,
            }
        }
        Some(failures) => Outcome {
            verified: Err(diags),
            made: None,
            refused: Some(Refused { plan: v, failures }),
        },
        None => Outcome {
            verified: Err(diags),
            made: None,
            refused: None,
        },
    }
}

/// Joins the slow rules' threads `handles`, their diagnostics into
/// `failures` and their approaches into `found`.
fn join_slow<'s>(
    handles: Vec<(bool, std::thread::ScopedJoinHandle<'s, SlowFound>)>,
    failures: &mut Diagnostics,
    found: &mut Vec<(usize, Vec<approach::Approach>)>,
) {
    for (_, h) in handles {
        let (d, near) = joined(h);
        failures.extend(d);
        found.push(near);
    }
}

/// What a rule's thread returned; its panic, passed on.
fn joined<T>(h: std::thread::ScopedJoinHandle<'_, T>) -> T {
    h.join().unwrap_or_else(|e| std::panic::resume_unwind(e))
}

/// Machine `i`'s slow rules, as a walk to run on a thread of its own, where
/// any applies, and whether they know their answer without walking.
fn slow_rules(p: &Program, i: usize) -> Option<(bool, impl FnOnce() -> SlowFound + Send + '_)> {
    let cx = machine_cx(p, i)?;
    let mut walk = rules::SlowRules::new(&cx);
    let settled = walk.settled();
    walk.any().then_some((settled, move || {
        let mut d = Diagnostics::new();
        if !settled {
            Plan::new(p, cx.machine).walk(&mut walk);
        }
        walk.flush();
        let near = walk.approaches();
        walk.report(&cx, &mut d);
        (d, (i, near))
    }))
}

/// What a machine's slow rules found: their diagnostics, and the machine's
/// index with the closest approaches they measured.
type SlowFound = (Diagnostics, (usize, Vec<approach::Approach>));

/// What machine `i`'s plan rules see of it.
fn machine_cx(p: &Program, i: usize) -> Option<MachineCx<'_>> {
    // IR read without its origins (a test's, a user's JSON) points nowhere.
    static UNKNOWN: std::sync::LazyLock<MachineOrigin> =
        std::sync::LazyLock::new(|| MachineOrigin::new(Default::default()));
    Some(MachineCx {
        program: p,
        machine: p.machines.get(i)?,
        origin: p.origins.machines.get(i).unwrap_or(&UNKNOWN),
    })
}
