//! A segmented ring's height loop in KRL: the main program (the usual
//! `krl/main.src.tera`) calls one module that holds the whole build:
//!
//! - its `.dat` declares, per segment `j`, the speed `SPD[j]` (mm/s), the
//!   error sum `ESUM[j]`, the working plane `ZB[j]` and the defocus
//!   `DFC[j]`; the gains, target, clamp and sensor scale; and one layer's
//!   points `XP[k]` (their Z is set at run time);
//! - its `DEF` lays the first layer `layers − 1` times in a `FOR` loop, then
//!   the last layer, segment by segment: `$VEL.CP = SPD[j]*0.001` (times
//!   `SQRT(1+((ZT-ZF)/ARC)^2)` over the transition, `v / cos γ`), `LIN`s at
//!   `Z = ZB[j] + DFC[j]` moving linearly to the next segment's over the
//!   transition; on a segment's last motion
//!   `TRIGGER WHEN DISTANCE=1 DELAY=<height_delay> DO SEG_UPD(j) PRIO=-1`
//!   starts the update as an interrupt when the sensor holds the segment's
//!   mean: no motion stops, and the advance run (at most five motions ahead)
//!   has not reached segment `j` of the next layer;
//! - `SEG_UPD(J)` reads `$ANIN[height_input]`, scales it to mm and runs the
//!   law's steps ([`crate::control::LAW`]) on segment `J`'s variables.

use super::modules::angle_value;
use super::orient::Orienter;
use super::{base_context, main_context, modules, EmitError, Sink, Templates};
use crate::back::height_loop::{constants, prepare, CellStep, LayerMove, LoopPlan, Part, Prepared};
use crate::control::{Step, LAW};
use crate::ir::{HeightLoop, HeightSensor, Ring, Robot};
use crate::numbers::{fixed, trimmed};
use crate::plan::{Move, MoveKind, Speed};
use crate::target::kuka::{ANOUT_DECIMALS, POS_DECIMALS, VEL_DECIMALS};
use crate::verify::VerifiedMachine;
use std::fmt::Write as _;
use std::io::Write;

/// Marker the module template's `body` is rendered as.
const BODY: &str = "\u{1}lmdc-body\u{1}";

/// Writes the programs of a robot that runs the ring's loop.
pub fn emit(
    m: VerifiedMachine<'_>,
    robot: &Robot,
    t: &Templates,
    sink: &mut dyn Sink,
) -> Result<(), EmitError> {
    let Prepared {
        ring,
        law,
        sensor,
        plan,
    } = prepare(m, robot.height_sensor, "KRL")?;
    let names = super::names(m, robot);
    let module = names.module(0);
    let base = base_context(m, robot, &names.stem);
    let mut w = Text {
        out: String::new(),
        robot,
        orient: Orienter::for_robot(robot),
        stats: modules::Stats::default(),
    };
    w.init(&plan, ring);
    w.head(&plan);
    w.layers(&plan, ring, sensor);
    w.tail(&plan);

    let mut ctx = base.clone();
    ctx.insert("name", &module);
    ctx.insert("module", &1);
    ctx.insert("lines", &w.stats.lin);
    ctx.insert("first_layer", &1);
    ctx.insert("last_layer", &plan.layers);
    ctx.insert("continues", &0);
    ctx.insert("body", BODY);
    let src = t
        .render("krl/module.src.tera", &ctx)
        .map_err(EmitError::Template)?;
    let (head, tail) = src.split_once(BODY).ok_or_else(|| {
        EmitError::Template("template krl/module.src.tera: it must contain {{ body }}".into())
    })?;
    let dat = t
        .render("krl/module.dat.tera", &ctx)
        .map_err(EmitError::Template)?;
    let data = data(&plan, ring, law, sensor, &mut w.orient);
    let dat = insert_before_enddat(&dat, &data).ok_or_else(|| {
        EmitError::Template(
            "template krl/module.dat.tera: it must end the DEFDAT with ENDDAT".into(),
        )
    })?;
    let mut main_ctx = base.clone();
    main_ctx.insert("modules", std::slice::from_ref(&module));
    main_context(&mut main_ctx, m, robot, w.stats);
    let main_src = t
        .render("krl/main.src.tera", &main_ctx)
        .map_err(EmitError::Template)?;
    let main_dat = t
        .render("krl/main.dat.tera", &main_ctx)
        .map_err(EmitError::Template)?;

    let update = update_routine(sensor);
    let mut out = sink.create(&format!("{module}.src"))?;
    out.write_all(head.as_bytes())?;
    out.write_all(w.out.as_bytes())?;
    out.write_all(tail.as_bytes())?;
    out.write_all(update.as_bytes())?;
    out.flush()?;
    drop(out);
    for (name, text) in [
        (format!("{module}.dat"), dat),
        (format!("{}.src", names.stem), main_src),
        (format!("{}.dat", names.stem), main_dat),
    ] {
        let mut out = sink.create(&name)?;
        out.write_all(text.as_bytes())?;
        out.flush()?;
    }
    Ok(())
}

