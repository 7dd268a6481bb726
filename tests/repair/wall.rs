//! A wall along an open path built on a scan (`wall { on = scan(…)  top =
//! … }`, docs/repair.md, *A wall on a scan*): a rib on the worn pad's scan
//! (examples/repair/worn_pad.ply, whose surface is `example_z`) starts on
//! the scanned surface under each bead and ends level at its top, in the
//! fewest layers the bead's heights allow, and lays the volume between the
//! scan and the top; what cannot be built is refused with where and why;
//! its finish is predicted and held; and every travel across the scan, of
//! the rib and of the worn pad, clears it.

use super::{compile, example_files, example_z, messages, number_after};
use lmdc::ir::{PathKind, Program};

/// examples/pad_rib.lmd with its `along`, `top` and `beads` replaced.
fn rib(along: &str, top: f64, beads: usize) -> String {
    rib_to(along, &format!("{top} mm"), beads)
}

/// examples/pad_rib.lmd with its `along`, `top` (as written) and `beads`
/// replaced.
pub(super) fn rib_to(along: &str, top: &str, beads: usize) -> String {
    let example = include_str!("../../examples/pad_rib.lmd");
    let from = example.find("  along = chain(").unwrap();
    let to = example.find("  beads = 2").unwrap();
    let mut src = example.to_string();
    src.replace_range(from..to, &format!("  along = {along}\n"));
    src.replace("top = 13 mm", &format!("top = {top}"))
        .replace("beads = 2", &format!("beads = {beads}"))
}

pub(super) const STRAIGHT: &str = "polyline(points = [[-25 mm, 0 mm], [20 mm, 0 mm]])";

pub(super) fn built(src: &str) -> Program {
    let c = compile(src, example_files(&["worn_pad.ply"]));
    match c.program {
        Some(p) => p.into_ir(),
        None => panic!("{}", messages(&c)),
    }
}

/// The laser-on points of the beads (not the leads) of layer `i`.
pub(super) fn bead_points(p: &Program, i: usize) -> Vec<lmdc::ir::Point> {
    p.layers[i]
        .paths
        .iter()
        .filter(|path| path.kind == PathKind::Wall)
        .flat_map(|path| path.points.iter().copied())
        .collect()
}

/// The volume the plan's laser-on moves stack: layer height × pitch ×
/// run.
pub(super) fn stacked(p: &Program) -> f64 {
    let mut sum = 0.0;
    for path in p.layers.iter().flat_map(|l| &l.paths) {
        for w in path.points.windows(2).filter(|w| w[0].laser_on) {
            let run = (w[1].pos[0] - w[0].pos[0]).hypot(w[1].pos[1] - w[0].pos[1]);
            sum += f64::from(w[0].layer_height) * f64::from(w[0].pitch) * run;
        }
    }
    sum
}

/// `∫ (top − z)` over the straight rib's band, x −25..20 mm and two
/// pitches across, from the pad's formula (900 × 100 cells); `top` a
/// function of x.
pub(super) fn band_integral_to(pitch: f64, top: impl Fn(f64) -> f64) -> f64 {
    let (nx, ny) = (900, 100);
    let (dx, dy) = (45.0 / nx as f64, 2.0 * pitch / ny as f64);
    let mut integral = 0.0;
    for i in 0..nx {
        for j in 0..ny {
            let x = -25.0 + (i as f64 + 0.5) * dx;
            let y = -pitch + (j as f64 + 0.5) * dy;
            integral += (top(x) - example_z(x, y)) * dx * dy;
        }
    }
    integral
}

/// `∫ (13 − z)` over the straight rib's band.
fn band_integral(pitch: f64) -> f64 {
    band_integral_to(pitch, |_| 13.0)
}

