//! KUKA KRL back end (KR C4/C5, KSS 8.x): one main program `<stem>.src/.dat`
//! that initialises the robot and calls motion modules `<stem>_m001.src/.dat`, …,
//! each holding at most the robot's `max_points_per_module` LIN lines.
//!
//! The programs' shape comes from the tera templates `krl/main.src.tera`,
//! `krl/main.dat.tera`, `krl/module.src.tera`, `krl/module.dat.tera` and
//! `krl/layer.tera`; the motion lines are written by [`modules`] without tera.
//! Conventions and the template context: `docs/krl.md`.
//!
//! Motion: every point is a `LIN` to the laser focus ([`Point::focus`]) with the
//! tool's beam axis along −normal ([`orient`]), `C_DIS` approximated except where
//! the laser switches. `$VEL.CP` (m/s) is set when the speed changes; the laser
//! output `$OUT` and the power `$ANOUT` switch through `TRIGGER WHEN DISTANCE=0`,
//! at the start of the motion from the point where the IR changes them, so they
//! happen on the path rather than when the advance run reads the line. Paths that
//! do not join the previous one are reached like in G-code: laser off, retract by
//! `clearance` along the nozzle, travel at `max_speed` to `clearance` above the next
//! start, approach.

pub mod modules;
pub mod orient;

use super::context::{counts, layer_context, styles};
use super::fixed::{fixed, trimmed};
use super::{program_stem, EmitError, Sink, Templates};
use crate::check::Verified;
use crate::diag::{Code, Diagnostic, Diagnostics};
use crate::ir::{FrameRef, Path, Point, Robot, ToolAxis};
use modules::{Modules, Switch, ANOUT_DECIMALS};
use orient::{Abc, Orienter};
use std::io::Write;

/// Longest KRL name (module, DEF and DEFDAT names).
pub const MAX_NAME: usize = 24;

/// Rounding distance of `C_DIS`, mm: small against a bead width, large enough
/// that the controller keeps the path speed over millimetre-spaced points.
pub const APPROX_MM: f64 = 0.2;

/// Speed of the move from home to the first point, % of the axes' maximum.
pub const HOME_PERCENT: u32 = 20;

/// KRL keywords a name made of the part and machine could collide with.
const RESERVED: &[&str] = &[
    "C_DIS", "C_ORI", "C_PTP", "C_VEL", "C_SPL", "WAIT_SEC", "SPTP_REL", "SLIN_REL",
];

/// The stem of the robot's file and program names: at most [`MAX_NAME`] minus the
/// module suffix `_m` and `digits` digits, so every module name is a valid KRL
/// name too.
pub fn stem(part: &str, robot: &Robot, digits: usize) -> String {
    let s = program_stem(part, &robot.name, MAX_NAME - 2 - digits);
    if RESERVED.contains(&s.to_ascii_uppercase().as_str()) {
        format!("p{s}")
    } else {
        s
    }
}

/// Digits of the module numbers: enough for an upper bound of the module count
/// (every point one LIN, at most three more per path and one at the end), at
/// least 3.
fn module_digits(p: &Verified, robot: &Robot) -> usize {
    let prog = p.ir();
    let paths: usize = prog.layers.iter().map(|l| l.paths.len()).sum();
    let lines = prog.point_count() + 3 * paths + 1;
    let modules = lines.div_ceil(robot.max_points_per_module.max(1));
    modules.to_string().len().max(3)
}

/// Writes the KRL programs for `robot`, machine number `index` of the IR.
///
/// Fails with [`EmitError::Program`] and `lmd::analog-range` when a laser power
/// would need `$ANOUT` beyond 1.0 (the robot's `full_scale`); nothing is written
/// then.
pub fn emit(
    p: &Verified,
    index: usize,
    robot: &Robot,
    t: &Templates,
    sink: &mut dyn Sink,
) -> Result<(), EmitError> {
    let prog = p.ir();
    analog_range(p, index, robot)?;
    let digits = module_digits(p, robot);
    let stem = stem(&prog.part, robot, digits);
    let base = base_context(p, robot, &stem);

    // Rendered first, so a broken template leaves no file.
    let mut main_ctx = base.clone();
    let probe = Modules::name(&stem, digits, 0);
    main_ctx.insert("modules", &[probe]);
    main_context(&mut main_ctx, p, robot, modules::Stats::default());
    t.render("krl/main.src.tera", &main_ctx)
        .map_err(EmitError::Template)?;

    let mut m = Motion {
        out: Modules::new(
            sink,
            t,
            base.clone(),
            stem.clone(),
            digits,
            robot.max_points_per_module,
            robot.laser_out,
            robot.power_out,
        ),
        orient: Orienter::new(robot.beam),
        robot,
        cursor: None,
        laser: false,
        anout: None,
        power_bits: 0,
    };
    let n_layers = prog.layers.len();
    for (li, layer) in prog.layers.iter().enumerate() {
        let mut ctx = base.clone();
        layer_context(&mut ctx, li, n_layers, layer);
        let text = t
            .render("krl/layer.tera", &ctx)
            .map_err(EmitError::Template)?;
        m.out.layer(li + 1, &text);
        let mut first = true;
        for path in &layer.paths {
            if path.points.is_empty() {
                continue;
            }
            m.path(path, first);
            first = false;
        }
    }
    m.end();
    let (names, stats) = m.out.finish()?;

    let mut ctx = base;
    ctx.insert("modules", &names);
    main_context(&mut ctx, p, robot, stats);
    let src = t
        .render("krl/main.src.tera", &ctx)
        .map_err(EmitError::Template)?;
    let dat = t
        .render("krl/main.dat.tera", &ctx)
        .map_err(EmitError::Template)?;
    let mut out = sink.create(&format!("{stem}.src"))?;
    out.write_all(src.as_bytes())?;
    out.flush()?;
    drop(out);
    let mut out = sink.create(&format!("{stem}.dat"))?;
    out.write_all(dat.as_bytes())?;
    out.flush()?;
    Ok(())
}

