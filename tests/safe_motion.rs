//! The motion around the deposits (issue 31), read back from the programs'
//! text, not from the plan: every program starts and ends by one rule (a
//! CNC lifts Z alone to its safe height first, moves across at it, and ends
//! there after the cell's end sequence; a robot leaves home by PTP and goes
//! back to it, its positioner's angles included), rotary axes with stops
//! unwind between layers and keep their branch, and the laser-off lines a
//! positioner turns on are held to its speeds.

use crate::support::example;
use crate::support::krl_check as krl;
use lmdc::back::{MemorySink, Templates};
use lmdc::diag::Code;
use lmdc::ir::Kinematics;
use proptest::prelude::*;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Every file lmdc writes for `src` (the file at `path`), by name.
fn programs(path: &Path, src: &str) -> BTreeMap<String, String> {
    let c = example::compile_file(path, src);
    let p = c
        .program
        .unwrap_or_else(|| panic!("{}: {:#?}", path.display(), c.diagnostics));
    emit(&p)
}

fn emit(p: &lmdc::verify::Verified) -> BTreeMap<String, String> {
    let mut sink = MemorySink::default();
    lmdc::pipeline::emit(p, &Templates::builtin().unwrap(), &mut sink, &mut ()).unwrap();
    sink.files
        .into_iter()
        .map(|(n, b)| (n, String::from_utf8(b).unwrap()))
        .collect()
}

/// A line without its comments (`( … )` or `; …`).
fn code(line: &str) -> &str {
    let end = line.find(['(', ';']).unwrap_or(line.len());
    line[..end].trim()
}

/// A G-code motion line: rapid or not, and its words as written (a word
/// may be an expression: `Z[#<zt> + 14.000]`).
#[derive(Debug)]
struct Motion {
    /// Its line's index in the file.
    at: usize,
    rapid: bool,
    words: BTreeMap<char, String>,
}

impl Motion {
    fn axes(&self) -> BTreeSet<char> {
        self.words
            .keys()
            .copied()
            .filter(|k| "XYZABC".contains(*k))
            .collect()
    }

    fn value(&self, k: char) -> Option<f64> {
        self.words.get(&k)?.parse().ok()
    }
}

/// The motion lines of a G-code program, in order.
fn motions(text: &str) -> Vec<Motion> {
    let mut out = Vec::new();
    for (at, raw) in text.lines().enumerate() {
        let line = code(raw);
        let mut tokens = line.split_whitespace();
        let rapid = match tokens.next() {
            Some("G0" | "G00") => true,
            Some("G1" | "G01") => false,
            _ => continue,
        };
        let mut words: BTreeMap<char, String> = BTreeMap::new();
        let mut last = None;
        for t in tokens {
            let first = t.chars().next().unwrap();
            if first.is_ascii_alphabetic() {
                words.insert(first, t[1..].to_string());
                last = Some(first);
            } else if let Some(k) = last {
                // The rest of an expression with spaces in it.
                let w = words.get_mut(&k).unwrap();
                w.push(' ');
                w.push_str(t);
            }
        }
        out.push(Motion { at, rapid, words });
    }
    out
}

