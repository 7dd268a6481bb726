//! `lmdc fmt`: one canonical layout for `.lmd` files.
//!
//! The layout is printed from the syntax tree, so it cannot change what the
//! file means: [`format()`] parses its own output and refuses to return text
//! whose tree ([`without_spans`]) differs from the input's. Comments are not
//! in the tree; they are found in the text and put back where they were —
//! before the statement that follows them, or after the statement whose
//! line they end. A statement with a comment inside its value (between the
//! items of a list, say) is kept as written, only re-indented.
//!
//! The layout: one statement a line, blocks opened on the statement's line
//! and closed on a line of their own, two spaces of indentation, one space
//! round `=` and the infix operators, `60 mm` for a number and its unit, at
//! most one blank line between statements (where the file had one), the
//! trailing comments of consecutive one-line statements lined up two
//! spaces after the longest, a call or list that does not fit in
//! [`WIDTH`] columns broken one item a line with a trailing comma, and LF
//! line ends. Numbers keep their digits as written.

use crate::diag::Diagnostic;
use crate::span::{Span, Spanned};
use crate::syntax::ast::{Arg, BinOp, Body, Expr, ExprKind, File, Stmt, UnOp};

/// The column a line is kept within where a call or list can be broken.
pub const WIDTH: usize = 100;

/// Indentation of one level.
const INDENT: &str = "  ";

/// Why a text cannot be formatted.
#[derive(Debug)]
pub enum FmtError {
    /// It does not parse.
    Syntax(Box<Diagnostic>),
    /// The formatted text would mean something else (a bug in lmdc, never
    /// returned as text).
    Changed,
}

/// `source` in the canonical layout.
pub fn format(source: &str) -> Result<String, FmtError> {
    let file = crate::syntax::parse(source).map_err(|d| FmtError::Syntax(Box::new(d)))?;
    let comments = comments(source);
    let mut p = Printer {
        src: source,
        comments: &comments,
        out: String::new(),
    };
    p.region(&file.stmts, 0, source.len(), 0);
    let mut out = p.out;
    while out.ends_with("\n\n") {
        out.pop();
    }
    if !out.is_empty() && !out.ends_with('\n') {
        out.push('\n');
    }
    let same =
        crate::syntax::parse(&out).is_ok_and(|again| without_spans(again) == without_spans(file));
    if same {
        Ok(out)
    } else {
        Err(FmtError::Changed)
    }
}

/// A comment of the source: where it is.
#[derive(Clone, Copy, Debug)]
struct Comment {
    span: Span,
}

/// Every comment of `src` (which parses), in order: `//` to the line's end,
/// `/* … */`; texts in quotes skipped, as the grammar reads them.
fn comments(src: &str) -> Vec<Comment> {
    let b = src.as_bytes();
    let mut found = Vec::new();
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            b'"' => {
                i += 1;
                while i < b.len() && !matches!(b[i], b'"' | b'\n' | b'\r') {
                    i += 1;
                }
                i += 1;
            }
            b'/' if b.get(i + 1) == Some(&b'/') => {
                let start = i;
                while i < b.len() && !matches!(b[i], b'\n' | b'\r') {
                    i += 1;
                }
                found.push(Comment {
                    span: Span::new(start, i),
                });
            }
            b'/' if b.get(i + 1) == Some(&b'*') => {
                let start = i;
                i += 2;
                while i < b.len() && !(b[i] == b'*' && b.get(i + 1) == Some(&b'/')) {
                    i += 1;
                }
                i = (i + 2).min(b.len());
                found.push(Comment {
                    span: Span::new(start, i),
                });
            }
            _ => i += 1,
        }
    }
    found
}

/// Whether `text` holds a line end.
fn has_newline(text: &str) -> bool {
    text.contains(['\n', '\r'])
}

/// How many line ends `text` holds (CRLF counts once).
fn newlines(text: &str) -> usize {
    text.replace("\r\n", "\n").matches(['\n', '\r']).count()
}

