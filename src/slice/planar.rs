//! Planar slicing of an extrusion: flat layers `lift` apart (layer `k` is laid on
//! the plane z = k·lift), each filled with contour passes and raster tracks by
//! [`crate::fill`] (seed 001), and each track given a process style by the
//! style rules or by inheritance from the layer below (seed 002). Every track
//! becomes a path whose points carry their style's process values; the laser is
//! on from a track's first point to its last.

use super::styling::Styler;
use super::MAX_TOTAL_POINTS;
use crate::bead::MIN_OFFSET_RATIO;
use crate::diag::{Diagnostic, Diagnostics};
use crate::fill::{
    self, FillError, FillSpec, Pattern as FillPattern, RasterSpec, Track, TrackKind,
};
use crate::geometry::outline;
use crate::geometry::profile::Profile;
use crate::ir::{Frame, Layer, Path, PathKind, Point};
use crate::sema::model::{Extrusion, Measure, Model, Pattern, PlanarSlicing, Shape};
use crate::style;
use crate::units::{short, Length};

/// A spot this many bead widths from every track centre line is reported.
const THIN_GAP: f64 = 0.75;

/// Points the gap check samples over a whole part.
const GAP_SAMPLES: usize = 20_000_000;

/// Slices an extrusion into filled planar layers.
pub fn slice(
    model: &Model,
    extrusion: &Extrusion,
    slicing: &PlanarSlicing,
) -> Result<(Vec<Layer>, Diagnostics), Diagnostics> {
    let mut warnings = Diagnostics::new();
    let w = model.bead.width.0;
    let inset = match extrusion.measure {
        Measure::Outer => w / 2.0,
        Measure::Centre => 0.0,
    };
    let n = extrusion.layers.len();
    let lift = extrusion.lift.0;
    let mut out = Vec::with_capacity(n);
    let mut total = 0usize;
    let (mut short_tracks, mut first_short) = (0usize, None);
    // Style rules measure distances to the boundary in bead widths: a
    // hundredth of one is plenty, and keeps a fine chord error from turning
    // every arc into a thousand chords there.
    let mut styler = Styler::new(&model.styles, slicing.chord_error.0.max(w / 100.0));
    let (mut gaps, mut first_gap) = (0usize, None);
    let (mut thin_gaps, mut thin) = (0usize, None);
    let mut few_passes = None;
    let mut used = std::collections::BTreeSet::new();
    let mut sliver = None;
    // The gap check samples each layer; a budget over the whole part keeps it
    // linear however many layers there are.
    let gap_samples = (GAP_SAMPLES / n.max(1)).clamp(500, fill::MAX_SAMPLES);
    // The last layer's shape, raster angle, profile, tracks and gap: a layer
    // like it (a fixed profile, no rotation) reuses them instead of filling
    // and checking the same shape again.
    let mut last: Option<Filled> = None;
    for (k, shape) in extrusion.layers.iter().enumerate() {
        let angle = slicing
            .infill
            .map_or(0.0, |r| (r.angle.0 + r.rotate.0 * k as f64).to_degrees());
        let reuse = matches!(&last, Some(f)
            if f.shape == shape && f.angle.rem_euclid(360.0) == angle.rem_euclid(360.0));
        let (profile, tracks, gap) = match last.take() {
            Some(f) if reuse => (f.profile, f.tracks, f.gap),
            _ => {
                let profile = outline::profile(shape, slicing.chord_error.0);
                let (tracks, gap) = fill_layer(
                    &profile,
                    k,
                    angle,
                    inset,
                    w,
                    gap_samples,
                    extrusion,
                    slicing,
                )?;
                (profile, tracks, gap)
            }
        };
        if let Some(g) = gap {
            if g.distance > w {
                gaps += 1;
                first_gap.get_or_insert((k, g));
            } else {
                thin_gaps += 1;
                if thin.is_none_or(|(_, t): (usize, fill::Gap)| g.distance > t.distance) {
                    thin = Some((k, g));
                }
            }
        }
        let passes = tracks
            .iter()
            .filter_map(|t| match t.kind {
                TrackKind::Contour { index } => Some(index + 1),
                TrackKind::Infill => None,
            })
            .max()
            .unwrap_or(0);
        if passes < slicing.contours && few_passes.is_none() {
            few_passes = Some((k, passes));
        }
        for t in &tracks {
            // A contour loop whose sides run closer than the tracks may (a
            // sliver: mean width 2·area/perimeter) piles up like any overlap.
            if let TrackKind::Contour { .. } = t.kind {
                let thickness = 2.0 * loop_area(&t.points) / style::length(&t.points).max(1e-12);
                if thickness < MIN_OFFSET_RATIO * w
                    && sliver.is_none_or(|(_, s): (usize, f64)| thickness < s)
                {
                    sliver = Some((k, thickness));
                }
            }
            if style::length(&t.points) < w {
                short_tracks += 1;
                first_short.get_or_insert(k);
            }
        }
        total += tracks.iter().map(|t| t.points.len()).sum::<usize>();
        if total > MAX_TOTAL_POINTS {
            return Err(Diagnostic::error(
                "lmd::too-many-points",
                format!("the fill needs more than {MAX_TOTAL_POINTS} points"),
            )
            .label(slicing.span, "slicing")
            .help("use fewer layers or a larger chord error")
            .into());
        }
        let styles = styler.layer(k, &profile, &tracks);
        used.extend(styles.iter().copied());
        out.push(layer(model, slicing, k, n, lift, &tracks, &styles));
        last = Some(Filled {
            shape,
            angle,
            profile,
            tracks,
            gap,
        });
    }
    if let Some((k, g)) = first_gap {
        return Err(Diagnostic::error(
            "lmd::fill-gap",
            format!(
                "the tracks leave a spot unfilled on {gaps} layer{}: on layer {}, ({}, {}) mm is {} from the nearest track, more than the bead width {}",
                if gaps == 1 { "" } else { "s" },
                k + 1,
                short(g.at[0]),
                short(g.at[1]),
                Length(g.distance),
                Length(w)
            ),
        )
        .label(extrusion.shape_span, "this shape")
        .label(slicing.span, "fill")
        .help("raster lines miss parts of a profile narrower than the offset, and line ends reach at most `extend` past their neighbours: a smaller offset, a larger `extend`, a contour pass or another raster angle fills them")
        .into());
    }
    if let Some((k, g)) = thin {
        warnings.push(
            Diagnostic::warning(
                "lmd::thin-gap",
                format!(
                    "no bead reaches some spots on {thin_gaps} layer{}: the farthest, on layer {}, is ({}, {}) mm, {} from the nearest track centre line (a bead reaches {})",
                    if thin_gaps == 1 { "" } else { "s" },
                    k + 1,
                    short(g.at[0]),
                    short(g.at[1]),
                    Length(g.distance),
                    Length(w / 2.0)
                ),
            )
            .label(extrusion.shape_span, "this shape")
            .label(slicing.span, "fill")
            .help("often the strip the raster leaves at its far edge when the profile is not a whole number of offsets wide; a contour pass, a width of whole offsets, or a smaller offset closes it"),
        );
    }
    if let Some((k, t)) = sliver {
        warnings.push(
            Diagnostic::warning(
                "lmd::overlap",
                format!(
                    "a contour pass on layer {} is a sliver whose sides run {} apart, {:.0} % of the {} bead: it piles up",
                    k + 1,
                    Length(t),
                    100.0 * t / w,
                    Length(w)
                ),
            )
            .label(extrusion.shape_span, "this shape")
            .label(slicing.span, "contours")
            .help("the profile narrows to less than the passes need there; fewer contours, or a raster for the middle"),
        );
    }
    for st in model
        .styles
        .table
        .iter()
        .filter(|st| !used.contains(&st.id))
    {
        warnings.push(
            Diagnostic::warning(
                "lmd::unused",
                format!("style `{}` picks no track on any layer", st.name),
            )
            .label(st.span, "never applied")
            .help("an earlier style may take its tracks first (the first style in the file wins), or no track meets its `when`"),
        );
    }
    if let Some((k, passes)) = few_passes {
        warnings.push(
            Diagnostic::warning(
                "lmd::few-contours",
                format!(
                    "only {passes} of the {} contour passes fit inside the profile on layer {}",
                    slicing.contours,
                    k + 1
                ),
            )
            .label(slicing.span, "contours")
            .help("the profile is narrower there than the passes need; fewer contours, or a raster inside them"),
        );
    }
    if let Some(first) = first_short {
        warnings.push(
            Diagnostic::warning(
                "lmd::short-track",
                format!(
                    "{short_tracks} track{} shorter than the bead width {} (first on layer {})",
                    if short_tracks == 1 { " is" } else { "s are" },
                    Length(w),
                    first + 1
                ),
            )
            .label(slicing.span, "fill")
            .help("short tracks overheat and pile up: a slower or cooler style, or a profile without slivers"),
        );
    }
    Ok((out, warnings))
}

