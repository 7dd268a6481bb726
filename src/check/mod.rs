//! Checks on the IR: every process constraint, on every point, once. The result is
//! a [`Verified`] proof that the back ends require, so unchecked IR cannot reach
//! them (the idea of naga's validator).

use crate::diag::{Code, Diagnostic, Diagnostics};
use crate::ir::{Machine, Program};
use crate::units::short;

/// IR that passed every check, with the warnings found on the way.
#[derive(Debug)]
pub struct Verified {
    program: Program,
    warnings: Diagnostics,
}

impl Verified {
    /// The checked IR.
    pub fn ir(&self) -> &Program {
        &self.program
    }

    /// Warnings (the checks passed regardless).
    pub fn warnings(&self) -> &Diagnostics {
        &self.warnings
    }

    /// Gives the IR back.
    pub fn into_ir(self) -> Program {
        self.program
    }
}

/// Relative slack for comparisons against limits: values are stored as `f32`.
const SLACK: f64 = 1e-5;

/// Collects the worst offender of one rule over all points.
struct Offence {
    what: &'static str,
    count: usize,
    worst: f64,
    at: (usize, usize, usize),
}

impl Offence {
    fn new(what: &'static str) -> Self {
        Offence {
            what,
            count: 0,
            worst: f64::NAN,
            at: (0, 0, 0),
        }
    }

    /// Records `value` as out of range; keeps the one farthest beyond `limit`.
    fn hit(&mut self, value: f64, limit: f64, at: (usize, usize, usize)) {
        if self.count == 0 || (value - limit).abs() > (self.worst - limit).abs() {
            self.worst = value;
            self.at = at;
        }
        self.count += 1;
    }
}

