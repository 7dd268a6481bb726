//! A one-line progress display on stderr for long runs: which stage is
//! running and for how long, redrawn ten times a second once the run has
//! taken a second. Only on a terminal (a log or a CI capture gets nothing),
//! and never with `--quiet`. Hand-written: one line with a spinner and a
//! clock is all a stage-by-stage pipeline can say, not worth a dependency.

use lmdc::pipeline::Observer;
use std::io::Write;
use std::sync::{Arc, Condvar, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// Nothing is drawn before a run has taken this long (the environment
/// variable `LMDC_PROGRESS_AFTER_MS` changes it, for tests of the terminal
/// case on inputs that compile quickly).
const DELAY: Duration = Duration::from_secs(1);

fn delay() -> Duration {
    std::env::var("LMDC_PROGRESS_AFTER_MS")
        .ok()
        .and_then(|v| v.parse().ok())
        .map_or(DELAY, Duration::from_millis)
}
/// Time between redraws.
const TICK: Duration = Duration::from_millis(100);
const SPINNER: [char; 4] = ['|', '/', '-', '\\'];

struct State {
    what: String,
    stage: &'static str,
    done: bool,
    /// Whether a line is on the screen now.
    drawn: bool,
}

/// The progress line of one run; an [`Observer`] of its stages.
pub struct Progress {
    shared: Option<Arc<(Mutex<State>, Condvar)>>,
    thread: Option<JoinHandle<()>>,
}

/// What is running after stage `finished` (a name the pipeline reports).
fn next(finished: &str) -> &'static str {
    match finished {
        "parse" => "checking",
        "check" => "slicing",
        "slice" => "verifying",
        "verify" => "writing",
        n if n.starts_with("emit") => "writing",
        _ => "finishing",
    }
}

fn clear(err: &mut impl Write) {
    let _ = write!(err, "\r\x1b[2K");
    let _ = err.flush();
}

impl Progress {
    /// Progress for a run on `what` (the file): drawn only when `enabled`
    /// (stderr is a terminal and `--quiet` was not given).
    pub fn start(enabled: bool, what: String) -> Progress {
        if !enabled {
            return Progress {
                shared: None,
                thread: None,
            };
        }
        let shared = Arc::new((
            Mutex::new(State {
                what,
                stage: "parsing",
                done: false,
                drawn: false,
            }),
            Condvar::new(),
        ));
        let theirs = Arc::clone(&shared);
        let thread = std::thread::Builder::new()
            .name("progress".into())
            .spawn(move || draw(&theirs))
            .ok();
        Progress {
            shared: Some(shared),
            thread,
        }
    }

    /// Runs `print` (which writes to stderr) with the progress line cleared
    /// first, so the two do not mix; the line comes back at the next tick.
    pub fn print(&self, print: impl FnOnce()) {
        let Some(shared) = &self.shared else {
            return print();
        };
        let mut s = shared.0.lock().unwrap_or_else(|e| e.into_inner());
        if s.drawn {
            clear(&mut std::io::stderr());
            s.drawn = false;
        }
        print();
    }

    /// Stops drawing and clears the line.
    pub fn finish(mut self) {
        self.stop();
    }

    fn stop(&mut self) {
        if let Some(shared) = &self.shared {
            let mut s = shared.0.lock().unwrap_or_else(|e| e.into_inner());
            s.done = true;
            shared.1.notify_all();
        }
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        self.stop();
    }
}

impl Observer for Progress {
    fn stage(&mut self, name: &'static str) {
        if let Some(shared) = &self.shared {
            shared.0.lock().unwrap_or_else(|e| e.into_inner()).stage = next(name);
        }
    }
}

fn draw(shared: &(Mutex<State>, Condvar)) {
    let start = Instant::now();
    let after = delay();
    let mut turn = 0usize;
    let mut s = shared.0.lock().unwrap_or_else(|e| e.into_inner());
    loop {
        // The first line comes as soon as the delay is over (at once with a
        // delay of 0, so a quick run still shows it), then every tick.
        let wait = after.saturating_sub(start.elapsed()).max(if turn == 0 {
            Duration::ZERO
        } else {
            TICK
        });
        s = shared
            .1
            .wait_timeout(s, wait)
            .unwrap_or_else(|e| e.into_inner())
            .0;
        let mut err = std::io::stderr();
        if s.done {
            if s.drawn {
                clear(&mut err);
            }
            return;
        }
        let t = start.elapsed();
        if t < after {
            continue;
        }
        turn += 1;
        let _ = write!(
            err,
            "\r\x1b[2K{} {}: {} … {:.1} s",
            SPINNER[turn % SPINNER.len()],
            s.what,
            s.stage,
            t.as_secs_f64()
        );
        let _ = err.flush();
        s.drawn = true;
    }
}

/// Passes every stage to both observers (the timings and the progress).
pub struct Both<'a>(pub &'a mut dyn Observer, pub &'a mut dyn Observer);

impl Observer for Both<'_> {
    fn stage(&mut self, name: &'static str) {
        self.0.stage(name);
        self.1.stage(name);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stages_name_what_runs_next() {
        assert_eq!(next("parse"), "checking");
        assert_eq!(next("emit KRL"), "writing");
        assert_eq!(next("write"), "finishing");
    }

    #[test]
    fn disabled_progress_starts_no_thread() {
        let mut p = Progress::start(false, "f".into());
        p.stage("parse");
        assert!(p.thread.is_none() && p.shared.is_none());
        let mut ran = false;
        p.print(|| ran = true);
        assert!(ran);
        p.finish();
    }
}
