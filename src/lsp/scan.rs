//! The editor's view of a file: its tokens and, at any offset, the blocks
//! and calls around it. It works on tokens, not on the syntax tree, so
//! completion and hover keep working while the file being typed does not
//! parse (`bead b { wid` has no tree).

use crate::sema::schema::{self, Block, Kind};
use crate::span::Span;

/// What a token is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tok {
    /// A name or word: `bead`, `width`, `mm`.
    Ident,
    /// Digits: `60`, `0.5`, `1e-3`.
    Number,
    /// `"text"`.
    Str,
    /// One character of punctuation.
    Punct(char),
}

/// A token and where it is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Token {
    /// What it is.
    pub tok: Tok,
    /// Its bytes.
    pub span: Span,
    /// Its line, from 0.
    pub line: usize,
}

/// The tokens of `text`, comments and blanks left out. Never fails: a
/// character lmdc does not know is punctuation.
pub fn tokens(text: &str) -> Vec<Token> {
    let b = text.as_bytes();
    let (mut i, mut line) = (0usize, 0usize);
    let mut out = Vec::new();
    while i < b.len() {
        let c = b[i];
        let start = i;
        let tok = match c {
            b'\n' => {
                line += 1;
                i += 1;
                continue;
            }
            c if c.is_ascii_whitespace() => {
                i += 1;
                continue;
            }
            b'/' if b.get(i + 1) == Some(&b'/') => {
                while i < b.len() && b[i] != b'\n' {
                    i += 1;
                }
                continue;
            }
            b'/' if b.get(i + 1) == Some(&b'*') => {
                i += 2;
                while i < b.len() && !(b[i] == b'*' && b.get(i + 1) == Some(&b'/')) {
                    line += usize::from(b[i] == b'\n');
                    i += 1;
                }
                i = (i + 2).min(b.len());
                continue;
            }
            b'"' => {
                i += 1;
                while i < b.len() && b[i] != b'"' && b[i] != b'\n' {
                    i += 1;
                }
                i = (i + 1).min(b.len());
                Tok::Str
            }
            c if c.is_ascii_digit()
                || (c == b'.' && b.get(i + 1).is_some_and(u8::is_ascii_digit)) =>
            {
                while i < b.len()
                    && (b[i].is_ascii_digit()
                        || b[i] == b'.' && b.get(i + 1) != Some(&b'.')
                        || (b[i] == b'e' || b[i] == b'E')
                            && b.get(i + 1)
                                .is_some_and(|n| n.is_ascii_digit() || *n == b'-'))
                {
                    i += if b[i] == b'e' || b[i] == b'E' { 2 } else { 1 };
                }
                Tok::Number
            }
            c if c.is_ascii_alphabetic() || c == b'_' || c >= 0x80 => {
                while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_' || b[i] >= 0x80)
                {
                    i += 1;
                }
                Tok::Ident
            }
            c => {
                i += 1;
                Tok::Punct(c as char)
            }
        };
        let end = i.min(b.len());
        // A name of non-ASCII letters may end inside a character; so may `µ`.
        let end = (end..=b.len())
            .find(|&e| text.is_char_boundary(e))
            .unwrap_or(b.len());
        i = end;
        out.push(Token {
            tok,
            span: Span::new(start, end),
            line,
        });
    }
    out
}

/// A block or call the offset is inside.
#[derive(Clone, Copy, Debug)]
pub enum Frame {
    /// `… { … }`: the block it is, if lmdc knows it.
    Brace(Option<&'static Block>),
    /// `name(…)`: the call it is, if lmdc knows it.
    Paren(Option<&'static Block>),
    /// `[ … ]`.
    List,
}

/// The frames around byte `offset`, outermost first.
pub fn frames(text: &str, toks: &[Token], offset: usize) -> Vec<Frame> {
    let mut stack: Vec<Frame> = Vec::new();
    for (i, t) in toks.iter().enumerate() {
        if t.span.start >= offset {
            break;
        }
        match t.tok {
            Tok::Punct('{') => {
                let block = brace_block(text, toks, i, &stack);
                stack.push(Frame::Brace(block));
            }
            Tok::Punct('(') => {
                let block = prev_ident(text, toks, i)
                    .and_then(schema::block)
                    .filter(|b| b.is_call());
                stack.push(Frame::Paren(block));
            }
            Tok::Punct('[') => stack.push(Frame::List),
            Tok::Punct('}' | ')' | ']') => {
                stack.pop();
            }
            _ => {}
        }
    }
    stack
}

/// The block the frames' innermost brace or call is.
pub fn innermost_block(frames: &[Frame]) -> Option<&'static Block> {
    frames.iter().rev().find_map(|f| match f {
        Frame::Brace(b) | Frame::Paren(b) => Some(*b),
        Frame::List => None,
    })?
}

/// The text of token `i - 1` if it is a name on the same line.
fn prev_ident<'t>(text: &'t str, toks: &[Token], i: usize) -> Option<&'t str> {
    let p = toks.get(i.checked_sub(1)?)?;
    (p.tok == Tok::Ident && p.line == toks[i].line).then(|| &text[p.span.start..p.span.end])
}

