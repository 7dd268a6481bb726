//! `lmd::collision`: the machine's head ([`crate::collision::head`]) keeps its
//! gap from the plate, the fixtures and the part as it grows, at every pose
//! of the plan (docs/collision.md).
//!
//! The plan is followed move by move. The part grows behind it: each
//! deposit move lays its bead as lumps ([`crate::collision::material`])
//! once the head has passed over it. A pose is *checked*: the plate by the
//! head's lowest point, the material first by the plane through the nozzle's
//! tip square to the beam (everything below it, by the groups' bounds: the
//! head is clear) and else lump by lump near the head. A checked pose
//! certifies every pose within its distance less the gap of it (the head
//! cannot have moved further), so the plan is checked again only where it
//! has moved that far: on a long move, at poses along it, and never less
//! than every 0.5 mm where it comes close. A bead laid after the check
//! shortens the certified distance by its own.

mod fixed;
mod moved;
mod narrow;

use super::approach::Approach;
use super::rule::{MachineCx, PlanRule};
use crate::collision::head::{add, cross, dist, dot, scale, sub, HeadShape, Pose};
use crate::collision::material::{Lump, Material};
use crate::diag::message::collision as says;
use crate::diag::{Diagnostics, Worst};
use crate::ir::{Fixture, FixtureShape, Kinematics, Machine, Point, Program};
use crate::plan::{Move, MoveKind, Visit, Where};

/// How far a check looks for material, mm: beyond it the head is clear by
/// at least this.
const CAP_MM: f64 = 8.0;
/// The least a check moves on where the head comes close, mm.
const MIN_STEP_MM: f64 = 0.5;
/// Beads are laid as lumps this far apart along their path, mm (each
/// standing for the stretch behind it).
const BEAD_STEP_MM: f64 = 1.5;
/// Fixtures' surfaces are sampled this far apart, mm.
const FIXTURE_STEP_MM: f64 = 2.0;
/// A bead's width where the program has none (a ring's), mm.
const DEFAULT_WIDTH_MM: f64 = 3.0;

/// What the head came too close to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Obstacle {
    /// The plate, the part's `z = 0`.
    Plate,
    /// A fixture, by index.
    Fixture(usize),
    /// The part laid so far, in this layer (from 0).
    Part(usize),
}

/// Where the head came closest: the move, the body and what it hit.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Close {
    pub at: Where,
    pub body: usize,
    pub what: Obstacle,
}

impl std::fmt::Display for Close {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.at)
    }
}

/// The rule over one machine's plan.
pub(super) struct Collision<'p> {
    program: &'p Program,
    head: HeadShape,
    standoff: f64,
    /// A 3-axis CNC's nozzle points straight down whatever the normal.
    vertical: bool,
    /// Its plan meets a tilted layer (refused by `lmd::needs-tilt`): not
    /// followed further.
    tilted: bool,
    material: Material,
    /// The last checked pose and how far it is from everything, mm.
    cert: Option<(Pose, f64)>,
    /// The head's lowest point along its beam at that pose (`x·up`).
    low: f64,
    /// The last pose a move ended at, and the head's lowest points there
    /// along Z and along its beam.
    lows: Option<(Pose, (f64, f64))>,
    /// The material's bound along a beam direction (cached: most moves keep
    /// their direction).
    support: Option<([f64; 3], f64)>,
    last: Option<Pose>,
    layer: usize,
    /// The deposits so far, as runs `[layer, path, first, last]` of
    /// points, until the grid is built ([`Collision::index`]).
    runs: Vec<[u32; 4]>,
    /// Whether the grid is built (the first pose the plane does not clear).
    indexed: bool,
    /// The IR point whose bead end was bounded last.
    bounded: Option<Where>,
    width: f64,
    /// The worst by obstacle kind: the plate, fixtures, the part.
    worst: [Option<Worst<Close>>; 3],
    /// By obstacle kind, how much higher up its beam the head must sit to
    /// keep its gap at every pose found too close; `None` once one pose is
    /// not helped by that (material beside the head).
    raise: [Option<f64>; 3],
    /// By body, how much its radii must shrink (the factor) to keep its
    /// gap from the part at every pose found too close; `None` once a pose
    /// is not helped by that (the part along its axis).
    narrow: Vec<Option<f64>>,
    /// The closest each body came to each obstacle, by
    /// [`Collision::slot`]: the distance, the move, how far along it, the
    /// focus.
    closest: Vec<Option<Nearest>>,
    /// Which fixtures a pose came within the gap of.
    fixture_hit: Vec<bool>,
    /// The box round every focus of the plan, seen from above (least and
    /// greatest X and Y), and the least `|up_z|` of its beams: how far the
    /// head reaches sideways ([`Collision::moved`]).
    extent: Extent,
    /// The one fixture checked, in a probe ([`Collision::against`]).
    only: Option<usize>,
    /// The fixtures fixed to the machine, checked in its coordinates: on
    /// its base, and on its tilt axis's body.
    fixed: Vec<fixed::Fixed>,
}

