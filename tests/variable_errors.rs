//! Seed 003's mistakes: each reported where it is made, with the existing
//! machinery and precise codes, every one of them in one run; bad tops
//! (negative, overflowing, undefined at a point, a footprint of no width) are
//! diagnostics, never panics.

use lmdc::pipeline::compile;
use proptest::prelude::*;

const WALL: &str = "examples/ramp_wall.lmd";

fn source(path: &str) -> String {
    std::fs::read_to_string(path).unwrap()
}

/// `(code, message)` of every error of a run.
fn errors(src: &str) -> Vec<(String, String)> {
    let c = compile(src, &mut ());
    let e: Vec<(String, String)> = c
        .diagnostics
        .iter()
        .filter(|d| d.is_error())
        .map(|d| (d.code.as_str().to_string(), d.message.clone()))
        .collect();
    assert_eq!(c.program.is_none(), !e.is_empty(), "{e:#?}");
    e
}

fn has(errors: &[(String, String)], code: &str, fragment: &str) -> bool {
    errors
        .iter()
        .any(|(c, m)| c == code && m.contains(fragment))
}

/// `text` with `from` replaced by `to` (which must occur).
fn edit(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "{from:?} is not in the source");
    text.replacen(from, to, 1)
}

#[test]
fn every_mistake_of_a_variable_file_in_one_run() {
    let wall = source(WALL);
    let mut src = edit(
        &wall,
        "top = 20 mm + 16 % * (x + 50 mm)",
        "top = 20 mm + layer * 1 mm + x",
    );
    src = edit(&src, "scan = auto", "scan = z");
    src = edit(&src, "tolerance = 0.1 mm", "tolerance = -1 mm");
    src = edit(&src, "power = 1000 W", "power = 1000 W\n  speed = 6 mm/s");
    src = edit(&src, "layers = auto", "layers = auto\n  offset = 3 mm");
    src = edit(&src, "part ramp_wall", "part ramp_wall\nlet tilt = 2 * y");
    let e = errors(&src);
    for (code, fragment) in [
        ("lmd::layer-outside-profile", "`top` uses `layer`"),
        ("lmd::bad-choice", "`scan` must be one of: auto, x, y"),
        ("lmd::not-positive", "`tolerance` must be greater than zero"),
        (
            "lmd::position-outside-top",
            "`y` is a point's position only inside",
        ),
        ("lmd::speed-from-bead", "take their speeds from bead `b316`"),
        ("lmd::fill-gap", "tracks 3 mm apart leave gaps"),
    ] {
        assert!(has(&e, code, fragment), "no {code} {fragment:?} in {e:#?}");
    }
    assert_eq!(e.len(), 6, "{e:#?}");
}

#[test]
fn a_top_goes_with_variable_slicing_and_a_height_with_planar() {
    let wall = source(WALL);
    let e = errors(&edit(&wall, "slicing variable {", "slicing planar {"));
    assert!(
        has(&e, "lmd::bad-choice", "planar slicing lays flat layers"),
        "{e:#?}"
    );
    let e = errors(&edit(
        &wall,
        "top = 20 mm + 16 % * (x + 50 mm)",
        "height = 20 mm",
    ));
    assert!(has(&e, "lmd::bad-choice", "this one has none"), "{e:#?}");
    let e = errors(&edit(
        &wall,
        "bead = b316\n",
        "bead = b316\n  height = 20 mm\n",
    ));
    assert!(
        has(&e, "lmd::conflicting-fields", "a `height` or a `top`"),
        "{e:#?}"
    );
}

#[test]
fn variable_layers_need_a_bead_map_and_no_styles() {
    let wall = source(WALL);
    let e = errors(&edit(
        &wall,
        "model = linear(slope = -0.135 mm / (1 mm/s), intercept = 1.82 mm)",
        "model = measured(height = 1 mm, speed = 6 mm/s)",
    ));
    assert!(
        has(&e, "lmd::bead-map-needed", "measured at one speed"),
        "{e:#?}"
    );
    let e = errors(&format!(
        "{wall}\nstyle edge {{\n  power = 900 W\n  when {{ paths = infill }}\n}}\n"
    ));
    assert!(
        has(&e, "lmd::unsupported", "variable layers take every speed"),
        "{e:#?}"
    );
}

/// The help of the first error with `code`.
fn help(src: &str, code: &str) -> String {
    let c = compile(src, &mut ());
    let d = c.diagnostics.iter().find(|d| d.code == code);
    let d = d.unwrap_or_else(|| panic!("no {code} in {:#?}", c.diagnostics));
    d.help.clone().unwrap_or_default()
}

