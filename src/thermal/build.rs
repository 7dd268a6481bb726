//! The part as it is built: a fin of layer nodes per island (a *column*)
//! standing on a shared plate of rings (docs/thermal.md, *The model*).
//!
//! One island makes one chain of nodes, solved by the Thomas algorithm.
//! Several islands make a tree rooted at the plate: the plate's outer
//! rings are shared; a column that stands on the plate stands on its own
//! first ring (its *foot*, its share of the plate within half the plate's
//! thickness of the islands); a column of an island that split off stands
//! on the top node of the column it split from. A tree is solved in linear
//! time too: each column is eliminated from its top down onto what it
//! stands on (the columns last made first, so a column's children are
//! folded into its top before it is eliminated), the rings' chain is
//! solved, and the columns are filled back from their bottoms up.
//!
//! A column of islands that merged stands on the tops of several columns:
//! on the first as in a tree, on the others by *joins*, which close cycles
//! through the plate. Such a graph is solved by conjugate gradients with
//! the tree's solve (the joins left out) as the preconditioner
//! ([`super::cg`]).

use super::{
    Load, Material, Node, Plate, COARSENING, DEPOSIT_STEP, FIRST_STEP, MAX_DEPOSIT_STEPS,
    STEP_GROWTH,
};
use std::f64::consts::PI;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// Where a column of islands stands.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stand {
    /// On the plate: on its own foot, a share of the plate's first ring.
    Plate,
    /// On the top node of column `c` (made before it): an island that
    /// split off the island below, or of islands that merged, the first
    /// of the columns they stand on (the others are its joins).
    On(usize),
}

/// A merged column's link to a column it stands on besides its [`Stand`].
#[derive(Clone, Copy, Debug)]
struct Join {
    /// The column stood on (made before the merged one).
    parent: usize,
    /// The merged column's share of that column's top, by footprint.
    share: f64,
    /// The conductance between that top and the merged column's first
    /// layer, W/K (0 until that is laid).
    g: f64,
}

/// The part as it is built: the plate's shared rings, then one column per
/// island, each (standing on the plate) its foot ring and its fin's nodes
/// from the bottom up, or (standing on a column) its fin's nodes.
#[derive(Clone, Debug)]
pub struct Build {
    material: Material,
    plate: Plate,
    /// The plate's rings every column shares, from the outermost in.
    shared: Vec<Node>,
    /// Each island's column: its foot ring (on the plate), then its fin's
    /// nodes.
    columns: Vec<Vec<Node>>,
    /// Where each column stands.
    stands: Vec<Stand>,
    /// The conductance into each column's lowest node from what it stands
    /// on, W/K: the innermost shared ring into its foot; the top of the
    /// column below into its first layer (0 until that is laid).
    below: Vec<f64>,
    /// Each column's share of what it stands on, by footprint.
    shares: Vec<f64>,
    /// The area a column's first layer covers on its foot, m²: its foot's
    /// top loses heat from it too until that layer is laid.
    bare: Vec<f64>,
    /// Whether a column carries others on its top (whose face is then
    /// covered).
    carries: Vec<bool>,
    /// Each column's joins: the tops it stands on besides `stands`' (a
    /// column of islands that merged; empty for every other).
    joins: Vec<Vec<Join>>,
    /// Set where a step's conjugate gradients did not converge; shared by
    /// the clones a prediction tries its levers on, so that the prediction
    /// knows to fall back to one column.
    unsolved: Arc<AtomicBool>,
}

impl Build {
    /// A plate at its start temperature, nothing on it yet.
    pub fn new(material: Material, plate: Plate) -> Build {
        Build {
            material,
            plate,
            shared: Vec::new(),
            columns: Vec::new(),
            stands: Vec::new(),
            below: Vec::new(),
            shares: Vec::new(),
            bare: Vec::new(),
            carries: Vec::new(),
            joins: Vec::new(),
            unsolved: Arc::new(AtomicBool::new(false)),
        }
    }

    /// Whether every step so far was solved to its tolerance (a step of a
    /// graph of merged columns whose conjugate gradients did not converge
    /// was not), in this build or any clone of it.
    pub fn solved(&self) -> bool {
        !self.unsolved.load(Ordering::Relaxed)
    }

    /// The temperature of the top of the part, where the next layer goes,
    /// °C: the top of the first column (the part's, with one island), or
    /// the plate's under the first layer.
    pub fn top(&self) -> f64 {
        self.top_of(0)
    }

    /// The temperature of the top of island `c`'s column, °C: its top
    /// layer's, or before its first layer what it stands on: its foot, or
    /// the top of the column it split from.
    pub fn top_of(&self, c: usize) -> f64 {
        match self.columns.get(c) {
            Some(col) if col.is_empty() && !self.joins[c].is_empty() => self.merged_top(c),
            _ => self.tree_top(c),
        }
    }

