//! The head against the cell (issue 32, docs/collision.md): each collision
//! case is refused with its numbers, and following the help builds; and a
//! property over random heads and fixtures compares lmdc's verdict with a
//! distance computed here, independently: points sampled on the head's
//! solids at poses along every move of the plan, against the fixture's box.

use lmdc::diag::Code;
use lmdc::pipeline::compile;
use lmdc::plan::{Move, MoveKind, Visit};
use proptest::prelude::*;

fn case(name: &str) -> String {
    std::fs::read_to_string(format!("tests/cases/errors/collision/{name}/input.lmd")).unwrap()
}

/// The number after `before` in `text`.
fn number_after(text: &str, before: &str) -> f64 {
    let at = text
        .find(before)
        .unwrap_or_else(|| panic!("no `{before}` in {text}"))
        + before.len();
    let s: String = text[at..]
        .chars()
        .take_while(|c| c.is_ascii_digit() || *c == '.' || *c == '-')
        .collect();
    s.parse().unwrap()
}

#[test]
fn a_steep_nozzle_over_the_plate_is_refused_and_the_standoff_it_names_builds() {
    let src = case("nozzle_plate");
    let c = compile(&src, &mut ());
    assert!(c.program.is_none());
    let d = c
        .diagnostics
        .iter()
        .find(|d| d.code == Code::Collision)
        .expect("lmd::collision");
    assert!(d.message.contains("of the plate"), "{}", d.message);
    let close = number_after(&d.message, "comes within ");
    assert!(close > 0.0 && close < 2.0, "{}", d.message);
    let help = d.help.as_deref().unwrap();
    let standoff = number_after(help, "a `standoff` of ");
    assert!(standoff > 15.0, "{help}");
    let fixed = src.replace("standoff = 15 mm", &format!("standoff = {standoff} mm"));
    let c = compile(&fixed, &mut ());
    assert!(c.program.is_some(), "{:#?}", c.diagnostics);
    // The plate was the only obstacle: a hundredth less is refused again.
    let short = src.replace(
        "standoff = 15 mm",
        &format!("standoff = {} mm", standoff - 0.01),
    );
    assert!(compile(&short, &mut ()).program.is_none());
}

#[test]
fn a_body_running_into_the_layer_it_builds_is_refused_without_a_standoff() {
    let c = compile(&case("body_part"), &mut ());
    let d = c
        .diagnostics
        .iter()
        .find(|d| d.code == Code::Collision && d.message.contains("the body"))
        .expect("the body's collision");
    assert!(
        d.message.contains("the part laid so far (layer"),
        "{}",
        d.message
    );
    // Raising the head does not take the body off the part beside it.
    assert!(!d.help.as_deref().unwrap().contains("`standoff` of"));
}

#[test]
fn a_fixture_in_the_heads_way_is_refused_and_moved_away_builds() {
    let src = case("head_fixture");
    let c = compile(&src, &mut ());
    let msgs: Vec<&str> = c
        .diagnostics
        .iter()
        .filter(|d| d.code == Code::Collision)
        .map(|d| d.message.as_str())
        .collect();
    assert_eq!(msgs.len(), 2, "both machines: {msgs:?}");
    assert!(msgs.iter().all(|m| m.contains("fixture `clamp`")));
    let moved = src.replace("at = [20 mm, 0 mm, 0 mm]", "at = [60 mm, 0 mm, 0 mm]");
    let c = compile(&moved, &mut ());
    assert!(c.program.is_some(), "{:#?}", c.diagnostics);
}

/// The head's solids of a machine, as (start, end, radius at start, at
/// end) up the beam from the focus.
fn solids(head: &lmdc::ir::Head) -> Vec<[f64; 4]> {
    let mut s = head.standoff;
    head.bodies
        .iter()
        .map(|b| {
            let f = [s, s + b.length, b.diameters[0] / 2.0, b.diameters[1] / 2.0];
            s += b.length;
            f
        })
        .collect()
}

/// Points on the surface of the solids at a pose, about 1 mm apart.
fn surface(solids: &[[f64; 4]], focus: [f64; 3], up: [f64; 3]) -> Vec<[f64; 3]> {
    let e1 = {
        let t = if up[0].abs() < 0.6 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let c = [
            up[1] * t[2] - up[2] * t[1],
            up[2] * t[0] - up[0] * t[2],
            up[0] * t[1] - up[1] * t[0],
        ];
        let l = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
        c.map(|x| x / l)
    };
    let e2 = [
        up[1] * e1[2] - up[2] * e1[1],
        up[2] * e1[0] - up[0] * e1[2],
        up[0] * e1[1] - up[1] * e1[0],
    ];
    let at = |s: f64, r: f64, a: f64| {
        let (sin, cos) = a.sin_cos();
        [0, 1, 2].map(|i| focus[i] + s * up[i] + r * (cos * e1[i] + sin * e2[i]))
    };
    let mut out = Vec::new();
    for &[s0, s1, r0, r1] in solids {
        let rings = ((s1 - s0) / 1.0).ceil() as usize;
        for k in 0..=rings {
            let t = k as f64 / rings as f64;
            let (s, r) = (s0 + t * (s1 - s0), r0 + t * (r1 - r0));
            let around = ((std::f64::consts::TAU * r) / 1.0).ceil().max(8.0) as usize;
            for j in 0..around {
                out.push(at(s, r, std::f64::consts::TAU * j as f64 / around as f64));
            }
        }
        // The end discs.
        for (s, r) in [(s0, r0), (s1, r1)] {
            let n = (r / 1.0).ceil() as usize;
            for q in 0..n {
                let rr = r * q as f64 / n as f64;
                let around = ((std::f64::consts::TAU * rr) / 1.0).ceil().max(1.0) as usize;
                for j in 0..around {
                    out.push(at(s, rr, std::f64::consts::TAU * j as f64 / around as f64));
                }
            }
        }
    }
    out
}

