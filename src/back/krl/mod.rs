//! KUKA KRL back end (KR C4/C5, KSS 8.x): one main program `<stem>.src/.dat`
//! that initialises the robot and calls motion modules `<stem>_m001.src/.dat`, …,
//! each holding at most the robot's `max_points_per_module` LIN lines.
//!
//! The programs' shape comes from the tera templates `krl/main.src.tera`,
//! `krl/main.dat.tera`, `krl/module.src.tera`, `krl/module.dat.tera` and
//! `krl/layer.tera`; the motion lines are written by [`modules`] without tera.
//! Conventions and the template context: `docs/krl.md`.
//!
//! Motion: every move of the motion plan ([`crate::plan`]) is a `LIN` to the
//! laser focus with the tool's beam axis along −normal ([`orient`]), `C_DIS`
//! approximated except where the laser switches; rapid moves go at the robot's
//! `max_speed`. `$VEL.CP` (m/s) is set when the speed changes; the laser output
//! `$OUT` and the power `$ANOUT` switch through `TRIGGER WHEN DISTANCE=0` on the
//! motion that starts where the plan switches them, so they happen on the path
//! rather than when the advance run reads the line.

pub mod height_loop;
pub mod modules;
/// The tool orientation, decided by the plan ([`crate::plan::orient`]): the
/// verifier solves the arm for the same `A B C` this back end writes.
pub use crate::plan::orient;

use super::context::{counts, layer_context, shown, styles};
use super::{EmitError, Sink, Templates};
use crate::ir::{FrameRef, Layer, Load, Robot, ToolAxis};
use crate::numbers::{fixed, trimmed};
use crate::plan::{Io, Move, MoveKind, Speed, Visit};
use crate::target::kuka;
use crate::target::names::KrlNames;
use crate::verify::VerifiedMachine;
use modules::{Modules, Switch};
use orient::{Abc, Orienter};
use std::io::Write;

/// Longest KRL name (module, DEF and DEFDAT names).
pub const MAX_NAME: usize = kuka::MAX_NAME;

/// Rounding distance of `C_DIS` when the robot declares no `blending`, mm.
pub const APPROX_MM: f64 = kuka::APO_CDIS_MM;

/// Speed of the move from home to the first point, % of the axes' maximum.
pub const HOME_PERCENT: u32 = 20;

/// The names of `robot`'s files for the verified plan `m`.
pub fn names(m: VerifiedMachine<'_>, robot: &Robot) -> KrlNames {
    let prog = m.ir();
    let paths = prog.layers.iter().map(|l| l.paths.len()).sum();
    KrlNames::new(&prog.part, robot, prog.point_count(), paths)
}

/// Writes the KRL programs of the verified robot `m` (`robot` is its machine).
pub fn emit(
    m: VerifiedMachine<'_>,
    robot: &Robot,
    t: &Templates,
    sink: &mut dyn Sink,
) -> Result<(), EmitError> {
    let prog = m.ir();
    if prog.loop_on_machine().is_some() {
        return height_loop::emit(m, robot, t, sink);
    }
    let names = names(m, robot);
    let base = base_context(m, robot, &names.stem);

    // Rendered first, so a broken template leaves no file.
    let mut main_ctx = base.clone();
    main_ctx.insert("modules", &[names.module(0)]);
    main_context(&mut main_ctx, m, robot, modules::Stats::default());
    t.render("krl/main.src.tera", &main_ctx)
        .map_err(EmitError::Template)?;

    let mut w = Writer {
        out: Modules::new(
            sink,
            t,
            base.clone(),
            names.clone(),
            robot.max_points_per_module,
            number(&robot.laser_out),
            number(&robot.power_out),
        ),
        orient: Orienter::for_robot(robot),
        robot,
        templates: t,
        base: &base,
        layers: prog.layers.len(),
        normal: None,
        rot: nalgebra::Matrix3::identity(),
        abc: Abc {
            a: 0.0,
            b: 0.0,
            c: 0.0,
        },
        switch: None,
        anout: None,
        power_bits: 0,
        last: None,
        error: None,
    };
    m.plan().walk(&mut w);
    if let Some(e) = w.error {
        return Err(e);
    }
    let (modules, stats) = w.out.finish()?;

    let mut ctx = base.clone();
    ctx.insert("modules", &modules);
    main_context(&mut ctx, m, robot, stats);
    let src = t
        .render("krl/main.src.tera", &ctx)
        .map_err(EmitError::Template)?;
    let dat = t
        .render("krl/main.dat.tera", &ctx)
        .map_err(EmitError::Template)?;
    let mut out = sink.create(&format!("{}.src", names.stem))?;
    out.write_all(src.as_bytes())?;
    out.flush()?;
    drop(out);
    let mut out = sink.create(&format!("{}.dat", names.stem))?;
    out.write_all(dat.as_bytes())?;
    out.flush()?;
    Ok(())
}

