//! The machine checks of one run, all at once (issue: errors came in rounds):
//! every machine is checked whatever another one found, and `--machine`
//! checks that machine alone. The report of three machines' mistakes in one
//! run, each naming its machine and pointing at the field that declares the
//! limit, is tests/cases/errors/machines/every_machine_error.

use crate::support::example::{duct, tooth};
use lmdc::pipeline::{compile, compile_for};

/// Three machines, three kinds of mistake: a CNC whose X and A travel the part
/// exceeds, a second CNC too slow for the scan speeds, a robot whose analog
/// full scale is below the planned power.
fn three_mistakes() -> String {
    duct(&[
        ("full_scale = 4000 W", "full_scale = 3000 W"),
        ("x = -500 mm .. 500 mm", "x = -20 mm .. 500 mm"),
        ("a = -110 deg .. 110 deg", "a = -30 deg .. 30 deg"),
    ]) + "
machine slow {
  kind = cnc
  head { standoff = 15 mm  nozzle = frustum(length = 45 mm, tip = 12 mm, top = 40 mm) }
  axes = 5
  dialect = linuxcnc
  max_speed = 5 mm/s
}
"
}

#[test]
fn one_machine_is_checked_alone() {
    let src = three_mistakes();
    // kr60's own error only.
    let c = compile_for(&src, Some("kr60"), &mut ()).unwrap();
    let codes: Vec<&str> = c.diagnostics.iter().map(|d| d.code.as_str()).collect();
    assert_eq!(codes, ["lmd::analog-range"]);
    // A fine machine builds, whatever the others' problems.
    let src = src.replace("full_scale = 3000 W", "full_scale = 4000 W");
    let c = compile_for(&src, Some("kr60"), &mut ()).unwrap();
    assert!(c.diagnostics.is_empty(), "{:?}", c.diagnostics);
    let p = c.program.expect("kr60 alone is fine");
    let names: Vec<&str> = p.machines().map(|m| m.machine().name()).collect();
    assert_eq!(names, ["kr60"]);
    // An unknown name is a usage error that lists the machines.
    let e = compile_for(&src, Some("kr61"), &mut ()).err().unwrap();
    assert_eq!(e.declared, "kr60, dmu5, slow");
}

#[test]
fn warnings_come_with_errors() {
    // The seam at the bend's extreme is a warning; the slow machine an error.
    let src = duct(&[("seam = 90 deg", "seam = 0 deg")])
        + "machine slow { kind = cnc\n head { standoff = 15 mm  nozzle = frustum(length = 45 mm, tip = 12 mm, top = 40 mm) }\n axes = 5\n max_speed = 5 mm/s }\n";
    let c = compile(&src, &mut ());
    let codes: Vec<&str> = c.diagnostics.iter().map(|d| d.code.as_str()).collect();
    assert!(codes.contains(&"lmd::seam-at-bend-extreme"), "{codes:?}");
    assert!(codes.contains(&"lmd::machine-speed"), "{codes:?}");
}

#[test]
fn two_machines_that_would_write_one_file() {
    let src = duct(&[]) + "machine DMU5 { kind = cnc\n head { standoff = 15 mm  nozzle = frustum(length = 45 mm, tip = 12 mm, top = 40 mm) }\n axes = 5\n max_speed = 100 mm/s }\n";
    let c = compile(&src, &mut ());
    let clash: Vec<_> = c
        .diagnostics
        .iter()
        .filter(|d| d.code == "lmd::name-clash")
        .collect();
    assert_eq!(clash.len(), 1, "{:?}", c.diagnostics);
    assert!(
        clash[0].message.contains("twisted_duct_dmu5.ngc"),
        "{}",
        clash[0].message
    );
}

fn errors(src: &str) -> Vec<lmdc::diag::Diagnostic> {
    let c = compile(src, &mut ());
    assert!(c.program.is_none(), "want errors");
    c.diagnostics
        .into_vec()
        .into_iter()
        .filter(|d| d.is_error())
        .collect()
}

#[test]
fn an_s_word_too_large_to_write_is_an_error_not_s0() {
    // 1500 W × 1e16 = 1.5e19: used to be written as S0.
    let d = errors(&tooth(&[(
        "dialect = linuxcnc",
        "dialect = linuxcnc\n  s_per_watt = 1e16",
    )]));
    assert_eq!(d.len(), 1, "{d:#?}");
    assert_eq!(d[0].code, "lmd::resolution");
    assert!(d[0].message.contains("1500 W"), "{}", d[0].message);
    assert!(
        d[0].help.as_deref().unwrap().contains("lower `s_per_watt`"),
        "{:?}",
        d[0].help
    );
}

#[test]
fn s_decimals_too_few_for_the_power_is_named() {
    // S = W × 0.00025 with no decimals wrote S1 (4000 W) for the whole ramp down
    // to 2100 W (S 0.525).
    let src = duct(&[(
        "dialect = linuxcnc",
        "dialect = linuxcnc\n  s_per_watt = 0.00025",
    )]);
    let d = errors(&src);
    assert_eq!(d.len(), 1, "{d:#?}");
    assert_eq!(d[0].code, "lmd::resolution");
    assert!(d[0].message.contains("dmu5"), "{}", d[0].message);
    assert!(
        d[0].help.as_deref().unwrap().contains("`s_decimals = 3`"),
        "{:?}",
        d[0].help
    );
    // And with them, it builds and writes S0.525 for 2100 W.
    let src = src.replace(
        "s_per_watt = 0.00025",
        "s_per_watt = 0.00025\n  s_decimals = 3",
    );
    let c = compile(&src, &mut ());
    let p = c.program.unwrap_or_else(|| panic!("{:?}", c.diagnostics));
    let mut sink = lmdc::back::MemorySink::default();
    lmdc::back::emit(
        p.machine(1).unwrap(),
        &lmdc::back::Templates::builtin().unwrap(),
        &mut sink,
    )
    .unwrap();
    let text = sink.text("twisted_duct_dmu5.ngc").unwrap();
    assert!(text.contains("S0.525"), "2100 W");
    assert!(text.contains("S1.000"), "4000 W");
}

#[test]
fn a_speed_that_rounds_to_zero_is_an_error_on_every_machine() {
    let d = errors(&tooth(&[
        ("speed = 6 mm/s)", "speed = 0.0004 mm/s)"),
        ("speed = 6 mm/s\n", "speed = 0.0004 mm/s\n"),
    ]));
    let res: Vec<_> = d.iter().filter(|d| d.code == "lmd::resolution").collect();
    assert_eq!(res.len(), 2, "{d:#?}");
    assert!(
        res.iter().any(|d| d.message.contains("$VEL.CP = 0")),
        "{res:#?}"
    );
    assert!(res.iter().any(|d| d.message.contains("F0")), "{res:#?}");
}

#[test]
fn a_full_scale_too_coarse_for_the_power_is_named() {
    let d = errors(&tooth(&[("full_scale = 2000 W", "full_scale = 1e9 W")]));
    assert_eq!(d.len(), 1, "{d:#?}");
    assert_eq!(d[0].code, "lmd::resolution");
    assert!(d[0].message.contains("$ANOUT[1] = 0"), "{}", d[0].message);
    assert!(
        d[0].help.as_deref().unwrap().contains("full_scale"),
        "{:?}",
        d[0].help
    );
}