/// Rule 1 for a CNC's program `text`: Z alone up to the safe height first,
/// then across at that height; at the end Z alone, after everything else
/// the program switches, to the same height where the program writes the
/// part's coordinates (a table written in machine coordinates is read back
/// in tests/table.rs).
fn check_gcode(name: &str, text: &str) {
    let m = motions(text);
    let (first, second, last) = (&m[0], &m[1], &m[m.len() - 1]);
    let z: BTreeSet<char> = ['Z'].into();
    assert!(first.rapid && first.axes() == z, "{name}: first {first:?}");
    assert!(
        second.rapid && second.words.get(&'Z') == first.words.get(&'Z'),
        "{name}: across at the safe height: {second:?} after {first:?}"
    );
    // A Z alone, unless the last retract already ended at the safe height.
    assert!(
        last.rapid && (last.axes() == z || last.words.get(&'Z') == first.words.get(&'Z')),
        "{name}: last {last:?}"
    );
    // Nothing moves, dwells or switches the cell after a last lift (a
    // retract that ends at the safe height is followed by the cell's end
    // sequence).
    let lifted = last.axes() == z;
    for raw in text.lines().skip(last.at + 1).filter(|_| lifted) {
        let l = code(raw);
        assert!(
            !raw.contains("gas") && !raw.contains("powder") && !l.starts_with("G"),
            "{name}: `{raw}` after the last lift"
        );
    }
    if !text.contains("machine axes") {
        if let (Some(a), Some(b)) = (first.value('Z'), last.value('Z')) {
            assert_eq!(a, b, "{name}: ends at the height it started at");
        }
    }
    // No move goes nowhere: every motion line changes where the axes are
    // (a layer change straight up and down wrote its crossing twice).
    let mut at: BTreeMap<char, &str> = BTreeMap::new();
    for mv in &m {
        let was = at.clone();
        for (k, v) in &mv.words {
            if "XYZABC".contains(*k) {
                at.insert(*k, v);
            }
        }
        assert!(
            at != was,
            "{name}: line {} moves nowhere: {:?}",
            mv.at + 1,
            mv.words
        );
    }
}

/// Rule 1 for a robot's programs: the main program goes home by PTP first
/// and last, to the same axes (a positioner's E1 and E2 with them, where
/// `ext`); the first module's first motion is the one PTP to a pose, from
/// home. Returns the home line.
fn check_krl(files: &BTreeMap<String, String>, main: &str, ext: bool) -> String {
    let text = &files[main];
    let homes: Vec<&str> = text.lines().filter(|l| l.starts_with("PTP {A1")).collect();
    assert_eq!(homes.len(), 2, "{main}: home at the start and the end");
    assert_eq!(homes[0], homes[1], "{main}");
    assert_eq!(
        homes[0].contains(",E1 ") && homes[0].contains(",E2 "),
        ext,
        "{main}"
    );
    let first = text
        .lines()
        .skip_while(|l| !l.starts_with("PTP {A1"))
        .find_map(|l| l.split(';').next().unwrap_or("").trim().strip_suffix("( )"))
        .unwrap_or_else(|| panic!("{main}: no module called"));
    let module = &files[&format!("{first}.src")];
    let motion = module
        .lines()
        .map(str::trim_start)
        .find(|l| l.starts_with("LIN ") || l.starts_with("PTP "))
        .unwrap();
    assert!(
        motion.starts_with("PTP {X "),
        "{first}: starts with `{motion}`"
    );
    let ptps = files
        .iter()
        .filter(|(n, _)| n.ends_with(".src") && n.as_str() != main)
        .flat_map(|(_, t)| t.lines())
        .filter(|l| l.trim_start().starts_with("PTP "))
        .count();
    assert_eq!(ptps, 1, "{main}: one PTP to a pose, from home");
    homes[0].to_string()
}

/// Whether `name` is a KRL motion module (`<stem>_m001.src`).
fn is_module(name: &str) -> bool {
    name.strip_suffix(".src")
        .and_then(|s| s.rsplit_once("_m"))
        .is_some_and(|(_, n)| n.len() >= 3 && n.bytes().all(|b| b.is_ascii_digit()))
}

/// Checks every program in `files` by rule 1: each G-code program, and
/// each robot's (one main program a robot of `p`).
fn check_all(what: &str, files: &BTreeMap<String, String>, p: &lmdc::ir::Program) {
    for (name, text) in files {
        if name.ends_with(".ngc") || name.ends_with(".nc") || name.ends_with(".mpf") {
            check_gcode(&format!("{what} {name}"), text);
        }
    }
    let mains: Vec<&String> = files
        .keys()
        .filter(|n| n.ends_with(".src") && !is_module(n))
        .collect();
    let robot = |abb: bool| {
        p.machines
            .iter()
            .filter(|m| {
                matches!(m, lmdc::ir::Machine::Robot(r) if (r.controller == lmdc::ir::Controller::Abb) == abb)
            })
            .count()
    };
    assert_eq!(mains.len(), robot(false), "{what}: a main program a robot");
    check_rapid(what, files, robot(true));
    for main in mains {
        // A positioner's programs couple the base to it.
        let ext = files[main].contains("$ACT_EX_AX");
        check_krl(files, main, ext);
    }
}