/// Every number that follows `before` in `text` up to `after`.
fn values<'t>(text: &'t str, before: &str, after: &str) -> Vec<&'t str> {
    // The help is wrapped only when drawn: the text itself is one line.
    text.split(before)
        .skip(1)
        .filter_map(|r| r.split(after).next())
        .collect()
}

/// The layer count `src` compiles to, or its diagnostics.
fn layers_of(src: &str) -> usize {
    let c = compile(src, &mut ());
    match &c.program {
        Some(p) => p.ir().layers.len(),
        None => panic!("does not compile: {:#?}", c.diagnostics),
    }
}

#[test]
fn a_declared_layer_count_outside_the_range_names_the_range() {
    let src = edit(&source(WALL), "layers = auto", "layers = 30");
    let e = errors(&src);
    assert!(
        has(
            &e,
            "lmd::layer-height",
            "30 layers lay 0.6731 mm .. 1.194 mm"
        ),
        "{e:#?}"
    );
    // ⌈35.808/1.024⌉ = 35 … ⌊20.192/0.4543⌋ = 44: each named count builds.
    let help = help(&src, "lmd::layer-height");
    assert!(help.contains("between 35 and 44 layers"), "{help}");
    assert!(help.contains("`layers = auto` (35)"), "{help}");
    for n in [35, 44] {
        let fixed = edit(&src, "layers = 30", &format!("layers = {n}"));
        assert_eq!(layers_of(&fixed), n);
    }
    assert_eq!(layers_of(&edit(&src, "layers = 30", "layers = auto")), 35);
}

#[test]
fn a_declared_count_is_refused_in_favour_of_counts_whose_tracks_build() {
    // A wedge 15.6 mm across: its heights allow 10 to 12 layers, but at 10
    // the balanced tracks, stretched to close on the far edge, need speeds
    // outside the bead's. The help names only 11 and 12, and each builds.
    let wedge = source("examples/wedge.lmd");
    let src = edit(&wedge, "height = 15 mm", "height = 15.6 mm");
    let src = edit(&src, "layers = auto", "layers = 9");
    let help = help(&src, "lmd::layer-height");
    assert!(help.contains("use 11 or 12 layers"), "{help}");
    for n in [11, 12] {
        assert_eq!(
            layers_of(&edit(&src, "layers = 9", &format!("layers = {n}"))),
            n
        );
    }
    let e = errors(&edit(&src, "layers = 9", "layers = 10"));
    assert!(
        has(&e, "lmd::no-layer-count", "declared 10 layers"),
        "{e:#?}"
    );
}
#[test]
fn bad_tops_are_diagnostics() {
    let wall = source(WALL);
    let top = "top = 20 mm + 16 % * (x + 50 mm)";
    for (bad, code, fragment) in [
        (
            "top = 10 mm - 30 % * (x + 50 mm)",
            "lmd::top-height",
            "the top is -",
        ),
        ("top = 0 mm", "lmd::top-height", "the top is 0 mm"),
        (
            "top = 1e300 mm * 1e300 * (x + 60 mm)",
            "lmd::overflow",
            "too large",
        ),
        (
            "top = 1000 mm^2 / x",
            "lmd::top-height",
            "cannot be computed at (0, 0) mm",
        ),
        (
            "top = 20 deg",
            "lmd::unit-mismatch",
            "`top` must be a length",
        ),
        (
            "top = edges(along = z, from = 1 mm, to = 2 mm)",
            "lmd::bad-choice",
            "`along`",
        ),
        (
            "top = edges(along = x, from = -1 mm, to = 2 mm)",
            "lmd::not-positive",
            "`from`",
        ),
        (
            "top = plane(height = 20 mm, slope_x = 90 deg)",
            "lmd::out-of-range",
            "89 deg",
        ),
        (
            "top = plane(height = 20 mm, slope_x = 1e300)",
            "lmd::top-height",
            "the top is -4.880e301 mm",
        ),
    ] {
        let e = errors(&edit(&wall, top, bad));
        assert!(
            has(&e, code, fragment),
            "{bad}: no {code} {fragment:?} in {e:#?}"
        );
    }
    // A footprint of no width, and one narrower than a bead.
    for (profile, fragment) in [
        (
            "profile = outline([0 mm, 0 mm], [100 mm, 0 mm], [50 mm, 0 mm])",
            "",
        ),
        (
            "profile = rectangle(width = 100 mm, height = 1 mm)",
            "narrower than the 2.4 mm bead",
        ),
    ] {
        let src = edit(
            &wall,
            "profile = rectangle(width = 100 mm, height = 2.4 mm)",
            profile,
        );
        let e = errors(&src);
        assert!(
            !e.is_empty() && e.iter().any(|(_, m)| m.contains(fragment)),
            "{e:#?}"
        );
    }
}

