//! How much of a data file lmdc reads: a measurement sheet
//! (`fit(…, data = "…")`, and `lmdc fit`) at most [`MAX_SHEET`] bytes, a
//! mesh at most [`MAX_MESH`] — and a binary STL no more than its header
//! counts. The read itself stops one byte past the cap, whatever the file
//! claims to be: metadata says nothing about `/dev/zero`, a pipe or a
//! file still growing. The checker opens no file: the caller's
//! [`super::DataReader`] does (the command line's and the language
//! server's with [`read_file`]), and the checker holds what any reader
//! returns to the same caps.

use crate::geometry::mesh::stl::MAX_TRIANGLES;
use std::io::Read;

/// Most bytes of a `.lmd` source, from a file, a pipe or an editor.
pub const MAX_SOURCE: u64 = 16 << 20;

/// Most bytes of a measurement sheet, for `fit(…)` and `lmdc fit` alike:
/// tens of thousands of coupons' rows.
pub const MAX_SHEET: u64 = 16 << 20;

/// Most bytes of a mesh file: a binary STL of the most triangles lmdc
/// reads ([`MAX_TRIANGLES`], 50 bytes each) is just under it.
pub const MAX_MESH: u64 = 1 << 30;

/// What a data file is read as: its kind decides how much of it is read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Data {
    /// A measurement sheet (CSV text).
    Sheet,
    /// A mesh: an STL (binary or ASCII) or a 3MF.
    Mesh,
    /// A scan to build on: PLY, XYZ text, STL or 3MF (capped as a mesh).
    Scan,
}

impl Data {
    /// The most bytes a file of this kind may have.
    pub fn cap(self) -> u64 {
        match self {
            Data::Sheet => MAX_SHEET,
            Data::Mesh | Data::Scan => MAX_MESH,
        }
    }

    /// Why `bytes` (all of a file, from any reader) are too many, if they
    /// are.
    pub fn too_long(self, bytes: &[u8]) -> Option<String> {
        (bytes.len() as u64 > self.cap()).then(|| larger_than(self.cap()))
    }
}

/// The reason given for a file past `cap` bytes.
fn larger_than(cap: u64) -> String {
    format!("it is larger than {} MB", cap >> 20)
}

/// Bytes of a binary STL's header and triangle count.
const STL_HEAD: usize = 84;

/// Reads a data file of kind `kind` from `r`, at most its cap: the
/// bytes, or why they are not read. A mesh whose first bytes can only be
/// a binary STL's header (no `solid` of an ASCII STL, no ZIP of a 3MF) is
/// read to the length its count gives and not a byte further: `/dev/zero`
/// as a mesh is 85 bytes read, not a gigabyte.
pub fn read_capped(r: impl Read, kind: Data) -> Result<Vec<u8>, String> {
    let mut r = r.take(kind.cap() + 1);
    let mut bytes = Vec::new();
    if kind == Data::Mesh {
        // A scan is not held to an STL's count: a PLY or XYZ text may start
        // with anything a binary STL header could.
        (&mut r)
            .take(STL_HEAD as u64)
            .read_to_end(&mut bytes)
            .map_err(|e| e.to_string())?;
        if let Some(count) = binary_stl_count(&bytes) {
            if count > MAX_TRIANGLES as u64 {
                return Err(format!(
                    "its binary STL header counts {count} triangles, more than the {MAX_TRIANGLES} lmdc reads"
                ));
            }
            let expected = STL_HEAD as u64 + 50 * count;
            (&mut r)
                .take(expected + 1 - STL_HEAD as u64)
                .read_to_end(&mut bytes)
                .map_err(|e| e.to_string())?;
            if bytes.len() as u64 > expected {
                return Err(format!(
                    "it goes on past the {expected} bytes its binary STL header counts ({count} triangles), and is no ASCII STL or 3MF: not read further"
                ));
            }
            return Ok(bytes);
        }
    }
    r.read_to_end(&mut bytes).map_err(|e| e.to_string())?;
    match kind.too_long(&bytes) {
        Some(why) => Err(why),
        None => Ok(bytes),
    }
}

/// Opens and reads the data file at `path` as [`read_capped`] does; a
/// folder is refused by name rather than by the system's word for it.
pub fn read_file(path: &std::path::Path, kind: Data) -> Result<Vec<u8>, String> {
    let f = std::fs::File::open(path).map_err(|e| e.to_string())?;
    if f.metadata().is_ok_and(|m| m.is_dir()) {
        return Err("it is a directory".into());
    }
    read_capped(f, kind)
}

/// The triangle count of a binary STL whose first bytes are `head`, when
/// they can only be one: a full header that starts no ASCII STL
/// (`solid`, after blanks) and no ZIP package.
fn binary_stl_count(head: &[u8]) -> Option<u64> {
    if head.len() < STL_HEAD
        || head.trim_ascii_start().starts_with(b"solid")
        || head.starts_with(b"PK\x03\x04")
    {
        return None;
    }
    Some(u64::from(u32::from_le_bytes([
        head[80], head[81], head[82], head[83],
    ])))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An endless stream of zeros: what `/dev/zero` gives.
    struct Zeros;
    impl Read for Zeros {
        fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
            buf.fill(0);
            Ok(buf.len())
        }
    }

    #[test]
    fn an_endless_stream_is_read_to_the_cap_and_no_further() {
        let e = read_capped(Zeros, Data::Sheet).unwrap_err();
        assert_eq!(e, "it is larger than 16 MB");
        // As a mesh, its 84 bytes are a binary STL header of no triangle:
        // one byte more says it is none.
        let e = read_capped(Zeros, Data::Mesh).unwrap_err();
        assert!(e.contains("past the 84 bytes"), "{e}");
    }

    #[test]
    fn a_binary_stl_is_read_to_its_count() {
        let mut stl = vec![7u8; 80];
        stl.extend(2u32.to_le_bytes());
        stl.extend([1u8; 100]);
        assert_eq!(read_capped(&stl[..], Data::Mesh).unwrap(), stl);
        stl.push(0);
        assert!(read_capped(&stl[..], Data::Mesh).is_err());
        // An ASCII STL or a 3MF is read whole.
        let ascii = b"solid x\nendsolid x\n".repeat(10);
        assert_eq!(read_capped(&ascii[..], Data::Mesh).unwrap(), ascii);
        let mut head = vec![0u8; 80];
        head.extend(u32::MAX.to_le_bytes());
        let e = read_capped(&head[..], Data::Mesh).unwrap_err();
        assert!(e.contains("4294967295 triangles"), "{e}");
    }
}