/// Rule 1 on an ABB robot's RAPID (`abb` of them): `main` goes home
/// (`MoveAbsJ`) first and last, and the motion modules leave home once,
/// by the `MoveJ` that is their first motion.
fn check_rapid(what: &str, files: &BTreeMap<String, String>, abb: usize) {
    let stems: Vec<&str> = files
        .keys()
        .filter_map(|n| n.strip_suffix(".mod"))
        .collect();
    let mains: Vec<&str> = stems
        .iter()
        .copied()
        .filter(|s| {
            !s.rsplit_once("_m")
                .is_some_and(|(_, n)| n.bytes().all(|b| b.is_ascii_digit()))
        })
        .collect();
    assert_eq!(mains.len(), abb, "{what}: a main module an ABB robot");
    let is_motion = |l: &&str| {
        ["MoveAbsJ ", "MoveJ ", "MoveL ", "TriggL "]
            .iter()
            .any(|k| l.starts_with(k))
    };
    for main in mains {
        let text = &files[&format!("{main}.mod")];
        let motions: Vec<&str> = text
            .lines()
            .map(str::trim_start)
            .filter(is_motion)
            .collect();
        assert!(
            motions.len() == 2 && motions.iter().all(|l| l.starts_with("MoveAbsJ lmd_home")),
            "{what}: {main} moves home and back only, by MoveAbsJ: {motions:?}"
        );
        let moves: Vec<&str> = files
            .iter()
            .filter(|(n, _)| n.starts_with(&format!("{main}_m")))
            .flat_map(|(_, t)| t.lines().map(str::trim_start).filter(is_motion))
            .collect();
        assert!(
            moves[0].starts_with("MoveJ "),
            "{what}: {main} starts with {}",
            moves[0]
        );
        assert_eq!(moves.iter().filter(|l| l.starts_with("MoveJ ")).count(), 1);
    }
}

#[test]
fn every_example_starts_and_ends_by_one_rule() {
    for path in example::files() {
        let src = std::fs::read_to_string(&path).unwrap();
        let c = example::compile_file(&path, &src);
        let Some(p) = c.program else { continue };
        check_all(&path.display().to_string(), &emit(&p), p.ir());
    }
}

/// A home at the wrist singularity, or near it, is left by PTP, never by
/// a LIN: the ring's module wrote a LIN from home, which at KUKA's home
/// (A5 = 0) turns the tool by 180° through the singularity.
#[test]
fn a_ring_leaves_even_a_singular_home_by_ptp() {
    for (home, written) in [
        (None, "A4 0,A5 0,A6 0}"),
        (
            Some("[0 deg, -90 deg, 90 deg, 120 deg, 20 deg, 0 deg]"),
            "A4 120,A5 20,A6 0}",
        ),
        (
            Some("[0 deg, -90 deg, 90 deg, 0 deg, 4.75 deg, 0 deg]"),
            "A4 0,A5 4.75,A6 0}",
        ),
    ] {
        let src = match home {
            None => example::edited("segmented_ring.lmd", &[]),
            Some(h) => example::edited(
                "segmented_ring.lmd",
                &[("  arm = kr60ha", &format!("  home = {h}\n  arm = kr60ha"))],
            ),
        };
        let files = programs(Path::new("examples/segmented_ring.lmd"), &src);
        let line = check_krl(&files, "segmented_ring_kr60.src", false);
        assert!(line.contains(written), "{line}");
        let module = &files["segmented_ring_kr60_m001.src"];
        let ptp = module.lines().find(|l| l.starts_with("PTP {X")).unwrap();
        // The configuration the verifier checked, from home.
        assert!(ptp.contains(",S ") && ptp.contains(",T "), "{ptp}");
        let g = &files["segmented_ring_mill3.ngc"];
        check_gcode("segmented_ring_mill3.ngc", g);
    }
}

