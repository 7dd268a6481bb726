//! The fixtures fixed to the machine (`fixture { machine = NAME }`): they
//! do not turn with the part, so the head is checked against them in the
//! machine's own coordinates, its pose taken there through the part's
//! frame at the move's axes ([`PartFrame`]; docs/collision.md).
//!
//! As the part's check, a checked pose certifies every pose within its
//! distance less the gap; the head's path in the machine's coordinates is
//! not straight where a table or a positioner turns, so a move is followed
//! in pieces over which its axes turn at most [`PIECE_DEG`], each taken as
//! straight.

use super::{fixture_lumps, lerp, widen, Extent, CAP_MM, MIN_STEP_MM};
use crate::collision::head::{HeadShape, Pose};
use crate::collision::material::{Lump, Material};
use crate::ir::Program;
use crate::plan::kinematics::Rotary;
use crate::plan::part_frame::PartFrame;
use nalgebra::{Point3, Vector3};

/// The most a move's rotary axes turn over a piece followed as straight,
/// degrees.
const PIECE_DEG: f64 = 2.0;

/// What the head came near: how near, which body, the lump, its pose in
/// the machine's coordinates, how far along the move, the focus in the
/// part's.
pub(super) struct Found {
    pub d: f64,
    pub body: usize,
    pub lump: Lump,
    pub pose: Pose,
    pub way: f64,
    pub focus: [f64; 3],
}

/// The check against one machine's own fixtures: those on its base, or
/// those on its tilt axis's body (`tilts`).
pub(super) struct Fixed {
    frame: PartFrame,
    pub(super) tilts: bool,
    material: Material,
    /// The last checked pose (the machine's coordinates) and how far it is
    /// from every fixture, mm (at most [`CAP_MM`]).
    cert: Option<(Pose, f64)>,
    /// The last move's end: the head in the part's coordinates, the axes.
    last: Option<(Pose, Rotary)>,
    /// As [`super::Collision`]'s `extent`, in the machine's coordinates:
    /// the box round every focus checked, seen from above, and the least
    /// `|up_z|` (where to move a fixture, [`super::Collision::moved`]).
    pub(super) extent: Extent,
}

impl Fixed {
    /// The check of machine `name` (whose part's frame is `frame`) against
    /// the fixtures of `program` fixed to it, on its tilt axis's body or
    /// not (`tilts`); with `only`, that one alone. `None` where it has
    /// none.
    pub(super) fn new(
        program: &Program,
        name: &str,
        (frame, tilts): (Option<PartFrame>, bool),
        only: Option<usize>,
    ) -> Option<Fixed> {
        let mut material = Material::default();
        for (i, f) in program.fixtures.iter().enumerate() {
            if f.fixed_to(name) == Some(true) && f.tilts == tilts && only.is_none_or(|o| o == i) {
                fixture_lumps(f, i, &mut material);
            }
        }
        if material.is_empty() {
            return None;
        }
        Some(Fixed {
            frame: frame?,
            tilts,
            material,
            cert: None,
            last: None,
            extent: ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2], 1.0),
        })
    }

    /// The head at `p` (the part's coordinates) with the axes at `axes`,
    /// in the machine's coordinates.
    fn in_machine(&self, p: &Pose, axes: Rotary) -> Pose {
        let iso = self.frame.at(axes, self.tilts);
        let f = iso * Point3::from(p.focus);
        let u = iso.rotation * Vector3::from(p.up);
        Pose {
            focus: [f.x, f.y, f.z],
            up: [u.x, u.y, u.z],
        }
    }

    /// Follows the head from the last move's end to `to` (the part's
    /// coordinates), the axes going to `axes`; a PTP (`ptp`) is checked at
    /// its end. What comes within [`CAP_MM`] is pushed on `found`.
    pub(super) fn follow(
        &mut self,
        head: &HeadShape,
        (to, axes): (Pose, Rotary),
        ptp: bool,
        found: &mut Vec<Found>,
    ) {
        let from = self.last.replace((to, axes));
        let Some((a, ea)) = from.filter(|_| !ptp) else {
            self.check(head, (&to, axes), 1.0, found);
            return;
        };
        let turn = (axes.tilt - ea.tilt).abs().max((axes.c - ea.c).abs());
        let pieces = (turn / PIECE_DEG).ceil().clamp(1.0, 1e5) as usize;
        for k in 0..pieces {
            let t = [k, k + 1].map(|i| i as f64 / pieces as f64);
            self.piece(head, [(a, ea), (to, axes)], t, found);
        }
    }

    /// The part's pose and the axes at `t` along a move.
    fn along(ends: &[(Pose, Rotary); 2], t: f64) -> (Pose, Rotary) {
        let [(a, ea), (b, eb)] = ends;
        let axes = Rotary {
            tilt: ea.tilt + t * (eb.tilt - ea.tilt),
            c: ea.c + t * (eb.c - ea.c),
        };
        (lerp(a, b, t), axes)
    }

    /// Follows the piece `[t0, t1]` of a move as straight in the machine's
    /// coordinates, checking wherever the head has moved as far as the
    /// last check certified (at least every [`MIN_STEP_MM`]).
    fn piece(
        &mut self,
        head: &HeadShape,
        ends: [(Pose, Rotary); 2],
        [t0, t1]: [f64; 2],
        found: &mut Vec<Found>,
    ) {
        let (b, eb) = Self::along(&ends, t1);
        let end = self.in_machine(&b, eb);
        widen(&mut self.extent, &end);
        let (a, ea) = Self::along(&ends, t0);
        let rate = self.in_machine(&a, ea).moved(&end, head.reach) / (t1 - t0);
        let mut t = t0;
        loop {
            let margin = match self.cert {
                Some((p, d)) => {
                    let (h, eh) = Self::along(&ends, t);
                    let here = p.moved(&self.in_machine(&h, eh), head.reach);
                    if p.moved(&end, head.reach).max(here) <= d - head.gap {
                        return;
                    }
                    (d - head.gap - here).max(MIN_STEP_MM)
                }
                None => 0.0,
            };
            t = if rate > 0.0 {
                (t + margin / rate).min(t1)
            } else {
                t1
            };
            let (p, e) = Self::along(&ends, t);
            self.check(head, (&p, e), t, found);
            if t >= t1 {
                return;
            }
        }
    }

    /// Checks the head at `p` (the part's coordinates) with the axes at
    /// `axes`, `way` along its move, and certifies the pose.
    fn check(
        &mut self,
        head: &HeadShape,
        (p, axes): (&Pose, Rotary),
        way: f64,
        out: &mut Vec<Found>,
    ) {
        let pose = self.in_machine(p, axes);
        widen(&mut self.extent, &pose);
        let d = match self.material.nearest(head, &pose, CAP_MM) {
            Some((d, body, lump)) => {
                out.push(Found {
                    d,
                    body,
                    lump,
                    pose,
                    way,
                    focus: p.focus,
                });
                d
            }
            None => CAP_MM,
        };
        self.cert = Some((pose, d));
    }
}
