//! Emitted programs run through LinuxCNC's own interpreter `rs274`: the path it
//! interprets must be the IR's. Skipped when rs274 is not installed, except under
//! CI (install it with `bash .ci/install-rs274.sh`, export LMDC_RS274).

use crate::support::gcode_common as common;
use crate::support::m66;
use crate::support::ring;
use crate::support::rs274;

use common::fixture::*;
use common::*;
use lmdc::ir::*;
use rs274::CanonCall;

/// The nozzle direction of the axes, written out here rather than taken from the
/// library, so a wrong formula there cannot agree with itself.
fn tool_direction(kin: Kinematics, a: f64, b: f64, c: f64) -> [f64; 3] {
    let c = c.to_radians();
    match kin {
        Kinematics::HeadAc | Kinematics::TableAc => {
            let a = a.to_radians();
            [a.sin() * c.sin(), -a.sin() * c.cos(), a.cos()]
        }
        Kinematics::HeadBc | Kinematics::TableBc => {
            let b = b.to_radians();
            [b.sin() * c.cos(), b.sin() * c.sin(), b.cos()]
        }
        Kinematics::Xyz => [0.0, 0.0, 1.0],
    }
}

/// A move the IR asks for with the laser on: from one point of a path to the next.
struct Deposit {
    from: Point,
    to: Point,
    at: String,
}

fn deposits(p: &Program) -> Vec<Deposit> {
    let mut out = Vec::new();
    for (li, l) in p.layers.iter().enumerate() {
        for (pi, path) in l.paths.iter().enumerate() {
            for (k, w) in path.points.windows(2).enumerate() {
                if w[0].laser_on {
                    out.push(Deposit {
                        from: w[0],
                        to: w[1],
                        at: format!("layer {li} path {pi} move {k}"),
                    });
                }
            }
        }
    }
    out
}

/// Where each lead-out of machine `m`'s plan ends, in order.
fn lead_outs(p: &Program, m: usize) -> Vec<[f64; 3]> {
    struct Ends(Vec<[f64; 3]>);
    impl lmdc::plan::Visit for Ends {
        fn motion(&mut self, m: &lmdc::plan::Move) {
            if m.kind == lmdc::plan::MoveKind::LeadOut {
                self.0.push(m.to);
            }
        }
    }
    let mut ends = Ends(Vec::new());
    lmdc::plan::Plan::new(p, &p.machines[m]).walk(&mut ends);
    ends.0
}

fn near3(got: [f64; 3], want: [f64; 3], tol: f64) -> bool {
    (0..3).all(|i| (got[i] - want[i]).abs() <= tol)
}

/// Rotates the whole part by `deg` about Z, so the normals lean towards another
/// azimuth and C takes a less special value.
fn rotate_about_z(mut p: Program, deg: f64) -> Program {
    let (s, c) = deg.to_radians().sin_cos();
    let rot = |v: [f64; 3]| [c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]];
    let rot32 = |v: [f32; 3]| {
        let r = rot([v[0] as f64, v[1] as f64, v[2] as f64]);
        [r[0] as f32, r[1] as f32, r[2] as f32]
    };
    for l in &mut p.layers {
        l.frame.origin = rot(l.frame.origin);
        l.frame.x = rot(l.frame.x);
        l.frame.y = rot(l.frame.y);
        l.frame.z = rot(l.frame.z);
        for path in &mut l.paths {
            for pt in &mut path.points {
                pt.pos = rot(pt.pos);
                pt.normal = rot32(pt.normal);
                pt.tangent = rot32(pt.tangent);
            }
        }
    }
    p
}

