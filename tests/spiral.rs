//! `layer_change = spiral(…)` on a wall sliced normal to its spine: the end
//! of every layer's loop climbs to the next layer with the laser on, every
//! point lays one layer height (the first layer's climb, rising off the
//! plate, up to two), and the plan switches the laser once.

use lmdc::ir::{Machine, Program};
use lmdc::plan::{Move, Plan, Visit};

/// examples/spiral_tube.lmd with `change` for its layer change and `layers`.
fn tube(change: &str, layers: &str) -> Program {
    let src = std::fs::read_to_string("examples/spiral_tube.lmd")
        .unwrap()
        .replace("layer_change = spiral(length = 20 mm)", change)
        .replace("layers = auto", layers);
    let c = lmdc::pipeline::compile(&src, &mut ());
    let m: Vec<String> = c.diagnostics.iter().map(|d| d.message.clone()).collect();
    c.program
        .unwrap_or_else(|| panic!("{}", m.join("\n")))
        .into_ir()
}

/// How often the laser switches on in `m`'s plan.
fn laser_starts(p: &Program, m: &Machine) -> usize {
    struct Count(usize);
    impl Visit for Count {
        fn motion(&mut self, _: &Move) {}
        fn laser_on(&mut self, _: &Move) {
            self.0 += 1;
        }
    }
    let mut c = Count(0);
    Plan::new(p, m).walk(&mut c);
    c.0
}

#[test]
fn each_loop_climbs_its_last_length_and_the_laser_stays_on() {
    let (length, tall) = (20.0, 5.0);
    let p = tube("layer_change = spiral(length = 20 mm)", "layers = 10");
    let n = p.layers.len();
    assert_eq!(n, 10);
    let h = tall / n as f64;
    assert!(p.continuous);
    for (i, layer) in p.layers.iter().enumerate() {
        let pts = &layer.paths[0].points;
        let z0 = i as f64 * h;
        // Arc length along the loop in plan view (the tube is straight up).
        let mut along = vec![0.0];
        for w in pts.windows(2) {
            let d = (w[1].pos[0] - w[0].pos[0]).hypot(w[1].pos[1] - w[0].pos[1]);
            along.push(along.last().unwrap() + d);
        }
        let total = *along.last().unwrap();
        // A point where the climb starts. It is put on the section at its
        // angle, and the first layer's cuts too, off the chords the 24
        // points span (0.3 % shorter than the circle's arcs): within 0.1 mm.
        assert!(
            along.iter().any(|s| (s - (total - length)).abs() < 0.1),
            "layer {i}: {along:?}"
        );
        for (q, s) in pts.iter().zip(&along) {
            let t = ((s - (total - length)) / length).clamp(0.0, 1.0);
            assert!((q.pos[2] - (z0 + t * h)).abs() < 1e-9, "layer {i}: {q:?}");
            // One layer height over the climb below; the first layer's
            // climb fills down to the plate.
            let laid = if i == 0 { h * (1.0 + t) } else { h };
            assert!((f64::from(q.layer_height) - laid).abs() < 1e-5, "layer {i}");
        }
        if let Some(next) = p.layers.get(i + 1) {
            assert_eq!(pts.last().unwrap().pos, next.paths[0].points[0].pos);
        }
    }
    for m in &p.machines {
        assert_eq!(laser_starts(&p, m), 1, "{}", m.name());
    }
    // With `lift`, the same tube starts every layer with the laser off.
    let lift = tube("layer_change = lift", "layers = 10");
    assert!(!lift.continuous);
    for m in &lift.machines {
        assert_eq!(laser_starts(&lift, m), 10, "{}", m.name());
    }
}

#[test]
fn a_spiral_without_length_is_a_helix_and_auto_layers_leave_room_for_the_first_climb() {
    let p = tube("layer_change = spiral", "layers = auto");
    let n = p.layers.len();
    let h = 5.0 / n as f64;
    let h_max = p.limits.layer_height[1];
    // The first climb lays up to two layer heights, within the bead's range.
    let most = p.layers[0].paths[0]
        .points
        .iter()
        .map(|q| f64::from(q.layer_height))
        .fold(0.0, f64::max);
    assert!(
        (most - 2.0 * h).abs() < 1e-5 && most <= h_max + 1e-9,
        "{most} {h_max}"
    );
    // The whole loop climbs: every point but the first rises.
    let pts = &p.layers[3].paths[0].points;
    assert!(pts.windows(2).all(|w| w[1].pos[2] > w[0].pos[2]));
    assert!((pts.last().unwrap().pos[2] - pts[0].pos[2] - h).abs() < 1e-9);
}

