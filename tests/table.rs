//! Tilting tables (issue 22): the part turns under a vertical nozzle.
//!
//! The programs are read back here with a forward kinematics of the test's
//! own (nalgebra rotations, not the library's formulas): the written
//! machine axes must bring the IR's points under the nozzle to the
//! resolution they are printed at, the angles must stand the IR's normal
//! up, F must keep the IR's speed along the part, and LinuxCNC's `rs274`
//! must run the machine-coordinate program to the same path. The errors
//! (a linear axis past its travel in machine coordinates, C winding further
//! than it travels in one layer, a rotary axis too fast) must carry the
//! numbers computed here.

use crate::support::fixture::{bent_tube, cnc5};
use crate::support::gcode_common::{emit, refused, verified};
use crate::support::{ring, rs274};
use lmdc::ir::*;
use nalgebra::{Rotation3, Vector3};

/// The example: an elbow on an A/C table, written both ways.
const EXAMPLE: &str = "examples/ring_table.lmd";

/// A motion line of a G-code program, every axis as written (modal).
#[derive(Clone, Copy, Debug)]
struct Line {
    rapid: bool,
    xyz: [f64; 3],
    tilt: f64,
    c: f64,
    /// F as written, per minute.
    f: f64,
    /// The laser is on during the move.
    laser: bool,
    /// The layer it belongs to (from the layer comments), from 1.
    layer: usize,
}

/// The motion lines of `text` (LinuxCNC syntax: `( )` comments).
fn motion(text: &str, tilt_letter: char) -> Vec<Line> {
    let mut out = Vec::new();
    let mut cur = Line {
        rapid: true,
        xyz: [0.0; 3],
        tilt: 0.0,
        c: 0.0,
        f: 0.0,
        laser: false,
        layer: 0,
    };
    for raw in text.lines() {
        if raw.starts_with("(layer ") {
            cur.layer += 1;
        }
        let line = raw.split('(').next().unwrap_or("").trim();
        match line {
            "M3" => cur.laser = true,
            "M5" => cur.laser = false,
            _ => {}
        }
        let words: Vec<&str> = line.split_whitespace().collect();
        let Some(&g) = words.first() else { continue };
        if g != "G0" && g != "G1" {
            continue;
        }
        cur.rapid = g == "G0";
        for w in &words[1..] {
            let (k, v) = w.split_at(1);
            let v: f64 = v
                .parse()
                .unwrap_or_else(|_| panic!("bad word {w} in {raw}"));
            match k.chars().next().unwrap() {
                'X' => cur.xyz[0] = v,
                'Y' => cur.xyz[1] = v,
                'Z' => cur.xyz[2] = v,
                'C' => cur.c = v,
                'F' => cur.f = v,
                'S' => {}
                l if l == tilt_letter => cur.tilt = v,
                l => panic!("axis {l} on a {tilt_letter}/C machine: {raw}"),
            }
        }
        out.push(cur);
    }
    out
}

/// Rotation by `deg` about a unit axis, right-handed.
fn rot(axis: Vector3<f64>, deg: f64) -> Rotation3<f64> {
    Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), deg.to_radians())
}

/// The tilt axis of a table.
fn tilt_axis_of(kin: Kinematics) -> Vector3<f64> {
    match kin {
        Kinematics::TableAc => Vector3::x(),
        Kinematics::TableBc => Vector3::y(),
        other => panic!("{other:?} is no table"),
    }
}

/// Forward kinematics of a table with ISO directions (a positive angle turns
/// the tool about the part, the table the other way): the part's point
/// (part coordinates) under the nozzle when the linear axes are at `m`
/// (machine coordinates) and the table at (`tilt`, `c`). Undoes the
/// trunnion's tilt about its axis, then C's turn about its own.
fn part_point(
    kin: Kinematics,
    t: &RotaryTable,
    origin: [f64; 3],
    m: [f64; 3],
    tilt: f64,
    c: f64,
) -> [f64; 3] {
    let (m, p, ca) = (
        Vector3::from(m),
        Vector3::from(t.tilt_axis),
        Vector3::from(t.c_axis),
    );
    let q = p + rot(tilt_axis_of(kin), tilt) * (m - p);
    let w = ca + rot(Vector3::z(), c) * (q - ca);
    (w - Vector3::from(origin)).into()
}

