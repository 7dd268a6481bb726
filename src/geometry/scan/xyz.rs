//! Point clouds as text, a point a line: `x y z`, `x,y,z` or `x;y;z`
//! (what scanner software exports as XYZ, ASC, TXT or CSV), more columns
//! (normals, intensity) ignored. Blank lines and lines starting with `#`
//! or `//` are skipped, and so is a first line that holds no number (a
//! CSV's header).
//!
//! Where the fields are separated by semicolons, tabs or spaces, a comma
//! inside a field is a decimal comma (`-28,8;-8,8;10,0`, as scanner
//! software set to a European locale writes). Every line holds as many
//! numbers as the first (a line with another count is a line the reader
//! would misread, named with both counts); and a first column that counts
//! the lines (0, 1, 2, … or 1, 2, 3, …) in front of three more is an index,
//! not x: refused, so a point is never read from the wrong columns.

use super::{check_points, Raw, ScanError, MAX_POINTS};

/// The numbers of one line: its fields split at semicolons and white
/// space, commas inside them decimal commas, when that gives three or
/// more; else split at commas too.
fn numbers(t: &str) -> Vec<f64> {
    let fields: Vec<&str> = t
        .split(|c: char| c == ';' || c.is_whitespace())
        .map(|f| f.trim_matches(','))
        .filter(|f| !f.is_empty())
        .collect();
    let parse = |c: &str| c.parse::<f64>().ok();
    if fields.len() >= 3 && fields.iter().any(|f| f.contains(',')) {
        let decimal: Vec<f64> = fields
            .iter()
            .map_while(|f| parse(&f.replacen(',', ".", 1)))
            .collect();
        if decimal.len() >= 3 {
            return decimal;
        }
    }
    t.split(|c: char| c == ',' || c == ';' || c.is_whitespace())
        .filter(|c| !c.is_empty())
        .map_while(parse)
        .collect()
}

/// The points of an XYZ/CSV text.
pub fn read(bytes: &[u8]) -> Result<Raw, ScanError> {
    let text = String::from_utf8_lossy(bytes);
    let mut vertices = Vec::new();
    // The first data line's count of numbers, and its line.
    let mut columns: Option<(usize, usize)> = None;
    // Whether the first column has counted the lines so far, from where.
    let mut counting: Option<f64> = None;
    for (i, line) in text.lines().enumerate() {
        let t = line.trim();
        if t.is_empty() || t.starts_with('#') || t.starts_with("//") {
            continue;
        }
        let nums = numbers(t);
        if nums.len() < 3 {
            let header = vertices.is_empty() && i == 0 && nums.is_empty();
            if header {
                continue;
            }
            return Err(ScanError::Line {
                line: i + 1,
                text: t.chars().take(40).collect(),
            });
        }
        match columns {
            None => {
                columns = Some((nums.len(), i + 1));
                counting = (nums.len() >= 4 && nums[0].fract() == 0.0).then_some(nums[0]);
            }
            Some((n, first)) if n != nums.len() => {
                return Err(ScanError::Columns {
                    line: i + 1,
                    count: nums.len(),
                    first,
                    expected: n,
                });
            }
            Some(_) => {}
        }
        if counting.is_some_and(|c| nums[0] != c + vertices.len() as f64) {
            counting = None;
        }
        if vertices.len() == MAX_POINTS {
            return Err(ScanError::TooMany {
                what: "points",
                count: MAX_POINTS as u64 + 1,
                max: MAX_POINTS,
            });
        }
        vertices.push([nums[0] as f32, nums[1] as f32, nums[2] as f32]);
    }
    if let (Some(from), true) = (counting, vertices.len() >= 3) {
        return Err(ScanError::Index { from });
    }
    let raw = Raw {
        vertices,
        triangles: Vec::new(),
    };
    check_points(&raw)?;
    Ok(raw)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spaces_commas_semicolons_and_a_header() {
        let raw =
            read(b"x,y,z,intensity\n1,2,3,99\n\n# a comment\n4 5 6 98\n7;8;9.5;97\n").unwrap();
        assert_eq!(
            raw.vertices,
            vec![[1.0, 2.0, 3.0], [4.0, 5.0, 6.0], [7.0, 8.0, 9.5]]
        );
    }

    #[test]
    fn a_short_line_is_named() {
        assert_eq!(
            read(b"1 2 3\n4 5\n"),
            Err(ScanError::Line {
                line: 2,
                text: "4 5".into()
            })
        );
        assert_eq!(read(b"x y z\n"), Err(ScanError::Empty));
        assert!(matches!(
            read(b"1 2 inf\n"),
            Err(ScanError::NotFinite { vertex: 0 })
        ));
        assert!(read(&[0xff, 0xfe, 0x00]).is_err());
    }

    #[test]
    fn decimal_commas_in_fields_split_by_semicolons_or_tabs() {
        let raw = read(b"-28,8;-8,8;10,0\n1,5;2;3,25\n").unwrap();
        assert_eq!(raw.vertices, vec![[-28.8, -8.8, 10.0], [1.5, 2.0, 3.25]]);
        let raw = read(b"-28,8\t-8,8\t10,0\t0,5\n").unwrap();
        assert_eq!(raw.vertices, vec![[-28.8, -8.8, 10.0]]);
        // Commas between fields stay separators, with spaces or without.
        let raw = read(b"1.5, 2.5, 3.5\n1,2,3\n").unwrap();
        assert_eq!(raw.vertices, vec![[1.5, 2.5, 3.5], [1.0, 2.0, 3.0]]);
    }

    #[test]
    fn a_line_with_another_count_of_numbers_is_named() {
        assert_eq!(
            read(b"1 2 3\n4 5 6\n7 8 9 10\n"),
            Err(ScanError::Columns {
                line: 3,
                count: 4,
                first: 1,
                expected: 3
            })
        );
        // A decimal-comma line in a file of points is misread as more
        // columns: named, not kept as a stray point.
        assert!(matches!(
            read(b"1.5;2.5;3.5\n1,5;2,5;3,5;7\n"),
            Err(ScanError::Columns { line: 2, .. })
        ));
    }

    #[test]
    fn a_first_column_counting_the_lines_is_an_index() {
        assert_eq!(
            read(b"0 1.5 2.5 3.5\n1 1.6 2.5 3.4\n2 1.7 2.5 3.3\n"),
            Err(ScanError::Index { from: 0.0 })
        );
        assert_eq!(
            read(b"i,x,y,z\n1,1.5,2.5,3.5\n2,1.6,2.5,3.4\n3,1.7,2.5,3.3\n"),
            Err(ScanError::Index { from: 1.0 })
        );
        // x on a 1 mm grid with normals: whole numbers, not counting.
        let grid = read(b"0 0 1 0 0 1\n1 0 1 0 0 1\n1 1 1 0 0 1\n").unwrap();
        assert_eq!(grid.vertices.len(), 3);
    }
}
