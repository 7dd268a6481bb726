//! Expected files, compared with what lmdc produces and rewritten on request:
//! the machinery of `tests/cases/` (tests/cases.rs) and of the one-line
//! diagnostic tests (tests/codes.rs). `LMDC_BLESS=1` rewrites every expected
//! file that differs (and removes the ones no longer produced) instead of
//! failing; a mismatch otherwise fails with a diff that names the file.

use similar::TextDiff;
use std::collections::BTreeMap;
use std::fs;
use std::path::Path;

/// Whether this run rewrites expected files (`LMDC_BLESS` set, not empty,
/// not `0`).
pub fn blessing() -> bool {
    std::env::var("LMDC_BLESS").is_ok_and(|v| !v.is_empty() && v != "0")
}

/// At most this many lines of diff are shown for one file.
const MAX_DIFF_LINES: usize = 60;

/// What differs between `expected` and `actual` (the bytes of the file
/// `name`), as a unified diff of at most [`MAX_DIFF_LINES`] lines.
pub fn diff(name: &str, expected: &[u8], actual: &[u8]) -> String {
    let (Ok(e), Ok(a)) = (std::str::from_utf8(expected), std::str::from_utf8(actual)) else {
        return format!(
            "{name}: binary contents differ ({} bytes expected, {} produced)\n",
            expected.len(),
            actual.len()
        );
    };
    let d = TextDiff::from_lines(e, a);
    let text = d
        .unified_diff()
        .context_radius(3)
        .header(&format!("{name} (expected)"), &format!("{name} (produced)"))
        .to_string();
    let lines: Vec<&str> = text.lines().collect();
    let count = |tag| d.iter_all_changes().filter(|c| c.tag() == tag).count();
    let (removed, added) = (
        count(similar::ChangeTag::Delete),
        count(similar::ChangeTag::Insert),
    );
    let mut out = format!("{name}: differs (-{removed} +{added} lines)\n");
    for l in lines.iter().take(MAX_DIFF_LINES) {
        out.push_str(l);
        out.push('\n');
    }
    if lines.len() > MAX_DIFF_LINES {
        out.push_str(&format!(
            "… and {} more lines of diff\n",
            lines.len() - MAX_DIFF_LINES
        ));
    }
    out
}

/// Compares the file `path` with `produced`. Returns what is wrong, or
/// nothing; when blessing, writes the file instead.
pub fn check_file(path: &Path, produced: &[u8]) -> Option<String> {
    let shown = path.display().to_string();
    match fs::read(path) {
        Ok(bytes) if bytes == produced => None,
        _ if blessing() => {
            if let Some(dir) = path.parent() {
                fs::create_dir_all(dir).unwrap();
            }
            fs::write(path, produced).unwrap_or_else(|e| panic!("writing {shown}: {e}"));
            None
        }
        Ok(bytes) => Some(diff(&shown, &bytes, produced)),
        Err(_) => Some(format!(
            "{shown}: missing; lmdc produces {} bytes:\n{}",
            produced.len(),
            preview(produced)
        )),
    }
}

/// Compares the files of `dir` with `produced` (name → bytes): each produced
/// file must be there with the same bytes, and every other file of `dir`
/// (except the ones `keep` names) is a stale expectation. Returns one entry
/// per problem; when blessing, rewrites and removes instead.
pub fn check_dir(
    dir: &Path,
    produced: &BTreeMap<String, Vec<u8>>,
    keep: impl Fn(&str) -> bool,
) -> Vec<String> {
    let mut problems: Vec<String> = produced
        .iter()
        .filter_map(|(name, bytes)| check_file(&dir.join(name), bytes))
        .collect();
    let mut present: Vec<String> = fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    present.sort();
    for name in present {
        if keep(&name) || produced.contains_key(&name) {
            continue;
        }
        let path = dir.join(&name);
        if blessing() {
            fs::remove_file(&path).unwrap_or_else(|e| panic!("removing {}: {e}", path.display()));
        } else {
            problems.push(format!(
                "{}: expected, but lmdc no longer produces it",
                path.display()
            ));
        }
    }
    problems
}

/// The first lines of a produced file, for a missing expectation.
fn preview(bytes: &[u8]) -> String {
    let text = String::from_utf8_lossy(bytes);
    let lines: Vec<&str> = text.lines().collect();
    let mut out: String = lines
        .iter()
        .take(20)
        .map(|l| format!("  | {l}\n"))
        .collect();
    if lines.len() > 20 {
        out.push_str(&format!("  | … {} more lines\n", lines.len() - 20));
    }
    out
}

/// How a failed comparison ends: the problems, and how to accept them.
pub fn fail(what: &str, problems: &[String]) -> ! {
    panic!(
        "{what}:\n\n{}\nIf every change is intended, rewrite the expected files with \
         LMDC_BLESS=1 (tests/cases/README.md) and review the diff.",
        problems.join("\n")
    )
}