/// A closest approach: the distance, the move, how far along it, the focus.
type Nearest = (f64, Where, f64, [f64; 3]);

impl<'p> PlanRule<'p> for Collision<'p> {
    fn new(cx: &MachineCx<'p>) -> Option<Self> {
        Self::against(cx, None)
    }

    fn report(self, cx: &MachineCx<'p>, out: &mut Diagnostics) {
        let declared = cx.origin.written(crate::ir::MachineField::Head);
        for (w, raise) in self
            .worst
            .iter()
            .zip(self.raise)
            .filter_map(|(w, r)| Some((w.as_ref()?, r)))
        {
            let with = match w.at.what {
                Obstacle::Plate => says::With::Plate,
                Obstacle::Fixture(i) => match &self.program.fixtures[i] {
                    f if f.is_scan() => says::With::Scan,
                    f => says::With::Fixture(&f.name),
                },
                Obstacle::Part(l) => says::With::Part(l + 1),
            };
            let placed = match w.at.what {
                Obstacle::Fixture(i) => self.program.origins.fixtures.get(i).copied(),
                _ => None,
            };
            let moved = match w.at.what {
                // The part built on stays where it is.
                Obstacle::Fixture(i) if self.program.fixtures[i].is_scan() => None,
                Obstacle::Fixture(i) => self.moved(cx, i),
                _ => None,
            };
            out.push(says::collision(&says::Hit {
                machine: cx.machine.name(),
                body: &self.head.names[w.at.body],
                with,
                worst: w,
                standoff: raise.map(|r| self.standoff + r),
                declared,
                placed,
                moved,
                narrower: match w.at.what {
                    Obstacle::Part(_) => self.narrowed(cx, w.at.body),
                    _ => None,
                },
            }));
        }
    }
}

impl<'p> Collision<'p> {
    /// The rule for `cx`'s machine; with `only`, against that fixture alone
    /// (no other fixture, no part laid): what a probe of where to move it
    /// asks ([`moved`]), which another obstacle nearer the head would hide.
    fn against(cx: &MachineCx<'p>, only: Option<usize>) -> Option<Self> {
        let common = cx.machine.common();
        let vertical = match cx.machine {
            Machine::Cnc(c) => c.effective_kinematics() == Kinematics::Xyz,
            Machine::Robot(_) => false,
        };
        let name = cx.machine.name();
        let mut material = Material::default();
        for (i, f) in cx.program.fixtures.iter().enumerate() {
            if f.fixed_to(name) == Some(false) && only.is_none_or(|o| o == i) {
                fixture_lumps(f, i, &mut material);
            }
        }
        let frame = crate::plan::part_frame::PartFrame::of(cx.machine);
        let fixed = [false, true]
            .into_iter()
            .filter_map(|tilts| fixed::Fixed::new(cx.program, name, (frame.clone(), tilts), only))
            .collect();
        let width = cx
            .program
            .bead
            .as_ref()
            .map_or(DEFAULT_WIDTH_MM, |b| b.width);
        Some(Collision {
            program: cx.program,
            head: HeadShape::of(&common.head),
            standoff: common.head.standoff,
            vertical,
            tilted: false,
            material,
            cert: None,
            low: 0.0,
            lows: None,
            support: None,
            last: None,
            layer: 0,
            runs: Vec::new(),
            indexed: false,
            bounded: None,
            width,
            worst: [None, None, None],
            raise: [Some(0.0); 3],
            narrow: vec![Some(1.0); common.head.bodies.len()],
            closest: vec![None; common.head.bodies.len() * (cx.program.fixtures.len() + 2)],
            fixture_hit: vec![false; cx.program.fixtures.len()],
            extent: ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2], 1.0),
            only,
            fixed,
        })
    }
}

