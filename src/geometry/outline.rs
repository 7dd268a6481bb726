//! The model's 2-D shapes as [`Profile`]s and [`Region`]s: outlines of lines
//! and arcs map to vertices with bulges; sections (centred on the origin) to
//! their exact outlines, an ellipse flattened within the chord error; a
//! placed shape is turned and moved exactly (bulges survive a rigid motion);
//! a region is its outline and its holes; islands are every island's loops.

use super::profile::{Profile, Vertex};
use super::region::Region;
use super::section::Section;
use super::shape::{Outline, Segment, Shape, Turn};
use std::f64::consts::PI;

/// The outer outline of `shape` (a region's holes are left out: see
/// [`region`]); `chord_error` bounds the flattening of an ellipse.
pub fn profile(shape: &Shape, chord_error: f64) -> Profile {
    match shape {
        Shape::Outline(o) => Profile::new(outline(o)),
        Shape::Section(s) => Profile::new(section(s, chord_error)),
        Shape::Placed(p) => profile(&p.shape, chord_error).placed(p.turn.0, xy(p.at)),
        Shape::Region(r) => profile(&r.outline, chord_error),
        // The first (lowest) island's: the callers of a single outline
        // (a variable top's footprint) never get a mesh's islands.
        Shape::Islands(v) => v
            .first()
            .map_or_else(|| Profile::new(Vec::new()), |s| profile(s, chord_error)),
    }
}

/// The region of `shape`: its outline and, for a `region(…)`, its holes in
/// the order written. The loops are not checked here
/// ([`Region::faults`] does).
pub fn region(shape: &Shape, chord_error: f64) -> Region {
    match shape {
        Shape::Region(r) => Region::new(
            profile(&r.outline, chord_error),
            r.holes
                .iter()
                .map(|h| profile(&h.shape, chord_error))
                .collect(),
        ),
        Shape::Placed(p) => region(&p.shape, chord_error).placed(p.turn.0, xy(p.at)),
        Shape::Islands(v) => Region::islands(v.iter().map(|s| region(s, chord_error))),
        other => Region::from(profile(other, chord_error)),
    }
}

fn xy(p: [crate::units::Length; 2]) -> [f64; 2] {
    [p[0].0, p[1].0]
}

/// Bulge (tan of a quarter of the swept angle, + counter-clockwise) of the
/// shorter arc of radius `r` over a chord `c`.
pub fn bulge(c: f64, r: f64, turn: Turn) -> f64 {
    let half = (c / (2.0 * r)).clamp(-1.0, 1.0).asin(); // θ/2
    let b = (half / 2.0).tan();
    match turn {
        Turn::Left => b,
        Turn::Right => -b,
    }
}

fn outline(o: &Outline) -> Vec<Vertex> {
    let mut out = vec![Vertex {
        x: o.start[0].0,
        y: o.start[1].0,
        bulge: 0.0,
    }];
    for seg in &o.segments {
        let (to, b) = match *seg {
            Segment::Line { to } => (xy(to), 0.0),
            Segment::Arc { to, radius, turn } => {
                let from = out.last().map(|v| [v.x, v.y]).unwrap_or_default();
                let to = xy(to);
                let c = (to[0] - from[0]).hypot(to[1] - from[1]);
                (to, bulge(c, radius.0, turn))
            }
        };
        if let Some(last) = out.last_mut() {
            last.bulge = b;
        }
        out.push(Vertex {
            x: to[0],
            y: to[1],
            bulge: 0.0,
        });
    }
    // A last piece that returns to the start repeats the first vertex;
    // `Profile::new` drops it.
    out
}

fn v(x: f64, y: f64, bulge: f64) -> Vertex {
    Vertex { x, y, bulge }
}

fn section(s: &Section, chord_error: f64) -> Vec<Vertex> {
    // tan(90°/4): a quarter circle.
    let quarter = (PI / 8.0).tan();
    match *s {
        Section::Circle { r } => vec![v(r.0, 0.0, 1.0), v(-r.0, 0.0, 1.0)],
        Section::Rectangle { a, b } => vec![
            v(-a.0, -b.0, 0.0),
            v(a.0, -b.0, 0.0),
            v(a.0, b.0, 0.0),
            v(-a.0, b.0, 0.0),
        ],
        Section::RoundedRectangle { a, b, r } => {
            let (a, b, r) = (a.0, b.0, r.0.min(a.0).min(b.0));
            vec![
                v(-a + r, -b, 0.0),
                v(a - r, -b, quarter),
                v(a, -b + r, 0.0),
                v(a, b - r, quarter),
                v(a - r, b, 0.0),
                v(-a + r, b, quarter),
                v(-a, b - r, 0.0),
                v(-a, -b + r, quarter),
            ]
        }
        Section::Polygon { n, r } => (0..n)
            .map(|k| {
                let t = 2.0 * PI * k as f64 / n as f64;
                v(r.0 * t.cos(), r.0 * t.sin(), 0.0)
            })
            .collect(),
        Section::Ellipse { a, b } => {
            // Chord error of a circle of the larger radius bounds the ellipse's.
            let big = a.0.max(b.0);
            // `max` first: a sub-micron ellipse must not make clamp's bounds cross.
            let e = chord_error.max(1e-6).min(big.max(1e-6));
            let step = 2.0 * (1.0 - e / big).acos();
            let n = ((2.0 * PI / step).ceil() as usize).clamp(8, 100_000);
            (0..n)
                .map(|k| {
                    let t = 2.0 * PI * k as f64 / n as f64;
                    v(a.0 * t.cos(), b.0 * t.sin(), 0.0)
                })
                .collect()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quarter_and_half_circle_bulges() {
        // A quarter circle of radius 1: chord √2, bulge tan(22.5°).
        let b = bulge(2f64.sqrt(), 1.0, Turn::Left);
        assert!((b - (PI / 8.0).tan()).abs() < 1e-12);
        // A half circle: bulge 1; turning right: negative.
        assert!((bulge(2.0, 1.0, Turn::Right) + 1.0).abs() < 1e-12);
    }
}
