//! A strict reader of the RAPID subset lmdc writes for ABB robots
//! (docs/rapid.md): it parses every module with its own grammar
//! (tests/support/rapid.pest), checks the modules, the data and every
//! instruction against the forms the doc allows, then *executes* `PROC main()`
//! — following its routine calls into the motion modules — into a [`Trace`]
//! of motions with the speed, zone, laser and power state each one runs with,
//! and a timeline of the cell's outputs. Tests compare that trace, move by
//! move, with the IR the program was written from.
//!
//! Written from the text of docs/rapid.md, not from lmdc's types: it shares
//! no code with the emitter.
//!
//! What it checks: each file `X.mod` holds `MODULE X`; the main module holds
//! the data and `PROC main()`, a motion module one routine named as it and no
//! data; numbers are plain decimals (an exponent only as `9E+09`, "no axis",
//! in external axes), to the doc's decimals; names have at most 32
//! characters, a letter first, and are no RAPID reserved word; data is
//! declared (with the storage class the doc gives its type, `lmd_` names)
//! before any routine and is of the type its use wants; quaternions have
//! norm 1 within 1e-5; confdata are integers with cfx 0..7, `[0,0,0,0]`
//! under `ConfJ \Off` (no arm); speeddata are `[v_tcp,500,5000,1000]` with
//! v_tcp > 0, at most 50 declared, ABB's `v<n>` only for the joint moves, in
//! place only for the linear ones; analog values 0..1; signals are
//! `do<n>`/`ao<n>` or named (a RAPID name, no `lmd_` data, not `ao<n>` for
//! a digital one nor `do<n>` for an analog one), the laser's and its
//! power's (the names `run` is given) only switched by `TriggIO`
//! in the motion modules (the main routine may only switch them off); the
//! triggers are `lmd_on`/`lmd_off`/`lmd_power` with `\Start` and their
//! `_end` twins without, distance 0; a `TriggL`'s triggers are set by
//! `TriggIO`s since the previous motion and every `TriggIO` is used by the
//! `TriggL` right after it; a trigger that switches the laser to the state
//! it has is refused, and one that switches it where its move starts
//! follows a fine point; `MoveAbsJ` only in main, `MoveJ` only as the move
//! from home; other outputs and dwells only where the robot stands, with the
//! laser off, in a motion module with a comment; a wait never follows a
//! blended motion; `! layer N of M` comments number the layers 1, 2, …;
//! every module is called.
//!
//! Stricter than RobotStudio/RobotWare: it reads only the subset (these
//! instructions, argument forms, data types and storage classes; keywords in
//! the case lmdc writes, where RAPID ignores case; `lmd_` data names; one
//! module per file), refuses exponents RAPID reads, extra decimals, an unused
//! `TriggIO` (RAPID ignores it), a redundant laser switch (RAPID switches it
//! again), a wait after a blended motion (RobotWare only warns, "corner path
//! failure", and stops there), and quaternions RobotWare would normalise.
//! Looser: it knows no controller, so it does not check that the signals
//! exist or their logical ranges, that a mechanical unit such as `STN1`
//! exists, that targets are reachable, within the joint limits or of the
//! right configuration (only the confdata's form; the arm tests check the
//! rest), that a tool's load is plausible (only mass > 0, inertia ≥ 0), that
//! speeds are within the robot's limits, nor the trigger's timing; and its
//! reserved words are the manual's list, not the names of built-in
//! instructions and data.
#![allow(dead_code)]

use pest::iterators::Pair;
use pest::Parser;
use std::collections::BTreeMap;

#[derive(pest_derive::Parser)]
#[grammar = "../tests/support/rapid.pest"]
struct RapidParser;

// ------------------------------------------------------------------ the trace

/// The RAPID files of one program: file name (`duct.mod`) → text.
pub type Files = BTreeMap<String, String>;

/// A motion instruction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    MoveAbsJ,
    MoveJ,
    MoveL,
    TriggL,
}

/// A position and orientation: mm, and a unit quaternion `q1` (scalar) first.
#[derive(Clone, Debug, PartialEq)]
pub struct Pose {
    pub pos: [f64; 3],
    pub quat: [f64; 4],
}

/// A `robtarget` written in place.
#[derive(Clone, Debug, PartialEq)]
pub struct RobTarget {
    /// x y z, mm.
    pub pos: [f64; 3],
    /// q1 q2 q3 q4.
    pub quat: [f64; 4],
    /// cf1 cf4 cf6 cfx.
    pub conf: [i32; 4],
    /// eax_a … eax_f, `None` for `9E+09`.
    pub extax: [Option<f64>; 6],
}

/// A `jointtarget`.
#[derive(Clone, Debug, PartialEq)]
pub struct JointTarget {
    /// Axes 1..6, deg.
    pub robax: [f64; 6],
    /// eax_a … eax_f, `None` for `9E+09`.
    pub extax: [Option<f64>; 6],
}

/// Where a motion goes.
#[derive(Clone, Debug, PartialEq)]
pub enum Target {
    Pose(RobTarget),
    Joints(JointTarget),
}

/// One motion as the robot runs it.
#[derive(Clone, Debug, PartialEq)]
pub struct Motion {
    pub kind: Kind,
    pub target: Target,
    /// The speeddata's `v_tcp`, mm/s.
    pub speed: f64,
    /// `None` at a `fine` point, the zone's `pzone_tcp` (mm) where blended.
    pub zone: Option<f64>,
    /// The laser is on during the motion.
    pub laser: bool,
    /// A trigger without `\Start` switches the laser at the motion's end.
    pub switch_at_end: bool,
    /// The power's analog output during the motion, 0..1.
    pub power: f64,
    /// The module the instruction is in.
    pub module: String,
    /// Its line.
    pub line: usize,
}

impl Motion {
    /// The Cartesian target, `None` for a `MoveAbsJ`.
    pub fn pose(&self) -> Option<&RobTarget> {
        match &self.target {
            Target::Pose(p) => Some(p),
            Target::Joints(_) => None,
        }
    }
}

/// One step of the program, in order.
#[derive(Clone, Debug, PartialEq)]
pub enum Event {
    /// `trace.motions[i]` runs.
    Motion(usize),
    /// `WaitTime \InPos, t`.
    Dwell(f64),
    /// `WaitRob \InPos`.
    WaitRob,
    /// `SetDO <signal>, 0|1` (`do3`, `doGas`).
    SetDO(String, bool),
    /// `SetAO <signal>, x` (`ao2`, `aoPowderRate`).
    SetAO(String, f64),
}

/// A `tooldata`.
#[derive(Clone, Debug, PartialEq)]
pub struct ToolData {
    pub robhold: bool,
    pub tframe: Pose,
    /// kg.
    pub mass: f64,
    /// mm.
    pub cog: [f64; 3],
    pub aom: [f64; 4],
    /// kg·m².
    pub inertia: [f64; 3],
}

/// A `wobjdata`.
#[derive(Clone, Debug, PartialEq)]
pub struct WobjData {
    pub robhold: bool,
    pub ufprog: bool,
    /// The mechanical unit the work object moves with (`""`: none).
    pub ufmec: String,
    pub uframe: Pose,
    pub oframe: Pose,
}