/// After the last deposit every machine does the same, in the same order:
/// retract, feeder off, post-flow, gas off; then the mill lifts Z alone to
/// its safe height and the robot goes home (tests/cases/planar/cell_end).
#[test]
fn every_machine_ends_retract_feeder_gas_then_away() {
    let path = Path::new("tests/cases/planar/cell_end/input.lmd");
    let files = programs(path, &std::fs::read_to_string(path).unwrap());
    let g = &files["sprocket_tooth_mill3.ngc"];
    let lines: Vec<&str> = g.lines().collect();
    let off = lines.iter().rposition(|l| *l == "M5").unwrap();
    let last_off = lines[..off]
        .iter()
        .rposition(|l| *l == "M5")
        .expect("the last deposit's laser off");
    let tail: Vec<&str> = lines[last_off + 1..]
        .iter()
        .copied()
        .filter(|l| !l.starts_with("(end"))
        .collect();
    assert_eq!(
        tail,
        [
            "G0 X40.000 Y22.400 Z25.493",
            "M65 P1 (powder off)",
            "G4 P5",
            "M65 P0 (gas off)",
            "G0 Z40.000",
            "M5",
            "M2"
        ]
    );
    let last = files
        .iter()
        .filter(|(n, _)| n.contains("kr30_m0") && n.ends_with(".src"))
        .map(|(_, t)| t)
        .next_back()
        .unwrap();
    let lines: Vec<&str> = last.lines().collect();
    let from = lines.iter().rposition(|l| l.starts_with("LIN ")).unwrap();
    let tail = &lines[from + 1..];
    assert_eq!(
        tail,
        [
            "WAIT SEC 0 ; advance-run stop: the outputs switch here",
            "$OUT[3]=FALSE ; powder off",
            "WAIT SEC 5.00",
            "$OUT[2]=FALSE ; gas off",
            "END"
        ]
    );
    let src = std::fs::read_to_string(path).unwrap();
    let p = example::compile_file(path, &src).program.unwrap();
    check_all("cell_end", &files, p.ir());
}

/// The C and tilt angles of a 5-axis program's motion lines, with whether
/// the laser was on during each and the layer (from 1) it belongs to.
fn rotary(text: &str, tilt: char) -> Vec<(f64, f64, bool, usize)> {
    let (mut laser, mut layer) = (false, 0);
    let (mut t, mut c) = (0.0, 0.0);
    let mut out = Vec::new();
    let m = motions(text);
    let mut next = m.iter().peekable();
    for (i, raw) in text.lines().enumerate() {
        if raw.starts_with("(layer ") {
            layer += 1;
        }
        match code(raw) {
            "M3" => laser = true,
            "M5" => laser = false,
            _ => {}
        }
        if let Some(mv) = next.next_if(|mv| mv.at == i) {
            t = mv.value(tilt).unwrap_or(t);
            c = mv.value('C').unwrap_or(c);
            out.push((t, c, laser && !mv.rapid, layer));
        }
    }
    out
}

