//! G-code back end: one program per CNC, `<part>_<machine>.<extension>`.
//!
//! The program's shape (header, per-layer comment block, footer) comes from the
//! tera templates `gcode/header.tera`, `gcode/layer.tera` and `gcode/footer.tera`;
//! the motion lines between them are written by `writer` without tera, since
//! there are millions of them. Conventions, the template context and what each
//! dialect profile needs on the machine: `docs/gcode.md`.
//!
//! Motion: each move of the motion plan ([`crate::plan`]) is one line: X Y Z the
//! laser focus (tool-tip programming), a tilting head's tilt axis and C as the
//! plan solved them; rapid moves are G0, the others G1 at their feed. The laser
//! switches (and S) are written where the plan switches them.

mod dialect;
pub mod height_loop;
mod writer;

use super::context::{counts, layer_context, shown, styles};
use super::{EmitError, Sink, Templates};
use crate::ir::{Cell, Cnc, Kinematics, Layer, Program, RotaryTable, Signal};
use crate::numbers::trimmed;
use crate::plan::kinematics::Rotary;
use crate::plan::{table, Io, Move, MoveKind, Speed, Visit};
use crate::target::gcode::{blending_line, RATE_DECIMALS};
use crate::target::names::gcode_file;
use crate::verify::VerifiedMachine;
use dialect::{comment_safe, delimiters, Words};
use writer::{Stats, Writer};

/// Decimals of a dwell's seconds.
const DWELL_DECIMALS: usize = 2;

/// Writes the G-code program of the verified CNC `m` (`cnc` is its machine).
/// The file may be incomplete when writing fails; sinks discard the files of a
/// failed run.
pub fn emit(
    m: VerifiedMachine<'_>,
    cnc: &Cnc,
    t: &Templates,
    sink: &mut dyn Sink,
) -> Result<(), EmitError> {
    let prog = m.ir();
    if prog.loop_on_machine().is_some() {
        return height_loop::emit(m, cnc, t, sink);
    }
    let kin = cnc.effective_kinematics();
    let five = kin != Kinematics::Xyz;
    let tilt_letter = kin.tilt_letter().map(|c| c as u8);
    let file = gcode_file(&prog.part, cnc);
    let base = base_context(m, cnc, kin, &file);

    // Rendered before the file is created, so a broken template leaves no file.
    let mut ctx = base.clone();
    header_context(&mut ctx, prog, cnc, five);
    let header = t
        .render("gcode/header.tera", &ctx)
        .map_err(EmitError::Template)?;

    let out = sink.create(&file)?;
    let mut g = Motion {
        w: Writer::new(out, Words::new(&cnc.dialect), tilt_letter),
        dwell: &cnc.dialect.dwell,
        cell: &cnc.cell,
        comment: delimiters(cnc.dialect.comment),
        templates: t,
        base: &base,
        layers: prog.layers.len(),
        table: table::machine_output(cnc).map(|t| MachineFrame {
            kin,
            table: t,
            origin: cnc.placement.origin,
            last: None,
        }),
        error: None,
    };
    g.w.raw(header.as_bytes());
    m.plan().walk(&mut g);
    if let Some(e) = g.error {
        return Err(e);
    }

    let mut ctx = base.clone();
    footer_context(&mut ctx, prog, cnc, five, g.w.stats);
    let footer = t
        .render("gcode/footer.tera", &ctx)
        .map_err(EmitError::Template)?;
    g.w.raw(footer.as_bytes());
    g.w.finish()?;
    Ok(())
}

/// Writes a CNC's motion plan: G0 for rapid moves, G1 for the others.
struct Motion<'a, 'w> {
    w: Writer<'w>,
    /// The dialect's dwell line, `{s}` where the seconds go.
    dwell: &'a str,
    /// The gas and powder outputs and the lines that switch them.
    cell: &'a Cell,
    /// The dialect's comment delimiters.
    comment: (&'static str, &'static str),
    templates: &'a Templates,
    base: &'a tera::Context,
    layers: usize,
    /// A table written in machine coordinates: lmdc's inverse kinematics.
    table: Option<MachineFrame>,
    error: Option<EmitError>,
}

