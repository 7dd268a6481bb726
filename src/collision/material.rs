//! What is there for the head to keep clear of: the part as it grows and the
//! fixtures, as *lumps* — points each standing for everything within a radius
//! of it — indexed two ways.
//!
//! - By **group** (a layer, a fixture): each keeps the box of its lumps in
//!   a frame of its own (from its first lump, one axis its normal). These
//!   bound how high the material reaches along any
//!   direction in a few operations a group ([`Material::highest`]): where
//!   everything lies below a plane through the nozzle's tip, square to the
//!   beam, the head (above that plane) is clear of it — the common case,
//!   decided without looking at a single lump.
//! - By **cell** of a uniform grid, for the cases where it is not: the lumps
//!   near the head are measured one by one ([`Material::nearest`]).
//!
//! Memory stays bounded: a cell whose lumps lie flat (within
//! [`FLAT_MM`] of each other in Z: a plate's layers) keeps only their box
//! once it holds [`CELL_LUMPS`], which bounds the head as closely from
//! above; and past [`MAX_LUMPS`] in all, every cell keeps its box (the
//! head's distance is then bounded by the boxes, less closely beside them).

use super::head::{add, cross, dist, dot, sub, HeadShape, Pose};
use std::collections::HashMap;

/// A point of material with the radius it stands for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lump {
    /// Where, mm.
    pub at: [f64; 3],
    /// Everything within this of `at` may be material, mm.
    pub r: f64,
    /// Its group: the layer it was laid in, or a fixture.
    pub group: u32,
}

/// A lump as a cell holds it.
#[derive(Clone, Copy, Debug)]
struct Stored {
    at: [f32; 3],
    r: f32,
    /// Its radius as laid, before it took in the lumps beside it
    /// ([`MERGE`]).
    r0: f32,
    group: u32,
}

impl Stored {
    fn of(l: &Lump) -> Stored {
        // Rounded outward: the f32 position is within 1e-7 relative of the
        // f64 one, which the radius takes up.
        let slack = l.at.iter().fold(0.0f64, |m, c| m.max(c.abs())) * 2e-7;
        let r = (l.r + slack) as f32;
        Stored {
            at: l.at.map(|c| c as f32),
            r,
            r0: r,
            group: l.group,
        }
    }

    /// Takes in `l` where it lies almost wholly inside: within
    /// [`MERGE`] of this lump's radius as laid, so a lump grows by at most
    /// that fraction however many it takes in.
    fn take_in(&mut self, l: &Lump) -> bool {
        if l.group != self.group {
            return false;
        }
        let at = self.at.map(f64::from);
        let reach = dist(at, l.at) + l.r;
        let r0 = f64::from(self.r0);
        if reach > r0 * (1.0 + MERGE) {
            return false;
        }
        self.r = self.r.max((reach * (1.0 + 1e-6)) as f32);
        true
    }

    fn lump(&self) -> Lump {
        Lump {
            at: self.at.map(f64::from),
            r: f64::from(self.r),
            group: self.group,
        }
    }
}

/// A group's bounds (module docs): its box in a frame of its own, whose
/// first axis is the group's direction.
#[derive(Clone, Copy, Debug)]
struct Group {
    o: [f64; 3],
    axes: [[f64; 3]; 3],
    /// The least and greatest `(x − o)·axis` of its lumps, their radii in.
    lo: [f64; 3],
    hi: [f64; 3],
}

impl Group {
    fn new(l: &Lump, n: [f64; 3]) -> Group {
        // Two axes square to `n`, from whichever world axis it is least
        // along.
        let pick = if n[0].abs() < 0.6 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let e1 = unit(cross(n, pick));
        let e2 = cross(n, e1);
        Group {
            o: l.at,
            axes: [n, e1, e2],
            lo: [-l.r; 3],
            hi: [l.r; 3],
        }
    }

    fn add(&mut self, l: &Lump) {
        let v = sub(l.at, self.o);
        for k in 0..3 {
            let a = dot(v, self.axes[k]);
            self.lo[k] = self.lo[k].min(a - l.r);
            self.hi[k] = self.hi[k].max(a + l.r);
        }
    }

    /// How far `p` lies from the group's box, mm (0 inside it).
    fn distance(&self, p: [f64; 3]) -> f64 {
        let v = sub(p, self.o);
        (0..3)
            .map(|k| {
                let q = dot(v, self.axes[k]);
                (self.lo[k] - q).max(q - self.hi[k]).max(0.0).powi(2)
            })
            .sum::<f64>()
            .sqrt()
    }

