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
#![allow(dead_code)]

use std::collections::{BTreeMap, HashMap, VecDeque};

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

#[derive(Clone, Debug, PartialEq)]
enum Value {
    Int(i64),
    Real(f64),
    Bool(bool),
    Enum(String),
    Struct(BTreeMap<String, f64>),
    Array(Vec<Value>),
    /// Declared, never assigned: reading it is KRL's "value not assigned".
    Unset(Ty),
    /// A system table (`TOOL_DATA[n]`) whose value the test does not know.
    Opaque,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Ty {
    Int,
    Real,
    Bool,
    Pos,
}

impl Value {
    fn num(&self) -> Result<f64, String> {
        match self {
            Value::Int(i) => Ok(*i as f64),
            Value::Real(r) => Ok(*r),
            Value::Unset(_) => Err("value not assigned".into()),
            v => Err(format!("{v:?} is not a number")),
        }
    }

    fn int(&self) -> Result<i64, String> {
        match self {
            Value::Int(i) => Ok(*i),
            Value::Unset(_) => Err("value not assigned".into()),
            v => Err(format!("{v:?} is not an INT")),
        }
    }

    /// `v` stored in a variable that holds `self`'s type: INT ← REAL rounds.
    fn coerce(&self, v: Value) -> Result<Value, String> {
        let ty = match self {
            Value::Int(_) | Value::Unset(Ty::Int) => Ty::Int,
            Value::Real(_) | Value::Unset(Ty::Real) => Ty::Real,
            Value::Bool(_) | Value::Unset(Ty::Bool) => Ty::Bool,
            Value::Struct(_) | Value::Unset(Ty::Pos) => Ty::Pos,
            _ => return Ok(v),
        };
        Ok(match (ty, v) {
            (Ty::Int, Value::Int(i)) => Value::Int(i),
            (Ty::Int, Value::Real(r)) => Value::Int(r.round() as i64),
            (Ty::Real, Value::Int(i)) => Value::Real(i as f64),
            (Ty::Real, Value::Real(r)) => Value::Real(r),
            (Ty::Bool, Value::Bool(b)) => Value::Bool(b),
            (Ty::Pos, Value::Struct(s)) => Value::Struct(s),
            (t, v) => return Err(format!("cannot store {v:?} in a {t:?}")),
        })
    }
}

// ---------------------------------------------------------------- tokens

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Num(String),
    Name(String),
    Enum(String),
    Op(&'static str),
}

fn tokens(s: &str) -> Result<Vec<Tok>, String> {
    let b = s.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let c = b[i] as char;
        if c.is_ascii_whitespace() {
            i += 1;
        } else if c.is_ascii_digit() || (c == '.' && i + 1 < b.len() && b[i + 1].is_ascii_digit()) {
            let start = i;
            while i < b.len() && (b[i].is_ascii_digit() || b[i] == b'.') {
                i += 1;
            }
            out.push(Tok::Num(s[start..i].to_string()));
        } else if c.is_ascii_alphabetic() || c == '$' || c == '_' || c == '#' {
            let start = i;
            i += 1;
            while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_') {
                i += 1;
            }
            let w = s[start..i].to_string();
            out.push(if let Some(e) = w.strip_prefix('#') {
                Tok::Enum(e.to_string())
            } else {
                Tok::Name(w.to_ascii_uppercase())
            });
        } else {
            let two = s.get(i..i + 2).unwrap_or("");
            let op: &'static str = match two {
                "<=" => "<=",
                ">=" => ">=",
                "==" => "==",
                "<>" => "<>",
                _ => match c {
                    '+' => "+",
                    '-' => "-",
                    '*' => "*",
                    '/' => "/",
                    '(' => "(",
                    ')' => ")",
                    '[' => "[",
                    ']' => "]",
                    '{' => "{",
                    '}' => "}",
                    ',' => ",",
                    '<' => "<",
                    '>' => ">",
                    '=' => "=",
                    ':' => ":",
                    '.' => ".",
                    _ => return Err(format!("unexpected character {c:?}")),
                },
            };
            i += op.len();
            out.push(Tok::Op(op));
        }
    }
    Ok(out)
}

// ---------------------------------------------------------------- syntax

#[derive(Clone, Debug)]
enum Expr {
    Num(Value),
    Bool(bool),
    Enum(String),
    /// A variable, indices, a member.
    Var(Place),
    Agg(Vec<(String, Expr)>),
    Neg(Box<Expr>),
    Not(Box<Expr>),
    Bin(&'static str, Box<Expr>, Box<Expr>),
    Sqrt(Box<Expr>),
}

#[derive(Clone, Debug)]
struct Place {
    name: String,
    index: Option<Box<Expr>>,
    member: Option<String>,
}

struct P<'t> {
    t: &'t [Tok],
    i: usize,
}

