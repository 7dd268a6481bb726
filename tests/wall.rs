//! A wall along an open path (`wall NAME { along = … }`): every bead lies
//! at its offset from the path (distances computed here, not by lmdc's
//! geometry), each layer's deposits and leads are as long as the path's
//! offsets and the leads, the layers are as many as the height over the
//! bead's rise, the beads alternate direction layer by layer, and random
//! open polylines are either refused with a diagnostic or laid within
//! tolerance of the path and inside the machine's travel.

use lmdc::ir::{PathKind, Program};
use lmdc::plan::{Move, MoveKind, Plan, Speed, Visit};
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};

/// A piece of a path: a line, or an arc (centre, radius, start and end
/// angles).
#[derive(Clone, Copy, Debug)]
enum Piece {
    Line([f64; 2], [f64; 2]),
    Arc([f64; 2], f64, f64, f64),
}

impl Piece {
    fn distance(&self, p: [f64; 2]) -> f64 {
        match *self {
            Piece::Line(a, b) => {
                let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                let t = (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy))
                    .clamp(0.0, 1.0);
                (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
            }
            Piece::Arc(c, r, from, to) => {
                let phi = (p[1] - c[1]).atan2(p[0] - c[0]);
                let (lo, hi) = (from.min(to), from.max(to));
                // Within the sweep (angles taken round to it).
                let inside = (0..3).any(|k| {
                    let a = phi + (k as f64 - 1.0) * 2.0 * PI;
                    (lo..=hi).contains(&a)
                });
                let ends = [from, to]
                    .map(|a| (p[0] - c[0] - r * a.cos()).hypot(p[1] - c[1] - r * a.sin()));
                if inside {
                    ((p[0] - c[0]).hypot(p[1] - c[1]) - r).abs()
                } else {
                    ends[0].min(ends[1])
                }
            }
        }
    }
}

fn distance(path: &[Piece], p: [f64; 2]) -> f64 {
    path.iter()
        .map(|s| s.distance(p))
        .fold(f64::INFINITY, f64::min)
}

/// examples/rib.lmd's path: 50 mm along x, a quarter circle of 10 mm
/// radius turning left, 30 mm along y.
fn rib_path() -> Vec<Piece> {
    vec![
        Piece::Line([0.0, 0.0], [50.0, 0.0]),
        Piece::Arc([50.0, 10.0], 10.0, -FRAC_PI_2, 0.0),
        Piece::Line([60.0, 10.0], [60.0, 40.0]),
    ]
}

/// The cross-section of a single track `w` wide and `h` high (a circular
/// segment), mm².
fn segment_area(w: f64, h: f64) -> f64 {
    let r = (w * w / 4.0 + h * h) / (2.0 * h);
    r * r * ((r - h) / r).acos() - (r - h) * (2.0 * r * h - h * h).sqrt()
}

fn compile(src: &str) -> Program {
    let c = lmdc::pipeline::compile(src, &mut ());
    let m: Vec<String> = c.diagnostics.iter().map(|d| d.message.clone()).collect();
    c.program
        .unwrap_or_else(|| panic!("{}", m.join("\n")))
        .into_ir()
}

fn rib(edits: &[(&str, &str)]) -> Program {
    let mut src = std::fs::read_to_string("examples/rib.lmd").unwrap();
    for (a, b) in edits {
        assert!(src.contains(a), "{a}");
        src = src.replace(a, b);
    }
    compile(&src)
}

/// The bead of examples/rib.lmd at 10 mm/s: 3 mm wide, 1 mm high.
const W: f64 = 3.0;
const H: f64 = 1.0;

fn length(points: &[lmdc::ir::Point]) -> f64 {
    points
        .windows(2)
        .map(|w| (w[1].pos[0] - w[0].pos[0]).hypot(w[1].pos[1] - w[0].pos[1]))
        .sum()
}

