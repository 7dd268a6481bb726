//! A measured part to build on: a scan as points or a triangle mesh (PLY,
//! ASCII XYZ/CSV, STL, 3MF, E57), placed in the part's coordinates, and the
//! surface seen from above as a height field on a square grid
//! ([`HeightField`]), the base a repair's first layer lies on
//! (docs/repair.md).
//!
//! The readers return [`Raw`]: the file's vertices in its own units and its
//! faces as triangles of vertex indices. [`HeightField::new`] places them
//! and estimates the surface robustly (each cell's height a plane fitted
//! through the points of its 3 × 3 cells, the wild ones left out; a mesh's
//! faces rastered; then cells that stand out from their neighbours by more
//! than a declared height replaced by the neighbours' median). Before that, a scan may be
//! moved onto its nominal by a best fit ([`register`]).

pub mod e57;
mod grid;
pub mod nearest;
pub mod ply;
pub mod register;
pub mod section;
pub mod xyz;

pub use grid::{Estimate, GridFault, HeightField, Stats, MAX_CELLS};
pub use register::{Fit, FitFault, Freedom, Rigid};

use crate::geometry::mesh::{Mesh, Placement};
use nalgebra::{Rotation3, Vector3};

/// Where a scan's points go in the part's coordinates: scaled, turned,
/// moved — a declared placement, and a best fit's move after it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// mm per file unit.
    pub scale: f64,
    /// The turn, after scaling.
    pub rot: Rotation3<f64>,
    /// Where the file's origin goes, mm.
    pub at: Vector3<f64>,
}

impl From<Placement> for Pose {
    fn from(p: Placement) -> Pose {
        Pose {
            scale: p.scale,
            rot: Rotation3::from_euler_angles(p.turn[0], p.turn[1], p.turn[2]),
            at: Vector3::from(p.at),
        }
    }
}

impl Pose {
    /// The vertex `v` placed, mm.
    pub fn apply(&self, v: &[f32; 3]) -> [f64; 3] {
        let p = self.rot
            * (Vector3::new(f64::from(v[0]), f64::from(v[1]), f64::from(v[2])) * self.scale)
            + self.at;
        [p.x, p.y, p.z]
    }

    /// This pose, then the rigid move `m`.
    pub fn then(&self, m: &Rigid) -> Pose {
        Pose {
            scale: self.scale,
            rot: m.rot * self.rot,
            at: m.rot * self.at + m.shift,
        }
    }
}

/// Most vertices (points) a scan may have: 12 bytes each once read and 16
/// while the grid sorts them; a line scanner's pass over a 300 mm part at
/// 0.1 mm is a few million.
pub const MAX_POINTS: usize = 10_000_000;

/// Most triangles a scan's faces may have (as for a mesh solid).
pub const MAX_FACES: usize = crate::geometry::mesh::stl::MAX_TRIANGLES;

/// A scan as read: vertices in the file's units, and triangles (faces of
/// more corners fanned into triangles) as indices into them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Raw {
    /// The points, in the file's units, in its order.
    pub vertices: Vec<[f32; 3]>,
    /// Triangles of three vertex indices; empty for a point cloud.
    pub triangles: Vec<[u32; 3]>,
}

impl Raw {
    /// A scan given as an STL's or 3MF's triangles (corners as written).
    pub fn from_triangles(tris: &[crate::geometry::mesh::stl::Triangle]) -> Raw {
        let mut vertices = Vec::with_capacity(tris.len() * 3);
        let mut triangles = Vec::with_capacity(tris.len());
        for t in tris {
            let i = vertices.len() as u32;
            vertices.extend_from_slice(t);
            triangles.push([i, i + 1, i + 2]);
        }
        Raw {
            vertices,
            triangles,
        }
    }
}

/// Most faces a scan's [`Faces::solid`] builds a tree of: more, and the
/// faces are not kept nor consulted (a height field's rule stands).
pub const MAX_TREE_FACES: usize = 4_000_000;

