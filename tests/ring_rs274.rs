//! The LinuxCNC controller of seed 004 executed: the program lmdc writes for
//! `examples/segmented_ring.lmd`'s mill runs in rs274 (LinuxCNC's own
//! interpreter), its `M66` reads answered with the heights `lmdc simulate`
//! computes (tests/support/m66.rs says how). The feeds and heights rs274
//! reports are the simulation's, layer by layer and segment by segment: the
//! O-word subroutine runs the same law.

use crate::support::m66;
use crate::support::ring;
use crate::support::rs274;
use crate::support::skip;

use lmdc::ir::Machine;
use rs274::CanonCall;

/// One G1 with the laser on: where to and the feed in force, mm/s.
#[derive(Clone, Copy, Debug)]
struct Feed {
    pos: [f64; 3],
    speed: f64,
}

#[test]
fn the_o_word_subroutine_sets_the_speeds_lmdc_simulate_computes() {
    if rs274::find_rs274().is_none() {
        skip::skip(
            "the_o_word_subroutine_sets_the_speeds_lmdc_simulate_computes",
            "rs274",
            "run `bash .ci/install-rs274.sh` or set LMDC_RS274",
        );
        return;
    }
    let src = std::fs::read_to_string(ring::EXAMPLE).unwrap();
    let p = ring::compile(ring::EXAMPLE, &src);
    let r = p.ir().ring.clone().expect("a ring");
    let Some(Machine::Cnc(cnc)) = p.ir().machines.iter().find(|m| m.name() == "mill3") else {
        panic!("mill3 is a CNC")
    };
    let sensor = cnc.height_sensor.expect("a sensor");
    let rows = ring::simulation(&src);
    let inputs: Vec<Vec<f64>> = rows
        .iter()
        .map(|l| l.iter().map(|x| x.height / sensor.full_scale).collect())
        .collect();
    let files = ring::files(&p, "mill3");
    let (_, ngc) = files.iter().next().expect("one program");
    let text = m66::scripted(ngc, sensor.input, &inputs);
    let calls = rs274::interpret_source(&text).unwrap_or_else(|e| panic!("rs274: {e}"));
    let body = rs274::program_body(&calls);
    let (mut feed, mut laser) = (0.0, false);
    let mut got = Vec::new();
    for c in body {
        match *c {
            CanonCall::FeedRate(f) => feed = f / 60.0,
            CanonCall::SpindleOn => laser = true,
            CanonCall::SpindleOff => laser = false,
            CanonCall::Feed { x, y, z, .. } if laser => got.push(Feed {
                pos: [x, y, z],
                speed: feed,
            }),
            CanonCall::Traverse { .. } => assert!(!laser, "G0 with the laser on"),
            _ => {}
        }
    }
    let n = r.segments.len();
    let per = r.flat_moves + r.transition_moves;
    assert_eq!(got.len(), n * per * rows.len(), "one G1 per point");
    let arc = r.radius * r.transition.to_radians();
    for (l, layer) in got.chunks(n * per).enumerate() {
        for (j, seg) in layer.chunks(per).enumerate() {
            let row = rows[l][j];
            let plane = if l == 0 { 0.0 } else { rows[l - 1][j].total };
            let d = r.segments[j].defocus;
            for (k, g) in seg.iter().enumerate() {
                let at = format!("layer {} segment {} move {k}: {g:?}", l + 1, j + 1);
                // rs274 prints 4 decimals: F in mm/min, positions in mm.
                if k < r.flat_moves {
                    assert!((g.speed - row.speed).abs() < 2e-6, "{at}: want {row:?}");
                    assert!(
                        (g.pos[2] - (plane + d)).abs() < 6e-5,
                        "{at}: want {}",
                        plane + d
                    );
                } else {
                    // Up (or down) to the next segment's height; the last
                    // one to where segment 1 lands if it laid the target
                    // (it is read at the seam, after this transition), and
                    // level on the last layer.
                    let zf = plane + d;
                    let zt = match (j + 1 < n, l + 1 < rows.len()) {
                        (true, _) => {
                            (if l == 0 {
                                0.0
                            } else {
                                rows[l - 1][j + 1].total
                            }) + r.segments[j + 1].defocus
                        }
                        (false, true) => {
                            (if l == 0 { 0.0 } else { rows[l - 1][0].total })
                                + r.layer_height
                                + r.segments[0].defocus
                        }
                        (false, false) => zf,
                    };
                    let want = row.speed * (1.0 + ((zt - zf) / arc).powi(2)).sqrt();
                    // ARC is written with 6 decimals: 2e-7 of it.
                    assert!(
                        (g.speed - want).abs() < 2e-6 + 1e-6 * want,
                        "{at}: want {want}"
                    );
                    let f = (k + 1 - r.flat_moves) as f64 / r.transition_moves as f64;
                    assert!(
                        (g.pos[2] - (zf + f * (zt - zf))).abs() < 6e-5,
                        "{at}: height"
                    );
                }
            }
        }
    }
}

