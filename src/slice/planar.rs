//! Planar slicing of an extrusion: flat layers `lift` apart (layer `k` is laid on
//! the plane z = k·lift), each filled with contour passes and raster tracks by
//! [`crate::fill`], and each track given a process style by the style rules
//! or by inheritance from the layer below. Every track becomes a path whose
//! points carry their style's process values; the laser is on from a track's
//! first point to its last.
//!
//! A profile with holes is checked on each layer first: every hole that
//! crosses, touches or lies outside the outline or another hole is reported
//! (`slice::holes`). Linked raster tracks (`link = …`) get a path of their
//! own between them, from the one's last point to the next one's first:
//! [`PathKind::Travel`] with the laser off, [`PathKind::Infill`] with it on;
//! both join the tracks on either side, so the nozzle neither stops nor
//! lifts. Contour seams follow the slicing's seam rule, layer by layer.

use super::holes;
use super::layers::{self, Layers};
use super::spiral;
use super::styling::{self, Styler};
use super::MAX_TOTAL_POINTS;
use crate::bead::MIN_OFFSET_RATIO;
use crate::diag::{message, Diagnostic, Diagnostics, Worst};
use crate::fill::pitch::{self, Apart, Strand};
use crate::fill::{
    self, FillError, FillSpec, Linking, Pattern as FillPattern, RasterSpec, Seam, Track, TrackKind,
};
use crate::geometry::outline;
use crate::geometry::region::Region;
use crate::ir::{Frame, Layer, Path, PathKind, Point};
use crate::sema::model::{
    Bead, Extrusion, LayerChange, LinkMode, Measure, Model, Pattern, PlanarSlicing, SeamRule, Shape,
};
use crate::style;
use crate::units::{Length, Speed};
use nalgebra::Point3;

use std::collections::{BTreeMap, BTreeSet};

/// A spot this many bead widths from every track centre line is reported.
const THIN_GAP: f64 = 0.75;

/// Points the gap check samples over a whole part.
const GAP_SAMPLES: usize = 20_000_000;

/// Slices an extrusion into filled planar layers. Returns the layers and any
/// warnings, or every diagnostic found (the errors and the warnings with them).
pub fn slice(
    model: &Model,
    bead: &Bead,
    extrusion: &Extrusion,
    slicing: &PlanarSlicing,
) -> Result<(Vec<Layer>, Diagnostics), Diagnostics> {
    let mut diags = Diagnostics::new();
    let Some(plan) = layers::plan(bead, extrusion, slicing, &mut diags) else {
        return Err(diags);
    };
    let inset = match extrusion.measure {
        Measure::Outer => bead.width.0 / 2.0,
        Measure::Centre => 0.0,
    };
    let band = super::budget::band(slicing, inset);
    if super::budget::planar(
        (&plan.shapes, !plan.varies()),
        extrusion,
        slicing,
        [band, inset],
        &mut diags,
    )
    .is_none()
    {
        return Err(diags);
    }
    styling::never_applies(&model.styles, plan.shapes.len(), &mut diags);
    // Every layer filled: its diagnostics go on with it, errors (a spot left
    // unfilled) included, so the machine checks still run in this run.
    match fill_layers(model, bead, extrusion, slicing, &plan, &mut diags) {
        Some(mut out) => match spiral_wall(&mut out, bead, &plan, extrusion, slicing) {
            Ok(()) => Ok((out, diags)),
            Err(d) => {
                diags.push(d);
                Err(diags)
            }
        },
        None => Err(diags),
    }
}

/// `layer_change = spiral` on a planar one-bead wall: the last `length` of
/// each layer's loop climbs to the next layer's first point with the laser
/// on ([`spiral`]). A point a share `t` up the climb lies `t` layer heights
/// over its layer's plane, one layer height over the climb below; the
/// first layer's climb lays `(1 + t)` layer heights, at the speed that
/// lays that. Every layer must be the same single loop (the one the layer
/// below climbed into).
fn spiral_wall(
    out: &mut [Layer],
    bead: &Bead,
    plan: &Layers,
    extrusion: &Extrusion,
    slicing: &PlanarSlicing,
) -> Result<(), Diagnostic> {
    let LayerChange::Spiral { length } = slicing.layer_change else {
        return Ok(());
    };
    let length = length.map_or(f64::INFINITY, |l| l.0);
    let refuse = |k: usize, loops: usize| {
        message::slicing::spiral_needs_one_loop(
            k,
            loops,
            slicing.layer_change_span.unwrap_or(slicing.span),
            extrusion.profile_span,
        )
    };
    if plan.varies() {
        return Err(refuse(0, 1));
    }
    let (h, pitch) = (plan.lift.0, plan.pitch);
    let deposit = bead.deposit();
    let speed_for = |laid: f64| deposit.speed_for(Length(laid * h), pitch).0;
    for layer in out.iter_mut() {
        let k = layer.index;
        let [path] = &mut layer.paths[..] else {
            return Err(refuse(k, layer.paths.len()));
        };
        let mut pos: Vec<Point3<f64>> = path.points.iter().map(|q| q.pos.into()).collect();
        if let Some(cut) = spiral::climb_start(&pos, length) {
            cut_moves(&mut path.points, &mut pos, &[cut]);
        }
        let mut t = spiral::shares(&pos, length);
        if k == 0 {
            let cuts = spiral::first_climb_cuts(&t, slicing.tolerance.rise);
            cut_moves(&mut path.points, &mut pos, &cuts);
            t = spiral::shares(&pos, length);
        }
        let laid: Vec<f64> = t.iter().map(|&t| spiral::laid(k, t)).collect();
        let m = path.points.len();
        for (j, q) in path.points.iter_mut().enumerate() {
            q.pos[2] += t[j] * h;
            q.layer_height = (laid[j] * h) as f32;
            // The move on lays the mean of its ends' heights (the last
            // point has no move: it keeps the speed of the one before).
            let along = 0.5 * (laid[j] + laid[(j + 1).min(m - 1)]);
            if along != 1.0 {
                let v = f64::from(q.speed) * speed_for(along) / speed_for(1.0);
                q.speed = if v.is_finite() { v as f32 } else { 0.0 };
            }
        }
    }
    spiral::join_layers(out);
    Ok(())
}

