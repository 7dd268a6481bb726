//! The design solid's volume, where the model says enough to know it: what
//! the report compares the deposited volume with. Computed from the model
//! (not from the plan, which would compare the plan with itself).
//!
//! - a loft wall: the wall's centre line times the bead width,
//!   swept along the spine: `V = w·∫∮ ρ/R dl ds`, `ρ/R` the stretch of a
//!   point at distance ρ from the bend axis (1 on a straight spine). The band
//!   between two parallel curves `w` apart holds the mid-curve's length
//!   times `w`, sharp corners included;
//! - an extrusion built in flat layers: each layer's profile area
//!   times its lift. A profile given as the tracks' centre line (`size =
//!   centre`) is widened by half a bead all round (Steiner's formula
//!   `A + P·w/2 + π·w²/4`, exact for a convex outline);
//! - a footprint up to a top: `∫ top dA` over the footprint (a
//!   plane or edges top: the area times the top at the centroid; an
//!   expression: sampled on a 256 × 256 grid);
//! - a wall on a scan: `∫ (top − B) dA` over the band the wall covers,
//!   from its right face to its left: the sum over 64 parallel offsets
//!   of the path of `∫ (top − B) ds` along each, times their spacing
//!   (parallel curves' lengths take the bends' stretch), sampled every
//!   0.1 mm (at most 100 000 places an offset);
//! - a footprint filled along a tilted build direction `d`
//!   (`direction = auto`): the same integral in the part turned so `d` is
//!   up, as the fill is planned — over the footprint seen along `d`, of
//!   the target's length along `d` above the scan (a 64 × 64 grid: each
//!   point walks a line through the target).

use crate::diag::Diagnostics;
use crate::geometry::outline::{profile, region};
use crate::geometry::profile::Profile;
use crate::sema::model::{
    Build, Loft, Measure, Model, OpenWall, Shape, Spine, Top, TopExtrusion, WallOnScan,
};
use serde::Serialize;

/// Stations along a loft's spine and angles round its section summed over.
const STATIONS: usize = 400;
const ANGLES: usize = 720;
/// Chord error of flattened outlines, mm.
const CHORD: f64 = 0.005;
/// Samples a side of an expression top's grid.
const GRID: usize = 256;
/// Offsets of a wall's path across its band, and the spacing along each
/// its gap is sampled at, mm.
const BAND: usize = 64;
const ALONG: f64 = 0.1;
/// Samples a side of the grid along a tilted build direction, whose
/// points each walk a line through the target.
const GRID_ALONG: usize = 64;

/// The design solid's volume, or why it is not known.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum Design {
    /// Known.
    Known {
        /// mm³.
        volume_mm3: f64,
        /// What was measured, in words.
        what: String,
    },
    /// Not known.
    Unknown {
        /// Why not.
        why: String,
    },
}

/// The design volume of `model`'s solid; `along`: the build direction
/// of a fill planned along a tilted one (the plan's layers' frame z).
pub fn volume(model: &Model, along: Option<[f64; 3]>) -> Design {
    let Some(bead) = &model.bead else {
        return Design::Unknown {
            why: "a ring's wall has no bead model (its segment table gives the widths)".into(),
        };
    };
    let w = bead.width.0;
    let got = match &model.build {
        Build::Duct { loft, .. } => loft_wall(loft, w),
        Build::Block {
            extrusion, slicing, ..
        } => {
            let mut scratch = Diagnostics::new();
            crate::slice::layers::plan(bead, extrusion, slicing, &mut scratch)
                .map(|layers| {
                    let v: f64 = layers
                        .shapes
                        .iter()
                        .map(|s| area(s, extrusion.measure, w) * layers.lift.0)
                        .sum();
                    (v, "each layer's profile area times its lift".to_string())
                })
                .ok_or_else(|| "the layers could not be planned".to_string())
        }
        Build::Variable { extrusion, .. } => match along {
            None => top_volume(extrusion, w, GRID),
            Some(d) => crate::slice::top::seen_along(extrusion, bead, d)
                .ok_or_else(|| "the part does not turn to the build direction".to_string())
                .and_then(|turned| top_volume(&turned, w, GRID_ALONG))
                .map(|(v, _)| {
                    (v, "the footprint seen along the build direction: its integral, along it, of the target less the scanned surface".to_string())
                }),
        },
        Build::ScanWall { wall, on, pitch, .. } => Ok(scan_wall(wall, on, w, pitch.0)),
        #[allow(unreachable_patterns)]
        _ => Err("lmdc does not measure this kind of solid yet".into()),
    };
    match got {
        Ok((v, what)) if v.is_finite() && v > 0.0 => Design::Known {
            volume_mm3: v,
            what,
        },
        Ok(_) => Design::Unknown {
            why: "the solid's volume came out empty".into(),
        },
        Err(why) => Design::Unknown { why },
    }
}

