//! `lmd::collision` for a robot's arm: its links, capsules sized from its
//! catalogue entry ([`crate::target::arm::Model::links`], `column`) and
//! hung on the axis angles [`super::ArmRule`] solves at every pose, keep
//! the head's gap from the positioner's faceplate and the fixtures
//! ([`crate::collision::arm`]); without a positioner the tool keeps it
//! from the plate; the wrist, the tool and the head keep it
//! from the upper arm and the column (an arm folded back onto itself:
//! adjacent links always touch at their joint, so are not checked). On
//! the PTPs from and back to home ([`super::ptp`]) the head is checked too,
//! against the plate, the fixtures and, on the way back, the finished
//! part. Each pose is checked against a few solids, each culled by the
//! spheres round it and the link first; the closest approach of every link
//! to every solid is kept for the report.

use crate::collision::arm::{
    body_capsule, capsule_capsule, capsules, column, Solid, COLUMN, LINKS, TOOL, UPPER_ARM, WRIST,
};
use crate::collision::capsule::{segment_point, Capsule};
use crate::collision::head::{add, dist, scale, HeadShape, Pose};
use crate::collision::material::{Lump, Material};
use crate::diag::message::collision::{self as says, Against, LinkFix};
use crate::diag::message::words::Words;
use crate::diag::Diagnostics;
use crate::diag::Worst;
use crate::ir::MachineField;
use crate::ir::{Program, Robot, ToolAxis, FACEPLATE_THICKNESS_MM};
use crate::plan::arm::{frame, Along, Joints, Solver};
use crate::plan::kinematics::Rotary;
use crate::plan::positioner::Kin;
use crate::plan::Where;
use crate::verify::approach::Approach;
use crate::verify::rule::MachineCx;
use nalgebra::{Isometry3, Point3, Vector3};

/// How far a check of the head on a PTP looks for a fixture or the part,
/// mm: beyond it the head is clear by at least this (as the head's own
/// check, `verify::collision`).
const CAP_MM: f64 = 8.0;
/// The part's beads are laid as lumps this far apart along their path
/// for the PTP back home, mm (as the head's own check lays them).
const BEAD_STEP_MM: f64 = 1.5;

/// Where a pose lies: on a move of the plan, or on a PTP from or back to
/// home.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Place {
    /// A move's end, or a pose along the LIN to it.
    Move(Along),
    /// `way` along the PTP from home to the move to `at`, or (`back`) the
    /// PTP back home after it.
    Ptp { back: bool, way: f64, at: Where },
}

impl Place {
    /// The move and how far along it, as the report lists approaches.
    fn at_way(&self) -> (Where, f64) {
        match *self {
            Place::Move(a) => (a.at, a.way),
            Place::Ptp { way, at, .. } => (at, way),
        }
    }

    /// Whether it lies on a PTP.
    pub(crate) fn ptp(&self) -> bool {
        matches!(self, Place::Ptp { .. })
    }
}

/// A place as a message names it, the joint moves in its controller's
/// words.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Worded(pub Place, pub Words);

impl std::fmt::Display for Worded {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let Worded(place, words) = *self;
        match place {
            Place::Move(a) => write!(f, "{a}"),
            Place::Ptp {
                back: false,
                way,
                at,
            } => write!(
                f,
                "{:.0} % of the way along the {} from home to {at}",
                way * 100.0,
                words.leave_home()
            ),
            Place::Ptp {
                back: true, way, ..
            } => write!(
                f,
                "{:.0} % of the way along the {} back home",
                way * 100.0,
                words.back_home()
            ),
        }
    }
}

/// Where a link came close: the pose, and the link (in [`LINKS`], or past
/// them the head's body).
#[derive(Clone, Copy, Debug)]
pub(crate) struct LinkAt {
    pub place: Place,
    pub link: usize,
}

/// The closest a link came to a solid: the distance, where, and the
/// focus there (the part's coordinates).
type Closest = (f64, Place, [f64; 3]);

/// What a link (or the head) keeps its gap from.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Target {
    /// [`Links::solids`]' first, where the positioner declares one.
    Faceplate,
    /// The program's fixture of this index.
    Fixture(usize),
    /// The plate: the tool without a positioner, the head on a PTP.
    Plate,
    /// The arm's own link (in [`LINKS`]).
    Own(usize),
    /// The finished part (the head on the PTP back home).
    Part,
}

