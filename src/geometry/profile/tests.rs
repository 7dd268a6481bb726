use super::*;
use std::f64::consts::PI;

/// A `w` × `h` rectangle from the origin with corners rounded to radius `r`.
fn rounded(w: f64, h: f64, r: f64) -> Profile {
    Profile::rounded_rectangle(w, h, r)
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

#[test]
fn circle_and_rectangle_areas() {
    assert!(close(Profile::circle(3.0).area(), 9.0 * PI, 1e-12));
    assert!(close(Profile::rectangle(4.0, 2.5).area(), 10.0, 1e-12));
    let r = rounded(10.0, 6.0, 2.0);
    assert!(close(r.area(), 60.0 - (4.0 - PI) * 4.0, 1e-12));
}

#[test]
fn clockwise_input_is_reversed_with_its_arcs() {
    let q = (PI / 8.0).tan();
    // The rounded rectangle's loop run clockwise: reversed order, negated bulges.
    let ccw = rounded(10.0, 6.0, 2.0);
    let n = ccw.vertices().len();
    let cw: Vec<Vertex> = (0..n)
        .rev()
        .map(|i| Vertex {
            bulge: -ccw.vertices()[(i + n - 1) % n].bulge,
            ..ccw.vertices()[i]
        })
        .collect();
    assert!(cw.iter().any(|v| v.bulge == -q));
    let p = Profile::new(cw);
    assert!(close(p.area(), ccw.area(), 1e-12));
    assert!(p.vertices().iter().all(|v| v.bulge >= 0.0));
}

#[test]
fn repeated_vertices_and_closing_point_are_dropped() {
    let p = Profile::new(vec![
        Vertex::line(0.0, 0.0),
        Vertex::line(1.0, 0.0),
        Vertex::line(1.0, 0.0),
        Vertex::line(1.0, 1.0),
        Vertex::line(0.0, 0.0),
    ]);
    assert_eq!(p.vertices().len(), 3);
    assert!(close(p.area(), 0.5, 1e-15));
}

#[test]
fn arcs_beyond_a_half_circle_are_split_without_changing_the_shape() {
    // Three quarters of a unit circle from (1, 0) to (0, -1), closed by a line.
    let b = (3.0 * PI / 2.0 / 4.0).tan();
    let p = Profile::new(vec![Vertex::arc(1.0, 0.0, b), Vertex::line(0.0, -1.0)]);
    assert_eq!(p.vertices().len(), 3);
    assert!(p.vertices().iter().all(|v| v.bulge.abs() <= 1.0));
    // The split point is on the circle, at 135°.
    let m = p.vertices()[1];
    assert!(close(m.x, -(0.5f64).sqrt(), 1e-12) && close(m.y, (0.5f64).sqrt(), 1e-12));
    assert!(close(p.area(), 0.75 * PI + 0.5, 1e-12));
}

#[test]
fn circle_offset_is_a_smaller_circle() {
    let inner = Profile::circle(10.0).offset_inward(2.5);
    assert_eq!(inner.len(), 1);
    let c = &inner[0];
    assert!(close(c.area(), PI * 7.5 * 7.5, 1e-9));
    for v in c.vertices() {
        assert!(close(v.x.hypot(v.y), 7.5, 1e-9));
    }
    for k in 0..16 {
        let phi = k as f64 * PI / 8.0;
        let p = [8.0 * phi.cos(), 8.0 * phi.sin()];
        assert!(close(c.distance_to_boundary(p), 0.5, 1e-9));
    }
}

#[test]
fn offset_past_the_middle_vanishes_and_zero_is_a_clone() {
    assert!(Profile::circle(1.0).offset_inward(1.5).is_empty());
    assert!(Profile::rectangle(4.0, 2.0).offset_inward(1.2).is_empty());
    let r = rounded(10.0, 6.0, 2.0);
    let same = r.offset_inward(0.0);
    assert_eq!(same.len(), 1);
    assert_eq!(same[0].vertices(), r.vertices());
    assert!(r.offset_inward(f64::NAN).is_empty());
}

#[test]
fn rounded_rectangle_offset_by_its_radius_has_sharp_corners() {
    let inner = rounded(10.0, 6.0, 2.0).offset_inward(2.0);
    assert_eq!(inner.len(), 1);
    assert!(close(inner[0].area(), 6.0 * 2.0, 1e-9));
    assert_eq!(inner[0].corners(45.0).len(), 4);
}

#[test]
fn a_dumbbell_splits_into_two_loops() {
    // Two 10×10 squares joined by a 2 mm wide neck.
    let p = Profile::new(vec![
        Vertex::line(0.0, 0.0),
        Vertex::line(10.0, 0.0),
        Vertex::line(10.0, 4.0),
        Vertex::line(20.0, 4.0),
        Vertex::line(20.0, 0.0),
        Vertex::line(30.0, 0.0),
        Vertex::line(30.0, 10.0),
        Vertex::line(20.0, 10.0),
        Vertex::line(20.0, 6.0),
        Vertex::line(10.0, 6.0),
        Vertex::line(10.0, 10.0),
        Vertex::line(0.0, 10.0),
    ]);
    assert_eq!(p.offset_inward(0.5).len(), 1);
    let parts = p.offset_inward(1.5);
    assert_eq!(parts.len(), 2);
    // Each is the 7×7 square plus a little bulge toward the neck, where the
    // offset rounds the neck's corners.
    for part in &parts {
        assert!(part.area() > 49.0 && part.area() < 49.5, "{}", part.area());
    }
    assert!(close(parts[0].area(), parts[1].area(), 1e-9));
}

#[test]
fn contains_and_distance_on_a_rounded_rectangle() {
    let r = rounded(10.0, 6.0, 2.0);
    assert!(r.contains([5.0, 3.0]));
    assert!(r.contains([5.0, 0.0])); // on the boundary
    assert!(!r.contains([0.1, 0.1])); // cut off by the rounded corner
    assert!(!r.contains([11.0, 3.0]));
    assert!(!r.contains([f64::NAN, 3.0]));
    // From the corner square's far corner to the arc: √2·2 − 2.
    assert!(close(
        r.distance_to_boundary([0.0, 0.0]),
        8f64.sqrt() - 2.0,
        1e-12
    ));
    assert!(close(r.distance_to_boundary([5.0, 3.0]), 3.0, 1e-12));
}

#[test]
fn bow_tie_crosses_itself_at_its_middle() {
    let p = Profile::new(vec![
        Vertex::line(0.0, 0.0),
        Vertex::line(2.0, 2.0),
        Vertex::line(2.0, 0.0),
        Vertex::line(0.0, 2.0),
    ]);
    let at = p.self_intersection().expect("a bow tie crosses itself");
    assert!(close(at[0], 1.0, 1e-9) && close(at[1], 1.0, 1e-9), "{at:?}");
}

#[test]
fn a_vertex_touching_another_edge_is_found() {
    // The notch's tip at (5, 0) touches the bottom edge.
    let p = Profile::new(vec![
        Vertex::line(0.0, 0.0),
        Vertex::line(10.0, 0.0),
        Vertex::line(10.0, 10.0),
        Vertex::line(6.0, 10.0),
        Vertex::line(5.0, 0.0),
        Vertex::line(4.0, 10.0),
        Vertex::line(0.0, 10.0),
    ]);
    let at = p
        .self_intersection()
        .expect("the tip touches the bottom edge");
    assert!(close(at[0], 5.0, 1e-9) && close(at[1], 0.0, 1e-9), "{at:?}");
    assert_eq!(rounded(10.0, 6.0, 2.0).self_intersection(), None);
    assert_eq!(Profile::circle(2.0).self_intersection(), None);
}

#[test]
fn polyline_meets_the_chord_error_and_stays_bounded() {
    let c = Profile::circle(50.0);
    let pts = c.polyline(0.01);
    assert!(pts.len() > 8);
    assert_ne!(pts.first(), pts.last());
    for (i, a) in pts.iter().enumerate() {
        let b = pts[(i + 1) % pts.len()];
        assert!(close(a[0].hypot(a[1]), 50.0, 1e-9));
        let mid = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
        assert!(c.distance_to_boundary(mid) <= 0.01 + 1e-12);
    }
    assert!(c.polyline(1e-300).len() <= 2 * MAX_ARC_CHORDS);
    assert!(c.polyline(f64::NAN).len() <= 2 * MAX_ARC_CHORDS);
    assert_eq!(Profile::rectangle(2.0, 1.0).polyline(0.1).len(), 4);
}

#[test]
fn corners_are_sharp_turns_not_tangent_joins() {
    assert_eq!(rounded(10.0, 6.0, 2.0).corners(1.0), Vec::<[f64; 2]>::new());
    assert_eq!(Profile::rectangle(2.0, 1.0).corners(89.0).len(), 4);
    assert_eq!(Profile::rectangle(2.0, 1.0).corners(91.0).len(), 0);
    // A "D": a diameter and a half circle meet at two right angles.
    let d = Profile::new(vec![Vertex::arc(1.0, 0.0, 1.0), Vertex::line(-1.0, 0.0)]);
    let mut c = d.corners(80.0);
    c.sort_by(|a, b| a[0].total_cmp(&b[0]));
    assert_eq!(c, vec![[-1.0, 0.0], [1.0, 0.0]]);
}

#[test]
fn bounds_reach_the_arcs() {
    let [lo, hi] = Profile::circle(2.0).bounds().unwrap();
    assert!(close(lo[0], -2.0, 1e-12) && close(lo[1], -2.0, 1e-12));
    assert!(close(hi[0], 2.0, 1e-12) && close(hi[1], 2.0, 1e-12));
}

#[test]
fn non_finite_profiles_do_not_panic() {
    let p = Profile::new(vec![
        Vertex::line(0.0, 0.0),
        Vertex::line(f64::NAN, 0.0),
        Vertex::arc(1.0, f64::INFINITY, 1e300),
    ]);
    assert!(!p.is_finite());
    assert!(p.offset_inward(1.0).is_empty());
    assert_eq!(p.self_intersection(), None);
    assert!(!p.contains([0.5, 0.5]));
    assert!(p.distance_to_boundary([0.5, 0.5]).is_nan());
    let _ = (p.area(), p.polyline(0.1), p.corners(10.0), p.bounds());
    let huge = Profile::new(vec![Vertex::arc(0.0, 0.0, 1e300), Vertex::line(1.0, 0.0)]);
    assert!(huge.is_finite());
    // Its split point lies 5e299 away: too far to offset.
    assert!(huge.offset_inward(1.0).is_empty());
    assert!(Profile::new(vec![]).offset_inward(1.0).is_empty());
    assert!(Profile::circle(0.0).polyline(0.1).len() <= 1);
}
