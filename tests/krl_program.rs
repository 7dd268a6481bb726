//! KRL programs read back by an independent checker (tests/support/krl_check.rs)
//! and compared with the IR they were written from: every deposit is a LIN with
//! the laser on to the focus, at the IR's speed and power, with the beam along
//! −normal; splitting into modules changes nothing the robot does; numbers and
//! names are what KRL accepts.

use crate::support::gcode_common::{fixture, planar, verified};
use crate::support::ir_moves::{beam_axis, deposits, dist};
use crate::support::krl_check as krl;
use crate::support::krl_run;
use lmdc::back::krl::orient::Orienter;
use lmdc::back::{EmitError, MemorySink, Templates};
use lmdc::ir::*;
use lmdc::verify::Verified;
use proptest::prelude::*;

fn robot_files(p: &Verified, index: usize) -> Result<krl::Files, EmitError> {
    let m = p.machine(index).expect("a verified machine");
    assert!(
        matches!(m.machine(), Machine::Robot(_)),
        "machine {index} is not a robot"
    );
    let mut sink = MemorySink::default();
    lmdc::back::emit(m, &Templates::builtin().unwrap(), &mut sink)?;
    Ok(sink
        .files
        .into_iter()
        .map(|(n, b)| (n, String::from_utf8(b).expect("KRL is UTF-8")))
        .collect())
}

fn main_name(files: &krl::Files) -> String {
    // The main program is the .src no module name extends.
    let srcs: Vec<&String> = files.keys().filter(|n| n.ends_with(".src")).collect();
    srcs.iter()
        .map(|n| n.trim_end_matches(".src").to_string())
        .find(|stem| {
            srcs.iter()
                .all(|o| o.trim_end_matches(".src") == stem || o.starts_with(&format!("{stem}_m")))
        })
        .expect("a main program")
}

fn run(p: &Verified, index: usize) -> (krl::Files, krl::Trace) {
    let Machine::Robot(r) = &p.ir().machines[index] else {
        panic!()
    };
    let files = robot_files(p, index).unwrap_or_else(|e| panic!("emit failed: {e:?}"));
    let main = main_name(&files);
    if let Some((_, law)) = p.ir().loop_on_machine() {
        // A ring's loop: KRL beyond the strict checker's subset, run by the
        // interpreter with a sensor that reads the target every layer.
        let s = r.height_sensor.expect("a sensor");
        let run = krl_run::run_steady(
            &files,
            &main,
            r.laser_out.number().unwrap(),
            r.power_out.number().unwrap(),
            law.target / s.full_scale,
        )
        .unwrap_or_else(|e| panic!("KRL run failed: {e}"));
        return (files, ring_trace(run));
    }
    let trace = krl::run(
        &files,
        &main,
        r.laser_out.number().unwrap(),
        r.power_out.number().unwrap(),
    )
    .unwrap_or_else(|e| panic!("KRL check failed: {e}"));
    assert_load(r, trace.load.as_ref());
    (files, trace)
}

/// The main program sets the load the robot declares, to the digits it
/// writes, or the controller's load data of its tool.
fn assert_load(r: &Robot, got: Option<&krl::LoadSet>) {
    let Some(l) = r.load else {
        assert_eq!(got, Some(&krl::LoadSet::Table(r.tool.index)));
        return;
    };
    let Some(krl::LoadSet::Value { mass, cm, j }) = got else {
        panic!("want the declared load {l:?}, got {got:?}")
    };
    let near = |a: f64, b: f64, tol: f64| (a - b).abs() <= tol;
    assert!(near(*mass, l.mass, 5e-4), "M {mass} want {}", l.mass);
    for i in 0..3 {
        assert!(near(cm[i], l.cog[i], 5e-4), "CM {cm:?} want {:?}", l.cog);
        assert!(near(cm[3 + i], l.inertia_axes[i], 5e-4), "CM {cm:?}");
        assert!(
            near(j[i], l.inertia[i], 5e-7),
            "J {j:?} want {:?}",
            l.inertia
        );
    }
}

/// The interpreter's run as the strict checker's trace.
fn ring_trace(run: krl_run::Run) -> krl::Trace {
    krl::Trace {
        lins: run
            .motions
            .into_iter()
            .map(|m| krl::Lin {
                pos: m.pos,
                abc: m.abc,
                speed: m.speed,
                laser: m.laser,
                anout: m.anout,
                approximated: m.approximated,
                switch_at_end: false,
                module: m.module,
                ptp: false,
                config: None,
                ext: None,
            })
            .collect(),
        ptps: run.ptps,
        lines_per_module: run.lin_lines,
        laser_at_end: run.laser_at_end,
        ..krl::Trace::default()
    }
}

