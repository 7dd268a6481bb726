//! The whole pipeline, one direction: source → syntax → semantic model → IR
//! (geometry and slicing) → checks (the IR and each machine's motion plan) →
//! back ends. No file I/O here: the CLI reads the source and supplies the
//! [`Sink`] the programs are written to.
//!
//! Every stage runs as far as its input allows, so one run reports every error
//! it can: a model with errors in some blocks is still sliced and checked when
//! what slicing needs is there, and every machine is checked whatever another
//! one did. Diagnostics come out in source order.

use crate::back::{self, EmitError, Sink, Templates};
use crate::diag::{Code, Diagnostics};
use crate::overrides::{Override, SetError};
use crate::provenance::Provenance;
use crate::sema::model::Model;
use crate::verify::{self, Select, Verified};
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
/// and every diagnostic (warnings too), in source order.
pub struct Compiled {
    /// The checked IR, if the program has no errors.
    pub program: Option<Verified>,
    /// Errors and warnings.
    pub diagnostics: Diagnostics,
    /// Where the only errors are the slow rules' (a robot's arm): the plan
    /// every other rule passed, for `lmdc preview` to draw with them.
    pub refused: Option<verify::Refused>,
}

/// `--machine NAME` names no machine of the file.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("there is no machine called `{name}`; this file declares: {declared}")]
pub struct NoSuchMachine {
    /// The name asked for.
    pub name: String,
    /// The machines the file declares, comma-separated.
    pub declared: String,
}

/// What a compilation is asked for besides the source: the command line's
/// `FILE`, `--machine` and `--set`.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Options {
    /// The file the source was read from, as the programs' headers name it
    /// (`None`: text from no file).
    pub file: Option<String>,
    /// Only this machine's checks and program (`None`: every machine).
    pub machine: Option<String>,
    /// Top-level constants replaced before the file is checked (`--set`).
    pub set: Vec<Override>,
    /// Reads the data files the program names (`fit(…, data = "…")`;
    /// `None`: a program that names one is refused).
    pub data: Option<DataFiles>,
    /// Warnings expected by code (`--allow CODE`): reported, each marked
    /// allowed, failing no run.
    pub allow: Vec<crate::diag::Code>,
}

/// Reads a data file a program names, by its path as written.
#[derive(Clone)]
pub struct DataFiles(pub sema::DataReader);

impl std::fmt::Debug for DataFiles {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("DataFiles(..)")
    }
}

impl PartialEq for DataFiles {
    fn eq(&self, other: &Self) -> bool {
        std::rc::Rc::ptr_eq(&self.0, &other.0)
    }
}

impl Eq for DataFiles {}

