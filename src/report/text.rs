//! The report as text: a table of the layers, then the totals in words.
//! Numbers are rounded for people; `--json` keeps them whole.

use super::{Design, Report, Tally};
use crate::numbers::{duration, energy, length, mass, trimmed};
use crate::units::short;
use std::fmt::Write;

/// A duration as `h:mm:ss.s` for the table.
fn clock(s: f64) -> String {
    let s = if s.is_finite() { s.max(0.0) } else { 0.0 };
    let tenths = (s * 10.0).round() as u64;
    let (h, m, sec, t) = (
        tenths / 36_000,
        tenths / 600 % 60,
        tenths / 10 % 60,
        tenths % 10,
    );
    format!("{h}:{m:02}:{sec:02}.{t}")
}

fn volume(mm3: f64) -> String {
    if mm3.abs() < 1000.0 {
        format!("{mm3:.1} mm³")
    } else {
        format!("{:.1} cm³", mm3 / 1000.0)
    }
}

fn percent(x: f64) -> String {
    format!("{:.1} %", x * 100.0)
}

fn row(out: &mut String, label: &str, t: &Tally, volumes: bool) {
    let _ = write!(
        out,
        "{label:>6} {:>10.3} {:>9.3} {:>11} {:>11} {:>10.1} {:>9.2}",
        t.deposit_mm / 1000.0,
        t.travel_mm / 1000.0,
        clock(t.time_s()),
        clock(t.laser_on_s),
        t.energy_j / 1000.0,
        t.powder_g,
    );
    if volumes {
        // The layer's one statement: what the bead lays of what it stacks.
        let share = if t.stacked_volume_mm3 > 0.0 {
            format!("{:.1} %", t.bead_volume_mm3 / t.stacked_volume_mm3 * 100.0)
        } else {
            "—".into()
        };
        let _ = write!(
            out,
            " {:>9.2} {:>11.2} {:>9}",
            t.bead_volume_mm3 / 1000.0,
            t.stacked_volume_mm3 / 1000.0,
            share
        );
    }
    out.push('\n');
}

/// What the deposit was checked at: the speeds reached, or the programmed
/// ones taken as reached.
fn reached(r: &super::Reached) -> String {
    let Some(a) = r.acceleration_mm_s2 else {
        return "no `acceleration` declared: the programmed speeds are taken as reached".into();
    };
    format!(
        "the deposit checked at the speeds reached with {} mm/s² and a blending of {} mm ({}){}",
        trimmed(a, 1),
        trimmed(r.blending_mm, 3),
        r.blending_from,
        if r.leads {
            ", runs started and stopped on leads"
        } else {
            ", runs starting and stopping at rest"
        }
    )
}

/// The whole report as text.
pub fn render(r: &Report) -> String {
    let mut out = String::new();
    let volumes = r.bead.is_some();
    let n = r.layers.len();
    let _ = writeln!(
        out,
        "{} on {}: {} layer{} (moves timed at their programmed speeds, rapids at {} mm/s; {})\n",
        r.part,
        r.machine,
        n,
        if n == 1 { "" } else { "s" },
        trimmed(r.rapid_mm_s, 3),
        reached(&r.reached)
    );
    let _ = write!(
        out,
        "{:>6} {:>10} {:>9} {:>11} {:>11} {:>10} {:>9}",
        "layer", "deposit m", "travel m", "time", "laser on", "energy kJ", "powder g"
    );
    if volumes {
        let _ = write!(
            out,
            " {:>9} {:>11} {:>9}",
            "bead cm³", "stacked cm³", "bead/stk"
        );
    }
    out.push('\n');
    for l in &r.layers {
        row(&mut out, &l.layer.to_string(), &l.tally, volumes);
    }
    row(&mut out, "total", &r.total, volumes);
    out.push('\n');
    totals(&mut out, r);
    registration(&mut out, r);
    metal(&mut out, r);
    thermal(&mut out, r);
    approaches(&mut out, r);
    out
}