    /// [`Build::top_of`] following each column's [`Stand`] alone.
    fn tree_top(&self, c: usize) -> f64 {
        let mut c = c;
        // A column made before its parent's first layer has none: the
        // parents are earlier columns, so this ends.
        loop {
            match self.columns.get(c) {
                Some(col) if !col.is_empty() => return col[col.len() - 1].t,
                Some(_) => match self.stands[c] {
                    Stand::On(p) if p < c => c = p,
                    _ => return self.plate.temperature,
                },
                None => return self.plate.temperature,
            }
        }
    }

    /// The top of a merged column before its first layer: the mean of the
    /// tops it stands on, each weighted by the area its first layer will
    /// be joined to it by ([`Build::tops_under`]).
    fn merged_top(&self, c: usize) -> f64 {
        let tops = self.tops_under(c);
        let total: f64 = tops.iter().map(|(_, n)| n.footprint).sum();
        if total.is_nan() || total <= 0.0 {
            return self.tree_top(c);
        }
        tops.iter().map(|(_, n)| n.footprint / total * n.t).sum()
    }

    /// The tops column `c` stands on that have a layer, each as the part
    /// of it `c` takes (its footprint times `c`'s share of it), with the
    /// column: its [`Stand`]'s first, then its joins'.
    fn tops_under(&self, c: usize) -> Vec<(usize, Node)> {
        let part = |p: usize, share: f64| {
            self.columns[p].last().map(|top| {
                let part = Node {
                    footprint: top.footprint * share,
                    ..*top
                };
                (p, part)
            })
        };
        let first = match self.stands[c] {
            Stand::On(p) => part(p, self.shares[c]),
            Stand::Plate => None,
        };
        first
            .into_iter()
            .chain(self.joins[c].iter().filter_map(|j| part(j.parent, j.share)))
            .collect()
    }

    /// How many nodes the model has (the cost of a step).
    pub fn nodes(&self) -> usize {
        self.shared.len() + self.columns.iter().map(Vec::len).sum::<usize>()
    }

    /// How many islands' columns the model has (0 before the first layer).
    pub fn columns(&self) -> usize {
        self.columns.len()
    }

    /// Lays a layer of one island (the whole part's): see
    /// [`Build::lay_on`].
    pub fn lay(&mut self, load: &Load) -> f64 {
        if self.columns.is_empty() && load.valid() {
            self.stand(std::slice::from_ref(load));
        }
        self.lay_on(0, load)
    }

    /// Sets up the plate under the first layer's islands, one column each
    /// standing on the plate (their loads give their footprints): see
    /// [`Build::plant`].
    pub fn stand(&mut self, firsts: &[Load]) {
        self.plant(&vec![Stand::Plate; firsts.len()], firsts);
    }

    /// Sets up every column the build will have: column `c` stands where
    /// `stands[c]` says, and `firsts[c]` is its first layer (its footprint
    /// and outline). The plate's rings are about every column that ever
    /// stands on it, each foot its share of the first ring by its first
    /// layer's footprint, fixed from the start (a column that appears
    /// later has its foot from the start, bare until it is laid on); a
    /// column that splits off another takes its share of that column's
    /// top by its footprint among the columns that split off it. Nothing
    /// if already set up, or a column lays no metal, or none stands on the
    /// plate; a column said to stand on a later one stands on the plate.
    pub fn plant(&mut self, stands: &[Stand], firsts: &[Load]) {
        self.plant_merged(stands, &[], firsts);
    }

