//! A tilting table's kinematics: where the machine's linear axes put the
//! nozzle for a point of the part, with the table at given angles.
//!
//! The part sits on the C table, which turns about its axis (parallel to Z
//! at tilt 0) through [`RotaryTable::c_axis`]; the C table sits on the trunnion,
//! which tilts about its axis (X for A, Y for B) through
//! [`RotaryTable::tilt_axis`]. The nozzle does not turn. A point `w` of the part
//! (in machine coordinates with every rotary axis at 0: the program's point
//! plus the placement's origin) is brought under the nozzle at
//!
//! ```text
//! q = c + Rz(−C)·(w − c)          (the C table turns the part)
//! M = p + Rt(−T)·(q − p)          (the trunnion tilts the C table)
//! ```
//!
//! with `c`, `p` the two axes' points, `T` the tilt angle and `Rt` the turn
//! about X (A) or Y (B). The angles' signs are ISO's for a table (a positive
//! angle turns the tool about the part by the right-hand rule, the table
//! the other way round), as LinuxCNC's `xyzac-trt-kins` / `xyzbc-trt-kins`
//! compute them with `conventional-directions` set: `x/y/z-rot-point` is
//! `c`, and its `x/y/z-offset` is `p − c`. So the nozzle direction in the
//! part is [`super::kinematics::direction`]'s, the head's formula.

use super::kinematics::Rotary;
use crate::ir::{Cnc, Kinematics, RotaryTable, TableOutput};

