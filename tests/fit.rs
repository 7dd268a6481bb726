//! `lmdc fit` and the fits behind it: least squares against values worked
//! out by hand or by another method here, a power law through exact
//! points, a round trip from a known model through noisy measurements back
//! to it, and the command's output on good and bad sheets (snapshots in
//! tests/fit/<case>/: `data.csv`, `args`, and `output.txt`, what the
//! command prints and its exit status; `LMDC_BLESS=1` rewrites them).

use crate::support::expected::{self, fail};
use lmdc::bead::fit::{self, Fault, Given, Kind};
use lmdc::bead::sheet::{self, Column};
use lmdc::bead::HeightModel;
use lmdc::units::{Density, MassFlow};
use std::path::Path;
use std::process::Command;

fn sheet_of(rows: &[(f64, f64)]) -> sheet::Sheet {
    let mut text = String::from("speed (mm/s),height (mm)\n");
    for (v, h) in rows {
        text.push_str(&format!("{v},{h}\n"));
    }
    sheet::read(&text).unwrap()
}

#[test]
fn a_line_by_hand() {
    // (1, 3), (2, 2), (3, 2.5), (4, 1): x̄ = 2.5, ȳ = 2.125,
    // Σ(x−x̄)(y−ȳ) = −1.5·0.875 − 0.5·−0.125 + 0.5·0.375 + 1.5·−1.125 = −2.75,
    // Σ(x−x̄)² = 5: slope −0.55, intercept 2.125 + 0.55·2.5 = 3.5.
    // Fitted 2.95, 2.4, 1.85, 1.3: residuals 0.05, −0.4, 0.65, −0.3,
    // SS_res = 0.0025 + 0.16 + 0.4225 + 0.09 = 0.675;
    // SS_tot = 0.765625 + 0.015625 + 0.140625 + 1.265625 = 2.1875.
    let s = sheet_of(&[(1.0, 3.0), (2.0, 2.0), (3.0, 2.5), (4.0, 1.0)]);
    let f = fit::fit(&s, Kind::Linear, Given::default()).unwrap();
    let HeightModel::Linear { slope, intercept } = f.model else {
        panic!("{:?}", f.model)
    };
    assert!((slope + 0.55).abs() < 1e-9, "{slope}");
    assert!((intercept.0 - 3.5).abs() < 1e-9, "{intercept:?}");
    for ((_, r), want) in f.residuals.iter().zip([0.05, -0.4, 0.65, -0.3]) {
        assert!((r - want).abs() < 1e-9, "{r} vs {want}");
    }
    assert!((f.r2 - (1.0 - 0.675 / 2.1875)).abs() < 1e-9, "{}", f.r2);
    assert!((f.rms - (0.675f64 / 4.0).sqrt()).abs() < 1e-9);
    assert_eq!(f.range, [1.0, 4.0]);
}

#[test]
fn a_line_by_the_normal_equations() {
    // An independent method: solve [Σ1 Σx; Σx Σx²]·[b; a] = [Σy; Σxy] by
    // Cramer's rule on seed 003-like data with uneven noise.
    let rows = [
        (4.0, 1.283),
        (4.0, 1.27),
        (5.5, 1.079),
        (6.0, 1.012),
        (7.2, 0.851),
        (8.7, 0.649),
        (8.7, 0.638),
    ];
    let n = rows.len() as f64;
    let (sx, sy) = rows.iter().fold((0.0, 0.0), |a, r| (a.0 + r.0, a.1 + r.1));
    let sxx: f64 = rows.iter().map(|r| r.0 * r.0).sum();
    let sxy: f64 = rows.iter().map(|r| r.0 * r.1).sum();
    let det = n * sxx - sx * sx;
    let a = (n * sxy - sx * sy) / det;
    let b = (sy * sxx - sx * sxy) / det;
    let f = fit::fit(&sheet_of(&rows), Kind::Linear, Given::default()).unwrap();
    let HeightModel::Linear { slope, intercept } = f.model else {
        panic!()
    };
    assert!((slope - a).abs() < 1e-9 && (intercept.0 - b).abs() < 1e-9);
}

