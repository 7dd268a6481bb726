//! G-code back end: one program per CNC, `<part>_<machine>.<extension>`.
//!
//! The program's shape (header, per-layer comment block, footer) comes from the
//! tera templates `gcode/header.tera`, `gcode/layer.tera` and `gcode/footer.tera`;
//! the motion lines between them are written by `writer` without tera, since
//! there are millions of them. Conventions, the template context and what each
//! dialect profile needs on the machine: `docs/gcode.md`.
//!
//! Motion: X Y Z are the laser focus ([`Point::focus`], tool-tip programming); a
//! tilting head adds its tilt axis and C from the point's normal ([`kinematics`]).
//! G1 with the laser on deposits; everything with the laser off is G0, except the
//! final approach to a path, which is G1 at the path's feed. Paths that do not join
//! the previous one, and every new layer, are reached through a transition: laser
//! off, retract by `clearance` along the nozzle, G0 to `clearance` above the next
//! start, approach.

mod dialect;
pub mod kinematics;
mod limits;
mod writer;

use super::context::{counts, layer_context, styles};
use super::fixed::trimmed;
use super::{program_stem, EmitError, Sink, Templates};
use crate::check::Verified;
use crate::ir::{AxisLimits, Cnc, Kinematics, Path, Point};
use dialect::{comment_safe, delimiters, Words};
use kinematics::Rotary;
use limits::{Checker, Where};
use writer::{Stats, Writer};

pub use limits::NEEDS_TILT_DEG;

/// Longest file name stem: Sinumerik 840D program names have at most 24 characters.
pub const MAX_NAME: usize = 24;

/// The file name of the program for `cnc`: `identifier(part_machine).extension`,
/// the stem at most [`MAX_NAME`] characters (the part's name is shortened first, so
/// two machines keep distinct names).
pub fn file_name(part: &str, cnc: &Cnc) -> String {
    format!(
        "{}.{}",
        program_stem(part, &cnc.name, MAX_NAME),
        cnc.dialect.extension
    )
}

/// The kinematics the program is written for: a machine declared with fewer than
/// five axes has no rotary axes, whatever its kinematics says.
pub fn effective_kinematics(cnc: &Cnc) -> Kinematics {
    if cnc.axes >= 5 {
        cnc.kinematics
    } else {
        Kinematics::Xyz
    }
}

/// Writes the G-code program for `cnc`, machine number `index` of the IR.
///
/// Fails with [`EmitError::Program`] when the plan does not fit the machine:
/// `lmd::needs-tilt` (tilted layers on a machine without rotary axes) and
/// `lmd::axis-limit` (a position beyond an axis' travel, one diagnostic per axis with
/// the worst case), all found in one pass. The file may then be incomplete; sinks
/// discard files of a failed run.
pub fn emit(
    p: &Verified,
    index: usize,
    cnc: &Cnc,
    t: &Templates,
    sink: &mut dyn Sink,
) -> Result<(), EmitError> {
    let prog = p.ir();
    let kin = effective_kinematics(cnc);
    let five = kin != Kinematics::Xyz;
    let tilt_letter = match kin {
        Kinematics::HeadAc => Some(b'A'),
        Kinematics::HeadBc => Some(b'B'),
        Kinematics::Xyz => None,
    };
    let file = file_name(&prog.part, cnc);
    let base = base_context(p, cnc, kin, &file);

    // Rendered before the file is created, so a broken template leaves no file.
    let mut ctx = base.clone();
    header_context(&mut ctx, p, cnc, five);
    let header = t
        .render("gcode/header.tera", &ctx)
        .map_err(EmitError::Template)?;

    let out = sink.create(&file)?;
    let mut m = Motion {
        w: Writer::new(out, Words::new(&cnc.dialect), tilt_letter),
        chk: Checker::new(cnc.limits, five),
        kin,
        five,
        clearance: cnc.clearance,
        lim: cnc.limits,
        cursor: None,
    };
    m.w.raw(header.as_bytes());
    let n_layers = prog.layers.len();
    for (li, layer) in prog.layers.iter().enumerate() {
        let mut ctx = base.clone();
        layer_context(&mut ctx, li, n_layers, layer);
        let text = t
            .render("gcode/layer.tera", &ctx)
            .map_err(EmitError::Template)?;
        m.w.raw(text.as_bytes());
        let mut first = true;
        for (pi, path) in layer.paths.iter().enumerate() {
            if path.points.is_empty() {
                continue;
            }
            m.path(li, pi, path, first);
            first = false;
        }
    }
    m.end();

    let mut ctx = base;
    footer_context(&mut ctx, p, cnc, five, m.w.stats);
    let footer = t
        .render("gcode/footer.tera", &ctx)
        .map_err(EmitError::Template)?;
    m.w.raw(footer.as_bytes());
    let written = m.w.finish();
    if m.chk.failed {
        let tilt_name = if kin == Kinematics::HeadBc { "B" } else { "A" };
        let span = prog.origins.machines.get(index).copied();
        return Err(EmitError::Program(m.chk.into_diagnostics(
            &cnc.name,
            tilt_name,
            cnc.clearance,
            span,
        )));
    }
    written?;
    Ok(())
}