/// Checks `program`; returns the proof or every violation found.
pub fn verify(program: Program) -> Result<Verified, Diagnostics> {
    let mut diags = Diagnostics::new();
    let lim = program.limits.clone();
    let o = &program.origins;
    let [h_min, h_max] = lim.layer_height;
    let [v_min, v_max] = lim.speed;
    let [p_min, p_max] = lim.power;
    let machine_speed = program
        .machines
        .iter()
        .map(|m| match m {
            Machine::Robot(r) => r.max_speed,
            Machine::Cnc(c) => c.max_speed,
        })
        .fold(f64::INFINITY, f64::min);

    let mut nonfinite = Offence::new("non-finite value");
    let mut not_unit = Offence::new("direction that is not a unit vector");
    let mut low_h = Offence::new("layer height below h_min");
    let mut high_h = Offence::new("layer height above h_max");
    let mut slow = Offence::new("speed below the bead model's range");
    let mut fast = Offence::new("speed above the bead model's range");
    let mut too_fast = Offence::new("speed above the machine's limit");
    let mut low_p = Offence::new("power below the laser's range");
    let mut high_p = Offence::new("power above the laser's range");

    for (li, layer) in program.layers.iter().enumerate() {
        for (pi, path) in layer.paths.iter().enumerate() {
            for (k, pt) in path.points.iter().enumerate() {
                let at = (li, pi, k);
                let vals = [
                    pt.pos[0],
                    pt.pos[1],
                    pt.pos[2],
                    pt.layer_height as f64,
                    pt.speed as f64,
                    pt.power as f64,
                    pt.powder as f64,
                    pt.defocus as f64,
                ];
                let dirs = [pt.normal, pt.tangent];
                if vals.iter().any(|v| !v.is_finite())
                    || dirs.iter().flatten().any(|v| !v.is_finite())
                {
                    nonfinite.hit(f64::NAN, 0.0, at);
                    continue;
                }
                for d in dirs {
                    let n = d
                        .iter()
                        .map(|&c| (c as f64) * (c as f64))
                        .sum::<f64>()
                        .sqrt();
                    if (n - 1.0).abs() > 1e-4 {
                        not_unit.hit(n, 1.0, at);
                    }
                }
                let v = pt.speed as f64;
                if v > machine_speed * (1.0 + SLACK) {
                    too_fast.hit(v, machine_speed, at);
                }
                if !pt.laser_on {
                    continue;
                }
                let h = pt.layer_height as f64;
                if h < h_min * (1.0 - SLACK) {
                    low_h.hit(h, h_min, at);
                }
                if h > h_max * (1.0 + SLACK) {
                    high_h.hit(h, h_max, at);
                }
                if v < v_min * (1.0 - SLACK) {
                    slow.hit(v, v_min, at);
                }
                if v > v_max * (1.0 + SLACK) {
                    fast.hit(v, v_max, at);
                }
                let p = pt.power as f64;
                if p < p_min * (1.0 - SLACK) {
                    low_p.hit(p, p_min, at);
                }
                if p > p_max * (1.0 + SLACK) {
                    high_p.hit(p, p_max, at);
                }
            }
        }
    }

    if nonfinite.count > 0 {
        let (l, p, k) = nonfinite.at;
        diags.push(Diagnostic::error(
            Code::NonFinite,
            format!(
                "{} point{} carry a value that is not a finite number (first at layer {}, path {}, point {})",
                nonfinite.count,
                if nonfinite.count == 1 { "" } else { "s" },
                l + 1,
                p + 1,
                k + 1
            ),
        )
        .help("this is a bug in lmdc's geometry for this input; please report it with the .lmd file"));
    }
    let mut report = |off: Offence,
                      limit: f64,
                      unit: &str,
                      spans: &[Option<crate::span::Span>],
                      help: &str| {
        if off.count == 0 {
            return;
        }
        let (l, p, k) = off.at;
        let mut d = Diagnostic::error(
            Code::OutOfRange,
            format!(
                "{} point{} with a {}: the worst is {} {unit} (limit {} {unit}) at layer {}, path {}, point {}",
                off.count,
                if off.count == 1 { "" } else { "s" },
                off.what,
                short(off.worst),
                short(limit),
                l + 1,
                p + 1,
                k + 1
            ),
        )
        .help(help.to_string());
        for (i, s) in spans.iter().enumerate() {
            d = d.label_opt(
                *s,
                if i == 0 {
                    "limit declared here"
                } else {
                    "this produces it"
                },
            );
        }
        diags.push(d);
    };

    report(
        not_unit,
        1.0,
        "",
        &[],
        "this is a bug in lmdc's geometry; please report it with the .lmd file",
    );
    let geom = [o.bead_height, o.spine, o.slicing];
    // Planar layers have no spine: their height is the declared or derived lift.
    let planar_help = "a flat layer rises by what its tracks lay (A/w for one track, A/d for tracks d apart): `layer_height = auto` derives it, or declare one within the bead's heights";
    report(
        low_h,
        h_min,
        "mm",
        &geom,
        if o.spine.is_none() {
            planar_help
        } else {
            "use more layers' worth of height per layer (fewer layers), a larger bend radius, or a bead model that reaches lower heights"
        },
    );
    report(
        high_h,
        h_max,
        "mm",
        &geom,
        if o.spine.is_none() {
            planar_help
        } else {
            "use more layers, a larger bend radius, or a bead model that reaches higher beads"
        },
    );
    report(
        slow,
        v_min,
        "mm/s",
        &[o.bead_speed],
        "the bead model is not valid this slow: widen its speed range if the process allows",
    );
    report(
        fast,
        v_max,
        "mm/s",
        &[o.bead_speed],
        "the bead model is not valid this fast: widen its speed range if the process allows",
    );
    report(
        too_fast,
        machine_speed,
        "mm/s",
        &[o.machines.first().copied(), o.bead_speed],
        "lower the speeds or raise the machine's max_speed if it really can go faster",
    );
    report(
        low_p,
        p_min,
        "W",
        &[o.power],
        "raise the power schedule into the laser's range",
    );
    report(
        high_p,
        p_max,
        "W",
        &[o.power],
        "lower the power schedule into the laser's range",
    );

    if diags.has_errors() {
        Err(diags)
    } else {
        Ok(Verified {
            program,
            warnings: diags,
        })
    }
}
