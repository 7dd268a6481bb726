//! The G-code program as text: modal words, laser switching, transitions, vendor
//! dialects, refusals, a golden program and determinism.

use crate::support::gcode_common as common;
use common::fixture::*;
use common::*;
use lmdc::back::{MemorySink, Templates};
use lmdc::ir::*;

/// One line of a program, as far as these tests care.
#[derive(Debug, PartialEq)]
enum Line {
    /// G0/G1 (`rapid`), with its words.
    Move {
        rapid: bool,
        words: Vec<(char, f64)>,
    },
    /// An `S` word on its own.
    S(f64),
    LaserOn,
    LaserOff,
    Comment,
    Other(String),
}

fn word(line: &str, letter: char) -> Option<f64> {
    line.split_whitespace()
        .find(|w| w.starts_with(letter))
        .map(|w| w[1..].parse().unwrap_or_else(|_| panic!("bad word {w:?}")))
}

fn parse(text: &str, d: &Dialect) -> Vec<Line> {
    let (g0, g1) = if d.padded_g {
        ("G00 ", "G01 ")
    } else {
        ("G0 ", "G1 ")
    };
    text.lines()
        .map(|l| {
            if l.starts_with('(') || l.starts_with(';') {
                Line::Comment
            } else if l == d.laser_on {
                Line::LaserOn
            } else if l == d.laser_off {
                Line::LaserOff
            } else if l.starts_with(g0) || l.starts_with(g1) {
                Line::Move {
                    rapid: l.starts_with(g0),
                    words: l
                        .split_whitespace()
                        .skip(1)
                        .map(|w| {
                            let v = w[1..]
                                .parse()
                                .unwrap_or_else(|_| panic!("bad word {w:?} in {l:?}"));
                            (w.chars().next().unwrap(), v)
                        })
                        .collect(),
                }
            } else if l.starts_with('S') {
                Line::S(word(l, 'S').unwrap())
            } else {
                Line::Other(l.to_string())
            }
        })
        .collect()
}

/// Checks the modal rules on a program: F and S only when they change, the laser
/// switched only when its state changes, never a G0 with the laser on, and S set
/// before the laser fires. Returns (laser starts, deposit lines).
fn check_modal(text: &str, d: &Dialect) -> (usize, usize) {
    let (mut f, mut s, mut laser) = (None, None, false);
    let (mut starts, mut deposits) = (0, 0);
    let lines = parse(text, d);
    for (i, line) in lines.iter().enumerate() {
        match line {
            Line::Move { rapid, words } => {
                for &(letter, v) in words {
                    match letter {
                        'F' => {
                            assert!(!rapid, "line {}: F on a G0", i + 1);
                            assert_ne!(f, Some(v), "line {}: F{v} repeated", i + 1);
                            f = Some(v);
                        }
                        'S' => {
                            assert_ne!(s, Some(v), "line {}: S{v} repeated", i + 1);
                            s = Some(v);
                        }
                        _ => {}
                    }
                }
                if *rapid {
                    assert!(!laser, "line {}: G0 with the laser on", i + 1);
                } else {
                    assert!(f.is_some(), "line {}: G1 before any F", i + 1);
                    if laser {
                        deposits += 1;
                    }
                }
            }
            Line::S(v) => {
                assert_ne!(s, Some(*v), "line {}: S{v} repeated", i + 1);
                s = Some(*v);
            }
            Line::LaserOn => {
                assert!(!laser, "line {}: laser on twice", i + 1);
                laser = true;
                starts += 1;
                // The laser fires at the power of the move that follows.
                let next = lines[i + 1..]
                    .iter()
                    .find_map(|l| match l {
                        Line::Move { words, .. } => Some(words),
                        _ => None,
                    })
                    .expect("a move after laser on");
                assert!(
                    !next.iter().any(|w| w.0 == 'S'),
                    "line {}: S changes only after the laser is on",
                    i + 1
                );
            }
            Line::LaserOff => {
                assert!(laser, "line {}: laser off twice", i + 1);
                laser = false;
            }
            Line::Comment | Line::Other(_) => {}
        }
    }
    assert!(!laser, "laser on at the end");
    (starts, deposits)
}

fn ir_deposits(p: &Program) -> usize {
    p.layers
        .iter()
        .flat_map(|l| &l.paths)
        .flat_map(|p| p.points.windows(2))
        .filter(|w| w[0].laser_on)
        .count()
}

