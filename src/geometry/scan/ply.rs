//! PLY scans (ASCII, binary little and big endian) through `ply-rs-bw`:
//! the `vertex` element's `x`, `y`, `z` (any numeric type) and, where the
//! file has them, the `face` element's `vertex_indices` (or
//! `vertex_index`), polygons fanned into triangles. Other elements and
//! properties (normals, colours, intensities) are read past and dropped.
//! The header's counts are checked against [`MAX_POINTS`] and
//! [`MAX_FACES`] before any payload is read.

use super::{check_points, Raw, ScanError, MAX_FACES, MAX_POINTS};
use ply_rs_bw::parser::{Parser, Reader};
use ply_rs_bw::ply::{PropertyAccess, PropertyAccessResult};

/// A vertex's position as the file writes it (missing coordinates are NaN,
/// so a file without `z` is caught).
struct Vertex([f64; 3]);

impl Vertex {
    fn set(&mut self, name: &str, v: f64) -> PropertyAccessResult {
        let i = match name {
            "x" => 0,
            "y" => 1,
            "z" => 2,
            _ => return PropertyAccessResult::Ignored,
        };
        self.0[i] = v;
        PropertyAccessResult::Set
    }
}

impl PropertyAccess for Vertex {
    fn new() -> Self {
        Vertex([f64::NAN; 3])
    }
    fn set_char(&mut self, n: &str, v: i8) -> PropertyAccessResult {
        self.set(n, v.into())
    }
    fn set_uchar(&mut self, n: &str, v: u8) -> PropertyAccessResult {
        self.set(n, v.into())
    }
    fn set_short(&mut self, n: &str, v: i16) -> PropertyAccessResult {
        self.set(n, v.into())
    }
    fn set_ushort(&mut self, n: &str, v: u16) -> PropertyAccessResult {
        self.set(n, v.into())
    }
    fn set_int(&mut self, n: &str, v: i32) -> PropertyAccessResult {
        self.set(n, v.into())
    }
    fn set_uint(&mut self, n: &str, v: u32) -> PropertyAccessResult {
        self.set(n, v.into())
    }
    fn set_float(&mut self, n: &str, v: f32) -> PropertyAccessResult {
        self.set(n, v.into())
    }
    fn set_double(&mut self, n: &str, v: f64) -> PropertyAccessResult {
        self.set(n, v)
    }
}

/// A face's corners (any integer list type).
#[derive(Default)]
struct Face(Vec<i64>);

impl Face {
    fn set(&mut self, name: &str, v: impl Iterator<Item = i64>) -> PropertyAccessResult {
        if name == "vertex_indices" || name == "vertex_index" {
            self.0 = v.collect();
            PropertyAccessResult::Set
        } else {
            PropertyAccessResult::Ignored
        }
    }
}

impl PropertyAccess for Face {
    fn new() -> Self {
        Face::default()
    }
    fn set_list_char(&mut self, n: &str, v: Vec<i8>) -> PropertyAccessResult {
        self.set(n, v.into_iter().map(i64::from))
    }
    fn set_list_uchar(&mut self, n: &str, v: Vec<u8>) -> PropertyAccessResult {
        self.set(n, v.into_iter().map(i64::from))
    }
    fn set_list_short(&mut self, n: &str, v: Vec<i16>) -> PropertyAccessResult {
        self.set(n, v.into_iter().map(i64::from))
    }
    fn set_list_ushort(&mut self, n: &str, v: Vec<u16>) -> PropertyAccessResult {
        self.set(n, v.into_iter().map(i64::from))
    }
    fn set_list_int(&mut self, n: &str, v: Vec<i32>) -> PropertyAccessResult {
        self.set(n, v.into_iter().map(i64::from))
    }
    fn set_list_uint(&mut self, n: &str, v: Vec<u32>) -> PropertyAccessResult {
        self.set(n, v.into_iter().map(i64::from))
    }
}

/// Anything else: read past.
struct Skip;

impl PropertyAccess for Skip {
    fn new() -> Self {
        Skip
    }
}

/// The points and faces of a PLY file.
pub fn read(bytes: &[u8]) -> Result<Raw, ScanError> {
    let ply = |e: ply_rs_bw::parser::ParseError| ScanError::Ply(first_line(&e.to_string()));
    let mut reader = Reader::new(bytes);
    let header = Parser::<Skip>::new()
        .read_header(&mut reader)
        .map_err(ply)?;
    let Some(vdef) = header.elements.get("vertex") else {
        return Err(ScanError::NoVertices);
    };
    if !["x", "y", "z"]
        .iter()
        .all(|k| vdef.properties.contains_key(*k))
    {
        return Err(ScanError::NoVertices);
    }
    too_many("points", vdef.count, MAX_POINTS)?;
    if let Some(f) = header.elements.get("face") {
        too_many("faces", f.count, MAX_FACES)?;
    }
    let mut raw = Raw::default();
    for (name, def) in &header.elements {
        match name.as_str() {
            "vertex" => {
                let vs = Parser::<Vertex>::new()
                    .read_payload_for_element(&mut reader, def, &header)
                    .map_err(ply)?;
                raw.vertices = vs.iter().map(|v| v.0.map(|c| c as f32)).collect();
            }
            "face" => {
                let fs = Parser::<Face>::new()
                    .read_payload_for_element(&mut reader, def, &header)
                    .map_err(ply)?;
                raw.triangles = fan(&fs, vdef.count)?;
            }
            _ => {
                Parser::<Skip>::new()
                    .read_payload_for_element(&mut reader, def, &header)
                    .map_err(ply)?;
            }
        }
    }
    check_points(&raw)?;
    Ok(raw)
}

