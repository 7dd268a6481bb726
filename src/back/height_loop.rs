//! A segmented ring whose height loop runs on the machine, as the back ends
//! write it: one layer in a loop. Every layer has the same points in plan
//! view ([`crate::ir::Ring`]); only each segment's speed and working plane
//! change, and those the program computes as it measures. So the program is
//! the first layer run `layers − 1` times, then the last layer once (its last
//! transition stays level and the build ends there).
//!
//! [`LoopPlan::collect`] follows the machine's motion plan — the same moves
//! and events the verifier checked — and keeps what a looping program needs:
//! the moves before the first deposit, the first layer's and the last
//! layer's deposit moves with their segment and place in it, where the plan
//! ends a segment ([`Visit::segment_end`]), and the moves after the last
//! deposit. Each back end renders that in its own language.

use super::EmitError;
use crate::ir::{HeightLoop, HeightSensor, Layer, Program, Ring};
use crate::numbers::trimmed;
use crate::plan::{Io, Move, MoveKind, Plan, SegmentEnd, Visit, Where};
use crate::verify::VerifiedMachine;

/// What a looping writer starts from: the ring, its law, the sensor the
/// machine reads and the plan collected for the loop.
pub struct Prepared<'p> {
    /// The ring.
    pub ring: &'p Ring,
    /// The law the program runs.
    pub law: &'p HeightLoop,
    /// The machine's height sensor.
    pub sensor: HeightSensor,
    /// The machine's motion plan, as the loop needs it.
    pub plan: LoopPlan,
}

/// The ring, law and plan of machine `m`, whose `sensor` the verifier
/// required (`lmd::height-sensor`). `writer` names the back end for the
/// error a verified machine cannot reach.
pub fn prepare<'p>(
    m: VerifiedMachine<'p>,
    sensor: Option<HeightSensor>,
    writer: &str,
) -> Result<Prepared<'p>, EmitError> {
    let (Some((ring, law)), Some(sensor)) = (m.ir().loop_on_machine(), sensor) else {
        return Err(EmitError::Template(format!(
            "internal error: a ring's loop reached the {writer} writer without its ring or sensor"
        )));
    };
    Ok(Prepared {
        ring,
        law,
        sensor,
        plan: LoopPlan::collect(&m.plan()),
    })
}

/// The loop's constants as both looping programs declare them: a name (KRL
/// writes it in capitals), the value and what it is, for the comment.
pub fn constants(
    ring: &Ring,
    law: &HeightLoop,
    sensor: &HeightSensor,
) -> [(&'static str, f64, &'static str); 7] {
    [
        ("kp", law.kp, "(mm/s)/mm, proportional gain"),
        ("ki", law.ki, "(mm/s)/mm, integral gain"),
        ("hr", law.target, "mm, target height per layer"),
        ("vmin", law.clamp[0], "mm/s, lowest speed"),
        ("vmax", law.clamp[1], "mm/s, highest speed"),
        ("hscale", sensor.full_scale, "mm at an input of 1.0"),
        (
            "arc",
            ring.radius * ring.transition.to_radians(),
            "mm, a transition's horizontal length",
        ),
    ]
}

/// Where a deposit move lies in its segment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Part {
    /// On the segment's constant part: at its own height.
    Flat,
    /// Move `step` (from 1) of the `of` over its transition: `step/of` of the
    /// way to the next segment's height.
    Transition {
        /// From 1.
        step: usize,
        /// The transition's moves.
        of: usize,
    },
}

/// One deposit move of a layer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LayerMove {
    /// The move as planned (nominal height and speed).
    pub planned: Move,
    /// The index of its target in the layer's path (from 1: point 0 is where
    /// the layer starts).
    pub point: usize,
    /// Its segment, from 0.
    pub segment: usize,
    /// Where in the segment.
    pub part: Part,
    /// The segment this move ends, if it does (the plan's event).
    pub ends: Option<SegmentEnd>,
    /// Whether it is the first move of its segment.
    pub first: bool,
}

/// A gas or powder step of the plan outside the deposits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CellStep {
    /// Switch.
    Io(Io),
    /// Wait, standing, s.
    Dwell(f64),
}