/// A tilting table written in machine coordinates ([`TableOutput::Machine`]).
struct MachineFrame {
    kin: Kinematics,
    table: RotaryTable,
    origin: [f64; 3],
    /// The last move's target: part point, machine point (both under the
    /// origin) and angles.
    last: Option<([f64; 3], [f64; 3], Rotary)>,
}

impl MachineFrame {
    /// The machine point of `m`, and the speed its F says (mm/s, or deg/s
    /// for rotary axes alone: [`table::machine_feed`]).
    fn place(&mut self, m: &Move) -> ([f64; 3], f32) {
        let at = table::written(self.kin, &self.table, self.origin, m.to, m.axes);
        let speed = match (m.speed, self.last) {
            (Speed::Feed(v), Some((part, machine, r))) => {
                let turn = (m.axes.tilt - r.tilt, m.axes.c - r.c);
                let d = (table::distance(part, m.to), table::distance(machine, at));
                table::machine_feed(v as f64, d.0, d.1, turn).speed as f32
            }
            (Speed::Feed(v), None) => v,
            (Speed::Rapid, _) => 0.0,
        };
        self.last = Some((m.to, at, m.axes));
        (at, speed)
    }
}

impl Visit for Motion<'_, '_> {
    fn layer(&mut self, index: usize, layer: &Layer) {
        let mut ctx = self.base.clone();
        layer_context(&mut ctx, index, self.layers, layer);
        match self.templates.render("gcode/layer.tera", &ctx) {
            Ok(text) => self.w.raw(text.as_bytes()),
            Err(e) => {
                self.error.get_or_insert(EmitError::Template(e));
                self.w.silence();
            }
        }
    }

    fn laser_on(&mut self, next: &Move) {
        self.w.laser_on(next.power);
    }

    fn laser_off(&mut self) {
        self.w.laser_off();
    }

    fn dwell(&mut self, seconds: f64) {
        self.w
            .raw(format!("{}\n", dwell_line(self.dwell, seconds)).as_bytes());
    }

    fn io(&mut self, event: Io) {
        for line in io_lines(self.cell, self.comment, event) {
            self.w.raw(format!("{line}\n").as_bytes());
        }
    }

    #[inline]
    fn motion(&mut self, m: &Move) {
        let (to, speed) = match self.table.as_mut() {
            Some(t) => t.place(m),
            None => (m.to, if let Speed::Feed(v) = m.speed { v } else { 0.0 }),
        };
        if m.kind == MoveKind::Lift {
            self.w.lift(to[2]);
            return;
        }
        match m.speed {
            Speed::Rapid => self.w.rapid(to, m.axes),
            Speed::Feed(_) => self.w.feed(to, m.axes, speed, m.power),
        }
    }
}

/// The G-code lines of a gas or powder event: the cell's output lines with
/// `{n}` (and `{v}`) filled in, each with a comment between `comment`'s
/// delimiters saying what it switches.
pub fn io_lines(cell: &Cell, comment: (&str, &str), event: Io) -> Vec<String> {
    // (line with `{n}` and `{v}`, output, value, what it switches)
    let mut lines: Vec<(&str, &Signal, Option<f64>, String)> = Vec::new();
    let rate = |g_min: f32| {
        cell.powder.as_ref().and_then(|p| p.rate.as_ref()).map(|r| {
            (
                cell.analog_output.as_str(),
                &r.output,
                Some(g_min as f64 / r.full_scale),
                format!("powder {} g/min", trimmed(g_min as f64, 2)),
            )
        })
    };
    let (on, off) = (cell.output_on.as_str(), cell.output_off.as_str());
    // A CNC's outputs are numbered (sema refuses a signal's name): `{n}`
    // is the number.
    match (event, &cell.gas, &cell.powder) {
        (Io::GasOn, Some(g), _) => lines.push((on, &g.output, None, "gas on".into())),
        (Io::GasOff, Some(g), _) => lines.push((off, &g.output, None, "gas off".into())),
        (Io::PowderOn(r), _, Some(p)) => {
            lines.extend(rate(r));
            lines.push((on, &p.output, None, "powder on".into()));
        }
        (Io::PowderRate(r), _, Some(_)) => lines.extend(rate(r)),
        (Io::PowderOff, _, Some(p)) => lines.push((off, &p.output, None, "powder off".into())),
        _ => {}
    }
    let (open, close) = comment;
    lines
        .into_iter()
        .map(|(template, n, v, what)| {
            let mut text = template.replace("{n}", &n.to_string());
            if let Some(v) = v {
                text = text.replace("{v}", &trimmed(v, RATE_DECIMALS));
            }
            format!("{text} {open}{what}{close}")
        })
        .collect()
}