/// Puts a point on each move `j` a share `u` along it, for every `(j, u)`
/// of `cuts` (in order), laid like the point the move leaves.
fn cut_moves(points: &mut Vec<Point>, pos: &mut Vec<Point3<f64>>, cuts: &[(usize, f64)]) {
    let mut new_points = Vec::with_capacity(points.len() + cuts.len());
    let mut new_pos = Vec::with_capacity(points.len() + cuts.len());
    let mut cuts = cuts.iter().peekable();
    for (j, (q, &p)) in points.iter().zip(pos.iter()).enumerate() {
        new_points.push(*q);
        new_pos.push(p);
        while let Some(&(_, u)) = cuts.next_if(|c| c.0 == j) {
            let at = p + (pos[j + 1] - p) * u;
            let mut q = *q;
            q.pos = at.into();
            new_points.push(q);
            new_pos.push(at);
        }
    }
    *points = new_points;
    *pos = new_pos;
}

/// The samples the gap check and the strips' measure take of each of `n`
/// layers: a budget over the whole part keeps them linear however many
/// layers there are.
fn samples_per_layer(n: usize) -> (usize, usize) {
    let gap = (GAP_SAMPLES / n.max(1)).clamp(500, fill::MAX_SAMPLES);
    let strips =
        (pitch::STRIP_SAMPLES / n.max(1)).clamp(pitch::MIN_STRIP_SAMPLES, pitch::MAX_STRIP_SAMPLES);
    (gap, strips)
}

/// Fills, styles and lays every layer of `plan`; `None` after an error that
/// leaves no layers to go on with. (A spot left unfilled is an error that
/// leaves every layer: the layers come back with it.)
fn fill_layers(
    model: &Model,
    bead: &Bead,
    extrusion: &Extrusion,
    slicing: &PlanarSlicing,
    plan: &Layers,
    diags: &mut Diagnostics,
) -> Option<Vec<Layer>> {
    let w = bead.width.0;
    let inset = match extrusion.measure {
        Measure::Outer => w / 2.0,
        Measure::Centre => 0.0,
    };
    let n = plan.shapes.len();
    let lift = plan.lift.0;
    let pitch = plan.pitch.0;
    let varies = plan.varies();
    let mut out = Vec::with_capacity(n);
    let mut total = 0usize;
    let mut found = Findings::default();
    // Style rules measure distances to the boundary in bead widths: a
    // hundredth of one is plenty, and keeps a fine chord error from turning
    // every arc into a thousand chords there.
    let mut styler = Styler::new(&model.styles, slicing.chord_error.0.max(w / 100.0));
    let values = Values::table(model, slicing);
    let (gap_samples, strip_samples) = samples_per_layer(n);
    // The last layer's shape, raster angle, profile, tracks and gap: a layer
    // like it (a fixed profile, no rotation) reuses them instead of filling
    // and checking the same shape again.
    let mut last: Option<Filled> = None;
    let mut lean = Lean::new(slicing.max_overhang, lift, slicing.chord_error.0, w);
    for (k, shape) in plan.shapes.iter().enumerate() {
        let angle = slicing
            .infill
            .map_or(0.0, |r| (r.angle.0 + r.rotate.0 * k as f64).to_degrees());
        let seam = seam_at(slicing.seam, k);
        // Where the layer below ended: a layer of islands starts nearest it.
        let from = last.as_ref().and_then(Filled::end);
        let reuse = matches!(&last, Some(f)
            if f.shape == shape
                && f.angle.rem_euclid(360.0) == angle.rem_euclid(360.0)
                && f.seam == seam);
        let mut filled = match last.take() {
            Some(f) if reuse => f,
            _ => {
                let at = Where {
                    k,
                    varies,
                    extrusion,
                    slicing,
                };
                let how = How {
                    angle,
                    seam,
                    inset,
                    w,
                    pitch,
                    gap_samples,
                    strip_samples,
                };
                match fill_shape(shape, &how, &at) {
                    Ok((region, islands, gap)) => {
                        Filled::new(shape, angle, seam, region, islands, gap)
                    }
                    Err(errors) => {
                        for d in errors {
                            diags.push(d);
                        }
                        return None;
                    }
                }
            }
        };
        filled.order(from);
        found.layer(k, &filled, slicing.contours, w);
        lean.layer(k, &filled.region);
        total += filled.tracks.iter().map(|t| t.points.len()).sum::<usize>();
        if total > MAX_TOTAL_POINTS {
            diags.push(message::slicing::too_many_fill_points(
                MAX_TOTAL_POINTS,
                slicing.span,
            ));
            return None;
        }
        let styles = styler.layer(k, &filled.region, &filled.tracks);
        found.used.extend(styles.iter().copied());
        let tracks = Tracks {
            tracks: &filled.tracks,
            pitch: &filled.pitch,
            styles: &styles,
        };
        out.push(layer(&values, k, n, [lift, pitch], &tracks));
        last = Some(filled);
    }
    found.report(model, bead, extrusion, slicing, diags);
    lean.report(slicing.span, diags);
    Some(out)
}

