//! `lmdc calibrate`: the coupons of a `calibration` block become an
//! ordinary plan (checked like any part), the sheet's rows are those
//! coupons, a filled-in sheet fits without editing, and a matrix too large
//! for its plate is refused with its numbers, writing nothing.

use crate::support::krl_parser::TempDir;
use lmdc::bead::fit::{self, Given, Kind};
use lmdc::bead::{sheet, HeightModel};
use lmdc::diag::Code;
use lmdc::pipeline;
use lmdc::sema::model::Build;
use std::process::Command;

const EXAMPLE: &str = include_str!("../examples/calibration.lmd");

fn lmdc(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_lmdc"))
        .args(args)
        .env("NO_COLOR", "1")
        .output()
        .unwrap()
}

/// The rows of a CSV text without its `#` lines, split at commas (the
/// sheet lmdc writes quotes nothing).
fn rows(text: &str) -> Vec<Vec<String>> {
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

/// `EXAMPLE` with its calibration block's `from` replaced by `to`.
fn edited(from: &str, to: &str) -> String {
    assert!(EXAMPLE.contains(from), "{from}");
    EXAMPLE.replace(from, to)
}

#[test]
fn the_sheet_lists_every_coupon_where_the_plan_lays_it() {
    // Two powers, so the matrix is 6 speeds × 2 powers × 2 repeats, laid in
    // the matrix's order.
    let src = edited(
        "  coupon = track\n",
        "  coupon = track\n  powers = [900 W, 1100 W]\n  order = sorted\n",
    )
    .replace("plate = [100 mm, 120 mm]", "plate = [200 mm, 120 mm]");
    let (c, model) =
        pipeline::compile_with_model(&src, &pipeline::Options::default(), &mut ()).unwrap();
    let program = c.program.expect("the coupons compile");
    let Some(Build::Calibration(cal)) = model.map(|m| m.build) else {
        panic!("no calibration")
    };
    let table = rows(&lmdc::slice::calibration::sheet("coupons", &cal));
    let (header, body) = table.split_first().unwrap();
    assert_eq!(
        header.join(","),
        "id,kind,speed (mm/s),power (W),feed (g/min),x (mm),y (mm),length (mm),width (mm),height (mm),area (mm^2),mass (g)"
    );
    assert_eq!(body.len(), 6 * 2 * 2);
    let ir = program.ir();
    assert_eq!(ir.layers.len(), body.len(), "a track coupon is one layer");
    let num = |s: &str| s.parse::<f64>().unwrap();
    for (k, (row, layer)) in body.iter().zip(&ir.layers).enumerate() {
        // Powder outer, power, then speed, then the repeats.
        let speed = 4.0 + (8.7 - 4.0) * ((k / 2) % 6) as f64 / 5.0;
        let power = [900.0, 1100.0][k / 12];
        assert_eq!(row[0], format!("c{:02}", k + 1));
        assert_eq!(row[1], "track");
        assert!((num(&row[2]) - speed).abs() < 1e-4, "{row:?}");
        assert_eq!(num(&row[3]), power);
        assert_eq!(num(&row[4]), 12.0);
        // Where the plan lays it: the middle of its one track.
        let pts = &layer.paths[0].points;
        let (a, b) = (pts[0].pos, pts[1].pos);
        assert!((num(&row[5]) - (a[0] + b[0]) / 2.0).abs() < 1e-3, "{row:?}");
        assert!((num(&row[6]) - a[1]).abs() < 1e-3, "{row:?}");
        assert!(((b[0] - a[0]) - 30.0).abs() < 1e-9 && num(&row[7]) == 30.0);
        assert!((pts[0].speed as f64 - speed).abs() < 1e-4);
        assert_eq!(pts[0].power as f64, power);
        assert!(row[8..].iter().all(String::is_empty), "{row:?}");
        // Its comment names it.
        assert!(
            layer
                .label
                .starts_with(&format!("coupon {}: speed ", row[0])),
            "{}",
            layer.label
        );
        // On the plate, `spacing` from its edges.
        assert!(a[0] >= 8.0 - 1e-9 && b[0] <= 200.0 - 8.0 + 1e-9);
        assert!(a[1] - 1.2 >= 8.0 - 1e-9 && a[1] + 1.2 <= 120.0 - 8.0 + 1e-9);
    }
    // Coupons do not touch: every two are a spacing apart across or along.
    for (i, p) in ir.layers.iter().enumerate() {
        for q in &ir.layers[..i] {
            let (a, b) = (p.paths[0].points[0].pos, q.paths[0].points[0].pos);
            assert!(
                (a[1] - b[1]).abs() >= 2.4 + 8.0 - 1e-9 || (a[0] - b[0]).abs() >= 30.0 + 8.0 - 1e-9
            );
        }
    }
}

#[test]
fn walls_and_pads_are_laid_as_declared() {
    let wall = edited("coupon = track", "coupon = wall(layers = 3)");
    let c = pipeline::compile(&wall, &mut ());
    let p = c.program.expect("walls compile");
    let ir = p.ir();
    assert_eq!(ir.layers.len(), 12 * 3);
    // The bead's height is 0.6 .. 1.3 mm: layers 0.95 mm apart.
    for (i, l) in ir.layers.iter().enumerate() {
        let z = l.paths[0].points[0].pos[2];
        assert!((z - (i % 3) as f64 * 0.95).abs() < 1e-9, "layer {i}: z {z}");
        assert_eq!(l.on_plate, i % 3 == 0);
    }
    let pad = edited(
        "coupon = track",
        "coupon = pad(tracks = 4, offset = 1.6 mm)",
    );
    let c = pipeline::compile(&pad, &mut ());
    let p = c.program.expect("pads compile");
    for l in &p.ir().layers {
        let ys: Vec<f64> = l.paths.iter().map(|q| q.points[0].pos[1]).collect();
        assert_eq!(ys.len(), 4);
        for w in ys.windows(2) {
            assert!((w[1] - w[0] - 1.6).abs() < 1e-9, "{ys:?}");
        }
    }
}

#[test]
fn a_power_outside_the_laser_is_refused() {
    // The laser gives 800 .. 1200 W: a 1500 W coupon is checked like any point.
    let src = edited(
        "  coupon = track\n",
        "  coupon = track\n  powers = [1000 W, 1500 W]\n",
    )
    .replace("plate = [100 mm, 120 mm]", "plate = [200 mm, 120 mm]");
    let c = pipeline::compile(&src, &mut ());
    assert!(c.program.is_none());
    assert!(c.diagnostics.has_errors());
}

#[test]
fn a_matrix_too_large_for_its_plate_is_refused_with_its_numbers() {
    let src = edited("plate = [100 mm, 120 mm]", "plate = [50 mm, 30 mm]");
    let c = pipeline::compile(&src, &mut ());
    let d = c
        .diagnostics
        .iter()
        .find(|d| d.code == Code::CouponsPlate)
        .expect("lmd::coupons-plate");
    // 12 coupons of 30 × 2.4 mm, 8 mm apart: (30 − 8)/(2.4 + 8) → 2 a
    // column, 6 columns: 8 + 6·38 = 236 mm along x, 8 + 2·10.4 = 28.8 mm
    // across.
    let text = d.message.to_string();
    for n in ["12 coupons", "236 mm", "28.8 mm", "50 mm", "30 mm"] {
        assert!(text.contains(n), "{n} not in: {text}");
    }
    // The command writes nothing and says so with exit 1.
    let dir = TempDir::new("calib-plate");
    let file = dir.write("plate.lmd", src.as_bytes());
    let out = dir.path().join("out");
    let o = lmdc(&[
        "calibrate",
        file.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(
        o.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(!out.exists() || std::fs::read_dir(&out).unwrap().next().is_none());
}

#[test]
fn a_file_without_a_calibration_block_is_a_usage_error() {
    let o = lmdc(&[
        "calibrate",
        "examples/flange.lmd",
        "-o",
        "/nonexistent/never",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("no `calibration"));
}

/// A uniform number in [-1, 1) from a 64-bit LCG (Knuth's MMIX constants).
fn noise(state: &mut u64) -> f64 {
    *state = state
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    ((*state >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
}

#[test]
fn a_filled_sheet_fits_back_to_the_model_it_was_measured_from() {
    let dir = TempDir::new("calib-round-trip");
    let out = dir.path().join("out");
    let o = lmdc(&[
        "calibrate",
        "examples/calibration.lmd",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let csv = out.join("coupons.coupons.csv");
    let text = std::fs::read_to_string(&csv).unwrap();
    for name in ["coupons_mill.ngc", "coupons_kr.src", "coupons_kr.dat"] {
        assert!(out.join(name).exists(), "{name}");
    }
    // Seed 003's line, measured with ±0.01 mm of noise.
    let (slope, intercept, amp) = (-0.135, 1.82, 0.01);
    let mut state = 20u64;
    let header_at = text.lines().position(|l| l.starts_with("id,")).unwrap();
    let cols: Vec<&str> = text.lines().nth(header_at).unwrap().split(',').collect();
    let (vi, hi) = (
        cols.iter().position(|c| c.starts_with("speed")).unwrap(),
        cols.iter().position(|c| c.starts_with("height")).unwrap(),
    );
    let mut filled = String::new();
    for (i, line) in text.lines().enumerate() {
        if i <= header_at {
            filled.push_str(line);
        } else {
            let mut cells: Vec<String> = line.split(',').map(str::to_string).collect();
            let v: f64 = cells[vi].parse().unwrap();
            cells[hi] = format!("{:.4}", slope * v + intercept + amp * noise(&mut state));
            filled.push_str(&cells.join(","));
        }
        filled.push('\n');
    }
    std::fs::write(&csv, &filled).unwrap();
    let s = sheet::read(&filled).unwrap_or_else(|d| panic!("{d:?}"));
    let f = fit::fit(&s, Kind::Linear, Given::default()).unwrap();
    let HeightModel::Linear {
        slope: a,
        intercept: b,
    } = f.model
    else {
        panic!("{:?}", f.model)
    };
    // Noise of ±0.01 over 4 .. 8.7 mm/s moves the slope by at most
    // 2·0.01/4.7 and the intercept by that times 8.7 plus 0.01.
    assert!((a - slope).abs() < 2.0 * amp / 4.7, "slope {a}");
    assert!(
        (b.0 - intercept).abs() < 2.0 * amp / 4.7 * 8.7 + amp,
        "intercept {b:?}"
    );
    assert!(f.rms <= amp && f.residuals.len() == 12, "rms {}", f.rms);
    assert_eq!(f.range, [4.0, 8.7]);
    // And `lmdc fit` reads the very file.
    let o = lmdc(&["fit", csv.to_str().unwrap(), "--model", "linear"]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(String::from_utf8_lossy(&o.stdout).contains("linear("));
}

#[test]
fn a_matrix_beyond_what_lmdc_lays_is_refused_before_it_is_made() {
    // 1000 speeds × 11 powers = 11 000 coupons > 10 000.
    let powers: Vec<String> = (0..11).map(|i| format!("{} W", 900 + 10 * i)).collect();
    let src = edited("count = 6", "count = 1000")
        .replace(
            "  coupon = track\n",
            &format!("  coupon = track\n  powers = [{}]\n", powers.join(", ")),
        )
        .replace("repeat = 2", "repeat = 1");
    let c = pipeline::compile(&src, &mut ());
    let d = c
        .diagnostics
        .iter()
        .find(|d| d.code == Code::CountRange)
        .expect("lmd::count-range");
    assert!(
        d.message.to_string().contains("11000 coupons"),
        "{}",
        d.message
    );
}

/// `lmdc calibrate` takes the shared options as `check` and `build` do:
/// `--set` changes a `let` (here the number of speeds, which the sheet
/// shows), an unknown name is a usage error, and `--deny-warnings` fails
/// on a warning.
#[test]
fn calibrate_takes_set_and_deny_warnings() {
    let dir = tempfile::tempdir().unwrap();
    let src = edited("part coupons\n", "part coupons\n\nlet N = 6\n").replacen(
        "count = 6",
        "count = N",
        1,
    );
    let file = dir.path().join("coupons.lmd");
    std::fs::write(&file, &src).unwrap();
    let (f, out) = (file.to_str().unwrap(), dir.path().join("out"));
    let o = lmdc(&["calibrate", f, "-o", out.to_str().unwrap(), "--set", "N=3"]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let sheet = std::fs::read_to_string(out.join("coupons.coupons.csv")).unwrap();
    // Three speeds, twice each.
    assert_eq!(rows(&sheet).len() - 1, 6, "{sheet}");

    let o = lmdc(&["calibrate", f, "-o", out.to_str().unwrap(), "--set", "M=3"]);
    assert_eq!(
        o.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );

    // An arm whose base is only an index cannot be checked: a warning
    // (`lmd::arm-unchecked`).
    let warned = src.replacen(
        "  full_scale = 2000 W\n",
        "  full_scale = 2000 W\n  arm = kr60ha\n",
        1,
    );
    assert_ne!(warned, src);
    std::fs::write(&file, &warned).unwrap();
    let o = lmdc(&["calibrate", f, "-o", out.to_str().unwrap()]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let o = lmdc(&[
        "calibrate",
        f,
        "-o",
        out.to_str().unwrap(),
        "--deny-warnings",
    ]);
    assert_eq!(
        o.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// A coupon kind lmdc does not know: the error lists every kind, the calls
/// too, and suggests the nearest.
#[test]
fn an_unknown_coupon_lists_every_kind() {
    for (word, near) in [("blob", None), ("walls", Some("wall(layers = …)"))] {
        let src = edited("coupon = track", &format!("coupon = {word}"));
        let c = pipeline::compile(&src, &mut ());
        let d = c
            .diagnostics
            .iter()
            .find(|d| d.code == lmdc::diag::Code::BadChoice)
            .unwrap_or_else(|| panic!("{word}: no bad-choice"));
        for kind in ["track", "wall(layers = …)", "pad(tracks = …, offset = …)"] {
            assert!(d.message.contains(kind), "{word}: {}", d.message);
        }
        match near {
            Some(n) => assert!(
                d.help.as_deref().is_some_and(|h| h.contains(n)),
                "{:?}",
                d.help
            ),
            None => assert!(d.help.is_none(), "{:?}", d.help),
        }
    }
}

/// The speed, power and feed of every row of `src`'s sheet, in its order,
/// and its ids.
fn laid(src: &str) -> (Vec<[String; 3]>, Vec<String>) {
    let (_, model) =
        pipeline::compile_with_model(src, &pipeline::Options::default(), &mut ()).unwrap();
    let Some(Build::Calibration(cal)) = model.map(|m| m.build) else {
        panic!("no calibration")
    };
    let table = rows(&lmdc::slice::calibration::sheet("coupons", &cal));
    let body = &table[1..];
    (
        body.iter()
            .map(|r| [r[2].clone(), r[3].clone(), r[4].clone()])
            .collect(),
        body.iter().map(|r| r[0].clone()).collect(),
    )
}

/// Issue 33: coupons were laid in speed order, repeats side by side, so a
/// plate that warms up looked like a speed effect. By default they are
/// laid in an order shuffled by `seed`: the same matrix, the same order
/// for the same seed, another for another seed; numbered in the order
/// laid.
#[test]
fn coupons_are_laid_in_a_seeded_random_order() {
    let matrix = edited(
        "  coupon = track\n",
        "  coupon = track\n  powers = [900 W, 1100 W]\n",
    )
    .replace("plate = [100 mm, 120 mm]", "plate = [200 mm, 120 mm]");
    let sorted =
        laid(&matrix.replace("  coupon = track\n", "  coupon = track\n  order = sorted\n"));
    let random = laid(&matrix);
    assert_eq!(random, laid(&matrix), "the same seed, the same order");
    let seeded = laid(&matrix.replace("  coupon = track\n", "  coupon = track\n  seed = 7\n"));
    assert_ne!(random.0, sorted.0, "shuffled");
    assert_ne!(random.0, seeded.0, "another seed, another order");
    let bag = |mut v: Vec<[String; 3]>| {
        v.sort();
        v
    };
    assert_eq!(
        bag(random.0.clone()),
        bag(sorted.0.clone()),
        "the same coupons"
    );
    assert_eq!(bag(seeded.0), bag(sorted.0.clone()));
    let ids: Vec<String> = (1..=24).map(|k| format!("c{k:02}")).collect();
    assert_eq!(random.1, ids, "numbered in the order laid");
    // Seed 1 is Fisher–Yates over SplitMix64 (docs/calibration.md), here
    // as an independent implementation computed it: pinned, so that a seed
    // keeps its order across versions.
    let order = [
        7, 20, 21, 12, 23, 22, 11, 3, 5, 16, 18, 15, 4, 19, 10, 8, 6, 9, 13, 1, 14, 0, 2, 17,
    ];
    let expected: Vec<[String; 3]> = order.iter().map(|&k| sorted.0[k].clone()).collect();
    assert_eq!(random.0, expected);
}

/// docs/calibration.md shows the sheet's start as `lmdc calibrate` writes
/// it for examples/calibration.lmd: its three `#` lines, the header and
/// the first coupon (issue 38 item 6: the example left the `#` lines out).
#[test]
fn the_sheet_in_the_docs_starts_as_lmdc_writes_it() {
    let (_, model) =
        pipeline::compile_with_model(EXAMPLE, &pipeline::Options::default(), &mut ()).unwrap();
    let Some(Build::Calibration(cal)) = model.map(|m| m.build) else {
        panic!("no calibration")
    };
    let sheet = lmdc::slice::calibration::sheet("coupons", &cal);
    let docs = std::fs::read_to_string("docs/calibration.md").unwrap();
    let shown: Vec<&str> = docs
        .lines()
        .skip_while(|l| !l.starts_with("# lmdc calibrate:"))
        .take_while(|l| !l.starts_with("```"))
        .collect();
    assert_eq!(shown.len(), 5, "{shown:?}");
    let written: Vec<&str> = sheet.lines().take(shown.len()).collect();
    assert_eq!(shown, written);
}
