//! KRL's values and their arithmetic: `INT` and `REAL` kept apart as KRL
//! types them (`INT / INT` truncates), `BOOL`, enums, `POS` aggregates.

use std::collections::BTreeMap;

#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Int(i64),
    Real(f64),
    Bool(bool),
    Enum(String),
    Struct(BTreeMap<String, f64>),
    Array(Vec<Value>),
    /// Declared, never assigned: reading it is KRL's "value not assigned".
    Unset(Ty),
    /// A system table (`TOOL_DATA[n]`, `LOAD_DATA[n]`) whose value the test
    /// does not know.
    Opaque,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Ty {
    Int,
    Real,
    Bool,
    Pos,
}

impl Value {
    pub fn num(&self) -> Result<f64, String> {
        match self {
            Value::Int(i) => Ok(*i as f64),
            Value::Real(r) => Ok(*r),
            Value::Unset(_) => Err("value not assigned".into()),
            v => Err(format!("{v:?} is not a number")),
        }
    }

    pub fn int(&self) -> Result<i64, String> {
        match self {
            Value::Int(i) => Ok(*i),
            Value::Unset(_) => Err("value not assigned".into()),
            v => Err(format!("{v:?} is not an INT")),
        }
    }

    /// `v` stored in a variable that holds `self`'s type: INT ← REAL rounds.
    pub fn coerce(&self, v: Value) -> Result<Value, String> {
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

pub fn binary(o: &str, a: Value, b: Value) -> Result<Value, String> {
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

pub fn compare(o: &str, x: f64, y: f64) -> Result<Value, String> {
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
