//! Nozzle direction ↔ rotary axis angles of a tilting head.
//!
//! The direction is `t`, the unit vector from the tool tip back up the nozzle, which
//! is the layer normal of the IR (the beam travels along −t). With every axis at 0
//! the nozzle points straight down (t = +Z).
//!
//! * [`Kinematics::HeadAc`]: A tilts about X, then C turns about Z:
//!   `t = (sinA·sinC, −sinA·cosC, cosA)`.
//! * [`Kinematics::HeadBc`]: B tilts about Y, then C turns about Z:
//!   `t = (sinB·cosC, sinB·sinC, cosB)`.
//!
//! * [`Kinematics::TableAc`], [`Kinematics::TableBc`]: the same angles. With
//!   the ISO directions of a table's axes (a positive angle turns the *tool*
//!   about the part by the right-hand rule, so the table itself turns the
//!   other way, as LinuxCNC's trt kinematics with `conventional-directions`
//!   take them), the nozzle direction in part coordinates is the head's
//!   formula: the table at `(A, C)` presents the part so that `t` points up
//!   ([`super::table`]).
//!
//! Every direction but the vertical one has two families of solutions,
//! `(tilt, C + k·360°)` and `(−tilt, C + 180° + k·360°)`; the vertical one has any C.
//! [`follow`] picks the member closest to where the axes are, so C never jumps
//! further than the direction change forces it to.

use crate::ir::Kinematics;

/// A position of the two rotary axes, deg.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Rotary {
    /// The tilt axis: A for [`Kinematics::HeadAc`], B for [`Kinematics::HeadBc`].
    pub tilt: f64,
    /// The C axis (about Z).
    pub c: f64,
}

/// Tilts below this (deg) count as vertical: C stays where it is. It is half the
/// 0.001° resolution the angles are printed with, so the nozzle direction written
/// is off by less than the printing already allows.
pub const VERTICAL_DEG: f64 = 0.0005;

/// The nozzle direction `t` the axes at `r` give (unit vector). [`Kinematics::Xyz`]
/// always points straight down: `t = +Z`.
pub fn direction(kin: Kinematics, r: Rotary) -> [f64; 3] {
    let (st, ct) = r.tilt.to_radians().sin_cos();
    let (sc, cc) = r.c.to_radians().sin_cos();
    match kin {
        Kinematics::HeadAc | Kinematics::TableAc => [st * sc, -st * cc, ct],
        Kinematics::HeadBc | Kinematics::TableBc => [st * cc, st * sc, ct],
        Kinematics::Xyz => [0.0, 0.0, 1.0],
    }
}

/// Angle between `n` and +Z, deg (0 = nozzle vertical). `n` need not be unit.
pub fn tilt_of(n: [f64; 3]) -> f64 {
    // atan2 rather than acos(nz): accurate near vertical. sqrt rather than hypot:
    // directions cannot overflow, and hypot is several times slower.
    (n[0] * n[0] + n[1] * n[1]).sqrt().atan2(n[2]).to_degrees()
}

/// The principal solution for direction `n`: tilt in `[0°, 180°]`, C in
/// `(−180°, 180°]`, or `None` for C when `n` is vertical (tilt below
/// [`VERTICAL_DEG`]). `n` need not be unit; it must not be zero.
pub fn principal(kin: Kinematics, n: [f64; 3]) -> (f64, Option<f64>) {
    let tilt = tilt_of(n);
    if tilt < VERTICAL_DEG {
        return (0.0, None);
    }
    let c = match kin {
        // sinA·sinC = nx, −sinA·cosC = ny, with sinA > 0.
        Kinematics::HeadAc | Kinematics::TableAc => n[0].atan2(-n[1]),
        // sinB·cosC = nx, sinB·sinC = ny.
        Kinematics::HeadBc | Kinematics::TableBc => n[1].atan2(n[0]),
        Kinematics::Xyz => return (tilt, None),
    };
    (tilt, Some(c.to_degrees()))
}

/// `c + k·360°` closest to `reference`.
pub fn unwrap_near(c: f64, reference: f64) -> f64 {
    c + 360.0 * ((reference - c) / 360.0).round()
}

/// How far the axes move from `a` to `b`, deg: the cost [`follow`] minimises.
fn travel(a: Rotary, b: Rotary) -> f64 {
    (a.tilt - b.tilt).abs() + (a.c - b.c).abs()
}

