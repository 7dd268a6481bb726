//! The melt pool's view of a run of deposits: the metal a stretch lays
//! beyond the plan, averaged over a bead width.
//!
//! Metal laid at a point does not stay there: the melt pool, about a bead
//! width long, spreads it. So the layer's height at a place is taken as the
//! mean of what was laid over the bead width around it (a moving average
//! over a window of one bead width), and a place passes the tolerance when
//! that mean lies more than `rise_tolerance` above the plan. This keeps the
//! prediction finite where the model's `1/v` is not (a start from rest) and
//! makes a short ramp count by the metal it lays, not by its peak.
//!
//! The run is cut into cells of a sixteenth of the window, each holding the
//! exact integral of its excess ([`Step::excess`]); the windows are the
//! runs of sixteen cells, slid cell by cell, inside the run (a run shorter
//! than the window is one window). A *place* is a stretch of consecutive
//! windows past the tolerance; its height is its worst window's mean. Long
//! stretches at the programmed speed lay no excess and are skipped whole
//! cells at a time, so the pass costs the moves plus the slow stretches'
//! length over a sixteenth of a bead width.

use crate::diag::message::verify::bump::{Bump, CornerPass, Lies};
use crate::plan::profile::{Dynamics, Step};
use crate::plan::Where;

/// Cells a window is cut into.
const CELLS: usize = 16;

/// What a deposit move carries into the profile.
#[derive(Clone, Copy, Debug)]
pub(super) struct Laid {
    /// Whether it deposits (else it only passes by).
    pub deposit: bool,
    /// What the plan lays along it, mm (the predicted rise, else the
    /// layer height).
    pub rise: f64,
    /// The point whose values it carries.
    pub at: Where,
}

/// A corner a cell holds: the slowest move start in it.
#[derive(Clone, Copy, Debug, Default)]
struct Slowest {
    /// Entry over programmed speed (1: not slowed).
    ratio: f64,
    entry: f64,
    speed: f64,
    /// The corner: the cosine of its turn, and its room for blending.
    cos: f64,
    room: f64,
}

/// A stretch of a run, a sixteenth of the window long (the last shorter).
#[derive(Clone, Copy, Debug)]
struct Cell {
    len: f64,
    /// `∫ (v_p/v − 1) ds` over it, mm.
    excess: f64,
    /// The same weighted by the planned rise, mm².
    metal: f64,
    /// The planned rise times length, mm², for the mean planned rise.
    planned: f64,
    /// How long it runs slower than the tolerance allows, mm.
    slow: f64,
    /// The move that lays most of its excess, how much, and its speed.
    top: (f64, Option<Where>, f64),
    corner: Option<Slowest>,
}

impl Default for Cell {
    fn default() -> Self {
        Cell {
            len: 0.0,
            excess: 0.0,
            metal: 0.0,
            planned: 0.0,
            slow: 0.0,
            top: (0.0, None, 0.0),
            corner: None,
        }
    }
}

/// A place past the tolerance, while its windows last.
#[derive(Clone, Copy, Debug)]
struct Open {
    start: bool,
    worst: Bump,
    length: f64,
    corner: Option<Slowest>,
}

/// Every place past the tolerance, sorted by where it lies.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Places {
    /// How many, and by where they lie.
    pub count: u64,
    /// At a run's start.
    pub starts: u64,
    /// At a run's end.
    pub ends: u64,
    /// Whole short runs.
    pub whole: u64,
    /// Inside runs.
    pub inside: u64,
    /// The worst of all, at a start or end, inside.
    pub worst: Option<Bump>,
    /// The worst at a run's start or end.
    pub worst_end: Option<Bump>,
    /// The worst on a run shorter than the window.
    pub worst_short: Option<Bump>,
    /// The worst inside a run.
    pub worst_inside: Option<Bump>,
}

/// The window sliding along the runs of one plan.
pub(super) struct Pool {
    dynamics: Dynamics,
    tol: f64,
    cell_len: f64,
    /// Inside a run of deposits.
    running: bool,
    /// Cells finished in this run.
    cells: usize,
    cell: Cell,
    ring: [Cell; CELLS],
    next: usize,
    /// Finished cells in a row with no excess.
    quiet: usize,
    open: Option<Open>,
    /// Whether the run's first window is still to come.
    first: bool,
    /// What it found.
    pub places: Places,
}

