//! A measurement sheet: the coupons of a calibration build, one a row of a
//! CSV file, with the units of each column in its header (`speed (mm/s)`,
//! `height (mm)`). What `lmdc fit` and `model = fit(…, data = "…")` read.
//!
//! The reader is small on purpose: a sheet is what a spreadsheet saves,
//! comma-separated, a field in double quotes where it holds a comma. Lines
//! that are blank or start with `#` are skipped. Columns lmdc does not know
//! (notes, operator) are kept out of the way; a column it knows must say its
//! unit, one it can convert. A row whose measurements are all empty is a
//! coupon not measured yet and is skipped; a cell that is not a number is
//! an error pointing at it.

use crate::span::Span;

/// A quantity a sheet may hold, and the units its header may give it in
/// (each with its factor to lmdc's unit, the first).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Column {
    /// Scan speed, mm/s.
    Speed,
    /// Bead height, mm.
    Height,
    /// Bead width, mm.
    Width,
    /// Cross-section, mm².
    Area,
    /// The metal a coupon holds, g.
    Mass,
    /// The powder feed, g/min.
    Feed,
    /// The length laid, mm (with `mass`: the metal per length).
    Length,
    /// Laser power, W.
    Power,
}

impl Column {
    /// Every column lmdc reads.
    pub const ALL: [Column; 8] = [
        Column::Speed,
        Column::Height,
        Column::Width,
        Column::Area,
        Column::Mass,
        Column::Feed,
        Column::Length,
        Column::Power,
    ];

    /// Its name in a header.
    pub fn name(self) -> &'static str {
        match self {
            Column::Speed => "speed",
            Column::Height => "height",
            Column::Width => "width",
            Column::Area => "area",
            Column::Mass => "mass",
            Column::Feed => "feed",
            Column::Length => "length",
            Column::Power => "power",
        }
    }

    /// The units it may be written in, with their factor to the first.
    pub fn units(self) -> &'static [(&'static str, f64)] {
        match self {
            Column::Speed => &[
                ("mm/s", 1.0),
                ("mm/min", 1.0 / 60.0),
                ("m/min", 1000.0 / 60.0),
            ],
            Column::Height | Column::Width | Column::Length => {
                &[("mm", 1.0), ("um", 1e-3), ("µm", 1e-3)]
            }
            Column::Area => &[("mm^2", 1.0), ("mm²", 1.0), ("mm2", 1.0)],
            Column::Mass => &[("g", 1.0), ("mg", 1e-3)],
            Column::Feed => &[("g/min", 1.0), ("g/s", 60.0)],
            Column::Power => &[("W", 1.0), ("kW", 1000.0)],
        }
    }

    fn of(name: &str) -> Option<Column> {
        let name = name.trim().to_ascii_lowercase();
        let name = if name == "powder" { "feed" } else { &name };
        Column::ALL.into_iter().find(|c| c.name() == name)
    }
}

/// One measured coupon: its line in the file (from 1) and what was
/// measured on it, in lmdc's units (mm, mm/s, mm², g, g/min, W).
#[derive(Clone, Debug, PartialEq)]
pub struct Coupon {
    /// The line of the file it is on.
    pub line: usize,
    /// Its `id`, if the sheet has one.
    pub id: Option<String>,
    /// Where its row is in the file (bytes).
    pub span: Span,
    /// The values of the columns the sheet has, by [`Column`].
    values: [Option<f64>; 8],
}

impl Coupon {
    /// The value of `c`, if the sheet has the column and the cell is filled.
    pub fn get(&self, c: Column) -> Option<f64> {
        self.values[c as usize]
    }

    /// Its scan speed, mm/s (every coupon measured has one).
    pub fn speed(&self) -> f64 {
        self.values[Column::Speed as usize].unwrap_or(f64::NAN)
    }
}

/// The coupons measured in a sheet, and which columns it has.
#[derive(Clone, Debug, PartialEq)]
pub struct Sheet {
    /// The coupons with a measurement, in the file's order.
    pub coupons: Vec<Coupon>,
    /// The columns the header names.
    pub columns: Vec<Column>,
    /// Rows whose measurements are all empty: coupons not measured yet.
    pub unmeasured: usize,
    /// Where its header is in the file (bytes).
    pub header: Span,
}

