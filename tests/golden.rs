//! Golden programs: every file lmdc writes for tests/golden/small_duct.lmd (a
//! KUKA robot split into modules, LinuxCNC, Fagor 8070 and M20 CNCs) and for the
//! three planar examples (sprocket tooth, styled chord, the flange with its
//! holes, linked raster, rotating seams, placement, gas and powder), the three
//! of seed 003 (ramp wall, wedge, ramp cuboid) and the ring of seed 004 with
//! its height loop, as insta snapshots.
//! Review every diff line by line: these are what machines run.

use lmdc::back::{MemorySink, Templates};
use lmdc::pipeline::{compile, emit};

/// Snapshots the list of files written for `path` (as `<prefix>files`) and each
/// file (as `<prefix><name>`).
fn programs(path: &str, prefix: &str) {
    let src = std::fs::read_to_string(path).unwrap();
    let c = compile(&src, &mut ());
    let p = c.program.expect("compiles");
    let mut sink = MemorySink::default();
    emit(&p, &Templates::builtin().unwrap(), &mut sink, &mut ()).expect("emits");
    let mut names: Vec<&str> = sink.files.iter().map(|(n, _)| n.as_str()).collect();
    names.sort();
    insta::assert_snapshot!(format!("{prefix}files"), names.join("\n"));
    for (name, bytes) in &sink.files {
        let text = String::from_utf8(bytes.clone()).expect("UTF-8");
        insta::assert_snapshot!(format!("{prefix}{}", name.replace('.', "_")), text);
    }
}

#[test]
fn small_duct_programs() {
    programs("tests/golden/small_duct.lmd", "");
}

#[test]
fn sprocket_tooth_programs() {
    programs("examples/sprocket_tooth.lmd", "sprocket__");
}

#[test]
fn styled_chord_programs() {
    programs("examples/styled_chord.lmd", "chord__");
}

#[test]
fn flange_programs() {
    programs("examples/flange.lmd", "flange__");
}

// Seed 003: variable-thickness layers on a 3-axis CNC and a KUKA robot.

#[test]
fn ramp_wall_programs() {
    programs("examples/ramp_wall.lmd", "ramp_wall__");
}

#[test]
fn wedge_programs() {
    programs("examples/wedge.lmd", "wedge__");
}

#[test]
fn ramp_cuboid_programs() {
    programs("examples/ramp_cuboid.lmd", "ramp_cuboid__");
}

// Seed 004: a ring whose height loop runs on the robot (KRL) and the mill
// (LinuxCNC).

#[test]
fn segmented_ring_programs() {
    programs("examples/segmented_ring.lmd", "segmented_ring__");
}
