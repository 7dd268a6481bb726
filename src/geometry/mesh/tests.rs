//! Meshes of known solids made here, their sections against the solids'
//! areas, and the faults of broken ones.

use super::stl::{self, Triangle};
use super::*;
use std::f64::consts::{PI, TAU};

const FLAT: Placement = Placement {
    scale: 1.0,
    turn: [0.0; 3],
    at: [0.0; 3],
};

/// The one island of a section.
fn region(loops: Vec<Loop>) -> Result<Section, SectionFault> {
    let mut all = islands(loops)?;
    assert_eq!(all.len(), 1, "one island");
    Ok(all.remove(0))
}

/// Two triangles of the quad `a b c d` (counter-clockwise from outside).
fn quad(out: &mut Vec<Triangle>, a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) {
    let f = |p: [f64; 3]| p.map(|x| x as f32);
    out.push([f(a), f(b), f(c)]);
    out.push([f(a), f(c), f(d)]);
}

/// A `2a` square box `h` tall with a hole of radius `r` through it, the
/// hole an `n`-gon (`n` a multiple of 8, so the square's corners are on
/// the rays of the hole's corners).
pub fn box_with_hole(a: f64, r: f64, h: f64, n: usize) -> Vec<Triangle> {
    let ray = |i: usize| TAU * i as f64 / n as f64;
    let outer = |i: usize, z: f64| {
        let t = ray(i % n);
        let s = a / t.cos().abs().max(t.sin().abs());
        [s * t.cos(), s * t.sin(), z]
    };
    let inner = |i: usize, z: f64| {
        let t = ray(i % n);
        [r * t.cos(), r * t.sin(), z]
    };
    let mut out = Vec::new();
    for i in 0..n {
        let j = i + 1;
        quad(
            &mut out,
            outer(i, 0.0),
            outer(j, 0.0),
            outer(j, h),
            outer(i, h),
        );
        quad(
            &mut out,
            inner(j, 0.0),
            inner(i, 0.0),
            inner(i, h),
            inner(j, h),
        );
        quad(&mut out, outer(i, h), outer(j, h), inner(j, h), inner(i, h));
        quad(
            &mut out,
            outer(j, 0.0),
            outer(i, 0.0),
            inner(i, 0.0),
            inner(j, 0.0),
        );
    }
    out
}

/// A cone of base radius `r` and height `h`, its base an `n`-gon.
pub fn cone(r: f64, h: f64, n: usize) -> Vec<Triangle> {
    let f = |p: [f64; 3]| p.map(|x| x as f32);
    let rim = |i: usize| {
        let t = TAU * (i % n) as f64 / n as f64;
        [r * t.cos(), r * t.sin(), 0.0]
    };
    let mut out = Vec::new();
    for i in 0..n {
        out.push([f(rim(i)), f(rim(i + 1)), f([0.0, 0.0, h])]);
        out.push([f(rim(i + 1)), f(rim(i)), f([0.0; 3])]);
    }
    out
}

/// The area of a regular `n`-gon in a circle of radius `r`.
fn ngon(r: f64, n: usize) -> f64 {
    n as f64 / 2.0 * r * r * (TAU / n as f64).sin()
}

#[test]
fn box_with_hole_sections_are_the_square_less_the_hole() {
    let (a, r, h, n) = (20.0, 6.0, 10.0, 64);
    let mesh = Mesh::new(&box_with_hole(a, r, h, n), FLAT).unwrap();
    let mut s = mesh.sections();
    for k in 0..10 {
        let z = (k as f64 + 0.5) * h / 10.0;
        let sec = region(s.loops(z).unwrap()).unwrap();
        // The square: its four corners and nothing between them.
        assert_eq!(sec.outline.len(), 4, "layer {k}");
        assert!((area(&sec.outline) - 4.0 * a * a).abs() < 1e-3);
        assert_eq!(sec.holes.len(), 1);
        let hole = -area(&sec.holes[0]);
        // The n-gon's area exactly (to f32 corners), and the circle's to
        // the chord: the segments between the polygon and the circle.
        assert!((hole - ngon(r, n)).abs() < 1e-4, "{hole}");
        let sagitta = r * (1.0 - (PI / n as f64).cos());
        assert!((PI * r * r - hole).abs() <= TAU * r * sagitta);
    }
}