/// What running `main` did.
#[derive(Debug, Default)]
pub struct Trace {
    /// The motions in execution order.
    pub motions: Vec<Motion>,
    /// Motions, dwells, waits and `SetDO`/`SetAO`, in order.
    pub events: Vec<Event>,
    /// Dwells: (motions run before it, seconds).
    pub dwells: Vec<(usize, f64)>,
    /// Routines called from main, in order.
    pub calls: Vec<String>,
    /// Motion instructions per module.
    pub moves_per_module: BTreeMap<String, usize>,
    /// `! layer …` comments: (motions run before it, the comment).
    pub layers: Vec<(usize, String)>,
    /// The tool, work object and home the motions use.
    pub tool: Option<ToolData>,
    pub wobj: Option<WobjData>,
    pub home: Option<JointTarget>,
    /// The declared speeddata: name → `v_tcp`.
    pub speeds: BTreeMap<String, f64>,
    /// `ConfJ`, `ConfL`: `\On` is true.
    pub conf_j: Option<bool>,
    pub conf_l: Option<bool>,
    /// The laser and its power when main ends.
    pub laser_at_end: bool,
    pub power_at_end: f64,
}

/// The signals of an ABB robot's laser and its power as docs/rapid.md
/// names them: the names the robot gives (`laser = "doLaserOn"`), else
/// `do<laser>` and `ao<power_output>`.
pub fn signals(r: &lmdc::ir::Robot) -> (String, String) {
    let name = |s: &lmdc::ir::Signal, prefix: &str| match s {
        lmdc::ir::Signal::Number(n) => format!("{prefix}{n}"),
        lmdc::ir::Signal::Name(name) => name.clone(),
    };
    (name(&r.laser_out, "do"), name(&r.power_out, "ao"))
}

/// Reads every file and runs `PROC main()` of `<main>.mod`; `laser` and
/// `power` are the signals of the laser's digital output (`do1`,
/// `doLaserOn`) and of its power's analog output (`ao2`, `aoLaserPower`).
pub fn run(files: &Files, main: &str, laser: &str, power: &str) -> Result<Trace, String> {
    let mut modules = BTreeMap::new();
    for (file, text) in files {
        let stem = file
            .strip_suffix(".mod")
            .ok_or_else(|| format!("{file}: not a module file (.mod)"))?;
        let m = parse_module(file, text)?;
        structure(&m, stem, stem == main).map_err(|e| e.at(file))?;
        modules.insert(stem.to_string(), m);
    }
    let first = modules
        .get(main)
        .ok_or_else(|| format!("no main module: {main}.mod was not given"))?;
    let data = declare(first)?;
    let mut st = State {
        modules: &modules,
        data: &data,
        main,
        laser_no: laser.to_string(),
        power_no: power.to_string(),
        trace: Trace::default(),
        laser: false,
        power: 0.0,
        pending: Vec::new(),
        stopped: true,
        module: String::new(),
        layer: (0, 0),
    };
    for (name, d) in &data {
        if let Value::Speed(v) = d.value {
            st.trace.speeds.insert(name.clone(), v);
        }
    }
    st.routine(first)?;
    for name in modules.keys() {
        if name != main && !st.trace.calls.contains(name) {
            return Err(format!("{name}.mod: main never calls {name}"));
        }
    }
    st.trace.laser_at_end = st.laser;
    st.trace.power_at_end = st.power;
    Ok(st.trace)
}

// ------------------------------------------------------------- syntax tree

/// An error at a line of the file being read, or one already placed.
#[derive(Debug)]
enum E {
    At(usize, String),
    Done(String),
}

impl E {
    fn at(self, file: &str) -> String {
        match self {
            E::At(line, msg) => format!("{file}:{line}: {msg}"),
            E::Done(s) => s,
        }
    }
}

type R<T> = Result<T, E>;

fn err<T>(line: usize, msg: impl Into<String>) -> R<T> {
    Err(E::At(line, msg.into()))
}

#[derive(Clone, Debug)]
struct Expr {
    line: usize,
    kind: X,
}

#[derive(Clone, Debug)]
enum X {
    Num(String),
    Str(String),
    Name(String),
    Agg(Vec<Expr>),
}

#[derive(Debug)]
enum Arg {
    Expr(Expr),
    Comma,
    Opt(String, Option<Expr>),
}

#[derive(Debug)]
struct Instr {
    line: usize,
    name: String,
    args: Vec<Arg>,
    comment: Option<String>,
}

#[derive(Debug)]
enum Line {
    /// A whole-line comment: its line and text.
    Note(usize, String),
    Instr(Instr),
}

#[derive(Debug)]
struct Routine {
    line: usize,
    keyword: String,
    name: String,
    body: Vec<Line>,
}

#[derive(Debug)]
struct Decl {
    line: usize,
    storage: String,
    ty: String,
    name: String,
    init: Option<Expr>,
}

#[derive(Debug, Default)]
struct Module {
    file: String,
    line: usize,
    keyword: String,
    name: String,
    decls: Vec<Decl>,
    routines: Vec<Routine>,
}

fn line_of(p: &Pair<Rule>) -> usize {
    p.line_col().0
}

/// A syntax error: the grammar's rules in words.
fn syntax(file: &str, e: pest::error::Error<Rule>) -> String {
    let e = e.renamed_rules(|r| {
        match r {
            Rule::name => "a name",
            Rule::number => "a number",
            Rule::string => "a string",
            Rule::aggregate => "an aggregate `[…]`",
            Rule::comma => "`,`",
            Rule::opt => "an optional argument `\\Name`",
            Rule::comment | Rule::note => "a comment",
            Rule::EOI => "the end of the file",
            other => return format!("{other:?}"),
        }
        .to_string()
    });
    let (line, col) = match e.line_col {
        pest::error::LineColLocation::Pos(p) => p,
        pest::error::LineColLocation::Span(p, _) => p,
    };
    format!("{file}:{line}:{col}: syntax: {}", e.variant.message())
}

fn parse_module(file: &str, text: &str) -> Result<Module, String> {
    let mut pairs = RapidParser::parse(Rule::file, text).map_err(|e| syntax(file, e))?;
    let top = pairs
        .next()
        .ok_or_else(|| format!("{file}: nothing parsed"))?;
    let mut m = Module {
        file: file.to_string(),
        ..Module::default()
    };
    for p in top.into_inner() {
        match p.as_rule() {
            Rule::header => {
                m.line = line_of(&p);
                let mut names = p.into_inner().filter(|p| p.as_rule() == Rule::name);
                m.keyword = names.next().map_or("", |p| p.as_str()).to_string();
                m.name = names.next().map_or("", |p| p.as_str()).to_string();
            }
            Rule::decl => m.decls.push(decl(p)),
            Rule::routine => m.routines.push(routine(p)),
            _ => {}
        }
    }
    Ok(m)
}

