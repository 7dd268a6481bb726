//! Diagnostics: one plain struct for every error and warning, a sink that collects
//! them, and rendering through miette. [`Code`] lists every code (and generates
//! `docs/diagnostics.md`); `message` holds the wording of every diagnostic —
//! the builders below are private to this module, so only it can write one.

mod code;
pub mod json;
pub(crate) mod message;
/// The reports of the command line's mistakes (the binary writes them).
pub use message::usage;
/// The reports of a measurement sheet's mistakes and of a model it cannot
/// be fitted to (`lmdc fit` prints them).
pub mod sheet {
    pub use super::message::calib::{fault, sheet as faults};
}
mod worst;

use crate::span::Span;
pub use code::{Code, Group};
use std::fmt;
pub(crate) use worst::{plural, Worst};

/// How bad a diagnostic is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Severity {
    /// Compilation fails; nothing is written.
    Error,
    /// Compilation goes on; the user should look.
    Warning,
}

/// A span with a short text shown under it.
#[derive(Clone, Debug, PartialEq)]
pub struct Label {
    /// Where.
    pub span: Span,
    /// What to say there.
    pub text: String,
}

/// One error or warning about the program.
#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    /// Stable code, e.g. `lmd::unit-mismatch` (see docs/diagnostics.md).
    pub code: Code,
    /// Error or warning.
    pub severity: Severity,
    /// One sentence saying what is wrong.
    pub message: String,
    /// Places in the source, first the primary one.
    pub labels: Vec<Label>,
    /// What would fix it.
    pub help: Option<String>,
    /// For a warning the file or the command line expects: why (the
    /// reason of the file's `allow "lmd::…" = "…"`, or `--allow`). An
    /// allowed warning is reported but fails no run (`--deny-warnings`,
    /// `--deny`).
    pub allowed: Option<String>,
}

impl Diagnostic {
    /// A new error.
    pub(in crate::diag) fn error(code: Code, message: impl Into<String>) -> Self {
        Diagnostic {
            code,
            severity: Severity::Error,
            message: message.into(),
            labels: Vec::new(),
            help: None,
            allowed: None,
        }
    }

    /// A new warning.
    pub(in crate::diag) fn warning(code: Code, message: impl Into<String>) -> Self {
        Diagnostic {
            severity: Severity::Warning,
            ..Diagnostic::error(code, message)
        }
    }

    /// Adds a label.
    pub(in crate::diag) fn label(mut self, span: Span, text: impl Into<String>) -> Self {
        self.labels.push(Label {
            span,
            text: text.into(),
        });
        self
    }

    /// Adds a label if the span is known.
    pub(in crate::diag) fn label_opt(self, span: Option<Span>, text: impl Into<String>) -> Self {
        match span {
            Some(s) => self.label(s, text),
            None => self,
        }
    }

    /// Sets the help text.
    pub(in crate::diag) fn help(mut self, help: impl Into<String>) -> Self {
        self.help = Some(help.into());
        self
    }

    /// Is this an error?
    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

/// Collected diagnostics of one run, in the order they were found.
#[derive(Clone, Debug, Default)]
pub struct Diagnostics {
    items: Vec<Diagnostic>,
    /// The warnings expected, by code, and why: each one recorded, before
    /// or after, is marked [`Diagnostic::allowed`].
    allows: Vec<(Code, String)>,
}

impl Diagnostics {
    /// An empty sink.
    pub fn new() -> Self {
        Self::default()
    }

    /// Records a diagnostic.
    pub fn push(&mut self, mut d: Diagnostic) {
        mark(&self.allows, &mut d);
        self.items.push(d);
    }

    /// Records all of `other`, and the warnings it allows.
    pub fn extend(&mut self, other: Diagnostics) {
        for (code, why) in other.allows {
            self.allow(code, why);
        }
        for d in other.items {
            self.push(d);
        }
    }

