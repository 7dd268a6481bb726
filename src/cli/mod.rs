//! The `lmdc` command line: argument parsing, reading the source, printing
//! diagnostics, writing outputs atomically, exit codes.

mod calibrate;
mod fit;
mod fit_thermal;
mod fmt;
pub mod messages;
pub mod preview;
pub mod progress;
pub mod report;
mod simulate;
pub mod sink;
pub mod timings;

use clap::{Parser, Subcommand, ValueEnum};
use lmdc::back::{EmitError, Templates};
use lmdc::diag::usage;
use lmdc::overrides::Override;
use lmdc::pipeline::{self, Observer};
use messages::MessageFormat;
use progress::Progress;
use std::io::{IsTerminal, Read, Write};
use std::path::{Path, PathBuf};

/// Exit code: the program has errors.
pub const EXIT_PROGRAM: u8 = 1;
/// Exit code: bad usage or an I/O problem.
pub const EXIT_USAGE: u8 = 2;

/// Largest source file lmdc reads (16 MiB).
pub const MAX_SOURCE: u64 = lmdc::sema::data::MAX_SOURCE;

/// lmdc compiles a .lmd description of a laser metal deposition part into the
/// programs that build it: KRL for KUKA robots, G-code for CNCs.
#[derive(Parser, Debug)]
#[command(name = "lmdc", version, about, long_about = None, after_help = "\
Examples:
  lmdc check part.lmd                    check the part and its process, write nothing
  lmdc build part.lmd                    write every machine's program into out/
  lmdc build part.lmd -o build --machine kr60 --emit ir
                                         only the robot kr60, plus the plan as JSON
  lmdc report part.lmd                   time, lengths, energy, powder and metal, per layer
  lmdc preview part.lmd                  the plan in 3-D: out/<part>.preview.html
  lmdc simulate ring.lmd --csv loop.csv  run a ring's height loop against its plant
  lmdc calibrate coupons.lmd             coupon programs and out/<part>.coupons.csv to fill in
  lmdc fit out/<part>.coupons.csv        fit bead models to the filled-in sheet
Exit status: 0 success, 1 errors in the .lmd file, 2 usage or file errors.")]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Colour the error messages: auto (when printing to a terminal), always, never.
    #[arg(long, global = true, value_enum, default_value_t = Color::Auto)]
    color: Color,
    /// How diagnostics are printed: human (drawn on stderr) or json (one
    /// object a line on stdout; docs/diagnostics.md).
    #[arg(long, global = true, value_enum, value_name = "FORMAT", default_value_t = MessageFormat::Human)]
    message_format: MessageFormat,
    /// No progress line on a terminal.
    #[arg(short, long, global = true)]
    quiet: bool,
    /// Fail when the file has any warning: exit status 1, nothing written
    /// (for CI; the warnings are reported as usual).
    #[arg(long, global = true)]
    deny_warnings: bool,
    /// Expect the warnings of CODE (`lmd::height-rounded` or
    /// `height-rounded`): still reported, marked allowed, never failing the
    /// run; repeatable or comma-separated. A file can expect one itself,
    /// with its reason: `allow "lmd::CODE" = "why"`.
    #[arg(long, global = true, value_name = "CODE", value_delimiter = ',', value_parser = warning_code)]
    allow: Vec<lmdc::diag::Code>,
    /// Fail on the warnings of CODE, as --deny-warnings does on all (exit
    /// status 1, nothing written) unless the file allows them; repeatable
    /// or comma-separated.
    #[arg(long, global = true, value_name = "CODE", value_delimiter = ',', value_parser = warning_code)]
    deny: Vec<lmdc::diag::Code>,
    /// Replace the value of the file's top-level `let NAME` by VALUE, in a
    /// unit of the same kind as the file's (`--set R1=300mm`); repeatable,
    /// for parameter sweeps. The programs' headers list what was set.
    #[arg(long = "set", global = true, value_name = "NAME=VALUE")]
    set: Vec<Override>,
}