/// One line of a run of statements: its code and its trailing comment.
struct Line {
    code: String,
    comment: Option<String>,
}

struct Printer<'s> {
    src: &'s str,
    comments: &'s [Comment],
    out: String,
}

impl<'s> Printer<'s> {
    /// The comments starting in `from..to`.
    fn comments_in(&self, from: usize, to: usize) -> Vec<Comment> {
        self.comments
            .iter()
            .filter(|c| c.span.start >= from && c.span.start < to)
            .copied()
            .collect()
    }

    fn text(&self, c: Comment) -> &'s str {
        self.src[c.span.start..c.span.end].trim_end()
    }

    /// Prints `stmts`, which lie in `from..to` of the source, at `depth`,
    /// with the comments between them.
    fn region(&mut self, stmts: &[Stmt], from: usize, to: usize, depth: usize) {
        let pad = INDENT.repeat(depth);
        let mut cursor = from;
        let mut run: Vec<Line> = Vec::new();
        let mut first = true;
        for (i, s) in stmts.iter().enumerate() {
            let leading = self.comments_in(cursor, s.span.start);
            let gap_start = cursor;
            // A blank line before the statement (or its comments) where
            // the file had one, not at the top of a region.
            let before = leading.first().map_or(s.span.start, |c| c.span.start);
            let blank = !first && newlines(&self.src[gap_start..before]) >= 2;
            if blank || !leading.is_empty() {
                self.flush(&mut run);
            }
            if blank {
                self.out.push('\n');
            }
            let mut at = None;
            for c in &leading {
                if at.is_some_and(|a| newlines(&self.src[a..c.span.start]) >= 2) {
                    self.out.push('\n');
                }
                self.out.push_str(&pad);
                self.out.push_str(self.text(*c));
                self.out.push('\n');
                at = Some(c.span.end);
            }
            if at.is_some_and(|a| newlines(&self.src[a..s.span.start]) >= 2) {
                self.out.push('\n');
            }
            first = false;
            // The trailing comments: on the statement's last line.
            let next = stmts.get(i + 1).map_or(to, |n| n.span.start);
            let line_end = self.src[end(self.src, s)..next]
                .find(['\n', '\r'])
                .map_or(next, |k| end(self.src, s) + k);
            let trailing: Vec<Comment> = self.comments_in(end(self.src, s), line_end);
            cursor = trailing.last().map_or(end(self.src, s), |c| c.span.end);
            let comment = (!trailing.is_empty()).then(|| {
                trailing
                    .iter()
                    .map(|c| self.text(*c))
                    .collect::<Vec<_>>()
                    .join(" ")
            });
            let code = self.stmt(s, depth);
            if has_newline(&code) || matches!(s.body, Body::Block(..)) {
                self.flush(&mut run);
                self.out.push_str(&code);
                if let Some(c) = comment {
                    self.out.push_str("  ");
                    self.out.push_str(&c);
                }
                self.out.push('\n');
            } else {
                run.push(Line { code, comment });
            }
        }
        self.flush(&mut run);
        let rest = self.comments_in(cursor, to);
        let mut at = cursor;
        for c in rest {
            if newlines(&self.src[at..c.span.start]) >= 2 && !stmts.is_empty() {
                self.out.push('\n');
            }
            self.out.push_str(&pad);
            self.out.push_str(self.text(c));
            self.out.push('\n');
            at = c.span.end;
        }
    }

    /// Prints a run of one-line statements, their trailing comments lined up.
    fn flush(&mut self, run: &mut Vec<Line>) {
        let col = run
            .iter()
            .filter(|l| l.comment.is_some())
            .map(|l| l.code.chars().count())
            .max()
            .unwrap_or(0);
        for l in run.drain(..) {
            self.out.push_str(&l.code);
            if let Some(c) = l.comment {
                let n = col - l.code.chars().count() + 2;
                self.out.push_str(&" ".repeat(n));
                self.out.push_str(&c);
            }
            self.out.push('\n');
        }
    }

    /// A statement at `depth` (its lines indented, no final line end).
    fn stmt(&mut self, s: &Stmt, depth: usize) -> String {
        let pad = INDENT.repeat(depth);
        let inner = self.comments_in(s.span.start, end(self.src, s));
        let braces = match &s.body {
            Body::Block(_, b) => Some(*b),
            _ => None,
        };
        let outside_braces = inner
            .iter()
            .any(|c| braces.is_none_or(|b| c.span.start < b.start || c.span.start >= b.end));
        if outside_braces {
            return self.verbatim(Span::new(s.span.start, end(self.src, s)), depth);
        }
        let mut head = format!("{pad}{}", s.kind.node);
        if let Some(n) = &s.name {
            head.push(' ');
            head.push_str(&self.name(n));
        }
        match &s.body {
            Body::None => head,
            Body::Assign(e) => {
                head.push_str(" = ");
                let flat = expr(self.src, e);
                let text = if head.chars().count() + flat.chars().count() <= WIDTH {
                    head + &flat
                } else {
                    head + &broken(self.src, e, depth)
                };
                // A unit lmdc does not know is one only before a line end or
                // a closing bracket (grammar/lmd.pest): where the layout
                // would move what follows it, the statement stays as written.
                if same_statement(&text, s) {
                    text
                } else {
                    self.verbatim(Span::new(s.span.start, end(self.src, s)), depth)
                }
            }
            Body::Block(stmts, b) => {
                let saved = std::mem::take(&mut self.out);
                // Comments on the line of `{` stay there.
                let line_end = self.src[b.start + 1..b.end]
                    .find(['\n', '\r'])
                    .map_or(b.end, |k| b.start + 1 + k);
                let first = stmts.first().map_or(b.end, |f| f.span.start);
                let on_brace = self.comments_in(b.start + 1, line_end.min(first));
                let from = on_brace.last().map_or(b.start + 1, |c| c.span.end);
                self.region(stmts, from, b.end.saturating_sub(1), depth + 1);
                let body = std::mem::replace(&mut self.out, saved);
                head.push_str(" {");
                let commented = !on_brace.is_empty();
                for c in on_brace {
                    head.push_str("  ");
                    head.push_str(self.text(c));
                }
                if body.is_empty() && !commented {
                    head.push('}');
                    return head;
                }
                format!("{head}\n{body}{pad}}}")
            }
        }
    }

    /// A statement's name as written: in quotes if it was.
    fn name(&self, n: &Spanned<String>) -> String {
        if self.src[n.span.start..].starts_with('"') {
            format!("\"{}\"", n.node)
        } else {
            n.node.clone()
        }
    }

    /// The source of `span` as written, its first line at `depth` and the
    /// lines after it moved so that the least indented is one level deeper;
    /// a last line that closes a bracket goes back to `depth`, as a broken
    /// call's `)` does.
    fn verbatim(&self, span: Span, depth: usize) -> String {
        let text = self.src[span.start..span.end]
            .replace("\r\n", "\n")
            .replace('\r', "\n");
        let mut lines = text.lines();
        let pad = INDENT.repeat(depth);
        let mut out = format!("{pad}{}", lines.next().unwrap_or_default().trim());
        let mut rest: Vec<&str> = lines.collect();
        let closing = rest
            .last()
            .map(|l| l.trim())
            .filter(|l| l.starts_with([')', ']', '}']));
        if closing.is_some() {
            rest.pop();
        }
        let least = rest
            .iter()
            .filter(|l| !l.trim().is_empty())
            .map(|l| l.len() - l.trim_start().len())
            .min()
            .unwrap_or(0);
        let deeper = INDENT.repeat(depth + 1);
        for l in rest {
            out.push('\n');
            if !l.trim().is_empty() {
                out.push_str(&deeper);
                out.push_str(l[least.min(l.len() - l.trim_start().len())..].trim_end());
            }
        }
        if let Some(close) = closing {
            out.push('\n');
            out.push_str(&pad);
            out.push_str(close);
        }
        out
    }
}

