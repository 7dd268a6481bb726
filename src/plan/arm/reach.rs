//! The arm's reach over a whole part, without solving its poses one by one:
//! whether some point of the part lies beyond reach whatever the tool's turn
//! ([`beyond`], `lmd::reach`'s quick refusal, milliseconds where following
//! a large plan pose by pose takes minutes), and a base that brings the part
//! within reach ([`fix`], the help of `lmd::reach`).
//!
//! Both rest on one bound. The wrist centre lies a fixed distance from the
//! tool's focus, whatever the tool's orientation: the flange is `TCP ·
//! TOOL⁻¹` and the wrist centre `c4` behind the flange, so it is the point
//! `TOOL⁻¹ · (0, 0, −c4)` of the TCP's frame, `|(0, 0, −c4) − t_tool|` from
//! its origin. The arm reaches a pose only where the wrist centre lies at
//! most `c2 + √(c3² + a2²)` from the A2 axis, and A2 turns on the circle of
//! radius `√(a1² + b²)` round A1's axis at the height `c1`: a focus farther
//! than those two lengths together from that circle is out of reach.

use super::clearance::{self, clearance};
use super::{frame, Solver};
use crate::ir::{Machine, Pose, Program, Robot, Spin};
use crate::plan::{Plan, Where};
use nalgebra::{Isometry3, Point3, Rotation3, Vector3};

/// How far beyond A2's circle round A1's axis a suggested base keeps the
/// part, mm: room for the robot's own foot and column.
pub const FOOT_MM: f64 = 200.0;
/// The steps a suggested base is searched in, mm.
pub const STEP_MM: f64 = 50.0;
/// The most candidate bases solved pose by pose before giving up.
pub const TRIES: usize = 24;
/// The share of the arm's reach a suggested base keeps every sampled wrist
/// centre within: clear of the stretched arm.
pub const KEEP: f64 = 0.9;

/// A part beyond the arm's reach, found from its points before any pose
/// is solved.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Beyond {
    /// How many of the IR's points the arm cannot reach whatever the tool's
    /// turn (the plan's poses out of reach are at least as many).
    pub count: u64,
    /// The farthest of them.
    pub at: Where,
    /// The least distance its wrist centre would be from the A2 axis, mm.
    pub least: f64,
    /// The nearest and farthest the arm puts the wrist centre from A2, mm.
    pub span: [f64; 2],
}

/// The geometry of the bound: the robot's base, A2's circle, and how far
/// the wrist centre lies from the focus.
struct Reach {
    base: Isometry3<f64>,
    /// A2's circle: its radius and height, mm, and A2's distance from
    /// A1's axis along the arm (the solver's measure of reach).
    ring: f64,
    c1: f64,
    a1: f64,
    /// The wrist centre's distance from the focus, mm.
    wrist: f64,
    span: [f64; 2],
}

impl Reach {
    fn of(s: &Solver, robot: &Robot) -> Option<Reach> {
        Some(Reach::with(
            s,
            frame(&robot.base.value?),
            &robot.tool.value?,
        ))
    }

    /// The bound of the arm of `s` with the base `base` and the tool `t`.
    fn with(s: &Solver, base: Isometry3<f64>, t: &Pose) -> Reach {
        let [a1, _, b, c1, _, _, c4] = s.arm().opw;
        Reach {
            base,
            ring: a1.hypot(b),
            c1,
            a1,
            wrist: (t.x * t.x + t.y * t.y + (t.z + c4).powi(2)).sqrt(),
            span: s.span(),
        }
    }

    /// The least distance from A2 the wrist centre can have with the focus
    /// at `f` (in the robot's frame), mm.
    fn least(&self, f: &Point3<f64>) -> f64 {
        let h = f.x.hypot(f.y);
        (h - self.ring).hypot(f.z - self.c1) - self.wrist
    }
}

/// Whether the arm of `robot` cannot reach some point of `program` whatever
/// the tool's turn, and which: `None` where every point may be reachable (the
/// poses are then solved one by one), where the robot declares no arm or
/// only indices for its base and tool, or where a positioner moves the part.
pub fn beyond(program: &Program, robot: &Robot) -> Option<Beyond> {
    if robot.positioner.is_some() {
        return None;
    }
    let r = Reach::of(&Solver::new(robot)?, robot)?;
    let mut out: Option<Beyond> = None;
    for (layer, l) in program.layers.iter().enumerate() {
        for (path, p) in l.paths.iter().enumerate() {
            for (point, pt) in p.points.iter().enumerate() {
                let d = r.least(&(r.base * Point3::from(pt.focus())));
                if d.is_nan() || d <= r.span[1] {
                    continue;
                }
                let at = Where::Point { layer, path, point };
                let b = out.get_or_insert(Beyond {
                    count: 0,
                    at,
                    least: d,
                    span: r.span,
                });
                b.count += 1;
                if d > b.least {
                    (b.at, b.least) = (at, d);
                }
            }
        }
    }
    out
}

