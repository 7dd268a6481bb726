//! Run emitted G-code through LinuxCNC's standalone interpreter `rs274` and
//! parse its canonical-command output (std only).
//!
//! Install the interpreter with `bash .ci/install-rs274.sh` (it prints the
//! path of the `rs274-run` wrapper). Use it from an integration test with
//! `#[path = "support/rs274.rs"] mod rs274;`.
//!
//! What rs274 prints (LinuxCNC 2.9, Debian 12 `linuxcnc-uspace`), one call a
//! line on stdout, e.g. `   14 N..... STRAIGHT_FEED(10.1235, 5.0000, 3.0000, 45.0000, 0.0000, 90.0000)`:
//! a running count, the block's N word (`N.....` when the block has none),
//! then the call. Positions are X Y Z A B C only (U V W words are rejected),
//! in the program's current length units (G21: mm, G20: inch, see
//! [`CanonCall::LengthUnits`]), angles in degrees, feeds in units per minute
//! (G94), all rounded to 4 decimals. Analog output values have 6 decimals.
//! On an error rs274 exits with status 1 and prints the message and the
//! offending block on stderr (after a line `executing` it always prints).
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::{AtomicU64, Ordering};

/// One canonical machining call printed by rs274.
#[derive(Debug, Clone, PartialEq)]
pub enum CanonCall {
    /// `STRAIGHT_TRAVERSE(x, y, z, a, b, c)`: G0.
    Traverse {
        x: f64,
        y: f64,
        z: f64,
        a: f64,
        b: f64,
        c: f64,
    },
    /// `STRAIGHT_FEED(x, y, z, a, b, c)`: G1.
    Feed {
        x: f64,
        y: f64,
        z: f64,
        a: f64,
        b: f64,
        c: f64,
    },
    /// `SET_FEED_RATE(f)`: units per minute under G94 (under G93 the inverse
    /// time number). rs274 also prints `SET_FEED_RATE(0.0000)` at start-up,
    /// on G94/G93 and at program end.
    FeedRate(f64),
    /// `SET_SPINDLE_SPEED(spindle, s)`: the S word.
    SpindleSpeed(f64),
    /// `START_SPINDLE_CLOCKWISE(spindle)`: M3.
    SpindleOn,
    /// `START_SPINDLE_COUNTERCLOCKWISE(spindle)`: M4.
    SpindleOnCcw,
    /// `STOP_SPINDLE_TURNING(spindle)`: M5, and also M2/M30 (program end).
    SpindleOff,
    /// M62/M63 (`SET_/CLEAR_MOTION_OUTPUT_BIT(i)`, `synced: true`) and
    /// M64/M65 (`SET_/CLEAR_AUX_OUTPUT_BIT(i)`, `synced: false`).
    DigitalOut { index: u32, on: bool, synced: bool },
    /// M67 (`SET_MOTION_OUTPUT_VALUE(i,v)`, `synced: true`) and
    /// M68 (`SET_AUX_OUTPUT_VALUE(i,v)`, `synced: false`).
    AnalogOut {
        index: u32,
        value: f64,
        synced: bool,
    },
    /// `DWELL(seconds)`: G4 P.
    Dwell(f64),
    /// `COMMENT("...")`: a `( ... )` comment, text as written (case kept,
    /// leading/trailing spaces kept). The interpreter adds its own comments
    /// starting with `interpreter: ` (see [`is_interpreter_comment`]).
    /// `;` comments produce nothing.
    Comment(String),
    /// `MESSAGE("...")`: `(MSG,...)` and `(DEBUG,...)` comments, text after
    /// the comma as written (usually with a leading space).
    Message(String),
    /// `USE_LENGTH_UNITS(CANON_UNITS_MM|CANON_UNITS_INCHES|CANON_UNITS_CM)`:
    /// `"mm"`, `"inch"` or `"cm"`. Printed at start-up (mm) and on G20/G21.
    LengthUnits(String),
    /// `PROGRAM_END()`: M2 or M30.
    ProgramEnd,
    /// Anything else: the call as printed without the count and N word, e.g.
    /// `ARC_FEED(2.0000, 0.0000, 1.0000, 0.0000, -1, 0.0000, 0.0000, 0.0000, 0.0000)`,
    /// `FLOOD_ON()`, `PROGRAM_STOP()`, `FINISH()` (a `%`-terminated file), or
    /// a raw stdout line that is not a call (e.g. `(PRINT,...)` output).
    Other(String),
}

