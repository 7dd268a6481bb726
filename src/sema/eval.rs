//! Evaluation of expressions to values with units. Errors are pushed to the sink
//! and the failed expression evaluates to `None`, so one mistake is reported once
//! and does not cascade.

use crate::diag::{message, Diagnostic, Diagnostics};
use crate::sema::suggest::did_you_mean;
use crate::sema::value::{Call, CallArg, Spanned, Value};
use crate::span::Span;
use crate::syntax::ast::{Arg, BinOp, Expr, ExprKind, UnOp};
use crate::units::{parse_unit, Dim, Quantity};
use std::collections::{HashMap, HashSet};

enum LetState<'a> {
    Pending(&'a Expr),
    Busy,
    /// The value, and whether it depends on the layer number.
    Done(Option<Value>, bool),
}

/// The name of the built-in layer number (0-based) that profile expressions may
/// use: `let R = min(layer + 2, 10) * d`.
pub const LAYER: &str = "layer";

/// The name of the built-in height of the layer's plane above the first
/// layer's (`layer · layer_height`, a length) that profile expressions may use.
pub const Z: &str = "layer_z";

/// The longest chain of constants evaluated one inside another (`let a2 = a1 +
/// 1 mm`, `let a1 = a0 + 1 mm`, …). Evaluation recurses through each constant
/// it has not computed yet, so an unbounded chain would overflow the stack; a
/// constant already computed costs nothing, so this bounds only chains written
/// out of order or very long ones.
pub const MAX_CONSTANT_CHAIN: usize = 128;

/// The deepest evaluation, in nested expression nodes and constants together.
/// The parser bounds one expression to
/// [`MAX_EXPR_DEPTH`](crate::syntax::MAX_EXPR_DEPTH); this bounds what chains
/// of constants stack on top of that, within a 2 MiB thread stack in a debug
/// build.
pub const MAX_EVAL_DEPTH: usize = 512;

/// The names of the position builtins a `top` expression may use: the point's
/// x and y (lengths) in the footprint's frame. Elsewhere they are plain
/// words (`scan = x`, `beam = -z`).
pub const POSITION: [&str; 2] = ["x", "y"];

/// The constants of a file, evaluated on demand (so order does not matter) with
/// cycle detection.
pub struct Env<'a> {
    lets: HashMap<String, (Span, LetState<'a>, &'a Expr)>,
    /// Expression nodes being evaluated, one inside another.
    depth: usize,
    /// Constants being evaluated, one inside another.
    chain: usize,
    /// Whether the evaluation has been cut short by a depth limit (reported
    /// once: every level above it fails too).
    cut: bool,
    /// The value of [`LAYER`] (0 outside a per-layer evaluation).
    layer: usize,
    /// The value of [`Z`], mm (0 outside a per-layer evaluation).
    z: f64,
    /// Counts reads of [`LAYER`], directly or through a constant that uses it, so
    /// a constant knows whether it must be recomputed for another layer.
    layer_reads: u64,
    /// The point [`POSITION`] names while a `top` is evaluated (mm); `None`
    /// elsewhere, where `x` and `y` are words.
    position: Option<[f64; 2]>,
    /// Counts reads of [`POSITION`], as `layer_reads` does for the layer.
    position_reads: u64,
    /// Names of everything declared (constants, sections, beads, …), for
    /// "did you mean" hints.
    pub known: Vec<String>,
    /// How the program's data files are read (`fit(…, data = "…")`).
    pub data: Option<super::DataReader>,
}

impl<'a> Env<'a> {
    /// An environment with no constants.
    pub fn new() -> Self {
        Env {
            lets: HashMap::new(),
            depth: 0,
            chain: 0,
            cut: false,
            layer: 0,
            z: 0.0,
            layer_reads: 0,
            position: None,
            position_reads: 0,
            known: Vec::new(),
            data: None,
        }
    }

    /// An environment with a file's `let`s, as a model keeps them to
    /// evaluate an expression again later (a profile on each layer, a top
    /// at each point). A name declared twice was reported by the checker;
    /// the first declaration is the one it used.
    pub fn with_constants(constants: &'a [(String, Span, Expr)]) -> Self {
        let mut env = Env::new();
        for (name, span, e) in constants {
            let _ = env.declare(name, *span, e);
        }
        env
    }