/// The volume between the scan under a wall's band and its top, for beads
/// `w` wide `pitch` apart. Where the scan has no surface the plan was
/// refused: such points add nothing here.
fn scan_wall(wall: &OpenWall, on: &WallOnScan, w: f64, pitch: f64) -> (f64, String) {
    let [left, right] = wall.reach(w, pitch);
    let step = (left + right) / BAND as f64;
    let mut sum = 0.0;
    let mut collapsed = 0;
    let mut top = crate::slice::wall::top_form(wall, on);
    for k in 0..BAND {
        let d = -right + (k as f64 + 0.5) * step;
        let Some(path) = wall.path.offset(d) else {
            collapsed += 1;
            continue;
        };
        let line = path.flatten(CHORD);
        let length: f64 = line
            .windows(2)
            .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
            .sum();
        // A long wall sampled more coarsely: at most 1e5 places an offset.
        let along = ALONG.max(length / 1e5);
        for piece in line.windows(2) {
            let [a, b] = [piece[0], piece[1]];
            let len = (b[0] - a[0]).hypot(b[1] - a[1]);
            let n = (len / along).ceil().max(1.0) as usize;
            for i in 0..n {
                let f = (i as f64 + 0.5) / n as f64;
                let p = [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])];
                let gap = match (on.base.surface.at(p), top.at(p)) {
                    (Some(z), Ok(t)) => (t - z).max(0.0),
                    _ => 0.0,
                };
                sum += gap * len / n as f64;
            }
        }
    }
    let mut what =
        "the band the wall covers, face to face: its integral of the top less the scanned surface"
            .to_string();
    if collapsed > 0 {
        what += &format!(", without {collapsed} of its {BAND} offsets, which collapse on a bend");
    }
    (sum * step, what)
}

fn loft_wall(loft: &Loft, w: f64) -> Result<(f64, String), String> {
    // The checker already moved a section measured at its outer face to the
    // bead's centre line (sema/loft.rs): the sections are the mid-curve.
    let geo = loft.geometry();
    let (length, radius) = match loft.spine {
        Spine::Line { length } => (length.0, None),
        Spine::Arc { radius, angle } => (radius.0 * angle.0.abs(), Some(radius.0)),
    };
    let mut sum = 0.0;
    for i in 0..STATIONS {
        let s = (i as f64 + 0.5) / STATIONS as f64;
        let f = geo.frame(s);
        let at = |j: usize| {
            let theta = std::f64::consts::TAU * j as f64 / ANGLES as f64;
            geo.point(&f, s, theta).1
        };
        let mut prev = at(0);
        for j in 1..=ANGLES {
            let uv = at(j % ANGLES);
            let dl = ((uv[0] - prev[0]).powi(2) + (uv[1] - prev[1]).powi(2)).sqrt();
            let m = [(uv[0] + prev[0]) / 2.0, (uv[1] + prev[1]) / 2.0];
            let stretch = match (radius, geo.bend_distance(&f, m)) {
                (Some(r), Some(rho)) if r > 0.0 => rho / r,
                _ => 1.0,
            };
            sum += dl * stretch;
            prev = uv;
        }
    }
    Ok((
        w * sum * length / STATIONS as f64,
        "the loft's wall: its centre line times the bead width, swept along the spine".into(),
    ))
}