/// Where the nozzle is between paths.
#[derive(Clone, Copy, Debug)]
struct Cursor {
    focus: [f64; 3],
    /// Unit vector up the nozzle (the retract direction).
    up: [f64; 3],
    rot: Rotary,
    normal: [f32; 3],
}

impl Cursor {
    fn joins(&self, p: &Point) -> bool {
        super::joins(self.focus, self.normal, p)
    }
}

/// The motion section of one program.
struct Motion<'w> {
    w: Writer<'w>,
    chk: Checker,
    kin: Kinematics,
    five: bool,
    clearance: f64,
    lim: AxisLimits,
    cursor: Option<Cursor>,
}

fn f64s(n: [f32; 3]) -> [f64; 3] {
    [n[0] as f64, n[1] as f64, n[2] as f64]
}

fn along(p: [f64; 3], dir: [f64; 3], d: f64) -> [f64; 3] {
    [p[0] + d * dir[0], p[1] + d * dir[1], p[2] + d * dir[2]]
}

impl Motion<'_> {
    /// Unit vector up the nozzle for a point with `normal`: the normal on a tilting
    /// head, +Z otherwise.
    fn up(&self, normal: [f32; 3]) -> [f64; 3] {
        if !self.five {
            return [0.0, 0.0, 1.0];
        }
        let n = f64s(normal);
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        [n[0] / len, n[1] / len, n[2] / len]
    }

    /// One path: a transition to its start unless it joins, then a line per point.
    fn path(&mut self, li: usize, pi: usize, path: &Path, first_in_layer: bool) {
        let pts = &path.points[..];
        let Some(first) = pts.first() else { return };
        let joined = match self.cursor {
            Some(c) if !first_in_layer && c.joins(first) => Some(c),
            _ => None,
        };
        let cur = match joined {
            Some(c) => {
                if !self.five {
                    self.chk.vertical(first.normal, || Where::Point {
                        layer: li,
                        path: pi,
                        point: 0,
                    });
                }
                c
            }
            None => self.transition(li, pi, first, pts.len() > 1 && first.laser_on),
        };
        let mut rot = cur.rot;
        let mut normal = cur.normal;
        let (kin, five) = (self.kin, self.five);
        for (k, seg) in pts.windows(2).enumerate() {
            let (from, to) = (&seg[0], &seg[1]);
            let at = || Where::Point {
                layer: li,
                path: pi,
                point: k + 1,
            };
            if !five {
                self.chk.vertical(to.normal, at);
            } else if to.normal != normal {
                // Most parts keep one normal over many points: solve only on a change.
                normal = to.normal;
                rot = kinematics::follow(kin, f64s(normal), rot);
            }
            let f = to.focus();
            self.chk.position(f, rot, at);
            if from.laser_on {
                self.w.laser_on(from.power);
                self.w.feed(f, rot, from.speed, from.power);
            } else {
                self.w.laser_off();
                self.w.rapid(f, rot);
            }
        }
        let last = &pts[pts.len() - 1];
        // The last point's flag says whether the laser stays on into a path that
        // joins; off means off now, not at the next transition.
        if !last.laser_on {
            self.w.laser_off();
        }
        self.cursor = Some(Cursor {
            focus: last.focus(),
            up: self.up(last.normal),
            rot,
            normal: last.normal,
        });
        if self.chk.failed {
            self.w.silence();
        }
    }

    /// Laser off, retract, G0 above `first`, approach (G1 at its feed when
    /// `feed_in`, else G0). Returns the new cursor at `first`.
    fn transition(&mut self, li: usize, pi: usize, first: &Point, feed_in: bool) -> Cursor {
        let clearance = Where::Clearance {
            layer: li,
            path: pi,
        };
        let at_first = || Where::Point {
            layer: li,
            path: pi,
            point: 0,
        };
        self.w.laser_off();
        let prev = self.cursor.map(|c| c.rot).unwrap_or_default();
        if let Some(c) = self.cursor {
            self.retract(c, clearance);
        }
        let rot = if self.five {
            kinematics::reposition(
                self.kin,
                f64s(first.normal),
                prev,
                self.lim.tilt,
                self.lim.rotary,
            )
        } else {
            self.chk.vertical(first.normal, at_first);
            Rotary::default()
        };
        let up = self.up(first.normal);
        let f0 = first.focus();
        let above = along(f0, up, self.clearance);
        self.chk.position(above, rot, || clearance);
        self.w.rapid(above, rot);
        self.chk.position(f0, rot, at_first);
        if feed_in {
            self.w.feed(f0, rot, first.speed, first.power);
        } else {
            self.w.rapid(f0, rot);
        }
        let c = Cursor {
            focus: f0,
            up,
            rot,
            normal: first.normal,
        };
        self.cursor = Some(c);
        c
    }

    fn retract(&mut self, c: Cursor, at: Where) {
        let r = along(c.focus, c.up, self.clearance);
        self.chk.position(r, c.rot, || at);
        self.w.rapid(r, c.rot);
    }

    /// After the last path: laser off and retract.
    fn end(&mut self) {
        self.w.laser_off();
        if let Some(c) = self.cursor {
            self.retract(c, Where::End);
        }
    }
}