impl Pool {
    /// A pool a `window` mm long (a bead width) on a machine with
    /// `dynamics`, passing at `tol` above the plan.
    pub fn new(dynamics: Dynamics, window: f64, tol: f64) -> Self {
        Pool {
            dynamics,
            tol,
            cell_len: window / CELLS as f64,
            running: false,
            cells: 0,
            cell: Cell::default(),
            ring: [Cell::default(); CELLS],
            next: 0,
            quiet: CELLS,
            open: None,
            first: true,
            places: Places::default(),
        }
    }

    /// A move as the machine runs it.
    pub fn step(&mut self, s: &Step<Laid>) {
        if !s.data.deposit {
            self.end_run();
            return;
        }
        let inside = self.running;
        if !self.running {
            self.running = true;
            self.cells = 0;
            self.cell = Cell::default();
            self.ring = [Cell::default(); CELLS];
            self.quiet = CELLS;
            self.first = true;
        }
        if inside && s.entry < s.speed {
            // A corner or speed step inside the run: the slowest of its cell.
            let c = Slowest {
                ratio: s.entry / s.speed,
                entry: s.entry,
                speed: s.speed,
                cos: s.corner.cos,
                room: s.corner.room,
            };
            if self.cell.corner.is_none_or(|o| c.ratio < o.ratio) {
                self.cell.corner = Some(c);
            }
        }
        let slow = s.speed / (1.0 + self.tol);
        let (up, down) = s.cruise();
        let mut x = 0.0;
        while x < s.len {
            // At the programmed speed, with nothing in the window: skip
            // whole cells.
            if x >= up && self.quiet >= CELLS && self.cell.excess == 0.0 {
                let room = self.cell_len - self.cell.len;
                let whole = ((down - x - room) / self.cell_len).floor();
                if whole >= 1.0 {
                    self.cells += whole as usize;
                    x += whole * self.cell_len;
                    self.first = false;
                }
            }
            let end = (x + self.cell_len - self.cell.len).min(s.len);
            self.add(s, x, end, slow);
            x = end;
            if self.cell.len >= self.cell_len * (1.0 - 1e-9) {
                self.finish_cell();
            }
        }
    }

    /// The stretch `from..to` of `s` into the current cell.
    fn add(&mut self, s: &Step<Laid>, from: f64, to: f64, slow: f64) {
        let e = s.excess(from, to);
        let c = &mut self.cell;
        c.len += to - from;
        c.excess += e;
        c.metal += e * s.data.rise;
        c.planned += (to - from) * s.data.rise;
        c.slow += s.slower(from, to, slow);
        if e > c.top.0 || c.top.1.is_none() {
            c.top = (e.max(c.top.0), Some(s.data.at), s.speed);
        }
    }

    fn finish_cell(&mut self) {
        let c = std::mem::take(&mut self.cell);
        self.cells += 1;
        self.ring[self.next] = c;
        self.next = (self.next + 1) % CELLS;
        if c.excess > 0.0 {
            self.quiet = 0;
        } else {
            self.quiet = (self.quiet + 1).min(CELLS);
        }
        if self.cells >= CELLS {
            self.window(false);
        }
    }

    /// The run of deposits under way ends.
    pub fn end_run(&mut self) {
        if !self.running {
            return;
        }
        if self.cell.len > 0.0 {
            self.finish_cell();
        }
        if self.cells < CELLS {
            // A run shorter than the window is one window.
            self.window(true);
        }
        if let Some(o) = self.open.take() {
            self.close(o, true);
        }
        self.running = false;
    }

