//! Continuous gradual ("normal") slicing of a loft: layer `i` is deposited on
//! the section plane at station `i/n`; a point at distance ρ from the bend axis
//! gets the local height ρ·Δδ (seed 000), and the move from it to the next
//! point the speed at which the wall, one bead wide, rises by the mean of
//! their heights: `A(v)/w` ([`crate::deposit`]).

use super::section_points::{self, Sample, Spacing};
use super::spiral;
use crate::geometry::{LoftGeometry, SectionFrame};
use crate::ir::{Frame, Layer, Path, PathKind, Point};
use crate::sema::model::{Bead, Model, SeamRule};
use crate::units::{Length, Speed};
use nalgebra::Vector3;

/// Everything per-point generation needs, fixed per plan.
pub struct Setup {
    /// Where each layer starts (rad from the section's x axis, layer by
    /// layer).
    pub seam: SeamRule,
    /// Each layer's seam angle (rad from the section's x axis), worked out
    /// from `seam` before slicing ([`seam_angles`]).
    pub starts: Vec<f64>,
    /// Number of layers.
    pub layers: usize,
    /// Δδ (rad) for an arc spine; the layer height (mm) for a line.
    pub step: f64,
    /// How the points are spaced round each layer.
    pub spacing: Spacing,
    /// The most points a layer may have.
    pub max_points: usize,
    /// `nozzle = wall`: each point's build direction follows the wall's
    /// lean (`false`: the spine's tangent).
    pub follow: bool,
    /// `rise_tolerance`: how far (a share of their mean) a move's ends'
    /// heights may differ, where the first layer's climb is cut.
    pub rise: f64,
    /// `layer_change = spiral`: how much of the end of each layer's loop
    /// climbs to the next layer (mm; infinite: all of it); `None`: none,
    /// the nozzle lifts between layers.
    pub climb: Option<f64>,
}

impl Setup {
    /// Layer `i`'s seam, rad from the section's x axis.
    pub fn seam_at(&self, i: usize) -> f64 {
        self.starts
            .get(i)
            .copied()
            .unwrap_or(std::f64::consts::FRAC_PI_2)
    }

    /// The seam is one angle on every layer (what the seam advice is for).
    pub fn fixed_seam(&self) -> bool {
        matches!(self.seam, SeamRule::Toward(_))
    }

    /// The equal angles the seam advice scans: the grid of `points = k`, or
    /// whole degrees.
    pub fn scan_grid(&self) -> usize {
        match self.spacing {
            Spacing::Count(k) => k,
            Spacing::Chord { .. } => 360,
        }
    }
}

/// The seam angle (rad from the section's x axis) of each of `layers`
/// layers: the rule's direction; or, for `staggered(shift)`, `shift` of arc
/// length along the layer's own loop (the way the nozzle runs) past the
/// angle the layer below started at, wrapping round — layer 0 at the
/// default 90°. So each layer's start and stop lie a fixed distance on from
/// the one below, as on a planar wall, on a section that changes too.
pub fn seam_angles(geo: &LoftGeometry, rule: SeamRule, layers: usize) -> Vec<f64> {
    let default = std::f64::consts::FRAC_PI_2;
    let SeamRule::Staggered { shift } = rule else {
        return (0..layers)
            .map(|i| rule.direction(i).unwrap_or(default))
            .collect();
    };
    let mut out = Vec::with_capacity(layers);
    let mut at = default;
    for i in 0..layers {
        if i > 0 {
            at = walk(geo, i as f64 / layers as f64, at, shift.0);
        }
        out.push(at);
    }
    out
}

/// How closely [`walk`] follows the section: its chords stray at most this
/// far (mm) from the outline, so its arc length is the outline's to a few
/// parts in a million.
const WALK_CHORD: f64 = 1e-3;

