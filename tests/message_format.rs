//! `--message-format json`: every diagnostic of every error example comes out
//! as one line of JSON on stdout that validates against
//! docs/diagnostics.schema.json, reads back into the very diagnostic the
//! compiler made (round trip), and points at the line and column the drawn
//! report names.

use crate::support::schema;

use lmdc::diag::json::JsonDiagnostic;
use lmdc::pipeline::compile_for;
use serde_json::Value;
use std::process::{Command, Output};

fn lmdc(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lmdc"))
        .args(args)
        .env("NO_COLOR", "1")
        .output()
        .expect("runs")
}

fn schema() -> Value {
    serde_json::from_str(&std::fs::read_to_string("docs/diagnostics.schema.json").unwrap())
        .expect("the schema is JSON")
}

fn examples() -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir("examples/errors")
        .unwrap()
        .map(|e| e.unwrap().path().display().to_string())
        .filter(|p| p.ends_with(".lmd"))
        .collect();
    v.sort();
    v
}

#[test]
fn every_error_example_validates_and_round_trips() {
    let schema = schema();
    let mut seen = 0;
    for file in examples() {
        let o = lmdc(&["check", "--message-format", "json", &file]);
        assert_eq!(o.status.code(), Some(1), "{file}");
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(
            !stderr.contains("×"),
            "{file}: drawn reports on stderr: {stderr}"
        );
        let stdout = String::from_utf8(o.stdout).unwrap();
        let source = std::fs::read_to_string(&file).unwrap();
        let want: Vec<_> = compile_for(&source, None, &mut ())
            .unwrap()
            .diagnostics
            .into_vec();
        let lines: Vec<&str> = stdout.lines().collect();
        assert_eq!(lines.len(), want.len(), "{file}: one line a diagnostic");
        let human = String::from_utf8(lmdc(&["check", &file]).stderr).unwrap();
        for (line, want) in lines.iter().zip(&want) {
            let v: Value = serde_json::from_str(line).expect("JSON");
            let errors = schema::validate(&schema, &v);
            assert!(errors.is_empty(), "{file}: {errors:?}\n{line}");
            let j = JsonDiagnostic::parse(line).unwrap();
            assert_eq!(&j.to_diagnostic().unwrap(), want, "{file}: round trip");
            assert_eq!(j.file, file);
            // The drawn report names the primary span as file:line:column
            // (ASCII sources: characters are bytes).
            if let Some(s) = j.spans.first().filter(|_| source.is_ascii()) {
                let at = format!("{file}:{}:{}]", s.line_start, s.column_start);
                assert!(human.contains(&at), "{file}: {at} not in\n{human}");
                assert!(
                    source.get(s.byte_start..s.byte_end).is_some(),
                    "{file}: bytes"
                );
            }
            seen += 1;
        }
    }
    assert!(seen > 30, "only {seen} diagnostics");
}

#[test]
fn build_and_report_speak_json_too_and_success_is_silent() {
    for cmd in ["build", "report", "preview"] {
        let o = lmdc(&[
            cmd,
            "--message-format",
            "json",
            "examples/errors/unit_mismatch.lmd",
        ]);
        assert_eq!(o.status.code(), Some(1), "{cmd}");
        let out = String::from_utf8(o.stdout).unwrap();
        assert!(!out.is_empty(), "{cmd}");
        for line in out.lines() {
            assert!(JsonDiagnostic::parse(line).is_ok(), "{cmd}: {line}");
        }
    }
    let o = lmdc(&[
        "check",
        "--message-format",
        "json",
        "examples/twisted_duct.lmd",
    ]);
    assert_eq!(o.status.code(), Some(0));
    assert!(o.stdout.is_empty(), "no diagnostics, no lines");
}

#[test]
fn the_schema_documents_every_field_the_encoder_writes() {
    // A diagnostic with every optional part, through the encoder.
    // (Written as data: only lmdc's message module words diagnostics.)
    use lmdc::diag::{Code, Diagnostic, Label, Severity};
    use lmdc::span::Span;
    let label = |start, end, text: &str| Label {
        span: Span::new(start, end),
        text: text.into(),
    };
    let d = Diagnostic {
        code: Code::Unused,
        severity: Severity::Warning,
        message: "unused `x`".into(),
        labels: vec![label(0, 4, "here"), label(5, 6, "")],
        help: Some("remove it".into()),
        allowed: Some("kept for the next revision".into()),
    };
    let line = lmdc::diag::json::Encoder::new("f.lmd", "part x\n").line(&d);
    let v: Value = serde_json::from_str(&line).unwrap();
    assert!(schema::validate(&schema(), &v).is_empty(), "{line}");
    let mut bad = v.clone();
    bad["spans"][0]["column_start"] = 0.into();
    bad["severity"] = "note".into();
    assert_eq!(schema::validate(&schema(), &bad).len(), 2);
}
