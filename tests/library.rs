//! The library's front door (`lmdc::compile`, docs/testing.md) and the
//! worked property of examples/laser_property.rs, over every example and,
//! with proptest, over swept `--set` values of the flange.

#[path = "../examples/laser_property.rs"]
#[allow(dead_code)]
mod laser_property;

/// docs/testing.md's crate of one's own: its test, compiled here as a
/// user's crate compiles it (lmdc's public API only) and run.
#[path = "../examples/my-parts/tests/flange.rs"]
mod my_parts;

use lmdc::diag::Code;
use proptest::prelude::*;

/// The code block of docs/testing.md that opens with `first`.
fn testing_md_block(doc: &str, lang: &str, first: &str) -> String {
    let open = format!("```{lang}\n{first}\n");
    let start = doc.find(&open).unwrap_or_else(|| panic!("no {open:?}")) + lang.len() + 4;
    let end = start + doc[start..].find("```").unwrap();
    doc[start..end].to_string()
}

/// docs/testing.md's two files are examples/my-parts' (its manifest with
/// lmdc at `../..`, in the checkout, for `../lmdc`, beside it), and Cargo
/// takes that manifest: copied beside a lock file of lmdc's with lmdc by
/// its absolute path, `cargo tree --offline` resolves lmdc and proptest.
/// A manifest Cargo refuses (no target of the crate's own: a crate of
/// tests alone is one), or a dependency lmdc's lock does not hold, fails.
#[test]
fn the_crate_of_ones_own_is_examples_my_parts_and_cargo_takes_it() {
    let doc = std::fs::read_to_string("docs/testing.md").unwrap();
    let read = |p: &str| std::fs::read_to_string(p).unwrap_or_else(|e| panic!("{p}: {e}"));
    let manifest = testing_md_block(&doc, "toml", "# my-parts/Cargo.toml");
    let test = testing_md_block(&doc, "rust", "// my-parts/tests/flange.rs");
    assert_eq!(
        manifest.replace("\"../lmdc\"", "\"../..\""),
        read("examples/my-parts/Cargo.toml")
    );
    assert_eq!(test, read("examples/my-parts/tests/flange.rs"));
    let dir = tempfile::tempdir().unwrap();
    let root = std::env::current_dir().unwrap();
    let here = |p: &str| dir.path().join(p);
    let lmdc = format!("{:?}", root.display().to_string());
    std::fs::write(here("Cargo.toml"), manifest.replace("\"../lmdc\"", &lmdc)).unwrap();
    std::fs::copy("Cargo.lock", here("Cargo.lock")).unwrap();
    for d in ["src", "tests", "parts"] {
        std::fs::create_dir(here(d)).unwrap();
    }
    std::fs::copy("examples/my-parts/src/lib.rs", here("src/lib.rs")).unwrap();
    std::fs::write(here("tests/flange.rs"), &test).unwrap();
    std::fs::copy("examples/flange.lmd", here("parts/flange.lmd")).unwrap();
    let out = std::process::Command::new(option_env!("CARGO").unwrap_or("cargo"))
        .args(["tree", "--offline", "-e", "normal,dev", "--depth", "1"])
        .current_dir(dir.path())
        .output()
        .unwrap();
    let tree = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(tree.starts_with("my-parts v0.1.0"), "{tree}");
    assert!(
        tree.contains(&format!("lmdc v{}", env!("CARGO_PKG_VERSION"))),
        "{tree}"
    );
    assert!(tree.contains("proptest v1."), "{tree}");
}

#[test]
fn the_laser_is_on_for_deposits_only_on_every_example() {
    let mut n = 0;
    for f in [
        "flange",
        "ramp_cuboid",
        "ramp_wall",
        "segmented_ring",
        "sprocket_tooth",
        "styled_chord",
        "wedge",
    ] {
        let src = std::fs::read_to_string(format!("examples/{f}.lmd")).unwrap();
        let broken = laser_property::check(&src, &lmdc::Options::default()).unwrap();
        assert!(broken.is_empty(), "{f}: {broken:?}");
        n += 1;
    }
    assert_eq!(n, 7);
}

/// The property can fail: a travel with the laser on, and a deposit with
/// it off, are both caught.
#[test]
fn the_property_catches_a_laser_left_on() {
    use lmdc::plan::{Move, MoveKind, Speed, Visit, Where};
    let mv = |kind| Move {
        kind,
        to: [0.0; 3],
        normal: [0.0, 0.0, 1.0],
        axes: Default::default(),
        speed: Speed::Rapid,
        power: 0.0,
        at: Where::Point {
            layer: 0,
            path: 0,
            point: 0,
        },
    };
    let mut l = laser_property::Laser::default();
    l.laser_on(&mv(MoveKind::Deposit));
    l.motion(&mv(MoveKind::Deposit));
    l.motion(&mv(MoveKind::Travel));
    l.laser_off();
    l.motion(&mv(MoveKind::Deposit));
    assert_eq!(l.broken.len(), 2, "{:?}", l.broken);
}

