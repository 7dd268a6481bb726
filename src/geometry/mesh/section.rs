//! Horizontal sections of a [`Mesh`], bottom to top, by a sweep: the
//! triangles sorted by their lowest corner enter the active list as the
//! plane reaches them and leave it once it has passed their highest, so a
//! section costs time linear in the triangles it crosses (plus the sort,
//! once).
//!
//! A corner on the plane counts as above it, so every triangle the plane
//! crosses has exactly two edges that cross it, and the plane never runs
//! along a face: the pieces of a closed mesh always join into closed loops.
//! Each piece runs with the solid on its left, so outlines come out
//! counter-clockwise and holes clockwise.

use super::{Mesh, MAX_LISTED};
use crate::geometry::profile::meet;
use crate::geometry::shape::{Hole, Outline, RegionShape, Segment, Shape};
use crate::span::Span;
use crate::units::Length;
use cavalier_contours::polyline::{PlineSource, PlineSourceMut, Polyline};
use cavalier_contours::static_aabb2d_index::StaticAABB2DIndex;
use std::collections::HashMap;

/// One closed loop of a section, with the solid on its left.
pub type Loop = Vec<[f64; 2]>;

/// One island of a section of the mesh: its outline and holes.
#[derive(Clone, Debug, PartialEq)]
pub struct Section {
    /// The outer loop, counter-clockwise.
    pub outline: Loop,
    /// The holes, clockwise.
    pub holes: Vec<Loop>,
}

/// Why a section is no set of islands, each an outline and its holes.
#[derive(Clone, Debug, PartialEq)]
pub enum SectionFault {
    /// The plane cuts nothing there.
    Empty,
    /// The pieces do not join into a loop: a chain ends at `at` (a mesh
    /// that passed [`Mesh::new`] has none; kept as a check).
    Open {
        /// Where the chain ends.
        at: [f64; 2],
        /// Triangles of the chain (file numbers).
        triangles: Vec<usize>,
    },
    /// A hole (a clockwise loop) inside no outline (a mesh that passed
    /// [`Mesh::new`] has none; kept as a check).
    StrayHole {
        /// A point of the hole.
        at: [f64; 2],
    },
    /// Two loops cross or touch, or an outline lies straight inside
    /// another (no hole between): two shells of the mesh overlap there, and
    /// the layer would lay metal twice where they do.
    Overlap {
        /// A point the two shells share: where their loops meet, or a
        /// corner of the inner outline.
        at: [f64; 2],
    },
}

/// The sections of a mesh at rising heights.
pub struct Sections<'m> {
    mesh: &'m Mesh,
    /// Triangles by their lowest corner.
    order: Vec<u32>,
    /// Each triangle's lowest and highest corner.
    range: Vec<[f64; 2]>,
    next: usize,
    active: Vec<u32>,
    last: f64,
}

impl Mesh {
    /// Its sections, asked for at rising heights.
    pub fn sections(&self) -> Sections<'_> {
        let range: Vec<[f64; 2]> = self
            .triangles
            .iter()
            .map(|t| {
                let z = t.map(|i| self.vertices[i as usize][2]);
                [z[0].min(z[1]).min(z[2]), z[0].max(z[1]).max(z[2])]
            })
            .collect();
        let mut order: Vec<u32> = (0..self.triangles.len() as u32).collect();
        order.sort_unstable_by(|&a, &b| range[a as usize][0].total_cmp(&range[b as usize][0]));
        Sections {
            mesh: self,
            order,
            range,
            next: 0,
            active: Vec::new(),
            last: f64::NEG_INFINITY,
        }
    }
}

impl Mesh {
    /// How many pieces of outline the sections of the mesh, scaled by `k`
    /// (its lowest point staying on the plate), cut `lift` apart halfway
    /// up each of `layers` layers, have together: one for every triangle
    /// a cutting plane crosses (the count of [`Sections::loops`]'s pieces,
    /// in time linear in the triangles, before any is cut).
    pub fn crossings(&self, k: f64, lift: f64, layers: f64) -> f64 {
        let last = layers - 1.0;
        self.triangles
            .iter()
            .map(|t| {
                let z = t.map(|i| self.vertices[i as usize][2] * k / lift - 0.5);
                let lo = z[0].min(z[1]).min(z[2]).ceil().max(0.0);
                let hi = z[0].max(z[1]).max(z[2]).floor().min(last);
                (hi - lo + 1.0).max(0.0)
            })
            .sum()
    }
}

impl Section {
    /// The island's area (mm²): its outline's less its holes'.
    pub fn area(&self) -> f64 {
        area(&self.outline).abs() - self.holes.iter().map(|h| area(h).abs()).sum::<f64>()
    }