/// What the command line asked for cannot be done with this file: the
/// source itself may be fine.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum UsageError {
    /// `--machine` names no machine of the file.
    #[error(transparent)]
    Machine(#[from] NoSuchMachine),
    /// A `--set` the file cannot take.
    #[error(transparent)]
    Set(#[from] SetError),
}

/// Compiles `source` to verified IR for every machine it declares.
pub fn compile(source: &str, obs: &mut dyn Observer) -> Compiled {
    match compile_for(source, None, obs) {
        Ok(c) => c,
        Err(_) => unreachable!("no machine was named"),
    }
}

/// Compiles `source` for the machine called `machine` alone (its checks, its
/// program), or for every machine when `None`.
pub fn compile_for(
    source: &str,
    machine: Option<&str>,
    obs: &mut dyn Observer,
) -> Result<Compiled, NoSuchMachine> {
    let options = Options {
        machine: machine.map(str::to_string),
        ..Options::default()
    };
    compile_with(source, &options, obs).map_err(|e| match e {
        UsageError::Machine(m) => m,
        UsageError::Set(_) => unreachable!("nothing was set"),
    })
}

/// Compiles `source` as `options` say.
pub fn compile_with(
    source: &str,
    options: &Options,
    obs: &mut dyn Observer,
) -> Result<Compiled, UsageError> {
    compile_keeping(source, options, obs, None, |_, _| ()).map(|c| c.0)
}

/// [`compile_with`], running `meanwhile` on the program once every check has
/// passed but the slow ones (a robot's arm, every move solved), while those
/// finish ([`verify::verify_with`]). What `meanwhile` made is given back only
/// when the program compiled without errors: `lmdc build` writes its
/// programs into a staging folder meanwhile and commits them only then.
pub fn compile_then<R>(
    source: &str,
    options: &Options,
    obs: &mut dyn Observer,
    meanwhile: impl FnOnce(&Verified, &mut dyn Observer) -> R,
) -> Result<(Compiled, Option<R>), UsageError> {
    compile_keeping(source, options, obs, None, meanwhile)
}

/// [`compile_with`], also giving back the checked model when the program
/// compiled (the plan report reads its bead model and design solid).
pub fn compile_with_model(
    source: &str,
    options: &Options,
    obs: &mut dyn Observer,
) -> Result<(Compiled, Option<Model>), UsageError> {
    let mut model = None;
    let (c, _) = compile_keeping(source, options, obs, Some(&mut model), |_, _| ())?;
    if c.program.is_none() {
        model = None;
    }
    Ok((c, model))
}

/// [`compile_with_model`] for `machine`, reading the data files the
/// program names (`fit(…, data = "…")`) with `data`: the CLI's reader opens
/// them beside the .lmd file.
pub fn compile_reading(
    source: &str,
    machine: Option<&str>,
    obs: &mut dyn Observer,
    data: sema::DataReader,
) -> Result<(Compiled, Option<Model>), NoSuchMachine> {
    let options = Options {
        machine: machine.map(str::to_string),
        data: Some(DataFiles(data)),
        ..Options::default()
    };
    compile_with_model(source, &options, obs).map_err(|e| match e {
        UsageError::Machine(m) => m,
        UsageError::Set(_) => unreachable!("nothing was set"),
    })
}

fn compile_keeping<R>(
    source: &str,
    options: &Options,
    obs: &mut dyn Observer,
    keep: Option<&mut Option<Model>>,
    meanwhile: impl FnOnce(&Verified, &mut dyn Observer) -> R,
) -> Result<(Compiled, Option<R>), UsageError> {
    let mut diagnostics = Diagnostics::new();
    for &code in &options.allow {
        diagnostics.allow(code, ALLOWED_BY_COMMAND_LINE);
    }
    let mut from = Provenance::new(source, options.file.as_deref());
    from.set = options.set.iter().map(|s| s.to_string()).collect();
    let ran = run(
        source,
        options,
        obs,
        &mut diagnostics,
        keep,
        from,
        meanwhile,
    )?;
    diagnostics.sort_by_source();
    Ok((
        Compiled {
            program: ran.program,
            diagnostics,
            refused: ran.refused,
        },
        ran.made,
    ))
}

/// The reason a warning allowed by `--allow` gives.
pub const ALLOWED_BY_COMMAND_LINE: &str = "--allow on the command line";

/// What [`run`] gives back besides the diagnostics.
struct Ran<R> {
    program: Option<Verified>,
    made: Option<R>,
    refused: Option<verify::Refused>,
}

impl<R> Ran<R> {
    fn none() -> Ran<R> {
        Ran {
            program: None,
            made: None,
            refused: None,
        }
    }
}

fn run<R>(
    source: &str,
    options: &Options,
    obs: &mut dyn Observer,
    diagnostics: &mut Diagnostics,
    keep: Option<&mut Option<Model>>,
    from: Provenance,
    meanwhile: impl FnOnce(&Verified, &mut dyn Observer) -> R,
) -> Result<Ran<R>, UsageError> {
    let mut ast = match syntax::parse(source) {
        Ok(a) => a,
        Err(d) => {
            diagnostics.push(d);
            return Ok(Ran::none());
        }
    };
    crate::overrides::apply(&mut ast, &options.set)?;
    let machine = options.machine.as_deref();
    // The machines the file declares, checked or not: one refused for its
    // own errors is reported for them when `--machine` names it, not as
    // unknown.
    let names: Vec<String> = ast
        .stmts
        .iter()
        .filter(|s| s.kind.node == "machine")
        .filter_map(|s| s.name.as_ref().map(|n| n.node.clone()))
        .collect();
    let declared = machine.is_some_and(|name| names.iter().any(|n| n == name));
    obs.stage("parse");
    let (model, d) = sema::check_reading(&ast, options.data.as_ref().map(|d| d.0.clone()));
    drop(ast);
    diagnostics.extend(d);
    obs.stage("check");
    let Some(model) = model else {
        return Ok(Ran::none());
    };
    let select = match machine {
        None => Select::All,
        Some(name) => match model.machines.iter().position(|(m, _)| m.name() == name) {
            Some(i) => Select::One(i),
            None if declared && diagnostics.has_errors() => return Ok(Ran::none()),
            None => {
                return Err(UsageError::Machine(NoSuchMachine {
                    name: name.to_string(),
                    declared: names.join(", "),
                }))
            }
        },
    };
    let mut program = match lower::lower(&model) {
        Ok((p, w)) => {
            diagnostics.extend(w);
            p
        }
        Err(e) => {
            diagnostics.extend(e);
            return Ok(Ran::none());
        }
    };
    if let Some(d) = held_finish(&program, &model) {
        diagnostics.push(d);
    }
    // Only the report keeps the model; a build frees it before verifying.
    match keep {
        Some(k) => *k = Some(model),
        None => drop(model),
    }
    obs.stage("slice");
    // A positioner's angles, layer by layer, then the free turn about the
    // nozzle axis, where the file leaves it to lmdc (through the positioner).
    crate::plan::positioner::choose(&mut program);
    crate::plan::spin::choose(&mut program);
    Ok(verify_then(
        program,
        select,
        from,
        obs,
        diagnostics,
        meanwhile,
    ))
}

/// Verifies the lowered `program`, running `meanwhile` beside the slow rules
/// when the program has no errors so far, and adds what the verifier found
/// to `diagnostics`.
fn verify_then<R>(
    program: crate::ir::Program,
    select: Select,
    from: Provenance,
    obs: &mut dyn Observer,
    diagnostics: &mut Diagnostics,
    meanwhile: impl FnOnce(&Verified, &mut dyn Observer) -> R,
) -> Ran<R> {
    // The slow rules (an arm's) go on beside `meanwhile`; the stage `verify`
    // ends when the others have, `verify arm` when they have too.
    let clean = !diagnostics.has_errors();
    // `None` until the other rules passed; then whether the slow ones run on.
    let mut waiting = None;
    let out = verify::verify_with(program, select, from, |v, slow| {
        obs.stage("verify");
        waiting = Some(slow);
        clean.then(|| meanwhile(v, obs))
    });
    match waiting {
        None => obs.stage("verify"),
        Some(true) => obs.stage("verify arm"),
        Some(false) => {}
    }
    let refused = out.refused.filter(|_| clean);
    match out.verified {
        Ok(v) if !diagnostics.has_errors() => {
            diagnostics.extend(v.warnings().clone());
            Ran {
                program: Some(v),
                made: out.made.flatten(),
                refused: None,
            }
        }
        Ok(v) => {
            diagnostics.extend(v.warnings().clone());
            Ran::none()
        }
        Err(mut e) => {
            e.retain(|d| !reported_already(d.code, diagnostics));
            diagnostics.extend(e);
            Ran {
                refused,
                ..Ran::none()
            }
        }
    }
}

/// Verifier findings that repeat an error the checker reported at the
/// declaration itself, as `(checker's code, verifier's code)`: a power
/// schedule outside the laser's range puts every point's power outside it
/// too. The checker keeps such a value so that the machine checks still run,
/// and the fault is reported once, where it was declared.
const REPORTED_BY_CHECKER: &[(Code, Code)] = &[(Code::PowerSchedule, Code::PointPower)];

/// Whether a verifier finding of `code` repeats an error in `earlier`.
fn reported_already(code: Code, earlier: &Diagnostics) -> bool {
    REPORTED_BY_CHECKER
        .iter()
        .any(|&(first, then)| then == code && earlier.iter().any(|d| d.code == first))
}

/// Writes the programs of every verified machine into `sink`.
pub fn emit(
    program: &Verified,
    templates: &Templates,
    sink: &mut dyn Sink,
    obs: &mut dyn Observer,
) -> Result<(), EmitError> {
    for m in program.machines() {
        back::emit(m, templates, sink)?;
        obs.stage(match m.machine() {
            crate::ir::Machine::Robot(_) => "emit KRL",
            crate::ir::Machine::Cnc(_) => "emit G-code",
        });
    }
    Ok(())
}

/// What `lmdc simulate` shows: a ring's declared loop run offline against its
/// declared plant, with [`crate::control::simulate()`] — the law the programs
/// run ([`crate::control::LAW`]).
pub struct Simulated {
    /// The run, when the source declares a ring with a `control height` loop
    /// and has no errors.
    pub run: Option<RingSimulation>,
    /// Errors and warnings of checking the source (the loop's analysis
    /// included), in source order.
    pub diagnostics: Diagnostics,
    /// Why there is no run although the source has no errors.
    pub nothing: Option<&'static str>,
}

/// A ring's loop run against its plant.
pub struct RingSimulation {
    /// The part's name.
    pub part: String,
    /// The loop as declared.
    pub controller: crate::control::Controller,
    /// The plant it ran against.
    pub plant: crate::control::Plant,
    /// Each segment's start speed (the table's).
    pub start: Vec<crate::units::Speed>,
    /// Every layer and segment.
    pub simulation: crate::control::Simulation,
    /// The compile-time analysis of the same loop.
    pub analysis: crate::control::Analysis,
}

/// Checks `source` (its constants replaced as `set` says) and runs its
/// ring's loop against the declared plant. A loop the verifier would refuse
/// (unstable, too slow) is still simulated — seeing it diverge is the point —
/// and its findings come with it.
pub fn simulate(source: &str, set: &[Override]) -> Result<Simulated, SetError> {
    use crate::sema::model::Build;
    let mut diagnostics = Diagnostics::new();
    let done = |run, mut diagnostics: Diagnostics, nothing| {
        diagnostics.sort_by_source();
        Ok(Simulated {
            run,
            diagnostics,
            nothing,
        })
    };
    let mut ast = match syntax::parse(source) {
        Ok(a) => a,
        Err(d) => {
            diagnostics.push(d);
            return done(None, diagnostics, None);
        }
    };
    crate::overrides::apply(&mut ast, set)?;
    let (model, d) = sema::check(&ast);
    diagnostics.extend(d);
    let Some(model) = model.filter(|_| !diagnostics.has_errors()) else {
        return done(None, diagnostics, None);
    };
    let Build::Ring(r) = &model.build else {
        return done(None, diagnostics, Some("it declares no `ring`"));
    };
    let Some(c) = &r.control else {
        return done(
            None,
            diagnostics,
            Some("its ring declares no `control height { … }` loop"),
        );
    };
    let start = r.table.speeds();
    let run = crate::control::analyse(&c.controller, &start, r.layers).and_then(|analysis| {
        let simulation = crate::control::simulate(&c.controller, &c.plant, &start, r.layers)?;
        Ok(RingSimulation {
            part: model.part.clone(),
            controller: c.controller,
            plant: c.plant.clone(),
            start,
            simulation,
            analysis,
        })
    });
    match run {
        Ok(run) => done(Some(run), diagnostics, None),
        Err(e) => {
            // The checker lets through only loops that can run: a bug.
            diagnostics.push(crate::diag::message::internal::loop_simulation(&e));
            done(None, diagnostics, None)
        }
    }
}

/// What the preview draws of a part built on a scan or up to a top: the
/// scanned surface on a square grid of its `cell` (coarser past
/// [`crate::preview::repair::MAX_SCAN`] points) and the report's finish
/// ([`crate::report::finish`]); `None` for another solid. Here because it
/// joins the model with the report for the preview, which read only the
/// plan.
pub fn repair_overlay(
    program: &crate::ir::Program,
    model: &Model,
) -> Option<crate::preview::repair::Overlay> {
    use crate::preview::repair::{Overlay, MAX_FINISH, MAX_SCAN};
    use crate::sema::model::Build;
    let base = match &model.build {
        Build::Variable { extrusion, .. } => extrusion.base.as_ref(),
        Build::ScanWall { on, .. } => Some(&on.base),
        _ => return None,
    };
    let mut out = Overlay::default();
    if let Some(base) = base {
        let s = &base.surface;
        let ([x0, y0], [x1, y1]) = s.extent();
        let area = ((x1 - x0) * (y1 - y0)).abs();
        let step = s.cell().max((area / MAX_SCAN as f64).sqrt());
        if step.is_finite() && step > 0.0 {
            let (nx, ny) = (((x1 - x0) / step) as usize, ((y1 - y0) / step) as usize);
            for j in 0..=ny {
                for i in 0..=nx {
                    let p = [x0 + i as f64 * step, y0 + j as f64 * step];
                    if let Some(z) = s.at(p) {
                        out.scan.push([p[0] as f32, p[1] as f32, z as f32]);
                    }
                }
            }
        }
    }
    if let Some((f, samples)) = crate::report::finish::sampled(program, model) {
        let k = samples.len().div_ceil(MAX_FINISH).max(1);
        out.finish = samples
            .iter()
            .step_by(k)
            .map(|s| [s.at[0] as f32, s.at[1] as f32, s.top as f32, s.off as f32])
            .collect();
        (out.below, out.above) = (f.below_mm, f.above_mm);
    }
    Some(out)
}

/// A repair's predicted finish off its top by more than the
/// `finish_tolerance` its slicing declares, or not predicted at all
/// (`lmd::finish`); `None` when it declares none or the finish is
/// within it. Here because it joins
/// the plan with the model's top, which the verifier does not read.
/// Without `finish_tolerance`, a repair on a scan whose finished face is
/// predicted to fall short of its top by more than the thinnest layer the
/// bead lays (an edge narrower than a bead, a gap too thin to fill) is
/// warned of: held to nothing, it would be found only in the report.
fn short_finish(
    program: &crate::ir::Program,
    model: &Model,
    top: crate::span::Span,
) -> Option<crate::diag::Diagnostic> {
    use crate::sema::model::Build;
    if matches!(&model.build, Build::Variable { extrusion, .. } if extrusion.base.is_none()) {
        return None;
    }
    let f = crate::report::finish::of(program, model)?;
    let thinnest = program.limits.layer_height[0];
    (f.below_mm > thinnest)
        .then(|| crate::diag::message::top::finish_short(f.below_mm, f.below_at, thinnest, top))
}

fn held_finish(program: &crate::ir::Program, model: &Model) -> Option<crate::diag::Diagnostic> {
    use crate::sema::model::Build;
    let (slicing, top) = match &model.build {
        Build::Variable { slicing, extrusion } => (slicing, extrusion.top_span),
        Build::ScanWall { slicing, on, .. } => (slicing, on.top_span),
        _ => return None,
    };
    let Some((tolerance, at)) = slicing.finish_tolerance else {
        return short_finish(program, model, top);
    };
    // Before the positioner's and the spin's angles are chosen: they turn
    // the nozzle about its point, which the finish does not read.
    let Some(f) = crate::report::finish::of(program, model) else {
        return Some(crate::diag::message::top::finish_unknown(at));
    };
    let off = crate::diag::message::top::FinishOff {
        below: (f.below_mm, f.below_at),
        above: (f.above_mm, f.above_at),
        rms: f.rms_mm,
        points: f.points,
        tolerance: tolerance.0,
    };
    (f.below_mm > tolerance.0 || f.above_mm > tolerance.0)
        .then(|| crate::diag::message::top::finish_off(&off, at, top))
}
