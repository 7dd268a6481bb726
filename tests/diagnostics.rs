//! Diagnostics whose advice is computed: applying the advice silences them.
//! (What every example's diagnostics say is in tests/cases/errors/.)

use lmdc::pipeline::compile;

/// The seam advice is computed: applying it silences the warning, and it
/// never advises the seam the file already has (issue 9).
#[test]
fn the_seam_advice_is_one_that_works() {
    let duct = std::fs::read_to_string("examples/twisted_duct.lmd").unwrap();
    for (twist, seam) in [(45, 0), (90, 90)] {
        let src = duct
            .replace("twist = 45 deg", &format!("twist = {twist} deg"))
            .replace("seam = 90 deg", &format!("seam = {seam} deg"));
        let c = compile(&src, &mut ());
        let warning = c
            .diagnostics
            .iter()
            .find(|d| d.code == "lmd::seam-at-bend-extreme")
            .unwrap_or_else(|| panic!("twist {twist}, seam {seam}: no warning"));
        let help = warning.help.as_deref().unwrap_or("");
        let advised = help
            .split("`seam = ")
            .nth(1)
            .and_then(|rest| rest.split(" deg`").next())
            .unwrap_or_else(|| panic!("no seam advised: {help}"));
        assert_ne!(advised, seam.to_string(), "{help}");
        let fixed = src.replace(
            &format!("seam = {seam} deg"),
            &format!("seam = {advised} deg"),
        );
        let c = compile(&fixed, &mut ());
        assert!(c.program.is_some(), "{:?}", c.diagnostics);
        assert!(
            !c.diagnostics
                .iter()
                .any(|d| d.code == "lmd::seam-at-bend-extreme"),
            "twist {twist}: seam {advised} still warns: {:?}",
            c.diagnostics
        );
    }
}

#[test]
fn each_fix_of_a_bend_too_tight_builds() {
    // Parse each value out of the help, write it into the file, compile.
    let path = "examples/errors/bend_too_tight.lmd";
    let src = std::fs::read_to_string(path).unwrap();
    let c = lmdc::pipeline::compile(&src, &mut ());
    let d = c
        .diagnostics
        .iter()
        .find(|d| d.code == "lmd::bend-too-tight");
    let help = d
        .and_then(|d| d.help.clone())
        .expect("a bend-too-tight help");
    let number = |before: &str, after: &str| -> f64 {
        let r = help
            .split(before)
            .nth(1)
            .unwrap_or_else(|| panic!("{before:?}: {help}"));
        r.split(after).next().unwrap().parse().unwrap()
    };
    let radius = number("a bend radius of at least ", " mm");
    let speed = number("speeds up to ", " mm/s");
    let percent = number("a section at most ", "% of the declared size");
    let size = format!("{} mm", 60.0 * percent / 100.0);
    let edits = [
        vec![("let R1 = 100 mm", format!("let R1 = {radius} mm"))],
        // "at least": a few millimetres more still builds.
        vec![("let R1 = 100 mm", format!("let R1 = {} mm", radius + 7.0))],
        vec![(
            "speed = 7 mm/s .. 10 mm/s",
            format!("speed = 7 mm/s .. {speed} mm/s"),
        )],
        vec![
            ("let D1 = 60 mm", format!("let D1 = {size}")),
            ("let L1 = 60 mm", format!("let L1 = {size}")),
        ],
    ];
    for edit in edits {
        let mut fixed = src.clone();
        for (from, to) in &edit {
            assert!(fixed.contains(from), "{from}");
            fixed = fixed.replacen(from, to, 1);
        }
        let c = lmdc::pipeline::compile(&fixed, &mut ());
        assert!(c.program.is_some(), "{edit:?}: {:#?}", c.diagnostics);
    }
}