/// The solution for direction `n` closest to `prev` (the axes' current position):
/// the two families unwrapped next to `prev.c`, the one with less axis travel
/// winning (ties: the positive tilt). Vertical directions keep `prev.c`.
pub fn follow(kin: Kinematics, n: [f64; 3], prev: Rotary) -> Rotary {
    let (tilt, c) = principal(kin, n);
    let Some(c) = c else {
        return Rotary {
            tilt: 0.0,
            c: prev.c,
        };
    };
    let plus = Rotary {
        tilt,
        c: unwrap_near(c, prev.c),
    };
    let minus = Rotary {
        tilt: -tilt,
        c: unwrap_near(c + 180.0, prev.c),
    };
    if travel(prev, minus) < travel(prev, plus) {
        minus
    } else {
        plus
    }
}

/// Like [`follow`], but for a free move (laser off, nozzle retracted) where the
/// axes may take any route: a solution inside `tilt_range` and `c_range` (deg,
/// `[min, max]`) is preferred to a closer one outside, so a C axis with limited
/// travel unwinds between paths instead of running into its stop.
pub fn reposition(
    kin: Kinematics,
    n: [f64; 3],
    prev: Rotary,
    tilt_range: [f64; 2],
    c_range: [f64; 2],
) -> Rotary {
    let near = follow(kin, n, prev);
    let inside = |r: Rotary| {
        r.tilt >= tilt_range[0] && r.tilt <= tilt_range[1] && r.c >= c_range[0] && r.c <= c_range[1]
    };
    if inside(near) {
        return near;
    }
    // Both families, each moved by whole turns into the C range when it can be.
    let (tilt, c) = principal(kin, n);
    let c = c.unwrap_or(prev.c);
    let mut best: Option<Rotary> = None;
    for cand in [
        Rotary { tilt, c },
        Rotary {
            tilt: -tilt,
            c: c + 180.0,
        },
    ] {
        let mut r = Rotary {
            tilt: cand.tilt,
            c: unwrap_near(cand.c, prev.c),
        };
        if r.c < c_range[0] {
            r.c += 360.0 * ((c_range[0] - r.c) / 360.0).ceil();
        } else if r.c > c_range[1] {
            r.c -= 360.0 * ((r.c - c_range[1]) / 360.0).ceil();
        }
        if inside(r) && best.is_none_or(|b| travel(prev, r) < travel(prev, b)) {
            best = Some(r);
        }
    }
    best.unwrap_or(near)
}

/// Where the axes stand over a run of directions followed from a start.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sweep {
    /// The lowest and highest tilt, deg.
    pub tilt: [f64; 2],
    /// The lowest and highest C, deg.
    pub c: [f64; 2],
}

impl Sweep {
    fn at(r: Rotary) -> Self {
        Sweep {
            tilt: [r.tilt; 2],
            c: [r.c; 2],
        }
    }

    fn add(&mut self, r: Rotary) {
        self.tilt = [self.tilt[0].min(r.tilt), self.tilt[1].max(r.tilt)];
        self.c = [self.c[0].min(r.c), self.c[1].max(r.c)];
    }

    /// How far it leaves `tilt_range` and `c_range`, deg (0: inside).
    fn excess(&self, tilt_range: [f64; 2], c_range: [f64; 2]) -> f64 {
        let out = |v: [f64; 2], r: [f64; 2]| (r[0] - v[0]).max(0.0) + (v[1] - r[1]).max(0.0);
        out(self.tilt, tilt_range) + out(self.c, c_range)
    }
}

/// Where [`follow`] takes the axes over `normals` (in order; repeats cost
/// nothing) from `start`.
pub fn sweep(kin: Kinematics, normals: impl Iterator<Item = [f64; 3]>, start: Rotary) -> Sweep {
    let mut s = Sweep::at(start);
    let mut at = start;
    let mut last: Option<[f64; 3]> = None;
    for n in normals {
        if last != Some(n) {
            at = follow(kin, n, at);
            s.add(at);
            last = Some(n);
        }
    }
    s
}