    /// Declares `let name = expr`. Returns the span of an earlier declaration of
    /// the same name, if any.
    pub fn declare(&mut self, name: &str, name_span: Span, expr: &'a Expr) -> Option<Span> {
        if let Some((prev, _, _)) = self.lets.get(name) {
            return Some(*prev);
        }
        self.lets
            .insert(name.to_string(), (name_span, LetState::Pending(expr), expr));
        self.known.push(name.to_string());
        None
    }

    /// Is `name` a constant?
    pub fn is_constant(&self, name: &str) -> bool {
        self.lets.contains_key(name)
    }

    /// Evaluates every constant (so errors in unused ones are reported too).
    ///
    /// Each constant is computed after the constants it uses (a depth-first
    /// walk with its own stack, in the order evaluation would meet them), so
    /// no evaluation recurses through a chain of constants, however long: a
    /// file of thousands of `let`s, each using the one before, is fine. A
    /// constant that uses one still being walked (a cycle) is left to the lazy
    /// evaluation, which reports the cycle.
    pub fn eval_all(&mut self, diags: &mut Diagnostics) {
        let mut names: Vec<_> = self.lets.keys().cloned().collect();
        names.sort();
        // Constants on the walk's stack or computed. Names borrow from `names`
        // or from the expressions, both of which outlive the walk.
        let mut seen: HashSet<&str> = HashSet::new();
        for root in &names {
            if seen.contains(root.as_str()) {
                continue;
            }
            let Some(expr) = self.lets.get(root.as_str()).map(|l| l.2) else {
                continue;
            };
            seen.insert(root);
            let mut stack: Vec<(&str, Vec<&str>, usize)> = vec![(root, uses(expr), 0)];
            while let Some((name, deps, next)) = stack.last_mut() {
                if let Some(&d) = deps.get(*next) {
                    *next += 1;
                    if !seen.contains(d) {
                        if let Some(e) = self.lets.get(d).map(|l| l.2) {
                            seen.insert(d);
                            stack.push((d, uses(e), 0));
                        }
                    }
                    continue;
                }
                let name = *name;
                stack.pop();
                let span = self.lets[name].0;
                self.lookup(name, span, diags);
            }
        }
    }

    fn lookup(&mut self, name: &str, at: Span, diags: &mut Diagnostics) -> Option<Option<Value>> {
        let Some((decl, state, _)) = self.lets.get_mut(name) else {
            if let (Some(p), Some(i)) = (self.position, POSITION.iter().position(|&n| n == name)) {
                self.position_reads += 1;
                return Some(Some(Value::Quantity(Quantity {
                    value: p[i],
                    dim: Dim::LENGTH,
                })));
            }
            if name == LAYER || name == Z {
                self.layer_reads += 1;
                return Some(Some(Value::Quantity(if name == Z {
                    Quantity {
                        value: self.z,
                        dim: Dim::LENGTH,
                    }
                } else {
                    Quantity {
                        value: self.layer as f64,
                        dim: Dim::NONE,
                    }
                })));
            }
            return None;
        };
        let decl = *decl;
        match std::mem::replace(state, LetState::Busy) {
            LetState::Done(v, dependent) => {
                *state = LetState::Done(v.clone(), dependent);
                if dependent {
                    self.layer_reads += 1;
                }
                Some(v)
            }
            LetState::Busy => {
                diags.push(message::value::cycle(name, at, decl));
                Some(None)
            }
            LetState::Pending(expr) => {
                if self.chain >= MAX_CONSTANT_CHAIN {
                    // Left pending: computed again (and failing again, silently)
                    // only if another chain reaches it as deep.
                    if let Some((_, st, _)) = self.lets.get_mut(name) {
                        *st = LetState::Pending(expr);
                    }
                    self.cut(diags, |d| {
                        d.push(message::value::chain_too_long(
                            name,
                            MAX_CONSTANT_CHAIN,
                            at,
                            decl,
                        ))
                    });
                    return Some(None);
                }
                let before = (self.layer_reads, self.position_reads);
                self.chain += 1;
                let v = self.eval(expr, diags).map(|s| s.value);
                self.chain -= 1;
                // A constant read at one point or layer holds only there.
                let dependent = (self.layer_reads, self.position_reads) != before;
                if let Some((_, st, _)) = self.lets.get_mut(name) {
                    *st = LetState::Done(v.clone(), dependent);
                }
                Some(v)
            }
        }
    }

