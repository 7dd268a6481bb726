//! Does the program fit the machine? Every position written is checked against the
//! axis travel, and on a machine without a tilting head every normal against the
//! vertical. Problems are collected over the whole program and reported once per
//! rule and axis, with the worst case, so one run shows everything to fix.

use super::kinematics::{tilt_of, Rotary};
use crate::diag::{Code, Diagnostic, Diagnostics};
use crate::ir::AxisLimits;
use crate::span::Span;
use crate::units::short;
use std::fmt;

/// A normal tilted more than this (deg) cannot be followed by a vertical nozzle.
pub const NEEDS_TILT_DEG: f64 = 0.01;

/// Slack on travel limits: half the printed resolution, since a value that prints
/// as the limit is what the control sees.
const SLACK: f64 = 5e-4;

/// Where in the program a position is written (0-based indices).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Where {
    /// The IR point itself.
    Point {
        layer: usize,
        path: usize,
        point: usize,
    },
    /// The retract/clearance moves before a path.
    Clearance { layer: usize, path: usize },
    /// The retract after the last path.
    End,
}

impl fmt::Display for Where {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Where::Point { layer, path, point } => write!(
                f,
                "layer {}, path {}, point {}",
                layer + 1,
                path + 1,
                point + 1
            ),
            Where::Clearance { layer, path } => write!(
                f,
                "the clearance move before layer {}, path {}",
                layer + 1,
                path + 1
            ),
            Where::End => f.write_str("the retract after the last path"),
        }
    }
}

/// The worst offender of one rule.
#[derive(Clone, Copy, Debug)]
struct Worst {
    count: u64,
    value: f64,
    limit: f64,
    at: Where,
}

fn hit(slot: &mut Option<Worst>, value: f64, limit: f64, at: Where) {
    match slot {
        Some(w) => {
            w.count += 1;
            if (value - limit).abs() > (w.value - w.limit).abs() {
                w.value = value;
                w.limit = limit;
                w.at = at;
            }
        }
        None => {
            *slot = Some(Worst {
                count: 1,
                value,
                limit,
                at,
            })
        }
    }
}

#[inline]
fn within(v: f64, [lo, hi]: [f64; 2]) -> bool {
    v >= lo - SLACK && v <= hi + SLACK
}

/// The nearer end of `range` to `v`.
fn bound(v: f64, [lo, hi]: [f64; 2]) -> f64 {
    if v < lo {
        lo
    } else {
        hi
    }
}

/// Collects the problems of one program.
pub(crate) struct Checker {
    lim: AxisLimits,
    /// Whether the rotary axes exist (and are checked).
    five: bool,
    /// X Y Z tilt C.
    axes: [Option<Worst>; 5],
    tilted: Option<Worst>,
    tan2: f64,
    /// Whether anything was found.
    pub failed: bool,
}

impl Checker {
    /// A checker for `lim`; `five` when the machine has the rotary axes.
    pub fn new(lim: AxisLimits, five: bool) -> Self {
        Checker {
            lim,
            five,
            axes: [None; 5],
            tilted: None,
            tan2: NEEDS_TILT_DEG.to_radians().tan().powi(2),
            failed: false,
        }
    }

    /// Checks a position the program writes; `at` is only called on a problem.
    #[inline]
    pub fn position(&mut self, p: [f64; 3], r: Rotary, at: impl FnOnce() -> Where) {
        let l = &self.lim;
        let ok = within(p[0], l.x)
            && within(p[1], l.y)
            && within(p[2], l.z)
            && (!self.five || (within(r.tilt, l.tilt) && within(r.c, l.rotary)));
        if !ok {
            self.position_problem(p, r, at());
        }
    }

    #[cold]
    fn position_problem(&mut self, p: [f64; 3], r: Rotary, at: Where) {
        let l = self.lim;
        let vals = [
            (p[0], l.x),
            (p[1], l.y),
            (p[2], l.z),
            (r.tilt, l.tilt),
            (r.c, l.rotary),
        ];
        let n = if self.five { 5 } else { 3 };
        for (i, &(v, range)) in vals.iter().enumerate().take(n) {
            if !within(v, range) {
                hit(&mut self.axes[i], v, bound(v, range), at);
                self.failed = true;
            }
        }
    }

    /// On a machine without rotary axes: checks that normal `n` is vertical.
    #[inline]
    pub fn vertical(&mut self, n: [f32; 3], at: impl FnOnce() -> Where) {
        let (x, y, z) = (n[0] as f64, n[1] as f64, n[2] as f64);
        if z <= 0.0 || x * x + y * y > self.tan2 * z * z {
            let t = tilt_of([x, y, z]);
            hit(&mut self.tilted, t, NEEDS_TILT_DEG, at());
            self.failed = true;
        }
    }

