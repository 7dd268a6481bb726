//! Holes, links and seams through the language: `.lmd` sources written here
//! are compiled, and the IR and the motion plan are checked against the
//! geometry computed here from the numbers in the source (circles and
//! axis-parallel rectangles, whose distances are exact in a line).

use lmdc::ir::{Layer, PathKind, Program};
use lmdc::pipeline::compile;
use lmdc::plan::{Move, MoveKind, Visit, Where};
use proptest::prelude::*;

/// A hole as the source writes it, centred at `c`.
#[derive(Clone, Copy, Debug)]
enum Hole {
    Circle { c: [f64; 2], r: f64 },
    Rect { c: [f64; 2], half: [f64; 2] },
}

impl Hole {
    fn source(&self) -> String {
        match *self {
            Hole::Circle { c, r } => format!(
                "place(circle(radius = {r} mm), at = [{} mm, {} mm])",
                c[0], c[1]
            ),
            Hole::Rect { c, half } => format!(
                "place(rectangle(width = {} mm, height = {} mm), at = [{} mm, {} mm])",
                2.0 * half[0],
                2.0 * half[1],
                c[0],
                c[1]
            ),
        }
    }

    /// Signed distance from `p` to the hole's edge: negative inside.
    fn distance(&self, p: [f64; 2]) -> f64 {
        match *self {
            Hole::Circle { c, r } => (p[0] - c[0]).hypot(p[1] - c[1]) - r,
            Hole::Rect { c, half } => {
                let d = [(p[0] - c[0]).abs() - half[0], (p[1] - c[1]).abs() - half[1]];
                let outside = d[0].max(0.0).hypot(d[1].max(0.0));
                outside + d[0].max(d[1]).min(0.0)
            }
        }
    }

    /// How far it reaches from its centre (a bound).
    fn reach(&self) -> f64 {
        match *self {
            Hole::Circle { r, .. } => r,
            Hole::Rect { half, .. } => half[0].hypot(half[1]),
        }
    }

    fn centre(&self) -> [f64; 2] {
        match *self {
            Hole::Circle { c, .. } | Hole::Rect { c, .. } => c,
        }
    }
}

/// A plate `w` × `h` centred on the origin, with holes, built with 3 mm
/// beads (`size = outer`, so track centres keep 1.5 mm from every face).
fn plate(w: f64, h: f64, holes: &[Hole], slicing: &str) -> String {
    let holes: Vec<String> = holes.iter().map(Hole::source).collect();
    format!(
        "part plate
profile p = region(
  outline = rectangle(width = {w} mm, height = {h} mm),
  holes = [{}]
)
bead b {{
  width = 3 mm
  speed = 4 mm/s .. 18 mm/s
  model = linear(slope = -0.1 mm / (1 mm/s), intercept = 2 mm)
}}
extrude e {{
  profile = p
  size = outer
  bead = b
}}
slicing planar {{
  layers = 3
{slicing}
}}
process {{
  speed = 10 mm/s
  power = 1500 W
  powder = 8 g/min
}}
machine m {{
  kind = cnc
  head {{ standoff = 15 mm  nozzle = frustum(length = 45 mm, tip = 12 mm, top = 40 mm) }}
  axes = 3
  dialect = linuxcnc
  max_speed = 50 mm/s
  clearance = 4 mm
}}
",
        holes.join(",\n    ")
    )
}

/// Whether every point of segment a–b keeps at least `inset − tol` inside
/// the plate and away from every hole, sampled every 0.01 mm.
fn segment_keeps(
    a: [f64; 2],
    b: [f64; 2],
    w: f64,
    h: f64,
    holes: &[Hole],
    inset: f64,
    tol: f64,
) -> bool {
    let n = ((b[0] - a[0]).hypot(b[1] - a[1]) / 0.01).ceil().max(1.0) as usize;
    (0..=n).all(|k| {
        let f = k as f64 / n as f64;
        let p = [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])];
        let edge = (w / 2.0 - p[0].abs()).min(h / 2.0 - p[1].abs());
        edge >= inset - tol && holes.iter().all(|hl| hl.distance(p) >= inset - tol)
    })
}

fn xy(p: [f64; 3]) -> [f64; 2] {
    [p[0], p[1]]
}

