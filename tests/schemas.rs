//! What lmdc writes as data follows its published schemas: the IR
//! (`--emit ir`, docs/ir.schema.json), the report (`report --json`,
//! docs/report.schema.json) and the motion plan (`--emit plan`,
//! docs/plan.schema.json), for every example, checked by validators
//! independent of lmdc, as users' own checks would run them:
//! jsonschema-rs, and Python's jsonschema for the messages of what fails
//! (tests/support/validate_json.py). The schemas are closed (a field they
//! do not list is an error), so a field lmdc adds without its schema fails
//! here; src/json_schema.rs keeps the IR's and the report's in step with the
//! types.
//!
//! The duct and the ring are built with fewer points (the same kinds of
//! data, smaller): every line of every plan and every point of every IR is
//! validated.

use crate::support::example::edited;
use crate::support::skip::skip;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

const VALIDATOR: &str = "tests/support/validate_json.py";

/// Whether Python's jsonschema can run; under CI its absence fails.
fn have_validator(test: &str) -> bool {
    let ok = Command::new("python3")
        .args(["-c", "import jsonschema, jsonschema_rs"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !ok {
        skip(
            test,
            "Python's jsonschema and jsonschema-rs",
            "python3 -m pip install jsonschema jsonschema-rs",
        );
    }
    ok
}

/// Runs the validator on `files` against `schema`: `Err` with its report.
fn validate(schema: &str, lines: bool, files: &[PathBuf]) -> Result<(), String> {
    let mut cmd = Command::new("python3");
    cmd.arg(VALIDATOR).arg(schema);
    if lines {
        cmd.arg("--lines");
    }
    let o = cmd.args(files).output().unwrap();
    match o.status.code() {
        Some(0) => Ok(()),
        _ => Err(format!(
            "{}{}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        )),
    }
}

/// Each example's file, the large ones made small (written into `dir`; they
/// read no data files).
fn examples(dir: &Path) -> Vec<(String, PathBuf)> {
    let mut names: Vec<String> = std::fs::read_dir("examples")
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".lmd"))
        .collect();
    names.sort();
    names
        .into_iter()
        .map(|n| {
            let small = match n.as_str() {
                "twisted_duct.lmd" => Some(edited(&n, &[("points = 360", "points = 24")])),
                "segmented_ring.lmd" => Some(edited(&n, &[("step = 1 deg", "step = 10 deg")])),
                _ => None,
            };
            let file = match small {
                Some(src) => {
                    let f = dir.join(&n);
                    std::fs::write(&f, src).unwrap();
                    f
                }
                None => Path::new("examples").join(&n),
            };
            (n, file)
        })
        .collect()
}

fn lmdc(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_lmdc"))
        .args(args)
        .output()
        .unwrap()
}

/// Builds every example into `dir` with its IR, plan and report: the IR
/// files, the plan files and the report files (one JSON object a line).
fn outputs(dir: &Path) -> (Vec<PathBuf>, Vec<PathBuf>, Vec<PathBuf>) {
    let (mut irs, mut plans, mut reports) = (vec![], vec![], vec![]);
    for (name, file) in examples(dir) {
        let stem = name.trim_end_matches(".lmd");
        let out = dir.join(stem);
        let (f, o) = (file.to_str().unwrap(), out.to_str().unwrap());
        let b = lmdc(&["build", f, "-o", o, "--emit", "ir", "--emit", "plan", "-q"]);
        let r = lmdc(&["report", f, "--json"]);
        assert_eq!(
            b.status.code(),
            Some(0),
            "{name}: {}",
            String::from_utf8_lossy(&b.stderr)
        );
        assert_eq!(
            r.status.code(),
            Some(0),
            "{name}: {}",
            String::from_utf8_lossy(&r.stderr)
        );
        let report = out.join("report.jsonl");
        std::fs::write(&report, &r.stdout).unwrap();
        reports.push(report);
        for e in std::fs::read_dir(&out).unwrap() {
            let p = e.unwrap().path();
            let n = p.file_name().unwrap().to_string_lossy().into_owned();
            if n.ends_with(".ir.json") {
                irs.push(p);
            } else if n.ends_with(".plan.jsonl") {
                plans.push(p);
            }
        }
    }
    (irs, plans, reports)
}

#[test]
fn every_examples_ir_report_and_plan_follow_the_schemas() {
    if !have_validator("every_examples_ir_report_and_plan_follow_the_schemas") {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let (irs, plans, reports) = outputs(dir.path());
    assert!(
        irs.len() >= 10 && plans.len() >= 2 * irs.len() - 2,
        "{irs:?} {plans:?}"
    );
    for (schema, lines, files) in [
        ("docs/ir.schema.json", false, &irs),
        ("docs/report.schema.json", true, &reports),
        ("docs/plan.schema.json", true, &plans),
    ] {
        if let Err(e) = validate(schema, lines, files) {
            panic!("lmdc's output does not follow {schema}:\n{e}");
        }
    }
}

/// The schemas refuse what lmdc does not write: an unknown field, a missing
/// one, a value of the wrong kind (so the test above can fail).
#[test]
fn the_schemas_refuse_broken_data() {
    if !have_validator("the_schemas_refuse_broken_data") {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("flange");
    let b = lmdc(&[
        "build",
        "examples/flange.lmd",
        "-o",
        out.to_str().unwrap(),
        "--emit",
        "ir",
        "--emit",
        "plan",
        "-q",
    ]);
    assert_eq!(b.status.code(), Some(0));
    let ir: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("flange.ir.json")).unwrap())
            .unwrap();
    let plan = std::fs::read_to_string(out.join("flange_mill3.plan.jsonl")).unwrap();
    let first_move = plan
        .lines()
        .find(|l| l.contains(r#""type":"move""#))
        .unwrap();
    let mv: Value = serde_json::from_str(first_move).unwrap();

    let mut cases: Vec<(&str, &str, Value, &str)> = Vec::new();
    let mut ir_extra = ir.clone();
    ir_extra["layers"][0]["paths"][0]["points"][0]["temperature"] = 900.into();
    cases.push(("ir", "docs/ir.schema.json", ir_extra, "temperature"));
    let mut ir_missing = ir.clone();
    ir_missing["layers"][0]["paths"][0]["points"][0]
        .as_object_mut()
        .unwrap()
        .remove("pos");
    cases.push(("ir", "docs/ir.schema.json", ir_missing, "pos"));
    let mut machine_extra = ir.clone();
    machine_extra["machines"][0]["spindle"] = 1.into();
    cases.push(("ir", "docs/ir.schema.json", machine_extra, "spindle"));
    let mut plan_kind = mv.clone();
    plan_kind["kind"] = "jump".into();
    cases.push(("plan", "docs/plan.schema.json", plan_kind, "jump"));
    let mut plan_power = mv.clone();
    plan_power["power"] = (-5.0).into();
    cases.push(("plan", "docs/plan.schema.json", plan_power, "-5"));

    for (i, (what, schema, doc, word)) in cases.into_iter().enumerate() {
        let file = dir.path().join(format!("{what}{i}.json"));
        std::fs::write(&file, doc.to_string()).unwrap();
        match validate(schema, false, &[file]) {
            Ok(()) => panic!("{schema} accepts a broken {what} (case {i}: {word})"),
            Err(e) => assert!(
                e.contains(word),
                "case {i}: the error does not name `{word}`:\n{e}"
            ),
        }
    }
}
