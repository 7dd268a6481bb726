//! What the server answers, in lmdc's terms (byte offsets, markdown): hover,
//! completion, definition and references. The block tables
//! ([`crate::sema::schema`]) say what each field means, takes and defaults
//! to; a compiled plan says what `auto` chose.

use super::names::{self, Decl};
use super::scan::{self, innermost_block, Frame, Tok, Token};
use crate::sema::schema::{self, Block, Field, Kind};
use crate::span::Span;

/// A hover: markdown and the span it is about.
#[derive(Clone, Debug, PartialEq)]
pub struct Hover {
    /// What to show.
    pub markdown: String,
    /// The word it explains.
    pub span: Span,
}

/// One completion.
#[derive(Clone, Debug, PartialEq)]
pub struct Completion {
    /// What is shown and inserted.
    pub label: String,
    /// What kind of thing it is (LSP's CompletionItemKind: 5 field,
    /// 6 variable, 14 keyword, 11 unit, 3 function, 21 constant).
    pub kind: u8,
    /// A line beside it.
    pub detail: String,
    /// More, in markdown.
    pub documentation: String,
    /// What to insert instead of the label, if it differs.
    pub insert: Option<String>,
}

/// The units completion offers after a number (each one lmdc reads: a test
/// parses them all).
pub const UNITS: &[&str] = &[
    "mm",
    "cm",
    "m",
    "um",
    "in",
    "deg",
    "rad",
    "s",
    "ms",
    "min",
    "h",
    "W",
    "kW",
    "g",
    "kg",
    "%",
    "mm/s",
    "mm/min",
    "mm/s^2",
    "g/min",
    "g/s",
    "g/cm^3",
    "J/mm",
    "Hz",
    "degC",
    "W/m^2/degC",
];

/// What a compiled plan chose for a field written `auto`, if it knows.
pub type Chosen<'a> = &'a dyn Fn(&str) -> Option<String>;

/// `offset` within `text` and on a character's first byte.
fn boundary(text: &str, offset: usize) -> usize {
    let mut o = offset.min(text.len());
    while !text.is_char_boundary(o) {
        o -= 1;
    }
    o
}

/// The hover at byte `offset`.
pub fn hover(text: &str, offset: usize, chosen: Chosen<'_>) -> Option<Hover> {
    let offset = boundary(text, offset);
    let toks = scan::tokens(text);
    let i = scan::at(&toks, offset)?;
    let t = toks[i];
    if t.tok != Tok::Ident {
        return None;
    }
    let word = &text[t.span.start..t.span.end];
    let frames = scan::frames(text, &toks, t.span.start);
    let next = toks.get(i + 1).map(|n| n.tok);
    if let Some(u) = names::unit_at(text, &toks, i) {
        return Some(Hover {
            markdown: describe_unit(&text[u.start..u.end]),
            span: u,
        });
    }
    let markdown = if next == Some(Tok::Punct('(')) {
        schema::block(word)
            .filter(|b| b.is_call())
            .map(describe_block)?
    } else if names::is_key(&toks, i) {
        key_hover(text, &toks, i, &frames, word)?
    } else if let Some(d) = names::declarations(text, &toks)
        .into_iter()
        .find(|d| d.name == word)
    {
        describe_decl(text, &d)
    } else if word == "auto" {
        let key = field_of_value(text, &toks, i)?;
        let f = innermost_block(&frames)?.field(key)?;
        let picked = chosen(key)?;
        format!("`{key} = auto`: {picked}\n\n{}", f.help)
    } else {
        return None;
    };
    Some(Hover {
        markdown,
        span: t.span,
    })
}

/// What a unit measures, or that lmdc does not read it.
fn describe_unit(unit: &str) -> String {
    match crate::units::parse_unit(unit) {
        Ok((_, dim)) => format!("**`{unit}`** measures {}", dim.describe()),
        Err(_) => match crate::units::unit_meant(unit) {
            Some(m) => format!("**`{unit}`**: no unit lmdc reads; did you mean `{m}`?"),
            None => format!("**`{unit}`**: no unit lmdc reads"),
        },
    }
}

/// The hover of a key: a field of the block around it, or a top-level
/// statement's block.
fn key_hover(text: &str, toks: &[Token], i: usize, frames: &[Frame], word: &str) -> Option<String> {
    if let Some(b) = innermost_block(frames) {
        return b.field(word).map(|f| describe_field(f, b));
    }
    if !frames.is_empty() {
        return None;
    }
    // A top-level statement: the block it opens.
    let open = toks[i..].iter().position(|t| t.tok == Tok::Punct('{'))? + i;
    let inside = scan::frames(text, toks, toks[open].span.end);
    innermost_block(&inside).map(describe_block)
}

