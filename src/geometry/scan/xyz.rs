//! Point clouds as text, a point a line: `x y z`, `x,y,z` or `x;y;z`
//! (what scanner software exports as XYZ, ASC, TXT or CSV), more columns
//! (normals, intensity) ignored. Blank lines and lines starting with `#`
//! or `//` are skipped, and so is a first line that holds no number (a
//! CSV's header).

use super::{check_points, Raw, ScanError, MAX_POINTS};

/// The points of an XYZ/CSV text.
pub fn read(bytes: &[u8]) -> Result<Raw, ScanError> {
    let text = String::from_utf8_lossy(bytes);
    let mut vertices = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let t = line.trim();
        if t.is_empty() || t.starts_with('#') || t.starts_with("//") {
            continue;
        }
        let cols: Vec<&str> = t
            .split(|c: char| c == ',' || c == ';' || c.is_whitespace())
            .filter(|c| !c.is_empty())
            .collect();
        let nums: Vec<f64> = cols.iter().map_while(|c| c.parse().ok()).collect();
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
        if vertices.len() == MAX_POINTS {
            return Err(ScanError::TooMany {
                what: "points",
                count: MAX_POINTS as u64 + 1,
                max: MAX_POINTS,
            });
        }
        vertices.push([nums[0] as f32, nums[1] as f32, nums[2] as f32]);
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
        let raw = read(b"x,y,z,intensity\n1,2,3,99\n\n# a comment\n4 5 6\n7;8;9.5\n").unwrap();
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
}
