//! Where the part sits on a CNC: axis limits apply to the program's positions
//! plus the declared origin, the help names the origins that fit, and the
//! program selects the work offset that holds it.

use crate::support::example;

use example::tooth;
use lmdc::pipeline::compile;

/// The tooth on a mill whose X travels 0 .. 300 mm (program X spans about
/// -0.3 .. 41.3 mm with the track ends): its origin must be placed.
const MILL: &str = "x = -50 mm .. 150 mm";

#[test]
fn limits_apply_to_the_placed_part_and_the_help_names_the_origins_that_fit() {
    let src = tooth(&[(MILL, "x = 100 mm .. 400 mm")]);
    let c = compile(&src, &mut ());
    let d: Vec<_> = c
        .diagnostics
        .iter()
        .filter(|d| d.code == "lmd::axis-limit")
        .collect();
    assert_eq!(d.len(), 1, "{:?}", c.diagnostics);
    let help = d[0].help.as_deref().unwrap();
    // Origins from 100 − min to 400 − max fit; the help says so.
    assert!(
        help.contains("place the part with its origin at X"),
        "{help}"
    );
    assert!(help.contains("(now 0)"), "{help}");
    // Placed inside, it builds, and the program selects G55 and says where.
    let src = tooth(&[
        (MILL, "x = 100 mm .. 400 mm"),
        (
            "clearance = 5 mm\n  limits",
            "clearance = 5 mm\n  work_offset = 2\n  origin = [200 mm, 0 mm, 0 mm]\n  limits",
        ),
    ]);
    let c = compile(&src, &mut ());
    let p = c.program.unwrap_or_else(|| panic!("{:?}", c.diagnostics));
    let mut sink = lmdc::back::MemorySink::default();
    let m = p
        .machines()
        .find(|m| m.machine().name() == "mill3")
        .unwrap();
    lmdc::back::emit(m, &lmdc::back::Templates::builtin().unwrap(), &mut sink).unwrap();
    let text = sink.text("sprocket_tooth_mill3.ngc").unwrap();
    assert!(
        text.contains(
            "(part origin at X200.000 Y0.000 Z0.000 in machine coordinates: set G55 to it)"
        ),
        "{text}"
    );
    assert!(text.lines().any(|l| l == "G55"), "{text}");
}

#[test]
fn a_part_longer_than_the_travel_says_so() {
    let src = tooth(&[(MILL, "x = 0 mm .. 30 mm")]);
    let c = compile(&src, &mut ());
    let d: Vec<_> = c
        .diagnostics
        .iter()
        .filter(|d| d.code == "lmd::axis-limit")
        .collect();
    assert_eq!(d.len(), 1, "{:?}", c.diagnostics);
    assert!(
        d[0].help
            .as_deref()
            .unwrap()
            .contains("more than the 30 mm the axis travels"),
        "{:?}",
        d[0].help
    );
}

#[test]
fn a_bad_placement_is_reported() {
    let src = tooth(&[(
        "clearance = 5 mm\n  limits",
        "clearance = 5 mm\n  work_offset = 7\n  origin = [1 mm, 2 mm]\n  limits",
    )]);
    let c = compile(&src, &mut ());
    assert_eq!(c.diagnostics.error_count(), 2, "{:?}", c.diagnostics);
}