/// What every command shares: how to print, and what to change in the file.
pub struct Common {
    /// Colour the drawn reports.
    pub color: bool,
    /// `--message-format`.
    pub format: MessageFormat,
    /// `--deny-warnings`.
    pub deny_warnings: bool,
    /// `--allow`.
    pub allow: Vec<lmdc::diag::Code>,
    /// `--deny`.
    pub deny: Vec<lmdc::diag::Code>,
    /// `--set`.
    pub set: Vec<Override>,
}

impl Common {
    /// The pipeline's options for `file` and `machine`.
    pub fn options(&self, file: &Path, machine: Option<&str>) -> pipeline::Options {
        pipeline::Options {
            file: Some(file.display().to_string()),
            machine: machine.map(str::to_string),
            set: self.set.clone(),
            data: Some(pipeline::DataFiles(data_reader(file))),
            allow: self.allow.clone(),
        }
    }

    /// The exit code `--deny-warnings` and `--deny` call for after `d` was
    /// printed (`None`: go on): the warnings they name that nothing allows.
    pub fn denied(&self, file: &Path, d: &lmdc::diag::Diagnostics) -> Option<u8> {
        let n = d.unallowed_warnings(|c| self.deny_warnings || self.deny.contains(&c));
        let how = if self.deny_warnings {
            "--deny-warnings".to_string()
        } else {
            let codes: Vec<&str> = self.deny.iter().map(|c| c.as_str()).collect();
            format!("--deny {}", codes.join(","))
        };
        (n > 0).then(|| messages::fail(file, usage::denied_warnings(n, &how)))
    }
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum Color {
    Auto,
    Always,
    Never,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Emit {
    /// The machine programs (always written).
    Programs,
    /// The plan as JSON: OUT/<part>.ir.json (see docs/ir.md).
    Ir,
    /// Each machine's motion plan as JSON lines: OUT/<part>_<machine>.plan.jsonl (docs/plan.md).
    Plan,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Compile FILE and write the program of each machine it declares.
    Build {
        /// The .lmd file.
        file: PathBuf,
        /// Directory the programs are written to (created if missing).
        #[arg(short = 'o', long = "out", value_name = "DIR", default_value = "out")]
        out: PathBuf,
        /// Only write the program for this machine (its name in the file).
        #[arg(long, value_name = "NAME")]
        machine: Option<String>,
        /// Also write the plan (layers and process points) as JSON.
        #[arg(long, value_enum, value_name = "WHAT", value_delimiter = ',')]
        emit: Vec<Emit>,
        /// Use your own templates: files in DIR (e.g. DIR/krl/main.src.tera)
        /// replace the built-in ones of the same name.
        #[arg(long, value_name = "DIR")]
        templates: Option<PathBuf>,
        /// Print the time and peak memory of each compiler stage.
        #[arg(long)]
        timings: bool,
    },
    /// Check FILE (syntax, units, geometry, process limits, every machine's limits) without writing anything.
    Check {
        /// The .lmd file.
        file: PathBuf,
        /// Only check for this machine (its name in the file).
        #[arg(long, value_name = "NAME")]
        machine: Option<String>,
    },
    /// Report what each machine's program takes, per layer and in total: lengths, time at
    /// the programmed speeds, laser time, energy, powder, and the metal the bead model lays
    /// against what the layers stack and the design solid (docs/preview.md).
    Report {
        /// The .lmd file.
        file: PathBuf,
        /// Only this machine's plan (its name in the file).
        #[arg(long, value_name = "NAME")]
        machine: Option<String>,
        /// One JSON object a machine on stdout instead of text.
        #[arg(long)]
        json: bool,
        /// Density of the deposited metal in g/cm³, for a bead model that declares none
        /// (mass_balance declares its own).
        #[arg(long, value_name = "G_PER_CM3")]
        density: Option<f64>,
    },
    /// Write one self-contained HTML page showing a machine's plan in 3-D — coloured by
    /// speed, height, predicted height error, power, style, path kind or layer — with
    /// per-layer plots of speed, height and height error (docs/preview.md). A plan refused
    /// by its robot arm's rules alone is drawn too, its errors heading the page (exit 1).
    Preview {
        /// The .lmd file.
        file: PathBuf,
        /// The machine whose plan is shown (default: the first declared).
        #[arg(long, value_name = "NAME")]
        machine: Option<String>,
        /// The page to write (default: out/<part>.preview.html).
        #[arg(short = 'o', long = "out", value_name = "FILE")]
        out: Option<PathBuf>,
    },
    /// Write the coupon programs of FILE's `calibration { … }` block (one per machine,
    /// checked like any part) and the measurement sheet OUT/<part>.coupons.csv that
    /// `lmdc fit` reads once filled in (docs/calibration.md).
    Calibrate {
        /// The .lmd file with a `calibration` block.
        file: PathBuf,
        /// Directory the programs and the sheet are written to (created if missing).
        #[arg(short = 'o', long = "out", value_name = "DIR", default_value = "out")]
        out: PathBuf,
    },
    /// Fit bead models to a measurement sheet (the CSV `lmdc calibrate` writes, filled in):
    /// least squares of a line, a power law (in log space), a mass balance's efficiency
    /// (from area or mass) and a table; prints each fit's R² and residuals, the measured
    /// range, the model the data favour and the `bead { … }` block to paste
    /// (docs/calibration.md).
    Fit {
        /// The measurement sheet: one coupon a row, units in the header (`speed (mm/s)`).
        data: PathBuf,
        /// Fit only this model.
        #[arg(long, value_enum, value_name = "MODEL")]
        model: Option<FitModel>,
        /// What the heights are: a single track's, a wall's rise per layer, filled layers' rise.
        #[arg(long, value_enum, default_value = "track")]
        kind: FitKind,
        /// The tracks' offset in the layers measured, mm (with `--kind layer`).
        #[arg(long, value_name = "MM")]
        offset: Option<f64>,
        /// The metal's density in g/cm³ (a mass balance).
        #[arg(long, value_name = "G_PER_CM3")]
        density: Option<f64>,
        /// The powder feed in g/min, for coupons whose row has no `feed`.
        #[arg(long, value_name = "G_PER_MIN")]
        feed: Option<f64>,
        /// One JSON object on stdout instead of text.
        #[arg(long)]
        json: bool,
        /// Fit the thermal model instead: DATA holds interpass temperatures measured on a
        /// build of this file's plan (`layer, interpass (degC)` a row, or `layer, island,
        /// interpass (degC)`), and the absorptivity and heat transfer coefficient that fit
        /// them best are printed (docs/thermal.md).
        #[arg(long, value_name = "FILE.lmd")]
        plan: Option<PathBuf>,
    },
    /// Format .lmd files in the canonical layout (docs/fmt.md), in place; from stdin to
    /// stdout without FILES. Comments are kept and the meaning never changes.
    Fmt {
        /// The .lmd files (none: stdin).
        files: Vec<PathBuf>,
        /// Write nothing; exit 1 listing the files that are not formatted (for CI).
        #[arg(long)]
        check: bool,
    },
    /// Run a ring's height loop (`control height`) offline against its declared plant: each segment's speed, height and total, layer by layer, and the final totals against the target.
    Simulate {
        /// The .lmd file.
        file: PathBuf,
        /// Also write every layer and segment as CSV: layer,segment,speed_mm_s,height_mm,total_mm,target_mm.
        #[arg(long, value_name = "FILE")]
        csv: Option<PathBuf>,
        /// Print every N-th layer (and the first and the last); N ≥ 1.
        #[arg(long, value_name = "N", default_value_t = 10,
              value_parser = clap::value_parser!(u64).range(1..))]
        every: u64,
    },
    /// Run the language server on stdin/stdout for an editor: diagnostics as you type,
    /// hover, go to definition, references and completion (docs/editors.md).
    Lsp,
}

