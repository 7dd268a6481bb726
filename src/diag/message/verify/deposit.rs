//! What the verifier says when the plan's bead model does not lay the
//! layers the plan stacks (`lmd::deposit`).

use crate::diag::{plural, Code, Diagnostic, Worst};
use crate::numbers::trimmed;
use crate::span::Span;
use std::fmt::Display;

/// The point farthest off, as the model sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorstPoint {
    /// Its planned layer height, mm.
    pub planned: f64,
    /// What the model lays there, mm.
    pub rise: f64,
    /// Its speed across the normal, mm/s.
    pub speed: f64,
    /// The strip it fills, mm.
    pub pitch: f64,
    /// The speed that would lay the planned height there, mm/s (`None`: a
    /// bead measured at one speed, which lays one height).
    pub needs: Option<f64>,
    /// Its style (0: the process block's).
    pub style: u16,
}

/// The speeds a style's own speed may take: what every one of its tracks
/// lays against what it plans.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StyleSpeeds {
    /// The style.
    pub style: u16,
    /// The narrowest and the widest strip its tracks fill, mm.
    pub strips: [f64; 2],
    /// The speed at which its tracks lay, over their length, what they
    /// plan, and the speeds at which every one lays within the tolerance,
    /// mm/s (`None`: no one speed does).
    pub fits: Option<(f64, [f64; 2])>,
}

/// How the layers' mean errors add up.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Drift {
    /// The first layer (0-based) after which the sum passes the bound, and
    /// the sum there, mm.
    pub passed: Option<(usize, f64)>,
    /// The sum after the last layer, mm.
    pub last: f64,
    /// The largest sum, by size, mm.
    pub largest: f64,
    /// The layers in the plan.
    pub layers: usize,
    /// `max_drift`, mm.
    pub limit: f64,
}

impl Drift {
    /// Adds layer `layer`'s running sum `sum`.
    pub fn add(&mut self, layer: usize, sum: f64, limit: f64) {
        self.last = sum;
        if sum.abs() > self.largest.abs() {
            self.largest = sum;
        }
        if self.passed.is_none() && sum.abs() > limit {
            self.passed = Some((layer, sum));
        }
    }
}

/// What the rule found (the worst point at an `At`).
#[derive(Clone, Copy, Debug)]
pub struct DepositMiss<At> {
    /// Points off by more than the tolerance: how many, the worst ratio
    /// of predicted to planned, where.
    pub worst: Option<Worst<At>>,
    /// The worst point's numbers.
    pub point: Option<WorstPoint>,
    /// Laser-on points checked.
    pub checked: u64,
    /// What the model lays over what the plan stacks, over the whole plan.
    pub share: f64,
    /// `rise_tolerance`.
    pub tolerance: f64,
    /// The layers' errors added up.
    pub drift: Drift,
    /// The narrowest and the widest strip a laser-on point fills, mm.
    pub strips: [f64; 2],
    /// Where the worst point's style sets its speed: the speeds that style
    /// may take.
    pub style: Option<StyleSpeeds>,
}

fn mm(x: f64) -> String {
    format!("{} mm", trimmed(x, 3))
}

fn percent(x: f64) -> String {
    format!("{} %", trimmed(x * 100.0, 1))
}

