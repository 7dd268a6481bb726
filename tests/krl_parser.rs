//! Every KRL file lmdc writes is read by a third-party KUKA KRL parser:
//! `LMDC_KRL_PARSER` names a command that takes KRL files and exits non-zero
//! on a syntax error. CI installs `krlcheck`, grammars-v4's ANTLR grammar
//! `kuka/krl.g4` behind a small driver (`sh ../shared/tools/krlcheck/install.sh`,
//! see its README for where the grammar is stricter or looser than KSS 8.x),
//! and there a missing parser fails these tests; elsewhere they say on the
//! terminal that they were skipped. tests/krl_program.rs's own checker always
//! runs.

use crate::support::krl_parser as parser;
use crate::support::skip;

use lmdc::back::{MemorySink, Templates};
use lmdc::ir::Machine;
use std::path::PathBuf;

fn have_parser(test: &str) -> bool {
    if parser::find_krl_parser().is_some() {
        return true;
    }
    skip::skip(
        test,
        "a KRL parser",
        "run `sh ../shared/tools/krlcheck/install.sh` and export LMDC_KRL_PARSER=$HOME/.local/bin/krlcheck",
    );
    false
}

/// A main program and a motion module in the shape lmdc writes (header lines,
/// `;FOLD INI` with `BAS`, system variables, `PTP`/`LIN` with `C_DIS`,
/// `TRIGGER`, module calls): the parser must take it, or the checks below
/// would say nothing about the emitter.
const MAIN_SRC: &str = "&ACCESS RVP
&REL 1
DEF part_kr60( )
; part_kr60: written by hand in lmdc's style
;FOLD INI
  BAS(#INITMOV,0)
;ENDFOLD
$TOOL = TOOL_DATA[1]
$BASE = BASE_DATA[2]
$TOOL = {X 0.0,Y 0.0,Z 350.0,A 0.0,B 0.0,C 0.0}
$IPO_MODE = #BASE
$ADVANCE = 3
$ORI_TYPE = #VAR
$APO.CDIS = 0.2
$ACC.CP = 2.0
$OUT[3] = FALSE
$ANOUT[2] = 0.0
PTP {A1 0.0,A2 -90.0,A3 90.0,A4 0.0,A5 0.0,A6 0.0}
part_kr60_m001( )
$OUT[3] = FALSE
PTP {A1 0.0,A2 -90.0,A3 90.0,A4 0.0,A5 0.0,A6 0.0}
END
";
const MAIN_DAT: &str = "&ACCESS RVP
&REL 1
DEFDAT part_kr60
; no data
ENDDAT
";
const MODULE_SRC: &str = "&ACCESS RVP
&REL 1
DEF part_kr60_m001( )
; layer 1 of 1
$VEL.CP = 0.25
LIN {X 30.0,Y 0.0,Z 10.5,A 0.0,B 0.0,C 180.0} C_DIS
LIN {X 30.0,Y 0.0,Z 0.5,A 0.0,B 0.0,C 180.0}
$VEL.CP = 0.008333
TRIGGER WHEN DISTANCE=0 DELAY=0 DO $ANOUT[2]=0.625
TRIGGER WHEN DISTANCE=0 DELAY=0 DO $OUT[3]=TRUE
LIN {X 0.0,Y 30.0,Z 0.5,A 0.0,B -0.123,C -179.5} C_DIS
TRIGGER WHEN DISTANCE=0 DELAY=0 DO $OUT[3]=FALSE
LIN {X 0.0,Y 30.0,Z 10.5,A 0.0,B 0.0,C 180.0} C_DIS
END
";
const MODULE_DAT: &str = "&ACCESS RVP
&REL 1
DEFDAT part_kr60_m001
ENDDAT
";

#[test]
fn lmdc_style_krl_parses() {
    if !have_parser("lmdc_style_krl_parses") {
        return;
    }
    parser::parse_sources(&[
        ("part_kr60.src", MAIN_SRC),
        ("part_kr60.dat", MAIN_DAT),
        ("part_kr60_m001.src", MODULE_SRC),
        ("part_kr60_m001.dat", MODULE_DAT),
    ])
    .unwrap_or_else(|e| panic!("the parser rejects valid KRL:\n{e}"));
}

/// `text` with `from` replaced by `to`; `from` must occur in `text`.
fn broken(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "{from:?} is not in the program");
    text.replace(from, to)
}

