//! The file's names: where each is declared (`let`, `section`, `bead`,
//! `loft`, …) and where it is used, from the tokens.

use super::scan::{starts_entry, Tok, Token};
use crate::span::Span;

/// The statement words that declare a name others may use.
pub const DECLARING: &[&str] = &[
    "let", "section", "profile", "bead", "loft", "extrude", "style", "machine", "ring", "wall",
];

/// A declared name.
#[derive(Clone, Debug, PartialEq)]
pub struct Decl {
    /// The declaring word: `let`, `bead`, …
    pub kind: String,
    /// The name.
    pub name: String,
    /// Where the name is written.
    pub name_span: Span,
    /// The whole statement, as far as the next top-level one.
    pub span: Span,
}

/// Every declaration at the top of the file.
pub fn declarations(text: &str, toks: &[Token]) -> Vec<Decl> {
    let word = |t: &Token| &text[t.span.start..t.span.end];
    let mut depth = 0i64;
    let mut starts = Vec::new();
    for (i, t) in toks.iter().enumerate() {
        match t.tok {
            Tok::Punct('{' | '(' | '[') => depth += 1,
            Tok::Punct('}' | ')' | ']') => depth -= 1,
            Tok::Ident if depth <= 0 && starts_entry(toks, i) => starts.push(i),
            _ => {}
        }
    }
    let mut out = Vec::new();
    for (n, &i) in starts.iter().enumerate() {
        let kind = word(&toks[i]);
        let Some(name) = toks.get(i + 1).filter(|t| t.tok == Tok::Ident) else {
            continue;
        };
        if !DECLARING.contains(&kind) || name.line != toks[i].line {
            continue;
        }
        let end = starts
            .get(n + 1)
            .map_or(text.len(), |&j| toks[j].span.start);
        let end = text[..end].trim_end().len();
        out.push(Decl {
            kind: kind.to_string(),
            name: word(name).to_string(),
            name_span: name.span,
            span: Span::new(toks[i].span.start, end.max(name.span.end)),
        });
    }
    out
}

/// The unit token `i` is (part of), whole: `W` in `power = 1800 W`,
/// `mm/s` for the `s` of `7 mm/s`. The grammar decides, read from each
/// number before it on its line ([`crate::syntax::unit_after`]), so a unit
/// spelt as a constant's name is never taken for the constant.
pub fn unit_at(text: &str, toks: &[Token], i: usize) -> Option<Span> {
    let t = toks[i];
    for p in toks[..i].iter().rev().take(16) {
        if p.line != t.line {
            return None;
        }
        match p.tok {
            Tok::Number => {
                let unit = crate::syntax::unit_after(text, p.span.start)
                    .filter(|u| u.start <= t.span.start && t.span.end <= u.end);
                if unit.is_some() {
                    return unit;
                }
            }
            Tok::Ident | Tok::Punct('/' | '*' | '^' | '-' | '·') => {}
            _ => return None,
        }
    }
    None
}

/// Whether token `i` is (part of) a unit ([`unit_at`]).
pub fn is_unit(text: &str, toks: &[Token], i: usize) -> bool {
    unit_at(text, toks, i).is_some()
}

/// Where `name` is used: every token of it that is not a field's key, a
/// declaration's name or a unit.
pub fn uses(text: &str, toks: &[Token], name: &str, decls: &[Decl]) -> Vec<Span> {
    toks.iter()
        .enumerate()
        .filter(|(i, t)| {
            t.tok == Tok::Ident
                && &text[t.span.start..t.span.end] == name
                && !decls.iter().any(|d| d.name_span == t.span)
                && !is_key(toks, *i)
                && !is_unit(text, toks, *i)
        })
        .map(|(_, t)| t.span)
        .collect()
}

/// Whether token `i` is a field's key or a statement's word (`width` in
/// `width = 6 mm`, `limits` in `limits {`).
pub fn is_key(toks: &[Token], i: usize) -> bool {
    starts_entry(toks, i)
        && toks
            .get(i + 1)
            .is_some_and(|n| matches!(n.tok, Tok::Punct('=' | '{')) || n.tok == Tok::Ident)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lsp::scan::tokens;

    #[test]
    fn declarations_and_their_uses() {
        let text = "let w = 6 mm\nbead b {\n  width = w\n}\nloft l { wall = b  from = w }\n";
        let t = tokens(text);
        let d = declarations(text, &t);
        let names: Vec<&str> = d.iter().map(|d| d.name.as_str()).collect();
        assert_eq!(names, ["w", "b", "l"]);
        assert_eq!(
            &text[d[1].span.start..d[1].span.end],
            "bead b {\n  width = w\n}"
        );
        let u = uses(text, &t, "w", &d);
        assert_eq!(u.len(), 2);
        assert!(u.iter().all(|s| &text[s.start..s.end] == "w"));
    }

    #[test]
    fn a_unit_spelt_as_a_constant_is_a_unit() {
        let text = "let W = 3 mm\nlet s = 2\np = 1800 W  v = 7 mm/s  q = s * W\nk = 1.5 KW\n";
        let t = tokens(text);
        let d = declarations(text, &t);
        let at = |needle: &str, n: usize| {
            let o = text.match_indices(needle).nth(n).unwrap().0;
            t.iter().position(|t| t.span.start == o).unwrap()
        };
        assert!(is_unit(text, &t, at("W", 1)), "1800 W");
        assert!(is_unit(text, &t, at("s", 1)), "mm/s");
        assert!(
            is_unit(text, &t, at("KW", 0)),
            "an unknown unit at a line's end"
        );
        assert!(!is_unit(text, &t, at("s", 2)), "s * W uses the constant");
        assert!(!is_unit(text, &t, at("W", 2)), "s * W uses the constant");
        let w: Vec<usize> = uses(text, &t, "W", &d).iter().map(|s| s.start).collect();
        assert_eq!(w, [text.find("* W").unwrap() + 2]);
    }
}
