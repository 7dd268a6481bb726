//! Fixtures fixed to a machine (`fixture { machine = NAME }`, issue 32,
//! docs/collision.md): in the machine's own coordinates, not turning with
//! the part. Where the part does not turn, such a fixture is the same
//! obstacle as one on the plate at the place the machine's frame puts it
//! (the same refusal, the same distances); on a tilting table it is met
//! where the table takes the part, and the help's move builds.

use super::collision::{case, number_after};
use lmdc::diag::Code;
use lmdc::pipeline::compile;

/// The collision messages of `src`, and their helps.
fn collisions(src: &str) -> Vec<(String, String)> {
    compile(src, &mut ())
        .diagnostics
        .iter()
        .filter(|d| d.code == Code::Collision)
        .map(|d| (d.message.clone(), d.help.clone().unwrap_or_default()))
        .collect()
}

/// Every closest approach to fixture `clamp` (or `clamp_…`), by machine
/// and body.
fn approaches(src: &str) -> Vec<(String, String, f64)> {
    let c = compile(src, &mut ());
    let v = c.program.unwrap_or_else(|| panic!("{:#?}", c.diagnostics));
    let mut out = Vec::new();
    for m in v.machines() {
        for a in lmdc::report::Report::of_plan(m).approaches {
            if a.with.starts_with("fixture clamp") {
                out.push((m.machine().name().to_string(), a.body, a.distance_mm));
            }
        }
    }
    out.sort_by(|a, b| (&a.0, &a.1).cmp(&(&b.0, &b.1)));
    out
}

/// The clamp of errors/collision/head_fixture on a CNC whose part's
/// origin is at `[100, 50, 20]` mm and a robot whose base stands the part
/// at `[800, 100, 300]` mm turned a quarter about Z: fixed to each machine
/// where its frame puts the plate's clamp, it is refused the same way and
/// kept the same distance from, and the help moves it by as much (its
/// `at` in the machine's coordinates). Only how many poses are too close
/// may differ: the poses are checked where each check's own steps fall.
#[test]
fn a_fixture_fixed_where_the_machine_puts_the_plates_is_the_same_obstacle() {
    let base = case("head_fixture")
        .replace(
            "  axes = 3\n",
            "  axes = 3\n  origin = [100 mm, 50 mm, 20 mm]\n",
        )
        .replace(
            "  laser = 1\n",
            "  laser = 1\n  base = frame(1, x = 800 mm, y = 100 mm, z = 300 mm, a = 90 deg)\n",
        );
    let clamp = "fixture clamp {\n  shape = box(size = [10 mm, 10 mm, 30 mm])\n  at = [20 mm, 0 mm, 0 mm]  // the centre of its bottom face\n}";
    assert!(base.contains(clamp));
    // The part's (20, 0, 0): the CNC's (120, 50, 20); turned a quarter
    // about Z, (0, 20, 0) from the robot's base at (800, 100, 300).
    let fixed = |mill: [f64; 3], kr: [f64; 3]| {
        let one = |name: &str, at: [f64; 3]| {
            format!(
                "fixture clamp_{name} {{\n  shape = box(size = [10 mm, 10 mm, 30 mm])\n  at = [{} mm, {} mm, {} mm]\n  machine = {name}\n}}",
                at[0], at[1], at[2]
            )
        };
        base.replace(
            clamp,
            &format!("{}\n\n{}", one("mill", mill), one("kr", kr)),
        )
    };
    let on_plate = collisions(&base);
    let on_machines = collisions(&fixed([120.0, 50.0, 20.0], [800.0, 120.0, 300.0]));
    assert_eq!(on_plate.len(), 2, "{on_plate:#?}");
    assert_eq!(on_machines.len(), 2, "{on_machines:#?}");
    for ((m0, h0), (m1, h1)) in on_plate.iter().zip(&on_machines) {
        let name = if m1.contains("`mill`") { "mill" } else { "kr" };
        let uncounted = |m: &str| m[..m.rfind(" (").unwrap_or(m.len())].to_string();
        assert_eq!(
            uncounted(m0).replace("fixture `clamp`", &format!("fixture `clamp_{name}`")),
            uncounted(m1)
        );
        let by0 = number_after(h0, "move fixture `clamp` ");
        let by1 = number_after(h1, &format!("move fixture `clamp_{name}` "));
        assert!((by0 - by1).abs() < 0.1 + 1e-9, "{h0}\n{h1}");
    }
    // Moved out of the head's way (the plate's clamp 10 mm further in +x,
    // the robot's +x turned: +y), both build, and every closest approach
    // to it is the plate's, within the half millimetre the checks step
    // by where the head comes close (each check certifies its own poses:
    // the two fall at different places along a move).
    let far = base.replace("at = [20 mm, 0 mm, 0 mm]", "at = [30 mm, 0 mm, 0 mm]");
    let plate = approaches(&far);
    assert_eq!(plate.len(), 2, "the nozzle, on both: {plate:?}");
    let machine = approaches(&fixed([130.0, 50.0, 20.0], [800.0, 130.0, 300.0]));
    assert_eq!(plate.len(), machine.len(), "{plate:?}\n{machine:?}");
    for (p, m) in plate.iter().zip(&machine) {
        assert_eq!((&p.0, &p.1), (&m.0, &m.1));
        assert!((p.2 - m.2).abs() <= 0.5, "{p:?} vs {m:?}");
    }
}

