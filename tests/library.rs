//! The library's front door (`lmdc::compile`, docs/testing.md) and the
//! worked property of examples/laser_property.rs, over every example and,
//! with proptest, over swept `--set` values of the flange.

#[path = "../examples/laser_property.rs"]
#[allow(dead_code)]
mod laser_property;

use lmdc::diag::Code;
use proptest::prelude::*;

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