    /// Evaluates `f` with [`LAYER`] = `layer` and [`Z`] = `z` (mm): constants
    /// that depend on the layer are recomputed, the others keep their values.
    pub fn at_layer<R>(&mut self, layer: usize, z: f64, f: impl FnOnce(&mut Self) -> R) -> R {
        let old = std::mem::replace(&mut self.layer, layer);
        let old_z = std::mem::replace(&mut self.z, z);
        self.forget_layer_values();
        let r = f(self);
        self.layer = old;
        self.z = old_z;
        self.forget_layer_values();
        r
    }

    /// Evaluates `f` with [`POSITION`] = `(x, y)` (mm): `x` and `y` are
    /// lengths inside it, and constants read at another point are recomputed.
    pub fn at_position<R>(&mut self, x: f64, y: f64, f: impl FnOnce(&mut Self) -> R) -> R {
        let old = self.position.replace([x, y]);
        self.forget_layer_values();
        let r = f(self);
        self.position = old;
        self.forget_layer_values();
        r
    }

    fn forget_layer_values(&mut self) {
        for (_, state, expr) in self.lets.values_mut() {
            if matches!(state, LetState::Done(_, true)) {
                *state = LetState::Pending(expr);
            }
        }
    }

    /// How often the layer builtins have been read so far (directly or
    /// through a constant that uses them): a rise across an evaluation means
    /// its value depends on the layer.
    pub fn layer_reads(&self) -> u64 {
        self.layer_reads
    }

    /// How often the position builtins have been read so far.
    pub fn position_reads(&self) -> u64 {
        self.position_reads
    }

    /// Whether evaluating `e` reads the layer number.
    pub fn depends_on_layer(&mut self, e: &Expr) -> bool {
        let before = self.layer_reads;
        let mut scratch = Diagnostics::new();
        self.eval(e, &mut scratch);
        self.layer_reads > before
    }

    /// Reports `d` (the first time a depth limit cuts an evaluation short; the
    /// levels above it fail with it and say nothing more).
    fn cut(&mut self, diags: &mut Diagnostics, report: impl FnOnce(&mut Diagnostics)) {
        if !self.cut {
            self.cut = true;
            report(diags);
        }
    }

    /// Evaluates an expression.
    pub fn eval(&mut self, e: &Expr, diags: &mut Diagnostics) -> Option<Spanned> {
        if self.depth >= MAX_EVAL_DEPTH {
            self.cut(diags, |d| {
                d.push(message::value::too_deep(MAX_EVAL_DEPTH, e.span))
            });
            return None;
        }
        self.depth += 1;
        let v = self.eval_node(e, diags);
        self.depth -= 1;
        if self.depth == 0 {
            // The next top-level evaluation reports its own limit.
            self.cut = false;
        }
        v
    }

    /// One node. Each kind has its own function and every diagnostic is
    /// built in a function of its own: in a debug build a function's frame
    /// holds the temporaries of all its branches, and this recursion is as
    /// deep as the expression, so a lean frame here is what lets
    /// [`MAX_EXPR_DEPTH`](crate::syntax::MAX_EXPR_DEPTH) fit a small stack.
    fn eval_node(&mut self, e: &Expr, diags: &mut Diagnostics) -> Option<Spanned> {
        let value = match &e.kind {
            ExprKind::Number { value, unit } => number(*value, unit.as_ref(), diags)?,
            ExprKind::Ident(name) => match self.lookup(name, e.span, diags) {
                Some(v) => v?,
                None => Value::Symbol(name.clone()),
            },
            ExprKind::Str(s) => Value::Str(s.clone()),
            ExprKind::List(items) => self.list(items, diags)?,
            ExprKind::Call { func, args } => self.call(e, func, args, diags)?,
            ExprKind::Unary { op, expr } => self.unary(*op, expr, diags)?,
            ExprKind::Binary { op, lhs, rhs } => self.binary_node(*op, lhs, rhs, diags)?,
        };
        finite(value, e.span, diags)
    }

