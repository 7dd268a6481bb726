//! Reading the KRL subset: tokens, expressions, statements, routines of a
//! `.src`, the declarations of a `.dat`.

use super::value::{Ty, Value};
use std::collections::{BTreeMap, HashMap};

#[derive(Clone, Debug, PartialEq)]
pub enum Tok {
    Num(String),
    Name(String),
    Enum(String),
    Op(&'static str),
}

pub fn tokens(s: &str) -> Result<Vec<Tok>, String> {
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
pub enum Expr {
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
pub struct Place {
    pub name: String,
    pub index: Option<Box<Expr>>,
    pub member: Option<String>,
}

pub struct P<'t> {
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
pub fn leak(o: &str) -> &'static str {
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
pub fn number(s: &str) -> Result<Value, String> {
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
pub enum Action {
    Assign(Place, Expr),
    Call(String, Vec<Expr>),
}

#[derive(Clone, Debug)]
pub enum Stmt {
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
pub struct Routine {
    pub params: Vec<String>,
    pub body: Vec<Stmt>,
    pub file: String,
}

pub fn ty(name: &str) -> Result<Ty, String> {
    match name {
        "INT" => Ok(Ty::Int),
        "REAL" => Ok(Ty::Real),
        "BOOL" => Ok(Ty::Bool),
        "POS" => Ok(Ty::Pos),
        t => Err(format!("type {t} is not in the subset")),
    }
}

/// Lines without comments, header lines and empty ones: (line number, text).
pub fn code_lines(text: &str) -> Vec<(usize, String)> {
    text.lines()
        .enumerate()
        .filter_map(|(i, l)| {
            let l = l.split(';').next().unwrap_or("").trim();
            (!l.is_empty() && !l.starts_with('&')).then(|| (i + 1, l.to_string()))
        })
        .collect()
}

pub fn action(t: &[Tok]) -> Result<Action, String> {
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
pub fn block(
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
pub fn routines(file: &str, text: &str) -> Result<Vec<(String, Routine)>, String> {
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
pub fn data(file: &str, text: &str) -> Result<HashMap<String, Value>, String> {
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

pub fn eval_const(x: &Expr) -> Result<Value, String> {
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