#[test]
fn file_is_named_after_part_and_machine() {
    let p = verified(bent_tube(2, 4, 20.0, vec![Machine::Cnc(cnc5())]));
    let (name, _) = emit(&p, 0);
    assert_eq!(name, "bent_tube_mill5.ngc");
}

#[test]
fn modal_words_and_laser_on_five_axis() {
    let p = verified(bent_tube(5, 24, 40.0, vec![Machine::Cnc(cnc5())]));
    let (_, text) = emit(&p, 0);
    let (starts, deposits) = check_modal(&text, &cnc5().dialect);
    // One laser start per layer: every layer is one closed wall.
    assert_eq!(starts, 5);
    assert_eq!(deposits, ir_deposits(p.ir()));
}

#[test]
fn modal_words_and_laser_on_planar_part() {
    let p = verified(planar(3, vec![Machine::Cnc(cnc3())]));
    let (_, text) = emit(&p, 0);
    let (starts, deposits) = check_modal(&text, &cnc3().dialect);
    // Per layer: contour + joined raster start, raster after its gap, island.
    assert_eq!(starts, 3 * 3);
    assert_eq!(deposits, ir_deposits(p.ir()));
    // The hotter restart after the gap sets S on its own line, then fires.
    assert!(
        text.contains("G0 X12.000 Y12.000 Z-3.000\nS1700\nM3\n"),
        "{text}"
    );
}

/// The planar examples: every track fires the laser once; F and S are written
/// only when they change — in the styled chord, at each end of a styled track.
#[test]
fn modal_words_in_the_planar_examples() {
    for (file, styled) in [
        ("examples/sprocket_tooth.lmd", false),
        ("examples/styled_chord.lmd", true),
    ] {
        let src = std::fs::read_to_string(file).unwrap();
        let p = lmdc::pipeline::compile(&src, &mut ())
            .program
            .unwrap_or_else(|| panic!("{file} compiles"));
        for (index, m) in p.ir().machines.iter().enumerate() {
            let Machine::Cnc(cnc) = m else { continue };
            let (_, text) = emit(&p, index);
            // The postamble switches the laser off once more, for safety.
            let body = &text[..text.find("end of ").expect("an end comment")];
            let (starts, deposits) = check_modal(body, &cnc.dialect);
            let tracks: usize = p.ir().layers.iter().map(|l| l.paths.len()).sum();
            assert_eq!(starts, tracks, "{file}: one laser start a track");
            assert_eq!(deposits, ir_deposits(p.ir()), "{file}");
            // Speed changes between consecutive feed moves — each track's
            // approach at its first speed, then its deposits — are the only
            // F changes after the first F (a track's speed follows the
            // strip it fills: a contour a bead from the raster runs slower;
            // F is written to 0.1 mm/min).
            let speeds: Vec<i64> = p
                .ir()
                .layers
                .iter()
                .flat_map(|l| &l.paths)
                .flat_map(|path| {
                    let deposits = path.points.iter().filter(|q| q.laser_on);
                    std::iter::once(&path.points[0]).chain(deposits)
                })
                .map(|q| (f64::from(q.speed) * 600.0).round() as i64)
                .collect();
            let changes = speeds.windows(2).filter(|w| w[0] != w[1]).count();
            let f_words = body
                .lines()
                .filter(|l| l.starts_with('G'))
                .filter(|l| l.split_whitespace().any(|w| w.starts_with('F')))
                .count();
            assert_eq!(f_words, changes + 1, "{file}");
            // Style changes between consecutive tracks are the only S
            // changes after the first S.
            let powers: Vec<f32> = p
                .ir()
                .layers
                .iter()
                .flat_map(|l| &l.paths)
                .map(|path| path.points[0].power)
                .collect();
            let power_changes = powers.windows(2).filter(|w| w[0] != w[1]).count();
            let s_words = body
                .lines()
                .filter(|l| l.starts_with('G'))
                .filter(|l| l.split_whitespace().any(|w| w.starts_with('S')))
                .count();
            assert_eq!(s_words, power_changes + 1, "{file}");
            assert_eq!(power_changes > 0, styled, "{file}");
        }
    }
}