/// Whether `text` parses to the one statement `s`, spans aside.
fn same_statement(text: &str, s: &Stmt) -> bool {
    let Ok(f) = crate::syntax::parse(text) else {
        return false;
    };
    let want = without_spans(File {
        stmts: vec![s.clone()],
    });
    without_spans(f) == want
}

/// Where a statement's last token ends: the parser's span of a statement
/// runs on over the blanks and comments after it, and an expression's stops
/// short of the brackets round its last operand.
fn end(src: &str, s: &Stmt) -> usize {
    match &s.body {
        Body::Assign(e) => {
            let mut at = e.span.end;
            let mut scan = at;
            let b = src.as_bytes();
            while scan < b.len() {
                match b[scan] {
                    b' ' | b'\t' | b'\n' | b'\r' => scan += 1,
                    b')' => {
                        scan += 1;
                        at = scan;
                    }
                    b'/' if b.get(scan + 1) == Some(&b'*') => {
                        scan = src[scan + 2..]
                            .find("*/")
                            .map_or(b.len(), |k| scan + 2 + k + 2);
                    }
                    b'/' if b.get(scan + 1) == Some(&b'/') => {
                        scan = src[scan..].find(['\n', '\r']).map_or(b.len(), |k| scan + k);
                    }
                    _ => break,
                }
            }
            at
        }
        Body::Block(_, b) => b.end,
        Body::None => s.name.as_ref().map_or(s.kind.span.end, |n| n.span.end),
    }
}

