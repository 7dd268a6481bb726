//! `lmdc simulate FILE`: a ring's height loop run offline against its
//! declared plant ([`lmdc::pipeline::simulate`]), printed as a table every
//! few layers and a summary of each segment's total against the target;
//! `--csv` writes every layer and segment for plotting.

use lmdc::control::{Finding, Severity, Simulation};
use lmdc::pipeline::RingSimulation;
use std::fmt::Write as _;
use std::path::Path;

/// The text `lmdc simulate` prints: the loop, every `every`-th layer (and
/// the first and the last) segment by segment, and the totals.
pub fn report(r: &RingSimulation, every: usize) -> String {
    let c = &r.controller;
    let sim = &r.simulation;
    let layers = sim.layers();
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{}: {} layers × {} segments; kp = {}, ki = {}, target {} mm a layer, clamp {} .. {} mm/s",
        r.part,
        layers,
        r.start.len(),
        c.kp(),
        c.ki(),
        c.target().0,
        c.clamp().low().0,
        c.clamp().high().0
    );
    let _ = writeln!(
        s,
        "plant: h = g·(1 + {} %·layer)/v per segment, g calibrated so each table speed lays the target{}",
        r.plant.drift() * 100.0,
        if r.start.iter().enumerate().all(|(j, v)| {
            r.plant
                .deposition(j)
                .is_some_and(|g| (g.0 - c.target().0 * v.0).abs() <= 1e-9 * g.0.abs())
        }) {
            ""
        } else {
            ", scaled by the declared factors"
        }
    );
    for f in &r.analysis.findings {
        let what = match f.severity() {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        let _ = writeln!(s, "{what}: {f}");
    }
    let _ = writeln!(s);
    let _ = writeln!(
        s,
        "{:>6} {:>8} {:>11} {:>10} {:>10} {:>10}",
        "layer", "segment", "speed mm/s", "height mm", "total mm", "target mm"
    );
    let every = every.max(1);
    for layer in 0..layers {
        let n = layer + 1;
        if !(layer == 0 || n % every == 0 || n == layers) {
            continue;
        }
        rows(&mut s, sim, layer, c.target().0);
    }
    let _ = writeln!(s);
    let target = c.target().0 * layers as f64;
    let _ = writeln!(s, "after {layers} layers (target {target:.3} mm):");
    let _ = writeln!(
        s,
        "{:>8} {:>11} {:>11} {:>10} {:>10}",
        "segment", "start mm/s", "final mm/s", "total mm", "error mm"
    );
    let totals = sim.totals();
    for t in &totals {
        let _ = writeln!(
            s,
            "{:>8} {:>11.3} {:>11.3} {:>10.3} {:>+10.3}",
            t.segment + 1,
            r.start[t.segment].0,
            t.final_speed.0,
            t.built.0,
            t.error().0
        );
    }
    // The first of equal errors.
    let worst = totals
        .iter()
        .fold(None, |w: Option<&lmdc::control::Total>, t| match w {
            Some(w) if w.error().0.abs() >= t.error().0.abs() => Some(w),
            _ => Some(t),
        });
    if let Some(w) = worst {
        let _ = writeln!(
            s,
            "largest error: segment {}, {:+.3} mm ({:+.2} % of {target:.3} mm)",
            w.segment + 1,
            w.error().0,
            100.0 * w.error().0 / target
        );
    }
    s
}

fn rows(s: &mut String, sim: &Simulation, layer: usize, target: f64) {
    for x in sim.samples().iter().filter(|x| x.layer == layer) {
        let _ = writeln!(
            s,
            "{:>6} {:>8} {:>11.3} {:>10.4} {:>10.3} {:>10.3}",
            layer + 1,
            x.segment + 1,
            x.speed.0,
            x.height.0,
            x.total.0,
            target * (layer + 1) as f64
        );
    }
}

/// Writes `text` to `path` through a temporary file beside it, so a reader
/// never sees half a file.
pub fn write_atomically(path: &Path, text: &str) -> std::io::Result<()> {
    let name = path
        .file_name()
        .ok_or_else(|| std::io::Error::other("no file name"))?;
    let mut tmp_name = std::ffi::OsString::from(".");
    tmp_name.push(name);
    tmp_name.push(format!(".lmdc-{}.tmp", std::process::id()));
    let tmp = path.with_file_name(tmp_name);
    let r = std::fs::write(&tmp, text).and_then(|()| std::fs::rename(&tmp, path));
    if r.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    r
}

/// Whether any finding is an error (the build would refuse the loop).
pub fn refused(r: &RingSimulation) -> bool {
    r.analysis
        .findings
        .iter()
        .any(|f: &Finding| f.severity() == Severity::Error)
}
