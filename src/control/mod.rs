//! Closed-loop layer-height control on a segmented ring (seed 004, Shen et
//! al. 2018): the maths as pure functions of numbers, tested against the
//! formulas and the paper's tables. Nothing here reads the semantic model or
//! writes IR: sema builds these types from the source, the slicer and the
//! verifier use them, and the code generators write [`LAW`]'s steps
//! (`docs/design/seed004.md`).
//!
//! | module | question | the paper |
//! |---|---|---|
//! | [`gain`] | what unit is a gain in | eq. 6's "s⁻¹", right only per (m/s)/mm |
//! | [`law`] | the next layer's speed | eq. 6, clamp 1.9–20 mm/s |
//! | [`plant`] | what height a speed lays, for simulation | §4: `h ∝ 1/v` |
//! | [`mod@simulate`] | the loop over N layers offline | Fig. 9, Table 2 |
//! | [`linear`] | stability and settling of the linearised loop | — |
//! | [`analysis`] | the compile-time check and its messages | — |
//! | [`table`] | per-segment process values, energy density | Table 1, eq. 10 |
//! | [`geometry`] | the layer's points, transitions `v / cos γ` | eq. 1–5, 7–8 |
//! | [`paper`] | the reference numbers | Tables 1–2 |
//!
//! Every function checks its inputs and returns [`Invalid`] instead of
//! panicking or producing NaN.

pub mod analysis;
pub mod gain;
pub mod geometry;
pub mod invalid;
pub mod law;
pub mod linear;
pub mod paper;
pub mod plant;
pub mod simulate;
pub mod table;

#[cfg(test)]
mod props;
#[cfg(test)]
mod reference;

pub use analysis::{analyse, Analysis, Finding, Severity};
pub use gain::SpeedPerLength;
pub use geometry::{LayerSpec, Ring, RingPoint, SegmentMoves, Transition};
pub use invalid::Invalid;
pub use law::{Clamp, Controller, LoopState, Step, LAW};
pub use linear::LoopGains;
pub use plant::{Deposition, Plant};
pub use simulate::{simulate, Sample, Simulation, Total};
pub use table::{EnergyDensity, SegmentProcess, SegmentTable};