    /// An upper bound of `x·u` over the group.
    fn highest(&self, u: [f64; 3]) -> f64 {
        let mut h = dot(self.o, u);
        for k in 0..3 {
            let a = dot(u, self.axes[k]);
            h += if a >= 0.0 {
                a * self.hi[k]
            } else {
                a * self.lo[k]
            };
        }
        h
    }
}

fn unit(a: [f64; 3]) -> [f64; 3] {
    let len = dot(a, a).sqrt();
    [a[0] / len, a[1] / len, a[2] / len]
}

/// What a cell holds: its lumps, or only their box.
#[derive(Clone, Debug)]
enum Cell {
    Lumps {
        lumps: Vec<Stored>,
        /// Their box, radii in.
        lo: [f64; 3],
        hi: [f64; 3],
    },
    Box {
        lo: [f64; 3],
        hi: [f64; 3],
        /// The last group put in.
        group: u32,
    },
}

impl Cell {
    fn bounds(&self) -> ([f64; 3], [f64; 3]) {
        match self {
            Cell::Lumps { lo, hi, .. } | Cell::Box { lo, hi, .. } => (*lo, *hi),
        }
    }
}

/// A hasher for cell keys: a multiply-and-rotate per word (FxHash's), far
/// cheaper than the default SipHash for three small integers; the keys
/// are coordinates, not input anyone chooses to collide.
#[derive(Clone, Copy, Debug, Default)]
pub struct CellHasher(u64);

impl std::hash::Hasher for CellHasher {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for b in bytes {
            self.write_u64(u64::from(*b));
        }
    }

    fn write_i32(&mut self, i: i32) {
        self.write_u64(i as u32 as u64);
    }

    fn write_u64(&mut self, w: u64) {
        self.0 = (self.0.rotate_left(5) ^ w).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }

    fn write_usize(&mut self, w: usize) {
        self.write_u64(w as u64);
    }
}

/// Maps keyed by cells.
type CellMap<V> = HashMap<[i32; 3], V, std::hash::BuildHasherDefault<CellHasher>>;

/// A coarse cell: its occupied cells, and the largest lump radius among
/// them (mm), so that one vast lump widens the search only round itself.
#[derive(Debug, Default)]
struct Coarse {
    fine: Vec<[i32; 3]>,
    r_max: f64,
}

/// The material index: lumps by group and by cell.
#[derive(Debug)]
pub struct Material {
    groups: Vec<Group>,
    /// Each group's key (a layer's index, or a fixture's) → its slot.
    keys: HashMap<u32, usize>,
    /// The group added to last, and its slot.
    last: Option<(u32, usize)>,
    cells: CellMap<Cell>,
    /// The occupied cells of each coarse cell ([`COARSE`] cells a side).
    coarse: CellMap<Coarse>,
    cell: f64,
    /// The largest lump radius, mm.
    r_max: f64,
    /// Lumps held (not in boxes).
    held: usize,
    /// Whether every cell keeps only its box (past [`MAX_LUMPS`]).
    boxed: bool,
}

/// The side of a grid cell, mm: a few beads wide, so the head's
/// neighbourhood spans tens of cells, not thousands.
pub const CELL_MM: f64 = 12.0;

/// Cells a side of a coarse cell: the search skips empty space and far
/// material a coarse cell at a time.
pub const COARSE: i32 = 4;

/// Lumps a cell holds before it keeps only their box, where they lie flat.
pub const CELL_LUMPS: usize = 256;

/// How much larger than laid a lump of a crowded cell (past
/// [`CELL_LUMPS`]) may grow to take in the next lump of its layer: a path
/// of points far closer than its bead is wide (a wall of 100 000 points a
/// layer) then keeps a lump every few tenths of a bead, not one a point,
/// so the head's neighbourhood holds as many lumps as any other plan's.
/// The material is overstated by at most this fraction of a lump, only
/// there.
pub const MERGE: f64 = 1.0 / 32.0;

/// How flat, mm: the box of a plate's layers bounds the head from above as
/// closely as their lumps.
pub const FLAT_MM: f64 = 4.0;

/// Lumps held in all before every cell keeps only its box: about 100 MB.
pub const MAX_LUMPS: usize = 5_000_000;

impl Default for Material {
    fn default() -> Self {
        Material {
            groups: Vec::new(),
            keys: HashMap::new(),
            last: None,
            cells: CellMap::default(),
            coarse: CellMap::default(),
            cell: CELL_MM,
            r_max: 0.0,
            held: 0,
            boxed: false,
        }
    }
}