/// The area a layer of `shape` covers: the shape itself less its holes
/// (outer face), or, for a centre line, the outline widened and every hole
/// shrunk by half a bead (Steiner's formula `A ± P·d + π·d²`: exact for an
/// outward offset of a convex loop and for a round hole; a polygonal hole's
/// sharp inner corners add up to (4 − π)·d²).
fn area(shape: &Shape, measure: Measure, w: f64) -> f64 {
    let r = region(shape, CHORD);
    let hole = |p: &Profile| match measure {
        Measure::Outer => p.area(),
        Measure::Centre => steiner(p, -w / 2.0),
    };
    r.outer()
        .iter()
        .map(|p| widened(p, measure, w))
        .sum::<f64>()
        - r.holes().iter().map(hole).sum::<f64>()
}

/// The area of one outer loop: itself, or its centre line widened by half a
/// bead.
fn widened(p: &Profile, measure: Measure, w: f64) -> f64 {
    match measure {
        Measure::Outer => p.area(),
        Measure::Centre => steiner(p, w / 2.0),
    }
}

/// The area of `p` offset outward by `d` (inward when negative).
fn steiner(p: &Profile, d: f64) -> f64 {
    (p.area() + perimeter(p) * d + std::f64::consts::PI * d * d).max(0.0)
}

fn perimeter(p: &Profile) -> f64 {
    let pts = p.polyline(CHORD);
    (0..pts.len())
        .map(|i| {
            let (a, b) = (pts[i], pts[(i + 1) % pts.len()]);
            ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt()
        })
        .sum()
}

/// Area and centroid of a closed polyline.
fn centroid(pts: &[[f64; 2]]) -> Option<(f64, [f64; 2])> {
    let (mut a, mut cx, mut cy) = (0.0, 0.0, 0.0);
    for i in 0..pts.len() {
        let (p, q) = (pts[i], pts[(i + 1) % pts.len()]);
        let cross = p[0] * q[1] - q[0] * p[1];
        a += cross;
        cx += (p[0] + q[0]) * cross;
        cy += (p[1] + q[1]) * cross;
    }
    (a.abs() > 1e-12).then(|| (a / 2.0, [cx / (3.0 * a), cy / (3.0 * a)]))
}

/// `∫ f dA` over the footprint `p` within its bounds `[lo, hi]`, by the
/// midpoints of an `n` × `n` grid; the first point `f` has no value at
/// ends it.
fn integral(
    p: &Profile,
    [lo, hi]: [[f64; 2]; 2],
    n: usize,
    mut f: impl FnMut([f64; 2]) -> Result<f64, &'static str>,
) -> Result<f64, String> {
    let (dx, dy) = ((hi[0] - lo[0]) / n as f64, (hi[1] - lo[1]) / n as f64);
    let mut sum = 0.0;
    for i in 0..n {
        for j in 0..n {
            let q = [lo[0] + (i as f64 + 0.5) * dx, lo[1] + (j as f64 + 0.5) * dy];
            if p.contains(q) {
                sum += f(q)? * dx * dy;
            }
        }
    }
    Ok(sum)
}

/// A plane's or edges' top at `c` over a footprint within `[lo, hi]`
/// (`None` for an expression).
pub(super) fn linear_top(ex: &TopExtrusion, [lo, hi]: [[f64; 2]; 2], c: [f64; 2]) -> Option<f64> {
    match &ex.top {
        Top::Plane { at, height, slope } => {
            Some(height.0 + slope[0] * (c[0] - at[0].0) + slope[1] * (c[1] - at[1].0))
        }
        Top::Edges { along, from, to } => {
            let k = match along {
                crate::sema::model::Axis::X => 0,
                crate::sema::model::Axis::Y => 1,
            };
            let span = hi[k] - lo[k];
            let t = if span > 0.0 {
                (c[k] - lo[k]) / span
            } else {
                0.0
            };
            Some(from.0 + (to.0 - from.0) * t)
        }
        Top::Expr(_) | Top::Mesh(_) | Top::Solid(_) => None,
    }
}

