//! Every error of a run at once (issue 8): mistakes planted in a valid file,
//! each in a place that no other planted mistake makes fail, are all
//! reported by one run, each once, whichever of them are planted together.

use lmdc::pipeline::compile;
use proptest::prelude::*;

/// A small valid file: a planar plate with two styles, inheritance and two
/// machines (and two sections it does not use, a place for their mistakes).
const VALID: &str = r#"part plate

let w = 39.6 mm  // 19 offsets of 2.085 mm: the raster meets the contour an offset away

section disc = circle(diameter = 30 mm)
section ring = polygon(sides = 6, circumradius = 10 mm)
profile plate = outline([0 mm, 0 mm], [w, 0 mm], [w, 20 mm], [0 mm, 20 mm])

bead track {
  width = 3 mm
  speed = 6 mm/s .. 14 mm/s
  model = linear(slope = -0.05 mm / (1 mm/s), intercept = 1.2 mm)
}

extrude block {
  profile = plate
  bead = track
}

slicing planar {
  layers = 3
  contours = 1
  infill = raster(angle = 90 deg)
}

process {
  speed = 10 mm/s
  power = 2000 W
  power_range = 1500 W .. 2500 W
  powder = 12 g/min
  defocus = 0 mm
}

style edge {
  power = 2300 W
  speed = 10.2 mm/s
  when { paths = outer_contour }
}

style short {
  power = 1700 W
  when {
    paths = infill
    shorter_than = 12 mm
  }
}

inheritance {
  band = 1 mm
  hit = 99 %
}

machine mill {
  kind = cnc
  head { standoff = 15 mm  nozzle = frustum(length = 45 mm, tip = 12 mm, top = 40 mm) }
  axes = 3
  dialect = m20
  max_speed = 100 mm/s
}

machine kr30 {
  kind = robot
  head { standoff = 15 mm  nozzle = frustum(length = 45 mm, tip = 12 mm, top = 40 mm) }
  load = load(mass = 18 kg, cog = [0 mm, 0 mm, 160 mm])
  laser = 1
  power_output = 1
  full_scale = 4000 W
  max_speed = 100 mm/s
}
"#;

/// A mistake: the text it replaces and its replacement, and what a run must
/// report for it: the code and a fragment of the message.
struct Mistake {
    find: &'static str,
    replace: &'static str,
    code: &'static str,
    says: &'static str,
}

const MISTAKES: &[Mistake] = &[
    Mistake {
        find: "  width = 3 mm\n",
        replace: "  width = 3 mm\n  nozzle = 2 mm\n",
        code: "lmd::unknown-field",
        says: "bead `track` has no field `nozzle`",
    },
    Mistake {
        find: "defocus = 0 mm",
        replace: "defocus = 0 s",
        code: "lmd::unit-mismatch",
        says: "`defocus` must be a length",
    },
    Mistake {
        find: "paths = infill",
        replace: "paths = infil",
        code: "lmd::bad-choice",
        says: "`paths` must be one of",
    },
    Mistake {
        find: "let w = 39.6 mm  // 19 offsets of 2.085 mm: the raster meets the contour an offset away\n",
        replace: "let w = 39.6 mm  // 19 offsets of 2.085 mm: the raster meets the contour an offset away\nlet w = 50 mm\n",
        code: "lmd::duplicate-name",
        says: "`w` is declared twice",
    },
    Mistake {
        find: "speed = 10.2 mm/s",
        replace: "speed = 20 mm/s",
        code: "lmd::style-speed",
        says: "style `edge` scans at 20 mm/s",
    },
    Mistake {
        find: "profile = plate",
        replace: "profile = plat",
        code: "lmd::unknown-name",
        says: "there is no profile or section called `plat`",
    },
    Mistake {
        find: "kind = cnc",
        replace: "kind = cnx",
        code: "lmd::bad-choice",
        says: "`kind` must be one of",
    },
    Mistake {
        find: "full_scale = 4000 W",
        replace: "full_scale = 4000 mm",
        code: "lmd::unit-mismatch",
        says: "`full_scale` must be a power",
    },
    Mistake {
        find: "hit = 99 %",
        replace: "hit = 150 %",
        code: "lmd::hit-range",
        says: "`hit` is the share of a track",
    },
    Mistake {
        find: "contours = 1\n",
        replace: "contours = 1 mm\n",
        code: "lmd::expected-whole-number",
        says: "`contours` must be a whole number",
    },
    Mistake {
        find: "power = 2000 W",
        replace: "power = 3000 W",
        code: "lmd::power-schedule",
        says: "the power 3000 W lies outside the laser's range",
    },
    Mistake {
        find: "power = 1700 W",
        replace: "power = 1000 W",
        code: "lmd::style-power",
        says: "style `short` sets 1000 W",
    },
    Mistake {
        find: "\ninheritance {",
        replace: "\nproces { }\n\ninheritance {",
        code: "lmd::unknown-statement",
        says: "`proces` does not start a statement",
    },
    Mistake {
        find: "diameter = 30 mm",
        replace: "diameter = -30 mm",
        code: "lmd::not-positive",
        says: "`diameter` must be greater than zero",
    },
    Mistake {
        find: "machine kr30",
        replace: "machine mill",
        code: "lmd::duplicate-name",
        says: "machine `mill` is declared twice",
    },
    Mistake {
        find: "shorter_than = 12 mm",
        replace: "shorter_than = 12 deg",
        code: "lmd::unit-mismatch",
        says: "`shorter_than` must be a length",
    },
    Mistake {
        find: "circumradius = 10 mm)",
        replace: "circumradius = 10 mm, side = 5 mm)",
        code: "lmd::conflicting-fields",
        says: "give either `circumradius` or `side`, not both",
    },
];

