//! RAPID programs (`controller = abb`) read back by the test suite's own
//! reader (tests/support/rapid_check.rs) and compared, move by move, with
//! the IR they were written from: every deposit is a motion with the laser
//! on to the focus, at the IR's speed and power, with the beam along
//! −normal; splitting into modules changes nothing the robot does; home at
//! the start and the end. The RAPID twin of tests/krl_program.rs.

use crate::support::gcode_common::{fixture, planar, verified};
use crate::support::ir_moves::{beam_axis, deposits, dist};
use crate::support::rapid_check::{self as rapid, Files, Kind, Target};
use lmdc::back::{MemorySink, Templates};
use lmdc::ir::*;
use lmdc::verify::Verified;

fn abb(mut r: Robot) -> Robot {
    r.controller = Controller::Abb;
    r
}

fn robot_files(p: &Verified, index: usize) -> Files {
    let m = p.machine(index).expect("a verified machine");
    let mut sink = MemorySink::default();
    lmdc::back::emit(m, &Templates::builtin().unwrap(), &mut sink)
        .unwrap_or_else(|e| panic!("emit failed: {e:?}"));
    sink.files
        .into_iter()
        .map(|(n, b)| (n, String::from_utf8(b).expect("RAPID is UTF-8")))
        .collect()
}

/// The main module: the `.mod` no other module's name extends.
fn main_name(files: &Files) -> String {
    let stems: Vec<&str> = files
        .keys()
        .filter_map(|n| n.strip_suffix(".mod"))
        .collect();
    stems
        .iter()
        .find(|s| {
            stems
                .iter()
                .all(|o| o == *s || o.starts_with(&format!("{s}_m")))
        })
        .expect("a main module")
        .to_string()
}

fn robot(p: &Verified, index: usize) -> &Robot {
    match &p.ir().machines[index] {
        Machine::Robot(r) => r,
        m => panic!("machine {index} is not a robot: {m:?}"),
    }
}

fn run(p: &Verified, index: usize) -> (Files, rapid::Trace) {
    let r = robot(p, index);
    assert_eq!(r.controller, Controller::Abb);
    let files = robot_files(p, index);
    let main = main_name(&files);
    let trace = rapid::run(&files, &main, &rapid::signals(r).0, &rapid::signals(r).1)
        .unwrap_or_else(|e| panic!("RAPID check failed: {e}"));
    (files, trace)
}

/// Column `k` of the rotation of the unit quaternion `q` (`q1` scalar),
/// written out by hand.
fn quat_column(q: [f64; 4], k: usize) -> [f64; 3] {
    let [w, x, y, z] = q;
    let m = [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y - w * z),
            2.0 * (x * z + w * y),
        ],
        [
            2.0 * (x * y + w * z),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z - w * x),
        ],
        [
            2.0 * (x * z - w * y),
            2.0 * (y * z + w * x),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ];
    [m[0][k], m[1][k], m[2][k]]
}