#[test]
fn compile_reports_what_the_options_get_wrong() {
    let src = std::fs::read_to_string("examples/flange.lmd").unwrap();
    let machine = lmdc::Options {
        machine: Some("nope".into()),
        ..Default::default()
    };
    let d = lmdc::compile(&src, &machine).err().unwrap();
    assert_eq!(d.iter().next().unwrap().code, Code::NoSuchMachine);
    let set = lmdc::Options {
        set: vec!["OD=3 deg".parse().unwrap()],
        ..Default::default()
    };
    let d = lmdc::compile(&src, &set).err().unwrap();
    assert_eq!(d.iter().next().unwrap().code, Code::BadSet);
    // A machine refused for its own mistake is reported for it, not as
    // unknown, when it is the one asked for; an unknown name lists it.
    let bad_mill = src.replacen("  work_offset = 1 ", "  work_offset = 9 ", 1);
    let mill = lmdc::Options {
        machine: Some("mill3".into()),
        ..Default::default()
    };
    let d = lmdc::compile(&bad_mill, &mill).err().unwrap();
    let codes: Vec<Code> = d.iter().map(|d| d.code).collect();
    assert_eq!(codes, [Code::CountRange], "{d:?}");
    assert!(d.iter().next().unwrap().message.contains("work_offset"));
    let d = lmdc::compile(&bad_mill, &machine).err().unwrap();
    let first = d.iter().next().unwrap();
    assert_eq!(first.code, Code::NoSuchMachine);
    assert!(first.message.contains("mill3, kr30"), "{}", first.message);
    let broken = src.replacen("let OD = 80 mm", "let OD = 80 deg", 1);
    let d = lmdc::compile(&broken, &lmdc::Options::default())
        .err()
        .unwrap();
    assert!(d.has_errors());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(6))]
    /// A sweep of the flange's outside diameter: where it compiles, the
    /// property holds on both machines.
    #[test]
    fn the_property_holds_over_a_sweep(od in 70.0f64..95.0) {
        let src = std::fs::read_to_string("examples/flange.lmd").unwrap();
        let options = lmdc::Options {
            set: vec![format!("OD={od:.2} mm").parse().unwrap()],
            ..Default::default()
        };
        if let Ok(broken) = laser_property::check(&src, &options) {
            prop_assert!(broken.is_empty(), "{:?}", broken);
        }
    }
}

/// The flange's design solid, as its drawing gives it (not as lmdc models
/// it): a disc of diameter `od` with a 30 mm bore and six 9 mm holes on a
/// 60 mm circle from 30°. How far `p` lies inside it in plan, mm
/// (negative: outside).
fn inside_flange(p: [f64; 3], od: f64) -> f64 {
    let r = p[0].hypot(p[1]);
    let holes = (0..6).map(|k| {
        let a = (30.0 + 60.0 * k as f64).to_radians();
        (p[0] - 30.0 * a.cos()).hypot(p[1] - 30.0 * a.sin()) - 4.5
    });
    holes.fold((od / 2.0 - r).min(r - 15.0), f64::min)
}

/// The least margin by which the deposit points of `ir` (the points of a
/// path the laser is on between) lie inside the flange's design solid, and
/// where.
fn least_margin(ir: &lmdc::ir::Program, od: f64) -> (f64, String) {
    let mut least = (f64::INFINITY, String::new());
    for (l, layer) in ir.layers.iter().enumerate() {
        for (k, path) in layer.paths.iter().enumerate() {
            for (i, w) in path.points.windows(2).enumerate() {
                if !w[0].laser_on {
                    continue;
                }
                for (j, p) in [(i, w[0]), (i + 1, w[1])] {
                    // It stands on the plate (z = 0); the drawing leaves its
                    // height to the layers.
                    let m = if p.pos[2] < 0.0 {
                        p.pos[2]
                    } else {
                        inside_flange(p.pos, od)
                    };
                    if m < least.0 {
                        least = (m, format!("layer {l} path {k} point {j} at {:?}", p.pos));
                    }
                }
            }
        }
    }
    least
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(6))]
    /// The second worked property of docs/testing.md: every deposit point
    /// lies inside the design solid — with `size = outer`, at least half a
    /// bead inside every face in plan (the bead's edge on the face), less
    /// the outlines' chord error.
    #[test]
    fn every_deposit_point_lies_inside_the_design_solid(od in 72.0f64..95.0) {
        let src = std::fs::read_to_string("examples/flange.lmd").unwrap();
        let options = lmdc::Options {
            set: vec![format!("OD={od:.3} mm").parse().unwrap()],
            ..Default::default()
        };
        if let Ok(program) = lmdc::compile(&src, &options) {
            let (margin, at) = least_margin(program.ir(), od);
            prop_assert!(margin >= 1.5 - 0.02, "{margin:.4} mm inside at {at}");
        }
    }
}

/// The property can fail: a flange drawn 2 mm smaller than the part lmdc
/// planned puts its outer contour outside.
#[test]
fn the_design_property_catches_a_point_outside() {
    let src = std::fs::read_to_string("examples/flange.lmd").unwrap();
    let program = lmdc::compile(&src, &lmdc::Options::default()).unwrap();
    let (margin, _) = least_margin(program.ir(), 80.0);
    assert!(margin >= 1.48, "{margin}");
    let (smaller, at) = least_margin(program.ir(), 76.0);
    assert!(smaller < 0.0, "{smaller} at {at}");
}