fn decl(p: Pair<Rule>) -> Decl {
    let line = line_of(&p);
    let kids: Vec<Pair<Rule>> = p
        .into_inner()
        .filter(|p| p.as_rule() != Rule::comment)
        .collect();
    let word = |i: usize| kids.get(i).map_or("", |p| p.as_str()).to_string();
    Decl {
        line,
        storage: word(0),
        ty: word(1),
        name: word(2),
        init: kids.get(3).cloned().map(expr),
    }
}

fn routine(p: Pair<Rule>) -> Routine {
    let mut r = Routine {
        line: line_of(&p),
        keyword: String::new(),
        name: String::new(),
        body: Vec::new(),
    };
    for (k, q) in p.into_inner().enumerate() {
        match (k, q.as_rule()) {
            (0, _) => r.keyword = q.as_str().to_string(),
            (1, _) => r.name = q.as_str().to_string(),
            (_, Rule::note) => r.body.push(Line::Note(line_of(&q), q.as_str().to_string())),
            (_, Rule::instr) => r.body.push(Line::Instr(instr(q))),
            _ => {}
        }
    }
    r
}

fn instr(p: Pair<Rule>) -> Instr {
    let mut i = Instr {
        line: line_of(&p),
        name: String::new(),
        args: Vec::new(),
        comment: None,
    };
    for (k, q) in p.into_inner().enumerate() {
        match q.as_rule() {
            _ if k == 0 => i.name = q.as_str().to_string(),
            Rule::comma => i.args.push(Arg::Comma),
            Rule::comment => i.comment = Some(q.as_str().to_string()),
            Rule::opt => {
                let mut kids = q.into_inner();
                let name = kids.next().map_or("", |n| n.as_str()).to_string();
                i.args.push(Arg::Opt(name, kids.next().map(expr)));
            }
            _ => i.args.push(Arg::Expr(expr(q))),
        }
    }
    i
}

fn expr(p: Pair<Rule>) -> Expr {
    let line = line_of(&p);
    let s = p.as_str();
    let kind = match p.as_rule() {
        Rule::aggregate => X::Agg(p.into_inner().map(expr).collect()),
        Rule::number => X::Num(s.to_string()),
        Rule::string => X::Str(s.trim_matches('"').to_string()),
        _ => X::Name(s.to_string()),
    };
    Expr { line, kind }
}

/// The expression as RAPID text.
fn show(e: &Expr) -> String {
    match &e.kind {
        X::Num(s) | X::Name(s) => s.clone(),
        X::Str(s) => format!("\"{s}\""),
        X::Agg(v) => format!("[{}]", v.iter().map(show).collect::<Vec<_>>().join(",")),
    }
}

/// An argument list's form: `E` for each value, optional arguments by name
/// (`E, E \Start \DOp:=E, E`).
fn shape(args: &[Arg]) -> String {
    let mut out = String::new();
    for a in args {
        let tok = match a {
            Arg::Comma => {
                out.push(',');
                continue;
            }
            Arg::Expr(_) => "E".to_string(),
            Arg::Opt(n, None) => format!("\\{n}"),
            Arg::Opt(n, Some(_)) => format!("\\{n}:=E"),
        };
        if !out.is_empty() {
            out.push(' ');
        }
        out.push_str(&tok);
    }
    out
}

/// The positional arguments, in order.
fn positional(args: &[Arg]) -> Vec<&Expr> {
    args.iter()
        .filter_map(|a| match a {
            Arg::Expr(e) => Some(e),
            _ => None,
        })
        .collect()
}

/// The value of the optional argument `\name:=…`.
fn opt<'i>(i: &'i Instr, name: &str) -> R<&'i Expr> {
    i.args
        .iter()
        .find_map(|a| match a {
            Arg::Opt(n, Some(e)) if n == name => Some(e),
            _ => None,
        })
        .ok_or_else(|| E::At(i.line, format!("{} without \\{name}", i.name)))
}

/// Which of `forms` the instruction's arguments have.
fn want(i: &Instr, forms: &[&str]) -> R<usize> {
    let got = shape(&i.args);
    forms.iter().position(|f| *f == got).map_or_else(
        || {
            let want = forms
                .iter()
                .map(|f| format!("`{} {f};`", i.name))
                .collect::<Vec<_>>()
                .join(" or ");
            err(
                i.line,
                format!("`{} {got};` is not a form lmdc writes: want {want}", i.name),
            )
        },
        Ok,
    )
}

// ------------------------------------------------------------------- names

/// RAPID's reserved words (Technical reference manual, RAPID overview).
const RESERVED: &[&str] = &[
    "ALIAS",
    "AND",
    "BACKWARD",
    "CASE",
    "CONNECT",
    "CONST",
    "DEFAULT",
    "DIV",
    "DO",
    "ELSE",
    "ELSEIF",
    "ENDFOR",
    "ENDFUNC",
    "ENDIF",
    "ENDMODULE",
    "ENDPROC",
    "ENDRECORD",
    "ENDTEST",
    "ENDTRAP",
    "ENDWHILE",
    "ERROR",
    "EXIT",
    "FALSE",
    "FOR",
    "FROM",
    "FUNC",
    "GOTO",
    "IF",
    "INOUT",
    "LOCAL",
    "MOD",
    "MODULE",
    "NOSTEPIN",
    "NOT",
    "NOVIEW",
    "OR",
    "PERS",
    "PROC",
    "RAISE",
    "READONLY",
    "RECORD",
    "RETRY",
    "RETURN",
    "STEP",
    "SYSMODULE",
    "TEST",
    "THEN",
    "TO",
    "TRAP",
    "TRUE",
    "TRYNEXT",
    "UNDO",
    "VAR",
    "VIEWONLY",
    "WHILE",
    "WITH",
    "XOR",
];

/// A RAPID name: at most 32 characters, a letter then letters, digits and
/// `_`, no reserved word.
fn check_name(n: &str, line: usize) -> R<()> {
    if n.chars().count() > 32 {
        return err(
            line,
            format!("the name `{n}` has {} characters, more than 32", n.len()),
        );
    }
    let ok = n.starts_with(|c: char| c.is_ascii_alphabetic())
        && n.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if !ok {
        return err(
            line,
            format!("`{n}` is not a RAPID name (a letter, then letters, digits and _)"),
        );
    }
    if RESERVED.iter().any(|r| r.eq_ignore_ascii_case(n)) {
        return err(line, format!("`{n}` is a RAPID reserved word"));
    }
    Ok(())
}

/// `! layer N of M: …`: N and M.
fn layer_note(text: &str) -> Option<(usize, usize)> {
    let rest = text
        .strip_prefix('!')?
        .trim_start()
        .strip_prefix("layer ")?;
    let (n, rest) = rest.split_once(" of ")?;
    let (of, _) = rest.split_once(':')?;
    Some((n.parse().ok()?, of.parse().ok()?))
}