/// How the limit was kept: by which levers, and the time waits alone would
/// have added.
fn kept(h: &crate::report::heat::Heat) -> String {
    use crate::ir::Cooling;
    let layers = |n: usize| format!("{n} layer{}", if n == 1 { "" } else { "s" });
    match h.cooling.levers() {
        [Cooling::Dwell] => format!("kept by waiting {} longer", duration(h.added_s)),
        [Cooling::Power] => format!(
            "kept by lowering the power of {}",
            layers(h.layers_at_less_power)
        ),
        [Cooling::Order] => match h.dwell_alone_s {
            Some(d) => format!(
                "kept by the order of the islands with no wait added, where waiting alone would add {}",
                duration(d)
            ),
            None => "kept by the order of the islands; waits alone of at most an hour would not keep it".to_string(),
        },
        _ => {
            let mut by = Vec::new();
            if h.layers_reordered > 0 {
                by.push(format!(
                    "the order of the islands in {}",
                    layers(h.layers_reordered)
                ));
            }
            if h.layers_at_less_power > 0 {
                by.push(format!(
                    "lowering the power of {}",
                    layers(h.layers_at_less_power)
                ));
            }
            if h.added_s > 0.0 {
                by.push(format!("waiting {} longer", duration(h.added_s)));
            }
            let by = if by.is_empty() {
                "kept with nothing changed".to_string()
            } else {
                format!("kept by {}", by.join(", "))
            };
            match h.dwell_alone_s {
                Some(d) => format!("{by}, where waiting alone would add {}", duration(d)),
                None => format!("{by}; waits alone of at most an hour would not keep it"),
            }
        }
    }
}

/// The thermal prediction: the hottest start and peak, what the limit
/// cost, and each layer's temperatures.
fn thermal(out: &mut String, r: &Report) {
    let Some(h) = &r.thermal else { return };
    let limit = match h.max_interpass_c {
        Some(m) => format!(" (limit {} °C, {})", trimmed(m, 1), kept(h)),
        None => String::new(),
    };
    let _ = writeln!(
        out,
        "\nthermal     {}: the hottest start of a layer {} °C, layer {}{limit}; the hottest layer as laid {} °C, layer {} (its mean, not the melt pool's; docs/thermal.md)",
        h.material,
        trimmed(h.hottest_interpass_c, 1),
        h.hottest_layer,
        trimmed(h.peak_c, 1),
        h.peak_layer
    );
    let _ = writeln!(
        out,
        "{:>6} {:>11} {:>12} {:>9} {:>9} {:>9} {:>7}",
        "layer", "starts", "interpass °C", "peak °C", "wait s", "added s", "power"
    );
    for l in &h.layers {
        let _ = writeln!(
            out,
            "{:>6} {:>11} {:>12} {:>9} {:>9} {:>9} {:>7}",
            l.layer,
            clock(l.start_s),
            format!("{:.1}", l.interpass_c),
            format!("{:.1}", l.peak_c),
            format!("{:.1}", l.wait_s),
            format!("{:.1}", l.added_s),
            percent(l.power_share)
        );
        for i in &l.islands {
            let _ = writeln!(
                out,
                "{:>6} {:>11} {:>12} {:>9}   island at ({} mm, {} mm)",
                "",
                clock(i.start_s),
                format!("{:.1}", i.interpass_c),
                format!("{:.1}", i.peak_c),
                trimmed(i.at_mm[0], 1),
                trimmed(i.at_mm[1], 1)
            );
        }
    }
}

/// The closest approach of each body to each thing of the cell.
fn approaches(out: &mut String, r: &Report) {
    if r.approaches.is_empty() {
        return;
    }
    let _ = writeln!(out, "\nclosest approaches (the gap each body keeps):");
    for a in &r.approaches {
        let pair = format!("{} – {}", a.body, a.with);
        let _ = writeln!(
            out,
            "  {pair:<34} {:>9} mm (gap {} mm) at {}",
            trimmed(a.distance_mm, 2),
            trimmed(a.gap_mm, 3),
            a.at
        );
    }
}

/// The totals in words: time, length, laser, powder.
fn totals(out: &mut String, r: &Report) {
    let t = &r.total;
    let _ = writeln!(
        out,
        "time        {} (motion {}, dwell {})",
        duration(t.time_s()),
        duration(t.motion_s),
        duration(t.dwell_s)
    );
    let _ = writeln!(
        out,
        "length      {} deposited, {} travel",
        length(t.deposit_mm),
        length(t.travel_mm)
    );
    let mean = if t.laser_on_s > 0.0 {
        format!(", mean power {:.0} W", t.energy_j / t.laser_on_s)
    } else {
        String::new()
    };
    let _ = writeln!(
        out,
        "laser on    {}; energy {}{mean}",
        duration(t.laser_on_s),
        energy(t.energy_j)
    );
    let _ = writeln!(
        out,
        "powder fed  {} (while the laser is on)",
        mass(t.powder_g)
    );
    if !r.branch_changes.is_empty() {
        let layers: Vec<String> = r.branch_changes.iter().map(|l| l.to_string()).collect();
        let _ = writeln!(
            out,
            "tilt        goes over to its other side (the axes' other solution for the same nozzle direction) in layer{} {}: a table turns the part over only retracted, where a layer needs it within the stops; a head swings through vertical, C staying where it is",
            if layers.len() == 1 { "" } else { "s" },
            layers.join(", ")
        );
    }
}