#[test]
fn a_spiral_with_a_moving_seam_is_refused() {
    let src = std::fs::read_to_string("examples/spiral_tube.lmd")
        .unwrap()
        .replace("seam = 90 deg", "seam = rotating(step = 90 deg)");
    let c = lmdc::pipeline::compile(&src, &mut ());
    assert!(c.program.is_none());
    let d = c.diagnostics.iter().next().unwrap();
    assert_eq!(d.code, lmdc::diag::Code::ConflictingFields);
    assert!(d.message.contains("its seam cannot move"), "{}", d.message);
}

/// tests/cases/planar/spiral_wall with `change` for its layer change.
fn planar_wall(change: &str) -> Result<Program, String> {
    let src = std::fs::read_to_string("tests/cases/planar/spiral_wall/input.lmd")
        .unwrap()
        .replace("layer_change = spiral(length = 15 mm)", change);
    let c = lmdc::pipeline::compile(&src, &mut ());
    let m: Vec<String> = c.diagnostics.iter().map(|d| d.message.clone()).collect();
    c.program.map(|p| p.into_ir()).ok_or_else(|| m.join("\n"))
}

#[test]
fn a_planar_one_bead_wall_climbs_its_last_length_and_each_point_lays_one_layer() {
    let length = 15.0;
    let p = planar_wall("layer_change = spiral(length = 15 mm)").unwrap();
    assert_eq!(p.layers.len(), 6);
    assert!(p.continuous);
    // The bead's rise one bead wide at the process speed, by the mass
    // balance: A = feed·efficiency/(density·v), h = A/w.
    let (feed, eff, rho, w, v) = (20.0 / 60.0, 0.5, 7.9e-3, 4.0, 12.0);
    let h = feed * eff / (rho * v) / w;
    for (i, layer) in p.layers.iter().enumerate() {
        assert_eq!(layer.paths.len(), 1, "layer {i}");
        let pts = &layer.paths[0].points;
        let z0 = i as f64 * h;
        let mut along = vec![0.0];
        for q in pts.windows(2) {
            let d = (q[1].pos[0] - q[0].pos[0]).hypot(q[1].pos[1] - q[0].pos[1]);
            along.push(along.last().unwrap() + d);
        }
        let total = *along.last().unwrap();
        // A 30 × 20 mm rectangle's centre line, closed, and a point where
        // the climb starts (inside its last side): the moves before it stay
        // on the layer's plane.
        assert!((total - 100.0).abs() < 1e-9, "{total}");
        assert!(
            along.iter().any(|s| (s - (total - length)).abs() < 1e-9),
            "layer {i}: {along:?}"
        );
        for (j, (q, s)) in pts.iter().zip(&along).enumerate() {
            let t = ((s - (total - length)) / length).clamp(0.0, 1.0);
            assert!((q.pos[2] - (z0 + t * h)).abs() < 1e-5, "layer {i}: {q:?}");
            let laid = if i == 0 { h * (1.0 + t) } else { h };
            assert!(
                (f64::from(q.layer_height) - laid).abs() < 1e-5,
                "layer {i}: {} not {laid}",
                q.layer_height
            );
            // The move on lays the mean of its ends' heights: a mass
            // balance lays h·v/v', so its speed is v·h/laid.
            let next = along[(j + 1).min(pts.len() - 1)];
            let t1 = ((next - (total - length)) / length).clamp(0.0, 1.0);
            let mean = if i == 0 { 1.0 + 0.5 * (t + t1) } else { 1.0 };
            assert!(
                (f64::from(q.speed) - v / mean).abs() < 1e-3,
                "layer {i} point {j}: {} not {}",
                q.speed,
                v / mean
            );
        }
        // One move, one speed: its ends lay within the rise tolerance
        // (3 %) of their mean, on the first layer's climb too.
        for q in pts.windows(2) {
            let (a, b) = (f64::from(q[0].layer_height), f64::from(q[1].layer_height));
            assert!(
                (b - a).abs() <= 0.03 * 0.5 * (a + b) + 1e-6,
                "layer {i}: {a} {b}"
            );
        }
        if let Some(next) = p.layers.get(i + 1) {
            assert_eq!(pts.last().unwrap().pos, next.paths[0].points[0].pos);
        }
    }
    for m in &p.machines {
        assert_eq!(laser_starts(&p, m), 1, "{}", m.name());
    }
    // A helix: every point but the first rises, one layer a loop.
    let helix = planar_wall("layer_change = spiral").unwrap();
    let pts = &helix.layers[2].paths[0].points;
    assert!(pts.windows(2).all(|q| q[1].pos[2] > q[0].pos[2]));
    assert!((pts.last().unwrap().pos[2] - pts[0].pos[2] - h).abs() < 1e-5);
}