    /// The window of the last cells (all of a short run's): past the
    /// tolerance or not.
    fn window(&mut self, whole: bool) {
        if self.quiet >= CELLS {
            if let Some(o) = self.open.take() {
                self.close(o, false);
            }
            self.first = false;
            return;
        }
        let sum = |f: fn(&Cell) -> f64| self.ring.iter().map(f).sum::<f64>();
        // A window is a bead width long; a run shorter than that is a
        // window of its own length.
        let len = if whole {
            sum(|c| c.len)
        } else {
            self.cell_len * CELLS as f64
        };
        let excess = sum(|c| c.excess);
        let over = len > 0.0 && excess > self.tol * len;
        let start = self.first || whole;
        self.first = false;
        if !over {
            if let Some(o) = self.open.take() {
                self.close(o, false);
            }
            return;
        }
        let (metal, planned) = (sum(|c| c.metal), sum(|c| c.planned));
        let newest = self.ring[(self.next + CELLS - 1) % CELLS];
        let top = self
            .ring
            .iter()
            .filter(|c| c.top.1.is_some())
            .max_by(|a, b| a.top.0.total_cmp(&b.top.0))
            .copied()
            .unwrap_or(newest);
        let bump = Bump {
            at: top.top.1.unwrap_or(Where::End),
            lies: Lies::Inside,
            share: excess / len,
            mm: metal / len,
            planned: planned / sum(|c| c.len).max(f64::MIN_POSITIVE),
            speed: top.top.2,
            length: 0.0,
            slow: top.top.2 / (1.0 + self.tol),
            corner: None,
        };
        let corner = self.ring.iter().filter_map(|c| c.corner).reduce(slower);
        match &mut self.open {
            Some(o) => {
                o.length += newest.slow;
                o.corner = [o.corner, newest.corner]
                    .into_iter()
                    .flatten()
                    .reduce(slower);
                if bump.share > o.worst.share {
                    o.worst = bump;
                }
            }
            None => {
                self.open = Some(Open {
                    start,
                    worst: bump,
                    length: sum(|c| c.slow),
                    corner,
                })
            }
        }
    }

    /// Counts a place whose windows have passed; `end` when the run ends
    /// in it.
    fn close(&mut self, o: Open, end: bool) {
        let lies = match (o.start, end) {
            (true, true) => Lies::Whole,
            (true, false) => Lies::Start,
            (false, true) => Lies::End,
            (false, false) => Lies::Inside,
        };
        let d = self.dynamics;
        let mut b = Bump {
            lies,
            length: o.length,
            corner: o.corner.filter(|c| c.cos < 1.0).map(|c| {
                let turn = c.cos.clamp(-1.0, 1.0).acos();
                CornerPass {
                    turn_deg: turn.to_degrees(),
                    room: c.room,
                    reached: c.entry,
                    speed: c.speed,
                    needs: d.blending_for(c.speed / (1.0 + self.tol), turn),
                    best: Dynamics {
                        blending: c.room,
                        ..d
                    }
                    .corner_speed(turn, 2.0 * c.room, 2.0 * c.room),
                }
            }),
            ..o.worst
        };
        if lies == Lies::Inside {
            if let Some(c) = &b.corner {
                b.slow = c.speed / (1.0 + self.tol);
            }
        }
        let p = &mut self.places;
        p.count += 1;
        let (n, slot) = match lies {
            Lies::Start => (&mut p.starts, &mut p.worst_end),
            Lies::End => (&mut p.ends, &mut p.worst_end),
            Lies::Whole => (&mut p.whole, &mut p.worst_short),
            Lies::Inside => (&mut p.inside, &mut p.worst_inside),
        };
        *n += 1;
        for slot in [slot, &mut p.worst] {
            if slot.is_none_or(|w| b.share > w.share) {
                *slot = Some(b);
            }
        }
    }
}