/// What would bring a part within the arm's reach.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Fix {
    /// A base, in whole mm and turned as declared, that stands the part on
    /// or above the plane of the robot's foot and in front of it, from
    /// which the arm follows [`clearance::SAMPLES`] of the plan's moves within
    /// every rule [`clearance()`] checks.
    Base(Pose),
    /// No base can: two of the part's points lie `across` mm apart, and no
    /// two foci the arm reaches with this tool lie more than `most` apart.
    TooLarge {
        /// The part's extent along one axis, mm.
        across: f64,
        /// The most two reachable foci lie apart, mm.
        most: f64,
    },
    /// None of the bases tried lets the arm follow the plan; the part's
    /// extent along one axis is `across` mm (0: not known).
    Unfound {
        /// The part's extent, mm.
        across: f64,
    },
}

/// A base that brings `machine`'s poses of `program` within reach, turned
/// as declared: `TooLarge` where the part is larger than any two poses the
/// arm reaches lie apart; else the first base tried (nearest where lmdc
/// would put the part, in front of the robot and above its foot, in steps
/// of [`STEP_MM`]) from which every sampled wrist centre ([`clearance::sample`]'s
/// moves) lies within [`KEEP`] of the reach and the arm follows the sampled
/// moves within every rule [`clearance()`] checks (at most [`TRIES`]
/// followed).
pub fn fix(program: &Program, machine: &Machine) -> Fix {
    let Machine::Robot(robot) = machine else {
        return Fix::Unfound { across: 0.0 };
    };
    let Some(s) = Solver::new(robot) else {
        return Fix::Unfound { across: 0.0 };
    };
    let Some(r) = Reach::of(&s, robot) else {
        return Fix::Unfound { across: 0.0 };
    };
    let b = robot.base.value.unwrap_or_default();
    let turn = frame(&Pose {
        x: 0.0,
        y: 0.0,
        z: 0.0,
        ..b
    })
    .rotation;
    let (lo, hi) = extent(program, &turn);
    let across = (0..3).map(|i| hi[i] - lo[i]).fold(0.0, f64::max);
    let most = 2.0 * (r.ring + r.span[1] + r.wrist);
    if across > most {
        return Fix::TooLarge { across, most };
    }
    // As the file turns the tool; `auto` as it would choose again: 0°
    // where that passes.
    let deg = match robot.spin {
        Spin::Declared { deg } => deg,
        Spin::Auto { .. } => 0.0,
    };
    let moves = clearance::sample(program, &Plan::new(program, machine));
    let wrists = wrists(robot, deg, &moves, &turn);
    for t in candidates(&s, &r, robot, lo, hi)
        .into_iter()
        .filter(|t| r.keeps(&wrists, t))
        .take(TRIES)
    {
        let mut moved = robot.clone();
        let base = Pose {
            x: t.x,
            y: t.y,
            z: t.z,
            ..b
        };
        moved.base.value = Some(base);
        if clearance(&moved, deg, &moves) >= 0.0 {
            return Fix::Base(base);
        }
    }
    Fix::Unfound { across }
}

/// The bases to try, in whole mm, nearest first to where lmdc would put
/// the part: its centre 60 % of the forearm's reach in front of A1, and a
/// tool length and the wrist below A2 (a nozzle pointing down has the
/// wrist at A2's height), but the part's lowest focus no lower than the
/// robot's foot and its nearest [`FOOT_MM`] beyond A2's circle; in steps
/// of [`STEP_MM`] as far as the arm reaches. `lo` and `hi` bound the foci
/// in the robot's axes, the base not yet moved.
fn candidates(
    s: &Solver,
    r: &Reach,
    robot: &Robot,
    lo: [f64; 3],
    hi: [f64; 3],
) -> Vec<Vector3<f64>> {
    let [a1, _, _, c1, _, _, c4] = s.arm().opw;
    let tool = robot.tool.value.map_or(0.0, |t| t.x.hypot(t.y).hypot(t.z));
    let centre = |i: usize| (lo[i] + hi[i]) / 2.0;
    let (front, floor) = (FOOT_MM + r.ring - lo[0], -lo[2]);
    let ideal = Vector3::new(
        (a1 + 0.6 * r.span[1] - centre(0)).max(front).ceil(),
        (-centre(1)).round(),
        (c1 - tool - c4 - centre(2)).max(floor).ceil(),
    );
    let n = ((r.ring + r.span[1] + r.wrist) / STEP_MM).ceil() as i64;
    let mut out: Vec<Vector3<f64>> = (-n..=n)
        .flat_map(|i| (-n..=n).map(move |k| (i, k)))
        .map(|(i, k)| ideal + Vector3::new(i as f64, 0.0, k as f64) * STEP_MM)
        .filter(|t| t.x >= front && t.z >= floor)
        .collect();
    out.sort_by(|a, b| (a - ideal).norm().total_cmp(&(b - ideal).norm()));
    out
}