    /// The length of all its loops (mm).
    pub fn perimeter(&self) -> f64 {
        std::iter::once(&self.outline)
            .chain(&self.holes)
            .map(|l| {
                (0..l.len())
                    .map(|i| {
                        let (a, b) = (l[i], l[(i + 1) % l.len()]);
                        (b[0] - a[0]).hypot(b[1] - a[1])
                    })
                    .sum::<f64>()
            })
            .sum()
    }

    /// The diagonal of the box round its outline (mm): no line across the
    /// island is longer.
    pub fn diagonal(&self) -> f64 {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in &self.outline {
            for i in 0..2 {
                lo[i] = lo[i].min(p[i]);
                hi[i] = hi[i].max(p[i]);
            }
        }
        (hi[0] - lo[0]).hypot(hi[1] - lo[1])
    }
}

impl Sections<'_> {
    /// The loops of the plane `z = h`, each with the solid on its left.
    /// Heights must not fall from one call to the next (a lower one is
    /// taken as the last).
    pub fn loops(&mut self, h: f64) -> Result<Vec<Loop>, SectionFault> {
        let h = h.max(self.last);
        self.last = h;
        while let Some(&t) = self.order.get(self.next) {
            if self.range[t as usize][0] >= h {
                break;
            }
            self.active.push(t);
            self.next += 1;
        }
        let range = &self.range;
        self.active.retain(|&t| range[t as usize][1] >= h);
        // Each crossed triangle's piece, from the edge where its corners go
        // from above to below to the one where they go back up.
        let mut piece: HashMap<u32, (u32, u32)> = HashMap::with_capacity(self.active.len());
        for &t in &self.active {
            if let Some((from, to)) = self.piece(t, h) {
                piece.insert(from, (to, t));
            }
        }
        self.join(piece, h)
    }

    /// The edges (into, out of) where triangle `t` crosses `z = h`.
    fn piece(&self, t: u32, h: f64) -> Option<(u32, u32)> {
        let m = self.mesh;
        let tri = m.triangles[t as usize];
        let above = tri.map(|i| m.vertices[i as usize][2] >= h);
        let (mut down, mut up) = (None, None);
        for s in 0..3 {
            match (above[s], above[(s + 1) % 3]) {
                (true, false) => down = Some(m.tri_edges[t as usize][s]),
                (false, true) => up = Some(m.tri_edges[t as usize][s]),
                _ => {}
            }
        }
        Some((down?, up?))
    }

    /// Where edge `e` crosses `z = h` (computed from the edge alone, so the
    /// two triangles at it agree to the bit).
    fn point(&self, e: u32, h: f64) -> [f64; 2] {
        let [a, b] = self.mesh.edges[e as usize].map(|i| self.mesh.vertices[i as usize]);
        let t = ((h - a[2]) / (b[2] - a[2])).clamp(0.0, 1.0);
        [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
    }

    /// Joins the pieces into loops, walking from edge to edge.
    fn join(&self, mut piece: HashMap<u32, (u32, u32)>, h: f64) -> Result<Vec<Loop>, SectionFault> {
        let mut starts: Vec<u32> = piece.keys().copied().collect();
        // The same loops in the same order whatever the hash map's order.
        starts.sort_unstable();
        let mut loops = Vec::new();
        for s in starts {
            if !piece.contains_key(&s) {
                continue;
            }
            let mut pts = Vec::new();
            let mut tris = Vec::new();
            let mut e = s;
            loop {
                pts.push(self.point(e, h));
                let Some((next, t)) = piece.remove(&e) else {
                    return Err(SectionFault::Open {
                        at: self.point(e, h),
                        triangles: tris,
                    });
                };
                if tris.len() < MAX_LISTED {
                    tris.push(self.mesh.file_number(t));
                }
                if next == s {
                    break;
                }
                e = next;
            }
            if let Some(l) = cleaned(pts) {
                loops.push(l);
            }
        }
        Ok(loops)
    }
}