/// `$ANOUT` value for `power` W: the fraction of full scale, as written.
pub fn anout(power: f32, robot: &Robot) -> f64 {
    super::fixed::rounded(power as f64 / robot.full_scale_power, ANOUT_DECIMALS)
}

/// `lmd::analog-range`: the highest laser-on power must fit the analog output.
fn analog_range(p: &Verified, index: usize, robot: &Robot) -> Result<(), EmitError> {
    let prog = p.ir();
    let mut worst: Option<(f32, usize, usize)> = None;
    for (li, layer) in prog.layers.iter().enumerate() {
        for path in &layer.paths {
            for (k, pt) in path.points.iter().enumerate() {
                if pt.laser_on && !worst.is_some_and(|w| pt.power <= w.0) {
                    worst = Some((pt.power, li, k));
                }
            }
        }
    }
    let Some((power, li, k)) = worst else {
        return Ok(());
    };
    let x = anout(power, robot);
    if x <= 1.0 {
        return Ok(());
    }
    let mut d = Diagnostics::new();
    d.push(
        Diagnostic::error(
            Code::AnalogRange,
            format!(
                "laser power {} W needs $ANOUT[{}] = {} on robot `{}`, beyond the analog output's 1.0",
                fixed(power as f64, 0),
                robot.power_out,
                fixed(x, 3),
                robot.name
            ),
        )
        .label_opt(
            prog.origins.machines.get(index).copied(),
            format!(
                "full_scale = {} W is the power at $ANOUT = 1.0",
                fixed(robot.full_scale_power, 0)
            ),
        )
        .label_opt(
            prog.origins.power,
            format!("first reached in layer {}, point {}", li + 1, k + 1),
        )
        .help(format!(
            "set `full_scale` to the power the laser source gives at full analog input \
             (at least {} W), or lower the power",
            fixed(power as f64, 0)
        )),
    );
    Err(EmitError::Program(d))
}

/// Where the nozzle is between paths.
#[derive(Clone, Copy, Debug)]
struct Cursor {
    focus: [f64; 3],
    normal: [f32; 3],
    abc: Abc,
}

impl Cursor {
    fn joins(&self, p: &Point) -> bool {
        super::joins(self.focus, self.normal, p)
    }
}

/// The motion of one robot program.
struct Motion<'a> {
    out: Modules<'a>,
    orient: Orienter,
    robot: &'a Robot,
    cursor: Option<Cursor>,
    /// The laser state the last motion left.
    laser: bool,
    /// The last `$ANOUT` value set, in 1/10⁴ of full scale.
    anout: Option<i64>,
    /// The power (f32 bits) it was set for.
    power_bits: u32,
}

fn up(normal: [f32; 3]) -> [f64; 3] {
    let n = [normal[0] as f64, normal[1] as f64, normal[2] as f64];
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    [n[0] / len, n[1] / len, n[2] / len]
}

fn along(p: [f64; 3], dir: [f64; 3], d: f64) -> [f64; 3] {
    [p[0] + d * dir[0], p[1] + d * dir[1], p[2] + d * dir[2]]
}