/// A straight rib two beads wide across the pad's trough, to 13 mm: its
/// beads run on the lines `y = ±p/2` (`p` their pitch) from x = −25 to 20
/// mm; the first layer lies on the scanned surface within the scanner's
/// noise and the surface estimate's fit (0.1 mm), every layer `i` of `N`
/// at `B + i·(13 − B)/N` and the last ending at 13 mm. `N` is the fewest
/// whose layers are within the bead's heights over the gaps the formula
/// gives along the lines, and the layers stack the integral of `13 − z`
/// over the band the beads fill (two pitches wide) within 2 %.
#[test]
fn a_rib_on_the_worn_pad_starts_on_its_scan_and_ends_level_at_its_top() {
    let p = built(&rib(STRAIGHT, 13.0, 2));
    let n = p.layers.len();
    let first = bead_points(&p, 0);
    let pitch = f64::from(first[0].pitch);
    for q in &first {
        let [x, y, z] = q.pos;
        // The pitch is kept to f32 in the IR.
        assert!((y.abs() - pitch / 2.0).abs() < 1e-6, "{y} off its line");
        assert!((-25.0 - 1e-9..=20.0 + 1e-9).contains(&x), "{x}");
        assert!((z - example_z(x, y)).abs() < 0.1, "({x}, {y}): {z}");
    }
    // Each bead runs the other way from the one below it, and the layers
    // take the beads in turn across the wall.
    let runs = |i: usize| runs(&p, i);
    for i in 1..n {
        let (below, here) = (runs(i - 1), runs(i));
        assert_eq!(here.len(), 2);
        assert_eq!(
            here[0].0,
            below[1].0,
            "layer {i} starts where {} ended",
            i - 1
        );
        for (side, forward) in &here {
            let under = below.iter().find(|b| b.0 == *side).unwrap();
            assert_ne!(*forward, under.1, "layer {i}: a bead runs as the one below");
        }
    }
    for i in 0..n {
        for q in bead_points(&p, i) {
            let h = f64::from(q.layer_height);
            let want = 13.0 - (n - i) as f64 * h;
            assert!((q.pos[2] - want).abs() < 1e-4, "layer {i}: {q:?}");
        }
    }
    // The fewest layers over the gaps along the lines.
    let [lo, hi] = p.limits.layer_height;
    let gaps: Vec<f64> = (0..=450)
        .flat_map(|k| {
            let x = -25.0 + 0.1 * k as f64;
            [-pitch / 2.0, pitch / 2.0].map(|y| 13.0 - example_z(x, y))
        })
        .collect();
    let (g_lo, g_hi) = gaps
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), &g| (a.min(g), b.max(g)));
    let fewest = (g_hi / hi).ceil();
    assert!(
        (g_hi / hi - fewest).abs() > 0.05,
        "too near a whole count to tell"
    );
    assert_eq!(n as f64, fewest, "gaps {g_lo} .. {g_hi}, bead {lo} .. {hi}");
    assert!(g_lo / fewest >= lo, "{g_lo} / {fewest} < {lo}");
    // The volume: stacked by the plan, and between the scan and the top.
    let (stacked, integral) = (stacked(&p), band_integral(pitch));
    assert!(
        (stacked / integral - 1.0).abs() < 0.02,
        "stacked {stacked} mm³ vs ∫ {integral} mm³"
    );
}

/// The example: its path's arc and its leads. The lead before each bead
/// runs 3 mm straight into the bead's first point and the one after 3 mm
/// on from its last, laser off, at the bead's height and speed there; the
/// last layer ends at 13 mm on the arc too; the report measures the band
/// the rib covers (two pitches and a bead's flanks: `p + w` wide) and
/// finds the plan stacking `2p/(p + w)` of it within 1 %.
#[test]
fn the_pad_rib_example_runs_its_leads_and_is_measured_by_its_band() {
    let src = include_str!("../../examples/pad_rib.lmd");
    let p = built(src);
    for layer in &p.layers {
        let paths = &layer.paths;
        assert_eq!(paths.len(), 6);
        for k in (0..6).step_by(3) {
            let (into, bead, out) = (&paths[k], &paths[k + 1], &paths[k + 2]);
            assert_eq!(
                [into.kind, bead.kind, out.kind],
                [PathKind::Lead, PathKind::Wall, PathKind::Lead]
            );
            let (a, b) = (into.points[1], bead.points[0]);
            assert_eq!(a.pos, b.pos);
            assert_eq!((a.speed, a.layer_height), (b.speed, b.layer_height));
            let run = into.points[1].pos[0] - into.points[0].pos[0];
            let rise = into.points[1].pos[1] - into.points[0].pos[1];
            assert!((run.hypot(rise) - 3.0).abs() < 1e-9);
            assert!(into.points.iter().chain(&out.points).all(|q| !q.laser_on));
            let last = bead.points[bead.points.len() - 1];
            assert_eq!(out.points[0].pos, last.pos);
        }
    }
    let last = bead_points(&p, p.layers.len() - 1);
    let on_arc = last
        .iter()
        .filter(|q| q.pos[0] > 10.5 && q.pos[1] > 0.5 && q.pos[1] < 4.5)
        .count();
    assert!(on_arc > 4, "{on_arc} points on the arc");
    for q in &last {
        assert!((q.pos[2] + f64::from(q.layer_height) - 13.0).abs() < 1e-4);
    }
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_lmdc"))
        .args(["report", "examples/pad_rib.lmd"])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    let design = number_after(&text, "design      ", ' ');
    let stacked = number_after(&text, "the layers stack ", ' ');
    let pitch = f64::from(bead_points(&p, 0)[0].pitch);
    let share = 2.0 * pitch / (pitch + 2.4);
    assert!(
        (stacked / design / share - 1.0).abs() < 0.01,
        "{stacked} of {design} mm³, not {share}: {text}"
    );
}