/// `lmdc fit --model`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum FitModel {
    /// `H = slope·v + intercept`.
    Linear,
    /// `H = height·(v/speed)^exponent`, fitted in log space.
    Power,
    /// The catch efficiency from each coupon's area or mass.
    #[value(name = "mass_balance")]
    MassBalance,
    /// The mean height at each speed, joined by lines.
    Table,
}

impl FitModel {
    fn kind(self) -> lmdc::bead::fit::Kind {
        use lmdc::bead::fit::Kind;
        match self {
            FitModel::Linear => Kind::Linear,
            FitModel::Power => Kind::Power,
            FitModel::MassBalance => Kind::MassBalance,
            FitModel::Table => Kind::Table,
        }
    }
}

/// `lmdc fit --kind`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum FitKind {
    /// A single track's height.
    Track,
    /// The rise per layer of a wall one bead wide.
    Wall,
    /// The rise per layer of filled layers (`--offset`).
    Layer,
}

impl FitKind {
    fn name(self) -> &'static str {
        match self {
            FitKind::Track => "track",
            FitKind::Wall => "wall",
            FitKind::Layer => "layer",
        }
    }
}

/// Runs `lmdc fit` (`command` is a [`Command::Fit`]).
fn fit_command(command: Command, output: (bool, MessageFormat)) -> u8 {
    let Command::Fit {
        data,
        model,
        kind,
        offset,
        density,
        feed,
        json,
        plan,
    } = command
    else {
        unreachable!("only `lmdc fit` comes here")
    };
    if let Some(plan) = plan {
        return fit_thermal::run(&data, &plan, json, output);
    }
    fit::run(
        fit::Args {
            file: &data,
            model: model.map(FitModel::kind),
            kind: kind.name(),
            offset,
            density,
            feed,
            json,
        },
        output,
    )
}