    fn list(&mut self, items: &[Expr], diags: &mut Diagnostics) -> Option<Value> {
        let mut out = Vec::with_capacity(items.len());
        let mut ok = true;
        for it in items {
            match self.eval(it, diags) {
                Some(v) => out.push(v),
                None => ok = false,
            }
        }
        ok.then_some(Value::List(out))
    }

    fn call(
        &mut self,
        e: &Expr,
        func: &crate::syntax::ast::Ident,
        args: &[Arg],
        diags: &mut Diagnostics,
    ) -> Option<Value> {
        let mut out = Vec::with_capacity(args.len());
        let mut ok = true;
        for Arg { name, value } in args {
            match self.eval(value, diags) {
                Some(v) => out.push(CallArg {
                    name: name.as_ref().map(|n| (n.node.clone(), n.span)),
                    value: v,
                }),
                None => ok = false,
            }
        }
        if !ok {
            return None;
        }
        if matches!(func.node.as_str(), "min" | "max") && !self.lets.contains_key(&func.node) {
            min_max(&func.node, e.span, &out, diags)
        } else if crate::sema::math::FUNCTIONS.contains(&func.node.as_str())
            && !self.lets.contains_key(&func.node)
        {
            crate::sema::math::call(&func.node, e.span, &out, diags)
        } else {
            Some(Value::Call(Call {
                func: func.node.clone(),
                func_span: func.span,
                args: out,
            }))
        }
    }

    fn unary(&mut self, op: UnOp, expr: &Expr, diags: &mut Diagnostics) -> Option<Value> {
        let v = self.eval(expr, diags)?;
        match (op, v.value) {
            (UnOp::Pos, v) => Some(v),
            (UnOp::Neg, Value::Quantity(q)) => Some(Value::Quantity(Quantity {
                value: -q.value,
                dim: q.dim,
            })),
            // `-z` names an axis direction: keep the sign in the symbol.
            (UnOp::Neg, Value::Symbol(s)) => Some(Value::Symbol(format!("-{s}"))),
            (UnOp::Neg, other) => {
                not_negatable(&other, expr.span, diags);
                None
            }
        }
    }

    fn binary_node(
        &mut self,
        op: BinOp,
        lhs: &Expr,
        rhs: &Expr,
        diags: &mut Diagnostics,
    ) -> Option<Value> {
        let l = self.eval(lhs, diags);
        let r = self.eval(rhs, diags);
        let (l, r) = (l?, r?);
        binary(op, l, r, diags)
    }
}

/// A number with its unit.
fn number(
    value: f64,
    unit: Option<&crate::span::Spanned<String>>,
    diags: &mut Diagnostics,
) -> Option<Value> {
    let (factor, dim) = match unit {
        None => (1.0, Dim::NONE),
        Some(u) => match parse_unit(&u.node) {
            Ok(x) => x,
            Err(bad) => {
                let meant = crate::units::unit_meant(&bad.0).map(|m| {
                    // The whole unit as written, with the unknown part replaced.
                    u.node.replacen(bad.0.as_str(), m, 1)
                });
                diags.push(message::value::unknown_unit(
                    &bad.0,
                    meant.as_deref(),
                    u.span,
                ));
                return None;
            }
        },
    };
    Some(Value::Quantity(Quantity {
        value: value * factor,
        dim,
    }))
}

fn not_negatable(other: &Value, span: Span, diags: &mut Diagnostics) {
    diags.push(message::value::cannot_negate(other.got(), span));
}

/// `value` at `span`, unless it is a quantity that is not finite.
fn finite(value: Value, span: Span, diags: &mut Diagnostics) -> Option<Spanned> {
    if let Value::Quantity(q) = &value {
        if !q.value.is_finite() {
            diags.push(message::value::not_finite(span));
            return None;
        }
    }
    Some(Spanned { value, span })
}

/// The names `e` reads, in the order evaluation meets them (left to right).
/// Walks with its own stack: expressions are bounded in depth by the parser,
/// but this costs nothing.
fn uses(e: &Expr) -> Vec<&str> {
    let mut out = Vec::new();
    let mut todo = vec![e];
    while let Some(e) = todo.pop() {
        match &e.kind {
            ExprKind::Ident(n) => out.push(n.as_str()),
            ExprKind::Number { .. } | ExprKind::Str(_) => {}
            ExprKind::List(items) => todo.extend(items.iter().rev()),
            ExprKind::Call { args, .. } => todo.extend(args.iter().rev().map(|a| &a.value)),
            ExprKind::Unary { expr, .. } => todo.push(expr),
            ExprKind::Binary { lhs, rhs, .. } => {
                todo.push(rhs);
                todo.push(lhs);
            }
        }
    }
    out
}

