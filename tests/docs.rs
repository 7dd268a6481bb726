//! The documentation keeps up with the code: every diagnostic code the compiler
//! can emit is listed in docs/diagnostics.md, and every listed code exists.

use std::collections::BTreeSet;

fn codes_in(text: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    let mut rest = text;
    while let Some(i) = rest.find("lmd::") {
        let tail = &rest[i + 5..];
        let end = tail
            .find(|c: char| !(c.is_ascii_lowercase() || c == '-'))
            .unwrap_or(tail.len());
        if end > 0 {
            out.insert(format!("lmd::{}", &tail[..end]));
        }
        rest = &tail[end..];
    }
    out
}

fn source_codes(dir: &std::path::Path, out: &mut BTreeSet<String>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            source_codes(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            let text = std::fs::read_to_string(&p).unwrap();
            // Only codes in string literals: `"lmd::…"`.
            for c in codes_in(&text) {
                if text.contains(&format!("\"{c}\"")) {
                    out.insert(c);
                }
            }
        }
    }
}

#[test]
fn every_diagnostic_code_is_documented() {
    let mut used = BTreeSet::new();
    source_codes(std::path::Path::new("src"), &mut used);
    let documented = codes_in(&std::fs::read_to_string("docs/diagnostics.md").unwrap());
    let missing: Vec<_> = used.difference(&documented).collect();
    assert!(
        missing.is_empty(),
        "not in docs/diagnostics.md: {missing:?}"
    );
    let stale: Vec<_> = documented.difference(&used).collect();
    assert!(stale.is_empty(), "documented but never emitted: {stale:?}");
}