/// A warning's code as `--allow` and `--deny` take it.
fn warning_code(text: &str) -> Result<lmdc::diag::Code, String> {
    use lmdc::sema::allow;
    match allow::code(text) {
        Some(c) if allow::warns(c) => Ok(c),
        Some(c) => Err(format!(
            "{} is not a warning: only warnings can be allowed or denied",
            c.as_str()
        )),
        None => Err(format!(
            "no code of lmdc's is `{text}` (docs/diagnostics.md lists every code; \
             a warning's report names its own)"
        )),
    }
}

/// Runs the command line; returns the exit code.
pub fn run(cli: Cli) -> u8 {
    let color = match cli.color {
        Color::Always => true,
        Color::Never => false,
        Color::Auto => std::io::stderr().is_terminal() && std::env::var_os("NO_COLOR").is_none(),
    };
    let format = cli.message_format;
    messages::set_format(format);
    if let Some(c) = cli.allow.iter().find(|c| cli.deny.contains(c)) {
        let d = usage::allow_and_deny(c.as_str());
        return messages::fail(Path::new(""), d);
    }
    let common = Common {
        color,
        format,
        deny_warnings: cli.deny_warnings,
        allow: cli.allow,
        deny: cli.deny,
        set: cli.set,
    };
    // Progress only where a person watches: a terminal, not a log.
    let progress =
        |file: &Path| Progress::start(!cli.quiet && std::io::stderr().is_terminal(), shown(file));
    match cli.command {
        Command::Check { file, machine } => {
            let p = progress(&file);
            check(&file, machine.as_deref(), &common, p)
        }
        Command::Fmt { files, check } => fmt::run(&files, check),
        Command::Simulate { file, csv, every } => {
            let every = usize::try_from(every).unwrap_or(usize::MAX);
            simulate(&file, csv.as_deref(), every, &common)
        }
        Command::Build {
            file,
            out,
            machine,
            emit,
            templates,
            timings,
        } => {
            let p = progress(&file);
            let args = BuildArgs {
                file: &file,
                out: &out,
                machine: machine.as_deref(),
                emit: &emit,
                templates: templates.as_deref(),
                timings,
            };
            build(args, &common, p)
        }
        Command::Report {
            file,
            machine,
            json,
            density,
        } => {
            let p = progress(&file);
            let args = report::Args {
                file: &file,
                machine: machine.as_deref(),
                json,
                density,
            };
            report::run(args, &common, p)
        }
        Command::Lsp => match lmdc::lsp::run_stdio() {
            Ok(status) => status,
            Err(e) => {
                eprintln!("error: the language server stopped: {e}");
                EXIT_USAGE
            }
        },
        Command::Calibrate { file, out } => {
            let p = progress(&file);
            calibrate::run(&file, &out, &common, p)
        }
        command @ Command::Fit { .. } => fit_command(command, (color, format)),
        Command::Preview { file, machine, out } => {
            let p = progress(&file);
            preview::run(&file, machine.as_deref(), out.as_deref(), &common, p)
        }
    }
}