/// A loop without repeated points or points on a straight run between
/// their neighbours; `None` when nothing with an area is left.
fn cleaned(pts: Vec<[f64; 2]>) -> Option<Loop> {
    let mut out: Vec<[f64; 2]> = Vec::with_capacity(pts.len());
    for p in pts {
        if out.last() != Some(&p) {
            out.push(p);
        }
    }
    while out.len() > 1 && out.first() == out.last() {
        out.pop();
    }
    // Drop points exactly on the line through their neighbours, until none
    // is left (a face split in many triangles cuts into many pieces).
    let mut changed = true;
    while changed && out.len() >= 3 {
        changed = false;
        let mut kept: Vec<[f64; 2]> = Vec::with_capacity(out.len());
        let n = out.len();
        for i in 0..n {
            let a = kept.last().copied().unwrap_or(out[(i + n - 1) % n]);
            let (b, c) = (out[i], out[(i + 1) % n]);
            let cross = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
            let scale = (c[0] - a[0]).hypot(c[1] - a[1]).powi(2);
            let ahead = (b[0] - a[0]) * (c[0] - a[0]) + (b[1] - a[1]) * (c[1] - a[1]) > 0.0;
            if cross.abs() <= 1e-12 * scale && ahead {
                changed = true;
            } else {
                kept.push(b);
            }
        }
        out = kept;
    }
    (out.len() >= 3 && area(&out).abs() > 0.0).then_some(out)
}