#[test]
fn transitions_retract_along_the_normal() {
    let p = verified(bent_tube(3, 8, 30.0, vec![Machine::Cnc(cnc5())]));
    let (_, text) = emit(&p, 0);
    let ir = p.ir();
    let moves: Vec<&str> = text.lines().filter(|l| l.starts_with('G')).collect();
    // The retract after layer 1 and the positions above layer 2's start.
    let last = ir.layers[0].paths[0].points.last().unwrap();
    let next = &ir.layers[1].paths[0].points[0];
    let up = |pt: &Point, d: f64| {
        let f = pt.focus();
        [
            f[0] + d * pt.normal[0] as f64,
            f[1] + d * pt.normal[1] as f64,
            f[2] + d * pt.normal[2] as f64,
        ]
    };
    let xyz = |l: &str| {
        [
            word(l, 'X').unwrap(),
            word(l, 'Y').unwrap(),
            word(l, 'Z').unwrap(),
        ]
    };
    assert!(moves[1].starts_with("G0 "), "the motion starts with a G0");
    // ... of Z alone, to the safe height, then across at that height.
    let only_z = moves[1].split_whitespace().skip(1).collect::<Vec<_>>();
    assert!(
        only_z.len() == 1 && only_z[0].starts_with('Z'),
        "{}",
        moves[1]
    );
    assert_eq!(word(moves[2], 'Z'), word(moves[1], 'Z'), "{}", moves[2]);
    let close = |a: [f64; 3], b: [f64; 3]| (0..3).all(|k| (a[k] - b[k]).abs() < 1e-3);
    // Layer 1 is a closed ring: its end is above its start too, so look after the
    // approach.
    let k = 4 + moves[4..]
        .windows(3)
        .position(|w| {
            w.iter()
                .all(|l| l.starts_with("G0 ") || l.starts_with("G1 "))
                && close(xyz(w[0]), up(last, 10.0))
        })
        .expect("a retract 10 mm up the nozzle after layer 1");
    assert!(moves[k].starts_with("G0 "));
    assert!(close(xyz(moves[k + 1]), up(next, 10.0)), "{}", moves[k + 1]);
    assert!(moves[k + 1].starts_with("G0 "));
    assert!(close(xyz(moves[k + 2]), next.focus()), "{}", moves[k + 2]);
    assert!(moves[k + 2].starts_with("G1 "), "approach at feed");
    // The head turns while retracted, not during the approach.
    assert_eq!(word(moves[k + 1], 'A'), word(moves[k + 2], 'A'));
    assert_ne!(word(moves[k], 'A'), word(moves[k + 1], 'A'));
}

#[test]
fn a_new_layer_starts_with_a_transition_even_where_the_last_ended() {
    // Two layers on the same plane, the second starting where the first ended.
    let mut ir = planar(2, vec![Machine::Cnc(cnc3())]);
    for l in &mut ir.layers {
        l.paths.truncate(1);
        for pt in &mut l.paths[0].points {
            pt.pos[2] = 0.0;
        }
    }
    // The contour is closed and leaves the laser on (it is meant to be joined).
    let end = ir.layers[0].paths[0].points.last().unwrap();
    assert_eq!(end.pos, ir.layers[1].paths[0].points[0].pos);
    assert!(end.laser_on);
    let (_, text) = emit(&verified(ir), 0);
    // The laser goes off where the layer's last deposit ends, before the next
    // layer's block (docs/ir.md: on exactly during deposit moves).
    let first = text.split("(layer 2 of 2").next().unwrap();
    assert!(first.trim_end().ends_with("M5"), "{text}");
    let second = text.split("(layer 2 of 2").nth(1).unwrap();
    let before_deposit: Vec<&str> = second
        .lines()
        .skip(1)
        .take_while(|l| !l.starts_with("M3"))
        .collect();
    // Retract and approach; no travel between, which would go nowhere
    // (it was written as a second `G0 … Z7.000`, issue 38 item 5).
    assert_eq!(
        before_deposit,
        [
            "G0 X0.000 Y0.000 Z7.000",
            "G1 X0.000 Y0.000 Z-3.000 F360 S1600"
        ],
        "{text}"
    );
}

