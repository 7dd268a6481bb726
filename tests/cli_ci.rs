//! What a CI job needs from `lmdc`: `--deny-warnings`, every failure as a
//! JSON object with a code under `--message-format json` (usage and file
//! errors too), `--set NAME=VALUE` for parameter sweeps, and programs whose
//! headers name their source, its sha256 and the lmdc version.

use crate::support::schema;
use crate::support::skip::skip;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn lmdc(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lmdc"))
        .args(args)
        .env("NO_COLOR", "1")
        .output()
        .expect("runs")
}

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("lmdc-ci-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// A plate whose width is a constant, on a CNC and a robot (it compiles
/// without a word).
fn plate(width: &str) -> String {
    include_str!("codes/plate.lmd")
        .replacen(
            "part plate\n",
            &format!("part plate\n\nlet W = {width}\nlet POWER = 1500 W\n"),
            1,
        )
        .replacen("rectangle(width = 20 mm", "rectangle(width = W", 1)
        .replacen("power = 1500 W", "power = POWER", 1)
}

/// Every line of `stdout` as a diagnostic object valid against
/// docs/diagnostics.schema.json.
fn json_lines(o: &Output) -> Vec<Value> {
    let schema: Value =
        serde_json::from_str(&std::fs::read_to_string("docs/diagnostics.schema.json").unwrap())
            .unwrap();
    String::from_utf8(o.stdout.clone())
        .unwrap()
        .lines()
        .map(|l| {
            let v: Value = serde_json::from_str(l).unwrap_or_else(|e| panic!("{e}: {l}"));
            let errors = schema::validate(&schema, &v);
            assert!(errors.is_empty(), "{errors:?}\n{l}");
            v
        })
        .collect()
}

/// Files written into `d`, sorted (the build's bookkeeping left out).
fn written(d: &Path) -> Vec<String> {
    let Ok(rd) = std::fs::read_dir(d) else {
        return Vec::new();
    };
    let mut v: Vec<String> = rd
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| !n.starts_with(".lmdc"))
        .collect();
    v.sort();
    v
}

