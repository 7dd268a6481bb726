//! `lmd::reach`'s reports: a part the arm cannot reach, found pose by pose
//! or from the part's points before any pose is solved
//! ([`crate::plan::arm::reach::beyond`]), with the base that would bring it
//! within reach ([`crate::plan::arm::reach::fix`]) as the help.

use super::Worst;
use crate::diag::message::verify::arm::{self as msg, ArmAt, ReachFix};
use crate::diag::Diagnostic;
use crate::ir::Machine;
use crate::numbers::trimmed;
use crate::plan::arm::reach::{fix, Beyond, Fix};
use crate::plan::arm::Along;
use crate::verify::rule::MachineCx;

/// Poses the arm cannot reach, the worst `w`, against its reach `span`.
pub(super) fn report(cx: &MachineCx<'_>, at: &ArmAt<'_>, w: &Worst, span: [f64; 2]) -> Diagnostic {
    with_fix(cx, |fix| msg::reach(at, w, span, false, fix))
}

/// A part beyond reach, found from its points: `b`.
pub(super) fn quick(cx: &MachineCx<'_>, at: &ArmAt<'_>, b: &Beyond) -> Diagnostic {
    let w = Worst {
        count: b.count,
        value: b.least,
        limit: b.span[1],
        at: Along { at: b.at, way: 1.0 },
    };
    with_fix(cx, |fix| msg::reach(at, &w, b.span, true, fix))
}

/// The report `make` writes with what would fix it.
fn with_fix(cx: &MachineCx<'_>, make: impl FnOnce(ReachFix<'_>) -> Diagnostic) -> Diagnostic {
    let Machine::Robot(r) = cx.machine else {
        return make(ReachFix::Unfound { across: 0.0 });
    };
    if r.positioner.is_some() {
        return make(ReachFix::Positioner);
    }
    match fix(cx.program, cx.machine) {
        Fix::Base(p) => {
            let n = |v: f64| trimmed(v, 6);
            let text = format!(
                "frame({}, x = {} mm, y = {} mm, z = {} mm, a = {} deg, b = {} deg, c = {} deg)",
                r.base.index,
                n(p.x),
                n(p.y),
                n(p.z),
                n(p.a),
                n(p.b),
                n(p.c)
            );
            make(ReachFix::Base(&text))
        }
        Fix::TooLarge { across, most } => make(ReachFix::TooLarge { across, most }),
        Fix::Unfound { across } => make(ReachFix::Unfound { across }),
    }
}
