//! Template variables shared by the back ends, so a layer's comment says the
//! same thing in KRL and G-code.

use crate::ir::{Layer, Program};
use crate::numbers::{duration, energy, fixed, length, mass};
use crate::provenance::{Provenance, VERSION};
use crate::verify::Summary;

/// Longest name written into a comment: the comment lines of the built-in
/// templates then stay far inside every control's line length (LinuxCNC: 255).
pub const MAX_SHOWN: usize = 64;

/// `name` as comments show it: at most [`MAX_SHOWN`] characters, the start kept
/// and `...` marking the cut. File and program names keep the whole name's
/// hash, so shortened names never make two programs alike.
pub fn shown(name: &str) -> String {
    if name.chars().count() <= MAX_SHOWN {
        return name.to_string();
    }
    let head: String = name.chars().take(MAX_SHOWN - 3).collect();
    format!("{head}...")
}

/// The one-line summary the programs' headers carry (template variable
/// `summary`), from the verifier's summary of the plan, e.g. `plan: 36.76 m
/// deposited, 4.06 m travel; 1 h 19 min, laser on 1 h 15 min, dwell 0.0 s;
/// 9.90 MJ; powder 3.454 kg`. No brackets: G-code comments are in brackets.
pub fn summary(s: &Summary) -> String {
    let t = &s.total;
    format!(
        "plan: {} deposited, {} travel; {}, laser on {}, dwell {}; {}; powder {}",
        length(t.deposit_mm),
        length(t.travel_mm),
        duration(t.time_s()),
        duration(t.laser_on_s),
        duration(t.dwell_s),
        energy(t.energy_j),
        mass(t.powder_g),
    )
}

/// `source` (the `.lmd` file as given on the command line, at most
/// [`MAX_SHOWN`] characters, its end kept: the file's name says more than
/// the first directories), `sha256` (of the source's bytes), `set` (the
/// constants `--set` replaced, `NAME = VALUE; …`, empty when none) and
/// `version` (lmdc's), each passed through the back end's comment
/// sanitiser `safe`: every program names what it was compiled from.
pub fn provenance(ctx: &mut tera::Context, p: &Provenance, safe: &dyn Fn(&str) -> String) {
    let file = p.shown_file();
    let n = file.chars().count();
    let file = if n <= MAX_SHOWN {
        file.to_string()
    } else {
        let tail: String = file.chars().skip(n - (MAX_SHOWN - 3)).collect();
        format!("...{tail}")
    };
    ctx.insert("source", &safe(&file));
    ctx.insert("sha256", &p.sha256);
    ctx.insert("set", &safe(&p.set.join("; ")));
    ctx.insert("version", VERSION);
}

/// `layers`, `paths`, `points`: the program's totals.
pub fn counts(ctx: &mut tera::Context, prog: &Program) {
    ctx.insert("layers", &prog.layers.len());
    ctx.insert(
        "paths",
        &prog.layers.iter().map(|l| l.paths.len()).sum::<usize>(),
    );
    ctx.insert("points", &prog.point_count());
}

/// The variables of a layer's comment block: `layer` (0-based index), `number`
/// (1-based), `layers`, `station`, `h_min`/`h_max` (deposit heights in mm — of every
/// point the laser is on towards or from, the end of each run included —
/// every point's if the layer deposits nothing), `paths`, `points`.
pub fn layer_context(ctx: &mut tera::Context, li: usize, n_layers: usize, layer: &Layer) {
    let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
    let (mut any_on, mut points) = (false, 0usize);
    for path in &layer.paths {
        points += path.points.len();
        // A point deposits when the laser is on towards it or from it: the
        // end of a run (laser off from there on) is the run's last deposit.
        let mut arriving = false;
        for pt in &path.points {
            let deposits = pt.laser_on || arriving;
            arriving = pt.laser_on;
            if deposits && !any_on {
                any_on = true;
                (lo, hi) = (f32::INFINITY, f32::NEG_INFINITY);
            }
            if deposits || !any_on {
                lo = lo.min(pt.layer_height);
                hi = hi.max(pt.layer_height);
            }
        }
    }
    if points == 0 {
        (lo, hi) = (0.0, 0.0);
    }
    ctx.insert("layer", &layer.index);
    ctx.insert("number", &(li + 1));
    ctx.insert("layers", &n_layers);
    ctx.insert("station", &fixed(layer.station, 4));
    ctx.insert("h_min", &fixed(lo as f64, 3));
    ctx.insert("h_max", &fixed(hi as f64, 3));
    ctx.insert("paths", &layer.paths.len());
    ctx.insert("points", &points);
    ctx.insert("label", &label(&layer.label));
}

/// A layer's label as a comment holds it on every back end: letters,
/// digits, spaces and `. , : / - _` (the IR may come from elsewhere: no
/// bracket, semicolon or line break ends a comment early).
fn label(text: &str) -> String {
    text.chars()
        .take(200)
        .map(|c| {
            if c.is_ascii_alphanumeric() || " .,:/-_".contains(c) {
                c
            } else {
                ' '
            }
        })
        .collect()
}

/// `styles`: one line per row of the style table, e.g. `style 1 edge: power
/// 1300 W, speed 5 mm/s, powder process, colour #d62728` (`process`: the style
/// leaves that value to the process block), each passed through the back
/// end's comment sanitiser `safe` (the checker allows only word names, but
/// the IR may come from elsewhere).
pub fn styles(ctx: &mut tera::Context, p: &Program, safe: &dyn Fn(&str) -> String) {
    let value = |v: Option<f64>, unit: &str| match v {
        Some(v) => format!("{} {unit}", crate::numbers::trimmed(v, 3)),
        None => "process".to_string(),
    };
    let lines: Vec<String> = p
        .styles
        .iter()
        .map(|s| {
            safe(&format!(
                "style {} {}: power {}, speed {}, powder {}, colour {}",
                s.id,
                shown(&s.name),
                value(s.power, "W"),
                value(s.speed, "mm/s"),
                value(s.powder, "g/min"),
                s.colour
            ))
        })
        .collect();
    ctx.insert("styles", &lines);
}
