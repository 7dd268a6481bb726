//! A solid given as a triangle mesh (an STL file): its corners welded into
//! vertices, its edges paired, checked closed and manifold, placed, and cut
//! by horizontal planes into the loops of each layer ([`Sections`]).
//!
//! Triangles are numbered from 0 in the order of the file, so an error can
//! name the ones a repair tool should look at.

pub mod highest;
mod section;
pub mod stl;
#[cfg(test)]
mod tests;
pub mod three_mf;

pub use section::{area, islands, oriented, shape_of, Loop, Section, SectionFault, Sections};

use nalgebra::{Rotation3, Vector3};
use std::collections::HashMap;

/// The units a mesh's coordinates may be in (`mesh(units = …)`): an STL
/// does not say; a 3MF's own unit is one of them.
pub const UNITS: &[&str] = &["mm", "cm", "m", "in"];

/// Most triangles a fault lists.
pub const MAX_LISTED: usize = 8;

/// The lowest point may be this far (mm) from the plate: float noise (an
/// exact quarter turn's cosine is 6·10⁻¹⁷, not 0), far below any bead.
pub const ON_PLATE: f64 = 1e-6;

/// The third number of `at` that stands the mesh on the plate, when
/// `exact` would: in the fewest decimals (0 to 7) that keep the lowest
/// point within [`ON_PLATE`] of it, rounded up (so the point lands on or
/// just above the plate, never below), unless `exact` is that decimal to
/// float noise. Following the advice therefore always builds.
pub fn plate_z(exact: f64) -> f64 {
    for d in 0..=7 {
        let k = 10f64.powi(d);
        let near = (exact * k).round() / k;
        if (near - exact).abs() <= 1e-12 * exact.abs().max(1.0) {
            return near;
        }
        let up = (exact * k).ceil() / k;
        if up - exact <= ON_PLATE / 2.0 {
            return up;
        }
    }
    exact
}

/// Where a mesh goes: scaled from its file's units to mm, turned about the
/// x, then the y, then the z axis, then moved.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    /// mm per file unit.
    pub scale: f64,
    /// Turns about x, y and z (rad), applied in that order.
    pub turn: [f64; 3],
    /// Where the file's origin goes (mm).
    pub at: [f64; 3],
}

/// A closed, manifold, consistently oriented triangle mesh, placed, its
/// triangles facing out.
#[derive(Debug)]
pub struct Mesh {
    /// The welded vertices (mm, placed).
    vertices: Vec<[f64; 3]>,
    /// Each triangle's vertices, counter-clockwise seen from outside.
    triangles: Vec<[u32; 3]>,
    /// Each triangle's edges (`a→b`, `b→c`, `c→a`), as indices into `edges`.
    tri_edges: Vec<[u32; 3]>,
    /// Each edge's two vertices (lower index first).
    edges: Vec<[u32; 2]>,
    /// Each kept triangle's number in the file.
    file_index: Vec<u32>,
}

/// Why a mesh is no solid.
#[derive(Clone, Debug, PartialEq)]
pub enum MeshFault {
    /// Edges used by one triangle only: the surface has a hole.
    Open {
        /// How many such edges.
        edges: usize,
        /// Triangles at them (file numbers), at most [`MAX_LISTED`].
        triangles: Vec<usize>,
        /// The first such edge's ends (mm, placed).
        at: [[f64; 3]; 2],
    },
    /// Edges shared by more than two triangles.
    NonManifold {
        /// How many such edges.
        edges: usize,
        /// The triangles at the first one (file numbers).
        triangles: Vec<usize>,
        /// Its ends (mm, placed).
        at: [[f64; 3]; 2],
    },
    /// Two triangles that share an edge and disagree on which side is out
    /// (both run along it the same way).
    Flipped {
        /// How many such edges.
        edges: usize,
        /// The two triangles at the first one (file numbers).
        triangles: [usize; 2],
        /// Its ends (mm, placed).
        at: [[f64; 3]; 2],
    },
    /// The mesh encloses no volume.
    Flat,
}