/// The distance from `p` to the box `lo`–`hi`.
fn to_box(p: [f64; 3], lo: [f64; 3], hi: [f64; 3]) -> f64 {
    (0..3)
        .map(|i| (lo[i] - p[i]).max(p[i] - hi[i]).max(0.0).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// Every move's poses, about every 2 mm along it.
struct Poses {
    last: Option<[f64; 3]>,
    out: Vec<[f64; 3]>,
}

impl Visit for Poses {
    fn motion(&mut self, m: &Move) {
        if m.kind == MoveKind::Home {
            return;
        }
        if let Some(a) = self.last {
            let d = (0..3).map(|i| (m.to[i] - a[i]).powi(2)).sum::<f64>().sqrt();
            let n = (d / 2.0).ceil().max(1.0) as usize;
            for k in 1..n {
                let t = k as f64 / n as f64;
                self.out
                    .push([0, 1, 2].map(|i| a[i] + t * (m.to[i] - a[i])));
            }
        }
        self.out.push(m.to);
        self.last = Some(m.to);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, ..ProptestConfig::default() })]

    /// A clamp of random size and place beside the plate, a head of random
    /// standoff and nozzle: where the head, sampled here at every pose of
    /// the 3-axis mill's plan, comes within the gap of the clamp less the
    /// sampling's own error, lmdc refuses the plan for the clamp; where it
    /// keeps the gap plus the error lmdc allows itself (the clamp's surface
    /// as lumps 2 mm apart), lmdc does not.
    #[test]
    fn the_verdict_on_a_fixture_agrees_with_an_independent_distance(
        x in 12.0f64..45.0,
        y in -15.0f64..15.0,
        size in prop::array::uniform3(4.0f64..20.0),
        standoff in 8.0f64..25.0,
        top in 20.0f64..50.0,
    ) {
        let src = std::fs::read_to_string("tests/codes/plate.lmd").unwrap()
            .replace("machine kr {", "machine kr_unused {")
            .replace("standoff = 15 mm", &format!("standoff = {standoff} mm"))
            .replace("top = 40 mm", &format!("top = {top} mm"))
            + &format!(
                "\nfixture clamp {{\n  shape = box(size = [{} mm, {} mm, {} mm])\n  at = [{x} mm, {y} mm, 0 mm]\n}}\n",
                size[0], size[1], size[2]
            );
        let c = lmdc::pipeline::compile_for(&src, Some("mill"), &mut ()).unwrap();
        let refused = c.diagnostics.iter().any(|d| d.code == Code::Collision && d.message.contains("fixture `clamp`"));
        // The independent distance, over the plan of the same IR.
        let ir = match &c.program {
            Some(p) => p.ir().clone(),
            None => {
                // Rebuild without the fixture for the plan's poses.
                let bare = src.split("\nfixture clamp").next().unwrap().to_string();
                lmdc::pipeline::compile_for(&bare, Some("mill"), &mut ()).unwrap().program.expect("builds bare").ir().clone()
            }
        };
        let m = ir.machines.iter().find(|m| m.name() == "mill").unwrap();
        let mut poses = Poses { last: None, out: Vec::new() };
        lmdc::plan::Plan::new(&ir, m).walk(&mut poses);
        let head = &m.common().head;
        let sol = solids(head);
        let lo = [x - size[0] / 2.0, y - size[1] / 2.0, 0.0];
        let hi = [x + size[0] / 2.0, y + size[1] / 2.0, size[2]];
        let mut near = f64::INFINITY;
        for f in &poses.out {
            // Skip poses whose head cannot come near (its bounding sphere).
            let reach = sol.last().unwrap()[1] + 60.0;
            if to_box(*f, lo, hi) > reach {
                continue;
            }
            for p in surface(&sol, *f, [0.0, 0.0, 1.0]) {
                near = near.min(to_box(p, lo, hi));
            }
        }
        let gap = head.gap;
        // Sampling here: points 1 mm apart on the head, poses 2 mm apart.
        let mine = 1.5;
        // lmdc's allowance: the clamp's lumps stand for 2 mm patches.
        let its = 1.5;
        if near < gap - mine {
            prop_assert!(refused, "head {near:.3} mm from the clamp, accepted");
        }
        if near > gap + its {
            prop_assert!(!refused, "head {near:.3} mm from the clamp, refused: {:#?}", c.diagnostics);
        }
    }
}
