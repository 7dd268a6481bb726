//! pest pairs → [`ast::File`]. The grammar is in `grammar/lmd.pest`.

use super::ast::*;
use crate::diag::{message, Diagnostic};
use crate::span::{Span, Spanned};
use pest::iterators::Pair;
use pest::pratt_parser::{Assoc, Op, PrattParser};
use pest::Parser;
use std::sync::OnceLock;

#[derive(pest_derive::Parser)]
#[grammar = "../grammar/lmd.pest"]
struct LmdParser;

/// Deeper nesting than this is refused before parsing, so no input can exhaust the
/// stack of the recursive-descent parser.
pub const MAX_NESTING: usize = 64;

/// The deepest expression accepted: operators and brackets nested into one
/// another along one path (`-(-(1))` is 4 deep: two signs, two brackets;
/// `1 + 2 + 3` is 2; `f([1, 2])` is 2). pest reads
/// a chain of operators in a loop, but the Pratt parser, the tree and the
/// evaluator recurse once per level, so without a bound ten thousand minus
/// signs overflow the stack. 256 is far beyond any hand-written value and, at
/// the debug build's frame sizes, well inside a 2 MiB thread stack.
pub const MAX_EXPR_DEPTH: usize = 256;

/// Parses a whole file. pest stops at the first syntax error, so this returns one
/// diagnostic; everything after parsing accumulates errors.
///
/// A leading UTF-8 byte order mark and every line-end convention (LF, CRLF,
/// CR alone) are accepted; spans refer to `source` as given.
pub fn parse(source: &str) -> Result<File, Diagnostic> {
    let normalized = normalize(source);
    let source: &str = &normalized;
    check_nesting(source)?;
    let mut pairs = LmdParser::parse(Rule::file, source).map_err(|e| syntax_error(source, e))?;
    let file = pairs.next().ok_or_else(message::syntax::empty_parse)?;
    let stmts = file
        .into_inner()
        .filter(|p| p.as_rule() == Rule::stmt)
        .map(stmt)
        .collect::<Result<_, _>>()?;
    Ok(File { stmts })
}

/// The unit written after the number that starts at byte `number` of
/// `source`, as the grammar reads a quantity there (`mm/s` in `7 mm/s`,
/// `KW` in `1.5 KW` at a line's end), or `None` when the number stands
/// alone. The language server asks this to tell a unit from a name spelt
/// the same (`W` in `1800 W` beside `let W = 3 mm`): only the grammar
/// decides what a word after a number is.
pub fn unit_after(source: &str, number: usize) -> Option<Span> {
    let rest = source.get(number..)?;
    let quantity = LmdParser::parse(Rule::quantity, rest).ok()?.next()?;
    quantity
        .into_inner()
        .find(|p| matches!(p.as_rule(), Rule::unit | Rule::unknown_unit))
        .map(|u| Span::new(number + u.as_span().start(), number + u.as_span().end()))
}

/// The source as the grammar reads it, byte for byte as long as `source`, so
/// every span points at the same text in both: a leading byte order mark
/// (U+FEFF, 3 bytes, which editors on Windows write) becomes 3 spaces, and a
/// carriage return not followed by a line feed (classic Mac OS line ends)
/// becomes a line feed, since the grammar ends comments and strings at `\n`
/// and would otherwise read a CR-only file as one line.
fn normalize(source: &str) -> std::borrow::Cow<'_, str> {
    let bom = source.starts_with('\u{feff}');
    let lone_cr = source
        .as_bytes()
        .windows(2)
        .any(|w| w[0] == b'\r' && w[1] != b'\n')
        || source.ends_with('\r');
    if !bom && !lone_cr {
        return source.into();
    }
    let mut bytes = source.as_bytes().to_vec();
    if bom {
        bytes[..3].copy_from_slice(b"   ");
    }
    for i in 0..bytes.len() {
        if bytes[i] == b'\r' && bytes.get(i + 1) != Some(&b'\n') {
            bytes[i] = b'\n';
        }
    }
    // Only ASCII bytes and a whole 3-byte character were replaced by ASCII.
    String::from_utf8(bytes)
        .map(Into::into)
        .unwrap_or_else(|_| source.into())
}

