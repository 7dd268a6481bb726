//! `direction = auto` (docs/repair.md, *Undercuts*): a target that
//! overhangs the scan, filled along a tilted build direction `d`.
//!
//! Layers laid along `d` stand on each other along `d`: every line along
//! `d` over the footprint must meet the target above the scan in one
//! piece, from the scan up, or its upper piece is laid on nothing. The
//! lines go through the finished face: the footprint's points, each at
//! the target's highest point over it (the profile is the face's outline
//! seen from above, whatever its slope), followed down along
//! `−d` to the scan, which they must meet through its top: the scan is a
//! height field seen from above, and a line that comes under it up a
//! flank steeper than itself may be passing under a part that overhangs
//! itself (`Meets::Flank`). The directions tried are [`Direction::tried`]'s
//! (a degree of arc apart), up to the most the bead and the machines
//! tilt; the first that builds every line is the least tilt. Along a
//! tilted direction the outermost lines run [`SLACK`] of a bead inside the
//! footprint's edge, so that a face leaning between two directions tried
//! does not refuse both. A direction that fails at a line is likely to
//! fail there again at the next, so that line is tried first.
//!
//! Then the fill is planned as a vertical one is, in the part turned so
//! that `d` is up: the scan's surface turned and rastered again (what it
//! hides from `d`'s side is no surface: `lmd::scan-coverage`), the target
//! turned (its inside test turned back into the part), the footprint the
//! finished face (the profile lifted as the lines are) seen along `d`.
//! Its layers are
//! turned back: each point's position, nozzle and travel direction, and
//! the layer's frame, whose `z` is then `d`. A point's layer height and
//! pitch are along and across `d`, as they were along and across the
//! turned vertical: `lmd::stacking`, deposit and the bead's tilt read them
//! as a tilted nozzle's. In the turned part a level (`level = …`) is a
//! height along `d`, so it is levelled to a plane square to `d`; and
//! `follow = surface` follows the turned scan, its nozzle's whole tilt
//! from the part's vertical held to the machines' (module `follow`).

use super::direction::{Direction, MAX_TILT, TILT_STEP};
use crate::diag::message::top::{LineFault, Untilted};
use crate::diag::{message, Diagnostics};
use crate::geometry::outline;
use crate::geometry::profile::Profile;
use crate::geometry::scan::nearest::TriangleTree;
use crate::geometry::scan::{Faces, HeightField};
use crate::geometry::shape::{Outline, Segment, Shape};
use crate::geometry::target::{Inner, Target, Turned};
use crate::ir::{Frame, Kinematics, Layer, Machine};
use crate::sema::model::{
    Bead, Model, ScanBase, Top, TopExtrusion, TopSolid, TurnedFrame, VariableSlicing,
};
use crate::span::Span;
use crate::units::Length;
use nalgebra::{Rotation3, Vector3};
use std::cell::Cell;
use std::collections::HashMap;
use std::sync::Arc;

/// The step along a line, mm: a piece of the target thinner than this
/// along it can be missed.
const STEP: f64 = 0.05;

/// Most lines over the footprint (their spacing grows to fit).
const MAX_LINES: f64 = 4000.0;

/// How far inside the footprint's edge the outermost lines run, mm: on
/// it, to within a hundredth of a millimetre.
const EDGE: f64 = 0.01;

/// How far inside the footprint's edge the outermost lines run along a
/// tilted direction, in bead widths. A face of the target leaning as the
/// direction does is met by the lines along its edge only to the angle
/// the directions are tried at: a line a hundredth inside a slab's face
/// that leans 36.6° leaves it through the face along 36° or 37°. The
/// sliver this lets through, at most a twentieth of a bead wide, is less
/// than a bead's own flank (it is laid over, or left, by that much).
const SLACK: f64 = 1.0 / 20.0;

/// Chord error of the footprint's outline, mm (the footprint's own).
const CHORD_ERROR: f64 = 0.01;

