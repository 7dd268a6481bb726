//! `lmd::collision` for a robot's arm: its links, capsules sized from its
//! catalogue entry ([`crate::target::arm::Model::links`]) and hung on the
//! axis angles [`super::ArmRule`] solves at every pose, keep the head's gap
//! from the positioner's faceplate and the fixtures
//! ([`crate::collision::arm`]). Each pose is checked against a few solids,
//! each culled by the spheres round it and the link first; the closest
//! approach of every link to every solid is kept for the report.

use crate::collision::arm::{capsules, Solid, LINKS};
use crate::collision::capsule::Capsule;
use crate::diag::message::collision::{self as says, Against};
use crate::diag::Diagnostics;
use crate::diag::Worst;
use crate::ir::MachineField;
use crate::ir::{Robot, FACEPLATE_THICKNESS_MM};
use crate::plan::arm::{frame, Along, Joints, Solver};
use crate::plan::kinematics::Rotary;
use crate::plan::positioner::Kin;
use crate::plan::Move;
use crate::verify::approach::Approach;
use crate::verify::rule::MachineCx;
use nalgebra::{Isometry3, Point3};

/// Where a link came close: the pose, and the link (in [`LINKS`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct LinkAt {
    pub along: Along,
    pub link: usize,
}

impl std::fmt::Display for LinkAt {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.along)
    }
}

/// The closest a link came to a solid: the distance, where, and the
/// focus there (the part's coordinates).
type Closest = (f64, Along, [f64; 3]);

/// The arm's links against the cell, along one robot's plan.
pub(crate) struct Links {
    radii: [f64; 3],
    gap: f64,
    /// The positioner, and the part's base on its flange inverted (the
    /// faceplate's frame is the part's times it).
    kin: Option<(Kin, Isometry3<f64>)>,
    /// Without a positioner, the part's base in the robot's frame, inverted.
    part_inv: Isometry3<f64>,
    /// The faceplate's diameter, mm.
    faceplate: Option<f64>,
    /// The solids: the faceplate first where there is one, then the
    /// fixtures (in the part's coordinates).
    solids: Vec<Solid>,
    /// The positioner's angles last seen, and the part's and the
    /// faceplate's frames there, inverted.
    at: Option<(Rotary, Isometry3<f64>, Isometry3<f64>)>,
    worst: Vec<Option<Worst<LinkAt>>>,
    /// By solid, by link.
    closest: Vec<[Option<Closest>; 3]>,
    /// The largest faceplate that keeps the gap at every pose found too
    /// close (`None` once a pose is not helped by any).
    keeps: Option<f64>,
}

impl Links {
    /// The check of `robot`'s arm against the positioner's faceplate and
    /// `cx`'s fixtures: `None` where the arm is not from the catalogue,
    /// its base has no value, or there is nothing to check.
    pub(crate) fn new(cx: &MachineCx<'_>, robot: &Robot) -> Option<Links> {
        let arm = robot.arm.as_ref()?;
        let radii = match arm.links {
            Some(r) => r,
            None => crate::target::arm::model(arm.model.as_deref()?)?.links,
        };
        let base = frame(robot.base.value.as_ref()?);
        let faceplate = robot.positioner.as_ref().and_then(|p| p.faceplate);
        let mut solids: Vec<Solid> = faceplate
            .map(|d| Solid::faceplate(d, FACEPLATE_THICKNESS_MM))
            .into_iter()
            .collect();
        solids.extend(cx.program.fixtures.iter().map(Solid::of));
        if solids.is_empty() {
            return None;
        }
        Some(Links {
            radii,
            gap: robot.common.head.gap,
            kin: Kin::of(robot).map(|k| (k, base.inverse())),
            part_inv: base.inverse(),
            faceplate,
            worst: vec![None; solids.len()],
            closest: vec![[None; 3]; solids.len()],
            solids,
            at: None,
            keeps: faceplate,
        })
    }