impl Visit for Collision<'_> {
    fn layer(&mut self, index: usize, _layer: &crate::ir::Layer) {
        self.layer = index;
    }

    fn motion(&mut self, m: &Move) {
        if m.kind == MoveKind::Home || self.tilted {
            // Back home by PTP: the axes' path, not a pose of the plan.
            return;
        }
        if self.vertical && m.normal[2] < 1.0 - 1e-6 {
            // Layers a 3-axis machine cannot follow: `lmd::needs-tilt`
            // refuses the plan, whose poses mean nothing.
            self.tilted = true;
            self.worst = [None, None, None];
            self.closest.fill(None);
            return;
        }
        let pose = Pose {
            focus: m.to,
            up: self.up(m.normal),
        };
        widen(&mut self.extent, &pose);
        match self.last.filter(|_| !m.kind.ptp()) {
            Some(from) => self.sweep(from, pose, m.at),
            None => self.check(&pose, (m.at, 1.0)),
        }
        // The plate's distance is linear along a move that keeps its beam:
        // its ends give the closest approach.
        if let Some((plate, body)) = self.head.lowest(&pose, [0.0, 0.0, 1.0]) {
            self.near(body, Obstacle::Plate, plate, (m.at, 1.0, pose.focus));
        }
        self.last = Some(pose);
        self.follow_fixed(m, pose);
        if m.deposits() && self.only.is_none() {
            self.lay(m);
        }
    }
}

