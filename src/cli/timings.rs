//! `--timings`: wall time and peak heap memory of each stage, measured with a
//! counting global allocator.

use lmdc::pipeline::Observer;
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};
use std::time::Instant;

/// The system allocator, counting live and peak bytes.
pub struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        let p = System.alloc(l);
        if !p.is_null() {
            let now = LIVE.fetch_add(l.size(), Relaxed) + l.size();
            PEAK.fetch_max(now, Relaxed);
        }
        p
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        System.dealloc(p, l);
        LIVE.fetch_sub(l.size(), Relaxed);
    }
    unsafe fn realloc(&self, p: *mut u8, l: Layout, new: usize) -> *mut u8 {
        let q = System.realloc(p, l, new);
        if !q.is_null() {
            if new > l.size() {
                let now = LIVE.fetch_add(new - l.size(), Relaxed) + new - l.size();
                PEAK.fetch_max(now, Relaxed);
            } else {
                LIVE.fetch_sub(l.size() - new, Relaxed);
            }
        }
        q
    }
}

/// Records each stage's time and peak memory.
pub struct Timings {
    last: Instant,
    start: Instant,
    rows: Vec<(&'static str, f64, usize)>,
    points: usize,
}

impl Timings {
    /// Starts the clock and the peak.
    pub fn start() -> Self {
        PEAK.store(LIVE.load(Relaxed), Relaxed);
        let now = Instant::now();
        Timings {
            last: now,
            start: now,
            rows: Vec::new(),
            points: 0,
        }
    }

    /// The number of points, for the per-point column.
    pub fn set_points(&mut self, n: usize) {
        self.points = n;
    }

    /// The table printed to stderr.
    pub fn report(&self) -> String {
        let mut s = String::from("stage            time      peak heap   per point\n");
        for (name, secs, peak) in &self.rows {
            let per = if self.points > 0 {
                format!("{:>7.1} B", *peak as f64 / self.points as f64)
            } else {
                String::new()
            };
            s.push_str(&format!(
                "{name:<14} {:>7.3} s  {:>9.1} MB  {per}\n",
                secs,
                *peak as f64 / 1e6
            ));
        }
        s.push_str(&format!(
            "{:<14} {:>7.3} s  ({} points)\n",
            "total",
            self.start.elapsed().as_secs_f64(),
            self.points
        ));
        s
    }
}

impl Observer for Timings {
    fn stage(&mut self, name: &'static str) {
        let now = Instant::now();
        let peak = PEAK.swap(LIVE.load(Relaxed), Relaxed);
        self.rows
            .push((name, (now - self.last).as_secs_f64(), peak));
        self.last = now;
    }
}