/// `lmdc check`: compiles and verifies `file` for `machine` (every machine
/// when `None`), prints its diagnostics and a one-line summary; writes
/// nothing.
fn check(file: &Path, machine: Option<&str>, common: &Common, mut p: Progress) -> u8 {
    let Some(source) = read_source(file) else {
        return EXIT_USAGE;
    };
    let options = common.options(file, machine);
    let compiled = match pipeline::compile_with(&source, &options, &mut p) {
        Ok(c) => c,
        Err(e) => return messages::fail(file, usage::refused(&e)),
    };
    p.finish();
    messages::print(
        &compiled.diagnostics,
        file,
        &source,
        common.color,
        common.format,
    );
    if let Some(code) = common.denied(file, &compiled.diagnostics) {
        return code;
    }
    match compiled.program {
        Some(p) => {
            let n = p.machines().count();
            eprintln!(
                "ok: {} layers, {} points, {} machine{}",
                p.ir().layers.len(),
                p.ir().point_count(),
                n,
                if n == 1 { "" } else { "s" }
            );
            0
        }
        None => EXIT_PROGRAM,
    }
}

/// Compiles `source` (read from `file`) for `machine`, observed by `obs` and
/// `progress`, running `meanwhile` while the slow checks finish
/// ([`pipeline::compile_then`]), and prints its diagnostics above the
/// progress line: the checked program and what `meanwhile` made (only with
/// a program that compiled; its own output comes before the diagnostics), or
/// the exit code — usage for a machine the file does not declare, program
/// errors otherwise (and `--deny-warnings`).
fn compile_and_print<R>(
    source: &str,
    file: &Path,
    machine: Option<&str>,
    obs: &mut dyn Observer,
    progress: &mut Progress,
    common: &Common,
    meanwhile: impl FnOnce(&lmdc::verify::Verified, &mut dyn Observer) -> R,
) -> Result<(lmdc::verify::Verified, Option<R>), u8> {
    let options = common.options(file, machine);
    let both = &mut progress::Both(obs, progress);
    let (compiled, made) = pipeline::compile_then(source, &options, both, meanwhile)
        .map_err(|e| messages::fail(file, usage::refused(&e)))?;
    let (color, format) = (common.color, common.format);
    progress.print(|| messages::print(&compiled.diagnostics, file, source, color, format));
    if let Some(code) = common.denied(file, &compiled.diagnostics) {
        return Err(code);
    }
    Ok((compiled.program.ok_or(EXIT_PROGRAM)?, made))
}

/// What `lmdc build` was asked for.
struct BuildArgs<'a> {
    file: &'a Path,
    out: &'a Path,
    machine: Option<&'a str>,
    emit: &'a [Emit],
    templates: Option<&'a Path>,
    timings: bool,
}