impl Collision<'_> {
    /// Follows the head along move `m` (to `pose`) against the fixtures
    /// fixed to the machine, where it has any.
    fn follow_fixed(&mut self, m: &Move, pose: Pose) {
        let mut found = Vec::new();
        for fixed in &mut self.fixed {
            fixed.follow(&self.head, (pose, m.axes), m.kind.ptp(), &mut found);
        }
        for f in found {
            let what = self.obstacle(&f.lump);
            self.near(f.body, what, f.d, (m.at, f.way, f.focus));
            if f.d < self.head.gap {
                self.hit(f.d, f.body, f.lump, (&f.pose, m.at));
            }
        }
    }

    fn up(&self, normal: [f32; 3]) -> [f64; 3] {
        if self.vertical {
            return [0.0, 0.0, 1.0];
        }
        let n = normal.map(f64::from);
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        n.map(|c| c / len)
    }

    /// Follows the head from `a` to `b`, checking it wherever it has moved
    /// as far as its last check certified.
    fn sweep(&mut self, a: Pose, b: Pose, at: Where) {
        if a.up == b.up && self.clear_between(&a, &b) {
            return;
        }
        let rate = a.moved(&b, self.head.reach);
        if rate <= 0.0 {
            if self.cert.is_none() {
                self.check(&b, (at, 1.0));
            }
            return;
        }
        let gap = self.head.gap;
        let mut t = 0.0;
        loop {
            let margin = match self.cert {
                Some((p, d)) => {
                    let here = lerp(&a, &b, t);
                    if p.moved(&b, self.head.reach)
                        .max(p.moved(&here, self.head.reach))
                        <= d - gap
                    {
                        return;
                    }
                    (d - gap - p.moved(&here, self.head.reach)).max(MIN_STEP_MM)
                }
                None => 0.0,
            };
            t = (t + margin / rate).min(1.0);
            if t >= 1.0
                && self
                    .cert
                    .is_some_and(|(p, _)| p.moved(&b, self.head.reach) < MIN_STEP_MM)
            {
                // The move ends within a step of the last check: a path of
                // points closer than that is checked against the material
                // every step, not at every point (the plate, at every one).
                self.check_plate(&b, (at, t));
                return;
            }
            self.check(&lerp(&a, &b, t), (at, t));
            if t >= 1.0 {
                return;
            }
        }
    }

    /// Whether the head, its beam the same at `a` and `b`, keeps its gap
    /// all the way between them by the plane through its tip and the
    /// plate (both linear along the move: their least is at an end); if
    /// so, `b` is certified.
    fn clear_between(&mut self, a: &Pose, b: &Pose) -> bool {
        let up = b.up;
        let z = [0.0, 0.0, 1.0];
        // The last move ended at `a`: its lows are known.
        let (pa, la) = match self.lows {
            Some((p, lows)) if p == *a => lows,
            _ => (self.head.lowest_along(a, z), self.head.lowest_along(a, up)),
        };
        let lows_b = (self.head.lowest_along(b, z), self.head.lowest_along(b, up));
        self.lows = Some((*b, lows_b));
        let plate = pa.min(lows_b.0);
        let low = la.min(lows_b.1);
        let clear = if self.material.is_empty() {
            f64::INFINITY
        } else {
            low - self.highest(up)
        };
        let d = plate.min(clear);
        if d < self.head.gap {
            return false;
        }
        self.cert = Some((*b, d));
        self.low = lows_b.1;
        true
    }

    /// Checks the head at `pose` against everything, recording what it
    /// comes within its gap of, and certifies the pose.
    fn check(&mut self, pose: &Pose, (at, way): (Where, f64)) {
        let gap = self.head.gap;
        let mut d = self.check_plate(pose, (at, way));
        let low = self.head.lowest_along(pose, pose.up);
        if !self.material.is_empty() {
            let mut clear = low - self.highest(pose.up);
            if clear < gap {
                // Groups beyond the cap from every point of the head
                // (within its reach of the focus) are at least that far.
                let far = self.head.reach + CAP_MM;
                let near = self.material.highest_near(pose.up, pose.focus, far);
                clear = (low - near).min(CAP_MM);
            }
            if clear >= gap {
                // Everything lies below the plane through the tip.
                d = d.min(clear);
            } else {
                self.index();
                match self.material.nearest(&self.head, pose, CAP_MM) {
                    Some((near, body, lump)) => {
                        d = d.min(near);
                        let what = self.obstacle(&lump);
                        self.near(body, what, near, (at, way, pose.focus));
                        if near < gap {
                            self.hit(near, body, lump, (pose, at));
                        }
                    }
                    None => d = d.min(CAP_MM),
                }
            }
        }
        self.cert = Some((*pose, d));
        self.low = low;
    }

    /// Checks the head at `pose` against the plate (its lowest point: a
    /// few operations, so every pose is checked); returns its distance.
    fn check_plate(&mut self, pose: &Pose, (at, way): (Where, f64)) -> f64 {
        let gap = self.head.gap;
        let Some((plate, body)) = self.head.lowest(pose, [0.0, 0.0, 1.0]) else {
            return f64::INFINITY;
        };
        self.near(body, Obstacle::Plate, plate, (at, way, pose.focus));
        if plate < gap {
            let close = Close {
                at,
                body,
                what: Obstacle::Plate,
            };
            Worst::hit(&mut self.worst[0], plate, gap, close);
            // Up the beam by Δ raises the lowest point by Δ·up_z.
            let need = (pose.up[2] > 0.05).then(|| (gap - plate) / pose.up[2]);
            self.raise[0] = self.raise[0].zip(need).map(|(a, b)| a.max(b));
        }
        plate
    }

    /// What a lump is of: a fixture or the part.
    fn obstacle(&self, lump: &Lump) -> Obstacle {
        let fixtures = self.program.fixtures.len() as u32;
        if lump.group >= u32::MAX - fixtures {
            Obstacle::Fixture((u32::MAX - lump.group - 1) as usize)
        } else {
            Obstacle::Part(lump.group as usize)
        }
    }

    /// Where body `body`'s closest approach to `what` is kept.
    fn slot(&self, body: usize, what: Obstacle) -> usize {
        let kinds = self.program.fixtures.len() + 2;
        body * kinds
            + match what {
                Obstacle::Plate => 0,
                Obstacle::Part(_) => 1,
                Obstacle::Fixture(i) => 2 + i,
            }
    }

    /// Keeps `d` as body `body`'s closest approach to `what` where it is.
    fn near(
        &mut self,
        body: usize,
        what: Obstacle,
        d: f64,
        (at, way, focus): (Where, f64, [f64; 3]),
    ) {
        let k = self.slot(body, what);
        if let Some(slot) = self.closest.get_mut(k) {
            if slot.is_none_or(|c| d < c.0) {
                *slot = Some((d, at, way, focus));
            }
        }
    }

    /// The closest approaches found, by body and obstacle.
    pub(super) fn approaches(&self) -> Vec<Approach> {
        let kinds = self.program.fixtures.len() + 2;
        let mut out = Vec::new();
        for (k, c) in self.closest.iter().enumerate() {
            let Some((d, at, way, focus)) = *c else {
                continue;
            };
            let with = match k % kinds {
                0 => "plate".to_string(),
                1 => "part".to_string(),
                i => self.program.fixtures[i - 2].label(),
            };
            out.push(Approach::new(
                (&self.head.names[k / kinds], &with),
                (d, self.head.gap),
                at,
                way,
                focus,
            ));
        }
        out
    }

    fn hit(&mut self, d: f64, body: usize, lump: Lump, (pose, at): (&Pose, Where)) {
        let what = self.obstacle(&lump);
        let slot = if let Obstacle::Fixture(i) = what {
            if let Some(h) = self.fixture_hit.get_mut(i) {
                *h = true;
            }
            1
        } else {
            2
        };
        let close = Close { at, body, what };
        Worst::hit(&mut self.worst[slot], d, self.head.gap, close);
        let need = self.raise_for(pose, &lump);
        self.raise[slot] = self.raise[slot].zip(need).map(|(a, b)| a.max(b));
        if slot == 2 {
            let k = self.narrow_for(pose, &lump, body);
            self.narrow[body] = self.narrow[body].zip(k).map(|(a, b)| a.min(b));
        }
    }

    /// How much body `body`'s radii must shrink (the factor, below 1) for
    /// it to keep its gap from `lump` at `pose`, found by halving to 1/10⁴;
    /// `None` where even its axis does not.
    fn narrow_for(&self, pose: &Pose, lump: &Lump, body: usize) -> Option<f64> {
        let b = self.head.bodies.get(body)?;
        if lump.r <= 0.0 {
            // A cell's box: where in it the material lies is not known.
            return None;
        }
        let v = sub(lump.at, pose.focus);
        let s = dot(v, pose.up);
        let rho = (dot(v, v) - s * s).max(0.0).sqrt();
        let clear = |k: f64| {
            let f = crate::collision::head::Frustum {
                s: b.s,
                r: b.r.map(|r| r * k),
            };
            f.distance(s, rho) - lump.r >= self.head.gap
        };
        if !clear(0.0) {
            return None;
        }
        Some(crate::collision::bisect(0.0, 1.0, 1e-4, clear))
    }

    /// How far up its beam the head at `pose` must sit to keep its gap from
    /// `lump`, where that helps: the lump lies below the nozzle's tip, so
    /// the distance grows as the head rises (found by halving, to 0.01 mm).
    fn raise_for(&self, pose: &Pose, lump: &Lump) -> Option<f64> {
        if lump.r <= 0.0 {
            // A cell's box: where in it the material lies is not known.
            return None;
        }
        let tip = self.head.bodies.first()?.s[0];
        if dot(sub(lump.at, pose.focus), pose.up) >= tip {
            return None;
        }
        let clear = |raise: f64| {
            let p = Pose {
                focus: add(pose.focus, scale(pose.up, raise)),
                up: pose.up,
            };
            self.head.distance_to(&p, lump.at) - lump.r >= self.head.gap
        };
        let mut hi = self.head.gap + lump.r;
        while !clear(hi) {
            hi *= 2.0;
            if hi > 1e4 {
                return None;
            }
        }
        Some(crate::collision::bisect(hi, 0.0, 0.01, clear))
    }

    /// The material's bound along `u`, cached for the direction last asked.
    fn highest(&mut self, u: [f64; 3]) -> f64 {
        match self.support {
            Some((v, h)) if v == u => h,
            _ => {
                let h = self.material.highest(u);
                self.support = Some((u, h));
                h
            }
        }
    }

    /// Bounds material (and puts it in the grid once the grid is built),
    /// keeping the certificate and the cached bound.
    fn add(&mut self, l: Lump, n: [f64; 3], grid: bool) {
        if let Some((v, h)) = self.support.as_mut() {
            *h = h.max(dot(l.at, *v) + l.r);
        }
        if let Some((p, d)) = self.cert.as_mut() {
            // A lump below the plane through the tip by at least the
            // certified distance cannot shorten it (the bead just laid,
            // under the nozzle); else, nor one beyond the head's reach.
            let below = self.low - (dot(l.at, p.up) + l.r);
            let v = sub(l.at, p.focus);
            let near = self.head.reach + *d + l.r;
            if below < *d && dot(v, v) < near * near {
                *d = d.min(self.head.distance_to(p, l.at) - l.r);
            }
        }
        if grid {
            self.material.add(l, n);
        } else {
            self.material.bound(&l, n);
        }
    }

    /// Lays the bead of deposit move `m`: bounded by a sphere round each
    /// end holding its cross-section, and, once the grid is built, put in
    /// it as lumps.
    fn lay(&mut self, m: &Move) {
        let (Some(from), Some(to)) = (m.source().point(self.program), m.at.point(self.program))
        else {
            return;
        };
        let (from, to) = (*from, *to);
        let n = from.normal.map(f64::from);
        let (w, rise) = self.section(&from);
        let r = (w * w + rise * rise).sqrt() / 2.0;
        let group = self.layer as u32;
        // A run's moves share their ends: each bounds its end, the run's
        // first its start too.
        let first = self.bounded != Some(m.source());
        for p in [from.pos, to.pos].into_iter().skip(usize::from(!first)) {
            let at = add(p, scale(n, rise / 2.0));
            self.add(Lump { at, r, group }, n, false);
        }
        self.bounded = Some(m.at);
        if self.indexed {
            self.lumps(&from, &to, group);
        } else if let Where::Point { layer, path, point } = m.at {
            let key = [layer, path, point].map(|k| k as u32);
            match self.runs.last_mut() {
                Some(run) if run[0] == key[0] && run[1] == key[1] && run[3] + 1 == key[2] => {
                    run[3] = key[2];
                }
                _ => self.runs.push([key[0], key[1], key[2], key[2]]),
            }
        }
    }

    /// Builds the grid, once: the bead of every deposit so far as lumps.
    fn index(&mut self) {
        if self.indexed {
            return;
        }
        self.indexed = true;
        let program = self.program;
        for [layer, path, first, last] in std::mem::take(&mut self.runs) {
            let pts = &program.layers[layer as usize].paths[path as usize].points;
            for k in first..=last {
                let (from, to) = (&pts[k as usize - 1], &pts[k as usize]);
                self.lumps(from, to, layer);
            }
        }
    }

    /// A bead's width and height at `p`, mm.
    fn section(&self, p: &Point) -> (f64, f64) {
        (
            self.width.max(f64::from(p.pitch)),
            f64::from(p.rise.max(0.0)),
        )
    }

    /// The lumps of the bead from `from` to `to` in the grid: every
    /// [`BEAD_STEP_MM`] or less, each standing for the stretch behind it,
    /// three across a bead wider than twice its height.
    fn lumps(&mut self, from: &Point, to: &Point, group: u32) {
        let n = from.normal.map(f64::from);
        let (w, rise) = self.section(from);
        let len = dist(from.pos, to.pos);
        let pieces = (len / BEAD_STEP_MM).ceil().max(1.0);
        let along = len / pieces;
        let side = cross(sub(to.pos, from.pos), n);
        let side_len = dot(side, side).sqrt();
        let across: &[f64] = if w / 2.0 <= rise || side_len < 1e-9 {
            &[0.0]
        } else {
            &[-1.0, 0.0, 1.0]
        };
        let part = if across.len() == 1 { w / 2.0 } else { w / 6.0 };
        let r = (along * along + part * part + rise * rise / 4.0).sqrt();
        let side = if side_len > 1e-9 {
            scale(side, w / 3.0 / side_len)
        } else {
            [0.0; 3]
        };
        for k in 1..=pieces as usize {
            let t = k as f64 / pieces;
            let centre = add(lerp3(from.pos, to.pos, t), scale(n, rise / 2.0));
            for &q in across {
                let at = add(centre, scale(side, q));
                self.material.insert(Lump { at, r, group });
            }
        }
    }
}