/// A signal, digital (`do1`, `doLaserOn`) or `analog` (`ao2`,
/// `aoLaserPower`): `do<n>`/`ao<n>` by number, or a signal's own name — a
/// RAPID name that is not the program's data (`lmd_…`, or declared), nor
/// the numbered name of the other kind.
fn signal(e: &Expr, analog: bool, data: &BTreeMap<String, Data>) -> R<String> {
    let (want, other) = if analog { ("ao", "do") } else { ("do", "ao") };
    let X::Name(s) = &e.kind else {
        return err(e.line, format!("`{}` is not a signal", show(e)));
    };
    check_name(s, e.line)?;
    let number = |p: &str| {
        s.strip_prefix(p)
            .filter(|n| !n.is_empty() && n.chars().all(|c| c.is_ascii_digit()))
    };
    if number(other).is_some() {
        return err(
            e.line,
            format!("`{s}` is not a signal {want}<n> or a signal's name"),
        );
    }
    if let Some(n) = number(want) {
        if n.parse::<u16>()
            .ok()
            .filter(|k| k.to_string() == n)
            .is_none()
        {
            return err(e.line, format!("`{s}` is not a signal {want}<n>"));
        }
    }
    let own = s.to_ascii_lowercase().starts_with("lmd_")
        || data.keys().any(|k| k.eq_ignore_ascii_case(s));
    if own {
        return err(e.line, format!("`{s}` is the program's data, not a signal"));
    }
    Ok(s.clone())
}

// ------------------------------------------------------------------ values

/// A plain decimal: optional `-`, digits, optional `.digits`.
fn plain(s: &str) -> Option<f64> {
    let t = s.strip_prefix('-').unwrap_or(s);
    let (int, frac) = t.split_once('.').unwrap_or((t, "0"));
    let digits = |p: &str| !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit());
    if digits(int) && digits(frac) {
        s.parse().ok()
    } else {
        None
    }
}

fn num(e: &Expr) -> R<f64> {
    match &e.kind {
        X::Num(s) => plain(s).map_or_else(
            || {
                err(
                    e.line,
                    format!(
                        "`{s}` is not a plain decimal number (an exponent is written only as \
                         9E+09 in external axes)"
                    ),
                )
            },
            Ok,
        ),
        X::Name(n) if ["nan", "inf"].contains(&n.to_ascii_lowercase().as_str()) => err(
            e.line,
            format!("`{n}`: NaN and inf are not numbers RAPID reads"),
        ),
        _ => err(e.line, format!("want a number, got `{}`", show(e))),
    }
}

/// A number of at most `max` decimals.
fn num_dec(e: &Expr, max: usize, what: &str) -> R<f64> {
    let v = num(e)?;
    if let X::Num(s) = &e.kind {
        let dec = s.split_once('.').map_or(0, |(_, f)| f.len());
        if dec > max {
            return err(
                e.line,
                format!("`{s}`: {what} is written with at most {max} decimals"),
            );
        }
    }
    Ok(v)
}

fn int(e: &Expr, what: &str) -> R<i32> {
    let v = num_dec(e, 0, what)?;
    if v.abs() > i32::MAX as f64 {
        return err(e.line, format!("{what} `{}` out of range", show(e)));
    }
    Ok(v as i32)
}

fn boolean(e: &Expr) -> R<bool> {
    match &e.kind {
        X::Name(n) if n == "TRUE" => Ok(true),
        X::Name(n) if n == "FALSE" => Ok(false),
        _ => err(e.line, format!("want TRUE or FALSE, got `{}`", show(e))),
    }
}

fn string(e: &Expr) -> R<String> {
    match &e.kind {
        X::Str(s) => Ok(s.clone()),
        _ => err(e.line, format!("want a string, got `{}`", show(e))),
    }
}

/// An aggregate of exactly `n` components.
fn agg<'e>(e: &'e Expr, n: usize, what: &str) -> R<&'e [Expr]> {
    match &e.kind {
        X::Agg(v) if v.len() == n => Ok(v),
        _ => err(
            e.line,
            format!(
                "{what} is an aggregate of {n} components, got `{}`",
                show(e)
            ),
        ),
    }
}

fn nums<const N: usize>(e: &Expr, what: &str, dec: usize) -> R<[f64; N]> {
    let v = agg(e, N, what)?;
    let mut out = [0.0; N];
    for (o, x) in out.iter_mut().zip(v) {
        *o = num_dec(x, dec, what)?;
    }
    Ok(out)
}

/// A unit quaternion, norm 1 within 1e-5.
fn quat(e: &Expr, dec: usize) -> R<[f64; 4]> {
    let q = nums::<4>(e, "an orientation", dec)?;
    let norm = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    if (norm - 1.0).abs() > 1e-5 {
        return err(
            e.line,
            format!(
                "the quaternion `{}` has norm {norm}, not 1 within 1e-5",
                show(e)
            ),
        );
    }
    Ok(q)
}

fn pose(e: &Expr) -> R<Pose> {
    let v = agg(e, 2, "a pose")?;
    Ok(Pose {
        pos: nums::<3>(&v[0], "a position", 6)?,
        quat: quat(&v[1], 6)?,
    })
}

/// External axes: plain numbers, or `9E+09` for none.
fn extax(e: &Expr) -> R<[Option<f64>; 6]> {
    let v = agg(e, 6, "the external axes")?;
    let mut out = [None; 6];
    for (o, x) in out.iter_mut().zip(v) {
        *o = match &x.kind {
            X::Num(s) if s == "9E+09" => None,
            _ => Some(num_dec(x, 3, "an external axis")?),
        };
    }
    Ok(out)
}

fn robtarget(e: &Expr) -> R<RobTarget> {
    let v = agg(e, 4, "a robtarget")?;
    let c = agg(&v[2], 4, "a confdata")?;
    let mut conf = [0; 4];
    for (o, x) in conf.iter_mut().zip(c) {
        *o = int(x, "a confdata component")?;
    }
    if !(0..=7).contains(&conf[3]) {
        return err(
            e.line,
            format!("cfx {} outside 0..7 in `{}`", conf[3], show(&v[2])),
        );
    }
    Ok(RobTarget {
        pos: nums::<3>(&v[0], "a position (mm)", 3)?,
        quat: quat(&v[1], 6)?,
        conf,
        extax: extax(&v[3])?,
    })
}

fn jointtarget(e: &Expr) -> R<JointTarget> {
    let v = agg(e, 2, "a jointtarget")?;
    Ok(JointTarget {
        robax: nums::<6>(&v[0], "the robot's axes", 6)?,
        extax: extax(&v[1])?,
    })
}

fn tooldata(e: &Expr) -> R<ToolData> {
    let v = agg(e, 3, "a tooldata")?;
    let load = agg(&v[2], 6, "a loaddata")?;
    let t = ToolData {
        robhold: boolean(&v[0])?,
        tframe: pose(&v[1])?,
        mass: num(&load[0])?,
        cog: nums::<3>(&load[1], "a centre of gravity", 6)?,
        aom: quat(&load[2], 6)?,
        inertia: [num(&load[3])?, num(&load[4])?, num(&load[5])?],
    };
    if !t.robhold {
        return err(e.line, "the tool is held by the robot (robhold TRUE)");
    }
    if t.mass <= 0.0 || t.inertia.iter().any(|i| *i < 0.0) {
        return err(e.line, "a tool's mass is above 0 and its inertia 0 or more");
    }
    Ok(t)
}