/// What cannot be built on the scan is refused, with where: a path off
/// the scan (`lmd::scan-coverage`, the first point and how many more), a
/// top below the scanned surface, a top no layer count reaches (with the
/// tops that work: each of them builds in the count named); and the
/// fields that do not go with a wall on a scan.
#[test]
fn a_rib_off_its_scan_below_it_or_between_counts_is_refused_with_where() {
    let files = || example_files(&["worn_pad.ply"]);
    let off = compile(
        &rib("polyline(points = [[20 mm, 0 mm], [40 mm, 0 mm]])", 13.0, 1),
        files(),
    );
    let m = messages(&off);
    // The scan's points reach x = 33 mm, its surface half a 1 mm cell
    // beyond; the rib is sampled every cell from x = 20 mm.
    assert!(
        m.contains("scan-coverage: the scan has no point under (34, 0) mm and at 6 other points"),
        "{m}"
    );
    let below = compile(&rib(STRAIGHT, 9.9, 1), files());
    let m = messages(&below);
    assert!(m.contains("is not above the scanned surface"), "{m}");
    // 0.3 .. 1.8 mm to add: no count lays both with a bead of ratio 2.
    let between = compile(&rib(STRAIGHT, 10.3, 1), files());
    let d = super::diagnostic(&between, "lmd::no-layer-count");
    let help = d.help.clone().unwrap();
    let lo = number_after(&help, "a top from ", ' ');
    let hi = number_after(&help, &format!("a top from {} to ", lo), ' ');
    let count = number_after(&help, "mm (", ' ');
    for top in [lo, hi] {
        let p = built(&rib(STRAIGHT, top, 1));
        assert_eq!(p.layers.len() as f64, count, "top {top}: {help}");
    }
}

/// The fields that do not go with a wall on a scan, each refused where it
/// is written: planar slicing, `height` beside `on`, `top` without `on`,
/// `on` without `top`, and the variable slicing's fields lmdc plans under
/// an extrusion only (`scan`, `direction`); `follow = surface` without a
/// tilted bead or a tilting machine.
#[test]
fn the_fields_a_wall_on_a_scan_does_not_take_are_refused() {
    let files = || example_files(&["worn_pad.ply"]);
    let codes = |src: &str| {
        let c = compile(src, files());
        assert!(c.program.is_none(), "{src}");
        messages(&c)
    };
    let src = rib(STRAIGHT, 13.0, 1);
    let planar = src.replace("slicing variable {", "slicing planar {");
    assert!(
        codes(&planar).contains("planar slicing does not build a wall on a scan"),
        "{}",
        codes(&planar)
    );
    let height = src.replace("top = 13 mm", "top = 13 mm\n  height = 3 mm");
    assert!(codes(&height).contains("a wall on a scan rises to its `top`"));
    let no_scan = src.replace(
        "on = scan(file = \"repair/worn_pad.ply\", units = mm, cell = 1 mm)",
        "",
    );
    assert!(codes(&no_scan).contains("`top` is the finished height of a wall built on a scan"));
    let no_top = src.replace("top = 13 mm", "");
    assert!(codes(&no_top).contains("`on = scan(…)` needs a `top`"));
    for field in ["scan = x", "direction = auto"] {
        let with = src.replace("layers = auto", &format!("layers = auto\n  {field}"));
        let key = field.split(' ').next().unwrap();
        let m = codes(&with);
        assert!(
            m.contains(&format!("`{key}` does not apply to a wall along a path")),
            "{field}: {m}"
        );
    }
    // The nozzle along the scan's normal needs a bead measured tilted and
    // a machine that tilts: the example's bead and mill3 are neither.
    let follow = src.replace("layers = auto", "layers = auto\n  follow = surface");
    let m = codes(&follow);
    assert!(
        m.contains("bead `b316` was measured with the nozzle vertical only"),
        "{m}"
    );
    assert!(m.contains("machine `mill3` moves X Y Z only"), "{m}");
}

