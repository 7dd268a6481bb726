//! ABB RAPID back end (IRC5 with RobotWare 6, OmniCore with RobotWare 7):
//! a main module `<stem>.mod` with the data and `PROC main()`, which calls
//! motion modules `<stem>_m001.mod`, … of at most the robot's
//! `max_points_per_module` motion instructions each. The subset written,
//! and why each instruction is the one it is: docs/rapid.md.
//!
//! The motion is the plan's ([`crate::plan`]), as the KRL back end writes
//! it: every move a `MoveL` to the laser focus with the tool's beam along
//! −normal, the laser and its power switched on the path by `TriggIO`
//! triggers of a `TriggL`, gas and powder where the robot stands.
//! Positions carry the configuration (`confdata`) of the solution the
//! verifier checked, and a positioner's angles as external axes.

pub mod modules;

use super::context::{counts, layer_context, styles};
use super::fmt::key as key_of;
use super::krl::{base_context, beam_text, comment_safe, home_config, positioner_text};
use super::{EmitError, Sink, Templates};
use crate::ir::{Layer, Load, Pose, Robot};
use crate::numbers::{fixed, trimmed};
use crate::plan::arm::{Joints, Solver};
use crate::plan::positioner::Kin;
use crate::plan::{orient::Orienter, Io, Move, MoveKind, Speed, Visit};
use crate::target::names::KrlNames;
use crate::target::rapid::{
    self as abb, signal, AO_DECIMALS, POS_DECIMALS, QUAT_DECIMALS, SPEED_DECIMALS,
};
use crate::verify::VerifiedMachine;
use modules::{Modules, Set, Target};
use nalgebra::{Matrix3, Rotation3, UnitQuaternion};
use std::collections::HashMap;
use std::io::Write;

/// The speed of the joint moves from and back to home (ABB's `v200`).
pub const HOME_SPEED: &str = "v200";

/// The names of `robot`'s files for the verified plan `m`: KRL's scheme
/// (its 24 characters are inside RAPID's 32), a stem that is a RAPID
/// keyword prefixed with `p`.
pub fn names(m: VerifiedMachine<'_>, robot: &Robot) -> KrlNames {
    let mut n = super::krl::names(m, robot);
    let upper = n.stem.to_ascii_uppercase();
    if abb::RESERVED.contains(&upper.as_str()) {
        n.stem = format!("p{}", n.stem);
    }
    n
}

/// Writes the RAPID modules of the verified robot `m` (`robot` is its
/// machine).
pub fn emit(
    m: VerifiedMachine<'_>,
    robot: &Robot,
    t: &Templates,
    sink: &mut dyn Sink,
) -> Result<(), EmitError> {
    let prog = m.ir();
    let names = names(m, robot);
    let base = base_context(m, robot, &names.stem);
    // Rendered first, so a broken template leaves no file.
    let mut first = base.clone();
    main_context(&mut first, m, robot, &[], modules::Stats::default());
    first.insert("modules", &[names.module(0)]);
    t.render("rapid/main.mod.tera", &first)
        .map_err(EmitError::Template)?;

    let mut w = Writer {
        out: Modules::new(
            sink,
            t,
            base.clone(),
            names.clone(),
            robot.max_points_per_module,
            [
                signal(&robot.laser_out, false),
                signal(&robot.power_out, true),
            ],
        ),
        orient: Orienter::for_robot(robot),
        conf: Conf::new(robot),
        robot,
        templates: t,
        base: &base,
        layers: prog.layers.len(),
        normal: None,
        rot: Matrix3::identity(),
        quat: [1.0, 0.0, 0.0, 0.0],
        speeds: Speeds::default(),
        switch: None,
        power: None,
        last: None,
        error: None,
    };
    m.plan().walk(&mut w);
    if let Some(e) = w.error {
        return Err(e);
    }
    let speeds = w.speeds.list;
    let (modules, stats) = w.out.finish()?;
    let mut ctx = base;
    main_context(&mut ctx, m, robot, &speeds, stats);
    ctx.insert("modules", &modules);
    let text = t
        .render("rapid/main.mod.tera", &ctx)
        .map_err(EmitError::Template)?;
    let mut out = sink.create(&format!("{}.mod", names.stem))?;
    out.write_all(text.as_bytes())?;
    out.flush()?;
    Ok(())
}