fn build(args: BuildArgs<'_>, common: &Common, mut progress: Progress) -> u8 {
    let BuildArgs {
        file,
        out,
        machine,
        emit,
        templates,
        timings,
    } = args;
    let templates = match Templates::load(templates) {
        Ok(t) => t,
        Err(e) => return messages::fail(file, usage::output(&e.to_string())),
    };
    // A build killed in this directory is finished or undone first, whether
    // or not this one succeeds (src/cli/sink.rs).
    if let Err(e) = sink::recover(out) {
        let why = format!("output directory {}: {e}", shown(out));
        return messages::fail(file, usage::output(&why));
    }
    let Some(source) = read_source(file) else {
        return EXIT_USAGE;
    };
    let mut clock = timings.then(timings::Timings::start);
    let obs: &mut dyn Observer = match clock.as_mut() {
        Some(t) => t,
        None => &mut (),
    };
    // The programs are written into the staging folder while the arm's
    // checks finish, and committed only if they pass (`compile_then`).
    let stage = |program: &lmdc::verify::Verified, obs: &mut dyn Observer| {
        let what = Staged {
            out,
            templates: &templates,
            plans: emit.contains(&Emit::Plan),
            ir: emit.contains(&Emit::Ir),
        };
        what.write(program, obs)
    };
    let (program, staged) =
        match compile_and_print(&source, file, machine, obs, &mut progress, common, stage) {
            Ok((p, Some(staged))) => (p, staged),
            // Not staged beside the checks (they all ran first): now.
            Ok((p, None)) => {
                let staged = stage(&p, &mut ());
                (p, staged)
            }
            Err(code) => return code,
        };
    let sink = match staged {
        Ok(s) => s,
        Err(code) => return code,
    };
    let paths = match sink.commit() {
        Ok(p) => p,
        Err(e) => {
            let why = format!("writing into {}: {e}", shown(out));
            return messages::fail(file, usage::output(&why));
        }
    };
    progress.finish();
    if let Some(t) = clock.as_mut() {
        t.stage("write");
        t.set_points(program.ir().point_count());
        eprint!("{}", t.report());
    }
    for p in paths {
        eprintln!("wrote {}", shown(&p));
    }
    0
}

/// What a build writes into its staging folder: the programs, and the
/// plans and the IR when asked.
struct Staged<'a> {
    out: &'a Path,
    templates: &'a Templates,
    plans: bool,
    ir: bool,
}

impl Staged<'_> {
    /// Writes `program`'s files into a staging folder of `out` and flushes
    /// them to disk: the sink to commit, or a usage exit code (printed).
    fn write(
        &self,
        program: &lmdc::verify::Verified,
        obs: &mut dyn Observer,
    ) -> Result<sink::AtomicDir, u8> {
        let out = self.out;
        let mut sink = sink::AtomicDir::new(out).map_err(|e| {
            let why = format!("cannot create the output directory {}: {e}", shown(out));
            messages::fail(Path::new(""), usage::output(&why))
        })?;
        write_programs(program, self.templates, &mut sink, obs, out)?;
        if self.plans {
            write_plans(program, &mut sink)?;
        }
        if self.ir {
            write_ir(program, &mut sink)?;
            obs.stage("emit IR");
        }
        sink.flush().map_err(|e| {
            let why = format!("writing into {}: {e}", shown(out));
            messages::fail(Path::new(""), usage::output(&why))
        })?;
        obs.stage("flush");
        Ok(sink)
    }
}

/// The set of files a build writes for `machine` (`None`: the IR).
fn set_key(program: &lmdc::verify::Verified, machine: Option<String>) -> sink::SetKey {
    sink::SetKey {
        part: program.ir().part.clone(),
        machine,
    }
}