#[test]
fn every_bead_of_the_rib_lies_at_its_offset_from_the_edge() {
    let p = rib(&[]);
    let path = rib_path();
    // Two beads on the left of the path, A/h apart: half a bead and half a
    // bead plus the offset from it.
    let pitch = segment_area(W, H) / H;
    let offsets = [W / 2.0, W / 2.0 + pitch];
    let mut seen = [0usize; 2];
    for layer in &p.layers {
        for path_ in layer.paths.iter().filter(|q| q.kind == PathKind::Wall) {
            let d = distance(&path, [path_.points[0].pos[0], path_.points[0].pos[1]]);
            let j = if (d - offsets[0]).abs() < (d - offsets[1]).abs() {
                0
            } else {
                1
            };
            seen[j] += 1;
            for q in &path_.points {
                let e = distance(&path, [q.pos[0], q.pos[1]]) - offsets[j];
                assert!(
                    e.abs() < 1e-6,
                    "layer {}: {:?} is {e} mm off",
                    layer.index,
                    q.pos
                );
                // Left of the path: inside the L.
                assert!(q.pos[1] >= -1e-9 && q.pos[0] <= 60.0 + 1e-9, "{:?}", q.pos);
            }
        }
    }
    assert_eq!(seen, [p.layers.len(); 2]);
}

#[test]
fn layers_are_the_height_over_the_beads_rise() {
    // Two beads at the flat-top offset A/h rise h a layer: 10 mm in 10.
    let p = rib(&[]);
    assert_eq!(p.layers.len(), 10);
    // One bead centred on the path rises A/w: 10 mm in ⌈10 / (A/w)⌉.
    let one = rib(&[
        ("beads = 2 ", "beads = 1 "),
        ("side = left ", "side = centre "),
    ]);
    let rise = segment_area(W, H) / W;
    assert_eq!(one.layers.len(), (10.0 / rise).ceil() as usize);
    for (k, layer) in one.layers.iter().enumerate() {
        for q in layer.paths.iter().flat_map(|p| &p.points) {
            assert!((q.pos[2] - k as f64 * rise).abs() < 1e-6);
            assert!((q.layer_height as f64 - rise).abs() < 1e-5);
        }
    }
}

/// Per layer, the length of the deposits and of the leads in `m`'s plan.
fn plan_lengths(p: &Program, m: usize) -> Vec<[f64; 2]> {
    struct Sum {
        at: Option<[f64; 3]>,
        layer: usize,
        out: Vec<[f64; 2]>,
        speed: f32,
    }
    impl Visit for Sum {
        fn layer(&mut self, index: usize, _: &lmdc::ir::Layer) {
            self.layer = index;
            self.out.push([0.0; 2]);
        }
        fn motion(&mut self, m: &Move) {
            let from = self.at.replace(m.to);
            let Some(f) = from else { return };
            let d = (0..3).map(|i| (m.to[i] - f[i]).powi(2)).sum::<f64>().sqrt();
            match m.kind {
                MoveKind::Deposit => self.out[self.layer][0] += d,
                MoveKind::LeadIn | MoveKind::LeadOut => {
                    // At the bead's speed, not at rapid.
                    assert_eq!(m.speed, Speed::Feed(self.speed));
                    self.out[self.layer][1] += d;
                }
                _ => {}
            }
        }
    }
    let mut s = Sum {
        at: None,
        layer: 0,
        out: Vec::new(),
        speed: 10.0,
    };
    Plan::new(p, &p.machines[m]).walk(&mut s);
    s.out
}

#[test]
fn each_layer_lays_the_paths_offsets_and_runs_the_leads() {
    let one = rib(&[
        ("beads = 2 ", "beads = 1 "),
        ("side = left ", "side = centre "),
    ]);
    let along = 50.0 + 30.0 + 10.0 * FRAC_PI_2;
    for m in 0..one.machines.len() {
        for (k, [laid, leads]) in plan_lengths(&one, m).into_iter().enumerate() {
            assert!(
                (laid - along).abs() < 1e-3 * along,
                "layer {k}: {laid} mm laid, path {along}"
            );
            assert!((leads - 6.0).abs() < 1e-6, "layer {k}: leads {leads}");
        }
    }
    // Two beads: the inner one's quarter circle is the offset's shorter.
    let p = rib(&[]);
    let pitch = segment_area(W, H) / H;
    let both: f64 = [W / 2.0, W / 2.0 + pitch]
        .iter()
        .map(|d| 80.0 + (10.0 - d) * FRAC_PI_2)
        .sum();
    for (k, [laid, leads]) in plan_lengths(&p, 0).into_iter().enumerate() {
        assert!(
            (laid - both).abs() < 1e-3 * both,
            "layer {k}: {laid} mm laid, offsets {both}"
        );
        assert!((leads - 12.0).abs() < 1e-6, "layer {k}: leads {leads}");
    }
}

