//! The dense duct benchmark (examples/bench/dense_duct.lmd: 1000 layers × 3600
//! points = 3.6 M points): front end (parse → check → slice → verify) and each
//! back end, writing into a sink that discards the bytes but counts them.
//! Peak memory per stage: `lmdc build examples/bench/dense_duct.lmd --timings`.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use lmdc::back::{Sink, Templates};
use lmdc::ir::Machine;
use lmdc::pipeline::compile;
use std::io::{self, Write};

/// Discards output, counting bytes (so the writer cannot be optimised away).
#[derive(Default)]
struct Null {
    bytes: u64,
}

struct NullFile<'a>(&'a mut u64);

impl Write for NullFile<'_> {
    fn write(&mut self, b: &[u8]) -> io::Result<usize> {
        *self.0 += b.len() as u64;
        Ok(b.len())
    }
    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

impl Sink for Null {
    fn create(&mut self, _: &str) -> io::Result<Box<dyn Write + '_>> {
        Ok(Box::new(NullFile(&mut self.bytes)))
    }
}

fn dense(c: &mut Criterion) {
    let src = std::fs::read_to_string("examples/bench/dense_duct.lmd").unwrap();
    let program = compile(&src, &mut ()).program.expect("dense duct compiles");
    let points = program.ir().point_count() as u64;
    let templates = Templates::builtin().unwrap();
    let mut g = c.benchmark_group("dense_duct");
    g.sample_size(10);
    g.throughput(Throughput::Elements(points));
    g.bench_function("front end (parse..verify)", |b| {
        b.iter(|| compile(&src, &mut ()).program.unwrap())
    });
    for m in program.machines() {
        let name = match m.machine() {
            Machine::Robot(_) => "emit KRL",
            Machine::Cnc(_) => "emit G-code",
        };
        g.bench_function(name, |b| {
            b.iter(|| {
                let mut sink = Null::default();
                lmdc::back::emit(m, &templates, &mut sink).unwrap();
                sink.bytes
            })
        });
    }
    g.finish();
}

criterion_group!(benches, dense);
criterion_main!(benches);
