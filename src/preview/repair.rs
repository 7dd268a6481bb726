//! What the preview draws of a part built on a scan (docs/repair.md, *The
//! preview*): the scanned surface as a field of points, and the finished
//! face's places coloured by how far the plan's bead model predicts it
//! departs from the top asked for (the report's `finish`). The plan alone
//! does not hold the scan's surface or the top: the pipeline joins the
//! model and the report into an [`Overlay`] (`pipeline::repair_overlay`),
//! which the page only draws.

use serde::Serialize;

/// Most points of the scanned surface the page carries.
pub const MAX_SCAN: usize = 20_000;

/// Most places of the finish the page carries.
pub const MAX_FINISH: usize = 20_000;

/// The scan and the finish, as the page draws them.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Overlay {
    /// The scanned surface: `[x, y, z]`, mm, on a square grid.
    pub scan: Vec<[f32; 3]>,
    /// The finish's places: `[x, y, top, departure]`, mm.
    pub finish: Vec<[f32; 4]>,
    /// The most the face lies below the top, mm (≥ 0).
    pub below: f64,
    /// The most it stands above, mm (≥ 0).
    pub above: f64,
}
