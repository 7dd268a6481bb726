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
    // Holes, links and seams.
    let flange = std::fs::read_to_string("examples/flange.lmd")
        .unwrap()
        .replace("layers = 6", "layers = 2");
    let mut v = vec![duct, tooth, chord, flange];
    for f in [
        "hole_faults",
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
    fn mutated_sources_never_panic(which in 0usize..11, edits in prop::collection::vec(edit(), 1..6)) {
        let src = apply(&corpus()[which], &edits);
        run(&src);
    }

    #[test]
    fn arbitrary_text_never_panics(
        chars in prop::collection::vec(any::<char>().prop_filter("printable", |c| !c.is_control()), 0..200)
    ) {
        run(&chars.into_iter().collect::<String>());
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
             machine m {{ kind = cnc  head {{ standoff = 15 mm  nozzle = frustum(length = 45 mm, tip = 12 mm, top = 40 mm) }}  axes = 3  dialect = linuxcnc  max_speed = 50 mm/s }}\n"
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
        // Holes, links and seams at their limits.
        part(
            "region(circle(diameter = 20 mm), holes = [place(circle(diameter = 1e300 mm), at = [1e300 mm, 0 mm])])",
            "layers = 2  offset = 1.6 mm  infill = raster(link = laser_on)",
        ),
        part(
            "region(circle(diameter = 20 mm), holes = [bolt_circle(circle(diameter = 1e-9 mm), count = 1000, diameter = 1e-9 mm, from = 1e300 deg)])",
            "layers = 2  offset = 1.6 mm  contours = 2  infill = raster(link = laser_off)",
        ),
        part(
            "place(region(square(side = 30 mm), holes = [square(side = 30 mm - layer * 1 mm)]), at = [1e5 mm, 0 mm], turn = 1e300 deg)",
            "layers = 20  offset = 1.6 mm  infill = raster(link = laser_on)  seam = rotating(step = 1e300 deg, from = -1e300 deg)",
        ),
        part(
            "region(outline([0 mm, 0 mm], [40 mm, 0 mm], [40 mm, 40 mm], [0 mm, 40 mm]), holes = [outline([10 mm, 10 mm], [30 mm, 30 mm], [30 mm, 10 mm], [10 mm, 30 mm])])",
            "layers = 2  offset = 1.6 mm  contours = 1  infill = raster(link = laser_on)  seam = random(seed = 4294967295)",
        ),
        part(
            "region(circle(diameter = 40 mm), holes = [circle(diameter = 39.999999 mm)])",
            "layers = 2  offset = 1.6 mm  contours = 3  infill = raster(angle = 45 deg, link = laser_off)  seam = sharpest_corner",
        ),
    ] {
        run(&src);
    }
}

// ---------------------------------------------------------------------------
// Deep and long inputs. These run the `lmdc` binary: a stack overflow aborts
// the process it happens in, and must fail one test, not kill the runner.

use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// What `lmdc check` did with a source.
struct Checked {
    code: Option<i32>,
    stderr: String,
    took: Duration,
}