#[test]
fn each_bead_runs_the_other_way_from_the_one_below() {
    for beads in ["beads = 1 ", "beads = 2 ", "beads = 3 "] {
        let p = rib(&[("beads = 2 ", beads)]);
        // Each bead by its distance from the path, and which end it starts at.
        let starts = |k: usize| -> Vec<(i64, bool)> {
            let mut v: Vec<(i64, bool)> = p.layers[k]
                .paths
                .iter()
                .filter(|q| q.kind == PathKind::Wall)
                .map(|q| {
                    let a = q.points[0].pos;
                    let d = distance(&rib_path(), [a[0], a[1]]);
                    ((d * 1000.0).round() as i64, a[1] < 20.0)
                })
                .collect();
            v.sort();
            v
        };
        for k in 1..p.layers.len() {
            let (a, b) = (starts(k - 1), starts(k));
            assert_eq!(a.len(), b.len());
            for (x, y) in a.iter().zip(&b) {
                assert_eq!(x.0, y.0);
                assert_ne!(
                    x.1, y.1,
                    "{beads}: layer {k} starts its bead at the same end"
                );
            }
        }
    }
    // One way: every bead from the path's start, and its lead-in before it.
    let p = rib(&[("direction = alternate ", "direction = one_way ")]);
    for layer in &p.layers {
        for w in layer.paths.windows(3) {
            if w[1].kind == PathKind::Wall {
                assert!(w[1].points[0].pos[1] < 5.0 && w[1].points[0].pos[0] < 1e-9);
                assert_eq!(w[0].kind, PathKind::Lead);
                assert_eq!(w[2].kind, PathKind::Lead);
                let lead_in = &w[0].points;
                assert!(lead_in.iter().all(|q| !q.laser_on));
                assert!(
                    (lead_in[0].pos[0] + 3.0).abs() < 1e-9,
                    "{:?}",
                    lead_in[0].pos
                );
            }
        }
    }
}

#[test]
fn stopping_ends_have_no_leads_and_switch_at_the_paths_ends() {
    let p = rib(&[("ends = lead(length = 3 mm) ", "ends = stop ")]);
    assert!(p
        .layers
        .iter()
        .flat_map(|l| &l.paths)
        .all(|q| q.kind == PathKind::Wall));
    for [_, leads] in plan_lengths(&p, 0) {
        assert_eq!(leads, 0.0);
    }
    let first = &p.layers[0].paths[0].points;
    assert!(
        (length(first) - (80.0 + (10.0 - W / 2.0 - segment_area(W, H) / H) * FRAC_PI_2)).abs()
            < 0.1
    );
}

/// Whether segments `a`–`b` and `c`–`d` come within `gap` of each other.
fn near(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2], gap: f64) -> bool {
    let seg = |p: [f64; 2], a: [f64; 2], b: [f64; 2]| Piece::Line(a, b).distance(p);
    let cross = |o: [f64; 2], p: [f64; 2], q: [f64; 2]| {
        (p[0] - o[0]) * (q[1] - o[1]) - (p[1] - o[1]) * (q[0] - o[0])
    };
    let proper = cross(a, b, c) * cross(a, b, d) < 0.0 && cross(c, d, a) * cross(c, d, b) < 0.0;
    proper
        || seg(a, c, d)
            .min(seg(b, c, d))
            .min(seg(c, a, b))
            .min(seg(d, a, b))
            < gap
}

/// A random walk of `steps` (length, turn in degrees) from the origin.
fn walk(steps: &[(f64, f64)]) -> Vec<[f64; 2]> {
    let (mut p, mut heading) = ([0.0f64, 0.0f64], 0.0f64);
    let mut out = vec![p];
    for &(len, turn) in steps {
        heading += turn.to_radians();
        p = [p[0] + len * heading.cos(), p[1] + len * heading.sin()];
        out.push(p);
    }
    out
}