/// The trace does what the IR asks: the laser-on motions are exactly the
/// IR's deposits, to the focus, at their speed and power, beam along
/// −normal; every linear speed within the robot's; the laser switches only
/// after a fine point or on the fly at a motion's end; off at the end.
fn assert_follows(p: &Verified, index: usize, trace: &rapid::Trace) {
    let r = robot(p, index);
    let want = deposits(p.ir());
    let got: Vec<&rapid::Motion> = trace.motions.iter().filter(|m| m.laser).collect();
    assert_eq!(got.len(), want.len(), "one laser-on motion per IR deposit");
    let (axis, sign) = beam_axis(r.beam);
    for (k, ((from, to), m)) in want.iter().zip(&got).enumerate() {
        let at = format!("deposit {k}: {m:?}");
        let t = m.pose().unwrap_or_else(|| panic!("{at}: a Cartesian move"));
        assert!(dist(t.pos, to.focus()) <= 1e-3, "{at}: position");
        let v = from.speed as f64;
        assert!((m.speed - v).abs() <= 6e-4, "{at}: speed, want {v}");
        let x = from.power as f64 / r.full_scale_power;
        assert!((m.power - x).abs() <= 6e-5, "{at}: power, want {x}");
        let beam = quat_column(t.quat, axis);
        let n = to.normal;
        for i in 0..3 {
            assert!(
                (beam[i] * sign + n[i] as f64).abs() < 1e-5,
                "{at}: beam {beam:?} not along −normal {n:?}"
            );
        }
    }
    for m in &trace.motions {
        if matches!(m.kind, Kind::MoveL | Kind::TriggL) {
            assert!(m.speed <= r.max_speed + 1e-9, "{m:?} beyond max_speed");
        }
    }
    for w in trace.motions.windows(2) {
        if w[0].laser != w[1].laser {
            assert!(
                w[0].zone.is_none() || w[0].switch_at_end,
                "a switch after a blended motion: {w:?}"
            );
        }
    }
    assert!(!trace.laser_at_end);
    let layers = p.ir().layers.len();
    assert_eq!(
        trace.layers.len(),
        layers,
        "one `! layer N of {layers}` a layer"
    );
    assert_homes(r, trace);
}

/// Home at the start and the end: the arm's home axes, a positioner's home
/// angles with them; the move from home a MoveJ, then linear moves.
fn assert_homes(r: &Robot, trace: &rapid::Trace) {
    let ms = &trace.motions;
    let homes: Vec<&rapid::Motion> = ms.iter().filter(|m| m.kind == Kind::MoveAbsJ).collect();
    assert_eq!(homes.len(), 2, "home at the start and the end");
    assert_eq!(ms[0].kind, Kind::MoveAbsJ);
    assert_eq!(ms[ms.len() - 1].kind, Kind::MoveAbsJ);
    for h in homes {
        let Target::Joints(j) = &h.target else {
            panic!("{h:?}")
        };
        assert!(j
            .robax
            .iter()
            .zip(&r.home)
            .all(|(a, b)| (a - b).abs() < 1e-3));
        let want = r.positioner.as_ref().map(|p| p.home);
        let got = j.extax[0].zip(j.extax[1]).map(|(a, b)| [a, b]);
        assert_eq!(got.is_some(), want.is_some(), "{j:?}");
        if let (Some(g), Some(w)) = (got, want) {
            assert!((g[0] - w[0]).abs() < 1e-3 && (g[1] - w[1]).abs() < 1e-3);
        }
    }
    assert_eq!(ms[1].kind, Kind::MoveJ, "the move from home: {:?}", ms[1]);
    let inner = &ms[2..ms.len() - 1];
    assert!(inner
        .iter()
        .all(|m| matches!(m.kind, Kind::MoveL | Kind::TriggL)));
}

fn planar_robot(robot: Robot) -> Verified {
    verified(planar(3, vec![Machine::Robot(abb(robot))]))
}

#[test]
fn planar_program_follows_the_ir() {
    let p = planar_robot(fixture::robot());
    let (files, trace) = run(&p, 0);
    assert_follows(&p, 0, &trace);
    assert!(files.keys().all(|n| n.ends_with(".mod")));
}