impl P<'_> {
    fn peek(&self) -> Option<&Tok> {
        self.t.get(self.i)
    }
    fn op(&mut self, o: &str) -> bool {
        if self.peek() == Some(&Tok::Op(leak(o))) {
            self.i += 1;
            true
        } else {
            false
        }
    }
    fn word(&mut self, w: &str) -> bool {
        if matches!(self.peek(), Some(Tok::Name(n)) if n == w) {
            self.i += 1;
            true
        } else {
            false
        }
    }
    fn expect(&mut self, o: &str) -> Result<(), String> {
        if self.op(o) {
            Ok(())
        } else {
            Err(format!("want `{o}` at {:?}", self.peek()))
        }
    }
    fn done(&self) -> Result<(), String> {
        match self.peek() {
            None => Ok(()),
            Some(t) => Err(format!("unexpected {t:?}")),
        }
    }
    fn name(&mut self) -> Result<String, String> {
        match self.peek().cloned() {
            Some(Tok::Name(n)) => {
                self.i += 1;
                Ok(n)
            }
            t => Err(format!("want a name, got {t:?}")),
        }
    }

    fn expr(&mut self) -> Result<Expr, String> {
        let mut l = self.and()?;
        while self.word("OR") {
            l = Expr::Bin("OR", Box::new(l), Box::new(self.and()?));
        }
        Ok(l)
    }
    fn and(&mut self) -> Result<Expr, String> {
        let mut l = self.cmp()?;
        while self.word("AND") {
            l = Expr::Bin("AND", Box::new(l), Box::new(self.cmp()?));
        }
        Ok(l)
    }
    fn cmp(&mut self) -> Result<Expr, String> {
        let l = self.sum()?;
        for o in ["<=", ">=", "==", "<>", "<", ">"] {
            if self.op(o) {
                return Ok(Expr::Bin(leak(o), Box::new(l), Box::new(self.sum()?)));
            }
        }
        Ok(l)
    }
    fn sum(&mut self) -> Result<Expr, String> {
        let mut l = self.product()?;
        loop {
            if self.op("+") {
                l = Expr::Bin("+", Box::new(l), Box::new(self.product()?));
            } else if self.op("-") {
                l = Expr::Bin("-", Box::new(l), Box::new(self.product()?));
            } else {
                return Ok(l);
            }
        }
    }
    fn product(&mut self) -> Result<Expr, String> {
        let mut l = self.unary()?;
        loop {
            if self.op("*") {
                l = Expr::Bin("*", Box::new(l), Box::new(self.unary()?));
            } else if self.op("/") {
                l = Expr::Bin("/", Box::new(l), Box::new(self.unary()?));
            } else {
                return Ok(l);
            }
        }
    }
    fn unary(&mut self) -> Result<Expr, String> {
        if self.op("-") {
            return Ok(Expr::Neg(Box::new(self.unary()?)));
        }
        if self.op("+") {
            return self.unary();
        }
        if self.word("NOT") {
            return Ok(Expr::Not(Box::new(self.unary()?)));
        }
        self.atom()
    }
    fn atom(&mut self) -> Result<Expr, String> {
        match self.peek().cloned() {
            Some(Tok::Num(n)) => {
                self.i += 1;
                Ok(Expr::Num(number(&n)?))
            }
            Some(Tok::Enum(e)) => {
                self.i += 1;
                Ok(Expr::Enum(e))
            }
            Some(Tok::Op("(")) => {
                self.i += 1;
                let e = self.expr()?;
                self.expect(")")?;
                Ok(e)
            }
            Some(Tok::Op("{")) => {
                self.i += 1;
                let mut parts = Vec::new();
                loop {
                    let k = self.name()?;
                    parts.push((k, self.expr()?));
                    if self.op("}") {
                        return Ok(Expr::Agg(parts));
                    }
                    self.expect(",")?;
                }
            }
            Some(Tok::Name(n)) if n == "TRUE" || n == "FALSE" => {
                self.i += 1;
                Ok(Expr::Bool(n == "TRUE"))
            }
            Some(Tok::Name(n)) if n == "SQRT" => {
                self.i += 1;
                self.expect("(")?;
                let e = self.expr()?;
                self.expect(")")?;
                Ok(Expr::Sqrt(Box::new(e)))
            }
            Some(Tok::Name(_)) => Ok(Expr::Var(self.place()?)),
            t => Err(format!("want a value, got {t:?}")),
        }
    }
    fn place(&mut self) -> Result<Place, String> {
        let name = self.name()?;
        let index = if self.op("[") {
            let e = self.expr()?;
            self.expect("]")?;
            Some(Box::new(e))
        } else {
            None
        };
        let member = if self.op(".") {
            Some(self.name()?)
        } else {
            None
        };
        Ok(Place {
            name,
            index,
            member,
        })
    }
}

/// The interned operator text (`Tok::Op` holds `&'static str`).
fn leak(o: &str) -> &'static str {
    for k in [
        "<=", ">=", "==", "<>", "+", "-", "*", "/", "(", ")", "[", "]", "{", "}", ",", "<", ">",
        "=", ":", ".",
    ] {
        if k == o {
            return k;
        }
    }
    panic!("operator {o}")
}