/// Whether a–b lies on the straight path `pts` (a link running back along
/// its own track over the track's extension).
fn on_path(pts: &[[f64; 2]], a: [f64; 2], b: [f64; 2]) -> bool {
    let dist = |x: [f64; 2], p: [f64; 2], q: [f64; 2]| {
        let d = [q[0] - p[0], q[1] - p[1]];
        let len2 = (d[0] * d[0] + d[1] * d[1]).max(1e-300);
        let f = (((x[0] - p[0]) * d[0] + (x[1] - p[1]) * d[1]) / len2).clamp(0.0, 1.0);
        (x[0] - p[0] - f * d[0]).hypot(x[1] - p[1] - f * d[1])
    };
    pts.windows(2)
        .any(|s| dist(a, s[0], s[1]) < 1e-6 && dist(b, s[0], s[1]) < 1e-6)
}

/// The link paths of a layer, by index. Linked raster comes as runs of
/// paths each starting where the one before ended, track, link, track, …:
/// the odd places of a run are links (a laser-off link is also a travel).
fn links(layer: &Layer) -> Vec<(usize, Vec<[f64; 2]>)> {
    let mut out = Vec::new();
    let mut place = 0usize;
    for (i, p) in layer.paths.iter().enumerate() {
        let joins = i > 0
            && p.kind != PathKind::Contour
            && layer.paths[i - 1].kind != PathKind::Contour
            && layer.paths[i - 1].points.last().map(|l| l.pos) == Some(p.points[0].pos);
        place = if joins { place + 1 } else { 0 };
        assert_eq!(
            p.kind == PathKind::Travel,
            place % 2 == 1 && p.kind != PathKind::Infill,
            "path {i}: a travel only between two tracks"
        );
        if place % 2 == 1 {
            out.push((i, p.points.iter().map(|q| xy(q.pos)).collect()));
        }
    }
    out
}

fn compile_ir(src: &str) -> Result<Program, String> {
    let c = compile(src, &mut ());
    match c.program {
        Some(v) => Ok(v.into_ir()),
        None => Err(c
            .diagnostics
            .iter()
            .filter(|d| d.is_error())
            .map(|d| format!("{}: {}", d.code.as_str(), d.message))
            .collect::<Vec<_>>()
            .join("\n")),
    }
}

