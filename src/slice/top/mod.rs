//! Slicing a solid with a variable top: `N`
//! layers that each lay the same fraction `H/N` of the local height, so the
//! last one ends on the top everywhere. The maths is in
//! [`crate::slice::variable`]; this module applies it to the model and
//! writes IR:
//!
//! 1. the footprint and the scan axis (`auto`: the axis the top rises more
//!    along, the paper's rule);
//! 2. the top sampled where tracks can run → the layer count
//!    (`count`: `⌈H_max/h_max⌉ ≤ N ≤ ⌊H_min/h_min⌋`);
//! 3. the track lines across (`layout`: balanced unequal-height overlap,
//!    closed on the far edge by one uniform stretch);
//! 4. the tracks along, each in the fewest constant-speed segments within
//!    the height tolerance (`tracks`);
//! 5. the IR (`emit`).
//!
//! Steps 2–4 repeat until the top's range over the tracks' points lies in
//! the range the count was chosen for (the samples of step 2 need not hit
//! the tracks' own points; a round or two at most). Each step is linear in
//! the points it makes.

mod count;
/// The convex hull of points (the thermal model's outline of a layer).
pub(crate) use count::hull;
/// A footprint seen along a tilted build direction (the report's design
/// volume of a tilted fill).
pub(crate) use tilted::seen_along;
mod deposit;
mod direction;
mod emit;
mod follow;
mod footprint;
mod layout;
mod level;
mod surface;
mod tilted;
mod too_short;
mod tracks;
mod undercut;
mod underside;

use crate::diag::{message, Diagnostics};
use crate::ir::Layer;
use crate::sema::model::{Axis, Bead, Level, Model, Top, TopExtrusion, VariableSlicing};
use crate::slice::variable::segments::SegmentSpec;
use crate::slice::variable::speed::BeadMap;
use crate::slice::variable::Positive;
use crate::units::Length;
use count::TopRange;
use footprint::{sample, Footprint, Sampled};
use std::num::NonZeroU32;
use surface::Surface;

// What a wall on a scan lays its beads with (`crate::slice::wall`): the
// same layers of the same fraction of the gap, on the same process.
pub(in crate::slice) use emit::direction;
pub(in crate::slice) use emit::{along, Process};
pub(in crate::slice) use follow::{check as follow_check, limit as follow_limit, Follow};
pub(in crate::slice) use footprint::spaced;
pub(in crate::slice) use level::{mean_heights, passes, stacked};
pub(in crate::slice) use surface::Base;
pub(crate) use surface::{Bad as TopFault, Form as TopForm};
pub(in crate::slice) use too_short::report_at as segments_too_short;
pub(in crate::slice) use tracks::{Failure, Track};

/// Rounds of count → layout → tracks before the range must have settled.
const MAX_ROUNDS: usize = 6;

/// Layer counts tried besides the fewest when the tracks' spacing needs
/// speeds outside the bead's range.
const MAX_COUNT_TRIES: usize = 32;

/// Slices a footprint up to its top in variable layers. Returns the layers
/// and any warnings, or every diagnostic found.
pub fn slice(
    model: &Model,
    bead: &Bead,
    ex: &TopExtrusion,
    slicing: &VariableSlicing,
) -> Result<(Vec<Layer>, Diagnostics), Diagnostics> {
    follow::check(model, bead, slicing)?;
    if let Some(at) = slicing.direction {
        if let Some(tilted) = tilted::slice(model, bead, ex, slicing, at) {
            return tilted;
        }
    }
    plan(model, bead, ex, slicing)
}

/// `ex`'s layers planned from above: its scan levelled first when
/// `level = …`, else from its base. A tilted fill's, in the part turned
/// so its direction is up.
fn plan(
    model: &Model,
    bead: &Bead,
    ex: &TopExtrusion,
    slicing: &VariableSlicing,
) -> Result<(Vec<Layer>, Diagnostics), Diagnostics> {
    match (&ex.base, slicing.level) {
        (Some(scan), Level::Auto(_) | Level::At(..)) => {
            level::slice(model, bead, ex, slicing, scan)
        }
        _ => build(model, bead, ex, slicing, Base::of(ex, None)).map(|b| (b.layers, b.warnings)),
    }
}