/// A KRL number: digits with a `.` is REAL, else INT. No exponent, NaN or inf.
fn number(s: &str) -> Result<Value, String> {
    if !s.bytes().all(|b| b.is_ascii_digit() || b == b'.') || s.matches('.').count() > 1 {
        return Err(format!("`{s}` is not a KRL number"));
    }
    if s.contains('.') {
        s.parse().map(Value::Real).map_err(|e| format!("{s}: {e}"))
    } else {
        s.parse().map(Value::Int).map_err(|e| format!("{s}: {e}"))
    }
}

#[derive(Clone, Debug)]
enum Action {
    Assign(Place, Expr),
    Call(String, Vec<Expr>),
}

#[derive(Clone, Debug)]
enum Stmt {
    Do(Action),
    For(String, Expr, Expr, Vec<Stmt>),
    If(Expr, Vec<Stmt>, Vec<Stmt>),
    Lin(Expr, bool),
    Ptp(Expr),
    Trigger {
        distance: i64,
        delay: f64,
        action: Action,
    },
    Wait(Expr),
    /// `BAS(…)`: the KUKA package's setup, nothing this interpreter models.
    Bas,
    Decl(Ty, Vec<String>),
}

#[derive(Clone, Debug)]
struct Routine {
    params: Vec<String>,
    body: Vec<Stmt>,
    file: String,
}

fn ty(name: &str) -> Result<Ty, String> {
    match name {
        "INT" => Ok(Ty::Int),
        "REAL" => Ok(Ty::Real),
        "BOOL" => Ok(Ty::Bool),
        "POS" => Ok(Ty::Pos),
        t => Err(format!("type {t} is not in the subset")),
    }
}

/// Lines without comments, header lines and empty ones: (line number, text).
fn code_lines(text: &str) -> Vec<(usize, String)> {
    text.lines()
        .enumerate()
        .filter_map(|(i, l)| {
            let l = l.split(';').next().unwrap_or("").trim();
            (!l.is_empty() && !l.starts_with('&')).then(|| (i + 1, l.to_string()))
        })
        .collect()
}

fn action(t: &[Tok]) -> Result<Action, String> {
    let mut p = P { t, i: 0 };
    let place = p.place()?;
    if p.op("=") {
        let e = p.expr()?;
        p.done()?;
        return Ok(Action::Assign(place, e));
    }
    if place.index.is_none() && place.member.is_none() && p.op("(") {
        let mut args = Vec::new();
        if !p.op(")") {
            loop {
                args.push(p.expr()?);
                if p.op(")") {
                    break;
                }
                p.expect(",")?;
            }
        }
        p.done()?;
        return Ok(Action::Call(place.name, args));
    }
    Err("neither an assignment nor a call".into())
}

/// Parses the statements of `lines` up to one of `ends` (returned).
fn block(
    lines: &[(usize, String)],
    at: &mut usize,
    ends: &[&str],
) -> Result<(Vec<Stmt>, String), String> {
    let mut out = Vec::new();
    while *at < lines.len() {
        let (n, l) = &lines[*at];
        *at += 1;
        let up = l.to_ascii_uppercase();
        let first = up.split_whitespace().next().unwrap_or("");
        if ends.contains(&first) {
            return Ok((out, first.to_string()));
        }
        let e = |m: String| format!("line {n}: {m} in `{l}`");
        let t = tokens(l).map_err(e)?;
        let s = match first {
            "FOR" => {
                let mut p = P { t: &t[1..], i: 0 };
                let v = p.name().map_err(e)?;
                p.expect("=").map_err(e)?;
                let a = p.expr().map_err(e)?;
                if !p.word("TO") {
                    return Err(e("FOR without TO".into()));
                }
                let b = p.expr().map_err(e)?;
                p.done().map_err(e)?;
                let (body, _) = block(lines, at, &["ENDFOR"])?;
                Stmt::For(v, a, b, body)
            }
            "IF" => {
                let mut p = P { t: &t[1..], i: 0 };
                let c = p.expr().map_err(e)?;
                if !p.word("THEN") {
                    return Err(e("IF without THEN".into()));
                }
                p.done().map_err(e)?;
                let (yes, end) = block(lines, at, &["ELSE", "ENDIF"])?;
                let no = if end == "ELSE" {
                    block(lines, at, &["ENDIF"])?.0
                } else {
                    Vec::new()
                };
                Stmt::If(c, yes, no)
            }
            "LIN" | "PTP" => {
                let mut p = P { t: &t[1..], i: 0 };
                let target = p.expr().map_err(e)?;
                let approx = p.word("C_DIS") || p.word("C_PTP");
                p.done().map_err(e)?;
                if first == "LIN" {
                    Stmt::Lin(target, approx)
                } else {
                    Stmt::Ptp(target)
                }
            }
            "TRIGGER" => {
                let mut p = P { t: &t[1..], i: 0 };
                let mut ok = p.word("WHEN") && p.word("DISTANCE") && p.op("=");
                let distance = match p.peek() {
                    Some(Tok::Num(d)) if ok => d.parse::<i64>().map_err(|x| e(x.to_string()))?,
                    _ => return Err(e("TRIGGER WHEN DISTANCE=<0|1>".into())),
                };
                p.i += 1;
                ok = p.word("DELAY") && p.op("=");
                let neg = p.op("-");
                let delay = match (ok, p.peek()) {
                    (true, Some(Tok::Num(d))) => d.parse::<f64>().map_err(|x| e(x.to_string()))?,
                    _ => return Err(e("DELAY=<ms>".into())),
                };
                p.i += 1;
                if !p.word("DO") {
                    return Err(e("TRIGGER without DO".into()));
                }
                // The action runs to PRIO=…, which only a call has.
                let rest = &t[1 + p.i..];
                let prio = rest
                    .iter()
                    .position(|x| *x == Tok::Name("PRIO".into()))
                    .unwrap_or(rest.len());
                let a = action(&rest[..prio]).map_err(e)?;
                if matches!(a, Action::Call(..)) != (prio < rest.len()) {
                    return Err(e("a TRIGGER calls with PRIO, assigns without".into()));
                }
                if !(distance == 0 || distance == 1) {
                    return Err(e("DISTANCE is 0 or 1".into()));
                }
                Stmt::Trigger {
                    distance,
                    delay: if neg { -delay } else { delay },
                    action: a,
                }
            }
            "WAIT" => {
                let mut p = P { t: &t[1..], i: 0 };
                if !p.word("SEC") {
                    return Err(e("WAIT without SEC".into()));
                }
                let x = p.expr().map_err(e)?;
                p.done().map_err(e)?;
                Stmt::Wait(x)
            }
            "DECL" => {
                let mut p = P { t: &t[1..], i: 0 };
                let k = ty(&p.name().map_err(e)?).map_err(e)?;
                let mut names = vec![p.name().map_err(e)?];
                while p.op(",") {
                    names.push(p.name().map_err(e)?);
                }
                p.done().map_err(e)?;
                Stmt::Decl(k, names)
            }
            _ if up.starts_with("BAS(") => Stmt::Bas,
            _ => Stmt::Do(action(&t).map_err(e)?),
        };
        out.push(s);
    }
    Err(format!("no {ends:?}"))
}