impl Sheet {
    /// Whether the header names `c`.
    pub fn has(&self, c: Column) -> bool {
        self.columns.contains(&c)
    }
}

/// The columns that are measurements, not parameters: a row with none of
/// them filled is a coupon still to measure.
const MEASURED: [Column; 4] = [Column::Height, Column::Width, Column::Area, Column::Mass];

/// A mistake in a measurement sheet, its spans bytes of the sheet's text:
/// the data of what `diag::message::calib::sheet` says.
#[derive(Clone, Debug, PartialEq)]
pub enum SheetFault {
    /// The sheet holds no row at all.
    Empty(Span),
    /// The header (its cells) has no `speed` column.
    NoSpeedColumn(Span),
    /// A row has more cells than the header; `at` is the first extra one.
    ExtraCell {
        /// The row's line, from 1.
        line: usize,
        /// The first cell too many.
        at: Span,
        /// How many columns the header has.
        columns: usize,
    },
    /// A measured row has no speed.
    NoSpeed {
        /// The row's line, from 1.
        line: usize,
        /// Its first cell.
        at: Span,
    },
    /// A cell is not a number.
    NotANumber(Column, String, Span),
    /// A cell is zero or below.
    NotPositive(Column, String, Span),
    /// A column is named twice: here and first.
    DuplicateColumn(Column, Span, Span),
    /// A column does not say its unit.
    MissingUnit(Column, Span),
    /// A column's unit is not one lmdc converts.
    WrongUnit(Column, String, Span),
}

impl SheetFault {
    /// Where the mistake is, in the sheet's text.
    pub fn span(&self) -> Span {
        match self {
            SheetFault::Empty(at) | SheetFault::NoSpeedColumn(at) => *at,
            SheetFault::ExtraCell { at, .. } | SheetFault::NoSpeed { at, .. } => *at,
            SheetFault::NotANumber(_, _, at) | SheetFault::NotPositive(_, _, at) => *at,
            SheetFault::DuplicateColumn(_, at, _) => *at,
            SheetFault::MissingUnit(_, at) | SheetFault::WrongUnit(_, _, at) => *at,
        }
    }
}

/// Reads `text`, a measurement sheet; every mistake in it is a
/// [`SheetFault`] whose spans are bytes of `text`.
pub fn read(text: &str) -> Result<Sheet, Vec<SheetFault>> {
    let mut diags = Vec::new();
    let mut lines = rows(text);
    let Some((_, header)) = lines.next() else {
        return Err(vec![SheetFault::Empty(Span::new(0, text.len()))]);
    };
    let (id, kinds) = header_columns(&header, &mut diags);
    let named = |c: Column| {
        header
            .iter()
            .any(|h| Column::of(split_unit(&h.0).0) == Some(c))
    };
    if !named(Column::Speed) {
        diags.push(SheetFault::NoSpeedColumn(cells_span(&header)));
    }
    // A header lmdc cannot read makes every row's complaint the same one.
    if !diags.is_empty() {
        return Err(diags);
    }
    let mut sheet = Sheet {
        coupons: Vec::new(),
        columns: kinds.iter().flatten().map(|(c, _)| *c).collect(),
        unmeasured: 0,
        header: cells_span(&header),
    };
    for (line, cells) in lines {
        if let Some(extra) = cells.get(header.len()) {
            diags.push(SheetFault::ExtraCell {
                line,
                at: extra.1,
                columns: header.len(),
            });
            continue;
        }
        let mut values = [None; 8];
        for (k, (cell, at)) in cells.iter().enumerate() {
            let Some((col, factor)) = kinds[k] else {
                continue;
            };
            values[col as usize] = number(cell, *at, col, &mut diags).map(|x| x * factor);
        }
        let filled = |c: Column| values[c as usize].is_some();
        if !MEASURED.iter().any(|&c| filled(c)) {
            sheet.unmeasured += 1;
            continue;
        }
        if !filled(Column::Speed) {
            let at = cells.first().map_or(Span::new(0, 0), |c| c.1);
            diags.push(SheetFault::NoSpeed { line, at });
            continue;
        }
        sheet.coupons.push(Coupon {
            line,
            id: id
                .and_then(|k| cells.get(k))
                .map(|c| c.0.trim().to_string()),
            span: cells_span(&cells),
            values,
        });
    }
    if diags.is_empty() {
        Ok(sheet)
    } else {
        Err(diags)
    }
}