/// The trace does what the IR asks: laser-on LINs are exactly the IR's deposits,
/// to the focus, at their speed and power, nozzle along the normal; every speed
/// within the robot's limit; laser off at the end.
fn assert_follows(p: &Verified, index: usize, trace: &krl::Trace) {
    let ir = p.ir();
    let Machine::Robot(r) = &ir.machines[index] else {
        panic!()
    };
    let want = deposits(ir);
    let got: Vec<&krl::Lin> = trace.lins.iter().filter(|l| l.laser).collect();
    assert_eq!(got.len(), want.len(), "one laser-on LIN per IR deposit");
    let (axis, sign) = beam_axis(r.beam);
    for (k, ((from, to), lin)) in want.iter().zip(&got).enumerate() {
        let at = format!("deposit {k}: {lin:?}");
        assert!(dist(lin.pos, to.focus()) <= 0.0009, "{at}: position");
        assert!(
            (lin.speed - from.speed as f64).abs() <= 0.0006,
            "{at}: speed {} want {}",
            lin.speed,
            from.speed
        );
        let x = from.power as f64 / r.full_scale_power;
        assert!((lin.anout - x).abs() <= 0.00006, "{at}: $ANOUT want {x}");
        let m = krl::matrix(lin.abc);
        let beam = krl::column(&m, axis);
        let n = to.normal;
        for i in 0..3 {
            assert!(
                (beam[i] * sign + n[i] as f64).abs() < 1e-4,
                "{at}: beam {beam:?} not along −normal {n:?}"
            );
        }
    }
    for lin in &trace.lins {
        assert!(lin.speed <= r.max_speed + 1e-9, "{lin:?} beyond max_speed");
        assert!(lin.pos.iter().chain(&lin.abc).all(|v| v.is_finite()));
    }
    // Only where the laser switches is a LIN exact, unless it switches on
    // the fly at the LIN's end (a lead); it is on for no travel.
    for w in trace.lins.windows(2) {
        if w[0].laser != w[1].laser {
            assert!(
                !w[0].approximated || w[0].switch_at_end,
                "switch after an approximated LIN: {w:?}"
            );
        }
    }
    assert!(!trace.laser_at_end);
    if ir.loop_on_machine().is_some() {
        // A ring's loop writes its own moves (docs/krl.md), its module
        // starting with the PTP from home too.
        assert_eq!(trace.ptps, 3, "home, a PTP from home, home");
        return;
    }
    // Home at the start and the end: the arm's home axes, and a
    // positioner's home angles with them.
    assert_eq!(trace.homes.len(), 2, "home at start and end");
    let mut home = r.home.to_vec();
    if let Some(p) = &r.positioner {
        home.extend(p.home);
    }
    for h in &trace.homes {
        assert_eq!(h.len(), home.len(), "{h:?} vs {home:?}");
        assert!(
            h.iter().zip(&home).all(|(a, b)| (a - b).abs() < 1e-3),
            "{h:?} vs {home:?}"
        );
    }

    assert_eq!(
        trace.ptps, 3,
        "home at start and end, and a PTP from home to the first pose"
    );
    assert!(
        trace.lins[0].ptp,
        "the first motion is a PTP: {:?}",
        trace.lins[0]
    );
    assert!(trace.lins[1..].iter().all(|l| !l.ptp));
}

fn planar_robot(robot: Robot) -> Verified {
    verified(planar(3, vec![Machine::Robot(robot)]))
}

#[test]
fn planar_program_follows_the_ir() {
    let p = planar_robot(fixture::robot());
    let (_, trace) = run(&p, 0);
    assert_follows(&p, 0, &trace);
    // The fixture's 3 layers × 3 paths: the raster joins the contour, the island
    // does not; each transition is retract (none for the first), travel, approach.
    let transitions = 3 * 2;
    let lins = deposits(p.ir()).len() + 3 /* laser-off raster gaps */;
    assert_eq!(trace.lins.len(), lins + 3 * transitions - 1 + 1);
}