/// The routines of a `.src` file.
fn routines(file: &str, text: &str) -> Result<Vec<(String, Routine)>, String> {
    let lines = code_lines(text);
    let mut at = 0;
    let mut out = Vec::new();
    while at < lines.len() {
        let (n, l) = &lines[at];
        at += 1;
        let e = |m: String| format!("{file}:{n}: {m} in `{l}`");
        let t = tokens(l).map_err(e)?;
        let mut p = P { t: &t, i: 0 };
        if !p.word("DEF") {
            return Err(e("want DEF".into()));
        }
        let name = p.name().map_err(e)?;
        p.expect("(").map_err(e)?;
        let mut params = Vec::new();
        while !p.op(")") {
            params.push(p.name().map_err(e)?);
            p.expect(":").map_err(e)?;
            if !p.word("IN") {
                return Err(e("only IN parameters".into()));
            }
            p.op(",");
        }
        p.done().map_err(e)?;
        let (body, _) = block(&lines, &mut at, &["END"]).map_err(|m| format!("{file}: {m}"))?;
        out.push((
            name,
            Routine {
                params,
                body,
                file: file.to_string(),
            },
        ));
    }
    Ok(out)
}

/// The variables a `.dat` declares, with their values.
fn data(file: &str, text: &str) -> Result<HashMap<String, Value>, String> {
    let mut vars = HashMap::new();
    let lines = code_lines(text);
    let mut it = lines.iter();
    match it.next() {
        Some((_, l)) if l.to_ascii_uppercase().starts_with("DEFDAT ") => {}
        other => return Err(format!("{file}: want DEFDAT, got {other:?}")),
    }
    let mut ended = false;
    for (n, l) in it {
        let e = |m: String| format!("{file}:{n}: {m} in `{l}`");
        if ended {
            return Err(e("text after ENDDAT".into()));
        }
        if l.eq_ignore_ascii_case("ENDDAT") {
            ended = true;
            continue;
        }
        let t = tokens(l).map_err(e)?;
        let mut p = P { t: &t, i: 0 };
        if p.word("DECL") {
            let k = ty(&p.name().map_err(e)?).map_err(e)?;
            let name = p.name().map_err(e)?;
            if p.op("[") {
                let size = match p.peek() {
                    Some(Tok::Num(s)) => s.parse::<usize>().map_err(|x| e(x.to_string()))?,
                    _ => return Err(e("array size".into())),
                };
                p.i += 1;
                p.expect("]").map_err(e)?;
                p.done().map_err(e)?;
                vars.insert(name, Value::Array(vec![Value::Unset(k); size]));
            } else {
                let v = if p.op("=") {
                    let x = p.expr().map_err(e)?;
                    let v = eval_const(&x).map_err(e)?;
                    Value::Unset(k).coerce(v).map_err(e)?
                } else {
                    Value::Unset(k)
                };
                p.done().map_err(e)?;
                vars.insert(name, v);
            }
        } else {
            // `NAME[i]=value`: an array element's initial value.
            let place = p.place().map_err(e)?;
            p.expect("=").map_err(e)?;
            let x = p.expr().map_err(e)?;
            p.done().map_err(e)?;
            let v = eval_const(&x).map_err(e)?;
            let Some(Value::Array(a)) = vars.get_mut(&place.name) else {
                return Err(e("not a declared array".into()));
            };
            let i = match place.index.as_deref().map(eval_const) {
                Some(Ok(Value::Int(i))) if i >= 1 && (i as usize) <= a.len() => i as usize - 1,
                _ => return Err(e("index".into())),
            };
            a[i] = a[i].coerce(v).map_err(e)?;
        }
    }
    if !ended {
        return Err(format!("{file}: no ENDDAT"));
    }
    Ok(vars)
}