/// The rib's finish (docs/repair.md, *A wall on a scan*): the bead
/// model's face at the middle of every move of the last layer, the scan
/// there plus what each layer's move over it raises it by. Its segments
/// each keep the mean of `|G − G_seg|` within the tolerance (0.1 mm), and
/// every layer lays `G_seg/N` where `G/N` was asked: the face departs
/// from the top by `G_seg − G` on the mean within that tolerance (and the
/// bead model's rises, held within 3 % of each layer's 1.12 mm at most).
/// `finish_tolerance` below its worst departure is refused with it; at
/// the worst, the plan is the one without it, byte for byte.
#[test]
fn a_ribs_finish_is_predicted_from_its_moves_and_held() {
    let src = include_str!("../../examples/pad_rib.lmd");
    let files = || example_files(&["worn_pad.ply"]);
    let (c, model) = crate::support::data::compile_with_files_and_model(src, files());
    let p = c.program.unwrap().into_ir();
    let (f, samples) = lmdc::report::finish::sampled(&p, &model.unwrap()).unwrap();
    assert_eq!(f.points, samples.len());
    let moves = p.layers[p.layers.len() - 1]
        .paths
        .iter()
        .filter(|path| path.kind == PathKind::Wall)
        .map(|path| path.points.len() - 1)
        .sum::<usize>();
    assert_eq!(f.points, moves);
    let mean = samples.iter().map(|s| s.off.abs()).sum::<f64>() / samples.len() as f64;
    assert!(mean <= 0.1 + 0.03 * 1.12, "mean departure {mean}");
    assert!(samples.iter().all(|s| s.top == 13.0));
    let worst = f.below_mm.max(f.above_mm);
    assert!(worst > 0.1, "{f:?}");
    let held = |t: f64| {
        let with = src.replace(
            "layers = auto",
            &format!("layers = auto\n  finish_tolerance = {t} mm"),
        );
        compile(&with, files())
    };
    let refused = held(0.1);
    let m = messages(&refused);
    assert!(m.contains("lmd::finish"), "{m}");
    assert!(
        m.contains(&format!("falls {} mm below the top", short(f.below_mm))),
        "{m}"
    );
    let kept = held((worst * 1e4).ceil() / 1e4);
    let plain = compile(src, files());
    let ir = |c: &lmdc::pipeline::Compiled| {
        serde_json::to_string(c.program.as_ref().expect("built").ir()).unwrap()
    };
    assert_eq!(ir(&kept), ir(&plain));
}

/// A length as lmdc prints it (four significant digits).
fn short(v: f64) -> String {
    lmdc::units::short(v)
}

/// Every travel that moves across the scanned part keeps the focus at
/// least the machine's clearance above the scanned surface (the pad's,
/// from its formula, within the scan's 0.1 mm of noise and fit), on both
/// machines of the rib and of the worn pad: the first travels, before
/// any bead is laid, have only the scan below them. And no move at all
/// (an approach, a lead, a bead) takes the focus under the scanned
/// surface: a lead on the first layer runs on at the bead's height above
/// the scan, where the scan rises past the path's end.
#[test]
fn every_travel_across_the_scan_clears_it_by_the_clearance() {
    use lmdc::plan::{Move, MoveKind, Plan};
    for example in ["examples/pad_rib.lmd", "examples/worn_pad.lmd"] {
        let src = std::fs::read_to_string(example).unwrap();
        let p = built(&src);
        let mut travels = 0;
        for m in &p.machines {
            let clearance = m.common().clearance;
            let mut last: Option<[f64; 3]> = None;
            Plan::new(&p, m).walk(&mut |mv: &Move| {
                if let Some(a) = last {
                    let b = mv.to;
                    let run = (b[0] - a[0]).hypot(b[1] - a[1]);
                    let across = mv.kind == MoveKind::Travel && run > 1e-6;
                    travels += usize::from(across);
                    let n = (run / 0.5).ceil().max(1.0) as usize;
                    for i in 0..=n {
                        let f = i as f64 / n as f64;
                        let q = [0, 1, 2].map(|k| a[k] + f * (b[k] - a[k]));
                        let on_scan = q[0].abs() <= 33.0 && q[1].abs() <= 13.0;
                        let surface = example_z(q[0], q[1]) - 0.1;
                        let floor = if across { surface + clearance } else { surface };
                        assert!(
                            !on_scan || q[2] >= floor,
                            "{example} on {}: a {:?} move at {q:?} under {floor}",
                            m.name(),
                            mv.kind
                        );
                    }
                }
                last = Some(mv.to);
            });
        }
        assert!(travels >= 8, "{example}: {travels} travels");
    }
}

