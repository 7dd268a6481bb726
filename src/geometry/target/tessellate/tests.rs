//! The triangles of each kind of target against the solid's own volume
//! (in closed form) and faces.

use super::*;
use crate::geometry::profile::Profile;
use crate::geometry::section::{Morph, Section};
use crate::geometry::spine::Spine;
use crate::geometry::target::LoftTarget;
use crate::units::{Angle, Length};
use std::f64::consts::PI;

/// The volume the triangles hold, by the divergence theorem: positive
/// when they face out.
fn volume(tris: &[Tri]) -> f64 {
    tris.iter()
        .map(|[a, b, c]| {
            let (a, b, c) = (Vector3::from(*a), Vector3::from(*b), Vector3::from(*c));
            a.dot(&b.cross(&c)) / 6.0
        })
        .sum()
}

/// Every edge of the triangles run once each way: they close a solid.
fn closed(tris: &[Tri]) -> bool {
    let key = |p: [f64; 3]| p.map(f64::to_bits);
    let mut edges: Vec<([u64; 3], [u64; 3])> = tris
        .iter()
        .flat_map(|t| (0..3).map(move |i| (key(t[i]), key(t[(i + 1) % 3]))))
        .collect();
    edges.sort_unstable();
    let back = |(a, b): &([u64; 3], [u64; 3])| edges.binary_search(&(*b, *a)).is_ok();
    edges.iter().all(back)
}

fn circle(r: f64) -> Section {
    Section::Circle { r: Length(r) }
}

fn loft(from: Section, to: Section, morph: Morph, spine: Spine, twist: f64) -> Target {
    Target::Loft(LoftTarget::new(from, to, morph, spine, twist).unwrap())
}

/// A 40 × 20 mm plate 10 mm tall with a hole 10 mm across: closed,
/// facing out, its volume `(800 − 25π)·10` mm³ within what flattening
/// the hole takes, its top and bottom the region's area.
#[test]
fn a_prism_with_a_hole_closes_its_volume() {
    let hole = Profile::circle(5.0).placed(0.0, [20.0, 10.0]);
    let region = Region::new(Profile::rectangle(40.0, 20.0), vec![hole]);
    let tris = Target::Prism {
        region,
        height: 10.0,
    }
    .triangles();
    assert!(closed(&tris));
    let exact = (800.0 - 25.0 * PI) * 10.0;
    // The hole's chords stand at most CHORD inside its circle: its
    // area is short by at most its perimeter × CHORD.
    let slack = 2.0 * PI * 5.0 * CHORD * 10.0;
    let v = volume(&tris);
    assert!(v > exact && v - exact <= slack, "{v} against {exact}");
    let top: f64 = tris
        .iter()
        .filter(|t| t.iter().all(|p| p[2] == 10.0))
        .map(|[a, b, c]| 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])))
        .sum();
    assert!((top - v / 10.0).abs() <= 1e-9, "top {top}");
}

/// A cone frustum lofted straight (60 to 20 mm across, 20 mm tall): its
/// side is straight between its ends, one station apart; closed, facing
/// out, and its volume `πh/3 (R² + Rr + r²)` within the chords'.
#[test]
fn a_straight_cone_is_one_interval_and_holds_its_volume() {
    let spine = Spine::Line {
        length: Length(20.0),
    };
    let t = loft(circle(30.0), circle(10.0), Morph::Radial, spine, 0.0);
    let Target::Loft(l) = &t else { unreachable!() };
    let m = angles(&l.geometry).len();
    let tris = t.triangles();
    let end = |t: &&Tri| t.iter().all(|p| p[2] == 0.0) || t.iter().all(|p| p[2] == 20.0);
    assert_eq!(tris.iter().filter(|t| !end(t)).count(), 2 * m);
    assert!(closed(&tris));
    let exact = PI * 20.0 / 3.0 * (900.0 + 300.0 + 100.0);
    let v = volume(&tris);
    // A polygon within CHORD of its circle holds at least (1 − CHORD/r)²
    // of its area.
    assert!(
        v < exact && v >= exact * (1.0 - CHORD / 10.0).powi(2),
        "{v} against {exact}"
    );
}