/// The angle `d` mm of arc length along the section at station `s` past
/// angle `from`, going round the way the points run (and wrapping).
fn walk(geo: &LoftGeometry, s: f64, from: f64, d: f64) -> f64 {
    use std::f64::consts::TAU;
    let f = geo.frame(s);
    let fine = Spacing::Chord {
        error: WALK_CHORD,
        rise: f64::MAX,
    };
    let samples = section_points::angles(geo, &f, s, from, fine, MAX_WALK)
        .or_else(|_| section_points::angles(geo, &f, s, from, Spacing::Count(4096), MAX_WALK))
        .unwrap_or_default();
    let mut thetas: Vec<f64> = samples.iter().map(|p| p.theta).collect();
    thetas.push(from + TAU);
    let pts: Vec<_> = thetas.iter().map(|&th| geo.point(&f, s, th).0).collect();
    let lengths: Vec<f64> = pts.windows(2).map(|w| (w[1] - w[0]).norm()).collect();
    let total: f64 = lengths.iter().sum();
    if !(total > 0.0 && d.is_finite()) {
        return from;
    }
    let mut left = d.rem_euclid(total);
    for (j, &l) in lengths.iter().enumerate() {
        if left <= l {
            // The point that far along the chord, by its own angle in the
            // section frame: a straight side is one chord, however long.
            let t = if l > 0.0 { left / l } else { 0.0 };
            let q = pts[j] + (pts[j + 1] - pts[j]) * t - f.spine.origin;
            return q.dot(&f.y).atan2(q.dot(&f.x)).rem_euclid(TAU);
        }
        left -= l;
    }
    from
}

/// The most points [`walk`] follows a section by.
const MAX_WALK: usize = 200_000;

/// A seam this close (relative to the layer's span across the bend) to the
/// innermost or outermost point sits where the layer height is extreme.
pub const SEAM_EXTREME: f64 = 0.02;

/// Where each of a layer's sample angles (the seam + j·Δθ) falls across the
/// bend, over every layer: on how many layers it is at the innermost or
/// outermost point, and how far from the middle it strays at worst. The
/// angle that fares best is the seam to advise.
pub struct SeamScan {
    extreme: Vec<usize>,
    worst: Vec<f64>,
}

impl SeamScan {
    /// A scan of `k` sample angles.
    pub fn new(k: usize) -> Self {
        SeamScan {
            extreme: vec![0; k],
            worst: vec![0.0; k],
        }
    }

    /// Sample `j` sits at `x` across the bend on one layer (0 = innermost,
    /// 1 = outermost).
    fn add(&mut self, j: usize, x: f64) {
        if let (Some(e), Some(w)) = (self.extreme.get_mut(j), self.worst.get_mut(j)) {
            if !(SEAM_EXTREME..=1.0 - SEAM_EXTREME).contains(&x) {
                *e += 1;
            }
            *w = w.max((x - 0.5).abs());
        }
    }

    /// The sample whose seam would sit at an extreme on the fewest layers
    /// (then the one that strays least from the middle), and that count.
    pub fn best(&self) -> Option<(usize, usize)> {
        (0..self.extreme.len())
            .min_by(|&a, &b| {
                self.extreme[a]
                    .cmp(&self.extreme[b])
                    .then(self.worst[a].total_cmp(&self.worst[b]))
            })
            .map(|j| (j, self.extreme[j]))
    }
}

/// The build direction at each point of layer `i` when the nozzle follows
/// the wall: from the point to the same section angle on the next layer
/// (the last layer: from the one below), less its part along the path, so
/// it lies in the plane of the wall's normal and the spine. Each point's
/// height becomes that step's length: what the bead stacks along the
/// tilted nozzle (a cone's `Δz / cos α`).
fn follow_wall(
    geo: &LoftGeometry,
    plan: &Setup,
    i: usize,
    samples: &[Sample],
    pos: &[nalgebra::Point3<f64>],
    tangents: &[Vector3<f64>],
    heights: &mut [f64],
) -> Vec<[f32; 3]> {
    let n = plan.layers as f64;
    let (other, sign) = if i + 1 < plan.layers {
        ((i + 1) as f64 / n, 1.0)
    } else {
        ((i as f64 - 1.0).max(0.0) / n, -1.0)
    };
    let f = geo.frame(other);
    let along = geo.frame(i as f64 / n).z();
    samples
        .iter()
        .zip(pos)
        .zip(tangents)
        .zip(heights.iter_mut())
        .map(|(((sample, p), t), h)| {
            let (q, _) = geo.point(&f, other, sample.theta);
            let mut d: Vector3<f64> = (q - p) * sign;
            d -= t * d.dot(t);
            let len = d.norm();
            if len > 1e-12 && d.dot(&along) > 0.0 {
                *h = len;
                let u = d / len;
                [u.x as f32, u.y as f32, u.z as f32]
            } else {
                [along.x as f32, along.y as f32, along.z as f32]
            }
        })
        .collect()
}

