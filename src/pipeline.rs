//! The whole pipeline, one direction: source → syntax → semantic model → IR
//! (geometry and slicing) → checks → back ends. No file I/O here: the CLI
//! reads the source and supplies the [`Sink`] the programs are written to.

use crate::back::{self, EmitError, Sink, Templates};
use crate::check::{self, Verified};
use crate::diag::{Code, Diagnostic, Diagnostics};
use crate::{lower, sema, syntax};

/// Told when each stage finishes (for `lmdc build --timings`).
pub trait Observer {
    /// Stage `name` just finished.
    fn stage(&mut self, name: &'static str);
}

impl Observer for () {
    fn stage(&mut self, _: &'static str) {}
}

/// The result of compiling a source: the verified IR when there were no errors,
/// and every diagnostic (warnings too).
pub struct Compiled {
    /// The checked IR, if the program has no errors.
    pub program: Option<Verified>,
    /// Errors and warnings, in the order found.
    pub diagnostics: Diagnostics,
}

/// Compiles `source` to verified IR.
pub fn compile(source: &str, obs: &mut dyn Observer) -> Compiled {
    let mut diagnostics = Diagnostics::new();
    let fail = |diagnostics| Compiled {
        program: None,
        diagnostics,
    };
    let ast = match syntax::parse(source) {
        Ok(a) => a,
        Err(d) => {
            diagnostics.push(d);
            return fail(diagnostics);
        }
    };
    obs.stage("parse");
    let (model, d) = sema::check(&ast);
    drop(ast);
    diagnostics.extend(d);
    obs.stage("check");
    let Some(model) = model else {
        return fail(diagnostics);
    };
    let program = match lower::lower(&model) {
        Ok((p, w)) => {
            diagnostics.extend(w);
            p
        }
        Err(e) => {
            diagnostics.extend(e);
            return fail(diagnostics);
        }
    };
    obs.stage("slice");
    let verified = match check::verify(program) {
        Ok(v) => v,
        Err(e) => {
            diagnostics.extend(e);
            return fail(diagnostics);
        }
    };
    diagnostics.extend(verified.warnings().clone());
    obs.stage("verify");
    Compiled {
        program: Some(verified),
        diagnostics,
    }
}

/// The indices of the machines to emit: all, or the one called `name`.
pub fn select_machines(program: &Verified, name: Option<&str>) -> Result<Vec<usize>, String> {
    let machines = &program.ir().machines;
    match name {
        None => Ok((0..machines.len()).collect()),
        Some(n) => match machines.iter().position(|m| m.name() == n) {
            Some(i) => Ok(vec![i]),
            None => Err(format!(
                "there is no machine called `{n}`; this file declares: {}",
                machines
                    .iter()
                    .map(|m| m.name())
                    .collect::<Vec<_>>()
                    .join(", ")
            )),
        },
    }
}

/// Emits the programs of the machines `which` into `sink`.
pub fn emit(
    program: &Verified,
    which: &[usize],
    templates: &Templates,
    sink: &mut dyn Sink,
    obs: &mut dyn Observer,
) -> Result<(), EmitError> {
    let mut problems = Diagnostics::new();
    let mut named = Named {
        inner: sink,
        names: Vec::new(),
        machine: 0,
        clash: None,
    };
    for &i in which {
        named.machine = i;
        match back::emit(program, i, templates, &mut named) {
            Ok(()) => {}
            Err(EmitError::Program(d)) => problems.extend(d),
            Err(EmitError::Io(_)) if named.clash.is_some() => {
                if let Some((name, first)) = named.clash.take() {
                    problems.push(clash(program, &name, first, i));
                }
            }
            Err(e) => return Err(e),
        }
        obs.stage(match program.ir().machines[i] {
            crate::ir::Machine::Robot(_) => "emit KRL",
            crate::ir::Machine::Cnc(_) => "emit G-code",
        });
    }
    if problems.is_empty() {
        Ok(())
    } else {
        Err(EmitError::Program(problems))
    }
}

/// Runs every back end into nothing: their own checks (axis limits, tilt,
/// analog range, file names that clash) without writing a file. What passes
/// here, [`emit`] writes.
pub fn check_machines(program: &Verified) -> Result<(), EmitError> {
    let templates = Templates::builtin().map_err(EmitError::Template)?;
    let all: Vec<usize> = (0..program.ir().machines.len()).collect();
    emit(program, &all, &templates, &mut back::NullSink, &mut ())
}

/// A sink that remembers which machine wrote each file name and refuses a
/// second file of the same name.
struct Named<'s> {
    inner: &'s mut dyn Sink,
    names: Vec<(String, usize)>,
    machine: usize,
    /// The clashing name and the machine that wrote it first.
    clash: Option<(String, usize)>,
}

impl Sink for Named<'_> {
    fn create(&mut self, name: &str) -> std::io::Result<Box<dyn std::io::Write + '_>> {
        if let Some((_, first)) = self.names.iter().find(|(n, _)| n == name) {
            self.clash = Some((name.to_string(), *first));
            return Err(std::io::Error::new(
                std::io::ErrorKind::AlreadyExists,
                format!("{name} is written twice"),
            ));
        }
        self.names.push((name.to_string(), self.machine));
        self.inner.create(name)
    }
}

fn clash(program: &Verified, name: &str, first: usize, second: usize) -> Diagnostic {
    let ms = &program.ir().machines;
    let o = &program.ir().origins.machines;
    Diagnostic::error(
        Code::NameClash,
        format!(
            "machines `{}` and `{}` would both write {name}",
            ms[first].name(),
            ms[second].name()
        ),
    )
    .label_opt(o.get(second).copied(), "second machine")
    .label_opt(o.get(first).copied(), "first machine")
    .help("file names keep letters, digits and `_` of the part's and the machine's names: give the machines names that differ there")
}
