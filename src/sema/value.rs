//! What an expression evaluates to: a quantity, a range, a name, a text, a
//! call or a list, each with the span it was written at. The evaluator is
//! [`crate::sema::eval`]; the words a message uses for each kind of value are in
//! `crate::diag::message::value`, which reads a value as a `Got`.

use crate::diag::message::value::Got;
use crate::span::Span;
use crate::units::Quantity;

/// An evaluated expression.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// A number with a dimension.
    Quantity(Quantity),
    /// `lo .. hi`, same dimension.
    Range(Quantity, Quantity),
    /// A bare name that is not a constant: a section, a bead, or a keyword such as
    /// `auto`. The reader that expects it decides.
    Symbol(String),
    /// `"text"`
    Str(String),
    /// `f(…)`: interpreted by the reader that expects it.
    Call(Call),
    /// `[a, b]`
    List(Vec<Spanned>),
}

impl Value {
    /// What this value is, for a message that refuses it.
    pub fn got(&self) -> Got<'_> {
        match self {
            Value::Quantity(q) => Got::Quantity(q.dim),
            Value::Range(q, _) => Got::Range(q.dim),
            Value::Symbol(s) => Got::Name(s),
            Value::Str(_) => Got::Text,
            Value::Call(c) => Got::Call(&c.func),
            Value::List(_) => Got::List,
        }
    }

    /// What this value is, in words ("a length (mm)"), for a message that
    /// takes the words alone.
    pub fn describe(&self) -> String {
        self.got().describe()
    }
}

/// A value and the source it came from.
#[derive(Clone, Debug, PartialEq)]
pub struct Spanned {
    /// The value.
    pub value: Value,
    /// Where it was written.
    pub span: Span,
}

/// An evaluated call: `circle(diameter = 60 mm)`.
#[derive(Clone, Debug, PartialEq)]
pub struct Call {
    /// The function name.
    pub func: String,
    /// Where the name is.
    pub func_span: Span,
    /// Arguments in order.
    pub args: Vec<CallArg>,
}

/// One evaluated argument.
#[derive(Clone, Debug, PartialEq)]
pub struct CallArg {
    /// Its name, with span, if named.
    pub name: Option<(String, Span)>,
    /// Its value.
    pub value: Spanned,
}