/// The beads of a straight rib's layer `i` in the order laid: each one's
/// side of the path (`y > 0`) and whether it runs toward +x.
fn runs(p: &Program, i: usize) -> Vec<(bool, bool)> {
    p.layers[i]
        .paths
        .iter()
        .filter(|path| path.kind == PathKind::Wall)
        .map(|path| {
            let (a, b) = (path.points[0].pos, path.points[path.points.len() - 1].pos);
            (a[1] > 0.0, b[0] > a[0])
        })
        .collect()
}

/// Each bead of a straight rib (on `y < 0` or `y > 0`) runs the other way
/// from every bead under it on its line, passes and layers alike.
fn alternates(p: &Program) {
    let dirs = |i: usize| runs(p, i);
    for i in 1..p.layers.len() {
        let below = dirs(i - 1);
        for (side, forward) in dirs(i) {
            for under in below.iter().filter(|b| b.0 == side) {
                assert_ne!(forward, under.1, "layer {i}: a bead runs as the one below");
            }
        }
    }
}

/// Levelled first (`level = auto`): the straight rib's passes fill the
/// trough under its beads up to the level, the scan's highest point under
/// them (the formula's within the 0.1 mm of noise and fit), in as many
/// passes as the deepest place needs of the bead's tallest layer, none
/// standing more than half the lowest layer proud of the level; then the
/// fewest flat layers that reach 13 mm, each at `z_L + i·(13 − z_L)/N`,
/// the first of them on the levelled part (`on_plate`). The layers stack
/// the integral of `13 − z` over the beads' band within 3 %, and the
/// finish is within the segments' tolerance on the mean, as unlevelled.
/// The beads alternate across the passes and on past them, after two
/// passes or one. A declared level the scan stands above by more than
/// half a bead is refused.
#[test]
fn a_rib_levelled_first_fills_the_trough_then_rises_flat() {
    let src = rib(STRAIGHT, 13.0, 2).replace("layers = auto", "layers = auto\n  level = auto");
    let (c, model) =
        crate::support::data::compile_with_files_and_model(&src, example_files(&["worn_pad.ply"]));
    let m = messages(&c);
    let p = c.program.unwrap_or_else(|| panic!("{m}")).into_ir();
    let [lo, hi] = p.limits.layer_height;
    let pitch = f64::from(bead_points(&p, 0)[0].pitch);
    let lines = [-pitch / 2.0, pitch / 2.0];
    let along = || (0..=450).map(|k| -25.0 + 0.1 * k as f64);
    let (mut highest, mut deepest) = (f64::NEG_INFINITY, f64::INFINITY);
    for x in along() {
        for y in lines {
            highest = highest.max(example_z(x, y));
            deepest = deepest.min(example_z(x, y));
        }
    }
    let first = p
        .layers
        .iter()
        .position(|l| l.on_plate)
        .expect("a regular layer on the level");
    alternates(&p);
    let level = bead_points(&p, first)[0].pos[2];
    assert!(
        (level - highest).abs() < 0.1,
        "level {level}, scan's highest {highest}"
    );
    assert_eq!(first as f64, ((level - deepest) / hi).ceil(), "passes");
    for i in 0..first {
        for q in bead_points(&p, i) {
            let top = q.pos[2] + f64::from(q.layer_height);
            assert!(top <= level + lo / 2.0 + 0.1, "pass {i}: {q:?} tops {top}");
        }
    }
    let n = p.layers.len() - first;
    assert_eq!(n as f64, ((13.0 - level) / hi).ceil(), "regular layers");
    let h = (13.0 - level) / n as f64;
    for i in 0..n {
        for q in bead_points(&p, first + i) {
            assert!((q.pos[2] - (level + i as f64 * h)).abs() < 1e-4, "{q:?}");
            assert!((f64::from(q.layer_height) - h).abs() < 1e-4, "{q:?}");
        }
    }
    let (stacked, integral) = (stacked(&p), band_integral(pitch));
    assert!(
        (stacked / integral - 1.0).abs() < 0.03,
        "stacked {stacked} mm³ vs ∫ {integral} mm³"
    );
    let (_, samples) = lmdc::report::finish::sampled(&p, &model.unwrap()).unwrap();
    let mean = samples.iter().map(|s| s.off.abs()).sum::<f64>() / samples.len() as f64;
    assert!(mean <= 0.1 + 0.03 * hi, "mean departure {mean}");
    // One pass (odd): the beads still alternate from it to the first
    // regular layer.
    let odd = rib(STRAIGHT, 13.0, 2).replace("layers = auto", "layers = auto\n  level = 9.7 mm");
    let p = built(&odd);
    let first = p.layers.iter().position(|l| l.on_plate).unwrap();
    assert_eq!(first, 1, "one pass up to 9.7 mm");
    alternates(&p);
    let low = rib(STRAIGHT, 13.0, 2).replace("layers = auto", "layers = auto\n  level = 9 mm");
    let m = messages(&compile(&low, example_files(&["worn_pad.ply"])));
    assert!(
        m.contains("lmd::repair-level: the scanned surface at (-25, "),
        "{m}"
    );
    assert!(m.contains("above the level 9 mm"), "{m}");
}