/// `data` inserted before the rendered `.dat`'s `ENDDAT` line.
fn insert_before_enddat(dat: &str, data: &str) -> Option<String> {
    let at = dat.rfind("ENDDAT")?;
    let mut out = String::with_capacity(dat.len() + data.len());
    out.push_str(&dat[..at]);
    out.push_str(data);
    out.push_str(&dat[at..]);
    Some(out)
}

/// The module's body being written.
struct Text<'a> {
    out: String,
    robot: &'a Robot,
    orient: Orienter,
    stats: modules::Stats,
}

impl Text<'_> {
    fn line(&mut self, indent: usize, text: &str) {
        for _ in 0..indent {
            self.out.push_str("  ");
        }
        self.out.push_str(text);
        self.out.push('\n');
    }

    /// A whole position aggregate.
    fn pos(&mut self, m: &Move) -> String {
        let abc = self.orient.abc(m.normal);
        format!(
            "{{X {},Y {},Z {},A {},B {},C {}}}",
            fixed(m.to[0], POS_DECIMALS),
            fixed(m.to[1], POS_DECIMALS),
            fixed(m.to[2], POS_DECIMALS),
            fixed(angle_value(abc.a), POS_DECIMALS),
            fixed(abc.b, POS_DECIMALS),
            fixed(angle_value(abc.c), POS_DECIMALS)
        )
    }

    fn vel(&self, m: &Move) -> String {
        let v = match m.speed {
            Speed::Rapid => self.robot.max_speed,
            Speed::Feed(v) => v as f64,
        };
        trimmed(v / 1000.0, VEL_DECIMALS)
    }

    /// The loop's variables at their start values. A `.dat`'s values persist
    /// from one run to the next (KRL writes assignments back into the data
    /// list), so a second run would start from the first run's last speeds
    /// and working planes: the program sets them before it moves.
    fn init(&mut self, plan: &LoopPlan, ring: &Ring) {
        self.line(
            0,
            "; start values: the .dat keeps the last run's, so they are set here",
        );
        for (j, s) in ring.segments.iter().enumerate() {
            // The working plane of the segment's first layer, from the plan.
            let z0 = plan.first_plane(j, s.defocus);
            let k = j + 1;
            self.line(0, &format!("SPD[{k}] = {}", real(trimmed(s.speed, 6))));
            self.line(0, &format!("ESUM[{k}] = 0.0"));
            self.line(0, &format!("ZB[{k}] = {}", real(trimmed(z0, POS_DECIMALS))));
            self.line(
                0,
                &format!("DFC[{k}] = {}", real(trimmed(s.defocus, POS_DECIMALS))),
            );
        }
    }

    /// The moves before the first deposit: exact stops; the laser and the
    /// first segment's power switch at the end of the last one (the approach).
    fn head(&mut self, plan: &LoopPlan) {
        self.line(0, "; to the ring's first point");
        let n = plan.head.len();
        for (i, m) in plan.head.iter().enumerate() {
            if i + 1 == n {
                self.cell(&plan.prepare);
            }
            if m.kind == MoveKind::FromHome {
                self.ptp_from_home(m);
                continue;
            }
            let vel = format!("$VEL.CP = {}", self.vel(m));
            self.line(0, &vel);
            if i + 1 == n {
                if let Some(first) = plan.body.first() {
                    let x = super::anout(first.planned.power, self.robot);
                    let (p, l) = (&self.robot.power_out, &self.robot.laser_out);
                    self.line(
                        0,
                        &format!(
                            "TRIGGER WHEN DISTANCE=1 DELAY=0 DO $ANOUT[{p}]={}",
                            fixed(x, ANOUT_DECIMALS)
                        ),
                    );
                    self.line(
                        0,
                        &format!("TRIGGER WHEN DISTANCE=1 DELAY=0 DO $OUT[{l}]=TRUE"),
                    );
                    self.stats.laser_ons += 1;
                }
            }
            let pos = self.pos(m);
            self.line(0, &format!("LIN {pos}"));
            self.stats.lin += 1;
        }
    }

    /// The PTP from home to above the first point, with the Status and
    /// Turn the verifier checked where the arm is known (the axes it
    /// stands for as a comment), as every robot program starts.
    fn ptp_from_home(&mut self, m: &Move) {
        let pos = self.pos(m);
        let rot = self.orient.rotation(m.normal);
        let line = match super::home_config(self.robot, m, &rot) {
            Some((s, t, j)) => {
                let axes: Vec<String> = j
                    .iter()
                    .enumerate()
                    .map(|(i, a)| format!("A{} {}", i + 1, fixed(*a, POS_DECIMALS)))
                    .collect();
                format!(
                    "PTP {},S {s},T {t}}} ; from home, axes {}",
                    pos.trim_end_matches('}'),
                    axes.join(" ")
                )
            }
            None => format!("PTP {pos} ; from home"),
        };
        self.line(0, &line);
    }

    /// Gas and powder where the robot stands: after an advance-run stop, as
    /// the plan's other programs switch them (docs/krl.md).
    fn cell(&mut self, steps: &[CellStep]) {
        if steps.is_empty() {
            return;
        }
        self.line(0, "WAIT SEC 0 ; advance-run stop: the outputs switch here");
        for step in steps {
            match *step {
                CellStep::Io(e) => {
                    for l in super::io_lines(self.robot, e) {
                        self.line(0, &l);
                    }
                }
                CellStep::Dwell(t) => self.line(0, &format!("WAIT SEC {}", fixed(t, 2))),
            }
        }
    }

    fn layers(&mut self, plan: &LoopPlan, ring: &Ring, sensor: HeightSensor) {
        let delay = (sensor.delay * 1000.0).round() as i64;
        if plan.layers <= 1 {
            self.line(0, "; the only layer");
            self.layer(&plan.body, ring, delay, 0, true);
            return;
        }
        self.line(
            0,
            &format!(
                "; layers 1 .. {}: the same {} motions, each segment at its speed SPD[j] and working plane ZB[j]",
                plan.layers - 1,
                plan.body.len()
            ),
        );
        self.line(0, &format!("FOR L = 1 TO {}", plan.layers - 1));
        self.layer(&plan.body, ring, delay, 1, false);
        self.line(0, "ENDFOR");
        self.line(
            0,
            &format!(
                "; layer {}: the last; its last transition stays level and the build ends there",
                plan.layers
            ),
        );
        self.layer(&plan.last, ring, delay, 0, true);
    }

    /// One layer's motions, grouped per segment into runs of like moves.
    fn layer(&mut self, moves: &[LayerMove], ring: &Ring, delay: i64, ind: usize, last: bool) {
        let mut i = 0;
        while i < moves.len() {
            let m = &moves[i];
            if m.first {
                self.segment(m.segment, ring, ind);
            }
            if matches!(m.part, Part::Transition { step: 1, .. }) {
                // Where the transition leads, read as late as the advance
                // run allows: the next segment's height, which its update
                // (a layer ago, or segment 1's this layer) has set by now
                // (the verifier's loop-timing rule).
                let zt = self.target_height(m.segment, ring, last);
                self.line(ind, &zt);
                self.line(
                    ind,
                    &format!(
                        "$VEL.CP = SPD[{}]*0.001*SQRT(1+((ZT-ZF)/ARC)*((ZT-ZF)/ARC))",
                        m.segment + 1
                    ),
                );
            }
            // A run: like moves that follow, up to a segment's end.
            let mut j = i + 1;
            while j < moves.len()
                && moves[j].segment == m.segment
                && !moves[j].first
                && same_part(moves[j].part, m.part)
                && !matches!(moves[j].part, Part::Transition { step: 1, .. })
                && m.ends.is_none()
                && moves[j].ends.is_none()
            {
                j += 1;
            }
            if m.first || m.ends.is_some() || j == i + 1 {
                self.one(m, ring, delay, ind, last);
                i += 1;
            } else {
                self.run(&moves[i..j], ring, ind);
                i = j;
            }
        }
    }

    /// A segment's heights and speed, set before its first motion.
    fn segment(&mut self, j: usize, ring: &Ring, ind: usize) {
        self.line(
            ind,
            &format!("; {}", crate::back::height_loop::segment_title(ring, j)),
        );
        self.line(ind, &format!("ZF = ZB[{0}]+DFC[{0}]", j + 1));
        self.line(ind, &format!("$VEL.CP = SPD[{}]*0.001", j + 1));
    }

    /// `ZT = …`: where segment `j`'s transition leads — the next segment's
    /// height, the next layer's first for the last segment, level on the
    /// build's last layer.
    fn target_height(&self, j: usize, ring: &Ring, last_layer: bool) -> String {
        let n = ring.segments.len();
        if last_layer && j + 1 == n {
            return "ZT = ZF".into();
        }
        let next = (j + 1) % n + 1;
        format!("ZT = ZB[{next}]+DFC[{next}]")
    }

    fn z(part: Part, ring: &Ring, segment: usize) -> String {
        match part {
            Part::Flat => "ZF".to_string(),
            Part::Transition { step, of } if step == of => "ZT".to_string(),
            Part::Transition { of, .. } => {
                let t0 = segment * (ring.flat_moves + ring.transition_moves) + ring.flat_moves;
                format!("ZF+(ZT-ZF)*(K-{t0})/{of}.0")
            }
        }
    }

    /// One motion written out: the first of a segment (its power switches at
    /// its start), a segment's last (its update is triggered at its end).
    fn one(&mut self, m: &LayerMove, ring: &Ring, delay: i64, ind: usize, last_of_build: bool) {
        self.line(ind, &format!("K = {}", m.point));
        self.line(ind, "P = XP[K]");
        let z = Self::z(m.part, ring, m.segment);
        self.line(ind, &format!("P.Z = {z}"));
        if m.first {
            let x = super::anout(m.planned.power, self.robot);
            self.line(
                ind,
                &format!(
                    "TRIGGER WHEN DISTANCE=0 DELAY=0 DO $ANOUT[{}]={}",
                    self.robot.power_out,
                    fixed(x, ANOUT_DECIMALS)
                ),
            );
        }
        if let Some(e) = m.ends {
            self.line(
                ind,
                &format!(
                    "TRIGGER WHEN DISTANCE=1 DELAY={delay} DO SEG_UPD({}) PRIO=-1",
                    e.segment + 1
                ),
            );
        }
        // The build's last motion ends exactly: the laser goes off there.
        self.line(
            ind,
            if m.ends.is_some_and(|e| e.last) && last_of_build {
                "LIN P"
            } else {
                "LIN P C_DIS"
            },
        );
        self.stats.lin += 1;
        self.stats.deposits += 1;
    }

    /// A run of like motions in a `FOR` loop over their points.
    fn run(&mut self, moves: &[LayerMove], ring: &Ring, ind: usize) {
        let (a, b) = (moves[0].point, moves[moves.len() - 1].point);
        self.line(ind, &format!("FOR K = {a} TO {b}"));
        self.line(ind + 1, "P = XP[K]");
        let z = Self::z(moves[0].part, ring, moves[0].segment);
        self.line(ind + 1, &format!("P.Z = {z}"));
        self.line(ind + 1, "LIN P C_DIS");
        self.line(ind, "ENDFOR");
        self.stats.lin += 1;
        self.stats.deposits += 1;
    }

    /// After the last deposit: the laser off as the retract starts. The
    /// retract is planned from the nominal last point; the real one is as
    /// high as the loop built, so it is written relative to it (`ZT`, the
    /// last segment's height): the nozzle backs off by the clearance
    /// whatever the part's height.
    fn tail(&mut self, plan: &LoopPlan) {
        self.line(0, "; the build is done: back off from where it ended");
        let end = plan.last.last().or(plan.body.last()).map(|m| m.planned.to);
        for (i, m) in plan.tail.iter().enumerate() {
            if i == 0 {
                let l = &self.robot.laser_out;
                self.line(
                    0,
                    &format!("TRIGGER WHEN DISTANCE=0 DELAY=0 DO $OUT[{l}]=FALSE"),
                );
            }
            let vel = format!("$VEL.CP = {}", self.vel(m));
            self.line(0, &vel);
            let pos = self.pos(m);
            match end {
                Some(e) => {
                    self.line(0, &format!("P = {pos}"));
                    let dz = m.to[2] - e[2];
                    let sign = if dz < 0.0 { '-' } else { '+' };
                    let dz = fixed(dz.abs(), POS_DECIMALS);
                    self.line(0, &format!("P.Z = ZT{sign}{dz}"));
                    self.line(0, "LIN P");
                }
                None => self.line(0, &format!("LIN {pos}")),
            }
            self.stats.lin += 1;
        }
        self.cell(&plan.finish);
    }
}