fn eval_const(x: &Expr) -> Result<Value, String> {
    match x {
        Expr::Num(v) => Ok(v.clone()),
        Expr::Bool(b) => Ok(Value::Bool(*b)),
        Expr::Neg(x) => match eval_const(x)? {
            Value::Int(i) => Ok(Value::Int(-i)),
            Value::Real(r) => Ok(Value::Real(-r)),
            v => Err(format!("-{v:?}")),
        },
        Expr::Agg(parts) => {
            let mut s = BTreeMap::new();
            for (k, x) in parts {
                s.insert(k.clone(), eval_const(x)?.num()?);
            }
            Ok(Value::Struct(s))
        }
        x => Err(format!("{x:?} is not a constant")),
    }
}

// ---------------------------------------------------------------- running

struct Planned {
    pos: [f64; 3],
    abc: [f64; 3],
    speed: f64,
    approximated: bool,
    module: String,
    triggers: Vec<(i64, f64, Action, Frame)>,
}

/// The variables an action sees: the routine's locals and its module's data.
#[derive(Clone)]
struct Frame {
    module: String,
    locals: HashMap<String, Value>,
    routine: String,
    args: Vec<f64>,
}

struct Vm<'a> {
    routines: HashMap<String, Routine>,
    dats: HashMap<String, HashMap<String, Value>>,
    system: HashMap<String, Value>,
    laser_no: i64,
    power_no: i64,
    cfg: Config,
    sensor: &'a mut dyn FnMut(&Read) -> Result<f64, String>,
    queue: VecDeque<Planned>,
    /// Triggers waiting for their delay: motions left, action, frame.
    delayed: Vec<(usize, Action, Frame)>,
    pending: Vec<(i64, f64, Action, Frame)>,
    laser: bool,
    anout: f64,
    run: Run,
    /// Whether the code running is a trigger's (the main run).
    in_trigger: bool,
    depth: usize,
}

/// Runs `main` (a `.src` with its `DEF`), following calls into the other
/// files. `laser`/`power` are the `$OUT`/`$ANOUT` the program switches.
pub fn run(
    files: &Files,
    main: &str,
    laser: u16,
    power: u16,
    cfg: Config,
    sensor: &mut dyn FnMut(&Read) -> Result<f64, String>,
) -> Result<Run, String> {
    let mut vm = Vm {
        routines: HashMap::new(),
        dats: HashMap::new(),
        system: HashMap::new(),
        laser_no: laser as i64,
        power_no: power as i64,
        cfg,
        sensor,
        queue: VecDeque::new(),
        delayed: Vec::new(),
        pending: Vec::new(),
        laser: false,
        anout: 0.0,
        run: Run::default(),
        in_trigger: false,
        depth: 0,
    };
    for (name, text) in files {
        let stem = name[..name.len() - 4].to_ascii_uppercase();
        if name.ends_with(".dat") {
            vm.dats.insert(stem, data(name, text)?);
        } else if name.ends_with(".src") {
            let lins = text
                .lines()
                .filter(|l| l.trim_start().starts_with("LIN "))
                .count();
            vm.run.lin_lines.insert(stem.clone(), lins);
            for (r, body) in routines(name, text)? {
                if vm.routines.insert(r.clone(), body).is_some() {
                    return Err(format!("{r} is defined twice"));
                }
            }
        } else {
            return Err(format!("unexpected file {name}"));
        }
    }
    vm.system.insert("$VEL.CP".into(), Value::Unset(Ty::Real));
    vm.system.insert("$ADVANCE".into(), Value::Int(3));
    let main = main.to_ascii_uppercase();
    vm.call(&main, &[])?;
    vm.stop("the program's end", &main)?;
    vm.run.laser_at_end = vm.laser;
    if !vm.pending.is_empty() {
        return Err("a TRIGGER without a motion after it".into());
    }
    Ok(vm.run)
}