fn wobjdata(e: &Expr) -> R<WobjData> {
    let v = agg(e, 5, "a wobjdata")?;
    let w = WobjData {
        robhold: boolean(&v[0])?,
        ufprog: boolean(&v[1])?,
        ufmec: string(&v[2])?,
        uframe: pose(&v[3])?,
        oframe: pose(&v[4])?,
    };
    if w.robhold {
        return err(
            e.line,
            "the work object is not held by the robot (robhold FALSE)",
        );
    }
    if w.ufprog == w.ufmec.is_empty() {
        return Ok(w);
    }
    err(
        e.line,
        "a fixed user frame (ufprog TRUE) has no mechanical unit, a moving one \
         (ufprog FALSE) names its unit",
    )
}

/// A speeddata's `v_tcp`, above zero; the other three ABB's `v`-speeds'.
fn speeddata(e: &Expr) -> R<f64> {
    let v = nums::<4>(e, "a speeddata", 3)?;
    if v[0] <= 0.0 || v[1..] != [500.0, 5000.0, 1000.0] {
        return err(
            e.line,
            format!(
                "a speeddata is [v_tcp,500,5000,1000], v_tcp above 0, got `{}`",
                show(e)
            ),
        );
    }
    Ok(v[0])
}

/// A zonedata's `pzone_tcp`: not a fine point, every size 0 or more.
fn zonedata(e: &Expr) -> R<f64> {
    let v = agg(e, 7, "a zonedata")?;
    if boolean(&v[0])? {
        return err(e.line, "a stop point is written `fine`, not a zonedata");
    }
    let mut sizes = [0.0; 6];
    for (s, x) in sizes.iter_mut().zip(&v[1..]) {
        *s = num(x)?;
    }
    if sizes[0] <= 0.0 || sizes.iter().any(|s| *s < 0.0) {
        return err(
            e.line,
            "a zone's sizes are 0 or more, its pzone_tcp above 0",
        );
    }
    Ok(sizes[0])
}

/// A value for an analog output: 0..1, 4 decimals.
fn analog(e: &Expr) -> R<f64> {
    let x = num_dec(e, 4, "an analog value")?;
    if !(0.0..=1.0).contains(&x) {
        return err(e.line, format!("the analog value {x} is outside 0..1"));
    }
    Ok(x)
}

/// A digital value: 0 or 1.
fn digital(e: &Expr) -> R<bool> {
    match int(e, "a digital value")? {
        0 => Ok(false),
        1 => Ok(true),
        v => err(e.line, format!("a digital value is 0 or 1, got {v}")),
    }
}

// ------------------------------------------------------ modules and data

/// A module's frame: `MODULE <stem>`; the main module holds the data and
/// `PROC main()`, a motion module `PROC <stem>()` alone; data before routines.
fn structure(m: &Module, stem: &str, main: bool) -> R<()> {
    if m.keyword != "MODULE" {
        return err(m.line, format!("want `MODULE {stem}`, got `{}`", m.keyword));
    }
    check_name(&m.name, m.line)?;
    if m.name != stem {
        return err(
            m.line,
            format!(
                "the file {stem}.mod holds `MODULE {}`: a module is named as its file",
                m.name
            ),
        );
    }
    let want = if main { "main" } else { stem };
    match m.routines.as_slice() {
        [r] if r.keyword == "PROC" && r.name == want => {}
        [_, r, ..] => {
            return err(
                r.line,
                format!("module {stem} holds one routine, PROC {want}()"),
            )
        }
        [r] => {
            return err(
                r.line,
                format!("want `PROC {want}()`, got `{} {}()`", r.keyword, r.name),
            )
        }
        [] => return err(m.line, format!("module {stem} has no PROC {want}()")),
    }
    if let Some(d) = m.decls.first().filter(|_| !main) {
        return err(
            d.line,
            "a motion module declares no data: main's module holds it",
        );
    }
    let first = m.routines.first().map_or(usize::MAX, |r| r.line);
    if let Some(d) = m.decls.iter().find(|d| d.line > first) {
        return err(d.line, "data is declared before the routines");
    }
    Ok(())
}

/// A declared datum.
#[derive(Debug)]
struct Data {
    ty: &'static str,
    value: Value,
    line: usize,
}

#[derive(Debug)]
enum Value {
    Tool(ToolData),
    Wobj(WobjData),
    Joint(JointTarget),
    /// `v_tcp`.
    Speed(f64),
    /// `pzone_tcp`.
    Zone(f64),
    Trigg,
}

/// The data types lmdc declares, with their storage class.
const TYPES: [(&str, &str); 6] = [
    ("tooldata", "PERS"),
    ("wobjdata", "PERS"),
    ("jointtarget", "CONST"),
    ("speeddata", "CONST"),
    ("zonedata", "CONST"),
    ("triggdata", "VAR"),
];

fn declare(m: &Module) -> Result<BTreeMap<String, Data>, String> {
    let mut data = BTreeMap::new();
    let mut speeds = 0;
    for d in &m.decls {
        declare_one(d, &mut data).map_err(|e| e.at(&m.file))?;
        speeds += usize::from(d.ty == "speeddata");
        if speeds > 50 {
            let e = "at most 50 speeddata are declared; further speeds are written in place";
            return Err(E::At(d.line, e.into()).at(&m.file));
        }
    }
    Ok(data)
}

fn declare_one(d: &Decl, data: &mut BTreeMap<String, Data>) -> R<()> {
    check_name(&d.name, d.line)?;
    if !d.name.starts_with("lmd_") {
        return err(d.line, format!("`{}`: lmdc's data is named lmd_…", d.name));
    }
    let Some(&(ty, storage)) = TYPES.iter().find(|(t, _)| *t == d.ty) else {
        return err(
            d.line,
            format!("`{}` is not a data type lmdc declares", d.ty),
        );
    };
    if d.storage != storage {
        return err(
            d.line,
            format!("a {ty} is declared {storage}, not `{}`", d.storage),
        );
    }
    if let Some((k, old)) = data.iter().find(|(k, _)| k.eq_ignore_ascii_case(&d.name)) {
        return err(
            d.line,
            format!("`{}` is declared again (`{k}`, line {})", d.name, old.line),
        );
    }
    let value = match (ty, &d.init) {
        ("triggdata", None) => Value::Trigg,
        ("triggdata", Some(_)) => return err(d.line, "a triggdata is declared without a value"),
        (_, None) => return err(d.line, format!("the {ty} `{}` needs a value", d.name)),
        ("tooldata", Some(e)) => Value::Tool(tooldata(e)?),
        ("wobjdata", Some(e)) => Value::Wobj(wobjdata(e)?),
        ("jointtarget", Some(e)) => Value::Joint(jointtarget(e)?),
        ("speeddata", Some(e)) => Value::Speed(speeddata(e)?),
        (_, Some(e)) => Value::Zone(zonedata(e)?),
    };
    data.insert(
        d.name.clone(),
        Data {
            ty,
            value,
            line: d.line,
        },
    );
    Ok(())
}

