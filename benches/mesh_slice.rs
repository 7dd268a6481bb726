//! A mesh of 10⁶ triangles read, checked and cut into layers: a tube (outer
//! radius 40 mm, bore 25 mm, 100 mm tall) whose walls are 1000 triangles
//! round and 250 bands up, sliced in 400 layers of 0.25 mm, so each layer
//! crosses about 4000 triangles of the million. Measures what
//! `mesh(file = "…")` adds to a build: reading the binary STL, welding and
//! pairing the edges, and the sweep's sections.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use lmdc::geometry::mesh::stl::{self, Triangle};
use lmdc::geometry::mesh::{islands, Mesh, Placement};
use std::f64::consts::TAU;

const ROUND: usize = 1000;
const BANDS: usize = 250;
const HEIGHT: f64 = 100.0;
const LAYERS: usize = 400;

fn quad(out: &mut Vec<Triangle>, a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) {
    let f = |p: [f64; 3]| p.map(|x| x as f32);
    out.push([f(a), f(b), f(c)]);
    out.push([f(a), f(c), f(d)]);
}

/// The tube: outer and inner walls in bands, and the two end rings.
fn tube() -> Vec<Triangle> {
    let at = |r: f64, i: usize, k: usize| {
        let t = TAU * (i % ROUND) as f64 / ROUND as f64;
        [r * t.cos(), r * t.sin(), HEIGHT * k as f64 / BANDS as f64]
    };
    let (ro, ri) = (40.0, 25.0);
    let mut out = Vec::with_capacity(4 * ROUND * (BANDS + 1));
    for i in 0..ROUND {
        let j = i + 1;
        for k in 0..BANDS {
            quad(
                &mut out,
                at(ro, i, k),
                at(ro, j, k),
                at(ro, j, k + 1),
                at(ro, i, k + 1),
            );
            quad(
                &mut out,
                at(ri, j, k),
                at(ri, i, k),
                at(ri, i, k + 1),
                at(ri, j, k + 1),
            );
        }
        quad(
            &mut out,
            at(ro, i, BANDS),
            at(ro, j, BANDS),
            at(ri, j, BANDS),
            at(ri, i, BANDS),
        );
        quad(
            &mut out,
            at(ro, j, 0),
            at(ro, i, 0),
            at(ri, i, 0),
            at(ri, j, 0),
        );
    }
    out
}

fn mesh(c: &mut Criterion) {
    let tris = tube();
    let bytes = stl::to_binary(&tris);
    let place = Placement {
        scale: 1.0,
        turn: [0.0; 3],
        at: [0.0; 3],
    };
    let mut g = c.benchmark_group("mesh");
    g.sample_size(10);
    g.throughput(Throughput::Elements(tris.len() as u64));
    g.bench_function("read_and_check", |b| {
        b.iter(|| {
            Mesh::new(&stl::read(&bytes).unwrap(), place)
                .unwrap()
                .triangle_count()
        })
    });
    let m = Mesh::new(&tris, place).unwrap();
    g.bench_function("sections", |b| {
        b.iter(|| {
            let mut s = m.sections();
            let lift = HEIGHT / LAYERS as f64;
            (0..LAYERS)
                .map(|k| {
                    islands(s.loops((k as f64 + 0.5) * lift).unwrap())
                        .unwrap()
                        .iter()
                        .map(|island| island.holes.len())
                        .sum::<usize>()
                })
                .sum::<usize>()
        })
    });
    g.finish();
}

criterion_group!(benches, mesh);
criterion_main!(benches);