/// Generates layer `i`. Returns the layer and how its seam sits: the seam's
/// offset toward the bend centre relative to the layer's extremes (0 = innermost
/// … 1 = outermost), for arc spines; `scan` learns where every angle of the
/// seam advice's grid sits. `Err(n)`: the layer needs `n` points, more than
/// the setup allows.
pub fn layer(
    model: &Model,
    bead: &Bead,
    geo: &LoftGeometry,
    plan: &Setup,
    i: usize,
    scan: &mut SeamScan,
) -> Result<(Layer, Option<f64>), usize> {
    let s = i as f64 / plan.layers as f64;
    let f = geo.frame(s);
    let n = f.z();
    let normal = [n.x as f32, n.y as f32, n.z as f32];
    let seam = plan.seam_at(i);
    let samples = section_points::angles(geo, &f, s, seam, plan.spacing, plan.max_points)?;
    let k = samples.len();

    let mut pos = Vec::with_capacity(k);
    let mut heights = Vec::with_capacity(k);
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for &Sample { theta, .. } in &samples {
        let (p, uv) = geo.point(&f, s, theta);
        let h = match geo.bend_distance(&f, uv) {
            Some(rho) => {
                lo = lo.min(rho);
                hi = hi.max(rho);
                rho * plan.step
            }
            None => plan.step,
        };
        pos.push(p);
        heights.push(h);
    }
    let across = |h: f64| (h / plan.step - lo) / (hi - lo);
    if hi > lo && plan.fixed_seam() {
        scan_seams(geo, &f, s, plan, &samples, &heights, &across, scan);
    }
    let seam_at = (hi > lo).then(|| across(heights[0]));

    // Central differences, kept exactly in the layer plane.
    let tangents: Vec<Vector3<f64>> = (0..k)
        .map(|jj| {
            let mut t: Vector3<f64> = pos[(jj + 1) % k] - pos[(jj + k - 1) % k];
            t -= n * t.dot(&n);
            t.try_normalize(1e-12).unwrap_or(f.y)
        })
        .collect();
    let mut normals = match plan.follow {
        true => follow_wall(geo, plan, i, &samples, &pos, &tangents, &mut heights),
        false => vec![normal; k],
    };
    // The loop closed: its last point is its first again (the next layer's
    // first, where it climbs).
    pos.push(pos[0]);
    heights.push(heights[0]);
    normals.push(normals[0]);
    let mut c = Closed {
        pos,
        heights,
        normals,
        tangents,
    };
    if let Some(length) = plan.climb {
        let up = Climb {
            geo,
            plan,
            i,
            length,
        };
        let mut samples = samples;
        up.cut(&mut samples, &mut c);
        up.apply(&samples, &mut c.pos, &mut c.heights, &mut c.normals);
    }
    let points = wall_points(model, bead, i, &c);
    let o = f.spine.origin;
    let layer = Layer {
        index: i,
        station: s,
        frame: Frame {
            origin: [o.x, o.y, o.z],
            x: [f.x.x, f.x.y, f.x.z],
            y: [f.y.x, f.y.y, f.y.z],
            z: [n.x, n.y, n.z],
        },
        paths: vec![Path {
            kind: PathKind::Wall,
            points,
        }],
        label: String::new(),
        on_plate: false,
    };
    Ok((layer, seam_at))
}

