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

/// The line that sets a declared corner blending of `{mm}` on a profile's
/// control, if lmdc knows one: LinuxCNC's `G64 P` (a path tolerance: a
/// blend that starts `d` before a corner of turn θ leaves the path by
/// `d·tan(θ/4) ≤ d`, so the control rounds at least as much as declared)
/// and Sinumerik's `G641 ADIS=` (the rounding distance itself).
pub fn blending_line(profile: &str) -> Option<&'static str> {
    match profile {
        "linuxcnc" => Some("G64 P{mm}"),
        "sinumerik840d" => Some("G641 ADIS={mm}"),
        _ => None,
    }
}

/// Whether a dialect's laser lines switch while the machine moves on, so a
/// lead-in brings the nozzle through the switch at speed: LinuxCNC's
/// `M62 P…`/`M63 P…` switch a motion-synchronised output at the start of
/// the next move. Spindle words (`M3`/`M5`) and the other controls' lines
/// are taken to wait for the motion to stop, as LinuxCNC's `M3`/`M5` do.
pub fn laser_on_the_fly(d: &Dialect) -> bool {
    let word = |line: &str, m: &str| line.split_whitespace().next() == Some(m);
    d.profile == "linuxcnc" && word(&d.laser_on, "M62") && word(&d.laser_off, "M63")
}

/// The blending a program's preamble sets up, mm: LinuxCNC's `G64 P…` or
/// Sinumerik's `ADIS=…`, the last one written; `None` when it sets none.
pub fn preamble_blending(preamble: &[String]) -> Option<f64> {
    let mut found = None;
    for line in preamble {
        let mut words = line.split_whitespace().peekable();
        while let Some(w) = words.next() {
            let value = match w {
                "G64" => words.peek().and_then(|p| p.strip_prefix('P')),
                _ => w.strip_prefix("ADIS="),
            };
            if let Some(v) = value.and_then(|v| v.parse::<f64>().ok()) {
                found = Some(v.max(0.0));
            }
        }
    }
    found
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_built_in_preambles_say_which_blending_they_set() {
        let preamble = |p: &str| profile(p).unwrap().preamble;
        assert_eq!(preamble_blending(&preamble("linuxcnc")), Some(0.02));
        assert_eq!(preamble_blending(&preamble("sinumerik840d")), None);
        let lines = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<Vec<_>>();
        assert_eq!(
            preamble_blending(&lines(&["G64 P0.1", "G642 ADIS=0.3"])),
            Some(0.3)
        );
        assert_eq!(preamble_blending(&lines(&["G64"])), None);
    }

    #[test]
    fn only_motion_synchronised_outputs_switch_on_the_fly() {
        let mut d = profile("linuxcnc").unwrap();
        assert!(!laser_on_the_fly(&d), "M3/M5 wait for the motion");
        d.laser_on = "M62 P0".into();
        d.laser_off = "M63 P0".into();
        assert!(laser_on_the_fly(&d));
        d.profile = "sinumerik840d".into();
        assert!(!laser_on_the_fly(&d));
    }
}
