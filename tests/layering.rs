//! The pipeline's direction, held against the code (ARCHITECTURE.md, "Layers
//! and the direction of imports"): every `crate::MODULE` a source file names
//! (its tests left out) is a module of an earlier layer than the file's own,
//! or one of the exceptions listed here with why. A new import against the
//! direction fails this test; so does an exception no file needs any more.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// The top-level modules in pipeline order, a layer a line: a module may
/// import those of the layers above its own, not its own layer's others
/// (they are independent) nor the layers below.
const LAYERS: &[&[&str]] = &[
    // Leaves every stage reads: quantities, places, numbers, faults.
    &["span", "units", "numbers", "invalid", "provenance"],
    // The maths the stages build on, free of the language: a bead's
    // cross-section and fit, the solid's geometry, the loop's control
    // theory, the band styles' regions.
    &["bead", "geometry", "control", "style"],
    // One deposit model; a layer's fill over geometry; the thermal model of
    // a part as it is built.
    &["deposit", "fill", "thermal"],
    // The IR: the contract between the front end and the back ends.
    &["ir"],
    // What lmdc knows of controllers; the head's solids and the material.
    &["target", "collision"],
    // Diagnostics and the wording of every message.
    &["diag"],
    // Source → typed AST.
    &["syntax"],
    // The checker (AST → model) and the formatter (AST → text).
    &["sema", "fmt"],
    // `--set`: replaces a constant before the checker runs.
    &["overrides"],
    // Geometry and slicing: model → layers.
    &["slice"],
    // Model → IR.
    &["lower"],
    // IR + machine → moves.
    &["plan"],
    // Every process and machine rule over the IR and the plans.
    &["verify"],
    // What reads a verified plan: the writers, the report, the preview.
    &["back", "report", "preview"],
    // The stages strung together.
    &["pipeline"],
    // What serves the stages to people and tools.
    &["json_schema", "lsp"],
    &["cli"],
];

/// Imports against the direction that stay, each with why
/// (ARCHITECTURE.md says the same).
const EXCEPTIONS: &[(&str, &str, &str)] = &[
    (
        "diag",
        "slice",
        "a message matches on what a maths module found wrong: the variable layers' NoLayerCount, OutOfRange and SegmentError",
    ),
    (
        "diag",
        "plan",
        "a bump's place is a plan::Where, which the message prints",
    ),
    (
        "diag",
        "pipeline",
        "the usage errors (no such machine) are the pipeline's, worded in diag::usage",
    ),
    (
        "diag",
        "overrides",
        "a `--set` that cannot be read is an overrides::SetError, worded in diag::usage",
    ),
];

/// Modules that must never reach the front end's: the IR, the plan, the
/// verifier and the back ends read the IR, not the language.
const BACK: &[&str] = &[
    "ir",
    "target",
    "collision",
    "plan",
    "verify",
    "back",
    "preview",
];
const FRONT: &[&str] = &["syntax", "sema", "slice", "lower", "overrides", "fmt"];

fn layer_of(module: &str) -> Option<usize> {
    LAYERS.iter().position(|l| l.contains(&module))
}

/// The top-level modules each module names, from every file under `src/`
/// (a file's `#[cfg(test)]` part and `tests.rs` files left out, comments
/// stripped).
fn imports() -> BTreeMap<String, BTreeSet<(String, String)>> {
    let mut out: BTreeMap<String, BTreeSet<(String, String)>> = BTreeMap::new();
    let mut stack = vec![Path::new("src").to_path_buf()];
    while let Some(dir) = stack.pop() {
        for e in std::fs::read_dir(&dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
                continue;
            }
            if p.extension().is_none_or(|x| x != "rs") || p.ends_with("tests.rs") {
                continue;
            }
            let rel = p
                .strip_prefix("src")
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/");
            let module = rel
                .split('/')
                .next()
                .unwrap()
                .trim_end_matches(".rs")
                .to_string();
            let text = std::fs::read_to_string(&p).unwrap();
            let code = text.split("#[cfg(test)]").next().unwrap();
            for line in code.lines() {
                let line = line.split("//").next().unwrap();
                let mut rest = line;
                while let Some(i) = rest.find("crate::") {
                    rest = &rest[i + "crate::".len()..];
                    let name: String = rest
                        .chars()
                        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                        .collect();
                    if !name.is_empty() && name != module {
                        out.entry(module.clone())
                            .or_default()
                            .insert((name, rel.clone()));
                    }
                }
            }
        }
    }
    out
}

#[test]
fn every_module_is_in_a_layer() {
    for module in imports().keys() {
        if ["lib", "main"].contains(&module.as_str()) {
            continue;
        }
        assert!(
            layer_of(module).is_some(),
            "src/{module} is in no layer of tests/layering.rs: put it where the pipeline reads it"
        );
    }
}

#[test]
fn imports_run_with_the_pipeline() {
    let mut wrong = Vec::new();
    let mut used = BTreeSet::new();
    for (module, names) in imports() {
        let Some(from) = layer_of(&module) else {
            continue;
        };
        for (name, file) in names {
            let Some(to) = layer_of(&name) else {
                continue;
            };
            if to < from {
                continue;
            }
            match EXCEPTIONS.iter().find(|e| e.0 == module && e.1 == name) {
                Some(e) => {
                    used.insert((e.0, e.1));
                }
                None => wrong.push(format!("src/{file} imports crate::{name}")),
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "imports against the pipeline (tests/layering.rs, ARCHITECTURE.md):\n{}",
        wrong.join("\n")
    );
    for e in EXCEPTIONS {
        assert!(
            used.contains(&(e.0, e.1)),
            "the exception {} → {} is needed no more: take it out of tests/layering.rs and ARCHITECTURE.md",
            e.0,
            e.1
        );
    }
}

#[test]
fn the_ir_and_what_reads_it_know_nothing_of_the_language() {
    let mut wrong = Vec::new();
    for (module, names) in imports() {
        if !BACK.contains(&module.as_str()) {
            continue;
        }
        for (name, file) in names {
            if FRONT.contains(&name.as_str()) {
                wrong.push(format!("src/{file} imports crate::{name}"));
            }
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

/// The test's own reading of imports finds what it is meant to: an import
/// written as a path, a `use` and a nested group.
#[test]
fn the_reader_finds_imports() {
    let found = imports();
    let sema = &found["sema"];
    assert!(sema.iter().any(|(n, _)| n == "ir"));
    assert!(sema.iter().any(|(n, _)| n == "geometry"));
    assert!(!found["geometry"].iter().any(|(n, _)| n == "sema"));
}