/// The dialect's dwell line for `seconds`.
pub fn dwell_line(dwell: &str, seconds: f64) -> String {
    let (head, tail) = dwell.split_once("{s}").unwrap_or((dwell, ""));
    format!("{head}{}{tail}", trimmed(seconds, DWELL_DECIMALS))
}

/// Variables every template of the verified CNC `m` sees, the plan's
/// one-line summary among them.
fn base_context(m: VerifiedMachine<'_>, cnc: &Cnc, kin: Kinematics, file: &str) -> tera::Context {
    let p = m.ir();
    let style = cnc.dialect.comment;
    let (open, close) = delimiters(style);
    let kin_name = kin.word();
    let (axes, tilt) = match kin.tilt_letter() {
        None => ("X Y Z", ""),
        Some('B') => ("X Y Z B C", "B"),
        Some(_) => ("X Y Z A C", "A"),
    };
    let mut ctx = tera::Context::new();
    ctx.insert(
        "summary",
        &comment_safe(&super::context::summary(m.summary()), style),
    );
    ctx.insert("comment_open", open);
    ctx.insert("comment_close", close);
    ctx.insert("part", &comment_safe(&shown(&p.part), style));
    ctx.insert("machine", &comment_safe(&shown(&cnc.name), style));
    ctx.insert("profile", &comment_safe(&cnc.dialect.profile, style));
    ctx.insert("file", file);
    ctx.insert("program", file.split('.').next().unwrap_or(file));
    ctx.insert("generator", concat!("lmdc ", env!("CARGO_PKG_VERSION")));
    super::context::provenance(&mut ctx, m.provenance(), &|t| comment_safe(t, style));
    ctx.insert("kinematics", kin_name);
    ctx.insert("axes", axes);
    ctx.insert("tilt_axis", tilt);
    ctx.insert("five_axis", &(kin != Kinematics::Xyz));
    // What the program's X Y Z are: the tool tip in part coordinates, or a
    // table's machine coordinates.
    let frame = match table::machine_output(cnc) {
        Some(_) => "machine",
        None => "part",
    };
    ctx.insert("coordinates", frame);
    ctx
}

fn header_context(ctx: &mut tera::Context, prog: &Program, cnc: &Cnc, five: bool) {
    let style = cnc.dialect.comment;
    counts(ctx, prog);
    styles(ctx, prog, &|t| comment_safe(t, style));
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
    // A declared blending, in the line the control takes it with.
    let blending = match (cnc.blending, blending_line(&cnc.dialect.profile)) {
        (Some(d), Some(line)) => line.replace("{mm}", &trimmed(d, 3)),
        _ => String::new(),
    };
    ctx.insert("blending", &blending);
    let p = cnc.placement;
    let work_offset = match p.work_offset {
        1..=6 => format!("G{}", 53 + p.work_offset),
        _ => String::new(),
    };
    ctx.insert("work_offset", &work_offset);
    ctx.insert("origin", &p.origin.map(|v| crate::numbers::fixed(v, 3)));
    ctx.insert(
        "tcp_on",
        if tcp(cnc, five) {
            cnc.dialect.tcp_on.trim()
        } else {
            ""
        },
    );
}

/// Whether the program switches the control's tool-tip transform on: a
/// 5-axis program unless a table's is written in machine coordinates.
fn tcp(cnc: &Cnc, five: bool) -> bool {
    five && table::machine_output(cnc).is_none()
}

fn footer_context(ctx: &mut tera::Context, p: &Program, cnc: &Cnc, five: bool, s: Stats) {
    counts(ctx, p);
    ctx.insert(
        "tcp_off",
        if tcp(cnc, five) {
            cnc.dialect.tcp_off.trim()
        } else {
            ""
        },
    );
    ctx.insert("postamble", &cnc.dialect.postamble);
    ctx.insert("rapids", &s.rapids);
    ctx.insert("deposits", &s.deposits);
    ctx.insert("approaches", &s.approaches);
    ctx.insert("laser_switches", &s.laser_switches);
    ctx.insert("motion_lines", &(s.rapids + s.deposits + s.approaches));
}