/// `VALID` with the mistakes `which` planted.
fn planted(which: &[usize]) -> String {
    let mut src = VALID.to_string();
    for &i in which {
        let m = &MISTAKES[i];
        src = src.replacen(m.find, m.replace, 1);
    }
    src
}

#[test]
fn the_valid_file_builds_and_each_mistake_has_its_place() {
    let c = compile(VALID, &mut ());
    assert!(c.program.is_some(), "{:?}", c.diagnostics);
    for m in MISTAKES {
        assert_eq!(VALID.matches(m.find).count(), 1, "{:?}", m.find);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn every_planted_mistake_is_reported_once(
        which in proptest::sample::subsequence((0..MISTAKES.len()).collect::<Vec<_>>(), 1..=MISTAKES.len())
    ) {
        let src = planted(&which);
        let c = compile(&src, &mut ());
        prop_assert!(c.program.is_none());
        let errors: Vec<_> = c.diagnostics.iter().filter(|d| d.is_error()).collect();
        for &i in &which {
            let m = &MISTAKES[i];
            let hits = errors
                .iter()
                .filter(|d| d.code == m.code && d.message.contains(m.says))
                .count();
            prop_assert_eq!(hits, 1, "{} {:?} in {:#?}", m.code, m.says, errors);
        }
        // Nothing else: each mistake is reported once, not cascaded.
        prop_assert_eq!(errors.len(), which.len(), "{:#?}", errors);
    }
}

/// The codes of the errors `src` gives, in source order.
fn error_codes(src: &str) -> Vec<&'static str> {
    let c = compile(src, &mut ());
    assert!(c.program.is_none());
    c.diagnostics
        .iter()
        .filter(|d| d.is_error())
        .map(|d| d.code.as_str())
        .collect()
}

#[test]
fn a_power_outside_the_laser_does_not_hide_the_machine_checks() {
    // The schedule's fault is reported once, at the declarations (not again
    // for every point), and the slow machine in the same run.
    let src = VALID
        .replacen("power = 2000 W", "power = 3000 W", 1)
        .replacen("max_speed = 100 mm/s", "max_speed = 5 mm/s", 1);
    assert_eq!(
        error_codes(&src),
        ["lmd::power-schedule", "lmd::machine-speed"]
    );
}

#[test]
fn a_spot_left_unfilled_does_not_hide_the_machine_checks() {
    let src = std::fs::read_to_string("examples/errors/unfilled_tab.lmd")
        .unwrap()
        .replacen("max_speed = 50 mm/s", "max_speed = 2 mm/s", 1);
    assert_eq!(error_codes(&src), ["lmd::fill-gap", "lmd::machine-speed"]);
}