/// A layer's loop, closed: `k + 1` points (the last the first again, or
/// where the loop climbs to), each one's layer height and build direction,
/// and the `k` points' tangents.
struct Closed {
    pos: Vec<nalgebra::Point3<f64>>,
    heights: Vec<f64>,
    normals: Vec<[f32; 3]>,
    tangents: Vec<Vector3<f64>>,
}

/// The IR points of layer `i`'s loop `c`.
fn wall_points(model: &Model, bead: &Bead, i: usize, c: &Closed) -> Vec<Point> {
    let power = model.process.power.at(i).watts() as f32;
    let powder = model.process.powder.g_min() as f32;
    let defocus = model.process.defocus.0 as f32;
    let deposit = bead.deposit();
    let k = c.tangents.len();
    let mut points = Vec::with_capacity(k + 1);
    for j in 0..=k {
        let t = c.tangents[j % k];
        let h = c.heights[j];
        // A wall one bead wide: each point's deposit fills the bead's width.
        // The move to the next point lays the mean of its ends' heights (the
        // layer's height varies linearly along it): its speed lays that.
        // (The closing point has no move: it keeps the speed of the move
        // from the first point, as the next loop round would have it.)
        let next = if j < k { j + 1 } else { 1 % k };
        let along = 0.5 * (h + c.heights[next]);
        // The bead's speed is the deposit point's over its ground; the
        // program moves the focus, which a tilted, defocused nozzle carries
        // on another curve: its speed is scaled by the two moves' lengths.
        let from = if j < k { j } else { 0 };
        let v =
            deposit.speed_for(Length(along), bead.width).0 * focus_over_ground(c, from, defocus);
        let p = c.pos[j];
        points.push(Point {
            pos: [p.x, p.y, p.z],
            normal: c.normals[j],
            tangent: [t.x as f32, t.y as f32, t.z as f32],
            layer_height: h as f32,
            speed: clamp_speed(Speed(v)) as f32,
            power,
            powder,
            defocus,
            laser_on: j < k,
            style: 0,
            pitch: bead.width.0 as f32,
            rise: 0.0,
        });
    }
    points
}

/// How much longer the focus's move from point `j` of `c` to the next is
/// than the ground the deposit point covers (across point `j`'s normal):
/// the path speed over the deposit's speed ([`crate::ir::Point::speed_across`]).
/// 1 where the nozzle is not defocused, or the move covers no ground.
fn focus_over_ground(c: &Closed, j: usize, defocus: f32) -> f64 {
    let (Some(p), Some(q)) = (c.pos.get(j), c.pos.get(j + 1)) else {
        return 1.0;
    };
    let n = |i: usize| Vector3::from(c.normals[i].map(f64::from));
    let (n0, n1) = (n(j), n(j + 1));
    let d = q - p;
    let ground = (d - n0 * d.dot(&n0)).norm();
    let focus = (d + (n1 - n0) * f64::from(defocus)).norm();
    if ground > 1e-12 && focus.is_finite() {
        focus / ground
    } else {
        1.0
    }
}

/// A spiral layer change on layer `i`: the end of its loop climbs to the
/// next layer.
struct Climb<'g> {
    geo: &'g LoftGeometry,
    plan: &'g Setup,
    i: usize,
    /// How much of the loop's end climbs (mm; at most the whole loop).
    length: f64,
}

