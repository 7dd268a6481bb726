//! `--set NAME=VALUE`: replaces the value of a top-level `let` before the
//! file is checked, for parameter sweeps without rewriting the file's text.
//!
//! The value is parsed as an expression of the language and must be of the
//! same kind as the file's value (a length for a length, an angle for an
//! angle, a range for a range): a sweep that sets a radius in degrees fails
//! here, naming both, instead of as a unit error somewhere the constant is
//! used. Every span of the new value is the file's value's span, so what
//! the checker finds wrong with it points at the `let` it replaced.

use crate::diag::Diagnostics;
use crate::sema::eval::Env;
use crate::sema::value::Value;
use crate::span::Span;
use crate::syntax::ast::{Body, Expr, ExprKind, File};
use std::str::FromStr;

/// One `--set NAME=VALUE`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Override {
    /// The constant's name.
    pub name: String,
    /// Its new value, as written (`300 mm`, `45 deg`, `7 mm/s .. 9 mm/s`).
    pub value: String,
}

impl FromStr for Override {
    type Err = String;

    /// Reads `NAME=VALUE` (spaces round either are dropped).
    fn from_str(s: &str) -> Result<Self, String> {
        let Some((name, value)) = s.split_once('=') else {
            return Err(format!("`{s}` is not NAME=VALUE (e.g. `R1=300 mm`)"));
        };
        let (name, value) = (name.trim(), value.trim());
        let word = name
            .chars()
            .next()
            .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
            && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
        if !word {
            return Err(format!("`{name}` is not the name of a constant"));
        }
        if value.is_empty() {
            return Err(format!("`{name}=` gives no value"));
        }
        Ok(Override {
            name: name.to_string(),
            value: value.to_string(),
        })
    }
}

impl std::fmt::Display for Override {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} = {}", self.name, self.value)
    }
}

/// Why an override cannot be applied.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SetError {
    /// No top-level `let` has the name.
    #[error("`--set {name}`: the file has no top-level `let {name}`{hint}")]
    UnknownName {
        /// The name given.
        name: String,
        /// `; did you mean …` or the constants the file declares.
        hint: String,
    },
    /// The value is not one expression of the language, or does not evaluate.
    #[error("`--set {name}={value}`: {why}")]
    BadValue {
        /// The name given.
        name: String,
        /// The value given.
        value: String,
        /// What is wrong with it.
        why: String,
    },
    /// The value is of another kind than the file's.
    #[error("`--set {name}={value}` gives {got}, but `{name}` is {want} in the file")]
    Unit {
        /// The name given.
        name: String,
        /// The value given.
        value: String,
        /// What the value is ("an angle (deg)").
        got: String,
        /// What the file's value is ("a length (mm)").
        want: String,
    },
    /// One name set twice.
    #[error("`--set {0}` is given twice")]
    Twice(String),
}

/// Replaces the value of each overridden top-level `let` of `file`; returns
/// the overrides as the programs' headers list them (`NAME = VALUE`).
pub fn apply(file: &mut File, sets: &[Override]) -> Result<Vec<String>, SetError> {
    for (i, s) in sets.iter().enumerate() {
        if sets[..i].iter().any(|t| t.name == s.name) {
            return Err(SetError::Twice(s.name.clone()));
        }
    }
    let mut replaced = Vec::new();
    for s in sets {
        let value = parse_value(s)?;
        let at = find(file, &s.name)?;
        check_kind(file, s, &file.stmts[at], &value)?;
        if let Body::Assign(e) = &mut file.stmts[at].body {
            let mut value = value;
            respan(&mut value, e.span);
            *e = value;
        }
        replaced.push(s.to_string());
    }
    Ok(replaced)
}

/// The override's text as one expression.
fn parse_value(s: &Override) -> Result<Expr, SetError> {
    let bad = |why: String| SetError::BadValue {
        name: s.name.clone(),
        value: s.value.clone(),
        why,
    };
    let parsed = crate::syntax::parse(&format!("x = {}\n", s.value))
        .map_err(|d| bad(format!("it is not a value: {}", d.message)))?;
    match parsed.stmts.as_slice() {
        [one] if one.name.is_none() => match &one.body {
            Body::Assign(e) => Ok(e.clone()),
            _ => Err(bad("it is not a value".into())),
        },
        _ => Err(bad(
            "it is not one value (a number with its unit, a range, a name …)".into(),
        )),
    }
}

/// The index of the top-level `let name = …`.
fn find(file: &File, name: &str) -> Result<usize, SetError> {
    let is_let =
        |s: &crate::syntax::ast::Stmt| s.kind.node == "let" && matches!(s.body, Body::Assign(_));
    if let Some(i) = file
        .stmts
        .iter()
        .position(|s| is_let(s) && s.name.as_ref().is_some_and(|n| n.node == name))
    {
        return Ok(i);
    }
    let names: Vec<&str> = file
        .stmts
        .iter()
        .filter(|s| is_let(s))
        .filter_map(|s| s.name.as_ref().map(|n| n.node.as_str()))
        .collect();
    let close = names
        .iter()
        .filter(|n| strsim::levenshtein(n, name) <= 2.max(name.len() / 3))
        .min_by_key(|n| strsim::levenshtein(n, name));
    let hint = match (close, names.is_empty()) {
        (Some(c), _) => format!("; did you mean `{c}`?"),
        (None, true) => " (it declares no constants)".to_string(),
        (None, false) => format!("; it declares: {}", names.join(", ")),
    };
    Err(SetError::UnknownName {
        name: name.to_string(),
        hint,
    })
}

