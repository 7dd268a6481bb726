//! The closest each body a machine carries came to each thing of the cell
//! along its plan (docs/collision.md, *Closest approaches*): what
//! `lmdc report` lists and `lmdc preview` marks, gathered by the collision
//! rules as they check (`verify::collision`, `verify::arm`).

use crate::plan::Where;
use serde::Serialize;

/// The closest one body came to one thing, and where.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Approach {
    /// The body: a head's solid (`nozzle`, `body`, …) or an arm's link
    /// (`upper arm`, `forearm`, `wrist`).
    pub body: String,
    /// What it came near: `plate`, `fixture NAME`, `part`, `positioner
    /// faceplate`.
    pub with: String,
    /// How far apart they were, mm (negative: one ran that deep into the
    /// other).
    pub distance_mm: f64,
    /// The gap the body keeps, mm.
    pub gap_mm: f64,
    /// The layer of the move, from 1 (none: the retract after the last
    /// path).
    pub layer: Option<usize>,
    /// The path in the layer, from 1.
    pub path: Option<usize>,
    /// The point in the path, from 1 (none: a clearance move).
    pub point: Option<usize>,
    /// How far along the move to it the pose lies (1: at its end).
    pub way: f64,
    /// The move, in the messages' words.
    pub at: String,
    /// The laser focus at that pose, in the part's coordinates, mm.
    pub focus: [f64; 3],
}

impl Approach {
    /// The approach of `body` to `with`, `distance` apart (`gap` kept),
    /// `way` along the move to `at`, the focus at `focus`.
    pub fn new(
        (body, with): (&str, &str),
        (distance, gap): (f64, f64),
        at: Where,
        way: f64,
        focus: [f64; 3],
    ) -> Approach {
        let (layer, path, point) = match at {
            Where::Point { layer, path, point } => {
                (Some(layer + 1), Some(path + 1), Some(point + 1))
            }
            Where::Clearance { layer, path } => (Some(layer + 1), Some(path + 1), None),
            Where::End => (None, None, None),
        };
        let along = if way < 1.0 {
            format!("{:.0} % of the way along the move to {at}", way * 100.0)
        } else {
            at.to_string()
        };
        Approach {
            body: body.to_string(),
            with: with.to_string(),
            distance_mm: distance,
            gap_mm: gap,
            layer,
            path,
            point,
            way,
            at: along,
            focus,
        }
    }
}