fn same_part(a: Part, b: Part) -> bool {
    matches!(
        (a, b),
        (Part::Flat, Part::Flat) | (Part::Transition { .. }, Part::Transition { .. })
    )
}

/// The module's data: the loop's constants, each segment's variables and
/// one layer's points.
fn data(
    plan: &LoopPlan,
    ring: &Ring,
    law: &HeightLoop,
    sensor: HeightSensor,
    orient: &mut Orienter,
) -> String {
    let n = ring.segments.len();
    let mut s = String::new();
    let r6 = |v: f64| trimmed(v, 6);
    let _ = writeln!(
        s,
        "; the height loop (control::law): after segment j, SEG_UPD(j) sets SPD[j] and ZB[j]"
    );
    let _ = writeln!(s, "DECL INT L=0");
    let _ = writeln!(s, "DECL INT K=0");
    let _ = writeln!(s, "DECL POS P={{X 0.0,Y 0.0,Z 0.0,A 0.0,B 0.0,C 0.0}}");
    let _ = writeln!(s, "DECL REAL ZF=0.0");
    let _ = writeln!(s, "DECL REAL ZT=0.0");
    for (name, v, what) in constants(ring, law, &sensor) {
        let name = name.to_uppercase();
        let _ = writeln!(s, "DECL REAL {name}={} ; {what}", real(r6(v)));
    }
    // Set by the program before it moves (see `Text::init`).
    for (name, what) in [
        ("SPD", "mm/s, each segment's speed"),
        ("ESUM", "mm, each segment's sum of height errors"),
        ("ZB", "mm, each segment's working plane"),
        ("DFC", "mm, each segment's defocus"),
    ] {
        let _ = writeln!(s, "DECL REAL {name}[{n}] ; {what}");
    }
    let _ = writeln!(
        s,
        "DECL POS XP[{}] ; one layer's points (Z is set as the layer is laid)",
        plan.body.len()
    );
    for m in &plan.body {
        let abc = orient.abc(m.planned.normal);
        let _ = writeln!(
            s,
            "XP[{}]={{X {},Y {},Z 0.0,A {},B {},C {}}}",
            m.point,
            fixed(m.planned.to[0], POS_DECIMALS),
            fixed(m.planned.to[1], POS_DECIMALS),
            fixed(angle_value(abc.a), POS_DECIMALS),
            fixed(abc.b, POS_DECIMALS),
            fixed(angle_value(abc.c), POS_DECIMALS)
        );
    }
    s
}