    /// [`Build::plant`] with islands that merge: each `(c, p)` of `joins`
    /// says that column `c`, standing on a column's top, stands on column
    /// `p`'s top too (`p` made before `c`, not `c`'s [`Stand`]; others are
    /// left out). A column's share of each top it stands on is by its
    /// footprint among every column that stands on that top.
    pub fn plant_merged(&mut self, stands: &[Stand], joins: &[(usize, usize)], firsts: &[Load]) {
        if !self.columns.is_empty() || stands.len() != firsts.len() || firsts.is_empty() {
            return;
        }
        if !firsts.iter().all(Load::valid) {
            return;
        }
        let stands: Vec<Stand> = (0..stands.len())
            .map(|c| match stands[c] {
                Stand::On(p) if p < c => Stand::On(p),
                _ => Stand::Plate,
            })
            .collect();
        let mut joins: Vec<(usize, usize)> = joins
            .iter()
            .copied()
            .filter(|&(c, p)| matches!(stands.get(c), Some(Stand::On(q)) if *q != p && p < c))
            .collect();
        joins.sort_unstable();
        joins.dedup();
        let on_plate: Vec<Load> = firsts
            .iter()
            .zip(&stands)
            .filter(|(_, s)| **s == Stand::Plate)
            .map(|(l, _)| *l)
            .collect();
        let (foot, into) = self.plate_rings(&on_plate);
        let plate_area: f64 = on_plate.iter().map(Load::footprint).sum();
        // Each parent's children's footprints together.
        let mut children = vec![0.0; stands.len()];
        for (s, l) in stands.iter().zip(firsts) {
            if let Stand::On(p) = s {
                children[*p] += l.footprint();
            }
        }
        for &(c, p) in &joins {
            children[p] += firsts[c].footprint();
        }
        for (s, l) in stands.iter().zip(firsts) {
            let (col, below, share) = match s {
                Stand::Plate => {
                    // All of the ring for one island: `a/a` is exactly 1.
                    let share = l.footprint() / plate_area;
                    let foot = Node {
                        capacity: foot.capacity * share,
                        surface: foot.surface * share,
                        footprint: foot.footprint * share,
                        // Joined to a layer when the island's first is laid.
                        up: 0.0,
                        ..foot
                    };
                    (vec![foot], into * share, share)
                }
                Stand::On(p) => (Vec::new(), 0.0, l.footprint() / children[*p]),
            };
            self.columns.push(col);
            self.below.push(below);
            self.shares.push(share);
            self.bare.push(if *s == Stand::Plate {
                l.footprint()
            } else {
                0.0
            });
        }
        self.joins = vec![Vec::new(); stands.len()];
        for (c, p) in joins {
            self.joins[c].push(Join {
                parent: p,
                share: firsts[c].footprint() / children[p],
                g: 0.0,
            });
        }
        self.carries = vec![false; stands.len()];
        self.stands = stands;
    }

    /// Lays island `c`'s part of a layer: it appears at the ambient
    /// temperature on top of the island's column and takes up the laser's
    /// absorbed energy evenly over its time. Returns its temperature when
    /// it is laid (its peak: it cools from then on), °C. A load without
    /// metal, or an island with no column, only lets its time pass.
    pub fn lay_on(&mut self, c: usize, load: &Load) -> f64 {
        if !load.valid() || c >= self.columns.len() {
            self.cool(load.time.max(0.0));
            return self.top_of(c);
        }
        self.push(c, load);
        let steps = ((load.time / DEPOSIT_STEP).ceil() as usize).clamp(1, MAX_DEPOSIT_STEPS);
        let dt = load.time / steps as f64;
        let heat = self.material.absorptivity * load.energy;
        if dt <= 0.0 {
            // Laid at once: the energy lands on the layer as it appears.
            let col = &mut self.columns[c];
            let top = col.len() - 1;
            col[top].t += heat / col[top].capacity;
            return self.top_of(c);
        }
        for _ in 0..steps {
            self.step(dt, heat / load.time, c);
        }
        self.top_of(c)
    }

    /// Cools for `seconds`, nothing laid: steps from [`FIRST_STEP`]
    /// growing by [`STEP_GROWTH`], the last cut to what remains, so that a
    /// longer cooling repeats a shorter one's steps (the temperature it
    /// predicts never rises with the time allowed, and
    /// [`Build::cooling_to`]'s answer is what this cools to).
    pub fn cool(&mut self, seconds: f64) {
        let mut left = seconds;
        let mut dt = FIRST_STEP;
        while left > 0.0 {
            let d = left.min(dt);
            self.step(d, 0.0, 0);
            left -= d;
            dt *= STEP_GROWTH;
        }
    }

    /// The least cooling, s, after which the top of the first column is at
    /// most `limit` °C, if one of at most `longest` s is: see
    /// [`Build::cooling_of`].
    pub fn cooling_to(&self, limit: f64, longest: f64) -> Option<f64> {
        self.cooling_of(0, limit, longest)
    }