    /// The diagnostics for machine `name` (declared at `span`); `tilt_name` is the
    /// tilt axis letter, `clearance` the retract distance (mentioned in hints).
    pub fn into_diagnostics(
        self,
        name: &str,
        tilt_name: &str,
        clearance: f64,
        span: Option<Span>,
    ) -> Diagnostics {
        let mut diags = Diagnostics::new();
        let plural = |n: u64| if n == 1 { "" } else { "s" };
        if let Some(w) = self.tilted {
            diags.push(
                Diagnostic::error(
                    Code::NeedsTilt,
                    format!(
                        "the part's layers tilt the nozzle up to {}° from vertical ({} point{}, the worst at {}), \
                         but machine `{name}` moves X Y Z only and keeps the nozzle vertical",
                        short(w.value),
                        w.count,
                        plural(w.count),
                        w.at
                    ),
                )
                .label_opt(span, "this machine has no tilting axes")
                .help(
                    "compile for a 5-axis machine (axes 5, kinematics head_ac or head_bc), \
                     or slice the part in planar (horizontal) layers",
                ),
            );
        }
        let names = ["X", "Y", "Z", tilt_name, "C"];
        for (i, w) in self.axes.iter().enumerate() {
            let Some(w) = w else { continue };
            let unit = if i < 3 { "mm" } else { "°" };
            let range = [
                self.lim.x,
                self.lim.y,
                self.lim.z,
                self.lim.tilt,
                self.lim.rotary,
            ][i];
            let sep = if i < 3 { " " } else { "" };
            let mut help = match i {
                0..=2 => format!(
                    "the part does not fit this machine's travel: place the part inside \
                     X [{}, {}], Y [{}, {}], Z [{}, {}] mm (program coordinates), or correct \
                     the machine's limits",
                    short(self.lim.x[0]),
                    short(self.lim.x[1]),
                    short(self.lim.y[0]),
                    short(self.lim.y[1]),
                    short(self.lim.z[0]),
                    short(self.lim.z[1]),
                ),
                3 => format!(
                    "the layers tilt the nozzle further than the {tilt_name} axis of `{name}` \
                     can go: use a machine whose head tilts further, or build the part in an \
                     orientation whose layers tilt less"
                ),
                _ => "the C axis turns past its stop while following the normals around the \
                      part: widen the C limits if the axis turns endlessly, or orient the part \
                      so the paths wind less"
                    .to_string(),
            };
            if i < 3 && !matches!(w.at, Where::Point { .. }) {
                help.push_str(&format!(
                    "; the clearance moves go {} mm beyond the path along the nozzle, a \
                     smaller clearance may do",
                    short(clearance)
                ));
            }
            diags.push(
                Diagnostic::error(
                    Code::AxisLimit,
                    format!(
                        "axis {} of machine `{name}` would have to reach {}{sep}{unit}, beyond its \
                         limit of {}{sep}{unit}, at {} ({} position{} outside [{}, {}]{sep}{unit})",
                        names[i],
                        short(w.value),
                        short(w.limit),
                        w.at,
                        w.count,
                        plural(w.count),
                        short(range[0]),
                        short(range[1]),
                    ),
                )
                .label_opt(span, "machine and its axis limits declared here")
                .help(help),
            );
        }
        diags
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn limits() -> AxisLimits {
        AxisLimits {
            x: [-100.0, 100.0],
            y: [-100.0, 100.0],
            z: [0.0, 200.0],
            tilt: [-30.0, 30.0],
            rotary: [-360.0, 360.0],
        }
    }

    #[test]
    fn keeps_the_worst_and_counts_all() {
        let mut c = Checker::new(limits(), true);
        let r = Rotary { tilt: 0.0, c: 0.0 };
        c.position([0.0, 0.0, 100.0], r, || unreachable!());
        c.position(
            [0.0, 0.0, 100.0],
            Rotary {
                tilt: 30.0004,
                c: 0.0,
            },
            || unreachable!(),
        );
        let at = |k| {
            move || Where::Point {
                layer: 0,
                path: 0,
                point: k,
            }
        };
        c.position([120.0, 0.0, 100.0], r, at(1));
        c.position([-150.0, 0.0, 100.0], r, at(2));
        c.position([0.0, 0.0, 100.0], Rotary { tilt: 40.0, c: 0.0 }, at(3));
        assert!(c.failed);
        let d: Vec<_> = c.into_diagnostics("m", "A", 10.0, None).into_vec();
        assert_eq!(d.len(), 2);
        assert!(d[0].message.contains("axis X"), "{}", d[0].message);
        assert!(d[0].message.contains("-150 mm"), "{}", d[0].message);
        assert!(
            d[0].message.contains("limit of -100 mm"),
            "{}",
            d[0].message
        );
        assert!(d[0].message.contains("point 3"), "{}", d[0].message);
        assert!(d[0].message.contains("2 positions"), "{}", d[0].message);
        assert!(d[1].message.contains("axis A"), "{}", d[1].message);
        assert!(d[1].message.contains("40°"), "{}", d[1].message);
    }

    #[test]
    fn vertical_within_a_hundredth_of_a_degree() {
        let mut c = Checker::new(limits(), false);
        let small = 0.009f64.to_radians();
        c.vertical(
            [small.sin() as f32, 0.0, small.cos() as f32],
            || unreachable!(),
        );
        assert!(!c.failed);
        let big = 0.02f64.to_radians();
        c.vertical([0.0, big.sin() as f32, big.cos() as f32], || Where::End);
        assert!(c.failed);
    }
}