/// The header's cells as columns (with their unit's factor) and where the
/// `id` column is; every unknown unit or missing one reported.
#[allow(clippy::type_complexity)]
fn header_columns(
    header: &[(String, Span)],
    diags: &mut Vec<SheetFault>,
) -> (Option<usize>, Vec<Option<(Column, f64)>>) {
    let mut id = None;
    let mut seen: Vec<(Column, Span)> = Vec::new();
    let kinds = header
        .iter()
        .enumerate()
        .map(|(k, (cell, at))| {
            let (name, unit) = split_unit(cell);
            if name.eq_ignore_ascii_case("id") {
                id = Some(k);
                return None;
            }
            let col = Column::of(name)?;
            if let Some((_, first)) = seen.iter().find(|(c, _)| *c == col) {
                diags.push(SheetFault::DuplicateColumn(col, *at, *first));
                return None;
            }
            seen.push((col, *at));
            let Some(unit) = unit else {
                diags.push(SheetFault::MissingUnit(col, *at));
                return None;
            };
            match col.units().iter().find(|(u, _)| *u == unit) {
                Some(&(_, factor)) => Some((col, factor)),
                None => {
                    diags.push(SheetFault::WrongUnit(col, unit.to_string(), *at));
                    None
                }
            }
        })
        .collect();
    (id, kinds)
}

/// `height (mm)` or `height [mm]` → (`height`, `mm`); a cell with no
/// brackets has no unit.
fn split_unit(cell: &str) -> (&str, Option<&str>) {
    let cell = cell.trim();
    for (open, close) in [('(', ')'), ('[', ']')] {
        if let (Some(a), true) = (cell.find(open), cell.ends_with(close)) {
            let unit = cell[a + 1..cell.len() - 1].trim();
            return (cell[..a].trim(), Some(unit));
        }
    }
    (cell, None)
}

/// A cell as a number of `col`: empty is `None`; anything else must be a
/// finite number greater than zero (every quantity of a coupon is).
fn number(cell: &str, at: Span, col: Column, diags: &mut Vec<SheetFault>) -> Option<f64> {
    let t = cell.trim();
    if t.is_empty() {
        return None;
    }
    match t.parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Some(x),
        Ok(x) if x.is_finite() => {
            diags.push(SheetFault::NotPositive(col, t.to_string(), at));
            None
        }
        _ => {
            diags.push(SheetFault::NotANumber(col, t.to_string(), at));
            None
        }
    }
}

/// The span covering a row's cells.
fn cells_span(cells: &[(String, Span)]) -> Span {
    match (cells.first(), cells.last()) {
        (Some(a), Some(b)) => a.1.join(b.1),
        _ => Span::new(0, 0),
    }
}

/// The rows of `text` that are not blank or comments: their line (from 1)
/// and their cells, each with its span (a quoted cell's, quotes included).
fn rows(text: &str) -> impl Iterator<Item = (usize, Vec<(String, Span)>)> + '_ {
    lines(text).enumerate().filter_map(|(i, (at, line))| {
        let t = line.trim();
        (!t.is_empty() && !t.starts_with('#')).then(|| (i + 1, cells(line, at)))
    })
}

/// The lines of `text`, each with the byte it starts at, without its end:
/// LF, CRLF or a lone CR (as old Mac spreadsheets write a CSV).
fn lines(text: &str) -> impl Iterator<Item = (usize, &str)> + '_ {
    let b = text.as_bytes();
    let mut start = 0;
    std::iter::from_fn(move || {
        if start >= b.len() {
            return None;
        }
        let at = start;
        let end = b[at..]
            .iter()
            .position(|&c| c == b'\n' || c == b'\r')
            .map_or(b.len(), |k| at + k);
        start = match b.get(end..end + 2) {
            Some(b"\r\n") => end + 2,
            _ => end + 1,
        };
        Some((at, &text[at..end]))
    })
}