/// `$ANOUT` value for `power` W: the fraction of full scale, as written.
pub fn anout(power: f32, robot: &Robot) -> f64 {
    crate::target::written(power as f64 / robot.full_scale_power, kuka::ANOUT_DECIMALS)
}

/// Writes a robot's motion plan: a `LIN` per move.
struct Writer<'a, 's> {
    out: Modules<'s>,
    orient: Orienter,
    robot: &'a Robot,
    templates: &'a Templates,
    base: &'a tera::Context,
    layers: usize,
    /// The normal the orientation was last solved for, and its `A B C`.
    normal: Option<[f32; 3]>,
    rot: nalgebra::Matrix3<f64>,
    abc: Abc,
    /// A laser switch waiting for the next motion's start.
    switch: Option<Switch>,
    /// The last `$ANOUT` value set, in 1/10⁴ of full scale.
    anout: Option<i64>,
    /// The power (f32 bits) it was set for.
    power_bits: u32,
    /// What the last motion was for.
    last: Option<MoveKind>,
    error: Option<EmitError>,
}

impl Writer<'_, '_> {
    /// The `$ANOUT` value to set before depositing at `power`, if it changed.
    fn power(&mut self, power: f32) -> Option<f64> {
        // Most moves repeat the power of the move before.
        if self.anout.is_some() && power.to_bits() == self.power_bits {
            return None;
        }
        self.power_bits = power.to_bits();
        let x = anout(power, self.robot);
        let key = (x * 1e4).round() as i64;
        if self.anout == Some(key) {
            return None;
        }
        self.anout = Some(key);
        Some(x)
    }
}

impl Visit for Writer<'_, '_> {
    fn layer(&mut self, index: usize, layer: &Layer) {
        let mut ctx = self.base.clone();
        layer_context(&mut ctx, index, self.layers, layer);
        match self.templates.render("krl/layer.tera", &ctx) {
            Ok(text) => self.out.layer(index + 1, &text),
            Err(e) => {
                self.error.get_or_insert(EmitError::Template(e));
            }
        }
    }

    fn laser_on(&mut self, next: &Move) {
        if self.last == Some(MoveKind::LeadIn) {
            // On the fly, where the lead-in ends, at the run's power.
            let x = self.power(next.power);
            self.out.switch_at_end(x, Switch::On);
            return;
        }
        self.switch = Some(Switch::On);
    }

    fn laser_off(&mut self) {
        // Attached to the next motion's start: the end point of the last
        // deposit (on the fly when that motion is a lead-out).
        self.switch = Some(Switch::Off);
    }

    fn dwell(&mut self, seconds: f64) {
        self.out.wait(seconds);
    }

    fn io(&mut self, event: Io) {
        let mut lines = Vec::new();
        if self.switch == Some(Switch::Off) {
            // The plan retracts before any switching, so this is only a guard:
            // the laser goes off before gas or powder do.
            self.switch = None;
            lines.push(format!("$OUT[{}]=FALSE", self.robot.laser_out));
        }
        lines.extend(io_lines(self.robot, event));
        self.out.io(&lines);
    }

    #[inline]
    fn motion(&mut self, m: &Move) {
        if self.normal != Some(m.normal) {
            // Most parts keep one normal over many moves: solve only on a change.
            self.normal = Some(m.normal);
            self.rot = self.orient.rotation(m.normal);
            self.abc = orient::abc(&self.rot);
        }
        // A positioner's E1 and E2 on every motion (E6POS).
        let ext = self
            .robot
            .positioner
            .as_ref()
            .map(|_| [m.axes.tilt, m.axes.c]);
        match m.kind {
            MoveKind::FromHome => {
                self.last = Some(m.kind);
                let config = home_config(self.robot, m, &self.rot);
                self.out.ptp(m.to, self.abc, ext, config);
                return;
            }
            // The main program goes home after the modules (main.src.tera).
            MoveKind::Home => return,
            _ => {}
        }
        let speed = match m.speed {
            Speed::Rapid => self.robot.max_speed,
            Speed::Feed(v) => v as f64,
        };
        let deposit = m.deposits();
        let x = if deposit { self.power(m.power) } else { None };
        if m.kind == MoveKind::LeadOut && self.switch == Some(Switch::Off) {
            // Off where the last deposit ends, the robot going on.
            self.switch = None;
            self.out.switch_at_end(None, Switch::Off);
        }
        let s = self.switch.take();
        self.last = Some(m.kind);
        self.out.lin(m.to, self.abc, ext, speed, x, s, deposit);
    }
}