#[test]
fn a_power_law_through_exact_points_is_that_law() {
    // H = 2.5·v^−0.6 at five speeds: the fit passes every point.
    let law = |v: f64| 2.5 * v.powf(-0.6);
    let rows: Vec<(f64, f64)> = [3.0, 4.5, 6.0, 8.0, 11.0]
        .iter()
        .map(|&v| (v, law(v)))
        .collect();
    let f = fit::fit(&sheet_of(&rows), Kind::Power, Given::default()).unwrap();
    let HeightModel::Power {
        height,
        speed,
        exponent,
    } = f.model
    else {
        panic!("{:?}", f.model)
    };
    assert!((exponent + 0.6).abs() < 1e-9, "{exponent}");
    assert!((height.0 - law(speed.0)).abs() < 1e-9);
    // The reference speed: √(3·11) ≈ 5.745, to 0.1 mm/s.
    assert!((speed.0 - 5.7).abs() < 1e-12);
    assert!(f.rms < 1e-9 && (f.r2 - 1.0).abs() < 1e-9);
}

#[test]
fn a_mass_balance_from_areas_and_from_masses() {
    // η = 0.35 of 12 g/min into 7.9 g/cm³ at v: A = η·ṁ/(ρ·v), mm²; a
    // track L long holds m = η·ṁ·L/v, g.
    let (eta, feed, rho) = (0.35, 12.0, 7.9e-3);
    let area = |v: f64| eta * feed / 60.0 / (rho * v);
    let mass = |v: f64, l: f64| eta * feed / 60.0 * l / v;
    let mut a = String::from("speed (mm/s),feed (g/min),area (mm^2)\n");
    let mut m = String::from("speed (mm/s),length (mm),mass (mg)\n");
    for (v, l) in [(4.0, 30.0), (6.0, 40.0), (8.7, 50.0)] {
        a.push_str(&format!("{v},{feed},{}\n", area(v)));
        m.push_str(&format!("{v},{l},{}\n", mass(v, l) * 1000.0));
    }
    let given = Given {
        density: Some(Density(rho)),
        feed: None,
    };
    let f = fit::fit(&sheet::read(&a).unwrap(), Kind::MassBalance, given).unwrap();
    let HeightModel::MassBalance { efficiency, .. } = f.model else {
        panic!()
    };
    assert!((efficiency - eta).abs() < 1e-9 && f.unit == "mm²");
    // By mass, the feed given (the sheet has none).
    let given = Given {
        feed: Some(MassFlow(feed / 60.0)),
        ..given
    };
    let s = sheet::read(&m).unwrap();
    assert!((s.coupons[0].get(Column::Mass).unwrap() - mass(4.0, 30.0)).abs() < 1e-12);
    let f = fit::fit(&s, Kind::MassBalance, given).unwrap();
    let HeightModel::MassBalance { efficiency, .. } = f.model else {
        panic!()
    };
    assert!((efficiency - eta).abs() < 1e-9 && f.unit == "g");
}

#[test]
fn a_table_is_the_mean_at_each_speed_and_refuses_a_rise() {
    let s = sheet_of(&[(4.0, 1.3), (4.0, 1.26), (6.0, 1.0), (8.0, 0.7), (8.0, 0.74)]);
    let f = fit::fit(&s, Kind::Table, Given::default()).unwrap();
    let HeightModel::Table(t) = &f.model else {
        panic!()
    };
    assert_eq!(t.speeds(), [4.0, 6.0, 8.0]);
    for (h, want) in t.heights().iter().zip([1.28, 1.0, 0.72]) {
        assert!((h - want).abs() < 1e-12);
    }
    // At 6 mm/s the two coupons average 1.3 mm, above the 1.0 mm at 4
    // mm/s: the fault names the second speed and the coupons at both
    // (lines 2, 3 and 4 of the sheet).
    let s = sheet_of(&[(4.0, 1.0), (6.0, 1.2), (6.0, 1.4), (8.0, 0.7)]);
    let Err(Fault::Table { faults, means, .. }) = fit::fit(&s, Kind::Table, Given::default())
    else {
        panic!()
    };
    assert!((means[1] - 1.3).abs() < 1e-12);
    assert_eq!(faults.len(), 1);
    assert_eq!(faults[0].0, lmdc::bead::TableFault::NotFalling(1));
    let lines: Vec<usize> = faults[0].1.iter().map(|r| r.0).collect();
    assert_eq!(lines, [2, 3, 4]);
}