/// Writes every verified machine's programs into `sink`, each machine's
/// files one set (replaced together); a usage exit code when a template or
/// the disk fails.
fn write_programs(
    program: &lmdc::verify::Verified,
    templates: &Templates,
    sink: &mut sink::AtomicDir,
    inner: &mut dyn Observer,
    out: &Path,
) -> Result<(), u8> {
    // pipeline::emit reports a stage after each machine: the files created
    // by then are that machine's set.
    let mut marks = Marks {
        inner,
        count: sink.counter(),
        at: Vec::new(),
    };
    let which: Vec<usize> = program.machines().map(|m| m.index()).collect();
    let emitted = pipeline::emit(program, templates, sink, &mut marks);
    let ends = std::mem::take(&mut marks.at);
    drop(marks);
    let name = |i: usize| program.ir().machines[i].name().to_string();
    if ends.len() == which.len() {
        for (&i, &end) in which.iter().zip(&ends) {
            sink.end_set(set_key(program, Some(name(i))), end);
        }
    } else {
        let names: Vec<String> = which.iter().map(|&i| name(i)).collect();
        let end = sink.counter().get();
        sink.end_set(set_key(program, Some(names.join(","))), end);
    }
    match emitted {
        Ok(()) => Ok(()),
        Err(EmitError::Template(e)) => {
            Err(messages::fail(Path::new(""), usage::output(&e.to_string())))
        }
        Err(EmitError::Io(e)) => Err(messages::fail(
            Path::new(""),
            usage::output(&format!("writing into {}: {e}", shown(out))),
        )),
    }
}

/// Writes each machine's motion plan as `<part>_<machine>.plan.jsonl` into
/// `sink`, each a set of its own.
fn write_plans(program: &lmdc::verify::Verified, sink: &mut sink::AtomicDir) -> Result<(), u8> {
    use lmdc::back::Sink;
    for m in program.machines() {
        let stem = format!("{}_{}", program.ir().part, m.machine().name());
        let name = format!(
            "{}.plan.jsonl",
            lmdc::target::names::windows_safe(&lmdc::back::identifier(&stem, 64))
        );
        let written = (|| -> std::io::Result<()> {
            let mut w = sink.create(&name)?;
            lmdc::plan::lines::write(&m.plan(), m.machine(), &mut w)?;
            w.flush()
        })();
        if let Err(e) = written {
            let why = format!("writing {name}: {e}");
            return Err(messages::fail(Path::new(""), usage::output(&why)));
        }
        let end = sink.counter().get();
        sink.end_set(
            set_key(program, Some(format!("{}.plan", m.machine().name()))),
            end,
        );
    }
    Ok(())
}

/// Writes the IR as `<part>.ir.json` into `sink`, a set of its own.
fn write_ir(program: &lmdc::verify::Verified, sink: &mut sink::AtomicDir) -> Result<(), u8> {
    let name = format!(
        "{}.ir.json",
        lmdc::target::names::windows_safe(&lmdc::back::identifier(&program.ir().part, 64))
    );
    let written = (|| -> std::io::Result<()> {
        use lmdc::back::Sink;
        let mut w = sink.create(&name)?;
        serde_json::to_writer(&mut w, program.ir()).map_err(std::io::Error::other)?;
        w.write_all(b"\n")?;
        w.flush()
    })();
    if let Err(e) = written {
        let why = format!("writing {name}: {e}");
        return Err(messages::fail(Path::new(""), usage::output(&why)));
    }
    let end = sink.counter().get();
    sink.end_set(set_key(program, None), end);
    Ok(())
}

fn simulate(file: &Path, csv: Option<&Path>, every: usize, common: &Common) -> u8 {
    let Some(source) = read_source(file) else {
        return EXIT_USAGE;
    };
    let s = match pipeline::simulate(&source, &common.set) {
        Ok(s) => s,
        Err(e) => return messages::fail(file, usage::bad_set(&e)),
    };
    messages::print(&s.diagnostics, file, &source, common.color, common.format);
    if let Some(code) = common.denied(file, &s.diagnostics) {
        return code;
    }
    let Some(run) = s.run else {
        if let Some(why) = s.nothing {
            // A valid file that is no ring: the command does not apply to it.
            let d = usage::nothing_to_do(&shown(file), "simulate", why);
            return messages::fail(file, d);
        }
        return EXIT_PROGRAM;
    };
    // A loop the build would refuse is simulated, but says so, and writes
    // nothing: a failed run leaves no file behind.
    let refused = simulate::refused(&run);
    if let Some(path) = csv.filter(|_| !refused) {
        let mut text = String::new();
        // Writing into a String cannot fail.
        let _ = run.simulation.write_csv(&mut text);
        if let Err(e) = simulate::write_atomically(path, &text) {
            let why = format!("writing {}: {e}", shown(path));
            return messages::fail(file, usage::output(&why));
        }
        eprintln!("wrote {}", shown(path));
    }
    print!("{}", simulate::report(&run, every));
    if refused {
        let csv = csv.map_or(String::new(), |p| format!("; {} not written", shown(p)));
        eprintln!(
            "the build refuses this loop (`lmdc check {}` shows where){csv}",
            shown(file)
        );
        EXIT_PROGRAM
    } else {
        0
    }
}