/// The scan's best fit to its nominal: the move, the residual, the
/// placement that would give it without the fit.
fn registration(out: &mut String, r: &Report) {
    let Some(g) = &r.registration else {
        return;
    };
    let v = |p: [f64; 3], d: usize| {
        format!(
            "{}, {}, {}",
            trimmed(p[0], d),
            trimmed(p[1], d),
            trimmed(p[2], d)
        )
    };
    let _ = writeln!(
        out,
        "scan fit    the scan moved onto its nominal `{}` by [{}] mm and turned [{}]° after its declared placement, in {} iterations: it keeps {} of the {} points fitted (the rest worn or stray), {} mm RMS from the nominal and {} mm at most, within the `fit_tolerance` of {} mm (the same place as `turn = [{}] deg`, `at = [{}] mm` without `register`)",
        g.nominal,
        v(g.moved, 3),
        v(g.turned, 3),
        g.iterations,
        percent(g.inliers),
        g.points,
        trimmed(g.rms, 4),
        trimmed(g.max, 4),
        trimmed(g.tolerance, 4),
        v(g.turn, 4),
        v(g.at, 4),
    );
}

/// The metal: what the bead model lays, what the layers stack, the design.
fn metal(out: &mut String, r: &Report) {
    let t = &r.total;
    let Some(bead) = &r.bead else {
        return;
    };
    let density = r
        .density_g_cm3
        .map(|d| format!(" at {} g/cm³", trimmed(d, 3)));
    let mut line = format!(
        "bead model  lays {} (bead {} mm wide, {}; deposits {})",
        volume(t.bead_volume_mm3),
        trimmed(bead.width_mm, 3),
        bead.measured_as,
        bead.spacing
    );
    if let (Some(m), Some(d)) = (r.bead_mass_g, &density) {
        let _ = write!(line, " = {}{d}", mass(m));
    }
    if let Some(e) = r.bead_efficiency {
        let _ = write!(line, ": {} of the powder caught", percent(e));
    }
    if let Some(e) = bead.declared_efficiency {
        let _ = write!(line, " (the model declares {})", percent(e));
    }
    let _ = writeln!(out, "{line}");
    if let Some(f) = &bead.fit {
        fitted(out, bead, f);
    }
    if let Some(d) = &r.deposit {
        deposit(out, t, d);
    }
    design(out, r);
    if r.density_g_cm3.is_none() {
        let _ = writeln!(
            out,
            "mass        the bead model declares no density: give one with --density (g/cm³)"
        );
    }
}

/// The model the program fitted to its data: its numbers and how well.
fn fitted(out: &mut String, bead: &super::BeadInfo, f: &crate::ir::BeadFit) {
    use crate::ir::BeadModel;
    let numbers = match &bead.model {
        BeadModel::Linear { slope, intercept } => format!(
            "H = {} mm/(mm/s)·v + {} mm",
            trimmed(*slope, 6),
            trimmed(*intercept, 6)
        ),
        BeadModel::Power {
            height,
            speed,
            exponent,
        } => format!(
            "H = {} mm·(v / {} mm/s)^{}",
            trimmed(*height, 6),
            trimmed(*speed, 3),
            trimmed(*exponent, 6)
        ),
        BeadModel::MassBalance { efficiency, .. } => {
            format!("efficiency {}", trimmed(*efficiency, 6))
        }
        BeadModel::Table { speed, .. } => format!("a table of {} speeds", speed.len()),
        BeadModel::Measured { height, speed } => {
            format!("{} mm at {} mm/s", trimmed(*height, 6), trimmed(*speed, 3))
        }
    };
    let range = bead.measured.map_or(String::new(), |[a, b]| {
        format!(", measured {} .. {} mm/s", trimmed(a, 3), trimmed(b, 3))
    });
    let _ = writeln!(
        out,
        "fitted      {} to {} coupons at {} speeds of {}{range}: {numbers}; R² {}, RMS {} {}",
        f.model,
        f.points,
        f.speeds,
        f.data,
        trimmed(f.r2, 6),
        trimmed(f.rms, 6),
        f.unit
    );
}

/// What the bead lays against what the layers stack: one statement, with
/// the worst layer and the errors added up, against the tolerances.
fn deposit(out: &mut String, t: &super::Tally, d: &super::DepositCheck) {
    let within =
        (d.worst_share - 1.0).abs() <= d.rise_tolerance && d.worst_drift_mm.abs() <= d.max_drift_mm;
    let _ = writeln!(
        out,
        "stacked     the layers stack {} (each deposit's layer height × the strip it fills): the bead model lays {} of it; layer {} the farthest off at {}, the layers' errors adding up to {} mm at most ({})",
        volume(t.stacked_volume_mm3),
        ratio(t.bead_volume_mm3, t.stacked_volume_mm3),
        d.worst_layer,
        percent(d.worst_share),
        crate::numbers::fixed(d.worst_drift_mm, 3),
        if within {
            format!(
                "within the {} and {} mm the plan allows",
                percent(d.rise_tolerance),
                trimmed(d.max_drift_mm, 3)
            )
        } else {
            "beyond what the plan allows: see lmd::deposit".into()
        }
    );
}