/// `true` if rs274 is there; `false` (the test `test` skipped) if not,
/// outside CI: under CI a missing rs274 fails the test.
pub fn available(test: &str) -> bool {
    if find_rs274().is_some() {
        return true;
    }
    super::skip::skip(
        test,
        "LinuxCNC's rs274",
        "run `bash .ci/install-rs274.sh` and export LMDC_RS274=<the path it prints>",
    );
    false
}

/// The `rs274-run` wrapper: `$LMDC_RS274` if set (not checked for existence,
/// so a wrong setting fails loudly), else the install script's default
/// location `${XDG_CACHE_HOME:-$HOME/.cache}/lmdc-rs274/bin/rs274-run` if it
/// exists, else `None`.
pub fn find_rs274() -> Option<PathBuf> {
    if let Some(p) = std::env::var_os("LMDC_RS274") {
        if !p.is_empty() {
            return Some(PathBuf::from(p));
        }
    }
    let cache = match std::env::var_os("XDG_CACHE_HOME") {
        Some(x) if Path::new(&x).is_absolute() => PathBuf::from(x),
        _ => PathBuf::from(std::env::var_os("HOME")?).join(".cache"),
    };
    let wrapper = cache.join("lmdc-rs274").join("bin").join("rs274-run");
    if wrapper.is_file() {
        Some(wrapper)
    } else {
        None
    }
}

/// Run rs274 on `ngc` and return its raw stdout. `Err` holds the
/// interpreter's error text (stderr without the `executing` line), prefixed
/// by the exit status, when rs274 exits non-zero.
pub fn run_raw(ngc: &Path) -> Result<String, String> {
    let wrapper = find_rs274().ok_or_else(|| {
        "rs274 not installed: run `bash .ci/install-rs274.sh` or set LMDC_RS274".to_string()
    })?;
    let out = Command::new(&wrapper)
        .arg(ngc)
        .stdin(std::process::Stdio::null())
        .output()
        .map_err(|e| format!("cannot run {}: {e}", wrapper.display()))?;
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    if out.status.success() {
        return Ok(stdout);
    }
    let stderr = String::from_utf8_lossy(&out.stderr);
    let msg: Vec<&str> = stderr
        .lines()
        .filter(|l| l.trim() != "executing" && !l.trim().is_empty())
        .collect();
    let status = match out.status.code() {
        Some(c) => format!("exit status {c}"),
        None => "killed by a signal".to_string(),
    };
    Err(format!("rs274 failed ({status}): {}", msg.join("\n")))
}

/// Run rs274 on `ngc` and parse every canonical call it printed, start-up
/// and end-of-program calls included (see [`program_body`]).
pub fn interpret(ngc: &Path) -> Result<Vec<CanonCall>, String> {
    parse_canon(&run_raw(ngc)?)
}

/// [`interpret`] G-code given as text (written to a temporary file).
pub fn interpret_source(source: &str) -> Result<Vec<CanonCall>, String> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.subsec_nanos())
        .unwrap_or(0);
    let path =
        std::env::temp_dir().join(format!("lmdc-rs274-{}-{n}-{nanos}.ngc", std::process::id()));
    std::fs::write(&path, source).map_err(|e| format!("write {}: {e}", path.display()))?;
    let result = interpret(&path);
    let _ = std::fs::remove_file(&path);
    result
}

/// The calls made by the program itself: drops the interpreter's fixed
/// start-up sequence (up to and including the first `ON_RESET()`) and
/// everything from `PROGRAM_END()` on. The resets M2 itself makes before
/// `PROGRAM_END()` stay (`SET_FEED_RATE(0)`, `SpindleOff`, `Other`s).
pub fn program_body(calls: &[CanonCall]) -> &[CanonCall] {
    let start = calls
        .iter()
        .position(|c| matches!(c, CanonCall::Other(s) if s == "ON_RESET()"))
        .map_or(0, |i| i + 1);
    let end = calls[start..]
        .iter()
        .position(|c| *c == CanonCall::ProgramEnd)
        .map_or(calls.len(), |i| start + i);
    &calls[start..end]
}

/// A comment rs274 itself adds, e.g. `interpreter: feed mode set to units per minute`.
pub fn is_interpreter_comment(call: &CanonCall) -> bool {
    matches!(call, CanonCall::Comment(s) if s.starts_with("interpreter: "))
}