/// The part-frame direction a vertical nozzle points along (up the nozzle)
/// with the table at (`tilt`, `c`).
fn nozzle_in_part(kin: Kinematics, tilt: f64, c: f64) -> [f64; 3] {
    (rot(Vector3::z(), c) * rot(tilt_axis_of(kin), tilt) * Vector3::z()).into()
}

/// How far a point can print from where it should be: each linear word half
/// a digit off, and each angle's half digit (0.0005°) turning the point at
/// its distance from both axes.
fn resolution(t: &RotaryTable, machine: [f64; 3]) -> f64 {
    let d = |a: [f64; 3]| {
        let v = Vector3::from(machine) - Vector3::from(a);
        v.norm()
    };
    0.0005 * 3f64.sqrt() + (d(t.c_axis) + d(t.tilt_axis)) * 0.0005f64.to_radians() + 1e-9
}

/// The IR's laser-on moves, in order: (from, to).
fn deposits(p: &Program) -> Vec<(Point, Point)> {
    let mut out = Vec::new();
    for l in &p.layers {
        for path in &l.paths {
            for w in path.points.windows(2) {
                if w[0].laser_on {
                    out.push((w[0], w[1]));
                }
            }
        }
    }
    out
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

fn minus(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// The example's two machines' programs and the IR.
fn example() -> (lmdc::verify::Verified, String, String) {
    let src = std::fs::read_to_string(EXAMPLE).unwrap();
    let v = ring::compile(EXAMPLE, &src);
    let tcp = ring::files(&v, "trt_tcp").into_values().next().unwrap();
    let machine = ring::files(&v, "trt_machine").into_values().next().unwrap();
    (v, tcp, machine)
}

fn table_of(v: &lmdc::verify::Verified, name: &str) -> Cnc {
    match v.ir().machines.iter().find(|m| m.name() == name) {
        Some(Machine::Cnc(c)) => c.clone(),
        _ => panic!("no CNC {name}"),
    }
}

/// Checks the laser-on G1 lines of `lines` against the IR's deposits: the
/// part point `to_part` makes of each line is the deposit's end, the
/// angles stand its normal up. Returns how many were checked.
fn check_deposits(
    v: &lmdc::verify::Verified,
    cnc: &Cnc,
    lines: &[Line],
    to_part: &dyn Fn(&Line) -> ([f64; 3], f64),
) -> usize {
    let want = deposits(v.ir());
    let kin = cnc.kinematics;
    let mut n = 0;
    for l in lines.iter().filter(|l| !l.rapid && l.laser) {
        let (_, to) = want.get(n).expect("more deposits written than the IR has");
        let (got, tol) = to_part(l);
        let err = norm(minus(got, to.focus()));
        assert!(
            err <= tol,
            "deposit {n}: the axes bring {got:?} under the nozzle, the IR's point is {:?} ({err} mm off, resolution {tol})",
            to.focus()
        );
        let t = nozzle_in_part(kin, l.tilt, l.c);
        let normal = to.normal.map(|x| x as f64);
        assert!(
            norm(minus(t, normal)) < 1e-4,
            "deposit {n}: the table at {} C{} stands {t:?} up, the normal is {normal:?}",
            l.tilt,
            l.c
        );
        n += 1;
    }
    assert_eq!(n, want.len(), "the program lays fewer deposits than the IR");
    n
}

/// The part's point a machine-coordinate line of `cnc` brings under the
/// nozzle, and how far off it can print.
fn machine_to_part(cnc: &Cnc, l: &Line) -> ([f64; 3], f64) {
    let t = cnc.table.expect("a table");
    let o = cnc.placement.origin;
    let m = [l.xyz[0] + o[0], l.xyz[1] + o[1], l.xyz[2] + o[2]];
    (
        part_point(cnc.kinematics, &t, o, m, l.tilt, l.c),
        resolution(&t, m),
    )
}

#[test]
fn machine_coordinates_reconstruct_the_ir_path() {
    let (v, _, text) = example();
    let cnc = table_of(&v, "trt_machine");
    let t = cnc.table.expect("a table");
    assert_eq!(t.output, TableOutput::Machine);
    let lines = motion(&text, 'A');
    let n = check_deposits(&v, &cnc, &lines, &|l| machine_to_part(&cnc, l));
    assert!(n > 1000, "{n} deposits");
    // The table really turns: the part's points are not where the program
    // writes them.
    let tilted = lines.iter().filter(|l| l.tilt.abs() > 20.0).count();
    assert!(
        tilted > 100,
        "{tilted} lines with the table tilted past 20°"
    );
    assert!(!text.contains("M428") && text.contains("machine axes"));
}

/// Both programs end at the part's safe height (issue 31: the machine-
/// coordinate program ended with the tip 2.68 mm below it): the last line
/// moves Z alone, the table standing where the last layer left it, and the
/// tip it puts under the nozzle, read back through the test's forward
/// kinematics, is at the height the first line lifted to (at A = C = 0,
/// where the two frames agree).
#[test]
fn both_programs_end_at_the_parts_safe_height() {
    let (v, tcp, machine) = example();
    for (name, text) in [("trt_tcp", &tcp), ("trt_machine", &machine)] {
        let cnc = table_of(&v, name);
        let t = cnc.table.expect("a table");
        let o = cnc.placement.origin;
        let lines = motion(text, 'A');
        let (first, before, last) = (lines[0], lines[lines.len() - 2], lines[lines.len() - 1]);
        let last_line = text
            .lines()
            .rfind(|l| l.starts_with("G0") || l.starts_with("G1"))
            .unwrap();
        assert!(
            last_line.starts_with("G0 Z") && !last_line.contains(['X', 'Y', 'A', 'C']),
            "{name}: {last_line}"
        );
        assert_eq!((before.tilt, before.c), (last.tilt, last.c), "{name}");
        assert!(
            last.tilt.abs() > 20.0,
            "{name}: the table is tilted at the end"
        );
        let safe = first.xyz[2];
        let tip = if name == "trt_machine" {
            let m = [last.xyz[0] + o[0], last.xyz[1] + o[1], last.xyz[2] + o[2]];
            part_point(cnc.kinematics, &t, o, m, last.tilt, last.c)
        } else {
            last.xyz
        };
        assert!(
            (tip[2] - safe).abs() < 0.002,
            "{name}: the tip ends at z = {}, the safe height is {safe}",
            tip[2]
        );
    }
}

#[test]
fn tcp_output_writes_part_coordinates_and_the_same_angles() {
    let (v, tcp, machine) = example();
    let cnc = table_of(&v, "trt_tcp");
    assert_eq!(cnc.table.map(|t| t.output), Some(TableOutput::Tcp));
    let lines = motion(&tcp, 'A');
    check_deposits(&v, &cnc, &lines, &|l| (l.xyz, 0.0005 * 3f64.sqrt() + 1e-9));
    // The same plan: line for line the same angles, F where the table
    // stands still.
    let other = motion(&machine, 'A');
    assert_eq!(lines.len(), other.len());
    for (a, b) in lines.iter().zip(&other) {
        assert_eq!((a.tilt, a.c, a.laser), (b.tilt, b.c, b.laser));
    }
}

#[test]
fn c_stays_continuous_inside_every_layer_and_within_its_limits() {
    let (v, _, text) = example();
    let cnc = table_of(&v, "trt_machine");
    let lines = motion(&text, 'A');
    for w in lines.windows(2) {
        let (a, b) = (w[0], w[1]);
        // Inside a layer's feed moves; a layer's first rapid moves turn the
        // table to where the layer starts.
        if a.layer == b.layer && a.layer > 0 && !b.rapid {
            assert!(
                (a.c - b.c).abs() < 1.0,
                "layer {}: C {} -> {}",
                a.layer,
                a.c,
                b.c
            );
        }
        for l in [a, b] {
            let (lo, hi) = (cnc.limits.rotary, cnc.limits.tilt);
            assert!(l.c >= lo[0] && l.c <= lo[1] && l.tilt >= hi[0] && l.tilt <= hi[1]);
        }
    }
}

/// In machine coordinates F is the machine axes' feed over the move's
/// time, and that time is the part's length at the IR's speed: the chord
/// at F takes as long as the IR's move.
#[test]
fn machine_feed_keeps_the_irs_speed_along_the_part() {
    let (v, _, text) = example();
    let want = deposits(v.ir());
    let lines = motion(&text, 'A');
    let mut prev: Option<Line> = None;
    let mut n = 0;
    for l in &lines {
        if let (Some(p), false, true) = (prev, l.rapid, l.laser) {
            let (from, to) = want[n];
            let t_ir = norm(minus(to.focus(), from.focus())) / from.speed as f64;
            let t_written = norm(minus(l.xyz, p.xyz)) / (l.f / 60.0);
            assert!(
                (t_written - t_ir).abs() <= 1e-3 * t_ir + 1e-4,
                "deposit {n}: the line takes {t_written} s at F{}, the IR's move {t_ir} s",
                l.f
            );
            n += 1;
        }
        prev = Some(*l);
    }
    assert_eq!(n, want.len());
}

/// LinuxCNC's interpreter runs the machine-coordinate program (identity
/// kinematics), and the axes it commands bring the IR's path under the
/// nozzle.
#[test]
fn rs274_runs_the_machine_coordinate_program() {
    if !rs274::available("rs274_runs_the_machine_coordinate_program") {
        return;
    }
    let (v, _, text) = example();
    let cnc = table_of(&v, "trt_machine");
    let t = cnc.table.unwrap();
    let o = cnc.placement.origin;
    let all = rs274::interpret_source(&text).unwrap_or_else(|e| panic!("rs274 refused it: {e}"));
    assert!(all.contains(&rs274::CanonCall::ProgramEnd));
    let mut lines = Vec::new();
    let mut laser = false;
    for call in rs274::program_body(&all) {
        match *call {
            rs274::CanonCall::SpindleOn => laser = true,
            rs274::CanonCall::SpindleOff => laser = false,
            rs274::CanonCall::Feed { x, y, z, a, b, c } => {
                assert_eq!(b, 0.0, "B moved on an A/C table");
                lines.push(Line {
                    rapid: false,
                    xyz: [x, y, z],
                    tilt: a,
                    c,
                    f: 0.0,
                    laser,
                    layer: 0,
                });
            }
            _ => {}
        }
    }
    // rs274 reports positions with the work offset applied (G54 is zero in
    // its default parameters): the program's numbers.
    check_deposits(&v, &cnc, &lines, &|l| {
        let m = [l.xyz[0] + o[0], l.xyz[1] + o[1], l.xyz[2] + o[2]];
        (
            part_point(cnc.kinematics, &t, o, m, l.tilt, l.c),
            resolution(&t, m),
        )
    });
}

/// The number after `before` in `text`, up to the next space.
fn number_after(text: &str, before: &str) -> f64 {
    let at = text
        .find(before)
        .unwrap_or_else(|| panic!("no `{before}` in: {text}"))
        + before.len();
    let s: String = text[at..]
        .chars()
        .take_while(|c| c.is_ascii_digit() || *c == '.' || *c == '-' || *c == '−')
        .collect();
    s.replace('−', "-")
        .parse()
        .unwrap_or_else(|_| panic!("no number after `{before}` in: {text}"))
}

fn messages(d: &lmdc::diag::Diagnostics, code: lmdc::diag::Code) -> Vec<String> {
    d.iter()
        .filter(|x| x.code == code)
        .map(|x| x.message.clone())
        .collect()
}

/// Z's travel is checked where the table puts the machine's Z: the error
/// names the highest machine Z the plan reaches, read here off the program
/// written with room to spare.
#[test]
fn a_linear_limit_is_checked_in_machine_coordinates() {
    let (v, _, text) = example();
    let cnc = table_of(&v, "trt_machine");
    let top = motion(&text, 'A')
        .iter()
        .map(|l| l.xyz[2] + cnc.placement.origin[2])
        .fold(f64::NEG_INFINITY, f64::max);
    let mut ir = v.ir().clone();
    ir.machines.retain(|m| m.name() == "trt_machine");
    let Machine::Cnc(c) = &mut ir.machines[0] else {
        unreachable!()
    };
    c.limits.z[1] = top - 10.0;
    let d = refused(ir);
    let m = messages(&d, lmdc::diag::Code::AxisLimit);
    assert_eq!(m.len(), 1, "{m:?}");
    assert!(m[0].starts_with("axis Z "), "{}", m[0]);
    let reported = number_after(&m[0], "would have to reach ");
    // The message rounds to 4 significant digits.
    assert!(
        (reported - top).abs() <= 5e-4 * top.abs(),
        "reported {reported}, the program reaches {top}"
    );
}

/// A table on the fixture's machine, its axes off the origin.
fn table_machine(output: TableOutput, c_range: [f64; 2]) -> Cnc {
    let mut c = cnc5();
    c.name = "trt".into();
    c.kinematics = Kinematics::TableAc;
    c.table = Some(RotaryTable {
        c_axis: [10.0, -5.0, 0.0],
        tilt_axis: [0.0, -5.0, -80.0],
        output,
    });
    c.limits.rotary = c_range;
    // The hand-made layers lean 30° over a small circle: a nozzle standing
    // off farther keeps clear of them (what is checked here is C).
    c.head.standoff = 40.0;
    c
}

/// Two layers of 72 moves round a circle whose normals lean 30° and wind
/// `turns` times round the vertical along each layer.
fn winding(turns: f64, machine: Cnc) -> Program {
    let mut p = bent_tube(2, 72, 10.0, vec![Machine::Cnc(machine)]);
    for l in &mut p.layers {
        for path in &mut l.paths {
            let n = path.points.len().max(2) - 1;
            for (j, pt) in path.points.iter_mut().enumerate() {
                let th = (turns * 360.0 * j as f64 / 72.0_f64.max(n as f64)).to_radians();
                let (s, c) = (30f64.to_radians().sin(), 30f64.to_radians().cos());
                pt.normal = [(s * th.sin()) as f32, (-s * th.cos()) as f32, c as f32];
            }
        }
        // The travel path's one point keeps the layer's last normal.
        let last = l.paths[0].points.last().unwrap().normal;
        for path in l.paths.iter_mut().skip(1) {
            for pt in &mut path.points {
                pt.normal = last;
            }
        }
    }
    p
}

#[test]
fn a_layer_that_winds_further_than_c_travels_is_refused_with_its_turn() {
    // Three turns in a layer: 1080°, C travels 720°.
    let d = refused(winding(
        3.0,
        table_machine(TableOutput::Machine, [-360.0, 360.0]),
    ));
    let m = messages(&d, lmdc::diag::Code::CUnwind);
    assert_eq!(m.len(), 1, "{d:?}");
    let turn = number_after(&m[0], "would turn through ");
    assert!((turn - 1080.0).abs() < 1e-6, "{}", m[0]);
    assert!(m[0].contains("travel of 720°"), "{}", m[0]);
}

#[test]
fn a_layer_that_fits_starts_where_its_whole_turn_stays_within_c() {
    // One and a half turns (540°) in a C range of 800°: the layer's first
    // normal stands up at C 0 (and 180) plus whole turns; from C 0, the
    // closest, it would end at 540°: it starts at −180° (tilted the other
    // way) or −360° instead.
    for output in [TableOutput::Machine, TableOutput::Tcp] {
        let v = verified(winding(1.5, table_machine(output, [-400.0, 400.0])));
        let (_, text) = emit(&v, 0);
        let lines = motion(&text, 'A');
        let mut layer_c: std::collections::BTreeMap<usize, (f64, f64)> = Default::default();
        for w in lines.windows(2) {
            assert!(
                (-400.0..=400.0).contains(&w[1].c),
                "C {} past its travel",
                w[1].c
            );
            if w[0].layer == w[1].layer && !w[1].rapid {
                assert!(
                    (w[0].c - w[1].c).abs() <= 7.5 + 1e-3,
                    "C jumps {} -> {}",
                    w[0].c,
                    w[1].c
                );
            }
            let e = layer_c.entry(w[1].layer).or_insert((w[1].c, w[1].c));
            *e = (e.0.min(w[1].c), e.1.max(w[1].c));
        }
        let turned = layer_c.values().map(|(lo, hi)| hi - lo).fold(0.0, f64::max);
        assert!(turned >= 540.0 - 1e-6, "the layers turn C by {turned}°");
    }
}

#[test]
fn a_rotary_axis_faster_than_its_rotary_speed_is_refused_with_the_speed() {
    let mut m = table_machine(TableOutput::Tcp, [-3600.0, 3600.0]);
    m.rotary_speed = Some(10.0);
    let p = winding(3.0, m);
    // Each move turns C by 15° in the time its chord takes at its speed;
    // the fastest is the shortest time.
    let worst = deposits(&p)
        .iter()
        .map(|(a, b)| 15.0 / (norm(minus(b.focus(), a.focus())) / a.speed as f64))
        .fold(0.0, f64::max);
    let d = refused(p);
    let m = messages(&d, lmdc::diag::Code::AxisSpeed);
    assert_eq!(m.len(), 1, "{m:?}");
    assert!(m[0].starts_with("the C axis"), "{}", m[0]);
    let got = number_after(&m[0], "would have to move at ");
    assert!(
        (got - worst).abs() <= 5e-3 * worst,
        "reported {got}°/s, computed {worst}°/s"
    );
}

/// A head accepts no table's fields; a 3-axis machine no rotary speed.
#[test]
fn table_fields_on_a_machine_without_a_table_are_refused() {
    let src = std::fs::read_to_string(EXAMPLE).unwrap();
    let head = src.replacen("  kinematics = table_ac\n", "  kinematics = head_ac\n", 1);
    let c = lmdc::pipeline::compile(&head, &mut ());
    let text: Vec<String> = c.diagnostics.iter().map(|d| d.message.clone()).collect();
    for key in ["c_axis", "tilt_axis", "table_output"] {
        assert!(
            text.iter().any(
                |m| m.contains(&format!("`{key}` describes a tilting table"))
                    && m.contains("`head_ac`")
            ),
            "{key}: {text:?}"
        );
    }
}

/// The table turns the part about C under the nozzle: far from the C axis
/// the linear axes move much further than the nozzle moves along the part.
/// Each move turns C by 15° (the normals' azimuth, the same tilt), so its
/// machine chord is `|Rz(−15°)·(w₂ − c) − (w₁ − c)|` (the tilt turns both
/// ends alike), over the time the part's chord takes at the IR's speed.
#[test]
fn linear_axes_faster_than_max_speed_in_machine_coordinates_are_refused() {
    let mut m = table_machine(TableOutput::Machine, [-3600.0, 3600.0]);
    m.table = Some(RotaryTable {
        c_axis: [500.0, -5.0, 0.0],
        tilt_axis: [0.0, -5.0, -80.0],
        output: TableOutput::Machine,
    });
    m.limits.x = [-2000.0, 2000.0];
    m.limits.y = [-2000.0, 2000.0];
    m.limits.z = [-2000.0, 2000.0];
    let c = Vector3::from([500.0, -5.0, 0.0]);
    let p = winding(3.0, m);
    let worst = deposits(&p)
        .iter()
        .map(|(a, b)| {
            let (wa, wb) = (Vector3::from(a.focus()), Vector3::from(b.focus()));
            let chord = (rot(Vector3::z(), -15.0) * (wb - c) - (wa - c)).norm();
            chord / ((wb - wa).norm() / a.speed as f64)
        })
        .fold(0.0, f64::max);
    let d = refused(p);
    let msgs = messages(&d, lmdc::diag::Code::AxisSpeed);
    let linear: Vec<_> = msgs
        .iter()
        .filter(|m| m.starts_with("the X Y Z axes"))
        .collect();
    assert_eq!(linear.len(), 1, "{msgs:?}");
    let got = number_after(linear[0], "would have to move at ");
    assert!(
        (got - worst).abs() <= 5e-4 * worst,
        "reported {got} mm/s, computed {worst} mm/s"
    );
    assert!(worst > 200.0, "{worst}");
}

/// The preview's angle plot carries each layer's lowest and highest tilt
/// and C: those of the program's lines under each layer's comment.
#[test]
fn the_preview_carries_the_tables_angles_per_layer() {
    let (v, _, text) = example();
    let m = v
        .machines()
        .find(|m| m.machine().name() == "trt_machine")
        .unwrap();
    let page = lmdc::preview::html(m);
    let start = page
        .find(r#"<script id="data" type="application/json">"#)
        .unwrap();
    let rest = &page[start..];
    let json = &rest[rest.find('>').unwrap() + 1..rest.find("</script>").unwrap()];
    let d: serde_json::Value = serde_json::from_str(json).unwrap();
    let r = &d["meta"]["rotary"];
    assert_eq!(r["kinematics"], "table_ac");
    assert_eq!(r["axes"], serde_json::json!(["A", "C"]));
    let got = r["layers"].as_array().unwrap();
    let lines = motion(&text, 'A');
    assert_eq!(got.len(), v.ir().layers.len());
    let mut tilted = 0;
    for (k, g) in got.iter().enumerate() {
        // The moves written after layer k's comment (the first lift with
        // the first layer).
        let of = |f: fn(&Line) -> f64| {
            let vals: Vec<f64> = lines
                .iter()
                .filter(|l| l.layer.max(1) == k + 1)
                .map(f)
                .collect();
            let lo = vals.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = vals.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            [lo, hi]
        };
        for (a, want) in [of(|l| l.tilt), of(|l| l.c)].iter().enumerate() {
            for e in 0..2 {
                let v = g[a][e].as_f64().unwrap();
                assert!(
                    (v - want[e]).abs() <= 5e-4 + 1e-9,
                    "layer {} axis {a}: page {v}, program {}",
                    k + 1,
                    want[e]
                );
            }
        }
        if g[0][1].as_f64().unwrap() > 20.0 {
            tilted += 1;
        }
    }
    assert!(tilted > 10, "{tilted} layers tilted past 20°");
    // A 3-axis machine's page has no angle plot.
    let flange = std::fs::read_to_string("examples/flange.lmd").unwrap();
    let f = ring::compile("flange", &flange);
    let m = f
        .machines()
        .find(|m| matches!(m.machine(), Machine::Cnc(_)))
        .unwrap();
    assert!(lmdc::preview::html(m).contains(r#""rotary":null"#));
}

/// Where a table's axes are decides where every point goes: a table that
/// does not say is refused, not placed at the machine's zero.
#[test]
fn a_table_must_say_where_its_axes_are() {
    let src = std::fs::read_to_string(EXAMPLE).unwrap();
    let without = src
        .replacen(
            "  c_axis = [250 mm, 200 mm, 150 mm]  // the C table's centre, on its face\n",
            "",
            1,
        )
        .replacen(
            "  tilt_axis = [0 mm, 200 mm, 50 mm]  // the A trunnion, 100 mm below the face\n",
            "",
            1,
        );
    assert_ne!(without, src);
    let c = lmdc::pipeline::compile(&without, &mut ());
    assert!(c.program.is_none());
    let text: Vec<String> = c.diagnostics.iter().map(|d| d.message.clone()).collect();
    for key in ["c_axis", "tilt_axis"] {
        assert!(
            text.iter()
                .any(|m| m.starts_with(&format!("a `table_ac` machine needs `{key}`"))),
            "{key}: {text:?}"
        );
    }
}

/// A fill along a tilted direction (docs/repair.md, *Undercuts*) on a
/// table: examples/leaning_slab.lmd's slab, leaning 30° toward +x, on this
/// example's machine-coordinate table. The table turns the part so that
/// the slab's lean stands up under the vertical nozzle: every deposit read
/// back through the test's forward kinematics is the IR's point, and the
/// direction the table stands up is the lean, 30° from the part's
/// vertical, on every deposit.
#[test]
fn a_leaning_slab_is_filled_with_the_table_standing_its_lean_up() {
    let slab = std::fs::read_to_string("examples/leaning_slab.lmd").unwrap();
    let table = std::fs::read_to_string(EXAMPLE).unwrap();
    let machine = &table[table.find("machine trt_machine").unwrap()..];
    let machine = &machine[..machine.find("\n}\n").unwrap() + 3];
    let src = format!("{}{machine}", &slab[..slab.find("machine mill5").unwrap()]);
    let file = |p: &str| std::fs::read(format!("examples/{p}")).unwrap();
    let c = crate::support::data::compile_with_files(
        &src,
        ["repair/worn_pad.ply", "repair/leaning_slab.stl"].map(|p| (p, file(p))),
    );
    let v = c.program.unwrap_or_else(|| {
        panic!(
            "{}",
            lmdc::diag::render(&c.diagnostics, "leaning_slab", &src, false)
        )
    });
    let cnc = table_of(&v, "trt_machine");
    let text = ring::files(&v, "trt_machine").into_values().next().unwrap();
    let lines = motion(&text, 'A');
    let n = check_deposits(&v, &cnc, &lines, &|l| machine_to_part(&cnc, l));
    assert!(n > 1000, "{n} deposits");
    let lean = 30f64.to_radians();
    let d = [lean.sin(), 0.0, lean.cos()];
    for l in lines.iter().filter(|l| !l.rapid && l.laser) {
        let up = nozzle_in_part(cnc.kinematics, l.tilt, l.c);
        assert!(
            norm(minus(up, d)) < 1e-4,
            "the table at A{} C{} stands {up:?} up, not the slab's lean",
            l.tilt,
            l.c
        );
    }
}
