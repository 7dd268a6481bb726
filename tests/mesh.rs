//! Solids given as meshes (`mesh(file = "…")`), through the whole
//! pipeline: the same plan from a binary and an ASCII file, the sections'
//! areas in the plan's contours, layers of separate islands, and broken
//! meshes refused with where.

use crate::support::three_mf as package;
use lmdc::geometry::mesh::stl::{self, Triangle};
use lmdc::geometry::mesh::three_mf;
use lmdc::geometry::outline;
use lmdc::pipeline::{compile_reading, Compiled};
use lmdc::sema::model::Build;
use lmdc::slice::layers;
use std::collections::BTreeMap;
use std::f64::consts::TAU;
use std::rc::Rc;

/// Two triangles of the quad `a b c d` (counter-clockwise from outside).
fn quad(out: &mut Vec<Triangle>, a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) {
    let f = |p: [f64; 3]| p.map(|x| x as f32);
    out.push([f(a), f(b), f(c)]);
    out.push([f(a), f(c), f(d)]);
}

/// A `2a` square box `h` tall centred on (`cx`, `cy`), a hole of radius
/// `r` through it as an `n`-gon (`n` a multiple of 8).
fn box_with_hole(c: [f64; 2], a: f64, r: f64, h: f64, n: usize) -> Vec<Triangle> {
    let ray = |i: usize| TAU * (i % n) as f64 / n as f64;
    let outer = |i: usize, z: f64| {
        let t = ray(i);
        let s = a / t.cos().abs().max(t.sin().abs());
        [c[0] + s * t.cos(), c[1] + s * t.sin(), z]
    };
    let inner = |i: usize, z: f64| [c[0] + r * ray(i).cos(), c[1] + r * ray(i).sin(), z];
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

/// The plate of tests/codes/plate.lmd with `profile` for its profile.
fn source(profile: &str) -> String {
    include_str!("codes/plate.lmd")
        .replace(
            "profile = rectangle(width = 20 mm, height = 10.2 mm)  // 5 offsets between the outermost tracks",
            profile,
        )
        .replace("  layers = 2\n", "")
        // A mesh's sections are no whole number of offsets wide: a bead over
        // a speed range lays each track's strip (0.7 mm at 6 mm/s, as the
        // base's).
        .replace(
            "  model = measured(height = 0.7 mm, speed = 6 mm/s)",
            "  speed = 2 mm/s .. 12 mm/s\n  model = linear(slope = -0.1 mm / (1 mm/s), intercept = 1.3 mm)",
        )
}

/// Compiles `src` with `files` as the files beside it.
fn compile(src: &str, files: BTreeMap<&'static str, Vec<u8>>) -> Compiled {
    crate::support::data::compile_with_files(src, files)
}

fn messages(c: &Compiled) -> String {
    c.diagnostics
        .iter()
        .map(|d| d.message.clone())
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn binary_and_ascii_give_the_same_plan() {
    let tris = box_with_hole([15.0, 15.0], 15.0, 5.0, 4.2, 32);
    let src = source("profile = mesh(\"part.stl\")");
    let plan = |bytes: Vec<u8>| {
        let c = compile(&src, BTreeMap::from([("part.stl", bytes)]));
        let m = messages(&c);
        let p = c.program.unwrap_or_else(|| panic!("{m}"));
        serde_json::to_string(p.ir()).unwrap()
    };
    let b = plan(stl::to_binary(&tris));
    let a = plan(stl::to_ascii(&tris).into_bytes());
    assert!(b == a, "the binary and the ASCII file give different plans");
    // 4.2 mm in whole layers of the lift the tracks lay (the second
    // layer's height over the first's), rounded up.
    let ir: lmdc::ir::Program = serde_json::from_str(&b).unwrap();
    let lift = ir.layers[1].frame.origin[2] - ir.layers[0].frame.origin[2];
    assert_eq!(ir.layers.len(), (4.2 / lift - 1e-9).ceil() as usize);
}

#[test]
fn the_contours_follow_the_sections() {
    // A box 30 mm square with a 10 mm hole; `size = outer`: the first
    // contour runs half a bead (1.1 mm) inside the square and outside the
    // hole, so its points are 13.9 mm from the centre in x or y at most,
    // and at least 5 + 1.1 mm from it.
    let tris = box_with_hole([0.0, 0.0], 15.0, 5.0, 1.4, 32);
    let src = source("profile = mesh(\"part.stl\")")
        .replace("offset = 1.6 mm", "offset = 1.6 mm\n  contours = 1");
    let c = compile(&src, BTreeMap::from([("part.stl", stl::to_binary(&tris))]));
    let m = messages(&c);
    let p = c.program.unwrap_or_else(|| panic!("{m}"));
    let ir = p.ir();
    let lift = ir.layers[1].frame.origin[2] - ir.layers[0].frame.origin[2];
    assert_eq!(ir.layers.len(), (1.4 / lift - 1e-9).ceil() as usize);
    // Each contour path's points, on the first layer.
    let paths: Vec<Vec<[f64; 2]>> = ir.layers[0]
        .paths
        .iter()
        .filter(|p| p.kind == lmdc::ir::PathKind::Contour)
        .map(|p| p.points.iter().map(|q| [q.pos[0], q.pos[1]]).collect())
        .collect();
    let pts: Vec<[f64; 2]> = paths.concat();
    assert!(!pts.is_empty());
    let outer = pts
        .iter()
        .map(|p| p[0].abs().max(p[1].abs()))
        .fold(0.0, f64::max);
    assert!((outer - 13.9).abs() < 1e-6, "{outer}");
    // The nearest the contour's pieces come to the centre: the hole's
    // 32-gon, 1.1 mm out, is nearest at its sides' middles.
    let dist = |a: [f64; 2], b: [f64; 2]| {
        let d = [b[0] - a[0], b[1] - a[1]];
        let len2 = d[0] * d[0] + d[1] * d[1];
        let t = if len2 > 0.0 {
            (-(a[0] * d[0] + a[1] * d[1]) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (a[0] + t * d[0]).hypot(a[1] + t * d[1])
    };
    let inner = paths
        .iter()
        .flat_map(|p| p.windows(2).map(|w| dist(w[0], w[1])))
        .fold(f64::INFINITY, f64::min);
    let apothem = 5.0 * (std::f64::consts::PI / 32.0).cos();
    assert!((inner - (apothem + 1.1)).abs() < 1e-3, "{inner}");
}

#[test]
fn a_missing_triangle_is_refused_with_its_neighbours() {
    let mut tris = box_with_hole([15.0, 15.0], 15.0, 5.0, 4.2, 16);
    let gone = tris.remove(21);
    let mut near: Vec<usize> = (0..tris.len())
        .filter(|&i| tris[i].iter().filter(|c| gone.contains(c)).count() == 2)
        .collect();
    near.sort_unstable();
    let list = near
        .iter()
        .map(|t| t.to_string())
        .collect::<Vec<_>>()
        .join(", ");
    let c = compile(
        &source("profile = mesh(\"part.stl\")"),
        BTreeMap::from([("part.stl", stl::to_binary(&tris))]),
    );
    assert!(c.program.is_none());
    let m = messages(&c);
    assert!(m.contains("is open: 3 edge(s)"), "{m}");
    assert!(
        m.contains(&format!("triangles {list} (counted from 0")),
        "{m}\n{list}"
    );
}

#[test]
fn a_mesh_off_the_plate_is_refused() {
    let tris = box_with_hole([15.0, 15.0], 15.0, 5.0, 4.2, 16);
    let c = compile(
        &source("profile = mesh(\"part.stl\", at = [0 mm, 0 mm, 2.5 mm])"),
        BTreeMap::from([("part.stl", stl::to_binary(&tris))]),
    );
    let m = messages(&c);
    assert!(
        m.contains("lowest point at z = 2.5 mm, above the plate"),
        "{m}"
    );
    assert!(c
        .diagnostics
        .iter()
        .any(|d| d.help.as_deref().is_some_and(|h| h.contains("to 0 mm"))));
}

/// The area of a regular `n`-gon in a circle of radius `r`.
fn ngon(r: f64, n: usize) -> f64 {
    n as f64 / 2.0 * r * r * (TAU / n as f64).sin()
}

#[test]
fn islands_are_filled_each_and_joined_by_a_laser_off_travel() {
    // Two boxes with a hole each, side by side on the plate: the 30 mm one
    // 4.2 mm tall, the 20 mm one 2.1 mm: two islands up to 2.1 mm, one
    // above.
    let (a, b) = (
        ([15.0, 15.0], 15.0, 5.0, 4.2),
        ([55.0, 15.0], 10.0, 3.0, 2.1),
    );
    let mut tris = box_with_hole(a.0, a.1, a.2, a.3, 16);
    tris.extend(box_with_hole(b.0, b.1, b.2, b.3, 16));
    let data: lmdc::sema::DataReader = {
        let bytes = stl::to_binary(&tris);
        Rc::new(move |_: &str, _| Ok(bytes.clone()))
    };
    let (c, model) =
        compile_reading(&source("profile = mesh(\"part.stl\")"), None, &mut (), data).unwrap();
    let m = messages(&c);
    let ir = c.program.unwrap_or_else(|| panic!("{m}")).into_ir();
    let lift = ir.layers[1].frame.origin[2] - ir.layers[0].frame.origin[2];
    assert_eq!(ir.layers.len(), (4.2 / lift - 1e-9).ceil() as usize);
    // Each layer's region against the two solids, cut halfway up it.
    let model = model.unwrap();
    let (bead, Build::Block { extrusion, slicing }) = (model.bead.as_ref().unwrap(), &model.build)
    else {
        panic!("a mesh builds a block");
    };
    let plan = layers::plan(bead, extrusion, slicing, &mut Default::default()).unwrap();
    let area = |(_, h, r, _): ([f64; 2], f64, f64, f64)| 4.0 * h * h - ngon(r, 16);
    for (k, shape) in plan.shapes.iter().enumerate() {
        let cut = (k as f64 + 0.5) * lift;
        let region = outline::region(shape, 0.01);
        let two = cut < b.3;
        assert_eq!(region.outer().len(), if two { 2 } else { 1 }, "layer {k}");
        let want = area(a) + if two { area(b) } else { 0.0 };
        assert!(
            (region.area() - want).abs() < 1e-3,
            "layer {k}: {}",
            region.area()
        );
    }
    // On a layer of two islands, every path lies in one of them, each
    // island's paths come together, and the path that leaves the first
    // ends with the laser off (the plan lifts and travels from there, as
    // between any two tracks that are not linked).
    let island = |p: &lmdc::ir::Point| usize::from(p.pos[0] > 35.0);
    for layer in ir
        .layers
        .iter()
        .filter(|l| l.frame.origin[2] + lift / 2.0 < b.3)
    {
        let mut order: Vec<usize> = Vec::new();
        for p in &layer.paths {
            let i = island(&p.points[0]);
            assert!(
                p.points.iter().all(|q| island(q) == i),
                "a path spans both islands"
            );
            if order.last() != Some(&i) {
                order.push(i);
            }
        }
        assert_eq!(order.len(), 2, "layer {}: {order:?}", layer.index);
        for w in layer.paths.windows(2) {
            if island(&w[0].points[0]) != island(&w[1].points[0]) {
                assert!(!w[0].points.last().unwrap().laser_on);
                assert_ne!(w[1].kind, lmdc::ir::PathKind::Travel);
            }
        }
    }
}

#[test]
fn a_file_that_is_no_stl_says_why() {
    let c = compile(
        &source("profile = mesh(\"part.stl\", units = in)"),
        BTreeMap::from([(
            "part.stl",
            b"solid x\n facet normal 0 0 0\n  outer loop\n   vertex 1 2\n".to_vec(),
        )]),
    );
    let m = messages(&c);
    assert!(
        m.contains("line 4: expected `vertex X Y Z`, three numbers"),
        "{m}"
    );
    let c = compile(&source("profile = mesh(\"nothing.stl\")"), BTreeMap::new());
    assert!(messages(&c).contains("cannot read the mesh file `nothing.stl`: no file"));
}

/// A frustum standing on the plate: an `n`-gon of radius `r0` at the bottom,
/// `r1` at the top, `h` tall (an inverted cone when `r1 > r0`).
fn frustum(r0: f64, r1: f64, h: f64, n: usize) -> Vec<Triangle> {
    let at = |r: f64, i: usize, z: f64| {
        let t = TAU * (i % n) as f64 / n as f64;
        [r * t.cos(), r * t.sin(), z]
    };
    let f = |p: [f64; 3]| p.map(|x| x as f32);
    let mut out = Vec::new();
    for i in 0..n {
        let j = i + 1;
        quad(
            &mut out,
            at(r0, i, 0.0),
            at(r0, j, 0.0),
            at(r1, j, h),
            at(r1, i, h),
        );
        out.push([f([0.0, 0.0, h]), f(at(r1, i, h)), f(at(r1, j, h))]);
        out.push([f([0.0; 3]), f(at(r0, j, 0.0)), f(at(r0, i, 0.0))]);
    }
    out
}

#[test]
fn an_outline_leaning_out_past_max_overhang_is_refused_with_its_angle() {
    let src = source("profile = mesh(\"part.stl\")").replace(
        "offset = 1.6 mm",
        "offset = 1.6 mm\n  contours = 1\n  max_overhang = 30 deg",
    );
    // 10 mm at the bottom, 15 mm at the top, 5 mm tall: the side leans 45°.
    let tris = frustum(10.0, 15.0, 5.0, 64);
    let c = compile(&src, BTreeMap::from([("part.stl", stl::to_binary(&tris))]));
    assert!(c.program.is_none());
    let d = c
        .diagnostics
        .iter()
        .find(|d| d.code == lmdc::diag::Code::Overhang)
        .unwrap_or_else(|| panic!("{}", messages(&c)));
    let m = &d.message;
    assert!(m.starts_with("the part's outline leans out "), "{m}");
    let deg: f64 = m["the part's outline leans out ".len()..]
        .split('°')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!((40.0..=45.5).contains(&deg), "{m}");
    assert!(
        m.contains("more than the 30° `max_overhang` allows, at layer "),
        "{m}"
    );
    assert!(m.contains(" mm, "), "names where: {m}");
    // Upright, the same frustum leans in: nothing to refuse.
    let upright = frustum(15.0, 10.0, 5.0, 64);
    let c = compile(
        &src,
        BTreeMap::from([("part.stl", stl::to_binary(&upright))]),
    );
    assert!(c.program.is_some(), "{}", messages(&c));
}

/// A box from corner `lo` to corner `hi`, its faces out.
fn cuboid(lo: [f64; 3], hi: [f64; 3]) -> Vec<Triangle> {
    let p =
        |i: usize, j: usize, k: usize| [[lo[0], hi[0]][i], [lo[1], hi[1]][j], [lo[2], hi[2]][k]];
    let mut out = Vec::new();
    quad(&mut out, p(0, 0, 0), p(0, 1, 0), p(1, 1, 0), p(1, 0, 0));
    quad(&mut out, p(0, 0, 1), p(1, 0, 1), p(1, 1, 1), p(0, 1, 1));
    quad(&mut out, p(0, 0, 0), p(1, 0, 0), p(1, 0, 1), p(0, 0, 1));
    quad(&mut out, p(1, 1, 0), p(0, 1, 0), p(0, 1, 1), p(1, 1, 1));
    quad(&mut out, p(0, 1, 0), p(0, 0, 0), p(0, 0, 1), p(0, 1, 1));
    quad(&mut out, p(1, 0, 0), p(1, 1, 0), p(1, 1, 1), p(1, 0, 1));
    out
}

#[test]
fn each_layer_of_islands_starts_nearest_where_the_layer_below_ended() {
    // A plate 1.4 mm thick with three 10 mm pillars on it in a row: above
    // the plate each layer has three islands.
    let centres = [[12.0, 10.0], [40.0, 11.0], [66.0, 10.0]];
    let (plate, top) = (1.4, 4.9);
    let mut tris = cuboid([0.0, 0.0, 0.0], [80.0, 21.0, plate]);
    for c in centres {
        tris.extend(cuboid(
            [c[0] - 5.0, c[1] - 5.0, plate],
            [c[0] + 5.0, c[1] + 5.0, top],
        ));
    }
    let c = compile(
        &source("profile = mesh(\"part.stl\")"),
        BTreeMap::from([("part.stl", stl::to_binary(&tris))]),
    );
    let m = messages(&c);
    let ir = c.program.unwrap_or_else(|| panic!("{m}")).into_ir();
    let island = |p: &lmdc::ir::Point| {
        centres
            .iter()
            .position(|c| (p.pos[0] - c[0]).abs() < 6.0)
            .expect("a point on a pillar")
    };
    let xy = |p: &lmdc::ir::Point| [p.pos[0], p.pos[1]];
    let dist = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
    // Where each layer ends, and on a layer of pillars, each island's start
    // and end in the order they are laid.
    let mut end = xy(ir.layers[0].paths.last().unwrap().points.last().unwrap());
    let (mut laid, mut lowest_first) = (0.0, 0.0);
    let mut lowest_end = end;
    let mut pillar_layers = 0;
    for layer in &ir.layers[1..] {
        let paths = &layer.paths;
        if layer.frame.origin[2] < plate - 1e-9 {
            end = xy(paths.last().unwrap().points.last().unwrap());
            lowest_end = end;
            continue;
        }
        pillar_layers += 1;
        // (island, start, end) of each island's run of paths.
        let mut runs: Vec<(usize, [f64; 2], [f64; 2])> = Vec::new();
        for p in paths {
            let i = island(&p.points[0]);
            let (first, last) = (xy(&p.points[0]), xy(p.points.last().unwrap()));
            match runs.last_mut() {
                Some(r) if r.0 == i => r.2 = last,
                _ => runs.push((i, first, last)),
            }
        }
        assert_eq!(runs.len(), 3, "layer {}: {runs:?}", layer.index);
        // Each island is the nearest of those left to where the last one
        // (or the layer below) ended.
        let mut at = end;
        for (n, r) in runs.iter().enumerate() {
            let nearest = runs[n..]
                .iter()
                .map(|q| dist(at, q.1))
                .fold(f64::INFINITY, f64::min);
            assert_eq!(dist(at, r.1), nearest, "layer {}, island {n}", layer.index);
            laid += dist(at, r.1);
            at = r.2;
        }
        end = at;
        // The same islands visited from the lowest (least y, then x: the
        // first pillar) each layer, then nearest next.
        let mut left: Vec<_> = runs.clone();
        left.sort_by_key(|r| r.0);
        let mut at = lowest_end;
        let mut next = 0;
        while !left.is_empty() {
            let r = left.remove(next);
            lowest_first += dist(at, r.1);
            at = r.2;
            next = (0..left.len())
                .min_by(|&a, &b| dist(at, left[a].1).total_cmp(&dist(at, left[b].1)))
                .unwrap_or(0);
        }
        lowest_end = at;
    }
    assert!(pillar_layers >= 4, "{pillar_layers}");
    assert!(
        laid < lowest_first,
        "travel between islands {laid} mm, from the lowest {lowest_first} mm"
    );
}

/// `tris` as a 3MF model's vertices (each distinct corner once, in the
/// order they first come) and triangles, scaled by `k`.
fn indexed(tris: &[Triangle], k: f64) -> (Vec<[f64; 3]>, Vec<[usize; 3]>) {
    let mut ids: BTreeMap<[u32; 3], usize> = BTreeMap::new();
    let mut vertices = Vec::new();
    let faces = tris
        .iter()
        .map(|t| {
            t.map(|c| {
                *ids.entry(c.map(f32::to_bits)).or_insert_with(|| {
                    vertices.push(c.map(|x| f64::from(x) * k));
                    vertices.len() - 1
                })
            })
        })
        .collect();
    (vertices, faces)
}

/// Each layer's region of the mesh program `src` reading `bytes`.
fn regions(src: &str, bytes: Vec<u8>) -> Vec<lmdc::geometry::region::Region> {
    let data: lmdc::sema::DataReader = Rc::new(move |_: &str, _| Ok(bytes.clone()));
    let (c, model) = compile_reading(src, None, &mut (), data).unwrap();
    let m = messages(&c);
    let model = model.unwrap_or_else(|| panic!("{m}"));
    assert!(c.program.is_some(), "{m}");
    let (bead, Build::Block { extrusion, slicing }) = (model.bead.as_ref().unwrap(), &model.build)
    else {
        panic!("a mesh builds a block");
    };
    let plan = layers::plan(bead, extrusion, slicing, &mut Default::default()).unwrap();
    plan.shapes
        .iter()
        .map(|s| outline::region(s, 0.01))
        .collect()
}

/// A part drawn in inches and read in mm is too narrow for a bead: refused
/// before it is cut, with its size in inches and `units = in`, which then
/// builds; a 3MF that names the wrong unit gets the unit to export it with.
#[test]
fn a_mesh_too_small_for_a_bead_names_the_unit_it_would_fit_in() {
    // 2.4 × 1.2 × 0.9 in, its numbers read as mm; plate.lmd's bead is
    // 2.2 mm wide, its contour 1.1 mm inside the faces (`size = outer`).
    let (v, t) = indexed(&cuboid([0.0; 3], [2.4, 1.2, 0.9]), 1.0);
    let bytes = stl::to_binary(&cuboid([0.0; 3], [2.4, 1.2, 0.9]));
    let src = |units: &str| source(&format!("profile = mesh(\"part.stl\"{units})"));
    let c = compile(&src(""), BTreeMap::from([("part.stl", bytes.clone())]));
    assert!(c.program.is_none());
    let d: Vec<_> = c.diagnostics.iter().collect();
    assert_eq!(d.len(), 1, "{}", messages(&c));
    assert_eq!(d[0].code, lmdc::diag::Code::FillEmpty);
    assert!(
        d[0].message
            .contains("is 2.4 × 1.2 × 0.9 mm as placed: narrower than the 2.2 mm bead"),
        "{}",
        d[0].message
    );
    let help = d[0].help.as_deref().unwrap();
    assert!(
        help.starts_with("in inches it would be 60.96 × 30.48 × 22.86 mm")
            && help.contains("write `units = in`"),
        "{help}"
    );
    // Following it builds.
    let c = compile(&src(", units = in"), BTreeMap::from([("part.stl", bytes)]));
    assert!(c.program.is_some(), "{}", messages(&c));
    // A 3MF whose model says millimetre: export it again in inches.
    let c = compile(
        &source("profile = mesh(\"part.3mf\")"),
        BTreeMap::from([("part.3mf", package::package(&v, &t, "millimeter", &[None]))]),
    );
    let help = c.diagnostics.iter().find_map(|d| d.help.clone()).unwrap();
    assert!(
        help.contains("not the `millimeter` it names, export it again with `unit=\"inch\"`"),
        "{help}"
    );
}

#[test]
fn a_3mf_builds_the_plan_of_the_same_stl() {
    let tris = box_with_hole([15.0, 15.0], 15.0, 5.0, 4.2, 32);
    let (v, t) = indexed(&tris, 1.0);
    let plan = |file: &str, bytes: Vec<u8>| {
        let c = compile(
            &source(&format!("profile = mesh(\"{file}\")")),
            BTreeMap::from([("part.stl", bytes.clone()), ("part.3mf", bytes)]),
        );
        let m = messages(&c);
        let p = c.program.unwrap_or_else(|| panic!("{m}"));
        serde_json::to_value(&p.ir().layers).unwrap()
    };
    let stl = plan("part.stl", stl::to_binary(&tris));
    // Told apart by the name and, under any name, by the ZIP's signature.
    let package = package::package(&v, &t, "millimeter", &[None]);
    assert!(plan("part.3mf", package.clone()) == stl);
    assert!(plan("part.stl", package) == stl);
}

#[test]
fn a_3mf_in_inches_is_placed_by_its_build_items() {
    // The box in inches, made twice by two build items: one turned 90°
    // about z and moved 2 in along x, one moved 4 in along x and 1 in
    // along y. The file's origin is the box's corner (the box spans 0 to
    // 30 mm), so in mm the first spans x 50.8 - 30 to 50.8, y 0 to 30, the
    // second x 101.6 to 131.6, y 25.4 to 55.4.
    let tris = box_with_hole([15.0, 15.0], 15.0, 5.0, 2.8, 16);
    let (v, t) = indexed(&tris, 1.0 / 25.4);
    let turned = [0.0, 1.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 0.0, 0.0];
    let moved = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 4.0, 1.0, 0.0];
    let bytes = package::package(&v, &t, "inch", &[Some(turned), Some(moved)]);
    let rs = regions(&source("profile = mesh(\"part.3mf\")"), bytes);
    let area = 4.0 * 15.0 * 15.0 - ngon(5.0, 16);
    let want = [[[20.8, 0.0], [50.8, 30.0]], [[101.6, 25.4], [131.6, 55.4]]];
    assert!(!rs.is_empty());
    for (k, r) in rs.iter().enumerate() {
        assert_eq!(r.outer().len(), 2, "layer {k}");
        assert!(
            (r.area() - 2.0 * area).abs() < 1e-3,
            "layer {k}: {}",
            r.area()
        );
        let b = r.bounds().unwrap();
        assert!((b[0][0] - want[0][0][0]).abs() < 1e-4, "{b:?}");
        assert!((b[0][1] - 0.0).abs() < 1e-4, "{b:?}");
        assert!((b[1][0] - want[1][1][0]).abs() < 1e-4, "{b:?}");
        assert!((b[1][1] - want[1][1][1]).abs() < 1e-4, "{b:?}");
        // The gap between the two islands: a point between them is in
        // neither, a point in each is in one.
        assert!(!r.contains([76.0, 20.0]));
        assert!(r.contains([want[0][0][0] + 1.0, 15.0]));
        assert!(r.contains([want[1][0][0] + 1.0, 40.4]));
    }
    // `units` that disagrees with the file's is refused where it is written.
    let c = compile(
        &source("profile = mesh(\"part.3mf\", units = mm)"),
        BTreeMap::from([("part.3mf", package::package(&v, &t, "inch", &[None]))]),
    );
    assert!(
        messages(&c).contains(
            "says its unit is the inch (`unit=\"inch\"`), and `units = mm` says otherwise"
        ),
        "{}",
        messages(&c)
    );
}

#[test]
fn a_broken_3mf_is_refused_with_where() {
    let tris = box_with_hole([15.0, 15.0], 15.0, 5.0, 2.8, 16);
    let (v, mut t) = indexed(&tris, 1.0);
    let refused = |bytes: Vec<u8>, says: &str| {
        let c = compile(
            &source("profile = mesh(\"part.3mf\")"),
            BTreeMap::from([("part.3mf", bytes)]),
        );
        assert!(c.program.is_none());
        let m = messages(&c);
        assert!(m.contains(says), "{m}\nwanted: {says}");
    };
    refused(
        b"solid x\nendsolid x\n".to_vec(),
        "is no 3MF lmdc can read: a 3MF is a ZIP package, and this is none",
    );
    // A missing triangle: open, with the two triangles beside it.
    let gone = t.remove(21);
    let mut near: Vec<usize> = (0..t.len())
        .filter(|&i| t[i].iter().filter(|c| gone.contains(c)).count() == 2)
        .collect();
    near.sort_unstable();
    let list = near.iter().map(|x| x.to_string()).collect::<Vec<_>>();
    refused(
        package::package(&v, &t, "millimeter", &[None]),
        &format!(
            "is open: 3 edge(s) belong to one triangle only, so it encloses no solid; triangles {}",
            list.join(", ")
        ),
    );
    // A triangle naming a vertex past the last.
    t[7][1] = v.len() + 3;
    refused(
        package::package(&v, &t, "millimeter", &[None]),
        &format!(
            "triangle 7 of object 1 names vertex {}, but the object has {} vertices",
            v.len() + 3,
            v.len()
        ),
    );
}

/// A model of one triangle (object 1), object 2 made of object 1 moved
/// by `component`, built by an item of object 2 with `item`.
fn nested(component: &str, item: &str) -> String {
    format!(
        "<?xml version=\"1.0\"?>\n<model unit=\"centimeter\" xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\"><resources>\
         <object id=\"1\"><mesh><vertices><vertex x=\"1\" y=\"0\" z=\"0\"/><vertex x=\"0\" y=\"1\" z=\"0\"/><vertex x=\"0\" y=\"0\" z=\"1\"/></vertices>\
         <triangles><triangle v1=\"0\" v2=\"1\" v3=\"2\"/></triangles></mesh></object>\
         <object id=\"2\"><components><component objectid=\"1\" transform=\"{component}\"/></components></object>\
         </resources><build><item objectid=\"2\" transform=\"{item}\"/></build></model>"
    )
}

#[test]
fn components_are_placed_by_their_transform_then_the_item_s() {
    // The component moves by (10, 0, 0), the item mirrors x and moves
    // by (0, 5, 0): (x, y, z) goes to (-(x + 10), y + 5, z), and the
    // mirrored triangle's corners swap to keep facing out.
    let m = three_mf::read(&package::zip_model(&nested(
        "1 0 0 0 1 0 0 0 1 10 0 0",
        "-1 0 0 0 1 0 0 0 1 0 5 0",
    )))
    .unwrap();
    assert_eq!(m.scale, 10.0);
    assert_eq!(m.unit, "centimeter");
    assert_eq!(
        m.triangles,
        vec![[[-11.0, 5.0, 0.0], [-10.0, 5.0, 1.0], [-10.0, 6.0, 0.0]]]
    );
}

#[test]
fn what_is_no_3mf_says_where() {
    assert!(matches!(
        three_mf::read(b"PK\x03\x04 no zip"),
        Err(three_mf::ThreeMfError::NotZip { .. })
    ));
    let loops = nested("1 0 0 0 1 0 0 0 1 0 0 0", "1 0 0 0 1 0 0 0 1 0 0 0")
        .replace("<component objectid=\"1\"", "<component objectid=\"2\"");
    assert_eq!(
        three_mf::read(&package::zip_model(&loops)).unwrap_err(),
        three_mf::ThreeMfError::TooDeep { object: 2, item: 1 }
    );
    let missing = nested("1 0 0 0 1 0 0 0 1 0 0 0", "1 0 0 0 1 0 0 0 1 0 0 0")
        .replace("<item objectid=\"2\"", "<item objectid=\"9\"");
    assert_eq!(
        three_mf::read(&package::zip_model(&missing)).unwrap_err(),
        three_mf::ThreeMfError::NoObject { id: 9, item: 1 }
    );
    let no_item = nested("1 0 0 0 1 0 0 0 1 0 0 0", "1 0 0 0 1 0 0 0 1 0 0 0");
    let no_item = no_item.replace(
        "<item objectid=\"2\" transform=\"1 0 0 0 1 0 0 0 1 0 0 0\"/>",
        "",
    );
    assert_eq!(
        three_mf::read(&package::zip_model(&no_item)).unwrap_err(),
        three_mf::ThreeMfError::NoItem
    );
    let bad = package::zip_model("<model><resources>");
    assert!(
        matches!(
            three_mf::read(&bad),
            Err(three_mf::ThreeMfError::Xml { .. })
        ),
        "{:?}",
        three_mf::read(&bad)
    );
}

/// The numbers of the overlap error in `m`: the layer (from 1), the cut's
/// height and the point (mm).
fn overlap_numbers(m: &str) -> (usize, f64, [f64; 2]) {
    let rest = m
        .split("the sections of two shells of the mesh overlap on layer ")
        .nth(1)
        .unwrap_or_else(|| panic!("no overlap error: {m}"));
    let num = |s: &str| {
        s.trim()
            .parse::<f64>()
            .unwrap_or_else(|_| panic!("{s} in {m}"))
    };
    let (layer, rest) = rest.split_once(" (cut at z = ").unwrap();
    let (z, rest) = rest.split_once(" mm), at (").unwrap();
    let (x, rest) = rest.split_once(", ").unwrap();
    let (y, _) = rest.split_once(") mm").unwrap();
    (layer.parse().unwrap(), num(z), [num(x), num(y)])
}

/// The layer height the plate program builds the mesh `tris` with.
fn lift(tris: &[Triangle]) -> f64 {
    let c = compile(
        &source("profile = mesh(\"part.stl\")"),
        BTreeMap::from([("part.stl", stl::to_binary(tris))]),
    );
    let m = messages(&c);
    let ir = c.program.unwrap_or_else(|| panic!("{m}")).into_ir();
    ir.layers[1].frame.origin[2] - ir.layers[0].frame.origin[2]
}

/// Whether `p` lies in the box from `lo` to `hi` (in plan, edges included).
fn in_box(p: [f64; 2], lo: [f64; 3], hi: [f64; 3]) -> bool {
    (0..2).all(|i| lo[i] - 1e-9 <= p[i] && p[i] <= hi[i] + 1e-9)
}

#[test]
fn overlapping_shells_are_refused_on_the_first_layer_they_share() {
    // A 10 mm box 3.5 mm tall, and a second standing in it from 1.5 mm up,
    // overlapping it by 5 × 5 mm in plan: the layers cut below 1.5 mm see
    // one square, the first above both.
    let (a, b) = (
        ([0.0, 0.0, 0.0], [10.0, 10.0, 3.5]),
        ([5.0, 5.0, 1.5], [15.0, 15.0, 3.5]),
    );
    let lift = lift(&cuboid(a.0, a.1));
    let mut tris = cuboid(a.0, a.1);
    tris.extend(cuboid(b.0, b.1));
    let c = compile(
        &source("profile = mesh(\"part.stl\")"),
        BTreeMap::from([("part.stl", stl::to_binary(&tris))]),
    );
    assert!(c.program.is_none());
    let m = messages(&c);
    let (layer, z, p) = overlap_numbers(&m);
    // Each layer is cut halfway up: the first cut above the second box's
    // floor.
    let first = (1..).find(|&k| (k as f64 - 0.5) * lift > b.0[2]).unwrap();
    assert_eq!(layer, first, "{m}");
    // The message's z to its 4 significant digits.
    assert!((z - (first as f64 - 0.5) * lift).abs() < 1e-3, "{m}");
    assert!(in_box(p, a.0, a.1) && in_box(p, b.0, b.1), "{p:?}: {m}");
    assert!(
        c.diagnostics.iter().any(|d| d
            .help
            .as_deref()
            .is_some_and(|h| h.contains("unite the shells"))),
        "{m}"
    );
}

#[test]
fn a_shell_inside_another_is_refused_at_a_point_of_both() {
    // No loops cross: the inner square lies straight in the outer one, with
    // no hole between, and would be laid twice.
    let (a, b) = (
        ([0.0, 0.0, 0.0], [20.0, 20.0, 2.0]),
        ([5.0, 6.0, 0.0], [12.0, 13.0, 2.0]),
    );
    let lift = lift(&cuboid(a.0, a.1));
    let mut tris = cuboid(a.0, a.1);
    tris.extend(cuboid(b.0, b.1));
    let c = compile(
        &source("profile = mesh(\"part.stl\")"),
        BTreeMap::from([("part.stl", stl::to_binary(&tris))]),
    );
    let m = messages(&c);
    let (layer, z, p) = overlap_numbers(&m);
    assert_eq!(layer, 1, "{m}");
    assert!((z - lift / 2.0).abs() < 1e-3, "{m}");
    assert!(in_box(p, a.0, a.1) && in_box(p, b.0, b.1), "{p:?}: {m}");
}

#[test]
fn shells_apart_and_islands_in_holes_still_build() {
    // Two boxes 1 mm apart: two islands on every layer.
    let mut apart = cuboid([0.0, 0.0, 0.0], [10.0, 10.0, 2.0]);
    apart.extend(cuboid([11.0, 0.0, 0.0], [21.0, 10.0, 2.0]));
    let src = source("profile = mesh(\"part.stl\")");
    for r in regions(&src, stl::to_binary(&apart)) {
        assert_eq!(r.outer().len(), 2);
        assert!((r.area() - 200.0).abs() < 1e-6, "{}", r.area());
    }
    // A 60 mm box with a hole of radius 18; in the hole a 20 mm box with a
    // hole of radius 6, and in that hole a 6 mm pillar: outline, hole,
    // island, its hole, island.
    let n = 32;
    let mut nested = box_with_hole([30.0, 30.0], 30.0, 18.0, 2.0, n);
    nested.extend(box_with_hole([30.0, 30.0], 10.0, 6.0, 2.0, n));
    nested.extend(cuboid([27.0, 27.0, 0.0], [33.0, 33.0, 2.0]));
    let want = 3600.0 - ngon(18.0, n) + 400.0 - ngon(6.0, n) + 36.0;
    let layers = regions(&src, stl::to_binary(&nested));
    assert_eq!(layers.len(), 3);
    for r in layers {
        assert_eq!((r.outer().len(), r.holes().len()), (3, 2));
        assert!(
            (r.area() - want).abs() < 1e-3,
            "{} against {want}",
            r.area()
        );
    }
}

/// The number after `before` and up to ` mm` in `s`.
fn number_after(s: &str, before: &str) -> f64 {
    let rest = s
        .split(before)
        .nth(1)
        .unwrap_or_else(|| panic!("no `{before}` in {s}"));
    let end = rest.find(" mm").unwrap();
    rest[..end].parse().unwrap_or_else(|_| panic!("{rest}"))
}

#[test]
fn a_mesh_a_hair_below_the_plate_says_by_how_much_and_the_z_that_fixes_it() {
    // A box laid on its side by 1.5708 rad, not quite a quarter turn: its
    // far top edge ends 5 mm · cos(1.5708) below the plate.
    let (lo, hi) = ([0.0, 0.0, 0.0], [10.0, 10.0, 5.0]);
    let bytes = stl::to_binary(&cuboid(lo, hi));
    // The rounded quarter turn a user types is the point of the test.
    #[allow(clippy::approx_constant)]
    let turn = 1.5708_f64;
    let below = hi[2] * turn.cos();
    assert!(below < -1e-6);
    let call = |z: &str| {
        format!("profile = mesh(\"part.stl\", turn = [{turn} rad, 0 deg, 0 deg], at = [0 mm, 0 mm, {z}])")
    };
    let c = compile(
        &source(&call("0 mm")),
        BTreeMap::from([("part.stl", bytes.clone())]),
    );
    let m = messages(&c);
    let shown = number_after(&m, "lowest point at z = ");
    assert!(m.contains("mm, below the plate"), "{m}");
    assert!(
        shown < 0.0 && (shown - below).abs() <= 0.05 * below.abs(),
        "{m}"
    );
    let help = c.diagnostics.iter().find_map(|d| d.help.clone()).unwrap();
    let fix = number_after(&help, "`at` to ");
    assert!((0.0..=1e-6).contains(&(fix + below)), "{help}");
    // Following the advice builds.
    let c = compile(
        &source(&call(&format!("{fix} mm"))),
        BTreeMap::from([("part.stl", bytes)]),
    );
    assert!(c.program.is_some(), "{}", messages(&c));
}

#[test]
fn a_lowest_point_within_a_millionth_of_a_mm_is_on_the_plate() {
    let bytes = stl::to_binary(&cuboid([0.0, 0.0, 2.0], [10.0, 10.0, 4.0]));
    let at = |z: &str| format!("profile = mesh(\"part.stl\", at = [0 mm, 0 mm, {z} mm])");
    for z in ["-2.0000009", "-1.9999991"] {
        let c = compile(
            &source(&at(z)),
            BTreeMap::from([("part.stl", bytes.clone())]),
        );
        assert!(c.program.is_some(), "{z}: {}", messages(&c));
    }
    // The box's floor is at the file's z = 2 mm: -2 mm for `at`'s z stands
    // it on the plate.
    for (z, low, place) in [
        ("-2.0000011", "-0.0000011", "below"),
        ("-1.9999989", "0.0000011", "above"),
    ] {
        let c = compile(
            &source(&at(z)),
            BTreeMap::from([("part.stl", bytes.clone())]),
        );
        let m = messages(&c);
        assert!(
            m.contains(&format!("lowest point at z = {low} mm, {place} the plate")),
            "{m}"
        );
        let help = c.diagnostics.iter().find_map(|d| d.help.clone()).unwrap();
        assert_eq!(number_after(&help, "`at` to "), -2.0, "{help}");
    }
}

/// The fewest points a raster fill of a mesh of volume `v`, surface `s`,
/// diagonal in plan `d` and height `h` lays in layers `lift` apart, tracks
/// `offset` apart inside `contours` contours: what docs/language.md gives.
fn least_fill_points([v, s, d, h]: [f64; 4], lift: f64, offset: f64, contours: f64) -> f64 {
    let raster = v - s * (contours + 1.0) * offset;
    let n = (h / lift).ceil();
    2.0 * (raster / (lift * d * offset) - n).max(0.0)
}

#[test]
fn a_mesh_in_the_wrong_units_is_refused_before_slicing_with_its_size() {
    // A 60 × 30 × 22 box written in mm, read in metres.
    let (x, y, z) = (60.0, 30.0, 22.0);
    let bytes = stl::to_binary(&cuboid([0.0; 3], [x, y, z]));
    let src = |units: &str| source(&format!("profile = mesh(\"part.stl\", units = {units})"));
    // In mm it builds: its fill has at least the points the bound says.
    let c = compile(&src("mm"), BTreeMap::from([("part.stl", bytes.clone())]));
    let m = messages(&c);
    let ir = c.program.unwrap_or_else(|| panic!("{m}")).into_ir();
    let lift = ir.layers[1].frame.origin[2] - ir.layers[0].frame.origin[2];
    // plate.lmd: tracks 1.6 mm apart, no contour (the default with a
    // raster).
    let (offset, contours) = (1.6, 0.0);
    let box_numbers = |k: f64| {
        let (a, b, c) = (x * k, y * k, z * k);
        [a * b * c, 2.0 * (a * b + b * c + c * a), a.hypot(b), c]
    };
    let laid: usize = ir
        .layers
        .iter()
        .flat_map(|l| &l.paths)
        .filter(|p| p.kind == lmdc::ir::PathKind::Infill)
        .map(|p| p.points.len())
        .sum();
    let bound = least_fill_points(box_numbers(1.0), lift, offset, contours);
    assert!(bound > 0.0 && bound <= laid as f64, "{bound} > {laid}");
    // In metres it is refused at once, with its size and the unit in which
    // it would fit.
    let c = compile(&src("m"), BTreeMap::from([("part.stl", bytes)]));
    assert!(c.program.is_none());
    let m = messages(&c);
    assert!(
        m.contains("(read in `units = m`) is 60000 × 30000 × 22000 mm as placed"),
        "{m}"
    );
    let layers = (z * 1000.0 / lift).ceil() as usize;
    assert!(m.contains(&format!("its {layers} layers of ")), "{m}");
    let least = least_fill_points(box_numbers(1000.0), lift, offset, contours);
    let shown = number_after(&m.replace(" points", " mm"), "need at least ");
    assert!(
        (shown - least).abs() <= 1e-6 * least,
        "{shown} against {least}"
    );
    assert!(least > 20_000_000.0);
    assert!(m.contains("more than the 20000000 a plan may hold"), "{m}");
    assert!(
        c.diagnostics
            .iter()
            .any(|d| d.code == lmdc::diag::Code::TooManyPoints
                && d.help
                    .as_deref()
                    .is_some_and(|h| h.contains("in mm it would be 60 × 30 × 22 mm"))),
        "{m}"
    );
}