/// The case errors/collision/machine_fixture: a probe fixed beside an A/C
/// table is met where the table's tilt takes the cone, refused with the
/// move that keeps the gap; moved there it builds, a tenth short it is
/// refused again; on the plate (the part's coordinates) the same `at`
/// lies far from the cone and builds.
#[test]
fn a_probe_beside_a_tilting_table_is_met_where_the_table_takes_the_part() {
    let src = case("machine_fixture");
    let found = collisions(&src);
    assert_eq!(found.len(), 1, "{found:#?}");
    let (message, help) = &found[0];
    assert!(message.contains("runs into fixture `probe`"), "{message}");
    let by = number_after(help, "move fixture `probe` ");
    assert!(help.contains("mm in +y"), "{help}");
    let y = ((310.0 + by) * 10.0f64).round() / 10.0;
    let at = "at = [250 mm, 310 mm, 100 mm]";
    assert!(src.contains(at));
    let moved = |y: f64| src.replace(at, &format!("at = [250 mm, {y} mm, 100 mm]"));
    let c = compile(&moved(y), &mut ());
    assert!(c.program.is_some(), "{:#?}", c.diagnostics);
    assert!(
        !collisions(&moved(((y - 0.1) * 10.0f64).round() / 10.0)).is_empty(),
        "a tenth short"
    );
    // On the plate it would stand 310 mm from the cone's axis: no pose
    // comes near it (the safe height rising over its top is another
    // matter: beyond the Z axis's travel).
    let on_plate = src.replace("  machine = trt\n", "");
    assert_eq!(collisions(&on_plate), vec![]);
}

/// A fixture fixed to a machine this file does not declare is refused
/// with the closest name; one fixed to a robot whose base has no values,
/// with what to give it.
#[test]
fn a_fixture_fixed_to_an_unknown_or_unplaced_machine_is_refused() {
    let src = case("head_fixture");
    let at = "  at = [20 mm, 0 mm, 0 mm]  // the centre of its bottom face\n";
    let c = compile(&src.replace(at, &format!("{at}  machine = mil\n")), &mut ());
    let d = c
        .diagnostics
        .iter()
        .find(|d| d.code == Code::UnknownName)
        .unwrap_or_else(|| panic!("{:#?}", c.diagnostics));
    assert!(d.help.as_deref().unwrap_or("").contains("`mill`"), "{d:?}");
    let c = compile(&src.replace(at, &format!("{at}  machine = kr\n")), &mut ());
    let d = c
        .diagnostics
        .iter()
        .find(|d| d.code == Code::MissingField)
        .unwrap_or_else(|| panic!("{:#?}", c.diagnostics));
    assert!(
        d.message.contains("fixed to robot `kr`, whose `base`"),
        "{d:?}"
    );
}

/// Each deposit move's end on the robot of examples/duct_positioner.lmd,
/// with the positioner's angles there.
struct Deposits(Vec<lmdc::plan::Move>);

impl lmdc::plan::Visit for Deposits {
    fn motion(&mut self, m: &lmdc::plan::Move) {
        if m.deposits() {
            self.0.push(*m);
        }
    }
}

