//! Code a help text shows is code a user can copy: every snippet in
//! backticks that looks like code (it has `=`, `{` or `(`) parses, as a
//! statement, as a field inside a block, or as a value (issue 9 item 7).
//! `…` in a snippet stands for "a value here".

use lmdc::pipeline::compile;
use lmdc::syntax::parse;

/// Small files that make the checker give its help texts: every statement
/// missing, every statement in the wrong shape, and fields in the wrong shape.
const SOURCES: &[&str] = &[
    "",
    "part p = 1\nlet x { }\nsection s { }\nprofile q { }\nbead b = 1\nloft l = 1\nslicing = 1\nprocess p\nstyle s = 1\ninheritance x\nmachine m = 1",
    "extrude e = 1\nslicing { }\nmachine m { }",
    "part p\nbead b { width = 2 mm  speed { }  model = 1 }\nextrude e { profile = 1  bead = 2 }\nslicing planar { contours = 0  infill = 1 }\nprocess { power = layer * 1 W  powder = 1 }\nmachine m { kind = cnc  axes = 4  preamble = 1  kinematics = head_ac }",
    "part p\nsection a = polygon(sides = 6)\nloft l { from = 1  to = a  spine = 1  morph = superellipse  wall = b }\nslicing normal { points = 10  chord_error = 1 mm }\nprocess { power = 1 W  powder = 1 g/min }\nstyle s { when { } }\ninheritance { }\nmachine m { kind = robot  home = 1 }",
];

/// The snippets of a help text that look like code.
fn snippets(help: &str) -> Vec<String> {
    help.split('`')
        .skip(1)
        .step_by(2)
        .filter(|s| s.contains(['=', '{', '(']))
        .map(str::to_string)
        .collect()
}

/// Whether `code` parses as one of the forms a help text shows.
fn parses(code: &str) -> bool {
    let code = code.replace("= …", "= 1").replace('…', "x");
    [
        code.clone(),
        format!("b {{ {code} }}"),
        format!("let x = {code}"),
    ]
    .iter()
    .any(|src| parse(src).is_ok())
}

#[test]
fn code_in_help_texts_parses() {
    let mut sources: Vec<String> = SOURCES.iter().map(|s| s.to_string()).collect();
    for e in std::fs::read_dir("examples/errors").unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x == "lmd") {
            sources.push(std::fs::read_to_string(p).unwrap());
        }
    }
    let mut checked = std::collections::BTreeSet::new();
    let mut bad = Vec::new();
    for src in &sources {
        for d in compile(src, &mut ()).diagnostics.iter() {
            for s in snippets(d.help.as_deref().unwrap_or("")) {
                if checked.insert(s.clone()) && !parses(&s) {
                    bad.push((d.code.as_str(), s));
                }
            }
        }
    }
    assert!(
        bad.is_empty(),
        "help texts whose code does not parse: {bad:#?}"
    );
    // The sources above reach this many distinct snippets: a test that
    // checks none would pass for nothing.
    assert!(
        checked.len() >= 25,
        "only {} snippets: {checked:#?}",
        checked.len()
    );
}

#[test]
fn the_snippet_check_rejects_what_the_parser_rejects() {
    assert!(parses("process { powder = 45.9 g/min  power = 2100 W }"));
    assert!(!parses("process { powder = 45.9 g/min, power = 2100 W }"));
    assert!(parses("speed = 6 mm/s"));
    assert!(parses("ramp(from = …, to = …, layers = …)"));
}