/// Most points of a layer's outline checked for its lean (spread over it).
const LEAN_SAMPLES: usize = 512;

/// `max_overhang` on planar layers (`lmd::overhang`): how far each layer's
/// outline and holes step out over the region of the layer below — a point
/// of the layer outside the layer below's region, by its distance to that
/// region, over the layer height, is its lean from the vertical nozzle. A
/// layer that leans in stands on the layer below and is not counted.
/// Without `max_overhang` a lean past 45° or a step past half a bead is
/// warned ([`crate::deposit::DEFAULT_OVERHANG`]).
struct Lean {
    /// The lean allowed, rad.
    limit: f64,
    /// Whether the file declared it (`max_overhang`: an error past it).
    declared: bool,
    /// The bead's width, mm.
    bead: f64,
    lift: f64,
    chord: f64,
    below: Option<Region>,
    worst: Option<Worst<Spot>>,
    /// The step at the worst place, mm.
    step: f64,
}

/// A place on a planar layer: the layer (from 0) and a point (mm).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Spot {
    k: usize,
    at: [f64; 2],
}

impl std::fmt::Display for Spot {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "layer {}, ({} mm, {} mm)",
            self.k + 1,
            crate::units::short(self.at[0]),
            crate::units::short(self.at[1])
        )
    }
}

impl Lean {
    fn new(limit: Option<f64>, lift: f64, chord: f64, bead: f64) -> Self {
        use crate::deposit::{DEFAULT_OVERHANG, DEFAULT_OVERHANG_STEP};
        let default = DEFAULT_OVERHANG
            .to_radians()
            .min((DEFAULT_OVERHANG_STEP * bead).atan2(lift));
        Lean {
            limit: limit.unwrap_or(default),
            declared: limit.is_some(),
            bead,
            lift,
            chord,
            below: None,
            worst: None,
            step: 0.0,
        }
    }

    /// Measures layer `k`'s region against the one below, then keeps it.
    fn layer(&mut self, k: usize, region: &Region) {
        let limit = self.limit;
        if let Some(below) = &self.below {
            let pts: Vec<[f64; 2]> = region.polylines(self.chord).concat();
            let stride = pts.len().div_ceil(LEAN_SAMPLES).max(1);
            for &p in pts.iter().step_by(stride) {
                if below.contains(p) {
                    continue;
                }
                let d = below.distance_to_boundary(p);
                // Past ¾ of a bead it lands beside the layer below:
                // lmd::stacking's error, not a second report.
                if !self.declared && d > 0.75 * self.bead {
                    continue;
                }
                let lean = d.atan2(self.lift);
                if lean > limit {
                    let at = Spot { k, at: p };
                    Worst::hit(&mut self.worst, lean, limit, at);
                    if self.worst.is_some_and(|w| w.at == at) {
                        self.step = d;
                    }
                }
            }
        }
        self.below = Some(region.clone());
    }

    fn report(self, slicing: crate::span::Span, diags: &mut Diagnostics) {
        if let Some(w) = self.worst {
            let fix = message::verify::OverhangFix {
                step: self.step,
                height: self.lift,
                planar: true,
                declared: self.declared,
                bead: self.bead,
                tilting: None,
            };
            diags.push(message::verify::overhang(&w, &fix, Some(slicing)));
        }
    }
}

/// Which layer is being filled, for the errors of its fill.
struct Where<'a> {
    k: usize,
    /// Whether the profile changes from layer to layer (the error then says
    /// the builtin's value).
    varies: bool,
    extrusion: &'a Extrusion,
    slicing: &'a PlanarSlicing,
}

/// What the layers showed that the user should hear of, gathered layer by
/// layer and reported once for the whole part.
#[derive(Default)]
struct Findings {
    /// Layers with a spot more than a bead width from every track, and the
    /// first such spot.
    gaps: usize,
    first_gap: Option<(usize, fill::Gap)>,
    /// Layers whose neighbouring tracks run farther apart than the bead,
    /// and the widest such gap.
    apart: usize,
    widest: Option<(usize, Apart)>,
    /// Layers with a spot no bead reaches, and the farthest such spot.
    thin_gaps: usize,
    thin: Option<(usize, fill::Gap)>,
    /// The first layer with fewer contour passes than asked, and how many fit.
    few_passes: Option<(usize, usize)>,
    /// The thinnest contour sliver (layer, mean width).
    sliver: Option<(usize, f64)>,
    /// Tracks shorter than a bead, and the first layer with one.
    short_tracks: usize,
    first_short: Option<usize>,
    /// Style ids given to some track.
    used: BTreeSet<u16>,
}