impl Material {
    /// Bounds a lump in its group (whose direction is `n`, used if it
    /// starts one): what [`Material::highest`] reads. Cheap: a plan bounds
    /// every deposit.
    pub fn bound(&mut self, l: &Lump, n: [f64; 3]) {
        // Lumps come a layer at a time: the last group is the likely one.
        match self.last.filter(|&(g, _)| g == l.group) {
            Some((_, i)) => self.groups[i].add(l),
            None => {
                let i = match self.keys.get(&l.group) {
                    Some(&i) => {
                        self.groups[i].add(l);
                        i
                    }
                    None => {
                        self.groups.push(Group::new(l, n));
                        self.keys.insert(l.group, self.groups.len() - 1);
                        self.groups.len() - 1
                    }
                };
                self.last = Some((l.group, i));
            }
        }
    }

    /// Bounds a lump and puts it in the grid.
    pub fn add(&mut self, l: Lump, n: [f64; 3]) {
        self.bound(&l, n);
        self.insert(l);
    }

    /// Puts a lump into its cell (bounded already).
    pub fn insert(&mut self, l: Lump) {
        self.r_max = self.r_max.max(l.r);
        let key = self.key(l.at);
        let (lo, hi) = (sub(l.at, [l.r; 3]), add(l.at, [l.r; 3]));
        let boxed = self.boxed;
        let coarse = self
            .coarse
            .entry(key.map(|k| k.div_euclid(COARSE)))
            .or_default();
        coarse.r_max = coarse.r_max.max(l.r);
        let cell = self.cells.entry(key).or_insert_with(|| {
            coarse.fine.push(key);
            if boxed {
                Cell::Box {
                    lo,
                    hi,
                    group: l.group,
                }
            } else {
                Cell::Lumps {
                    lumps: Vec::new(),
                    lo,
                    hi,
                }
            }
        });
        match cell {
            Cell::Box {
                lo: a,
                hi: b,
                group,
            } => {
                *a = min3(*a, lo);
                *b = max3(*b, hi);
                *group = l.group;
            }
            Cell::Lumps {
                lumps,
                lo: a,
                hi: b,
            } => {
                *a = min3(*a, lo);
                *b = max3(*b, hi);
                let crowded = lumps.len() >= CELL_LUMPS;
                if let Some(s) = lumps.last_mut().filter(|_| crowded) {
                    if s.take_in(&l) {
                        self.r_max = self.r_max.max(f64::from(s.r));
                        coarse.r_max = coarse.r_max.max(f64::from(s.r));
                        return;
                    }
                }
                lumps.push(Stored::of(&l));
                self.held += 1;
                if lumps.len() >= CELL_LUMPS && b[2] - a[2] <= FLAT_MM {
                    // A plate's layers: their box bounds the head from
                    // above as closely.
                    self.held -= lumps.len();
                    *cell = Cell::Box {
                        lo: *a,
                        hi: *b,
                        group: l.group,
                    };
                }
            }
        }
        if self.held > MAX_LUMPS {
            self.box_all();
        }
    }

    /// Every cell keeps only its box from now on.
    fn box_all(&mut self) {
        for cell in self.cells.values_mut() {
            if let Cell::Lumps { lumps, lo, hi } = cell {
                let group = lumps.last().map_or(0, |s| s.group);
                *cell = Cell::Box {
                    lo: *lo,
                    hi: *hi,
                    group,
                };
            }
        }
        self.held = 0;
        self.boxed = true;
    }

    /// Whether nothing is bounded.
    pub fn is_empty(&self) -> bool {
        self.groups.is_empty()
    }

    /// The cell `p` is in.
    fn key(&self, p: [f64; 3]) -> [i32; 3] {
        p.map(|c| (c / self.cell).floor().clamp(-1e9, 1e9) as i32)
    }

