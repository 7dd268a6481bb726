//! Diagnostics as JSON lines (`--message-format json`): one object per
//! diagnostic, for CI tools and editors, in the shape
//! `docs/diagnostics.schema.json` describes (and `docs/diagnostics.md`
//! documents). Like rustc's, every span carries both byte offsets (exact, for
//! tools that slice the file) and 1-based lines and columns (for people and
//! editors); columns count characters, not bytes, so a name with `é` in it
//! does not shift what follows.

use super::{Code, Diagnostic, Label, Lines, Severity};
use crate::span::Span;
use serde::{Deserialize, Serialize};

/// The value of every diagnostic object's `type` field: a stream may carry
/// other objects (the plan report) between diagnostics.
pub const TYPE: &str = "diagnostic";

/// One diagnostic as it is written on a line of JSON.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JsonDiagnostic {
    /// Always [`TYPE`].
    #[serde(rename = "type")]
    pub kind: String,
    /// The stable code, e.g. `lmd::unit-mismatch`.
    pub code: String,
    /// `error` or `warning`.
    pub severity: String,
    /// One sentence saying what is wrong.
    pub message: String,
    /// The file the spans point into, as given on the command line.
    pub file: String,
    /// The labelled places in the source, the primary one first.
    pub spans: Vec<JsonSpan>,
    /// What would fix it, if lmdc knows.
    pub help: Option<String>,
    /// For a warning the file or the command line expects, why (the file's
    /// `allow` reason, or `--allow`); absent otherwise. An allowed warning
    /// fails no run.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub allowed: Option<String>,
}

/// A labelled place in the source.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JsonSpan {
    /// First byte (0-based).
    pub byte_start: usize,
    /// One past the last byte.
    pub byte_end: usize,
    /// Line of the first byte (1-based).
    pub line_start: usize,
    /// Column of the first byte (1-based, in characters).
    pub column_start: usize,
    /// Line of the end (1-based).
    pub line_end: usize,
    /// Column of the end (1-based, in characters; one past the last
    /// character, as rustc counts).
    pub column_end: usize,
    /// Whether this is the diagnostic's main place (the first label).
    pub is_primary: bool,
    /// The text shown under the span (may be empty).
    pub label: String,
}

/// Why a JSON object is not a diagnostic lmdc could have written.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum ParseError {
    /// Not JSON of the right shape.
    #[error("not a diagnostic object: {0}")]
    Shape(String),
    /// A code lmdc does not have.
    #[error("unknown code `{0}`")]
    Code(String),
    /// A severity other than `error` or `warning`.
    #[error("unknown severity `{0}`")]
    Severity(String),
}

/// Converts diagnostics of one source to JSON objects; the source's lines are
/// indexed once, so converting many diagnostics stays linear in the file.
pub struct Encoder<'s> {
    lines: Lines<'s>,
    file: String,
}

impl<'s> Encoder<'s> {
    /// An encoder for diagnostics about `source`, read from `file`.
    pub fn new(file: &str, source: &'s str) -> Self {
        Encoder {
            lines: Lines::new(source),
            file: file.to_string(),
        }
    }

    /// `d` as a JSON object.
    pub fn encode(&self, d: &Diagnostic) -> JsonDiagnostic {
        JsonDiagnostic {
            kind: TYPE.into(),
            code: d.code.as_str().into(),
            severity: match d.severity {
                Severity::Error => "error",
                Severity::Warning => "warning",
            }
            .into(),
            message: d.message.clone(),
            file: self.file.clone(),
            spans: d
                .labels
                .iter()
                .enumerate()
                .map(|(i, l)| self.span(l, i == 0))
                .collect(),
            help: d.help.clone(),
            allowed: d.allowed.clone(),
        }
    }

    /// `d` as one line of JSON (no line break).
    pub fn line(&self, d: &Diagnostic) -> String {
        // A struct of strings and numbers always serialises.
        serde_json::to_string(&self.encode(d)).unwrap_or_default()
    }

    fn span(&self, l: &Label, primary: bool) -> JsonSpan {
        // Clamp as the renderer does: a stale span must not fail the output.
        let start = self.lines.floor(l.span.start);
        let end = self.lines.ceil(l.span.end.max(start));
        let (line_start, column_start) = self.position(start);
        let (line_end, column_end) = self.position(end);
        JsonSpan {
            byte_start: start,
            byte_end: end,
            line_start,
            column_start,
            line_end,
            column_end,
            is_primary: primary,
            label: l.text.clone(),
        }
    }

    /// 1-based line and character column of byte `at` (a char boundary).
    fn position(&self, at: usize) -> (usize, usize) {
        let k = self.lines.line_of(at);
        let start = self.lines.starts[k].min(at);
        (k + 1, self.lines.src[start..at].chars().count() + 1)
    }
}

impl JsonDiagnostic {
    /// Reads one line written by [`Encoder::line`].
    pub fn parse(line: &str) -> Result<JsonDiagnostic, ParseError> {
        let d: JsonDiagnostic =
            serde_json::from_str(line).map_err(|e| ParseError::Shape(e.to_string()))?;
        if d.kind != TYPE {
            return Err(ParseError::Shape(format!("type `{}`", d.kind)));
        }
        Ok(d)
    }

    /// The diagnostic this object describes (spans by their byte offsets).
    pub fn to_diagnostic(&self) -> Result<Diagnostic, ParseError> {
        let code = Code::ALL
            .iter()
            .copied()
            .find(|c| c.as_str() == self.code)
            .ok_or_else(|| ParseError::Code(self.code.clone()))?;
        let severity = match self.severity.as_str() {
            "error" => Severity::Error,
            "warning" => Severity::Warning,
            s => return Err(ParseError::Severity(s.to_string())),
        };
        Ok(Diagnostic {
            code,
            severity,
            message: self.message.clone(),
            labels: self
                .spans
                .iter()
                .map(|s| Label {
                    span: Span::new(s.byte_start, s.byte_end),
                    text: s.label.clone(),
                })
                .collect(),
            help: self.help.clone(),
            allowed: self.allowed.clone(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_count_characters_and_lines_every_line_end() {
        let src = "part é\r\nlet a = b\rlet c = 1\n";
        let at = src.find('b').unwrap();
        let d = Diagnostic::error(Code::UnknownName, "no `b`")
            .label(Span::new(at, at + 1), "here")
            .label(Span::new(5, 7), "")
            .help("declare it");
        let j = Encoder::new("f.lmd", src).encode(&d);
        let s = &j.spans[0];
        assert_eq!((s.line_start, s.column_start), (2, 9));
        assert_eq!((s.line_end, s.column_end), (2, 10));
        assert!(s.is_primary && !j.spans[1].is_primary);
        // `é` is two bytes and one column.
        assert_eq!((j.spans[1].column_start, j.spans[1].column_end), (6, 7));
        let line = Encoder::new("f.lmd", src).line(&d);
        assert!(!line.contains('\n'));
        let back = JsonDiagnostic::parse(&line)
            .unwrap()
            .to_diagnostic()
            .unwrap();
        assert_eq!(back, d);
    }

    #[test]
    fn stale_spans_are_clamped() {
        let d = Diagnostic::warning(Code::Unused, "x").label(Span::new(50, 3), "");
        let j = Encoder::new("f", "é\n").encode(&d);
        assert_eq!((j.spans[0].byte_start, j.spans[0].byte_end), (3, 3));
        assert_eq!((j.spans[0].line_start, j.spans[0].column_start), (2, 1));
    }
}