/// Variable layers built: the layers, their warnings, and the tracks' lines.
pub(super) struct Built {
    layers: Vec<Layer>,
    warnings: Diagnostics,
    scan: Axis,
    lines: layout::Layout,
}

impl Built {
    fn new(layers: Vec<Layer>, warnings: Diagnostics, scan: Axis, lines: layout::Layout) -> Self {
        Built {
            layers,
            warnings,
            scan,
            lines,
        }
    }
}

/// Slices `ex` from `base` up to its top.
fn build(
    model: &Model,
    bead: &Bead,
    ex: &TopExtrusion,
    slicing: &VariableSlicing,
    base: Base<'_>,
) -> Result<Built, Diagnostics> {
    // A layer count's help names only tops that plan: each is tried by
    // the same steps, up to its tracks (not their layers, nor a help).
    let plans = |t: &Top| {
        let mut tried = ex.clone();
        tried.top = t.clone();
        let base = match base {
            Base::Scan(_) => Base::of(&tried, None),
            b => b,
        };
        build_with(model, bead, &tried, slicing, base, None).is_ok()
    };
    build_with(model, bead, ex, slicing, base, Some(&plans))
}

/// The constant-speed segments' tolerance and shortest length (the
/// bead's width unless declared).
fn segment_spec(bead: &Bead, slicing: &VariableSlicing) -> Result<SegmentSpec, Diagnostics> {
    let positive = |what, l: Length| Positive::new(what, l).map_err(|e| internal(e.to_string()));
    Ok(SegmentSpec {
        tolerance: positive("tolerance", slicing.tolerance)?,
        min_length: positive("min_length", slicing.min_length.unwrap_or(bead.width))?,
    })
}

/// [`build`], its layers laid when `plans` is given (the count's help tries
/// its tops by it); without, only up to the tracks, the layers left empty:
/// whether `ex` plans at all.
fn build_with(
    model: &Model,
    bead: &Bead,
    ex: &TopExtrusion,
    slicing: &VariableSlicing,
    base: Base<'_>,
    plans: Option<&dyn Fn(&Top) -> bool>,
) -> Result<Built, Diagnostics> {
    let w = bead.width.0;
    let fp = Footprint::new(ex, w)?;
    let mut top = Surface::over(ex, |axis| fp.written_extent(axis), base);
    // Samples every eighth of a bead: a top that bends within a bead is
    // seen, a plane costs nothing (its samples are dropped again).
    let pitch = w / 8.0;
    let CountInput {
        scan,
        sampled,
        count_pitch,
        map,
        range,
    } = count_input(&fp, &mut top, pitch, ex, bead, slicing)?;
    let mut range = range;
    let spec = segment_spec(bead, slicing)?;
    // More layers than the fewest, when the tracks' spacing needs speeds
    // outside the bead's range at the fewest (count → layout → tracks again).
    let mut instead: Option<NonZeroU32> = None;
    let mut tried: Vec<u32> = Vec::new();
    let mut missed = None;
    while tried.len() < MAX_ROUNDS + MAX_COUNT_TRIES {
        // A count's help names only counts whose tracks can be laid.
        let mut builds = |c: NonZeroU32| {
            let Ok(lines) = layout::lay(&fp, scan, &sampled, c, bead, slicing, ex) else {
                return false;
            };
            tracks::plan(&fp, scan, &lines, &mut top, spec, pitch)
                .is_ok_and(|p| deposit::unfillable(&p.tracks, c, bead).is_none())
        };
        let probe = count::Probe {
            fp: &fp,
            scan,
            pitch,
            builds: &mut builds,
            plans,
        };
        let fewest = count::layers(&range, bead, &map, ex, slicing, probe)?;
        let n = instead.unwrap_or(fewest);
        tried.push(n.get());
        let lines = layout::lay(&fp, scan, &sampled, n, bead, slicing, ex)?;
        let planned =
            tracks::plan(&fp, scan, &lines, &mut top, spec, pitch).map_err(|p| match p {
                tracks::Problem::Top(b, more) => b.report(ex, more),
                tracks::Problem::Invalid(e) => internal(e.to_string()),
            })?;
        failures(&planned, scan, bead, slicing, ex, spec)?;
        let Some(actual) = planned.range else {
            return Err(fp.too_narrow(ex, scan).into());
        };
        if !range.holds(&actual) {
            range = range.union(actual);
            continue;
        }
        if let Some(miss) = deposit::unfillable(&planned.tracks, n, bead) {
            // A balanced layout's pitches change with the count: go to the
            // nearest count its tracks can lay, once each.
            let next = match (slicing.layers, count_pitch) {
                (None, None) => {
                    deposit::nearest(&planned.tracks, n, bead).filter(|c| !tried.contains(&c.get()))
                }
                _ => None,
            };
            missed = Some((miss, n));
            match next {
                Some(c) => {
                    instead = Some(c);
                    continue;
                }
                None => break,
            }
        }
        if plans.is_none() {
            return Ok(Built::new(Vec::new(), Diagnostics::new(), scan, lines));
        }
        let tracks = Planned {
            lines: &lines,
            tracks: &planned.tracks,
            scan,
            n,
        };
        let process = process(model, bead, ex, slicing, base);
        let (layers, warnings) = finish(model, bead, ex, slicing, &tracks, &process)?;
        return Ok(Built::new(layers, warnings, scan, lines));
    }
    if let Some((miss, n)) = missed {
        return Err(deposit::report(&miss, n, bead, slicing, ex, scan).into());
    }
    Err(internal(
        "the top's range over the tracks did not settle".into(),
    ))
}