/// The axes a run that must not unwind C (a tilting table's layer: the
/// part turns under the nozzle, and a turn back with the nozzle near the
/// part would sweep it through the part) starts at, for its first
/// direction `normals[0]`: of the two solutions, each moved by whole turns
/// of C, the one closest to `prev` from which [`follow`] keeps every
/// direction of the run inside `tilt_range` and `c_range`; where none
/// does, the one that leaves them least (the verifier reports it).
pub fn run_start<I>(kin: Kinematics, normals: I, prev: Rotary, ranges: [[f64; 2]; 2]) -> Rotary
where
    I: Iterator<Item = [f64; 3]> + Clone,
{
    let [tilt_range, c_range] = ranges;
    let Some(first) = normals.clone().next() else {
        return prev;
    };
    let (tilt, c) = principal(kin, first);
    let families: &[(f64, f64)] = match c {
        Some(c) => &[(tilt, c), (-tilt, c + 180.0)],
        None => &[(0.0, prev.c)],
    };
    let mut best: Option<(f64, f64, Rotary)> = None;
    for &(t, c) in families {
        let c0 = unwrap_near(c, prev.c);
        for k in -2..=2 {
            let start = Rotary {
                tilt: t,
                c: c0 + 360.0 * k as f64,
            };
            let excess = sweep(kin, normals.clone(), start).excess(tilt_range, c_range);
            let key = (excess, travel(prev, start));
            if best.is_none_or(|(e, d, _)| key < (e, d)) {
                best = Some((key.0, key.1, start));
            }
        }
    }
    best.map_or(prev, |b| b.2)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: [f64; 3], b: [f64; 3]) -> bool {
        (0..3).all(|i| (a[i] - b[i]).abs() < 1e-12)
    }

    #[test]
    fn axes_at_zero_point_down() {
        for kin in [Kinematics::HeadAc, Kinematics::HeadBc] {
            assert!(close(direction(kin, Rotary::default()), [0.0, 0.0, 1.0]));
        }
    }

    #[test]
    fn ac_tilts_towards_minus_y_at_c0() {
        let t = direction(Kinematics::HeadAc, Rotary { tilt: 90.0, c: 0.0 });
        assert!(close(t, [0.0, -1.0, 0.0]), "{t:?}");
        let r = follow(Kinematics::HeadAc, [1.0, 0.0, 0.0], Rotary::default());
        assert!(
            (r.tilt - 90.0).abs() < 1e-9 && (r.c - 90.0).abs() < 1e-9,
            "{r:?}"
        );
    }

    #[test]
    fn passing_through_vertical_flips_the_tilt_not_c() {
        let kin = Kinematics::HeadBc;
        let a = follow(kin, [0.1, 0.0, 1.0], Rotary::default());
        assert!(a.tilt > 0.0 && a.c.abs() < 1e-9);
        let b = follow(kin, [0.0, 0.0, 1.0], a);
        assert_eq!(b, Rotary { tilt: 0.0, c: a.c });
        let c = follow(kin, [-0.1, 0.0, 1.0], b);
        assert!(c.tilt < 0.0 && c.c.abs() < 1e-9, "{c:?}");
    }

    #[test]
    fn a_run_starts_where_its_whole_sweep_fits() {
        // A layer whose normals wind once round, from C 300 on: no start
        // of the positive tilt keeps the turn inside −250° … 150° (300 and
        // −60 run past 150, −420 starts below −250), the negative tilt's
        // start at C −240 (the same direction) does.
        let kin = Kinematics::TableAc;
        let normals: Vec<[f64; 3]> = (0..=36)
            .map(|i| {
                let c = (i as f64 * 10.0 + 300.0).to_radians();
                [0.5 * c.sin(), -0.5 * c.cos(), 0.866]
            })
            .collect();
        let prev = Rotary {
            tilt: 30.0,
            c: 300.0,
        };
        let ranges = [[-120.0, 120.0], [-250.0, 150.0]];
        let r = run_start(kin, normals.iter().copied(), prev, ranges);
        let s = sweep(kin, normals.iter().copied(), r);
        assert!(s.c[0] >= -250.0 && s.c[1] <= 150.0, "{r:?} {s:?}");
        let tilt = tilt_of(normals[0]);
        assert!(
            (r.c + 240.0).abs() < 1e-6 && (r.tilt + tilt).abs() < 1e-9,
            "{r:?}"
        );
    }

    #[test]
    fn reposition_unwinds_into_the_c_range() {
        let kin = Kinematics::HeadAc;
        let prev = Rotary {
            tilt: 30.0,
            c: 350.0,
        };
        let r = reposition(
            kin,
            [0.5, 0.0, 0.866],
            prev,
            [-10.0, 120.0],
            [-360.0, 360.0],
        );
        // follow() would go to C 450; 90 is inside the range.
        assert!((r.c - 90.0).abs() < 1e-6, "{r:?}");
        assert!(r.tilt > 0.0);
    }
}
