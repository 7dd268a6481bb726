//! What each move of the page is part of: a wall, a contour, a raster
//! track, a link between two tracks, or travel.
//!
//! The IR says what a path is (`PathKind`) but has no kind of its own for a
//! link laid with the laser on: `slice::planar` writes it as an `Infill`
//! path between the two tracks it joins, from the one's last point to the
//! next one's first, so the three run as one deposit. Here a laser-on
//! infill path that [`crate::plan::joins`] an infill *track* is that track's
//! link, and the track after the link joins the link: along a chain the
//! two alternate, track first.

use crate::ir::{Layer, PathKind};
use crate::plan;

/// A move's class on the page (the number the page stores, 0–4).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum Kind {
    /// Laser off: approach, retract, travel, a link laid with the laser off.
    Travel = 0,
    /// A single-bead wall.
    Wall = 1,
    /// A contour pass of a filled layer.
    Contour = 2,
    /// A raster track (or a variable layer's track).
    Infill = 3,
    /// Raster tracks joined along the edge with the laser on.
    Link = 4,
}

impl Kind {
    /// The names the page's legend gives, indexed by the stored number.
    pub const NAMES: [&'static str; 5] = ["travel", "wall", "contour", "infill", "link"];
}

/// The class of each path of `layer`, by index.
pub fn classify(layer: &Layer) -> Vec<Kind> {
    let mut out = Vec::with_capacity(layer.paths.len());
    // The last path with points: its class and last point.
    let mut before: Option<(Kind, &crate::ir::Point)> = None;
    for path in &layer.paths {
        let mut kind = match path.kind {
            PathKind::Wall => Kind::Wall,
            PathKind::Contour => Kind::Contour,
            PathKind::Infill => Kind::Infill,
            PathKind::Travel | PathKind::Lead => Kind::Travel,
        };
        if let (Some(first), Some((Kind::Infill, last))) = (path.points.first(), before) {
            if kind == Kind::Infill
                && first.laser_on
                && plan::joins(last.focus(), last.normal, first)
            {
                kind = Kind::Link;
            }
        }
        out.push(kind);
        if let Some(last) = path.points.last() {
            before = Some((kind, last));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::{Frame, Path, Point};

    fn point(x: f64, y: f64, laser: bool) -> Point {
        Point {
            pos: [x, y, 0.0],
            normal: [0.0, 0.0, 1.0],
            tangent: [1.0, 0.0, 0.0],
            layer_height: 1.0,
            speed: 10.0,
            power: 1000.0,
            powder: 10.0,
            defocus: 0.0,
            laser_on: laser,
            style: 0,
            pitch: 2.0,
            rise: 1.0,
        }
    }

    fn path(kind: PathKind, pts: &[[f64; 2]], laser: bool) -> Path {
        let n = pts.len();
        Path {
            kind,
            points: pts
                .iter()
                .enumerate()
                .map(|(i, p)| point(p[0], p[1], laser && i + 1 < n))
                .collect(),
        }
    }

    fn layer(paths: Vec<Path>) -> Layer {
        Layer {
            index: 0,
            station: 0.0,
            frame: Frame {
                origin: [0.0; 3],
                x: [1.0, 0.0, 0.0],
                y: [0.0, 1.0, 0.0],
                z: [0.0, 0.0, 1.0],
            },
            paths,
            label: String::new(),
            on_plate: false,
        }
    }

    #[test]
    fn links_alternate_with_the_tracks_they_join() {
        use PathKind::*;
        let l = layer(vec![
            path(Contour, &[[0.0, 0.0], [10.0, 0.0], [0.0, 0.0]], true),
            // A serpentine: track, link, track, link, track.
            path(Infill, &[[1.0, 1.0], [9.0, 1.0]], true),
            path(Infill, &[[9.0, 1.0], [9.5, 2.0], [9.0, 3.0]], true),
            path(Infill, &[[9.0, 3.0], [1.0, 3.0]], true),
            path(Infill, &[[1.0, 3.0], [1.0, 5.0]], true),
            path(Infill, &[[1.0, 5.0], [9.0, 5.0]], true),
            // A link laid with the laser off is travel; the track after it
            // starts a chain of its own.
            path(Travel, &[[9.0, 5.0], [9.0, 7.0]], false),
            path(Infill, &[[9.0, 7.0], [1.0, 7.0]], true),
            // A track that starts elsewhere is a track.
            path(Infill, &[[1.0, 9.0], [9.0, 9.0]], true),
        ]);
        use Kind as K;
        assert_eq!(
            classify(&l),
            [
                K::Contour,
                K::Infill,
                K::Link,
                K::Infill,
                K::Link,
                K::Infill,
                K::Travel,
                K::Infill,
                K::Infill
            ]
        );
    }

    #[test]
    fn walls_are_walls() {
        let l = layer(vec![path(PathKind::Wall, &[[0.0, 0.0], [1.0, 0.0]], true)]);
        assert_eq!(classify(&l), [Kind::Wall]);
    }
}