/// What a line along a direction meets.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Meets {
    /// The target in one piece from the scan up.
    OnePiece,
    /// The target again above the scan after leaving it, at this point.
    Again([f64; 3]),
    /// The scan only below a gap under the target, which it left at this
    /// point, when the target contains the scanned part (the part as
    /// designed, module `underside`): air beside the part.
    Gap([f64; 3]),
    /// The scan on a flank steeper than the line, at this point: seen from
    /// above, the scan cannot tell such a flank from the hidden underside
    /// of a part that overhangs itself, under whose edge the line passes.
    Flank([f64; 3]),
    /// No scan under it, or no target over the scan.
    Nothing,
}

/// The lines over the footprint and what they are tested against.
struct Lines<'a> {
    /// The footprint's points on the finished face (each at the target's
    /// highest point over it), mm, the outermost [`EDGE`] inside its edge:
    /// the vertical lines.
    from: Vec<[f64; 3]>,
    /// The same, the outermost [`SLACK`] bead widths inside: the tilted
    /// lines.
    slack: Vec<[f64; 3]>,
    /// The lines' spacing over the footprint, mm.
    spacing: f64,
    /// The finished face's highest point over the footprint, mm.
    face: f64,
    /// Above the target and below the scan, mm.
    z: [f64; 2],
    scan: &'a HeightField,
    top: &'a Top,
    /// Whether the target contains the scanned part: a gap under it is air.
    holds: bool,
    /// The scan's faces, when it has them: where they close a solid,
    /// [`Lines::real_face`] asks them at a flank.
    faces: Option<&'a Faces>,
    /// Whether a line failed at a flank: where the scan has no faces, a
    /// step of the part may be what stops it.
    flanked: Cell<bool>,
}