    /// The part's and the faceplate's frames, inverted, with the
    /// positioner at `axes`.
    fn frames(&mut self, axes: Rotary) -> (Isometry3<f64>, Isometry3<f64>) {
        let Some((kin, base_inv)) = &self.kin else {
            return (self.part_inv, Isometry3::identity());
        };
        match self.at {
            Some((a, p, f)) if a == axes => (p, f),
            _ => {
                let part = kin.part([axes.tilt, axes.c]);
                let face = part * base_inv;
                let (p, f) = (part.inverse(), face.inverse());
                self.at = Some((axes, p, f));
                (p, f)
            }
        }
    }

    /// The arm at axis angles `j`, the positioner at `axes`, at `along`.
    pub(crate) fn check(&mut self, solver: &Solver, j: &Joints, m: &Move, along: Along) {
        let axes = m.axes;
        let caps = capsules(&solver.joint_points(j), self.radii);
        let (part_inv, face_inv) = self.frames(axes);
        let plate = usize::from(self.faceplate.is_some());
        for k in 0..self.solids.len() {
            let inv = if k < plate { face_inv } else { part_inv };
            for (link, cap) in &caps {
                let beyond = self.closest[k][*link].map_or(f64::INFINITY, |c| c.0);
                let Some(d) = self.solids[k].capsule(&inv, cap, beyond.max(self.gap)) else {
                    continue;
                };
                if d < beyond {
                    self.closest[k][*link] = Some((d, along, m.to));
                }
                if d < self.gap {
                    let at = LinkAt { along, link: *link };
                    Worst::hit(&mut self.worst[k], d, self.gap, at);
                    if k < plate {
                        self.keep_from(cap, &inv);
                    }
                }
            }
        }
    }

    /// Narrows the faceplate that keeps the gap to the one that keeps it
    /// from `cap` too (`inv`: the faceplate's frame, inverted).
    fn keep_from(&mut self, cap: &Capsule, inv: &Isometry3<f64>) {
        let Some(d) = self.keeps else {
            return;
        };
        let local = |p: [f64; 3]| {
            let q = inv * Point3::from(p);
            [q.x, q.y, q.z]
        };
        let c = Capsule {
            a: local(cap.a),
            b: local(cap.b),
            r: cap.r,
        };
        // Just short of the gap's edge, floored to what is printed.
        let need = Solid::faceplate_keeping(&c, FACEPLATE_THICKNESS_MM, d, self.gap + 0.005);
        self.keeps = need.map(|n| (n * 10.0).floor() / 10.0);
    }

    /// The closest approach of each link to each solid, where a pose came
    /// near enough to measure.
    pub(crate) fn approaches(&self, cx: &MachineCx<'_>) -> Vec<Approach> {
        let plate = usize::from(self.faceplate.is_some());
        let mut out = Vec::new();
        for (k, links) in self.closest.iter().enumerate() {
            let with = if k < plate {
                "positioner faceplate".to_string()
            } else {
                format!("fixture {}", cx.program.fixtures[k - plate].name)
            };
            for (link, c) in links.iter().enumerate() {
                if let Some((d, at, focus)) = *c {
                    out.push(Approach::new(
                        (LINKS[link], &with),
                        (d, self.gap),
                        at.at,
                        at.way,
                        focus,
                    ));
                }
            }
        }
        out
    }

    /// The reports: one for each solid a link came too close to.
    pub(crate) fn report(&self, cx: &MachineCx<'_>, out: &mut Diagnostics) {
        let plate = usize::from(self.faceplate.is_some());
        for (k, w) in self.worst.iter().enumerate() {
            let Some(w) = w else {
                continue;
            };
            let (with, placed) = if k < plate {
                (
                    Against::Faceplate(self.keeps),
                    cx.origin.written(MachineField::Faceplate),
                )
            } else {
                let i = k - plate;
                (
                    Against::Fixture(&cx.program.fixtures[i].name),
                    cx.program.origins.fixtures.get(i).copied(),
                )
            };
            out.push(says::link_collision(&says::LinkHit {
                machine: cx.machine.name(),
                link: LINKS[w.at.link],
                with,
                worst: w,
                arm: cx.origin.at(MachineField::Arm),
                placed,
            }));
        }
    }
}