/// What a looping program writes.
#[derive(Clone, Debug, Default)]
pub struct LoopPlan {
    /// Moves before the first deposit (travel, approach).
    pub head: Vec<Move>,
    /// Gas and powder before the first deposit, between the last two moves
    /// of `head` (above the first point, before the approach).
    pub prepare: Vec<CellStep>,
    /// The first layer's deposit moves: the loop's body.
    pub body: Vec<LayerMove>,
    /// The last layer's (empty with one layer: the body is the last).
    pub last: Vec<LayerMove>,
    /// Moves after the last deposit (the retract).
    pub tail: Vec<Move>,
    /// Gas and powder after the tail's moves.
    pub finish: Vec<CellStep>,
    /// Moves after those: a CNC's lift to its safe height, a robot's PTP
    /// home.
    pub park: Vec<Move>,
    /// Layers.
    pub layers: usize,
}

impl LoopPlan {
    /// The loop plan of `plan`, whose program must have a ring (else the
    /// body stays empty).
    pub fn collect(plan: &Plan<'_>) -> LoopPlan {
        let p = plan.program();
        let mut c = Collect {
            out: LoopPlan {
                layers: p.layers.len(),
                ..LoopPlan::default()
            },
            ring: p.ring.as_ref(),
            layer: 0,
            started: false,
            ended: false,
            end: None,
            segment: None,
        };
        plan.walk(&mut c);
        c.out
    }
}

impl LoopPlan {
    /// Segment `j`'s working plane on the first layer: its first flat
    /// move's height less its defocus (0 on the substrate).
    pub fn first_plane(&self, j: usize, defocus: f64) -> f64 {
        self.body
            .iter()
            .find(|m| m.segment == j && m.part == Part::Flat)
            .map_or(0.0, |m| m.planned.to[2] - defocus)
    }
}

/// A comment naming segment `j` (from 0) of `ring`: its angles, defocus and
/// power, as both looping programs label it.
pub fn segment_title(ring: &Ring, j: usize) -> String {
    let s = &ring.segments[j];
    let mu = 360.0 / ring.segments.len() as f64;
    format!(
        "segment {}: {} .. {} deg, defocus {} mm, {} W",
        j + 1,
        trimmed(mu * j as f64, 3),
        trimmed(mu * (j + 1) as f64, 3),
        trimmed(s.defocus, 3),
        trimmed(s.power, 1)
    )
}

/// The ring and its loop of a program whose loop runs on the machine.
pub fn on_machine(p: &Program) -> Option<(&Ring, &HeightLoop)> {
    p.loop_on_machine()
}

struct Collect<'a> {
    out: LoopPlan,
    ring: Option<&'a Ring>,
    layer: usize,
    /// A deposit move was seen.
    started: bool,
    /// The laser went off after the deposits.
    ended: bool,
    end: Option<SegmentEnd>,
    segment: Option<usize>,
}

impl Collect<'_> {
    /// A continuous ring's plan switches gas and powder only before its
    /// first deposit and after its last.
    fn cell(&mut self, step: CellStep) {
        if self.started || self.ended {
            self.out.finish.push(step);
        } else {
            self.out.prepare.push(step);
        }
    }
}

impl Visit for Collect<'_> {
    fn layer(&mut self, index: usize, _: &Layer) {
        self.layer = index;
        self.segment = None;
    }

    fn laser_off(&mut self) {
        self.ended = self.started;
    }

    fn segment_end(&mut self, end: SegmentEnd) {
        self.end = Some(end);
    }

    fn io(&mut self, event: Io) {
        self.cell(CellStep::Io(event));
    }

    fn dwell(&mut self, seconds: f64) {
        self.cell(CellStep::Dwell(seconds));
    }

    fn motion(&mut self, m: &Move) {
        let ends = self.end.take();
        if !m.deposits() {
            if self.started || self.ended {
                if matches!(m.kind, MoveKind::Lift | MoveKind::Home) {
                    self.out.park.push(*m);
                } else {
                    self.out.tail.push(*m);
                }
            } else {
                self.out.head.push(*m);
            }
            return;
        }
        self.started = true;
        let last_layer = self.out.layers.saturating_sub(1);
        let into = match self.layer {
            0 => &mut self.out.body,
            l if l == last_layer => &mut self.out.last,
            _ => return,
        };
        let (Some(r), Where::Point { point, .. }) = (self.ring, m.at) else {
            return;
        };
        let per = r.flat_moves + r.transition_moves;
        if point == 0 || per == 0 {
            return;
        }
        let segment = (point - 1) / per;
        let within = (point - 1) % per + 1;
        let part = if within <= r.flat_moves {
            Part::Flat
        } else {
            Part::Transition {
                step: within - r.flat_moves,
                of: r.transition_moves,
            }
        };
        let first = self.segment != Some(segment);
        self.segment = Some(segment);
        into.push(LayerMove {
            planned: *m,
            point,
            segment,
            part,
            ends,
            first,
        });
    }
}