impl Findings {
    fn layer(&mut self, k: usize, f: &Filled, contours: usize, w: f64) {
        if let Some(a) = f.apart {
            self.apart += 1;
            if self.widest.is_none_or(|(_, o)| a.apart > o.apart) {
                self.widest = Some((k, a));
            }
        }
        if let Some(g) = f.gap {
            if g.distance > w {
                self.gaps += 1;
                self.first_gap.get_or_insert((k, g));
            } else {
                self.thin_gaps += 1;
                if self.thin.is_none_or(|(_, t)| g.distance > t.distance) {
                    self.thin = Some((k, g));
                }
            }
        }
        let passes = f
            .tracks
            .iter()
            .filter_map(|t| match t.kind {
                TrackKind::Contour { index } => Some(index + 1),
                TrackKind::Infill => None,
            })
            .max()
            .unwrap_or(0);
        if passes < contours && self.few_passes.is_none() {
            self.few_passes = Some((k, passes));
        }
        // The length of the deposit under way: tracks linked with the laser
        // on are one deposit, started and stopped once.
        let mut run = 0.0;
        for (i, t) in f.tracks.iter().enumerate() {
            let length = style::length(&t.points);
            // A contour loop whose sides run closer than the tracks may (a
            // sliver: mean width 2·area/perimeter) piles up like any overlap.
            if let TrackKind::Contour { .. } = t.kind {
                let thickness = 2.0 * loop_area(&t.points) / length.max(1e-12);
                if thickness < MIN_OFFSET_RATIO * w
                    && self.sliver.is_none_or(|(_, s)| thickness < s)
                {
                    self.sliver = Some((k, thickness));
                }
            }
            run += length;
            if let (Some(l), Some(next)) = (&t.link, f.tracks.get(i + 1)) {
                if l.laser {
                    let mut link = Vec::with_capacity(l.via.len() + 2);
                    link.extend(t.points.last().copied());
                    link.extend_from_slice(&l.via);
                    link.push(next.points[0]);
                    run += style::length(&link);
                    continue;
                }
            }
            if run < w {
                self.short_tracks += 1;
                self.first_short.get_or_insert(k);
            }
            run = 0.0;
        }
    }

    /// Reports what was found: the warnings, and an error when a spot wider
    /// than a bead is unfilled.
    fn report(
        self,
        model: &Model,
        bead: &Bead,
        extrusion: &Extrusion,
        slicing: &PlanarSlicing,
        diags: &mut Diagnostics,
    ) {
        use message::slicing as say;
        let w = bead.width.0;
        let at = say::FillAt {
            shape: extrusion.shape_span,
            slicing: slicing.span,
        };
        if let Some((k, g)) = self.first_gap {
            diags.push(say::fill_gap(self.gaps, k, &g, w, at));
        }
        if let Some((k, a)) = self.widest {
            diags.push(say::tracks_apart(self.apart, k, &a, w, at));
        }
        if let Some((k, g)) = self.thin {
            diags.push(say::thin_gap(self.thin_gaps, k, &g, w, at));
        }
        if let Some((k, t)) = self.sliver {
            diags.push(say::contour_sliver(k, t, w, at));
        }
        for st in model
            .styles
            .table
            .iter()
            .filter(|st| !self.used.contains(&st.id))
        {
            diags.push(say::unused_style(&st.name, st.span));
        }
        if let Some((k, passes)) = self.few_passes {
            diags.push(say::few_contours(passes, slicing.contours, k, slicing.span));
        }
        if let Some(first) = self.first_short {
            diags.push(say::short_tracks(self.short_tracks, w, first, slicing.span));
        }
    }
}

/// The track without points that repeat the one before (within a nanometre),
/// or `None` if too little is left to move along: a raster track needs two
/// distinct points, a closed contour three. Sub-micron profiles flatten to such
/// points, and a direction of travel needs a distance.
fn distinct(mut t: Track) -> Option<Track> {
    super::dedup_points(&mut t.points);
    let need = match t.kind {
        TrackKind::Contour { .. } => 4,
        TrackKind::Infill => 2,
    };
    (t.points.len() >= need).then_some(t)
}

/// The tracks that keep enough distinct points ([`distinct`]); a track
/// linked to one that is dropped loses its link, so a link always leads to
/// the track that follows it.
fn distinct_tracks(tracks: Vec<Track>) -> Vec<Track> {
    let mut out: Vec<Track> = Vec::with_capacity(tracks.len());
    for t in tracks {
        match distinct(t) {
            Some(t) => out.push(t),
            // The track before (if kept) led here.
            None => {
                if let Some(prev) = out.last_mut() {
                    prev.link = None;
                }
            }
        }
    }
    if let Some(last) = out.last_mut() {
        last.link = None;
    }
    out
}

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
    seam: Seam,
    region: Region,
    /// Its tracks in the order they are laid.
    tracks: Vec<Track>,
    /// The strips their moves fill, track by track.
    pitch: Vec<TrackPitch>,
    /// Each island's tracks (visited in the order [`nearest_first`] gives
    /// from where the layer below ended; one for a layer of one piece).
    islands: Vec<Island>,
    gap: Option<fill::Gap>,
    /// The widest gap between neighbouring tracks of any island.
    apart: Option<Apart>,
}

