//! The speed a machine really reaches along its motion plan: a trapezoidal
//! profile under one path acceleration, slowed at every stop and corner.
//!
//! **The model** (docs/ir.md, *The speed the machine reaches*):
//!
//! - The control accelerates and brakes along the path at one rate `a`
//!   (the machine's `acceleration`), never faster than each move's
//!   programmed speed. From rest it reaches `v` after `v²/2a` of path; it
//!   starts braking `(v² − u²)/2a` before a point it must pass at `u`.
//! - It stops where the program makes it stand: where the laser switches
//!   (unless it switches on the fly, on a lead), at a dwell or an output,
//!   and at the program's start and end.
//! - A corner between two moves turning by θ is rounded by an arc tangent to
//!   both, starting `d` before the corner and ending `d` after it, where `d`
//!   is the machine's blending limited to half of each move (KUKA and
//!   LinuxCNC round at most half a segment). The arc's radius is
//!   `r = d / tan(θ/2)`, and the control passes it no faster than the
//!   centripetal limit `v² = a·r` allows, nor faster than either move's
//!   speed. Without blending (`d = 0`) every corner is a full stop; a move
//!   that goes on straight (θ = 0) is no corner at all.
//! - Where two moves' speeds differ, the junction is passed at the lower;
//!   the faster move speeds up after it (or slows down before it).
//! - The control looks ahead as far as it must: every move is planned
//!   knowing the stops and corners within braking distance after it.
//!   Orientation changes, axis limits and jerk are not modelled.
//!
//! [`Profiler`] plans a stream of moves with that model, keeping only the
//! moves within braking distance of the last one (the plan of a 3.6 M-point
//! part is never held); [`Step`] is one planned move with the closed forms
//! the verifier integrates: the metal laid per millimetre grows as `1/v`,
//! so what a stretch lays beyond its programmed speed's share is
//! `∫ (v_p/v − 1) ds` ([`Step::excess`]).

use std::collections::VecDeque;

/// How a machine moves along a path, as the profile models it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dynamics {
    /// Path acceleration and deceleration, mm/s² (> 0).
    pub accel: f64,
    /// How far before a corner the control may leave the path to round it,
    /// mm (0: an exact stop at every corner).
    pub blending: f64,
}

impl Dynamics {
    /// The path it takes to reach `v` from rest (and to stop from `v`):
    /// `v²/2a`, mm.
    pub fn ramp(&self, v: f64) -> f64 {
        v * v / (2.0 * self.accel)
    }

    /// The highest speed a corner turning by `turn` radians between moves
    /// `before` and `after` mm long can be passed at: the centripetal limit
    /// `√(a·r)` of the blend arc, `r = d / tan(θ/2)` with `d` the blending
    /// limited to half of each move. Infinite where the path goes on
    /// straight, 0 where it reverses or is not blended.
    pub fn corner_speed(&self, turn: f64, before: f64, after: f64) -> f64 {
        self.corner_speed_cos(turn.cos(), before, after)
    }

    /// [`Self::corner_speed`] of a turn given by its cosine (the dot product
    /// of the two moves' directions): `tan(θ/2) = √((1 − cos θ)/(1 + cos θ))`
    /// spares the plan's every junction an `acos` and a `tan`.
    fn corner_speed_cos(&self, cos: f64, before: f64, after: f64) -> f64 {
        // 1 − cos θ ≈ θ²/2: a turn below STRAIGHT goes on straight.
        if 1.0 - cos <= 0.5 * STRAIGHT * STRAIGHT {
            return f64::INFINITY;
        }
        let d = self.blending.min(0.5 * before).min(0.5 * after);
        if d <= 0.0 || 1.0 + cos <= 0.5 * STRAIGHT * STRAIGHT {
            return 0.0;
        }
        let tan_half = ((1.0 - cos) / (1.0 + cos)).sqrt();
        (self.accel * d / tan_half).sqrt()
    }