/// Levelled first with `ends = lead(3 mm)`: every stretch of a levelling
/// pass starts and stops as a regular layer's bead does, with a lead
/// before and after it, laser off, 3 mm over the ground straight on from
/// the stretch's end at its speed; a lead stands at least the bead's
/// height above the scan at its far end, and nowhere along it below the
/// scanned surface (the pad's formula, less the scan's 0.1 mm).
#[test]
fn a_levelled_ribs_passes_run_their_leads_over_the_scan() {
    let src = rib(STRAIGHT, 13.0, 2).replace("layers = auto", "layers = auto\n  level = auto");
    let p = built(&src);
    let first = p.layers.iter().position(|l| l.on_plate).unwrap();
    assert!(first >= 2, "{first} passes");
    let mut stretches = 0;
    for layer in &p.layers[..first] {
        let paths = &layer.paths;
        assert_eq!(paths.len() % 3, 0);
        for k in (0..paths.len()).step_by(3) {
            let (into, bead, out) = (&paths[k], &paths[k + 1], &paths[k + 2]);
            assert_eq!(
                [into.kind, bead.kind, out.kind],
                [PathKind::Lead, PathKind::Wall, PathKind::Lead]
            );
            stretches += 1;
            let (start, end) = (bead.points[0], bead.points[bead.points.len() - 1]);
            for (lead, at, far) in [(into, start, into.points[0]), (out, end, out.points[1])] {
                assert!(lead.points.iter().all(|q| !q.laser_on));
                assert!(lead.points.iter().any(|q| q.pos == at.pos));
                assert_eq!(far.speed, at.speed);
                let ground = (far.pos[0] - at.pos[0]).hypot(far.pos[1] - at.pos[1]);
                assert!((ground - 3.0).abs() < 1e-9, "{ground}");
                // Straight on along the line (y stays on the bead's line).
                assert!((far.pos[1] - at.pos[1]).abs() < 1e-9);
                let above = |q: [f64; 3]| q[2] - example_z(q[0], q[1]);
                assert!(above(far.pos) >= above(at.pos) - 0.2, "{far:?} vs {at:?}");
                assert!(far.pos[2] >= at.pos[2] - 1e-9);
                for s in 0..=20 {
                    let f = s as f64 / 20.0;
                    let q = [0, 1, 2].map(|c| at.pos[c] + f * (far.pos[c] - at.pos[c]));
                    assert!(above(q) > -0.1, "{q:?} under the scan");
                }
            }
        }
    }
    // The trough's passes: the first in three stretches (counts 1, 2, 1).
    assert!(stretches >= 4, "{stretches} stretches");
}
