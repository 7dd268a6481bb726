//! Running the program: the advance run ahead of the main run, triggers
//! fired when their motion runs, `$ANIN` asked of the test's sensor.

use super::syntax::{data, routines, Action, Expr, Place, Routine, Stmt};
use super::value::{binary, Ty, Value};
use super::{Config, Files, Motion, Read, Run};
use std::collections::{BTreeMap, HashMap, VecDeque};

pub struct Planned {
    pos: [f64; 3],
    abc: [f64; 3],
    speed: f64,
    approximated: bool,
    module: String,
    triggers: Vec<(i64, f64, Action, Frame)>,
}

/// The variables an action sees: the routine's locals and its module's data.
#[derive(Clone)]
pub struct Frame {
    module: String,
    locals: HashMap<String, Value>,
    routine: String,
    args: Vec<f64>,
}

pub struct Vm<'a> {
    routines: HashMap<String, Routine>,
    dats: HashMap<String, HashMap<String, Value>>,
    system: HashMap<String, Value>,
    laser_no: i64,
    power_no: i64,
    cfg: Config,
    sensor: &'a mut dyn FnMut(&Read) -> Result<f64, String>,
    queue: VecDeque<Planned>,
    /// Triggers waiting for their delay: motions left, action, frame.
    delayed: Vec<(usize, Action, Frame)>,
    pending: Vec<(i64, f64, Action, Frame)>,
    laser: bool,
    anout: f64,
    run: Run,
    /// Whether the code running is a trigger's (the main run).
    in_trigger: bool,
    depth: usize,
}

/// Runs `main` (a `.src` with its `DEF`), following calls into the other
/// files. `laser`/`power` are the `$OUT`/`$ANOUT` the program switches.
pub fn run(
    files: &Files,
    main: &str,
    laser: u16,
    power: u16,
    cfg: Config,
    sensor: &mut dyn FnMut(&Read) -> Result<f64, String>,
) -> Result<Run, String> {
    let mut vm = Vm {
        routines: HashMap::new(),
        dats: HashMap::new(),
        system: HashMap::new(),
        laser_no: laser as i64,
        power_no: power as i64,
        cfg,
        sensor,
        queue: VecDeque::new(),
        delayed: Vec::new(),
        pending: Vec::new(),
        laser: false,
        anout: 0.0,
        run: Run::default(),
        in_trigger: false,
        depth: 0,
    };
    for (name, text) in files {
        let stem = name[..name.len() - 4].to_ascii_uppercase();
        if name.ends_with(".dat") {
            vm.dats.insert(stem, data(name, text)?);
        } else if name.ends_with(".src") {
            let lins = text
                .lines()
                .filter(|l| l.trim_start().starts_with("LIN "))
                .count();
            vm.run.lin_lines.insert(stem.clone(), lins);
            for (r, body) in routines(name, text)? {
                if vm.routines.insert(r.clone(), body).is_some() {
                    return Err(format!("{r} is defined twice"));
                }
            }
        } else {
            return Err(format!("unexpected file {name}"));
        }
    }
    vm.system.insert("$VEL.CP".into(), Value::Unset(Ty::Real));
    vm.system.insert("$ADVANCE".into(), Value::Int(3));
    let main = main.to_ascii_uppercase();
    vm.call(&main, &[])?;
    vm.stop("the program's end", &main)?;
    vm.run.laser_at_end = vm.laser;
    if !vm.pending.is_empty() {
        return Err("a TRIGGER without a motion after it".into());
    }
    Ok(vm.run)
}