    /// The blending a corner turning by `turn` needs to be passed at `v`:
    /// `d = r·tan(θ/2)` with `r = v²/a`.
    pub fn blending_for(&self, v: f64, turn: f64) -> f64 {
        v * v / self.accel * (0.5 * turn.min(std::f64::consts::PI)).tan()
    }
}

/// A turn below this (radians, about 6·10⁻⁵ degrees) goes on straight: a
/// polyline's rounding noise is no corner.
const STRAIGHT: f64 = 1e-6;

/// The corner a move starts with, for the messages' fixes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Corner {
    /// The cosine of how far the path turns there (1: straight on, or a
    /// stop).
    pub cos: f64,
    /// Half the shorter of the two moves, mm: the most blending the
    /// control can use there.
    pub room: f64,
}

impl Default for Corner {
    fn default() -> Self {
        Corner {
            cos: 1.0,
            room: 0.0,
        }
    }
}

impl Corner {
    /// How far the path turns, radians.
    pub fn turn(&self) -> f64 {
        self.cos.clamp(-1.0, 1.0).acos()
    }
}

/// One move as the machine runs it: its programmed speed and the speeds it
/// enters and leaves with, each no higher than the programmed one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Step<T> {
    /// Its length, mm.
    pub len: f64,
    /// The programmed speed, mm/s.
    pub speed: f64,
    /// The speed at its start and at its end, mm/s.
    pub entry: f64,
    /// The speed at its end.
    pub exit: f64,
    /// The acceleration it was planned with, mm/s².
    pub accel: f64,
    /// The corner at its start.
    pub corner: Corner,
    /// What the caller attached to it.
    pub data: T,
}

impl<T> Step<T> {
    /// The highest speed it reaches: its programmed speed, or the peak of a
    /// move too short to get there.
    pub fn peak(&self) -> f64 {
        let a2 = 2.0 * self.accel;
        let top = (self.entry * self.entry + self.exit * self.exit + a2 * self.len) / 2.0;
        self.speed.min(top.max(0.0).sqrt())
    }

    /// Where it stops speeding up and where it starts slowing down, mm from
    /// its start: between the two it runs at its programmed speed (or
    /// passes its peak, where they meet).
    pub fn cruise(&self) -> (f64, f64) {
        let a2 = 2.0 * self.accel;
        let p2 = self.peak().powi(2);
        let up = ((p2 - self.entry * self.entry) / a2).clamp(0.0, self.len);
        let down = (self.len - (p2 - self.exit * self.exit) / a2).clamp(up, self.len);
        (up, down)
    }

    /// The speed `s` mm from its start.
    pub fn speed_at(&self, s: f64) -> f64 {
        let a2 = 2.0 * self.accel;
        let up = (self.entry * self.entry + a2 * s.max(0.0)).sqrt();
        let down = (self.exit * self.exit + a2 * (self.len - s).max(0.0)).sqrt();
        self.speed.min(up).min(down)
    }

    /// What the stretch `from..to` (mm from its start) lays beyond what it
    /// would at the programmed speed, in millimetres of path at that speed:
    /// `∫ (v_p/v − 1) ds`. Speeding up or slowing down at `a`, `ds = v dv/a`,
    /// so a stretch from `u₀` to `u₁` gives `v_p·|u₁ − u₀|/a − Δs` exactly
    /// (finite even from rest, where `1/v` is not).
    pub fn excess(&self, from: f64, to: f64) -> f64 {
        let (up, down) = self.cruise();
        let mut sum = 0.0;
        let (a, b) = (from.max(0.0), to.min(up));
        if b > a {
            sum += self.speed * (self.speed_at(b) - self.speed_at(a)) / self.accel - (b - a);
        }
        let (a, b) = (from.max(down), to.min(self.len));
        if b > a {
            sum += self.speed * (self.speed_at(a) - self.speed_at(b)) / self.accel - (b - a);
        }
        sum.max(0.0)
    }

