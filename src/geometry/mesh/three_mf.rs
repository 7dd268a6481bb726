//! 3MF files (the 3D Manufacturing Format: a ZIP package holding an XML
//! model), read with the `threemf` crate, as the triangles of every build
//! item placed by its transform, and the millimetres one unit of the model
//! is (its `unit` attribute).
//!
//! What lmdc builds is one solid: every build item's object (its mesh, or
//! its components', each placed by its own transform) goes into one list
//! of triangles, which [`super::Mesh::new`] welds and checks like an STL's.
//! Materials, colours, textures, beam lattices, slices and metadata are not
//! read; a package whose objects lie in more than one model part (the
//! production extension) is refused.
//!
//! Triangles are numbered from 0 through the build items in their order,
//! each object's triangles in the file's order, so the numbers a fault
//! names are the object's own when the build has one item of one mesh.

use super::stl::{Triangle, MAX_TRIANGLES};
use nalgebra::{Matrix4, Point3};
use std::collections::HashMap;
use std::io::Cursor;
use threemf::model::{Model, Object, Unit};

/// Most bytes the model parts of a package may hold once inflated, as
/// much as a mesh file may have (`sema::data::MAX_MESH`): about 10 M
/// triangles of XML, which the reader holds parsed at about twice that.
pub const MAX_MODEL_BYTES: u64 = 1 << 30;

/// Most times a model part may inflate its compressed size, once it is
/// past [`RATIO_FREE`] bytes: a mesh's XML deflates about 5 to 10 times,
/// a ZIP bomb's blank space a thousand.
pub const MAX_RATIO: u64 = 100;

/// Model parts up to this many bytes inflated are read whatever their
/// ratio: they cost little.
pub const RATIO_FREE: u64 = 16 << 20;

/// Most levels of components within components.
pub const MAX_DEPTH: usize = 32;

/// A 3MF's triangles (in the model's unit, each build item placed by its
/// transform) and how many mm one unit of it is.
#[derive(Debug)]
pub struct ThreeMf {
    /// Every build item's triangles, item after item.
    pub triangles: Vec<Triangle>,
    /// Millimetres per unit of the model (its `unit`).
    pub scale: f64,
    /// The model's unit as the file names it (`millimeter`, `inch`, …).
    pub unit: &'static str,
}

/// Why a file is no 3MF lmdc can read.
#[derive(Clone, Debug, PartialEq)]
pub enum ThreeMfError {
    /// Not a ZIP package (a 3MF is one).
    NotZip {
        /// What the ZIP reader said.
        why: String,
    },
    /// A package with no `.model` part.
    NoModel,
    /// Model parts that would inflate past [`MAX_MODEL_BYTES`].
    TooLarge {
        /// The bytes they declare.
        bytes: u64,
    },
    /// A model part that inflates more than [`MAX_RATIO`] times its
    /// compressed size (past [`RATIO_FREE`] bytes): a ZIP bomb.
    Inflates {
        /// The bytes it declares inflated.
        bytes: u64,
        /// Its bytes compressed.
        compressed: u64,
    },
    /// Objects in several model parts (the production extension).
    SeveralModels {
        /// How many model parts.
        count: usize,
    },
    /// A model part that is no 3MF model XML lmdc reads.
    Xml {
        /// What the XML reader said.
        why: String,
    },
    /// A build with no item: nothing to make.
    NoItem,
    /// A build item or component naming an object the model lacks.
    NoObject {
        /// The object id it names.
        id: usize,
        /// The build item (from 1) it is in.
        item: usize,
    },
    /// A triangle naming a vertex the object lacks.
    Index {
        /// The object's id.
        object: usize,
        /// The triangle, from 0 in the object.
        triangle: usize,
        /// The vertex index it names.
        index: usize,
        /// How many vertices the object has.
        vertices: usize,
    },
    /// A vertex or transform that is no finite number.
    NotFinite {
        /// The object's id.
        object: usize,
        /// The build item (from 1) it is in.
        item: usize,
    },
    /// Components nested deeper than [`MAX_DEPTH`] (or in a loop).
    TooDeep {
        /// The object where it went too deep.
        object: usize,
        /// The build item (from 1) it is in.
        item: usize,
    },
    /// A build of no triangle.
    Empty,
    /// More triangles than [`MAX_TRIANGLES`] once every item is placed.
    TooMany,
}