/// Emits machine 0 of `ir`, runs rs274 on it and compares the interpreted path with
/// the IR. Returns the number of deposit moves checked.
fn check_against_ir(ir: Program) -> usize {
    let Machine::Cnc(cnc) = ir.machines[0].clone() else {
        panic!("machine 0 must be a CNC")
    };
    let kin = cnc.effective_kinematics();
    let v = verified(ir);
    let (_, mut text) = emit(&v, 0);
    if let (Some(_), Some(s)) = (v.ir().loop_on_machine(), cnc.height_sensor) {
        // A ring's loop: every M66 reads the target height, so the program
        // lays the IR's nominal plan.
        let segments = v.ir().ring.as_ref().map_or(0, |r| r.segments.len());
        let on_target = ring::on_target_reading(&v, &cnc.name);
        let steady = vec![vec![on_target; segments]; v.ir().layers.len()];
        text = m66::scripted(&text, s.input, &steady);
    }
    let all = rs274::interpret_source(&text)
        .unwrap_or_else(|e| panic!("rs274 refused the program: {e}\n{text}"));
    assert!(all.contains(&CanonCall::ProgramEnd), "no program end");
    let body = rs274::program_body(&all);

    let want = deposits(v.ir());
    let mut next = 0; // index into `want` of the next deposit move
                      // Lead-outs: laser-off G1 moves on from a deposit's end (a machine's
                      // `ramp = lead`, a wall's `ends = lead(…)`), in the plan's order.
    let lead_outs = lead_outs(v.ir(), 0);
    let mut next_lead = 0;
    // A laser switched by a motion-synchronised output (M62/M63 P<n>).
    let synced = |line: &str| {
        line.trim()
            .strip_prefix("M62 P")
            .and_then(|n| n.trim().parse::<u32>().ok())
    };
    let laser_bit = synced(&cnc.dialect.laser_on);
    let (mut feed, mut speed, mut laser) = (0.0f64, 0.0f64, false);
    let mut prev_c: Option<f64> = None;
    let s_tol = 0.5 * 10f64.powi(-(cnc.dialect.s_decimals as i32)) + 1e-9;
    for call in body {
        match *call {
            CanonCall::FeedRate(f) => feed = f,
            CanonCall::SpindleSpeed(s) => speed = s,
            CanonCall::SpindleOn => {
                assert!(!laser, "laser switched on twice");
                laser = true;
            }
            CanonCall::SpindleOnCcw => panic!("M4 is not a laser switch"),
            CanonCall::SpindleOff => laser = false,
            CanonCall::DigitalOut {
                index,
                on,
                synced: true,
            } if Some(index) == laser_bit => {
                assert!(laser != on, "laser switched the same way twice");
                laser = on;
            }
            CanonCall::Traverse { a, b, c, .. } => {
                assert!(!laser, "G0 with the laser on");
                let axes = match kin {
                    Kinematics::HeadAc | Kinematics::TableAc => b,
                    Kinematics::HeadBc | Kinematics::TableBc => a,
                    Kinematics::Xyz => a.abs() + b.abs() + c.abs(),
                };
                assert_eq!(axes, 0.0, "an axis the machine lacks moved");
                prev_c = Some(c);
            }
            CanonCall::Feed { x, y, z, a, b, c } => {
                let pos = [x, y, z];
                if !laser
                    && lead_outs
                        .get(next_lead)
                        .is_some_and(|l| near3(pos, *l, 1e-3))
                {
                    next_lead += 1;
                    continue;
                }
                let d = want
                    .get(next)
                    .unwrap_or_else(|| panic!("more G1 moves than the IR has deposits"));
                let (target, process) = if laser {
                    next += 1;
                    (d.to, d.from)
                } else {
                    // The approach to a path lands where the next deposit starts.
                    (d.from, d.from)
                };
                assert!(
                    near3(pos, target.focus(), 1e-3),
                    "{}: G1 to {pos:?}, the IR's focus is {:?}",
                    d.at,
                    target.focus()
                );
                let n = target.normal.map(|v| v as f64);
                let t = tool_direction(kin, a, b, c);
                let want_t = if kin == Kinematics::Xyz {
                    [0.0, 0.0, 1.0]
                } else {
                    n
                };
                assert!(
                    near3(t, want_t, 1e-4),
                    "{}: axes A{a} B{b} C{c} point the nozzle along {t:?}, the normal is {n:?}",
                    d.at
                );
                match kin {
                    Kinematics::HeadAc | Kinematics::TableAc => {
                        assert_eq!(b, 0.0, "B moved on an A/C machine")
                    }
                    Kinematics::HeadBc | Kinematics::TableBc => {
                        assert_eq!(a, 0.0, "A moved on a B/C machine")
                    }
                    Kinematics::Xyz => assert_eq!([a, b, c], [0.0; 3], "rotary axes moved"),
                }
                // rs274 reports the F word as written, in the dialect's unit.
                let f = process.speed as f64 * cnc.dialect.feed.per_mm_s();
                assert!(
                    (feed - f).abs() <= 0.05 + 1e-6,
                    "{}: feed {feed} mm/min, the IR's speed is {} mm/s",
                    d.at,
                    process.speed
                );
                let s = process.power as f64 * cnc.dialect.s_per_watt;
                assert!(
                    (speed - s).abs() <= s_tol,
                    "{}: S{speed}, the IR's power is {} W",
                    d.at,
                    process.power
                );
                if let (true, Some(pc)) = (laser, prev_c) {
                    // Within a deposit C follows the normal without jumps.
                    assert!((c - pc).abs() < 90.0, "{}: C jumps {pc} -> {c}", d.at);
                }
                prev_c = Some(c);
            }
            _ => {}
        }
    }
    assert_eq!(
        next,
        want.len(),
        "the program deposits fewer moves than the IR"
    );
    assert!(!laser, "laser still on at the end");
    want.len()
}