#[test]
fn usage_and_file_errors_are_json_objects_with_a_code() {
    let d = dir("usage");
    let good = d.join("plate.lmd");
    std::fs::write(&good, plate("20 mm")).unwrap();
    let missing = d.join("missing.lmd");
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["check", s(&missing)], "lmd::unreadable"),
        (vec!["build", s(&d)], "lmd::unreadable"),
        (
            vec!["check", s(&good), "--machine", "nope"],
            "lmd::no-such-machine",
        ),
        (vec!["report", s(&good), "--density=-1"], "lmd::usage"),
        (
            vec!["build", s(&good), "--emit", "everything"],
            "lmd::usage",
        ),
        (vec!["check", s(&good), "--no-such-option"], "lmd::usage"),
        (vec!["check", s(&good), "--set", "W"], "lmd::usage"),
        (vec!["check", s(&good), "--set", "WW=1mm"], "lmd::bad-set"),
        (vec!["simulate", s(&good)], "lmd::usage"),
        (
            vec!["simulate", "examples/segmented_ring.lmd", "--every", "0"],
            "lmd::usage",
        ),
    ];
    for (mut args, code) in cases {
        args.extend(["--message-format", "json"]);
        let o = lmdc(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        let lines = json_lines(&o);
        assert_eq!(lines.len(), 1, "{args:?}: {lines:?}");
        assert_eq!(lines[0]["code"], code, "{args:?}: {lines:?}");
        assert_eq!(lines[0]["severity"], "error");
        assert!(!lines[0]["message"].as_str().unwrap().is_empty());
        assert!(
            o.stderr.is_empty(),
            "{args:?}: nothing for people on stderr: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        // The same mistake without JSON is said to people on stderr.
        args.truncate(args.len() - 2);
        let o = lmdc(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        assert!(o.stdout.is_empty(), "{args:?}");
        assert!(String::from_utf8_lossy(&o.stderr).contains("error"));
    }
    // The unknown machine's object names the machines there are.
    let o = lmdc(&[
        "check",
        s(&good),
        "--machine",
        "nope",
        "--message-format=json",
    ]);
    let m = json_lines(&o)[0]["message"].as_str().unwrap().to_string();
    assert!(m.contains("mill") && m.contains("kr"), "{m}");
}

/// `--allow CODE` and a file's `allow "lmd::CODE" = "why"` expect a
/// warning: reported, marked allowed (JSON's `allowed`), failing no run;
/// `--deny CODE` fails on that code alone. Codes are checked.
#[test]
fn warnings_are_allowed_and_denied_by_code() {
    let d = dir("allow");
    let out = d.join("out");
    let build = |file: &str, flags: &[&str]| {
        let mut args = vec!["build", file, "-o", s(&out), "--message-format", "json"];
        args.extend_from_slice(flags);
        lmdc(&args)
    };
    // flange's only warning is lmd::short-track.
    let o = build(
        "examples/flange.lmd",
        &["--deny-warnings", "--allow", "short-track"],
    );
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let lines = json_lines(&o);
    let w: Vec<&Value> = lines
        .iter()
        .filter(|l| l["severity"] == "warning")
        .collect();
    assert!(!w.is_empty());
    for l in &w {
        assert_eq!(l["code"], "lmd::short-track");
        assert_eq!(l["allowed"], "--allow on the command line");
    }
    assert!(!written(&out).is_empty());
    // --deny fails on its code, not on others.
    std::fs::remove_dir_all(&out).unwrap();
    let o = build("examples/flange.lmd", &["--deny", "lmd::short-track"]);
    assert_eq!(o.status.code(), Some(1));
    let last = json_lines(&o).last().unwrap().clone();
    assert_eq!(last["code"], "lmd::denied-warnings");
    assert!(
        last["message"]
            .as_str()
            .unwrap()
            .contains("--deny lmd::short-track"),
        "{last}"
    );
    assert!(written(&out).is_empty());
    let o = build("examples/flange.lmd", &["--deny", "unused,height-rounded"]);
    assert_eq!(o.status.code(), Some(0));
    // The file expects it, with its reason: --deny-warnings passes, the
    // reason is in every report of it.
    let f = d.join("flange.lmd");
    let src = std::fs::read_to_string("examples/flange.lmd").unwrap();
    let why = "the spokes end in short tracks by design";
    std::fs::write(
        &f,
        format!("{src}\nallow \"lmd::short-track\" = \"{why}\"\n"),
    )
    .unwrap();
    std::fs::remove_dir_all(&out).unwrap();
    let o = build(s(&f), &["--deny-warnings"]);
    assert_eq!(o.status.code(), Some(0));
    assert!(json_lines(&o)
        .iter()
        .filter(|l| l["severity"] == "warning")
        .all(|l| l["allowed"] == why));
    let o = lmdc(&["check", s(&f)]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("allowed warning[lmd::short-track]") && err.contains(why),
        "{err}"
    );
    // Codes are checked: unknown, not a warning, both allowed and denied.
    for flags in [
        &["--allow", "shrt-track"][..],
        &["--allow", "lmd::collision"],
        &["--deny", "nope"],
        &["--allow", "unused", "--deny", "lmd::unused"],
    ] {
        let mut args = vec!["check", "examples/flange.lmd"];
        args.extend_from_slice(flags);
        let o = lmdc(&args);
        assert_eq!(o.status.code(), Some(2), "{flags:?}");
    }
}

#[test]
fn deny_warnings_fails_a_file_with_warnings_and_writes_nothing() {
    let d = dir("deny");
    // flange has a warning (short tracks); the plate none.
    let out = d.join("out");
    let o = lmdc(&[
        "build",
        "examples/flange.lmd",
        "-o",
        s(&out),
        "--deny-warnings",
        "--message-format",
        "json",
    ]);
    assert_eq!(o.status.code(), Some(1));
    let lines = json_lines(&o);
    let warnings = lines.iter().filter(|l| l["severity"] == "warning").count();
    assert!(warnings > 0);
    let last = lines.last().unwrap();
    assert_eq!(last["code"], "lmd::denied-warnings");
    assert!(last["message"]
        .as_str()
        .unwrap()
        .starts_with(&format!("{warnings} warning")));
    assert!(written(&out).is_empty(), "{:?}", written(&out));
    // Without the flag the same build succeeds and writes.
    let o = lmdc(&["build", "examples/flange.lmd", "-o", s(&out), "-q"]);
    assert_eq!(o.status.code(), Some(0));
    assert!(!written(&out).is_empty());
    // A file without warnings passes.
    let good = d.join("plate.lmd");
    std::fs::write(&good, plate("20 mm")).unwrap();
    for cmd in ["check", "report"] {
        let o = lmdc(&[cmd, s(&good), "--deny-warnings"]);
        assert_eq!(o.status.code(), Some(0), "{cmd}");
    }
    for cmd in ["check", "report"] {
        let o = lmdc(&[cmd, "examples/flange.lmd", "--deny-warnings"]);
        assert_eq!(o.status.code(), Some(1), "{cmd}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            err.contains("--deny-warnings") && err.contains("lmd::short-track"),
            "{err}"
        );
    }
}

/// Builds `file` into a fresh directory with `args`; the IR and the G-code.
fn build(name: &str, file: &Path, args: &[&str]) -> (Value, String) {
    let out = dir(name);
    let mut all = vec![
        "build",
        s(file),
        "-o",
        s(&out),
        "--emit",
        "ir",
        "--machine",
        "mill",
    ];
    all.extend(args);
    let o = lmdc(&all);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let ir = serde_json::from_slice(&std::fs::read(out.join("plate.ir.json")).unwrap()).unwrap();
    let gcode = std::fs::read_to_string(out.join("plate_mill.ngc")).unwrap();
    (ir, gcode)
}

/// The G-code without its provenance line (which names the file and what
/// was set).
fn body(gcode: &str) -> String {
    gcode
        .lines()
        .filter(|l| !l.contains("sha256"))
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn set_gives_what_editing_the_file_gives() {
    let d = dir("set");
    let narrow = d.join("narrow.lmd");
    let wide = d.join("wide.lmd");
    std::fs::write(&narrow, plate("20 mm")).unwrap();
    std::fs::write(&wide, plate("30 mm")).unwrap();
    let (edited_ir, edited) = build("set-edited", &wide, &[]);
    let (set_ir, set) = build("set-set", &narrow, &["--set", "W=30 mm"]);
    let (cm_ir, cm) = build("set-cm", &narrow, &["--set", "W = 3 cm"]);
    let (narrow_ir, _) = build("set-narrow", &narrow, &[]);
    assert_eq!(set_ir, edited_ir);
    assert_eq!(cm_ir, edited_ir, "3 cm is 30 mm");
    assert_ne!(narrow_ir, edited_ir, "the value was used");
    assert_eq!(body(&set), body(&edited));
    assert_eq!(body(&cm), body(&edited));
    // The header says what was set.
    let line = set.lines().find(|l| l.contains("sha256")).unwrap();
    assert!(line.contains("set W = 30 mm"), "{line}");
    // Two at once, a power among them: in kW, as the file's in W.
    let (two, _) = build(
        "set-two",
        &narrow,
        &["--set", "W=30mm", "--set", "POWER=1.6 kW"],
    );
    let powers = |ir: &Value| -> Vec<f64> {
        let mut v = Vec::new();
        for l in ir["layers"].as_array().unwrap() {
            for p in l["paths"].as_array().unwrap() {
                for q in p["points"].as_array().unwrap() {
                    v.push(q["power"].as_f64().unwrap());
                }
            }
        }
        v
    };
    assert!(powers(&edited_ir).iter().all(|&p| p == 1500.0));
    assert!(powers(&two).iter().all(|&p| p == 1600.0));
}

#[test]
fn set_checks_units_names_and_values_as_the_file_would() {
    let d = dir("set-bad");
    let f = d.join("plate.lmd");
    std::fs::write(&f, plate("20 mm")).unwrap();
    let bad = [
        ("W=30 deg", "an angle"),
        ("POWER=3 mm", "a length"),
        ("Width=3 mm", "W, POWER"),
        ("WW=3 mm", "did you mean `W`"),
        ("W=3 furlongs", "furlongs"),
        ("W=(3 mm", "not"),
    ];
    for (set, says) in bad {
        let out = d.join("out");
        let o = lmdc(&["build", s(&f), "-o", s(&out), "--set", set]);
        assert_eq!(o.status.code(), Some(2), "{set}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(says), "{set}: {err}");
        assert!(written(&out).is_empty(), "{set}");
    }
    let o = lmdc(&["check", s(&f), "--set", "W=3mm", "--set", "W=4mm"]);
    assert_eq!(o.status.code(), Some(2));
    // A value of the right kind the part cannot take is the file's error,
    // at the `let` it replaced.
    let o = lmdc(&["check", s(&f), "--set", "W=1 mm"]);
    assert_eq!(
        o.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

#[test]
fn headers_name_the_source_its_sha256_and_the_version() {
    let out = dir("headers");
    let o = lmdc(&["build", "examples/flange.lmd", "-o", s(&out), "-q"]);
    assert_eq!(o.status.code(), Some(0));
    let Ok(sum) = Command::new("sha256sum")
        .arg("examples/flange.lmd")
        .output()
    else {
        skip(
            "headers_name_the_source_its_sha256_and_the_version",
            "sha256sum",
            "coreutils",
        );
        return;
    };
    let sum = String::from_utf8(sum.stdout).unwrap();
    let hash = sum.split_whitespace().next().unwrap();
    assert_eq!(hash.len(), 64);
    let version = env!("CARGO_PKG_VERSION");
    let mut programs = 0;
    for name in written(&out) {
        if name.ends_with(".dat") {
            continue;
        }
        programs += 1;
        let text = std::fs::read_to_string(out.join(&name)).unwrap();
        let head: Vec<&str> = text.lines().take(6).collect();
        let line = head
            .iter()
            .find(|l| l.contains("sha256"))
            .unwrap_or_else(|| panic!("{name}: {head:?}"));
        assert!(
            line.contains(&format!("source examples/flange.lmd, sha256 {hash}")),
            "{name}: {line}"
        );
        assert!(
            head.iter().any(|l| l.contains(&format!("lmdc {version}"))),
            "{name}: {head:?}"
        );
    }
    assert!(
        programs >= 3,
        "a G-code program, a KRL main program and its modules"
    );
    // Same input, same bytes: a second build is identical.
    let again = dir("headers-again");
    lmdc(&["build", "examples/flange.lmd", "-o", s(&again), "-q"]);
    for name in written(&out) {
        assert_eq!(
            std::fs::read(out.join(&name)).unwrap(),
            std::fs::read(again.join(&name)).unwrap(),
            "{name}"
        );
    }
}
