//! Why a scan covers no place under a footprint inside its span
//! (docs/repair.md, *The surface*): a `cell` finer than the points'
//! spacing, or `units` that spread them apart. The worn pad's scan has
//! its points every 0.5 mm.

use super::{compile, example_files, messages};

fn worn_pad(scan: &str) -> String {
    include_str!("../../examples/worn_pad.lmd").replace(
        "scan(file = \"repair/worn_pad.ply\", units = mm, cell = 1 mm)",
        &format!("scan(file = \"repair/worn_pad.ply\", {scan})"),
    )
}

fn help(src: &str) -> String {
    let c = compile(src, example_files(&["worn_pad.ply"]));
    let d = super::diagnostic(&c, "lmd::scan-coverage");
    d.help.clone().unwrap()
}

/// Cells of 0.2 mm under points 0.5 mm apart: the help says how few
/// cells the points fill, their spacing (the box's area over the points:
/// 66 × 26 mm over its 7 049 points, 0.4934 mm) and the cell that works,
/// 1.5 spacings rounded up to 0.1 mm; that cell builds. Read in inches,
/// the same points lie 12.5 mm apart: the help asks about `units` first.
#[test]
fn a_cell_finer_than_the_points_or_the_wrong_units_is_named() {
    let src = include_str!("../../examples/worn_pad.lmd");
    assert!(src.contains("scan(file = \"repair/worn_pad.ply\", units = mm, cell = 1 mm)"));
    let fine = help(&worn_pad("units = mm, cell = 0.2 mm"));
    let spacing = (66.0f64 * 26.0 / 7049.0).sqrt();
    assert!(fine.contains("of its 0.2 mm cells"), "{fine}");
    assert!(
        fine.contains(&format!("about {:.4} mm apart", spacing)),
        "{fine}"
    );
    let cell = (spacing * 15.0).ceil() / 10.0;
    assert!(
        fine.contains(&format!("a `cell` of at least {cell} mm")),
        "{fine}"
    );
    let c = compile(
        &worn_pad(&format!("units = mm, cell = {cell} mm")),
        example_files(&["worn_pad.ply"]),
    );
    assert!(c.program.is_some(), "{}", messages(&c));
    let inch = help(&worn_pad("units = in, cell = 1 mm"));
    assert!(inch.contains("check its `units` first"), "{inch}");
    assert!(inch.contains("x -838.2 .. 838.2 mm"), "{inch}");
}
