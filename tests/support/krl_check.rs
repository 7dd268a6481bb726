//! A strict reader of the KRL subset lmdc writes: it checks each file's
//! structure (header, `DEF name( )` … `END` with the file's name, `DEFDAT` …
//! `ENDDAT`), every statement against the forms lmdc may emit, identifiers (≤ 24
//! characters) and numbers (plain decimals: no exponent, NaN or inf), then
//! *executes* the main program — following module calls — into a trace of
//! motions with the speed, laser and power state each one runs with. It refuses
//! redundant writes (a `$VEL.CP` equal to the current one in the same module, a
//! `TRIGGER` that sets the laser to the state it already has) and triggers not
//! followed by a motion.
//!
//! Written independently of the emitter: it reads text, not lmdc's types.
#![allow(dead_code)]

use std::collections::BTreeMap;

/// One `LIN` as the robot runs it.
#[derive(Clone, Debug, PartialEq)]
pub struct Lin {
    /// X Y Z, mm.
    pub pos: [f64; 3],
    /// A B C, deg.
    pub abc: [f64; 3],
    /// `$VEL.CP` in force, converted to mm/s.
    pub speed: f64,
    /// `$OUT[laser]` during the motion.
    pub laser: bool,
    /// `$ANOUT[power]` during the motion.
    pub anout: f64,
    /// Ends with `C_DIS`.
    pub approximated: bool,
    /// The laser switches at its end point, by a `TRIGGER WHEN PATH=0`.
    pub switch_at_end: bool,
    /// Module it is in.
    pub module: String,
    /// A `PTP` to a Cartesian pose (the move from home): joint-interpolated,
    /// at the PTP speed the main program set, not `$VEL.CP`.
    pub ptp: bool,
    /// Its Status and Turn, where it has them.
    pub config: Option<(u8, u8)>,
    /// A positioner's E1 and E2, where the motion has them (E6POS).
    pub ext: Option<[f64; 2]>,
}

/// What running the main program did.
#[derive(Debug, Default)]
pub struct Trace {
    /// The LIN motions in execution order.
    pub lins: Vec<Lin>,
    /// `PTP` motions.
    pub ptps: usize,
    /// The main program's PTPs to axis angles (home), in order: A1..A6,
    /// then E1 and E2 where a positioner is moved too (E6AXIS).
    pub homes: Vec<Vec<f64>>,
    /// Modules called, in order.
    pub calls: Vec<String>,
    /// LIN lines per module.
    pub lines_per_module: BTreeMap<String, usize>,
    /// Final `$OUT[laser]`.
    pub laser_at_end: bool,
    /// `WAIT SEC` in the motion modules: (LINs run before it, seconds).
    pub waits: Vec<(usize, f64)>,
    /// Everything the motion modules do, in order: the timeline of motions,
    /// waits and the cell's outputs.
    pub events: Vec<Event>,
    /// What the main program sets `$LOAD` to, before its first motion.
    pub load: Option<LoadSet>,
}

/// A `$LOAD` the main program sets.
#[derive(Clone, Debug, PartialEq)]
pub enum LoadSet {
    /// `LOAD_DATA[n]`: the controller's load data of tool `n`.
    Table(u16),
    /// `{M …,CM {X …,Y …,Z …,A …,B …,C …},J {X …,Y …,Z …}}`: the mass (kg),
    /// the centre of gravity and principal axes (mm, deg), the principal
    /// moments of inertia (kg·m²).
    Value {
        mass: f64,
        cm: [f64; 6],
        j: [f64; 3],
    },
}