/// The parser checks something: each of these broken files is rejected, at the
/// line where it breaks.
#[test]
fn broken_krl_is_rejected() {
    if !have_parser("broken_krl_is_rejected") {
        return;
    }
    let lin = "LIN {X 0.0,Y 30.0,Z 0.5,A 0.0,B -0.123,C -179.5} C_DIS";
    let cases: Vec<(&str, String, usize)> = vec![
        // A LIN whose position lacks its closing brace.
        (
            "missing_brace.src",
            broken(MODULE_SRC, lin, &lin.replace("} C_DIS", " C_DIS")),
            11,
        ),
        // DEF without END: the error is at the end of the file.
        ("missing_end.src", broken(MODULE_SRC, "END\n", ""), 14),
        // DEFDAT without ENDDAT.
        ("missing_enddat.dat", broken(MAIN_DAT, "ENDDAT\n", ""), 5),
        // TRIGGER without DO.
        (
            "trigger_without_do.src",
            broken(
                MODULE_SRC,
                "DELAY=0 DO $OUT[3]=TRUE",
                "DELAY=0 $OUT[3]=TRUE",
            ),
            10,
        ),
        // A data module where routines belong.
        ("dat_as_src.src", MAIN_DAT.to_string(), 1),
    ];
    for (name, text, line) in &cases {
        let err = match parser::parse_sources(&[(name, text)]) {
            Ok(()) => panic!("the parser accepts broken KRL {name}:\n{text}"),
            Err(e) => e,
        };
        let at = format!("{name}:{line}:");
        assert!(
            err.contains(&at),
            "{name}: expected an error at line {line}, got:\n{err}"
        );
    }
}

/// Every example source: `examples/*.lmd`, the benchmarks in
/// `examples/bench/` and the golden small duct. The dense duct benchmark (3.6 M
/// points, 413 MB of KRL) is parsed with 72 points a layer instead of 3600:
/// the same program shape and lines, at a size a test can read.
fn sources() -> Vec<(PathBuf, String)> {
    let mut files: Vec<PathBuf> = Vec::new();
    for dir in ["examples", "examples/bench"] {
        files.extend(
            std::fs::read_dir(dir)
                .unwrap()
                .map(|e| e.unwrap().path())
                .filter(|p| p.extension().is_some_and(|e| e == "lmd")),
        );
    }
    files.sort();
    files.push(PathBuf::from("tests/cases/duct/small_duct/input.lmd"));
    files
        .into_iter()
        .map(|f| {
            let mut src = std::fs::read_to_string(&f).unwrap();
            // The benchmarks at a size that writes the same kinds of lines
            // (42 MB of KRL from the plate would take the parser 8 s).
            if f.ends_with("dense_duct.lmd") {
                assert!(src.contains("points = 3600"), "dense_duct.lmd changed");
                src = src.replace("points = 3600", "points = 72");
            }
            if f.ends_with("big_plate.lmd") {
                assert!(src.contains("layers = 400"), "big_plate.lmd changed");
                src = src.replace("layers = 400", "layers = 12");
            }
            (f, src)
        })
        .collect()
}

