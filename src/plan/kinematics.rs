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

/// An angle within this of an axis's limit (deg) is at the limit: half the
/// 0.001° the programs print angles with, so a tilt computed as
/// −30.0000001° against a stop at −30° is written as −30.000 and kept.
pub const LIMIT_TOL_DEG: f64 = 0.0005;

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

    /// How far it leaves `tilt_range` and `c_range`, deg (0: inside, an
    /// angle within [`LIMIT_TOL_DEG`] of a limit counting as at it).
    pub fn excess(&self, tilt_range: [f64; 2], c_range: [f64; 2]) -> f64 {
        let out = |v: [f64; 2], r: [f64; 2]| {
            (r[0] - v[0] - LIMIT_TOL_DEG).max(0.0) + (v[1] - r[1] - LIMIT_TOL_DEG).max(0.0)
        };
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

/// The axes a run that must not unwind C starts at, for its first
/// direction `normals[0]`: a tilting table's layer (the part turns under
/// the nozzle, and a turn back with the nozzle near the part would sweep
/// it through the part), or a head's paths from one retract to the next
/// (it unwinds only there, the laser off). Of the two solutions, each moved
/// by whole turns of C, the one from which [`follow`] keeps every
/// direction of the run inside `tilt_range` and `c_range` (inclusive, to
/// [`LIMIT_TOL_DEG`]); on a table, of those, one on the branch `prev` is
/// on (the sign of its tilt: a change of branch swings the part through
/// level to the other side, so it happens only where the run needs it); of
/// those, the nearest `prev` (the least axis travel). A head takes the
/// nearest of those that fit, either branch: where a run starts across
/// the vertical from where the last ended (a track back over a shaft's
/// crown) the head swings its tilt through vertical, retracted, rather
/// than turn C half a turn, which wound a repair's C by a turn every few
/// tracks. Where none fits, the one that leaves them least (the verifier
/// reports it).
pub fn run_start<I>(kin: Kinematics, normals: I, prev: Rotary, ranges: [[f64; 2]; 2]) -> Rotary
where
    I: Iterator<Item = [f64; 3]> + Clone,
{
    let Some(first) = normals.clone().next() else {
        return prev;
    };
    let (tilt, c) = principal(kin, first);
    let families: &[(f64, f64)] = match c {
        Some(c) => &[(tilt, c), (-tilt, c + 180.0)],
        None => &[(0.0, prev.c)],
    };
    let mut best: Option<((f64, bool, f64), Rotary)> = None;
    for &(t, c) in families {
        let start = Rotary {
            tilt: t,
            c: unwrap_near(c, prev.c),
        };
        let (excess, start) = fit_turns(sweep(kin, normals.clone(), start), start, ranges);
        let key = (
            excess,
            kin.is_table() && flips(prev, start),
            travel(prev, start),
        );
        if best.is_none_or(|(b, _)| key < b) {
            best = Some((key, start));
        }
    }
    best.map_or(prev, |b| b.1)
}

/// `start` moved by the whole turns of C that keep its run's `sweep`
/// (followed from `start`) inside `ranges` (tilt, C) and turn it least,
/// and by how much the run then leaves them (0: inside). Following a run
/// from a start a whole turn on turns C the same way a whole turn on, so
/// one sweep gives every start's: the turns that fit form an interval.
fn fit_turns(sweep: Sweep, start: Rotary, [tilt_range, c_range]: [[f64; 2]; 2]) -> (f64, Rotary) {
    let tilt_excess = Sweep {
        tilt: sweep.tilt,
        c: c_range,
    }
    .excess(tilt_range, c_range);
    let (lo, hi) = (sweep.c[0] - start.c, sweep.c[1] - start.c);
    let at = |k: f64| Rotary {
        tilt: start.tilt,
        c: start.c + 360.0 * k,
    };
    let c_excess = |k: f64| {
        Sweep {
            tilt: tilt_range,
            c: [at(k).c + lo, at(k).c + hi],
        }
        .excess(tilt_range, c_range)
    };
    let k_min = ((c_range[0] - LIMIT_TOL_DEG - lo - start.c) / 360.0).ceil();
    let k_max = ((c_range[1] + LIMIT_TOL_DEG - hi - start.c) / 360.0).floor();
    if k_min <= k_max {
        let k = 0.0f64.clamp(k_min, k_max);
        return (tilt_excess, at(k));
    }
    // Wider than C's travel: centred on it, as near as whole turns allow.
    let centre = ((c_range[0] + c_range[1] - lo - hi) / 2.0 - start.c) / 360.0;
    let k = [centre.floor(), centre.ceil()]
        .into_iter()
        .min_by(|a, b| {
            c_excess(*a)
                .total_cmp(&c_excess(*b))
                .then(a.abs().total_cmp(&b.abs()))
        })
        .unwrap_or(0.0);
    (tilt_excess + c_excess(k), at(k))
}

/// Whether the axes change branch from `a` to `b`: both tilted, to
/// opposite sides.
pub fn flips(a: Rotary, b: Rotary) -> bool {
    a.tilt.abs() >= VERTICAL_DEG && b.tilt.abs() >= VERTICAL_DEG && (a.tilt > 0.0) != (b.tilt > 0.0)
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

    /// A layer winding once round at a tilt of 30°, as a cone's with the
    /// nozzle along its wall.
    fn winding(from_c: f64) -> Vec<[f64; 3]> {
        (0..=36)
            .map(|i| {
                let c = (i as f64 * 10.0 + from_c).to_radians();
                [0.5 * c.sin(), -0.5 * c.cos(), 0.75f64.sqrt()]
            })
            .collect()
    }

    #[test]
    fn a_run_keeps_the_branch_the_last_one_took() {
        // The last layer ended at C 370 with A +30; this one winds from
        // C 10 through a whole turn. Inside C's ±360° it can start at
        // C −350 with A +30 (720° of C back), or on the other branch at
        // C −170 with A −30 (540° of C and 60° of A: nearer). The branch
        // is kept.
        let kin = Kinematics::TableAc;
        let normals = winding(10.0);
        let prev = Rotary {
            tilt: 30.0,
            c: 370.0,
        };
        let ranges = [[-30.0, 120.0], [-360.0, 360.0]];
        let r = run_start(kin, normals.iter().copied(), prev, ranges);
        assert!(
            (r.tilt - 30.0).abs() < 1e-9 && (r.c + 350.0).abs() < 1e-6,
            "{r:?}"
        );
        // Where the branch cannot fit (A stops at 0 on the plus side), the
        // run changes branch.
        let r = run_start(
            kin,
            normals.iter().copied(),
            prev,
            [[-30.0, 0.0], ranges[1]],
        );
        assert!(r.tilt < 0.0 && flips(prev, r), "{r:?}");
    }

    #[test]
    fn a_head_swings_its_tilt_through_vertical_rather_than_turn_c_half_a_turn() {
        // A track back over a shaft's crown (its axis along x): the last
        // run ended leaning 12° to −y (A +12, C 0); this one starts leaning
        // 12° to +y. A head swings A to −12 with C where it is (24° of A);
        // a table keeps its branch and turns C half a turn instead.
        let (s, c) = 12f64.to_radians().sin_cos();
        let normals = [[0.0, s, c], [0.0, 0.5 * s, 1.0]];
        let prev = Rotary { tilt: 12.0, c: 0.0 };
        let ranges = [[-90.0, 90.0], [-720.0, 720.0]];
        let head = run_start(Kinematics::HeadAc, normals.into_iter(), prev, ranges);
        assert!(
            (head.tilt + 12.0).abs() < 1e-9 && head.c.abs() < 1e-9,
            "{head:?}"
        );
        let table = run_start(Kinematics::TableAc, normals.into_iter(), prev, ranges);
        assert!(
            (table.tilt - 12.0).abs() < 1e-9 && (table.c.abs() - 180.0).abs() < 1e-9,
            "{table:?}"
        );
    }

    #[test]
    fn a_limit_is_reachable_to_the_printed_digit() {
        // A tilt a float's noise past the stop (−30.0000001°) is at it;
        // 0.001° past it is not.
        let kin = Kinematics::TableAc;
        let normals = winding(190.0);
        // The other branch of the first direction (C 190 at A +30).
        let prev = Rotary {
            tilt: -30.0,
            c: 10.0,
        };
        let s = sweep(kin, normals.iter().copied(), prev);
        let at = |lo: f64| s.excess([lo, 120.0], [-720.0, 720.0]);
        assert_eq!(at(-30.0 + 1e-7), 0.0);
        assert!(at(-30.0 + 1e-3) > 0.0);
        let ranges = [[-30.0 + 1e-7, 0.0], [-720.0, 720.0]];
        let r = run_start(kin, normals.iter().copied(), prev, ranges);
        assert!((r.tilt + 30.0).abs() < 1e-6, "{r:?}");
    }
}