#[test]
fn fagor8070_profile() {
    let mut cnc = cnc5();
    cnc.dialect = fagor8070();
    let p = verified(bent_tube(3, 8, 30.0, vec![Machine::Cnc(cnc.clone())]));
    let (name, text) = emit(&p, 0);
    assert_eq!(name, "bent_tube_mill5.nc");
    assert!(!text.contains('('), "no parenthesis comments:\n{text}");
    assert!(
        text.starts_with("; bent_tube_mill5: part bent tube"),
        "{text}"
    );
    assert!(text.contains("\n; layer 2 of 3: station 0.3333"), "{text}");
    let lines: Vec<&str> = text.lines().collect();
    let on = lines
        .iter()
        .position(|l| *l == "#RTCP ON")
        .expect("#RTCP ON");
    let off = lines
        .iter()
        .position(|l| *l == "#RTCP OFF")
        .expect("#RTCP OFF");
    let first_move = lines
        .iter()
        .position(|l| l.starts_with('G') && !l.starts_with("G21"))
        .unwrap();
    let last_move = lines
        .iter()
        .rposition(|l| l.starts_with("G0 ") || l.starts_with("G1 "))
        .unwrap();
    assert!(lines.iter().position(|l| *l == "G21 G90 G94 G17").unwrap() < on);
    assert!(on < first_move && last_move < off, "RTCP around the motion");
    assert_eq!(lines.last(), Some(&"M30"));
    assert_eq!(lines.iter().filter(|l| l.contains("RTCP")).count(), 2);
    check_modal(&text, &cnc.dialect);
}

#[test]
fn sinumerik840d_profile() {
    let mut cnc = cnc5_with(Kinematics::HeadBc);
    cnc.name = "840d cell".into();
    cnc.dialect = sinumerik840d();
    let p = verified(bent_tube(3, 8, 30.0, vec![Machine::Cnc(cnc.clone())]));
    let (name, text) = emit(&p, 0);
    assert_eq!(name, "bent_tube_840d_cell.mpf");
    let lines: Vec<&str> = text.lines().collect();
    let on = lines.iter().position(|l| *l == "TRAORI").expect("TRAORI");
    let off = lines.iter().position(|l| *l == "TRAFOOF").expect("TRAFOOF");
    let first_move = lines.iter().position(|l| l.starts_with("G0 ")).unwrap();
    let last_move = lines.iter().rposition(|l| l.starts_with("G0 ")).unwrap();
    assert!(on < first_move && last_move < off);
    assert_eq!(lines.last(), Some(&"M30"));
    assert!(text.contains("; profile sinumerik840d, kinematics head_bc, axes X Y Z B C"));
    // B/C words, S = 0.1 per W with one decimal: 3000 W -> S300.0.
    assert!(text.contains(" B10.000 C0.000"), "{text}");
    assert!(text.contains(" S300.0\nM10\n"), "{text}");
    assert!(!text.contains(" A"), "no A words on a B/C head");
    check_modal(&text, &cnc.dialect);
}

#[test]
fn m20_profile() {
    let mut cnc = cnc3();
    cnc.dialect = m20();
    let p = verified(planar(2, vec![Machine::Cnc(cnc.clone())]));
    let (name, text) = emit(&p, 0);
    assert_eq!(name, "planar_block_mill3.nc");
    for l in text
        .lines()
        .filter(|l| l.starts_with('G') && !l.starts_with("G21"))
    {
        assert!(l.starts_with("G00 ") || l.starts_with("G01 "), "{l}");
    }
    assert!(
        text.contains("\nM20\nG01 X20.000 Y0.000 Z-3.000\n"),
        "{text}"
    );
    assert!(text.contains("\nM21\n"));
    assert!(!text.lines().any(|l| l == "M3" || l == "M5"));
    assert!(
        !text.contains(" A") && !text.contains(" C"),
        "no rotary words"
    );
    let (starts, _) = check_modal(&text, &cnc.dialect);
    assert_eq!(starts, 2 * 3);
    // Seed 002's control reads F in mm/s: `F10` is 10 mm/s.
    let speed = p.ir().layers[0].paths[0].points[0].speed;
    let want = format!(" F{}", {
        let mut b = Vec::new();
        lmdc::numbers::push_trimmed(&mut b, speed as f64, 1);
        String::from_utf8(b).unwrap()
    });
    assert!(text.contains(&want), "want {want} in\n{text}");
    assert!(text.contains("F mm/s"), "the header names the F unit");
}

#[test]
fn needs_tilt_on_a_three_axis_machine() {
    let mut ir = bent_tube(4, 12, 30.0, vec![Machine::Cnc(cnc3())]);
    ir.origins.machines = vec![MachineOrigin::new(lmdc::span::Span::new(100, 140))];
    let d = refused(ir).into_vec();
    assert_eq!(d.len(), 1, "{d:#?}");
    assert_eq!(d[0].code, "lmd::needs-tilt");
    // Layers fan by 7.5°: the last one tilts 22.5°. Tilted: 3 layers × 13 points.
    assert!(d[0].message.contains("22.5°"), "{}", d[0].message);
    assert!(d[0].message.contains("39 points"), "{}", d[0].message);
    assert!(d[0].message.contains("layer 4"), "{}", d[0].message);
    assert!(d[0].message.contains("mill3"), "{}", d[0].message);
    assert!(d[0].help.as_deref().unwrap().contains("5-axis"));
    assert!(d[0].help.as_deref().unwrap().contains("planar"));
    assert_eq!(d[0].labels[0].span, lmdc::span::Span::new(100, 140));
}