impl<'m> Filled<'m> {
    /// A layer filled as `islands` (one for a layer of one piece; several
    /// are ordered by [`Filled::order`]).
    fn new(
        shape: &'m Shape,
        angle: f64,
        seam: Seam,
        region: Region,
        islands: Vec<Island>,
        gap: Option<fill::Gap>,
    ) -> Self {
        let apart = islands
            .iter()
            .filter_map(|i| i.apart)
            .max_by(|a, b| a.apart.total_cmp(&b.apart));
        let mut filled = Filled {
            shape,
            angle,
            seam,
            region,
            tracks: Vec::new(),
            pitch: Vec::new(),
            islands,
            gap,
            apart,
        };
        filled.order(None);
        filled
    }

    /// Where its last track ends.
    fn end(&self) -> Option<[f64; 2]> {
        self.tracks.last().and_then(|t| t.points.last().copied())
    }

    /// Its islands' tracks in the order they are laid, starting nearest
    /// `from` (also on a reused layer: the layer below may have ended
    /// elsewhere).
    fn order(&mut self, from: Option<[f64; 2]>) {
        let order = nearest_first(&self.islands, from);
        self.tracks = order
            .iter()
            .flat_map(|&i| self.islands[i].tracks.iter().cloned())
            .collect();
        self.pitch = order
            .iter()
            .flat_map(|&i| self.islands[i].pitch.iter().cloned())
            .collect();
    }
}

/// Where the contour loops of layer `k` start.
fn seam_at(rule: SeamRule, k: usize) -> Seam {
    match rule {
        SeamRule::Lowest => Seam::Lowest,
        SeamRule::SharpestCorner => Seam::SharpestCorner,
        SeamRule::Staggered { shift } => Seam::Along(shift.0 * k as f64),
        r => r.direction(k).map_or(Seam::Lowest, Seam::Toward),
    }
}

/// How a layer is filled: the raster's angle (deg), where contours start,
/// how far the first pass is inset, the bead's width, the strip the lift
/// was chosen for, and the gap check's samples.
#[derive(Clone, Copy)]
struct How {
    angle: f64,
    seam: Seam,
    inset: f64,
    w: f64,
    pitch: f64,
    gap_samples: usize,
    /// The samples [`fill::pitch::strips`] takes of the layer.
    strip_samples: usize,
}

/// A layer's region, each island's tracks (one list for a layer of one
/// piece) with the strips they fill, and the farthest spot no bead reaches.
type FilledShape = (Region, Vec<Island>, Option<fill::Gap>);

/// One island's tracks, the strip each of their moves fills
/// ([`fill::pitch`]) and the widest gap between neighbours.
#[derive(Clone)]
struct Island {
    tracks: Vec<Track>,
    pitch: Vec<TrackPitch>,
    apart: Option<Apart>,
}

/// The pitches of a track's moves, and of its laser-on link's to the next
/// track (empty without one).
#[derive(Clone, Debug, Default)]
struct TrackPitch {
    track: Vec<f64>,
    link: Vec<f64>,
}

impl Island {
    /// `tracks` of `region` with a bead `w` wide, the lift chosen for
    /// strips `offset` wide, their strips measured.
    fn new(region: &Region, tracks: Vec<Track>, [w, offset]: [f64; 2], samples: usize) -> Self {
        let links: Vec<Option<Vec<[f64; 2]>>> = tracks
            .iter()
            .enumerate()
            .map(|(i, t)| match (&t.link, tracks.get(i + 1)) {
                (Some(l), Some(next)) if l.laser => {
                    Some(link_points(t, &l.via, next)).filter(|p| p.len() >= 2)
                }
                _ => None,
            })
            .collect();
        // A laser-on link is a half circle across the two tracks' spacing
        // (`fill::link`), whose strip is the half disc the tracks' trimmed
        // ends leave: the layer's strips are measured on the tracks as they
        // were before the trim (the fill's front at the edge, which a
        // contour beside it sees), and the turn fills its spacing.
        let measured: Vec<Vec<[f64; 2]>> = tracks
            .iter()
            .enumerate()
            .map(|(i, t)| {
                let before = i.checked_sub(1).and_then(|k| links[k].as_ref());
                untrimmed(&t.points, before, links[i].as_ref())
            })
            .collect();
        let strands: Vec<Strand<'_>> = measured
            .iter()
            .enumerate()
            .map(|(chain, points)| Strand { points, chain })
            .collect();
        let found = pitch::strips(&strands, [w, offset], samples, |p| region.contains(p));
        let pitch = found
            .pitch
            .into_iter()
            .zip(tracks.iter().zip(&links))
            .map(|(mut track, (t, link))| {
                steady(&t.points, &mut track, offset);
                (track, (t, link))
            })
            .map(|(track, (_, link))| TrackPitch {
                link: link
                    .as_ref()
                    .map_or_else(Vec::new, |l| vec![turn_pitch(l, offset, w); l.len() - 1]),
                track,
            })
            .collect();
        Island {
            tracks,
            pitch,
            apart: found.apart,
        }
    }
}

