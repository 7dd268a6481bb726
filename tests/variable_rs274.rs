//! The G-code of each seed 003 example runs in LinuxCNC's interpreter
//! (`rs274`) and its Z follows the planned top: every deposit move of layer
//! `k` (from 0) ends at `z = k·H(x, y)/N`, with `H` the top the file states,
//! the layers in order, the last one on `(N − 1)/N` of the top — so the top
//! is reached when it has laid its `H/N`. Skipped without rs274, except
//! under CI.

use crate::support::rs274;
use crate::support::skip;

use lmdc::back::{MemorySink, Templates};
use lmdc::ir::Machine;
use lmdc::pipeline::compile;
use rs274::CanonCall;

type Top = fn([f64; 2]) -> f64;

fn ramp_wall_top(p: [f64; 2]) -> f64 {
    20.0 + 0.16 * (p[0] + 50.0)
}
fn wedge_top(p: [f64; 2]) -> f64 {
    8.0 + 5.0 * (p[1] + 7.5) / 15.0
}
fn ramp_cuboid_top(p: [f64; 2]) -> f64 {
    14.0 + 8.0 * (p[0] + 30.0) / 60.0 + 3.0 * (p[1] + 7.5) / 15.0
}

#[test]
fn z_follows_the_planned_top() {
    if rs274::find_rs274().is_none() {
        skip::skip(
            "z_follows_the_planned_top",
            "LinuxCNC's rs274",
            "run `bash .ci/install-rs274.sh` and export LMDC_RS274=<the path it prints>",
        );
        return;
    }
    for (path, top) in [
        ("examples/ramp_wall.lmd", ramp_wall_top as Top),
        ("examples/wedge.lmd", wedge_top as Top),
        ("examples/ramp_cuboid.lmd", ramp_cuboid_top as Top),
    ] {
        let src = std::fs::read_to_string(path).unwrap();
        let v = compile(&src, &mut ()).program.expect("compiles");
        let n = v.ir().layers.len();
        let m = v
            .machines()
            .find(|m| matches!(m.machine(), Machine::Cnc(_)))
            .expect("a CNC");
        let mut sink = MemorySink::default();
        lmdc::back::emit(m, &Templates::builtin().unwrap(), &mut sink).unwrap();
        let text = String::from_utf8(sink.files.pop().unwrap().1).unwrap();
        let calls = rs274::interpret_source(&text)
            .unwrap_or_else(|e| panic!("{path}: rs274 refused the program: {e}"));
        let (mut laser, mut layer, mut deposits) = (false, 0usize, 0usize);
        let mut off_top = 0.0f64;
        for call in rs274::program_body(&calls) {
            match *call {
                CanonCall::SpindleOn => laser = true,
                CanonCall::SpindleOff => laser = false,
                CanonCall::Feed { x, y, z, .. } if laser => {
                    // Defocus 0: the tool tip is the deposit point.
                    let h = top([x, y]);
                    let k = (z * n as f64 / h).round();
                    assert!(
                        (z - k * h / n as f64).abs() <= 1e-3,
                        "{path}: Z{z} at ({x}, {y}) is not on a layer's planned top ({h} mm / {n})"
                    );
                    let k = k as usize;
                    assert!(k >= layer && k < n, "{path}: layer {k} after {layer}");
                    layer = k;
                    if k == n - 1 {
                        off_top = off_top.max((z + h / n as f64 - h).abs());
                    }
                    deposits += 1;
                }
                _ => {}
            }
        }
        assert_eq!(layer, n - 1, "{path}: the last layer was not reached");
        // The last layer, laying H/N on (N − 1)/N of the top, ends on it.
        assert!(off_top <= 1e-3, "{path}: {off_top}");
        assert!(deposits > 0);
    }
}