    /// How much of `from..to` it runs slower than `below`, mm.
    pub fn slower(&self, from: f64, to: f64, below: f64) -> f64 {
        let a2 = 2.0 * self.accel;
        let (up, down) = self.cruise();
        let mut len = 0.0;
        // Speeding up from the entry, and slowing down to the exit.
        let rising = ((below * below - self.entry * self.entry) / a2).clamp(0.0, up);
        len += (to.min(rising) - from.max(0.0)).max(0.0);
        let falling =
            (self.len - (below * below - self.exit * self.exit) / a2).clamp(down, self.len);
        len += (to.min(self.len) - from.max(falling)).max(0.0);
        // A move that never gets up to `below` runs slower all along.
        if self.peak() < below {
            len = (to.min(self.len) - from.max(0.0)).max(0.0);
        }
        len
    }
}

/// A move waiting for what comes after it to fix its entry speed.
#[derive(Clone, Copy, Debug)]
struct Pending<T> {
    len: f64,
    speed: f64,
    /// The highest speed it can start with: the corner's and the speeds'
    /// limit, and what the moves before let it reach.
    reach: f64,
    /// Its entry speed as planned so far.
    entry: f64,
    corner: Corner,
    data: T,
}

/// The moves buffered past which a plan is made in any case: bounds the
/// memory where moves of no length pile up (every other plan finishes its
/// moves long before).
const MAX_PENDING: usize = 1 << 20;

/// Plans a stream of moves with [`Dynamics`]: each is handed on, as a
/// [`Step`], once the moves after it can no longer change it.
#[derive(Debug)]
pub struct Profiler<T> {
    dynamics: Dynamics,
    pending: VecDeque<Pending<T>>,
    /// Their total length, and the highest programmed speed among them.
    length: f64,
    fastest: f64,
    /// The last move's direction, length and speed (`None` after a stop).
    last: Option<([f64; 3], f64, f64)>,
}

impl<T: Copy> Profiler<T> {
    /// A profiler for a machine with `dynamics`, standing.
    pub fn new(dynamics: Dynamics) -> Self {
        Profiler {
            dynamics,
            pending: VecDeque::new(),
            length: 0.0,
            fastest: 0.0,
            last: None,
        }
    }

    /// The model it plans with.
    pub fn dynamics(&self) -> Dynamics {
        self.dynamics
    }

    /// A move along `delta` (mm) at `speed` mm/s carrying `data`; the moves
    /// it settles go to `out`. A move of no length takes no time and is
    /// dropped.
    pub fn push(&mut self, delta: [f64; 3], speed: f64, data: T, out: &mut impl FnMut(Step<T>)) {
        let len = (delta[0] * delta[0] + delta[1] * delta[1] + delta[2] * delta[2]).sqrt();
        if len.is_nan() || len <= 1e-9 {
            return;
        }
        let dir = delta.map(|c| c / len);
        let speed = speed.max(0.0);
        let (limit, corner) = match self.last {
            None => (0.0, Corner::default()),
            Some((d, before, v)) => {
                let cos = (d[0] * dir[0] + d[1] * dir[1] + d[2] * dir[2]).clamp(-1.0, 1.0);
                let room = 0.5 * before.min(len);
                let c = self.dynamics.corner_speed_cos(cos, before, len);
                (c.min(v).min(speed), Corner { cos, room })
            }
        };
        let reach = match self.pending.back() {
            Some(p) => limit.min((p.reach * p.reach + 2.0 * self.dynamics.accel * p.len).sqrt()),
            None => limit,
        };
        self.last = Some((dir, len, speed));
        self.pending.push_back(Pending {
            len,
            speed,
            reach,
            entry: reach,
            corner,
            data,
        });
        self.length += len;
        self.fastest = self.fastest.max(speed);
        // Plan once the buffer holds twice the braking distance from the
        // fastest speed: the first half is then settled.
        if self.length >= 2.0 * self.dynamics.ramp(self.fastest)
            || self.pending.len() >= MAX_PENDING
        {
            self.plan(false, out);
        }
    }