impl Reach {
    /// Whether every sampled wrist centre `w` (in the robot's axes, the
    /// base not yet moved) lies, with the base moved by `t`, within
    /// [`KEEP`] of the reach from A2 and farther than the arm folds.
    fn keeps(&self, w: &[Vector3<f64>], t: &Vector3<f64>) -> bool {
        let (near, far) = (self.span[0] + STEP_MM, KEEP * self.span[1]);
        w.iter().all(|v| {
            let p = v + t;
            (near..=far).contains(&(p.x.hypot(p.y) - self.a1).hypot(p.z - self.c1))
        })
    }
}

/// The extent of the part's foci in the robot's axes, turned by `turn`
/// (the base's rotation), not moved.
fn extent(program: &Program, turn: &nalgebra::UnitQuaternion<f64>) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in program
        .layers
        .iter()
        .flat_map(|l| &l.paths)
        .flat_map(|p| &p.points)
    {
        let f = turn * Vector3::from(p.focus());
        for i in 0..3 {
            lo[i] = lo[i].min(f[i]);
            hi[i] = hi[i].max(f[i]);
        }
    }
    (lo, hi)
}

/// The wrist centre of each of `moves` with the tool turned `deg` about its
/// beam, in the robot's axes turned by `turn`, the base not yet moved.
fn wrists(
    robot: &Robot,
    deg: f64,
    moves: &[crate::plan::Move],
    turn: &nalgebra::UnitQuaternion<f64>,
) -> Vec<Vector3<f64>> {
    let mut turned = robot.clone();
    turned.spin = Spin::Declared { deg };
    let mut orient = crate::plan::orient::Orienter::for_robot(&turned);
    let Some(tool) = turned.tool.value.map(|t| frame(&t)) else {
        return Vec::new();
    };
    let c4 = robot.arm.as_ref().map_or(0.0, |a| a.opw[6]);
    // The wrist centre in the TCP's frame.
    let q = tool.inverse() * Point3::new(0.0, 0.0, -c4);
    moves
        .iter()
        .map(|m| {
            let rot = Rotation3::from_matrix_unchecked(orient.rotation(m.normal));
            turn * (Vector3::from(m.to) + rot * q.coords)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::target::arm::CATALOGUE;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]
        /// The bound is one, for every catalogue arm, any tool on the
        /// flange, a shoulder offset `b` or none, and a focus anywhere in
        /// the cell turned any way: no wrist centre lies nearer A2's circle
        /// than [`Reach::least`] says, and where that is beyond the reach
        /// the pose has no solution.
        #[test]
        fn the_bound_refuses_no_reachable_pose(
            arm in 0..CATALOGUE.len(),
            b in prop::sample::select(vec![0.0, 40.0, -120.0]),
            t in prop::array::uniform3(-400.0f64..400.0),
            turn in prop::array::uniform3(-180.0f64..180.0),
            f in prop::array::uniform3(-4000.0f64..4000.0),
            abc in prop::array::uniform3(-180.0f64..180.0),
        ) {
            let mut a = crate::target::arm::model(CATALOGUE[arm].key).unwrap().arm(0.0, 5.0);
            a.opw[2] = b;
            let tool = Pose { x: t[0], y: t[1], z: t[2], a: turn[0], b: turn[1], c: turn[2] };
            let s = Solver::with(a, Isometry3::identity(), frame(&tool));
            let r = Reach::with(&s, Isometry3::identity(), &tool);
            let at = Pose { x: 0.0, y: 0.0, z: 0.0, a: abc[0], b: abc[1], c: abc[2] };
            let rot = *frame(&at).rotation.to_rotation_matrix().matrix();
            let w = s.wrist(&s.flange(f, &rot));
            let ring = (w.x.hypot(w.y) - r.ring).hypot(w.z - r.c1);
            let least = r.least(&Point3::from(f));
            prop_assert!(least <= ring + 1e-6, "bound {least} > {ring}");
            if least > r.span[1] {
                let home = s.upright();
                prop_assert!(s.solve(f, &rot, &home).is_empty(), "solved beyond the bound {least}");
            }
        }
    }
}