/// Refuses a value of another kind than the file's (the file's value and
/// the new one both evaluated among the file's constants). A file's value
/// that does not evaluate is left to the checker to report.
fn check_kind(
    file: &File,
    s: &Override,
    stmt: &crate::syntax::ast::Stmt,
    value: &Expr,
) -> Result<(), SetError> {
    let Body::Assign(was) = &stmt.body else {
        return Ok(());
    };
    let mut env = Env::new();
    for st in &file.stmts {
        if let (true, Some(n), Body::Assign(e)) = (st.kind.node == "let", &st.name, &st.body) {
            env.declare(&n.node, n.span, e);
        }
    }
    let mut scratch = Diagnostics::new();
    let old = env.eval(was, &mut scratch);
    let mut errors = Diagnostics::new();
    let Some(new) = env.eval(value, &mut errors) else {
        let why = errors
            .iter()
            .next()
            .map_or_else(|| "it has no value".to_string(), |d| d.message.clone());
        return Err(SetError::BadValue {
            name: s.name.clone(),
            value: s.value.clone(),
            why,
        });
    };
    let Some(old) = old else { return Ok(()) };
    if !same_kind(&old.value, &new.value) {
        return Err(SetError::Unit {
            name: s.name.clone(),
            value: s.value.clone(),
            got: new.value.describe(),
            want: old.value.describe(),
        });
    }
    Ok(())
}

/// Whether two values are of one kind: quantities and ranges of one
/// dimension, or values of one form.
fn same_kind(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Quantity(x), Value::Quantity(y)) => x.dim == y.dim,
        (Value::Range(x, _), Value::Range(y, _)) => x.dim == y.dim,
        (Value::Call(x), Value::Call(y)) => x.func == y.func,
        _ => std::mem::discriminant(a) == std::mem::discriminant(b),
    }
}

/// Points every span of `e` at `span`: the new value stands where the
/// file's was. Recursion is bounded by the parser's expression depth.
fn respan(e: &mut Expr, span: Span) {
    e.span = span;
    match &mut e.kind {
        ExprKind::Number { unit, .. } => {
            if let Some(u) = unit {
                u.span = span;
            }
        }
        ExprKind::Ident(_) | ExprKind::Str(_) => {}
        ExprKind::Call { func, args } => {
            func.span = span;
            for a in args {
                if let Some(n) = &mut a.name {
                    n.span = span;
                }
                respan(&mut a.value, span);
            }
        }
        ExprKind::List(items) => items.iter_mut().for_each(|x| respan(x, span)),
        ExprKind::Unary { expr, .. } => respan(expr, span),
        ExprKind::Binary { lhs, rhs, .. } => {
            respan(lhs, span);
            respan(rhs, span);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn set(src: &str, name: &str, value: &str) -> Result<File, SetError> {
        let mut f = crate::syntax::parse(src).unwrap();
        let o = Override {
            name: name.into(),
            value: value.into(),
        };
        apply(&mut f, &[o]).map(|_| f)
    }

    const SRC: &str = "let R = 250 mm\nlet A = 45 deg\nlet S = 7 mm/s .. 9 mm/s\n";

    #[test]
    fn a_value_of_the_same_kind_replaces_the_files() {
        let f = set(SRC, "R", "300 mm").unwrap();
        let Body::Assign(e) = &f.stmts[0].body else {
            panic!()
        };
        assert!(matches!(e.kind, ExprKind::Number { value, .. } if value == 300.0));
        // It stands where the file's value was.
        assert_eq!(e.span, Span::new(8, 14));
        assert!(set(SRC, "R", "0.3 m").is_ok());
        assert!(
            set(SRC, "R", "R + 10 mm").is_ok(),
            "the file's constants are there"
        );
        assert!(set(SRC, "S", "5 mm/s .. 6 mm/s").is_ok());
    }

    #[test]
    fn a_value_of_another_kind_is_refused_naming_both() {
        let e = set(SRC, "R", "30 deg").unwrap_err();
        assert!(matches!(e, SetError::Unit { .. }), "{e}");
        let text = e.to_string();
        assert!(
            text.contains("an angle") && text.contains("a length"),
            "{text}"
        );
        assert!(matches!(
            set(SRC, "S", "5 mm/s").unwrap_err(),
            SetError::Unit { .. }
        ));
    }

    #[test]
    fn unknown_names_and_bad_values() {
        let e = set(SRC, "RR", "1 mm").unwrap_err();
        assert!(e.to_string().contains("did you mean `R`"), "{e}");
        assert!(set(SRC, "zzzzzz", "1 mm")
            .unwrap_err()
            .to_string()
            .contains("R, A, S"));
        for bad in ["1 mm )", "1 KW", "1 mm\nlet q = 2", "nope +"] {
            assert!(
                matches!(set(SRC, "R", bad), Err(SetError::BadValue { .. })),
                "{bad}"
            );
        }
        assert!("R".parse::<Override>().is_err());
        assert!("1x=2".parse::<Override>().is_err());
        assert_eq!(
            "R = 3 mm".parse::<Override>().unwrap(),
            Override {
                name: "R".into(),
                value: "3 mm".into()
            }
        );
    }
}
