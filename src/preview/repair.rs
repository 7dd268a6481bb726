//! What the preview draws of a part built on a scan (docs/repair.md, *The
//! preview*): the scanned surface as a field of points, and the finished
//! face's places coloured by how far the plan's bead model predicts it
//! departs from the top asked for (the report's `finish`,
//! [`crate::report::finish`]). From the model, as the report's design is:
//! the plan alone does not hold the scan's surface or the top.

use crate::ir::Program;
use crate::report::finish;
use crate::sema::model::{Build, Model};
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

/// The overlay of `model`'s solid as `program` lays it; `None` for a solid
/// neither on a scan nor up to a top.
pub fn of(program: &Program, model: &Model) -> Option<Overlay> {
    let Build::Variable { extrusion, .. } = &model.build else {
        return None;
    };
    let mut out = Overlay::default();
    if let Some(base) = &extrusion.base {
        let s = &base.surface;
        let ([x0, y0], [x1, y1]) = s.extent();
        let area = ((x1 - x0) * (y1 - y0)).abs();
        let step = s.cell().max((area / MAX_SCAN as f64).sqrt());
        if step.is_finite() && step > 0.0 {
            let (nx, ny) = (((x1 - x0) / step) as usize, ((y1 - y0) / step) as usize);
            for j in 0..=ny {
                for i in 0..=nx {
                    let p = [x0 + i as f64 * step, y0 + j as f64 * step];
                    if let Some(z) = s.at(p) {
                        out.scan.push([p[0] as f32, p[1] as f32, z as f32]);
                    }
                }
            }
        }
    }
    if let Some((f, samples)) = finish::sampled(program, model) {
        let k = samples.len().div_ceil(MAX_FINISH).max(1);
        out.finish = samples
            .iter()
            .step_by(k)
            .map(|s| [s.at[0] as f32, s.at[1] as f32, s.top as f32, s.off as f32])
            .collect();
        (out.below, out.above) = (f.below_mm, f.above_mm);
    }
    Some(out)
}
