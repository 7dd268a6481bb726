//! Byte offsets (lmdc's spans) ↔ LSP positions (line and character). A
//! character counts UTF-16 code units unless the client agreed to UTF-8
//! bytes (LSP 3.17 `positionEncoding`).

/// How the client counts characters in a line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Encoding {
    /// UTF-16 code units: the protocol's default.
    Utf16,
    /// Bytes.
    Utf8,
}

/// Where each line of a text starts.
#[derive(Clone, Debug)]
pub struct LineIndex {
    starts: Vec<usize>,
    encoding: Encoding,
}

impl LineIndex {
    /// The index of `text`.
    pub fn new(text: &str, encoding: Encoding) -> Self {
        let mut starts = vec![0];
        starts.extend(text.match_indices('\n').map(|(i, _)| i + 1));
        LineIndex { starts, encoding }
    }

    /// The position of byte `offset` (clamped to the text, and back to a
    /// character boundary).
    pub fn position(&self, text: &str, offset: usize) -> (u32, u32) {
        let mut offset = offset.min(text.len());
        while !text.is_char_boundary(offset) {
            offset -= 1;
        }
        let line = self.starts.partition_point(|&s| s <= offset) - 1;
        let start = self.starts[line];
        let character = match self.encoding {
            Encoding::Utf8 => offset - start,
            Encoding::Utf16 => text[start..offset].encode_utf16().count(),
        };
        (line as u32, character as u32)
    }

    /// The byte offset of a position (a character past the line's end is its
    /// end; a line past the last is the text's end).
    pub fn offset(&self, text: &str, line: u32, character: u32) -> usize {
        let Some(&start) = self.starts.get(line as usize) else {
            return text.len();
        };
        let end = self
            .starts
            .get(line as usize + 1)
            .map_or(text.len(), |&e| e.saturating_sub(1));
        let line_text = &text[start..end.max(start)];
        let mut units = 0usize;
        for (i, c) in line_text.char_indices() {
            if units >= character as usize {
                return start + i;
            }
            units += match self.encoding {
                Encoding::Utf8 => c.len_utf8(),
                Encoding::Utf16 => c.len_utf16(),
            };
        }
        start + line_text.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn utf16_counts_code_units_and_round_trips() {
        // `µ` is 2 bytes and 1 UTF-16 unit; `𝜌` is 4 bytes and 2 units.
        let text = "a = 1 µm\nb = 𝜌 x\n";
        let ix = LineIndex::new(text, Encoding::Utf16);
        let x = text.find('x').unwrap();
        assert_eq!(ix.position(text, x), (1, 7));
        assert_eq!(ix.offset(text, 1, 7), x);
        let m = text.find('m').unwrap();
        assert_eq!(ix.position(text, m), (0, 7));
        let u8ix = LineIndex::new(text, Encoding::Utf8);
        assert_eq!(u8ix.position(text, m), (0, 8));
        assert_eq!(u8ix.offset(text, 0, 8), m);
    }

    #[test]
    fn positions_past_the_end_clamp() {
        let text = "ab\ncd";
        let ix = LineIndex::new(text, Encoding::Utf16);
        assert_eq!(ix.offset(text, 0, 99), 2);
        assert_eq!(ix.offset(text, 9, 0), text.len());
        assert_eq!(ix.position(text, 99), (1, 2));
    }
}