/// The analog output's value for `power` W: the fraction of full scale,
/// as written.
pub fn ao(power: f32, robot: &Robot) -> f64 {
    crate::target::written(power as f64 / robot.full_scale_power, AO_DECIMALS)
}

/// The most `speeddata` the main module declares: a program whose speed
/// changes from point to point (a height↔speed map) writes the speeds
/// after these in place, as aggregates.
pub const NAMED_SPEEDS: usize = 50;

/// The `speeddata` a program moves at: the first [`NAMED_SPEEDS`] named
/// `lmd_v1`, `lmd_v2`, … in the order first used, the rest in place.
#[derive(Default)]
struct Speeds {
    /// `(name, v_tcp as written)`.
    list: Vec<(String, String)>,
    by_key: HashMap<i64, usize>,
}

impl Speeds {
    /// How a motion at `v` mm/s names its speed.
    fn text(&mut self, v: f64) -> String {
        let k = key_of(v, SPEED_DECIMALS);
        if let Some(&i) = self.by_key.get(&k) {
            return self.list[i].0.clone();
        }
        let n = self.list.len();
        if n == NAMED_SPEEDS {
            return speeddata(&trimmed(v, SPEED_DECIMALS));
        }
        self.by_key.insert(k, n);
        let name = format!("lmd_v{}", n + 1);
        self.list.push((name.clone(), trimmed(v, SPEED_DECIMALS)));
        name
    }
}

/// A `speeddata` of `v_tcp` (mm/s, as written): the reorientation,
/// linear and rotating external axis speeds of ABB's `v`-speeds, so the
/// TCP speed is the one that binds.
pub fn speeddata(v_tcp: &str) -> String {
    format!("[{v_tcp},500,5000,1000]")
}

/// The configuration of each position: the arm solved from the solution
/// before, as the verifier follows it, from the one it starts from home.
struct Conf {
    solver: Option<Solver>,
    kin: Option<Kin>,
    prev: Option<Joints>,
}

impl Conf {
    fn new(robot: &Robot) -> Self {
        Conf {
            solver: Solver::new(robot),
            kin: Kin::of(robot),
            prev: None,
        }
    }

    /// The `confdata` of the move from home, whose solution is `j`.
    fn home(&mut self, j: Option<Joints>) -> [i32; 4] {
        self.prev = j;
        match (&self.solver, j) {
            (Some(s), Some(j)) => s.confdata(&j),
            _ => [0; 4],
        }
    }

    /// The `confdata` of the move `m` with the tool turned `rot`: the
    /// solution nearest the last (`[0, 0, 0, 0]` without an arm).
    fn of(&mut self, m: &Move, rot: &Matrix3<f64>) -> [i32; 4] {
        let (Some(s), Some(prev)) = (&self.solver, self.prev) else {
            return [0; 4];
        };
        let (to, rot) = match &self.kin {
            Some(k) => {
                let e = [m.axes.tilt, m.axes.c];
                let r = k.part(e).rotation.to_rotation_matrix().into_inner() * rot;
                (k.point(e, m.to), r)
            }
            None => (m.to, *rot),
        };
        match s.solve(to, &rot, &prev).first() {
            Some(j) => {
                self.prev = Some(*j);
                s.confdata(j)
            }
            None => s.confdata(&prev),
        }
    }
}

/// Writes a robot's motion plan.
struct Writer<'a, 's> {
    out: Modules<'s>,
    orient: Orienter,
    conf: Conf,
    robot: &'a Robot,
    templates: &'a Templates,
    base: &'a tera::Context,
    layers: usize,
    normal: Option<[f32; 3]>,
    rot: Matrix3<f64>,
    quat: [f64; 4],
    speeds: Speeds,
    /// A laser switch waiting for the next motion's start.
    switch: Option<bool>,
    /// The power last set, in 1/10⁴ of full scale.
    power: Option<i64>,
    last: Option<MoveKind>,
    error: Option<EmitError>,
}

impl Writer<'_, '_> {
    /// The power to set before depositing at `power` W, if it changed.
    fn power(&mut self, power: f32) -> Option<Set> {
        let x = ao(power, self.robot);
        let k = key_of(x, AO_DECIMALS);
        (self.power != Some(k)).then(|| {
            self.power = Some(k);
            Set::Power(x)
        })
    }

