//! A profile or section taken by its name inside another shape:
//! `place(ring, at = …)`, a region's `outline = inlet` or `holes = [bore, …]`,
//! `bolt_circle(bolt, …)`. The name stands for the declaration's own
//! expression, written in its place before anything else is read: a profile
//! that follows `layer` follows it there too, and an error in it points at
//! the declaration, as it would for the declaration itself.
//!
//! Names are written in only where a shape goes (a call's unnamed
//! arguments, `outline` and `holes`), so a constant sharing nothing with a
//! profile is never touched. A name that leads back to the shape it is in
//! is refused (`lmd::cycle`), and so is a nesting whose written-out size
//! passes [`MAX_NODES`] (`lmd::too-large`): three copies of three copies …
//! of a profile grow as 3ⁿ.

use crate::diag::{message, Diagnostics};
use crate::span::Span;
use crate::syntax::ast::{Body, Expr, ExprKind, File, Stmt};
use std::collections::BTreeMap;

/// The calls whose arguments are shapes.
const SHAPE_CALLS: [&str; 3] = ["place", "region", "bolt_circle"];

/// A region's named arguments that are shapes.
const SHAPE_ARGS: [&str; 2] = ["outline", "holes"];

/// Most expression nodes the names may write out in all: far beyond any
/// drawing (a flange's region is some hundred), well within memory.
pub const MAX_NODES: usize = 200_000;

/// What a name leading back to its own shape is replaced by: a symbol no
/// source can write, which the profile reader (`sema::solid::profile`) takes as
/// reported already.
pub const REPORTED: &str = "\u{0}reported";

/// `file` with every profile or section named inside a shape written out.
pub fn expand(file: &File, diags: &mut Diagnostics) -> File {
    let mut decls: BTreeMap<&str, (&Expr, Span)> = BTreeMap::new();
    for s in &file.stmts {
        if let (kind, Some(n), Body::Assign(e)) = (s.kind.node.as_str(), &s.name, &s.body) {
            if kind == "profile" || kind == "section" {
                // A second declaration is refused where they are read.
                decls.entry(n.node.as_str()).or_insert((e, n.span));
            }
        }
    }
    let lets = (file.stmts.iter())
        .filter(|s| s.kind.node == "let")
        .filter_map(|s| s.name.as_ref().map(|n| n.node.as_str()))
        .collect();
    let mut x = Expander {
        decls,
        lets,
        stack: Vec::new(),
        nodes: 0,
        over: false,
    };
    let mut out = file.clone();
    for s in &mut out.stmts {
        // A declaration's own name is on the stack while its body is
        // written out: `profile a = place(a, …)` leads back to it.
        let own = match (&s.name, s.kind.node.as_str()) {
            (Some(n), "profile" | "section") => Some(n.node.clone()),
            _ => None,
        };
        x.stack.extend(own.clone());
        match (s.kind.node.as_str(), &mut s.body) {
            // A profile is a shape as a whole: `profile p = ring` too.
            ("profile", Body::Assign(e)) => x.shape(e, "a profile", diags),
            _ => x.stmt(s, diags),
        }
        if own.is_some() {
            x.stack.pop();
        }
    }
    out
}

/// Whether an argument is a shape: unnamed, or `outline` / `holes`.
fn shape_arg(a: &crate::syntax::ast::Arg) -> bool {
    a.name
        .as_ref()
        .is_none_or(|n| SHAPE_ARGS.contains(&n.node.as_str()))
}

struct Expander<'f> {
    decls: BTreeMap<&'f str, (&'f Expr, Span)>,
    /// The constants: a name of one where a shape goes is evaluated and
    /// judged as a value.
    lets: std::collections::BTreeSet<&'f str>,
    /// The declarations being written out, one inside another.
    stack: Vec<String>,
    /// Nodes written out so far.
    nodes: usize,
    /// Whether [`MAX_NODES`] was passed (reported once).
    over: bool,
}