#[test]
fn axis_limits_are_all_reported() {
    let mut cnc = cnc5();
    cnc.limits.tilt = [-10.0, 10.0];
    cnc.limits.x = [-15.0, 500.0];
    let mut ir = bent_tube(4, 12, 30.0, vec![Machine::Cnc(cnc)]);
    ir.origins.machines = vec![MachineOrigin::new(lmdc::span::Span::new(7, 9))];
    let d = refused(ir).into_vec();
    assert_eq!(d.len(), 2, "one per axis: {d:#?}");
    assert!(d.iter().all(|d| d.code == "lmd::axis-limit"));
    assert!(d
        .iter()
        .all(|d| d.labels[0].span == lmdc::span::Span::new(7, 9)));
    // X: the tube (radius 20) reaches x = -20 at the first layer.
    assert!(d[0].message.contains("axis X"), "{}", d[0].message);
    assert!(d[0].message.contains("-20 mm"), "{}", d[0].message);
    assert!(d[0].message.contains("limit of -15 mm"), "{}", d[0].message);
    // A: 22.5° at the last layer, limit 10°.
    assert!(d[1].message.contains("axis A"), "{}", d[1].message);
    assert!(d[1].message.contains("22.5°"), "{}", d[1].message);
    assert!(d[1].message.contains("limit of 10°"), "{}", d[1].message);
    assert!(d[1].message.contains("layer 4"), "{}", d[1].message);
    assert!(d[1].help.is_some());
}

#[test]
fn clearance_moves_are_checked_too() {
    let mut cnc = cnc3();
    cnc.limits.z = [-100.0, 5.0];
    let d = refused(planar(1, vec![Machine::Cnc(cnc)])).into_vec();
    assert_eq!(d.len(), 1, "{d:#?}");
    assert!(d[0].message.contains("axis Z"), "{}", d[0].message);
    assert!(d[0].message.contains("7 mm"), "{}", d[0].message);
    assert!(d[0].message.contains("clearance move"), "{}", d[0].message);
    assert!(d[0].help.as_deref().unwrap().contains("clearance"));
}

#[test]
fn emitting_twice_gives_the_same_bytes() {
    let ir = bent_tube(6, 30, 45.0, vec![Machine::Cnc(cnc5())]);
    let a = emit(&verified(ir.clone()), 0);
    let b = emit(&verified(ir), 0);
    assert_eq!(a, b);
}

#[test]
fn numbers_are_plain_decimals() {
    let p = verified(bent_tube(6, 30, 45.0, vec![Machine::Cnc(cnc5())]));
    let (_, text) = emit(&p, 0);
    for l in text.lines().filter(|l| l.starts_with('G')) {
        for w in l.split_whitespace().skip(1) {
            let v = &w[1..];
            assert!(
                v.chars()
                    .all(|c| c.is_ascii_digit() || c == '.' || c == '-'),
                "{w} in {l}"
            );
            match w.as_bytes()[0] {
                b'X' | b'Y' | b'Z' | b'A' | b'C' => {
                    assert_eq!(v.split('.').nth(1).map(str::len), Some(3), "{w}")
                }
                b'F' => assert!(v.split('.').nth(1).is_none_or(|d| d.len() == 1), "{w}"),
                _ => {}
            }
        }
    }
}

#[test]
fn templates_can_be_replaced() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(dir.path().join("gcode")).unwrap();
    std::fs::write(
        dir.path().join("gcode/layer.tera"),
        "{{ comment_open }}LAYER {{ number }}/{{ layers }} z-height {{ h_max }}{{ comment_close }}\nM0\n",
    )
    .unwrap();
    let t = Templates::load(Some(dir.path())).unwrap();
    let p = verified(planar(2, vec![Machine::Cnc(cnc3())]));
    let mut sink = MemorySink::default();
    lmdc::back::emit(p.machine(0).unwrap(), &t, &mut sink).unwrap();
    let text = sink.text("planar_block_mill3.ngc").unwrap();
    assert!(text.contains("(LAYER 1/2 z-height 0.500)\nM0\n"), "{text}");
    assert!(text.contains("(LAYER 2/2 z-height 0.500)\nM0\n"), "{text}");
}

