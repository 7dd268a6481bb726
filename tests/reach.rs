//! `lmd::reach` on parts the arm cannot reach: a part drawn in inches is
//! refused from its points, before any pose is solved, and the help's base
//! is one the robot stands in front of, below the part, from where the
//! same file builds (each test follows the printed suggestion).

use crate::support::example;
use lmdc::diag::{Code, Diagnostic, Severity};
use lmdc::ir::{Machine, Pose, Program, Robot};
use lmdc::pipeline::{compile_for, Compiled};
use lmdc::plan::arm::reach::{beyond, FOOT_MM};

fn compile(src: &str, machine: &str) -> Compiled {
    compile_for(src, Some(machine), &mut ()).expect("the machine is declared")
}

/// The errors of `c`.
fn errors(c: &Compiled) -> Vec<&Diagnostic> {
    c.diagnostics
        .iter()
        .filter(|d| d.severity == Severity::Error)
        .collect()
}

/// The robot called `name` of `p`.
fn robot<'p>(p: &'p Program, name: &str) -> &'p Robot {
    p.machines
        .iter()
        .find_map(|m| match m {
            Machine::Robot(r) if r.name == name => Some(r),
            _ => None,
        })
        .expect("the robot")
}

/// The `base = frame(…)` the help of `d` suggests, as written.
fn suggested(d: &Diagnostic) -> String {
    let help = d.help.as_deref().expect("a help");
    let from = help.find("`base = frame(").expect("a base in the help") + 1;
    let len = help[from..].find('`').expect("the base's closing quote");
    help[from..from + len].to_string()
}

/// `key = <number> unit` of a `frame(…)` as written.
fn value(frame: &str, key: &str) -> f64 {
    let at = frame.find(&format!(" {key} = ")).expect("the key") + key.len() + 4;
    frame[at..]
        .split(' ')
        .next()
        .and_then(|v| v.parse().ok())
        .expect("a number")
}

/// `src` with its robot's `base = …` line replaced by `base`.
fn with_base(src: &str, base: &str) -> String {
    let line = src
        .lines()
        .find(|l| l.trim_start().starts_with("base = frame("))
        .expect("a base line");
    src.replacen(line, &format!("  {base}"), 1)
}

/// Refused for reach; the suggested base stands the part on or above the
/// plane of the robot's foot and in front of A2's circle; following it, the
/// file builds (whatever else the arm's rules found, from the old base).
/// Gives the error.
fn follow_the_help(src: &str, machine: &str) -> Diagnostic {
    let c = compile(src, machine);
    let errs = errors(&c);
    let reach = errs.iter().find(|d| d.code == Code::Reach);
    let reach = *reach.unwrap_or_else(|| panic!("refused for reach: {errs:#?}"));
    let base = suggested(reach);
    let fixed = compile(&with_base(src, &base), machine);
    let Some(p) = fixed.program.as_ref() else {
        panic!("following `{base}` builds: {:#?}", errors(&fixed))
    };
    let r = robot(p.ir(), machine);
    let b = r.base.value.expect("a base value");
    for (k, want) in [("x", b.x), ("y", b.y), ("z", b.z)] {
        assert_eq!(value(&base, k), want, "{base}");
    }
    let [a1, ..] = r.arm.as_ref().expect("an arm").opw;
    let (low, near) = foci(p.ir(), &b);
    assert!(
        low >= 0.0,
        "{base}: a focus {low} mm below the robot's foot"
    );
    assert!(
        near >= a1 + FOOT_MM - 1e-9,
        "{base}: a focus {near} mm from A1's axis, within its foot"
    );
    reach.clone()
}

/// The lowest focus of `p` with the part's base at `b`, and the nearest to
/// A1's axis, mm.
fn foci(p: &Program, b: &Pose) -> (f64, f64) {
    let r = nalgebra::Rotation3::from_euler_angles(
        b.c.to_radians(),
        b.b.to_radians(),
        b.a.to_radians(),
    );
    let t = nalgebra::Vector3::new(b.x, b.y, b.z);
    let mut out = (f64::INFINITY, f64::INFINITY);
    for pt in p
        .layers
        .iter()
        .flat_map(|l| &l.paths)
        .flat_map(|p| &p.points)
    {
        let f = r * nalgebra::Vector3::from(pt.focus()) + t;
        out = (out.0.min(f.z), out.1.min(f.x.hypot(f.y)));
    }
    out
}

/// The seed 000 duct on a 1 m tool: its far end beyond reach by a little,
/// found pose by pose. The base the help gave put the part 449 mm below the
/// robot's foot, and following it gave the same error and help.
#[test]
fn a_long_tools_reach_help_builds() {
    let src = example::duct(&[(
        "tool = frame(1, z = 350 mm)",
        "tool = frame(1, z = 1000 mm)",
    )]);
    let e = follow_the_help(&src, "kr60");
    assert!(!e.message.contains("at least"), "{}", e.message);
}

/// A part placed 3 m in front of the robot: refused from its points, and
/// the help's base builds.
#[test]
fn a_far_parts_reach_help_builds() {
    let src = std::fs::read_to_string("examples/errors/arm_out_of_reach.lmd").unwrap();
    let e = follow_the_help(&src, "kr60");
    assert!(e.message.contains("at least"), "{}", e.message);
}

/// The seed 000 duct drawn in inches on a KR 60 HA (a part 5 m across):
/// refused for reach from its points, before any pose is solved — the
/// count is the bound's, of the IR's points, and no error that needs a
/// solved pose (an axis limit, a singular LIN) is reported — with no base
/// to suggest. Following it pose by pose took 41 s and reported four more
/// errors.
#[test]
fn a_part_in_inches_is_refused_before_any_pose_is_solved() {
    let src = example::duct(&[
        ("let D1 = 60 mm", "let D1 = 60 in"),
        ("let L1 = 60 mm", "let L1 = 60 in"),
        ("let R1 = 250 mm", "let R1 = 250 in"),
        ("points = 360", "points = 36"),
    ]);
    let c = compile(&src, "kr60");
    let errs = errors(&c);
    assert_eq!(errs.len(), 1, "{errs:#?}");
    let e = errs[0];
    assert_eq!(e.code, Code::Reach);
    let refused = c.refused.as_ref().expect("only the arm refuses it");
    let b = beyond(refused.ir(), robot(refused.ir(), "kr60")).expect("beyond reach");
    assert!(
        e.message
            .contains(&format!("cannot reach at least {} poses", b.count)),
        "{}",
        e.message
    );
    let help = e.help.as_deref().unwrap_or_default();
    assert!(
        help.contains("no base brings the whole part within reach"),
        "{help}"
    );
}