    fn target(&mut self, m: &Move, conf: [i32; 4]) -> Target {
        Target {
            pos: m.to,
            quat: self.quat,
            conf,
            ext: self
                .robot
                .positioner
                .as_ref()
                .map(|_| [m.axes.tilt, m.axes.c]),
        }
    }
}

impl Visit for Writer<'_, '_> {
    fn layer(&mut self, index: usize, layer: &Layer) {
        let mut ctx = self.base.clone();
        layer_context(&mut ctx, index, self.layers, layer);
        match self.templates.render("rapid/layer.tera", &ctx) {
            Ok(text) => self.out.layer(index + 1, &text),
            Err(e) => {
                self.error.get_or_insert(EmitError::Template(e));
            }
        }
    }

    fn laser_on(&mut self, next: &Move) {
        if self.last == Some(MoveKind::LeadIn) {
            // On the fly, where the lead-in ends, at the run's power.
            let mut set: Vec<Set> = self.power(next.power).into_iter().collect();
            set.push(Set::Laser(true));
            self.out.at_end(&set);
            return;
        }
        self.switch = Some(true);
    }

    fn laser_off(&mut self) {
        self.switch = Some(false);
    }

    fn dwell(&mut self, seconds: f64) {
        self.out.wait(seconds);
    }

    fn io(&mut self, event: Io) {
        let mut lines = Vec::new();
        if self.switch == Some(false) {
            // A guard: the plan retracts before any switching.
            self.switch = None;
            let laser = signal(&self.robot.laser_out, false);
            lines.push(format!("SetDO {laser}, 0; ! laser off"));
        }
        lines.extend(io_lines(self.robot, event));
        self.out.io(&lines);
    }

    fn motion(&mut self, m: &Move) {
        if self.normal != Some(m.normal) {
            self.normal = Some(m.normal);
            self.rot = self.orient.rotation(m.normal);
            self.quat = quaternion(&self.rot);
        }
        match m.kind {
            MoveKind::FromHome => {
                self.last = Some(m.kind);
                let j = home_config(self.robot, m, &self.rot).map(|c| c.2);
                let conf = self.conf.home(j);
                let t = self.target(m, conf);
                self.out.joint(&t, HOME_SPEED);
                return;
            }
            // `main` goes home after the motion modules.
            MoveKind::Home => return,
            _ => {}
        }
        let conf = self.conf.of(m, &self.rot);
        let t = self.target(m, conf);
        let speed = match m.speed {
            Speed::Rapid => self.robot.max_speed,
            Speed::Feed(v) => v as f64,
        };
        let deposit = m.deposits();
        let mut start: Vec<Set> = Vec::new();
        if deposit {
            start.extend(self.power(m.power));
        }
        if m.kind == MoveKind::LeadOut && self.switch == Some(false) {
            // Off where the last deposit ends, the robot going on.
            self.switch = None;
            self.out.at_end(&[Set::Laser(false)]);
        }
        if let Some(on) = self.switch.take() {
            start.push(Set::Laser(on));
        }
        self.last = Some(m.kind);
        let speed = self.speeds.text(speed);
        self.out.line(&t, &speed, &start, deposit);
    }
}

/// The unit quaternion `[q1, q2, q3, q4]` (scalar first) of the rotation
/// `r`, its first non-zero component (as written) positive so one
/// orientation is always written alike.
pub fn quaternion(r: &Matrix3<f64>) -> [f64; 4] {
    let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(*r));
    let c = q.into_inner().coords;
    let q = [c.w, c.x, c.y, c.z];
    let lead = q
        .iter()
        .find(|v| key_of(**v, QUAT_DECIMALS) != 0)
        .copied()
        .unwrap_or(1.0);
    if lead < 0.0 {
        q.map(|v| -v)
    } else {
        q
    }
}

/// The RAPID lines of a gas or powder event on `robot`, each with its
/// comment.
pub fn io_lines(robot: &Robot, event: Io) -> Vec<String> {
    use crate::back::cell::CellOut;
    crate::back::cell::outputs(robot, event)
        .into_iter()
        .map(|o| match o {
            CellOut::Rate { n, fraction, g_min } => format!(
                "SetAO {}, {}; ! powder {} g/min",
                signal(n, true),
                fixed(fraction, AO_DECIMALS),
                trimmed(g_min as f64, 2)
            ),
            CellOut::Switch { n, on, what } => format!(
                "SetDO {}, {}; ! {what} {}",
                signal(n, false),
                u8::from(on),
                if on { "on" } else { "off" }
            ),
        })
        .collect()
}