/// How far (a share) the strips of a run of moves may differ and be laid
/// as one, at their mean: a third of the default `rise_tolerance`, so that
/// a contour's chords, each measured a little differently, keep one speed.
const STEADY: f64 = 0.01;

/// Lays runs of a track's moves whose `pitch`es lie within [`STEADY`] of
/// their mean (over their lengths) at that mean, and a run within
/// [`STEADY`] of the fill's `offset` at the offset: a track keeps its
/// speed where its strip hardly changes, and a regular fill the process
/// speed.
fn steady(points: &[[f64; 2]], pitch: &mut [f64], offset: f64) {
    let lengths: Vec<f64> = points
        .windows(2)
        .map(|m| (m[1][0] - m[0][0]).hypot(m[1][1] - m[0][1]))
        .collect();
    let mut start = 0;
    while start < pitch.len() {
        let (mut sum, mut len) = (0.0, 0.0);
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        let mut end = start;
        while end < pitch.len() {
            let (p, l) = (pitch[end], lengths.get(end).copied().unwrap_or(0.0));
            let (s, n) = (sum + p * l, len + l);
            let mean = if n > 0.0 { s / n } else { p };
            let (a, b) = (lo.min(p), hi.max(p));
            if end > start && (b > mean * (1.0 + STEADY) || a < mean * (1.0 - STEADY)) {
                break;
            }
            (sum, len, lo, hi) = (s, n, a, b);
            end += 1;
        }
        let mean = if len > 0.0 { sum / len } else { pitch[start] };
        let mean = if (mean / offset - 1.0).abs() <= STEADY {
            offset
        } else {
            mean
        };
        pitch[start..end].fill(mean);
        start = end;
    }
}

/// A track's `points` with the ends that a laser-on link trims restored:
/// the start by half the chord of the link `before` it (ending at its
/// first point), the end by half that of the link `after` it, along the
/// track.
fn untrimmed(
    points: &[[f64; 2]],
    before: Option<&Vec<[f64; 2]>>,
    after: Option<&Vec<[f64; 2]>>,
) -> Vec<[f64; 2]> {
    let mut out = points.to_vec();
    let half = |l: &Vec<[f64; 2]>| match (l.first(), l.last()) {
        (Some(a), Some(b)) => 0.5 * (b[0] - a[0]).hypot(b[1] - a[1]),
        _ => 0.0,
    };
    // `end` moved by `by` away from `other`, along the track.
    let grow = |end: [f64; 2], other: [f64; 2], by: f64| {
        let d = [end[0] - other[0], end[1] - other[1]];
        let len = d[0].hypot(d[1]);
        if len > 0.0 && by.is_finite() {
            [end[0] + d[0] / len * by, end[1] + d[1] / len * by]
        } else {
            end
        }
    };
    let n = out.len();
    if n < 2 {
        return out;
    }
    if let Some(l) = before {
        out[0] = grow(points[0], points[1], half(l));
    }
    if let Some(l) = after {
        out[n - 1] = grow(points[n - 1], points[n - 2], half(l));
    }
    out
}

/// The strip a laser-on link's half circle fills: its diameter, the chord
/// from its first point to its last (the fill's `offset` when within
/// [`STEADY`] of it, so a regular fill's turns keep the tracks' speed; `w`
/// where it has no length).
fn turn_pitch(link: &[[f64; 2]], offset: f64, w: f64) -> f64 {
    let chord = match (link.first(), link.last()) {
        (Some(a), Some(b)) => (b[0] - a[0]).hypot(b[1] - a[1]),
        _ => 0.0,
    };
    if !(chord.is_finite() && chord > 0.0) {
        w
    } else if (chord / offset - 1.0).abs() <= STEADY {
        offset
    } else {
        chord
    }
}

/// The points of the link from track `t` along `via` to `next`, without
/// points that repeat the one before: the path the IR lays it as.
fn link_points(t: &Track, via: &[[f64; 2]], next: &Track) -> Vec<[f64; 2]> {
    let mut points = Vec::with_capacity(via.len() + 2);
    points.extend(t.points.last().copied());
    points.extend_from_slice(via);
    points.extend(next.points.first().copied());
    super::dedup_points(&mut points);
    points
}

/// Fills one layer's `shape`: its region checked for holes that do not
/// make one, then filled ([`fill_layer`]). Separate islands (a mesh's
/// section) are each checked and filled on their own; the caller orders
/// them ([`nearest_first`]): the plan travels from one to the next with
/// the laser off, lifted, as between any two tracks that are not linked.
fn fill_shape(shape: &Shape, how: &How, at: &Where<'_>) -> Result<FilledShape, Vec<Diagnostic>> {
    let chord = at.slicing.chord_error.0;
    let layer = holes::Layer {
        k: at.k,
        varies: at.varies,
    };
    let one = |s: &Shape| {
        let region = outline::region(s, chord);
        let faults = holes::faults(&region, s, &layer);
        if !faults.is_empty() {
            return Err(faults);
        }
        let (tracks, gap) = fill_layer(&region, how, at).map_err(|e| vec![e])?;
        let island = Island::new(&region, tracks, [how.w, how.pitch], how.strip_samples);
        Ok((region, island, gap))
    };
    let Shape::Islands(parts) = shape else {
        let (region, island, gap) = one(shape)?;
        return Ok((region, vec![island], gap));
    };
    let mut regions = Vec::with_capacity(parts.len());
    let mut fills = Vec::with_capacity(parts.len());
    let mut gap: Option<fill::Gap> = None;
    for part in parts {
        let (region, island, g) = one(part)?;
        regions.push(region);
        fills.push(island);
        if let Some(g) = g.filter(|g| gap.is_none_or(|o| g.distance > o.distance)) {
            gap = Some(g);
        }
    }
    Ok((Region::islands(regions), fills, gap))
}