/// The plan's bead model does not lay the layers it plans.
pub fn deposit_miss(
    m: &DepositMiss<impl Display>,
    bead: Option<Span>,
    slicing: Option<Span>,
) -> Diagnostic {
    let mut msg = format!(
        "the bead model lays {} of the layers this plan stacks",
        percent(m.share)
    );
    if let Some(w) = &m.worst {
        msg.push_str(&format!(
            ": {} of {} laser-on point{} rise more than {} off their layer height",
            w.count,
            m.checked,
            plural(m.checked),
            percent(m.tolerance)
        ));
    }
    if let (Some(w), Some(p)) = (&m.worst, &m.point) {
        msg.push_str(&format!(
            "; the worst, at {}, rises {} where {} is planned ({} of it), at {} mm/s over a strip {} wide",
            w.at,
            mm(p.rise),
            mm(p.planned),
            percent(w.value),
            trimmed(p.speed, 2),
            mm(p.pitch)
        ));
    }
    let dr = &m.drift;
    let drift = match dr.passed {
        Some((layer, sum)) => format!(
            "added up, the layers {} {} after layer {} (`max_drift` is {}) and {} after the last of the {} layers",
            if sum < 0.0 { "fall short by" } else { "overshoot by" },
            mm(sum.abs()),
            layer + 1,
            mm(dr.limit),
            mm(dr.last.abs()),
            dr.layers
        ),
        None => format!(
            "added up over the {} layers the error stays within {} (`max_drift` {})",
            dr.layers,
            mm(dr.largest.abs()),
            mm(dr.limit)
        ),
    };
    let d = Diagnostic::error(Code::Deposit, msg)
        .label_opt(bead, "the bead model")
        .label_opt(slicing, "the layers");
    let mut help = format!("{drift}. ");
    if let Some(s) = &m.style {
        help.push_str(&style_speed(s, m.tolerance));
    } else if let Some(p) = &m.point {
        match p.needs {
            Some(v) => help.push_str(&format!(
                "at the worst point {} mm/s lays the planned {}",
                trimmed(v, 2),
                mm(p.planned)
            )),
            // One height fits every strip only where the strips agree.
            None if m.strips[1] > m.strips[0] * (1.0 + m.tolerance) => help.push_str(&format!(
                "the bead is measured at one speed, and the tracks fill strips from {} to {} wide (where they lie: a contour a bead from its neighbours fills the bead, a loop that comes back within a bead of itself less), which it raises by different heights: measure the bead over a speed range (`speed = … .. …` with a `linear(…)` or `table(…)` model) and the slicer runs each strip at the speed that lays its layer",
                mm(m.strips[0]),
                mm(m.strips[1])
            )),
            None => help.push_str(&format!(
                "the bead is measured at one speed, where it raises this strip {} a layer: plan that height",
                mm(p.rise)
            )),
        }
        if p.style != 0 {
            help.push_str(&format!(
                " (its style {} sets the speed: a style changes the bead the model lays)",
                p.style
            ));
        }
        help.push_str("; ");
    }
    help.push_str("let the slicer pick the speeds and layer heights (`layer_height = auto`, `layers = auto`), or give the bead model as it was measured (`measured_as`)");
    d.help(help)
}

/// The speed a style's own speed should take, or why none does. Speeds are
/// printed to 0.01 mm/s inside the range that passes.
fn style_speed(s: &StyleSpeeds, tolerance: f64) -> String {
    let strips = if s.strips[1] > s.strips[0] * (1.0 + 1e-3) {
        format!("strips {} to {} wide", mm(s.strips[0]), mm(s.strips[1]))
    } else {
        format!("strips {} wide", mm(s.strips[0]))
    };
    let leave = "or leave `speed` out of the style and the slicer runs each strip at the speed that lays its layer";
    match s.fits {
        Some((v, [lo, hi])) => {
            let lo = (lo * 100.0).ceil() / 100.0;
            let hi = (hi * 100.0).floor() / 100.0;
            let v = ((v * 100.0).round() / 100.0).max(lo).min(hi);
            format!(
                "style {} sets the speed of its tracks, which fill {strips}: `speed = {} mm/s` in it lays them the planned height on the whole, each within {} (each stays within it from {} to {} mm/s, though away from the middle the layers' errors add up), {leave}; ",
                s.style,
                trimmed(v, 2),
                percent(tolerance),
                trimmed(lo, 2),
                trimmed(hi, 2)
            )
        }
        None => format!(
            "style {} sets one speed for tracks that fill {strips}, which no one speed raises alike within {}: leave `speed` out of the style and the slicer runs each strip at the speed that lays its layer, or pick tracks whose strips agree; ",
            s.style,
            percent(tolerance)
        ),
    }
}
