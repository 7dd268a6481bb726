//! The `lmdc` command as a user runs it: exit codes, what is written (and that
//! nothing is written on failure), determinism, `--emit ir`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn lmdc(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lmdc"))
        .args(args)
        .env("NO_COLOR", "1")
        .output()
        .expect("runs")
}

fn out_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("lmdc-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn listing(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn help_is_for_process_engineers() {
    let o = lmdc(&["--help"]);
    assert_eq!(o.status.code(), Some(0));
    let text = String::from_utf8_lossy(&o.stdout);
    for want in ["build", "check", "Exit status"] {
        assert!(text.contains(want), "{text}");
    }
    let o = lmdc(&["build", "--help"]);
    let text = String::from_utf8_lossy(&o.stdout);
    for want in ["--machine", "--emit", "--templates", "--timings", "--out"] {
        assert!(text.contains(want), "{text}");
    }
}

#[test]
fn check_reports_success_and_failure() {
    let o = lmdc(&["check", "examples/twisted_duct.lmd"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let o = lmdc(&["check", "examples/errors/bend_too_tight.lmd"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("lmd::bend-too-tight"));
}

/// `check` runs the machines' own checks too (here the CNC's axis limits),
/// so a file `check` passes is one `build` writes.
#[test]
fn check_runs_the_machine_checks() {
    let src = std::fs::read_to_string("examples/sprocket_tooth.lmd")
        .unwrap()
        .replace("x = -50 mm .. 150 mm", "x = -50 mm .. 30 mm");
    let dir = out_dir("check-limits");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("tooth.lmd");
    std::fs::write(&file, src).unwrap();
    let o = lmdc(&["check", file.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("lmd::axis-limit"), "{}", stderr(&o));
    assert_eq!(listing(&dir), ["tooth.lmd"], "check writes nothing");

    // Two machines whose names differ only in what a file name drops.
    let src = std::fs::read_to_string("examples/sprocket_tooth.lmd")
        .unwrap()
        .replace("machine mill3 {", "machine \"mill 3\" {")
        .replace("machine kr30 {", "machine mill_3 {\n  kind = cnc\n  axes = 3\n  dialect = linuxcnc\n  max_speed = 50 mm/s\n}\nmachine kr30 {");
    std::fs::write(&file, src).unwrap();
    for cmd in ["check", "build"] {
        let o = lmdc(
            &[
                cmd,
                file.to_str().unwrap(),
                "--out",
                dir.join("out").to_str().unwrap(),
            ][..if cmd == "check" { 2 } else { 4 }],
        );
        assert_eq!(o.status.code(), Some(1), "{cmd}: {}", stderr(&o));
        assert!(
            stderr(&o).contains("lmd::name-clash"),
            "{cmd}: {}",
            stderr(&o)
        );
    }
    assert_eq!(listing(&dir), ["tooth.lmd"], "nothing written");
}

#[test]
fn build_writes_every_machine_deterministically() {
    let a = out_dir("a");
    let b = out_dir("b");
    for d in [&a, &b] {
        let o = lmdc(&[
            "build",
            "examples/twisted_duct.lmd",
            "-o",
            d.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    }
    let files = listing(&a);
    assert!(files.iter().any(|f| f.ends_with(".src")), "{files:?}");
    assert!(files.iter().any(|f| f.ends_with(".dat")), "{files:?}");
    assert!(files.iter().any(|f| f.ends_with(".ngc")), "{files:?}");
    assert!(
        !files.iter().any(|f| f.starts_with('.')),
        "temporary files left: {files:?}"
    );
    assert_eq!(files, listing(&b));
    #[cfg(unix)]
    for f in &files {
        use std::os::unix::fs::PermissionsExt;
        let mode = std::fs::metadata(a.join(f)).unwrap().permissions().mode();
        assert_eq!(
            mode & 0o644,
            0o644,
            "{f} is not readable by the cell's operators: {mode:o}"
        );
    }
    for f in &files {
        assert_eq!(
            std::fs::read(a.join(f)).unwrap(),
            std::fs::read(b.join(f)).unwrap(),
            "{f} differs"
        );
    }
    let _ = std::fs::remove_dir_all(&a);
    let _ = std::fs::remove_dir_all(&b);
}

#[test]
fn machine_selection_and_ir() {
    let d = out_dir("ir");
    let o = lmdc(&[
        "build",
        "examples/twisted_duct.lmd",
        "-o",
        d.to_str().unwrap(),
        "--machine",
        "dmu5",
        "--emit",
        "ir",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let files = listing(&d);
    assert!(files.iter().all(|f| !f.ends_with(".src")), "{files:?}");
    assert!(
        files.contains(&"twisted_duct.ir.json".to_string()),
        "{files:?}"
    );
    let ir: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.join("twisted_duct.ir.json")).unwrap()).unwrap();
    assert_eq!(ir["format"], "lmdc-ir");
    assert_eq!(ir["version"], lmdc::ir::VERSION);
    assert_eq!(ir["part"], "twisted_duct");
    assert_eq!(ir["units"]["speed"], "mm/s");
    let layer = &ir["layers"][3];
    assert_eq!(layer["index"], 3);
    for k in ["origin", "x", "y", "z"] {
        assert_eq!(layer["frame"][k].as_array().unwrap().len(), 3);
    }
    let p = &layer["paths"][0]["points"][0];
    for k in [
        "pos",
        "normal",
        "tangent",
        "layer_height",
        "speed",
        "power",
        "powder",
        "defocus",
        "laser_on",
    ] {
        assert!(!p[k].is_null(), "point lacks {k}");
    }
    // The IR reads back into the compiler's own type.
    let back: lmdc::ir::Program = serde_json::from_value(ir).unwrap();
    assert!(back.point_count() > 0);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn failures_write_nothing_and_exit_by_kind() {
    let d = out_dir("fail");
    let o = lmdc(&[
        "build",
        "examples/errors/unit_mismatch.lmd",
        "-o",
        d.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(!d.exists(), "output directory created for a failed build");

    let o = lmdc(&[
        "build",
        "examples/twisted_duct.lmd",
        "-o",
        d.to_str().unwrap(),
        "--machine",
        "nope",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("kr60"), "{}", stderr(&o));
    assert!(!d.exists());

    let o = lmdc(&["build", "no/such/file.lmd", "-o", d.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let o = lmdc(&["build", "examples", "-o", d.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let o = lmdc(&["frobnicate"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(!d.exists());
}

#[test]
fn bad_template_directory_override_is_a_usage_error() {
    let t = out_dir("tpl");
    std::fs::create_dir_all(t.join("gcode")).unwrap();
    std::fs::write(t.join("gcode/header.tera"), "{% if %}").unwrap();
    let d = out_dir("tplout");
    let o = lmdc(&[
        "build",
        "examples/twisted_duct.lmd",
        "-o",
        d.to_str().unwrap(),
        "--templates",
        t.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("gcode/header.tera"), "{}", stderr(&o));
    assert!(!d.exists());
    let _ = std::fs::remove_dir_all(&t);
}

#[test]
fn timings_report_every_stage() {
    let d = out_dir("timings");
    let o = lmdc(&[
        "build",
        "examples/twisted_duct.lmd",
        "-o",
        d.to_str().unwrap(),
        "--timings",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let text = stderr(&o);
    for stage in [
        "parse",
        "check",
        "slice",
        "verify",
        "emit KRL",
        "emit G-code",
        "write",
        "total",
    ] {
        assert!(
            text.lines().any(|l| l.starts_with(stage)),
            "no {stage} row in\n{text}"
        );
    }
    assert!(
        text.contains("peak heap") && text.contains("per point"),
        "{text}"
    );
    let _ = std::fs::remove_dir_all(&d);
}