/// Reads the source, at most [`MAX_SOURCE`] bytes whatever the file claims to
/// be: metadata says nothing about `/dev/zero`, a pipe or a file still
/// growing, so the read itself stops one byte past the cap.
pub(crate) fn read_source(file: &Path) -> Option<String> {
    let fail = |why: String| {
        messages::fail(file, usage::unreadable(&shown(file), &why));
        None
    };
    let f = match std::fs::File::open(file) {
        Ok(f) => f,
        Err(e) => return fail(e.to_string()),
    };
    match f.metadata() {
        Ok(m) if m.is_dir() => return fail("it is a directory".into()),
        Ok(_) => {}
        Err(e) => return fail(e.to_string()),
    }
    let mut bytes = Vec::new();
    if let Err(e) = f.take(MAX_SOURCE + 1).read_to_end(&mut bytes) {
        return fail(e.to_string());
    }
    if bytes.len() as u64 > MAX_SOURCE {
        return fail(format!("it is larger than {} MB", MAX_SOURCE >> 20));
    }
    text(file, bytes)
}

/// Reads a measurement sheet for `lmdc fit`, as `fit(…, data = …)` reads
/// one: at most [`lmdc::sema::data::MAX_SHEET`] bytes, one cap for both.
pub(crate) fn read_sheet(file: &Path) -> Option<String> {
    match lmdc::sema::data::read_file(file, lmdc::sema::data::Data::Sheet) {
        Ok(bytes) => text(file, bytes),
        Err(why) => {
            messages::fail(file, usage::unreadable(&shown(file), &why));
            None
        }
    }
}

/// `bytes` of `file` as text, or `None` after saying they are not UTF-8.
fn text(file: &Path, bytes: Vec<u8>) -> Option<String> {
    match String::from_utf8(bytes) {
        Ok(s) => Some(s),
        Err(e) => {
            let why = format!(
                "it is not UTF-8 text (invalid byte at offset {})",
                e.utf8_error().valid_up_to()
            );
            messages::fail(file, usage::unreadable(&shown(file), &why));
            None
        }
    }
}

/// Reads the data files a program names (`fit(…, data = "…")`,
/// `mesh(file = "…")`), relative to the folder of the .lmd file `file`,
/// each no further than its kind's cap ([`lmdc::sema::data`]).
pub fn data_reader(file: &Path) -> lmdc::sema::DataReader {
    let dir = file.parent().map(Path::to_path_buf).unwrap_or_default();
    std::rc::Rc::new(move |path: &str, kind| lmdc::sema::data::read_file(&dir.join(path), kind))
}

/// A path as it is safe to print: no control character from its name reaches
/// the terminal.
pub(crate) fn shown(path: &Path) -> String {
    lmdc::diag::sanitize(&path.display().to_string()).into_owned()
}

/// Passes stages on and notes how many files had been created at each.
struct Marks<'o> {
    inner: &'o mut dyn Observer,
    count: std::rc::Rc<std::cell::Cell<usize>>,
    at: Vec<usize>,
}

impl Observer for Marks<'_> {
    fn stage(&mut self, name: &'static str) {
        self.at.push(self.count.get());
        self.inner.stage(name);
    }
}
