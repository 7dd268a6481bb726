//! A [`Dialect`] turned into the byte strings the motion writer appends, and the
//! comment rules the templates rely on.

use crate::ir::{CommentStyle, Dialect};

/// What the writer needs from a dialect, ready to append.
pub(crate) struct Words {
    /// `G0 ` or `G00 `.
    pub rapid: &'static [u8],
    /// `G1 ` or `G01 `.
    pub feed: &'static [u8],
    /// The laser-on line(s), each ending in `\n`; empty if the dialect has none.
    pub laser_on: Vec<u8>,
    /// The laser-off line(s), likewise.
    pub laser_off: Vec<u8>,
    /// S per watt.
    pub s_per_watt: f64,
    /// Decimals of the S word (at most 9, what the formatter can print).
    pub s_decimals: usize,
    /// F per mm/s of speed (60 for mm/min).
    pub f_per_mm_s: f64,
    /// Most decimals of F.
    pub f_decimals: usize,
}

impl Words {
    /// The words of `d`.
    pub fn new(d: &Dialect) -> Self {
        let (rapid, feed): (&[u8], &[u8]) = if d.padded_g {
            (b"G00 ", b"G01 ")
        } else {
            (b"G0 ", b"G1 ")
        };
        Words {
            rapid,
            feed,
            laser_on: lines(&d.laser_on),
            laser_off: lines(&d.laser_off),
            s_per_watt: d.s_per_watt,
            s_decimals: d.s_decimals.min(9),
            f_per_mm_s: d.feed.per_mm_s(),
            f_decimals: crate::target::gcode::f_decimals(d.feed),
        }
    }
}

/// `text` as lines ending in `\n`, without blank lines or trailing blanks.
pub(crate) fn lines(text: &str) -> Vec<u8> {
    let mut out = Vec::new();
    for l in text
        .lines()
        .map(str::trim_end)
        .filter(|l| !l.trim().is_empty())
    {
        out.extend_from_slice(l.as_bytes());
        out.push(b'\n');
    }
    out
}

/// The comment delimiters of `style`: what goes before and after the text.
pub(crate) fn delimiters(style: CommentStyle) -> (&'static str, &'static str) {
    match style {
        CommentStyle::Parens => ("(", ")"),
        CommentStyle::Semicolon => ("; ", ""),
    }
}

/// `text` made safe inside a comment of `style`: one line of printable ASCII
/// (controls differ on other bytes), and no parentheses inside `(…)` comments
/// since they do not nest (`(` `)` become `[` `]`).
pub(crate) fn comment_safe(text: &str, style: CommentStyle) -> String {
    text.chars()
        .map(|c| match c {
            '(' if style == CommentStyle::Parens => '[',
            ')' if style == CommentStyle::Parens => ']',
            ' '..='~' => c,
            _ => '_',
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn comments_stay_on_one_line_and_do_not_nest() {
        assert_eq!(
            comment_safe("duct (v2)\nlong", CommentStyle::Parens),
            "duct [v2]_long"
        );
        assert_eq!(
            comment_safe("duct (v2) ö", CommentStyle::Semicolon),
            "duct (v2) _"
        );
    }

    #[test]
    fn dialect_lines_are_normalised() {
        assert_eq!(lines("M62 P0\n\nM3  \n"), b"M62 P0\nM3\n");
        assert!(lines("").is_empty());
    }
}
