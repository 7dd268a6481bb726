//! The file's names: where each is declared (`let`, `section`, `bead`,
//! `loft`, …) and where it is used, from the tokens.

use super::scan::{starts_entry, Tok, Token};
use crate::span::Span;

/// The statement words that declare a name others may use.
pub const DECLARING: &[&str] = &[
    "let", "section", "profile", "bead", "loft", "extrude", "style", "machine", "ring",
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

/// Where `name` is used: every token of it that is not a field's key or a
/// declaration's name.
pub fn uses(text: &str, toks: &[Token], name: &str, decls: &[Decl]) -> Vec<Span> {
    toks.iter()
        .enumerate()
        .filter(|(i, t)| {
            t.tok == Tok::Ident
                && &text[t.span.start..t.span.end] == name
                && !decls.iter().any(|d| d.name_span == t.span)
                && !is_key(toks, *i)
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
}