/// Which block the `{` at token `i` opens: a nested block by its key in the
/// enclosing one; at the top, by the statement's word (a machine by its
/// `kind`, a slicing by its strategy).
fn brace_block(text: &str, toks: &[Token], i: usize, stack: &[Frame]) -> Option<&'static Block> {
    let last = prev_ident(text, toks, i)?;
    if let Some(Frame::Brace(parent)) = stack.last() {
        return match (*parent)?.field(last)?.kind {
            Kind::Block(b) | Kind::Blocks(b) => Some(b),
            _ => None,
        };
    }
    if !stack.is_empty() {
        return None;
    }
    // `kind name {` or `kind {`.
    let (kind, name) = match prev_ident(text, toks, i - 1) {
        Some(k) => (k, Some(last)),
        None => (last, None),
    };
    match kind {
        // Until its kind is written, a machine takes what either kind does.
        "machine" => machine_kind(text, toks, i)
            .and_then(schema::block)
            .or(Some(&schema::machine::MACHINE)),
        "slicing" => name.and_then(schema::block),
        "process"
            if toks
                .iter()
                .any(|t| t.tok == Tok::Ident && word_is(text, t, "ring")) =>
        {
            schema::block("ring_process")
        }
        // `wall(…)` is a calibration coupon; the statement is a wall along a path.
        "wall" => Some(&schema::wall::WALL),
        k => schema::block(k),
    }
    .filter(|b| !b.is_call())
}

fn word_is(text: &str, t: &Token, w: &str) -> bool {
    &text[t.span.start..t.span.end] == w
}

/// `robot` or `cnc`: the `kind = …` written in the machine block opened at
/// token `open`.
fn machine_kind<'t>(text: &'t str, toks: &[Token], open: usize) -> Option<&'t str> {
    let mut depth = 0usize;
    for k in open..toks.len() {
        match toks[k].tok {
            Tok::Punct('{') => depth += 1,
            Tok::Punct('}') => {
                depth -= 1;
                if depth == 0 {
                    return None;
                }
            }
            Tok::Ident if depth == 1 && word_is(text, &toks[k], "kind") => {
                let v = toks.get(k + 2)?;
                if toks.get(k + 1)?.tok == Tok::Punct('=') && v.tok == Tok::Ident {
                    return Some(&text[v.span.start..v.span.end]);
                }
            }
            _ => {}
        }
    }
    None
}

/// Whether token `i` starts a field or statement: the first on its line,
/// or right after `{`, `(` or `,`.
pub fn starts_entry(toks: &[Token], i: usize) -> bool {
    match i.checked_sub(1).map(|p| toks[p]) {
        None => true,
        Some(p) => p.line != toks[i].line || matches!(p.tok, Tok::Punct('{' | '}' | '(' | ',')),
    }
}

/// The token that holds byte `offset` or ends there (a name being typed).
pub fn at(toks: &[Token], offset: usize) -> Option<usize> {
    toks.iter()
        .position(|t| t.span.start <= offset && offset <= t.span.end && t.tok == Tok::Ident)
        .or_else(|| {
            toks.iter()
                .position(|t| t.span.start <= offset && offset < t.span.end)
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn comments_and_strings_are_skipped_and_lines_counted() {
        let text = "// a\nbead b { /* x\ny */ width = 6 mm }\nlet s = \"q{\"";
        let t = tokens(text);
        let words: Vec<&str> = t.iter().map(|t| &text[t.span.start..t.span.end]).collect();
        assert_eq!(
            words,
            ["bead", "b", "{", "width", "=", "6", "mm", "}", "let", "s", "=", "\"q{\""]
        );
        assert_eq!(t[3].line, 2);
    }

    #[test]
    fn frames_know_machines_by_kind_and_nested_blocks_by_key() {
        let text = "machine m {\n  kind = cnc\n  limits {\n    x = \n  }\n}";
        let t = tokens(text);
        let off = text.find("x =").unwrap();
        let f = frames(text, &t, off);
        assert_eq!(innermost_block(&f).map(|b| b.name), Some("limits"));
        let off = text.find("kind").unwrap();
        let f = frames(text, &t, off);
        assert_eq!(innermost_block(&f).map(|b| b.name), Some("cnc"));
    }

    #[test]
    fn an_unfinished_file_still_has_frames() {
        let text = "bead b {\n  model = mass_balance(fe";
        let t = tokens(text);
        let f = frames(text, &t, text.len());
        assert_eq!(innermost_block(&f).map(|b| b.name), Some("mass_balance"));
    }
}