/// The process of `ex`'s layers from `base`: following the scan when
/// `follow = surface`, the nozzle's whole tilt in the part held to the
/// limit when planned turned.
fn process<'m>(
    model: &Model,
    bead: &Bead,
    ex: &TopExtrusion,
    slicing: &VariableSlicing,
    base: Base<'m>,
) -> emit::Process<'m> {
    emit::Process::of(model, bead, base).following(
        follow::limit(model, bead, slicing),
        follow::part_vertical(ex),
    )
}

/// The tracks whose height tolerance needs segments too short, as the error.
fn failures(
    planned: &tracks::Tracks,
    scan: Axis,
    bead: &Bead,
    slicing: &VariableSlicing,
    ex: &TopExtrusion,
    spec: SegmentSpec,
) -> Result<(), Diagnostics> {
    if planned.failures.is_empty() {
        return Ok(());
    }
    Err(too_short::report(
        &planned.failures,
        planned.tracks.len() + planned.failures.len(),
        scan,
        bead,
        slicing,
        ex,
        spec.min_length,
    )
    .into())
}

/// A count's tracks, laid and planned.
struct Planned<'a> {
    lines: &'a layout::Layout,
    tracks: &'a [tracks::Track],
    scan: Axis,
    n: NonZeroU32,
}

/// The layers of tracks that can all be laid, with the warnings they earn
/// (step 5).
fn finish(
    model: &Model,
    bead: &Bead,
    ex: &TopExtrusion,
    slicing: &VariableSlicing,
    p: &Planned<'_>,
    process: &emit::Process<'_>,
) -> Result<(Vec<Layer>, Diagnostics), Diagnostics> {
    let n = p.n;
    let mut warnings = Diagnostics::new();
    if let Some(d) = layout::stretch_warning(p.lines, bead.width.0, slicing, ex) {
        warnings.push(d);
    }
    short_tracks(p.tracks, bead.width.0, slicing, &mut warnings);
    let per_layer: usize = p.tracks.iter().map(|t| t.t.len()).sum();
    crate::slice::within_points(per_layer, n.get(), slicing.span)?;
    // Each track's speeds raise the layer by its height over the strip it
    // fills.
    let maps = p
        .tracks
        .iter()
        .map(|t| BeadMap::new(bead, Some(Length(t.pitch))))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| internal(e.to_string()))?;
    let layers = (0..n.get())
        .map(|i| emit::layer(model, &maps, process, p.tracks, p.scan, i, n))
        .collect();
    Ok((layers, warnings))
}

