//! The finished surface a variable-top plan lays, as its own bead model
//! predicts it, against the top the file asks for (docs/repair.md, *The
//! report*): where a repair ends up against its target.
//!
//! Every eighth of a bead along the last layer's tracks, the surface is the base under it (the
//! scan a repair starts on, else the plate) plus what every layer's move
//! over that place raises it by, `A/pitch` at the move's speed
//! ([`crate::ir::Point::predicted_rise`]). The tracks of a variable top run
//! along x or y, so a place is a line (the cross coordinate) and a
//! position along it: each layer's moves on the line are sorted once and
//! looked up by halving. A place a layer does not lay (a levelling pass
//! that leaves it, a too-thin gap) adds nothing there.
//!
//! A fill along a tilted build direction `d` (`direction = auto`) is
//! predicted in the part turned so that `d` is up, as its planner laid it:
//! its tracks run along that frame's x or y, its layers rise along `d`,
//! the scan and the target are the ones it was planned on
//! (`slice::top::seen_along`), and every place is named back in
//! the part, its departure measured along `d`.
//!
//! A wall on a scan is predicted at its last layer's moves' middles
//! (module `wall`).

use super::design::linear_top;
use crate::deposit::Deposit;
use crate::diag::Diagnostics;
use crate::geometry::outline::profile;
use crate::ir::{Layer, Program};
use crate::sema::model::{Build, Model, Top, TopExtrusion, TurnedFrame};
use serde::Serialize;
use std::collections::BTreeMap;

mod wall;

/// Chord error of the footprint's outline, mm (as the design volume's).
const CHORD: f64 = 0.005;

/// Most places one track is looked at.
const MAX_SAMPLES: f64 = 100_000.0;

/// The predicted finished surface against the top.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Finish {
    /// The places it is predicted at: every eighth of a bead along the
    /// last layer's tracks.
    pub points: usize,
    /// The most the surface lies below the top (≥ 0), mm, and where.
    pub below_mm: f64,
    /// Where it lies lowest against the top, mm.
    pub below_at: [f64; 2],
    /// The most it stands above the top (≥ 0), mm.
    pub above_mm: f64,
    /// Where it stands highest against the top, mm.
    pub above_at: [f64; 2],
    /// The root mean square of its departure from the top, mm.
    pub rms_mm: f64,
    /// The first layer's thickness, least and greatest, mm.
    pub first_layer_mm: [f64; 2],
    /// The build direction departures are measured along, where it is
    /// tilted (`direction = auto`); the places are then on the target's
    /// face, seen from above. Vertical: none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub along: Option<[f64; 3]>,
}

/// A line's moves in one layer: (from, to, rise), sorted.
type Moves = Vec<(f64, f64, f64)>;

/// The key of the line a move runs on, and its ends along it: along x (a
/// constant y) or along y (a constant x); `None` for a move across.
fn on_line(a: [f64; 3], b: [f64; 3]) -> Option<((u8, i64), f64, f64)> {
    let key = |c: f64| (c * 1e6).round() as i64;
    if (a[1] - b[1]).abs() <= 1e-9 {
        Some(((0, key(a[1])), a[0].min(b[0]), a[0].max(b[0])))
    } else if (a[0] - b[0]).abs() <= 1e-9 {
        Some(((1, key(a[0])), a[1].min(b[1]), a[1].max(b[1])))
    } else {
        None
    }
}

