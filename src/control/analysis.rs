//! The compile-time check of a declared loop: signs, stability at every
//! segment's speed, settling time against the number of layers. Each problem
//! is a [`Finding`] carrying its numbers; [`Finding`]'s `Display` and
//! [`Finding::help`] hold all the wording, in one place:
//! `crate::diag::message::control`.
//!
//! The operating point of segment `j` is its start speed `v_j` (Table 1's), at
//! which the segment is meant to lay `h_r`: the table was matched so that it
//! does, and the loop's only equilibrium is `h = h_r`. The loop is strongest
//! where `h_r/v` is largest, at the slowest segment, so that is where it goes
//! unstable first; it is also analysed at the clamp's low speed, which a
//! segment may be driven down to.

use super::gain::SpeedPerLength;
use super::invalid::Invalid;
use super::law::Controller;
use super::linear::LoopGains;
use crate::units::Speed;
use std::num::NonZeroUsize;

/// A loop that corrects less than this share of an error over the whole
/// build (`ρᴺ` above it) never settles: an error, not a warning.
pub const NEVER_SETTLES: f64 = 0.5;

/// A stable loop that leaves at most this share of an error after the last
/// layer corrects enough: no warning, even if it takes longer than the build
/// to settle to [`super::linear::SETTLED`] (2 %). Seed 004's ring, as
/// published (its gains, 130 layers), leaves 2.9 % at its slowest segment
/// (13 mm/s, ρ¹³⁰): a whole missing layer (0.23 mm) would end 0.007 mm off,
/// and its simulation against the declared plant ends within 0.038 mm
/// (0.13 %) of 29.90 mm, as the paper reports — a warning there would cry
/// wolf. 5 % is three time constants, the other usual settling band.
pub const SETTLED_ENOUGH: f64 = 0.05;

/// The loop about one segment's operating speed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SegmentLoop {
    /// The segment, from 0; `None` for the clamp's low speed.
    pub segment: Option<usize>,
    /// Its operating speed.
    pub speed: Speed,
    /// `p`, `q` there.
    pub gains: LoopGains,
    /// `ρ(A)`.
    pub radius: f64,
    /// Layers to settle to 2 %, if stable.
    pub settling: Option<f64>,
}

impl SegmentLoop {
    fn new(c: &Controller, segment: Option<usize>, speed: Speed) -> Self {
        let gains = LoopGains::at(c.kp(), c.ki(), c.target(), speed);
        SegmentLoop {
            segment,
            speed,
            gains,
            radius: gains.spectral_radius(),
            settling: gains.settling_layers(),
        }
    }
}

/// Which gain a sign finding is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Gain {
    /// `kP`.
    Proportional,
    /// `kI`.
    Integral,
}

/// How bad a finding is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Severity {
    /// The loop must not run.
    Error,
    /// The loop runs but will not do what was declared.
    Warning,
}

/// One problem with a declared loop, with the numbers for its message.
#[derive(Clone, Debug, PartialEq)]
pub enum Finding {
    /// A gain that is not negative. With `h ∝ 1/v` a layer that comes out too
    /// low must slow its segment down, so both gains must be negative; a zero
    /// `kP` leaves the loop oscillating, a zero `kI` leaves the total error.
    Sign {
        /// Which gain.
        gain: Gain,
        /// Its value.
        value: SpeedPerLength,
    },
    /// `ρ ≥ 1` at some segment's speed.
    Unstable {
        /// The worst segment's loop.
        worst: SegmentLoop,
        /// How many segments are unstable.
        count: usize,
        /// Of how many.
        of: usize,
        /// The declared gains.
        kp: SpeedPerLength,
        /// The declared gains.
        ki: SpeedPerLength,
        /// Both gains times a factor below this are stable at every segment.
        limit: f64,
    },
    /// Stable at every segment's speed, unstable at the clamp's low end.
    UnstableAtClamp {
        /// The loop at `v_min`.
        at: SegmentLoop,
        /// Both gains times a factor below this are stable there.
        limit: Option<f64>,
    },
    /// Stable but slower than the build: settling takes more layers than it
    /// has. An error when less than half of an error is corrected by the end
    /// (`ρᴺ >` [`NEVER_SETTLES`]), else a warning.
    Slow {
        /// The slowest segment's loop.
        worst: SegmentLoop,
        /// Its settling time, layers.
        settling: f64,
        /// The build's layers.
        layers: usize,
        /// `ρᴺ`: the share of a starting error left at the end.
        residual: f64,
        /// The declared gains.
        kp: SpeedPerLength,
        /// The declared gains.
        ki: SpeedPerLength,
        /// Both gains times this settle within the build at every segment.
        scale: Option<f64>,
        /// Whether the same numbers read per (m/s)/mm — 1000 times larger —
        /// would be stable and correct most of an error: the paper's slip.
        per_metre: bool,
    },
}

impl Finding {
    /// Errors stop the build; warnings are printed.
    pub fn severity(&self) -> Severity {
        match self {
            Finding::Sign { .. } | Finding::Unstable { .. } => Severity::Error,
            Finding::Slow { residual, .. } if *residual > NEVER_SETTLES => Severity::Error,
            Finding::Slow { .. } | Finding::UnstableAtClamp { .. } => Severity::Warning,
        }
    }
}

