//! G-code controls as lmdc writes for them: the built-in dialect profiles (data
//! the one G-code back end renders; a machine block can override any of their
//! lines) and the resolution numbers are written at.

use crate::ir::{CommentStyle, Dialect, FeedUnit};

/// Decimals of X Y Z (mm) and of the rotary angles (deg).
pub const POS_DECIMALS: usize = 3;
/// Most decimals of F (trailing zeros dropped): 0.1 mm/min, or 0.01 where F is
/// in mm/s (0.1 mm/s would be 1–2 % of a typical scan speed).
pub fn f_decimals(feed: FeedUnit) -> usize {
    match feed {
        FeedUnit::MmPerMin => 1,
        FeedUnit::MmPerS => 2,
    }
}

/// Decimals of an analog output's value (a fraction of full scale), as the
/// powder feed rate is written: 1/10⁴, like KUKA's `$ANOUT`.
pub const RATE_DECIMALS: usize = 4;

/// Highest analog input `M66 E<n>` reads on LinuxCNC (`motion.analog-in-63`:
/// the motion module has at most 64, `num_aio`).
pub const MAX_ANALOG_INPUT: usize = 63;

/// The profile that runs a height loop on the machine: LinuxCNC's O-word
/// subroutines, named parameters and `M66` analog reads. The other
/// dialects' controls have equivalents (Sinumerik's `$A_INA`, Fagor's
/// `$(PLCR…)`) that lmdc does not write.
pub const LOOP_PROFILE: &str = "linuxcnc";

/// Profile names.
pub const PROFILES: &[&str] = &["linuxcnc", "fagor8070", "sinumerik840d", "m20"];

/// The profile called `name`.
pub fn profile(name: &str) -> Option<Dialect> {
    let lines = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    Some(match name {
        // LinuxCNC: M3/M5 switch the laser (spindle) and S is the power in W; tool-tip
        // control comes from the machine's kinematics module (e.g. xyzac-trt-kins),
        // not from a G-code.
        "linuxcnc" => Dialect {
            profile: name.into(),
            laser_on: "M3".into(),
            laser_off: "M5".into(),
            s_per_watt: 1.0,
            s_decimals: 0,
            preamble: lines(&["G21 G90 G94 G17", "G64 P0.02"]),
            postamble: lines(&["M5", "M2"]),
            dwell: "G4 P{s}".into(),
            tcp_on: String::new(),
            tcp_off: String::new(),
            comment: CommentStyle::Parens,
            padded_g: false,
            extension: "ngc".into(),
            feed: FeedUnit::MmPerMin,
        },
        "fagor8070" => Dialect {
            profile: name.into(),
            laser_on: "M3".into(),
            laser_off: "M5".into(),
            s_per_watt: 1.0,
            s_decimals: 0,
            preamble: lines(&["G71 G90 G94 G17"]),
            postamble: lines(&["M5", "M30"]),
            dwell: "G4 K{s}".into(),
            tcp_on: "#RTCP ON".into(),
            tcp_off: "#RTCP OFF".into(),
            comment: CommentStyle::Semicolon,
            padded_g: false,
            extension: "nc".into(),
            feed: FeedUnit::MmPerMin,
        },
        "sinumerik840d" => Dialect {
            profile: name.into(),
            laser_on: "M3".into(),
            laser_off: "M5".into(),
            s_per_watt: 1.0,
            s_decimals: 0,
            preamble: lines(&["G71 G90 G94 G17"]),
            postamble: lines(&["M5", "M30"]),
            dwell: "G4 F{s}".into(),
            tcp_on: "TRAORI".into(),
            tcp_off: "TRAFOOF".into(),
            comment: CommentStyle::Semicolon,
            padded_g: false,
            extension: "mpf".into(),
            feed: FeedUnit::MmPerMin,
        },
        // The dialect of seed 002's cell: M20 laser on, M21 off, S in W, F in mm/s.
        "m20" => Dialect {
            profile: name.into(),
            laser_on: "M20".into(),
            laser_off: "M21".into(),
            s_per_watt: 1.0,
            s_decimals: 0,
            // No feed mode: the control reads F in mm/s, and G94 (feed per minute on
            // ISO controls) would say otherwise.
            preamble: lines(&["G21 G90"]),
            postamble: lines(&["M21", "M30"]),
            dwell: "G04 P{s}".into(),
            tcp_on: String::new(),
            tcp_off: String::new(),
            comment: CommentStyle::Semicolon,
            padded_g: true,
            extension: "nc".into(),
            feed: FeedUnit::MmPerS,
        },
        _ => return None,
    })
}