/// With `ramp = lead` every run of deposits starts at the end of a laser-off
/// LIN at its first speed, collinear with its first deposit and `v²/2a` plus
/// `$APO.CDIS` long, and ends where a laser-off LIN goes on along its last
/// deposit `v²/2a` at its speed; the laser switches at those LINs' ends by a
/// path trigger, the robot going on (the LIN stays approximated).
#[test]
fn leads_switch_the_laser_on_the_fly_at_speed() {
    let mut robot = fixture::robot();
    robot.acceleration = Some(1000.0);
    robot.ramp = Ramp::Lead;
    let p = planar_robot(robot);
    let (files, trace) = run(&p, 0);
    assert_follows(&p, 0, &trace);
    let text: String = files.values().map(String::as_str).collect();
    assert!(!text.contains("TRIGGER WHEN DISTANCE=0 DELAY=0 DO $OUT"));
    let lins = &trace.lins;
    let mut runs = 0;
    for (i, w) in lins.windows(2).enumerate() {
        let dir = |a: &krl::Lin, b: &krl::Lin| {
            let d = [0, 1, 2].map(|k| b.pos[k] - a.pos[k]);
            let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            (d.map(|c| c / n), n)
        };
        if !w[0].laser && w[1].laser {
            runs += 1;
            assert!(w[0].approximated && w[0].switch_at_end, "{w:?}");
            // The lead-in: from the LIN before it, along the first deposit.
            let (lead, len) = dir(&lins[i - 1], &w[0]);
            let (first, _) = dir(&w[0], &w[1]);
            assert!((0..3).all(|k| (lead[k] - first[k]).abs() < 1e-3), "{w:?}");
            assert!((w[0].speed - w[1].speed).abs() < 1e-6);
            let want = w[1].speed * w[1].speed / 2000.0 + 0.2;
            assert!((len - want).abs() < 2e-3, "lead-in {len} mm, want {want}");
        }
        if w[0].laser && !w[1].laser {
            assert!(w[0].approximated && w[0].switch_at_end, "{w:?}");
            let (last, _) = dir(&lins[i - 1], &w[0]);
            let (lead, len) = dir(&w[0], &w[1]);
            assert!((0..3).all(|k| (lead[k] - last[k]).abs() < 1e-3), "{w:?}");
            let want = w[0].speed * w[0].speed / 2000.0;
            assert!((len - want).abs() < 2e-3, "lead-out {len} mm, want {want}");
        }
    }
    // Per layer: the contour (the raster joins it), the raster after its
    // gap, the island.
    assert_eq!(runs, 3 * 3);
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
        let mut r = fixture::robot();
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
    for (m, n) in &split.lines_per_module {
        assert!(*n <= 10, "{m} has {n} LIN lines");
    }
    let strip = |t: &krl::Trace| -> Vec<_> {
        t.lins
            .iter()
            .map(|l| (l.pos, l.abc, l.speed, l.laser, l.anout))
            .collect()
    };
    assert_eq!(strip(&split), strip(&one));
    // Every called module was written, as .src and .dat, and nothing else was.
    assert_eq!(files.len(), 2 * (split.calls.len() + 1));
}

#[test]
fn long_names_stay_valid_krl_names() {
    let mut r = fixture::robot();
    r.name = "the robot in the north cell".into();
    let mut ir = planar(1, vec![Machine::Robot(r)]);
    ir.part = "a rather long part name, with punctuation!".into();
    let p = verified(ir);
    let (files, _) = run(&p, 0);
    for name in files.keys() {
        let stem = name.rsplit_once('.').unwrap().0;
        assert!(stem.len() <= 24, "{name}");
    }
}

#[test]
fn power_beyond_full_scale_is_refused_with_nothing_written() {
    let mut r = fixture::robot();
    r.full_scale_power = 1000.0;
    let e = lmdc::verify::verify(
        planar(3, vec![Machine::Robot(r)]),
        lmdc::verify::Select::All,
    );
    let Err(d) = e else {
        panic!("want lmd::analog-range")
    };
    let d: Vec<_> = d.iter().collect();
    assert_eq!(d.len(), 1);
    assert_eq!(d[0].code, "lmd::analog-range");
    // The planar fixture's hottest point: 1700 W + 200 W in layer 3.
    assert!(d[0].message.contains("1900 W"), "{}", d[0].message);
    assert!(
        d[0].message.contains("$ANOUT[1] = 1.9 "),
        "{}",
        d[0].message
    );
}

#[test]
fn same_ir_same_bytes() {
    let p = verified(fixture::bent_tube(
        5,
        30,
        45.0,
        vec![Machine::Robot(fixture::robot())],
    ));
    assert_eq!(robot_files(&p, 0).unwrap(), robot_files(&p, 0).unwrap());
}

#[test]
fn examples_pass_the_checker_and_follow_their_ir() {
    let mut sources = vec!["tests/cases/duct/small_duct/input.lmd".to_string()];
    for e in std::fs::read_dir("examples").unwrap() {
        let path = e.unwrap().path();
        if path.extension().is_some_and(|x| x == "lmd") {
            sources.push(path.to_string_lossy().into_owned());
        }
    }
    let mut robots = 0;
    for s in sources {
        let src = std::fs::read_to_string(&s).unwrap();
        let p = crate::support::example::compile_file(std::path::Path::new(&s), &src)
            .program
            .unwrap_or_else(|| panic!("{s} compiles"));
        for (i, m) in p.ir().machines.iter().enumerate() {
            // An ABB robot's RAPID: tests/rapid_program.rs.
            if let Machine::Robot(r) = m {
                if r.controller == Controller::Abb {
                    continue;
                }
                let (_, trace) = run(&p, i);
                assert_follows(&p, i, &trace);
                for n in trace.lines_per_module.values() {
                    assert!(*n <= r.max_points_per_module);
                }
                robots += 1;
            }
        }
    }
    assert!(robots >= 2);
}