/// The loop about every segment, and what is wrong with it.
#[derive(Clone, Debug, PartialEq)]
pub struct Analysis {
    /// One per segment, in order.
    pub segments: Vec<SegmentLoop>,
    /// At the clamp's low speed.
    pub clamp_low: SegmentLoop,
    /// Errors first, then warnings.
    pub findings: Vec<Finding>,
}

impl Analysis {
    /// No error-severity finding: the loop may be built.
    pub fn is_ok(&self) -> bool {
        self.findings
            .iter()
            .all(|f| f.severity() == Severity::Warning)
    }
}

/// Checks `controller` about each segment's operating speed `speeds[j]` (its
/// start speed) for a build of `layers` layers.
pub fn analyse(
    controller: &Controller,
    speeds: &[Speed],
    layers: NonZeroUsize,
) -> Result<Analysis, Invalid> {
    if speeds.is_empty() {
        return Err(Invalid::Empty {
            what: "operating speeds",
        });
    }
    for &v in speeds {
        // The loop starts there, so the clamp must allow it (and it is > 0).
        controller.start("start speed", v)?;
    }
    let segments: Vec<SegmentLoop> = speeds
        .iter()
        .enumerate()
        .map(|(j, &v)| SegmentLoop::new(controller, Some(j), v))
        .collect();
    let clamp_low = SegmentLoop::new(controller, None, controller.clamp().low());
    let (kp, ki) = (controller.kp(), controller.ki());
    let mut findings = Vec::new();
    for (gain, value) in [(Gain::Proportional, kp), (Gain::Integral, ki)] {
        if value.0 >= 0.0 {
            findings.push(Finding::Sign { gain, value });
        }
    }
    if findings.is_empty() {
        findings.extend(stability(&segments, clamp_low, kp, ki));
    }
    if findings.is_empty() {
        findings.extend(settling(controller, &segments, layers.get()));
    }
    findings.sort_by_key(|f| f.severity() == Severity::Warning);
    Ok(Analysis {
        segments,
        clamp_low,
        findings,
    })
}

/// With negative gains: unstable segments (the worst by radius), else the clamp.
fn stability(
    segments: &[SegmentLoop],
    clamp_low: SegmentLoop,
    kp: SpeedPerLength,
    ki: SpeedPerLength,
) -> Option<Finding> {
    let unstable: Vec<&SegmentLoop> = segments.iter().filter(|l| l.radius >= 1.0).collect();
    let limit = segments
        .iter()
        .filter_map(|l| l.gains.stability_limit())
        .fold(f64::INFINITY, f64::min);
    if let Some(worst) = worst(unstable.iter().copied()) {
        return Some(Finding::Unstable {
            worst: *worst,
            count: unstable.len(),
            of: segments.len(),
            kp,
            ki,
            limit,
        });
    }
    (clamp_low.radius >= 1.0).then(|| Finding::UnstableAtClamp {
        at: clamp_low,
        limit: clamp_low.gains.stability_limit(),
    })
}

/// With a stable loop: the slowest segment against the build's layers.
fn settling(c: &Controller, segments: &[SegmentLoop], layers: usize) -> Option<Finding> {
    let worst = worst(segments.iter().filter(|l| l.settling.is_some()))?;
    let settling = worst.settling?;
    if settling <= layers as f64 || worst.gains.residual_after(layers) <= SETTLED_ENOUGH {
        return None;
    }
    let settles_all = |factor: f64| {
        segments.iter().all(|l| {
            l.gains
                .scaled(factor)
                .settling_layers()
                .is_some_and(|n| n <= layers as f64)
        })
    };
    let scale = segments
        .iter()
        .map(|l| l.gains.scale_to_settle(layers))
        .try_fold(0.0_f64, |acc, c| c.map(|c| acc.max(c)))
        .filter(|&c| settles_all(c));
    Some(Finding::Slow {
        worst: *worst,
        settling,
        layers,
        residual: worst.gains.residual_after(layers),
        kp: c.kp(),
        ki: c.ki(),
        scale,
        per_metre: per_metre(segments, layers),
    })
}

/// The loop with the largest spectral radius; the first of equals (segments 5
/// and 6 of Table 1 are the same loop: name 5).
fn worst<'a>(loops: impl Iterator<Item = &'a SegmentLoop>) -> Option<&'a SegmentLoop> {
    loops.fold(None, |best: Option<&SegmentLoop>, l| match best {
        Some(b) if b.radius >= l.radius => Some(b),
        _ => Some(l),
    })
}

/// Whether gains 1000 times larger — the same numbers read per (m/s)/mm —
/// would be stable everywhere and settle most of an error within the build:
/// the paper's own slip, worth naming in the help.
fn per_metre(segments: &[SegmentLoop], layers: usize) -> bool {
    segments.iter().all(|l| {
        let g = l.gains.scaled(1000.0);
        g.is_stable() && g.residual_after(layers) <= NEVER_SETTLES
    })
}
