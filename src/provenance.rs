//! Where a program came from: the source file as the command line named it,
//! the sha256 of its bytes, the constants `--set` changed and the lmdc
//! version. Every program's header says it, so a file found on a controller
//! can be traced to the exact `.lmd` text and compiler that wrote it.

use sha2::{Digest, Sha256};

/// This lmdc's version, as the headers and `lmdc --version` print it.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The source of one compilation.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Provenance {
    /// The file as given on the command line (empty: compiled from text
    /// that came from no named file).
    pub file: String,
    /// The sha256 of the source's bytes, 64 lowercase hex digits.
    pub sha256: String,
    /// The constants `--set` replaced, as `NAME = VALUE`, in the order given.
    pub set: Vec<String>,
}

impl Provenance {
    /// The provenance of `source`, read from `file` (`None`: no file).
    pub fn new(source: &str, file: Option<&str>) -> Self {
        Provenance {
            file: file.unwrap_or_default().to_string(),
            sha256: sha256_hex(source.as_bytes()),
            set: Vec::new(),
        }
    }

    /// The file's name as a header shows it: `(no file)` when it has none.
    pub fn shown_file(&self) -> &str {
        if self.file.is_empty() {
            "(no file)"
        } else {
            &self.file
        }
    }
}

/// The sha256 of `bytes` in lowercase hex.
pub fn sha256_hex(bytes: &[u8]) -> String {
    use std::fmt::Write;
    let digest = Sha256::digest(bytes);
    let mut out = String::with_capacity(64);
    for b in digest.iter() {
        // Writing into a String cannot fail.
        let _ = write!(out, "{b:02x}");
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sha256_of_known_texts() {
        // FIPS 180-2's examples.
        assert_eq!(
            sha256_hex(b"abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
        assert_eq!(
            sha256_hex(b""),
            "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855"
        );
    }
}
