//! How long emitting 3.6 M points takes. Not a timed test (timings are not
//! assertions): run it by hand in release and read the numbers:
//!
//! ```text
//! cargo test --release --test gcode_perf -- --ignored --nocapture
//! ```

#[path = "gcode_common.rs"]
mod common;
use common::fixture::*;
use common::*;
use lmdc::back::{Sink, Templates};
use lmdc::ir::*;
use std::io::{self, Write};
use std::time::Instant;

/// Counts the bytes and throws them away: times the back end, not the disk.
#[derive(Default)]
struct Discard {
    bytes: u64,
}

struct Counter<'a>(&'a mut Discard);

impl Write for Counter<'_> {
    fn write(&mut self, b: &[u8]) -> io::Result<usize> {
        self.0.bytes += b.len() as u64;
        Ok(b.len())
    }
    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

impl Sink for Discard {
    fn create(&mut self, _name: &str) -> io::Result<Box<dyn Write + '_>> {
        Ok(Box::new(Counter(self)))
    }
}

/// Writes into a directory, like the CLI.
struct Files(std::path::PathBuf);

impl Sink for Files {
    fn create(&mut self, name: &str) -> io::Result<Box<dyn Write + '_>> {
        Ok(Box::new(std::fs::File::create(self.0.join(name))?))
    }
}

fn time(label: &str, ir: Program) {
    let points = ir.point_count();
    let v = verified(ir);
    assert!(matches!(v.ir().machines[0], Machine::Cnc(_)));
    let t = Templates::builtin().unwrap();
    // The floor: one pass reading every point, as the back end must.
    let start = Instant::now();
    let mut sum = 0.0;
    for l in &v.ir().layers {
        for p in &l.paths {
            for pt in &p.points {
                sum += pt.focus()[0] + pt.speed as f64;
            }
        }
    }
    println!(
        "{label}: reading the points alone takes {:.3} s ({sum:.0})",
        start.elapsed().as_secs_f64()
    );
    // The VM this runs on is noisy: the best of five.
    let mut best = f64::INFINITY;
    let mut bytes = 0;
    for _ in 0..5 {
        let mut sink = Discard::default();
        let start = Instant::now();
        if let Err(e) = lmdc::back::emit(v.machine(0).unwrap(), &t, &mut sink) {
            panic!("{e}");
        }
        best = best.min(start.elapsed().as_secs_f64());
        bytes = sink.bytes;
    }
    println!(
        "{label}: {points} points, {:.1} MB in {best:.3} s ({:.0} ns/point), best of 5",
        bytes as f64 / 1e6,
        best * 1e9 / points as f64
    );
    let dir = tempfile::tempdir().unwrap();
    let mut sink = Files(dir.path().to_path_buf());
    let start = Instant::now();
    lmdc::back::emit(v.machine(0).unwrap(), &t, &mut sink).unwrap();
    println!("{label} to a file: {:.3} s", start.elapsed().as_secs_f64());
}

/// 3000 layers × 1200 points: the size of the dense duct.
fn dense(machine: Cnc) -> Program {
    let mut ir = bent_tube(3000, 1199, 45.0, vec![Machine::Cnc(machine)]);
    // The fixture lowers the power by 20 W a layer; hold it after 20 layers, as
    // seed 000 does.
    for l in &mut ir.layers {
        for p in &mut l.paths {
            for pt in &mut p.points {
                pt.power = pt.power.max(2600.0);
            }
        }
    }
    ir
}

#[test]
#[ignore = "timing; run by hand in release"]
fn emit_3_6_m_points() {
    let mut cnc = fixture::cnc5();
    cnc.limits.z = [-1000.0, 1000.0];
    // Endless C: the wobbling normals below circle the vertical in early layers.
    cnc.limits.rotary = [-1e6, 1e6];
    time("5-axis, one normal per layer", dense(cnc.clone()));

    // Worst case for the kinematics: the normal changes at every point.
    let mut ir = dense(cnc);
    for l in &mut ir.layers {
        for p in &mut l.paths {
            for (k, pt) in p.points.iter_mut().enumerate() {
                let w = 0.01 * (k as f32).sin();
                let n = [pt.normal[0] + w, pt.normal[1] - w, pt.normal[2]];
                let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
                pt.normal = [n[0] / len, n[1] / len, n[2] / len];
            }
        }
    }
    time("5-axis, a new normal at every point", ir);

    let mut ir = dense(cnc3());
    for l in &mut ir.layers {
        for p in &mut l.paths {
            for pt in &mut p.points {
                pt.normal = [0.0, 0.0, 1.0];
            }
        }
    }
    time("3-axis", ir);
}
