//! The examples as test inputs: an example file with some of its text
//! replaced, each replacement checked to apply (so a test never silently
//! compiles the unedited file).
#![allow(dead_code)]

/// `examples/<name>` with each `(from, to)` of `edits` replaced once.
pub fn edited(name: &str, edits: &[(&str, &str)]) -> String {
    let mut src = std::fs::read_to_string(format!("examples/{name}")).unwrap();
    for (from, to) in edits {
        assert!(src.contains(from), "{name} has no `{from}`");
        src = src.replacen(from, to, 1);
    }
    src
}

/// The seed 000 duct, edited.
pub fn duct(edits: &[(&str, &str)]) -> String {
    edited("twisted_duct.lmd", edits)
}

/// The seed 001 sprocket tooth, edited.
pub fn tooth(edits: &[(&str, &str)]) -> String {
    edited("sprocket_tooth.lmd", edits)
}