/// RAPID's predefined speeddata `v5` … `v7000`, allowed for `MoveAbsJ`.
const PREDEFINED_SPEEDS: [u32; 25] = [
    5, 10, 20, 30, 40, 50, 60, 80, 100, 150, 200, 300, 400, 500, 600, 800, 1000, 1500, 2000, 2500,
    3000, 4000, 5000, 6000, 7000,
];

// ---------------------------------------------------------------- running

/// A `TriggIO` waiting for its `TriggL`.
#[derive(Clone, Debug)]
struct Trig {
    name: String,
    line: usize,
    start: bool,
    set: Set,
}

#[derive(Clone, Copy, Debug)]
enum Set {
    Laser(bool),
    Power(f64),
}

struct State<'a> {
    modules: &'a BTreeMap<String, Module>,
    data: &'a BTreeMap<String, Data>,
    main: &'a str,
    laser_no: String,
    power_no: String,
    trace: Trace,
    laser: bool,
    power: f64,
    /// `TriggIO`s since the last motion.
    pending: Vec<Trig>,
    /// The robot stands: nothing moved since a `WaitRob \InPos` or a
    /// `WaitTime \InPos` (or since the start).
    stopped: bool,
    /// The module running.
    module: String,
    /// The last `! layer N of M` comment's N and M.
    layer: (usize, usize),
}

impl<'a> State<'a> {
    /// Runs a module's one routine.
    fn routine(&mut self, m: &Module) -> Result<(), String> {
        let Some(r) = m.routines.first() else {
            return Err(format!("{}: no routine", m.file));
        };
        let saved = std::mem::replace(&mut self.module, m.name.clone());
        for l in &r.body {
            match l {
                Line::Note(line, text) => self.note(*line, text).map_err(|e| e.at(&m.file))?,
                Line::Instr(i) => self.instr(i).map_err(|e| e.at(&m.file))?,
            }
        }
        if let Some(t) = self.pending.first() {
            let e = format!(
                "TriggIO {} is not followed by a TriggL that uses it",
                t.name
            );
            return Err(E::At(t.line, e).at(&m.file));
        }
        self.module = saved;
        Ok(())
    }

    /// A whole-line comment: `! layer N of M: …` numbers the layers 1, 2, …
    /// of one M.
    fn note(&mut self, line: usize, text: &str) -> R<()> {
        let Some((n, of)) = layer_note(text) else {
            return Ok(());
        };
        let (last, total) = self.layer;
        if n != last + 1 || (last > 0 && of != total) || n > of {
            return err(
                line,
                format!(
                    "`layer {n} of {of}` after layer {last} of {total}: the layer comments \
                     number the layers 1, 2, … of one total"
                ),
            );
        }
        self.layer = (n, of);
        let motions = self.trace.motions.len();
        self.trace.layers.push((motions, text.to_string()));
        Ok(())
    }

    fn in_main(&self) -> bool {
        self.module == self.main
    }

    fn instr(&mut self, i: &Instr) -> R<()> {
        if let Some(t) = self.pending.first() {
            if i.name != "TriggIO" && i.name != "TriggL" {
                return err(
                    t.line,
                    format!(
                        "TriggIO {} is not followed by a TriggL that uses it (line {} is a {})",
                        t.name, i.line, i.name
                    ),
                );
            }
        }
        let args = positional(&i.args);
        match i.name.as_str() {
            "ConfJ" | "ConfL" => self.conf(i),
            "SetDO" | "SetAO" => self.set(i, &args),
            "MoveAbsJ" => self.move_abs_j(i, &args),
            "MoveJ" | "MoveL" => self.move_jl(i, &args),
            "TriggIO" => self.trigg_io(i, &args),
            "TriggL" => self.trigg_l(i, &args),
            "WaitTime" | "WaitRob" => self.wait(i, &args),
            _ if i.args.is_empty() => self.call(i),
            other => err(
                i.line,
                format!("`{other}` is not an instruction lmdc writes"),
            ),
        }
    }

    fn call(&mut self, i: &Instr) -> R<()> {
        check_name(&i.name, i.line)?;
        if !self.in_main() {
            return err(
                i.line,
                format!("only main calls routines, {} calls {}", self.module, i.name),
            );
        }
        let modules = self.modules;
        let Some(m) = modules.get(&i.name).filter(|_| i.name != self.main) else {
            return err(
                i.line,
                format!(
                    "main calls {0}, but no module {0} ({0}.mod) was given",
                    i.name
                ),
            );
        };
        self.trace.calls.push(i.name.clone());
        self.routine(m).map_err(E::Done)
    }

    fn conf(&mut self, i: &Instr) -> R<()> {
        let on = want(i, &["\\On", "\\Off"])? == 0;
        if !self.in_main() || !self.trace.motions.is_empty() {
            return err(
                i.line,
                format!("{} is set in main, before the first motion", i.name),
            );
        }
        let slot = if i.name == "ConfJ" {
            &mut self.trace.conf_j
        } else {
            &mut self.trace.conf_l
        };
        if slot.is_some() {
            return err(i.line, format!("{} is set twice", i.name));
        }
        *slot = Some(on);
        Ok(())
    }

    /// A declared datum of type `ty` named by `e`.
    fn lookup(&self, e: &Expr, ty: &str) -> R<(&'a str, &'a Value)> {
        let data: &'a BTreeMap<String, Data> = self.data;
        let X::Name(n) = &e.kind else {
            return err(
                e.line,
                format!("want the name of a {ty}, got `{}`", show(e)),
            );
        };
        check_name(n, e.line)?;
        let Some((name, d)) = data.get_key_value(n.as_str()) else {
            if let Some(k) = data.keys().find(|k| k.eq_ignore_ascii_case(n)) {
                return err(
                    e.line,
                    format!("`{n}` is declared `{k}`: lmdc writes names as declared"),
                );
            }
            return err(e.line, format!("`{n}` is not declared (want a {ty})"));
        };
        if d.ty != ty {
            return err(e.line, format!("`{n}` is a {}, not a {ty}", d.ty));
        }
        Ok((name.as_str(), &d.value))
    }
}

/// The end of every motion: `<speed>, <zone>, lmd_tool \WObj:=lmd_wobj`.
struct Tail<'e> {
    speed: &'e Expr,
    zone: &'e Expr,
    tool: &'e Expr,
}