/// Random holes inside a `w` × `h` plate, at least 7 mm (two beads and a
/// margin) from the plate's faces and from each other.
fn holes_in(w: f64, h: f64) -> impl Strategy<Value = Vec<Hole>> {
    let one = (
        -0.5f64..0.5,
        -0.5f64..0.5,
        1.0f64..8.0,
        1.0f64..8.0,
        any::<bool>(),
    );
    prop::collection::vec(one, 0..6).prop_map(move |raw| {
        let mut kept: Vec<Hole> = Vec::new();
        for (fx, fy, a, b, round) in raw {
            // Whole hundredths of a mm: the source prints them exactly.
            let r2 = |v: f64| (v * 100.0).round() / 100.0;
            let c = [r2(fx * w), r2(fy * h)];
            let hole = if round {
                Hole::Circle { c, r: r2(a) }
            } else {
                Hole::Rect {
                    c,
                    half: [r2(a), r2(b)],
                }
            };
            let reach = hole.reach();
            let margin = 7.0;
            let fits = c[0].abs() + reach + margin < w / 2.0
                && c[1].abs() + reach + margin < h / 2.0
                && kept.iter().all(|k| {
                    let d = (c[0] - k.centre()[0]).hypot(c[1] - k.centre()[1]);
                    d > reach + k.reach() + margin
                });
            if fits {
                kept.push(hole);
            }
        }
        kept
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// No point of the IR (contours, raster, links) lies inside a hole, and
    /// every track keeps half a bead from every hole; every link keeps half
    /// a bead inside the part (or runs back along its own track).
    #[test]
    fn no_ir_point_lies_in_a_hole_and_links_stay_inside(
        (w, h, holes) in (60u32..110, 50u32..90).prop_flat_map(|(w, h)| {
            let (w, h) = (w as f64, h as f64);
            (Just(w), Just(h), holes_in(w, h))
        }),
        angle in 0u32..180,
        contours in 0usize..3,
        link in prop::sample::select(vec!["none", "laser_on", "laser_off"]),
    ) {
        let slicing = format!(
            "  contours = {contours}\n  infill = raster(angle = {angle} deg, rotate = 90 deg, link = {link})\n  seam = random(seed = 3)"
        );
        let src = plate(w, h, &holes, &slicing);
        let ir = match compile_ir(&src) {
            Ok(ir) => ir,
            // A web narrower than the fill reaches may leave a gap: that is
            // the gap check's business, not this test's.
            Err(e) if e.lines().all(|l| l.starts_with("lmd::fill-gap")) => return Ok(()),
            Err(e) => return Err(TestCaseError::fail(format!("{e}\n{src}"))),
        };
        for layer in &ir.layers {
            for path in &layer.paths {
                for pt in &path.points {
                    for hl in &holes {
                        let d = hl.distance(xy(pt.pos));
                        prop_assert!(d >= 0.0, "{:?} lies in {hl:?}\n{src}", pt.pos);
                        if path.kind != PathKind::Travel {
                            prop_assert!(d >= 1.5 - 1e-6,
                                "a deposit at {:?} is {d} mm from {hl:?}\n{src}", pt.pos);
                        }
                    }
                }
            }
            for (i, pts) in links(layer) {
                let before: Vec<[f64; 2]> =
                    layer.paths[i - 1].points.iter().map(|q| xy(q.pos)).collect();
                let after: Vec<[f64; 2]> = layer
                    .paths
                    .get(i + 1)
                    .map(|p| p.points.iter().map(|q| xy(q.pos)).collect())
                    .unwrap_or_default();
                for s in pts.windows(2) {
                    prop_assert!(
                        segment_keeps(s[0], s[1], w, h, &holes, 1.5, 1e-6)
                            || on_path(&before, s[0], s[1])
                            || on_path(&after, s[0], s[1]),
                        "link segment {:?}–{:?} leaves the part less half a bead\n{src}",
                        s[0],
                        s[1]
                    );
                }
            }
        }
    }
}

/// Counts what the plan of machine 0 does.
#[derive(Default)]
struct Count {
    starts: usize,
    retracts: usize,
    /// Laser-off moves at the layer's height inside a layer (links).
    level_travels: usize,
}

impl Visit for Count {
    fn laser_on(&mut self, _: &Move) {
        self.starts += 1;
    }
    fn motion(&mut self, m: &Move) {
        match m.kind {
            MoveKind::Retract => self.retracts += 1,
            MoveKind::Travel if matches!(m.at, Where::Point { .. }) => self.level_travels += 1,
            _ => {}
        }
    }
}

fn flange_with(link: &str) -> (Program, Count) {
    let src = std::fs::read_to_string("examples/flange.lmd")
        .unwrap()
        .replace("link = laser_on", &format!("link = {link}"));
    let c = compile(&src, &mut ());
    let v = c.program.expect("compiles");
    let mut count = Count::default();
    v.machine(0).unwrap().plan().walk(&mut count);
    (v.into_ir(), count)
}

#[test]
fn linking_saves_starts_and_lifts() {
    let (ir, none) = flange_with("none");
    let (_, off) = flange_with("laser_off");
    let (_, on) = flange_with("laser_on");
    // Without links every track is reached from the clearance: a retract
    // per path (bar the first), a start per path.
    let paths: usize = ir.layers.iter().map(|l| l.paths.len()).sum();
    assert_eq!(none.starts, paths);
    assert_eq!(none.level_travels, 0);
    // Linked with the laser off: as many starts, far fewer lifts, the
    // nozzle moving on at the layer's height instead.
    assert_eq!(off.starts, none.starts);
    assert!(
        off.retracts * 3 < none.retracts,
        "{} vs {}",
        off.retracts,
        none.retracts
    );
    assert!(off.level_travels > 0);
    // Linked with the laser on: tracks whose ends lie level join in
    // half-circle turns, one deposit; the flange's raster ends all lie on
    // its round edges, never level, so every link is laid with the laser
    // off at the layer's height, as `laser_off` lays it (fill::link: a
    // round turn there would reach into the contour's strip): the same
    // starts, lifts and level moves as with the laser off. The turns
    // themselves are tested on a rectangle (fill::link's unit tests,
    // tests/deposit.rs).
    assert_eq!(on.starts, off.starts);
    assert_eq!(on.retracts, off.retracts);
    assert_eq!(on.level_travels, off.level_travels);
}

/// The first point of the outer contour (the loop farthest from the
/// centre) of each layer.
fn outer_seams(ir: &Program) -> Vec<[f64; 2]> {
    ir.layers
        .iter()
        .map(|l| {
            let outer = l
                .paths
                .iter()
                .filter(|p| p.kind == PathKind::Contour)
                .max_by(|a, b| {
                    let r = |p: &lmdc::ir::Path| xy(p.points[0].pos)[0].hypot(p.points[0].pos[1]);
                    r(a).total_cmp(&r(b))
                })
                .unwrap();
            xy(outer.points[0].pos)
        })
        .collect()
}

fn flange_seams(seam: &str) -> Vec<[f64; 2]> {
    let src = std::fs::read_to_string("examples/flange.lmd")
        .unwrap()
        .replace(
            "seam = rotating(step = 137.5 deg)",
            &format!("seam = {seam}"),
        );
    outer_seams(&compile_ir(&src).unwrap())
}

#[test]
fn seams_move_between_layers_as_declared() {
    // The outer contour runs on a circle of radius 40 − 1.5 mm.
    let r = 38.5;
    let deg = |p: [f64; 2]| p[1].atan2(p[0]).to_degrees().rem_euclid(360.0);
    let rotating = flange_seams("rotating(step = 90 deg, from = 10 deg)");
    for (k, p) in rotating.iter().enumerate() {
        assert!((p[0].hypot(p[1]) - r).abs() < 1e-9);
        let want = (10.0 + 90.0 * k as f64).rem_euclid(360.0);
        assert!(
            (deg(*p) - want).abs() < 1e-6,
            "layer {k}: {} not {want}",
            deg(*p)
        );
    }
    // A fixed direction: the same spot on every layer.
    let fixed = flange_seams("45 deg");
    assert!(fixed.iter().all(|p| (deg(*p) - 45.0).abs() < 1e-6));
    let lowest = flange_seams("lowest");
    assert!(lowest.windows(2).all(|w| w[0] == w[1]));
    // Random: another spot on every layer, the same for the same seed.
    let a = flange_seams("random(seed = 11)");
    assert_eq!(a, flange_seams("random(seed = 11)"));
    assert_ne!(a, flange_seams("random(seed = 12)"));
    for i in 0..a.len() {
        for j in 0..i {
            assert!((deg(a[i]) - deg(a[j])).abs() > 1e-3, "layers {j} and {i}");
        }
    }
}

#[test]
fn a_seam_at_the_sharpest_corner_is_a_corner() {
    let src = plate(
        80.0,
        50.0,
        &[Hole::Circle {
            c: [0.0, 0.0],
            r: 8.0,
        }],
        "  contours = 1\n  infill = raster(angle = 0 deg, rotate = 90 deg)\n  seam = sharpest_corner",
    );
    let ir = compile_ir(&src).unwrap();
    for p in outer_seams(&ir) {
        // A corner of the contour 1.5 mm inside the 80 × 50 plate.
        assert!(
            (p[0].abs() - 38.5).abs() < 1e-9 && (p[1].abs() - 23.5).abs() < 1e-9,
            "{p:?}"
        );
    }
}

#[test]
fn a_hole_fault_is_reported_with_its_layer_when_the_profile_follows_it() {
    // The hole grows a millimetre a layer and meets the plate's edge on the
    // fourth layer.
    let src = plate(
        40.0,
        30.0,
        &[],
        "  contours = 1\n  infill = raster(angle = 0 deg)",
    )
    .replace("layers = 3", "layers = 6")
    .replace(
        "holes = []",
        "holes = [circle(radius = 12 mm + layer * 1 mm)]",
    );
    let c = compile(&src, &mut ());
    assert!(c.program.is_none());
    let holes: Vec<&str> = c
        .diagnostics
        .iter()
        .filter(|d| d.code.as_str() == "lmd::hole")
        .map(|d| d.message.as_str())
        .collect();
    assert_eq!(holes.len(), 1, "{holes:?}");
    assert!(
        holes[0].starts_with("hole 1 crosses or touches the outline at (")
            && holes[0].contains("on layer 4 (layer = 3)"),
        "{}",
        holes[0]
    );
}

#[test]
fn a_thousand_holes_on_one_spot_are_reported_briefly_and_quickly() {
    let src = plate(
        80.0,
        60.0,
        &[],
        "  contours = 1\n  infill = raster(angle = 0 deg)",
    )
    .replace(
        "holes = []",
        "holes = [bolt_circle(circle(diameter = 8 mm), count = 1000, diameter = 1 mm)]",
    );
    let t = std::time::Instant::now();
    let c = compile(&src, &mut ());
    assert!(c.program.is_none());
    let holes = c
        .diagnostics
        .iter()
        .filter(|d| d.code.as_str() == "lmd::hole")
        .count();
    assert_eq!(holes, lmdc::geometry::region::MAX_FAULTS + 1);
    assert!(t.elapsed().as_secs_f64() < 10.0, "{:?}", t.elapsed());
    let too_many = plate(
        80.0,
        60.0,
        &[],
        "  contours = 1\n  infill = raster(angle = 0 deg)",
    )
    .replace(
        "holes = []",
        "holes = [bolt_circle(circle(diameter = 1 mm), count = 1001, diameter = 50 mm)]",
    );
    let c = compile(&too_many, &mut ());
    assert!(c
        .diagnostics
        .iter()
        .any(|d| d.message == "`count` must be between 1 and 1000"));
}