/// `$LOAD`'s right-hand side: a table entry, or a LOAD aggregate with a
/// mass above zero and moments of inertia of zero or more.
fn load(rhs: &str) -> Result<LoadSet, String> {
    if let Some(n) = rhs
        .strip_prefix("LOAD_DATA[")
        .and_then(|r| r.strip_suffix(']'))
    {
        return n
            .parse()
            .map(LoadSet::Table)
            .map_err(|e| format!("LOAD_DATA[{n}]: {e}"));
    }
    let bad = || format!("`{rhs}` is not a LOAD aggregate {{M …,CM {{…}},J {{…}}}}");
    let inner = rhs
        .strip_prefix("{M ")
        .and_then(|r| r.strip_suffix('}'))
        .ok_or_else(bad)?;
    let (m, rest) = inner.split_once(",CM ").ok_or_else(bad)?;
    let (cm, j) = rest.split_once(",J ").ok_or_else(bad)?;
    let mass = number(m)?;
    let cm = aggregate(cm, &["X", "Y", "Z", "A", "B", "C"])?;
    let j = aggregate(j, &["X", "Y", "Z"])?;
    if mass <= 0.0 || j.iter().any(|j| *j < 0.0) {
        return Err(format!("`{rhs}`: a mass ≤ 0 or a moment of inertia < 0"));
    }
    Ok(LoadSet::Value {
        mass,
        cm: [cm[0], cm[1], cm[2], cm[3], cm[4], cm[5]],
        j: [j[0], j[1], j[2]],
    })
}

/// One step of a motion module.
#[derive(Clone, Debug, PartialEq)]
pub enum Event {
    /// `trace.lins[i]` runs.
    Lin(usize),
    /// `WAIT SEC t` (0: an advance-run stop).
    Wait(f64),
    /// `$OUT[n]=…` other than the laser's, written where the robot stands.
    Out(u16, bool),
    /// `$ANOUT[n]=x` other than the power's, written where the robot stands.
    Anout(u16, f64),
}

/// The KRL files of one robot program: name → text.
pub type Files = BTreeMap<String, String>;

/// Reads and runs `<main>.src`, with `laser`/`power` the `$OUT`/`$ANOUT`
/// indices the program must use.
pub fn run(files: &Files, main: &str, laser: u16, power: u16) -> Result<Trace, String> {
    for (name, text) in files {
        if let Some(stem) = name.strip_suffix(".dat") {
            check_dat(stem, text).map_err(|e| format!("{name}: {e}"))?;
        } else if !name.ends_with(".src") {
            return Err(format!("unexpected file {name}"));
        }
    }
    let mut st = State {
        files,
        laser_no: laser,
        power_no: power,
        trace: Trace::default(),
        vel: None,
        laser: false,
        anout: 0.0,
        depth: 0,
    };
    st.module(main, true)?;
    st.trace.laser_at_end = st.laser;
    Ok(st.trace)
}

struct State<'a> {
    files: &'a Files,
    laser_no: u16,
    power_no: u16,
    trace: Trace,
    /// m/s
    vel: Option<f64>,
    laser: bool,
    anout: f64,
    depth: usize,
}

fn check_name(name: &str) -> Result<(), String> {
    let ok = name.len() <= 24
        && name.starts_with(|c: char| c.is_ascii_alphabetic())
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if ok {
        Ok(())
    } else {
        Err(format!(
            "`{name}` is not a KRL name (letter, then [A-Za-z0-9_], ≤ 24)"
        ))
    }
}

fn header<'t>(lines: &mut impl Iterator<Item = (usize, &'t str)>) -> Result<(), String> {
    for want in ["&ACCESS RVP", "&REL 1"] {
        match lines.next() {
            Some((_, l)) if l == want => {}
            other => return Err(format!("want `{want}`, got {other:?}")),
        }
    }
    Ok(())
}

fn check_dat(stem: &str, text: &str) -> Result<(), String> {
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l));
    header(&mut lines)?;
    match lines.next() {
        Some((_, l)) if l == format!("DEFDAT {stem}") => {}
        other => return Err(format!("want `DEFDAT {stem}`, got {other:?}")),
    }
    check_name(stem)?;
    let rest: Vec<_> = lines.collect();
    match rest.last() {
        Some((_, "ENDDAT")) => {}
        other => return Err(format!("must end with ENDDAT, ends with {other:?}")),
    }
    for (n, l) in &rest[..rest.len() - 1] {
        if !l.trim_start().starts_with(';') && !l.trim().is_empty() {
            return Err(format!("line {n}: unexpected data `{l}`"));
        }
    }
    Ok(())
}