/// `[[x,y,z],[q1,q2,q3,q4]]` of a pose (a KUKA frame `X Y Z A B C`).
fn pose_text(p: &Pose) -> String {
    let f = crate::plan::arm::frame(p);
    let q = quaternion(&f.rotation.to_rotation_matrix().into_inner());
    let t = f.translation.vector;
    format!(
        "[[{},{},{}],[{}]]",
        trimmed(t.x, POS_DECIMALS),
        trimmed(t.y, POS_DECIMALS),
        trimmed(t.z, POS_DECIMALS),
        quat_text(q)
    )
}

fn quat_text(q: [f64; 4]) -> String {
    q.map(|v| trimmed(v, QUAT_DECIMALS)).join(",")
}

/// The `tooldata`: held by the robot, its frame and its load (mass kg,
/// centre of gravity mm, principal axes, moments of inertia kg·m²).
fn tooldata(robot: &Robot) -> String {
    let identity = Pose::default();
    let frame = pose_text(robot.tool.value.as_ref().unwrap_or(&identity));
    let load = robot.load.unwrap_or(Load {
        mass: 0.0,
        cog: [0.0; 3],
        inertia_axes: [0.0; 3],
        inertia: [0.0; 3],
    });
    let [x, y, z] = load.cog.map(|c| trimmed(c, 3));
    let [a, b, c] = load.inertia_axes;
    let aom = pose_text(&Pose {
        a,
        b,
        c,
        ..Pose::default()
    });
    // `[[0,0,0],[q]]` → `[q]`.
    let aom = &aom[aom.find("],[").map_or(0, |i| i + 2)..aom.len() - 1];
    let [ix, iy, iz] = load.inertia.map(|j| trimmed(j, 6));
    format!(
        "[TRUE,{frame},[{},[{x},{y},{z}],{aom},{ix},{iy},{iz}]]",
        trimmed(load.mass, 3)
    )
}

/// The mechanical unit a positioner's work object moves with.
pub const POSITIONER_UNIT: &str = "STN1";

/// The `wobjdata`: the base as the user frame, or, on a positioner, the
/// base on its flange as the object frame of a frame the unit moves.
fn wobjdata(robot: &Robot) -> String {
    let identity = Pose::default();
    let base = pose_text(robot.base.value.as_ref().unwrap_or(&identity));
    let zero = "[[0,0,0],[1,0,0,0]]";
    match robot.positioner {
        Some(_) => format!("[FALSE,FALSE,\"{POSITIONER_UNIT}\",{zero},{base}]"),
        None => format!("[FALSE,TRUE,\"\",{base},{zero}]"),
    }
}

/// The home `jointtarget`: the arm's axes, a positioner's two.
fn home_text(robot: &Robot) -> String {
    let axes: Vec<String> = robot.home.iter().map(|a| trimmed(*a, 3)).collect();
    let mut ext = Vec::new();
    modules::extax(&mut ext, robot.positioner.as_ref().map(|p| p.home));
    format!("[[{}],{}]", axes.join(","), String::from_utf8_lossy(&ext))
}

/// The zone `lmd_z` of the robot's blending `b` mm, in the pattern of
/// ABB's z-zones (`z1 = [FALSE,1,1,1,0.1,1,0.1]`).
fn zone_text(b: f64) -> String {
    let (b, t) = (trimmed(b, 3), trimmed(b / 10.0, 4));
    format!("[FALSE,{b},{b},{b},{t},{b},{t}]")
}