/// Checks brackets before pest runs: refuses nesting deeper than [`MAX_NESTING`]
/// (so no input can exhaust the parser's stack) and reports an unclosed or
/// mismatched bracket at the bracket itself, which says far more than pest's
/// "expected …" at the place where it gave up. Skips comments and strings.
fn check_nesting(source: &str) -> Result<(), Diagnostic> {
    let mut open: Vec<(char, usize)> = Vec::new();
    let bytes = source.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        let c = bytes[i];
        match c {
            b'/' if bytes.get(i + 1) == Some(&b'/') => {
                while i < bytes.len() && bytes[i] != b'\n' {
                    i += 1;
                }
                continue;
            }
            b'/' if bytes.get(i + 1) == Some(&b'*') => {
                i = match source[i + 2..].find("*/") {
                    Some(end) => i + 2 + end + 2,
                    // Everything after it is comment: the brackets before it
                    // look unclosed, but the comment is what needs fixing.
                    None => return Err(message::syntax::unclosed_comment(Span::new(i, i + 2))),
                };
                continue;
            }
            b'"' => {
                let open_at = i;
                i += 1;
                while i < bytes.len() && bytes[i] != b'"' && bytes[i] != b'\n' {
                    i += 1;
                }
                if i == bytes.len() || bytes[i] == b'\n' {
                    // pest would say "expected …" somewhere after it; the
                    // quote that opens the string is what needs fixing.
                    return Err(message::syntax::unclosed_text(Span::new(open_at, i)));
                }
            }
            b'(' | b'[' | b'{' => {
                open.push((c as char, i));
                if open.len() > MAX_NESTING {
                    return Err(message::syntax::brackets_too_deep(
                        MAX_NESTING,
                        Span::new(i, i + 1),
                    ));
                }
            }
            b')' | b']' | b'}' => {
                let want = match c {
                    b')' => '(',
                    b']' => '[',
                    _ => '{',
                };
                match open.pop() {
                    Some((o, _)) if o == want => {}
                    Some((o, at)) => {
                        return Err(message::syntax::mismatched_bracket(
                            o,
                            Span::new(at, at + 1),
                            c as char,
                            Span::new(i, i + 1),
                            closer(o),
                        ));
                    }
                    None => {
                        return Err(message::syntax::closes_nothing(
                            c as char,
                            Span::new(i, i + 1),
                        ));
                    }
                }
            }
            _ => {}
        }
        i += 1;
    }
    if let Some((o, at)) = open.pop() {
        return Err(message::syntax::never_closed(
            o,
            Span::new(at, at + 1),
            closer(o),
        ));
    }
    Ok(())
}

fn closer(open: char) -> char {
    match open {
        '(' => ')',
        '[' => ']',
        _ => '}',
    }
}

fn rule_name(r: &Rule) -> &'static str {
    match r {
        Rule::EOI => "end of file",
        Rule::stmt => "a statement (like `width = 6 mm` or `bead wall { … }`)",
        Rule::name => "a name",
        Rule::assign => "`=`",
        Rule::block => "`{`",
        Rule::expr => "a value",
        Rule::quantity | Rule::number => "a number",
        Rule::unit | Rule::unit_atom | Rule::unit_factor | Rule::unknown_unit => {
            "a unit (mm, deg, mm/s, W, g/min, …)"
        }
        Rule::string | Rule::string_inner => "a string",
        Rule::ident => "a name",
        Rule::call => "a function call",
        Rule::arg => "an argument",
        Rule::list => "a list `[…]`",
        Rule::range => "`..`",
        Rule::add => "`+`",
        Rule::sub | Rule::neg => "`-`",
        Rule::mul => "`*`",
        Rule::div => "`/`",
        Rule::pow => "`^`",
        Rule::pos => "`+`",
        _ => "something else",
    }
}

