//! Smoke test of the rs274 harness (tests/support/rs274.rs) on a hand-written
//! 5-axis program. Skipped when rs274 is not installed, except under CI,
//! where a missing rs274 fails (install it with `.ci/install-rs274.sh`).

use crate::support::rs274;

use rs274::CanonCall::{self, *};

const FIVE_AXIS: &str = "\
%
(lmdc smoke: 5-axis A/C deposition)
G21 G90 G94
; a semicolon comment is dropped by rs274
G0 X0 Y0 Z50 A0 C0
G0 X10.5 Y-20.25 Z5
M3 S1000
M62 P0 (powder on, synced with motion)
M67 E0 Q2.5
G1 X12.12345 Y-20.25 Z5 A15 C-90 F1200
G1 X14 C-180.5
G4 P0.5
M63 P0
M68 E1 Q0
M5
G0 Z50
M2
%
";

fn write_temp(name: &str, text: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("lmdc-rs274-smoke-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn assert_close(got: f64, want: f64, what: &str) {
    // rs274 prints 4 decimals.
    assert!(
        (got - want).abs() <= 0.5e-4 + 1e-9,
        "{what}: got {got}, want {want}"
    );
}

#[test]
fn five_axis_program_canon_calls() {
    if !rs274::available("five_axis_program_canon_calls") {
        return;
    }
    let path = write_temp("five_axis.ngc", FIVE_AXIS);
    let all = rs274::interpret(&path).expect("rs274 accepts the program");
    let _ = std::fs::remove_dir_all(path.parent().unwrap());

    // Start-up preamble, then the program, then PROGRAM_END and resets.
    assert_eq!(all[0], LengthUnits("mm".into()));
    assert!(all.contains(&ProgramEnd));

    let body: Vec<CanonCall> = rs274::program_body(&all)
        .iter()
        .filter(|c| !rs274::is_interpreter_comment(c))
        .cloned()
        .collect();
    let expected_prefix = vec![
        Comment("lmdc smoke: 5-axis A/C deposition".into()),
        // G94 resets the feed rate, G21 selects mm.
        FeedRate(0.0),
        LengthUnits("mm".into()),
        Traverse {
            x: 0.0,
            y: 0.0,
            z: 50.0,
            a: 0.0,
            b: 0.0,
            c: 0.0,
        },
        Traverse {
            x: 10.5,
            y: -20.25,
            z: 5.0,
            a: 0.0,
            b: 0.0,
            c: 0.0,
        },
        SpindleSpeed(1000.0),
        SpindleOn,
        // The comment on a block comes before the block's action.
        Comment("powder on, synced with motion".into()),
        DigitalOut {
            index: 0,
            on: true,
            synced: true,
        },
        AnalogOut {
            index: 0,
            value: 2.5,
            synced: true,
        },
        FeedRate(1200.0),
    ];
    assert!(
        body.len() > expected_prefix.len(),
        "body too short: {body:#?}"
    );
    // SET_FEED_MODE(0, 0) is an Other between G94's comment and FeedRate(0).
    let body_no_other: Vec<CanonCall> = body
        .iter()
        .filter(|c| !matches!(c, Other(_)))
        .cloned()
        .collect();
    assert_eq!(
        &body_no_other[..expected_prefix.len()],
        &expected_prefix[..],
        "whole body: {body_no_other:#?}"
    );

    let rest = &body_no_other[expected_prefix.len()..];
    match rest[0] {
        Feed { x, y, z, a, b, c } => {
            assert_close(x, 12.12345, "x"); // printed as 12.1235 (4 decimals)
            assert_close(y, -20.25, "y");
            assert_close(z, 5.0, "z");
            assert_close(a, 15.0, "a");
            assert_close(b, 0.0, "b");
            assert_close(c, -90.0, "c");
        }
        ref other => panic!("want Feed, got {other:?}"),
    }
    // Modal: unchanged words keep their values.
    assert_eq!(
        rest[1],
        Feed {
            x: 14.0,
            y: -20.25,
            z: 5.0,
            a: 15.0,
            b: 0.0,
            c: -180.5
        }
    );
    assert_eq!(
        &rest[2..],
        &[
            Dwell(0.5),
            DigitalOut {
                index: 0,
                on: false,
                synced: true
            },
            AnalogOut {
                index: 1,
                value: 0.0,
                synced: false
            },
            SpindleOff,
            Traverse {
                x: 14.0,
                y: -20.25,
                z: 50.0,
                a: 15.0,
                b: 0.0,
                c: -180.5
            },
            // What M2 itself does before PROGRAM_END().
            FeedRate(0.0),
            SpindleOff,
        ][..],
        "tail of body: {rest:#?}"
    );
}

#[test]
fn interpreter_errors_are_reported() {
    if !rs274::available("interpreter_errors_are_reported") {
        return;
    }
    let cases = [
        ("G21 G90\nM100\nM2\n", "Unknown m code used: M100"),
        ("G21 G90\nG1 X1\nM2\n", "Cannot do g1 with zero feed rate"),
        ("G21 G90\nG0 U1\nM2\n", "Bad character 'u' used"),
        (
            "G21 G90\nG0 X1\n",
            "File ended with no percent sign or program end",
        ),
    ];
    for (src, want) in cases {
        let err = rs274::interpret_source(src).expect_err(src);
        assert!(err.contains(want), "{src:?}: error {err:?} lacks {want:?}");
    }
}

#[test]
fn inch_programs_report_inches() {
    if !rs274::available("inch_programs_report_inches") {
        return;
    }
    let all = rs274::interpret_source("G20 G90 G94\nG1 X1 F10\nM2\n").unwrap();
    let body = rs274::program_body(&all);
    assert!(body.contains(&LengthUnits("inch".into())));
    assert!(body.contains(&FeedRate(10.0)));
    assert!(body.contains(&Feed {
        x: 1.0,
        y: 0.0,
        z: 0.0,
        a: 0.0,
        b: 0.0,
        c: 0.0
    }));
}

#[test]
fn parallel_runs_do_not_interfere() {
    // rs274 mmaps $HOME/.tool.mmap; the wrapper gives each run its own HOME.
    if !rs274::available("parallel_runs_do_not_interfere") {
        return;
    }
    let handles: Vec<_> = (0..8)
        .map(|i| {
            std::thread::spawn(move || {
                let src = format!("G21 G90 G94\nG1 X{i} C{i} F100\nM2\n");
                let all = rs274::interpret_source(&src).unwrap();
                let i = i as f64;
                assert!(all.contains(&Feed {
                    x: i,
                    y: 0.0,
                    z: 0.0,
                    a: 0.0,
                    b: 0.0,
                    c: i
                }));
            })
        })
        .collect();
    for h in handles {
        h.join().unwrap();
    }
}

#[test]
fn parser_handles_sample_output() {
    // Runs without rs274: real output lines as LinuxCNC 2.9 prints them.
    let out = "    1 N..... USE_LENGTH_UNITS(CANON_UNITS_MM)
    6 N..... ON_RESET()
    7 N10    COMMENT(\"Upper Case \"quoted\" comment\")
 hello 0.000000
    8 N20    STRAIGHT_TRAVERSE(-0.0000, -0.0001, 0.5000, 370.0000, 0.0000, -720.5000)
    9 N..... SET_SPINDLE_SPEED(0, 1000.0000)
   10 N..... START_SPINDLE_COUNTERCLOCKWISE(0)
   11 N..... SET_AUX_OUTPUT_BIT(1)
   12 N..... CLEAR_AUX_OUTPUT_BIT(1)
   13 N..... SET_AUX_OUTPUT_VALUE(1,100.000000)
   14 N..... MESSAGE(\" start deposition\")
   15 N..... ARC_FEED(2.0000, 0.0000, 1.0000, 0.0000, -1, 0.0000, 0.0000, 0.0000, 0.0000)
   16 N..... PROGRAM_END()
   17 N..... ON_RESET()
";
    let calls = rs274::parse_canon(out).unwrap();
    assert_eq!(
        calls,
        vec![
            LengthUnits("mm".into()),
            Other("ON_RESET()".into()),
            Comment("Upper Case \"quoted\" comment".into()),
            Other("hello 0.000000".into()),
            Traverse {
                x: -0.0,
                y: -0.0001,
                z: 0.5,
                a: 370.0,
                b: 0.0,
                c: -720.5
            },
            SpindleSpeed(1000.0),
            SpindleOnCcw,
            DigitalOut {
                index: 1,
                on: true,
                synced: false
            },
            DigitalOut {
                index: 1,
                on: false,
                synced: false
            },
            AnalogOut {
                index: 1,
                value: 100.0,
                synced: false
            },
            Message(" start deposition".into()),
            Other(
                "ARC_FEED(2.0000, 0.0000, 1.0000, 0.0000, -1, 0.0000, 0.0000, 0.0000, 0.0000)"
                    .into()
            ),
            ProgramEnd,
            Other("ON_RESET()".into()),
        ]
    );
    assert_eq!(rs274::program_body(&calls).len(), 10);
    assert!(rs274::parse_canon("    1 N..... STRAIGHT_FEED(1.0, 2.0)\n").is_err());
}