/// A plain decimal: optional `-`, digits, optional `.digits`.
pub fn number(s: &str) -> Result<f64, String> {
    let t = s.strip_prefix('-').unwrap_or(s);
    let (int, frac) = t.split_once('.').unwrap_or((t, "0"));
    let digits = |p: &str| !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit());
    if !digits(int) || !digits(frac) {
        return Err(format!("`{s}` is not a plain decimal number"));
    }
    s.parse::<f64>().map_err(|e| format!("`{s}`: {e}"))
}

/// A pose `{X …,Y …,Z …,A …,B …,C …}` followed by `more` keys, with or
/// without a positioner's `E1 …,E2 …` after `C`: the values without E1 and
/// E2, and E1 and E2.
fn with_ext(s: &str, more: &[&str]) -> Result<(Vec<f64>, Option<[f64; 2]>), String> {
    let pose = ["X", "Y", "Z", "A", "B", "C"];
    let mut keys: Vec<&str> = pose.to_vec();
    keys.extend(["E1", "E2"]);
    keys.extend(more);
    if let Ok(mut v) = aggregate(s, &keys) {
        let e = [v[6], v[7]];
        v.drain(6..8);
        return Ok((v, Some(e)));
    }
    let mut keys = pose.to_vec();
    keys.extend(more);
    aggregate(s, &keys).map(|v| (v, None))
}

/// `{K1 v1,K2 v2,…}` with exactly the keys `keys`.
fn aggregate(s: &str, keys: &[&str]) -> Result<Vec<f64>, String> {
    let inner = s
        .strip_prefix('{')
        .and_then(|s| s.strip_suffix('}'))
        .ok_or_else(|| format!("`{s}` is not an aggregate"))?;
    let parts: Vec<&str> = inner.split(',').collect();
    if parts.len() != keys.len() {
        return Err(format!("`{s}`: want components {keys:?}"));
    }
    parts
        .iter()
        .zip(keys)
        .map(|(p, k)| {
            let v = p
                .strip_prefix(k)
                .and_then(|v| v.strip_prefix(' '))
                .ok_or_else(|| format!("`{s}`: want `{k} <number>`, got `{p}`"))?;
            number(v)
        })
        .collect()
}

fn strip_comment(l: &str) -> &str {
    l.split(';').next().unwrap_or("").trim()
}

#[derive(Clone, Copy)]
enum Trig {
    Laser(bool),
    Power(f64),
    /// `TRIGGER WHEN PATH=0`: at the end point of its motion, the robot
    /// going on (a lead's switch on the fly).
    LaserAtEnd(bool),
    PowerAtEnd(f64),
}