/// A small deterministic noise source (xorshift), in ±`amp`.
fn noise(state: &mut u64, amp: f64) -> f64 {
    *state ^= *state << 13;
    *state ^= *state >> 7;
    *state ^= *state << 17;
    (*state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 * amp - amp
}

#[test]
fn noisy_coupons_give_back_the_model_within_the_noise() {
    // Seed 003's line, three coupons at each of eight speeds from 4 to
    // 8.7 mm/s, each height off by up to ±0.02 mm: the slope's error is at
    // most the noise over the speeds' spread (about 0.02/4.7 ≈ 0.004 mm
    // per mm/s for a worst case of opposite ends), the heights on the
    // line within the noise.
    let mut st = 0x2545_f491_4f6c_dd1d;
    let mut rows = Vec::new();
    for k in 0..8 {
        let v = 4.0 + 4.7 * k as f64 / 7.0;
        for _ in 0..3 {
            rows.push((v, -0.135 * v + 1.82 + noise(&mut st, 0.02)));
        }
    }
    let f = fit::fit(&sheet_of(&rows), Kind::Linear, Given::default()).unwrap();
    let HeightModel::Linear { slope, intercept } = f.model else {
        panic!()
    };
    assert!((slope + 0.135).abs() < 0.02 / 4.7, "{slope}");
    for v in [4.0, 6.0, 8.7] {
        let h = slope * v + intercept.0;
        assert!((h - (-0.135 * v + 1.82)).abs() < 0.02, "{v}: {h}");
    }
    assert!(f.rms < 0.02 && f.r2 > 0.99);
    // The line is what the data favour over the power law and a table.
    let fits: Vec<_> = [Kind::Linear, Kind::Power, Kind::Table]
        .iter()
        .map(|&k| fit::fit(&sheet_of(&rows), k, Given::default()).unwrap())
        .collect();
    assert_eq!(fit::favoured(&fits).unwrap().kind, Kind::Linear);
}

/// Where the command's snapshots are.
const ROOT: &str = "tests/fit";

#[test]
fn the_command_prints_what_each_case_expects() {
    let mut problems = Vec::new();
    let mut cases: Vec<_> = std::fs::read_dir(ROOT)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    cases.sort();
    assert!(cases.len() >= 6, "only {} cases in {ROOT}", cases.len());
    for case in cases {
        let args = std::fs::read_to_string(case.join("args")).unwrap_or_default();
        let data = case.join("data.csv");
        let out = Command::new(env!("CARGO_BIN_EXE_lmdc"))
            .arg("fit")
            .arg(&data)
            .args(args.split_whitespace())
            .env("NO_COLOR", "1")
            .output()
            .expect("runs");
        let text = format!(
            "$ lmdc fit {} {}\nexit status: {}\n--- stdout\n{}--- stderr\n{}",
            data.display(),
            args.trim(),
            out.status.code().unwrap_or(-1),
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
        if let Some(p) = expected::check_file(&Path::new(&case).join("output.txt"), text.as_bytes())
        {
            problems.push(p);
        }
    }
    if !problems.is_empty() {
        fail("lmdc fit's output changed", &problems);
    }
}

#[test]
fn a_bead_fitted_when_compiled_is_seed_003_within_the_noise() {
    // tests/cases/calib/seed_003_fit: seed 003's line with 0.01 mm of
    // noise, widths from 2.6 to 2.2 mm. The IR's bead is the line within
    // the noise at every speed measured, over 4 .. 8.7 mm/s, with the mean
    // width measured at each speed.
    let dir = Path::new("tests/cases/calib/seed_003_fit");
    let src = std::fs::read_to_string(dir.join("input.lmd")).unwrap();
    let root = dir.to_path_buf();
    let data: lmdc::sema::DataReader =
        std::rc::Rc::new(move |p: &str, _| std::fs::read(root.join(p)).map_err(|e| e.to_string()));
    let (c, _) = lmdc::pipeline::compile_reading(&src, None, &mut (), data).unwrap();
    let p = c.program.expect("compiles").into_ir();
    let b = p.bead.as_ref().unwrap();
    let lmdc::ir::BeadModel::Linear { slope, intercept } = b.model else {
        panic!("{:?}", b.model)
    };
    for v in [4.0, 5.0, 6.0, 7.0, 8.0, 8.7] {
        let off = slope * v + intercept - (-0.135 * v + 1.82);
        assert!(off.abs() < 0.01, "{v}: {off}");
    }
    assert_eq!(b.measured, Some([4.0, 8.7]));
    assert_eq!(b.speed, [4.0, 8.7]);
    let fit = b.fit.as_ref().unwrap();
    assert_eq!(
        (fit.points, fit.speeds, fit.model.as_str()),
        (12, 6, "linear")
    );
    // The sheet's widths at 4 mm/s: 2.63 and 2.62.
    let w = b.widths.as_ref().unwrap();
    assert_eq!(w.len(), 6);
    assert!((w[0][0] - 4.0).abs() < 1e-12 && (w[0][1] - 2.625).abs() < 1e-12);
}

/// `lmdc fit --json` gives every fitted number at full precision, as the
/// library fits it (to the last bit serde_json's parser keeps, not the
/// text's six digits), lists each model it could not fit with why, and
/// follows docs/fit.schema.json.
#[test]
fn the_json_has_every_number_at_full_precision_and_the_models_not_fitted() {
    let data = "tests/fit/seed_003/data.csv";
    let out = Command::new(env!("CARGO_BIN_EXE_lmdc"))
        .args(["fit", data, "--json"])
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(0));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let schema: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string("docs/fit.schema.json").unwrap()).unwrap();
    let errors = crate::support::schema::validate(&schema, &v);
    assert!(errors.is_empty(), "{errors:?}");
    // Without a density the mass balance is not fitted, and says so.
    let not = v["not_fitted"].as_array().unwrap();
    assert_eq!(not.len(), 1, "{not:?}");
    assert_eq!(not[0]["model"], "mass_balance");
    assert!(not[0]["reason"].as_str().unwrap().contains("density"));
    assert!(not[0]["help"].as_str().unwrap().contains("--density"));
    // The numbers are the library's own.
    let s = sheet::read(&std::fs::read_to_string(data).unwrap()).unwrap();
    let linear = fit::fit(&s, Kind::Linear, Given::default()).unwrap();
    let HeightModel::Linear { slope, intercept } = linear.model else {
        panic!()
    };
    let j = v["fits"]
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["model"] == "linear")
        .unwrap();
    // serde_json's default parser may miss the last bit.
    let same = |got: &serde_json::Value, want: f64| {
        let g = got.as_f64().unwrap();
        assert!(
            (g - want).abs() <= 2.0 * f64::EPSILON * want.abs(),
            "{g} against {want}"
        );
    };
    same(&j["parameters"]["slope"], slope);
    same(&j["parameters"]["intercept"], intercept.0);
    assert!(
        (slope - -0.1367).abs() > 1e-7,
        "more digits than the text's"
    );
    same(&j["r2"], linear.r2);
    let residuals = j["residuals"].as_array().unwrap();
    assert_eq!(residuals.len(), linear.residuals.len());
    for (r, &(line, x)) in residuals.iter().zip(&linear.residuals) {
        assert_eq!(r["line"].as_u64(), Some(line as u64));
        same(&r["residual"], x);
    }
    // A sheet at two powers adds its groups and the power line, to the
    // schema too.
    let out = Command::new(env!("CARGO_BIN_EXE_lmdc"))
        .args([
            "fit",
            "tests/fit/by_power/data.csv",
            "--model",
            "mass_balance",
        ])
        .args(["--density", "7.9", "--json"])
        .output()
        .expect("runs");
    let groups: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(
        groups["groups"]["pooling_hides"].as_bool().unwrap(),
        "{groups}"
    );
    assert!(groups["power_line"]["at"].as_array().unwrap().len() >= 2);
    let errors = crate::support::schema::validate(&schema, &groups);
    assert!(errors.is_empty(), "{errors:?}");
    // A broken document fails the schema: the test can fail.
    let mut bad = v.clone();
    bad["fits"][0]["parameters"] = serde_json::json!({ "slope": 1.0 });
    assert!(!crate::support::schema::validate(&schema, &bad).is_empty());
}