impl Vm<'_> {
    fn call(&mut self, name: &str, args: &[f64]) -> Result<(), String> {
        let r = self
            .routines
            .get(name)
            .cloned()
            .ok_or_else(|| format!("no routine {name}"))?;
        if r.params.len() != args.len() {
            return Err(format!("{name} takes {} arguments", r.params.len()));
        }
        self.depth += 1;
        if self.depth > 8 {
            return Err(format!("{name}: calls nest too deep"));
        }
        let module = r.file[..r.file.len() - 4].to_ascii_uppercase();
        let mut frame = Frame {
            module,
            locals: HashMap::new(),
            routine: name.to_string(),
            args: args.to_vec(),
        };
        for (p, a) in r.params.iter().zip(args) {
            frame.locals.insert(p.clone(), Value::Real(*a));
        }
        self.block(&r.body, &mut frame)
            .map_err(|e| format!("{name}: {e}"))?;
        self.depth -= 1;
        Ok(())
    }

    fn block(&mut self, body: &[Stmt], f: &mut Frame) -> Result<(), String> {
        for s in body {
            self.stmt(s, f)?;
        }
        Ok(())
    }

    fn stmt(&mut self, s: &Stmt, f: &mut Frame) -> Result<(), String> {
        let at = |e: String| format!("{e} in {s:?}");
        match s {
            Stmt::Bas => Ok(()),
            Stmt::Decl(k, names) => {
                for n in names {
                    let v = match f.locals.get(n) {
                        // A parameter: now typed.
                        Some(v) => Value::Unset(*k).coerce(v.clone()).map_err(at)?,
                        None => Value::Unset(*k),
                    };
                    f.locals.insert(n.clone(), v);
                }
                Ok(())
            }
            Stmt::Do(a) => self.act(a, f).map_err(at),
            Stmt::For(v, a, b, body) => {
                let (a, b) = (
                    self.eval(a, f).and_then(|x| x.int()).map_err(at)?,
                    self.eval(b, f).and_then(|x| x.int()).map_err(at)?,
                );
                let mut i = a;
                while i <= b {
                    let place = Place {
                        name: v.clone(),
                        index: None,
                        member: None,
                    };
                    self.assign(&place, Value::Int(i), f).map_err(at)?;
                    self.block(body, f)?;
                    i += 1;
                }
                Ok(())
            }
            Stmt::If(c, yes, no) => match self.eval(c, f).map_err(at)? {
                Value::Bool(true) => self.block(yes, f),
                Value::Bool(false) => self.block(no, f),
                v => Err(at(format!("IF on {v:?}"))),
            },
            Stmt::Lin(target, approx) => {
                let Value::Struct(p) = self.eval(target, f).map_err(at)? else {
                    return Err(at("LIN to a non-POS".into()));
                };
                let get = |k: &str| {
                    p.get(k)
                        .copied()
                        .filter(|v| v.is_finite())
                        .ok_or_else(|| at(format!("no finite {k}")))
                };
                let pos = [get("X")?, get("Y")?, get("Z")?];
                let abc = [get("A")?, get("B")?, get("C")?];
                let v = self
                    .system
                    .get("$VEL.CP")
                    .cloned()
                    .unwrap_or(Value::Unset(Ty::Real))
                    .num()
                    .map_err(|e| at(format!("$VEL.CP: {e}")))?;
                if !(v.is_finite() && v > 0.0) {
                    return Err(at(format!("$VEL.CP = {v}")));
                }
                let triggers = std::mem::take(&mut self.pending);
                self.queue.push_back(Planned {
                    pos,
                    abc,
                    speed: v * 1000.0,
                    approximated: *approx,
                    module: f.module.clone(),
                    triggers,
                });
                let advance = match self.system.get("$ADVANCE") {
                    Some(Value::Int(a)) => (*a).max(0) as usize,
                    _ => 3,
                };
                while self.queue.len() > advance {
                    self.main_step()?;
                }
                Ok(())
            }
            Stmt::Ptp(target) => {
                self.eval(target, f).map_err(at)?;
                if !self.pending.is_empty() {
                    return Err(at("TRIGGER before a PTP".into()));
                }
                self.stop("PTP", &f.module)?;
                if self.laser {
                    return Err(at("PTP with the laser on".into()));
                }
                self.run.ptps += 1;
                Ok(())
            }
            Stmt::Trigger {
                distance,
                delay,
                action,
            } => {
                self.pending
                    .push((*distance, *delay, action.clone(), f.clone()));
                Ok(())
            }
            Stmt::Wait(x) => {
                let t = self.eval(x, f).and_then(|v| v.num()).map_err(at)?;
                if t.is_nan() || t < 0.0 {
                    return Err(at(format!("WAIT SEC {t}")));
                }
                self.stop("WAIT SEC", &f.module)
            }
        }
    }

    /// An advance-run stop: every planned motion runs, every delayed trigger
    /// fires.
    fn stop(&mut self, why: &str, module: &str) -> Result<(), String> {
        if !self.queue.is_empty() || !self.delayed.is_empty() {
            self.run.stops.push(format!("{module}: {why}"));
        }
        while !self.queue.is_empty() {
            self.main_step()?;
        }
        for (_, a, mut fr) in std::mem::take(&mut self.delayed) {
            self.fire(&a, &mut fr)?;
        }
        Ok(())
    }

    /// The main run completes the oldest planned motion.
    fn main_step(&mut self) -> Result<(), String> {
        let Some(m) = self.queue.pop_front() else {
            return Ok(());
        };
        let mut due = Vec::new();
        for d in &mut self.delayed {
            d.0 = d.0.saturating_sub(1);
        }
        self.delayed.retain(|d| {
            if d.0 == 0 {
                due.push((d.1.clone(), d.2.clone()));
                false
            } else {
                true
            }
        });
        for (a, mut fr) in due {
            self.fire(&a, &mut fr)?;
        }
        let mut after = Vec::new();
        for (dist, delay, a, mut fr) in m.triggers {
            if dist == 0 && delay == 0.0 {
                self.fire(&a, &mut fr)?;
            } else if dist == 1 && delay == 0.0 {
                after.push((a, fr));
            } else if dist == 1 && delay > 0.0 {
                self.delayed.push((self.cfg.delay_motions.max(1), a, fr));
            } else {
                return Err(format!(
                    "TRIGGER DISTANCE={dist} DELAY={delay} not modelled"
                ));
            }
        }
        self.run.motions.push(Motion {
            pos: m.pos,
            abc: m.abc,
            speed: m.speed,
            laser: self.laser,
            anout: self.anout,
            approximated: m.approximated,
            module: m.module,
        });
        for (a, mut fr) in after {
            self.fire(&a, &mut fr)?;
        }
        Ok(())
    }

    /// A trigger's action, in the main run.
    fn fire(&mut self, a: &Action, f: &mut Frame) -> Result<(), String> {
        let was = std::mem::replace(&mut self.in_trigger, true);
        let r = self.act(a, f);
        self.in_trigger = was;
        r
    }

    fn act(&mut self, a: &Action, f: &mut Frame) -> Result<(), String> {
        match a {
            Action::Assign(p, x) => {
                let v = self.eval(x, f)?;
                if !self.in_trigger && (p.name == "$OUT" || p.name == "$ANOUT") {
                    self.stop(&format!("{} written in the advance run", p.name), &f.module)?;
                }
                self.assign(p, v, f)
            }
            Action::Call(name, args) => {
                let vals = args
                    .iter()
                    .map(|x| self.eval(x, f).and_then(|v| v.num()))
                    .collect::<Result<Vec<_>, _>>()?;
                if self.in_trigger {
                    self.run
                        .triggered
                        .push((name.clone(), vals.clone(), self.run.motions.len()));
                }
                self.call(name, &vals)
            }
        }
    }

    fn assign(&mut self, p: &Place, v: Value, f: &mut Frame) -> Result<(), String> {
        if p.name.starts_with('$') {
            let key = match &p.member {
                Some(m) => format!("{}.{m}", p.name),
                None => p.name.clone(),
            };
            if let Some(i) = &p.index {
                let i = self.eval(i, f)?.int()?;
                match p.name.as_str() {
                    "$OUT" if i == self.laser_no => {
                        let Value::Bool(b) = v else {
                            return Err("$OUT needs TRUE/FALSE".into());
                        };
                        self.laser = b;
                    }
                    "$ANOUT" if i == self.power_no => {
                        let x = v.num()?;
                        if !(0.0..=1.0).contains(&x) {
                            return Err(format!("$ANOUT = {x} outside 0..1"));
                        }
                        self.anout = x;
                    }
                    _ => return Err(format!("{}[{i}] is not the laser's", p.name)),
                }
                return Ok(());
            }
            self.system.insert(key, v);
            return Ok(());
        }
        let index = match &p.index {
            Some(ix) => Some(self.eval(ix, f)?.int()?),
            None => None,
        };
        let slot = self.slot(&p.name, f)?;
        let slot = match index {
            None => slot,
            Some(i) => {
                let Value::Array(a) = slot else {
                    return Err(format!("{} is not an array", p.name));
                };
                let n = a.len();
                if i < 1 || i as usize > n {
                    return Err(format!("{}[{i}] outside 1..{n}", p.name));
                }
                &mut a[i as usize - 1]
            }
        };
        match &p.member {
            None => {
                *slot = slot.coerce(v)?;
            }
            Some(m) => {
                let x = v.num()?;
                let Value::Struct(s) = slot else {
                    return Err(format!("{}.{m}: not a POS with a value", p.name));
                };
                if !s.contains_key(m) {
                    return Err(format!("no component {m}"));
                }
                s.insert(m.clone(), x);
            }
        }
        Ok(())
    }

    fn slot<'s>(&'s mut self, name: &str, f: &'s mut Frame) -> Result<&'s mut Value, String> {
        if f.locals.contains_key(name) {
            return Ok(f.locals.get_mut(name).unwrap());
        }
        self.dats
            .get_mut(&f.module)
            .and_then(|d| d.get_mut(name))
            .ok_or_else(|| format!("{name} is not declared in {}", f.module))
    }

    fn eval(&mut self, x: &Expr, f: &mut Frame) -> Result<Value, String> {
        Ok(match x {
            Expr::Num(v) => v.clone(),
            Expr::Bool(b) => Value::Bool(*b),
            Expr::Enum(e) => Value::Enum(e.clone()),
            Expr::Agg(parts) => {
                let mut s = BTreeMap::new();
                for (k, x) in parts {
                    s.insert(k.clone(), self.eval(x, f)?.num()?);
                }
                Value::Struct(s)
            }
            Expr::Neg(x) => match self.eval(x, f)? {
                Value::Int(i) => Value::Int(-i),
                Value::Real(r) => Value::Real(-r),
                v => return Err(format!("-{v:?}")),
            },
            Expr::Not(x) => match self.eval(x, f)? {
                Value::Bool(b) => Value::Bool(!b),
                v => return Err(format!("NOT {v:?}")),
            },
            Expr::Sqrt(x) => {
                let v = self.eval(x, f)?.num()?;
                if v.is_nan() || v < 0.0 {
                    return Err(format!("SQRT({v})"));
                }
                Value::Real(v.sqrt())
            }
            Expr::Bin(o, a, b) => {
                let (a, b) = (self.eval(a, f)?, self.eval(b, f)?);
                binary(o, a, b)?
            }
            Expr::Var(p) => self.read(p, f)?,
        })
    }

    fn read(&mut self, p: &Place, f: &mut Frame) -> Result<Value, String> {
        if p.name == "TOOL_DATA" || p.name == "BASE_DATA" {
            return Ok(Value::Opaque);
        }
        if p.name == "$ANIN" {
            let i = match &p.index {
                Some(ix) => self.eval(ix, f)?.int()?,
                None => return Err("$ANIN without an index".into()),
            };
            if !self.in_trigger {
                self.stop("$ANIN read in the advance run", &f.module.clone())?;
            }
            let v = (self.sensor)(&Read {
                input: i,
                routine: &f.routine,
                args: &f.args,
            })?;
            if !(-1.0..=1.0).contains(&v) {
                return Err(format!("$ANIN[{i}] = {v} outside -1..1"));
            }
            return Ok(Value::Real(v));
        }
        if p.name.starts_with('$') {
            let key = match &p.member {
                Some(m) => format!("{}.{m}", p.name),
                None => p.name.clone(),
            };
            return self
                .system
                .get(&key)
                .cloned()
                .ok_or_else(|| format!("{key} read before it is set"));
        }
        let index = match &p.index {
            Some(ix) => Some(self.eval(ix, f)?.int()?),
            None => None,
        };
        let slot = self.slot(&p.name, f)?;
        // Only the element: cloning a whole array of positions per read
        // would make a 46 800-motion run take minutes.
        let mut v = match index {
            None => slot.clone(),
            Some(i) => {
                let Value::Array(a) = slot else {
                    return Err(format!("{} is not an array", p.name));
                };
                let n = a.len();
                a.get((i - 1) as usize)
                    .filter(|_| i >= 1)
                    .cloned()
                    .ok_or_else(|| format!("{}[{i}] outside 1..{n}", p.name))?
            }
        };
        if let Some(m) = &p.member {
            let Value::Struct(s) = v else {
                return Err(format!("{}.{m} of a non-POS", p.name));
            };
            v = Value::Real(*s.get(m).ok_or_else(|| format!("no component {m}"))?);
        }
        if let Value::Unset(_) = v {
            return Err(format!("{}: value not assigned", p.name));
        }
        Ok(v)
    }
}