#[test]
fn five_axis_ac_head_follows_the_ir() {
    if !rs274::available("five_axis_ac_head_follows_the_ir") {
        return;
    }
    let ir = rotate_about_z(bent_tube(6, 24, 45.0, vec![Machine::Cnc(cnc5())]), 30.0);
    assert_eq!(check_against_ir(ir), 6 * 24);
}

#[test]
fn five_axis_ac_head_unrotated_fixture() {
    if !rs274::available("five_axis_ac_head_unrotated_fixture") {
        return;
    }
    let ir = bent_tube(4, 12, 30.0, vec![Machine::Cnc(cnc5())]);
    assert_eq!(check_against_ir(ir), 4 * 12);
}

#[test]
fn five_axis_bc_head_follows_the_ir() {
    if !rs274::available("five_axis_bc_head_follows_the_ir") {
        return;
    }
    let ir = rotate_about_z(
        bent_tube(
            5,
            16,
            60.0,
            vec![Machine::Cnc(cnc5_with(Kinematics::HeadBc))],
        ),
        -120.0,
    );
    assert_eq!(check_against_ir(ir), 5 * 16);
}

/// A tilting table under the control's transform (`table_output = tcp`):
/// the program is the head's, part coordinates and the angles that stand
/// the normal up, read as the part's direction.
#[test]
fn five_axis_ac_table_in_tcp_follows_the_ir() {
    if !rs274::available("five_axis_ac_table_in_tcp_follows_the_ir") {
        return;
    }
    let mut cnc = cnc5_with(Kinematics::TableAc);
    cnc.table = Some(RotaryTable {
        c_axis: [0.0, 0.0, 0.0],
        tilt_axis: [0.0, 0.0, -100.0],
        output: TableOutput::Tcp,
    });
    let ir = rotate_about_z(bent_tube(6, 24, 45.0, vec![Machine::Cnc(cnc)]), 30.0);
    assert_eq!(check_against_ir(ir), 6 * 24);
}

#[test]
fn three_axis_planar_part_follows_the_ir() {
    if !rs274::available("three_axis_planar_part_follows_the_ir") {
        return;
    }
    let ir = planar(3, vec![Machine::Cnc(cnc3())]);
    let n = deposits(&ir).len();
    assert_eq!(check_against_ir(ir), n);
    assert!(n > 0);
}