impl State<'_> {
    fn module(&mut self, name: &str, main: bool) -> Result<(), String> {
        check_name(name)?;
        self.depth += 1;
        if self.depth > 4 {
            return Err(format!("{name}: calls nest too deep"));
        }
        let file = format!("{name}.src");
        let text = self
            .files
            .get(&file)
            .ok_or_else(|| format!("{name} is called but {file} was not written"))?;
        let at = |n: usize, e: String| format!("{file}:{n}: {e}");
        let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l));
        header(&mut lines).map_err(|e| at(1, e))?;
        match lines.next() {
            Some((_, l)) if l == format!("DEF {name}( )") => {}
            other => return Err(at(3, format!("want `DEF {name}( )`, got {other:?}"))),
        }
        if !main {
            // A module starts with no speed of its own: the first motion sets one.
            self.vel = None;
        }
        let mut triggers: Vec<Trig> = Vec::new();
        let mut ended = false;
        for (n, raw) in lines {
            if ended {
                if raw.trim().is_empty() {
                    continue;
                }
                return Err(at(n, "text after END".into()));
            }
            let l = strip_comment(raw);
            if l.is_empty() {
                continue;
            }
            let r = self.statement(name, main, l, &mut triggers);
            match r {
                Ok(true) => ended = true,
                Ok(false) => {}
                Err(e) => return Err(at(n, format!("{e} in `{raw}`"))),
            }
        }
        if !ended {
            return Err(format!("{file}: no END"));
        }
        if !triggers.is_empty() {
            return Err(format!("{file}: TRIGGER without a following motion"));
        }
        self.depth -= 1;
        Ok(())
    }

    /// Runs one statement; `Ok(true)` at END.
    fn statement(
        &mut self,
        module: &str,
        main: bool,
        l: &str,
        triggers: &mut Vec<Trig>,
    ) -> Result<bool, String> {
        let out = format!("$OUT[{}]", self.laser_no);
        let anout = format!("$ANOUT[{}]", self.power_no);
        if l == "END" {
            return Ok(true);
        }
        if let Some(v) = l.strip_prefix("$VEL.CP = ") {
            let v = number(v)?;
            if !(v > 0.0 && v <= 3.0) {
                return Err(format!("$VEL.CP {v} m/s outside (0, 3]"));
            }
            if self.vel == Some(v) {
                return Err("$VEL.CP repeats the speed in force".into());
            }
            self.vel = Some(v);
            return Ok(false);
        }
        let start = l.strip_prefix("TRIGGER WHEN DISTANCE=0 DELAY=0 DO ");
        let end = l.strip_prefix("TRIGGER WHEN PATH=0 DELAY=0 DO ");
        if let Some(t) = start.or(end) {
            let (lhs, rhs) = t.split_once('=').ok_or("TRIGGER without assignment")?;
            if lhs == out {
                let on = match rhs {
                    "TRUE" => true,
                    "FALSE" => false,
                    _ => return Err(format!("{out} needs TRUE/FALSE")),
                };
                triggers.push(if end.is_some() {
                    Trig::LaserAtEnd(on)
                } else {
                    Trig::Laser(on)
                });
            } else if lhs == anout {
                let x = number(rhs)?;
                if !(0.0..=1.0).contains(&x) {
                    return Err(format!("{anout} = {x} outside 0..1"));
                }
                triggers.push(if end.is_some() {
                    Trig::PowerAtEnd(x)
                } else {
                    Trig::Power(x)
                });
            } else {
                return Err(format!("TRIGGER sets `{lhs}`, neither {out} nor {anout}"));
            }
            return Ok(false);
        }
        if let Some(rest) = l.strip_prefix("PTP {X ") {
            // A Cartesian PTP (from home), with or without Status and Turn.
            let agg = format!("{{X {rest}");
            let (v, ext) = with_ext(&agg, &["S", "T"]).or_else(|_| with_ext(&agg, &[]))?;
            let config = (v.len() == 8).then(|| (v[6] as u8, v[7] as u8));
            if self.laser || !triggers.is_empty() {
                return Err("PTP with the laser on or a trigger".into());
            }
            self.trace.ptps += 1;
            self.trace.events.push(Event::Lin(self.trace.lins.len()));
            self.trace.lins.push(Lin {
                pos: [v[0], v[1], v[2]],
                abc: [v[3], v[4], v[5]],
                speed: self.vel.map_or(0.0, |v| v * 1000.0),
                laser: self.laser,
                anout: self.anout,
                approximated: false,
                switch_at_end: false,
                module: module.to_string(),
                ptp: true,
                config,
                ext,
            });
            return Ok(false);
        }
        if let Some(rest) = l.strip_prefix("LIN ") {
            let (agg, approx) = match rest.strip_suffix(" C_DIS") {
                Some(a) => (a, true),
                None => (rest, false),
            };
            let (v, ext) = with_ext(agg, &[])?;
            for (k, a) in v[3..6].iter().enumerate() {
                let lim = if k == 1 { 90.0 } else { 180.0 };
                if a.abs() > lim || (k != 1 && *a == -180.0) {
                    return Err(format!("orientation angle {a} outside its range"));
                }
            }
            let vel = self.vel.ok_or("LIN before any $VEL.CP in this module")?;
            let mut at_end = Vec::new();
            for t in triggers.drain(..) {
                match t {
                    Trig::Laser(on) => {
                        if on == self.laser {
                            return Err("TRIGGER switches the laser to the state it has".into());
                        }
                        self.laser = on;
                    }
                    Trig::Power(x) => self.anout = x,
                    t => at_end.push(t),
                }
            }
            self.trace.events.push(Event::Lin(self.trace.lins.len()));
            *self
                .trace
                .lines_per_module
                .entry(module.to_string())
                .or_default() += 1;
            self.trace.lins.push(Lin {
                pos: [v[0], v[1], v[2]],
                abc: [v[3], v[4], v[5]],
                speed: vel * 1000.0,
                laser: self.laser,
                anout: self.anout,
                approximated: approx,
                switch_at_end: at_end.iter().any(|t| matches!(t, Trig::LaserAtEnd(_))),
                module: module.to_string(),
                ptp: false,
                config: None,
                ext,
            });
            for t in at_end {
                match t {
                    Trig::LaserAtEnd(on) => {
                        if on == self.laser {
                            return Err("TRIGGER switches the laser to the state it has".into());
                        }
                        self.laser = on;
                    }
                    Trig::PowerAtEnd(x) => self.anout = x,
                    _ => {}
                }
            }
            return Ok(false);
        }
        if !triggers.is_empty() {
            return Err("a TRIGGER must be followed by its motion".into());
        }
        if let (false, Some(t)) = (main, l.strip_prefix("WAIT SEC ")) {
            let t = number(t)?;
            if t.is_nan() || t < 0.0 {
                return Err(format!("WAIT SEC {t}"));
            }
            if self.laser {
                return Err("WAIT SEC with the laser on".into());
            }
            if self.trace.lins.last().is_some_and(|l| l.approximated) {
                return Err("WAIT SEC after an approximated LIN".into());
            }
            if t > 0.0 {
                self.trace.waits.push((self.trace.lins.len(), t));
            }
            self.trace.events.push(Event::Wait(t));
            return Ok(false);
        }
        // The cell's outputs: only where the robot stands (after an
        // advance-run stop, so the advance run cannot switch them motions
        // early) and with the laser off.
        let io = |l: &str, prefix: &str| -> Option<(u16, String)> {
            let rest = l.strip_prefix(prefix)?;
            let (n, v) = rest.split_once("]=")?;
            Some((n.parse().ok()?, v.to_string()))
        };
        let cell = io(l, "$OUT[")
            .map(|(n, v)| (n, v, false))
            .or_else(|| io(l, "$ANOUT[").map(|(n, v)| (n, v, true)));
        if let (false, Some((n, v, analog))) = (main, cell) {
            if (!analog && n == self.laser_no) || (analog && n == self.power_no) {
                return Err("the laser and its power switch only through TRIGGER".into());
            }
            if self.laser {
                return Err("an output switched with the laser on".into());
            }
            let stopped = matches!(
                self.trace.events.last(),
                Some(Event::Wait(_) | Event::Out(..) | Event::Anout(..))
            );
            if !stopped {
                return Err("an output switched without an advance-run stop before it".into());
            }
            self.trace.events.push(if analog {
                let x = number(&v)?;
                if !(0.0..=1.0).contains(&x) {
                    return Err(format!("$ANOUT[{n}] = {x} outside 0..1"));
                }
                Event::Anout(n, x)
            } else {
                Event::Out(
                    n,
                    match v.as_str() {
                        "TRUE" => true,
                        "FALSE" => false,
                        _ => return Err("TRUE/FALSE".into()),
                    },
                )
            });
            return Ok(false);
        }
        if !main {
            return Err("statement not allowed in a motion module".into());
        }
        // The main program's statements.
        if let Some(rhs) = l.strip_prefix("$LOAD = ") {
            if self.trace.load.is_some() || self.trace.ptps > 0 {
                return Err("$LOAD set twice, or after the robot moved".into());
            }
            self.trace.load = Some(load(rhs)?);
            return Ok(false);
        }
        if let Some(p) = l.strip_prefix("PTP ") {
            if self.trace.load.is_none() {
                return Err("the robot moves before the program sets $LOAD".into());
            }
            let axes = ["A1", "A2", "A3", "A4", "A5", "A6", "E1", "E2"];
            let v = aggregate(p, &axes).or_else(|_| aggregate(p, &axes[..6]))?;
            self.trace.homes.push(v.clone());
            if v.iter().any(|a| a.abs() > 360.0) {
                return Err("axis angle beyond ±360".into());
            }
            if self.laser {
                return Err("PTP with the laser on".into());
            }
            self.trace.ptps += 1;
            return Ok(false);
        }
        if let Some(callee) = l.strip_suffix("( )") {
            self.trace.calls.push(callee.to_string());
            return self.module(callee, false).map(|_| false);
        }
        if let Some(rhs) = l.strip_prefix(&format!("{out} = ")) {
            self.laser = match rhs {
                "TRUE" => return Err("the main program never switches the laser on".into()),
                "FALSE" => false,
                _ => return Err("TRUE/FALSE".into()),
            };
            return Ok(false);
        }
        if let Some(rhs) = l.strip_prefix(&format!("{anout} = ")) {
            self.anout = number(rhs)?;
            return Ok(false);
        }
        // A base coupled to a positioner: the base on its flange.
        if let Some(rhs) = l
            .strip_prefix("$BASE = EK(MACHINE_DEF[2].ROOT, MACHINE_DEF[2].MECH_TYPE, ")
            .and_then(|r| r.strip_suffix(')'))
        {
            aggregate(rhs, &["X", "Y", "Z", "A", "B", "C"])?;
            return Ok(false);
        }
        if let Some(rhs) = l
            .strip_prefix("$TOOL = ")
            .or_else(|| l.strip_prefix("$BASE = "))
        {
            let is_table = ["TOOL_DATA[", "BASE_DATA["]
                .iter()
                .any(|t| rhs.starts_with(t) && rhs.ends_with(']'));
            if !is_table {
                aggregate(rhs, &["X", "Y", "Z", "A", "B", "C"])?;
            }
            return Ok(false);
        }
        if let Some(v) = l.strip_prefix("$APO.CDIS = ") {
            let v = number(v)?;
            return if v > 0.0 {
                Ok(false)
            } else {
                Err("CDIS ≤ 0".into())
            };
        }
        if let Some(v) = l.strip_prefix("$ADVANCE = ") {
            let v = number(v)?;
            return if (1.0..=5.0).contains(&v) {
                Ok(false)
            } else {
                Err("$ADVANCE outside 1..5".into())
            };
        }
        let fixed = [
            "BAS(#INITMOV,0)",
            "$IPO_MODE = #BASE",
            "$ORI_TYPE = #VAR",
            "WAIT SEC 0",
            "$ACT_EX_AX = 2",
        ];
        if fixed.contains(&l) {
            return Ok(false);
        }
        if let Some(p) = l
            .strip_prefix("BAS(#PTP_PARAMS,")
            .and_then(|p| p.strip_suffix(')'))
        {
            let v = number(p)?;
            return if v > 0.0 && v <= 100.0 {
                Ok(false)
            } else {
                Err("PTP speed outside 0..100 %".into())
            };
        }
        Err("not a statement lmdc writes".into())
    }
}

/// The rotation matrix of KUKA `A B C` (deg), R = Rz(A)·Ry(B)·Rx(C), written out
/// by hand.
pub fn matrix(abc: [f64; 3]) -> [[f64; 3]; 3] {
    let (a, b, c) = (
        abc[0].to_radians(),
        abc[1].to_radians(),
        abc[2].to_radians(),
    );
    let (sa, ca) = a.sin_cos();
    let (sb, cb) = b.sin_cos();
    let (sc, cc) = c.sin_cos();
    [
        [ca * cb, ca * sb * sc - sa * cc, ca * sb * cc + sa * sc],
        [sa * cb, sa * sb * sc + ca * cc, sa * sb * cc - ca * sc],
        [-sb, cb * sc, cb * cc],
    ]
}

/// Column `k` of `m` (a tool axis in base coordinates).
pub fn column(m: &[[f64; 3]; 3], k: usize) -> [f64; 3] {
    [m[0][k], m[1][k], m[2][k]]
}