/// The track without points that repeat the one before (within a nanometre),
/// or `None` if too little is left to move along: a raster track needs two
/// distinct points, a closed contour three. Sub-micron profiles flatten to such
/// points, and a direction of travel needs a distance.
fn distinct(mut t: Track) -> Option<Track> {
    t.points
        .dedup_by(|b, a| (b[0] - a[0]).hypot(b[1] - a[1]) <= DISTINCT);
    let need = match t.kind {
        TrackKind::Contour { .. } => 4,
        TrackKind::Infill => 2,
    };
    (t.points.len() >= need).then_some(t)
}

/// Points closer than this (mm) are one point.
const DISTINCT: f64 = 1e-6;

/// Area enclosed by a closed polyline (shoelace), unsigned.
fn loop_area(p: &[[f64; 2]]) -> f64 {
    let twice: f64 = p
        .windows(2)
        .map(|s| s[0][0] * s[1][1] - s[1][0] * s[0][1])
        .sum();
    (twice / 2.0).abs()
}

/// A filled layer, kept for the next if it is the same.
struct Filled<'m> {
    shape: &'m Shape,
    /// Raster angle, deg.
    angle: f64,
    profile: Profile,
    tracks: Vec<Track>,
    gap: Option<fill::Gap>,
}

/// Fills one layer's `profile` with the raster at `angle` (deg) and finds the
/// farthest spot no bead reaches, if a raster promises a full layer.
#[allow(clippy::too_many_arguments)]
fn fill_layer(
    profile: &Profile,
    k: usize,
    angle: f64,
    inset: f64,
    w: f64,
    gap_samples: usize,
    extrusion: &Extrusion,
    slicing: &PlanarSlicing,
) -> Result<(Vec<Track>, Option<fill::Gap>), Diagnostics> {
    let spec = FillSpec {
        inset,
        contours: slicing.contours,
        offset: slicing.offset.0,
        raster: slicing.infill.map(|r| RasterSpec {
            angle_deg: angle,
            offset: slicing.offset.0,
            pattern: match r.pattern {
                Pattern::Serpentine => FillPattern::Serpentine,
                Pattern::OneWay => FillPattern::OneWay,
            },
            extend: r.extend.0,
        }),
    };
    let tracks: Vec<Track> = fill::fill(profile, &spec, slicing.chord_error.0)
        .map_err(|e| fill_error(e, k, extrusion, slicing))?
        .into_iter()
        .filter_map(distinct)
        .collect();
    if tracks.is_empty() {
        return Err(fill_error(FillError::Empty, k, extrusion, slicing));
    }
    // The whole profile is sampled, the outer face included when it is one:
    // a part narrower than a bead vanishes from the inset region, and is
    // exactly what goes unbuilt. Anything over w/2 from every centre line is
    // reached by no bead, but corners of contour and raster leave such slivers
    // anyway and the melt pool flows into them: a quarter bead width unreached
    // is worth a warning, a spot wider than a bead an error. Contours alone
    // make walls: unchecked.
    let gap = slicing
        .infill
        .and_then(|_| fill::gap(profile, 0.0, &tracks, THIN_GAP * w, gap_samples));
    Ok((tracks, gap))
}