#[test]
fn golden_five_axis_program() {
    let p = verified(bent_tube(2, 4, 20.0, vec![Machine::Cnc(cnc5())]));
    let (_, text) = emit(&p, 0);
    insta::assert_snapshot!(text, @r"
        (bent_tube_mill5: part bent tube on machine mill5, written by lmdc 0.1.0)
        (profile linuxcnc, kinematics head_ac, axes X Y Z A C)
        (2 layers, 3 paths, 11 points)
        (plan: 226.3 mm deposited, 99.4 mm travel; 43.0 s, laser on 40.1 s, dwell 0.0 s; 119.8 kJ; powder 30.7 g)
        (units: mm, deg, F mm/min, S = 1 per W)
        (X Y Z: tool tip = laser focus; A C: nozzle along the layer normal; clearance 10 mm)
        G21 G90 G94 G17
        (layer 1 of 2: station 0.0000, height 22.689..29.671 mm, 2 paths, 6 points)
        G0 Z31.080
        G0 X20.000 Y0.000 Z31.080 A0.000 C0.000
        G0 X20.000 Y0.000 Z1.430 A0.000 C0.000
        G1 X20.000 Y0.000 Z-8.570 A0.000 C0.000 F480 S3000
        M3
        G1 X0.000 Y20.000 Z-8.570 A0.000 C0.000
        G1 X-20.000 Y0.000 Z-8.570 A0.000 C0.000 F360
        G1 X0.000 Y-20.000 Z-8.570 A0.000 C0.000 F240
        G1 X20.000 Y0.000 Z-8.570 A0.000 C0.000 F360
        M5
        (layer 2 of 2: station 0.5000, height 22.689..29.671 mm, 1 path, 5 points)
        G0 X20.000 Y0.000 Z1.430 A0.000 C0.000
        G0 X22.223 Y0.000 Z23.983 A10.000 C90.000
        G1 X20.487 Y0.000 Z14.134 A10.000 C90.000 F480 S2980
        M3
        G1 X0.791 Y20.000 Z17.607 A10.000 C90.000
        G1 X-18.905 Y0.000 Z21.080 A10.000 C90.000 F360
        G1 X0.791 Y-20.000 Z17.607 A10.000 C90.000 F240
        G1 X20.487 Y0.000 Z14.134 A10.000 C90.000 F360
        M5
        G0 X22.223 Y0.000 Z23.983 A10.000 C90.000
        G0 Z31.080
        (end of bent_tube_mill5: 8 deposit moves, 2 laser starts, 17 motion lines)
        M2
    ");
}

#[test]
fn golden_planar_program() {
    let p = verified(planar(1, vec![Machine::Cnc(cnc3())]));
    let (_, text) = emit(&p, 0);
    insta::assert_snapshot!(text, @r"
        (planar_block_mill3: part planar block on machine mill3, written by lmdc 0.1.0)
        (profile linuxcnc, kinematics xyz, axes X Y Z)
        (1 layer, 3 paths, 11 points)
        (plan: 110.5 mm deposited, 71.1 mm travel; 19.7 s, laser on 16.1 s, dwell 0.0 s; 24.7 kJ; powder 2.15 g)
        (units: mm, deg, F mm/min, S = 1 per W)
        (X Y Z: tool tip = laser focus; clearance 10 mm)
        G21 G90 G94 G17
        (layer 1 of 1: station 0.0000, height 0.500..0.500 mm, 3 paths, 11 points)
        G0 Z7.000
        G0 X0.000 Y0.000 Z7.000
        G1 X0.000 Y0.000 Z-3.000 F360 S1500
        M3
        G1 X20.000 Y0.000 Z-3.000
        G1 X20.000 Y20.000 Z-3.000
        G1 X0.000 Y20.000 Z-3.000 F480
        G1 X0.000 Y0.000 Z-3.000 S1550
        G1 X10.000 Y10.000 Z-3.000 F420 S1500
        M5
        G0 X12.000 Y12.000 Z-3.000
        S1700
        M3
        G1 X20.000 Y20.000 Z-3.000
        M5
        G0 X20.000 Y20.000 Z7.000
        G0 X40.000 Y0.000 Z7.000
        G1 X40.000 Y0.000 Z-3.000 F360 S1500
        M3
        G1 X45.000 Y0.000 Z-3.000
        M5
        G0 X45.000 Y0.000 Z7.000
        (end of planar_block_mill3: 7 deposit moves, 3 laser starts, 15 motion lines)
        M2
    ");
}
