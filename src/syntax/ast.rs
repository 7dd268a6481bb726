//! The typed syntax tree. Every node carries its span; nothing here knows what a
//! bead or a machine is — that is the checker's job (src/sema).

use crate::span::{Span, Spanned};

/// An identifier with its span.
pub type Ident = Spanned<String>;

/// A whole `.lmd` file.
#[derive(Clone, Debug, PartialEq)]
pub struct File {
    /// Top-level statements in source order.
    pub stmts: Vec<Stmt>,
}

/// `kind name? (= expr | { stmts })?`
#[derive(Clone, Debug, PartialEq)]
pub struct Stmt {
    /// The leading word: `part`, `let`, `bead`, `width`, …
    pub kind: Ident,
    /// The optional name after it.
    pub name: Option<Ident>,
    /// What follows.
    pub body: Body,
    /// The whole statement.
    pub span: Span,
}

/// The part of a statement after its kind and name.
#[derive(Clone, Debug, PartialEq)]
pub enum Body {
    /// Nothing: `part duct`.
    None,
    /// `= expr`
    Assign(Expr),
    /// `{ … }` with the span of the braces.
    Block(Vec<Stmt>, Span),
}

/// An expression.
#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    /// What it is.
    pub kind: ExprKind,
    /// Where it is.
    pub span: Span,
}

/// Expression forms.
#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    /// `60 mm`, `7 mm/s`, `3`
    Number {
        /// The digits' value.
        value: f64,
        /// The unit text as written, if any.
        unit: Option<Spanned<String>>,
    },
    /// A name: a constant, a section, or a symbol such as `auto`.
    Ident(String),
    /// `"text"`
    Str(String),
    /// `f(a, name = b)`
    Call {
        /// The called name.
        func: Ident,
        /// Arguments in order.
        args: Vec<Arg>,
    },
    /// `[a, b, c]`
    List(Vec<Expr>),
    /// `-x`, `+x`
    Unary {
        /// The operator.
        op: UnOp,
        /// The operand.
        expr: Box<Expr>,
    },
    /// `a + b`, `a .. b`, …
    Binary {
        /// The operator.
        op: BinOp,
        /// Left operand.
        lhs: Box<Expr>,
        /// Right operand.
        rhs: Box<Expr>,
    },
}

/// A call argument, named (`diameter = 60 mm`) or positional.
#[derive(Clone, Debug, PartialEq)]
pub struct Arg {
    /// The name, if given.
    pub name: Option<Ident>,
    /// The value.
    pub value: Expr,
}

/// Prefix operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UnOp {
    /// `-`
    Neg,
    /// `+`
    Pos,
}

/// Infix operators, loosest first.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinOp {
    /// `a .. b`
    Range,
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `^` (integer exponents only)
    Pow,
}

impl BinOp {
    /// The operator as written.
    pub fn symbol(self) -> &'static str {
        match self {
            BinOp::Range => "..",
            BinOp::Add => "+",
            BinOp::Sub => "-",
            BinOp::Mul => "*",
            BinOp::Div => "/",
            BinOp::Pow => "^",
        }
    }
}