/// The cone leaning 30° on a head whose C stops at ±360°: every layer
/// winds C once round, and the head unwinds between layers, laser off, on
/// the travel, to the start of least travel (A on either side, never
/// changing side with the laser on); a head whose C turns only 340° is
/// refused with the turn one layer needs.
#[test]
fn a_heads_c_unwinds_between_layers_within_its_stops() {
    let path = Path::new("tests/cases/table/cone_head_stops/input.lmd");
    let src = std::fs::read_to_string(path).unwrap();
    let files = programs(path, &src);
    let text = &files["cone_head_mill5.ngc"];
    let r = rotary(text, 'A');
    assert!(r.iter().all(|&(_, c, ..)| (-360.0..=360.0).contains(&c)));
    assert!(
        r.iter().filter(|x| x.2).all(|&(a, ..)| a.abs() > 29.9),
        "leaning 30° while it lays"
    );
    for w in r.windows(2) {
        assert!(
            w[0].0 * w[1].0 > 0.0 || !w[1].2,
            "the tilt changes side with the laser on: {w:?}"
        );
    }
    let mut unwound = 0;
    for w in r.windows(2) {
        let turn = (w[1].1 - w[0].1).abs();
        if w[1].2 {
            // With the laser on, C turns by a point's share of the layer.
            assert!(turn < 10.0, "{w:?}");
        } else if turn > 180.0 {
            unwound += 1;
        }
    }
    assert!(unwound >= 30, "{unwound} unwinding travels");

    let narrow = src.replace("c = -360 deg .. 360 deg", "c = -170 deg .. 170 deg");
    let c = lmdc::pipeline::compile(&narrow, &mut ());
    assert!(c.program.is_none());
    let d = c
        .diagnostics
        .iter()
        .find(|d| d.code == Code::CUnwind)
        .expect("lmd::c-unwind");
    assert!(
        d.message.contains("through 360° between two retracts")
            && d.message.contains("340°")
            && d.message.contains("layer 1"),
        "{}",
        d.message
    );
}

/// The cone leaning 29.99° on an A/C table whose A stops at −30°: both
/// branches fit, and the table keeps the one it started on through every
/// layer (it swung between them); with A stopping at 0° on the plus side
/// it keeps the minus branch.
#[test]
fn a_table_keeps_its_branch() {
    let path = Path::new("tests/cases/table/cone_table_branch/input.lmd");
    let src = std::fs::read_to_string(path).unwrap();
    for (limits, sign) in [
        ("a = -30 deg .. 120 deg", 1.0),
        ("a = -30 deg .. 0 deg", -1.0),
    ] {
        let src = src.replace("a = -30 deg .. 120 deg", limits);
        let files = programs(path, &src);
        let r = rotary(&files["cone_table_trt.ngc"], 'A');
        let deposits: Vec<_> = r.iter().filter(|x| x.2).collect();
        assert!(deposits.len() > 1000);
        assert!(
            deposits.iter().all(|&&(a, ..)| a * sign > 29.9),
            "{limits}: A changes side"
        );
    }
}

/// A positioner's home: the program starts and ends there, and every
/// laser-off line that turns it keeps E1 and E2 within their speeds (read
/// back from the KRL: each LIN's turn over its length at its `$VEL.CP`).
#[test]
fn a_positioner_starts_and_ends_at_home_and_turns_within_its_speeds() {
    let path = Path::new("tests/cases/positioner/home/input.lmd");
    let src = std::fs::read_to_string(path).unwrap();
    let files = programs(path, &src);
    let home = check_krl(&files, "small_duct_kr60.src", true);
    assert!(home.contains(",E1 10,E2 45}"), "{home}");
    let trace = krl::run(&files, "small_duct_kr60", 3, 2).unwrap();
    let speeds = [5.0, 90.0];
    let mut slowed = 0;
    for w in trace.lins.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        let (Some(ea), Some(eb)) = (a.ext, b.ext) else {
            panic!("E1 and E2 on every motion")
        };
        let d = (0..3)
            .map(|i| (b.pos[i] - a.pos[i]).powi(2))
            .sum::<f64>()
            .sqrt();
        if d < 1e-3 {
            continue;
        }
        for i in 0..2 {
            let rate = (eb[i] - ea[i]).abs() / (d / b.speed);
            // The printed digits: angles to 0.001°, positions to 0.001 mm.
            let slack = 0.001 / (d / b.speed) + rate * 0.002 / d;
            assert!(
                rate <= speeds[i] + slack,
                "E{} at {rate} deg/s over {d} mm: {a:?} → {b:?}",
                i + 1
            );
        }
        if (eb[0] - ea[0]).abs() > 0.1 && b.speed < 100.0 {
            slowed += 1;
        }
    }
    assert!(slowed >= 2, "{slowed} slowed travels");

    let outside = src.replace("home = [10 deg, 45 deg]", "home = [100 deg, 45 deg]");
    let c = lmdc::pipeline::compile(&outside, &mut ());
    assert!(c.program.is_none());
    assert!(c
        .diagnostics
        .iter()
        .any(|d| d.code == Code::PositionerLimit && d.message.contains("at 100° at home")));
}