/// The key `k = …` whose value token `i` is in.
fn field_of_value<'t>(text: &'t str, toks: &[Token], i: usize) -> Option<&'t str> {
    let eq = toks[..i].iter().rposition(|t| t.tok == Tok::Punct('='))?;
    let k = toks.get(eq.checked_sub(1)?)?;
    (k.tok == Tok::Ident).then(|| &text[k.span.start..k.span.end])
}

fn describe_field(f: &Field, b: &Block) -> String {
    format!(
        "**`{}`** in `{}`\n\n{}\n\n*takes* {} · *default* {}",
        f.key,
        b.syntax,
        f.help,
        f.value_text(),
        f.default_text()
    )
}

fn describe_block(b: &Block) -> String {
    let fields: Vec<String> = b.fields.iter().map(|f| format!("`{}`", f.key)).collect();
    format!(
        "**`{}`**: {}\n\n*fields* {}",
        b.syntax,
        b.help,
        fields.join(", ")
    )
}

fn describe_decl(text: &str, d: &Decl) -> String {
    const MAX_LINES: usize = 12;
    let src = &text[d.span.start..d.span.end];
    let mut shown: Vec<&str> = src.lines().take(MAX_LINES).collect();
    if src.lines().count() > MAX_LINES {
        shown.push("…");
    }
    format!(
        "**{} `{}`**\n\n```lmd\n{}\n```",
        d.kind,
        d.name,
        shown.join("\n")
    )
}

/// Where the name at `offset` is declared.
pub fn definition(text: &str, offset: usize) -> Option<Span> {
    let offset = boundary(text, offset);
    let toks = scan::tokens(text);
    let i = scan::at(&toks, offset)?;
    if names::is_unit(text, &toks, i) {
        return None;
    }
    let t = toks[i];
    let word = &text[t.span.start..t.span.end];
    names::declarations(text, &toks)
        .into_iter()
        .find(|d| d.name == word)
        .map(|d| d.name_span)
}

/// Every place the name at `offset` is used, its declaration first when
/// asked for.
pub fn references(text: &str, offset: usize, with_declaration: bool) -> Vec<Span> {
    let offset = boundary(text, offset);
    let toks = scan::tokens(text);
    let Some(i) = scan::at(&toks, offset).filter(|&i| !names::is_unit(text, &toks, i)) else {
        return Vec::new();
    };
    let word = &text[toks[i].span.start..toks[i].span.end];
    let decls = names::declarations(text, &toks);
    let Some(d) = decls.iter().find(|d| d.name == word) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    if with_declaration {
        out.push(d.name_span);
    }
    out.extend(names::uses(text, &toks, word, &decls));
    out
}

/// What may be typed at byte `offset`.
pub fn completion(text: &str, offset: usize) -> Vec<Completion> {
    let offset = boundary(text, offset);
    let toks = scan::tokens(text);
    // The token before the word being typed.
    let typing = scan::at(&toks, offset).filter(|&i| toks[i].tok == Tok::Ident);
    let before = match typing {
        Some(i) => i.checked_sub(1),
        None => toks.iter().rposition(|t| t.span.end <= offset),
    };
    let prev = before.map(|p| toks[p]);
    let frames = scan::frames(text, &toks, offset);
    let line = text[..offset].matches('\n').count();
    if prev.is_some_and(|p| p.tok == Tok::Number && p.line == line) {
        return units();
    }
    let entry = match prev {
        None => true,
        Some(p) => p.line != line || matches!(p.tok, Tok::Punct('{' | '(' | ',' | '}')),
    };
    let block = innermost_block(&frames);
    match (entry, block) {
        (true, Some(b)) => fields(b, text, &toks, offset),
        (true, None) if frames.is_empty() => statements(),
        _ if prev.is_some_and(|p| p.tok == Tok::Punct('=')) => {
            let key = before.and_then(|p| field_of_value(text, &toks, p + 1));
            values(text, &toks, block.and_then(|b| b.field(key?)))
        }
        _ => Vec::new(),
    }
}

fn units() -> Vec<Completion> {
    UNITS
        .iter()
        .map(|u| Completion {
            label: (*u).to_string(),
            kind: 11,
            detail: "unit".into(),
            documentation: String::new(),
            insert: None,
        })
        .collect()
}