/// A 3MF affine transform as the file writes it: `m00 m01 m02 m10 m11 m12
/// m20 m21 m22 m30 m31 m32`, a point (x, y, z) going to
/// (x, y, z, 1) times the 4×3 matrix of those rows.
type Affine = [f64; 12];

/// The transform `m` as a matrix acting on column vectors (x, y, z, 1):
/// the file's rows are its columns.
fn matrix(m: &Affine) -> Matrix4<f64> {
    #[rustfmt::skip]
    let out = Matrix4::new(
        m[0], m[3], m[6], m[9],
        m[1], m[4], m[7], m[10],
        m[2], m[5], m[8], m[11],
        0.0, 0.0, 0.0, 1.0,
    );
    out
}

/// Whether `m` mirrors (its linear part's determinant is negative): the
/// triangles it places run the other way round.
fn mirrors(m: &Matrix4<f64>) -> bool {
    m.fixed_view::<3, 3>(0, 0).determinant() < 0.0
}

/// The triangles of the 3MF package `bytes`.
pub fn read(bytes: &[u8]) -> Result<ThreeMf, ThreeMfError> {
    check_package(bytes)?;
    // The ZIP reader inflates an entry no further than it declares (an
    // I/O error past it), so the declared sizes checked bound the work.
    let mut models = threemf::read(Cursor::new(bytes)).map_err(|e| match e {
        threemf::Error::Zip(z) => ThreeMfError::NotZip { why: z.to_string() },
        threemf::Error::XMLDe(x) => ThreeMfError::Xml { why: x.to_string() },
        other => ThreeMfError::Xml {
            why: other.to_string(),
        },
    })?;
    let model = match models.len() {
        0 => return Err(ThreeMfError::NoModel),
        1 => models.remove(0),
        count => return Err(ThreeMfError::SeveralModels { count }),
    };
    let (scale, unit) = unit(&model.unit);
    Ok(ThreeMf {
        triangles: build(&model)?,
        scale,
        unit,
    })
}

/// Checks `bytes` is a ZIP package whose model parts inflate to at most
/// [`MAX_MODEL_BYTES`] together and [`MAX_RATIO`] times their compressed
/// size each (as their entries declare), before inflating any.
fn check_package(bytes: &[u8]) -> Result<(), ThreeMfError> {
    let mut zip = zip::ZipArchive::new(Cursor::new(bytes))
        .map_err(|e| ThreeMfError::NotZip { why: e.to_string() })?;
    let mut total = 0u64;
    let mut models = 0usize;
    for i in 0..zip.len() {
        let f = zip
            .by_index_raw(i)
            .map_err(|e| ThreeMfError::NotZip { why: e.to_string() })?;
        let name = f
            .name()
            .map_err(|e| ThreeMfError::NotZip { why: e.to_string() })?;
        if name.ends_with(".model") {
            models += 1;
            let (bytes, compressed) = (f.size(), f.compressed_size());
            if bytes > RATIO_FREE && bytes > compressed.saturating_mul(MAX_RATIO) {
                return Err(ThreeMfError::Inflates { bytes, compressed });
            }
            total = total.saturating_add(bytes);
        }
    }
    if models == 0 {
        return Err(ThreeMfError::NoModel);
    }
    if total > MAX_MODEL_BYTES {
        return Err(ThreeMfError::TooLarge { bytes: total });
    }
    Ok(())
}

/// Millimetres per unit of `u`, and its name in the file.
fn unit(u: &Unit) -> (f64, &'static str) {
    match u {
        Unit::Micron => (0.001, "micron"),
        Unit::Millimeter => (1.0, "millimeter"),
        Unit::Centimeter => (10.0, "centimeter"),
        Unit::Inch => (25.4, "inch"),
        Unit::Foot => (304.8, "foot"),
        Unit::Meter => (1000.0, "meter"),
    }
}

/// Every build item's triangles, placed.
fn build(model: &Model) -> Result<Vec<Triangle>, ThreeMfError> {
    if model.build.item.is_empty() {
        return Err(ThreeMfError::NoItem);
    }
    let objects: HashMap<usize, &Object> =
        model.resources.object.iter().map(|o| (o.id, o)).collect();
    let mut out = Vec::new();
    for (n, item) in model.build.item.iter().enumerate() {
        let at = Place {
            objects: &objects,
            item: n + 1,
        };
        let m = item
            .transform
            .as_ref()
            .map_or_else(Matrix4::identity, matrix);
        at.object(item.objectid, &m, 0, &mut out)?;
    }
    if out.is_empty() {
        return Err(ThreeMfError::Empty);
    }
    Ok(out)
}