/// The design solid against what the plan stacks and the bead lays.
fn design(out: &mut String, r: &Report) {
    let t = &r.total;
    match &r.design {
        Some(Design::Known { volume_mm3, what }) => {
            let mut line = format!(
                "design      {} ({what}): the layers stack {} of it, the bead model lays {}",
                volume(*volume_mm3),
                ratio(t.stacked_volume_mm3, *volume_mm3),
                ratio(t.bead_volume_mm3, *volume_mm3)
            );
            if let (None, Some(f)) = (&r.design_missing, r.design_filled.filter(|f| *f < 0.995)) {
                let _ = write!(
                    line,
                    "; it holds {} ({}) more than the layers stack (lmdc breaks that down for flat layers only)",
                    percent(1.0 - f),
                    volume((1.0 - f) * volume_mm3)
                );
            }
            if let (Some(m), Some(e)) = (r.design_mass_g, r.design_efficiency) {
                let _ = write!(
                    line,
                    "; {} needs {} of the powder caught",
                    mass(m),
                    percent(e)
                );
            }
            let _ = writeln!(out, "{line}");
            if let Some(m) = &r.design_missing {
                missing(out, m, r.design_filled);
            }
            if let Some(f) = &r.finish {
                finish(out, f);
            }
        }
        Some(Design::Unknown { why }) => {
            let _ = writeln!(out, "design      volume not known: {why}");
        }
        None => {}
    }
}

/// The finished surface the bead model predicts against the top.
fn finish(out: &mut String, f: &super::finish::Finish) {
    let at = |p: [f64; 2]| format!("({}, {})", short(p[0]), short(p[1]));
    // A tilted fill's departures are along its build direction.
    let along = f.along.map_or(String::new(), |d| {
        format!(
            " (along the build direction ({}, {}, {}))",
            short(d[0]),
            short(d[1]),
            short(d[2])
        )
    });
    let _ = writeln!(
        out,
        "finish      the bead model's surface at {} places along the last layer's tracks{along}: up to {} mm below the top at {}, up to {} mm above it at {}, RMS {} mm; the first layer {} .. {} mm thick",
        f.points,
        short(f.below_mm),
        at(f.below_at),
        short(f.above_mm),
        at(f.above_at),
        short(f.rms_mm),
        short(f.first_layer_mm[0]),
        short(f.first_layer_mm[1]),
    );
}

/// What of the design the strips cover and what they leave, each figure
/// named for what it is.
fn missing(out: &mut String, m: &super::coverage::Missing, stacked: Option<f64>) {
    let figure = |f: &super::coverage::Figure| {
        let mass = f
            .mass_g
            .map_or(String::new(), |g| format!(" = {}", mass(g)));
        format!("{} ({}{mass})", percent(f.share), volume(f.volume_mm3))
    };
    // What the layers stack beyond what the strips cover: strips laid over
    // each other (a laser-on link along the raster's ends did, before its
    // round turn).
    let twice = stacked
        .map(|s| s - m.covered.share)
        .filter(|x| *x >= 0.0005)
        .map_or(String::new(), |x| {
            format!(
                ", and the layers stack {} of it more than that where strips overlap (counted twice)",
                percent(x)
            )
        });
    let _ = writeln!(
        out,
        "unfilled    the deposits' strips cover {} of the design{twice}; \
         {} is the band at the faces, between them and the outermost beads' strips, where the beads round off; \
         {} is hollow on purpose (inside contours with no infill); {} is missing for other reasons \
         (gaps between tracks, track ends short of a contour)",
        figure(&m.covered),
        figure(&m.faces),
        figure(&m.hollows),
        figure(&m.other)
    );
}

fn ratio(a: f64, b: f64) -> String {
    if b > 0.0 {
        percent(a / b)
    } else {
        "—".into()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn durations_read_as_people_say_them() {
        assert_eq!(duration(12.34), "12.3 s");
        assert_eq!(duration(252.0), "4 min 12 s");
        assert_eq!(duration(8772.0), "2 h 26 min");
        assert_eq!(clock(3725.06), "1:02:05.1");
        assert_eq!(duration(f64::NAN), "0.0 s");
    }
}