fn syntax_error(source: &str, e: pest::error::Error<Rule>) -> Diagnostic {
    use pest::error::{ErrorVariant, InputLocation};
    let span = match e.location {
        InputLocation::Pos(p) => Span::new(p, p),
        InputLocation::Span((a, b)) => Span::new(a, b),
    };
    let expected = match &e.variant {
        ErrorVariant::ParsingError { positives, .. } => {
            let mut names: Vec<&str> = positives.iter().map(rule_name).collect();
            names.sort_unstable();
            names.dedup();
            names
        }
        ErrorVariant::CustomError { .. } => Vec::new(),
    };
    // A letter outside ASCII where pest stopped: a name written with it.
    let letter = source
        .get(span.start..)
        .and_then(|rest| rest.chars().next())
        .filter(|c| !c.is_ascii() && c.is_alphabetic());
    message::syntax::syntax_error(span, &expected, letter)
}

fn span_of(p: &Pair<Rule>) -> Span {
    p.as_span().into()
}

fn ident(p: Pair<Rule>) -> Ident {
    Spanned::new(p.as_str().to_string(), span_of(&p))
}

fn stmt(p: Pair<Rule>) -> Result<Stmt, Diagnostic> {
    let span = span_of(&p);
    let mut kind = None;
    let mut name = None;
    let mut body = Body::None;
    for c in p.into_inner() {
        match c.as_rule() {
            Rule::ident => kind = Some(ident(c)),
            Rule::name => {
                if let Some(n) = c.into_inner().next() {
                    let s = span_of(&n);
                    let text = match n.as_rule() {
                        Rule::string => n.into_inner().as_str().to_string(),
                        _ => n.as_str().to_string(),
                    };
                    name = Some(Spanned::new(text, s));
                }
            }
            Rule::assign => {
                if let Some(e) = c.into_inner().next() {
                    check_depth(&e)?;
                    body = Body::Assign(expr(e)?);
                }
            }
            Rule::block => {
                let bs = span_of(&c);
                let inner = c.into_inner().map(stmt).collect::<Result<_, _>>()?;
                body = Body::Block(inner, bs);
            }
            _ => {}
        }
    }
    let kind = kind.ok_or_else(message::syntax::statement_without_name)?;
    Ok(Stmt {
        kind,
        name,
        body,
        span,
    })
}

/// Refuses an expression whose tree would be deeper than [`MAX_EXPR_DEPTH`],
/// before the Pratt parser recurses into it. Recurses only per bracket, which
/// [`check_nesting`] has bounded to [`MAX_NESTING`].
fn check_depth(e: &Pair<Rule>) -> Result<usize, Diagnostic> {
    let mut operators = 0;
    let mut deepest = 0;
    for c in e.clone().into_inner() {
        let inner = match c.as_rule() {
            Rule::neg
            | Rule::pos
            | Rule::range
            | Rule::add
            | Rule::sub
            | Rule::mul
            | Rule::div
            | Rule::pow => {
                operators += 1;
                0
            }
            Rule::expr => 1 + check_depth(&c)?,
            Rule::list => {
                1 + c
                    .into_inner()
                    .map(|x| check_depth(&x))
                    .try_fold(0, |m, d| d.map(|d| m.max(d)))?
            }
            Rule::call => {
                1 + c
                    .into_inner()
                    .filter(|a| a.as_rule() == Rule::arg)
                    .flat_map(|a| a.into_inner().filter(|x| x.as_rule() == Rule::expr))
                    .map(|x| check_depth(&x))
                    .try_fold(0, |m, d| d.map(|d| m.max(d)))?
            }
            _ => 0,
        };
        deepest = deepest.max(inner);
    }
    let depth = operators + deepest;
    if depth > MAX_EXPR_DEPTH {
        return Err(message::syntax::expression_too_deep(
            depth,
            MAX_EXPR_DEPTH,
            operators,
            span_of(e),
        ));
    }
    Ok(depth)
}