/// How tightly an expression binds (loosest first), as the parser's Pratt
/// table says.
fn strength(e: &Expr) -> u8 {
    match &e.kind {
        ExprKind::Binary { op, .. } => match op {
            BinOp::Range => 1,
            BinOp::Add | BinOp::Sub => 2,
            BinOp::Mul | BinOp::Div => 3,
            BinOp::Pow => 5,
        },
        ExprKind::Unary { .. } => 4,
        _ => 6,
    }
}

/// `e` on one line.
fn expr(src: &str, e: &Expr) -> String {
    match &e.kind {
        ExprKind::Number { unit, .. } => {
            let end = unit.as_ref().map_or(e.span.end, |u| u.span.start);
            let digits = src[e.span.start..end].trim();
            match unit {
                Some(u) => format!("{digits} {}", u.node),
                None => digits.to_string(),
            }
        }
        ExprKind::Ident(n) => n.clone(),
        ExprKind::Str(s) => format!("\"{s}\""),
        ExprKind::Call { func, args } => {
            let items: Vec<String> = args.iter().map(|a| arg(src, a, None)).collect();
            format!("{}({})", func.node, items.join(", "))
        }
        ExprKind::List(items) => {
            let items: Vec<String> = items.iter().map(|x| expr(src, x)).collect();
            format!("[{}]", items.join(", "))
        }
        ExprKind::Unary { op, expr: x } => {
            let sign = match op {
                UnOp::Neg => "-",
                UnOp::Pos => "+",
            };
            format!("{sign}{}", wrapped(src, x, strength(x) < 4))
        }
        ExprKind::Binary { op, lhs, rhs } => {
            let me = strength(e);
            // Left-associative but `^`: the right operand of equal strength
            // needs brackets, and for `^` the left one.
            let (l, r) = if *op == BinOp::Pow {
                (strength(lhs) <= me, strength(rhs) < me)
            } else {
                (strength(lhs) < me, strength(rhs) <= me)
            };
            // `a / (1 mm/s)`: a quantity with a compound unit after `*` or
            // `/` keeps its brackets, for the reader (the tree is the same).
            let compound = matches!(&rhs.kind, ExprKind::Number { unit: Some(u), .. } if u.node.contains(['/', '*', '·']));
            let r = r || (compound && matches!(op, BinOp::Mul | BinOp::Div));
            format!(
                "{} {} {}",
                wrapped(src, lhs, l),
                op.symbol(),
                wrapped(src, rhs, r)
            )
        }
    }
}

