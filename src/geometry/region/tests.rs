use super::*;
use crate::geometry::profile::Vertex;
use std::f64::consts::PI;

fn circle_at(r: f64, x: f64, y: f64) -> Profile {
    Profile::circle(r).placed(0.0, [x, y])
}

fn flange() -> Region {
    let mut holes = vec![circle_at(25.0, 0.0, 0.0)];
    for k in 0..6 {
        let a = k as f64 * PI / 3.0;
        holes.push(circle_at(6.0, 42.5 * a.cos(), 42.5 * a.sin()));
    }
    Region::new(Profile::circle(60.0), holes)
}

#[test]
fn area_and_containment_leave_the_holes_out() {
    let r = flange();
    let want = PI * (3600.0 - 625.0 - 6.0 * 36.0);
    assert!((r.area() - want).abs() < 1e-9, "{}", r.area());
    assert!(r.contains([30.0, 0.0])); // between the bore and a bolt hole
    assert!(!r.contains([42.5, 0.0])); // a bolt hole's centre
    assert!(r.contains([36.5, 0.0])); // a bolt hole's edge belongs to the part
    assert!(!r.contains([0.0, 0.0]));
    assert!((r.distance_to_boundary([30.0, 0.0]) - 5.0).abs() < 1e-12);
}

#[test]
fn an_offset_grows_the_holes_and_shrinks_the_outline_with_arcs() {
    let r = flange().offset_inward(1.5);
    assert_eq!(r.outer().len(), 1);
    assert_eq!(r.holes().len(), 7);
    let want = PI * (58.5f64.powi(2) - 26.5f64.powi(2) - 6.0 * 7.5f64.powi(2));
    assert!((r.area() - want).abs() < 1e-6, "{} {want}", r.area());
    // Every hole is still a circle: arcs stay arcs.
    for h in r.holes() {
        assert!(h.vertices().iter().all(|v| v.bulge.abs() > 0.1));
    }
}

#[test]
fn holes_that_grow_into_each_other_merge() {
    // Two holes 4 mm apart: 2.5 mm round each, they meet.
    let r = Region::new(
        Profile::rectangle(40.0, 20.0),
        vec![circle_at(3.0, 15.0, 10.0), circle_at(3.0, 25.0, 10.0)],
    );
    let o = r.offset_inward(2.5);
    assert_eq!(o.holes().len(), 1, "{o:?}");
    // Into the outline: a hole 1 mm from the edge opens into a notch.
    let r = Region::new(
        Profile::rectangle(40.0, 20.0),
        vec![circle_at(3.0, 20.0, 4.0)],
    );
    let o = r.offset_inward(1.0);
    assert_eq!((o.outer().len(), o.holes().len()), (1, 0), "{o:?}");
}

#[test]
fn a_region_without_holes_offsets_as_its_profile() {
    let p = Profile::rounded_rectangle(30.0, 20.0, 4.0);
    let a = Region::from(p.clone()).offset_inward(2.0);
    let b = p.offset_inward(2.0);
    assert_eq!(a.outer().len(), b.len());
    assert_eq!(a.outer()[0].vertices(), b[0].vertices());
}

#[test]
fn faults_name_the_hole() {
    let outline = Profile::rectangle(40.0, 20.0);
    let ok = Region::new(outline.clone(), vec![circle_at(3.0, 10.0, 10.0)]);
    assert_eq!(ok.check(), Ok(()));
    let crossing = Region::new(
        outline.clone(),
        vec![circle_at(3.0, 10.0, 10.0), circle_at(3.0, 39.0, 10.0)],
    );
    assert!(matches!(
        crossing.check(),
        Err(Fault::HoleOutline { hole: 1, .. })
    ));
    let outside = Region::new(outline.clone(), vec![circle_at(3.0, 60.0, 10.0)]);
    assert_eq!(outside.check(), Err(Fault::HoleOutside { hole: 0 }));
    let touching = Region::new(outline.clone(), vec![circle_at(3.0, 10.0, 3.0)]);
    assert!(matches!(
        touching.check(),
        Err(Fault::HoleOutline { hole: 0, .. })
    ));
    let overlapping = Region::new(
        outline.clone(),
        vec![
            circle_at(1.0, 30.0, 5.0),
            circle_at(3.0, 10.0, 10.0),
            circle_at(3.0, 14.0, 10.0),
        ],
    );
    match overlapping.check() {
        Err(Fault::Holes { hole, other, at }) => {
            assert_eq!((hole, other), (1, 2));
            assert!((at[0] - 12.0).abs() < 1e-9, "{at:?}");
        }
        other => panic!("{other:?}"),
    }
    let nested = Region::new(
        outline.clone(),
        vec![circle_at(5.0, 10.0, 10.0), circle_at(1.0, 10.0, 10.0)],
    );
    assert_eq!(nested.check(), Err(Fault::HoleInHole { hole: 1, other: 0 }));
    let bow = Profile::new(vec![
        Vertex::line(5.0, 5.0),
        Vertex::line(8.0, 8.0),
        Vertex::line(8.0, 5.0),
        Vertex::line(5.0, 8.0),
    ]);
    assert!(matches!(
        Region::new(outline, vec![bow]).check(),
        Err(Fault::HoleItself { hole: 0, .. })
    ));
}