#[test]
fn the_advised_tolerance_works() {
    let src = source("examples/errors/segments_too_short.lmd");
    let c = compile(&src, &mut ());
    let d = c
        .diagnostics
        .iter()
        .find(|d| d.code == "lmd::segments-too-short")
        .expect("segments too short");
    let help = d.help.clone().unwrap_or_default();
    let advised = help
        .split("`tolerance = ")
        .nth(1)
        .and_then(|r| r.split('`').next())
        .unwrap_or_else(|| panic!("no tolerance advised: {help}"));
    assert_eq!(advised, "0.098 mm", "{help}");
    let fixed = edit(
        &src,
        "tolerance = 0.05 mm",
        &format!("tolerance = {advised}"),
    );
    assert!(compile(&fixed, &mut ()).program.is_some());
}

/// Each `` `NAME = VALUE UNIT` `` the help names for the no-layer-count
/// example with `top` written in, with the count it says.
fn named(src: &str, name: &str, unit: &str) -> Vec<(String, usize)> {
    let help = help(src, "lmd::no-layer-count");
    let fixes = values(&help, &format!("`{name} = "), "; or");
    assert!(!fixes.is_empty(), "no `{name} = …` in {help}");
    fixes
        .into_iter()
        .map(|f| {
            let value = f.split(&format!(" {unit}`")).next().unwrap().to_string();
            let layers = f.split(": ").nth(1).and_then(|l| l.split(' ').next());
            (value, layers.and_then(|l| l.parse().ok()).expect(f))
        })
        .collect()
}

#[test]
fn each_fix_of_no_layer_count_works() {
    // A wall one bead wide rising 10 → 25 mm along x: its tracks run from
    // x = -48.8 to 48.8 mm and need a ratio of 2.44, the bead stacks 2.25.
    let src = source("examples/errors/no_layer_count.lmd");
    let top = "top = edges(along = x, from = 10 mm, to = 25 mm)";
    let e = errors(&src);
    assert!(
        has(&e, "lmd::no-layer-count", "10.18 mm .. 24.82 mm"),
        "{e:#?}"
    );
    // `to` keeping `from`, and `from` keeping `to`: in the file's terms.
    let [(to, n_to)] = &named(&src, "to", "mm")[..] else {
        panic!("one `to`")
    };
    let [(from, n_from)] = &named(&src, "from", "mm")[..] else {
        panic!("one `from`")
    };
    for (fixed, n) in [
        (
            format!("top = edges(along = x, from = 10 mm, to = {to} mm)"),
            n_to,
        ),
        (
            format!("top = edges(along = x, from = {from} mm, to = 25 mm)"),
            n_from,
        ),
    ] {
        assert_eq!(layers_of(&edit(&src, top, &fixed)), *n, "{fixed}");
    }
    // The values are the nearest that fit at a tenth of a millimetre.
    let nudged: f64 = to.parse::<f64>().unwrap() + 0.1;
    let e = errors(&edit(
        &src,
        top,
        &format!("top = edges(along = x, from = 10 mm, to = {nudged:.1} mm)"),
    ));
    assert!(has(&e, "lmd::no-layer-count", ""), "{e:#?}");
    // The bead reaching further: its speeds extended as the help says.
    let help = help(&src, "lmd::no-layer-count");
    let speeds = "speed = 4 mm/s .. 8.7 mm/s";
    for (fragment, range) in [
        ("speeds up to ", "4 mm/s .. {} mm/s"),
        ("speeds down to ", "{} mm/s .. 8.7 mm/s"),
    ] {
        let v = values(&help, fragment, " mm/s")[0];
        let fixed = edit(&src, speeds, &format!("speed = {}", range.replace("{}", v)));
        assert!(compile(&fixed, &mut ()).program.is_some(), "{fixed}");
    }
}

#[test]
fn a_fix_that_needs_another_declared_count_says_which() {
    // With `layers = 24` declared no `to` or `from` fits 24 layers: the
    // help names the count to declare with each, and both build.
    let src = edit(
        &source("examples/errors/no_layer_count.lmd"),
        "layers = auto",
        "layers = 24",
    );
    let help = help(&src, "lmd::no-layer-count");
    let top = "top = edges(along = x, from = 10 mm, to = 25 mm)";
    for (name, from, to) in [("to", "10 mm", "{} mm"), ("from", "{} mm", "25 mm")] {
        let fix = values(&help, &format!("`{name} = "), "`); or")[0];
        let value = fix.split(" mm`").next().unwrap();
        let n = fix.split("`layers = ").nth(1).expect(fix);
        let edges = format!(
            "top = edges(along = x, from = {}, to = {})",
            from.replace("{}", value),
            to.replace("{}", value)
        );
        let fixed = edit(
            &edit(&src, top, &edges),
            "layers = 24",
            &format!("layers = {n}"),
        );
        assert_eq!(layers_of(&fixed).to_string(), n, "{edges}");
    }
}