/// Runs `lmdc check` on `src` (through a file), killing it after `limit`.
fn check_binary(tag: &str, src: &str, limit: Duration) -> Checked {
    let dir = std::env::temp_dir().join(format!("lmdc-robust-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join(format!("{tag}.lmd"));
    std::fs::write(&file, src).unwrap();
    let start = Instant::now();
    let mut child = Command::new(env!("CARGO_BIN_EXE_lmdc"))
        .arg("check")
        .arg(&file)
        .env("NO_COLOR", "1")
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stderr = child.stderr.take().unwrap();
    let reader = std::thread::spawn(move || {
        let mut s = Vec::new();
        let _ = std::io::Read::read_to_end(&mut stderr, &mut s);
        s
    });
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{tag}: lmdc check ran longer than {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let took = start.elapsed();
    let stderr = String::from_utf8_lossy(&reader.join().unwrap()).into_owned();
    let _ = std::fs::remove_file(&file);
    Checked {
        code: status.code(),
        stderr,
        took,
    }
}

/// lmdc answered with diagnostics or success: no crash, no panic, nothing
/// but text on the terminal.
fn assert_answered(tag: &str, c: &Checked) {
    let head: String = c.stderr.chars().take(3000).collect();
    assert!(
        matches!(c.code, Some(0) | Some(1)),
        "{tag}: exit status {:?} (a signal, a panic or a usage error)\n{head}",
        c.code
    );
    assert!(!c.stderr.contains("panicked"), "{tag}: panicked\n{head}");
    assert!(
        !c.stderr.contains("overflowed its stack") && !c.stderr.contains("stack overflow"),
        "{tag}: stack overflow\n{head}"
    );
    if let Some(bad) = c.stderr.chars().find(|&ch| {
        ch.is_control() && !matches!(ch, '\n' | '\t') || matches!(ch, '\u{202a}'..='\u{202e}')
    }) {
        panic!("{tag}: lmdc printed the control character {bad:?}:\n{head}");
    }
}

/// A small planar part that builds in a moment, with `extra` appended.
fn small_part(extra: &str) -> String {
    format!(
        "part p\nlet w = 2.2 mm\n\
         profile q = outline([0 mm, 0 mm], [10 mm, 0 mm], [10 mm, 10 mm], [0 mm, 10 mm])\n\
         bead b {{ width = w  model = measured(height = 0.7 mm, speed = 6 mm/s) }}\n\
         extrude e {{ profile = q  bead = b }}\n\
         slicing planar {{ layers = 2  offset = 1.6 mm  infill = raster() }}\n\
         process {{ power = 1500 W  powder = 8 g/min }}\n\
         machine m {{ kind = cnc  head {{ standoff = 15 mm  nozzle = frustum(length = 45 mm, tip = 12 mm, top = 40 mm) }}  axes = 3  dialect = linuxcnc  max_speed = 50 mm/s }}\n{extra}\n"
    )
}

/// The cases of issue 9, each of which aborted with a stack overflow.
#[test]
fn long_chains_are_refused_with_a_diagnostic() {
    let minus = format!("let a = {}1\n", "-".repeat(9300));
    let plus = format!("let a = 1{}\n", " + 1".repeat(20_000));
    let pow = format!("let a = 1{}\n", " ^ 1".repeat(20_000));
    let range = format!("let a = 1 mm{}\n", " .. 1 mm".repeat(20_000));
    let mul = format!("let a = 1{}\n", " * 1".repeat(20_000));
    let div = format!("let a = 1{}\n", " / 1".repeat(20_000));
    let signs = format!("let a = {}1\n", "+-".repeat(10_000));
    let nested = format!("let a = 1 mm + {}(1 mm)\n", "-".repeat(300));
    for (tag, extra) in [
        ("minus", &minus),
        ("plus", &plus),
        ("pow", &pow),
        ("range", &range),
        ("mul", &mul),
        ("div", &div),
        ("signs", &signs),
        ("nested", &nested),
    ] {
        let c = check_binary(tag, &small_part(extra), Duration::from_secs(60));
        assert_answered(tag, &c);
        assert_eq!(c.code, Some(1), "{tag}:\n{}", c.stderr);
        assert!(
            c.stderr.contains("lmd::deep-expression") && c.stderr.contains("at most 256"),
            "{tag}:\n{}",
            c.stderr
        );
    }
}

/// 6 500 constants, each using the one before (and the same written in
/// reverse), are computed: the constants are evaluated in the order they use
/// each other, not by recursion.
#[test]
fn long_chains_of_constants_are_computed() {
    let duct = std::fs::read_to_string("examples/twisted_duct.lmd")
        .unwrap()
        .replace("points = 360", "points = 24");
    let mut chain: Vec<String> = vec!["let c0 = 0 mm".into()];
    chain.extend((1..6500).map(|i| format!("let c{i} = c{} + 0 mm", i - 1)));
    for (tag, lets) in [
        ("forward", chain.join("\n")),
        (
            "reverse",
            chain.iter().rev().cloned().collect::<Vec<_>>().join("\n"),
        ),
    ] {
        let src = duct.replace(
            "let R1 = 250 mm",
            &format!("{lets}\nlet R1 = c6499 + 250 mm"),
        );
        let c = check_binary(tag, &src, Duration::from_secs(120));
        assert_answered(tag, &c);
        assert_eq!(c.code, Some(0), "{tag}:\n{}", c.stderr);
    }
}

/// Deep brackets of every kind, long blocks, many statements: refused at 64
/// brackets, accepted below.
#[test]
fn deep_brackets_of_every_kind() {
    for (tag, open, close) in [
        ("paren", "(", ")"),
        ("list", "[", "]"),
        ("call", "f(", ")"),
        ("named", "f(x = ", ")"),
    ] {
        for (n, ok) in [(60, true), (100, false), (20_000, false)] {
            let src = small_part(&format!(
                "let a = {}1 mm{}",
                open.repeat(n),
                close.repeat(n)
            ));
            let c = check_binary(tag, &src, Duration::from_secs(60));
            assert_answered(tag, &c);
            assert_eq!(
                c.stderr.contains("lmd::too-deep"),
                !ok,
                "{tag} {n}:\n{}",
                c.stderr
            );
        }
    }
    let blocks = format!("style s {}{}", "{ a ".repeat(20_000), "}".repeat(20_000));
    let c = check_binary("blocks", &small_part(&blocks), Duration::from_secs(60));
    assert_answered("blocks", &c);
    assert!(c.stderr.contains("lmd::too-deep"), "{}", c.stderr);
}

/// 32 000 unknown statements: every one is found, a hundred are drawn, the
/// rest counted, in linear time (this took 12–29 s before, 64 000 a minute).
#[test]
fn thousands_of_errors_render_promptly() {
    let mut src = String::from("part p\n");
    for i in 0..32_000 {
        src.push_str(&format!("foo{i} = 1\n"));
    }
    let c = check_binary("many-errors", &src, Duration::from_secs(60));
    assert_answered("many-errors", &c);
    assert!(
        c.stderr.contains("and 31") && c.stderr.contains("more not shown"),
        "{}",
        &c.stderr[c.stderr.len().saturating_sub(500)..]
    );
    assert!(c.stderr.contains("errors in"), "{}", c.stderr);
    // A hundred reports drawn: the missing statements' errors (at the top of
    // the file, so first in source order) and unknown statements.
    let drawn = c.stderr.lines().filter(|l| l.starts_with("lmd::")).count();
    assert_eq!(drawn, 100, "{}", &c.stderr[..2000.min(c.stderr.len())]);
    assert!(c.stderr.matches("lmd::unknown-statement").count() >= 90);
    eprintln!("32 000 errors checked and rendered in {:?}", c.took);

    // The same on one line of 1 MB: each report draws a cut of the line.
    let one_line: String = (0..64_000).map(|i| format!("foo{i} = 1 ")).collect();
    let c = check_binary(
        "one-line",
        &format!("part p {one_line}"),
        Duration::from_secs(60),
    );
    assert_answered("one-line", &c);
    assert!(c.stderr.len() < 200_000, "{} bytes", c.stderr.len());
}

/// Drawing every one of 32 000 reports (no cap) takes time linear in their
/// number: the source's lines are indexed once, not scanned per report.
#[test]
fn rendering_is_linear() {
    let mut src = String::from("part p\n");
    for i in 0..32_000 {
        src.push_str(&format!("foo{i} = 1\n"));
    }
    let diags = compile(&src, &mut ()).diagnostics;
    assert!(diags.error_count() >= 32_000);
    let start = Instant::now();
    let text = lmdc::diag::render_at_most(&diags, "many.lmd", &src, false, usize::MAX);
    let took = start.elapsed();
    assert_eq!(text.matches("lmd::unknown-statement").count(), 32_000);
    assert!(text.contains("many.lmd:32001:1"), "the last report");
    eprintln!("32 000 reports drawn in {took:?}");
    assert!(took < Duration::from_secs(30), "{took:?}");
}

/// The deepest expressions and nestings the parser accepts are evaluated in a
/// 2 MiB thread (the test harness' default, and far less than the binary's),
/// in this debug build: the limits fit the stack with room to spare.
#[test]
fn the_limits_fit_a_small_stack() {
    let depth = lmdc::syntax::MAX_EXPR_DEPTH;
    let nest = lmdc::syntax::MAX_NESTING;
    let cases = vec![
        format!("let a = {}1 mm", "-".repeat(depth)),
        format!("let a = 1 mm{}", " + 1 mm".repeat(depth)),
        format!("let a = 2{}", " ^ 1".repeat(depth)),
        // Brackets and operators together, up to the limit.
        format!("let a = {}1{}", "-(".repeat(nest / 2), ")".repeat(nest / 2))
            + &" * 1".repeat(depth - nest),
        format!("let a = {}1 mm{}", "[".repeat(nest), "]".repeat(nest)),
        format!(
            "style s {}{}",
            "{ a ".repeat(nest - 1),
            "}".repeat(nest - 1)
        ),
        // A chain of constants that follow the layer, on top of a deep
        // expression: evaluated lazily, once per layer, one inside another.
        layer_chain(depth - 10, 127),
    ];
    for src in cases {
        let worker = std::thread::Builder::new()
            .stack_size(2 << 20)
            .spawn(move || {
                let c = compile(&src, &mut ());
                let _ = lmdc::diag::render(&c.diagnostics, "deep.lmd", &src, false);
                c.diagnostics
                    .iter()
                    .filter(|d| {
                        matches!(
                            d.code,
                            lmdc::diag::Code::TooDeep | lmdc::diag::Code::DeepExpression
                        )
                    })
                    .count()
            })
            .unwrap();
        assert_eq!(worker.join().unwrap(), 0, "a limit refused what it allows");
    }
}

/// A part whose profile uses the last of `n` constants, each using the one
/// before, the first of which follows the layer through `signs` minus signs:
/// re-evaluated lazily on each layer, through the whole chain.
fn layer_chain(signs: usize, n: usize) -> String {
    let lets: Vec<String> = (1..=n)
        .map(|i| format!("let k{i} = k{} + 0 mm", i - 1))
        .collect();
    small_part("").replace("[10 mm, 0 mm]", &format!("[10 mm + k{n} * 0, 0 mm]"))
        + &format!(
            "let k0 = layer * {}1 mm\n{}\n",
            "-".repeat(signs),
            lets.join("\n")
        )
}

/// Past the limits, evaluation stops with a diagnostic, in a small stack.
#[test]
fn constant_chains_past_the_limit_are_refused() {
    let worker = std::thread::Builder::new()
        .stack_size(2 << 20)
        .spawn(|| {
            let mut codes = Vec::new();
            for src in [layer_chain(1, 300), layer_chain(250, 200)] {
                let c = compile(&src, &mut ());
                let _ = lmdc::diag::render(&c.diagnostics, "chain.lmd", &src, false);
                codes.push(
                    c.diagnostics
                        .iter()
                        .map(|d| (d.code, d.message.clone()))
                        .collect::<Vec<_>>(),
                );
            }
            codes
        })
        .unwrap();
    for diags in worker.join().unwrap() {
        assert!(
            diags
                .iter()
                .any(|(c, _)| *c == lmdc::diag::Code::ConstantChain),
            "{diags:?}"
        );
    }
}

/// Characters a terminal would act on (escape sequences, bell, C1 controls,
/// bidirectional overrides), in every string field: lmdc checks the file and
/// draws its diagnostics without printing one of them.
#[test]
fn control_characters_never_reach_the_terminal() {
    for bad in [
        "\x1b[31m\x1b]0;owned\x07",
        "\0",
        "\x7f",
        "\u{9b}2J",
        "\u{202e}txt",
        "a\rb",
    ] {
        let src = small_part("")
            .replace("part p", &format!("part \"{bad}\""))
            .replace("machine m {", &format!("machine \"m{bad}\" {{ laser_on = \"{bad}\" laser_off = \"{bad}\" preamble = [\"{bad}\"] postamble = [\"{bad}\"] tcp_on = \"{bad}\""))
            + &format!("let {bad} = 1\nlet z = \"{bad}\" + 1\n{bad}\n");
        let c = check_binary("control", &src, Duration::from_secs(60));
        assert_answered(&format!("{bad:?}"), &c);
    }
}

/// Generated adversarial shapes: deep nesting and long chains of every
/// operator and bracket, long chains of constants in both orders, huge and
/// tiny numbers and control characters in every field. lmdc answers each
/// with diagnostics or a program, in bounded time.
mod generated {
    use super::*;

    const OPS: &[&str] = &[" + ", " - ", " * ", " / ", " ^ ", " .. ", "-", "+", " - -"];
    const OPENS: &[(&str, &str)] = &[("(", ")"), ("[", "]"), ("f(", ")"), ("min(", ")")];
    const NUMBERS: &[&str] = &[
        "1e308",
        "1e-308",
        "1e309",
        "0.0",
        "4e-324",
        "99999999999999999999999999999999",
        "0.000000000000000000000000000000000001",
        "1e16",
        "1e-16",
        "18446744073709551616",
    ];
    const UNITS: &[&str] = &["", " mm", " mm/s", " W", " g/min", " deg", " %", " um"];
    const STRINGS: &[&str] = &[
        "\x1b[2J", "\u{0}", "\u{7}", "\u{85}", "\u{202e}", "\t", "\x08\x08", "",
    ];
    const FIELDS: &[(&str, &str)] = &[
        ("width = w", "width = {}"),
        ("height = 0.7 mm", "height = {}"),
        ("speed = 6 mm/s", "speed = {}"),
        ("layers = 2", "layers = {}"),
        ("offset = 1.6 mm", "offset = {}"),
        ("power = 1500 W", "power = {}"),
        ("powder = 8 g/min", "powder = {}"),
        ("max_speed = 50 mm/s", "max_speed = {}"),
        ("[10 mm, 10 mm]", "[{}, 10 mm]"),
    ];

    fn shape() -> impl Strategy<Value = String> {
        prop_oneof![
            // A chain of one operator, up to far past the limit.
            (0..OPS.len(), 0usize..30_000).prop_map(|(o, n)| {
                format!("let g = 1 mm{}", format!("{}1 mm", OPS[o]).repeat(n))
            }),
            // Signs in front.
            (0usize..20_000, any::<bool>()).prop_map(|(n, plus)| {
                format!("let g = {}1 mm", if plus { "+-" } else { "-" }.repeat(n))
            }),
            // Brackets of one kind.
            (0..OPENS.len(), 0usize..5_000).prop_map(|(k, n)| {
                let (o, c) = OPENS[k];
                format!("let g = {}1 mm{}", o.repeat(n), c.repeat(n))
            }),
            // Brackets and operators mixed.
            (0usize..200, 0usize..200).prop_map(|(b, n)| {
                format!(
                    "let g = {}1 mm{}{}",
                    "-(".repeat(b),
                    ")".repeat(b),
                    " + 1 mm".repeat(n)
                )
            }),
            // Blocks.
            (0usize..5_000).prop_map(|n| format!("style s {}{}", "{ a ".repeat(n), "}".repeat(n))),
            // Constants, each using the next, in either order.
            (0usize..8_000, any::<bool>(), 0..OPS.len()).prop_map(|(n, rev, o)| {
                let mut v: Vec<String> = vec!["let h0 = 1 mm".into()];
                v.extend(
                    (1..=n).map(|i| {
                        format!("let h{i} = h{}{}0 mm", i - 1, OPS[o].trim_end_matches('-'))
                    }),
                );
                if rev {
                    v.reverse();
                }
                v.join("\n")
            }),
            // A cycle through many constants.
            (2usize..3_000).prop_map(|n| {
                (0..n)
                    .map(|i| format!("let y{i} = y{} + 1 mm", (i + 1) % n))
                    .collect::<Vec<_>>()
                    .join("\n")
            }),
        ]
    }

    fn number() -> impl Strategy<Value = String> {
        (0..NUMBERS.len(), 0..UNITS.len(), any::<bool>()).prop_map(|(n, u, neg)| {
            format!("{}{}{}", if neg { "-" } else { "" }, NUMBERS[n], UNITS[u])
        })
    }

    fn with_field(field: usize, value: &str) -> String {
        let (from, to) = FIELDS[field];
        small_part("").replace(from, &to.replace("{}", value))
    }

    fn strings() -> impl Strategy<Value = String> {
        (0..STRINGS.len(), 0..STRINGS.len()).prop_map(|(a, b)| {
            let (a, b) = (STRINGS[a], STRINGS[b]);
            small_part("")
                .replace("part p", &format!("part \"p{a}\""))
                .replace(
                    "machine m {",
                    &format!(
                        "machine \"m{b}\" {{ laser_on = \"M3{a}\" laser_off = \"{b}\" \
                         preamble = [\"G21{a}\", \"{b}\"] postamble = [\"M2{b}\"] \
                         tcp_on = \"{a}\" tcp_off = \"{b}\""
                    ),
                )
                .replace("bead b {", &format!("bead \"b{a}\" {{"))
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 24, failure_persistence: None, ..ProptestConfig::default() })]

        #[test]
        fn deep_and_long_shapes(s in shape()) {
            let c = check_binary("shape", &small_part(&s), Duration::from_secs(60));
            assert_answered(&s.chars().take(80).collect::<String>(), &c);
        }

        #[test]
        fn huge_and_tiny_numbers(field in 0..FIELDS.len(), v in number()) {
            let src = with_field(field, &v);
            let c = check_binary("number", &src, Duration::from_secs(60));
            assert_answered(&format!("{} = {v}", FIELDS[field].0), &c);
        }

        #[test]
        fn control_characters_in_string_fields(src in strings()) {
            let c = check_binary("strings", &src, Duration::from_secs(60));
            assert_answered(&format!("{src:?}"), &c);
        }
    }
}

/// A plate of 20 m × 20 m lays 250 km of track a layer in few points: the
/// stacking check once cut it into pieces a few millimetres long and held
/// them all (24 GB before the kernel killed it). Checked under a 1 GiB
/// address-space limit, which the run must stay within.
#[test]
fn a_huge_plate_is_checked_in_bounded_memory() {
    let src = small_part("")
        .replace(
            "outline([0 mm, 0 mm], [10 mm, 0 mm], [10 mm, 10 mm], [0 mm, 10 mm])",
            "rectangle(width = 20 m, height = 20 m)",
        )
        .replace("layers = 2", "layers = 3");
    let dir = std::env::temp_dir().join(format!("lmdc-plate-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("plate.lmd");
    std::fs::write(&file, &src).unwrap();
    let out = Command::new("sh")
        .arg("-c")
        .arg("ulimit -v 1048576 && exec \"$0\" check \"$1\"")
        .arg(env!("CARGO_BIN_EXE_lmdc"))
        .arg(&file)
        .env("NO_COLOR", "1")
        .output()
        .unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let stderr = String::from_utf8_lossy(&out.stderr);
    // The plate is larger than the machine: the axis limits say so, and
    // nothing else fails.
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("lmd::axis-limit"), "{stderr}");
    assert!(!stderr.contains("memory allocation"), "{stderr}");
}

/// A robot's head left with no solids (its `nozzle` and `body` lines
/// commented out, as a mutation once did): refused for the missing
/// nozzle, and the arm's check, which still runs to report every error
/// together, measures no body of none (it indexed past the links).
#[test]
fn a_robot_head_without_solids_is_refused_not_a_panic() {
    let src = std::fs::read_to_string("examples/twisted_duct.lmd")
        .unwrap()
        .replace("points = 360", "points = 24")
        .replace("    nozzle = frustum(", "    // nozzle = frustum(")
        .replace("    body = cylinder(", "    // body = cylinder(");
    let c = compile(&src, &mut ());
    assert!(c.program.is_none());
    assert!(
        c.diagnostics
            .iter()
            .any(|d| d.message.contains("`head` needs `nozzle`")),
        "{:?}",
        c.diagnostics.iter().map(|d| &d.message).collect::<Vec<_>>()
    );
}