/// Places a build item's objects.
struct Place<'a> {
    objects: &'a HashMap<usize, &'a Object>,
    /// The build item, from 1.
    item: usize,
}

impl Place<'_> {
    /// Adds object `id`'s triangles, placed by `m`, to `out`; `depth`
    /// components deep.
    fn object(
        &self,
        id: usize,
        m: &Matrix4<f64>,
        depth: usize,
        out: &mut Vec<Triangle>,
    ) -> Result<(), ThreeMfError> {
        let item = self.item;
        let object = self
            .objects
            .get(&id)
            .ok_or(ThreeMfError::NoObject { id, item })?;
        if depth > MAX_DEPTH {
            return Err(ThreeMfError::TooDeep { object: id, item });
        }
        if m.iter().any(|x| !x.is_finite()) {
            return Err(ThreeMfError::NotFinite { object: id, item });
        }
        if let Some(mesh) = &object.mesh {
            self.mesh(id, mesh, m, out)?;
        }
        for c in object.components.iter().flat_map(|c| &c.component) {
            // The component's own transform first, then the one placing it.
            let inner = m * c.transform.as_ref().map_or_else(Matrix4::identity, matrix);
            self.object(c.objectid, &inner, depth + 1, out)?;
        }
        Ok(())
    }

    /// Adds a mesh's triangles, placed by `m`, to `out`.
    fn mesh(
        &self,
        id: usize,
        mesh: &threemf::Mesh,
        m: &Matrix4<f64>,
        out: &mut Vec<Triangle>,
    ) -> Result<(), ThreeMfError> {
        let tris = &mesh.triangles.triangle;
        if out.len().saturating_add(tris.len()) > MAX_TRIANGLES {
            return Err(ThreeMfError::TooMany);
        }
        let vs = &mesh.vertices.vertex;
        let flip = mirrors(m);
        out.reserve(tris.len());
        for (t, tri) in tris.iter().enumerate() {
            let mut corners = [[0f32; 3]; 3];
            for (c, &v) in corners.iter_mut().zip(&[tri.v1, tri.v2, tri.v3]) {
                let p = vs.get(v).ok_or(ThreeMfError::Index {
                    object: id,
                    triangle: t,
                    index: v,
                    vertices: vs.len(),
                })?;
                let q = m.transform_point(&Point3::new(p.x, p.y, p.z));
                let q = [q.x as f32, q.y as f32, q.z as f32];
                if q.iter().any(|x| !x.is_finite()) {
                    return Err(ThreeMfError::NotFinite {
                        object: id,
                        item: self.item,
                    });
                }
                *c = q;
            }
            if flip {
                corners.swap(1, 2);
            }
            out.push(corners);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The file's rows are read as a row vector (x, y, z, 1) times them,
    /// and a transform after another is their product, the later on the left.
    #[test]
    fn transforms_read_as_the_file_writes_them() {
        let a = [
            0.3, -1.2, 0.5, 2.0, 0.1, -0.7, 0.4, 0.9, 1.5, 3.0, -2.0, 7.0,
        ];
        let b = [
            1.1, 0.2, -0.3, -0.4, 0.8, 0.6, 0.5, -0.9, 1.2, -1.0, 4.0, 0.5,
        ];
        let row = |m: &Affine, p: [f64; 3]| -> [f64; 3] {
            std::array::from_fn(|j| p[0] * m[j] + p[1] * m[3 + j] + p[2] * m[6 + j] + m[9 + j])
        };
        for p in [[0.0, 0.0, 0.0], [1.0, 2.0, 3.0], [-4.5, 0.25, 9.0]] {
            let one = (matrix(&b) * matrix(&a)).transform_point(&Point3::from(p));
            let two = row(&b, row(&a, p));
            for j in 0..3 {
                assert!((one[j] - two[j]).abs() < 1e-12, "{one:?} {two:?}");
            }
        }
        assert!(!mirrors(&Matrix4::identity()));
        assert!(mirrors(&matrix(&[
            -1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0
        ])));
    }
}
