//! A small KRL interpreter for the programs lmdc writes for a ring whose
//! height loop runs on the robot (seed 004): data lists with scalars, arrays
//! and `POS` aggregates; assignments with arithmetic (`INT`/`REAL` as KRL
//! types them: `INT / INT` truncates), `SQRT`, comparisons; `IF … ENDIF`,
//! `FOR … ENDFOR`; `LIN`/`PTP`; `TRIGGER WHEN DISTANCE … DELAY … DO` an
//! assignment or a subprogram call; calls of modules and local routines.
//!
//! It models the advance run: a motion is *planned* when the interpreter
//! reaches its line (its target and `$VEL.CP` are evaluated then, as the
//! robot does) and *run* when `$ADVANCE` more motions have been planned;
//! triggers fire when their motion runs (`DISTANCE=0` before it, `DISTANCE=1`
//! after it, a positive `DELAY` a further [`Config::delay_motions`] motions
//! later). So a program that reads a variable before the trigger that sets it
//! has run gets the old value here too. An advance-run stop (`WAIT SEC`, a
//! direct `$OUT`/`$ANOUT` write, `$ANIN` read outside a trigger) lets every
//! planned motion run first and is recorded, so a test can hold a motion
//! module to none.
//!
//! `$ANIN[n]` asks the test's sensor. Written from KRL's rules, not from
//! lmdc's types.
#![allow(dead_code, unused_imports)]

mod syntax;
mod value;
mod vm;

pub use vm::{run, run_steady};

use std::collections::BTreeMap;

/// File name → text.
pub type Files = BTreeMap<String, String>;

/// How far the simulated main run lags behind.
#[derive(Clone, Copy, Debug)]
pub struct Config {
    /// Motions a `DELAY` > 0 trigger fires after its own (the delay in
    /// motions; the longer, the later the update lands).
    pub delay_motions: usize,
}

/// A read of `$ANIN[input]`, from inside routine `routine` called with `args`.
#[derive(Debug)]
pub struct Read<'a> {
    /// The input.
    pub input: i64,
    /// The routine reading it.
    pub routine: &'a str,
    /// Its arguments.
    pub args: &'a [f64],
}

/// One motion as the robot runs it.
#[derive(Clone, Debug, PartialEq)]
pub struct Motion {
    /// X Y Z, mm.
    pub pos: [f64; 3],
    /// A B C, deg.
    pub abc: [f64; 3],
    /// `$VEL.CP` when it was planned, mm/s.
    pub speed: f64,
    /// `$OUT[laser]` during it.
    pub laser: bool,
    /// `$ANOUT[power]` during it.
    pub anout: f64,
    /// `C_DIS`.
    pub approximated: bool,
    /// The module it is in.
    pub module: String,
}

/// What running the program did.
#[derive(Debug, Default)]
pub struct Run {
    /// LIN motions in the order they ran.
    pub motions: Vec<Motion>,
    /// PTP motions.
    pub ptps: usize,
    /// `$OUT[laser]` at the end.
    pub laser_at_end: bool,
    /// LIN lines per module (as written, not as run).
    pub lin_lines: BTreeMap<String, usize>,
    /// Advance-run stops in motion modules: what caused each.
    pub stops: Vec<String>,
    /// Routines triggered, with their arguments, in the order they ran, and
    /// how many motions had run by then.
    pub triggered: Vec<(String, Vec<f64>, usize)>,
}