#[test]
fn each_fix_of_a_plane_top_works() {
    // The same wall with its top written as a plane: the height and the
    // slope that fit, each builds with the count named.
    let src = edit(
        &source("examples/errors/no_layer_count.lmd"),
        "top = edges(along = x, from = 10 mm, to = 25 mm)",
        "top = plane(at = [-50 mm, 0 mm], height = 10 mm, slope_x = 15 %)",
    );
    let [(height, n_height)] = &named(&src, "height", "mm")[..] else {
        panic!("one `height`")
    };
    let [(slope, n_slope)] = &named(&src, "slope_x", "%")[..] else {
        panic!("one `slope_x`")
    };
    for (from, to, n) in [
        ("height = 10 mm", format!("height = {height} mm"), n_height),
        ("slope_x = 15 %", format!("slope_x = {slope} %"), n_slope),
    ] {
        assert_eq!(layers_of(&edit(&src, from, &to)), *n, "{to}");
    }
}

#[test]
fn an_expression_top_is_named_where_its_tracks_run() {
    // An expression cannot be edited by the help: it names the heights
    // where the tracks run (1.2 mm inside the ends), which a top through
    // them builds with.
    let src = edit(
        &source("examples/errors/no_layer_count.lmd"),
        "top = edges(along = x, from = 10 mm, to = 25 mm)",
        "top = 10 mm + 15 % * (x + 50 mm)",
    );
    let help = help(&src, "lmd::no-layer-count");
    let high = values(
        &help,
        "a top at most ",
        " mm high where the tracks run highest",
    )[0];
    let low = values(&help, "at least ", " mm where they run lowest")[0];
    // The top's heights at the tracks' ends, x = ±48.8 mm.
    let (lo, hi) = (10.18, 24.82);
    for (a, b) in [
        (lo.to_string(), high.to_string()),
        (low.to_string(), hi.to_string()),
    ] {
        let top = format!("top = {a} mm + ({b} mm - {a} mm) * (x + 48.8 mm) / 97.6 mm");
        let fixed = edit(&src, "top = 10 mm + 15 % * (x + 50 mm)", &top);
        assert!(compile(&fixed, &mut ()).program.is_some(), "{top}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Random edits of the variable examples never panic.
    #[test]
    fn edits_of_variable_sources_do_not_panic(
        which in 0..3usize,
        at in any::<usize>(),
        len in 0..30usize,
        token in 0..12usize,
    ) {
        let files = ["examples/ramp_wall.lmd", "examples/wedge.lmd", "examples/ramp_cuboid.lmd"];
        let tokens = ["x", "y", "-", "0", "1e308", "/ x", "* y", "auto", "}", "layer", "0 mm", "%"];
        let src: Vec<char> = source(files[which])
            .replace("layers = auto", "layers = 3")
            .chars()
            .collect();
        let at = at % src.len();
        let end = (at + len).min(src.len());
        let mut edited: String = src[..at].iter().collect();
        edited.push_str(tokens[token]);
        edited.extend(&src[end..]);
        let _ = compile(&edited, &mut ());
    }
}

/// A stretched balanced layout names the footprint width that needs no
/// stretch: built with it, the warning is gone.
#[test]
fn the_footprint_a_stretch_warning_names_fits() {
    let wall = |width: &str| {
        format!(
            "part wall
bead b316 {{ width = 2.4 mm  speed = 4 mm/s .. 8.7 mm/s  model = linear(slope = -0.135 mm / (1 mm/s), intercept = 1.82 mm) }}
extrude wall {{ profile = rectangle(width = 30 mm, height = {width})  size = outer  bead = b316  top = 8 mm + 50 % * (y + 6 mm) }}
slicing variable {{ layers = auto  scan = x  segments {{ tolerance = 0.1 mm }} }}
process {{ power = 1000 W  powder = 12 g/min  defocus = 0 mm }}
machine mill {{ kind = cnc  head {{ standoff = 15 mm  nozzle = frustum(length = 45 mm, tip = 12 mm, top = 40 mm) }}  axes = 3  max_speed = 50 mm/s }}
"
        )
    };
    let h = help(&wall("12 mm"), "lmd::overlap-stretch");
    let fits = values(&h, "a footprint about ", " mm wide")[0];
    let c = compile(&wall(&format!("{fits} mm")), &mut ());
    assert!(c.program.is_some(), "{fits} mm: {:#?}", c.diagnostics);
    assert!(
        !c.diagnostics
            .iter()
            .any(|d| d.code == "lmd::overlap-stretch"),
        "{fits} mm: {:#?}",
        c.diagnostics
    );
}