/// The Status, Turn and axis angles of the PTP from home `m` with the tool
/// turned `rot`, where the arm is known: the solution the verifier checked
/// ([`crate::plan::arm::Solver::home_solution`]), through the positioner at
/// the move's angles.
pub fn home_config(
    robot: &Robot,
    m: &Move,
    rot: &nalgebra::Matrix3<f64>,
) -> Option<(u8, u8, [f64; 6])> {
    let s = crate::plan::arm::Solver::new(robot)?;
    let (to, rot) = match crate::plan::positioner::Kin::of(robot) {
        Some(k) => {
            let part = k.part([m.axes.tilt, m.axes.c]);
            let r = part.rotation.to_rotation_matrix().into_inner() * rot;
            (k.point([m.axes.tilt, m.axes.c], m.to), r)
        }
        None => (m.to, *rot),
    };
    let j = s.home_solution(to, &rot, &robot.home)?;
    Some((s.status(&j), crate::plan::arm::Solver::turn(&j), j))
}

/// A KUKA robot's output number: sema gives a KUKA robot numbered outputs
/// only (a signal's name is ABB's), so a name has none to write (0).
fn number(s: &crate::ir::Signal) -> u16 {
    s.number().unwrap_or_default()
}

/// The KRL lines of a gas or powder event on `robot` (assignments with a
/// comment; the caller puts them after an advance-run stop).
pub fn io_lines(robot: &Robot, event: Io) -> Vec<String> {
    use crate::back::cell::CellOut;
    crate::back::cell::outputs(robot, event)
        .into_iter()
        .map(|o| match o {
            CellOut::Rate { n, fraction, g_min } => format!(
                "$ANOUT[{n}]={} ; powder {} g/min",
                fixed(fraction, kuka::ANOUT_DECIMALS),
                trimmed(g_min as f64, 2)
            ),
            CellOut::Switch { n, on, what } => format!(
                "$OUT[{n}]={} ; {what} {}",
                if on { "TRUE" } else { "FALSE" },
                if on { "on" } else { "off" }
            ),
        })
        .collect()
}

/// Variables every template of the verified robot `m` sees, the plan's
/// one-line summary among them.
pub(crate) fn base_context(m: VerifiedMachine<'_>, robot: &Robot, stem: &str) -> tera::Context {
    let p = m.ir();
    let mut ctx = tera::Context::new();
    ctx.insert(
        "summary",
        &comment_safe(&super::context::summary(m.summary())),
    );
    ctx.insert("program", stem);
    ctx.insert("part", &comment_safe(&shown(&p.part)));
    ctx.insert("machine", &comment_safe(&shown(&robot.name)));
    ctx.insert("generator", concat!("lmdc ", env!("CARGO_PKG_VERSION")));
    super::context::provenance(&mut ctx, m.provenance(), &comment_safe);
    ctx
}