/// With `ramp = lead` and the laser on a motion-synchronised output
/// (`M62`/`M63`), rs274 switches it between a laser-off G1 collinear with a
/// run's first deposit, `v²/2a` and the blending long at its feed, and that
/// deposit; and off
/// between the run's last deposit and a laser-off G1 going on along it
/// `v²/2a` at its feed. Every deposit of the IR is a G1 with the output set.
#[test]
fn leads_switch_a_synchronised_output_at_speed() {
    if !rs274::available("leads_switch_a_synchronised_output_at_speed") {
        return;
    }
    let mut cnc = cnc3();
    cnc.acceleration = Some(1000.0);
    // Written as G64 P0.5; without it the contour's corners would stop.
    cnc.blending = Some(0.5);
    cnc.ramp = Ramp::Lead;
    cnc.dialect.laser_on = "M62 P0".into();
    cnc.dialect.laser_off = "M63 P0".into();
    let ir = planar(3, vec![Machine::Cnc(cnc)]);
    let want = deposits(&ir).len();
    let v = verified(ir);
    let (_, text) = emit(&v, 0);
    let all = rs274::interpret_source(&text)
        .unwrap_or_else(|e| panic!("rs274 refused the program: {e}\n{text}"));
    // Each feed move: (from, to, F mm/min, laser on); each switch: (on, move index).
    let (mut at, mut feed, mut laser) = ([0.0f64; 3], 0.0, false);
    let (mut moves, mut switches) = (Vec::new(), Vec::new());
    for c in rs274::program_body(&all) {
        match *c {
            CanonCall::FeedRate(f) => feed = f,
            CanonCall::Traverse { x, y, z, .. } => {
                assert!(!laser, "G0 with the laser on");
                at = [x, y, z];
            }
            CanonCall::Feed { x, y, z, .. } => {
                moves.push((at, [x, y, z], feed, laser));
                at = [x, y, z];
            }
            CanonCall::DigitalOut {
                index: 0,
                on,
                synced: true,
            } => {
                assert_ne!(on, laser, "a switch to the state the laser has");
                laser = on;
                switches.push((on, moves.len()));
            }
            // (M2 stops the spindle too: only a start would be wrong.)
            CanonCall::SpindleOn => panic!("the laser switches on the output, not the spindle"),
            _ => {}
        }
    }
    assert!(!laser, "laser on at the end");
    assert_eq!(moves.iter().filter(|m| m.3).count(), want);
    let dir = |m: &([f64; 3], [f64; 3], f64, bool)| {
        let d = [0, 1, 2].map(|k| m.1[k] - m.0[k]);
        let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        (d.map(|c| c / n), n)
    };
    let ramp = |f: f64| (f / 60.0).powi(2) / 2000.0;
    for &(on, k) in &switches {
        // The lead (before an on, after an off) and the deposit it meets.
        let (lead, deposit) = if on {
            (&moves[k - 1], &moves[k])
        } else {
            (&moves[k], &moves[k - 1])
        };
        assert!(!lead.3 && deposit.3, "{lead:?} {deposit:?}");
        let ((a, len), (b, _)) = (dir(lead), dir(deposit));
        assert!(
            (0..3).all(|i| (a[i] - b[i]).abs() < 1e-3),
            "{lead:?} {deposit:?}"
        );
        assert!(
            (lead.2 - deposit.2).abs() < 0.05,
            "the lead runs at the run's feed"
        );
        // A lead-in also holds the blending the control may round onto it.
        let want = ramp(deposit.2) + if on { 0.5 } else { 0.0 };
        assert!((len - want).abs() < 2e-3, "lead {len} mm, want {want}");
    }
    assert_eq!(switches.len(), 2 * 3 * 3, "on and off, 3 runs a layer");
}

#[test]
fn padded_g_words_run_in_rs274() {
    // rs274 reads LinuxCNC's dialect only (the vendor profiles are checked as text
    // in gcode_program.rs), but G00/G01 are plain RS274: the m20 dialect with
    // LinuxCNC's laser words must interpret to the same path.
    if !rs274::available("padded_g_words_run_in_rs274") {
        return;
    }
    let mut cnc = cnc3();
    cnc.dialect = m20();
    cnc.dialect.laser_on = "M3".into();
    cnc.dialect.laser_off = "M5".into();
    cnc.dialect.postamble = vec!["M2".into()];
    let ir = planar(2, vec![Machine::Cnc(cnc)]);
    let n = deposits(&ir).len();
    assert_eq!(check_against_ir(ir), n);
}