    /// Expects the warnings of `code`, for the reason `why`: those recorded
    /// so far and those to come are allowed (the first reason given for a
    /// code stands).
    pub fn allow(&mut self, code: Code, why: impl Into<String>) {
        if self.allows.iter().any(|(c, _)| *c == code) {
            return;
        }
        self.allows.push((code, why.into()));
        for d in &mut self.items {
            mark(&self.allows, d);
        }
    }

    /// Number of warnings not allowed ([`Diagnostic::allowed`]) whose code
    /// `counts` says yes to.
    pub fn unallowed_warnings(&self, counts: impl Fn(Code) -> bool) -> usize {
        self.items
            .iter()
            .filter(|d| d.severity == Severity::Warning && d.allowed.is_none() && counts(d.code))
            .count()
    }

    /// True when any recorded diagnostic is an error.
    pub fn has_errors(&self) -> bool {
        self.items.iter().any(Diagnostic::is_error)
    }

    /// Number of errors.
    pub fn error_count(&self) -> usize {
        self.items.iter().filter(|d| d.is_error()).count()
    }

    /// All diagnostics.
    pub fn iter(&self) -> impl Iterator<Item = &Diagnostic> {
        self.items.iter()
    }

    /// True when nothing was recorded.
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// Keeps only the diagnostics `keep` says yes to.
    pub fn retain(&mut self, keep: impl FnMut(&Diagnostic) -> bool) {
        self.items.retain(keep);
    }

    /// Orders the diagnostics by where they point in the source (their first
    /// label; those without a label last), keeping the order found among equals.
    pub fn sort_by_source(&mut self) {
        self.items
            .sort_by_key(|d| d.labels.first().map_or(usize::MAX, |l| l.span.start));
    }

    /// Consumes the sink.
    pub fn into_vec(self) -> Vec<Diagnostic> {
        self.items
    }
}

impl From<Diagnostic> for Diagnostics {
    fn from(d: Diagnostic) -> Self {
        Diagnostics {
            items: vec![d],
            allows: Vec::new(),
        }
    }
}

/// Marks `d` allowed when it is a warning whose code `allows` expects (an
/// error is never allowed).
fn mark(allows: &[(Code, String)], d: &mut Diagnostic) {
    if d.severity != Severity::Warning || d.allowed.is_some() {
        return;
    }
    if let Some((_, why)) = allows.iter().find(|(c, _)| *c == d.code) {
        d.allowed = Some(why.clone());
    }
}

/// At most this many diagnostics are drawn in full; the others are counted in
/// one line. Thousands of copies of one mistake tell a user nothing more, and
/// drawing them would take longer than compiling.
pub const MAX_RENDERED: usize = 100;

/// Source lines longer than this (bytes) are drawn cut to the parts round the
/// labels, so a file written on one line does not print megabytes per report.
const MAX_LINE: usize = 160;

/// Bytes kept either side of a label's start and end on a cut line.
const KEEP: usize = 40;

/// A label spanning more lines than this is drawn on its first line only.
const MAX_LABEL_LINES: usize = 40;

/// Labels whose snippets (a label's lines and one line either side) are at
/// most this many lines apart are drawn as one snippet with the lines between
/// them; farther apart, each in its own (miette's own sources merged snippets
/// up to thousands of lines apart).
const MAX_GAP: usize = 5;

/// The start of every line of a source, found once per [`render`] call so
/// that each report finds its lines by binary search instead of scanning the
/// file from the start (which made rendering quadratic: 32 000 reports of a
/// 32 000-line file took half a minute). Line ends: `\n`, `\r\n` and `\r`.
struct Lines<'s> {
    src: &'s str,
    starts: Vec<usize>,
}

impl<'s> Lines<'s> {
    fn new(src: &'s str) -> Self {
        let b = src.as_bytes();
        let mut starts = vec![0];
        let mut i = 0;
        while i < b.len() {
            match b[i] {
                b'\n' => starts.push(i + 1),
                b'\r' if b.get(i + 1) == Some(&b'\n') => {
                    i += 1;
                    starts.push(i + 1);
                }
                b'\r' => starts.push(i + 1),
                _ => {}
            }
            i += 1;
        }
        Lines { src, starts }
    }