fn main_context(
    ctx: &mut tera::Context,
    m: VerifiedMachine<'_>,
    robot: &Robot,
    speeds: &[(String, String)],
    s: modules::Stats,
) {
    counts(ctx, m.ir());
    styles(ctx, m.ir(), &comment_safe);
    ctx.insert("tooldata", &tooldata(robot));
    ctx.insert("wobjdata", &wobjdata(robot));
    ctx.insert("home", &home_text(robot));
    let speeds: Vec<_> = speeds
        .iter()
        .map(|(n, v)| serde_json::json!({ "name": n, "data": speeddata(v) }))
        .collect();
    ctx.insert("speeds", &speeds);
    ctx.insert(
        "zone",
        &zone_text(robot.blending.unwrap_or(crate::target::kuka::APO_CDIS_MM)),
    );
    ctx.insert("triggers", &modules::TRIGGERS);
    ctx.insert("home_speed", HOME_SPEED);
    ctx.insert(
        "conf_j",
        // The arm is checked, and the configurations written, where it
        // can be solved.
        if Solver::new(robot).is_some() {
            "On"
        } else {
            "Off"
        },
    );
    ctx.insert(
        "positioner",
        &robot.positioner.as_deref().map(|p| {
            positioner_text(
                p,
                ["eax_a (tilt)", "eax_b (rotate, at eax_a = 0)"],
                &format!("the work object moves with the mechanical unit {POSITIONER_UNIT}; every position is in it"),
            )
        }),
    );
    ctx.insert("spin", &super::krl::spin_text(robot.spin));
    ctx.insert("beam", beam_text(robot.beam));
    ctx.insert("laser_out", &robot.laser_out);
    ctx.insert("power_out", &robot.power_out);
    ctx.insert("laser_signal", &signal(&robot.laser_out, false));
    ctx.insert("power_signal", &signal(&robot.power_out, true));
    ctx.insert("full_scale", &trimmed(robot.full_scale_power, 3));
    ctx.insert("clearance", &trimmed(robot.clearance, 3));
    ctx.insert("module_lines", &robot.max_points_per_module);
    ctx.insert("move_lines", &s.moves);
    ctx.insert("deposits", &s.deposits);
    ctx.insert("laser_starts", &s.laser_ons);
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    /// The quaternion turns vectors as the matrix does, and one
    /// orientation is written one way whatever sign nalgebra gives.
    #[test]
    fn quaternions_turn_as_the_matrix_and_lead_positive() {
        for (axis, deg) in [
            (Vector3::x(), 180.0),
            (Vector3::y(), 180.0),
            (Vector3::new(1.0, 2.0, -0.5), 250.0),
            (Vector3::z(), -90.0),
        ] {
            let r = Rotation3::from_axis_angle(
                &nalgebra::Unit::new_normalize(axis),
                f64::to_radians(deg),
            );
            let q = quaternion(r.matrix());
            let uq =
                UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q[0], q[1], q[2], q[3]));
            let v = Vector3::new(0.3, -0.7, 0.2);
            assert!((uq * v - r * v).norm() < 1e-12, "{axis:?} {deg}");
            let lead = q.iter().find(|c| c.abs() >= 5e-7).unwrap();
            assert!(*lead > 0.0, "{q:?}");
            assert!((q.iter().map(|c| c * c).sum::<f64>() - 1.0).abs() < 1e-12);
        }
        // Straight down with the tool's X along the base's: a half turn about X.
        let down = Matrix3::new(1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, -1.0);
        assert_eq!(
            quaternion(&down).map(|c| trimmed(c, 6)),
            ["0", "1", "0", "0"]
        );
    }

    /// The first fifty speeds are named in the order used, a speed used
    /// again keeps its name, the fifty-first is written in place.
    #[test]
    fn fifty_speeds_are_named_and_the_rest_written_in_place() {
        let mut s = Speeds::default();
        assert_eq!(s.text(8.0), "lmd_v1");
        assert_eq!(s.text(250.0), "lmd_v2");
        assert_eq!(s.text(8.0004), "lmd_v1", "the same as written");
        for i in 0..48 {
            assert_eq!(s.text(10.0 + i as f64), format!("lmd_v{}", i + 3));
        }
        assert_eq!(s.text(7.25), "[7.25,500,5000,1000]");
        assert_eq!(s.text(250.0), "lmd_v2");
        assert_eq!(s.list.len(), NAMED_SPEEDS);
    }

    /// The zone follows ABB's z-zones: `z1`'s numbers at 1 mm.
    #[test]
    fn the_zone_is_shaped_like_abbs() {
        assert_eq!(zone_text(1.0), "[FALSE,1,1,1,0.1,1,0.1]");
        assert_eq!(zone_text(0.2), "[FALSE,0.2,0.2,0.2,0.02,0.2,0.02]");
    }
}
