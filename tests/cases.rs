//! The cases of `tests/cases/` (its README.md says how to add one and how to
//! bless): every folder with an `input.lmd` is compiled with the library, and
//! what lmdc produces — every program file under its own name, the
//! diagnostics as text and as JSON lines, the exit status of a failed build,
//! the IR where a case asks for it — must equal the files beside the input.
//! Review every change to them: the programs are what machines run.

use crate::support::expected::{self, blessing};
use lmdc::back::{MemorySink, Templates};
use lmdc::diag::json::Encoder;
use lmdc::diag::render;
use lmdc::pipeline::{compile_with_model, emit, DataFiles, Options};
use lmdc::sema::model::Build;
use lmdc::slice::calibration::sheet;
use serde_json::Value;
use std::collections::BTreeMap;
use std::fs;
use std::path::{Component, Path, PathBuf};

/// Where the cases are.
pub const ROOT: &str = "tests/cases";

/// The input of every case.
const INPUT: &str = "input.lmd";

/// Written beside a case's input for an input with errors.
const EXIT_STATUS: &str = "exit-status";

/// Produced only for the cases that have one (create it empty and bless).
const IR: &str = "ir.json";

/// Every case folder under `root`, sorted: a folder with an `input.lmd`
/// (the folders above hold folders only, and the root its README.md).
pub fn folders(root: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    let mut stray = Vec::new();
    walk(root, root, &mut found, &mut stray);
    assert!(
        stray.is_empty(),
        "files outside any case folder (a case is a folder with an {INPUT}): {stray:?}"
    );
    found.sort();
    found
}

fn walk(root: &Path, dir: &Path, found: &mut Vec<PathBuf>, stray: &mut Vec<PathBuf>) {
    if dir.join(INPUT).exists() {
        found.push(dir.to_path_buf());
        return;
    }
    for e in fs::read_dir(dir).unwrap() {
        let path = e.unwrap().path();
        if path.is_dir() {
            walk(root, &path, found, stray);
        } else if !(dir == root && path.file_name().is_some_and(|n| n == "README.md")) {
            stray.push(path);
        }
    }
}

/// `path` with its `..` and `.` taken out, written with `/`.
fn normal(path: &Path) -> String {
    let mut parts: Vec<String> = Vec::new();
    for c in path.components() {
        match c {
            Component::ParentDir => {
                assert!(
                    parts.pop().is_some(),
                    "{} leaves the repository",
                    path.display()
                );
            }
            Component::CurDir => {}
            c => parts.push(c.as_os_str().to_string_lossy().into_owned()),
        }
    }
    parts.join("/")
}

/// The file a case's input is, as the reports name it: the example a
/// symbolic link points at (`examples/flange.lmd`), else the input itself
/// (`tests/cases/…/input.lmd`) — the path `lmdc check` is given from the
/// repository's root.
pub fn input_name(case: &Path) -> String {
    let input = case.join(INPUT);
    match fs::read_link(&input) {
        Ok(target) => {
            let name = normal(&case.join(target));
            assert!(
                Path::new(&name).is_file(),
                "{}: links to {name}, which is not a file",
                input.display()
            );
            name
        }
        Err(_) => normal(&input),
    }
}

/// Floats rounded to 6 decimals, so that the IR does not churn with libm.
fn round(v: &mut Value) {
    match v {
        Value::Number(n) if n.is_f64() => {
            let x = (n.as_f64().unwrap() * 1e6).round() / 1e6;
            // -0 and 0 print alike
            let x = if x == 0.0 { 0.0 } else { x };
            *v = serde_json::json!(x);
        }
        Value::Array(a) => a.iter_mut().for_each(round),
        Value::Object(o) => o.values_mut().for_each(round),
        _ => {}
    }
}

/// Everything lmdc produces for the case in `case`, by file name.
pub fn produce(case: &Path) -> BTreeMap<String, Vec<u8>> {
    let name = input_name(case);
    let src = fs::read_to_string(case.join(INPUT))
        .unwrap_or_else(|e| panic!("{}: {e}", case.join(INPUT).display()));
    // Its data files (`fit(…, data = "…")`) beside it, as the CLI reads them.
    let dir = case.to_path_buf();
    let data: lmdc::sema::DataReader =
        std::rc::Rc::new(move |path: &str, _| fs::read(dir.join(path)).map_err(|e| e.to_string()));
    let options = Options {
        file: Some(name.clone()),
        data: Some(DataFiles(data)),
        ..Options::default()
    };
    let (c, model) =
        compile_with_model(&src, &options, &mut ()).expect("no machine named, nothing set");
    let mut out = BTreeMap::new();
    if !c.diagnostics.is_empty() {
        // What `lmdc check FILE --color never` draws on stderr, and what
        // `--message-format json` writes on stdout.
        let text = render(&c.diagnostics, &name, &src, false);
        out.insert("diagnostics.txt".to_string(), text.into_bytes());
        let enc = Encoder::new(&name, &src);
        let lines: String = c.diagnostics.iter().map(|d| enc.line(d) + "\n").collect();
        out.insert("diagnostics.jsonl".to_string(), lines.into_bytes());
    }
    let Some(p) = c.program else {
        assert!(
            c.diagnostics.has_errors(),
            "{name}: no program and no error (every failed build must say why)"
        );
        out.insert(EXIT_STATUS.to_string(), b"1\n".to_vec());
        return out;
    };
    let mut sink = MemorySink::default();
    emit(&p, &Templates::builtin().unwrap(), &mut sink, &mut ())
        .unwrap_or_else(|e| panic!("{name}: emitting failed: {e}"));
    let hash = lmdc::provenance::sha256_hex(src.as_bytes());
    for (file, bytes) in sink.files {
        let bytes = without_hash(&name, &file, bytes, &hash);
        assert!(
            !out.contains_key(&file) && file != INPUT && file != IR,
            "{name}: lmdc writes {file} twice, or over a file of the case"
        );
        out.insert(file, bytes);
    }
    if let Some(Build::Calibration(cal)) = model.as_ref().map(|m| &m.build) {
        // What `lmdc calibrate` writes beside the programs.
        let part = &p.ir().part;
        let file = format!(
            "{}.coupons.csv",
            lmdc::target::names::windows_safe(&lmdc::back::identifier(part, 64))
        );
        out.insert(file, sheet(part, cal).into_bytes());
    }
    if case.join(IR).exists() {
        // Through the text form, as a reader of `--emit ir` sees it (f32
        // values print short).
        let mut v: Value = serde_json::from_str(&serde_json::to_string(p.ir()).unwrap()).unwrap();
        round(&mut v);
        out.insert(
            IR.to_string(),
            (serde_json::to_string_pretty(&v).unwrap() + "\n").into_bytes(),
        );
    }
    out
}