fn hand_beam(abc: [f64; 3], beam: ToolAxis) -> [f64; 3] {
    let (axis, sign) = beam_axis(beam);
    let c = krl::column(&krl::matrix(abc), axis);
    [c[0] * sign, c[1] * sign, c[2] * sign]
}

fn beam_strategy() -> impl Strategy<Value = ToolAxis> {
    prop_oneof![
        Just(ToolAxis::PlusX),
        Just(ToolAxis::MinusX),
        Just(ToolAxis::PlusY),
        Just(ToolAxis::MinusY),
        Just(ToolAxis::PlusZ),
        Just(ToolAxis::MinusZ),
    ]
}

fn unit(v: [f64; 3]) -> Option<[f32; 3]> {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    (n > 1e-3).then(|| [(v[0] / n) as f32, (v[1] / n) as f32, (v[2] / n) as f32])
}

/// Angle (deg) between two directions, normalised in f64 first (an f32 normal is
/// unit only to ~1e-7, which alone moves acos(n·m) by tens of percent at 0.03°),
/// by atan2, which stays precise for small angles.
fn angle(n: [f32; 3], m: [f32; 3]) -> f64 {
    let u = |v: [f32; 3]| {
        let v = [v[0] as f64, v[1] as f64, v[2] as f64];
        let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        [v[0] / l, v[1] / l, v[2] / l]
    };
    let (a, b) = (u(n), u(m));
    let c = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    let sin = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
    let cos = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    sin.atan2(cos).to_degrees()
}

/// Angle (deg) of the rotation between two KUKA orientations.
fn rotation_between(a: [f64; 3], b: [f64; 3]) -> f64 {
    let (ma, mb) = (krl::matrix(a), krl::matrix(b));
    // trace(Maᵀ·Mb) = 1 + 2 cos θ
    let tr: f64 = (0..3)
        .map(|i| (0..3).map(|k| ma[k][i] * mb[k][i]).sum::<f64>())
        .sum();
    ((tr - 1.0) / 2.0).clamp(-1.0, 1.0).acos().to_degrees()
}

proptest! {
    /// A B C put the beam along −normal for any normal and beam axis, including
    /// the gimbal lock (B = ±90°: a beam along X pointing straight down), and stay
    /// in KUKA's ranges.
    #[test]
    fn abc_round_trips_to_the_normal(
        beam in beam_strategy(),
        raw in prop::collection::vec(
            prop_oneof![
                (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0).prop_map(|(x, y, z)| [x, y, z]),
                Just([0.0, 0.0, 1.0]),
                Just([1.0, 0.0, 0.0]),
                Just([0.0, -1.0, 0.0]),
                Just([1e-7, 0.0, 1.0]),
            ],
            1..12,
        ),
    ) {
        let mut o = Orienter::new(beam);
        for v in raw {
            let Some(n) = unit(v) else { continue };
            let abc = o.abc(n);
            let abc = [abc.a, abc.b, abc.c];
            prop_assert!(abc[0] > -180.0 && abc[0] <= 180.0);
            prop_assert!(abc[1].abs() <= 90.0);
            prop_assert!(abc[2] > -180.0 && abc[2] <= 180.0);
            let b = hand_beam(abc, beam);
            for i in 0..3 {
                prop_assert!((b[i] + n[i] as f64).abs() < 1e-6, "{abc:?} {n:?}");
            }
        }
    }

    /// Between two normals θ apart the tool turns by exactly θ (parallel transport): it never
    /// spins about the beam (which would whip the wrist round).
    #[test]
    fn orientation_moves_with_the_normal(
        beam in beam_strategy(),
        start in (-1.0f64..1.0, -1.0f64..1.0, 0.2f64..1.0),
        steps in prop::collection::vec((-0.05f64..0.05, -0.05f64..0.05, -0.05f64..0.05), 1..40),
    ) {
        let mut o = Orienter::new(beam);
        let mut v = [start.0, start.1, start.2];
        let Some(mut n) = unit(v) else { return Ok(()) };
        let mut prev = o.abc(n);
        for d in steps {
            v = [v[0] + d.0, v[1] + d.1, v[2] + d.2];
            let Some(m) = unit(v) else { continue };
            let theta = angle(n, m);
            let next = o.abc(m);
            let turn = rotation_between([prev.a, prev.b, prev.c], [next.a, next.b, next.c]);
            prop_assert!((turn - theta).abs() < 1e-6, "turned {turn}° for a {theta}° change");
            prev = next;
            n = m;
        }
    }
}