/// Every `.src`/`.dat` file lmdc writes for every robot of every example
/// parses.
#[test]
fn every_emitted_krl_file_parses() {
    if !have_parser("every_emitted_krl_file_parses") {
        return;
    }
    let templates = Templates::builtin().unwrap();
    let mut parsed = 0;
    let mut robots = 0;
    let mut mutant_rejected = false;
    let (mut all, mut dirs) = (Vec::new(), Vec::new());
    for (f, src) in sources() {
        let c = crate::support::example::compile_file(&f, &src);
        let Some(p) = c.program else {
            panic!(
                "{} does not compile:\n{}",
                f.display(),
                lmdc::diag::render(&c.diagnostics, &f.display().to_string(), &src, false)
            );
        };
        for m in p.machines() {
            let Machine::Robot(robot) = m.machine() else {
                continue;
            };
            if robot.controller == lmdc::ir::Controller::Abb {
                continue; // RAPID: tests/rapid_program.rs
            }
            robots += 1;
            let mut sink = MemorySink::default();
            if let Err(e) = lmdc::back::emit(m, &templates, &mut sink) {
                panic!(
                    "{}: emitting robot {} failed: {e}\n{e:?}",
                    f.display(),
                    robot.name
                );
            }
            // Named for the example and the robot: the parser's messages
            // name the file.
            let stem = f.file_stem().unwrap_or_default().to_string_lossy();
            let dir = parser::TempDir::new(&format!("{stem}-{}", robot.name));
            let paths: Vec<PathBuf> = sink
                .files
                .iter()
                .filter(|(name, _)| parser::is_krl_file(name))
                .map(|(name, bytes)| dir.write(name, bytes))
                .collect();
            assert!(
                !paths.is_empty(),
                "{}: robot {} wrote no .src/.dat file (wrote {:?})",
                f.display(),
                robot.name,
                sink.files.iter().map(|(n, _)| n).collect::<Vec<_>>()
            );
            parsed += paths.len();
            // One run of the parser for every file of every example: a
            // JVM's start a robot was most of this test's time.
            all.extend(paths);
            dirs.push(dir);
            if !mutant_rejected {
                mutant_rejected = lin_without_brace_is_rejected(&sink);
            }
        }
    }
    if let Err(e) = parser::parse_files(&all) {
        panic!("the KRL parser rejects lmdc's output:\n{e}");
    }
    drop(dirs);
    assert!(robots > 0, "no example declares a robot");
    assert!(parsed > 0, "no KRL file was parsed");
    assert!(mutant_rejected, "no emitted .src file has a LIN to break");
    eprintln!("{parsed} KRL files of {robots} robot(s) parsed");
}

/// Takes the first emitted `.src` file with a `LIN {...}` line, drops that
/// line's closing brace and checks the parser rejects the result at that line,
/// so a parser that accepted anything could not pass the test above. Returns
/// false when no file has such a line.
fn lin_without_brace_is_rejected(sink: &MemorySink) -> bool {
    for (name, bytes) in &sink.files {
        if !name.to_ascii_lowercase().ends_with(".src") {
            continue;
        }
        let text = String::from_utf8_lossy(bytes);
        let Some((i, _)) = text
            .lines()
            .enumerate()
            .find(|(_, l)| l.starts_with("LIN {") && l.contains('}'))
        else {
            continue;
        };
        let mutant: Vec<String> = text
            .lines()
            .enumerate()
            .map(|(k, l)| {
                if k == i {
                    l.replacen('}', "", 1)
                } else {
                    l.to_string()
                }
            })
            .collect();
        let mutant = mutant.join("\n") + "\n";
        match parser::parse_sources(&[(name, &mutant)]) {
            Ok(()) => panic!("the parser accepts {name} with line {} broken", i + 1),
            Err(e) => assert!(
                e.contains(&format!("{name}:{}:", i + 1)),
                "{name}: expected an error at line {}, got:\n{e}",
                i + 1
            ),
        }
        return true;
    }
    false
}

/// The expected KRL programs of tests/cases/ as reviewed, not only as lmdc
/// writes them today, parse: an expected file accepted with a syntax error
/// in it would otherwise stand as the reference.
#[test]
fn expected_krl_programs_parse() {
    if !have_parser("expected_krl_programs_parse") {
        return;
    }
    let mut paths = Vec::new();
    for case in crate::cases::folders(std::path::Path::new(crate::cases::ROOT)) {
        let mut files: Vec<PathBuf> = std::fs::read_dir(&case)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| parser::is_krl_file(&p.file_name().unwrap().to_string_lossy()))
            .collect();
        files.sort();
        paths.extend(files);
    }
    assert!(paths.len() >= 8, "only {} expected KRL files", paths.len());
    if let Err(e) = parser::parse_files(&paths) {
        panic!("the KRL parser rejects an expected program:\n{e}");
    }
}