/// The islands' tracks one island after the other: first the island whose
/// first track starts nearest to `from` (where the layer below ended; the
/// lowest island on the first layer), then always the one whose first
/// track starts nearest to where the last ended. A tie goes to the island
/// whose lowest point is lower (least y, then least x: the order islands
/// come in). Deterministic, and short for the handful of islands a layer
/// has (quadratic in their number); starting near the layer below keeps a
/// part of several islands from crossing back over itself every layer.
fn nearest_first(islands: &[Island], from: Option<[f64; 2]>) -> Vec<usize> {
    let mut left: Vec<usize> = (0..islands.len()).collect();
    let mut out = Vec::with_capacity(islands.len());
    let mut end = from;
    while !left.is_empty() {
        // `min_by` keeps the first of equal distances: the lower island.
        let next = end.map_or(0, |e| {
            let start = |i: usize| {
                islands[i]
                    .tracks
                    .first()
                    .and_then(|t| t.points.first())
                    .map_or(f64::INFINITY, |p| (p[0] - e[0]).hypot(p[1] - e[1]))
            };
            (0..left.len())
                .min_by(|&a, &b| start(left[a]).total_cmp(&start(left[b])))
                .unwrap_or(0)
        });
        let i = left.remove(next);
        end = islands[i]
            .tracks
            .last()
            .and_then(|t| t.points.last().copied())
            .or(end);
        out.push(i);
    }
    out
}

/// Fills one layer's `region` with the raster at `how.angle` (deg), contours
/// starting at `how.seam`, and finds the farthest spot no bead reaches, if a
/// raster promises a full layer.
fn fill_layer(
    region: &Region,
    how: &How,
    at: &Where<'_>,
) -> Result<(Vec<Track>, Option<fill::Gap>), Diagnostic> {
    let How {
        angle,
        seam,
        inset,
        w,
        gap_samples,
        ..
    } = *how;
    let slicing = at.slicing;
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
            link: match r.link {
                LinkMode::None => Linking::None,
                LinkMode::LaserOn => Linking::LaserOn,
                LinkMode::LaserOff => Linking::LaserOff,
            },
            // The last contour runs an offset beyond the raster's region:
            // the last line stays within a bead of it.
            closing: if slicing.contours > 0 {
                (w - slicing.offset.0).max(0.0)
            } else {
                f64::INFINITY
            },
        }),
        seam,
    };
    let tracks = distinct_tracks(
        fill::fill_region(region, &spec, slicing.chord_error.0).map_err(|e| fill_error(e, at))?,
    );
    if tracks.is_empty() {
        return Err(fill_error(FillError::Empty, at));
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
        .and_then(|_| fill::gap_in(region, 0.0, &tracks, THIN_GAP * w, gap_samples));
    Ok((tracks, gap))
}

fn fill_error(e: FillError, layer: &Where<'_>) -> Diagnostic {
    message::slicing::fill_error(
        &e,
        &message::slicing::FillLayer {
            k: layer.k,
            varies: layer.varies,
            shape: layer.extrusion.shape_span,
            profile: layer.extrusion.profile_span,
            slicing: layer.slicing.span,
        },
    )
}

/// A layer's tracks in the order they are laid, the strips their moves
/// fill and their styles.
struct Tracks<'a> {
    tracks: &'a [Track],
    pitch: &'a [TrackPitch],
    styles: &'a [u16],
}

/// Layer `k` of `n`: each track a path, and each link a path between its
/// two tracks. `pitch` is the strip the plan's lift was chosen for.
fn layer(values: &Values, k: usize, n: usize, [lift, pitch]: [f64; 2], t: &Tracks<'_>) -> Layer {
    let z = k as f64 * lift;
    let at = |style: u16| Laid {
        z,
        lift,
        pitch,
        deposit: values.of(style, k),
        defocus: values.defocus,
        style,
        bead: values.adapts(style),
    };
    let mut paths = Vec::with_capacity(t.tracks.len());
    let none = TrackPitch::default();
    for (i, (track, &style)) in t.tracks.iter().zip(t.styles).enumerate() {
        let kind = match track.kind {
            TrackKind::Contour { .. } => PathKind::Contour,
            TrackKind::Infill => PathKind::Infill,
        };
        let pitch = t.pitch.get(i).unwrap_or(&none);
        // `distinct` left at least two points.
        paths.push(path(kind, &track.points, &pitch.track, &at(style)));
        let (Some(link), Some(next)) = (&track.link, t.tracks.get(i + 1)) else {
            continue;
        };
        let points = link_points(track, &link.via, next);
        if points.len() >= 2 {
            // A link that deposits is laid like the track it leaves.
            let (kind, moves) = if link.laser {
                (PathKind::Infill, &pitch.link[..])
            } else {
                (PathKind::Travel, &[][..])
            };
            paths.push(path(kind, &points, moves, &at(style)));
        }
    }
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
        label: String::new(),
        on_plate: false,
    }
}

