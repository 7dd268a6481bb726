//! STL files, binary and ASCII, as triangles of three corners each (the
//! stored normals are not read: a corner order says which side is out, and
//! exporters disagree on the normals more often than on the order).
//!
//! A reader of its own rather than a crate: both formats fit in a page, and
//! the crates that read them bring their own dependencies into every build.

/// A triangle's three corners, as the file writes them.
pub type Triangle = [[f32; 3]; 3];

/// Most triangles an STL file may hold: 50 bytes each in a binary file (a
/// 1 GB file), and 72 bytes each once read.
pub const MAX_TRIANGLES: usize = 20_000_000;

/// Why a file is no STL lmdc can read.
#[derive(Clone, Debug, PartialEq)]
pub enum StlError {
    /// Neither a binary STL (84 bytes of header and count, 50 a triangle)
    /// nor an ASCII one (`solid …`).
    NotStl {
        /// How long the file is.
        len: usize,
    },
    /// A binary file whose length disagrees with its triangle count.
    Truncated {
        /// The count in its header.
        count: u64,
        /// The bytes it should have.
        expected: u64,
        /// The bytes it has.
        got: usize,
    },
    /// An ASCII file's line that is not what STL writes there.
    Ascii {
        /// The line, from 1.
        line: usize,
        /// What was expected there.
        expected: &'static str,
    },
    /// A corner that is no finite number.
    NotFinite {
        /// The triangle, from 0 in file order.
        triangle: usize,
    },
    /// A file with no triangle.
    Empty,
    /// More triangles than [`MAX_TRIANGLES`].
    TooMany {
        /// How many.
        count: u64,
    },
}

/// The triangles of an STL file, binary or ASCII.
pub fn read(bytes: &[u8]) -> Result<Vec<Triangle>, StlError> {
    let tris = if is_binary(bytes) {
        binary(bytes)?
    } else if ascii_start(bytes) {
        ascii(bytes)?
    } else if bytes.len() >= 84 {
        // A header and a count, but not the length they call for.
        let count = u64::from(u32::from_le_bytes([
            bytes[80], bytes[81], bytes[82], bytes[83],
        ]));
        return Err(StlError::Truncated {
            count,
            expected: 84 + 50 * count,
            got: bytes.len(),
        });
    } else {
        return Err(StlError::NotStl { len: bytes.len() });
    };
    if tris.is_empty() {
        return Err(StlError::Empty);
    }
    if let Some(t) = tris
        .iter()
        .position(|t| t.iter().flatten().any(|c| !c.is_finite()))
    {
        return Err(StlError::NotFinite { triangle: t });
    }
    Ok(tris)
}

/// Whether `bytes` is a binary STL: its length is what its count says (an
/// ASCII-looking header, `solid …`, is common in binary files too).
fn is_binary(bytes: &[u8]) -> bool {
    if bytes.len() < 84 {
        return false;
    }
    let count = u64::from(u32::from_le_bytes([
        bytes[80], bytes[81], bytes[82], bytes[83],
    ]));
    bytes.len() as u64 == 84 + 50 * count
}

fn ascii_start(bytes: &[u8]) -> bool {
    let text = bytes.trim_ascii_start();
    text.starts_with(b"solid") && std::str::from_utf8(bytes).is_ok()
}

fn binary(bytes: &[u8]) -> Result<Vec<Triangle>, StlError> {
    let count = (bytes.len() - 84) / 50;
    if count > MAX_TRIANGLES {
        return Err(StlError::TooMany {
            count: count as u64,
        });
    }
    let f = |b: &[u8], at: usize| f32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]]);
    Ok(bytes[84..]
        .chunks_exact(50)
        .map(|r| {
            // 12 bytes of normal, then three corners of 12, then 2 of attributes.
            let corner = |i: usize| {
                let at = 12 + 12 * i;
                [f(r, at), f(r, at + 4), f(r, at + 8)]
            };
            [corner(0), corner(1), corner(2)]
        })
        .collect())
}

fn ascii(bytes: &[u8]) -> Result<Vec<Triangle>, StlError> {
    // Checked UTF-8 by `ascii_start`.
    let text = std::str::from_utf8(bytes).unwrap_or_default();
    let mut out = Vec::new();
    let mut corners: Vec<[f32; 3]> = Vec::with_capacity(3);
    let mut in_facet = false;
    for (i, line) in text.lines().enumerate() {
        let line_no = i + 1;
        let bad = |expected| StlError::Ascii {
            line: line_no,
            expected,
        };
        let mut words = line.split_ascii_whitespace();
        match words.next() {
            None | Some("solid" | "endsolid" | "outer" | "endloop") => {}
            Some("facet") => {
                if in_facet {
                    return Err(bad("`endfacet` before the next `facet`"));
                }
                in_facet = true;
                corners.clear();
            }
            Some("vertex") => {
                if !in_facet || corners.len() == 3 {
                    return Err(bad("three `vertex` lines in each `facet`"));
                }
                let mut c = [0f32; 3];
                for x in &mut c {
                    *x = words
                        .next()
                        .and_then(|w| w.parse().ok())
                        .ok_or_else(|| bad("`vertex X Y Z`, three numbers"))?;
                }
                corners.push(c);
            }
            Some("endfacet") => {
                if !in_facet || corners.len() != 3 {
                    return Err(bad("three `vertex` lines before `endfacet`"));
                }
                in_facet = false;
                out.push([corners[0], corners[1], corners[2]]);
                if out.len() > MAX_TRIANGLES {
                    return Err(StlError::TooMany {
                        count: out.len() as u64,
                    });
                }
            }
            Some(_) => {
                return Err(bad(
                    "`facet`, `outer loop`, `vertex`, `endloop` or `endfacet`",
                ))
            }
        }
    }
    if in_facet {
        return Err(StlError::Ascii {
            line: text.lines().count(),
            expected: "`endfacet` before the end of the file",
        });
    }
    Ok(out)
}

/// `tris` as a binary STL (for tests, benches and the examples' scripts'
/// checks): a zero normal, no attributes.
pub fn to_binary(tris: &[Triangle]) -> Vec<u8> {
    let mut out = Vec::with_capacity(84 + 50 * tris.len());
    let mut header = [b' '; 80];
    header[..11].copy_from_slice(b"binary lmdc");
    out.extend_from_slice(&header);
    out.extend_from_slice(&(tris.len() as u32).to_le_bytes());
    for t in tris {
        out.extend_from_slice(&[0u8; 12]);
        for c in t {
            for x in c {
                out.extend_from_slice(&x.to_le_bytes());
            }
        }
        out.extend_from_slice(&[0u8; 2]);
    }
    out
}

/// `tris` as an ASCII STL (for tests).
pub fn to_ascii(tris: &[Triangle]) -> String {
    let mut out = String::from("solid lmdc\n");
    for t in tris {
        out.push_str("  facet normal 0 0 0\n    outer loop\n");
        for c in t {
            // `{:?}` writes the shortest text that reads back as the same f32.
            out.push_str(&format!("      vertex {:?} {:?} {:?}\n", c[0], c[1], c[2]));
        }
        out.push_str("    endloop\n  endfacet\n");
    }
    out.push_str("endsolid lmdc\n");
    out
}