impl State<'_> {
    fn move_abs_j(&mut self, i: &Instr, args: &[&Expr]) -> R<()> {
        want(i, &["E \\NoEOffs, E, E, E \\WObj:=E"])?;
        if !self.in_main() {
            return err(
                i.line,
                format!(
                    "MoveAbsJ in the motion module {}: only main goes home",
                    self.module
                ),
            );
        }
        let (_, Value::Joint(j)) = self.lookup(args[0], "jointtarget")? else {
            return err(i.line, "not a jointtarget");
        };
        let j = j.clone();
        self.trace.home.get_or_insert_with(|| j.clone());
        let tail = Tail {
            speed: args[1],
            zone: args[2],
            tool: args[3],
        };
        self.motion(i, Kind::MoveAbsJ, Target::Joints(j), &tail, Vec::new())
    }

    fn move_jl(&mut self, i: &Instr, args: &[&Expr]) -> R<()> {
        want(i, &["E, E, E, E \\WObj:=E"])?;
        let kind = if i.name == "MoveJ" {
            Kind::MoveJ
        } else {
            Kind::MoveL
        };
        let tail = Tail {
            speed: args[1],
            zone: args[2],
            tool: args[3],
        };
        let target = Target::Pose(robtarget(args[0])?);
        self.motion(i, kind, target, &tail, Vec::new())
    }

    fn trigg_l(&mut self, i: &Instr, args: &[&Expr]) -> R<()> {
        let forms: Vec<String> = (1..=8)
            .map(|n| {
                let more: String = (2..=n).map(|k| format!(" \\T{k}:=E")).collect();
                format!("E, E, E{more}, E, E \\WObj:=E")
            })
            .collect();
        let got = shape(&i.args);
        let Some(n) = forms.iter().position(|f| *f == got) else {
            // The message shows the forms with one and two triggers.
            return want(i, &[forms[0].as_str(), forms[1].as_str()]).map(|_| ());
        };
        let mut names = vec![args[2]];
        for k in 2..=n + 1 {
            names.push(opt(i, &format!("T{k}"))?);
        }
        let mut fired = Vec::new();
        for e in names {
            let (name, _) = self.lookup(e, "triggdata")?;
            let Some(k) = self.pending.iter().position(|t| t.name == name) else {
                return err(
                    e.line,
                    format!("TriggL fires {name}, which no TriggIO set since the previous motion"),
                );
            };
            fired.push(self.pending.remove(k));
        }
        if let Some(t) = self.pending.first() {
            return err(
                t.line,
                format!(
                    "TriggIO {} is not used by the TriggL that follows it (line {})",
                    t.name, i.line
                ),
            );
        }
        let tail = Tail {
            speed: args[1],
            zone: args[3],
            tool: args[4],
        };
        let target = Target::Pose(robtarget(args[0])?);
        self.motion(i, Kind::TriggL, target, &tail, fired)
    }

    /// `TriggIO <name>, 0 [\Start] \DOp:=do<laser>, 0|1;` or the same with
    /// `\AOp:=ao<power>, <fraction>`: `lmd_on`, `lmd_off`, `lmd_power` with
    /// `\Start`, `lmd_on_end`, `lmd_off_end`, `lmd_power_end` without.
    fn trigg_io(&mut self, i: &Instr, args: &[&Expr]) -> R<()> {
        let form = want(
            i,
            &[
                "E, E \\Start \\DOp:=E, E",
                "E, E \\DOp:=E, E",
                "E, E \\Start \\AOp:=E, E",
                "E, E \\AOp:=E, E",
            ],
        )?;
        let (name, _) = self.lookup(args[0], "triggdata")?;
        let name = name.to_string();
        if num(args[1])? != 0.0 {
            return err(i.line, "a trigger's distance is 0");
        }
        let (sig, want_no) = if form < 2 {
            ("DOp", &self.laser_no)
        } else {
            ("AOp", &self.power_no)
        };
        let n = signal(opt(i, sig)?, form >= 2, self.data)?;
        if &n != want_no {
            return err(
                i.line,
                format!("a trigger switches the laser's {want_no}, not {n}"),
            );
        }
        let set = if form < 2 {
            Set::Laser(digital(args[2])?)
        } else {
            Set::Power(analog(args[2])?)
        };
        let start = form % 2 == 0;
        let meant = match set {
            Set::Laser(true) => "lmd_on",
            Set::Laser(false) => "lmd_off",
            Set::Power(_) => "lmd_power",
        };
        let meant = if start {
            meant.to_string()
        } else {
            format!("{meant}_end")
        };
        if name != meant {
            let at = if start { "starts" } else { "ends" };
            return err(
                i.line,
                format!("this trigger, where its move {at}, is {meant}, not {name}"),
            );
        }
        if self.pending.iter().any(|t| t.name == name) {
            return err(
                i.line,
                format!("TriggIO {name} is set twice before its TriggL"),
            );
        }
        self.pending.push(Trig {
            name,
            line: i.line,
            start,
            set,
        });
        Ok(())
    }
}