/// The signed area of a loop (positive counter-clockwise).
pub fn area(l: &[[f64; 2]]) -> f64 {
    let n = l.len();
    (0..n)
        .map(|i| {
            let (a, b) = (l[i], l[(i + 1) % n]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
        / 2.0
}

/// The loops of a section as islands, each an outline and the holes inside
/// it, ordered by their lowest, then leftmost, point (the order the planar
/// slicer starts from before it visits them nearest first). A hole belongs
/// to the smallest loop round it, which must be an outline (an island
/// standing in another's hole keeps its own holes); an outline's smallest
/// loop round it must be a hole, if any: an outline straight inside
/// another, or two loops that cross or touch, are shells that overlap
/// ([`SectionFault::Overlap`]).
pub fn islands(loops: Vec<Loop>) -> Result<Vec<Section>, SectionFault> {
    let areas: Vec<f64> = loops.iter().map(|l| area(l)).collect();
    if !areas.iter().any(|&a| a > 0.0) {
        return Err(SectionFault::Empty);
    }
    let parent = nesting(&loops, &areas)?;
    // Each outline's island, by the outline's number among the loops.
    let mut island: Vec<Option<usize>> = vec![None; loops.len()];
    let mut out: Vec<Section> = Vec::new();
    for (i, l) in loops.iter().enumerate() {
        let p = parent[i].map(|j| areas[j] > 0.0);
        match (areas[i] > 0.0, p) {
            (true, None | Some(false)) => {
                island[i] = Some(out.len());
                out.push(Section {
                    outline: l.clone(),
                    holes: Vec::new(),
                });
            }
            (true, Some(true)) => return Err(SectionFault::Overlap { at: l[0] }),
            (false, Some(true)) => {}
            (false, None | Some(false)) => return Err(SectionFault::StrayHole { at: l[0] }),
        }
    }
    for (i, l) in loops.into_iter().enumerate() {
        if let (false, Some(j)) = (areas[i] > 0.0, parent[i]) {
            if let Some(k) = island[j] {
                out[k].holes.push(l);
            }
        }
    }
    out.sort_by(|a, b| {
        let (p, q) = (lowest(&a.outline), lowest(&b.outline));
        p[1].total_cmp(&q[1]).then(p[0].total_cmp(&q[0]))
    });
    Ok(out)
}

/// A section's islands as one shape: the one island's, or
/// [`Shape::Islands`]; `span` is where the shape is written (its holes'
/// too).
pub fn shape_of(mut islands: Vec<Section>, span: Span) -> Shape {
    if islands.len() == 1 {
        return islands.remove(0).shape(span);
    }
    Shape::Islands(islands.into_iter().map(|s| s.shape(span)).collect())
}

impl Section {
    /// The island as a shape: a region when it has holes.
    pub fn shape(self, span: Span) -> Shape {
        let outer = Shape::Outline(outline(&self.outline));
        if self.holes.is_empty() {
            return outer;
        }
        Shape::Region(Box::new(RegionShape {
            outline: outer,
            outline_span: span,
            holes: self
                .holes
                .iter()
                .map(|h| Hole {
                    shape: Shape::Outline(outline(h)),
                    span,
                })
                .collect(),
        }))
    }
}

/// A loop as an outline of lines, back to its start.
fn outline(l: &Loop) -> Outline {
    let mm = |p: [f64; 2]| [Length(p[0]), Length(p[1])];
    Outline {
        start: mm(l[0]),
        segments: l[1..]
            .iter()
            .chain(std::iter::once(&l[0]))
            .map(|&p| Segment::Line { to: mm(p) })
            .collect(),
    }
}

/// The loops of a section whose faces may run either way round (a
/// scan's, not a solid's) as islands: each loop turned so that the ones
/// inside an even number of others run counter-clockwise (outlines) and
/// the rest clockwise (holes), then [`islands`].
pub fn oriented(mut loops: Vec<Loop>) -> Result<Vec<Section>, SectionFault> {
    let areas: Vec<f64> = loops.iter().map(|l| area(l)).collect();
    let parent = nesting(&loops, &areas)?;
    for i in 0..loops.len() {
        let mut depth = 0usize;
        let mut p = parent[i];
        // Parents are strictly larger, so the chain ends.
        while let Some(j) = p {
            depth += 1;
            p = parent[j];
        }
        if (areas[i] > 0.0) != depth.is_multiple_of(2) {
            loops[i].reverse();
        }
    }
    islands(loops)
}

/// Each loop's parent: the smallest loop round it, if any; the
/// [`SectionFault::Overlap`] of the first two loops found to cross or
/// touch. Only loops whose bounding boxes overlap are compared (a sweep
/// over the boxes sorted by their left side), so a layer of many small
/// loops side by side costs little more than sorting them.
fn nesting(loops: &[Loop], areas: &[f64]) -> Result<Vec<Option<usize>>, SectionFault> {
    let boxes: Vec<[[f64; 2]; 2]> = loops.iter().map(bounds).collect();
    let mut order: Vec<usize> = (0..loops.len()).collect();
    order.sort_by(|&a, &b| boxes[a][0][0].total_cmp(&boxes[b][0][0]));
    let plines: Vec<Polyline<f64>> = loops.iter().map(pline).collect();
    let mut index: Vec<Option<StaticAABB2DIndex<f64>>> = (0..loops.len()).map(|_| None).collect();
    let mut parent: Vec<Option<usize>> = vec![None; loops.len()];
    for (k, &a) in order.iter().enumerate() {
        for &b in &order[k + 1..] {
            if boxes[b][0][0] > boxes[a][1][0] {
                break;
            }
            if boxes[b][0][1] > boxes[a][1][1] || boxes[a][0][1] > boxes[b][1][1] {
                continue;
            }
            // The longer loop's segment index, built once, serves every
            // shorter loop tested against it (an outline round many holes).
            let (big, small) = if loops[a].len() >= loops[b].len() {
                (a, b)
            } else {
                (b, a)
            };
            let idx = index[big].get_or_insert_with(|| plines[big].create_approx_aabb_index());
            if let Some(at) = meet(&plines[big], Some(idx), &plines[small]) {
                return Err(SectionFault::Overlap { at });
            }
            for (outer, inner) in [(a, b), (b, a)] {
                let holds =
                    encloses(boxes[outer], boxes[inner]) && inside(&loops[outer], loops[inner][0]);
                let smaller = parent[inner].is_none_or(|p| areas[outer].abs() < areas[p].abs());
                if holds && smaller {
                    parent[inner] = Some(outer);
                }
            }
        }
    }
    Ok(parent)
}

/// A loop as a closed polyline of lines.
fn pline(l: &Loop) -> Polyline<f64> {
    let mut pl = Polyline::new_closed();
    for p in l {
        pl.add(p[0], p[1], 0.0);
    }
    pl
}

/// The loop's bounding box, `[low corner, high corner]`.
fn bounds(l: &Loop) -> [[f64; 2]; 2] {
    l.iter().fold(
        [[f64::INFINITY; 2], [f64::NEG_INFINITY; 2]],
        |[lo, hi], p| {
            [
                [lo[0].min(p[0]), lo[1].min(p[1])],
                [hi[0].max(p[0]), hi[1].max(p[1])],
            ]
        },
    )
}

/// Whether box `a` holds box `b`.
fn encloses(a: [[f64; 2]; 2], b: [[f64; 2]; 2]) -> bool {
    a[0][0] <= b[0][0] && a[0][1] <= b[0][1] && b[1][0] <= a[1][0] && b[1][1] <= a[1][1]
}

/// The loop's lowest point (least y, then least x).
fn lowest(l: &Loop) -> [f64; 2] {
    l.iter()
        .copied()
        .min_by(|p, q| p[1].total_cmp(&q[1]).then(p[0].total_cmp(&q[0])))
        .unwrap_or([0.0, 0.0])
}

/// Whether `p` is inside loop `l` (even-odd rule; a point on it may go
/// either way, which cannot happen for a hole's corner: loops of a closed
/// mesh's section do not touch).
fn inside(l: &Loop, p: [f64; 2]) -> bool {
    let n = l.len();
    let mut odd = false;
    for i in 0..n {
        let (a, b) = (l[i], l[(i + 1) % n]);
        if (a[1] > p[1]) != (b[1] > p[1]) {
            let x = a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
            if x > p[0] {
                odd = !odd;
            }
        }
    }
    odd
}