impl Vm<'_> {
    fn call(&mut self, name: &str, args: &[f64]) -> Result<(), String> {
        let r = self
            .routines
            .get(name)
            .cloned()
            .ok_or_else(|| format!("no routine {name}"))?;
        if r.params.len() != args.len() {
            return Err(format!("{name} takes {} arguments", r.params.len()));
        }
        self.depth += 1;
        if self.depth > 8 {
            return Err(format!("{name}: calls nest too deep"));
        }
        let module = r.file[..r.file.len() - 4].to_ascii_uppercase();
        let mut frame = Frame {
            module,
            locals: HashMap::new(),
            routine: name.to_string(),
            args: args.to_vec(),
        };
        for (p, a) in r.params.iter().zip(args) {
            frame.locals.insert(p.clone(), Value::Real(*a));
        }
        self.block(&r.body, &mut frame)
            .map_err(|e| format!("{name}: {e}"))?;
        self.depth -= 1;
        Ok(())
    }

    fn block(&mut self, body: &[Stmt], f: &mut Frame) -> Result<(), String> {
        for s in body {
            self.stmt(s, f)?;
        }
        Ok(())
    }

    fn stmt(&mut self, s: &Stmt, f: &mut Frame) -> Result<(), String> {
        let at = |e: String| format!("{e} in {s:?}");
        match s {
            Stmt::Bas => Ok(()),
            Stmt::Decl(k, names) => {
                for n in names {
                    let v = match f.locals.get(n) {
                        // A parameter: now typed.
                        Some(v) => Value::Unset(*k).coerce(v.clone()).map_err(at)?,
                        None => Value::Unset(*k),
                    };
                    f.locals.insert(n.clone(), v);
                }
                Ok(())
            }
            Stmt::Do(a) => self.act(a, f).map_err(at),
            Stmt::For(v, a, b, body) => {
                let (a, b) = (
                    self.eval(a, f).and_then(|x| x.int()).map_err(at)?,
                    self.eval(b, f).and_then(|x| x.int()).map_err(at)?,
                );
                let mut i = a;
                while i <= b {
                    let place = Place {
                        name: v.clone(),
                        index: None,
                        member: None,
                    };
                    self.assign(&place, Value::Int(i), f).map_err(at)?;
                    self.block(body, f)?;
                    i += 1;
                }
                Ok(())
            }
            Stmt::If(c, yes, no) => match self.eval(c, f).map_err(at)? {
                Value::Bool(true) => self.block(yes, f),
                Value::Bool(false) => self.block(no, f),
                v => Err(at(format!("IF on {v:?}"))),
            },
            Stmt::Lin(target, approx) => {
                let Value::Struct(p) = self.eval(target, f).map_err(at)? else {
                    return Err(at("LIN to a non-POS".into()));
                };
                let get = |k: &str| {
                    p.get(k)
                        .copied()
                        .filter(|v| v.is_finite())
                        .ok_or_else(|| at(format!("no finite {k}")))
                };
                let pos = [get("X")?, get("Y")?, get("Z")?];
                let abc = [get("A")?, get("B")?, get("C")?];
                let v = self
                    .system
                    .get("$VEL.CP")
                    .cloned()
                    .unwrap_or(Value::Unset(Ty::Real))
                    .num()
                    .map_err(|e| at(format!("$VEL.CP: {e}")))?;
                if !(v.is_finite() && v > 0.0) {
                    return Err(at(format!("$VEL.CP = {v}")));
                }
                let triggers = std::mem::take(&mut self.pending);
                self.queue.push_back(Planned {
                    pos,
                    abc,
                    speed: v * 1000.0,
                    approximated: *approx,
                    module: f.module.clone(),
                    triggers,
                });
                let advance = match self.system.get("$ADVANCE") {
                    Some(Value::Int(a)) => (*a).max(0) as usize,
                    _ => 3,
                };
                while self.queue.len() > advance {
                    self.main_step()?;
                }
                Ok(())
            }
            Stmt::Ptp(target) => {
                self.eval(target, f).map_err(at)?;
                if !self.pending.is_empty() {
                    return Err(at("TRIGGER before a PTP".into()));
                }
                self.stop("PTP", &f.module)?;
                if self.laser {
                    return Err(at("PTP with the laser on".into()));
                }
                self.run.ptps += 1;
                Ok(())
            }
            Stmt::Trigger {
                distance,
                delay,
                action,
            } => {
                self.pending
                    .push((*distance, *delay, action.clone(), f.clone()));
                Ok(())
            }
            Stmt::Wait(x) => {
                let t = self.eval(x, f).and_then(|v| v.num()).map_err(at)?;
                if t.is_nan() || t < 0.0 {
                    return Err(at(format!("WAIT SEC {t}")));
                }
                self.stop("WAIT SEC", &f.module)
            }
        }
    }

    /// An advance-run stop: every planned motion runs, every delayed trigger
    /// fires.
    fn stop(&mut self, why: &str, module: &str) -> Result<(), String> {
        if !self.queue.is_empty() || !self.delayed.is_empty() {
            self.run.stops.push(format!("{module}: {why}"));
        }
        while !self.queue.is_empty() {
            self.main_step()?;
        }
        for (_, a, mut fr) in std::mem::take(&mut self.delayed) {
            self.fire(&a, &mut fr)?;
        }
        Ok(())
    }

    /// The main run completes the oldest planned motion.
    fn main_step(&mut self) -> Result<(), String> {
        let Some(m) = self.queue.pop_front() else {
            return Ok(());
        };
        let mut due = Vec::new();
        for d in &mut self.delayed {
            d.0 = d.0.saturating_sub(1);
        }
        self.delayed.retain(|d| {
            if d.0 == 0 {
                due.push((d.1.clone(), d.2.clone()));
                false
            } else {
                true
            }
        });
        for (a, mut fr) in due {
            self.fire(&a, &mut fr)?;
        }
        let mut after = Vec::new();
        for (dist, delay, a, mut fr) in m.triggers {
            if dist == 0 && delay == 0.0 {
                self.fire(&a, &mut fr)?;
            } else if dist == 1 && delay == 0.0 {
                after.push((a, fr));
            } else if dist == 1 && delay > 0.0 {
                self.delayed.push((self.cfg.delay_motions.max(1), a, fr));
            } else {
                return Err(format!(
                    "TRIGGER DISTANCE={dist} DELAY={delay} not modelled"
                ));
            }
        }
        self.run.motions.push(Motion {
            pos: m.pos,
            abc: m.abc,
            speed: m.speed,
            laser: self.laser,
            anout: self.anout,
            approximated: m.approximated,
            module: m.module,
        });
        for (a, mut fr) in after {
            self.fire(&a, &mut fr)?;
        }
        Ok(())
    }

    /// A trigger's action, in the main run.
    fn fire(&mut self, a: &Action, f: &mut Frame) -> Result<(), String> {
        let was = std::mem::replace(&mut self.in_trigger, true);
        let r = self.act(a, f);
        self.in_trigger = was;
        r
    }

    fn act(&mut self, a: &Action, f: &mut Frame) -> Result<(), String> {
        match a {
            Action::Assign(p, x) => {
                let v = self.eval(x, f)?;
                if !self.in_trigger && (p.name == "$OUT" || p.name == "$ANOUT") {
                    self.stop(&format!("{} written in the advance run", p.name), &f.module)?;
                }
                self.assign(p, v, f)
            }
            Action::Call(name, args) => {
                let vals = args
                    .iter()
                    .map(|x| self.eval(x, f).and_then(|v| v.num()))
                    .collect::<Result<Vec<_>, _>>()?;
                if self.in_trigger {
                    self.run
                        .triggered
                        .push((name.clone(), vals.clone(), self.run.motions.len()));
                }
                self.call(name, &vals)
            }
        }
    }

    fn assign(&mut self, p: &Place, v: Value, f: &mut Frame) -> Result<(), String> {
        if p.name.starts_with('$') {
            let key = match &p.member {
                Some(m) => format!("{}.{m}", p.name),
                None => p.name.clone(),
            };
            if let Some(i) = &p.index {
                let i = self.eval(i, f)?.int()?;
                match p.name.as_str() {
                    "$OUT" if i == self.laser_no => {
                        let Value::Bool(b) = v else {
                            return Err("$OUT needs TRUE/FALSE".into());
                        };
                        self.laser = b;
                    }
                    "$ANOUT" if i == self.power_no => {
                        let x = v.num()?;
                        if !(0.0..=1.0).contains(&x) {
                            return Err(format!("$ANOUT = {x} outside 0..1"));
                        }
                        self.anout = x;
                    }
                    _ => return Err(format!("{}[{i}] is not the laser's", p.name)),
                }
                return Ok(());
            }
            self.system.insert(key, v);
            return Ok(());
        }
        let index = match &p.index {
            Some(ix) => Some(self.eval(ix, f)?.int()?),
            None => None,
        };
        let slot = self.slot(&p.name, f)?;
        let slot = match index {
            None => slot,
            Some(i) => {
                let Value::Array(a) = slot else {
                    return Err(format!("{} is not an array", p.name));
                };
                let n = a.len();
                if i < 1 || i as usize > n {
                    return Err(format!("{}[{i}] outside 1..{n}", p.name));
                }
                &mut a[i as usize - 1]
            }
        };
        match &p.member {
            None => {
                *slot = slot.coerce(v)?;
            }
            Some(m) => {
                let x = v.num()?;
                let Value::Struct(s) = slot else {
                    return Err(format!("{}.{m}: not a POS with a value", p.name));
                };
                if !s.contains_key(m) {
                    return Err(format!("no component {m}"));
                }
                s.insert(m.clone(), x);
            }
        }
        Ok(())
    }

    fn slot<'s>(&'s mut self, name: &str, f: &'s mut Frame) -> Result<&'s mut Value, String> {
        if f.locals.contains_key(name) {
            return Ok(f.locals.get_mut(name).unwrap());
        }
        self.dats
            .get_mut(&f.module)
            .and_then(|d| d.get_mut(name))
            .ok_or_else(|| format!("{name} is not declared in {}", f.module))
    }

    fn eval(&mut self, x: &Expr, f: &mut Frame) -> Result<Value, String> {
        Ok(match x {
            Expr::Num(v) => v.clone(),
            Expr::Bool(b) => Value::Bool(*b),
            Expr::Enum(e) => Value::Enum(e.clone()),
            Expr::Agg(parts) => {
                let mut s = BTreeMap::new();
                for (k, x) in parts {
                    match self.eval(x, f)? {
                        // A nested aggregate (`$LOAD`'s `CM {…}`), flattened:
                        // its members as `CM.X`.
                        Value::Struct(inner) => {
                            s.extend(inner.into_iter().map(|(m, v)| (format!("{k}.{m}"), v)));
                        }
                        v => {
                            s.insert(k.clone(), v.num()?);
                        }
                    }
                }
                Value::Struct(s)
            }
            Expr::Neg(x) => match self.eval(x, f)? {
                Value::Int(i) => Value::Int(-i),
                Value::Real(r) => Value::Real(-r),
                v => return Err(format!("-{v:?}")),
            },
            Expr::Not(x) => match self.eval(x, f)? {
                Value::Bool(b) => Value::Bool(!b),
                v => return Err(format!("NOT {v:?}")),
            },
            Expr::Sqrt(x) => {
                let v = self.eval(x, f)?.num()?;
                if v.is_nan() || v < 0.0 {
                    return Err(format!("SQRT({v})"));
                }
                Value::Real(v.sqrt())
            }
            Expr::Bin(o, a, b) => {
                let (a, b) = (self.eval(a, f)?, self.eval(b, f)?);
                binary(o, a, b)?
            }
            Expr::Var(p) => self.read(p, f)?,
        })
    }

    fn read(&mut self, p: &Place, f: &mut Frame) -> Result<Value, String> {
        if ["TOOL_DATA", "BASE_DATA", "LOAD_DATA"].contains(&p.name.as_str()) {
            return Ok(Value::Opaque);
        }
        if p.name == "$ANIN" {
            let i = match &p.index {
                Some(ix) => self.eval(ix, f)?.int()?,
                None => return Err("$ANIN without an index".into()),
            };
            if !self.in_trigger {
                self.stop("$ANIN read in the advance run", &f.module.clone())?;
            }
            let v = (self.sensor)(&Read {
                input: i,
                routine: &f.routine,
                args: &f.args,
            })?;
            if !(-1.0..=1.0).contains(&v) {
                return Err(format!("$ANIN[{i}] = {v} outside -1..1"));
            }
            return Ok(Value::Real(v));
        }
        if p.name.starts_with('$') {
            let key = match &p.member {
                Some(m) => format!("{}.{m}", p.name),
                None => p.name.clone(),
            };
            return self
                .system
                .get(&key)
                .cloned()
                .ok_or_else(|| format!("{key} read before it is set"));
        }
        let index = match &p.index {
            Some(ix) => Some(self.eval(ix, f)?.int()?),
            None => None,
        };
        let slot = self.slot(&p.name, f)?;
        // Only the element: cloning a whole array of positions per read
        // would make a 46 800-motion run take minutes.
        let mut v = match index {
            None => slot.clone(),
            Some(i) => {
                let Value::Array(a) = slot else {
                    return Err(format!("{} is not an array", p.name));
                };
                let n = a.len();
                a.get((i - 1) as usize)
                    .filter(|_| i >= 1)
                    .cloned()
                    .ok_or_else(|| format!("{}[{i}] outside 1..{n}", p.name))?
            }
        };
        if let Some(m) = &p.member {
            let Value::Struct(s) = v else {
                return Err(format!("{}.{m} of a non-POS", p.name));
            };
            v = Value::Real(*s.get(m).ok_or_else(|| format!("no component {m}"))?);
        }
        if let Value::Unset(_) = v {
            return Err(format!("{}: value not assigned", p.name));
        }
        Ok(v)
    }
}

/// Runs a ring program whose sensor reads `value` on every input: with the
/// target height, the program lays the IR's nominal plan.
pub fn run_steady(
    files: &Files,
    main: &str,
    laser: u16,
    power: u16,
    value: f64,
) -> Result<Run, String> {
    let mut sensor = |_: &Read| Ok(value);
    run(
        files,
        main,
        laser,
        power,
        Config { delay_motions: 12 },
        &mut sensor,
    )
}