fn too_many(what: &'static str, count: usize, max: usize) -> Result<(), ScanError> {
    if count > max {
        return Err(ScanError::TooMany {
            what,
            count: count as u64,
            max,
        });
    }
    Ok(())
}

/// Faces fanned into triangles from their first corner; each index checked
/// against the `n` vertices. A face of fewer than three corners adds none.
fn fan(faces: &[Face], n: usize) -> Result<Vec<[u32; 3]>, ScanError> {
    let mut out = Vec::with_capacity(faces.len());
    for (k, f) in faces.iter().enumerate() {
        if let Some(&index) = f.0.iter().find(|&&i| i < 0 || i as u64 >= n as u64) {
            return Err(ScanError::BadIndex { face: k, index });
        }
        for j in 1..f.0.len().saturating_sub(1) {
            out.push([f.0[0] as u32, f.0[j] as u32, f.0[j + 1] as u32]);
        }
        too_many("faces", out.len(), MAX_FACES)?;
    }
    Ok(out)
}

/// The reader's message, first line only (it adds a context block).
fn first_line(s: &str) -> String {
    s.lines().next().unwrap_or(s).trim().to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    const ASCII: &[u8] = b"ply\nformat ascii 1.0\ncomment a worn pad\nelement vertex 4\n\
property float x\nproperty float y\nproperty float z\nproperty uchar red\n\
element face 1\nproperty list uchar int vertex_indices\nend_header\n\
0 0 1 255\n10 0 1.5 0\n10 10 2 0\n0 10 1.25 0\n4 0 1 2 3\n";

    #[test]
    fn ascii_points_and_a_quad() {
        let raw = read(ASCII).unwrap();
        assert_eq!(raw.vertices[2], [10.0, 10.0, 2.0]);
        assert_eq!(raw.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    }

    fn binary(big: bool) -> Vec<u8> {
        let fmt = if big {
            "binary_big_endian"
        } else {
            "binary_little_endian"
        };
        let mut b = format!(
            "ply\nformat {fmt} 1.0\nelement vertex 3\nproperty double x\n\
property double y\nproperty double z\nend_header\n"
        )
        .into_bytes();
        for v in [[1.0f64, 2.0, 3.0], [4.0, 5.0, 6.0], [-1.0, 0.5, 0.25]] {
            for c in v {
                b.extend(if big {
                    c.to_be_bytes()
                } else {
                    c.to_le_bytes()
                });
            }
        }
        b
    }

    #[test]
    fn binary_points_either_byte_order() {
        for big in [false, true] {
            let raw = read(&binary(big)).unwrap();
            assert_eq!(
                raw.vertices,
                vec![[1.0, 2.0, 3.0], [4.0, 5.0, 6.0], [-1.0, 0.5, 0.25]]
            );
            assert!(raw.triangles.is_empty());
        }
    }

    /// A binary mesh as scanner software writes one: float vertices, a
    /// uchar-counted list of int indices per face (a quad and a
    /// triangle), little-endian and big-endian.
    #[test]
    fn binary_faces_either_byte_order() {
        for big in [false, true] {
            let fmt = if big {
                "binary_big_endian"
            } else {
                "binary_little_endian"
            };
            let mut b = format!(
                "ply\nformat {fmt} 1.0\nelement vertex 5\nproperty float x\n\
property float y\nproperty float z\nelement face 2\n\
property list uchar int vertex_indices\nend_header\n"
            )
            .into_bytes();
            let f32s = |v: f32| {
                if big {
                    v.to_be_bytes()
                } else {
                    v.to_le_bytes()
                }
            };
            let i32s = |v: i32| {
                if big {
                    v.to_be_bytes()
                } else {
                    v.to_le_bytes()
                }
            };
            for v in [
                [0.0f32, 0.0, 1.0],
                [10.0, 0.0, 1.5],
                [10.0, 10.0, 2.0],
                [0.0, 10.0, 1.25],
                [5.0, 15.0, 1.0],
            ] {
                v.iter().for_each(|&c| b.extend(f32s(c)));
            }
            for face in [&[0, 1, 2, 3][..], &[3, 2, 4]] {
                b.push(face.len() as u8);
                face.iter().for_each(|&i| b.extend(i32s(i)));
            }
            let raw = read(&b).unwrap();
            assert_eq!(raw.vertices.len(), 5);
            assert_eq!(raw.vertices[4], [5.0, 15.0, 1.0]);
            assert_eq!(raw.triangles, vec![[0, 1, 2], [0, 2, 3], [3, 2, 4]]);
            // Cut short in the faces: an error, not a panic.
            assert!(read(&b[..b.len() - 3]).is_err());
        }
    }

    #[test]
    fn malformed_files_are_errors_not_panics() {
        // Truncated body.
        let b = binary(false);
        assert!(matches!(read(&b[..b.len() - 5]), Err(ScanError::Ply(_))));
        // No z.
        let no_z = b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n1 2\n";
        assert_eq!(read(no_z), Err(ScanError::NoVertices));
        // A face past the vertices.
        let bad = b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n\
0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n";
        assert_eq!(read(bad), Err(ScanError::BadIndex { face: 0, index: 7 }));
        // A header that claims more points than lmdc reads: refused before the body.
        let huge = b"ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\n\
property float x\nproperty float y\nproperty float z\nend_header\n";
        assert!(matches!(read(huge), Err(ScanError::TooMany { .. })));
        // Not a PLY at all, and an empty one.
        assert!(matches!(read(b"ply\nnonsense\n"), Err(ScanError::Ply(_))));
        let empty = b"ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
        assert_eq!(read(empty), Err(ScanError::Empty));
        let nan = b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\nnan 0 0\n";
        assert!(read(nan).is_err());
    }
}