impl Expander<'_> {
    fn stmt(&mut self, s: &mut Stmt, diags: &mut Diagnostics) {
        match &mut s.body {
            Body::Assign(e) => self.expr(e, diags),
            Body::Block(stmts, _) => {
                for s in stmts {
                    self.stmt(s, diags);
                }
            }
            Body::None => {}
        }
    }

    fn expr(&mut self, e: &mut Expr, diags: &mut Diagnostics) {
        match &mut e.kind {
            ExprKind::Call { func, args } => {
                let shaped = SHAPE_CALLS.contains(&func.node.as_str());
                for a in args {
                    if shaped && shape_arg(a) {
                        let what =
                            match (func.node.as_str(), a.name.as_ref().map(|n| n.node.as_str())) {
                                (_, Some("outline")) => "the outline of a region",
                                (_, Some(_)) => "a hole",
                                ("place", None) => "what `place` places",
                                _ => "what `bolt_circle` repeats",
                            };
                        self.shape(&mut a.value, what, diags);
                    } else {
                        self.expr(&mut a.value, diags);
                    }
                }
            }
            ExprKind::List(items) => {
                for i in items {
                    self.expr(i, diags);
                }
            }
            ExprKind::Unary { expr, .. } => self.expr(expr, diags),
            ExprKind::Binary { lhs, rhs, .. } => {
                self.expr(lhs, diags);
                self.expr(rhs, diags);
            }
            _ => {}
        }
    }

    /// Writes out a shape's declared name (or each in its list), and the
    /// names inside any other shape, each expression walked once.
    fn shape(&mut self, v: &mut Expr, what: &str, diags: &mut Diagnostics) {
        match &mut v.kind {
            ExprKind::List(items) => {
                for i in items {
                    self.shape(i, what, diags);
                }
            }
            ExprKind::Ident(n) if n == REPORTED || self.lets.contains(n.as_str()) => {}
            ExprKind::Ident(n) if !self.decls.contains_key(n.as_str()) => {
                let close = crate::sema::suggest::did_you_mean(n, self.decls.keys().copied());
                diags.push(message::shape::named_shape(what, n, v.span, close));
                v.kind = ExprKind::Ident(REPORTED.to_string());
            }
            ExprKind::Ident(n) => {
                let name = n.clone();
                let (decl, decl_at) = self.decls[name.as_str()];
                if self.stack.contains(&name) {
                    diags.push(message::shape::shape_cycle(&name, v.span, decl_at));
                    v.kind = ExprKind::Ident(REPORTED.to_string());
                    return;
                }
                let size = size(decl);
                if self.over || self.nodes + size > MAX_NODES {
                    if !self.over {
                        diags.push(message::shape::shapes_too_large(MAX_NODES, v.span));
                    }
                    self.over = true;
                    v.kind = ExprKind::Ident(REPORTED.to_string());
                    return;
                }
                self.nodes += size;
                let mut written = decl.clone();
                self.stack.push(name);
                // Names inside the declaration (itself a shape) are written
                // out in turn: `profile a = b` with `profile b = c` too.
                self.shape(&mut written, what, diags);
                self.stack.pop();
                *v = written;
            }
            _ => self.expr(v, diags),
        }
    }
}

/// The nodes of an expression.
fn size(e: &Expr) -> usize {
    1 + match &e.kind {
        ExprKind::Call { args, .. } => args.iter().map(|a| size(&a.value)).sum(),
        ExprKind::List(items) => items.iter().map(size).sum(),
        ExprKind::Unary { expr, .. } => size(expr),
        ExprKind::Binary { lhs, rhs, .. } => size(lhs) + size(rhs),
        _ => 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn expanded(src: &str) -> (String, Diagnostics) {
        let file = crate::syntax::parse(src).expect("parses");
        let mut d = Diagnostics::new();
        let out = expand(&file, &mut d);
        (format!("{:?}", out.stmts.last().unwrap().body), d)
    }

    #[test]
    fn a_name_in_place_is_written_out_and_a_constant_is_not() {
        let (body, d) = expanded(
            "let ring = 3 mm\nsection bore = circle(diameter = 30 mm)\nprofile p = place(bore, at = [ring, 0 mm], turn = 0 deg)",
        );
        assert!(d.is_empty());
        assert!(body.contains("circle"), "{body}");
        assert!(body.contains("Ident(\"ring\")"), "{body}");
    }

    #[test]
    fn a_name_for_a_name_is_written_out_to_the_shape() {
        let (body, d) = expanded(
            "section c = circle(diameter = 9 mm)\nprofile b = c\nprofile a = place(b, at = [0 mm, 0 mm], turn = 0 deg)",
        );
        assert!(d.is_empty(), "{d:?}");
        assert!(
            body.contains("circle") && !body.contains("Ident(\"b\")"),
            "{body}"
        );
    }

    #[test]
    fn a_shape_inside_itself_is_a_cycle() {
        let (_, d) = expanded(
            "profile a = place(b, at = [0 mm, 0 mm], turn = 0 deg)\nprofile b = region(outline = circle(diameter = 9 mm), holes = [a])",
        );
        assert_eq!(d.iter().count(), 2, "each declaration's own cycle: {d:?}");
        assert!(d.iter().all(|d| d.code == crate::diag::Code::Cycle));
    }

    #[test]
    fn copies_of_copies_stop_at_the_budget() {
        let mut src = String::from("section s0 = circle(diameter = 1 mm)\n");
        for k in 1..40 {
            let p = k - 1;
            src.push_str(&format!(
                "profile s{k} = region(outline = s{p}, holes = [s{p}, s{p}])\n"
            ));
        }
        let (_, d) = expanded(&src);
        assert!(
            d.iter().any(|d| d.code == crate::diag::Code::TooLarge),
            "{d:?}"
        );
    }
}