fn binary(o: &str, a: Value, b: Value) -> Result<Value, String> {
    if let (Value::Bool(x), Value::Bool(y)) = (&a, &b) {
        return match o {
            "AND" => Ok(Value::Bool(*x && *y)),
            "OR" => Ok(Value::Bool(*x || *y)),
            _ => Err(format!("{o} on BOOLs")),
        };
    }
    if let (Value::Int(x), Value::Int(y)) = (&a, &b) {
        let (x, y) = (*x, *y);
        return Ok(match o {
            "+" => Value::Int(x + y),
            "-" => Value::Int(x - y),
            "*" => Value::Int(x * y),
            // KRL: INT / INT is an INT, truncated.
            "/" if y != 0 => Value::Int(x / y),
            "/" => return Err("division by zero".into()),
            _ => compare(o, x as f64, y as f64)?,
        });
    }
    let (x, y) = (a.num()?, b.num()?);
    let r = match o {
        "+" => x + y,
        "-" => x - y,
        "*" => x * y,
        "/" if y != 0.0 => x / y,
        "/" => return Err("division by zero".into()),
        _ => return compare(o, x, y),
    };
    if !r.is_finite() {
        return Err(format!("{x} {o} {y} is not finite"));
    }
    Ok(Value::Real(r))
}

fn compare(o: &str, x: f64, y: f64) -> Result<Value, String> {
    Ok(Value::Bool(match o {
        "<" => x < y,
        ">" => x > y,
        "<=" => x <= y,
        ">=" => x >= y,
        "==" => x == y,
        "<>" => x != y,
        _ => return Err(format!("operator {o}")),
    }))
}

/// Runs a ring program whose sensor reads `value` on every input: with the
/// target height, the program lays the IR's nominal plan.
pub fn run_steady(
    files: &Files,
    main: &str,
    laser: u16,
    power: u16,
    value: f64,
) -> Result<Run, String> {
    let mut sensor = |_: &Read| Ok(value);
    run(
        files,
        main,
        laser,
        power,
        Config { delay_motions: 12 },
        &mut sensor,
    )
}
