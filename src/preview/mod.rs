//! The plan preview (`lmdc preview`): one self-contained HTML page that
//! draws a machine's motion plan in 3-D — deposits coloured by a quantity
//! (among them the height error the bead model predicts and what kind of
//! path a move is part of), travel faint, over the substrate with axes and
//! a scale bar — with a layer range, orbit and zoom, a plot of speed, height
//! and height error along a layer's path and one of the height error layer
//! by layer. Everything is inline (no network: the viewer is a small canvas
//! 2-D renderer of our own, `viewer.js`), and the same plan gives the same
//! bytes.
//!
//! The page carries the moves of the plan ([`crate::plan::Plan::walk`]), so
//! it shows what the program does: tool-tip positions (the laser focus),
//! approaches and retracts included. Past [`BUDGET`] moves it keeps every
//! k-th layer and every k-th deposit move of each run (its ends always), `k`
//! the smallest that fits, and says so on the page: a page of a few MB that
//! a browser draws interactively, against 3.6 M points of the dense duct.
//!
//! For a robot with an arm the page also plots each axis's range layer by
//! layer against its limits ([`joints`]), solved as the verifier solves it;
//! for a 5-axis CNC, its tilt axis and C ([`rotary`]): on a tilting table,
//! the angles the table presents each layer at.

mod encode;
mod error;
pub mod joints;
mod kind;
pub mod rotary;

use crate::diag::{Diagnostics, Severity};
use crate::ir::{Layer, Point};
use crate::plan::{Move, Speed, Visit, Where};
use crate::verify::{Refused, VerifiedMachine};
use encode::Columns;
use kind::Kind;

/// Most moves a page carries (about 14 bytes each, base64 on top).
pub const BUDGET: usize = 300_000;

const PAGE: &str = include_str!("page.html");
const VIEWER: &str = include_str!("viewer.js");

/// Which moves a page keeps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Decimation {
    /// Every this many layers (the last always).
    pub layers: usize,
    /// Every this many deposit moves of a run (its last always).
    pub moves: usize,
}

/// The decimation that brings `moves` moves within `budget`: the same
/// stride across layers and along paths, so both thin out alike.
pub fn decimation(moves: usize, budget: usize) -> Decimation {
    let mut k = 1;
    while moves.div_ceil(k * k) > budget.max(1) {
        k += 1;
    }
    Decimation {
        layers: k,
        moves: k,
    }
}

/// Counts moves.
struct Count(usize);

impl Visit for Count {
    fn motion(&mut self, _: &Move) {
        self.0 += 1;
    }
}

/// Collects the kept moves.
struct Collect<'a> {
    d: Decimation,
    rapid: f32,
    layers: &'a [Layer],
    cols: Columns,
    keep_layer: bool,
    /// Index of the deposit move in its run.
    run: usize,
    /// A deposit move skipped last: kept if it ends its run.
    pending: Option<Move>,
    /// The next kept move starts a new line (layers were skipped).
    gap: bool,
    /// `(layer number, first move)` of each kept layer.
    starts: Vec<(usize, usize)>,
    /// The class of each path of the layer being walked.
    kinds: Vec<Kind>,
    /// Every layer's height error, from every move (decimated or not).
    errors: error::Layers,
    /// Where the last move ended.
    last: Option<[f64; 3]>,
}

impl<'a> Collect<'a> {
    /// The IR point whose values `m` carries, and its path's index.
    fn source(&self, m: &Move) -> Option<(&'a Point, usize)> {
        let layers: &'a [Layer] = self.layers;
        match m.source() {
            Where::Point { layer, path, point } => layers
                .get(layer)
                .and_then(|l| l.paths.get(path))
                .and_then(|p| p.points.get(point))
                .map(|p| (p, path)),
            _ => None,
        }
    }

    fn push(&mut self, m: &Move) {
        let src = self.source(m);
        let speed = match m.speed {
            Speed::Feed(v) => v,
            Speed::Rapid => self.rapid,
        };
        let deposit = m.deposits();
        let on = src.filter(|_| deposit);
        self.cols.push(encode::Row {
            pos: m.to,
            speed,
            height: on.map_or(0.0, |(p, _)| p.layer_height),
            power: if deposit { m.power } else { 0.0 },
            style: src.map_or(0, |(p, _)| p.style),
            error: on.and_then(|(p, _)| error::of(p)),
            // Every deposit starts from a point of a path.
            kind: on
                .and_then(|(_, path)| self.kinds.get(path).copied())
                .unwrap_or(Kind::Travel),
            deposit,
            gap: std::mem::take(&mut self.gap),
        });
    }

    fn flush(&mut self) {
        if let Some(m) = self.pending.take() {
            self.push(&m);
        }
    }
}

