//! Gives every track of a planar layer its process style with
//! [`crate::style`]: the first style one of whose `when` blocks holds for the
//! track, else the style it inherits from the layer below (at least `hit` of its
//! length inside the band round that layer's tracks of one style), else 0, the
//! process block's values.

use crate::diag::{message, Diagnostics};
use crate::fill::{Track, TrackKind};
use crate::geometry::region::Region;
use crate::sema::model::{PathSelect, StyleCondition, Styles};
use crate::style::{self, BoundaryBand, Condition, Layout, PathClass, Rule, TrackFacts};

/// Assigns styles layer after layer, remembering the last layer's styled
/// tracks for inheritance.
pub struct Styler {
    /// Every `when` block as a rule, in file order, with the corner angle (deg)
    /// its `near_corner` uses, if any.
    rules: Vec<(Rule, Option<f64>)>,
    /// The distinct `near_boundary` distances and `near_corner` angles (deg)
    /// the rules use: their bands and corners are found once a layer.
    distances: Vec<f64>,
    angles: Vec<f64>,
    /// Band half-width and hit factor, if styles are inherited.
    inheritance: Option<(f64, f64)>,
    chord_error: f64,
    /// The previous layer's tracks that have a style other than 0.
    prev: Vec<(Vec<[f64; 2]>, u16)>,
}

impl Styler {
    /// A styler for the model's `styles`; `chord_error` flattens the boundary's
    /// arcs.
    pub fn new(styles: &Styles, chord_error: f64) -> Self {
        let mut rules = Vec::new();
        for s in &styles.table {
            for block in &s.rules {
                let mut angle = None;
                let when = block
                    .iter()
                    .map(|c| match *c {
                        StyleCondition::Paths(PathSelect::OuterContour) => {
                            Condition::Class(PathClass::OuterContour)
                        }
                        StyleCondition::Paths(PathSelect::InnerContour) => {
                            Condition::Class(PathClass::InnerContour)
                        }
                        StyleCondition::Paths(PathSelect::Contour) => Condition::Contour,
                        StyleCondition::Paths(PathSelect::Infill) => {
                            Condition::Class(PathClass::Infill)
                        }
                        StyleCondition::ShorterThan(l) => Condition::LengthBelow(l.0),
                        StyleCondition::LongerThan(l) => Condition::LengthAtLeast(l.0),
                        StyleCondition::NearBoundary(d) => Condition::BoundaryWithin(d.0),
                        StyleCondition::NearCorner(d, a) => {
                            angle = Some(a.deg());
                            Condition::CornerWithin(d.0)
                        }
                        // The language counts layers from 1, as the programs do.
                        StyleCondition::Layers(first, last) => Condition::Layers {
                            first: first.saturating_sub(1),
                            last: last.saturating_sub(1),
                        },
                    })
                    .collect();
                rules.push((Rule { when, style: s.id }, angle));
            }
        }
        let mut distances: Vec<f64> = Vec::new();
        let mut angles: Vec<f64> = Vec::new();
        for (rule, angle) in &rules {
            for c in &rule.when {
                if let Condition::BoundaryWithin(d) = *c {
                    if !distances.contains(&d) {
                        distances.push(d);
                    }
                }
            }
            if let Some(a) = *angle {
                if !angles.contains(&a) {
                    angles.push(a);
                }
            }
        }
        Styler {
            rules,
            distances,
            angles,
            inheritance: styles.inheritance.map(|i| (i.band.0, i.hit)),
            chord_error,
            prev: Vec::new(),
        }
    }

    /// The style of each of layer `k`'s `tracks` (filled in `region`: its
    /// holes' edges are boundary and their corners corners too).
    pub fn layer(&mut self, k: usize, region: &Region, tracks: &[Track]) -> Vec<u16> {
        if self.rules.is_empty() {
            return vec![0; tracks.len()];
        }
        // A `BoundaryWithin` band is built here once for the layer rather than
        // by `Condition::holds` for every track (which rebuilds it per call),
        // so the layout passed to `holds` needs no boundary.
        let boundary = if self.distances.is_empty() {
            Vec::new()
        } else {
            region.polylines(self.chord_error)
        };
        let bands: Vec<(f64, Option<BoundaryBand>)> = self
            .distances
            .iter()
            .map(|&d| (d, BoundaryBand::new(&boundary, d)))
            .collect();
        let corners: Vec<(f64, Vec<[f64; 2]>)> = self
            .angles
            .iter()
            .map(|&a| (a, region.loops().flat_map(|(l, _)| l.corners(a)).collect()))
            .collect();
        let prev: Vec<(&[[f64; 2]], u16)> =
            self.prev.iter().map(|(p, s)| (p.as_slice(), *s)).collect();
        // The layer below is indexed once, not once per track.
        let inherited = match self.inheritance {
            Some((band, hit)) if !prev.is_empty() => {
                Some(style::Inheritance::new(&prev, band, hit))
            }
            _ => None,
        };
        let ids: Vec<u16> = tracks
            .iter()
            .map(|t| {
                let facts = TrackFacts {
                    class: match t.kind {
                        TrackKind::Contour { index: 0 } => PathClass::OuterContour,
                        TrackKind::Contour { .. } => PathClass::InnerContour,
                        TrackKind::Infill => PathClass::Infill,
                    },
                    length: style::length(&t.points),
                    layer: k,
                };
                let by_rule = self.rules.iter().find_map(|(rule, angle)| {
                    let layout = Layout {
                        boundary: &[],
                        corners: angle
                            .and_then(|a| corners.iter().find(|c| c.0 == a))
                            .map_or(&[][..], |c| c.1.as_slice()),
                    };
                    rule.when
                        .iter()
                        .all(|c| match *c {
                            Condition::BoundaryWithin(d) => bands
                                .iter()
                                .find(|b| b.0 == d)
                                .and_then(|b| b.1.as_ref())
                                .is_some_and(|b| b.holds(&t.points)),
                            _ => c.holds(&t.points, &facts, &layout),
                        })
                        .then_some(rule.style)
                });
                by_rule
                    .or_else(|| inherited.as_ref()?.style_of(&t.points))
                    .unwrap_or(0)
            })
            .collect();
        if self.inheritance.is_some() {
            self.prev = tracks
                .iter()
                .zip(&ids)
                .filter(|(_, &id)| id != 0)
                .map(|(t, &id)| (t.points.clone(), id))
                .collect();
        }
        ids
    }
}

/// Warns about each style whose `layers` range starts past the part's last
/// layer (`layers` of them).
pub fn never_applies(styles: &Styles, layers: usize, diags: &mut Diagnostics) {
    for s in &styles.table {
        let first = s.rules.iter().flatten().find_map(|c| match *c {
            StyleCondition::Layers(a, _) if a > layers => Some(a),
            _ => None,
        });
        if let Some(a) = first {
            diags.push(message::slicing::style_layer_past_end(
                &s.name, a, layers, s.span,
            ));
        }
    }
}