/// `v` turned by `deg` about axis `axis` (0 X, 1 Y, 2 Z), right-handed.
fn turn(v: [f64; 3], axis: usize, deg: f64) -> [f64; 3] {
    let (s, c) = deg.to_radians().sin_cos();
    let [x, y, z] = v;
    match axis {
        0 => [x, c * y - s * z, s * y + c * z],
        1 => [c * x + s * z, y, -s * x + c * z],
        _ => [c * x - s * y, s * x + c * y, z],
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// The axis (0 X, 1 Y) the table of `kin` tilts about.
fn tilt_axis(kin: Kinematics) -> usize {
    if kin == Kinematics::TableBc {
        1
    } else {
        0
    }
}

/// Inverse kinematics: the machine's X Y Z that bring the part's point `w`
/// (machine coordinates at every rotary axis 0) under the nozzle with the
/// table at `r`.
pub fn machine_point(kin: Kinematics, t: &RotaryTable, w: [f64; 3], r: Rotary) -> [f64; 3] {
    let q = add(t.c_axis, turn(sub(w, t.c_axis), 2, -r.c));
    add(
        t.tilt_axis,
        turn(sub(q, t.tilt_axis), tilt_axis(kin), -r.tilt),
    )
}

/// Forward kinematics: the point of the part (machine coordinates at every
/// rotary axis 0) under the nozzle when the linear axes are at `m` and the
/// table at `r`.
pub fn part_point(kin: Kinematics, t: &RotaryTable, m: [f64; 3], r: Rotary) -> [f64; 3] {
    let q = add(
        t.tilt_axis,
        turn(sub(m, t.tilt_axis), tilt_axis(kin), r.tilt),
    );
    add(t.c_axis, turn(sub(q, t.c_axis), 2, r.c))
}

/// A program point `to` (part coordinates) in machine coordinates, both
/// under the placement's `origin`: what the machine's axes reach is the
/// result plus `origin`, as for a head's positions.
pub fn written(
    kin: Kinematics,
    t: &RotaryTable,
    origin: [f64; 3],
    to: [f64; 3],
    r: Rotary,
) -> [f64; 3] {
    sub(machine_point(kin, t, add(to, origin), r), origin)
}

/// The table of `cnc` when its program is written in machine coordinates
/// ([`TableOutput::Machine`]).
pub fn machine_output(cnc: &Cnc) -> Option<RotaryTable> {
    cnc.table
        .filter(|t| t.output == TableOutput::Machine && cnc.effective_kinematics().is_table())
}

/// Below this (mm) a machine chord counts as no linear motion: the control
/// reads F as the rotary axes' speed (deg/min), as LinuxCNC and the ISO
/// controls do for a move of rotary axes alone.
pub const NO_LINEAR_MM: f64 = 1e-3;

/// How a feed move of a table in machine coordinates is timed and written.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MachineFeed {
    /// The move's time, s: the part-frame length at the path speed (the
    /// deposit's speed is the part's), or the machine chord at it where the
    /// part-frame length is nil (the table turns the part under a point).
    pub time: f64,
    /// The speed to write as F, per second: the machine chord's, mm/s, or,
    /// with no linear motion, the rotary axes' combined speed, deg/s.
    pub speed: f64,
}

/// The time and F of a feed move at path speed `v` (mm/s) that goes `part`
/// mm on the part, `chord` mm in machine X Y Z and turns the rotary axes by
/// `(d_tilt, d_c)` degrees.
pub fn machine_feed(v: f64, part: f64, chord: f64, (d_tilt, d_c): (f64, f64)) -> MachineFeed {
    let turn = (d_tilt * d_tilt + d_c * d_c).sqrt();
    let length = if part >= NO_LINEAR_MM { part } else { chord };
    let time = length / v;
    let travel = if chord >= NO_LINEAR_MM { chord } else { turn };
    // Nothing moves (a repeated point): any F does; the path speed reads best.
    let speed = if time > 0.0 && travel > 1e-9 {
        travel / time
    } else {
        v
    };
    MachineFeed { time, speed }
}

/// The distance between two points, mm.
pub fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    let d = sub(a, b);
    (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
}

#[cfg(test)]
mod tests {
    use super::super::kinematics::direction;
    use super::*;
    use proptest::prelude::*;

    fn table() -> RotaryTable {
        RotaryTable {
            c_axis: [12.0, -7.0, 30.0],
            tilt_axis: [0.0, -20.0, 95.0],
            output: Default::default(),
        }
    }

    proptest! {
        /// Forward after inverse is the identity, for either table, at any
        /// angles and any point within a metre.
        #[test]
        fn forward_inverts_inverse(
            w in prop::array::uniform3(-1000.0f64..1000.0),
            tilt in -180.0f64..180.0,
            c in -720.0f64..720.0,
            bc in any::<bool>(),
        ) {
            let kin = if bc { Kinematics::TableBc } else { Kinematics::TableAc };
            let r = Rotary { tilt, c };
            let m = machine_point(kin, &table(), w, r);
            let back = part_point(kin, &table(), m, r);
            for i in 0..3 {
                prop_assert!((back[i] - w[i]).abs() < 1e-9, "{back:?} vs {w:?}");
            }
        }

        /// The table at the angles [`direction`] gives for a normal turns
        /// that normal straight up: the nozzle (vertical) points along it.
        #[test]
        fn the_solved_angles_turn_the_normal_up(
            tilt in -120.0f64..120.0,
            c in -360.0f64..360.0,
            bc in any::<bool>(),
        ) {
            let kin = if bc { Kinematics::TableBc } else { Kinematics::TableAc };
            let r = Rotary { tilt, c };
            let n = direction(kin, r);
            // A direction turns like the difference of two points.
            let t = table();
            let o = machine_point(kin, &t, [0.0; 3], r);
            let m = machine_point(kin, &t, n, r);
            let up = sub(m, o);
            prop_assert!(up[0].abs() < 1e-9 && up[1].abs() < 1e-9, "{up:?}");
            prop_assert!((up[2] - 1.0).abs() < 1e-9, "{up:?}");
        }
    }

    #[test]
    fn a_at_90_stands_the_part_up_towards_minus_y() {
        // Axes through the origin. At A 90 C 0 the head's formula gives
        // t = (0, −1, 0): the part's −Y points up the nozzle, so its +Y
        // goes down.
        let t = RotaryTable::default();
        let r = Rotary { tilt: 90.0, c: 0.0 };
        let m = machine_point(Kinematics::TableAc, &t, [0.0, 1.0, 0.0], r);
        assert!((m[2] + 1.0).abs() < 1e-12 && m[1].abs() < 1e-12, "{m:?}");
    }
}