/// Issue 33's reproducer (tests/fit/by_power/data.csv): twelve coupons at
/// 1200 W (η 0.37) and twelve at 1600 W (η 0.422), 12 g/min, with 1 % of
/// scatter. Pooled, one η lies between the two, with every residual
/// negative at 1200 W and positive at 1600 W; each power fitted apart
/// gives back its own η; fitting apart has the lower AICc, so pooling
/// hides the power. Every η is checked against `Σ A·x / Σ x²`, `x =
/// ṁ/(ρ·v)`, worked out here from the file.
#[test]
fn pooling_two_powers_hides_the_power() {
    let text = std::fs::read_to_string("tests/fit/by_power/data.csv").unwrap();
    let s = sheet::read(&text).unwrap();
    let given = Given {
        density: Some(Density(7.9e-3)),
        feed: None,
    };
    let eta_of = |keep: &dyn Fn(f64) -> bool| {
        let (mut sxy, mut sxx) = (0.0, 0.0);
        for c in s
            .coupons
            .iter()
            .filter(|c| keep(c.get(Column::Power).unwrap()))
        {
            let x = c.get(Column::Feed).unwrap() / 60.0 / (7.9e-3 * c.speed());
            sxy += x * c.get(Column::Area).unwrap();
            sxx += x * x;
        }
        sxy / sxx
    };
    let efficiency = |f: &fit::Fit| match f.model {
        HeightModel::MassBalance { efficiency, .. } => efficiency,
        _ => panic!("{:?}", f.model),
    };
    let pooled = fit::fit(&s, Kind::MassBalance, given).unwrap();
    let eta = efficiency(&pooled);
    assert!((eta - eta_of(&|_| true)).abs() < 1e-12);
    assert!((eta - 0.396).abs() < 0.001, "{eta}");
    assert_eq!(pooled.powers, [1200.0, 1600.0]);
    let p = fit::pooling(&s, &pooled, given).expect("two groups");
    assert_eq!(p.groups.len(), 2);
    for ((g, r, alone), (power, want)) in p.groups.iter().zip([(1200.0, 0.37), (1600.0, 0.422)]) {
        assert_eq!(
            (g.power, g.feed, g.lines.len()),
            (Some(power), Some(12.0), 12)
        );
        let got = efficiency(alone.as_ref().unwrap());
        assert!((got - eta_of(&|w| w == power)).abs() < 1e-12);
        assert!((got - want).abs() < 0.002, "{power} W: {got}");
        // Every residual of the pooled η on one side.
        if power < 1400.0 {
            assert_eq!((r.negative, r.positive), (12, 0));
        } else {
            assert_eq!((r.negative, r.positive), (0, 12));
        }
    }
    assert!(p.hides(), "{:?}", p.aicc);
    // The power as a variable: with two powers the line passes through
    // each power's own η, about the coupons' mean power (1400 W).
    let line = fit::power_line(&s, given).unwrap();
    assert_eq!(line.power, 1400.0);
    let apart: Vec<f64> = p
        .groups
        .iter()
        .map(|g| efficiency(g.2.as_ref().unwrap()))
        .collect();
    assert!((line.slope - (apart[1] - apart[0]) / 400.0).abs() < 1e-9);
    for ((w, e), want) in line.at.iter().zip(&apart) {
        assert!((e - want).abs() < 1e-9, "{w} W: {e} vs {want}");
    }
    assert!((line.aicc.unwrap() - p.aicc.unwrap()[1]).abs() < 1e-6);
    // One power alone is one group: nothing to pool.
    let one = fit::Group {
        power: Some(1200.0),
        feed: Some(12.0),
        lines: p.groups[0].0.lines.clone(),
    }
    .sheet(&s);
    let f = fit::fit(&one, Kind::MassBalance, given).unwrap();
    assert!(fit::pooling(&one, &f, given).is_none());
}

