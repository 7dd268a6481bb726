//! A segmented ring and its height loop as checked: the numbers
//! are already the control module's checked types, so the slicer and the
//! verifier cannot be handed a degenerate ring or loop.

use crate::control::{Controller, Plant, Ring, SegmentTable};
use crate::ir::RingOrigins;
use crate::units::{Angle, Length, MassFlow};
use std::num::NonZeroUsize;

/// `ring NAME { … }` with `slicing continuous { … }` and, if declared,
/// `control height { … }`.
#[derive(Clone, Debug)]
pub struct RingBuild {
    /// The ring's name.
    pub name: String,
    /// Radius, segments, transition.
    pub ring: Ring,
    /// One row per segment.
    pub table: SegmentTable,
    /// Layers to build.
    pub layers: NonZeroUsize,
    /// The nominal rise per layer.
    pub layer_height: Length,
    /// Points at most this far apart along the ring.
    pub step: Angle,
    /// The height loop, if declared; without one every layer runs the
    /// table's speeds.
    pub control: Option<HeightControl>,
    /// The process block's powder feed.
    pub powder: MassFlow,
    /// Where its parts are declared.
    pub origins: RingOrigins,
}

/// `control height { … }`.
#[derive(Clone, Debug)]
pub struct HeightControl {
    /// Gains, target and clamp.
    pub controller: Controller,
    /// Where the loop runs.
    pub run: LoopRun,
    /// What `lmdc simulate` and a schedule run the loop against.
    pub plant: Plant,
}

/// `run = on_machine | schedule`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LoopRun {
    /// The machine measures each segment and runs the law itself.
    OnMachine,
    /// Open loop: the speeds the loop chooses against the plant, written
    /// per layer and segment.
    Schedule,
}