/// On a positioner the part turns under the robot: a block fixed to the
/// robot 100 mm above where the focus is, in the robot's frame, at the
/// middle deposit of the duct (`examples/duct_positioner.lmd`) is met by
/// the head's body there and by the arm's tool — the checks take the head
/// into the robot's frame through E1 and E2 at every pose, the links are
/// there already — and the same block in the
/// part's coordinates at the same numbers is nowhere near the part.
#[test]
fn a_block_fixed_to_the_robot_over_a_positioner_is_met_where_the_head_is() {
    let src = std::fs::read_to_string("examples/duct_positioner.lmd").unwrap();
    let c = compile(&src, &mut ());
    let v = c.program.expect("the example builds");
    let m = (v.machines())
        .find(|m| m.machine().name() == "kr60")
        .expect("the robot");
    let lmdc::ir::Machine::Robot(robot) = m.machine() else {
        panic!("a robot");
    };
    let mut d = Deposits(Vec::new());
    m.plan().walk(&mut d);
    let mid = d.0[d.0.len() / 2];
    let kin = lmdc::plan::positioner::Kin::of(robot).expect("a positioner");
    let f = kin.point([mid.axes.tilt, mid.axes.c], mid.to);
    let at = format!("[{:.1} mm, {:.1} mm, {:.1} mm]", f[0], f[1], f[2] + 100.0);
    let block = |fixed: bool| {
        let machine = if fixed { "  machine = kr60\n" } else { "" };
        format!(
            "fixture block {{\n  shape = box(size = [40 mm, 40 mm, 20 mm])\n  at = {at}\n{machine}}}\n\nmachine kr60 {{"
        )
    };
    let fixed = src.replacen("machine kr60 {", &block(true), 1);
    let found = collisions(&fixed);
    // The head's check, and the arm's (the tool, flange to head top).
    for who in ["body of machine `kr60`", "tool of robot `kr60`"] {
        assert!(
            found
                .iter()
                .any(|(m, _)| m.contains(who) && m.contains("into fixture `block`")),
            "{who}: {found:#?}"
        );
    }
    assert!(
        !found.iter().any(|(m, _)| m.contains("machine `dmu5`")),
        "the CNC does not meet the robot's block: {found:#?}"
    );
    let on_plate = src.replacen("machine kr60 {", &block(false), 1);
    assert!(
        !collisions(&on_plate)
            .iter()
            .any(|(m, _)| m.contains("fixture `block`")),
        "on the plate, {at} is far from the duct"
    );
}

/// A block on an A/C table's cradle (`turns_with = tilt`): it tilts with
/// A and not with C. Placed where the cone's 60° tilt swings it into the
/// head's body — the body's point 110 mm up the beam from the focus, at
/// machine (250, 266.6, 240.6) mm, is the cradle's
/// `p + Rx(60°)·(M − p)` = (250, 68.4, 207.9) mm with the table level —
/// it is refused; the same block on the machine's base (no tilt) stands
/// 200 mm from the head and is not.
#[test]
fn a_block_on_a_tables_cradle_turns_into_the_head_with_the_tilt() {
    let src = case("machine_fixture");
    let probe = "fixture probe {\n  shape = cylinder(length = 200 mm, diameter = 30 mm)\n  at = [250 mm, 310 mm, 100 mm]  // machine coordinates: beside the table\n  machine = trt\n}";
    assert!(src.contains(probe));
    let (s, c) = (60f64.to_radians().sin(), 60f64.to_radians().cos());
    // M − p, p the tilt axis's point (0, 200, 50): turned back by +60°.
    let (y, z) = (266.612 - 200.0, 240.6 - 50.0);
    let at = [250.0, 200.0 + c * y - s * z, 50.0 + s * y + c * z - 10.0];
    let block = |turns: &str| {
        format!(
            "fixture clamp {{\n  shape = box(size = [20 mm, 20 mm, 20 mm])\n  at = [{:.1} mm, {:.1} mm, {:.1} mm]\n  machine = trt\n  turns_with = {turns}\n}}",
            at[0], at[1], at[2]
        )
    };
    let on_cradle = collisions(&src.replace(probe, &block("tilt")));
    assert_eq!(on_cradle.len(), 1, "{on_cradle:#?}");
    assert!(
        on_cradle[0].0.contains("the body of machine `trt` runs")
            && on_cradle[0].0.contains("into fixture `clamp`"),
        "{on_cradle:#?}"
    );
    assert_eq!(collisions(&src.replace(probe, &block("nothing"))), vec![]);
}

/// `turns_with = tilt` needs a machine with a tilt axis.
#[test]
fn turning_with_a_tilt_the_machine_has_not_is_refused() {
    let src = case("head_fixture");
    let at = "  at = [20 mm, 0 mm, 0 mm]  // the centre of its bottom face\n";
    let c = compile(
        &src.replace(at, &format!("{at}  machine = mill\n  turns_with = tilt\n")),
        &mut (),
    );
    assert!(
        c.diagnostics
            .iter()
            .any(|d| d.code == Code::ConflictingFields
                && d.message.contains("machine `mill` has no tilt axis")),
        "{:#?}",
        c.diagnostics
    );
    let c = compile(
        &src.replace(at, &format!("{at}  turns_with = tilt\n")),
        &mut (),
    );
    assert!(
        c.diagnostics
            .iter()
            .any(|d| d.code == Code::ConflictingFields && d.message.contains("on the plate")),
        "{:#?}",
        c.diagnostics
    );
}