/// Variables every template sees.
fn base_context(p: &Verified, cnc: &Cnc, kin: Kinematics, file: &str) -> tera::Context {
    let style = cnc.dialect.comment;
    let (open, close) = delimiters(style);
    let (kin_name, axes, tilt) = match kin {
        Kinematics::Xyz => ("xyz", "X Y Z", ""),
        Kinematics::HeadAc => ("head_ac", "X Y Z A C", "A"),
        Kinematics::HeadBc => ("head_bc", "X Y Z B C", "B"),
    };
    let mut ctx = tera::Context::new();
    ctx.insert("comment_open", open);
    ctx.insert("comment_close", close);
    ctx.insert("part", &comment_safe(&p.ir().part, style));
    ctx.insert("machine", &comment_safe(&cnc.name, style));
    ctx.insert("profile", &comment_safe(&cnc.dialect.profile, style));
    ctx.insert("file", file);
    ctx.insert("program", file.split('.').next().unwrap_or(file));
    ctx.insert("generator", concat!("lmdc ", env!("CARGO_PKG_VERSION")));
    ctx.insert("kinematics", kin_name);
    ctx.insert("axes", axes);
    ctx.insert("tilt_axis", tilt);
    ctx.insert("five_axis", &(kin != Kinematics::Xyz));
    ctx
}

fn header_context(ctx: &mut tera::Context, p: &Verified, cnc: &Cnc, five: bool) {
    let prog = p.ir();
    let style = cnc.dialect.comment;
    counts(ctx, p);
    styles(ctx, p, &|t| comment_safe(t, style));
    let u = &prog.units;
    let mut units = std::collections::BTreeMap::new();
    for (k, v) in [
        ("length", &u.length),
        ("angle", &u.angle),
        ("speed", &u.speed),
        ("power", &u.power),
        ("powder", &u.powder),
    ] {
        units.insert(k, comment_safe(v, style));
    }
    ctx.insert("units", &units);
    ctx.insert("feed_unit", cnc.dialect.feed.text());
    ctx.insert("s_per_watt", &trimmed(cnc.dialect.s_per_watt, 6));
    ctx.insert("s_decimals", &cnc.dialect.s_decimals);
    ctx.insert("clearance", &trimmed(cnc.clearance, 3));
    ctx.insert("preamble", &cnc.dialect.preamble);
    ctx.insert("tcp_on", if five { cnc.dialect.tcp_on.trim() } else { "" });
}

fn footer_context(ctx: &mut tera::Context, p: &Verified, cnc: &Cnc, five: bool, s: Stats) {
    counts(ctx, p);
    ctx.insert(
        "tcp_off",
        if five { cnc.dialect.tcp_off.trim() } else { "" },
    );
    ctx.insert("postamble", &cnc.dialect.postamble);
    ctx.insert("rapids", &s.rapids);
    ctx.insert("deposits", &s.deposits);
    ctx.insert("approaches", &s.approaches);
    ctx.insert("laser_switches", &s.laser_switches);
    ctx.insert("motion_lines", &(s.rapids + s.deposits + s.approaches));
}
