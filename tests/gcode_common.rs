//! Helpers shared by the G-code tests (included with `#[path]`; as a test target of
//! its own it has no tests).
#![allow(dead_code)]

#[path = "support/fixture.rs"]
pub mod fixture;

use lmdc::back::{MemorySink, Templates};
use lmdc::diag::Diagnostics;
use lmdc::ir::*;
use lmdc::verify::Verified;

/// Verifies `p` (it must pass every check).
pub fn verified(p: Program) -> Verified {
    lmdc::verify::verify(p, lmdc::verify::Select::All).expect("test IR passes the checks")
}

/// Verifies `p`, expecting it to be refused; returns the errors.
pub fn refused(p: Program) -> Diagnostics {
    match lmdc::verify::verify(p, lmdc::verify::Select::All) {
        Err(d) => d,
        Ok(_) => panic!("want the checks to refuse the plan"),
    }
}

/// Emits machine `index` of `p` and returns (file name, text).
pub fn emit(p: &Verified, index: usize) -> (String, String) {
    let mut sink = MemorySink::default();
    let m = p.machine(index).expect("a verified machine");
    assert!(
        matches!(m.machine(), Machine::Cnc(_)),
        "machine {index} is not a CNC"
    );
    lmdc::back::emit(m, &Templates::builtin().unwrap(), &mut sink)
        .unwrap_or_else(|e| panic!("emit failed: {e:?}"));
    assert_eq!(sink.files.len(), 1, "one file per CNC");
    let (name, bytes) = sink.files.pop().unwrap();
    (name, String::from_utf8(bytes).expect("G-code is UTF-8"))
}

/// The fixture's 5-axis LinuxCNC machine with another kinematics.
pub fn cnc5_with(kin: Kinematics) -> Cnc {
    let mut c = fixture::cnc5();
    c.kinematics = kin;
    c
}

/// A 3-axis LinuxCNC machine.
pub fn cnc3() -> Cnc {
    let mut c = fixture::cnc5();
    c.name = "mill3".into();
    c.axes = 3;
    c.kinematics = Kinematics::Xyz;
    c
}

/// A Fagor 8070-like dialect: `;` comments, `#RTCP ON`/`#RTCP OFF`.
pub fn fagor8070() -> Dialect {
    Dialect {
        profile: "fagor8070".into(),
        laser_on: "M3".into(),
        laser_off: "M5".into(),
        s_per_watt: 1.0,
        s_decimals: 0,
        preamble: vec!["G21 G90 G94 G17".into()],
        postamble: vec!["M30".into()],
        dwell: "G4 P{s}".into(),
        tcp_on: "#RTCP ON".into(),
        tcp_off: "#RTCP OFF".into(),
        comment: CommentStyle::Semicolon,
        padded_g: false,
        extension: "nc".into(),
        feed: FeedUnit::MmPerMin,
    }
}

/// A Sinumerik 840D-like dialect: TRAORI/TRAFOOF, `.mpf`.
pub fn sinumerik840d() -> Dialect {
    Dialect {
        profile: "sinumerik840d".into(),
        laser_on: "M10".into(),
        laser_off: "M11".into(),
        s_per_watt: 0.1,
        s_decimals: 1,
        preamble: vec!["G71 G90 G94 G17".into(), "G64".into()],
        postamble: vec!["M30".into()],
        dwell: "G4 P{s}".into(),
        tcp_on: "TRAORI".into(),
        tcp_off: "TRAFOOF".into(),
        comment: CommentStyle::Semicolon,
        padded_g: false,
        extension: "mpf".into(),
        feed: FeedUnit::MmPerMin,
    }
}

/// The dialect of seed 002's control: G00/G01, M20/M21 laser, S = power.
pub fn m20() -> Dialect {
    Dialect {
        profile: "m20".into(),
        laser_on: "M20".into(),
        laser_off: "M21".into(),
        s_per_watt: 1.0,
        s_decimals: 0,
        preamble: vec!["G21 G90 G94".into()],
        postamble: vec!["M30".into()],
        dwell: "G4 P{s}".into(),
        tcp_on: String::new(),
        tcp_off: String::new(),
        comment: CommentStyle::Semicolon,
        padded_g: true,
        extension: "nc".into(),
        feed: FeedUnit::MmPerS,
    }
}

/// A planar part for a 3-axis machine: `layers` flat square layers 0.5 mm apart,
/// each two deposit paths (a square contour, then a raster line that starts where
/// the contour ended, so it joins) and a laser-off gap inside the raster.
pub fn planar(layers: usize, machines: Vec<Machine>) -> Program {
    let mut out = Vec::new();
    for i in 0..layers {
        let z = 0.5 * i as f64;
        let pt = |x: f64, y: f64, speed: f32, power: f32, on: bool| Point {
            pos: [x, y, z],
            normal: [0.0, 0.0, 1.0],
            tangent: [1.0, 0.0, 0.0],
            layer_height: 0.5,
            speed,
            power,
            powder: 8.0,
            defocus: -3.0,
            laser_on: on,
            style: 0,
            pitch: 0.0,
            rise: 0.0,
        };
        let p = 1500.0 + 100.0 * i as f32;
        let contour = vec![
            pt(0.0, 0.0, 6.0, p, true),
            // A change too small to print: F and S stay as they are.
            pt(20.0, 0.0, 6.0001, p + 0.2, true),
            pt(20.0, 20.0, 8.0, p, true),
            pt(0.0, 20.0, 8.0, p + 50.0, true),
            // On: the raster joins here and the laser stays on.
            pt(0.0, 0.0, 8.0, p, true),
        ];
        let raster = vec![
            pt(0.0, 0.0, 7.0, p, true),
            pt(10.0, 10.0, 7.0, p, false),
            // Back on after a gap, hotter: S must be set before the laser fires.
            pt(12.0, 12.0, 7.0, p + 200.0, true),
            pt(20.0, 20.0, 7.0, p, false),
        ];
        // A separate island: needs a transition.
        let island = vec![pt(40.0, 0.0, 6.0, p, true), pt(45.0, 0.0, 6.0, p, false)];
        out.push(Layer {
            index: i,
            station: i as f64 / layers as f64,
            frame: Frame {
                origin: [0.0, 0.0, z],
                x: [1.0, 0.0, 0.0],
                y: [0.0, 1.0, 0.0],
                z: [0.0, 0.0, 1.0],
            },
            paths: vec![
                Path {
                    kind: PathKind::Contour,
                    points: contour,
                },
                Path {
                    kind: PathKind::Infill,
                    points: raster,
                },
                Path {
                    kind: PathKind::Wall,
                    points: island,
                },
            ],
            label: String::new(),
            on_plate: false,
        });
    }
    Program {
        fixtures: Vec::new(),
        format: FORMAT.into(),
        version: VERSION_BASIC,
        part: "planar block".into(),
        units: Units::default(),
        limits: Limits {
            layer_height: [0.1, 1.0],
            speed: [1.0, 50.0],
            power: [0.0, 4000.0],
            bead_width: 0.0,
            rise_tolerance: lmdc::ir::RISE_TOLERANCE,
            max_drift: lmdc::ir::MAX_DRIFT,
            max_overhang: None,
        },
        machines,
        styles: Vec::new(),
        heat: Heat::default(),
        thermal: None,
        continuous: false,
        ring: None,
        bead: None,
        layers: out,
        origins: Origins::default(),
    }
}