/// Rings of every shape — one segment or many, one layer or a few, a 3-axis
/// mill or an A/C head — run in rs274 with the sensor on target lay their IR:
/// every deposit at its focus and speed, the laser off at the end.
mod shapes {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(12))]
        #[test]
        fn every_ring_lays_its_ir_on_target(
            segments in prop_oneof![Just(1usize), 2..5usize, Just(10)],
            layers in 1..4usize,
            transition in prop_oneof![Just(2.0f64), Just(5.0)],
            step in prop_oneof![Just(1.0f64), Just(3.0)],
            five in any::<bool>(),
        ) {
            if rs274::find_rs274().is_none() {
                skip::skip("every_ring_lays_its_ir_on_target", "rs274", "run `bash .ci/install-rs274.sh`");
                return Ok(());
            }
            let src = ring::variant(segments, layers, transition, step, "z", five);
            let p = ring::compile("variant", &src);
            let ir = p.ir();
            let Some(Machine::Cnc(cnc)) = ir.machines.iter().find(|m| m.name() == "mill3") else {
                panic!("mill3")
            };
            let input = cnc.height_sensor.unwrap().input;
            let files = ring::files(&p, "mill3");
            let (_, ngc) = files.iter().next().unwrap();
            let steady = vec![vec![ring::on_target_reading(&p, "mill3"); segments]; layers];
            let text = if layers > 1 { m66::scripted(ngc, input, &steady) } else { ngc.clone() };
            let calls = rs274::interpret_source(&text).unwrap_or_else(|e| panic!("{e}\n{text}"));
            let (mut feed, mut laser) = (0.0, false);
            let mut got = Vec::new();
            for c in rs274::program_body(&calls) {
                match *c {
                    CanonCall::FeedRate(f) => feed = f / 60.0,
                    CanonCall::SpindleOn => laser = true,
                    CanonCall::SpindleOff => laser = false,
                    CanonCall::Feed { x, y, z, .. } if laser => got.push(([x, y, z], feed)),
                    _ => {}
                }
            }
            let want: Vec<_> = ir
                .layers
                .iter()
                .flat_map(|l| &l.paths)
                .flat_map(|p| p.points.windows(2))
                .filter(|w| w[0].laser_on)
                .map(|w| (w[0], w[1]))
                .collect();
            prop_assert_eq!(got.len(), want.len());
            for ((from, to), (pos, f)) in want.iter().zip(&got) {
                let at = to.focus();
                for i in 0..3 {
                    prop_assert!((pos[i] - at[i]).abs() < 1e-3, "{:?} vs {:?}", pos, at);
                }
                prop_assert!((f - from.speed as f64).abs() < 1e-3 * from.speed as f64, "{} vs {}", f, from.speed);
            }
            prop_assert!(!laser);
        }
    }
}
