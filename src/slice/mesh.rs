//! A mesh's layers: each layer's section, cut halfway up the part of the
//! layer the mesh reaches (so the top layer, rounded up past the mesh, is
//! cut within it), as an outline and its holes of straight pieces — the
//! mesh's own polygons, nothing smoothed. A layer cut into separate
//! islands is [`Shape::Islands`].

use crate::diag::{message, Diagnostics};
use crate::geometry::mesh::{self, Loop};
use crate::sema::model::{Hole, MeshSolid, Outline, RegionShape, Segment, Shape};
use crate::units::Length;

/// The shape of each of `n` layers `lift` apart; `None` after reporting a
/// layer whose section is no region.
pub fn shapes(
    m: &MeshSolid,
    n: usize,
    lift: Length,
    diags: &mut Diagnostics,
) -> Option<Vec<Shape>> {
    let mut sections = m.mesh.sections();
    let mut out = Vec::with_capacity(n.min(1 << 16));
    for k in 0..n {
        let base = k as f64 * lift.0;
        let z = (base + ((k + 1) as f64 * lift.0).min(m.top.0)) / 2.0;
        let section = sections
            .loops(z)
            .and_then(mesh::islands)
            .map_err(|f| diags.push(message::mesh::section(&f, k, z, m.span)))
            .ok()?;
        out.push(layer_shape(section, m));
    }
    Some(out)
}

/// A layer's islands as its shape: the one island's shape, or
/// [`Shape::Islands`].
fn layer_shape(mut islands: Vec<mesh::Section>, m: &MeshSolid) -> Shape {
    if islands.len() == 1 {
        return shape(islands.remove(0), m);
    }
    Shape::Islands(islands.into_iter().map(|s| shape(s, m)).collect())
}

/// An island as a shape: a region when it has holes.
fn shape(s: mesh::Section, m: &MeshSolid) -> Shape {
    let outer = Shape::Outline(outline(&s.outline));
    if s.holes.is_empty() {
        return outer;
    }
    Shape::Region(Box::new(RegionShape {
        outline: outer,
        outline_span: m.span,
        holes: s
            .holes
            .iter()
            .map(|h| Hole {
                shape: Shape::Outline(outline(h)),
                span: m.span,
            })
            .collect(),
    }))
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