/// Named signals (`laser = "doLaserOn"`, a gas valve's `"doGas"`) are
/// written by name, and the reader maps the laser and its power by the
/// names it is given: the trace follows the IR, the gas switches on
/// `doGas`, and the same program read as if the laser were `do5` is
/// refused at its first trigger.
#[test]
fn named_signals_are_written_and_read_back_by_name() {
    let mut robot = fixture::robot();
    robot.laser_out = Signal::Name("doLaserOn".into());
    robot.power_out = Signal::Name("aoLaserPower".into());
    robot.cell.gas = Some(Gas {
        output: Signal::Name("doGas".into()),
        pre_flow: 1.0,
        post_flow: 1.0,
    });
    let p = planar_robot(robot);
    let (files, trace) = run(&p, 0);
    assert_follows(&p, 0, &trace);
    let text: String = files.values().map(String::as_str).collect();
    assert!(text.contains("\\DOp:=doLaserOn, 1;"), "{text}");
    assert!(text.contains("\\AOp:=aoLaserPower, "), "{text}");
    assert!(!text.contains("do5") && !text.contains("ao1"), "{text}");
    use rapid::Event::SetDO;
    assert!(trace.events.contains(&SetDO("doGas".into(), true)));
    assert!(trace.events.contains(&SetDO("doLaserOn".into(), false)));
    let e = rapid::run(&files, &main_name(&files), "do5", "aoLaserPower")
        .expect_err("the laser is doLaserOn, not do5");
    assert!(e.contains("switches the laser's do5, not doLaserOn"), "{e}");
}

/// With `ramp = lead` the laser switches on the fly at the ends of the
/// lead-ins and of the last deposits, where those moves are blended.
#[test]
fn leads_switch_the_laser_on_the_fly() {
    let mut robot = fixture::robot();
    robot.acceleration = Some(1000.0);
    robot.ramp = Ramp::Lead;
    let p = planar_robot(robot);
    let (_, trace) = run(&p, 0);
    assert_follows(&p, 0, &trace);
    let on_the_fly = trace
        .motions
        .iter()
        .filter(|m| m.switch_at_end && m.zone.is_some())
        .count();
    assert!(on_the_fly > 0, "no switch on the fly");
}

#[test]
fn every_beam_axis_points_the_nozzle_along_the_normal() {
    for beam in [
        ToolAxis::PlusX,
        ToolAxis::MinusX,
        ToolAxis::PlusY,
        ToolAxis::MinusY,
        ToolAxis::PlusZ,
        ToolAxis::MinusZ,
    ] {
        let mut r = abb(fixture::robot());
        r.beam = beam;
        let p = verified(fixture::bent_tube(6, 24, 60.0, vec![Machine::Robot(r)]));
        let (_, trace) = run(&p, 0);
        assert_follows(&p, 0, &trace);
    }
}

#[test]
fn modules_split_the_motion_without_changing_it() {
    let mut small = fixture::robot();
    small.max_points_per_module = 10;
    let mut whole = fixture::robot();
    whole.max_points_per_module = 100_000;
    let (files, split) = run(&planar_robot(small), 0);
    let (_, one) = run(&planar_robot(whole), 0);
    assert!(split.calls.len() > 3, "{:?}", split.calls);
    assert_eq!(one.calls.len(), 1);
    for (m, n) in &split.moves_per_module {
        let called = split.calls.contains(m);
        assert!(!called || *n <= 10, "{m} has {n} motion instructions");
    }
    let strip = |t: &rapid::Trace| -> Vec<_> {
        t.motions
            .iter()
            .map(|m| (m.target.clone(), m.speed, m.zone, m.laser, m.power))
            .collect()
    };
    assert_eq!(strip(&split), strip(&one));
    // Every called module was written, and nothing else.
    assert_eq!(files.len(), split.calls.len() + 1);
}

#[test]
fn same_ir_same_bytes() {
    let r = abb(fixture::robot());
    let p = verified(fixture::bent_tube(5, 30, 45.0, vec![Machine::Robot(r)]));
    assert_eq!(robot_files(&p, 0), robot_files(&p, 0));
}

