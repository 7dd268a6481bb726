//! The dense duct benchmark (examples/bench/dense_duct.lmd: 1000 layers × 3600
//! points = 3.6 M points): front end (parse → check → slice → verify) and each
//! back end, writing into a sink that discards the bytes but counts them.
//! Peak memory per stage: `lmdc build examples/bench/dense_duct.lmd --timings`.
//!
//! `fixed-point floor` is what the write path is measured against: a line
//! of six numbers for every point of every machine's program (as many lines
//! as the programs' motion lines), formatted by a tight integer formatter
//! into one file — no templates, no modules, no motion planning, one file
//! to create; `…, into memory` only formats, `…, flushed` flushes the file
//! to disk too.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use lmdc::back::{Sink, Templates};
use lmdc::ir::Machine;
use lmdc::pipeline::compile;
use std::io::{self, Write};

/// Appends `v` with three decimals, fixed point, to `out`: an integer
/// formatter (no float formatting), the floor's one computation.
fn fixed3(out: &mut Vec<u8>, v: f64) {
    // Half away from zero by a cast (no call to `round`).
    let milli = (v * 1000.0 + 0.5f64.copysign(v)) as i64;
    let mut m = milli.unsigned_abs();
    // Digits from the last, into a buffer on the stack; appended at once.
    let mut buf = [0u8; 24];
    let mut i = buf.len();
    for _ in 0..3 {
        i -= 1;
        buf[i] = b'0' + (m % 10) as u8;
        m /= 10;
    }
    i -= 1;
    buf[i] = b'.';
    loop {
        i -= 1;
        buf[i] = b'0' + (m % 10) as u8;
        m /= 10;
        if m == 0 {
            break;
        }
    }
    if milli < 0 {
        i -= 1;
        buf[i] = b'-';
    }
    out.extend_from_slice(&buf[i..]);
}

/// Where the floor writes.
#[derive(Clone, Copy)]
enum Into {
    /// Bytes counted, not kept.
    Memory,
    /// One file.
    File,
    /// One file, flushed to disk.
    Disk,
}

/// Writes one line per point, `copies` times over, as `into` says (`file`
/// the file): the bytes written.
fn floor(program: &lmdc::ir::Program, copies: usize, file: &std::path::Path, into: Into) -> u64 {
    let mut f: Box<dyn Write> = match into {
        Into::Memory => Box::new(io::sink()),
        _ => Box::new(std::fs::File::create(file).unwrap()),
    };
    let mut buf = Vec::with_capacity(1 << 20);
    let mut bytes = 0;
    for _ in 0..copies {
        for p in program
            .layers
            .iter()
            .flat_map(|l| &l.paths)
            .flat_map(|p| &p.points)
        {
            let [x, y, z] = p.pos;
            let [nx, ny, _] = p.normal;
            for (tag, v) in [
                (b'X', x),
                (b'Y', y),
                (b'Z', z),
                (b'A', f64::from(nx) * 90.0),
                (b'C', f64::from(ny) * 180.0),
                (b'F', f64::from(p.speed) * 60.0),
            ] {
                buf.extend_from_slice(&[tag]);
                fixed3(&mut buf, v);
                buf.push(b' ');
            }
            buf.push(b'\n');
            if buf.len() >= 1 << 20 {
                f.write_all(&buf).unwrap();
                bytes += buf.len() as u64;
                buf.clear();
            }
        }
    }
    f.write_all(&buf).unwrap();
    drop(f);
    if let Into::Disk = into {
        std::fs::File::open(file).unwrap().sync_all().unwrap();
    }
    bytes + buf.len() as u64
}

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
    let dir = std::env::temp_dir().join(format!("lmdc-floor-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let copies = program.machines().count();
    for (name, into) in [
        ("fixed-point floor, into memory", Into::Memory),
        ("fixed-point floor", Into::File),
        ("fixed-point floor, flushed", Into::Disk),
    ] {
        g.bench_function(name, |b| {
            b.iter(|| floor(program.ir(), copies, &dir.join("floor.ngc"), into))
        });
    }
    let _ = std::fs::remove_dir_all(&dir);
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
