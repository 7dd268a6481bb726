//! Check KRL files with a third-party KUKA KRL parser (std only).
//!
//! The parser we use is grammars-v4's ANTLR grammar `kuka/krl.g4` behind a
//! `krl-parse` wrapper (docs/krl.md). Use it from an integration test with
//! `#[path = "support/krl_parser.rs"] mod krl_parser;`.
//!
//! `krl-parse FILE...` exits 0 when every file parses, 1 when one does not,
//! printing each error on stderr as `FILE:LINE:COL: MESSAGE` (ANTLR's wording,
//! e.g. `missing '}' at 'C_DIS'`), 2 on usage or I/O errors. A `.src` file must
//! hold DEF/DEFFCT routines, a `.dat` file a DEFDAT module.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicU64, Ordering};

/// The `krl-parse` wrapper: `$LMDC_KRL_PARSER` if set (not checked for
/// existence, so a wrong setting fails loudly), else the install script's
/// location `${XDG_CACHE_HOME:-$HOME/.cache}/lmdc-krl/bin/krl-parse`
/// if it exists, else `None`.
pub fn find_krl_parser() -> Option<PathBuf> {
    if let Some(p) = std::env::var_os("LMDC_KRL_PARSER") {
        if !p.is_empty() {
            return Some(PathBuf::from(p));
        }
    }
    let cache = match std::env::var_os("XDG_CACHE_HOME") {
        Some(x) if Path::new(&x).is_absolute() => PathBuf::from(x),
        _ => PathBuf::from(std::env::var_os("HOME")?).join(".cache"),
    };
    let wrapper = cache.join("lmdc-krl").join("bin").join("krl-parse");
    if wrapper.is_file() {
        Some(wrapper)
    } else {
        None
    }
}

/// Whether a file name is one the parser reads: `.src`, `.dat` or `.sub`,
/// in any case.
pub fn is_krl_file(name: &str) -> bool {
    let lower = name.to_ascii_lowercase();
    lower.ends_with(".src") || lower.ends_with(".dat") || lower.ends_with(".sub")
}

/// Parses `files` in one run of the parser. `Err` holds the parser's error
/// lines, each followed by the offending source line, prefixed by the exit
/// status.
pub fn parse_files(files: &[PathBuf]) -> Result<(), String> {
    if files.is_empty() {
        return Ok(());
    }
    let wrapper = find_krl_parser()
        .ok_or_else(|| "no KRL parser: set LMDC_KRL_PARSER (docs/krl.md)".to_string())?;
    let out = Command::new(&wrapper)
        .args(files)
        .stdin(Stdio::null())
        .output()
        .map_err(|e| format!("cannot run {}: {e}", wrapper.display()))?;
    if out.status.success() {
        return Ok(());
    }
    let status = match out.status.code() {
        Some(c) => format!("exit status {c}"),
        None => "killed by a signal".to_string(),
    };
    let stderr = String::from_utf8_lossy(&out.stderr);
    Err(format!(
        "KRL parser failed ({status}):\n{}",
        with_source_lines(&stderr)
    ))
}

/// Appends to every `FILE:LINE:COL: MESSAGE` line the text of that line of FILE.
fn with_source_lines(errors: &str) -> String {
    let mut out = String::new();
    for l in errors.lines() {
        out.push_str(l);
        out.push('\n');
        let mut parts = l.splitn(3, ':');
        let (Some(file), Some(line)) = (parts.next(), parts.next()) else {
            continue;
        };
        let Ok(n) = line.parse::<usize>() else {
            continue;
        };
        if let Ok(bytes) = std::fs::read(file) {
            let text = String::from_utf8_lossy(&bytes);
            if let Some(src) = text.lines().nth(n.saturating_sub(1)) {
                out.push_str(&format!("    | {src}\n"));
            }
        }
    }
    out
}

/// A directory under the system's temporary directory, removed on drop.
pub struct TempDir(PathBuf);

impl TempDir {
    pub fn new(tag: &str) -> TempDir {
        static COUNTER: AtomicU64 = AtomicU64::new(0);
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let nanos = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map(|d| d.subsec_nanos())
            .unwrap_or(0);
        let dir =
            std::env::temp_dir().join(format!("lmdc-krl-{tag}-{}-{n}-{nanos}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("create {}: {e}", dir.display()));
        TempDir(dir)
    }

    pub fn path(&self) -> &Path {
        &self.0
    }

    /// Writes `contents` to the file `name` in this directory (only the last
    /// component of `name` is used) and returns its path.
    pub fn write(&self, name: &str, contents: &[u8]) -> PathBuf {
        let base = Path::new(name)
            .file_name()
            .unwrap_or_else(|| panic!("not a file name: {name:?}"));
        let path = self.0.join(base);
        std::fs::write(&path, contents).unwrap_or_else(|e| panic!("write {}: {e}", path.display()));
        path
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Parses KRL given as text: each `(file name, contents)` is written to a
/// fresh temporary directory and all are parsed in one run.
pub fn parse_sources(files: &[(&str, &str)]) -> Result<(), String> {
    let dir = TempDir::new("src");
    let paths: Vec<PathBuf> = files
        .iter()
        .map(|(name, text)| dir.write(name, text.as_bytes()))
        .collect();
    parse_files(&paths)
}