/// `e`, in brackets when `bracket`.
fn wrapped(src: &str, e: &Expr, bracket: bool) -> String {
    if bracket {
        format!("({})", expr(src, e))
    } else {
        expr(src, e)
    }
}

/// An argument; broken over lines at `depth` when given one.
fn arg(src: &str, a: &Arg, depth: Option<usize>) -> String {
    let value = match depth {
        Some(d) => broken(src, &a.value, d),
        None => expr(src, &a.value),
    };
    match &a.name {
        Some(n) => format!("{} = {value}", n.node),
        None => value,
    }
}

/// `e` written to start at the end of a line at `depth`: a call or list
/// one item a line (each item flat if it fits, else broken in turn), any
/// other expression flat.
fn broken(src: &str, e: &Expr, depth: usize) -> String {
    let pad = INDENT.repeat(depth + 1);
    let fits = |s: &str| pad.len() + s.chars().count() < WIDTH;
    let items: Vec<String> = match &e.kind {
        ExprKind::Call { args, .. } => args
            .iter()
            .map(|a| {
                let flat = arg(src, a, None);
                if fits(&flat) {
                    flat
                } else {
                    arg(src, a, Some(depth + 1))
                }
            })
            .collect(),
        ExprKind::List(xs) => xs
            .iter()
            .map(|x| {
                let flat = expr(src, x);
                if fits(&flat) {
                    flat
                } else {
                    broken(src, x, depth + 1)
                }
            })
            .collect(),
        _ => return expr(src, e),
    };
    let (open, close) = match &e.kind {
        ExprKind::Call { func, .. } => (format!("{}(", func.node), ")"),
        _ => ("[".to_string(), "]"),
    };
    if items.is_empty() {
        return format!("{open}{close}");
    }
    let mut out = open;
    for i in items {
        out.push('\n');
        out.push_str(&pad);
        out.push_str(&i);
        out.push(',');
    }
    out.push('\n');
    out.push_str(&INDENT.repeat(depth));
    out.push_str(close);
    out
}

/// `file` with every span zeroed: two files with equal trees compare equal
/// however they were laid out.
pub fn without_spans(file: File) -> File {
    let mut file = file;
    file.stmts.iter_mut().for_each(stmt_without_spans);
    file
}

fn stmt_without_spans(s: &mut Stmt) {
    s.span = Span::default();
    s.kind.span = Span::default();
    if let Some(n) = &mut s.name {
        n.span = Span::default();
    }
    match &mut s.body {
        Body::None => {}
        Body::Assign(e) => expr_without_spans(e),
        Body::Block(stmts, b) => {
            *b = Span::default();
            stmts.iter_mut().for_each(stmt_without_spans);
        }
    }
}