    /// The line (0-based) holding byte `at`.
    fn line_of(&self, at: usize) -> usize {
        self.starts.partition_point(|&s| s <= at).saturating_sub(1)
    }

    /// Where line `k`'s text ends (before its line break).
    fn content_end(&self, k: usize) -> usize {
        let next = self.starts.get(k + 1).copied().unwrap_or(self.src.len());
        let text = &self.src.as_bytes()[self.starts[k]..next];
        let brk = if text.ends_with(b"\r\n") {
            2
        } else if text.ends_with(b"\n") || text.ends_with(b"\r") {
            1
        } else {
            0
        };
        next - brk
    }

    fn floor(&self, mut at: usize) -> usize {
        at = at.min(self.src.len());
        while !self.src.is_char_boundary(at) {
            at -= 1;
        }
        at
    }

    fn ceil(&self, mut at: usize) -> usize {
        at = at.min(self.src.len());
        while !self.src.is_char_boundary(at) {
            at += 1;
        }
        at
    }
}

/// What a character is drawn as: control characters (C0 but tab and line
/// feed, DEL, C1) as their Unicode control pictures or U+FFFD, and the
/// invisible bidirectional overrides (which can make a terminal show text in
/// another order than it is) as U+FFFD, so that no byte of the source or of a
/// name in a message reaches the terminal as a command.
fn shown(c: char) -> Option<char> {
    match c {
        '\n' | '\t' => None,
        '\0'..='\x1f' => char::from_u32(0x2400 + c as u32),
        '\x7f' => Some('\u{2421}'),
        '\u{80}'..='\u{9f}'
        | '\u{200e}'
        | '\u{200f}'
        | '\u{202a}'..='\u{202e}'
        | '\u{2066}'..='\u{2069}'
        | '\u{61c}' => Some('\u{fffd}'),
        _ => None,
    }
}

/// `text` as it is safe to print: control characters (C0 but tab and line
/// feed, DEL, C1) become their Unicode control pictures (`␛` for ESC) or
/// U+FFFD, and bidirectional overrides U+FFFD.
pub fn sanitize(text: &str) -> std::borrow::Cow<'_, str> {
    if !text.chars().any(|c| shown(c).is_some()) {
        return text.into();
    }
    text.chars().map(|c| shown(c).unwrap_or(c)).collect()
}

/// One line of a [`View`].
struct ViewLine {
    /// Where it starts in the view's text.
    start: usize,
    /// Its number in the source (0-based).
    number: usize,
}

/// The labels of `diag` as source byte ranges, clamped so a stale span can
/// never make the renderer fail; a label spanning many lines keeps its
/// first.
fn label_spans(lines: &Lines<'_>, diag: &Diagnostic) -> Vec<(usize, usize)> {
    diag.labels
        .iter()
        .map(|l| {
            let start = lines.floor(l.span.start);
            let end = lines.ceil(l.span.end.max(start));
            let first = lines.line_of(start);
            if lines.line_of(end.saturating_sub(1).max(start)) - first >= MAX_LABEL_LINES {
                (start, lines.content_end(first).max(start))
            } else {
                (start, end)
            }
        })
        .collect()
}

/// The source lines a view shows: each label's lines and one either side,
/// runs less than [`MAX_GAP`] apart merged.
fn shown_lines(lines: &Lines<'_>, spans: &[(usize, usize)]) -> impl Iterator<Item = usize> {
    let last_line = lines.starts.len() - 1;
    let mut ranges: Vec<(usize, usize)> = spans
        .iter()
        .map(|&(a, b)| {
            let l0 = lines.line_of(a);
            let l1 = lines.line_of(b.saturating_sub(1).max(a));
            (l0.saturating_sub(1), (l1 + 1).min(last_line))
        })
        .collect();
    ranges.sort_unstable();
    let mut shown: Vec<(usize, usize)> = Vec::new();
    for (lo, hi) in ranges {
        match shown.last_mut() {
            Some(last) if lo <= last.1 + MAX_GAP => last.1 = last.1.max(hi),
            _ => shown.push((lo, hi)),
        }
    }
    shown.into_iter().flat_map(|(lo, hi)| lo..=hi)
}