/// A bent tube (10 mm radius on a 40 mm bend through 90°, twisted a
/// half turn): closed, facing out, its volume Pappus's `πr²·Rα` within
/// the chords' (as the cone's), and every corner of it on the tube's
/// face.
#[test]
fn a_bent_twisted_tube_holds_pappus_volume() {
    let spine = Spine::Arc {
        radius: Length(40.0),
        angle: Angle(PI / 2.0),
    };
    let t = loft(circle(10.0), circle(10.0), Morph::Radial, spine, PI);
    let tris = t.triangles();
    assert!(closed(&tris));
    let exact = PI * 100.0 * 40.0 * PI / 2.0;
    let v = volume(&tris);
    assert!(
        v < exact && v >= exact * (1.0 - CHORD / 10.0).powi(2),
        "{v} against {exact}"
    );
    // The bend's centre line is the arc about (40, ·, 0) in the xz plane.
    for p in tris.iter().flatten() {
        let off = ((p[0] - 40.0).hypot(p[2]) - 40.0).hypot(p[1]);
        let on_face = (off - 10.0).abs() <= 1e-9;
        let on_end = off <= 10.0 + 1e-9;
        assert!(on_face || on_end, "{p:?} is {off} mm off the centre line");
    }
}

/// A square twisted a quarter turn over 30 mm: a twist keeps every
/// section's area, so the volume is `20² · 30`, which the triangles hold
/// within two chords over its sides; its corners are kept as angles of
/// their own.
#[test]
fn a_twisted_square_keeps_its_corners_and_volume() {
    let square = Section::Rectangle {
        a: Length(10.0),
        b: Length(10.0),
    };
    let spine = Spine::Line {
        length: Length(30.0),
    };
    let t = loft(square, square, Morph::Superellipse, spine, PI / 2.0);
    let Target::Loft(l) = &t else { unreachable!() };
    let a = angles(&l.geometry);
    for c in [PI / 4.0, 3.0 * PI / 4.0, 5.0 * PI / 4.0, 7.0 * PI / 4.0] {
        assert!(a.iter().any(|x| (x - c).abs() < 1e-12), "corner {c}");
    }
    let tris = t.triangles();
    assert!(closed(&tris));
    // Its triangles lie within about two chords of its twisted sides
    // (4 × 20 × 30 mm²), and inside them.
    let v = volume(&tris);
    assert!(v < 12_000.0 && 12_000.0 - v <= 2400.0 * 2.0 * CHORD, "{v}");
}

/// An extrusion of a mesh gives the mesh's faces, its sides with its
/// top: a box's twelve.
#[test]
fn a_mesh_target_gives_every_face_upright_ones_too() {
    let faces = crate::geometry::scan::nearest::block([0.0; 3], [5.0, 3.0, 2.0]);
    let t = Target::Mesh(crate::geometry::mesh::highest::Highest::new(faces).unwrap());
    let tris = t.triangles();
    assert_eq!(tris.len(), 12);
    assert!(closed(&tris));
    assert!((volume(&tris) - 30.0).abs() < 1e-12);
}

/// An untwisted box lofted straight needs only its corners: four quads
/// up its sides and its ends in one ring each, sixteen triangles.
#[test]
fn a_straight_boxs_sides_are_their_corners() {
    let rect = Section::Rectangle {
        a: Length(20.0),
        b: Length(12.0),
    };
    let spine = Spine::Line {
        length: Length(12.0),
    };
    let tris = loft(rect, rect, Morph::Radial, spine, 0.0).triangles();
    assert_eq!(tris.len(), 16);
    assert!(closed(&tris));
    assert!((volume(&tris) - 40.0 * 24.0 * 12.0).abs() < 1e-9);
}

/// How far the triangles' middles stray from the loft's faces, as the
/// loft's own inside test sees it: each middle moved `d` out along its
/// triangle's normal is outside, and `d` in is inside.
fn strays_within(t: &Target, d: f64) -> Result<(), String> {
    let Target::Loft(l) = t else { unreachable!() };
    for tri in t.triangles() {
        let [a, b, c] = tri.map(Vector3::from);
        let n = (b - a).cross(&(c - a));
        if n.norm() < 1e-12 {
            continue;
        }
        let n = n.normalize();
        let mid = (a + b + c) / 3.0;
        let (out, inn) = (mid + n * d, mid - n * d);
        if l.contains([out.x, out.y, out.z]) || !l.contains([inn.x, inn.y, inn.z]) {
            return Err(format!("{tri:?} strays more than {d} mm"));
        }
    }
    Ok(())
}

