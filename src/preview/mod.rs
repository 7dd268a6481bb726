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
//! A slider over the kept moves draws, at the chosen one, the head's
//! solids about the beam (the machine's `head`, as the collision check
//! takes it), a robot's links as capsules ([`joints::Links`]) and the part
//! laid by then; a button goes to the closest approach's move. Each kept
//! move's place in the plan rides in about two bytes
//! (`encode::Poses`).
//!
//! For a robot with an arm the page also plots each axis's range layer by
//! layer against its limits ([`joints`]), solved as the verifier solves it;
//! for a 5-axis CNC, its tilt axis and C ([`rotary`]): on a tilting table,
//! the angles the table presents each layer at.

mod encode;
mod error;
pub mod joints;
mod kind;
pub mod moving;
pub mod repair;
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
    /// The kept moves' places and beams.
    poses: encode::Poses,
    /// The plan's index of each kept move.
    kept: Vec<usize>,
    /// Moves of the plan so far, and deposits among them.
    index: usize,
    laid: usize,
    /// The place of the deposit move left pending.
    pending_place: Option<encode::Place>,
    /// Up the beam is +Z whatever the normal (a 3-axis CNC, as the
    /// collision check takes it).
    vertical: bool,
    /// The approaches' moves, found as the plan goes by.
    approaches: Vec<Seek>,
}

/// The plan's move an approach happened on: the move whose target it
/// names and whose line passes nearest its focus (`way` along it).
struct Seek {
    at: Where,
    way: f64,
    focus: [f64; 3],
    /// The distance from the focus, and the plan's move index.
    best: Option<(f64, usize)>,
}

impl Seek {
    fn of(a: &crate::verify::approach::Approach) -> Seek {
        let at = match (a.layer, a.path, a.point) {
            (Some(l), Some(p), Some(q)) => Where::Point {
                layer: l - 1,
                path: p - 1,
                point: q - 1,
            },
            (Some(l), Some(p), None) => Where::Clearance {
                layer: l - 1,
                path: p - 1,
            },
            _ => Where::End,
        };
        Seek {
            at,
            way: a.way,
            focus: a.focus,
            best: None,
        }
    }

    fn offer(&mut self, from: [f64; 3], m: &Move, index: usize) {
        if m.at != self.at {
            return;
        }
        let d = (0..3)
            .map(|k| (from[k] + self.way * (m.to[k] - from[k]) - self.focus[k]).powi(2))
            .sum::<f64>();
        if self.best.is_none_or(|(b, _)| d < b) {
            self.best = Some((d, index));
        }
    }
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

    /// The place of the move the plan is at.
    fn place(&self, m: &Move) -> encode::Place {
        let beam = if self.vertical {
            [0.0, 0.0, 1.0]
        } else {
            let n = m.normal.map(f64::from);
            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            if len > 0.0 && len.is_finite() {
                n.map(|c| c / len)
            } else {
                [0.0, 0.0, 1.0]
            }
        };
        encode::Place {
            index: self.index,
            laid: self.laid,
            at: m.at,
            beam,
            deposit: m.deposits(),
        }
    }

    fn push(&mut self, m: &Move, place: encode::Place) {
        self.poses.push(&place);
        self.kept.push(place.index);
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
        if let (Some(m), Some(place)) = (self.pending.take(), self.pending_place.take()) {
            self.push(&m, place);
        }
    }