impl Visit for Collect<'_> {
    fn layer(&mut self, index: usize, layer: &Layer) {
        self.flush();
        self.kinds = kind::classify(layer);
        self.errors.begin();
        let last = index + 1 == self.layers.len();
        let keep = index.is_multiple_of(self.d.layers) || last;
        if !keep && self.keep_layer {
            self.gap = true;
        }
        self.keep_layer = keep;
        if keep {
            self.starts.push((index + 1, self.cols.len()));
        }
    }

    fn laser_off(&mut self) {
        self.flush();
        self.run = 0;
    }

    fn motion(&mut self, m: &Move) {
        let from = self.last.replace(m.to);
        if m.deposits() {
            if let (Some((p, _)), Some(from)) = (self.source(m), from) {
                self.errors.deposit(p, error::ground(from, m.to, p.normal));
            }
        }
        if !self.keep_layer {
            return;
        }
        if m.deposits() {
            let k = self.run;
            self.run += 1;
            if k.is_multiple_of(self.d.moves) {
                self.pending = None;
                self.push(m);
            } else {
                self.pending = Some(*m);
            }
        } else {
            self.flush();
            self.push(m);
        }
    }
}

/// The preview page of `machine`'s plan, decimated to at most [`BUDGET`]
/// moves.
pub fn html(machine: VerifiedMachine<'_>) -> String {
    html_within(machine, BUDGET)
}

/// The preview page with at most about `budget` moves.
pub fn html_within(machine: VerifiedMachine<'_>, budget: usize) -> String {
    page(machine, budget, None)
}

/// The page of a plan refused only by the arm's rules: drawn as the other
/// rules passed it, headed by the arm's errors (each names its place), the
/// axes' plot showing where they go past their margins. `None` when the
/// refused program has no machine's plan to draw.
pub fn refused_html(refused: &Refused) -> Option<String> {
    // The arm's failures are a robot's: draw the first robot with an arm,
    // not the first machine, which may be a CNC that passed.
    let armed = |m: &VerifiedMachine<'_>| matches!(m.machine(), crate::ir::Machine::Robot(r) if r.arm.is_some());
    Some(page(
        refused
            .machines()
            .find(armed)
            .or_else(|| refused.machines().next())?,
        BUDGET,
        Some(refused.failures()),
    ))
}

fn page(machine: VerifiedMachine<'_>, budget: usize, failures: Option<&Diagnostics>) -> String {
    let program = machine.ir();
    let plan = machine.plan();
    let mut count = Count(0);
    plan.walk(&mut count);
    let d = decimation(count.0, budget);
    let rapid = machine.machine().common().max_speed as f32;
    let mut c = Collect {
        d,
        rapid,
        layers: &program.layers,
        cols: Columns::default(),
        keep_layer: true,
        run: 0,
        pending: None,
        gap: false,
        starts: Vec::new(),
        kinds: Vec::new(),
        errors: error::Layers::default(),
        last: None,
    };
    plan.walk(&mut c);
    c.flush();
    let layer_error = c.errors.finish();
    let arm = joints::of(machine.machine(), &plan, program.layers.len());
    let rotary = rotary::of(machine.machine(), &plan);
    let meta = encode::Meta {
        part: &program.part,
        machine: machine.machine().name(),
        layers: program.layers.len(),
        points: program.point_count(),
        moves: count.0,
        kept: c.cols.len(),
        decimation: d,
        starts: &c.starts,
        styles: &program.styles,
        kinds: Kind::NAMES,
        tolerance: program.limits.rise_tolerance * 100.0,
        max_drift: program.limits.max_drift,
        layer_error: &layer_error,
        arm: arm.as_ref(),
        rotary: rotary.as_ref(),
        refused: failures.map(|f| {
            f.iter()
                .filter(|d| d.severity == Severity::Error)
                .map(|d| encode::Failure {
                    code: d.code.to_string(),
                    message: d.message.clone(),
                    help: d.help.clone(),
                })
                .collect()
        }),
        approaches: &machine.summary().approaches,
        generator: concat!("lmdc ", env!("CARGO_PKG_VERSION")),
    };
    let data = c.cols.encode(&meta);
    // In page order, each marker replaced once: no inserted text is
    // searched again (the viewer's code mentions the markers' names).
    PAGE.replacen("{{TITLE}}", &encode::escape_html(&program.part), 1)
        .replacen("/*DATA*/", &data, 1)
        .replacen("/*VIEWER*/", VIEWER, 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimation_fits_the_budget_with_the_smallest_stride() {
        assert_eq!(decimation(70_000, BUDGET).moves, 1);
        let d = decimation(3_607_000, BUDGET);
        assert_eq!((d.layers, d.moves), (4, 4));
        assert!(3_607_000usize.div_ceil(16) <= BUDGET);
        assert_eq!(decimation(10, 0).moves, 4);
    }
}
