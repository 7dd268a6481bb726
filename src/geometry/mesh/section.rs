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
/// to the smallest outline round it (an island standing in another's hole
/// keeps its own holes).
pub fn islands(loops: Vec<Loop>) -> Result<Vec<Section>, SectionFault> {
    let (outer, holes): (Vec<Loop>, Vec<Loop>) = loops.into_iter().partition(|l| area(l) > 0.0);
    if outer.is_empty() {
        return Err(SectionFault::Empty);
    }
    let mut out: Vec<Section> = outer
        .into_iter()
        .map(|outline| Section {
            outline,
            holes: Vec::new(),
        })
        .collect();
    for h in holes {
        let p = h[0];
        let round = (0..out.len())
            .filter(|&i| inside(&out[i].outline, p))
            .min_by(|&i, &j| area(&out[i].outline).total_cmp(&area(&out[j].outline)));
        match round {
            Some(i) => out[i].holes.push(h),
            None => return Err(SectionFault::StrayHole { at: p }),
        }
    }
    out.sort_by(|a, b| {
        let (p, q) = (lowest(&a.outline), lowest(&b.outline));
        p[1].total_cmp(&q[1]).then(p[0].total_cmp(&q[0]))
    });
    Ok(out)
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