    /// An upper bound of how high the material reaches along the unit
    /// direction `u` (the greatest `x·u` of any of it): a few operations a
    /// group.
    pub fn highest(&self, u: [f64; 3]) -> f64 {
        self.groups
            .iter()
            .map(|g| g.highest(u))
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// [`Material::highest`] of the groups whose box comes within
    /// `radius` of `centre` (mm): a fixture metres away, high along a
    /// tilted `u`, does not hide the plane through the tip from the part.
    pub fn highest_near(&self, u: [f64; 3], centre: [f64; 3], radius: f64) -> f64 {
        self.groups
            .iter()
            .filter(|g| g.distance(centre) <= radius)
            .map(|g| g.highest(u))
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// The nearest material to the head at `pose` nearer than `cap` (its
    /// surface distance; a lower bound of it where a cell keeps only its
    /// box), with the head's body it is nearest and the lump (a box's:
    /// its centre, and the last group put in) standing for it; `None`
    /// where none is, or the head has no bodies.
    pub fn nearest(&self, head: &HeadShape, pose: &Pose, cap: f64) -> Option<(f64, usize, Lump)> {
        if head.bodies.is_empty() {
            return None;
        }
        let (centre, radius) = head.bound(pose);
        let reach = radius + cap + self.r_max.max(self.cell * 3f64.sqrt());
        let big = self.cell * COARSE as f64;
        let lo = sub(centre, [reach; 3]).map(|c| (c / big).floor().clamp(-1e9, 1e9) as i32);
        let hi = add(centre, [reach; 3]).map(|c| (c / big).floor().clamp(-1e9, 1e9) as i32);
        // Only where a fine cell is near: most poses pass every coarse
        // cell far from the head.
        let bounding = std::cell::OnceCell::new();
        let mut best: Option<(f64, usize, Lump)> = None;
        let limit = |b: &Option<(f64, usize, Lump)>| b.map_or(cap, |b| b.0.min(cap));
        let mut visit = |key: [i32; 3], coarse: &Coarse| {
            // The coarse cell's material lies within its
            // half-diagonal (and its largest lump's radius) of its centre.
            let c = key.map(|q| (q as f64 + 0.5) * big);
            let far = head.distance_to(pose, c) - big * 0.5 * 3f64.sqrt() - coarse.r_max;
            if far >= limit(&best) && far > 0.0 {
                return;
            }
            for key in &coarse.fine {
                let cell = &self.cells[key];
                let (clo, chi) = cell.bounds();
                let planes = bounding.get_or_init(|| planes(head, pose));
                let bound = box_bound(planes, (centre, radius), (clo, chi)).max(near_box(
                    head,
                    pose,
                    (clo, chi),
                ));
                // Clear of the head (a bound above 0), or no
                // nearer than what was found.
                if bound >= limit(&best) && bound > 0.0 {
                    continue;
                }
                match cell {
                    Cell::Box { group, .. } if bound < limit(&best) => {
                        let at = [0, 1, 2].map(|a| (clo[a] + chi[a]) / 2.0);
                        let l = Lump {
                            at,
                            r: 0.0,
                            group: *group,
                        };
                        best = Some((bound, 0, l));
                    }
                    Cell::Box { .. } => {}
                    Cell::Lumps { lumps, .. } => {
                        for s in lumps {
                            let l = s.lump();
                            let Some((d, body)) = head.distance(pose, l.at) else {
                                continue;
                            };
                            let d = d - l.r;
                            if d < limit(&best) {
                                best = Some((d, body, l));
                            }
                        }
                    }
                }
            }
        };
        // The occupied coarse cells within reach, in one order: the box's
        // own where it holds no more cells than are occupied, else the
        // occupied ones in it, sorted (a lump metres wide makes the reach,
        // and the box, vast).
        let span: f64 = (0..3).map(|a| f64::from(hi[a] - lo[a]) + 1.0).product();
        if span <= self.coarse.len() as f64 {
            for i in lo[0]..=hi[0] {
                for j in lo[1]..=hi[1] {
                    for k in lo[2]..=hi[2] {
                        if let Some(coarse) = self.coarse.get(&[i, j, k]) {
                            visit([i, j, k], coarse);
                        }
                    }
                }
            }
        } else {
            let mut keys: Vec<[i32; 3]> = (self.coarse.keys().copied())
                .filter(|q| (0..3).all(|a| (lo[a]..=hi[a]).contains(&q[a])))
                .collect();
            keys.sort_unstable();
            for key in keys {
                visit(key, &self.coarse[&key]);
            }
        }
        best
    }
}

/// How many directions a pose's head is bounded along for the boxes
/// ([`planes`]).
const PLANES: usize = 5;

/// Planes the head at `pose` lies wholly above: for each unit direction
/// `n`, the least `x·n` of its points. From the beam's direction to Z, in
/// their plane: the plane square to a tilted beam, through its tip, cuts
/// through a flat box of beads beside the nozzle (a box 12 mm wide rises
/// 6 mm along a beam tilted 30°), while a plane nearer the level one
/// passes over it — the box of a plate's layers under a nozzle tilted 30°
/// was bounded 1.16 mm from the head, its beads lying 7 mm below it.
fn planes(head: &HeadShape, pose: &Pose) -> [([f64; 3], f64); PLANES] {
    let z = [0.0, 0.0, 1.0];
    std::array::from_fn(|k| {
        let t = k as f64 / (PLANES - 1) as f64;
        let v = [0, 1, 2].map(|a| pose.up[a] * (1.0 - t) + z[a] * t);
        let len = dot(v, v).sqrt();
        // A beam pointing straight down: Z's plane is as good as its own.
        let n = if len > 1e-9 { v.map(|c| c / len) } else { z };
        (n, head.lowest_along(pose, n))
    })
}

/// A lower bound of the head's distance to anything in the box `lo`–`hi`:
/// the largest of how far the box lies below each of the planes the head
/// lies above ([`planes`]: the plane through its lowest point square to
/// its beam, and planes nearer the level one), and how far it lies
/// outside the sphere round the head.
fn box_bound(
    planes: &[([f64; 3], f64)],
    (centre, radius): ([f64; 3], f64),
    (lo, hi): ([f64; 3], [f64; 3]),
) -> f64 {
    let below = planes
        .iter()
        .map(|&(n, low)| {
            let top = (0..3)
                .map(|a| if n[a] >= 0.0 { hi[a] } else { lo[a] } * n[a])
                .sum::<f64>();
            low - top
        })
        .fold(f64::NEG_INFINITY, f64::max);
    let outside = {
        let d2: f64 = (0..3)
            .map(|a| {
                let c = centre[a].clamp(lo[a], hi[a]);
                (centre[a] - c).powi(2)
            })
            .sum();
        d2.sqrt() - radius
    };
    below.max(outside).max(0.0)
}

/// A lower bound of the head's distance to anything in the box `lo`–`hi`
/// by its centre: no nearer than the centre less the half-diagonal.
fn near_box(head: &HeadShape, pose: &Pose, (lo, hi): ([f64; 3], [f64; 3])) -> f64 {
    let c = [0, 1, 2].map(|a| (lo[a] + hi[a]) / 2.0);
    let half = [0, 1, 2].map(|a| (hi[a] - lo[a]) / 2.0);
    (head.distance_to(pose, c) - dot(half, half).sqrt()).max(0.0)
}

fn min3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0].min(b[0]), a[1].min(b[1]), a[2].min(b[2])]
}