/// The pieces of the line `a..b` a view shows: all of it when short, else
/// [`KEEP`] bytes round each label end in `here` (or its start).
fn line_segments(lines: &Lines<'_>, (a, b): (usize, usize), here: &[usize]) -> Vec<(usize, usize)> {
    if b - a <= MAX_LINE {
        return vec![(a, b)];
    }
    let wanted = if here.is_empty() {
        vec![(a, lines.floor(a + MAX_LINE / 2))]
    } else {
        here.iter()
            .map(|&p| {
                let p = p.min(b);
                (
                    lines.floor(p.saturating_sub(KEEP).max(a)),
                    lines.ceil((p + KEEP).min(b)),
                )
            })
            .collect()
    };
    let mut segs: Vec<(usize, usize)> = Vec::new();
    for (s, e) in wanted {
        match segs.last_mut() {
            Some(last) if s <= last.1 + 8 => last.1 = last.1.max(e),
            _ => segs.push((s, e)),
        }
    }
    segs
}

/// The few source lines one report draws, cut and cleaned: the lines of its
/// labels and one either side, long lines cut round the labels, control
/// characters replaced. Labels are moved to the view's offsets, and line and
/// column numbers are the source's, so the report reads as if drawn from the
/// whole file. Built in time proportional to what it shows.
struct View {
    name: String,
    text: String,
    lines: Vec<ViewLine>,
    /// (view offset, source byte column) of each label end, for the
    /// `file:line:column` miette prints.
    columns: Vec<(usize, usize)>,
}

impl View {
    /// A view of `diag`'s labels and the labels as `(start, end)` in it.
    fn new(lines: &Lines<'_>, name: &str, diag: &Diagnostic) -> (View, Vec<(usize, usize)>) {
        let spans = label_spans(lines, diag);
        let mut points: Vec<usize> = spans.iter().flat_map(|&(a, b)| [a, b]).collect();
        points.sort_unstable();
        points.dedup();
        let mut view = View {
            name: sanitize(name).into_owned(),
            text: String::new(),
            lines: Vec::new(),
            columns: Vec::new(),
        };
        let mut map: Vec<(usize, usize)> = Vec::new(); // (source, view)
        for k in shown_lines(lines, &spans) {
            view.push_line(lines, k, &points, &mut map);
        }
        map.sort_unstable();
        map.dedup_by_key(|m| m.0);
        let to_view = |p: usize| {
            map.binary_search_by_key(&p, |m| m.0)
                .map(|i| map[i].1)
                .unwrap_or(0)
        };
        view.columns = map
            .iter()
            .map(|&(p, v)| (v, p - lines.starts[lines.line_of(p)]))
            .collect();
        view.columns.sort_unstable();
        let spans = spans
            .iter()
            .map(|&(a, b)| (to_view(a), to_view(b).max(to_view(a))))
            .collect();
        (view, spans)
    }

    /// Appends source line `k`, cut round the label ends among `points`
    /// when long; records where each label end lands in `map`.
    fn push_line(
        &mut self,
        lines: &Lines<'_>,
        k: usize,
        points: &[usize],
        map: &mut Vec<(usize, usize)>,
    ) {
        let src = lines.src;
        let a = lines.starts[k];
        let b = lines.content_end(k);
        let next = lines.starts.get(k + 1).copied().unwrap_or(src.len() + 1);
        self.lines.push(ViewLine {
            start: self.text.len(),
            number: k,
        });
        let here: Vec<usize> = points
            .iter()
            .copied()
            .filter(|&p| p >= a && p < next)
            .collect();
        let mut at = a;
        for (s, e) in line_segments(lines, (a, b), &here) {
            if s > at {
                self.text.push('…');
            }
            for (i, c) in src[s..e].char_indices() {
                if here.binary_search(&(s + i)).is_ok() {
                    map.push((s + i, self.text.len()));
                }
                self.text.push(shown(c).unwrap_or(c));
            }
            if here.binary_search(&e).is_ok() {
                map.push((e, self.text.len()));
            }
            at = e;
        }
        if at < b {
            self.text.push('…');
        }
        // Label ends inside the line break stand at the end of the line.
        for &p in &here {
            if p > b {
                map.push((p, self.text.len()));
            }
        }
        if k + 1 < lines.starts.len() {
            self.text.push('\n');
        }
    }