/// A scan's faces as read and where they go: where they close a solid,
/// what tells a real step of the part (a face there) from the cliff its
/// height field draws under a part that overhangs itself (air there)
/// (docs/repair.md, *A scan with faces tells a step*). A scan's open
/// surface tells nothing: seen from one side, a scanner's mesh joins an
/// overhang's edge to the floor under it by faces where there is air.
#[derive(Debug)]
pub struct Faces {
    raw: Raw,
    pose: Pose,
    solid: std::sync::OnceLock<Option<nearest::TriangleTree>>,
}

impl Faces {
    /// The faces of `raw` placed by `pose`; `None` for a point cloud, or
    /// more than [`MAX_TREE_FACES`] faces (not asked: none kept).
    pub fn new(raw: Raw, pose: Pose) -> Option<Faces> {
        let n = raw.triangles.len();
        (n > 0 && n <= MAX_TREE_FACES).then(|| Faces {
            raw,
            pose,
            solid: std::sync::OnceLock::new(),
        })
    }

    /// The placed faces as a tree, each facing out of the solid they
    /// close, made once; `None` when they close none (a mesh solid's rule,
    /// [`Mesh::new`]: corners with the same coordinates are one, and every
    /// edge is shared by exactly two faces running it opposite ways).
    pub fn solid(&self) -> Option<&nearest::TriangleTree> {
        self.solid
            .get_or_init(|| {
                let tris: Vec<crate::geometry::mesh::stl::Triangle> = self
                    .raw
                    .triangles
                    .iter()
                    .map(|t| t.map(|i| self.raw.vertices[i as usize]))
                    .collect();
                let (x, y, z) = self.pose.rot.euler_angles();
                let place = Placement {
                    scale: self.pose.scale,
                    turn: [x, y, z],
                    at: self.pose.at.into(),
                };
                let mesh = Mesh::new(&tris, place).ok()?;
                let placed: Vec<nearest::Tri> = mesh.triangles().collect();
                Some(nearest::TriangleTree::new(&placed))
            })
            .as_ref()
    }
}

/// Why a scan file cannot be read.
#[derive(Clone, Debug, PartialEq)]
pub enum ScanError {
    /// A PLY whose header or body the reader refused (its words).
    Ply(String),
    /// An E57 the `e57` crate refused (its words).
    E57(String),
    /// A PLY with no `vertex` element, or one without `x`, `y` and `z`.
    NoVertices,
    /// A face naming a vertex the file does not have.
    BadIndex {
        /// The face, from 0.
        face: usize,
        /// The index it names.
        index: i64,
    },
    /// A line of an XYZ/CSV file that is not three numbers or more.
    Line {
        /// The line, from 1.
        line: usize,
        /// What it holds (shortened).
        text: String,
    },
    /// A line of an XYZ/CSV file with another count of numbers than the
    /// first data line's.
    Columns {
        /// The line, from 1.
        line: usize,
        /// How many numbers it holds.
        count: usize,
        /// The first data line, from 1.
        first: usize,
        /// How many that holds.
        expected: usize,
    },
    /// An XYZ/CSV file whose first column counts the lines from `from`:
    /// an index, not x.
    Index {
        /// Its first value.
        from: f64,
    },
    /// A coordinate that is no finite number.
    NotFinite {
        /// The vertex, from 0.
        vertex: usize,
    },
    /// More points or faces than lmdc reads.
    TooMany {
        /// "points" or "faces".
        what: &'static str,
        /// How many the file says or has.
        count: u64,
        /// The most lmdc reads.
        max: usize,
    },
    /// No point at all.
    Empty,
}

impl std::fmt::Display for ScanError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ScanError::Ply(why) => write!(f, "the PLY reader stopped: {why}"),
            ScanError::E57(why) => write!(f, "the E57 reader stopped: {why}"),
            ScanError::NoVertices => write!(
                f,
                "it has no `vertex` element with `x`, `y` and `z` properties"
            ),
            ScanError::BadIndex { face, index } => write!(
                f,
                "face {face} names vertex {index}, which the file does not have"
            ),
            ScanError::Line { line, text } => write!(
                f,
                "line {line} (`{text}`) is not three numbers x, y, z (separated by spaces, commas or semicolons)"
            ),
            ScanError::Columns { line, count, first, expected } => write!(
                f,
                "line {line} holds {count} numbers where line {first} holds {expected}: a point file has one point a line, every line with the same columns (a decimal comma in a comma-separated file splits a number in two: separate its fields by semicolons or tabs)"
            ),
            ScanError::Index { from } => write!(
                f,
                "its first column counts the lines ({from}, {}, {}, …): an index, not x; export the points without it, x y z first",
                from + 1.0,
                from + 2.0
            ),
            ScanError::NotFinite { vertex } => {
                write!(f, "point {vertex} has a coordinate that is no finite number")
            }
            ScanError::TooMany { what, count, max } => {
                write!(f, "it has {count} {what}, more than the {max} lmdc reads")
            }
            ScanError::Empty => write!(f, "it has no point"),
        }
    }
}