impl Lines<'_> {
    /// The footprint points of the lines, the outermost [`SLACK`] of a
    /// bead inside the edge when `slack`.
    fn points(&self, slack: bool) -> &[[f64; 3]] {
        if slack {
            &self.slack
        } else {
            &self.from
        }
    }

    /// What the line through footprint point `p` along `d` meets, walked
    /// down from above the target to the scan. It meets the scan through
    /// the scan's top, where the surface under it rose less than it fell
    /// since the last step; where the surface rose more (a flank steeper
    /// than the line, or the scan's edge, reached from beside), the line
    /// may be passing under a part that overhangs itself, which a height
    /// field seen from above shows as a cliff: nothing known to stand on.
    fn meets(&self, p: [f64; 3], d: [f64; 3]) -> Meets {
        let at = |s: f64| [p[0] + s * d[0], p[1] + s * d[1], p[2] + s * d[2]];
        let top = (self.z[1] - p[2]) / d[2];
        let bottom = (self.z[0] - p[2]) / d[2];
        // As a loft's vertical lines: a tall target is walked more coarsely,
        // so each line costs a bounded time.
        let n = ((top - bottom) / STEP)
            .ceil()
            .clamp(1.0, crate::geometry::target::MAX_LINE_SAMPLES) as usize;
        let (mut was, mut pieces) = (false, 0);
        // The last step's height and the scan's under it (none: off it);
        // where the line last left the target.
        let mut last: Option<(f64, Option<f64>)> = None;
        let mut left = None;
        for i in 0..=n {
            let q = at(top - (top - bottom) * i as f64 / n as f64);
            let under = self.scan.at([q[0], q[1]]);
            match under {
                Some(b) if q[2] <= b => {
                    // A rounding's worth of rise is no flank; nor is a
                    // face of a scan with faces.
                    let through_top = match last {
                        Some((z, Some(was_b))) if b - was_b <= z - q[2] + 1e-9 => true,
                        Some(_) => self.real_face(at(top), q, d, (top - bottom) / n as f64),
                        None => false,
                    };
                    return match (pieces, through_top, left) {
                        (0, _, _) => Meets::Nothing,
                        (_, false, _) => {
                            self.flanked.set(true);
                            Meets::Flank(q)
                        }
                        (_, true, Some(u)) if !was && self.holds => Meets::Gap(u),
                        (_, true, _) => Meets::OnePiece,
                    };
                }
                // Off the scan below its highest point: nothing known to
                // stand on.
                None if q[2] <= self.scan.stats.z_range[1] => return Meets::Nothing,
                _ => {}
            }
            last = Some((q[2], under));
            let is = self.top.contains(q);
            if is && !was {
                pieces += 1;
                if pieces > 1 {
                    return Meets::Again(q);
                }
            }
            if was && !is {
                left = Some(q);
            }
            was = is;
        }
        Meets::Nothing
    }

    /// Whether the line along `d` from `start` (above the target), which
    /// comes under the height field at `to` up a flank (the walk's steps
    /// `step` mm apart), meets a real step of the scanned part there
    /// ([`steps_onto`]); `false` for a scan without faces, or whose faces
    /// close no solid.
    fn real_face(&self, start: [f64; 3], to: [f64; 3], d: [f64; 3], step: f64) -> bool {
        self.faces
            .and_then(Faces::solid)
            .is_some_and(|tree| steps_onto(tree, [self.scan.cell(), step], [start, to], d))
    }

    /// Whether the scan's faces close a solid, once a flank asked them.
    fn solid_faces(&self) -> bool {
        self.flanked.get() && self.faces.and_then(Faces::solid).is_some()
    }

    /// The first line (the one at `first` tried first) along `d` that does
    /// not meet the target in one piece, and what it meets; `None` when
    /// every one does. `nothing`: whether a line meeting nothing fails.
    fn fails(
        &self,
        d: Direction,
        first: usize,
        nothing: bool,
        slack: bool,
    ) -> Option<(usize, Meets)> {
        let v = d.vector();
        let points = self.points(slack);
        let n = points.len();
        (0..n)
            .map(|i| (first + i) % n)
            .find_map(|k| match self.meets(points[k], v) {
                Meets::OnePiece => None,
                Meets::Nothing if !nothing => None,
                m => Some((k, m)),
            })
    }

    /// The least tilted direction in `(from, to]` deg that builds every
    /// line, the outermost [`SLACK`] of a bead inside the edge, among
    /// every direction [`Direction::azimuths`] says (`fine`) or the
    /// [`AZIMUTHS`](super::direction::AZIMUTHS) alone; or, one step more
    /// tilted at most, one that builds them to a hundredth of a
    /// millimetre: a slab leaning 30° is built along 30°, not along 29°
    /// within the slack.
    fn least(&self, from: f64, to: f64, fine: bool, witness: &mut usize) -> Option<Direction> {
        let d = self.first(Direction::tried(from, to, fine), true, witness)?;
        // Within the slack a face leaning along one of the azimuths tried
        // first is met a step early; along its own lean the lines meet it
        // to the hundredth.
        let near = Direction::tried(d.tilt - TILT_STEP, (d.tilt + TILT_STEP).min(to), false);
        Some(self.first(near, false, &mut witness.clone()).unwrap_or(d))
    }

    /// The first of `tried` that builds every line (the outermost
    /// [`SLACK`] of a bead inside the edge when `slack`); `witness`: the
    /// line tried first, then the last that failed.
    fn first(
        &self,
        mut tried: impl Iterator<Item = Direction>,
        slack: bool,
        witness: &mut usize,
    ) -> Option<Direction> {
        tried.find(|&d| match self.fails(d, *witness, true, slack) {
            Some((k, _)) => {
                *witness = k;
                false
            }
            None => true,
        })
    }
}