/// Whether the head keeps its gap from fixture `i` at every pose of `cx`'s
/// machine's plan (made again: its travels rise over the fixture where it
/// stands in `cx`'s program), the fixture alone checked.
pub(super) fn head_clear_of(cx: &MachineCx<'_>, i: usize) -> bool {
    let Some(mut rule) = Collision::against(cx, Some(i)) else {
        return false;
    };
    crate::plan::Plan::new(cx.program, cx.machine).walk(&mut rule);
    !rule.fixture_hit[i]
}

/// The lumps of fixture `f` (index `i`): its surface every
/// [`FIXTURE_STEP_MM`], each lump standing for the patch round it. Groups
/// count down from `u32::MAX`, apart from the layers.
pub(super) fn fixture_lumps(f: &Fixture, i: usize, m: &mut Material) {
    let group = u32::MAX - 1 - i as u32;
    let mut put = |at: [f64; 3], r: f64| m.add(Lump { at, r, group }, [0.0, 0.0, 1.0]);
    let [x0, y0, z0] = f.at;
    match &f.shape {
        FixtureShape::Mesh { samples, .. } => {
            for s in samples.0.iter() {
                put([x0 + s[0], y0 + s[1], z0 + s[2]], s[3]);
            }
        }
        FixtureShape::Box { size } => {
            let half = [size[0] / 2.0, size[1] / 2.0, size[2]];
            let lo = [x0 - half[0], y0 - half[1], z0];
            let hi = [x0 + half[0], y0 + half[1], z0 + half[2]];
            for axis in 0..3 {
                let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
                let (na, nb) = (steps(hi[a] - lo[a]), steps(hi[b] - lo[b]));
                let r =
                    ((hi[a] - lo[a]) / na as f64 / 2.0).hypot((hi[b] - lo[b]) / nb as f64 / 2.0);
                for face in [lo[axis], hi[axis]] {
                    for ia in 0..=na {
                        for ib in 0..=nb {
                            let mut p = [0.0; 3];
                            p[axis] = face;
                            p[a] = lo[a] + (hi[a] - lo[a]) * ia as f64 / na as f64;
                            p[b] = lo[b] + (hi[b] - lo[b]) * ib as f64 / nb as f64;
                            put(p, r);
                        }
                    }
                }
            }
        }
        FixtureShape::Cylinder { diameter, length } => {
            let rad = diameter / 2.0;
            let (diameter, length) = (*diameter, *length);
            let around = steps(std::f64::consts::PI * diameter).max(8);
            let up = steps(length);
            let radial = steps(rad);
            let arc = std::f64::consts::PI * diameter / around as f64;
            let r = (arc / 2.0)
                .hypot(length / up as f64 / 2.0)
                .max((rad / radial as f64 / 2.0).hypot(arc / 2.0));
            for k in 0..around {
                let a = k as f64 / around as f64 * std::f64::consts::TAU;
                let (s, c) = a.sin_cos();
                for h in 0..=up {
                    put(
                        [
                            x0 + rad * c,
                            y0 + rad * s,
                            z0 + length * h as f64 / up as f64,
                        ],
                        r,
                    );
                }
                for q in 0..radial {
                    let rr = rad * q as f64 / radial as f64;
                    for z in [z0, z0 + length] {
                        put([x0 + rr * c, y0 + rr * s, z], r);
                    }
                }
            }
        }
    }
}