/// What the expected programs hold in place of the source's sha256: a case's
/// programs do not change with a comment of its input (the headers'
/// provenance line is tested in tests/cli_ci.rs against `sha256sum`).
pub const HASH: &str = "<sha256 of the source>";

/// `bytes` (the program `file` of input `name`) with the source's `hash`
/// replaced by [`HASH`]: every line naming a `sha256` names the source's.
fn without_hash(name: &str, file: &str, bytes: Vec<u8>, hash: &str) -> Vec<u8> {
    let text = String::from_utf8(bytes).unwrap_or_else(|e| panic!("{name}: {file}: {e}"));
    let named = text.lines().filter(|l| l.contains("sha256 ")).count();
    assert_eq!(
        text.matches(hash).count(),
        named,
        "{name}: {file}: a sha256 that is not its source's"
    );
    let main = file.ends_with(".src") || !file.ends_with(".dat");
    assert!(
        !main || named > 0,
        "{name}: {file} does not name its source"
    );
    text.replace(hash, HASH).into_bytes()
}

/// Every case's files are what lmdc produces for its input. `LMDC_CASE=text`
/// runs only the cases whose folder contains `text`.
#[test]
fn every_case_produces_its_files() {
    let only = std::env::var("LMDC_CASE").unwrap_or_default();
    let all = folders(Path::new(ROOT));
    assert!(all.len() >= 30, "only {} cases in {ROOT}", all.len());
    let mut problems = Vec::new();
    let mut failed = 0;
    let mut ran = 0;
    for case in all.iter().filter(|c| c.to_string_lossy().contains(&only)) {
        ran += 1;
        let produced = produce(case);
        // The input and its data files (measurement sheets, meshes, scans,
        // a folder of them) are the case's; a sheet `lmdc calibrate` writes
        // (`*.coupons.csv`) is an output; a script that writes the data files.
        let p = expected::check_dir(case, &produced, |f| {
            f == INPUT
                || (f.ends_with(".csv") && !f.ends_with(".coupons.csv"))
                || f.ends_with(".stl")
                || f.ends_with(".ply")
                || f.ends_with(".py")
                || case.join(f).is_dir()
        });
        if !p.is_empty() {
            failed += 1;
            problems.push(format!("── {} ──\n{}", case.display(), p.join("\n")));
        }
    }
    assert!(ran > 0, "LMDC_CASE={only} names no case");
    if !problems.is_empty() {
        expected::fail(
            &format!("{failed} of {ran} cases differ from their expected files"),
            &problems,
        );
    }
    if blessing() {
        eprintln!("blessed {ran} cases");
    }
}

/// The inputs that link to a file (as every case of a user-facing example
/// does), by the file they link to.
fn linked() -> BTreeMap<String, PathBuf> {
    let mut by_target = BTreeMap::new();
    for case in folders(Path::new(ROOT)) {
        if fs::read_link(case.join(INPUT)).is_ok() {
            if let Some(other) = by_target.insert(input_name(&case), case.clone()) {
                panic!(
                    "{} and {} are cases of one file",
                    other.display(),
                    case.display()
                );
            }
        }
    }
    by_target
}

/// Examples too large to keep as expected programs; other tests compile them.
const NOT_CASES: &[(&str, &str)] = &[
    (
        "examples/twisted_duct.lmd",
        "193 layers, 69 673 points: 3.7 MB of programs; tests/cases/duct/small_duct is the same part, smaller",
    ),
    (
        "examples/duct_positioner.lmd",
        "281 layers, 101 441 points: 6 MB of KRL; tests/cases/positioner/small_duct is the same set-up on a smaller duct, tests/positioner.rs builds the example",
    ),
];

/// Every example is the input of a case, by a link (one file, never two
/// copies that drift apart): an example whose output changes shows in a
/// diff, and a new error example is a case from the start.
#[test]
fn every_example_is_a_case() {
    let linked = linked();
    let mut missing = Vec::new();
    for dir in ["examples", "examples/errors"] {
        let mut files: Vec<PathBuf> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|e| e == "lmd"))
            .collect();
        files.sort();
        for f in files {
            let name = normal(&f);
            if !linked.contains_key(&name) && !NOT_CASES.iter().any(|(n, _)| *n == name) {
                missing.push(name);
            }
        }
    }
    assert!(
        missing.is_empty(),
        "examples no case links to (tests/cases/README.md says how to add one): {missing:?}"
    );
    for (name, why) in NOT_CASES {
        assert!(Path::new(name).is_file(), "{name} ({why}) is gone");
        assert!(!linked.contains_key(*name), "{name} is a case after all");
    }
}