/// The fill of `ex` along the least tilted direction that builds it, when
/// vertical does not (`direction = auto` at `at`); `None` when vertical
/// builds it (or the top is no target mesh or solid on a scan), to be
/// planned from above as without `direction`.
pub(super) fn slice(
    model: &Model,
    bead: &Bead,
    ex: &TopExtrusion,
    slicing: &VariableSlicing,
    at: Span,
) -> Option<Result<(Vec<Layer>, Diagnostics), Diagnostics>> {
    let lines = lines(ex, bead)?;
    // Vertical is today's plan: its other refusals (a line off the scan or
    // the target) are its own.
    let (mut witness, _) = lines.fails(Direction::VERTICAL, 0, false, false)?;
    let (limit, by) = limit(model, bead);
    let Some(d) = lines.least(0.0, limit, true, &mut witness) else {
        return Some(Err(untilted(&lines, ex, at, (limit, &by), witness).into()));
    };
    Some(plan(model, bead, ex, slicing, &lines, d))
}

/// The lines over `ex`'s footprint (every eighth of a bead, or wider to
/// keep to [`MAX_LINES`]), when its top is a target mesh or
/// solid on a scan and has a face over the footprint.
fn lines<'a>(ex: &'a TopExtrusion, bead: &Bead) -> Option<Lines<'a>> {
    let scan = &ex.base.as_ref()?.surface;
    let bounds = match &ex.top {
        Top::Mesh(m) => m.surface.bounds(),
        Top::Solid(s) => s.surface.bounds()?,
        _ => return None,
    };
    let profile = outline::profile(&ex.shape, CHORD_ERROR);
    let [lo, hi] = profile.bounds()?;
    let spacing = (bead.width.0 / 8.0).max(((hi[0] - lo[0]) * (hi[1] - lo[1]) / MAX_LINES).sqrt());
    if !(spacing.is_finite() && spacing > 0.0) {
        return None;
    }
    // The two sets share most of their grid: each point's height once (a
    // turned target or a loft walks a line for it).
    let mut known: HashMap<[u64; 2], Option<f64>> = HashMap::new();
    let mut heights = |pts: Vec<[f64; 2]>| -> Vec<([f64; 2], Option<f64>)> {
        pts.into_iter()
            .map(|p| {
                let h = *known
                    .entry(p.map(f64::to_bits))
                    .or_insert_with(|| ex.top.mesh_at(p).flatten().filter(|h| h.is_finite()));
                (p, h)
            })
            .collect()
    };
    let from = heights(footprint(&profile, [lo, hi], spacing, EDGE));
    let slack = heights(footprint(&profile, [lo, hi], spacing, SLACK * bead.width.0));
    // The finished face's highest point over the footprint: where a point
    // has no target over it, its line passes there (and meets nothing).
    let face = from
        .iter()
        .filter_map(|&(_, h)| h)
        .fold(f64::NEG_INFINITY, f64::max);
    let lift = |pts: Vec<([f64; 2], Option<f64>)>| -> Vec<[f64; 3]> {
        pts.into_iter()
            .map(|(p, h)| [p[0], p[1], h.unwrap_or(face)])
            .collect()
    };
    let (from, slack) = (lift(from), lift(slack));
    let z = [scan.stats.z_range[0] - 1.0, bounds[1][2] + 1.0];
    let usable = !from.is_empty()
        && !slack.is_empty()
        && face.is_finite()
        && z.iter().all(|v| v.is_finite());
    usable.then_some(Lines {
        from,
        slack,
        spacing,
        face,
        z,
        scan,
        top: &ex.top,
        holds: super::underside::holds_scan(ex).is_some(),
        faces: ex.base.as_ref().and_then(|b| b.faces.as_deref()),
        flanked: Cell::new(false),
    })
}

