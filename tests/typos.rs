//! Mistakes a new user makes in units and comments (found by trying lmdc as
//! one): each is reported once, at the word that is wrong, with the fix —
//! not as a missing field, a constant to declare or an unclosed bracket
//! somewhere else.

use lmdc::pipeline::compile;

/// A small plate that builds; `edit` replaces text in it.
fn plate(edit: (&str, &str)) -> String {
    let src = "part plate
bead track {
  width = 2.2 mm
  model = measured(height = 0.7 mm, speed = 6 mm/s)
}
extrude block {
  profile = rectangle(width = 30 mm, height = 20 mm)
  bead = track
}
slicing planar { layers = 3  offset = 1.6 mm  contours = 1 }
process {
  speed = 6 mm/s
  power = 1500 W
  powder = 8 g/min
  defocus = -2 mm
}
machine mill { kind = cnc  head { standoff = 15 mm  nozzle = frustum(length = 45 mm, tip = 12 mm, top = 40 mm) }  axes = 3  dialect = linuxcnc  max_speed = 50 mm/s }
";
    if edit.0.is_empty() {
        return src.to_string();
    }
    assert_eq!(src.matches(edit.0).count(), 1, "{}", edit.0);
    src.replacen(edit.0, edit.1, 1)
}

/// Each error: its code, message and help.
fn errors(src: &str) -> Vec<(String, String, String)> {
    let c = compile(src, &mut ());
    c.diagnostics
        .iter()
        .filter(|d| d.is_error())
        .map(|d| {
            (
                d.code.as_str().to_string(),
                d.message.clone(),
                d.help.clone().unwrap_or_default(),
            )
        })
        .collect()
}

#[test]
fn the_plate_builds_with_its_one_line_blocks() {
    assert!(errors(&plate(("", ""))).is_empty());
}

#[test]
fn an_unknown_unit_at_the_end_of_a_line_is_an_unknown_unit() {
    // It used to start a field of its own that swallowed the next line:
    // "process needs `powder`" with `powder = 8 g/min` right below.
    let e = errors(&plate(("power = 1500 W", "power = 1.5 KW")));
    assert_eq!(e.len(), 1, "{e:#?}");
    assert_eq!(e[0].0, "lmd::unknown-unit");
    assert_eq!(e[0].1, "`KW` is not a unit lmdc knows");
    assert!(e[0].2.starts_with("did you mean `kW`?"), "{}", e[0].2);
    for (typo, meant) in [("1500 watts", "W"), ("1500 Watt", "W")] {
        let e = errors(&plate(("power = 1500 W", &format!("power = {typo}"))));
        assert_eq!(e.len(), 1, "{typo}: {e:#?}");
        assert!(
            e[0].2.starts_with(&format!("did you mean `{meant}`?")),
            "{typo}: {}",
            e[0].2
        );
    }
    // Inside a call, before its closing bracket, too.
    let e = errors(&plate(("width = 30 mm", "width = 30 MM")));
    assert_eq!(e.len(), 1, "{e:#?}");
    assert!(e[0].2.starts_with("did you mean `mm`?"), "{}", e[0].2);
}

#[test]
fn a_word_for_a_unit_in_a_compound_unit_gets_the_unit() {
    let e = errors(&plate((
        "speed = 6 mm/s\n  power",
        "speed = 6 mm/sec\n  power",
    )));
    assert_eq!(e.len(), 1, "{e:#?}");
    assert!(
        e[0].2
            .starts_with("`sec` is not a unit lmdc knows: write `s`"),
        "{}",
        e[0].2
    );
}

#[test]
fn an_unclosed_comment_is_reported_at_its_start() {
    let src = plate(("offset = 1.6 mm", "offset = 1.6 mm /* never closed"));
    let c = compile(&src, &mut ());
    let d: Vec<_> = c.diagnostics.iter().collect();
    assert_eq!(d.len(), 1, "{d:#?}");
    assert_eq!(d[0].message, "this comment is never closed");
    assert_eq!(d[0].labels[0].span.start, src.find("/*").unwrap());
}

#[test]
fn a_rotary_limit_on_a_three_axis_machine_is_refused() {
    // It was accepted and ignored, while a head_bc machine refused `a`.
    let e = errors(&plate((
        "max_speed = 50 mm/s }",
        "max_speed = 50 mm/s  limits { c = -10 deg .. 10 deg } }",
    )));
    assert_eq!(e.len(), 1, "{e:#?}");
    assert_eq!(e[0].0, "lmd::unknown-field");
    assert_eq!(e[0].1, "this machine moves X Y Z only: it has no C axis");
}

#[test]
fn a_time_out_of_range_says_which_end_it_passes() {
    let at = "defocus = -2 mm\n";
    let e = errors(&plate((at, "defocus = -2 mm\n  min_layer_time = 100 h\n")));
    assert_eq!(e.len(), 1, "{e:#?}");
    assert_eq!(e[0].0, "lmd::out-of-range");
    assert_eq!(
        e[0].1,
        "`min_layer_time` is 360000 s, more than the 3600 s lmdc allows"
    );
    let e = errors(&plate((at, "defocus = -2 mm\n  dwell = -5 s\n")));
    assert_eq!(e.len(), 1, "{e:#?}");
    assert_eq!(e[0].0, "lmd::not-positive");
    assert_eq!(e[0].1, "`dwell` is -5 s: a time cannot be negative");
    assert!(e[0].2.contains("`dwell = 5 s`"), "{}", e[0].2);
}

#[test]
fn a_name_with_a_letter_outside_ascii_says_so() {
    let src = plate(("part plate", "part plättchen"));
    let c = compile(&src, &mut ());
    let d: Vec<_> = c.diagnostics.iter().collect();
    assert_eq!(d.len(), 1, "{d:#?}");
    assert_eq!(
        d[0].help.as_deref(),
        Some("names are written with the letters a–z and A–Z, digits and `_`: `ä` is not one of them")
    );
}

#[test]
fn an_outline_on_one_line_encloses_no_area() {
    // It was reported as "the profile crosses itself at (60, 0) mm".
    let e = errors(&plate((
        "rectangle(width = 30 mm, height = 20 mm)",
        "outline([0 mm, 0 mm], [30 mm, 0 mm], [60 mm, 0 mm])",
    )));
    assert_eq!(e.len(), 1, "{e:#?}");
    assert_eq!(e[0].0, "lmd::degenerate");
    assert_eq!(
        e[0].1,
        "this outline encloses no area: its corners lie on one line"
    );
}