/// Every loft's triangles lie within two chords of its faces: rectangles
/// whose corners move (a superellipse morph between two of other
/// proportions, and one turned on its side), the same blended radially
/// (straight at its ends, curved between), a twisted square, a bent and
/// twisted tube, a circle bent into a square.
#[test]
fn every_lofts_triangles_lie_on_its_faces() {
    let rect = |w: f64, h: f64| Section::Rectangle {
        a: Length(w / 2.0),
        b: Length(h / 2.0),
    };
    let line = |l: f64| Spine::Line { length: Length(l) };
    let arc = |r: f64, deg: f64| Spine::Arc {
        radius: Length(r),
        angle: Angle(deg.to_radians()),
    };
    let cases = [
        (
            rect(44.0, 28.0),
            rect(40.0, 24.0),
            Morph::Superellipse,
            line(12.0),
            0.0,
        ),
        (
            rect(60.0, 20.0),
            rect(20.0, 60.0),
            Morph::Superellipse,
            line(30.0),
            0.0,
        ),
        (
            rect(44.0, 28.0),
            rect(40.0, 24.0),
            Morph::Radial,
            line(12.0),
            0.0,
        ),
        (
            rect(20.0, 20.0),
            rect(20.0, 20.0),
            Morph::Superellipse,
            line(30.0),
            PI / 2.0,
        ),
        (
            circle(10.0),
            circle(10.0),
            Morph::Radial,
            arc(40.0, 90.0),
            PI,
        ),
    ];
    for (k, (from, to, morph, spine, twist)) in cases.into_iter().enumerate() {
        let t = loft(from, to, morph, spine, twist);
        assert!(closed(&t.triangles()), "case {k}");
        strays_within(&t, 2.0 * CHORD).unwrap_or_else(|e| panic!("case {k}: {e}"));
    }
}

/// A circle bent into a square by a superellipse morph: its bend near the
/// diagonal sharpens toward the square end faster than the angles are
/// probed, and strays there up to 0.01 mm (docs/repair.md).
#[test]
fn a_circle_sharpening_into_a_square_strays_near_its_corner() {
    let square = Section::Rectangle {
        a: Length(10.0),
        b: Length(10.0),
    };
    let spine = Spine::Arc {
        radius: Length(60.0),
        angle: Angle(30f64.to_radians()),
    };
    let t = loft(circle(12.0), square, Morph::Superellipse, spine, 0.0);
    assert!(closed(&t.triangles()));
    assert!(strays_within(&t, 2.0 * CHORD).is_err());
    strays_within(&t, 0.01).unwrap();
}

/// Near a box, a plate keeps the loops that reach into it: a metre-wide
/// plate with a hole in the box and two far from it gives the same top
/// over the box (every point of a grid over it under one top face, or
/// under none in the hole, as the whole plate's), without the far holes'
/// sides or their bridges into the outline.
#[test]
fn a_prism_near_a_box_keeps_its_faces_there_and_drops_far_loops() {
    let holes = vec![
        Profile::circle(5.0).placed(0.0, [10.0, 0.0]),
        Profile::circle(20.0).placed(0.0, [400.0, 300.0]),
        Profile::circle(20.0).placed(0.0, [-400.0, -300.0]),
    ];
    let plate = Target::Prism {
        region: Region::new(
            Profile::rectangle(1000.0, 800.0).placed(0.0, [-500.0, -400.0]),
            holes,
        ),
        height: 10.0,
    };
    let whole = plate.triangles();
    let near = plate.triangles_near(Some([[-30.0, -30.0], [30.0, 30.0]]));
    assert!(
        near.len() < whole.len(),
        "{} of {}",
        near.len(),
        whole.len()
    );
    // The far holes' sides are gone.
    assert!(near.iter().all(|t| t
        .iter()
        .all(|p| p[0].abs() < 380.0 || p[2] == 0.0 || p[2] == 10.0)));
    let under = |tris: &[Tri], q: [f64; 2]| {
        tris.iter()
            .filter(|t| t.iter().all(|p| p[2] == 10.0))
            .filter(|[a, b, c]| {
                let side = |u: [f64; 3], v: [f64; 3]| {
                    (v[0] - u[0]) * (q[1] - u[1]) - (q[0] - u[0]) * (v[1] - u[1])
                };
                let s = [side(*a, *b), side(*b, *c), side(*c, *a)];
                s.iter().all(|&x| x > 0.0) || s.iter().all(|&x| x < 0.0)
            })
            .count()
    };
    for i in 0..24 {
        for j in 0..24 {
            // Off the hole's chords' corners: a point on an edge is under two.
            let q = [-29.3 + 2.5 * i as f64, -29.1 + 2.5 * j as f64];
            let inside_hole = (q[0] - 10.0).hypot(q[1]) < 5.0;
            let (a, b) = (under(&whole, q), under(&near, q));
            assert_eq!(a, b, "{q:?}");
            assert_eq!(a, usize::from(!inside_hole), "{q:?}");
        }
    }
}