/// The arm's links against the cell, along one robot's plan.
pub(crate) struct Links<'p> {
    program: &'p Program,
    radii: [f64; 3],
    column: Option<f64>,
    /// The tool's radius: the head's top's.
    tool: f64,
    head: HeadShape,
    /// Up the beam, in the tool's frame.
    up: Vector3<f64>,
    /// The head's top, up the beam from the focus, mm.
    top: f64,
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
    /// The solids first (in their order), then the plate, the arm's own
    /// links, the part.
    targets: Vec<Target>,
    /// The positioner's angles last seen, and the part's and the
    /// faceplate's frames there, inverted.
    at: Option<(Rotary, Isometry3<f64>, Isometry3<f64>)>,
    worst: Vec<Option<Worst<LinkAt>>>,
    /// By target, by link (then the head's bodies).
    closest: Vec<Vec<Option<Closest>>>,
    /// The largest faceplate that keeps the gap at every pose found too
    /// close (`None` once a pose is not helped by any).
    keeps: Option<f64>,
    /// What the head meets on a PTP, once built: the fixtures on the
    /// plate, and (`true`) the finished part.
    material: Option<(Material, bool)>,
    /// The fixtures fixed to the robot, once built: on its base (in its
    /// frame), and on its positioner's tilting arm (`true`: in the arm's
    /// frame at E1 = 0).
    fixed: Vec<(bool, Material)>,
}

impl<'p> Links<'p> {
    /// The check of `robot`'s arm against the cell of `cx`: `None` where
    /// the arm is not from the catalogue and declares no links, or its
    /// base has no value.
    pub(crate) fn new(cx: &MachineCx<'p>, robot: &Robot) -> Option<Links<'p>> {
        let arm = robot.arm.as_ref()?;
        let model = arm.model.as_deref().and_then(crate::target::arm::model);
        // The IR's, else (an IR written before it carried them) the
        // catalogue's.
        let radii = arm.links.or(model.map(|m| m.links))?;
        let base = frame(robot.base.value.as_ref()?);
        let faceplate = robot.positioner.as_ref().and_then(|p| p.faceplate);
        let mut solids: Vec<Solid> = faceplate
            .map(|d| Solid::faceplate(d, FACEPLATE_THICKNESS_MM))
            .into_iter()
            .collect();
        // Another machine's fixtures are not in this robot's cell.
        let name = cx.machine.name();
        let ours: Vec<usize> = (cx.program.fixtures.iter().enumerate())
            .filter(|(_, f)| f.fixed_to(name).is_some())
            .map(|(i, _)| i)
            .collect();
        solids.extend(ours.iter().map(|&i| Solid::of(&cx.program.fixtures[i])));
        let mut targets: Vec<Target> = faceplate.map(|_| Target::Faceplate).into_iter().collect();
        targets.extend(ours.iter().map(|&i| Target::Fixture(i)));
        targets.extend([Target::Plate, Target::Own(UPPER_ARM)]);
        let column = arm.column.or(model.map(|m| m.column));
        if column.is_some() {
            targets.push(Target::Own(COLUMN));
        }
        targets.push(Target::Part);
        let head = HeadShape::of(&robot.common.head);
        let who = LINKS.len() + head.bodies.len();
        Some(Links {
            program: cx.program,
            radii,
            column,
            tool: head.bodies.last().map_or(0.0, |b| b.r[1]),
            top: head.bodies.last().map_or(0.0, |b| b.s[1]),
            up: -beam(robot.beam),
            head,
            gap: robot.common.head.gap,
            kin: Kin::of(robot).map(|k| (k, base.inverse())),
            part_inv: base.inverse(),
            faceplate,
            worst: vec![None; targets.len()],
            closest: vec![vec![None; who]; targets.len()],
            solids,
            targets,
            at: None,
            keeps: faceplate,
            material: None,
            fixed: Vec::new(),
        })
    }

    /// The same check with nothing found yet: what a `home` proposed for
    /// the help is tried with.
    pub(crate) fn fresh(&self) -> Links<'p> {
        Links {
            program: self.program,
            radii: self.radii,
            column: self.column,
            tool: self.tool,
            head: self.head.clone(),
            up: self.up,
            top: self.top,
            gap: self.gap,
            kin: self.kin.clone(),
            part_inv: self.part_inv,
            faceplate: self.faceplate,
            solids: self.solids.clone(),
            targets: self.targets.clone(),
            at: None,
            worst: vec![None; self.worst.len()],
            closest: vec![vec![None; self.closest[0].len()]; self.closest.len()],
            keeps: self.faceplate,
            material: None,
            fixed: Vec::new(),
        }
    }