impl Mesh {
    /// The mesh of `tris` placed by `place`: corners with the same
    /// coordinates in the file are one vertex; a triangle with two equal
    /// corners is left out (its edges cancel).
    pub fn new(tris: &[stl::Triangle], place: Placement) -> Result<Mesh, MeshFault> {
        let rot = Rotation3::from_euler_angles(place.turn[0], place.turn[1], place.turn[2]);
        let at = Vector3::from(place.at);
        let mut index: HashMap<[u32; 3], u32> = HashMap::with_capacity(tris.len() / 2 + 3);
        let mut vertices = Vec::with_capacity(tris.len() / 2 + 3);
        let mut triangles = Vec::with_capacity(tris.len());
        let mut file_index = Vec::with_capacity(tris.len());
        for (i, t) in tris.iter().enumerate() {
            let mut ids = [0u32; 3];
            for (id, c) in ids.iter_mut().zip(t) {
                // -0.0 and 0.0 are the same corner.
                let key = c.map(|x| (x + 0.0).to_bits());
                *id = *index.entry(key).or_insert_with(|| {
                    let p = Vector3::new(f64::from(c[0]), f64::from(c[1]), f64::from(c[2]));
                    let q = rot * (p * place.scale) + at;
                    vertices.push([q.x, q.y, q.z]);
                    (vertices.len() - 1) as u32
                });
            }
            if ids[0] != ids[1] && ids[1] != ids[2] && ids[2] != ids[0] {
                triangles.push(ids);
                file_index.push(i as u32);
            }
        }
        let mut mesh = Mesh {
            vertices,
            triangles,
            tri_edges: Vec::new(),
            edges: Vec::new(),
            file_index,
        };
        mesh.pair_edges()?;
        let v = mesh.volume();
        if v.abs() <= 1e-9 * mesh.extent().powi(3) {
            return Err(MeshFault::Flat);
        }
        if v < 0.0 {
            // Every triangle faces in: the solid is the same, turned out.
            for t in &mut mesh.triangles {
                t.swap(1, 2);
            }
            for e in &mut mesh.tri_edges {
                // a→c, c→b, b→a: the edges of the swapped triangle.
                *e = [e[2], e[1], e[0]];
            }
        }
        Ok(mesh)
    }