/// How many pieces of at most [`FIXTURE_STEP_MM`] a length takes.
fn steps(len: f64) -> usize {
    ((len / FIXTURE_STEP_MM).ceil() as usize).clamp(1, 10_000)
}

/// The box round every focus seen from above, and the least `|up_z|` of
/// the beams: how far a plan's head reaches sideways.
type Extent = ([f64; 2], [f64; 2], f64);

/// Takes the head at `pose` into `extent`.
fn widen(extent: &mut Extent, pose: &Pose) {
    let (lo, hi, up_z) = extent;
    for k in 0..2 {
        lo[k] = lo[k].min(pose.focus[k]);
        hi[k] = hi[k].max(pose.focus[k]);
    }
    *up_z = up_z.min(pose.up[2].abs());
}

fn lerp(a: &Pose, b: &Pose, t: f64) -> Pose {
    if a.up == b.up {
        // The same beam: the same bits, which the cached bound is keyed by.
        return Pose {
            focus: lerp3(a.focus, b.focus, t),
            up: a.up,
        };
    }
    let up = lerp3(a.up, b.up, t);
    let len = dot(up, up).sqrt();
    Pose {
        focus: lerp3(a.focus, b.focus, t),
        up: if len > 1e-12 {
            scale(up, 1.0 / len)
        } else {
            b.up
        },
    }
}

