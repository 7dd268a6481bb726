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

#[test]
fn a_declared_layer_count_outside_the_range_names_the_range() {
    let e = errors(&edit(&source(WALL), "layers = auto", "layers = 40"));
    assert!(
        has(
            &e,
            "lmd::layer-height",
            "40 layers lay 0.5048 mm .. 0.8952 mm"
        ),
        "{e:#?}"
    );
    let c = compile(
        &edit(&source(WALL), "layers = auto", "layers = 40"),
        &mut (),
    );
    let help = c
        .diagnostics
        .iter()
        .next()
        .and_then(|d| d.help.clone())
        .unwrap_or_default();
    // ⌈35.808/1.28⌉ = 28 … ⌊20.192/0.6455⌋ = 31.
    assert!(help.contains("between 28 and 31 layers"), "{help}");
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

#[test]
fn each_fix_of_no_layer_count_works() {
    // The heights named are where the tracks run, 1.2 mm inside the wall's
    // ends (10.12 .. 19.88 mm for a top from 10 to 20 mm): a top whose
    // tracks reach at most 19.2 mm, or at least 10.328 mm, builds.
    let src = source("examples/errors/no_layer_count.lmd");
    let e = errors(&src);
    assert!(
        has(&e, "lmd::no-layer-count", "10.12 mm .. 19.88 mm"),
        "{e:#?}"
    );
    let top = "top = edges(along = x, from = 10 mm, to = 20 mm)";
    for fixed in [
        "top = 10.12 mm + 9.08 mm * (x + 48.8 mm) / 97.6 mm",
        "top = 10.328 mm + 9.552 mm * (x + 48.8 mm) / 97.6 mm",
    ] {
        let c = compile(&edit(&src, top, fixed), &mut ());
        assert!(c.program.is_some(), "{fixed}: {:#?}", c.diagnostics);
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