/// `∫ (top − base) dA` over `ex`'s footprint (a grid `n` a side where the
/// top is sampled), and what it measured.
fn top_volume(ex: &TopExtrusion, w: f64, n: usize) -> Result<(f64, String), String> {
    let p = profile(&ex.shape, CHORD);
    let pts = p.polyline(CHORD);
    let (_, c) = centroid(&pts).ok_or("the footprint is empty")?;
    let footprint = p.area();
    let widen = widened(&p, ex.measure, w) / footprint;
    let [lo, hi] = p.bounds().ok_or("the footprint is empty")?;
    let linear = |c: [f64; 2]| linear_top(ex, [lo, hi], c);
    let v = match (linear(c), &ex.top) {
        (Some(h), _) => footprint * h,
        (None, Top::Expr(e)) => {
            let mut heights = e.evaluator();
            let mut scratch = Diagnostics::new();
            integral(&p, [lo, hi], n, |q| {
                heights
                    .at(q[0], q[1], &mut scratch)
                    .map(|h| h.0)
                    .ok_or("the top has no value somewhere on the footprint")
            })?
        }
        (None, Top::Mesh(m)) => integral(&p, [lo, hi], n, |q| {
            m.surface
                .at(q)
                .ok_or("the target mesh does not cover the footprint everywhere")
        })?,
        (None, Top::Solid(t)) => integral(&p, [lo, hi], n, |q| {
            t.surface
                .at(q)
                .ok_or("the target solid does not cover the footprint everywhere")
        })?,
        (None, _) => return Err("the top is not known".into()),
    };
    let Some(base) = &ex.base else {
        return Ok((v * widen, "the footprint's integral of its top".to_string()));
    };
    // On a scan: less the measured part under the footprint (what is there).
    let under = integral(&p, [lo, hi], n, |q| {
        (base.surface.at(q)).ok_or("the scan does not cover the footprint everywhere")
    })?;
    Ok((
        (v - under) * widen,
        "the footprint's integral of its top less the scanned surface".to_string(),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centroid_of_a_square() {
        let (a, c) = centroid(&[[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]]).unwrap();
        assert!(
            (a - 4.0).abs() < 1e-12 && (c[0] - 1.0).abs() < 1e-12 && (c[1] - 1.0).abs() < 1e-12
        );
    }

    #[test]
    fn a_centre_line_hole_shrinks_by_half_a_bead() {
        // A 10 mm square hole's centre line, 2 mm bead: the opening left is
        // 8 × 8 = 64 mm²; Steiner's formula (exact for round holes, whose
        // inward offset is a circle) misses a square's sharp inner corners by
        // (4 − π)·d².
        let p = Profile::rectangle(10.0, 10.0);
        let a = steiner(&p, -1.0);
        assert!((a - 64.0).abs() <= 4.0 - std::f64::consts::PI + 1e-9, "{a}");
        assert!(
            (a - (100.0 - 40.0 + std::f64::consts::PI)).abs() < 1e-6,
            "{a}"
        );
    }

    #[test]
    fn a_centre_line_square_widens_by_half_a_bead() {
        // 10 mm square centre line, 2 mm bead: 12 × 12 with corners rounded by 1.
        let p = Profile::rectangle(10.0, 10.0);
        let a = widened(&p, Measure::Centre, 2.0);
        assert!(
            (a - (144.0 - 4.0 + std::f64::consts::PI)).abs() < 1e-6,
            "{a}"
        );
    }
}