/// The slower of two corners, by how much each slows the nozzle.
fn slower(a: Slowest, b: Slowest) -> Slowest {
    if b.ratio < a.ratio {
        b
    } else {
        a
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::profile::Profiler;

    const W: f64 = 2.2;
    const TOL: f64 = 0.03;

    /// The places the pool finds along `moves` (direction and length,
    /// speed, deposits), the machine standing before and after.
    fn places(d: Dynamics, moves: &[([f64; 3], f64, bool)]) -> Places {
        let mut profile = Profiler::new(d);
        let mut pool = Pool::new(d, W, TOL);
        for (i, &(delta, v, deposit)) in moves.iter().enumerate() {
            let laid = Laid {
                deposit,
                rise: 0.5,
                at: Where::Point {
                    layer: 0,
                    path: 0,
                    point: i,
                },
            };
            profile.push(delta, v, laid, &mut |s| pool.step(&s));
        }
        profile.stop(&mut |s| pool.step(&s));
        pool.end_run();
        pool.places
    }

    const SLOW: Dynamics = Dynamics {
        accel: 100.0,
        blending: 0.0,
    };

    #[test]
    fn a_ramp_from_rest_lays_its_own_length_again_over_the_window() {
        // 6 mm/s at 100 mm/s²: the ramp is v²/2a = 0.18 mm and lays 0.18 mm
        // of bead more; over a 2.2 mm window, 0.18/2.2 = 8.18 % of the plan.
        let p = places(SLOW, &[([20.0, 0.0, 0.0], 6.0, true)]);
        assert_eq!((p.count, p.starts, p.ends, p.inside), (2, 1, 1, 0));
        let start = p.worst_end.unwrap();
        let want = 0.18 / W;
        assert!((start.share - want).abs() < 1e-9, "{}", start.share);
        assert!((start.mm - 0.5 * want).abs() < 1e-9);
        assert!((start.planned - 0.5).abs() < 1e-9);
        // Slower than 6/1.03 mm/s for (6/1.03)²/2a on each ramp.
        let slow = (6.0f64 / 1.03).powi(2) / 200.0;
        assert!((start.length - slow).abs() < 1e-9, "{}", start.length);
        assert!((start.slow - 6.0 / 1.03).abs() < 1e-12);
        // At 3.6 mm/s the ramp is 0.0648 mm: 2.9 %, within the tolerance.
        let p = places(SLOW, &[([20.0, 0.0, 0.0], 3.6, true)]);
        assert_eq!(p.count, 0);
    }

    #[test]
    fn a_run_shorter_than_the_window_is_one_place() {
        // 1 mm from rest to rest at 6 mm/s: two ramps of 0.18 mm lay 0.36 mm
        // more over the run's own millimetre.
        let p = places(SLOW, &[([1.0, 0.0, 0.0], 6.0, true)]);
        assert_eq!((p.count, p.whole), (1, 1));
        assert!((p.worst.unwrap().share - 0.36).abs() < 1e-9);
    }

    #[test]
    fn a_run_entered_at_speed_lays_no_bump_at_its_start() {
        // A laser-off lead-in of v²/2a before the run: only the end is slow.
        let p = places(
            SLOW,
            &[
                ([0.18, 0.0, 0.0], 6.0, false),
                ([20.0, 0.0, 0.0], 6.0, true),
            ],
        );
        assert_eq!((p.count, p.starts, p.ends), (1, 0, 1));
        // And a lead-out after it: nothing.
        let p = places(
            SLOW,
            &[
                ([0.18, 0.0, 0.0], 6.0, false),
                ([20.0, 0.0, 0.0], 6.0, true),
                ([0.18, 0.0, 0.0], 6.0, false),
            ],
        );
        assert_eq!(p.count, 0);
    }

    #[test]
    fn an_unblended_corner_stops_the_nozzle_and_a_blend_keeps_it_going() {
        let legs = [
            ([0.18, 0.0, 0.0], 6.0, false),
            ([10.0, 0.0, 0.0], 6.0, true),
            ([0.0, 10.0, 0.0], 6.0, true),
            ([0.0, 0.18, 0.0], 6.0, false),
        ];
        // A full stop: 0.18 mm down and 0.18 mm up, 0.36/2.2 = 16.4 %.
        let p = places(SLOW, &legs);
        assert_eq!((p.count, p.inside), (1, 1));
        let b = p.worst_inside.unwrap();
        assert!((b.share - 0.36 / W).abs() < 1e-9, "{}", b.share);
        let c = b.corner.unwrap();
        assert!((c.turn_deg - 90.0).abs() < 1e-6);
        assert_eq!((c.reached, c.speed, c.room), (0.0, 6.0, 5.0));
        // The blending that holds 6/1.03 mm/s there: r = v²/a, d = r·tan 45°.
        assert!((c.needs - (6.0f64 / 1.03).powi(2) / 100.0).abs() < 1e-12);
        // Half a millimetre of blending: √(100·0.5) = 7.07 mm/s > 6, no dip.
        let blended = Dynamics {
            blending: 0.5,
            ..SLOW
        };
        assert_eq!(places(blended, &legs).count, 0);
    }
}