/// A REAL literal: always with a decimal point.
fn real(t: String) -> String {
    if t.contains('.') {
        t
    } else {
        format!("{t}.0")
    }
}

/// `SEG_UPD(J)`: the law's steps on segment `J`'s variables, the measured
/// height read from the sensor's input.
fn update_routine(sensor: HeightSensor) -> String {
    let mut s = String::new();
    let _ = writeln!(s);
    let _ = writeln!(s, "DEF SEG_UPD(J:IN)");
    let _ = writeln!(s, "DECL INT J");
    let _ = writeln!(s, "DECL REAL H,E");
    let _ = writeln!(
        s,
        "; run as an interrupt when segment J's mean height is on $ANIN[{}]: no motion, no advance-run stop",
        sensor.input
    );
    let _ = writeln!(s, "H = $ANIN[{}]*HSCALE", sensor.input);
    for step in LAW {
        match step {
            Step::Error => s.push_str("E = HR-H\n"),
            Step::Sum => s.push_str("ESUM[J] = ESUM[J]+E\n"),
            Step::Speed => s.push_str("SPD[J] = SPD[J]+KP*E+KI*ESUM[J]\n"),
            Step::ClampLow => s.push_str("IF SPD[J] < VMIN THEN\n  SPD[J] = VMIN\nENDIF\n"),
            Step::ClampHigh => s.push_str("IF SPD[J] > VMAX THEN\n  SPD[J] = VMAX\nENDIF\n"),
            Step::Plane => s.push_str("ZB[J] = ZB[J]+H\n"),
        }
    }
    s.push_str("END\n");
    s
}