/// The azimuth of a normal in the C convention of `kin`, deg (none when
/// vertical).
fn azimuth(kin: Kinematics, n: [f32; 3]) -> Option<f64> {
    let [x, y, _] = n.map(f64::from);
    if x.hypot(y) < 1e-6 {
        return None;
    }
    Some(
        match kin {
            Kinematics::HeadAc | Kinematics::TableAc => x.atan2(-y),
            _ => y.atan2(x),
        }
        .to_degrees(),
    )
}

/// How far C must turn along each layer of `p`: the normals' azimuth
/// changes, each the short way round.
fn layer_needs(p: &lmdc::ir::Program, kin: Kinematics) -> Vec<f64> {
    p.layers
        .iter()
        .map(|l| {
            let az: Vec<f64> = l
                .paths
                .iter()
                .flat_map(|p| &p.points)
                .filter_map(|q| azimuth(kin, q.normal))
                .collect();
            az.windows(2)
                .map(|w| ((w[1] - w[0] + 180.0).rem_euclid(360.0) - 180.0).abs())
                .sum()
        })
        .collect()
}

/// A cone of random size and lean, built with the nozzle along its wall on
/// a random tilting head or table with random stops.
fn cone(r0: f64, r1: f64, h: f64, kin: &str, tilt: [f64; 2], c: [f64; 2]) -> String {
    let tilt_letter = if kin.ends_with("bc") { 'b' } else { 'a' };
    let table = if kin.starts_with("table") {
        "  c_axis = [0 mm, 0 mm, 0 mm]\n  tilt_axis = [0 mm, 0 mm, -50 mm]\n  table_output = tcp\n"
    } else {
        ""
    };
    format!(
        "part cone\n\
         section base = circle(diameter = {d0} mm)\n\
         section top = circle(diameter = {d1} mm)\n\
         bead b {{\n  width = 4 mm\n  speed = 3 mm/s .. 14 mm/s\n  \
         model = mass_balance(feed = 20 g/min, efficiency = 50 %, density = 7.9 g/cm^3)\n}}\n\
         loft cone {{\n  from = base\n  to = top\n  spine = line(length = {h} mm)\n  wall = b\n}}\n\
         slicing normal {{\n  layers = auto\n  chord_error = 0.2 mm\n  nozzle = wall\n  max_overhang = 10 deg\n}}\n\
         process {{\n  powder = 20 g/min\n  power = 1200 W\n  defocus = -4 mm\n}}\n\
         machine m {{\n  kind = cnc\n  axes = 5\n  kinematics = {kin}\n  dialect = linuxcnc\n{table}  \
         max_speed = 100 mm/s\n  rotary_speed = 60 deg/s\n  limits {{\n    \
         {tilt_letter} = {t0} deg .. {t1} deg\n    c = {c0} deg .. {c1} deg\n  }}\n}}\n",
        d0 = 2.0 * r0,
        d1 = 2.0 * r1,
        t0 = tilt[0],
        t1 = tilt[1],
        c0 = c[0],
        c1 = c[1],
    )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, ..ProptestConfig::default() })]

    /// Random cones on random heads and tables with stops: a plan that
    /// builds keeps every rotary axis within its stops as written, turns C
    /// with the laser on by no more than each layer's own normals need, and
    /// starts and ends by rule 1; one that is refused is refused for a
    /// layer or run that needs more C than the stops allow.
    #[test]
    fn rotary_axes_stay_within_their_stops_and_unwind_only_laser_off(
        r0 in 12.0f64..30.0,
        r1 in 12.0f64..30.0,
        h in 12.0f64..30.0,
        kin in prop::sample::select(vec!["head_ac", "head_bc", "table_ac", "table_bc"]),
        minus in prop::sample::select(vec![0.0, 30.0, 90.0, 120.0]),
        c_lo in -400.0f64..-170.0,
        c_width in 350.0f64..1100.0,
    ) {
        let tilt = [-minus, 120.0];
        let c = [c_lo.round(), (c_lo + c_width).round()];
        let src = cone(r0, r1, h, kin, tilt, c);
        let compiled = lmdc::pipeline::compile(&src, &mut ());
        let Some(p) = compiled.program else {
            let codes: Vec<Code> = compiled.diagnostics.iter().map(|d| d.code).collect();
            let axes = [Code::AxisLimit, Code::CUnwind];
            if codes.iter().any(|c| !axes.contains(c)) {
                // Refused for something else (a bead off its speeds).
                return Ok(());
            }
            // Every layer of a cone winds C once round from a start whose
            // phase its first normal fixes: C's travel must be that turn
            // and the phase, up to a whole turn more (the plus tilt always
            // fits). Only a C that turns less may refuse it.
            prop_assert!(c[1] - c[0] < 720.0, "{src}\n{:#?}", compiled.diagnostics);
            return Ok(());
        };
        let files = emit(&p);
        let text = files.values().next().unwrap();
        check_gcode("cone", text);
        let letter = if kin.ends_with("bc") { 'B' } else { 'A' };
        let r = rotary(text, letter);
        for &(t, cc, ..) in &r {
            prop_assert!(t >= tilt[0] && t <= tilt[1], "{letter}{t} outside {tilt:?}");
            prop_assert!(cc >= c[0] && cc <= c[1], "C{cc} outside {c:?}");
        }
        let kinematics = match kin {
            "head_ac" => Kinematics::HeadAc,
            "head_bc" => Kinematics::HeadBc,
            "table_ac" => Kinematics::TableAc,
            _ => Kinematics::TableBc,
        };
        let needs = layer_needs(p.ir(), kinematics);
        let mut turned = vec![0.0f64; needs.len()];
        for w in r.windows(2) {
            if w[1].2 {
                turned[w[1].3 - 1] += (w[1].1 - w[0].1).abs();
            }
        }
        for (l, (t, n)) in turned.iter().zip(&needs).enumerate() {
            // Each move's C printed to 0.001°.
            prop_assert!(*t <= n + 0.002 * p.ir().layers[l].paths.iter().map(|p| p.points.len()).sum::<usize>() as f64,
                "layer {}: C turned {t}° with the laser on, its normals need {n}°", l + 1);
        }
    }
}

