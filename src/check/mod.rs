//! The verifier: every rule the plan must keep, checked once, before anything is
//! written. The result is a [`Verified`] proof the back ends require, so
//! unchecked IR cannot reach them (the idea of naga's validator); a back end
//! takes a [`VerifiedMachine`] and cannot fail on a limit.
//!
//! One small type per rule, each reporting every violation once (how many, and
//! the worst): the process rules over the IR's points (`process`: layer
//! height, bead speed, laser power, finite values), the machine rules over each
//! selected machine's motion plan (`machine`: speed, axis travel, tilt, analog
//! output) and the file names the machines would write (`names`); a ring's
//! height loop and what each machine needs to run it (`ring`). The machine
//! rules run whatever the process rules found, so one run reports everything.

mod cell;
mod machine;
mod names;
mod process;
mod resolution;
pub mod ring;
mod stacking;

pub use machine::NEEDS_TILT_DEG;

use crate::diag::Diagnostics;
use crate::ir::{Machine, Program};
use crate::plan::Plan;

/// IR that passed every check, for the machines it was checked for, with the
/// warnings found on the way.
#[derive(Debug)]
pub struct Verified {
    program: Program,
    machines: Vec<usize>,
    warnings: Diagnostics,
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
        self.machines.iter().map(move |&index| VerifiedMachine {
            program: &self.program,
            index,
        })
    }

    /// Machine number `index` of the IR, if its plan was checked.
    pub fn machine(&self, index: usize) -> Option<VerifiedMachine<'_>> {
        self.machines().find(|m| m.index == index)
    }

    /// Gives the IR back.
    pub fn into_ir(self) -> Program {
        self.program
    }
}

/// A machine whose motion plan passed every check: what a back end writes.
#[derive(Clone, Copy, Debug)]
pub struct VerifiedMachine<'a> {
    program: &'a Program,
    index: usize,
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

    /// The files its program is written to.
    pub fn files(&self) -> Vec<String> {
        let mut count = Count(0);
        self.plan().walk(&mut count);
        names::files(self.program, self.machine(), count.0)
    }
}

/// Counts moves.
struct Count(u64);

impl crate::plan::Visit for Count {
    fn motion(&mut self, _: &crate::plan::Move) {
        self.0 += 1;
    }
}

/// Machine `i`'s rules over its plan: their diagnostics, and the files it
/// would write.
fn machine_rules(p: &Program, i: usize) -> (Diagnostics, Option<(usize, Vec<String>)>) {
    let mut d = Diagnostics::new();
    let Some(m) = p.machines.get(i) else {
        return (d, None);
    };
    let mut rules = machine::MachineRules::new(p, m);
    rules.run(p);
    let moves = rules.moves;
    let origin = p.origins.machines.get(i).cloned().unwrap_or_default();
    rules.report(p, &origin, &mut d);
    ring::check_machine(p, m, &origin, &mut d);
    (d, Some((i, names::files(p, m, moves))))
}

/// Which machines to check and build.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Select {
    /// Every machine the file declares.
    All,
    /// Only the machine with this index.
    One(usize),
}

/// Checks `program` and the plans of the `select`ed machines; returns the proof,
/// or every error and warning found.
pub fn verify(program: Program, select: Select) -> Result<Verified, Diagnostics> {
    let mut diags = Diagnostics::new();
    let mut points = process::ProcessRules::new(&program);
    points.run(&program);
    let broken = points.finite.failed();
    points.report(&program, &mut diags);
    ring::check_loop(&program, &mut diags);

    let machines: Vec<usize> = match select {
        Select::All => (0..program.machines.len()).collect(),
        Select::One(i) => (i < program.machines.len())
            .then_some(i)
            .into_iter()
            .collect(),
    };
    // A plan through non-finite points would only repeat that error.
    if !broken {
        // The layer-on-layer rule and each machine's plan read the IR only:
        // they run side by side, and report in this fixed order.
        let p = &program;
        let (stack, plans) = std::thread::scope(|s| {
            let stack = s.spawn(move || {
                let mut d = Diagnostics::new();
                stacking::check(p, &mut d);
                d
            });
            let plans: Vec<_> = machines
                .iter()
                .map(|&i| s.spawn(move || machine_rules(p, i)))
                .collect();
            (
                stack.join(),
                plans.into_iter().map(|h| h.join()).collect::<Vec<_>>(),
            )
        });
        diags.extend(stack.unwrap_or_else(|e| std::panic::resume_unwind(e)));
        let mut files = Vec::new();
        for r in plans {
            let (d, f) = r.unwrap_or_else(|e| std::panic::resume_unwind(e));
            diags.extend(d);
            files.extend(f);
        }
        names::clashes(&program, &files, &mut diags);
    }

    if diags.has_errors() {
        Err(diags)
    } else {
        Ok(Verified {
            program,
            machines,
            warnings: diags,
        })
    }
}
