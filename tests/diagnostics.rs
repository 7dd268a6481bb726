//! Snapshots of the diagnostics for every file in examples/errors/: what a user
//! sees for each kind of mistake. Review every snapshot change.

use lmdc::diag::render;
use lmdc::pipeline::compile;
use std::path::Path;

fn diagnose(path: &Path) -> (String, bool) {
    let src = std::fs::read_to_string(path).unwrap();
    let c = compile(&src, &mut ());
    let name = format!(
        "examples/errors/{}",
        path.file_name().unwrap().to_string_lossy()
    );
    (
        render(&c.diagnostics, &name, &src, false),
        c.program.is_some(),
    )
}

#[test]
fn every_error_example_fails_with_its_diagnostic() {
    let mut files: Vec<_> = std::fs::read_dir("examples/errors")
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "lmd"))
        .collect();
    files.sort();
    assert!(files.len() >= 4);
    for f in files {
        let (text, ok) = diagnose(&f);
        assert!(!ok, "{} compiled", f.display());
        let name = f.file_stem().unwrap().to_string_lossy().into_owned();
        insta::assert_snapshot!(name, text);
    }
}

#[test]
fn bend_too_tight_names_the_numbers() {
    let (text, _) = diagnose(Path::new("examples/errors/bend_too_tight.lmd"));
    // Seed 000 with R1 = 100 mm: heights differ 2.24× (outer face 30 mm, 3 mm
    // inset, corners of the twisted square), the bead model spans 1.41×.
    assert!(text.contains("lmd::bend-too-tight"), "{text}");
    assert!(text.contains("needs h_max/h_min ≥"), "{text}");
    assert!(text.contains("a bend radius of at least"), "{text}");
}

#[test]
fn unit_mismatch_points_at_both_operands() {
    let (text, _) = diagnose(Path::new("examples/errors/unit_mismatch.lmd"));
    assert!(text.contains("lmd::unit-mismatch"), "{text}");
    assert!(
        text.contains("a length (mm)") && text.contains("an angle (deg)"),
        "{text}"
    );
    // The process power in mm/s is a second, independent error: all reported.
    assert!(text.contains("`power` must be a power (W)"), "{text}");
}

#[test]
fn unknown_names_get_suggestions() {
    let (text, _) = diagnose(Path::new("examples/errors/unknown_name.lmd"));
    for want in [
        "did you mean `wall_bead`?",
        "did you mean `seam`?",
        "did you mean `robot`?",
        "`outlet_section`",
    ] {
        assert!(text.contains(want), "missing {want:?} in\n{text}");
    }
}