/// The examples' robots made ABB robots, their KUKA arms an IRB 4600-40/2.55,
/// checked and followed: those that compile so (an ABB robot declares its
/// tool, base and load in full; a height loop is not written in RAPID; the
/// arm reaches the part where the KUKA arm did).
#[test]
fn examples_on_abb_robots_follow_their_ir() {
    let mut robots = 0;
    for path in crate::support::example::files() {
        let src = std::fs::read_to_string(&path).unwrap();
        if !src.contains("kind = robot") {
            continue;
        }
        let src: String = src
            .replacen("kind = robot", "kind = robot\n  controller = abb", 1)
            .lines()
            .map(|l| match l.trim_start().starts_with("arm =") {
                true => "  arm = irb4600_40_255\n".to_string(),
                false => format!("{l}\n"),
            })
            .collect();
        let Some(p) = crate::support::example::compile_file(&path, &src).program else {
            continue;
        };
        for (i, m) in p.ir().machines.iter().enumerate() {
            let Machine::Robot(r) = m else { continue };
            if p.ir().loop_on_machine().is_some() {
                continue;
            }
            let (_, trace) = run(&p, i);
            assert_follows(&p, i, &trace);
            for n in trace.moves_per_module.values() {
                assert!(*n <= r.max_points_per_module);
            }
            robots += 1;
        }
    }
    assert!(robots >= 10, "{robots} examples compile for an ABB robot");
}

/// The golden RAPID of tests/cases/rapid/ (what the writer is held to)
/// passes the reader and follows its IR.
#[test]
fn the_golden_cases_pass_the_reader_and_follow_their_ir() {
    let mut cases = 0;
    for dir in std::fs::read_dir("tests/cases/rapid").unwrap() {
        let dir = dir.unwrap().path();
        let input = dir.join("input.lmd");
        let src = std::fs::read_to_string(&input).unwrap();
        let compiled = crate::support::example::compile_file(&input, &src);
        let p = compiled
            .program
            .unwrap_or_else(|| panic!("{} compiles", input.display()));
        let mut files = Files::new();
        for f in std::fs::read_dir(&dir).unwrap() {
            let f = f.unwrap().path();
            if f.extension().is_some_and(|e| e == "mod") {
                let name = f.file_name().unwrap().to_string_lossy().into_owned();
                files.insert(name, std::fs::read_to_string(&f).unwrap());
            }
        }
        let (i, r) = p
            .ir()
            .machines
            .iter()
            .enumerate()
            .find_map(|(i, m)| match m {
                Machine::Robot(r) if r.controller == Controller::Abb => Some((i, r)),
                _ => None,
            })
            .expect("an ABB robot");
        // A reader before version 8 would write KRL for it.
        assert_eq!(
            p.ir().version,
            lmdc::ir::VERSION_BUDGET,
            "{}",
            dir.display()
        );
        let trace = rapid::run(
            &files,
            &main_name(&files),
            &rapid::signals(r).0,
            &rapid::signals(r).1,
        )
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
        assert_follows(&p, i, &trace);
        cases += 1;
    }
    assert!(cases >= 2, "{cases} RAPID cases");
}

/// An emitted program broken the ways a writer could break it is refused
/// by the reader, naming the problem.
#[test]
fn an_emitted_program_broken_is_refused() {
    let p = planar_robot(fixture::robot());
    let r = robot(&p, 0);
    let files = robot_files(&p, 0);
    let main = main_name(&files);
    let m1 = format!("{main}_m001.mod");
    let main_file = format!("{main}.mod");
    // (file, the first line holding this is dropped or edited, into, says)
    type Case<'a> = (&'a str, &'a str, Option<(&'a str, &'a str)>, &'a str);
    let cases: [Case; 4] = [
        (&m1, "TriggIO lmd_on,", None, "which no TriggIO set"),
        (&main_file, "ConfJ", None, "main sets ConfJ and ConfL"),
        (&main_file, "WaitRob", None, "a WaitRob \\InPos comes first"),
        (
            &m1,
            "MoveL [",
            Some(("9E+09", "9.0E+09")),
            "not a plain decimal",
        ),
    ];
    for (file, holding, edit, says) in cases {
        let mut broken = files.clone();
        let text = &broken[file];
        let k = text.lines().position(|l| l.contains(holding));
        let k = k.unwrap_or_else(|| panic!("{file} has no line holding `{holding}`"));
        let lines: Vec<String> = text
            .lines()
            .enumerate()
            .filter_map(|(i, l)| match (i == k, edit) {
                (false, _) => Some(l.to_string()),
                (true, None) => None,
                (true, Some((a, b))) => Some(l.replacen(a, b, 1)),
            })
            .collect();
        broken.insert(file.to_string(), lines.join("\n") + "\n");
        let e = rapid::run(&broken, &main, &rapid::signals(r).0, &rapid::signals(r).1)
            .err()
            .unwrap_or_else(|| panic!("`{holding}` in {file} broken, accepted"));
        assert!(e.contains(says), "`{holding}` in {file}: {e}");
    }
}