#[test]
fn a_planar_spiral_needs_one_loop_and_a_seam_that_stays() {
    let src = std::fs::read_to_string("tests/cases/planar/spiral_wall/input.lmd")
        .unwrap()
        .replace("contours = 1", "contours = 2");
    let c = lmdc::pipeline::compile(&src, &mut ());
    assert!(c.program.is_none());
    let wide: Vec<String> = c.diagnostics.iter().map(|d| d.message.clone()).collect();
    let wide = wide.join("\n");
    assert!(wide.contains("these layers are 2 contour passes"), "{wide}");
    let moving = std::fs::read_to_string("tests/cases/planar/spiral_wall/input.lmd")
        .unwrap()
        .replace("seam = lowest", "seam = staggered(shift = 5 mm)");
    let c = lmdc::pipeline::compile(&moving, &mut ());
    assert!(c.program.is_none());
    let d = c.diagnostics.iter().next().unwrap();
    assert_eq!(d.code, lmdc::diag::Code::ConflictingFields);
    assert!(d.message.contains("its seam cannot move"), "{}", d.message);
    // A hole makes two loops a layer.
    let holed = std::fs::read_to_string("tests/cases/planar/spiral_wall/input.lmd")
        .unwrap()
        .replace(
            "profile = rectangle(width = 30 mm, height = 20 mm)",
            "profile = region(outline = rectangle(width = 30 mm, height = 20 mm), holes = [circle(diameter = 6 mm)])",
        );
    let c = lmdc::pipeline::compile(&holed, &mut ());
    let m: Vec<String> = c.diagnostics.iter().map(|d| d.message.clone()).collect();
    assert!(c.program.is_none());
    assert!(m.iter().any(|m| m.contains("layer 1 has 2 loops")), "{m:?}");
}

#[test]
fn a_first_climb_the_bead_cannot_lay_is_refused_with_its_height_and_speed() {
    // At 8 mm/s a layer is 0.659 mm (the mass balance, 4 mm wide); the first
    // climb lays up to twice that, more than the 1.055 mm the bead lays at
    // its slowest 5 mm/s, and would need 4 mm/s.
    let src = std::fs::read_to_string("tests/cases/planar/spiral_wall/input.lmd")
        .unwrap()
        .replace("speed = 12 mm/s", "speed = 8 mm/s");
    let c = lmdc::pipeline::compile(&src, &mut ());
    assert!(c.program.is_none());
    let h = (20.0 / 60.0) * 0.5 / (7.9e-3 * 8.0) / 4.0;
    let height = c
        .diagnostics
        .iter()
        .find(|d| d.code == lmdc::diag::Code::PointHeight)
        .expect("a point-height error");
    assert!(height.message.contains("at layer 1"), "{}", height.message);
    // The worst point is the last laser-on one of the climb, within one
    // cut (3 %) of two layer heights.
    let worst: f64 = height.message["layer height above h_max: the worst is ".len()
        + height
            .message
            .find("layer height above h_max: the worst is ")
            .unwrap()..]
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(worst > 1.9 * h && worst < 2.0 * h + 1e-3, "{worst} {h}");
    // The advice is a spiral's: the first climb lays twice over, and a
    // lifted layer change lays one height everywhere.
    let help = height.help.as_deref().unwrap();
    assert!(
        help.contains("up to two layer heights") && help.contains("`layer_change = lift`"),
        "{help}"
    );
    assert!(c
        .diagnostics
        .iter()
        .any(|d| d.code == lmdc::diag::Code::PointSpeed));
}
