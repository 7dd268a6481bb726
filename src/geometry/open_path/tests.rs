use super::*;

fn path(points: &[[f64; 2]]) -> OpenPath {
    let v: Vec<Vertex> = points.iter().map(|p| Vertex::line(p[0], p[1])).collect();
    OpenPath::new(&v).expect("a path")
}

#[test]
fn an_l_has_its_length_and_directions() {
    let p = path(&[[0.0, 0.0], [30.0, 0.0], [30.0, 20.0]]);
    assert!((p.length() - 50.0).abs() < 1e-12);
    assert_eq!(p.start_direction(), [1.0, 0.0]);
    let e = p.end_direction();
    assert!(e[0].abs() < 1e-12 && (e[1] - 1.0).abs() < 1e-12);
    let r = p.reversed();
    assert_eq!(r.start(), [30.0, 20.0]);
    assert!((r.length() - 50.0).abs() < 1e-12);
}

#[test]
fn faults_of_the_points() {
    assert_eq!(
        OpenPath::new(&[Vertex::line(0.0, 0.0)]),
        Err(PathFault::TooFewPoints)
    );
    let same = [
        Vertex::line(0.0, 0.0),
        Vertex::line(1.0, 0.0),
        Vertex::line(1.0, 0.0),
    ];
    assert_eq!(
        OpenPath::new(&same),
        Err(PathFault::ZeroLength { piece: 1 })
    );
    let nan = [Vertex::line(0.0, 0.0), Vertex::line(f64::NAN, 0.0)];
    assert_eq!(OpenPath::new(&nan), Err(PathFault::NotFinite));
}

#[test]
fn a_crossing_and_a_return_are_found() {
    let z = path(&[
        [0.0, 0.0],
        [10.0, 0.0],
        [0.0, 5.0],
        [10.0, 5.0],
        [5.0, -5.0],
    ]);
    assert!(z.self_intersection().is_some());
    let back = path(&[[0.0, 0.0], [10.0, 0.0], [5.0, 0.0]]);
    assert!(back.self_intersection().is_some());
    let l = path(&[[0.0, 0.0], [30.0, 0.0], [30.0, 20.0]]);
    assert_eq!(l.self_intersection(), None);
}

#[test]
fn a_left_offset_of_an_l_keeps_its_distance() {
    let p = path(&[[0.0, 0.0], [30.0, 0.0], [30.0, 20.0]]);
    // Left of the path is the inside of the corner.
    let o = p.offset(2.0).expect("an offset");
    assert_eq!(o.start(), [0.0, 2.0]);
    let e = o.end();
    assert!((e[0] - 28.0).abs() < 1e-9 && (e[1] - 20.0).abs() < 1e-9);
    for q in o.flatten(0.01) {
        assert!((p.distance(q) - 2.0).abs() < 1e-6, "{q:?}");
    }
    // Right: round outside the corner.
    let o = p.offset(-2.0).expect("an offset");
    assert!((o.length() - (30.0 + 20.0 + std::f64::consts::PI)).abs() < 1e-6);
    for q in o.flatten(0.001) {
        assert!((p.distance(q) - 2.0).abs() < 1e-6, "{q:?}");
    }
}

#[test]
fn an_arc_tighter_than_the_wall_and_a_narrow_u_are_refused() {
    // A quarter circle of radius 2 about (0, 2), counter-clockwise.
    let b = (std::f64::consts::FRAC_PI_2 / 4.0).tan();
    let arc = OpenPath::new(&[Vertex::arc(0.0, 0.0, b), Vertex::line(2.0, 2.0)]).expect("arc");
    assert!((arc.length() - std::f64::consts::PI).abs() < 1e-9);
    assert_eq!(arc.wall_fault(1.5, 1.5), None);
    assert!(matches!(
        arc.wall_fault(2.5, 0.5),
        Some(PathFault::ArcTooTight { piece: 0, .. })
    ));
    // Outside the bend any reach goes.
    assert_eq!(arc.wall_fault(0.0, 10.0), None);
    let u = path(&[[0.0, 0.0], [20.0, 0.0], [20.0, 3.0], [0.0, 3.0]]);
    assert_eq!(u.wall_fault(1.0, 1.0), None);
    assert!(matches!(
        u.wall_fault(2.0, 2.0),
        Some(PathFault::Collapses { .. })
    ));
}

#[test]
fn an_arc_past_a_half_circle_is_split_and_keeps_its_number() {
    // Three quarters of a circle of radius 5 about the origin.
    let b = (3.0 * std::f64::consts::FRAC_PI_2 / 4.0).tan();
    let p = OpenPath::new(&[
        Vertex::line(5.0, -10.0),
        Vertex::arc(5.0, 0.0, b),
        Vertex::line(0.0, -5.0),
    ])
    .expect("path");
    assert_eq!(p.segments().count(), 3);
    assert_eq!(p.written_piece(2), 1);
    let want = 10.0 + 5.0 * 1.5 * std::f64::consts::PI;
    assert!((p.length() - want).abs() < 1e-9);
    for q in p.flatten(0.01) {
        assert!(p.distance(q) < 1e-9);
    }
    assert_eq!(p.self_intersection(), None);
}