/// The formats a scan may be in, by the file's name (or its first bytes).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Stanford PLY, ASCII or binary.
    Ply,
    /// STL, binary or ASCII.
    Stl,
    /// A 3MF package.
    ThreeMf,
    /// An E57 (ASTM E2807) scan: points, in metres.
    E57,
    /// Text: a point a line, `x y z` or `x,y,z` (more columns ignored).
    Xyz,
}

impl Format {
    /// The format of `path` with contents `bytes`: the magic words first
    /// (`ply`, `ASTM-E57`, a ZIP's `PK`, an STL's `solid` or binary length), then the
    /// extension; anything else is read as XYZ text.
    pub fn of(path: &str, bytes: &[u8]) -> Format {
        let ext = path
            .rsplit_once('.')
            .map(|(_, e)| e.to_ascii_lowercase())
            .unwrap_or_default();
        if bytes.starts_with(b"ply") {
            Format::Ply
        } else if bytes.starts_with(b"ASTM-E57") || ext == "e57" {
            Format::E57
        } else if bytes.starts_with(b"PK") || ext == "3mf" {
            Format::ThreeMf
        } else if ext == "stl" {
            Format::Stl
        } else {
            Format::Xyz
        }
    }
}

/// Checks every vertex is finite and there is one.
pub(crate) fn check_points(raw: &Raw) -> Result<(), ScanError> {
    if raw.vertices.is_empty() {
        return Err(ScanError::Empty);
    }
    if let Some(v) = raw
        .vertices
        .iter()
        .position(|p| p.iter().any(|c| !c.is_finite()))
    {
        return Err(ScanError::NotFinite { vertex: v });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A block's 12 triangles as a scan's faces, three corners each (as
    /// an STL gives them), turned inside out when `inward`.
    fn block_raw(inward: bool) -> Raw {
        let tris: Vec<nearest::Tri> = nearest::block([0.0; 3], [10.0, 4.0, 2.0]);
        let mut raw = Raw::default();
        for t in tris {
            let t = if inward { [t[0], t[2], t[1]] } else { t };
            let i = raw.vertices.len() as u32;
            raw.vertices.extend(t.map(|c| c.map(|v| v as f32)));
            raw.triangles.push([i, i + 1, i + 2]);
        }
        raw
    }

    #[test]
    fn faces_that_close_a_solid_face_out_and_an_open_surface_is_none() {
        let pose = Pose {
            scale: 1.0,
            rot: Rotation3::identity(),
            at: Vector3::zeros(),
        };
        for inward in [false, true] {
            let f = Faces::new(block_raw(inward), pose).unwrap();
            let tree = f.solid().expect("a closed block");
            // Down onto the top: its normal up, whichever way the file ran.
            let (t, n) = tree
                .first_hit([3.0, 1.0, 5.0], [0.0, 0.0, -1.0], 9.0)
                .unwrap();
            assert!((t - 3.0).abs() < 1e-9 && n == [0.0, 0.0, 1.0], "{t} {n:?}");
        }
        // A face left out: an open box, no solid.
        let mut open = block_raw(false);
        open.triangles.pop();
        assert!(Faces::new(open, pose).unwrap().solid().is_none());
        // One face turned against its neighbours: no solid either.
        let mut twisted = block_raw(false);
        twisted.triangles[0].swap(1, 2);
        assert!(Faces::new(twisted, pose).unwrap().solid().is_none());
        assert!(Faces::new(Raw::default(), pose).is_none());
    }
}