    /// Whether view line `i + 1` is the source line after view line `i`.
    fn follows(&self, i: usize) -> bool {
        i + 1 < self.lines.len() && self.lines[i].number + 1 == self.lines[i + 1].number
    }

    /// The view line holding view offset `at`.
    fn line_at(&self, at: usize) -> usize {
        self.lines
            .partition_point(|l| l.start <= at)
            .saturating_sub(1)
    }
}

impl miette::SourceCode for View {
    fn read_span<'a>(
        &'a self,
        span: &miette::SourceSpan,
        before: usize,
        after: usize,
    ) -> Result<Box<dyn miette::SpanContents<'a> + 'a>, miette::MietteError> {
        let start = span.offset();
        let end = start + span.len();
        if end > self.text.len() || self.lines.is_empty() {
            return Err(miette::MietteError::OutOfBounds);
        }
        let first = self.line_at(start);
        let last = self.line_at(end.saturating_sub(1).max(start));
        // Context lines only where the source's lines follow on: a view holds
        // the lines round each label, not what lies between labels.
        let mut lo = first;
        for _ in 0..before {
            if lo > 0 && self.lines[lo - 1].number + 1 == self.lines[lo].number {
                lo -= 1;
            }
        }
        let mut hi = last;
        for _ in 0..after {
            if self.follows(hi) {
                hi += 1;
            }
        }
        // miette draws two labels in one snippet when the first one's lines
        // reach the second's: count the lines up to the end of this run of
        // consecutive source lines, so labels the view shows together (at
        // most MAX_GAP lines apart) are drawn together, and no others.
        let mut run_end = hi;
        while self.follows(run_end) {
            run_end += 1;
        }
        // As miette's own sources do: with no lines before, the contents start
        // at the span, and the column says where that is on its line.
        let (data_start, column) = if before == 0 {
            let col = match self.columns.binary_search_by_key(&start, |c| c.0) {
                Ok(i) => self.columns[i].1,
                Err(_) => start - self.lines[first].start,
            };
            (start, col)
        } else {
            (self.lines[lo].start, 0)
        };
        let data_end = self.lines.get(hi + 1).map_or(self.text.len(), |l| l.start);
        Ok(Box::new(miette::MietteSpanContents::new_named(
            self.name.clone(),
            &self.text.as_bytes()[data_start..data_end],
            (data_start, data_end - data_start).into(),
            self.lines[lo].number,
            column,
            run_end - lo + 1,
        )))
    }
}

/// A diagnostic bound to its view, so miette can draw it.
#[derive(Debug)]
struct Rendered<'a> {
    diag: &'a Diagnostic,
    message: String,
    help: Option<String>,
    view: View,
    labels: Vec<(usize, usize, Option<String>)>,
}

impl fmt::Debug for View {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("View").field("name", &self.name).finish()
    }
}

impl fmt::Display for Rendered<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for Rendered<'_> {}

impl miette::Diagnostic for Rendered<'_> {
    fn code<'b>(&'b self) -> Option<Box<dyn fmt::Display + 'b>> {
        Some(Box::new(self.diag.code.as_str()))
    }
    fn severity(&self) -> Option<miette::Severity> {
        Some(match self.diag.severity {
            Severity::Error => miette::Severity::Error,
            Severity::Warning => miette::Severity::Warning,
        })
    }
    fn help<'b>(&'b self) -> Option<Box<dyn fmt::Display + 'b>> {
        self.help
            .as_ref()
            .map(|h| Box::new(h) as Box<dyn fmt::Display>)
    }
    fn source_code(&self) -> Option<&dyn miette::SourceCode> {
        if self.labels.is_empty() {
            None
        } else {
            Some(&self.view)
        }
    }
    fn labels(&self) -> Option<Box<dyn Iterator<Item = miette::LabeledSpan> + '_>> {
        if self.labels.is_empty() {
            return None;
        }
        Some(Box::new(self.labels.iter().enumerate().map(
            |(i, (start, end, text))| {
                if i == 0 {
                    miette::LabeledSpan::new_primary_with_span(text.clone(), (*start, end - start))
                } else {
                    miette::LabeledSpan::new_with_span(text.clone(), (*start, end - start))
                }
            },
        )))
    }
}

