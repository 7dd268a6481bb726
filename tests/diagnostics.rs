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