fn pratt() -> &'static PrattParser<Rule> {
    static P: OnceLock<PrattParser<Rule>> = OnceLock::new();
    P.get_or_init(|| {
        PrattParser::new()
            .op(Op::infix(Rule::range, Assoc::Left))
            .op(Op::infix(Rule::add, Assoc::Left) | Op::infix(Rule::sub, Assoc::Left))
            .op(Op::infix(Rule::mul, Assoc::Left) | Op::infix(Rule::div, Assoc::Left))
            .op(Op::prefix(Rule::neg) | Op::prefix(Rule::pos))
            .op(Op::infix(Rule::pow, Assoc::Right))
    })
}

fn expr(p: Pair<Rule>) -> Result<Expr, Diagnostic> {
    pratt()
        .map_primary(primary)
        .map_prefix(|op, rhs| {
            let rhs = rhs?;
            let span = span_of(&op).join(rhs.span);
            let op = if op.as_rule() == Rule::neg {
                UnOp::Neg
            } else {
                UnOp::Pos
            };
            Ok(Expr {
                kind: ExprKind::Unary {
                    op,
                    expr: Box::new(rhs),
                },
                span,
            })
        })
        .map_infix(|lhs, op, rhs| {
            let (lhs, rhs) = (lhs?, rhs?);
            let op = match op.as_rule() {
                Rule::range => BinOp::Range,
                Rule::add => BinOp::Add,
                Rule::sub => BinOp::Sub,
                Rule::mul => BinOp::Mul,
                Rule::div => BinOp::Div,
                _ => BinOp::Pow,
            };
            Ok(Expr {
                span: lhs.span.join(rhs.span),
                kind: ExprKind::Binary {
                    op,
                    lhs: Box::new(lhs),
                    rhs: Box::new(rhs),
                },
            })
        })
        .parse(p.into_inner())
}

