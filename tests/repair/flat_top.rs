//! A flat top on a scan that no layer count lays (docs/repair.md, *The
//! layers*): the help names the flat tops a count lays, as the slicer
//! plans them (each track's own strip included), not a top reshaped.

use super::{compile, example_files, messages, number_after};

fn worn_pad(top: f64) -> String {
    include_str!("../../examples/worn_pad.lmd").replace("top = 13 mm", &format!("top = {top} mm"))
}

/// The worn pad up to 10.3 mm (0.29 .. 1.79 mm to add) and up to 11.1 mm
/// (ratio 2.37 against the bead's 2.25): each refused with the same flat
/// tops, from 12.05 to 12.19 mm in 3 layers; both ends of that range
/// build in 3 layers, and a top just under it (12 mm, whose edge track's
/// narrow strip needs a speed over the bead's) does not.
#[test]
fn a_flat_top_no_count_lays_is_told_the_flat_tops_that_plan() {
    let mut named = Vec::new();
    for top in [10.3, 11.1] {
        let c = compile(&worn_pad(top), example_files(&["worn_pad.ply"]));
        let d = super::diagnostic(&c, "lmd::no-layer-count");
        let help = d.help.clone().unwrap();
        assert!(!help.contains("where the tracks run"), "{help}");
        let lo = number_after(&help, "a top from ", ' ');
        let hi = number_after(&help, &format!("a top from {lo} to "), ' ');
        let count = number_after(&help, "mm (", ' ');
        named.push((lo, hi, count));
    }
    assert_eq!(named[0], named[1]);
    let (lo, hi, count) = named[0];
    assert!(lo < hi, "{named:?}");
    for top in [lo, hi] {
        let c = compile(&worn_pad(top), example_files(&["worn_pad.ply"]));
        let m = messages(&c);
        let p = c.program.unwrap_or_else(|| panic!("{top}: {m}"));
        assert_eq!(p.ir().layers.len() as f64, count, "top {top}");
    }
    let under = compile(&worn_pad(lo - 0.05), example_files(&["worn_pad.ply"]));
    assert!(under.program.is_none(), "{} mm builds", lo - 0.05);
}