impl Motion<'_> {
    /// The switch a motion needs to leave the laser `on`.
    fn switch(&mut self, on: bool) -> Option<Switch> {
        if on == self.laser {
            return None;
        }
        self.laser = on;
        Some(if on { Switch::On } else { Switch::Off })
    }

    /// The `$ANOUT` value to set before depositing at `power`, if it changed.
    fn power(&mut self, power: f32) -> Option<f64> {
        // Most points repeat the power of the point before.
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

    /// A laser-off move at `max_speed`.
    fn travel(&mut self, pos: [f64; 3], abc: Abc) {
        let s = self.switch(false);
        self.out.lin(pos, abc, self.robot.max_speed, None, s, false);
    }

    /// One path: a transition to its start unless it joins, then a LIN per point.
    fn path(&mut self, path: &Path, first_in_layer: bool) {
        let pts = &path.points[..];
        let Some(first) = pts.first() else { return };
        let mut cur = match self.cursor {
            Some(c) if !first_in_layer && c.joins(first) => c,
            _ => self.transition(first, pts.len() > 1 && first.laser_on),
        };
        for seg in pts.windows(2) {
            let (from, to) = (&seg[0], &seg[1]);
            if to.normal != cur.normal {
                // Most parts keep one normal over many points: solve only on a change.
                cur.normal = to.normal;
                cur.abc = self.orient.abc(to.normal);
            }
            let f = to.focus();
            if from.laser_on {
                let x = self.power(from.power);
                let s = self.switch(true);
                self.out.lin(f, cur.abc, from.speed as f64, x, s, true);
            } else {
                self.travel(f, cur.abc);
            }
        }
        // A last point with the laser off needs nothing here: whatever motion comes
        // next asks for the laser state it needs and switches it at its start.
        cur.focus = pts[pts.len() - 1].focus();
        self.cursor = Some(cur);
    }

    /// Laser off, retract, travel above `first`, approach (at its speed when
    /// `feed_in`, else at `max_speed`). Returns the cursor at `first`.
    fn transition(&mut self, first: &Point, feed_in: bool) -> Cursor {
        let clearance = self.robot.clearance;
        if let Some(c) = self.cursor {
            self.travel(along(c.focus, up(c.normal), clearance), c.abc);
        }
        let abc = self.orient.abc(first.normal);
        let f0 = first.focus();
        self.travel(along(f0, up(first.normal), clearance), abc);
        let speed = if feed_in {
            first.speed as f64
        } else {
            self.robot.max_speed
        };
        let s = self.switch(false);
        self.out.lin(f0, abc, speed, None, s, false);
        let c = Cursor {
            focus: f0,
            normal: first.normal,
            abc,
        };
        self.cursor = Some(c);
        c
    }

    /// After the last path: laser off and retract.
    fn end(&mut self) {
        if let Some(c) = self.cursor {
            self.travel(along(c.focus, up(c.normal), self.robot.clearance), c.abc);
        }
    }
}

/// Variables every template sees.
fn base_context(p: &Verified, robot: &Robot, stem: &str) -> tera::Context {
    let mut ctx = tera::Context::new();
    ctx.insert("program", stem);
    ctx.insert("part", &comment_safe(&p.ir().part));
    ctx.insert("machine", &comment_safe(&robot.name));
    ctx.insert("generator", concat!("lmdc ", env!("CARGO_PKG_VERSION")));
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

fn beam_text(b: ToolAxis) -> &'static str {
    match b {
        ToolAxis::PlusX => "+X",
        ToolAxis::MinusX => "-X",
        ToolAxis::PlusY => "+Y",
        ToolAxis::MinusY => "-Y",
        ToolAxis::PlusZ => "+Z",
        ToolAxis::MinusZ => "-Z",
    }
}

fn main_context(ctx: &mut tera::Context, p: &Verified, robot: &Robot, s: modules::Stats) {
    counts(ctx, p);
    styles(ctx, p, &comment_safe);
    ctx.insert("tool_index", &robot.tool.index);
    ctx.insert("tool_value", &frame_value(&robot.tool));
    ctx.insert("base_index", &robot.base.index);
    ctx.insert("base_value", &frame_value(&robot.base));
    ctx.insert("beam", beam_text(robot.beam));
    ctx.insert("laser_out", &robot.laser_out);
    ctx.insert("power_out", &robot.power_out);
    ctx.insert("full_scale", &trimmed(robot.full_scale_power, 3));
    ctx.insert("max_speed", &trimmed(robot.max_speed / 1000.0, 6));
    ctx.insert("clearance", &trimmed(robot.clearance, 3));
    ctx.insert("approximation", &trimmed(APPROX_MM, 3));
    ctx.insert("home_percent", &HOME_PERCENT);
    let home: Vec<String> = robot
        .home
        .iter()
        .enumerate()
        .map(|(i, a)| format!("A{} {}", i + 1, trimmed(*a, 3)))
        .collect();
    ctx.insert("home", &home.join(","));
    ctx.insert("module_lines", &robot.max_points_per_module);
    ctx.insert("lin_lines", &s.lin);
    ctx.insert("deposits", &s.deposits);
    ctx.insert("laser_starts", &s.laser_ons);
}