/// Renders diagnostics as text, the way `lmdc` prints them. `color` selects ANSI
/// colours; tests use plain text so snapshots are stable.
///
/// Time and output are linear in the file and the number of diagnostics: the
/// source's lines are indexed once, each report draws only the lines round
/// its labels (long lines cut, labels over many lines drawn on their first),
/// and at most [`MAX_RENDERED`] reports are drawn — errors before warnings —
/// with one line counting the rest. Control characters, from the source or in
/// a message quoting it, are drawn as harmless symbols (see [`sanitize`]).
pub fn render(diags: &Diagnostics, file_name: &str, source: &str, color: bool) -> String {
    render_at_most(diags, file_name, source, color, MAX_RENDERED)
}

/// [`render`], drawing at most `max` reports instead of [`MAX_RENDERED`].
pub fn render_at_most(
    diags: &Diagnostics,
    file_name: &str,
    source: &str,
    color: bool,
    max: usize,
) -> String {
    let lines = Lines::new(source);
    let theme = if color {
        miette::GraphicalTheme::unicode()
    } else {
        miette::GraphicalTheme::unicode_nocolor()
    };
    let handler = miette::GraphicalReportHandler::new_themed(theme).with_width(100);
    let all: Vec<&Diagnostic> = diags.iter().filter(|d| d.allowed.is_none()).collect();
    let errors = diags.error_count();
    let warnings = all.len() - errors;
    // Errors first: a warning must not crowd out an error that stops the build.
    let mut chosen = vec![false; all.len()];
    let mut budget = max;
    for want_error in [true, false] {
        for (i, d) in all.iter().enumerate() {
            if budget > 0 && d.is_error() == want_error {
                chosen[i] = true;
                budget -= 1;
            }
        }
    }
    let mut out = String::new();
    for (d, _) in all.iter().zip(&chosen).filter(|(_, c)| **c) {
        let (view, spans) = View::new(&lines, file_name, d);
        let r = Rendered {
            diag: d,
            message: sanitize(&d.message).into_owned(),
            help: d.help.as_deref().map(|h| sanitize(h).into_owned()),
            labels: spans
                .into_iter()
                .zip(&d.labels)
                .map(|((a, b), l)| {
                    (
                        a,
                        b,
                        (!l.text.is_empty()).then(|| sanitize(&l.text).into_owned()),
                    )
                })
                .collect(),
            view,
        };
        // Writing into a String cannot fail.
        let _ = handler.render_report(&mut out, &r);
        out.push('\n');
    }
    // An allowed warning is expected: a line, not a report.
    for d in diags.iter().filter(|d| d.allowed.is_some()) {
        out.push_str(&format!(
            "allowed warning[{}]: {} ({})\n",
            d.code.as_str(),
            sanitize(&d.message),
            sanitize(d.allowed.as_deref().unwrap_or_default()),
        ));
    }
    let hidden = all.len() - all.len().min(max);
    if hidden > 0 {
        let hidden_errors = errors - errors.min(max);
        out.push_str(&format!(
            "… and {hidden} more not shown ({hidden_errors} error{}, {} warning{})\n",
            if hidden_errors == 1 { "" } else { "s" },
            hidden - hidden_errors,
            if hidden - hidden_errors == 1 { "" } else { "s" },
        ));
    }
    let file_name = sanitize(file_name);
    if errors > 0 {
        out.push_str(&format!(
            "{} error{}{} in {}\n",
            errors,
            if errors == 1 { "" } else { "s" },
            if warnings > 0 {
                format!(
                    ", {} warning{}",
                    warnings,
                    if warnings == 1 { "" } else { "s" }
                )
            } else {
                String::new()
            },
            file_name
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn one(span: (usize, usize), text: &str) -> Diagnostics {
        Diagnostic::error(Code::Syntax, "bad")
            .label(Span::new(span.0, span.1), text)
            .into()
    }

    #[test]
    fn control_characters_are_drawn_as_symbols() {
        let src = "part p\nlet a = \"\x1b[31m\x07\u{9b}\u{202e}\" + 1\n";
        let at = src.find('+').unwrap();
        let d: Diagnostics = Diagnostic::error(Code::Type, "name `\x1b]0;x\x07` here")
            .label(Span::new(at, at + 1), "label \x1b[2J")
            .help("help \r\x7f")
            .into();
        let text = render(&d, "f\x1b.lmd", src, false);
        assert!(
            !text.chars().any(|c| c.is_control() && c != '\n'),
            "{text:?}"
        );
        assert!(text.contains("␛[31m␇�"), "{text}");
        assert!(text.contains("name `␛]0;x␇` here"), "{text}");
        // The label still points at `+`, at byte column 23.
        assert!(text.contains("f␛.lmd:2:23]"), "{text}");
        assert!(text.contains("\"␛[31m␇��\" + 1\n"), "{text}");
    }

    #[test]
    fn every_line_end_gives_the_same_lines() {
        let lf = "part p\nlet a = 1\nlet b = c\nlet d = 2\n";
        let at = lf.find('c').unwrap();
        let want = render(&one((at, at + 1), "here"), "f", lf, false);
        assert!(want.contains("f:3:9]"), "{want}");
        for src in [lf.replace('\n', "\r\n"), lf.replace('\n', "\r")] {
            let at = src.find('c').unwrap();
            assert_eq!(render(&one((at, at + 1), "here"), "f", &src, false), want);
        }
    }

    #[test]
    fn long_lines_are_cut_round_the_label() {
        let src = format!(
            "part p {} oops {}",
            "a = 1 ".repeat(10_000),
            "b = 2 ".repeat(10_000)
        );
        let at = src.find("oops").unwrap();
        let text = render(&one((at, at + 4), "here"), "f", &src, false);
        assert!(text.len() < 2_000, "{} bytes", text.len());
        assert!(
            text.contains(" │ … 1 a = 1 a = 1") && text.contains("oops b = 2"),
            "{text}"
        );
        assert!(text.contains(&format!("f:1:{}]", at + 1)), "{text}");
        // A label over the whole line is drawn by its two ends.
        let text = render(&one((0, src.len()), "all"), "f", &src, false);
        assert!(text.len() < 2_000, "{} bytes", text.len());
    }

    #[test]
    fn many_reports_are_counted_errors_first() {
        let src = "x\n";
        let mut d = Diagnostics::new();
        for _ in 0..MAX_RENDERED {
            d.push(Diagnostic::warning(Code::Unused, "a warning").label(Span::new(0, 1), ""));
        }
        d.push(Diagnostic::error(Code::Syntax, "the error").label(Span::new(0, 1), ""));
        let text = render(&d, "f", src, false);
        assert!(text.contains("the error"), "an error was crowded out");
        assert_eq!(text.matches("a warning").count(), MAX_RENDERED - 1);
        assert!(
            text.contains("… and 1 more not shown (0 errors, 1 warning)"),
            "{text}"
        );
        assert!(text.ends_with(&format!("1 error, {MAX_RENDERED} warnings in f\n")));
    }

    #[test]
    fn stale_and_odd_spans_never_fail() {
        let src = "é\r\nb";
        for (a, b) in [(0, 1), (1, 2), (2, 3), (3, 4), (4, 99), (99, 120), (5, 2)] {
            let text = render(&one((a, b), "x"), "f", src, false);
            assert!(text.contains("lmd::syntax"), "{a}..{b}: {text}");
            assert!(!text.contains("Failed to read"), "{a}..{b}: {text}");
        }
        assert!(render(&one((0, 0), "x"), "f", "", false).contains("bad"));
    }
}