fn expr_without_spans(e: &mut Expr) {
    e.span = Span::default();
    match &mut e.kind {
        ExprKind::Number { unit, .. } => {
            if let Some(u) = unit {
                u.span = Span::default();
            }
        }
        ExprKind::Ident(_) | ExprKind::Str(_) => {}
        ExprKind::Call { func, args } => {
            func.span = Span::default();
            for a in args {
                if let Some(n) = &mut a.name {
                    n.span = Span::default();
                }
                expr_without_spans(&mut a.value);
            }
        }
        ExprKind::List(items) => items.iter_mut().for_each(expr_without_spans),
        ExprKind::Unary { expr, .. } => expr_without_spans(expr),
        ExprKind::Binary { lhs, rhs, .. } => {
            expr_without_spans(lhs);
            expr_without_spans(rhs);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fmt(s: &str) -> String {
        format(s).unwrap()
    }

    #[test]
    fn a_canonical_layout() {
        let src = "part   p\nlet R=2*(3mm+4 mm)   // r\nlet  S = -(1 mm)^2\n\n\n\nbead b{width=3mm\nmodel=measured(height=1mm,speed=6mm/s)}\n";
        assert_eq!(
            fmt(src),
            "part p\nlet R = 2 * (3 mm + 4 mm)  // r\nlet S = -1 mm ^ 2\n\nbead b {\n  width = 3 mm\n  model = measured(height = 1 mm, speed = 6 mm/s)\n}\n"
        );
    }

    #[test]
    fn brackets_where_the_tree_needs_them() {
        for (src, want) in [
            ("let a = (1 - 2) - 3", "let a = 1 - 2 - 3"),
            ("let a = 1 - (2 - 3)", "let a = 1 - (2 - 3)"),
            ("let a = (2 ^ 3) ^ 4", "let a = (2 ^ 3) ^ 4"),
            ("let a = 2 ^ 3 ^ 4", "let a = 2 ^ 3 ^ 4"),
            ("let a = (-2) ^ 2", "let a = (-2) ^ 2"),
            ("let a = 2 ^ -2", "let a = 2 ^ (-2)"),
            ("let a = (1 .. 2)", "let a = 1 .. 2"),
            ("let a = - - 1", "let a = --1"),
            ("let a = 2 mm / (1 mm/s)", "let a = 2 mm / (1 mm/s)"),
            ("let a = 2 mm / 1 mm", "let a = 2 mm / 1 mm"),
        ] {
            assert_eq!(fmt(src), format!("{want}\n"), "{src}");
        }
    }

    #[test]
    fn comments_are_kept_and_lined_up() {
        let src = "// head\n\npart p // the part\nbead b { // beads\n  width = 3 mm // w\n  height_long_name = 1 mm /* h */\n  // last\n}\n// end\n";
        let out = fmt(src);
        assert_eq!(
            out,
            "// head\n\npart p  // the part\nbead b {  // beads\n  width = 3 mm             // w\n  height_long_name = 1 mm  /* h */\n  // last\n}\n// end\n"
        );
        assert_eq!(fmt(&out), out, "idempotent");
    }

    #[test]
    fn a_comment_inside_a_value_keeps_the_statement_as_written() {
        let src = "let L = [1 mm,   // one\n      2 mm]\n";
        assert_eq!(fmt(src), "let L = [1 mm,   // one\n  2 mm]\n");
        assert_eq!(fmt(&fmt(src)), fmt(src));
        // Broken one item a line, its `)` back at the statement's depth
        // as a call lmdc breaks itself, however deep it was written.
        let src = "extrude e {\n  on = scan(\n      file = \"a.ply\",  // the scan\n        cell = 1 mm,\n    )\n}\n";
        let want = "extrude e {\n  on = scan(\n    file = \"a.ply\",  // the scan\n      cell = 1 mm,\n  )\n}\n";
        assert_eq!(fmt(src), want);
        assert_eq!(fmt(want), want);
    }

    #[test]
    fn long_calls_break_one_item_a_line() {
        let long = (0..20)
            .map(|i| format!("[{i} mm, 0 mm]"))
            .collect::<Vec<_>>()
            .join(", ");
        let src = format!("section s = outline({long})\n");
        let out = fmt(&src);
        assert!(out.lines().all(|l| l.chars().count() <= WIDTH), "{out}");
        assert!(out.contains("outline(\n  [0 mm, 0 mm],\n"), "{out}");
        assert_eq!(fmt(&out), out);
    }

    #[test]
    fn syntax_errors_are_refused() {
        assert!(matches!(format("let = ("), Err(FmtError::Syntax(_))));
    }
}