    /// Pairs every triangle's edges with its neighbour's; the faults when
    /// an edge has not exactly two triangles running along it both ways.
    fn pair_edges(&mut self) -> Result<(), MeshFault> {
        // (lower vertex, upper vertex, triangle, side of the triangle,
        // whether the triangle runs lower → upper), sorted by edge.
        let mut uses: Vec<(u32, u32, u32, u8, bool)> = Vec::with_capacity(3 * self.triangles.len());
        for (t, tri) in self.triangles.iter().enumerate() {
            for s in 0..3 {
                let (a, b) = (tri[s], tri[(s + 1) % 3]);
                uses.push((a.min(b), a.max(b), t as u32, s as u8, a < b));
            }
        }
        uses.sort_unstable();
        let mut tri_edges = vec![[0u32; 3]; self.triangles.len()];
        let mut edges = Vec::with_capacity(uses.len() / 2);
        let mut faults = Faults::default();
        for group in uses.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
            let e = edges.len() as u32;
            edges.push([group[0].0, group[0].1]);
            for &(_, _, t, s, _) in group {
                tri_edges[t as usize][s as usize] = e;
            }
            match group {
                [x, y] if x.4 != y.4 => {}
                [x, y] => faults.flipped(x.2, y.2, (x.0, x.1)),
                [x] => faults.open(x.2, (x.0, x.1)),
                many => faults.non_manifold(many.iter().map(|u| u.2), (many[0].0, many[0].1)),
            }
        }
        if let Some(f) = faults.first(self) {
            return Err(f);
        }
        self.tri_edges = tri_edges;
        self.edges = edges;
        Ok(())
    }

    /// The signed volume (mm³; positive when the triangles face out, as
    /// they do once [`Mesh::new`] has made it).
    pub fn volume(&self) -> f64 {
        self.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| Vector3::from(self.vertices[i as usize]));
                a.dot(&b.cross(&c)) / 6.0
            })
            .sum()
    }

    /// The area of its surface (mm²).
    pub fn surface(&self) -> f64 {
        self.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| Vector3::from(self.vertices[i as usize]));
                (b - a).cross(&(c - a)).norm() / 2.0
            })
            .sum()
    }

    /// The largest side of the box round the mesh (mm).
    fn extent(&self) -> f64 {
        let (lo, hi) = self.bounds();
        (0..3).map(|i| hi[i] - lo[i]).fold(0.0, f64::max)
    }

    /// The corners of the box round the mesh (mm).
    pub fn bounds(&self) -> ([f64; 3], [f64; 3]) {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for v in &self.vertices {
            for i in 0..3 {
                lo[i] = lo[i].min(v[i]);
                hi[i] = hi[i].max(v[i]);
            }
        }
        (lo, hi)
    }

    /// How many triangles it has (without those with two equal corners).
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Its triangles' corners (mm, placed), each triangle facing out.
    pub fn triangles(&self) -> impl Iterator<Item = [[f64; 3]; 3]> + '_ {
        self.triangles
            .iter()
            .map(|t| t.map(|i| self.vertices[i as usize]))
    }

    /// The file's number of kept triangle `t`.
    fn file_number(&self, t: u32) -> usize {
        self.file_index[t as usize] as usize
    }

    fn edge_ends(&self, (a, b): (u32, u32)) -> [[f64; 3]; 2] {
        [self.vertices[a as usize], self.vertices[b as usize]]
    }
}

/// The faults [`Mesh::pair_edges`] finds, gathered: how many of each kind
/// and the first of each.
#[derive(Default)]
struct Faults {
    open: usize,
    open_tris: Vec<u32>,
    open_first: Option<(u32, u32)>,
    many: usize,
    many_first: Option<(Vec<u32>, (u32, u32))>,
    flipped: usize,
    flipped_first: Option<([u32; 2], (u32, u32))>,
}

impl Faults {
    fn open(&mut self, t: u32, e: (u32, u32)) {
        self.open += 1;
        self.open_first.get_or_insert(e);
        if self.open_tris.len() < MAX_LISTED && !self.open_tris.contains(&t) {
            self.open_tris.push(t);
        }
    }

    fn non_manifold(&mut self, ts: impl Iterator<Item = u32>, e: (u32, u32)) {
        self.many += 1;
        if self.many_first.is_none() {
            self.many_first = Some((ts.take(MAX_LISTED).collect(), e));
        }
    }

    fn flipped(&mut self, a: u32, b: u32, e: (u32, u32)) {
        self.flipped += 1;
        self.flipped_first.get_or_insert(([a, b], e));
    }

    /// The fault to report: an open surface first (the most common, and
    /// one a missing triangle also makes look non-manifold nowhere else).
    fn first(self, m: &Mesh) -> Option<MeshFault> {
        let numbers = |ts: &[u32]| {
            let mut v: Vec<usize> = ts.iter().map(|&t| m.file_number(t)).collect();
            v.sort_unstable();
            v
        };
        if let Some(e) = self.open_first {
            return Some(MeshFault::Open {
                edges: self.open,
                triangles: numbers(&self.open_tris),
                at: m.edge_ends(e),
            });
        }
        if let Some((ts, e)) = self.many_first {
            return Some(MeshFault::NonManifold {
                edges: self.many,
                triangles: numbers(&ts),
                at: m.edge_ends(e),
            });
        }
        self.flipped_first.map(|(ts, e)| {
            let n = numbers(&ts);
            MeshFault::Flipped {
                edges: self.flipped,
                triangles: [n[0], n[1]],
                at: m.edge_ends(e),
            }
        })
    }
}