    /// The least cooling, s, after which the top of island `c`'s column is
    /// at most `limit` °C, if one of at most `longest` s is; to a
    /// thousandth of the step it falls in. Leaves `self` untouched.
    pub fn cooling_of(&self, c: usize, limit: f64, longest: f64) -> Option<f64> {
        if self.top_of(c) <= limit {
            return Some(0.0);
        }
        // March the same steps `cool` takes; bisect in the step it crosses
        // in, from the state at its start.
        let (mut at, mut done, mut dt) = (self.clone(), 0.0, FIRST_STEP);
        while done < longest {
            let d = dt.min(longest - done);
            let mut next = at.clone();
            next.step(d, 0.0, 0);
            if next.top_of(c) <= limit {
                let (mut lo, mut hi) = (0.0, d);
                while hi - lo > 1e-3 * d {
                    let mid = 0.5 * (lo + hi);
                    let mut m = at.clone();
                    m.step(mid, 0.0, 0);
                    if m.top_of(c) <= limit {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                return Some(done + hi);
            }
            at = next;
            done += d;
            dt *= STEP_GROWTH;
        }
        None
    }

    /// The plate's rings about the islands standing on it (footprints
    /// `Aᵢ`, outlines `Pᵢ`, `n` of them): the plate within `r` of them has
    /// the area `A(r) = ΣAᵢ + ΣPᵢ·r + n·π·r²` (Steiner, while they are
    /// more than `2r` apart). The feet together reach half the plate's
    /// thickness out (the cone heat spreads down in); the shared rings
    /// each reach twice as far as the last, the outermost to the plate's
    /// area. With one island this is the chain of rings about its
    /// footprint. Sets the shared rings; returns the feet as one ring and
    /// its conductance to the innermost shared ring.
    fn plate_rings(&mut self, firsts: &[Load]) -> (Node, f64) {
        let m = self.material;
        let [lx, ly, thick] = self.plate.size;
        let n = firsts.len() as f64;
        let a0: f64 = firsts.iter().map(Load::footprint).sum();
        let p0: f64 = firsts.iter().map(|l| l.perimeter).sum();
        let area = |r: f64| a0 + p0 * r + n * PI * r * r;
        let outline = |r: f64| p0 + n * 2.0 * PI * r;
        let total = (lx * ly).max(area(thick) * 2.0);
        // The radius at which the area is the plate's.
        let reach = {
            let (a, b, c) = (n * PI, p0, a0 - total);
            (-b + (b * b - 4.0 * a * c).sqrt()) / (2.0 * a)
        };
        let mut radii = vec![0.5 * thick];
        while radii[radii.len() - 1] * 2.0 < reach {
            let r = radii[radii.len() - 1] * 2.0;
            radii.push(r);
        }
        radii.push(reach);
        // Innermost first (the feet, as one), then reversed so the chain
        // runs outside in.
        let mut rings = Vec::with_capacity(radii.len());
        for (j, &r) in radii.iter().enumerate() {
            let inner = if j == 0 { 0.0 } else { radii[j - 1] };
            let plan = area(r) - if j == 0 { 0.0 } else { area(inner) };
            let top = if j == 0 { plan - a0 } else { plan };
            let edge = if j + 1 == radii.len() {
                outline(r) * thick
            } else {
                0.0
            };
            // To the next ring out: across the boundary at `r`, between the
            // two rings' middles.
            let out = radii.get(j + 1).map_or(0.0, |&next| {
                m.conductivity * thick * outline(r) / (0.5 * (next - inner))
            });
            rings.push(Node {
                capacity: m.volumetric() * plan * thick,
                surface: top.max(0.0) + edge,
                t: self.plate.temperature,
                up: out,
                layers: 0,
                height: thick,
                footprint: plan,
            });
        }
        // The chain runs from the outermost ring in: a ring's `up` is the
        // conductance to the next inner one.
        rings.reverse();
        let count = rings.len();
        for i in 0..count - 1 {
            rings[i].up = rings[i + 1].up;
        }
        let feet = rings.pop().expect("at least two rings");
        let into = rings[count - 2].up;
        self.shared = rings;
        (feet, into)
    }

    /// Puts a new layer on top of column `c` at the ambient temperature,
    /// joined to the node below (a column's first layer that split off
    /// another: to that one's top, by its share of it), and merges what
    /// has grown deep.
    fn push(&mut self, c: usize, load: &Load) {
        let m = self.material;
        let layer = Node {
            capacity: m.volumetric() * load.volume,
            surface: load.perimeter * load.height,
            t: self.plate.ambient,
            up: 0.0,
            layers: 1,
            height: load.height,
            footprint: load.footprint(),
        };
        if self.columns[c].is_empty() {
            self.join_first(c, &layer);
        }
        let col = &mut self.columns[c];
        if let Some(below) = col.last_mut() {
            below.up = link(m.conductivity, below, &layer);
        }
        col.push(layer);
        merge(m.conductivity, col);
    }

    /// Joins column `c`'s first layer to the tops it stands on (none on the
    /// plate): each by the part of the top `c` takes and, where it stands
    /// on several (islands that merged), the layer's footprint shared
    /// among them by those parts. A parent without a layer of its own
    /// carries nothing.
    fn join_first(&mut self, c: usize, layer: &Node) {
        let k = self.material.conductivity;
        let tops = self.tops_under(c);
        let total: f64 = tops.iter().map(|(_, n)| n.footprint).sum();
        let merged = !self.joins[c].is_empty();
        for (p, part) in tops {
            let on = if merged {
                Node {
                    footprint: layer.footprint * part.footprint / total,
                    ..*layer
                }
            } else {
                *layer
            };
            let g = link(k, &part, &on);
            if self.stands[c] == Stand::On(p) {
                self.below[c] = g;
            } else if let Some(j) = self.joins[c].iter_mut().find(|j| j.parent == p) {
                j.g = g;
            }
            self.carries[p] = true;
        }
    }

    /// The area node `i` of column `c` loses heat from besides its sides,
    /// m²: a column's top layer its top face (unless it carries others),
    /// a foot not yet laid on the area its island will cover.
    fn face(&self, c: usize, i: usize) -> f64 {
        let col = &self.columns[c];
        let foot = self.stands[c] == Stand::Plate;
        if i + 1 != col.len() {
            0.0
        } else if foot && i == 0 {
            self.bare[c]
        } else if self.carries[c] {
            0.0
        } else {
            col[i].footprint
        }
    }

    /// One implicit Euler step of `dt` s with `power` W into the top of
    /// column `into`: `(C/dt + H + G₋ + G₊)·T' − G₋·T'₋ − G₊·T'₊ = C/dt·T +
    /// H·T∞ + Q`. One column with the shared rings is a chain (the Thomas
    /// algorithm); several are a tree ([`Build::tree_step`]), or with
    /// joins a graph ([`Build::graph_solve`]).
    fn step(&mut self, dt: f64, power: f64, into: usize) {
        if dt <= 0.0 || self.columns.is_empty() {
            return;
        }
        if self.columns.len() > 1 || self.columns[0].len() < 2 {
            let joins = self.join_links();
            if joins.is_empty() {
                self.tree_step(dt, power, into);
            } else {
                let (diag, rhs) = self.system(dt, power, into);
                let t = self.graph_solve(&diag, &rhs, &joins);
                self.set_temperatures(&t);
            }
            return;
        }
        let mut chain = self.shared.clone();
        let last = chain.len() - 1;
        chain[last].up = self.below[0];
        chain.extend_from_slice(&self.columns[0]);
        chain_step(&mut chain, self.material, self.plate.ambient, dt, power);
        for (i, n) in chain.iter().enumerate() {
            if i < self.shared.len() {
                self.shared[i].t = n.t;
            } else {
                self.columns[0][i - self.shared.len()].t = n.t;
            }
        }
    }

    /// Where each column's nodes start in a step's flat vectors: the
    /// shared rings first, then each column from its bottom up.
    fn offsets(&self) -> Vec<usize> {
        let mut at = self.shared.len();
        self.columns
            .iter()
            .map(|col| {
                let o = at;
                at += col.len();
                o
            })
            .collect()
    }

    /// The flat index of column `c`'s top node, if it has one.
    fn top_index(&self, at: &[usize], c: usize) -> Option<usize> {
        let len = self.columns[c].len();
        (len > 0).then(|| at[c] + len - 1)
    }

    /// [`Build::step`]'s system over the tree (the joins left out), flat
    /// ([`Build::offsets`]): each node's diagonal and right-hand side. A
    /// top that carries columns has their conductances on its diagonal;
    /// the innermost shared ring has the feet's.
    fn system(&self, dt: f64, power: f64, into: usize) -> (Vec<f64>, Vec<f64>) {
        let (m, ambient) = (self.material, self.plate.ambient);
        let (mut diag, mut rhs) = (Vec::new(), Vec::new());
        let feet: f64 = (0..self.columns.len())
            .filter(|&c| self.stands[c] == Stand::Plate)
            .map(|c| self.below[c])
            .sum();
        let s = self.shared.len();
        for (i, n) in self.shared.iter().enumerate() {
            let below = if i > 0 { self.shared[i - 1].up } else { 0.0 };
            let up = if i + 1 == s { feet } else { n.up };
            let h = m.loss(n.t, ambient) * n.surface;
            diag.push(n.capacity / dt + h + below + up);
            rhs.push(n.capacity / dt * n.t + h * ambient);
        }
        for (c, col) in self.columns.iter().enumerate() {
            for (i, n) in col.iter().enumerate() {
                let below = if i == 0 { self.below[c] } else { col[i - 1].up };
                let h = m.loss(n.t, ambient) * (n.surface + self.face(c, i));
                diag.push(n.capacity / dt + h + below + n.up);
                rhs.push(n.capacity / dt * n.t + h * ambient);
            }
        }
        let at = self.offsets();
        if let Some(top) = (into < self.columns.len())
            .then(|| self.top_index(&at, into))
            .flatten()
        {
            rhs[top] += power;
        }
        for (c, s) in self.stands.iter().enumerate() {
            if let (Stand::On(p), false) = (s, self.columns[c].is_empty()) {
                if let Some(top) = self.top_index(&at, *p) {
                    diag[top] += self.below[c];
                }
            }
        }
        (diag, rhs)
    }

    /// [`Build::step`] over a tree of columns: [`Build::tree_solve`].
    fn tree_step(&mut self, dt: f64, power: f64, into: usize) {
        let (diag, rhs) = self.system(dt, power, into);
        let t = self.tree_solve(&diag, &rhs);
        self.set_temperatures(&t);
    }

    /// Solves the tree's system with `diag` on its diagonal (flat,
    /// [`Build::offsets`]) and the tree's conductances off it for `rhs`:
    /// each column eliminated from its top down onto what it stands on,
    /// the last made first (a column's children stand on it and are made
    /// after it), the rings solved as a chain, the columns filled back
    /// from their bottoms up, the first made first. Linear in the nodes.
    fn tree_solve(&self, diag: &[f64], rhs: &[f64]) -> Vec<f64> {
        let (mut a, mut r) = (diag.to_vec(), rhs.to_vec());
        let at = self.offsets();
        // Each column from the top down: `a·T = r + g·T_below` folds into
        // the node below as `a₋ −= g²/a`, `r₋ += g·r/a`.
        let (mut diag_j, mut rhs_j) = (0.0, 0.0);
        for c in (0..self.columns.len()).rev() {
            let (col, o) = (&self.columns[c], at[c]);
            for i in (1..col.len()).rev() {
                let g = col[i - 1].up;
                let (ai, ri) = (a[o + i], r[o + i]);
                a[o + i - 1] -= g * g / ai;
                r[o + i - 1] += g * ri / ai;
            }
            if col.is_empty() {
                continue;
            }
            let (a0, r0, g) = (a[o], r[o], self.below[c]);
            match self.stands[c] {
                Stand::Plate => {
                    diag_j -= g * g / a0;
                    rhs_j += g * r0 / a0;
                }
                Stand::On(p) => {
                    if let Some(top) = self.top_index(&at, p) {
                        a[top] -= g * g / a0;
                        r[top] += g * r0 / a0;
                    }
                }
            }
        }
        // The shared rings: a chain whose innermost ring carries the feet.
        let s = self.shared.len();
        a[s - 1] += diag_j;
        r[s - 1] += rhs_j;
        let ups: Vec<f64> = self.shared.iter().map(|n| n.up).collect();
        let mut t = thomas(&a[..s], &mut r[..s], &ups);
        let junction = t[s - 1];
        t.resize(a.len(), 0.0);
        for (c, col) in self.columns.iter().enumerate() {
            let under = match self.stands[c] {
                Stand::Plate => junction,
                Stand::On(p) => self.top_index(&at, p).map_or(junction, |top| t[top]),
            };
            let mut below = (under, self.below[c]);
            for (i, n) in col.iter().enumerate() {
                let k = at[c] + i;
                t[k] = (r[k] + below.1 * below.0) / a[k];
                below = (t[k], n.up);
            }
        }
        t
    }

    /// The joins that carry heat, as `(node, node, conductance)` in the
    /// flat vectors: a merged column's first node and a top it stands on.
    fn join_links(&self) -> Vec<(usize, usize, f64)> {
        let at = self.offsets();
        let mut links = Vec::new();
        for (c, joins) in self.joins.iter().enumerate() {
            let Some(&first) = at.get(c).filter(|_| !self.columns[c].is_empty()) else {
                continue;
            };
            for j in joins.iter().filter(|j| j.g > 0.0) {
                if let Some(top) = self.top_index(&at, j.parent) {
                    links.push((first, top, j.g));
                }
            }
        }
        links
    }

    /// The tree's conductances as `(node, node, conductance)` in the flat
    /// vectors: the rings' chain, the feet, each column's nodes and each
    /// column on the top it stands on.
    fn tree_links(&self) -> Vec<(usize, usize, f64)> {
        let at = self.offsets();
        let s = self.shared.len();
        let mut links: Vec<(usize, usize, f64)> =
            (1..s).map(|i| (i - 1, i, self.shared[i - 1].up)).collect();
        for (c, col) in self.columns.iter().enumerate() {
            if col.is_empty() {
                continue;
            }
            let under = match self.stands[c] {
                Stand::Plate => Some(s - 1),
                Stand::On(p) => self.top_index(&at, p),
            };
            if let Some(u) = under {
                links.push((u, at[c], self.below[c]));
            }
            links.extend((1..col.len()).map(|i| (at[c] + i - 1, at[c] + i, col[i - 1].up)));
        }
        links
    }

    /// Solves [`Build::step`]'s system over a graph: the tree's (`diag`,
    /// `rhs`, [`Build::system`]) with the joins' conductances `joins`
    /// added, by conjugate gradients preconditioned by the tree's solve
    /// ([`super::cg`]). Where they do not converge, the build is marked
    /// unsolved ([`Build::solved`]) and the last iterate kept.
    fn graph_solve(&self, diag: &[f64], rhs: &[f64], joins: &[(usize, usize, f64)]) -> Vec<f64> {
        let mut full = diag.to_vec();
        for &(i, j, g) in joins {
            full[i] += g;
            full[j] += g;
        }
        let mut links = self.tree_links();
        links.extend_from_slice(joins);
        let apply = |x: &[f64]| {
            let mut y: Vec<f64> = full.iter().zip(x).map(|(d, x)| d * x).collect();
            for &(i, j, g) in &links {
                y[i] -= g * x[j];
                y[j] -= g * x[i];
            }
            y
        };
        let (t, converged) = super::cg::solve(rhs, |r| self.tree_solve(diag, r), apply);
        if !converged {
            self.unsolved.store(true, Ordering::Relaxed);
        }
        t
    }

    /// Sets every node's temperature from the flat vector `t`.
    fn set_temperatures(&mut self, t: &[f64]) {
        let nodes = self
            .shared
            .iter_mut()
            .chain(self.columns.iter_mut().flatten());
        for (n, t) in nodes.zip(t) {
            n.t = *t;
        }
    }
}

/// Conductance from `below` (a plate ring, or a fin node) up into `above`,
/// W/K: their half-heights in series, the ring's down from its top through
/// the cone under the footprint.
fn link(k: f64, n: &Node, above: &Node) -> f64 {
    let lower = if n.layers == 0 {
        0.5 * n.height / (k * 0.5 * (above.footprint + n.footprint))
    } else {
        0.5 * n.height / (k * n.footprint)
    };
    1.0 / (lower + 0.5 * above.height / (k * above.footprint))
}

/// Merges neighbouring fin nodes of a column (its foot ring first) whose
/// layers together are at most a [`COARSENING`]th of their depth below
/// the top: energy kept, the temperature the mean weighted by heat
/// capacity.
fn merge(k: f64, col: &mut Vec<Node>) {
    let mut depth = 0u32; // layers above node i
    let mut i = col.len() - 1;
    while i > 2 {
        depth += col[i].layers;
        let (a, b) = (col[i - 2], col[i - 1]);
        // Node i−1 lies under `depth` layers; merge it with the one below.
        if (a.layers + b.layers) * COARSENING <= depth {
            let capacity = a.capacity + b.capacity;
            let height = a.height + b.height;
            let merged = Node {
                capacity,
                surface: a.surface + b.surface,
                t: (a.t * a.capacity + b.t * b.capacity) / capacity,
                up: 0.0,
                layers: a.layers + b.layers,
                height,
                footprint: (a.footprint * a.height + b.footprint * b.height) / height,
            };
            col[i - 2] = merged;
            col.remove(i - 1);
            i -= 1;
            let below = i - 2;
            col[below].up = link(k, &col[below], &col[i - 1]);
            col[i - 1].up = link(k, &col[i - 1], &col[i]);
        }
        i -= 1;
    }
}

/// One implicit Euler step of a chain of nodes (bottom first), `power` W
/// into the top one, which also loses heat from its top face.
fn chain_step(nodes: &mut [Node], m: Material, ambient: f64, dt: f64, power: f64) {
    let n = nodes.len();
    let mut diag = vec![0.0; n];
    let mut rhs = vec![0.0; n];
    for (i, node) in nodes.iter().enumerate() {
        let top = if i + 1 == n { node.footprint } else { 0.0 };
        let h = m.loss(node.t, ambient) * (node.surface + top);
        let below = if i > 0 { nodes[i - 1].up } else { 0.0 };
        diag[i] = node.capacity / dt + h + below + node.up;
        rhs[i] = node.capacity / dt * node.t + h * ambient;
    }
    rhs[n - 1] += power;
    let ups: Vec<f64> = nodes.iter().map(|n| n.up).collect();
    for (node, t) in nodes.iter_mut().zip(thomas(&diag, &mut rhs, &ups)) {
        node.t = t;
    }
}

/// Solves the symmetric tridiagonal system with `diag` and off-diagonal
/// `−ups[i]` between unknowns `i` and `i + 1` (the Thomas algorithm).
fn thomas(diag: &[f64], rhs: &mut [f64], ups: &[f64]) -> Vec<f64> {
    let n = diag.len();
    let mut c = vec![0.0; n];
    for i in 0..n {
        let (a, prev_c, prev_r) = if i > 0 {
            (-ups[i - 1], c[i - 1], rhs[i - 1])
        } else {
            (0.0, 0.0, 0.0)
        };
        let d = diag[i] - a * prev_c;
        c[i] = if i + 1 < n { -ups[i] / d } else { 0.0 };
        rhs[i] = (rhs[i] - a * prev_r) / d;
    }
    let mut t = vec![0.0; n];
    for i in (0..n).rev() {
        let next = if i + 1 < n { t[i + 1] } else { 0.0 };
        t[i] = rhs[i] - c[i] * next;
    }
    t
}

#[cfg(test)]
pub(super) mod reference {
    //! Exposes the tree's internals to the tests.
    use super::*;

    impl Build {
        /// Every node's temperature: the shared rings, then each column.
        pub fn temperatures(&self) -> Vec<f64> {
            self.shared
                .iter()
                .chain(self.columns.iter().flatten())
                .map(|n| n.t)
                .collect()
        }

        /// The same step solved as a dense linear system (Gaussian
        /// elimination), for the tests to check the tree solve against.
        pub fn dense_step(&mut self, dt: f64, power: f64, into: usize) {
            let (m, ambient) = (self.material, self.plate.ambient);
            let s = self.shared.len();
            let total = self.nodes();
            let mut a = vec![vec![0.0; total + 1]; total];
            let mut nodes: Vec<Node> = Vec::new();
            let couple = |a: &mut Vec<Vec<f64>>, i: usize, j: usize, g: f64| {
                a[i][i] += g;
                a[j][j] += g;
                a[i][j] -= g;
                a[j][i] -= g;
            };
            nodes.extend_from_slice(&self.shared);
            for i in 0..s - 1 {
                couple(&mut a, i, i + 1, self.shared[i].up);
            }
            // Each column's first node's index.
            let mut bases = Vec::new();
            for (c, col) in self.columns.iter().enumerate() {
                let base = nodes.len();
                bases.push(base);
                if !col.is_empty() {
                    let under = match self.stands[c] {
                        Stand::Plate => Some(s - 1),
                        Stand::On(p) => {
                            let len = self.columns[p].len();
                            (len > 0).then(|| bases[p] + len - 1)
                        }
                    };
                    if let Some(u) = under {
                        couple(&mut a, u, base, self.below[c]);
                    }
                }
                for (i, node) in col.iter().enumerate().take(col.len().saturating_sub(1)) {
                    couple(&mut a, base + i, base + i + 1, node.up);
                }
                nodes.extend_from_slice(col);
            }
            // A merged column's joins to the other tops it stands on.
            for (i, j, g) in self.join_links() {
                couple(&mut a, i, j, g);
            }
            let mut faces = vec![0.0; total];
            for (c, col) in self.columns.iter().enumerate() {
                for i in 0..col.len() {
                    faces[bases[c] + i] = self.face(c, i);
                }
                if c == into && !col.is_empty() {
                    a[bases[c] + col.len() - 1][total] += power;
                }
            }
            for (i, n) in nodes.iter().enumerate() {
                let h = m.loss(n.t, ambient) * (n.surface + faces[i]);
                a[i][i] += n.capacity / dt + h;
                a[i][total] += n.capacity / dt * n.t + h * ambient;
            }
            // Gaussian elimination with partial pivoting.
            for col in 0..total {
                let p = (col..total)
                    .max_by(|&x, &y| a[x][col].abs().total_cmp(&a[y][col].abs()))
                    .unwrap();
                a.swap(col, p);
                let pivot = a[col].clone();
                for row in a.iter_mut().take(total).skip(col + 1) {
                    let f = row[col] / pivot[col];
                    for (x, p) in row.iter_mut().zip(&pivot).skip(col) {
                        *x -= f * p;
                    }
                }
            }
            let mut t = vec![0.0; total];
            for r in (0..total).rev() {
                let sum: f64 = (r + 1..total).map(|k| a[r][k] * t[k]).sum();
                t[r] = (a[r][total] - sum) / a[r][r];
            }
            let mut it = t.into_iter();
            for n in self
                .shared
                .iter_mut()
                .chain(self.columns.iter_mut().flatten())
            {
                n.t = it.next().unwrap();
            }
        }

        /// Steps once, as the model does.
        pub fn step_once(&mut self, dt: f64, power: f64, into: usize) {
            self.step(dt, power, into);
        }

        /// Steps once by the tree's elimination, however many columns.
        pub fn tree_once(&mut self, dt: f64, power: f64, into: usize) {
            self.tree_step(dt, power, into);
        }

        /// The heat the part and the plate hold above `from` °C, J.
        pub fn heat_above(&self, from: f64) -> f64 {
            self.shared
                .iter()
                .chain(self.columns.iter().flatten())
                .map(|n| n.capacity * (n.t - from))
                .sum()
        }
    }
}