/// Whether the line along `d` from `start` (in the air over the part),
/// which comes under a height field of cells `cell` wide at `to` up a
/// flank (the walk's steps `step` mm apart), meets a real step of the
/// solid whose outward faces are `tree` there: the first face it crosses
/// lies where the height field rose (no farther on than the flank, nor
/// before the walk's last step, by a cell's diagonal and a half across
/// `d`: the height field's cliff stands where the cells' centres say, and
/// a rim cell takes the height of a face over part of it); the line enters
/// the solid through it (the face looks toward the line); and no face of
/// the part is over the line just before it, so that the height field,
/// which the fill is planned on, has the step where it is. Under a part
/// that overhangs itself the line meets no face at the cliff, or one with
/// the overhang over it: no step.
fn steps_onto(
    tree: &TriangleTree,
    [cell, step]: [f64; 2],
    [start, to]: [[f64; 3]; 2],
    d: [f64; 3],
) -> bool {
    let across = (1.0 - d[2] * d[2]).max(0.0).sqrt();
    if across < 1e-9 {
        return false;
    }
    let down = -Vector3::from(d);
    let to_len = (Vector3::from(to) - Vector3::from(start)).norm();
    let past = 1.5 * std::f64::consts::SQRT_2 * cell / across;
    let Some((t, normal)) = tree.first_hit(start, down.into(), to_len + past) else {
        return false;
    };
    let facing = Vector3::from(normal).dot(&down) < 0.0;
    if t < to_len - step - past || !facing {
        return false;
    }
    // A hundredth of a millimetre back along the line: in the air the
    // step stands in, open to the sky.
    let p = Vector3::from(start) + (t - 0.01).max(0.0) * down;
    tree.first_hit(p.into(), [0.0, 0.0, 1.0], f64::INFINITY)
        .is_none()
}

/// The points of `profile` (within `bounds`) every `spacing` at least
/// `edge` inside its edge, and along its edge `edge` inside, where the
/// outer beads' edges are: a line there along a direction that leans less
/// than the target's face leaves the target through it.
fn footprint(
    profile: &crate::geometry::profile::Profile,
    [lo, hi]: [[f64; 2]; 2],
    spacing: f64,
    edge: f64,
) -> Vec<[f64; 2]> {
    let count = |k: usize| ((hi[k] - lo[k]) / spacing).floor() as usize + 1;
    let mut from = Vec::new();
    for j in 0..count(1) {
        for i in 0..count(0) {
            let p = [
                lo[0] + (i as f64 + 0.5) * spacing,
                lo[1] + (j as f64 + 0.5) * spacing,
            ];
            if profile.contains(p) && profile.distance_to_boundary(p) >= edge {
                from.push(p);
            }
        }
    }
    for ring in profile.offset_inward(edge) {
        from.extend(subdivided(&ring.polyline(CHORD_ERROR), spacing));
    }
    from
}