fn primary(p: Pair<Rule>) -> Result<Expr, Diagnostic> {
    let span = span_of(&p);
    let kind = match p.as_rule() {
        Rule::quantity => {
            let mut value = 0.0;
            let mut unit = None;
            for c in p.into_inner() {
                match c.as_rule() {
                    Rule::number => {
                        value = c.as_str().parse::<f64>().unwrap_or(f64::INFINITY);
                        if !value.is_finite() {
                            return Err(message::syntax::number_too_large(span_of(&c)));
                        }
                    }
                    Rule::unit | Rule::unknown_unit => {
                        unit = Some(Spanned::new(c.as_str().to_string(), span_of(&c)))
                    }
                    _ => {}
                }
            }
            ExprKind::Number { value, unit }
        }
        Rule::ident => ExprKind::Ident(p.as_str().to_string()),
        Rule::string => ExprKind::Str(p.into_inner().as_str().to_string()),
        Rule::list => ExprKind::List(p.into_inner().map(expr).collect::<Result<_, _>>()?),
        Rule::call => {
            let mut inner = p.into_inner();
            let func = inner
                .next()
                .map(ident)
                .ok_or_else(message::syntax::call_without_name)?;
            let mut args = Vec::new();
            for a in inner {
                let mut parts = a.into_inner();
                let first = parts.next();
                let second = parts.next();
                match (first, second) {
                    (Some(n), Some(v)) => args.push(Arg {
                        name: Some(ident(n)),
                        value: expr(v)?,
                    }),
                    (Some(v), None) => args.push(Arg {
                        name: None,
                        value: expr(v)?,
                    }),
                    _ => {}
                }
            }
            ExprKind::Call { func, args }
        }
        Rule::expr => return expr(p),
        _ => return Err(message::syntax::unexpected_expression(span)),
    };
    Ok(Expr { kind, span })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diag::Code;

    fn one_expr(src: &str) -> Expr {
        let f = parse(&format!("x = {src}")).unwrap();
        match &f.stmts[0].body {
            Body::Assign(e) => e.clone(),
            b => panic!("{b:?}"),
        }
    }

    #[test]
    fn quantities_keep_their_units() {
        match one_expr("7.5 mm/s").kind {
            ExprKind::Number { value, unit } => {
                assert_eq!(value, 7.5);
                assert_eq!(unit.unwrap().node, "mm/s");
            }
            k => panic!("{k:?}"),
        }
    }

    #[test]
    fn precedence() {
        // 1 mm + 2 mm * 3  ==  1 mm + (2 mm * 3)
        match one_expr("1 mm + 2 mm * 3").kind {
            ExprKind::Binary { op, rhs, .. } => {
                assert_eq!(op, BinOp::Add);
                assert!(matches!(rhs.kind, ExprKind::Binary { op: BinOp::Mul, .. }));
            }
            k => panic!("{k:?}"),
        }
        match one_expr("1 mm .. 2 mm").kind {
            ExprKind::Binary { op, .. } => assert_eq!(op, BinOp::Range),
            k => panic!("{k:?}"),
        }
    }

    #[test]
    fn a_unit_never_swallows_the_next_line() {
        let f = parse("layers = 40\ng = 1").unwrap();
        assert_eq!(f.stmts.len(), 2);
    }

    #[test]
    fn statements_and_blocks() {
        let f = parse("part duct\nlet R = 100 mm\nbead wall {\n width = 6 mm\n}\n").unwrap();
        assert_eq!(f.stmts.len(), 3);
        assert_eq!(f.stmts[0].name.as_ref().unwrap().node, "duct");
        assert!(matches!(f.stmts[2].body, Body::Block(ref b, _) if b.len() == 1));
    }

    #[test]
    fn byte_order_mark_and_every_line_end() {
        let lf = "part p // a comment\nlet a = 1 mm\nbead b {\n width = a\n}\n";
        let want = parse(lf).unwrap();
        for src in [
            format!("\u{feff}{lf}"),
            lf.replace('\n', "\r\n"),
            lf.replace('\n', "\r"),
            format!("\u{feff}{}", lf.replace('\n', "\r")),
        ] {
            let f = parse(&src).unwrap_or_else(|e| panic!("{src:?}: {e:?}"));
            assert_eq!(f.stmts.len(), want.stmts.len(), "{src:?}");
            // Spans are the given text's: the same bytes, same length.
            let s = &f.stmts[1];
            assert_eq!(&src[s.kind.span.start..s.kind.span.end], "let");
            assert_eq!(&src[s.name.as_ref().unwrap().span.start..][..1], "a");
        }
    }

    #[test]
    fn an_unclosed_text_is_reported_at_its_quote() {
        for src in ["part \"p\nlet a = 1", "part \"p", "part \"p\rlet a = 1"] {
            let d = parse(src).unwrap_err();
            assert_eq!(d.code, Code::Syntax);
            assert_eq!(d.labels[0].span.start, 5, "{src:?}");
        }
    }

    #[test]
    fn expression_depth_is_bounded() {
        let at = |n: usize| format!("x = {}1", "-".repeat(n));
        assert!(parse(&at(MAX_EXPR_DEPTH)).is_ok());
        assert_eq!(
            parse(&at(MAX_EXPR_DEPTH + 1)).unwrap_err().code,
            Code::DeepExpression
        );
        // Brackets count too: 60 brackets, each holding 4 signs, is 300 deep.
        let mixed = format!("x = {}1{}", "----(".repeat(60), ")".repeat(60));
        assert_eq!(parse(&mixed).unwrap_err().code, Code::DeepExpression);
        let long = format!("x = [{}]", vec!["-1 mm"; 10_000].join(", "));
        assert!(parse(&long).is_ok(), "a long flat list is not deep");
    }

    #[test]
    fn deep_nesting_is_refused_not_a_crash() {
        let src = format!("x = {}1{}", "(".repeat(10_000), ")".repeat(10_000));
        assert_eq!(parse(&src).unwrap_err().code, Code::TooDeep);
    }
}