    /// Whether a pose was found within the gap of fixture `i`.
    pub(crate) fn fixture_hit(&self, i: usize) -> bool {
        let k = self.slot(Target::Fixture(i));
        self.targets[k] == Target::Fixture(i) && self.worst[k].is_some()
    }

    /// Whether no pose was found too close to anything.
    pub(crate) fn clear(&self) -> bool {
        self.worst.iter().all(Option::is_none)
    }

    /// What the help may search for, by target, where its worst pose lies
    /// off the PTPs (whose help is a home): a fixture to move (not the
    /// scanned part), a base farther off (the arm against itself), a turn
    /// about the beam (the tool at the plate).
    pub(crate) fn searches(&self) -> Vec<(usize, Search)> {
        let mut out = Vec::new();
        for (k, w) in self.worst.iter().enumerate() {
            let Some(w) = w.as_ref().filter(|w| !w.at.place.ptp()) else {
                continue;
            };
            let search = match self.targets[k] {
                Target::Fixture(i) if !self.program.fixtures[i].is_scan() => Search::Fixture(i),
                Target::Own(_) => Search::Base,
                Target::Plate if w.at.link == TOOL => Search::Spin,
                _ => continue,
            };
            out.push((k, search));
        }
        out
    }

    /// Whether any pose on a PTP was found too close.
    pub(crate) fn ptp_hit(&self) -> bool {
        self.worst.iter().flatten().any(|w| w.at.place.ptp())
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

    /// Keeps `d` as `who`'s closest approach to target `k`, and a hit
    /// where it is within the gap; whether it is.
    fn record(&mut self, k: usize, who: usize, d: f64, place: Place, focus: [f64; 3]) -> bool {
        let slot = &mut self.closest[k][who];
        if slot.is_none_or(|c| d < c.0) {
            *slot = Some((d, place, focus));
        }
        if d < self.gap {
            let at = LinkAt { place, link: who };
            Worst::hit(&mut self.worst[k], d, self.gap, at);
            return true;
        }
        false
    }

    /// The closest `who` came to target `k` so far (what a pose farther
    /// than it cannot change, unless within the gap).
    fn beyond(&self, k: usize, who: usize) -> f64 {
        self.closest[k][who]
            .map_or(f64::INFINITY, |c| c.0)
            .max(self.gap)
    }

    /// The arm at axis angles `j`, the positioner at `axes`, at `place`,
    /// the focus at `focus` (the part's coordinates): each link against
    /// the solids, the plate and the arm's own links; on a PTP, the head
    /// against the plate, the fixtures and the part too.
    pub(crate) fn check(
        &mut self,
        solver: &Solver,
        j: &Joints,
        axes: Rotary,
        place: Place,
        focus: [f64; 3],
    ) {
        let (p, tcp) = solver.joint_frames(j);
        let up = tcp.rotation * self.up;
        let head = Pose {
            focus: tcp.translation.vector.into(),
            up: up.into(),
        };
        let top = add(head.focus, scale(head.up, self.top));
        let mut caps: Vec<(usize, Capsule)> = Vec::with_capacity(7);
        caps.extend(capsules(&p, self.radii));
        if let Some(r) = self.column {
            caps.extend(column(&p, r).map(|c| (COLUMN, c)));
        }
        caps.push((
            TOOL,
            Capsule {
                a: p[5],
                b: top,
                r: self.tool,
            },
        ));
        let (part_inv, face_inv) = self.frames(axes);
        let plate = usize::from(self.faceplate.is_some());
        for k in 0..self.targets.len() {
            match self.targets[k] {
                Target::Faceplate | Target::Fixture(_) => {
                    let inv = match self.targets[k] {
                        Target::Faceplate => face_inv,
                        // Fixed to the robot: in its own frame, or in its
                        // positioner's tilting arm's.
                        Target::Fixture(i) if self.program.fixtures[i].machine.is_some() => {
                            self.machine_inv(i, axes, part_inv)
                        }
                        _ => part_inv,
                    };
                    for (link, cap) in &caps {
                        let Some(d) = self.solids[k].capsule(&inv, cap, self.beyond(k, *link))
                        else {
                            continue;
                        };
                        if self.record(k, *link, d, place, focus) && k < plate {
                            self.keep_from(cap, &inv);
                        }
                    }
                }
                Target::Plate if self.kin.is_none() => {
                    // The tool only: the wrist of a tool angled on its
                    // flange works beside the part, at its height
                    // (docs/collision.md, *The arm*).
                    for (link, cap) in caps.iter().filter(|c| c.0 == TOOL) {
                        let z = |q: [f64; 3]| (part_inv * Point3::from(q)).z;
                        let d = z(cap.a).min(z(cap.b)) - cap.r;
                        self.record(k, *link, d, place, focus);
                    }
                }
                Target::Own(o) => self.own(k, o, &caps, &head, place, focus),
                _ => {}
            }
        }
        if place.ptp() {
            let part = part_inv * tcp;
            let pose = Pose {
                focus: part.translation.vector.into(),
                up: (part.rotation * self.up).into(),
            };
            self.head_on_ptp([&pose, &head], axes, place, focus);
        }
    }

    /// The wrist, the tool and the head's bodies against the arm's own
    /// link `o` (target `k`).
    fn own(
        &mut self,
        k: usize,
        o: usize,
        caps: &[(usize, Capsule)],
        head: &Pose,
        place: Place,
        focus: [f64; 3],
    ) {
        let near = |a: &Capsule, b: &Capsule| {
            let (ca, cb) = (mid(a), mid(b));
            dist(ca, cb) - dist(a.a, a.b) / 2.0 - dist(b.a, b.b) / 2.0 - a.r - b.r
        };
        for (link, cap) in caps.iter().filter(|c| c.0 == WRIST || c.0 == TOOL) {
            for (_, other) in caps.iter().filter(|c| c.0 == o) {
                if near(cap, other) > self.beyond(k, *link) {
                    continue;
                }
                let d = capsule_capsule(cap, other);
                self.record(k, *link, d, place, focus);
            }
        }
        let (centre, radius) = self.head.bound(head);
        for (_, other) in caps.iter().filter(|c| c.0 == o) {
            let far = segment_point(other.a, other.b, centre) - radius - other.r;
            for b in 0..self.head.bodies.len() {
                let who = LINKS.len() + b;
                if far > self.beyond(k, who) {
                    continue;
                }
                let d = body_capsule(&self.head.bodies[b], head, other);
                self.record(k, who, d, place, focus);
            }
        }
    }

    /// The head on a PTP at `pose` (the part's coordinates; `robot`, the
    /// same in the robot's frame), the positioner at `axes`: against the plate by its lowest point,
    /// the fixtures and the part by their lumps.
    fn head_on_ptp(
        &mut self,
        [pose, robot]: [&Pose; 2],
        axes: Rotary,
        place: Place,
        focus: [f64; 3],
    ) {
        let plate = self.slot(Target::Plate);
        // A head of no bodies (only a standoff) has nothing to check.
        let Some((d, body)) = self.head.lowest(pose, [0.0, 0.0, 1.0]) else {
            return;
        };
        self.record(plate, LINKS.len() + body, d, place, focus);
        let on_plate = match &self.material {
            Some((m, _)) => m.nearest(&self.head, pose, CAP_MM),
            None => None,
        };
        let mut near = vec![on_plate];
        for (tilts, m) in &self.fixed {
            let inv = match (tilts, &self.kin) {
                (true, Some((kin, _))) => {
                    let e = [axes.tilt, axes.c];
                    kin.part_on_tilt(e) * kin.part(e).inverse()
                }
                _ => Isometry3::identity(),
            };
            let f = inv * Point3::from(robot.focus);
            let u = inv.rotation * Vector3::from(robot.up);
            let pose = Pose {
                focus: [f.x, f.y, f.z],
                up: [u.x, u.y, u.z],
            };
            near.push(m.nearest(&self.head, &pose, CAP_MM));
        }
        for (d, body, lump) in near.into_iter().flatten() {
            let fixtures = self.program.fixtures.len() as u32;
            let what = if lump.group >= u32::MAX - fixtures {
                Target::Fixture((u32::MAX - lump.group - 1) as usize)
            } else {
                Target::Part
            };
            let k = self.slot(what);
            self.record(k, LINKS.len() + body, d, place, focus);
        }
    }

    /// Where fixture `i`, fixed to the robot, sees the robot's frame with
    /// the positioner at `axes` (`part_inv`: the part's frame there,
    /// inverted): its own frame, or its positioner's tilting arm's.
    fn machine_inv(&self, i: usize, axes: Rotary, part_inv: Isometry3<f64>) -> Isometry3<f64> {
        match (&self.kin, self.program.fixtures[i].tilts) {
            (Some((kin, _)), true) => kin.part_on_tilt([axes.tilt, axes.c]) * part_inv,
            _ => Isometry3::identity(),
        }
    }

    /// The index of target `t`.
    fn slot(&self, t: Target) -> usize {
        self.targets.iter().position(|x| *x == t).unwrap_or(0)
    }

    /// Builds what the head meets on a PTP: the fixtures, and with `part`
    /// the beads of every layer that comes within reach of the head at any
    /// of `poses` (the part's coordinates).
    pub(crate) fn build_material(&mut self, part: bool, poses: &[Pose]) {
        if self.material.as_ref().is_some_and(|m| m.1 == part) {
            return;
        }
        let mut m = Material::default();
        let mut fixed = [(false, Material::default()), (true, Material::default())];
        for (i, f) in self.program.fixtures.iter().enumerate() {
            match &f.machine {
                None => crate::verify::collision::fixture_lumps(f, i, &mut m),
                // Only this robot's reach the links' targets.
                Some(_) if self.targets.contains(&Target::Fixture(i)) => {
                    let on = &mut fixed[usize::from(f.tilts)].1;
                    crate::verify::collision::fixture_lumps(f, i, on);
                }
                Some(_) => {}
            }
        }
        self.fixed = fixed.into_iter().filter(|f| !f.1.is_empty()).collect();
        if part {
            let spheres: Vec<_> = poses.iter().map(|p| self.head.bound(p)).collect();
            part_lumps(self.program, &spheres, &mut m);
        }
        self.material = Some((m, part));
    }

    /// The head's pose in the part's coordinates at axis angles `j`, the
    /// positioner at `axes`.
    pub(crate) fn head_pose(&mut self, solver: &Solver, j: &Joints, axes: Rotary) -> Pose {
        let (part_inv, _) = self.frames(axes);
        let part = part_inv * solver.tcp(j);
        Pose {
            focus: part.translation.vector.into(),
            up: (part.rotation * self.up).into(),
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

    /// The name of link or body `who`.
    fn who(&self, who: usize) -> &str {
        LINKS
            .get(who)
            .copied()
            .unwrap_or_else(|| &self.head.names[who - LINKS.len()])
    }

    /// What target `k` is called in the report.
    fn with(&self, k: usize) -> String {
        match self.targets[k] {
            Target::Faceplate => "positioner faceplate".to_string(),
            Target::Fixture(i) => self.program.fixtures[i].label(),
            Target::Plate => "plate".to_string(),
            Target::Own(o) => LINKS[o].to_string(),
            Target::Part => "part".to_string(),
        }
    }

    /// The closest approach of each link to each solid, where a pose came
    /// near enough to measure.
    pub(crate) fn approaches(&self) -> Vec<Approach> {
        let mut out = Vec::new();
        for (k, links) in self.closest.iter().enumerate() {
            let with = self.with(k);
            for (who, c) in links.iter().enumerate() {
                if let Some((d, at, focus)) = *c {
                    let (at, way) = at.at_way();
                    out.push(Approach::new(
                        (self.who(who), &with),
                        (d, self.gap),
                        at,
                        way,
                        focus,
                    ));
                }
            }
        }
        out
    }

    /// The reports: one for each target a link came too close to; `home`,
    /// a home whose PTPs keep the gap where one was found; `fixes`, by
    /// target, a change found to keep it ([`Links::searches`]).
    pub(crate) fn report(
        &self,
        cx: &MachineCx<'_>,
        home: Option<([f64; 6], says::HomeFrom)>,
        fixes: &[Option<LinkFix>],
        out: &mut Diagnostics,
    ) {
        let words = match cx.machine {
            crate::ir::Machine::Robot(r) => Words::of(r.controller),
            _ => Words::Kuka,
        };
        for (k, w) in self.worst.iter().enumerate() {
            let Some(w) = w else {
                continue;
            };
            let (with, placed) = match self.targets[k] {
                Target::Faceplate => (
                    Against::Faceplate(self.keeps),
                    cx.origin.written(MachineField::Faceplate),
                ),
                Target::Fixture(i) => (
                    match &cx.program.fixtures[i] {
                        f if f.is_scan() => Against::Scan,
                        f => Against::Fixture(&f.name),
                    },
                    cx.program.origins.fixtures.get(i).copied(),
                ),
                Target::Plate => (Against::Plate, None),
                Target::Own(o) => (Against::Own(LINKS[o]), None),
                Target::Part => (Against::Part, None),
            };
            let worst = crate::diag::Worst {
                at: Worded(w.at.place, words),
                count: w.count,
                value: w.value,
                limit: w.limit,
            };
            out.push(says::link_collision(&says::LinkHit {
                machine: cx.machine.name(),
                link: self.who(w.at.link),
                with,
                worst: &worst,
                arm: cx.origin.at(MachineField::Arm),
                placed,
                ptp: w.at.place.ptp().then_some(home),
                home: cx.origin.written(MachineField::Home),
                fix: fixes.get(k).cloned().flatten(),
                words,
            }));
        }
    }
}

/// What a link's help searches for ([`Links::searches`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Search {
    /// Where to move the fixture of this index.
    Fixture(usize),
    /// A base farther from the arm's foot.
    Base,
    /// A turn of the tool about the beam.
    Spin,
}

/// The beam's direction in the tool's frame.
pub(crate) fn beam(axis: ToolAxis) -> Vector3<f64> {
    match axis {
        ToolAxis::PlusX => Vector3::x(),
        ToolAxis::MinusX => -Vector3::x(),
        ToolAxis::PlusY => Vector3::y(),
        ToolAxis::MinusY => -Vector3::y(),
        ToolAxis::PlusZ => Vector3::z(),
        ToolAxis::MinusZ => -Vector3::z(),
    }
}

/// A capsule's axis's middle.
fn mid(c: &Capsule) -> [f64; 3] {
    scale(add(c.a, c.b), 0.5)
}

/// The beads of every layer of `program` whose points come within a
/// sphere of `spheres` (and the look-ahead of a check) as lumps in `m`:
/// each path's stretch between two points every [`BEAD_STEP_MM`], its
/// width the bead's (or the pitch), its height the rise.
fn part_lumps(program: &Program, spheres: &[([f64; 3], f64)], m: &mut Material) {
    let width = program.bead.as_ref().map_or(3.0, |b| b.width);
    for (li, layer) in program.layers.iter().enumerate() {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        let mut r_max: f64 = 0.0;
        for p in layer.paths.iter().flat_map(|p| &p.points) {
            for k in 0..3 {
                lo[k] = lo[k].min(p.pos[k]);
                hi[k] = hi[k].max(p.pos[k]);
            }
            r_max = r_max.max(width.max(f64::from(p.pitch)) + f64::from(p.rise.max(0.0)));
        }
        let near = spheres.iter().any(|(c, r)| {
            let d: [f64; 3] = std::array::from_fn(|k| (lo[k] - c[k]).max(c[k] - hi[k]).max(0.0));
            (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() < r + CAP_MM + r_max
        });
        if !near {
            continue;
        }
        for path in &layer.paths {
            for w in path.points.windows(2) {
                let (a, b) = (&w[0], &w[1]);
                let n = a.normal.map(f64::from);
                let rise = f64::from(a.rise.max(0.0));
                let half = width.max(f64::from(a.pitch)) / 2.0;
                let len = dist(a.pos, b.pos);
                let pieces = (len / BEAD_STEP_MM).ceil().clamp(1.0, 1e6);
                let r = (len / pieces / 2.0).hypot(half.hypot(rise / 2.0));
                for s in 0..pieces as usize {
                    let t = (s as f64 + 0.5) / pieces;
                    let on = add(a.pos, scale(crate::collision::head::sub(b.pos, a.pos), t));
                    let at = add(on, scale(n, rise / 2.0));
                    m.add(
                        Lump {
                            at,
                            r,
                            group: li as u32,
                        },
                        n,
                    );
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The joint moves from and back to home are KUKA's PTPs, and on an
    /// ABB robot the `MoveJ` from home and the `MoveAbsJ` back.
    #[test]
    fn ptp_places_are_named_in_the_controllers_words() {
        let from = Place::Ptp {
            back: false,
            way: 0.5,
            at: Where::End,
        };
        let back = Place::Ptp {
            back: true,
            way: 0.25,
            at: Where::End,
        };
        let said = |p, w| Worded(p, w).to_string();
        assert_eq!(
            said(from, Words::Kuka),
            "50 % of the way along the PTP from home to the retract after the last path"
        );
        assert_eq!(
            said(from, Words::Abb),
            "50 % of the way along the MoveJ from home to the retract after the last path"
        );
        assert_eq!(
            said(back, Words::Kuka),
            "25 % of the way along the PTP back home"
        );
        assert_eq!(
            said(back, Words::Abb),
            "25 % of the way along the MoveAbsJ back home"
        );
    }
}
