//! Texts that go into a program verbatim (`laser_on`, `preamble`, …): each must
//! be one line of printable ASCII, so nothing can slip a second command into a
//! program (a carriage return inside `laser_on = "M3␍G0 Z-500"` is a line end
//! to a control — and to lmdc's parser, which then finds the text unclosed; a
//! vertical tab or an escape must not reach a program either), and the lines a
//! program needs must be there.

use crate::diag::{message, Diagnostics};
use crate::span::Span;

/// Longest line lmdc writes from the source (LinuxCNC reads at most 255).
pub const MAX_LINE: usize = 200;

/// Whether `text`, the value of `key` at `span`, is one line a control can read;
/// reports it if not.
pub fn line(text: &str, key: &str, span: Span, diags: &mut Diagnostics) -> bool {
    if let Some((i, c)) = text
        .char_indices()
        .find(|&(_, c)| !(' '..='~').contains(&c))
    {
        diags.push(message::statement::program_text_character(
            key,
            c,
            text[..i].chars().count() + 1,
            span,
        ));
        return false;
    }
    if text.len() > MAX_LINE {
        diags.push(message::statement::program_text_too_long(
            key,
            text.len(),
            MAX_LINE,
            span,
        ));
        return false;
    }
    true
}

/// A laser switch line must not be empty: the program could not switch.
pub fn switch(text: &str, key: &str, span: Span, diags: &mut Diagnostics) -> bool {
    if !line(text, key, span, diags) {
        return false;
    }
    if text.trim().is_empty() {
        diags.push(message::statement::empty_switch(key, span));
        return false;
    }
    true
}

/// A dwell line must say where the seconds go, once: `{s}`.
pub fn dwell(text: &str, span: Span, diags: &mut Diagnostics) -> bool {
    if !line(text, "dwell", span, diags) {
        return false;
    }
    if text.matches("{s}").count() != 1 {
        diags.push(message::statement::dwell_without_seconds(span));

        return false;
    }
    true
}

/// Whether `lines` (the postamble) end the program: an `M2`, `M02` or `M30`.
pub fn ends_program(lines: &[String]) -> bool {
    lines.iter().any(|l| {
        l.split_whitespace()
            .any(|w| matches!(w.to_ascii_uppercase().as_str(), "M2" | "M02" | "M30"))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_printable_line() {
        let mut d = Diagnostics::new();
        assert!(line("G21 G90 (mm)", "preamble", Span::new(0, 1), &mut d));
        assert!(!line("M3\rG0 Z-500", "laser_on", Span::new(0, 1), &mut d));
        assert!(!line("M3\u{1b}[2J", "laser_on", Span::new(0, 1), &mut d));
        assert!(!line("M3 ö", "laser_on", Span::new(0, 1), &mut d));
        assert!(!switch("  ", "laser_off", Span::new(0, 1), &mut d));
        let msgs: Vec<_> = d.iter().map(|d| d.message.clone()).collect();
        assert!(
            msgs[0].contains("carriage return") && msgs[0].contains("character 3"),
            "{msgs:?}"
        );
        assert!(msgs[1].contains("U+001B"), "{msgs:?}");
        assert_eq!(d.error_count(), 4);
    }

    #[test]
    fn program_ends() {
        assert!(ends_program(&["M5".into(), "m30".into()]));
        assert!(ends_program(&["M5 M2".into()]));
        assert!(!ends_program(&["M5".into(), "M300".into()]));
        assert!(!ends_program(&[]));
    }
}