/// The cells of one line starting at byte `at`: comma-separated, a field
/// in double quotes may hold commas (`""` is a quote).
fn cells(line: &str, at: usize) -> Vec<(String, Span)> {
    let mut out = Vec::new();
    let mut cell = String::new();
    let (mut begin, mut quoted) = (0, false);
    let mut chars = line.char_indices().peekable();
    while let Some((i, ch)) = chars.next() {
        match ch {
            '"' if quoted && chars.peek().map(|c| c.1) == Some('"') => {
                cell.push('"');
                chars.next();
            }
            '"' => quoted = !quoted,
            ',' if !quoted => {
                out.push((std::mem::take(&mut cell), span(line, at, begin, i)));
                begin = i + 1;
            }
            c => cell.push(c),
        }
    }
    out.push((cell, span(line, at, begin, line.len())));
    out
}

/// The span of a cell's bytes `a..b` of `line` (at byte `at` of the
/// file), its surrounding blanks left out (an empty cell: where it is).
fn span(line: &str, at: usize, a: usize, b: usize) -> Span {
    let s = &line[a..b];
    let lead = s.len() - s.trim_start().len();
    let trail = s.len() - s.trim_end().len();
    if lead == s.len() {
        return Span::new(at + a, at + a);
    }
    Span::new(at + a + lead, at + b - trail)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_convert_and_unmeasured_rows_are_skipped() {
        let s = read(
            "id,speed (mm/min),height [um],width (mm),note\n\
             # the first plate\n\
             c1,240,1280,2.6,\"good, flat\"\n\
             c2,360,,,\n\
             \n\
             c3,522,645.5,2.2,\n",
        )
        .unwrap();
        assert_eq!(s.coupons.len(), 2);
        assert_eq!(s.unmeasured, 1);
        let c = &s.coupons[0];
        assert_eq!(c.line, 3);
        assert_eq!(c.id.as_deref(), Some("c1"));
        assert!((c.speed() - 4.0).abs() < 1e-12);
        assert!((c.get(Column::Height).unwrap() - 1.28).abs() < 1e-12);
        assert_eq!(c.get(Column::Area), None);
        assert_eq!(s.coupons[1].line, 6);
    }

    /// A sheet saved with lone CRs (an old Mac spreadsheet's CSV) reads as
    /// the same sheet with LFs or CRLFs: it once read as one header line
    /// and "0 coupons measured".
    #[test]
    fn lf_crlf_and_cr_line_ends_read_the_same() {
        let text = "id,speed (mm/s),height (mm)\n# plate 1\nc1,4,1.2\n\nc2,6,0.9\nc3,8,bad\n";
        let lf = read(text).unwrap_err();
        let place = |d: &[SheetFault], t: &str| {
            let sp = d[0].span();
            t[sp.start..sp.end].to_string()
        };
        for end in ["\r\n", "\r"] {
            let t = text.replace('\n', end);
            let d = read(&t).unwrap_err();
            assert_eq!(d.len(), lf.len());
            assert_eq!(place(&d, &t), "bad");
            let good = t.replace("bad", "0.7");
            let s = read(&good).unwrap();
            assert_eq!(s.coupons.len(), 3);
            assert_eq!(
                s.coupons.iter().map(|c| c.line).collect::<Vec<_>>(),
                [3, 5, 6]
            );
        }
    }

    #[test]
    fn a_bad_cell_is_pointed_at() {
        let text = "speed (mm/s),height (mm)\n4,1.2\n6,1,0x\n";
        let d = read(text).unwrap_err();
        assert_eq!(d.len(), 1);
        let text = "speed (mm/s),height (mm)\n4,1.2\n6, abc \n";
        let d = read(text).unwrap_err();
        let sp = d[0].span();
        assert_eq!(&text[sp.start..sp.end], "abc");
    }
}