    /// The machine stops here: every move so far is settled, the last
    /// braking to rest.
    pub fn stop(&mut self, out: &mut impl FnMut(Step<T>)) {
        self.plan(true, out);
        self.last = None;
    }

    /// Plans the buffered moves backwards from rest after the last (where
    /// the stream is cut short, a bound the settled ones do not depend
    /// on), and hands on those settled: all at a `stop`, else those whose
    /// entry no future move can lower — a move is settled once the path
    /// after its start is at least its braking distance long.
    fn plan(&mut self, stop: bool, out: &mut impl FnMut(Step<T>)) {
        let a2 = 2.0 * self.dynamics.accel;
        let mut exit = 0.0f64;
        for p in self.pending.iter_mut().rev() {
            p.entry = p.reach.min((exit * exit + a2 * p.len).sqrt());
            exit = p.entry;
        }
        // How many are settled: their entries and the next one's.
        let mut settled = self.pending.len();
        if !stop {
            let mut after = self.length;
            settled = 0;
            for p in &self.pending {
                if p.reach * p.reach > a2 * after {
                    break;
                }
                after -= p.len;
                settled += 1;
            }
            if settled < 2 && self.pending.len() >= MAX_PENDING {
                // Cut short: the front move leaves at its entry's bound.
                settled = 2;
            }
            // The last settled one waits for its successor's entry.
            settled = settled.saturating_sub(1);
        }
        for _ in 0..settled {
            let Some(p) = self.pending.pop_front() else {
                break;
            };
            let exit = self.pending.front().map_or(0.0, |n| n.entry);
            self.length -= p.len;
            out(Step {
                len: p.len,
                speed: p.speed,
                entry: p.entry,
                exit: exit.min(p.speed),
                accel: self.dynamics.accel,
                corner: p.corner,
                data: p.data,
            });
        }
        if self.pending.is_empty() {
            self.length = 0.0;
            self.fastest = 0.0;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn steps(d: Dynamics, moves: &[([f64; 3], f64)]) -> Vec<Step<usize>> {
        let mut p = Profiler::new(d);
        let mut got = Vec::new();
        for (i, &(delta, v)) in moves.iter().enumerate() {
            p.push(delta, v, i, &mut |s| got.push(s));
        }
        p.stop(&mut |s| got.push(s));
        got
    }

    const D: Dynamics = Dynamics {
        accel: 100.0,
        blending: 0.5,
    };

    #[test]
    fn from_rest_the_nozzle_needs_v2_over_2a_to_reach_its_speed() {
        // 10 mm/s at 100 mm/s²: 100/200 = 0.5 mm up, 0.5 mm down.
        assert_eq!(D.ramp(10.0), 0.5);
        let s = steps(D, &[([20.0, 0.0, 0.0], 10.0)]);
        assert_eq!(s.len(), 1);
        let s = s[0];
        assert_eq!((s.entry, s.exit), (0.0, 0.0));
        assert!((s.speed_at(0.125) - 5.0).abs() < 1e-12, "√(2·100·0.125)");
        assert_eq!(s.speed_at(0.5), 10.0);
        assert_eq!(s.speed_at(10.0), 10.0);
        assert!((s.speed_at(19.875) - 5.0).abs() < 1e-12);
        // Below 5 mm/s for 0.125 mm at each end.
        assert!((s.slower(0.0, 20.0, 5.0) - 0.25).abs() < 1e-12);
        // The metal laid over a ramp from rest: ∫₀^{v²/2a} (v/√(2as) − 1) ds
        // = v·√(2S/a) − S with S = v²/2a, = 2S − S = S: the ramp lays as
        // much again as its own length at speed.
        assert!((s.excess(0.0, 0.5) - 0.5).abs() < 1e-12);
        assert!((s.excess(0.0, 20.0) - 1.0).abs() < 1e-12);
        // Part of the ramp: 0 → 5 mm/s over 0.125 mm lays 10·5/100 − 0.125.
        assert!((s.excess(0.0, 0.125) - 0.375).abs() < 1e-12);
        assert_eq!(s.excess(1.0, 19.0), 0.0);
    }

    #[test]
    fn a_short_move_never_reaches_its_speed() {
        // 0.4 mm from rest to rest at 100 mm/s²: the peak is √(a·L) = √40.
        let s = steps(D, &[([0.0, 0.4, 0.0], 10.0)])[0];
        assert!((s.peak() - 40f64.sqrt()).abs() < 1e-12);
        assert!((s.speed_at(0.2) - 40f64.sqrt()).abs() < 1e-12);
        // It runs below its speed all along.
        assert!((s.slower(0.0, 0.4, 10.0) - 0.4).abs() < 1e-12);
        // ∫ (v_p/v − 1): twice v_p·peak/a − L.
        let want = 2.0 * 10.0 * 40f64.sqrt() / 100.0 - 0.4;
        assert!((s.excess(0.0, 0.4) - want).abs() < 1e-12);
    }

    #[test]
    fn a_corner_is_passed_at_the_centripetal_limit_of_its_blend() {
        // A right angle with 0.5 mm blending: r = 0.5/tan 45° = 0.5 mm,
        // v = √(100·0.5) = √50 ≈ 7.07 mm/s.
        let right = std::f64::consts::FRAC_PI_2;
        assert!((D.corner_speed(right, 10.0, 10.0) - 50f64.sqrt()).abs() < 1e-9);
        // 60° of turn: r = 0.5/tan 30°.
        let r = 0.5 / (30f64).to_radians().tan();
        let sixty = (60f64).to_radians();
        assert!((D.corner_speed(sixty, 10.0, 10.0) - (100.0 * r).sqrt()).abs() < 1e-9);
        // Short moves limit the blend to half of each: 0.3 mm → 0.15 mm.
        assert!((D.corner_speed(right, 0.3, 10.0) - 15f64.sqrt()).abs() < 1e-9);
        // Straight on: no limit; reversing or unblended: a stop.
        assert_eq!(D.corner_speed(0.0, 1.0, 1.0), f64::INFINITY);
        assert_eq!(D.corner_speed(std::f64::consts::PI, 1.0, 1.0), 0.0);
        let exact = Dynamics { blending: 0.0, ..D };
        assert_eq!(exact.corner_speed(right, 10.0, 10.0), 0.0);
        // And back: the blending that holds √50 through the right angle.
        assert!((D.blending_for(50f64.sqrt(), right) - 0.5).abs() < 1e-12);

        // In a plan: two 10 mm legs at 10 mm/s meet at √50.
        let s = steps(D, &[([10.0, 0.0, 0.0], 10.0), ([0.0, 10.0, 0.0], 10.0)]);
        assert!((s[0].exit - 50f64.sqrt()).abs() < 1e-9);
        assert!((s[1].entry - 50f64.sqrt()).abs() < 1e-9);
        assert!((s[1].corner.turn() - right).abs() < 1e-7);
        // The dip lays (v − u)²/2a on each side, in mm at speed:
        // v_p(v_p − u)/a − (v_p² − u²)/2a.
        let u = 50f64.sqrt();
        let side = 10.0 * (10.0 - u) / 100.0 - (100.0 - 50.0) / 200.0;
        assert!((side - (10.0 - u).powi(2) / 200.0).abs() < 1e-12);
        assert!((s[0].excess(9.0, 10.0) - side).abs() < 1e-12);
        assert!((s[1].excess(0.0, 1.0) - side).abs() < 1e-12);
    }

    /// The plan made with every move known: the junctions' limits, a
    /// forward pass and a backward pass from rest after the last.
    fn whole(d: Dynamics, moves: &[([f64; 3], f64)]) -> Vec<f64> {
        let len = |m: &[f64; 3]| (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt();
        let mut reach: Vec<f64> = Vec::new();
        for (i, (m, v)) in moves.iter().enumerate() {
            let limit = match i.checked_sub(1).map(|j| &moves[j]) {
                None => 0.0,
                Some((p, u)) => {
                    let cos = (0..3).map(|k| p[k] * m[k]).sum::<f64>() / (len(p) * len(m));
                    let turn = cos.clamp(-1.0, 1.0).acos();
                    d.corner_speed(turn, len(p), len(m)).min(*u).min(*v)
                }
            };
            let before = i.checked_sub(1).map_or(limit, |j| {
                (reach[j] * reach[j] + 2.0 * d.accel * len(&moves[j].0)).sqrt()
            });
            reach.push(limit.min(before));
        }
        let mut exit = 0.0f64;
        for i in (0..moves.len()).rev() {
            reach[i] = reach[i].min((exit * exit + 2.0 * d.accel * len(&moves[i].0)).sqrt());
            exit = reach[i];
        }
        reach
    }

    #[test]
    fn streaming_plans_what_the_whole_plan_would() {
        // Random walks of short and long moves, turns and speeds.
        let mut next = crate::test_random::uniform(0x2545_f491_4f6c_dd1d);
        for _ in 0..40 {
            let moves: Vec<_> = (0..300)
                .map(|_| {
                    let angle = if next() < 0.7 { 0.0 } else { next() * 6.0 };
                    let l = if next() < 0.8 {
                        0.01 + 0.2 * next()
                    } else {
                        5.0 * next()
                    };
                    ([l * angle.cos(), l * angle.sin(), 0.0], 2.0 + 20.0 * next())
                })
                .collect();
            let streamed = steps(D, &moves);
            let want = whole(D, &moves);
            assert_eq!(streamed.len(), moves.len());
            for (i, s) in streamed.iter().enumerate() {
                assert!(
                    (s.entry - want[i]).abs() < 1e-9,
                    "move {i}: {} vs {}",
                    s.entry,
                    want[i]
                );
                let exit = want.get(i + 1).copied().unwrap_or(0.0);
                assert!((s.exit - exit.min(s.speed)).abs() < 1e-9, "move {i}'s exit");
            }
        }
    }

    #[test]
    fn a_run_of_short_moves_ramps_across_them_and_streams() {
        // 1000 moves of 0.01 mm straight on at 10 mm/s: the ramp of 0.5 mm
        // spans 50 of them; the profile matches the single long move's.
        let moves: Vec<_> = (0..1000).map(|_| ([0.01, 0.0, 0.0], 10.0)).collect();
        let s = steps(D, &moves);
        assert_eq!(s.len(), 1000);
        let whole = steps(D, &[([10.0, 0.0, 0.0], 10.0)])[0];
        let mut at = 0.0;
        let mut excess = 0.0;
        for (i, st) in s.iter().enumerate() {
            assert_eq!(st.data, i, "in order");
            assert!((st.entry - whole.speed_at(at)).abs() < 1e-9, "move {i}");
            excess += st.excess(0.0, st.len);
            at += st.len;
        }
        assert!((excess - 1.0).abs() < 1e-9);
        // A speed change: the slower move's junction; the faster speeds up after.
        let s = steps(D, &[([5.0, 0.0, 0.0], 6.0), ([5.0, 0.0, 0.0], 8.0)]);
        assert_eq!(s[0].exit, 6.0);
        assert_eq!(s[1].entry, 6.0);
        assert!(
            (s[1].excess(0.0, 5.0) - (8.0 - 6.0f64).powi(2) / 200.0 - 8.0 * 8.0 / 200.0).abs()
                < 1e-12
        );
    }
}
