//! Seed 004's reference data (Shen et al. 2018, Tables 1 and 2 and §4), for
//! tests, examples and `lmdc simulate`'s default plant. The paper does not give
//! the ring's radius; [`RADIUS_MM`] is our choice.

use super::gain::SpeedPerLength;
use super::invalid::Invalid;
use super::law::{Clamp, Controller};
use super::table::{SegmentProcess, SegmentTable};
use crate::units::{Angle, Length, Power, Speed};

/// Table 1: defocus per segment, mm.
pub const DEFOCUS_MM: [f64; 10] = [-8.0, -7.0, -6.0, -5.0, -4.0, -4.0, -5.0, -6.0, -7.0, -8.0];
/// Table 1: laser power per segment, W.
pub const POWER_W: [f64; 10] = [
    1200.0, 1050.0, 920.0, 780.0, 650.0, 650.0, 780.0, 920.0, 1050.0, 1200.0,
];
/// Table 1: expected width per segment, mm.
pub const WIDTH_MM: [f64; 10] = [6.25, 5.55, 4.65, 3.50, 2.50, 2.50, 3.50, 4.65, 5.55, 6.25];
/// Table 1: starting scan speed per segment, mm/s.
pub const SPEED_MM_S: [f64; 10] = [4.0, 5.0, 6.0, 11.0, 13.0, 13.0, 11.0, 6.0, 5.0, 4.0];
/// Table 2: each segment's final scan speed, mm/s.
pub const FINAL_SPEED_MM_S: [f64; 10] = [
    3.6168, 4.4244, 6.2956, 11.7625, 16.975, 13.9186, 9.37676, 5.58236, 4.26298, 4.0073,
];
/// Table 2: each segment's built height, mm (target 29.90).
pub const TOTAL_MM: [f64; 10] = [
    29.1009, 29.5128, 29.9076, 29.9621, 29.1515, 28.9230, 29.1553, 29.8236, 29.8743, 29.6005,
];
/// The target height per layer, mm.
pub const TARGET_MM: f64 = 0.23;
/// The number of layers.
pub const LAYERS: usize = 130;
/// The gains as printed, "s⁻¹": right only when read as (m/s)/mm.
pub const KP_PRINTED: f64 = -0.00300;
/// The gains as printed, "s⁻¹": right only when read as (m/s)/mm.
pub const KI_PRINTED: f64 = -0.00035;
/// The speed clamp, mm/s.
pub const CLAMP_MM_S: [f64; 2] = [1.9, 20.0];
/// The transition at the end of each segment, degrees.
pub const TRANSITION_DEG: f64 = 2.0;
/// Our ring radius: not in the paper. 40 mm makes 25 mm segments, ten bead
/// widths or more each, and a 1.4 mm transition arc.
pub const RADIUS_MM: f64 = 40.0;

/// Table 1 as a checked table.
pub fn table1() -> Result<SegmentTable, Invalid> {
    SegmentTable::new(
        (0..10)
            .map(|j| SegmentProcess {
                defocus: Length(DEFOCUS_MM[j]),
                power: Power::from_watts(POWER_W[j]),
                width: Length(WIDTH_MM[j]),
                speed: Speed(SPEED_MM_S[j]),
            })
            .collect(),
    )
}

/// The transition angle.
pub fn transition() -> Angle {
    Angle::from_deg(TRANSITION_DEG)
}

/// The paper's loop with its gains read as (m/s)/mm: −3 and −0.35 (mm/s)/mm.
pub fn controller() -> Result<Controller, Invalid> {
    controller_with(
        SpeedPerLength::from_m_s_per_mm(KP_PRINTED),
        SpeedPerLength::from_m_s_per_mm(KI_PRINTED),
    )
}

/// The paper's loop with other gains (e.g. as printed, per (mm/s)/mm).
pub fn controller_with(kp: SpeedPerLength, ki: SpeedPerLength) -> Result<Controller, Invalid> {
    Controller::new(
        kp,
        ki,
        Length(TARGET_MM),
        Clamp::new(Speed(CLAMP_MM_S[0]), Speed(CLAMP_MM_S[1]))?,
    )
}