/// Parse rs274's stdout. Lines that are not `COUNT N... CALL(...)` become
/// `Other(line)`; a known call with malformed arguments is an `Err`.
pub fn parse_canon(stdout: &str) -> Result<Vec<CanonCall>, String> {
    let mut calls = Vec::new();
    for line in stdout.lines() {
        if line.trim().is_empty() {
            continue;
        }
        let call = match strip_prefix(line) {
            Some(call) => parse_call(call).map_err(|e| format!("{e} in rs274 line {line:?}"))?,
            None => CanonCall::Other(line.trim().to_string()),
        };
        calls.push(call);
    }
    Ok(calls)
}

/// `"   14 N..... CALL(...)"` -> `"CALL(...)"`.
fn strip_prefix(line: &str) -> Option<&str> {
    let rest = line.trim_start();
    let digits = rest.find(|c: char| !c.is_ascii_digit())?;
    if digits == 0 {
        return None;
    }
    let rest = rest[digits..].strip_prefix(' ')?.trim_start();
    if !rest.starts_with('N') {
        return None;
    }
    let end = rest.find(' ')?;
    let call = rest[end..].trim();
    if call.ends_with(')') && call.contains('(') {
        Some(call)
    } else {
        None
    }
}

fn parse_call(call: &str) -> Result<CanonCall, String> {
    let open = call.find('(').ok_or("no '('")?;
    let name = &call[..open];
    let args = &call[open + 1..call.len() - 1];
    let nums = || -> Result<Vec<f64>, String> {
        args.split(',')
            .map(|a| {
                let a = a.trim();
                a.parse::<f64>().map_err(|_| format!("bad number {a:?}"))
            })
            .collect()
    };
    let want = |n: usize| -> Result<Vec<f64>, String> {
        let v = nums()?;
        if v.len() == n {
            Ok(v)
        } else {
            Err(format!("{name} wants {n} arguments, got {}", v.len()))
        }
    };
    let index = |v: f64| -> Result<u32, String> {
        if v >= 0.0 && v.fract() == 0.0 {
            Ok(v as u32)
        } else {
            Err(format!("bad index {v}"))
        }
    };
    let quoted = || -> Result<String, String> {
        args.strip_prefix('"')
            .and_then(|s| s.strip_suffix('"'))
            .map(str::to_string)
            .ok_or_else(|| format!("{name}: unquoted text"))
    };
    Ok(match name {
        "STRAIGHT_TRAVERSE" | "STRAIGHT_FEED" => {
            let v = want(6)?;
            let (x, y, z, a, b, c) = (v[0], v[1], v[2], v[3], v[4], v[5]);
            if name == "STRAIGHT_TRAVERSE" {
                CanonCall::Traverse { x, y, z, a, b, c }
            } else {
                CanonCall::Feed { x, y, z, a, b, c }
            }
        }
        "SET_FEED_RATE" => CanonCall::FeedRate(want(1)?[0]),
        "SET_SPINDLE_SPEED" => CanonCall::SpindleSpeed(want(2)?[1]),
        "START_SPINDLE_CLOCKWISE" => CanonCall::SpindleOn,
        "START_SPINDLE_COUNTERCLOCKWISE" => CanonCall::SpindleOnCcw,
        "STOP_SPINDLE_TURNING" => CanonCall::SpindleOff,
        "SET_MOTION_OUTPUT_BIT"
        | "CLEAR_MOTION_OUTPUT_BIT"
        | "SET_AUX_OUTPUT_BIT"
        | "CLEAR_AUX_OUTPUT_BIT" => CanonCall::DigitalOut {
            index: index(want(1)?[0])?,
            on: name.starts_with("SET_"),
            synced: name.contains("MOTION"),
        },
        "SET_MOTION_OUTPUT_VALUE" | "SET_AUX_OUTPUT_VALUE" => {
            let v = want(2)?;
            CanonCall::AnalogOut {
                index: index(v[0])?,
                value: v[1],
                synced: name == "SET_MOTION_OUTPUT_VALUE",
            }
        }
        "DWELL" => CanonCall::Dwell(want(1)?[0]),
        "COMMENT" => CanonCall::Comment(quoted()?),
        "MESSAGE" => CanonCall::Message(quoted()?),
        "USE_LENGTH_UNITS" => CanonCall::LengthUnits(
            match args.trim() {
                "CANON_UNITS_MM" => "mm",
                "CANON_UNITS_INCHES" => "inch",
                "CANON_UNITS_CM" => "cm",
                other => return Err(format!("unknown length units {other:?}")),
            }
            .to_string(),
        ),
        "PROGRAM_END" => CanonCall::ProgramEnd,
        _ => CanonCall::Other(call.to_string()),
    })
}
