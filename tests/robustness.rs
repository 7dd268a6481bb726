//! No input makes lmdc panic: random edits of real sources go through the whole
//! pipeline (parse, check, slice, verify, and the back ends when it compiles).

use lmdc::back::{MemorySink, Templates};
use lmdc::pipeline::{compile, emit};
use proptest::prelude::*;

/// Sources to mutate: the example with few points (fast), and the error files.
fn corpus() -> Vec<String> {
    let duct = std::fs::read_to_string("examples/twisted_duct.lmd")
        .unwrap()
        .replace("points = 360", "points = 24");
    // The planar examples with few layers (fast), styles and inheritance.
    let tooth = std::fs::read_to_string("examples/sprocket_tooth.lmd")
        .unwrap()
        .replace("layers = 35", "layers = 3");
    let chord = std::fs::read_to_string("examples/styled_chord.lmd")
        .unwrap()
        .replace("layers = 30", "layers = 3");
    let mut v = vec![duct, tooth, chord];
    for f in [
        "bend_too_tight",
        "unit_mismatch",
        "syntax",
        "unknown_name",
        "style_errors",
        "unfilled_tab",
    ] {
        v.push(std::fs::read_to_string(format!("examples/errors/{f}.lmd")).unwrap());
    }
    v
}

/// Tokens an edit may insert: structure, operators, units, odd numbers.
const TOKENS: &[&str] = &[
    "{", "}", "(", ")", "[", "]", "=", "..", "-", "+", "*", "/", "^", ",", "\"", " ", "\n", "mm",
    "deg", "g/min", "W", "%", "0", "1", "9", "0.0", "1e308", "1e-308", "-0", "NaN", "let", "part",
    "loft", "bead", "machine", "slicing", "process", "auto", "kind", "µm", "°", "//", "/*", "é",
    "\u{0}",
];

#[derive(Clone, Debug)]
enum Edit {
    Delete(usize, usize),
    Insert(usize, usize),
    Duplicate(usize, usize),
}

fn apply(src: &str, edits: &[Edit]) -> String {
    let mut s: Vec<char> = src.chars().collect();
    for e in edits {
        let n = s.len().max(1);
        match *e {
            Edit::Delete(at, len) => {
                let at = at % n;
                let end = (at + len % 40).min(s.len());
                s.drain(at.min(s.len())..end);
            }
            Edit::Insert(at, tok) => {
                let at = (at % n).min(s.len());
                let t: Vec<char> = TOKENS[tok % TOKENS.len()].chars().collect();
                s.splice(at..at, t);
            }
            Edit::Duplicate(at, len) => {
                let at = (at % n).min(s.len());
                let end = (at + len % 60).min(s.len());
                let piece: Vec<char> = s[at..end].to_vec();
                s.splice(at..at, piece);
            }
        }
    }
    s.into_iter().collect()
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Edit::Delete(a, b)),
        (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Edit::Insert(a, b)),
        (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Edit::Duplicate(a, b)),
    ]
}

fn run(src: &str) {
    let c = compile(src, &mut ());
    // Rendering must not panic either (spans always inside the source).
    let _ = lmdc::diag::render(&c.diagnostics, "fuzz.lmd", src, false);
    assert_eq!(c.program.is_none(), c.diagnostics.has_errors());
    if let Some(p) = c.program {
        let mut sink = MemorySink::default();
        let _ = emit(&p, &Templates::builtin().unwrap(), &mut sink, &mut ());
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn mutated_sources_never_panic(which in 0usize..9, edits in prop::collection::vec(edit(), 1..6)) {
        let src = apply(&corpus()[which], &edits);
        run(&src);
    }

    #[test]
    fn arbitrary_text_never_panics(s in "\\PC{0,200}") {
        run(&s);
    }
}

#[test]
fn pathological_inputs() {
    let deep = "(".repeat(100_000);
    for src in [
        "",
        "part",
        "part x\nlet a = a",
        "part x\nlet a = b\nlet b = a",
        "let x = 1e999 mm",
        "let x = 1e200 mm * 1e200 mm * 1e200 mm",
        "let x = 2 ^ 1000",
        "let x = 0 mm / 0 mm",
        deep.as_str(),
        "part p\nsection s = circle(diameter = -1 mm)",
        "part p\nslicing normal { layers = 1e9 }",
        "\"unterminated",
        "/* unterminated comment",
    ] {
        run(src);
    }
}

/// Planar parts at the limits: many layers of a small plate, a huge plate
/// with a tiny offset, a profile that collapses on some layers, degenerate
/// arcs — each builds or fails with a diagnostic, promptly.
#[test]
fn pathological_planar_inputs() {
    let part = |profile: &str, slicing: &str| {
        format!(
            "part p\nlet w = 2.2 mm\nprofile q = {profile}\n\
             bead b {{ width = w  model = measured(height = 0.7 mm, speed = 6 mm/s) }}\n\
             extrude e {{ profile = q  bead = b }}\nslicing planar {{ {slicing} }}\n\
             process {{ power = 1500 W  powder = 8 g/min }}\n\
             machine m {{ kind = cnc  axes = 3  dialect = linuxcnc  max_speed = 50 mm/s }}\n"
        )
    };
    let square = "outline([0 mm, 0 mm], [10 mm, 0 mm], [10 mm, 10 mm], [0 mm, 10 mm])";
    for src in [
        part(square, "layers = 20000  offset = 1.6 mm  infill = raster()"),
        part(
            "outline([0 mm, 0 mm], [90000 mm, 0 mm], [90000 mm, 90000 mm], [0 mm, 90000 mm])",
            "layers = 2  offset = 0.7 mm  infill = raster(angle = 30 deg)",
        ),
        part(
            "outline([0 mm, 0 mm], [10 mm - layer * 1 mm, 0 mm], [10 mm - layer * 1 mm, 10 mm], [0 mm, 10 mm])",
            "layers = 12  offset = 1.6 mm  contours = 3  infill = raster()",
        ),
        part(
            "outline([0 mm, 0 mm], arc(to = [0 mm, 0 mm], radius = 5 mm), [1 mm, 1 mm])",
            "layers = 2  offset = 1.6 mm  infill = raster()",
        ),
        part(
            "outline([0 mm, 0 mm], [1e-9 mm, 0 mm], [1e-9 mm, 1e-9 mm])",
            "layers = 2  offset = 1.6 mm  infill = raster()",
        ),
        part(square, "layers = 2  offset = 1.6 mm  contours = 10000  infill = raster()"),
        part(square, "layers = 2  offset = 1.6 mm  chord_error = 1e-300 mm  contours = 2"),
        part(
            "ellipse(width = 0.000001 mm, height = 0.000001 mm)",
            "layers = 2  offset = 1.6 mm  infill = raster()",
        ),
        part(
            "circle(diameter = 20 mm)",
            "layers = 2  offset = 0.01 mm  infill = raster(rotate = 1e300 deg)",
        ),
    ] {
        run(&src);
    }
}