fn fill_error(e: FillError, k: usize, ex: &Extrusion, slicing: &PlanarSlicing) -> Diagnostics {
    let d = match e {
        FillError::SelfIntersecting { at } => Diagnostic::error(
            "lmd::self-intersecting",
            format!(
                "the profile crosses itself at ({}, {}) mm on layer {}{}",
                short(at[0]),
                short(at[1]),
                k + 1,
                // The builtin's value, for a profile that follows it.
                if ex.layers.windows(2).any(|w| w[0] != w[1]) {
                    format!(" (layer = {k})")
                } else {
                    String::new()
                }
            ),
        )
        .label(ex.shape_span, "this outline's edges cross")
        .label_opt(
            (ex.profile_span != ex.shape_span).then_some(ex.profile_span),
            "extruded here",
        )
        .help("reorder the outline's points so its edges do not cross; if its numbers use `layer`, check them at that layer"),
        FillError::Empty => Diagnostic::error(
            "lmd::fill-empty",
            format!("no track fits in the profile on layer {}", k + 1),
        )
        .label(ex.profile_span, "profile")
        .label(slicing.span, "fill")
        .help("the profile is narrower than the bead and its contour passes; make it larger or use fewer contours"),
        other => Diagnostic::error(
            "lmd::fill",
            format!("layer {} cannot be filled: {other}", k + 1),
        )
        .label(ex.profile_span, "profile")
        .label(slicing.span, "fill"),
    };
    d.into()
}