/// Every layer's laser-on moves by line, in the frame `turn` takes the
/// part into (the build direction up).
fn moves(layers: &[Layer], d: &Deposit, turn: &Turn) -> BTreeMap<(u8, i64), Vec<Moves>> {
    let mut out: BTreeMap<(u8, i64), Vec<Moves>> = BTreeMap::new();
    for (li, layer) in layers.iter().enumerate() {
        for path in &layer.paths {
            for (k, pt) in path.points.iter().enumerate() {
                let Some(next) = path.points.get(k + 1).filter(|_| pt.laser_on) else {
                    continue;
                };
                let Some((key, t0, t1)) = on_line(turn.planned(pt.pos), turn.planned(next.pos))
                else {
                    continue;
                };
                // A rise along a tilted nozzle (`follow = surface`) raises
                // the face by it over the normal's vertical share; a
                // vertical normal's share is exactly 1.
                let n = turn.planned(pt.normal.map(f64::from));
                let up = n[2] / (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
                let rise = match pt.predicted_rise(d, Some(next)) {
                    r if up > 0.0 && up < 1.0 => r / up,
                    r => r,
                };
                let per = out
                    .entry(key)
                    .or_insert_with(|| vec![Vec::new(); layers.len()]);
                per[li].push((t0, t1, rise));
            }
        }
    }
    for per in out.values_mut() {
        for m in per.iter_mut() {
            m.sort_by(|a, b| a.0.total_cmp(&b.0));
        }
    }
    out
}

/// What a layer's sorted moves raise the place `t` by: the move over it
/// (the first, where two meet), or nothing.
fn rise_at(m: &Moves, t: f64) -> f64 {
    let i = m.partition_point(|&(t0, ..)| t0 <= t + 1e-9);
    m[..i]
        .iter()
        .rev()
        .take(2)
        .find(|&&(t0, t1, _)| t >= t0 - 1e-9 && t <= t1 + 1e-9)
        .map_or(0.0, |&(.., r)| r)
}

/// The finished surface `model`'s variable top (or its wall on a scan) is
/// predicted at, from `program`'s layers; `None` for another build or a
/// plan without a bead.
pub fn of(program: &Program, model: &Model) -> Option<Finish> {
    sampled(program, model).map(|(f, _)| f)
}

/// A place the finish is predicted at: where, the top asked for there
/// and how far the predicted face departs from it (above: positive), mm.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Where, mm.
    pub at: [f64; 2],
    /// The top asked for, mm.
    pub top: f64,
    /// The predicted face less the top, mm.
    pub off: f64,
}

/// [`of`], with every place it looked at.
pub fn sampled(program: &Program, model: &Model) -> Option<(Finish, Vec<Sample>)> {
    match &model.build {
        Build::Variable { extrusion, .. } => of_fill(program, model, extrusion),
        Build::ScanWall { wall, on, .. } => wall::sampled(program, wall, on),
        _ => None,
    }
}

/// The finish of a footprint filled up to its top.
fn of_fill(program: &Program, model: &Model, ex: &TopExtrusion) -> Option<(Finish, Vec<Sample>)> {
    // A fill along a tilted direction is predicted where it was planned:
    // in the part turned so the direction is up.
    let along = tilted(program);
    let seen;
    let (ex, turn) = match along {
        None => (ex, Turn::default()),
        Some(d) => {
            seen = crate::slice::top::seen_along(ex, model.bead.as_ref()?, d)?;
            let frame = seen.turned.clone()?;
            (&seen, Turn { frame: Some(frame) })
        }
    };
    let d = program.bead.as_ref()?.deposit();
    let last = program.layers.last()?;
    let by_line = moves(&program.layers, &d, &turn);
    let mut top = Target::new(ex)?;
    let mut tally = Tally::new(first_layer(&program.layers[0])?, along);
    // Every eighth of a bead along the last layer's tracks.
    let step = program.limits.bead_width / 8.0;
    if !(step.is_finite() && step > 0.0) {
        return None;
    }
    for path in &last.paths {
        // The line the path runs on (a variable top's tracks are straight).
        let Some((line, ..)) = path
            .points
            .windows(2)
            .find_map(|w| on_line(turn.planned(w[0].pos), turn.planned(w[1].pos)))
        else {
            continue;
        };
        let Some(per) = by_line.get(&line) else {
            continue;
        };
        let first = turn.planned(path.points[0].pos);
        let end = turn.planned(path.points[path.points.len() - 1].pos);
        let (t0, t1, c) = match line.0 {
            0 => (first[0].min(end[0]), first[0].max(end[0]), first[1]),
            _ => (first[1].min(end[1]), first[1].max(end[1]), first[0]),
        };
        let n = ((t1 - t0) / step).ceil().clamp(1.0, MAX_SAMPLES) as usize;
        for i in 0..=n {
            let t = t0 + (t1 - t0) * i as f64 / n as f64;
            let [x, y] = if line.0 == 0 { [t, c] } else { [c, t] };
            let (Some(base), Some(want)) = (top.base([x, y]), top.at([x, y])) else {
                continue;
            };
            let off = base + per.iter().map(|m| rise_at(m, t)).sum::<f64>() - want;
            // The place on the target, named in the part.
            let at = turn.back([x, y, want]);
            tally.add([at[0], at[1]], at[2], off);
        }
    }
    tally.done()
}

