//! KUKA KR C4/C5 controllers (KSS 8.x) as lmdc writes for them.

/// Longest KRL name (module, DEF and DEFDAT names).
pub const MAX_NAME: usize = 24;

/// Highest `$VEL.CP` a KUKA controller accepts (its `$VEL_MA.CP` is at most
/// 3 m/s), mm/s.
pub const VEL_CP_MAX: f64 = 3000.0;

/// Decimals of X Y Z (mm) and A B C (deg) in a `LIN`.
pub const POS_DECIMALS: usize = 3;
/// Decimals of `$VEL.CP` (m/s): 0.001 mm/s.
pub const VEL_DECIMALS: usize = 6;
/// Decimals of `$ANOUT` (fraction of full scale).
pub const ANOUT_DECIMALS: usize = 4;

/// `$APO.CDIS` lmdc writes when a robot declares no `blending`, mm: small
/// against a bead width, large enough that the controller keeps the path
/// speed over millimetre-spaced points.
pub const APO_CDIS_MM: f64 = 0.2;

/// KRL keywords a name made of the part and machine could collide with.
pub const RESERVED: &[&str] = &[
    "C_DIS", "C_ORI", "C_PTP", "C_VEL", "C_SPL", "WAIT_SEC", "SPTP_REL", "SLIN_REL",
];

/// Highest analog input `$ANIN[n]` of a KR C4/C5 (`$ANIN[1]` … `$ANIN[32]`).
pub const MAX_ANIN: usize = 32;

/// The most motions KRL's advance run reads ahead of the robot (`$ADVANCE`
/// is 0 to 5; lmdc's main template sets 3, a user's template may set more):
/// what a ring's loop timing is checked against.
pub const MAX_ADVANCE: usize = 5;