    /// The page's move of each approach.
    fn approach_moves(&self) -> Vec<Option<encode::ApproachMove>> {
        self.approaches
            .iter()
            .map(|a| {
                let (_, index) = a.best?;
                let kept = self.kept.partition_point(|&k| k < index);
                let kept = kept.min(self.kept.len().checked_sub(1)?);
                Some(encode::ApproachMove {
                    kept,
                    exact: self.kept[kept] == index,
                })
            })
            .collect()
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
            self.laid += 1;
        }
        for a in &mut self.approaches {
            a.offer(from.unwrap_or(m.to), m, self.index);
        }
        let place = self.place(m);
        self.index += 1;
        if !self.keep_layer {
            return;
        }
        if m.deposits() {
            let k = self.run;
            self.run += 1;
            if k.is_multiple_of(self.d.moves) {
                self.pending = None;
                self.pending_place = None;
                self.push(m, place);
            } else {
                self.pending = Some(*m);
                self.pending_place = Some(place);
            }
        } else {
            self.flush();
            self.push(m, place);
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
    page(machine, budget, None, None)
}

/// The preview page of `machine`'s plan with a part's scan and finish
/// drawn over it ([`repair`]; `crate::pipeline::repair_overlay` makes it).
pub fn html_with(machine: VerifiedMachine<'_>, overlay: Option<&repair::Overlay>) -> String {
    page(machine, BUDGET, None, overlay)
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
        None,
    ))
}

fn page(
    machine: VerifiedMachine<'_>,
    budget: usize,
    failures: Option<&Diagnostics>,
    repair: Option<&repair::Overlay>,
) -> String {
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
        poses: encode::Poses::default(),
        kept: Vec::new(),
        index: 0,
        laid: 0,
        pending_place: None,
        vertical: match machine.machine() {
            crate::ir::Machine::Cnc(c) => c.effective_kinematics() == crate::ir::Kinematics::Xyz,
            crate::ir::Machine::Robot(_) => false,
        },
        approaches: machine.summary().approaches.iter().map(Seek::of).collect(),
    };
    plan.walk(&mut c);
    c.flush();
    let approach_moves = c.approach_moves();
    let layer_error = c.errors.finish();
    let want = posed(&c.kept, &approach_moves);
    let moving = moving::of(program, machine.machine(), &plan, want.clone());
    let arm = joints::of(machine.machine(), &plan, program.layers.len(), want);
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
        thermal: encode::Heat::of(program),
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
        approach_moves: &approach_moves,
        head: &machine.machine().common().head,
        fixtures: fixture_boxes(program, machine.machine()),
        moving,
        faceplate: encode::Faceplate::of(machine.machine()),
        repair,
        generator: concat!("lmdc ", env!("CARGO_PKG_VERSION")),
    };
    let data = c.cols.encode(&meta, &c.poses);
    // In page order, each marker replaced once: no inserted text is
    // searched again (the viewer's code mentions the markers' names).
    PAGE.replacen("{{TITLE}}", &encode::escape_html(&program.part), 1)
        .replacen("/*DATA*/", &data, 1)
        .replacen("/*VIEWER*/", VIEWER, 1)
}

/// The page's moves the arm is posed at, as `(plan move index, page move
/// index)` ascending: every k-th kept move (and the last), `k` the least
/// that keeps them within [`joints::POSES`], and every approach's move.
fn posed(kept: &[usize], approaches: &[Option<encode::ApproachMove>]) -> Vec<(usize, usize)> {
    let k = kept.len().div_ceil(joints::POSES).max(1);
    let mut out: Vec<usize> = (0..kept.len())
        .filter(|i| i.is_multiple_of(k) || i + 1 == kept.len())
        .chain(approaches.iter().flatten().map(|a| a.kept))
        .collect();
    out.sort_unstable();
    out.dedup();
    out.into_iter()
        .filter_map(|i| Some((*kept.get(i)?, i)))
        .collect()
}

/// The fixtures `machine`'s head meets, as drawn in the part's coordinates
/// (docs/collision.md): those on the plate, and those fixed to the machine
/// where the part does not turn, as their box there (a turned one's box
/// dashed, as a mesh's). Where a table or a positioner turns the part, a
/// fixture fixed to the machine stands elsewhere at every move: not drawn.
fn fixture_boxes<'a>(
    program: &'a crate::ir::Program,
    machine: &crate::ir::Machine,
) -> Vec<encode::FixtureBox<'a>> {
    crate::plan::part_frame::fixture_boxes(program, machine)
        .into_iter()
        .map(|p| {
            let mut b = encode::FixtureBox::of(p.fixture);
            (b.lo, b.hi) = p.bounds;
            if p.turned {
                b.kind = "mesh";
            }
            b
        })
        .collect()
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