fn max3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0].max(b[0]), a[1].max(b[1]), a[2].max(b[2])]
}

#[cfg(test)]
mod tests {
    use super::super::head::scale;
    use super::*;
    use proptest::prelude::*;

    /// The head sampled on its solids' surfaces: rings every 0.5 mm up each
    /// and every degree round it (not `HeadShape::distance`'s outline).
    fn sampled(head: &HeadShape, pose: &Pose) -> Vec<[f64; 3]> {
        let up = pose.up;
        let side = unit(cross(up, [0.0, 1.0, 0.0]));
        let other = cross(up, side);
        let mut out = Vec::new();
        for b in &head.bodies {
            let steps = ((b.s[1] - b.s[0]) / 0.5).ceil() as usize;
            for i in 0..=steps {
                let t = i as f64 / steps as f64;
                let (s, r) = (
                    b.s[0] + t * (b.s[1] - b.s[0]),
                    b.r[0] + t * (b.r[1] - b.r[0]),
                );
                for j in 0..360 {
                    let (sa, ca) = f64::from(j).to_radians().sin_cos();
                    let p = add(pose.focus, scale(up, s));
                    out.push(add(p, add(scale(side, r * ca), scale(other, r * sa))));
                }
            }
        }
        out
    }

    /// A flat cell of beads (a layer on a plate) keeps only its box; a
    /// nozzle tilted 30° beside it, its tip 13 mm above them and its cone
    /// leaning over them (`lmdc check` of the leaning slab mirrored, layer
    /// 1, path 5, point 41), is bounded no nearer than the gap — the
    /// plane square to the beam alone bounded it 1.16 mm away — and never
    /// farther than the head's surface, sampled, lies from the lumps.
    #[test]
    fn a_flat_box_beside_a_tilted_nozzle_is_bounded_from_above() {
        let head = HeadShape::of(&crate::ir::Head::typical());
        let mut m = Material::default();
        let mut lumps = Vec::new();
        for i in 0..18 {
            for j in 0..18 {
                let at = [-10.7 + 0.6 * f64::from(i), -10.7 + 0.6 * f64::from(j), 9.6];
                let l = Lump {
                    at,
                    r: 1.3,
                    group: 0,
                };
                lumps.push(l);
                m.add(l, [-0.5, 0.0, 0.866]);
            }
        }
        assert!(matches!(m.cells.values().next(), Some(Cell::Box { .. })));
        let pose = Pose {
            focus: [11.17, -0.8, 8.75],
            up: unit([-0.5, 0.0, 0.866]),
        };
        let points = sampled(&head, &pose);
        let truth = lumps
            .iter()
            .flat_map(|l| points.iter().map(|p| dist(*p, l.at) - l.r))
            .fold(f64::INFINITY, f64::min);
        assert!(truth > 7.0 && truth < 8.0, "{truth}");
        let cap = 20.0;
        let (d, ..) = m.nearest(&head, &pose, cap).expect("within the cap");
        assert!(d <= truth + 1e-9, "{d} vs {truth}");
        assert!(d >= head.gap && d > truth - 1.5, "{d} vs {truth}");
    }