/// Every example under examples/ (not the error or benchmark ones): its G-code
/// for each LinuxCNC machine runs in rs274 and follows the compiled IR.
#[test]
fn examples_run_in_rs274_and_follow_the_ir() {
    if !rs274::available("examples_run_in_rs274_and_follow_the_ir") {
        return;
    }
    let mut checked = 0;
    let files = crate::support::example::files();
    for f in files {
        let src = std::fs::read_to_string(&f).unwrap();
        let ir = crate::support::example::compile_file(&f, &src)
            .program
            .unwrap_or_else(|| panic!("{} does not compile", f.display()))
            .into_ir();
        for m in &ir.machines {
            let Machine::Cnc(c) = m else { continue };
            // A table in machine coordinates writes where the table brings
            // the part: tests/table.rs runs it through rs274 and its own
            // forward kinematics.
            if c.dialect.profile != "linuxcnc" || lmdc::plan::table::machine_output(c).is_some() {
                continue;
            }
            // The machine under test becomes machine 0 (check_against_ir's).
            let mut one = ir.clone();
            one.machines = vec![m.clone()];
            one.origins.machines.truncate(1);
            checked += check_against_ir(one);
        }
    }
    assert!(
        checked > 60_000,
        "the duct example's deposits were not all checked"
    );
}

/// The flange with its raster linked laser off: the links are G0 moves at
/// the layer's height between M5 and M3, and the program still deposits
/// exactly the IR's moves.
#[test]
fn flange_linked_laser_off_runs_in_rs274() {
    if !rs274::available("flange_linked_laser_off_runs_in_rs274") {
        return;
    }
    let src = std::fs::read_to_string("examples/flange.lmd")
        .unwrap()
        .replace("link = laser_on", "link = laser_off");
    let mut ir = lmdc::pipeline::compile(&src, &mut ())
        .program
        .expect("compiles")
        .into_ir();
    assert!(ir
        .layers
        .iter()
        .any(|l| l.paths.iter().any(|p| p.kind == PathKind::Travel)));
    ir.machines.retain(|m| matches!(m, Machine::Cnc(_)));
    ir.origins.machines.truncate(1);
    let n = deposits(&ir).len();
    assert_eq!(check_against_ir(ir), n);
}

/// The expected LinuxCNC programs of tests/cases/ as reviewed run in rs274
/// to their end (M2): an expected file accepted with a line rs274 refuses
/// would otherwise stand as the reference.
#[test]
fn expected_linuxcnc_programs_run_in_rs274() {
    if !rs274::available("expected_linuxcnc_programs_run_in_rs274") {
        return;
    }
    let mut ran = 0;
    for case in crate::cases::folders(std::path::Path::new(crate::cases::ROOT)) {
        let mut files: Vec<_> = std::fs::read_dir(&case)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|e| e == "ngc"))
            .collect();
        files.sort();
        for f in files {
            let calls = rs274::interpret(&f).unwrap_or_else(|e| panic!("{}: {e}", f.display()));
            assert!(
                calls.contains(&CanonCall::ProgramEnd),
                "{}: rs274 did not reach the program's end",
                f.display()
            );
            ran += 1;
        }
    }
    assert!(ran >= 7, "only {ran} expected .ngc files");
}

/// `lmdc calibrate`'s coupons (tracks, walls, pads) run in rs274 along the
/// IR's paths at each coupon's speed and power.
#[test]
fn calibration_coupons_follow_the_ir() {
    if !rs274::available("calibration_coupons_follow_the_ir") {
        return;
    }
    for coupon in [
        "track",
        "wall(layers = 3)",
        "pad(tracks = 3, offset = 1.6 mm)",
    ] {
        let src = include_str!("../examples/calibration.lmd")
            .replace("coupon = track", &format!("coupon = {coupon}"));
        let c = lmdc::pipeline::compile(&src, &mut ());
        let ir = c.program.expect("the coupons compile").ir().clone();
        let n = check_against_ir(ir);
        assert!(n >= 12, "{coupon}: {n} deposit moves");
    }
}