/// An ABB cell drawn at random: an arm of the catalogue, the part placed
/// in front of it, a tool turned about the beam, blending, leads, module
/// size.
#[allow(clippy::too_many_arguments)]
fn abb_cell(
    arm: usize,
    at: [f64; 3],
    tool_z: f64,
    spin: f64,
    blending: Option<f64>,
    lead: bool,
    lines: usize,
) -> Robot {
    let keys: Vec<&str> = lmdc::target::arm::CATALOGUE
        .iter()
        .filter(|m| m.maker == lmdc::target::arm::Maker::Abb)
        .map(|m| m.key)
        .collect();
    let model = lmdc::target::arm::model(keys[arm % keys.len()]).unwrap();
    let mut r = abb(fixture::robot());
    r.arm = Some(Box::new(model.arm(2.0, 5.0)));
    r.home = [0.0, 0.0, 0.0, 0.0, 90.0, 0.0];
    r.base.value = Some(Pose {
        x: at[0],
        y: at[1],
        z: at[2],
        ..Pose::default()
    });
    r.tool.value = Some(Pose {
        z: tool_z,
        ..Pose::default()
    });
    r.spin = Spin::Declared { deg: spin };
    r.blending = blending;
    if lead {
        r.acceleration = Some(1000.0);
        r.ramp = Ramp::Lead;
    }
    r.max_points_per_module = lines;
    r
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(24))]

    /// Random plans on random ABB cells: every plan the checks accept is
    /// written as RAPID the reader accepts and that follows its IR move by
    /// move, home to home; every position's configuration is one the
    /// reader takes (its form), and `ConfJ` is on for a checked arm.
    #[test]
    fn random_plans_on_random_abb_cells_read_back_as_their_ir(
        arm in 0usize..8,
        at in (900.0f64..1500.0, -300.0f64..300.0, 0.0f64..500.0),
        tool_z in 200.0f64..400.0,
        spin in proptest::sample::select(vec![0.0, 30.0, -90.0]),
        blending in proptest::option::of(0.1f64..2.0),
        lead in proptest::bool::ANY,
        lines in 5usize..60,
        tube in proptest::bool::ANY,
        layers in 1usize..5,
    ) {
        let r = abb_cell(arm, [at.0, at.1, at.2], tool_z, spin, blending, lead, lines);
        let machines = vec![Machine::Robot(r)];
        let program = if tube {
            fixture::bent_tube(layers + 1, 12, 30.0, machines)
        } else {
            planar(layers, machines)
        };
        // A cell whose arm cannot build the plan is refused with reasons:
        // the checks' business (tests/reach.rs and the cases), not this test's.
        let Ok(p) = lmdc::verify::verify(program, lmdc::verify::Select::All) else {
            return Ok(());
        };
        let (files, trace) = run(&p, 0);
        assert_follows(&p, 0, &trace);
        assert_homes(robot(&p, 0), &trace);
        let main = &files[&format!("{}.mod", main_name(&files))];
        proptest::prop_assert!(main.contains("ConfJ \\On;"), "{main}");
    }
}