    proptest! {
        /// A group's bound along any direction is at least every lump's
        /// reach along it.
        #[test]
        fn a_groups_bound_holds_in_every_direction(
            pts in prop::collection::vec((prop::array::uniform3(-50.0f64..50.0), 0.0f64..3.0), 1..40),
            u in prop::array::uniform3(-1.0f64..1.0),
            n in prop::array::uniform3(-1.0f64..1.0),
        ) {
            let len = |v: [f64; 3]| dot(v, v).sqrt();
            prop_assume!(len(u) > 0.1 && len(n) > 0.1);
            let (u, n) = (scale(u, 1.0 / len(u)), scale(n, 1.0 / len(n)));
            let mut m = Material::default();
            for (p, r) in &pts {
                m.add(Lump { at: *p, r: *r, group: 0 }, n);
            }
            let want = pts.iter().map(|(p, r)| dot(*p, u) + r).fold(f64::NEG_INFINITY, f64::max);
            prop_assert!(m.highest(u) >= want - 1e-9, "{} < {want}", m.highest(u));
        }

        /// The grid's nearest lump is the nearest of all, measured one by
        /// one, wherever the head stands; once the cells keep only boxes,
        /// what it finds is still no farther than the truth.
        #[test]
        fn the_grid_finds_the_nearest_lump(
            pts in prop::collection::vec(prop::array::uniform3(-120.0f64..120.0), 1..200),
            focus in prop::array::uniform3(-100.0f64..100.0),
            up in prop::array::uniform3(-1.0f64..1.0),
            boxed in any::<bool>(),
        ) {
            let len = dot(up, up).sqrt();
            prop_assume!(len > 0.1);
            let pose = Pose { focus, up: scale(up, 1.0 / len) };
            let head = HeadShape::of(&crate::ir::Head::typical());
            let mut m = Material::default();
            for p in &pts {
                m.add(Lump { at: *p, r: 1.0, group: 0 }, [0.0, 0.0, 1.0]);
            }
            if boxed {
                m.box_all();
            }
            let want = pts.iter().map(|p| head.distance_to(&pose, *p) - 1.0).fold(f64::INFINITY, f64::min);
            let cap = 25.0;
            match m.nearest(&head, &pose, cap) {
                Some((d, ..)) if boxed => prop_assert!(d <= want.max(0.0) + 1e-6, "{d} vs {want}"),
                Some((d, ..)) => prop_assert!((d - want).abs() < 1e-4, "{d} vs {want}"),
                None => prop_assert!(want >= cap - 1e-6, "missed {want}"),
            }
        }

        /// A box bounds the head's distance to everything in it from below.
        #[test]
        fn a_box_bound_is_a_lower_bound(
            p in prop::array::uniform3(-60.0f64..60.0),
            size in prop::array::uniform3(0.5f64..30.0),
            focus in prop::array::uniform3(-60.0f64..60.0),
            up in prop::array::uniform3(-1.0f64..1.0),
            t in prop::array::uniform3(0.0f64..1.0),
        ) {
            let len = dot(up, up).sqrt();
            prop_assume!(len > 0.1);
            let pose = Pose { focus, up: scale(up, 1.0 / len) };
            let head = HeadShape::of(&crate::ir::Head::typical());
            let hi = add(p, size);
            let inside = [0, 1, 2].map(|a| p[a] + t[a] * size[a]);
            let b = box_bound(&planes(&head, &pose), head.bound(&pose), (p, hi));
            prop_assert!(b <= head.distance_to(&pose, inside) + 1e-9);
        }
    }
}