fn layer(
    model: &Model,
    slicing: &PlanarSlicing,
    k: usize,
    n: usize,
    lift: f64,
    tracks: &[Track],
    styles: &[u16],
) -> Layer {
    let z = k as f64 * lift;
    let p = &model.process;
    let base = Values {
        power: p.power.at(k).watts() as f32,
        powder: p.powder.g_min() as f32,
        speed: slicing.speed.0 as f32,
    };
    let defocus = p.defocus.0 as f32;
    let paths = tracks
        .iter()
        .zip(styles)
        .filter(|(t, _)| t.points.len() >= 2)
        .map(|(t, &style)| {
            let v = match model.styles.table.iter().find(|s| s.id == style) {
                Some(s) => Values {
                    power: s.power.map_or(base.power, |p| p.watts() as f32),
                    powder: s.powder.map_or(base.powder, |m| m.g_min() as f32),
                    speed: s.speed.map_or(base.speed, |v| v.0 as f32),
                },
                None => base,
            };
            let m = t.points.len();
            let points = (0..m)
                .map(|i| {
                    let (a, b) = if i + 1 < m { (i, i + 1) } else { (i - 1, i) };
                    let (dx, dy) = (
                        t.points[b][0] - t.points[a][0],
                        t.points[b][1] - t.points[a][1],
                    );
                    let len = dx.hypot(dy).max(1e-12);
                    Point {
                        pos: [t.points[i][0], t.points[i][1], z],
                        normal: [0.0, 0.0, 1.0],
                        tangent: [(dx / len) as f32, (dy / len) as f32, 0.0],
                        layer_height: lift as f32,
                        speed: v.speed,
                        power: v.power,
                        powder: v.powder,
                        defocus,
                        laser_on: i + 1 < m,
                        style,
                    }
                })
                .collect();
            Path {
                kind: match t.kind {
                    TrackKind::Contour { .. } => PathKind::Contour,
                    TrackKind::Infill => PathKind::Infill,
                },
                points,
            }
        })
        .collect();
    Layer {
        index: k,
        station: k as f64 / n as f64,
        frame: Frame {
            origin: [0.0, 0.0, z],
            x: [1.0, 0.0, 0.0],
            y: [0.0, 1.0, 0.0],
            z: [0.0, 0.0, 1.0],
        },
        paths,
    }
}

/// The process values a track is deposited with.
#[derive(Clone, Copy)]
struct Values {
    power: f32,
    powder: f32,
    speed: f32,
}