/// How a layer's points are laid: its plane and rise, and a track's values.
struct Laid {
    z: f64,
    lift: f64,
    /// The strip the lift was chosen for, mm.
    pitch: f64,
    deposit: Deposit,
    defocus: f32,
    style: u16,
    /// The bead, where the track's speed follows the strip it fills (its
    /// speed is the process block's, and the model has a speed to choose).
    bead: Option<crate::deposit::Deposit>,
}

impl Laid {
    /// The speed of a move filling a strip `p` wide: the track's own where
    /// that is the strip the lift was chosen for or the speed is fixed,
    /// else the speed at which it lays, over `p`, what the track lays over
    /// the plan's strip.
    fn speed(&self, p: f64) -> f32 {
        let v = self.deposit.speed;
        let Some(bead) = &self.bead else { return v };
        if (p - self.pitch).abs() <= 1e-6 * self.pitch || p.is_nan() || p <= 0.0 {
            return v;
        }
        let powder = crate::units::MassFlow(f64::from(self.deposit.powder) / 60.0);
        let rise = bead.rise(Speed(f64::from(v)), Length(self.pitch), Some(powder));
        let u = bead.clone().fed(powder).speed_for(rise, Length(p)).0;
        if u.is_finite() && u > 0.0 {
            u as f32
        } else {
            v
        }
    }
}

/// The IR path through `pts` (at least two, each distinct from the next),
/// the laser on from each point to the next where `pitch` gives the strip
/// the move fills (none: a laser-off path).
fn path(kind: PathKind, pts: &[[f64; 2]], pitch: &[f64], l: &Laid) -> Path {
    let m = pts.len();
    let laser = !pitch.is_empty();
    let points = (0..m)
        .map(|i| {
            // Every point has a neighbour at a distance to take a direction from.
            let (a, b) = if i + 1 < m {
                (i, i + 1)
            } else {
                (i.saturating_sub(1), i)
            };
            let (dx, dy) = (pts[b][0] - pts[a][0], pts[b][1] - pts[a][1]);
            let len = dx.hypot(dy).max(1e-12);
            // The last point (no move) keeps the move before's.
            let p = pitch.get(i.min(m.saturating_sub(2))).copied();
            Point {
                pos: [pts[i][0], pts[i][1], l.z],
                normal: [0.0, 0.0, 1.0],
                tangent: [(dx / len) as f32, (dy / len) as f32, 0.0],
                layer_height: l.lift as f32,
                speed: p.map_or(l.deposit.speed, |p| l.speed(p)),
                power: l.deposit.power,
                powder: l.deposit.powder,
                defocus: l.defocus,
                laser_on: laser && i + 1 < m,
                style: l.style,
                pitch: p.unwrap_or(l.pitch) as f32,
                rise: 0.0,
            }
        })
        .collect();
    Path { kind, points }
}

/// The process values a track is deposited with.
#[derive(Clone, Copy)]
struct Deposit {
    power: f32,
    powder: f32,
    speed: f32,
}

/// The process block's values and each style's, looked up by style id once
/// per track rather than searched for.
struct Values<'m> {
    model: &'m Model,
    speed: f32,
    powder: f32,
    defocus: f32,
    styles: BTreeMap<u16, &'m crate::sema::model::Style>,
    /// The bead's deposit model, where it has speeds to choose from.
    bead: Option<crate::deposit::Deposit>,
}

impl<'m> Values<'m> {
    fn table(model: &'m Model, slicing: &PlanarSlicing) -> Self {
        Values {
            model,
            speed: slicing.speed.0 as f32,
            powder: model.process.powder.g_min() as f32,
            defocus: model.process.defocus.0 as f32,
            styles: model.styles.table.iter().map(|s| (s.id, s)).collect(),
            bead: model
                .bead
                .as_ref()
                .filter(|b| !matches!(b.model, crate::sema::model::HeightModel::Measured { .. }))
                .map(|b| b.deposit()),
        }
    }

    /// The bead model a track of `style` picks its speed from, by the strip
    /// it fills: where its speed is the process block's (the style sets
    /// none) and the model has speeds to choose from (not `measured`).
    fn adapts(&self, style: u16) -> Option<crate::deposit::Deposit> {
        if self.styles.get(&style).is_some_and(|s| s.speed.is_some()) {
            return None;
        }
        self.bead.clone()
    }

    /// The values of `style` on layer `k` (the process power may be a ramp).
    fn of(&self, style: u16, k: usize) -> Deposit {
        let power = self.model.process.power.at(k).watts() as f32;
        match self.styles.get(&style) {
            Some(s) => Deposit {
                power: s.power.map_or(power, |p| p.watts() as f32),
                powder: s.powder.map_or(self.powder, |m| m.g_min() as f32),
                speed: s.speed.map_or(self.speed, |v| v.0 as f32),
            },
            None => Deposit {
                power,
                powder: self.powder,
                speed: self.speed,
            },
        }
    }
}