#[test]
fn cone_sections_shrink_with_height() {
    let (r, h, n) = (15.0, 30.0, 48);
    let mesh = Mesh::new(&cone(r, h, n), FLAT).unwrap();
    let mut s = mesh.sections();
    for k in 0..30 {
        let z = k as f64 + 0.5;
        let sec = region(s.loops(z).unwrap()).unwrap();
        let rz = r * (1.0 - z / h);
        assert!(sec.holes.is_empty());
        assert_eq!(sec.outline.len(), n);
        let got = area(&sec.outline);
        assert!((got - ngon(rz, n)).abs() < 1e-4 * r * r, "{k}: {got}");
    }
    // Above the apex: nothing.
    assert_eq!(region(s.loops(h + 1.0).unwrap()), Err(SectionFault::Empty));
}

#[test]
fn a_missing_triangle_is_refused_with_its_neighbours() {
    let mut tris = box_with_hole(20.0, 6.0, 10.0, 16);
    let gone = tris.remove(37);
    // The triangles that shared an edge with it, found here by corners.
    let shares = |t: &Triangle| {
        let common = t.iter().filter(|c| gone.contains(c)).count();
        common == 2
    };
    let mut expect: Vec<usize> = (0..tris.len()).filter(|&i| shares(&tris[i])).collect();
    expect.sort_unstable();
    match Mesh::new(&tris, FLAT) {
        Err(MeshFault::Open {
            edges, triangles, ..
        }) => {
            assert_eq!(edges, 3);
            assert_eq!(triangles, expect);
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_flipped_triangle_and_a_fin_are_refused() {
    let mut tris = cone(10.0, 10.0, 8);
    tris[3].swap(0, 1);
    assert!(matches!(
        Mesh::new(&tris, FLAT),
        Err(MeshFault::Flipped {
            triangles: [_, _],
            ..
        })
    ));
    let mut tris = cone(10.0, 10.0, 8);
    // A fin: a third triangle (both ways) on the first edge.
    let [a, b, _] = tris[0];
    tris.push([a, b, [50.0, 50.0, 50.0]]);
    tris.push([b, a, [50.0, 50.0, 50.0]]);
    assert!(matches!(
        Mesh::new(&tris, FLAT),
        Err(MeshFault::NonManifold { .. })
    ));
}

#[test]
fn an_inside_out_mesh_is_turned_right() {
    let mut tris = cone(10.0, 10.0, 16);
    for t in &mut tris {
        t.swap(1, 2);
    }
    let mesh = Mesh::new(&tris, FLAT).unwrap();
    let sec = region(mesh.sections().loops(1.0).unwrap()).unwrap();
    assert!(area(&sec.outline) > 0.0);
}

#[test]
fn binary_and_ascii_read_the_same_triangles() {
    let tris = box_with_hole(20.0, 6.0, 10.0, 24);
    let b = stl::read(&stl::to_binary(&tris)).unwrap();
    let a = stl::read(stl::to_ascii(&tris).as_bytes()).unwrap();
    assert_eq!(a, tris);
    assert_eq!(b, tris);
    // A binary file whose header starts like an ASCII one is still binary.
    let mut bytes = stl::to_binary(&tris);
    bytes[..6].copy_from_slice(b"solid ");
    assert_eq!(stl::read(&bytes).unwrap(), tris);
}

#[test]
fn broken_files_are_refused_with_where() {
    let tris = cone(10.0, 10.0, 8);
    let mut bytes = stl::to_binary(&tris);
    bytes.pop();
    assert!(matches!(
        stl::read(&bytes),
        Err(stl::StlError::Truncated { count: 16, .. })
    ));
    let text = stl::to_ascii(&tris).replacen("vertex 10.0", "vertex ten", 1);
    assert!(matches!(
        stl::read(text.as_bytes()),
        Err(stl::StlError::Ascii { line: 4, .. })
    ));
    assert!(matches!(
        stl::read(b"hello"),
        Err(stl::StlError::NotStl { len: 5 })
    ));
    assert_eq!(
        stl::read(b"solid x\nendsolid x\n"),
        Err(stl::StlError::Empty)
    );
}

#[test]
fn placement_scales_turns_and_moves() {
    // A cone in cm, lying on its side (apex along +x), turned up by -90°
    // about y and lifted: the same sections as the upright one in mm.
    let upright = Mesh::new(&cone(10.0, 20.0, 16), FLAT).unwrap();
    let side: Vec<Triangle> = cone(1.0, 2.0, 16)
        .iter()
        .map(|t| t.map(|[x, y, z]| [z, y, -x]))
        .collect();
    let placed = Mesh::new(
        &side,
        Placement {
            scale: 10.0,
            turn: [0.0, -PI / 2.0, 0.0],
            at: [5.0, 0.0, 0.0],
        },
    )
    .unwrap();
    let (lo, hi) = placed.bounds();
    assert!(lo[2].abs() < 1e-5 && (hi[2] - 20.0).abs() < 1e-5);
    let a = area(
        &region(upright.sections().loops(5.0).unwrap())
            .unwrap()
            .outline,
    );
    let b = area(
        &region(placed.sections().loops(5.0).unwrap())
            .unwrap()
            .outline,
    );
    assert!((a - b).abs() < 1e-3, "{a} {b}");
}

#[test]
fn two_boxes_are_two_islands_each_with_its_hole() {
    // The second box 40 mm to the right of the first, and lower.
    let mut tris = box_with_hole(10.0, 3.0, 6.0, 16);
    let moved: Vec<Triangle> = box_with_hole(10.0, 4.0, 3.0, 16)
        .into_iter()
        .map(|t| t.map(|c| [c[0] + 40.0, c[1] + 5.0, c[2]]))
        .collect();
    tris.extend(moved);
    let mesh = Mesh::new(&tris, FLAT).unwrap();
    let mut s = mesh.sections();
    let low = islands(s.loops(1.0).unwrap()).unwrap();
    assert_eq!(low.len(), 2);
    // Lowest first: the first box reaches y = -10, the second y = -5.
    assert!(low[0].outline.iter().all(|p| p[0] < 20.0));
    let hole = |r: f64| -ngon(r, 16);
    for (sec, r) in low.iter().zip([3.0, 4.0]) {
        assert_eq!(sec.holes.len(), 1);
        assert!((area(&sec.outline) - 400.0).abs() < 1e-3);
        assert!((area(&sec.holes[0]) - hole(r)).abs() < 1e-3, "{r}");
    }
    let high = islands(s.loops(4.0).unwrap()).unwrap();
    assert_eq!(high.len(), 1);
}

#[test]
fn plate_z_is_the_shortest_decimal_that_stands_the_mesh_on_the_plate() {
    assert_eq!(plate_z(2.5), 2.5);
    assert_eq!(plate_z(0.0), 0.0);
    // 5 decimals would leave it 1.1e-6 mm up: off the plate.
    assert_eq!(plate_z(12.345_678_9), 12.345_679);
    assert_eq!(plate_z(0.000_022_04), 0.000_022_1);
    // Whatever the value, the lowest point lands on the plate or at most
    // half the tolerance above it, never below.
    let mut x = 0.000_000_3_f64;
    while x < 500.0 {
        let r = plate_z(x);
        assert!(
            (r - x).abs() <= 1e-12 * x.max(1.0) || (0.0..=ON_PLATE / 2.0).contains(&(r - x)),
            "{x} -> {r}"
        );
        x = x * 1.37 + 1e-7;
    }
}