impl Default for Env<'_> {
    fn default() -> Self {
        Self::new()
    }
}

fn binary(op: BinOp, l: Spanned, r: Spanned, diags: &mut Diagnostics) -> Option<Value> {
    let (lq, rq) = match (&l.value, &r.value) {
        (Value::Quantity(a), Value::Quantity(b)) => (*a, *b),
        _ => {
            let bad = if matches!(l.value, Value::Quantity(_)) {
                &r
            } else {
                &l
            };
            if let Some(d) = position_outside_top(&bad.value, bad.span) {
                diags.push(d);
                return None;
            }
            diags.push(message::value::operand_not_number(
                op.symbol(),
                bad.value.got(),
                bad.span,
            ));
            return None;
        }
    };
    let q = |value: f64, dim: Dim| Some(Value::Quantity(Quantity { value, dim }));
    match op {
        BinOp::Add | BinOp::Sub | BinOp::Range => {
            if lq.dim != rq.dim {
                diags.push(message::value::operand_units_differ(
                    op.symbol(),
                    (lq.dim, l.span),
                    (rq.dim, r.span),
                ));
                return None;
            }
            match op {
                BinOp::Add => q(lq.value + rq.value, lq.dim),
                BinOp::Sub => q(lq.value - rq.value, lq.dim),
                _ => {
                    if lq.value > rq.value {
                        diags.push(message::value::empty_range(l.span.join(r.span)));
                        return None;
                    }
                    Some(Value::Range(lq, rq))
                }
            }
        }
        BinOp::Mul => q(lq.value * rq.value, lq.dim.times(rq.dim)),
        BinOp::Div => {
            if rq.value == 0.0 {
                diags.push(message::value::division_by_zero(r.span));
                return None;
            }
            q(lq.value / rq.value, lq.dim.per(rq.dim))
        }
        BinOp::Pow => {
            let n = rq.value;
            if rq.dim != Dim::NONE || n.fract() != 0.0 || n.abs() > 16.0 {
                diags.push(message::value::bad_exponent(n, r.span));
                return None;
            }
            q(lq.value.powi(n as i32), lq.dim.powi(n as i32))
        }
    }
}

/// `min(a, b, …)` / `max(a, b, …)` of quantities of one dimension.
fn min_max(func: &str, span: Span, args: &[CallArg], diags: &mut Diagnostics) -> Option<Value> {
    let mut best: Option<Quantity> = None;
    for a in args {
        let q = match (&a.name, &a.value.value) {
            (None, Value::Quantity(q)) => *q,
            (_, other) => {
                diags.push(message::value::min_max_not_number(
                    func,
                    other.got(),
                    a.value.span,
                ));
                return None;
            }
        };
        if let Some(b) = best {
            if b.dim != q.dim {
                diags.push(message::value::min_max_units_differ(
                    func,
                    b.dim,
                    q.dim,
                    a.value.span,
                ));
                return None;
            }
        }
        best = Some(match best {
            None => q,
            Some(b) if (func == "min") == (q.value < b.value) => q,
            Some(b) => b,
        });
    }
    match best {
        Some(q) => Some(Value::Quantity(q)),
        None => {
            diags.push(message::value::min_max_empty(func, span));
            None
        }
    }
}

/// The error for `x` or `y` (or `-x`, `-y`) used as a number outside a
/// `top`, where they are the position; `None` for any other value.
pub fn position_outside_top(v: &Value, at: Span) -> Option<Diagnostic> {
    let Value::Symbol(s) = v else { return None };
    let name = s.strip_prefix('-').unwrap_or(s);
    POSITION
        .contains(&name)
        .then(|| message::value::position_outside_top(name, at))
}

/// An "unknown name" error with a did-you-mean hint over `candidates`.
pub fn unknown_name(name: &str, span: Span, what: &str, candidates: &[&str]) -> Diagnostic {
    let suggestion = did_you_mean(name, candidates.iter().copied());
    message::value::unknown_name(name, span, what, suggestion, candidates)
}