impl Climb<'_> {
    /// Puts a point where the loop's climb starts, when that falls inside
    /// a move, and on the first layer wherever its climb must be cut so
    /// that each move's ends lay within the rise tolerance of their mean
    /// ([`spiral::climb_start`], [`spiral::first_climb_cuts`], as on a
    /// planar wall): each on the section at its angle between its
    /// neighbours'.
    fn cut(&self, samples: &mut Vec<Sample>, c: &mut Closed) {
        let start: Vec<_> = spiral::climb_start(&c.pos, self.length)
            .into_iter()
            .collect();
        self.insert(samples, c, &start);
        if self.i == 0 {
            let t = spiral::shares(&c.pos, self.length);
            let cuts = spiral::first_climb_cuts(&t, self.plan.rise);
            self.insert(samples, c, &cuts);
        }
    }

    /// Inserts a point a share `u` of the angle along move `j` for every
    /// `(j, u)` of `cuts` (in order).
    fn insert(&self, samples: &mut Vec<Sample>, c: &mut Closed, cuts: &[(usize, f64)]) {
        let s = self.i as f64 / self.plan.layers as f64;
        let f = self.geo.frame(s);
        let k = samples.len();
        // Computed from the loop as it is, then put in from the back.
        let new: Vec<_> = cuts
            .iter()
            .filter(|&&(j, _)| j < k)
            .map(|&(j, u)| {
                let a = samples[j].theta;
                let b = samples
                    .get(j + 1)
                    .map_or(samples[0].theta + std::f64::consts::TAU, |n| n.theta);
                let theta = a + u * (b - a);
                let h = c.heights[j] + u * (c.heights[j + 1] - c.heights[j]);
                (j, theta, self.geo.point(&f, s, theta).0, h)
            })
            .collect();
        for &(j, theta, p, h) in new.iter().rev() {
            samples.insert(j + 1, Sample { theta, grid: None });
            c.pos.insert(j + 1, p);
            c.heights.insert(j + 1, h);
            c.normals.insert(j + 1, c.normals[j]);
            c.tangents.insert(j + 1, c.tangents[j]);
        }
    }

    /// Moves the points of the loop's last `length` (`pos`, `heights` and
    /// `normals` hold the closed loop: `k + 1` points, the last the first
    /// again) up toward the next layer: a point a share `t` of the way
    /// along the climb lies at station `(i + t)/n`, at its own angle in
    /// the section there, so it stands one layer height over the point of
    /// the climb below and lays the same height as on a flat layer; the
    /// last point is the next layer's first. The first layer's climb rises
    /// off the plate, so under it the bead fills down to the plate: it lays
    /// `(1 + t)` layer heights, at the speed that lays that. With the
    /// nozzle along the spine, each point's build direction turns with the
    /// section it lies in.
    fn apply(
        &self,
        samples: &[Sample],
        pos: &mut [nalgebra::Point3<f64>],
        heights: &mut [f64],
        normals: &mut [[f32; 3]],
    ) {
        let k = samples.len();
        let shares = spiral::shares(pos, self.length);
        let n = self.plan.layers as f64;
        for (j, &t) in shares.iter().enumerate() {
            if t <= 0.0 {
                continue;
            }
            let s = (self.i as f64 + t) / n;
            let f = self.geo.frame(s);
            let theta = samples[j % k].theta;
            pos[j] = self.geo.point(&f, s, theta).0;
            heights[j] *= spiral::laid(self.i, t);
            if !self.plan.follow {
                let z = f.z();
                normals[j] = [z.x as f32, z.y as f32, z.z as f32];
            }
        }
    }
}

/// Tells `scan` where each angle of the advice's grid sits across the bend
/// on this layer: from the layer's own points where they are the grid's
/// (`points = k`), else from the outline at each whole degree.
#[allow(clippy::too_many_arguments)]
fn scan_seams(
    geo: &LoftGeometry,
    f: &SectionFrame,
    s: f64,
    plan: &Setup,
    samples: &[Sample],
    heights: &[f64],
    across: &impl Fn(f64) -> f64,
    scan: &mut SeamScan,
) {
    if let Spacing::Count(_) = plan.spacing {
        for (p, &h) in samples.iter().zip(heights) {
            if let Some(j) = p.grid {
                scan.add(j, across(h));
            }
        }
        return;
    }
    let grid = plan.scan_grid();
    for j in 0..grid {
        let th = plan.seam_at(0) + j as f64 * std::f64::consts::TAU / grid as f64;
        let (_, uv) = geo.point(f, s, th);
        if let Some(rho) = geo.bend_distance(f, uv) {
            scan.add(j, across(rho * plan.step));
        }
    }
}

/// A speed the IR can hold: non-finite results (which the checks would refuse
/// anyway) become 0 so the checks report them as out of range, not as NaN.
fn clamp_speed(v: Speed) -> f64 {
    if v.0.is_finite() {
        v.0
    } else {
        0.0
    }
}