/// Text safe inside a `;` comment: printable ASCII (KRL files are Latin-1 on the
/// controller), one line.
pub fn comment_safe(text: &str) -> String {
    text.chars()
        .map(|c| {
            if c.is_ascii_graphic() || c == ' ' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// A frame as a KRL FRAME aggregate, or `None` when the controller's table entry
/// is used as it is.
fn frame_value(f: &FrameRef) -> Option<String> {
    f.value.map(|v| {
        format!(
            "{{X {},Y {},Z {},A {},B {},C {}}}",
            fixed(v.x, 3),
            fixed(v.y, 3),
            fixed(v.z, 3),
            fixed(v.a, 3),
            fixed(v.b, 3),
            fixed(v.c, 3)
        )
    })
}

/// A tool's load as KRL's LOAD aggregate (`$LOAD`): mass kg, centre of
/// gravity and principal axes in the flange's frame (mm, deg), principal
/// moments of inertia kg·m²; `None` when the controller's `LOAD_DATA[n]` is
/// used.
fn load_value(l: Option<&Load>) -> Option<String> {
    l.map(|l| {
        let [x, y, z] = l.cog.map(|c| fixed(c, 3));
        let [a, b, c] = l.inertia_axes.map(|c| fixed(c, 3));
        let [jx, jy, jz] = l.inertia.map(|j| fixed(j, 6));
        format!(
            "{{M {},CM {{X {x},Y {y},Z {z},A {a},B {b},C {c}}},J {{X {jx},Y {jy},Z {jz}}}}}",
            fixed(l.mass, 3)
        )
    })
}

pub(crate) fn beam_text(b: ToolAxis) -> &'static str {
    match b {
        ToolAxis::PlusX => "+X",
        ToolAxis::MinusX => "-X",
        ToolAxis::PlusY => "+Y",
        ToolAxis::MinusY => "-Y",
        ToolAxis::PlusZ => "+Z",
        ToolAxis::MinusZ => "-Z",
    }
}

fn main_context(ctx: &mut tera::Context, m: VerifiedMachine<'_>, robot: &Robot, s: modules::Stats) {
    counts(ctx, m.ir());
    styles(ctx, m.ir(), &comment_safe);
    ctx.insert("tool_index", &robot.tool.index);
    ctx.insert("tool_value", &frame_value(&robot.tool));
    ctx.insert("load_value", &load_value(robot.load.as_ref()));
    ctx.insert("base_index", &robot.base.index);
    ctx.insert("base_value", &frame_value(&robot.base));
    ctx.insert(
        "positioner",
        &robot.positioner.as_deref().map(|p| {
            positioner_text(
                p,
                ["E1 (tilt)", "E2 (rotate, at E1 = 0)"],
                "the base turns with E1 and E2 ($BASE coupled to MACHINE_DEF[2]); every position is in it",
            )
        }),
    );
    ctx.insert("beam", beam_text(robot.beam));
    ctx.insert("spin", &spin_text(robot.spin));
    ctx.insert("laser_out", &robot.laser_out);
    ctx.insert("power_out", &robot.power_out);
    ctx.insert("full_scale", &trimmed(robot.full_scale_power, 3));
    ctx.insert("max_speed", &trimmed(robot.max_speed / 1000.0, 6));
    ctx.insert("clearance", &trimmed(robot.clearance, 3));
    ctx.insert(
        "approximation",
        &trimmed(robot.blending.unwrap_or(APPROX_MM), 3),
    );
    ctx.insert("home_percent", &HOME_PERCENT);
    let mut home: Vec<String> = robot
        .home
        .iter()
        .enumerate()
        .map(|(i, a)| format!("A{} {}", i + 1, trimmed(*a, 3)))
        .collect();
    // An E6AXIS with the positioner's home angles: the program starts from
    // them and ends at them, as the plan's moves from and back home do.
    if let Some(p) = &robot.positioner {
        home.extend(
            p.home
                .iter()
                .enumerate()
                .map(|(i, e)| format!("E{} {}", i + 1, trimmed(*e, 3))),
        );
    }
    ctx.insert("home", &home.join(","));
    ctx.insert("module_lines", &robot.max_points_per_module);
    ctx.insert("lin_lines", &s.lin);
    ctx.insert("deposits", &s.deposits);
    ctx.insert("laser_starts", &s.laser_ons);
}

/// The header's lines on a positioner: its axes under the controller's
/// `names` (tilt, rotate), as its coupled kinematics must have them
/// (docs/robots.md), then how positions follow it (`coupling`).
pub(crate) fn positioner_text(
    p: &crate::ir::Positioner,
    names: [&str; 2],
    coupling: &str,
) -> Vec<String> {
    let v = |a: [f64; 3], d: usize| {
        let t: Vec<String> = a.iter().map(|c| trimmed(*c, d)).collect();
        format!("[{}]", t.join(", "))
    };
    let axis = |name: &str, a: &crate::ir::PositionerAxis| {
        format!(
            "{name} about {} through {} mm, {} .. {} deg, {} deg/s",
            v(a.direction, 6),
            v(a.point, 3),
            trimmed(a.limits[0], 3),
            trimmed(a.limits[1], 3),
            trimmed(a.speed, 3)
        )
    };
    vec![
        axis(names[0], &p.tilt),
        axis(names[1], &p.rotate),
        coupling.to_string(),
    ]
}

/// The header's line on the tool's turn about the beam; empty at the
/// default (`auto`, 0°).
pub(crate) fn spin_text(spin: crate::ir::Spin) -> String {
    let n = crate::numbers::trimmed;
    match spin {
        s if s.is_default() => String::new(),
        crate::ir::Spin::Declared { deg } => {
            format!("tool turned {} deg about the beam (spin, as declared)", n(deg, 3))
        }
        crate::ir::Spin::Auto { deg } => format!(
            "tool turned {} deg about the beam (spin = auto: at 0 deg the arm breaks a rule; docs/robots.md)",
            n(deg, 3)
        ),
    }
}