/// The closed polyline `ring` with a point at least every `spacing` along
/// each of its sides (at most 10 000 a side).
fn subdivided(ring: &[[f64; 2]], spacing: f64) -> Vec<[f64; 2]> {
    let mut out = Vec::new();
    for (k, &a) in ring.iter().enumerate() {
        let b = ring[(k + 1) % ring.len()];
        let n = ((b[0] - a[0]).hypot(b[1] - a[1]) / spacing)
            .ceil()
            .clamp(1.0, 1e4) as usize;
        out.extend((0..n).map(|i| {
            let t = i as f64 / n as f64;
            [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
        }));
    }
    out
}

/// The most tilt from vertical (deg) the bead and the machines allow, and
/// what holds it there: the bead's measured `tilt` (none: vertical), each
/// CNC's tilt axis (a 3-axis one's nozzle stays vertical). A robot's arm
/// has no single tilt limit; its poses are checked by its rules.
fn limit(model: &Model, bead: &Bead) -> (f64, String) {
    let mut most = match bead.tilt {
        Some((t, _)) => (
            t[1].to_degrees(),
            format!("bead `{}`'s measured `tilt`", bead.name),
        ),
        None => (
            0.0,
            format!("bead `{}`, measured vertical (no `tilt`)", bead.name),
        ),
    };
    for (m, _) in &model.machines {
        if let Machine::Cnc(c) = m {
            let t = match c.effective_kinematics() {
                Kinematics::Xyz => 0.0,
                _ => c.limits.tilt[0].abs().max(c.limits.tilt[1].abs()),
            };
            if t < most.0 {
                most = (t, format!("machine `{}`'s tilt axis", m.name()));
            }
        }
    }
    (most.0.clamp(0.0, MAX_TILT), most.1)
}

/// The refusal when no direction within `limit` builds every line: where
/// the most tilted allowed direction toward the one that would fails.
fn untilted(
    lines: &Lines<'_>,
    ex: &TopExtrusion,
    at: Span,
    limit: (f64, &str),
    witness: usize,
) -> crate::diag::Diagnostic {
    let mut k = witness;
    // Only to say what would build it: the 24 azimuths alone, so that a
    // refusal costs no more than a plan.
    let needs = lines.least(limit.0, MAX_TILT, false, &mut k);
    let best = Direction {
        tilt: (limit.0 / TILT_STEP + 1e-9).floor() * TILT_STEP,
        azimuth: needs.map_or(0.0, |d| d.azimuth),
    };
    let points = lines.points(true);
    let (point, meets) = match lines.fails(best, witness, true, true) {
        Some((_, Meets::Again(q))) => (q, LineFault::Again),
        Some((_, Meets::Flank(q))) => (q, LineFault::Flank),
        Some((_, Meets::Gap(q))) => (q, LineFault::Gap),
        Some((k, _)) => (points[k], LineFault::Nothing),
        None => (points[witness % points.len()], LineFault::Again),
    };
    message::top::untilted(&Untilted {
        at: point,
        meets,
        limit,
        needs: needs.map(Direction::pair),
        direction: at,
        top: ex.top_span,
        faces: lines.solid_faces(),
        flanked: lines.flanked.get(),
    })
}

/// The fill planned along `d` in the part turned so that `d` is up, and
/// turned back. `level` is a plane square to `d` (its height along `d`,
/// as the turned frame's `z`), levelled as a vertical fill's level is;
/// `follow = surface` follows the turned scan's normal, its tilt from the
/// part's vertical held to the machines' (module `follow`).
fn plan(
    model: &Model,
    bead: &Bead,
    ex: &TopExtrusion,
    slicing: &VariableSlicing,
    lines: &Lines<'_>,
    d: Direction,
) -> Result<(Vec<Layer>, Diagnostics), Diagnostics> {
    let rot = up(d.vector());
    let turned = turn(ex, lines, rot)?;
    let (layers, warnings) = super::plan(model, bead, &turned, slicing).map_err(|e| {
        let mut out = Diagnostics::new();
        for x in e.into_vec() {
            out.push(message::top::in_turned_frame(x, d.pair()));
        }
        out
    })?;
    let back = rot.inverse();
    let layers = layers.into_iter().map(|l| turn_back(l, &back)).collect();
    Ok((layers, warnings))
}

/// The rotation that turns `d` (a unit vector) up.
fn up(d: [f64; 3]) -> Rotation3<f64> {
    Rotation3::rotation_between(&Vector3::from(d), &Vector3::z())
        .unwrap_or_else(Rotation3::identity)
}

/// `ex` seen along `d` (a unit vector, tilted less than 85°) as a fill
/// along it is planned with `bead`: turned so `d` is up, its scan, target
/// and footprint (the finished face seen along `d`) with it.
/// `None` when its top is no target on a scan or does not turn. What the
/// report integrates a tilted fill's design volume over.
pub(crate) fn seen_along(ex: &TopExtrusion, bead: &Bead, d: [f64; 3]) -> Option<TopExtrusion> {
    if d[2].is_nan() || d[2] < MAX_TILT.to_radians().cos() - 1e-9 {
        return None;
    }
    let lines = lines(ex, bead)?;
    turn(ex, &lines, up(d)).ok()
}

/// `ex` turned by `rot`: its scan turned and rastered again, its
/// target turned, its footprint the finished face turned (the profile,
/// each point at the target's highest point over it),
/// and the way back into the part for the points its messages name.
fn turn(
    ex: &TopExtrusion,
    lines: &Lines<'_>,
    rot: Rotation3<f64>,
) -> Result<TopExtrusion, Diagnostics> {
    let internal = |what: &str| message::top::internal(what);
    let scan = ex
        .base
        .as_ref()
        .ok_or_else(|| internal("a tilted fill without a scan"))?;
    let surface = scan
        .surface
        .turned(&rot, f64::INFINITY)
        .map_err(|_| internal("the scan turned to the build direction has no surface"))?;
    let (inner, name) = match &ex.top {
        Top::Mesh(m) => (Inner::Mesh(m.surface.clone()), m.path.clone()),
        Top::Solid(s) => (Inner::Solid(s.surface.clone()), s.name.clone()),
        _ => return Err(internal("a tilted fill of a top that is no target")),
    };
    let target = Arc::new(Target::Turned(
        Turned::new(inner, rot).ok_or_else(|| internal("the target has no finite extent"))?,
    ));
    let profile = outline::profile(&ex.shape, CHORD_ERROR);
    // Lifted as the lines are, every `spacing` along the outline: a face
    // that is not flat is followed between its corners too.
    let ring = subdivided(&profile.polyline(CHORD_ERROR), lines.spacing);
    let mut pts: Vec<[Length; 2]> = Vec::new();
    for (k, &p) in ring.iter().enumerate() {
        let [a, b] = [
            ring[(k + ring.len() - 1) % ring.len()],
            ring[(k + 1) % ring.len()],
        ];
        let h = edge_height(&ex.top, &profile, [a, p, b]).unwrap_or(lines.face);
        let q = rot * Vector3::new(p[0], p[1], h);
        let q = [Length(q.x), Length(q.y)];
        if pts.last() != Some(&q) {
            pts.push(q);
        }
    }
    if pts.len() > 1 && pts.first() == pts.last() {
        pts.pop();
    }
    let (start, rest) = pts
        .split_first()
        .ok_or_else(|| internal("an empty footprint"))?;
    let shape = Shape::Outline(Outline {
        start: *start,
        segments: rest.iter().map(|&to| Segment::Line { to }).collect(),
    });
    Ok(TopExtrusion {
        shape,
        top: Top::Solid(TopSolid {
            name,
            surface: target.clone(),
        }),
        base: Some(ScanBase {
            surface: Arc::new(surface),
            // In the part's frame: the lines' alone.
            faces: None,
            ..scan.clone()
        }),
        turned: Some(TurnedFrame {
            back: rot.inverse(),
            face: lines.face,
            target,
        }),
        ..ex.clone()
    })
}

/// The finished face's height at `p`, a point of the footprint's edge
/// between `a` and `b`: the target's highest point [`EDGE`] inside the
/// edge, where the outermost lines run (on the edge itself the target's
/// side may or may not be over it). `None` where no target is there.
fn edge_height(top: &Top, profile: &Profile, [a, p, b]: [[f64; 2]; 3]) -> Option<f64> {
    let normal = |u: [f64; 2], v: [f64; 2]| {
        let (dx, dy) = (v[0] - u[0], v[1] - u[1]);
        let l = dx.hypot(dy);
        if l > 0.0 {
            [-dy / l, dx / l]
        } else {
            [0.0, 0.0]
        }
    };
    let [n, m] = [normal(a, p), normal(p, b)];
    let bisector = [n[0] + m[0], n[1] + m[1]];
    let l2 = bisector[0] * bisector[0] + bisector[1] * bisector[1];
    // Either side of the edge: the one inside the profile. Along the sum of
    // the sides' unit normals (length l), k·l²/2 off each side.
    [1.0, -1.0]
        .into_iter()
        .map(|s| {
            let k = if l2 > 1e-12 { s * 2.0 * EDGE / l2 } else { 0.0 };
            [p[0] + k * bisector[0], p[1] + k * bisector[1]]
        })
        .find(|&q| profile.contains(q))
        .and_then(|q| top.mesh_at(q).flatten())
        .filter(|h| h.is_finite())
}

/// A layer planned in the turned frame, turned back into the part by
/// `back`.
fn turn_back(mut layer: Layer, back: &Rotation3<f64>) -> Layer {
    let turn = |v: [f64; 3]| {
        let t = back * Vector3::from(v);
        [t.x, t.y, t.z]
    };
    let turn32 = |v: [f32; 3]| {
        let t = turn(v.map(f64::from));
        t.map(|c| c as f32)
    };
    for p in layer.paths.iter_mut().flat_map(|p| &mut p.points) {
        p.pos = turn(p.pos);
        p.normal = turn32(p.normal);
        p.tangent = turn32(p.tangent);
    }
    let f = layer.frame;
    layer.frame = Frame {
        origin: turn(f.origin),
        x: turn(f.x),
        y: turn(f.y),
        z: turn(f.z),
    };
    layer
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::scan::nearest::block;

    /// A plate, and on it a post 20 mm wide and 30 mm high, with a cap
    /// 24 mm wide over its top 4 mm when `capped`.
    fn part(capped: bool) -> TriangleTree {
        let mut tris = block([-40.0, -20.0, -10.0], [40.0, 20.0, 0.0]);
        tris.extend(block([-10.0, -20.0, 0.0], [10.0, 20.0, 30.0]));
        if capped {
            tris.extend(block([-12.0, -20.0, 26.0], [12.0, 20.0, 30.0]));
        }
        TriangleTree::new(&tris)
    }

    #[test]
    fn a_side_in_the_open_is_a_step_and_one_under_a_cap_is_not() {
        // 30° toward -x: the line runs down toward +x, onto the post's -x
        // side 0.5 mm below where it crosses x = -12; a height field of
        // 0.5 mm cells draws the cliff there (the cap's edge) or at the side.
        let (s, c) = (0.5, 30f64.to_radians().cos());
        let d = [-s, 0.0, c];
        let start = [-16.0, 0.0, 25.0];
        let on = |x: f64| [x, 0.0, start[2] - (x - start[0]) * c / s];
        let cs = [0.5, 0.05];
        assert!(steps_onto(&part(false), cs, [start, on(-10.25)], d));
        // Under the cap the side is as near, but the cap is over it: from
        // the cap's edge (where a height field draws the cliff) or as near
        // the side.
        assert!(!steps_onto(&part(true), cs, [start, on(-11.75)], d));
        assert!(!steps_onto(&part(true), cs, [start, on(-10.25)], d));
        // A face farther on than the flank is no step: the side from 4 mm
        // off, on cells of 0.5 mm; nor one the line met well before it.
        assert!(!steps_onto(&part(false), cs, [start, on(-14.0)], d));
        assert!(!steps_onto(&part(false), cs, [start, on(-6.0)], d));
        // A face the line leaves the solid by is no step: the same side
        // turned inward (its normal away from the line).
        let inward: Vec<_> = block([-10.0, -20.0, 0.0], [10.0, 20.0, 30.0])
            .into_iter()
            .map(|[a, b, c]| [a, c, b])
            .collect();
        let inward = TriangleTree::new(&inward);
        assert!(!steps_onto(&inward, cs, [start, on(-10.25)], d));
        // A vertical line never comes up a flank.
        let up = [0.0, 0.0, 1.0];
        assert!(!steps_onto(&part(false), cs, [start, start], up));
    }
}