/// What the layer count is chosen from (steps 1–2): the scan axis, the top
/// sampled for it, the pitch the count is chosen for, the heights the bead
/// stacks there and the top's range. The count's help runs it again on the
/// tops and beads it proposes.
pub(super) struct CountInput<'b> {
    scan: Axis,
    sampled: Sampled,
    count_pitch: Option<Length>,
    map: BeadMap<'b>,
    range: TopRange,
}

/// Steps 1–2 for `top` (the surface of `ex`'s top, or one the help tries)
/// over `fp`, sampled every `pitch`.
pub(super) fn count_input<'b>(
    fp: &Footprint,
    top: &mut Surface<'_>,
    pitch: f64,
    ex: &TopExtrusion,
    bead: &'b Bead,
    slicing: &VariableSlicing,
) -> Result<CountInput<'b>, Diagnostics> {
    let (scan, sampled) = scan_axis(fp, top, pitch, ex, slicing.scan)?;
    // The heights the count is chosen for: what the bead stacks at the
    // pitch the tracks will have, or its own heights for a balanced layout.
    let count_pitch = layout::count_pitch(fp, scan, bead.width.0, slicing).map(Length);
    let map = BeadMap::new(bead, count_pitch).map_err(|e| internal(e.to_string()))?;
    let range = TopRange::of(&sampled).ok_or_else(|| internal("an empty top range".into()))?;
    Ok(CountInput {
        scan,
        sampled,
        count_pitch,
        map,
        range,
    })
}

impl CountInput<'_> {
    /// The layer counts that lay this top within these heights, if any.
    pub(super) fn counts(&self) -> Option<crate::slice::variable::layers::LayerRange> {
        use crate::slice::variable::speed::HeightMap;
        crate::slice::variable::layers::layer_range(self.range.heights, self.map.heights()).ok()
    }
}

/// The scan axis (declared, or the axis the top rises more along; on a tie
/// the one the footprint is longer along) and the top sampled for it.
fn scan_axis(
    fp: &Footprint,
    top: &mut Surface<'_>,
    pitch: f64,
    ex: &TopExtrusion,
    declared: Option<Axis>,
) -> Result<(Axis, Sampled), Diagnostics> {
    let mut sampled = |axis| sample(fp, axis, top, pitch).map_err(|(b, more)| b.report(ex, more));
    if let Some(axis) = declared {
        return sampled(axis)?
            .map(|s| (axis, s))
            .ok_or_else(|| fp.too_narrow(ex, axis).into());
    }
    let (x, y) = (sampled(Axis::X)?, sampled(Axis::Y)?);
    let longer = |a: Axis| {
        let [lo, hi] = fp.written_extent(a);
        hi - lo
    };
    match (x, y) {
        (Some(x), Some(y)) => {
            let tie = (x.rise - y.rise).abs() <= 1e-9 * x.rise.max(y.rise);
            let along_x = if tie {
                longer(Axis::X) >= longer(Axis::Y)
            } else {
                x.rise > y.rise
            };
            Ok(if along_x { (Axis::X, x) } else { (Axis::Y, y) })
        }
        (Some(x), None) => Ok((Axis::X, x)),
        (None, Some(y)) => Ok((Axis::Y, y)),
        (None, None) => Err(fp.too_narrow(ex, Axis::X).into()),
    }
}

/// Warns of tracks shorter than the bead width: they overheat and pile up.
fn short_tracks(
    tracks: &[tracks::Track],
    w: f64,
    slicing: &VariableSlicing,
    out: &mut Diagnostics,
) {
    let short = tracks.iter().filter(|t| t.length() < w).count();
    if short > 0 {
        out.push(message::top::short_tracks(short, w, slicing.span));
    }
}

/// A state the checker's checks should have made impossible.
fn internal(what: String) -> Diagnostics {
    message::top::internal(&what)
}