/// Coupons of one power whose two halves differ only by scatter: fitting
/// them apart buys nothing, and pooling hides nothing.
#[test]
fn pooling_two_powers_that_lay_alike_hides_nothing() {
    let text = std::fs::read_to_string("tests/fit/by_power/data.csv").unwrap();
    // Both halves at η 0.37: the 1600 W areas scaled down by 0.37/0.422.
    let alike: String = text
        .lines()
        .enumerate()
        .map(|(i, l)| {
            if i == 0 || !l.contains(",1600,") {
                return format!("{l}\n");
            }
            let (head, area) = l.rsplit_once(',').unwrap();
            let a: f64 = area.parse().unwrap();
            format!("{head},{}\n", a * 0.37 / 0.422)
        })
        .collect();
    let s = sheet::read(&alike).unwrap();
    let given = Given {
        density: Some(Density(7.9e-3)),
        feed: None,
    };
    let pooled = fit::fit(&s, Kind::MassBalance, given).unwrap();
    let p = fit::pooling(&s, &pooled, given).unwrap();
    assert!(!p.hides(), "{:?}", p.aicc);
}

/// `fit(…, power = …)` fits the coupons laid at that power only, and the
/// bead says so (the IR's `powers`); a process at another power is warned
/// (`lmd::extrapolation`); pooled over both powers, the fit is warned of
/// (`lmd::pooled-fit`), its help naming the `power` that selects each.
#[test]
fn a_fit_at_the_process_power_takes_its_coupons() {
    let dir = Path::new("tests/fit/by_power");
    let root = dir.to_path_buf();
    let data: lmdc::sema::DataReader =
        std::rc::Rc::new(move |p: &str, _| std::fs::read(root.join(p)).map_err(|e| e.to_string()));
    let src = |power: &str, select: &str| {
        std::fs::read_to_string("tests/cases/calib/seed_003_fit/input.lmd")
            .unwrap()
            .replace(
                "model = fit(linear, data = \"coupons.csv\")",
                &format!(
                    "model = fit(mass_balance, data = \"data.csv\", density = 7.9 g/cm^3{select})"
                ),
            )
            .replace("power = 1000 W", &format!("power = {power}"))
    };
    let run = |s: String| {
        let (c, _) = lmdc::pipeline::compile_reading(&s, None, &mut (), data.clone()).unwrap();
        c
    };
    let codes = |c: &lmdc::pipeline::Compiled| -> Vec<lmdc::diag::Code> {
        c.diagnostics.iter().map(|d| d.code).collect()
    };
    let base = src("1600 W", "");
    assert!(
        base.contains("power = 1600 W") && base.contains("data.csv"),
        "{base}"
    );
    // Pooled: warned, with both selections in the help.
    let c = run(base);
    let pooled = c
        .diagnostics
        .iter()
        .find(|d| d.code == lmdc::diag::Code::PooledFit)
        .unwrap_or_else(|| panic!("{:?}", c.diagnostics));
    let help = pooled.help.clone().unwrap_or_default();
    assert!(
        help.contains("`power = 1200 W` or `power = 1600 W`"),
        "{help}"
    );
    // Following it: the 1600 W coupons alone, no warning.
    let c = run(src("1600 W", ", power = 1600 W"));
    assert!(codes(&c).is_empty(), "{:?}", c.diagnostics);
    let ir = c.program.unwrap().into_ir();
    let b = ir.bead.unwrap();
    assert_eq!(b.powers, Some(vec![1600.0]));
    assert_eq!(b.powders, Some(vec![12.0]));
    assert_eq!(b.fit.unwrap().points, 12);
    let lmdc::ir::BeadModel::MassBalance { efficiency, .. } = b.model else {
        panic!()
    };
    assert!((efficiency - 0.422).abs() < 0.002, "{efficiency}");
    // The 1600 W coupons for a process at 1200 W: warned.
    let c = run(src("1200 W", ", power = 1600 W"));
    assert_eq!(
        codes(&c),
        [lmdc::diag::Code::Extrapolation],
        "{:?}",
        c.diagnostics
    );
    assert!(c
        .diagnostics
        .iter()
        .all(|d| d.message.contains("measured at 1600 W")));
}