fn lerp3(a: [f64; 3], b: [f64; 3], t: f64) -> [f64; 3] {
    [
        a[0] + t * (b[0] - a[0]),
        a[1] + t * (b[1] - a[1]),
        a[2] + t * (b[2] - a[2]),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diag::Code;
    use crate::ir::MachineOrigin;
    use crate::plan::Speed;

    /// A travel made straight across the post of the case
    /// `collision/travel_over_post` at the ring's top plus the clearance —
    /// as the plan made it before it went over what is there — is found by
    /// the rule, whatever made it.
    #[test]
    fn a_travel_through_a_fixture_is_found_along_the_move() {
        let src =
            std::fs::read_to_string("tests/cases/collision/travel_over_post/input.lmd").unwrap();
        let c = crate::pipeline::compile(&src, &mut ());
        let v = c.program.expect("builds");
        let program = v.ir();
        let origin = MachineOrigin::default();
        let cx = MachineCx {
            program,
            machine: &program.machines[0],
            origin: &origin,
        };
        let mut rule = Collision::new(&cx).unwrap();
        let travel = |x: f64| Move {
            kind: MoveKind::Travel,
            to: [x, 0.0, 11.0],
            normal: [0.0, 0.0, 1.0],
            axes: Default::default(),
            speed: Speed::Rapid,
            power: 0.0,
            at: Where::Clearance { layer: 1, path: 2 },
        };
        let mut out = Diagnostics::new();
        let mut beside = Collision::new(&cx).unwrap();
        beside.motion(&travel(-45.0));
        beside.report(&cx, &mut out);
        assert!(out.is_empty(), "beside the post: clear");
        // Both ends clear of it, the middle through it.
        rule.motion(&travel(-45.0));
        rule.motion(&travel(45.0));
        rule.report(&cx, &mut out);
        let d: Vec<_> = out.iter().filter(|d| d.code == Code::Collision).collect();
        assert_eq!(d.len(), 1, "{out:?}");
        assert!(
            d[0].message.contains("runs into fixture `post`"),
            "{}",
            d[0].message
        );
        assert!(
            d[0].message
                .contains("the clearance move before layer 2, path 3"),
            "{}",
            d[0].message
        );
    }
}