/// The finish as its places are added: the worst each way, the squares,
/// every place.
struct Tally {
    f: Finish,
    squares: f64,
    samples: Vec<Sample>,
}

impl Tally {
    fn new(first_layer_mm: [f64; 2], along: Option<[f64; 3]>) -> Self {
        Tally {
            f: Finish {
                points: 0,
                below_mm: 0.0,
                below_at: [0.0; 2],
                above_mm: 0.0,
                above_at: [0.0; 2],
                rms_mm: 0.0,
                first_layer_mm,
                along,
            },
            squares: 0.0,
            samples: Vec::new(),
        }
    }

    /// The face departs from the top `top` by `off` at `at` (above:
    /// positive).
    fn add(&mut self, at: [f64; 2], top: f64, off: f64) {
        let f = &mut self.f;
        self.samples.push(Sample { at, top, off });
        f.points += 1;
        self.squares += off * off;
        if -off > f.below_mm {
            (f.below_mm, f.below_at) = (-off, at);
        }
        if off > f.above_mm {
            (f.above_mm, f.above_at) = (off, at);
        }
    }

    /// The finish and its places, if any was added.
    fn done(mut self) -> Option<(Finish, Vec<Sample>)> {
        (self.f.points > 0).then(|| {
            self.f.rms_mm = (self.squares / self.f.points as f64).sqrt();
            (self.f, self.samples)
        })
    }
}

/// The build direction of a plan laid along a tilted one (`direction =
/// auto`: every layer's frame z the same, not vertical).
fn tilted(program: &Program) -> Option<[f64; 3]> {
    let d = program.layers.first()?.frame.z;
    (d != [0.0, 0.0, 1.0]).then_some(d)
}

/// The way between the part and the frame a fill was planned in: none
/// for a vertical fill, else its build direction turned up.
#[derive(Default)]
struct Turn {
    frame: Option<TurnedFrame>,
}

impl Turn {
    /// `p` (mm, or a direction) of the part in the planning frame.
    fn planned(&self, p: [f64; 3]) -> [f64; 3] {
        match &self.frame {
            Some(f) => f.planned(p),
            None => p,
        }
    }

    /// The part's point at `p` of the planning frame.
    fn back(&self, p: [f64; 3]) -> [f64; 3] {
        self.frame.as_ref().map_or(p, |f| f.point(p))
    }
}

/// The first layer's least and greatest thickness along its laser-on
/// moves (both ends of each).
fn first_layer(layer: &Layer) -> Option<[f64; 2]> {
    let hs = layer
        .paths
        .iter()
        .flat_map(|p| p.points.windows(2))
        .filter(|w| w[0].laser_on)
        .flat_map(|w| [w[0].layer_height, w[1].layer_height])
        .map(f64::from);
    let (lo, hi) = hs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), h| {
        (a.min(h), b.max(h))
    });
    (lo <= hi).then_some([lo, hi])
}

/// The top the file asks for and the base the layers start on.
struct Target<'m> {
    ex: &'m TopExtrusion,
    bounds: [[f64; 2]; 2],
    heights: Option<crate::sema::TopHeights<'m>>,
}

impl<'m> Target<'m> {
    fn new(ex: &'m TopExtrusion) -> Option<Self> {
        let bounds = profile(&ex.shape, CHORD).bounds()?;
        let heights = match &ex.top {
            Top::Expr(e) => Some(e.evaluator()),
            _ => None,
        };
        Some(Target {
            ex,
            bounds,
            heights,
        })
    }

    fn at(&mut self, p: [f64; 2]) -> Option<f64> {
        if let Some(h) = self.ex.top.mesh_at(p) {
            return h;
        }
        match &mut self.heights {
            Some(h) => h.at(p[0], p[1], &mut Diagnostics::new()).map(|l| l.0),
            None => linear_top(self.ex, self.bounds, p),
        }
    }

    fn base(&self, p: [f64; 2]) -> Option<f64> {
        match &self.ex.base {
            Some(b) => b.surface.at(p),
            None => Some(0.0),
        }
    }
}