/// The fields of `b` not yet written in the block around `offset`.
fn fields(b: &Block, text: &str, toks: &[Token], offset: usize) -> Vec<Completion> {
    let written: Vec<&str> = toks
        .iter()
        .enumerate()
        .filter(|(i, t)| {
            t.tok == Tok::Ident && names::is_key(toks, *i) && same_block(toks, t.span.start, offset)
        })
        .map(|(_, t)| &text[t.span.start..t.span.end])
        .collect();
    b.fields
        .iter()
        .filter(|f| !written.contains(&f.key))
        .map(|f| Completion {
            label: f.key.to_string(),
            kind: 5,
            detail: f.value_text(),
            documentation: describe_field(f, b),
            insert: Some(if f.kind.is_block() {
                format!("{} {{ }}", f.key)
            } else {
                format!("{} = ", f.key)
            }),
        })
        .collect()
}

/// Whether `a` and `b` lie directly in the same block or call.
fn same_block(toks: &[Token], a: usize, b: usize) -> bool {
    let (lo, hi) = (a.min(b), a.max(b));
    let mut depth = 0i64;
    let mut min = 0i64;
    for t in toks
        .iter()
        .filter(|t| t.span.start >= lo && t.span.start < hi)
    {
        match t.tok {
            Tok::Punct('{' | '(' | '[') => depth += 1,
            Tok::Punct('}' | ')' | ']') => depth -= 1,
            _ => {}
        }
        min = min.min(depth);
    }
    depth == 0 && min == 0
}

/// The statements a file may hold, from the block tables.
fn statements() -> Vec<Completion> {
    let mut out: Vec<Completion> = ["part", "let", "section", "profile"]
        .iter()
        .map(|w| keyword(w, ""))
        .collect();
    // A nested block (`limits { … }`) is written inside its parent only.
    let nested = |b: &Block| {
        schema::BLOCKS.iter().any(|p| {
            p.fields.iter().any(|f| match f.kind {
                Kind::Block(x) | Kind::Blocks(x) => x.name == b.name,
                _ => false,
            })
        })
    };
    for b in schema::BLOCKS.iter().filter(|b| !b.is_call() && !nested(b)) {
        let Some(word) = b.syntax.split_whitespace().next() else {
            continue;
        };
        if b.syntax.ends_with('}') && !out.iter().any(|c| c.label == word) {
            out.push(keyword(word, b.help));
        }
    }
    out
}

fn keyword(word: &str, help: &str) -> Completion {
    Completion {
        label: word.to_string(),
        kind: 14,
        detail: help.to_string(),
        documentation: String::new(),
        insert: None,
    }
}

/// What may follow `field =`: its words, its calls and the file's names.
fn values(text: &str, toks: &[Token], field: Option<&Field>) -> Vec<Completion> {
    let mut out = Vec::new();
    if let Some(f) = field {
        collect_kind(&f.kind, &mut out);
    }
    for d in names::declarations(text, toks) {
        if field.map_or(d.kind != "machine", |f| takes(&f.kind, &d.kind)) {
            out.push(Completion {
                label: d.name.clone(),
                kind: 6,
                detail: format!("{} {}", d.kind, d.name),
                documentation: String::new(),
                insert: None,
            });
        }
    }
    out
}

/// Whether a field of `kind` may be given a name declared by `decl` (`let`,
/// `bead`, …): a bead's name where a bead is named, a constant where a
/// number or an expression goes, never where only words or texts do.
fn takes(kind: &Kind, decl: &str) -> bool {
    match kind {
        // A solid (a repair's target, `top = NAME`) is an extrusion or a loft.
        Kind::Name(k) => *k == decl || (*k == "solid" && matches!(decl, "extrude" | "loft")),
        Kind::Shape => matches!(decl, "let" | "section" | "profile"),
        Kind::Quantity(..) | Kind::Range(_) | Kind::Count(..) | Kind::Io(_) | Kind::Point => {
            decl == "let"
        }
        Kind::List(k, _) | Kind::Layered(k) | Kind::Deferred(k) => takes(k, decl),
        Kind::Either(ks) => ks.iter().any(|k| takes(k, decl)),
        Kind::Word(_) | Kind::Text | Kind::Lines | Kind::Call(_) => false,
        Kind::Block(_) | Kind::Blocks(_) => false,
    }
}

fn collect_kind(kind: &Kind, out: &mut Vec<Completion>) {
    match kind {
        Kind::Word(ws) => out.extend(ws.iter().map(|w| Completion {
            label: (*w).to_string(),
            kind: 21,
            detail: "word".into(),
            documentation: String::new(),
            insert: None,
        })),
        Kind::Call(bs) => out.extend(bs.iter().map(|b| Completion {
            label: b.name.to_string(),
            kind: 3,
            detail: b.syntax.to_string(),
            documentation: describe_block(b),
            insert: Some(format!("{}(", b.name)),
        })),
        Kind::Either(ks) => ks.iter().for_each(|k| collect_kind(k, out)),
        Kind::Layered(k) | Kind::Deferred(k) => collect_kind(k, out),
        _ => {}
    }
}