impl State<'_> {
    /// Runs a motion: its triggers with `\Start` before, the others after.
    fn motion(
        &mut self,
        i: &Instr,
        kind: Kind,
        target: Target,
        tail: &Tail,
        fired: Vec<Trig>,
    ) -> R<()> {
        self.order(i, kind)?;
        let speed = self.speed(tail.speed, kind)?;
        let zone = self.zone(tail.zone)?;
        let (_, Value::Tool(tool)) = self.lookup(tail.tool, "tooldata")? else {
            return err(i.line, "not a tooldata");
        };
        let (_, Value::Wobj(wobj)) = self.lookup(opt(i, "WObj")?, "wobjdata")? else {
            return err(i.line, "not a wobjdata");
        };
        if self.trace.tool.get_or_insert_with(|| tool.clone()) != tool
            || self.trace.wobj.get_or_insert_with(|| wobj.clone()) != wobj
        {
            return err(i.line, "every motion uses the one tool and work object");
        }
        self.axes(i, &target, !wobj.ufmec.is_empty())?;
        let (start, end): (Vec<Trig>, Vec<Trig>) = fired.into_iter().partition(|t| t.start);
        let switches = start.iter().any(|t| matches!(t.set, Set::Laser(_)));
        if let Some(m) = self
            .trace
            .motions
            .last()
            .filter(|m| switches && m.zone.is_some())
        {
            return err(
                i.line,
                format!(
                    "the laser switches where this move starts, but the move before \
                     ({}.mod:{}) is blended: it ends fine, so the switch is at its point",
                    m.module, m.line
                ),
            );
        }
        self.fire(&start)?;
        if self.laser && matches!(kind, Kind::MoveAbsJ | Kind::MoveJ) {
            return err(i.line, format!("{kind:?} with the laser on"));
        }
        let n = self.trace.motions.len();
        self.trace.events.push(Event::Motion(n));
        *self
            .trace
            .moves_per_module
            .entry(self.module.clone())
            .or_default() += 1;
        self.trace.motions.push(Motion {
            kind,
            target,
            speed,
            zone,
            laser: self.laser,
            switch_at_end: end.iter().any(|t| matches!(t.set, Set::Laser(_))),
            power: self.power,
            module: self.module.clone(),
            line: i.line,
        });
        self.stopped = false;
        self.fire(&end)
    }

    /// MoveAbsJ home first, MoveJ only right after it, then MoveL/TriggL;
    /// the configuration monitoring set before.
    fn order(&self, i: &Instr, kind: Kind) -> R<()> {
        let prev = self.trace.motions.last().map(|m| m.kind);
        let bad = match (kind, prev) {
            (Kind::MoveAbsJ, _) | (Kind::MoveJ, Some(Kind::MoveAbsJ)) => None,
            (Kind::MoveJ, _) => Some("MoveJ is only the move from home, right after MoveAbsJ"),
            (_, Some(Kind::MoveAbsJ)) => Some("the move from home is a MoveJ"),
            (_, None) => Some("the first motion is the MoveAbsJ home"),
            _ => None,
        };
        if let Some(b) = bad {
            return err(i.line, b);
        }
        if self.trace.conf_j.is_none() || self.trace.conf_l.is_none() {
            return err(i.line, "main sets ConfJ and ConfL before the first motion");
        }
        Ok(())
    }

    /// A motion's `v_tcp`: declared speeddata; for the joint moves also
    /// RAPID's `v<n>`, for the linear ones also a speeddata in place.
    fn speed(&self, e: &Expr, kind: Kind) -> R<f64> {
        let joint = matches!(kind, Kind::MoveAbsJ | Kind::MoveJ);
        match &e.kind {
            X::Agg(_) if !joint => return speeddata(e),
            X::Agg(_) => return err(e.line, "a joint move runs at v200 or a declared speed"),
            X::Name(n) if joint => {
                let v = n.strip_prefix('v').and_then(|v| v.parse::<u32>().ok());
                let known = |v: &u32| PREDEFINED_SPEEDS.contains(v) && format!("v{v}") == *n;
                if let Some(v) = v.filter(known) {
                    return Ok(f64::from(v));
                }
            }
            _ => {}
        }
        match self.lookup(e, "speeddata")? {
            (_, Value::Speed(v)) => Ok(*v),
            _ => err(e.line, "not a speeddata"),
        }
    }

    /// `None` for `fine`, else the declared zonedata's `pzone_tcp`.
    fn zone(&self, e: &Expr) -> R<Option<f64>> {
        if matches!(&e.kind, X::Name(n) if n == "fine") {
            return Ok(None);
        }
        match self.lookup(e, "zonedata")? {
            (_, Value::Zone(z)) => Ok(Some(*z)),
            _ => err(e.line, "not a zonedata"),
        }
    }

    /// External axes: eax_a and eax_b are the positioner's where the work
    /// object moves with one, the rest `9E+09`; confdata zero where no arm
    /// is declared (`ConfJ \\Off`).
    fn axes(&self, i: &Instr, target: &Target, positioner: bool) -> R<()> {
        let (extax, conf) = match target {
            Target::Pose(p) => (&p.extax, Some(p.conf)),
            Target::Joints(j) => (&j.extax, None),
        };
        if extax[2..].iter().any(Option::is_some) {
            return err(i.line, "external axes eax_c … eax_f are 9E+09");
        }
        if extax[..2].iter().any(|x| x.is_some() != positioner) {
            let why = if positioner {
                "the work object moves with a positioner: eax_a and eax_b hold its axes"
            } else {
                "no positioner: eax_a and eax_b are 9E+09"
            };
            return err(i.line, why);
        }
        if self.trace.conf_j == Some(false) && conf.is_some_and(|c| c != [0; 4]) {
            return err(
                i.line,
                "under ConfJ \\Off (no arm declared) the confdata is [0,0,0,0]",
            );
        }
        Ok(())
    }

    /// Switches what triggers set, refusing a laser switched to the state it has.
    fn fire(&mut self, ts: &[Trig]) -> R<()> {
        let (mut laser, mut power) = (false, false);
        for t in ts {
            match t.set {
                Set::Laser(on) => {
                    if std::mem::replace(&mut laser, true) {
                        return err(t.line, "two triggers switch the laser at one place");
                    }
                    if on == self.laser {
                        let state = if on { "on" } else { "off" };
                        return err(
                            t.line,
                            format!(
                                "TriggIO {} switches the laser {state}, and it is {state} already",
                                t.name
                            ),
                        );
                    }
                    self.laser = on;
                }
                Set::Power(x) => {
                    if std::mem::replace(&mut power, true) {
                        return err(t.line, "two triggers set the power at one place");
                    }
                    self.power = x;
                }
            }
        }
        Ok(())
    }

    /// `SetDO`/`SetAO`: where the robot stands; the laser's own signals only
    /// off and only in main, the others with the laser off and, in a motion
    /// module, a comment saying what they switch.
    fn set(&mut self, i: &Instr, args: &[&Expr]) -> R<()> {
        want(i, &["E, E"])?;
        let dig = i.name == "SetDO";
        let (n, value) = if dig {
            (
                signal(args[0], false, self.data)?,
                f64::from(u8::from(digital(args[1])?)),
            )
        } else {
            (signal(args[0], true, self.data)?, analog(args[1])?)
        };
        if !self.stopped {
            return err(
                i.line,
                format!(
                    "{} while the robot may move: a WaitRob \\InPos comes first",
                    i.name
                ),
            );
        }
        let ours = if dig {
            n == self.laser_no
        } else {
            n == self.power_no
        };
        if ours {
            if !self.in_main() {
                return err(
                    i.line,
                    "in a motion module the laser and its power switch only by TriggIO",
                );
            }
            if value != 0.0 {
                return err(i.line, "main only switches the laser and its power off");
            }
            if dig {
                self.laser = false;
            } else {
                self.power = 0.0;
            }
        } else if self.laser {
            return err(i.line, format!("{} with the laser on", i.name));
        } else if !self.in_main() && i.comment.is_none() {
            return err(
                i.line,
                format!(
                    "{} in a motion module has a `!` comment saying what it switches",
                    i.name
                ),
            );
        }
        self.trace.events.push(if dig {
            Event::SetDO(n, value == 1.0)
        } else {
            Event::SetAO(n, value)
        });
        Ok(())
    }

    /// `WaitTime \InPos, t` (a dwell) and `WaitRob \InPos`: the robot stops,
    /// after a fine point, with the laser off.
    fn wait(&mut self, i: &Instr, args: &[&Expr]) -> R<()> {
        let dwell = if i.name == "WaitRob" {
            want(i, &["\\InPos"])?;
            None
        } else {
            want(i, &["\\InPos, E"])?;
            let t = num(args[0])?;
            if t < 0.0 {
                return err(i.line, format!("a dwell of {t} s"));
            }
            Some(t)
        };
        if self.laser {
            return err(i.line, format!("{} with the laser on", i.name));
        }
        if let Some(m) = self.trace.motions.last().filter(|_| !self.stopped) {
            if m.zone.is_some() {
                return err(
                    i.line,
                    format!(
                        "{} after a blended motion ({}.mod:{}): the robot stops there anyway, \
                         with a corner path failure (50024); the motion before a wait ends fine",
                        i.name, m.module, m.line
                    ),
                );
            }
        }
        self.stopped = true;
        match dwell {
            Some(t) => {
                self.trace.dwells.push((self.trace.motions.len(), t));
                self.trace.events.push(Event::Dwell(t));
            }
            None => self.trace.events.push(Event::WaitRob),
        }
        Ok(())
    }
}