/// Where no side of the tilt fits a layer's winding within C's stops, the
/// head changes branch between layers, retracted, and the report names
/// those layers: C −100° .. 370° holds a whole turn only from a start
/// within −100° .. 10°, and the rotating seam moves each layer's start by
/// 90°, so every other layer needs the other side.
#[test]
fn a_branch_change_happens_laser_off_and_the_report_names_its_layers() {
    let path = Path::new("tests/cases/table/cone_head_stops/input.lmd");
    let src = std::fs::read_to_string(path).unwrap().replace(
        "c = -360 deg .. 360 deg",
        "a = -120 deg .. 120 deg\n    c = -100 deg .. 370 deg",
    );
    let p = lmdc::pipeline::compile(&src, &mut ())
        .program
        .expect("builds");
    let text = emit(&p).remove("cone_head_mill5.ngc").unwrap();
    let r = rotary(&text, 'A');
    let mut changed = Vec::new();
    for w in r.windows(2) {
        if w[0].0 * w[1].0 < 0.0 {
            assert!(!w[1].2, "the tilt changes side with the laser on: {w:?}");
            changed.push(w[1].3);
        }
    }
    assert!(changed.len() >= 10, "{changed:?}");
    let m = p.machines().next().unwrap();
    let report = lmdc::report::Report::of_plan(m);
    assert_eq!(report.branch_changes, changed);
    assert!(lmdc::report::text::render(&report).contains(&format!(
        "other side (the axes' other solution for the same nozzle direction) in layers {}, {}",
        changed[0], changed[1]
    )));
}