fn source(points: &[[f64; 2]], beads: usize, side: &str, ends: &str) -> String {
    let pts: Vec<String> = points
        .iter()
        .map(|p| format!("[{:.4} mm, {:.4} mm]", p[0], p[1]))
        .collect();
    let text = std::fs::read_to_string("examples/rib.lmd").unwrap();
    // The CNC alone: the robot's arm checks are the slow part.
    let cnc = text.split("machine kr30 {").next().unwrap_or_default();
    cnc.lines()
        .filter(|l| {
            let l = l.trim_start();
            !l.starts_with("arc(") && !l.starts_with("polyline(points = [[60")
        })
        .collect::<Vec<_>>()
        .join("\n")
        .replace(
            "polyline(points = [[0 mm, 0 mm], [50 mm, 0 mm]]),",
            &format!("polyline(points = [{}]),", pts.join(", ")),
        )
        .replace("beads = 2 ", &format!("beads = {beads} "))
        .replace("side = left ", &format!("side = {side} "))
        .replace("ends = lead(length = 3 mm) ", &format!("ends = {ends} "))
        .replace("height = 10 mm", "height = 3 mm")
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Random open polylines that do not cross themselves: a plan is
    /// either refused with a diagnostic about the path (a bend too tight
    /// for the wall) or every bead of it lies at its offset from the path,
    /// and every point of it inside the machine's travel.
    #[test]
    fn random_open_paths_are_laid_at_their_offsets_or_refused(
        steps in prop::collection::vec((4.0f64..40.0, -150.0f64..150.0), 1..7),
        beads in 1usize..4,
        side in 0usize..3,
        lead in any::<bool>(),
    ) {
        let points = walk(&steps);
        let n = points.len();
        for i in 0..n - 1 {
            for j in i + 2..n - 1 {
                prop_assume!(!near(points[i], points[i + 1], points[j], points[j + 1], 0.01));
            }
        }
        let side = ["centre", "left", "right"][side];
        let ends = if lead { "lead(length = 3 mm)" } else { "stop" };
        let src = source(&points, beads, side, ends);
        let c = lmdc::pipeline::compile(&src, &mut ());
        let Some(v) = c.program else {
            let codes: Vec<String> = c.diagnostics.iter().filter(|d| d.is_error()).map(|d| d.code.to_string()).collect();
            prop_assert!(!codes.is_empty());
            prop_assert!(
                codes.iter().all(|c| ["lmd::path-bend", "lmd::axis-limit", "lmd::collision"].contains(&c.as_str())),
                "{codes:?}"
            );
            return Ok(());
        };
        let p = v.into_ir();
        let path: Vec<Piece> = points.windows(2).map(|w| Piece::Line(w[0], w[1])).collect();
        let pitch = segment_area(W, H) / H;
        let pitch = if beads > 1 { pitch } else { W };
        let offsets: Vec<f64> = (0..beads)
            .map(|j| match side {
                "centre" => (j as f64 - (beads - 1) as f64 / 2.0).abs() * pitch,
                _ => W / 2.0 + j as f64 * pitch,
            })
            .collect();
        let origin = [250.0, 150.0, 40.0];
        for q in p.layers.iter().flat_map(|l| &l.paths).filter(|q| q.kind == PathKind::Wall).flat_map(|q| &q.points) {
            let d = distance(&path, [q.pos[0], q.pos[1]]);
            let e = offsets.iter().map(|o| (d - o).abs()).fold(f64::INFINITY, f64::min);
            prop_assert!(e < 1e-4, "{:?} is {d} mm from the path, offsets {offsets:?}", q.pos);
        }
        for q in p.layers.iter().flat_map(|l| &l.paths).flat_map(|q| &q.points) {
            let at = [q.pos[0] + origin[0], q.pos[1] + origin[1], q.pos[2] + origin[2]];
            prop_assert!((0.0..=500.0).contains(&at[0]) && (0.0..=400.0).contains(&at[1]) && (0.0..=300.0).contains(&at[2]), "{at:?}");
            prop_assert!(q.pos.iter().all(|c| c.is_finite()));
        }
    }
}
