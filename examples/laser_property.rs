//! A worked property test over lmdc as a library (docs/testing.md): for a
//! `.lmd` file and `--set`-style overrides, every machine's motion plan
//! switches the laser on only for deposit moves — it is never on during a
//! travel, approach, retract or lead — and every deposit starts where the
//! laser was switched on or a deposit ended.
//!
//! ```sh
//! cargo run --release --example laser_property -- examples/flange.lmd OD=90mm
//! ```
//!
//! Exit status 0 when the property holds, 1 when it does not, 2 on bad
//! input.

use lmdc::plan::{Move, Visit};
use std::process::ExitCode;

/// Follows the laser through a plan and notes every move that breaks the
/// property.
#[derive(Default)]
pub struct Laser {
    /// Whether the laser is on now.
    pub on: bool,
    /// Moves seen.
    pub moves: usize,
    /// Deposit moves seen.
    pub deposits: usize,
    /// What broke the property.
    pub broken: Vec<String>,
}

impl Visit for Laser {
    fn laser_on(&mut self, next: &Move) {
        if !next.deposits() {
            self.broken
                .push(format!("laser switched on before a {:?} move", next.kind));
        }
        self.on = true;
    }
    fn laser_off(&mut self) {
        self.on = false;
    }
    fn motion(&mut self, m: &Move) {
        self.moves += 1;
        if m.deposits() {
            self.deposits += 1;
        }
        if self.on != m.deposits() {
            self.broken.push(format!(
                "move {}: {:?} with the laser {}",
                self.moves,
                m.kind,
                if self.on { "on" } else { "off" }
            ));
        }
    }
}

/// Checks the property on every machine of `source` compiled with
/// `options`; the moves that break it.
pub fn check(source: &str, options: &lmdc::Options) -> Result<Vec<String>, String> {
    let program = lmdc::compile(source, options).map_err(|d| {
        d.iter()
            .map(|x| format!("{}: {}", x.code, x.message))
            .collect::<Vec<_>>()
            .join("\n")
    })?;
    let mut broken = Vec::new();
    for m in program.machines() {
        let mut laser = Laser::default();
        m.plan().walk(&mut laser);
        if laser.deposits == 0 {
            broken.push(format!("{}: no deposit at all", m.machine().name()));
        }
        broken.extend(
            laser
                .broken
                .into_iter()
                .map(|b| format!("{}: {b}", m.machine().name())),
        );
    }
    Ok(broken)
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some((file, sets)) = args.split_first() else {
        eprintln!("usage: laser_property FILE.lmd [NAME=VALUE …]");
        return ExitCode::from(2);
    };
    let source = match std::fs::read_to_string(file) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("{file}: {e}");
            return ExitCode::from(2);
        }
    };
    let set: Result<Vec<lmdc::overrides::Override>, String> =
        sets.iter().map(|s| s.parse()).collect();
    let options = match set {
        Ok(set) => lmdc::Options {
            file: Some(file.clone()),
            set,
            ..Default::default()
        },
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::from(2);
        }
    };
    match check(&source, &options) {
        Ok(broken) if broken.is_empty() => {
            println!("{file}: the laser is on for deposits only, on every machine");
            ExitCode::SUCCESS
        }
        Ok(broken) => {
            for b in broken {
                println!("{file}: {b}");
            }
            ExitCode::from(1)
        }
        Err(e) => {
            eprintln!("{e}");
            ExitCode::from(2)
        }
    }
}
