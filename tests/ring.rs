//! Seed 004 end to end: the compiled ring against the paper (Table 1, the
//! transitions' `v / cos γ`), `lmdc simulate` against the paper's result
//! (29.90 mm on every segment), the open-loop schedule as every back end
//! writes it, and the dialects that cannot run the loop.

use crate::support::ring as support;

use lmdc::ir::{Machine, Point, RingRun};

/// Table 1 of Shen et al.: defocus mm, power W, width mm, speed mm/s.
const TABLE_1: [(f64, f64, f64, f64); 10] = [
    (-8.0, 1200.0, 6.25, 4.0),
    (-7.0, 1050.0, 5.55, 5.0),
    (-6.0, 920.0, 4.65, 6.0),
    (-5.0, 780.0, 3.50, 11.0),
    (-4.0, 650.0, 2.50, 13.0),
    (-4.0, 650.0, 2.50, 13.0),
    (-5.0, 780.0, 3.50, 11.0),
    (-6.0, 920.0, 4.65, 6.0),
    (-7.0, 1050.0, 5.55, 5.0),
    (-8.0, 1200.0, 6.25, 4.0),
];

fn example() -> String {
    std::fs::read_to_string(support::EXAMPLE).unwrap()
}

/// The first layer's points, with the segment each belongs to.
fn first_layer(p: &lmdc::ir::Program) -> Vec<(usize, bool, Point)> {
    let r = p.ring.as_ref().unwrap();
    let per = r.flat_moves + r.transition_moves;
    let pts = &p.layers[0].paths[0].points;
    pts[..pts.len() - 1]
        .iter()
        .enumerate()
        .map(|(k, pt)| (k / per, k % per >= r.flat_moves, *pt))
        .collect()
}

#[test]
fn the_first_layer_lays_table_1() {
    let p = support::compile(support::EXAMPLE, &example());
    let ir = p.ir();
    let r = ir.ring.as_ref().unwrap();
    assert_eq!(r.segments.len(), 10);
    for (j, (s, want)) in r.segments.iter().zip(TABLE_1).enumerate() {
        assert_eq!((s.defocus, s.power, s.width, s.speed), want, "row {j}");
        // E = P/(D·v) with D the width: 1200/(6.25·4) = 48 J/mm².
        let e = want.1 / (want.2 * want.3);
        assert!((s.energy_density - e).abs() < 1e-9, "row {j}");
    }
    assert!((r.segments[0].energy_density - 48.0).abs() < 1e-12);
    let mut seen = [0usize; 10];
    for (j, transition, pt) in first_layer(ir) {
        if transition {
            continue;
        }
        seen[j] += 1;
        let (d, w, _, v) = TABLE_1[j];
        assert_eq!(pt.defocus as f64, d, "segment {j}");
        assert_eq!(pt.power as f64, w, "segment {j}");
        assert_eq!(pt.speed as f64, v, "segment {j}");
        assert!(pt.laser_on);
        // On the substrate, the focus `defocus` below it.
        assert_eq!(pt.pos[2], 0.0);
        assert_eq!(pt.focus()[2], d);
        // Segment j spans 36° from j·36° counter-clockwise from +x.
        let deg = pt.pos[1].atan2(pt.pos[0]).to_degrees().rem_euclid(360.0);
        assert!(deg >= 36.0 * j as f64 - 1e-9 && deg < 36.0 * (j + 1) as f64 - 2.0 + 1e-9);
    }
    assert!(seen.iter().all(|&n| n == r.flat_moves));
}

#[test]
fn transitions_run_at_v_over_cos_gamma() {
    let p = support::compile(support::EXAMPLE, &example());
    let ir = p.ir();
    let r = ir.ring.as_ref().unwrap();
    let arc = r.radius * r.transition.to_radians();
    let pts = &ir.layers[0].paths[0].points;
    let mut checked = 0;
    for (k, (j, transition, pt)) in first_layer(ir).into_iter().enumerate() {
        if !transition {
            continue;
        }
        // The rise from the table: the defocus step to the next segment, and
        // the layer height into the next layer after the last.
        let rise = match TABLE_1.get(j + 1) {
            Some(next) => next.0 - TABLE_1[j].0,
            None => TABLE_1[0].0 - TABLE_1[j].0 + r.layer_height,
        };
        let gamma = (rise / arc).atan();
        let want = TABLE_1[j].3 / gamma.cos();
        assert!(
            (pt.speed as f64 - want).abs() < 1e-5 * want,
            "segment {j}: {} mm/s, want {want}",
            pt.speed
        );
        // And from the points themselves: path length over horizontal length
        // (a chord against the arc: within 1e-4).
        let (a, b) = (pt.focus(), pts[k + 1].focus());
        let horizontal = (b[0] - a[0]).hypot(b[1] - a[1]);
        let path = horizontal.hypot(b[2] - a[2]);
        let from_points = TABLE_1[j].3 * path / horizontal;
        assert!((pt.speed as f64 - from_points).abs() < 1e-4 * want);
        checked += 1;
    }
    assert_eq!(checked, 10 * r.transition_moves);
    // Segment 1 → 2: 1 mm over 1.396 mm, γ = 35.6°, 4 mm/s → 4.92 mm/s.
    let first = first_layer(ir)
        .into_iter()
        .find(|(_, t, _)| *t)
        .map(|(_, _, pt)| pt.speed)
        .unwrap();
    assert!((first - 4.920).abs() < 5e-4, "{first}");
}

/// The paper's gains read per (m/s)/mm, against a plant calibrated so that
/// Table 1's speeds lay the target (with the example's 0.1 %/layer drift and
/// without): every segment ends within 0.1 mm of 29.90 mm.
#[test]
fn lmdc_simulate_builds_29_90_mm_on_every_segment() {
    for (tag, drift) in [("drift", "0.1 %"), ("none", "0 %"), ("down", "-0.1 %")] {
        let src = example().replace("drift = 0.1 %", &format!("drift = {drift}"));
        let rows = support::simulate_csv(tag, &src);
        let layers = support::by_layer(&rows, 10);
        assert_eq!(layers.len(), 130);
        // The first layer runs Table 1 and lays the target.
        for (j, row) in layers[0].iter().enumerate() {
            assert_eq!(row.speed, TABLE_1[j].3);
            assert!((row.height - 0.23).abs() < 1e-6);
        }
        for row in layers.last().unwrap() {
            assert!((row.target - 29.90).abs() < 1e-9);
            assert!(
                (row.total - 29.90).abs() < 0.1,
                "drift {drift}: segment {} ends at {} mm",
                row.segment,
                row.total
            );
            assert!((1.9..=20.0).contains(&row.speed));
        }
        // The CSV holds the library's numbers (the ones the program tests
        // feed the controllers), to its 6 decimals.
        let full = support::simulation(&src);
        for (l, layer) in layers.iter().enumerate() {
            for (j, row) in layer.iter().enumerate() {
                let f = full[l][j];
                for (a, b) in [
                    (row.speed, f.speed),
                    (row.height, f.height),
                    (row.total, f.total),
                ] {
                    assert!((a - b).abs() <= 5e-7 + 1e-12, "{row:?} vs {f:?}");
                }
            }
        }
    }
}

/// Read per (mm/s)/mm the same numbers are 1000 times weaker: the loop
/// never settles, and the build refuses it with both readings.
#[test]
fn the_gains_read_per_mm_s_are_refused() {
    let src = example()
        .replace("kp = -0.003 m/s/mm", "kp = -0.003 mm/s/mm")
        .replace("ki = -0.00035 m/s/mm", "ki = -0.00035 mm/s/mm");
    let c = lmdc::pipeline::compile(&src, &mut ());
    assert!(c.program.is_none());
    let text = lmdc::diag::render(&c.diagnostics, "ring.lmd", &src, false);
    assert!(text.contains("lmd::slow-loop"), "{text}");
    assert!(text.contains("never settles"), "{text}");
    assert!(text.contains("m/s/mm"), "{text}");
}

/// `run = schedule`: the loop run against the plant once, offline, and its
/// speeds written as a fixed schedule that every back end runs, the Fagor
/// dialect (which cannot run the loop) included.
#[test]
fn a_schedule_is_the_simulation_written_by_every_back_end() {
    let src = example()
        .replace("run = on_machine ", "run = schedule   ")
        .replace("dialect = linuxcnc", "dialect = fagor8070");
    let p = support::compile("schedule", &src);
    let ir = p.ir();
    let r = ir.ring.as_ref().unwrap();
    let RingRun::Schedule { speeds, control } = &r.run else {
        panic!("a schedule")
    };
    assert!(control.is_some());
    let sim = support::simulation(&src);
    assert_eq!(speeds.len(), 130);
    let per = r.flat_moves + r.transition_moves;
    for (l, layer) in ir.layers.iter().enumerate() {
        for j in 0..10 {
            let want = sim[l][j].speed;
            assert_eq!(speeds[l][j], want);
            let pt = layer.paths[0].points[j * per];
            assert!(
                (pt.speed as f64 - want).abs() < 1e-5 * want,
                "layer {l} segment {j}"
            );
            // The schedule's points keep the nominal layers.
            assert!((pt.pos[2] - l as f64 * 0.23).abs() < 1e-9);
        }
    }
    // The Fagor program: F (mm/min, 1 decimal) of each segment's first move.
    let files = support::files(&p, "mill3");
    let (name, nc) = files.iter().next().unwrap();
    assert!(name.ends_with(".nc"), "{name}");
    assert!(!nc.contains("M66"), "an open-loop program reads no sensor");
    let mut feed = 0.0;
    let mut deposits = Vec::new();
    let mut laser = false;
    for line in nc.lines() {
        match line.trim() {
            "M3" => laser = true,
            "M5" => laser = false,
            l if l.starts_with("G1 ") => {
                if let Some(f) = l.split_whitespace().find_map(|w| w.strip_prefix('F')) {
                    feed = f.parse::<f64>().unwrap() / 60.0;
                }
                if laser {
                    deposits.push(feed);
                }
            }
            _ => {}
        }
    }
    assert_eq!(deposits.len(), 130 * 10 * per);
    for (l, layer) in deposits.chunks(10 * per).enumerate() {
        for j in 0..10 {
            let got = layer[j * per];
            let want = sim[l][j].speed;
            assert!(
                (got - want).abs() <= 0.05 / 60.0 + 1e-5,
                "layer {l} segment {j}: {got} vs {want}"
            );
        }
    }
    // The robot's too: a plain program, one module per 2000 lines.
    let krl = support::files(&p, "kr60");
    assert!(krl.keys().any(|k| k.ends_with("_m002.src")));
    assert!(!krl.values().any(|t| t.contains("$ANIN")));
}

/// A closed loop on a control lmdc cannot write it for is refused, with the
/// way out; so is a machine without a sensor.
#[test]
fn a_loop_needs_linuxcnc_or_a_robot_and_a_sensor() {
    let fagor = example().replace("dialect = linuxcnc", "dialect = fagor8070");
    let c = lmdc::pipeline::compile(&fagor, &mut ());
    assert!(c.program.is_none());
    let text = lmdc::diag::render(&c.diagnostics, "ring.lmd", &fagor, false);
    assert!(text.contains("lmd::loop-dialect"), "{text}");
    assert!(
        text.contains("not supported on the") && text.contains("fagor8070 dialect"),
        "{text}"
    );
    assert!(text.contains("run = schedule"), "{text}");

    // The robot's sensor lines (the first of each), whatever their comments'
    // alignment.
    let mut dropped = Vec::new();
    let blind: String = example()
        .split_inclusive('\n')
        .filter(|l| {
            let key = ["  height_input", "  height_full_scale", "  height_delay"]
                .into_iter()
                .find(|k| l.starts_with(k));
            match key {
                Some(k) if !dropped.contains(&k) => {
                    dropped.push(k);
                    false
                }
                _ => true,
            }
        })
        .collect();
    assert_eq!(dropped.len(), 3);
    assert_ne!(blind, example());
    let c = lmdc::pipeline::compile(&blind, &mut ());
    assert!(c.program.is_none());
    let text = lmdc::diag::render(&c.diagnostics, "ring.lmd", &blind, false);
    assert!(text.contains("lmd::height-sensor"), "{text}");
    assert!(text.contains("`kr60` declares no height"), "{text}");
}

/// A ring plan is IR version 3, so an older reader refuses it rather than
/// running the nominal speeds open loop; machines keep their sensors.
#[test]
fn a_ring_plan_is_ir_version_3() {
    let p = support::compile(support::EXAMPLE, &example());
    let ir = p.ir();
    assert_eq!(ir.version, 3);
    assert!(ir.continuous);
    let json = serde_json::to_string(ir).unwrap();
    let back: lmdc::ir::Program = serde_json::from_str(&json).unwrap();
    assert_eq!(back.ring, ir.ring);
    for m in &ir.machines {
        let s = match m {
            Machine::Robot(r) => r.height_sensor,
            Machine::Cnc(c) => c.height_sensor,
        };
        assert_eq!(s.map(|s| (s.input, s.full_scale)), Some((3, 2.0)));
    }
}

#[test]
fn a_ring_its_beads_do_not_fit_is_refused_and_short_segments_are_named() {
    let diags = |radius: &str| {
        let src = example().replacen("radius = 40 mm", &format!("radius = {radius}"), 1);
        lmdc::pipeline::compile(&src, &mut ())
            .diagnostics
            .iter()
            .map(|d| (d.code.as_str(), d.message.clone()))
            .collect::<Vec<_>>()
    };
    // Table 1's widest bead is 6.25 mm: at a 3 mm radius its inner face
    // would cross the centre.
    let d = diags("3 mm");
    assert!(
        d.contains(&(
            "lmd::ring-too-small",
            "a ring of radius 3 mm cannot carry a bead 6.25 mm wide: its inner face would cross the centre".into()
        )),
        "{d:#?}"
    );
    // At 8 mm the ten segments are 2π·8/10 = 5.027 mm long: four of Table 1's
    // beads (6.25 and 5.55 mm, twice each) are wider.
    let d = diags("8 mm");
    assert!(
        d.contains(&(
            "lmd::short-track",
            "4 segments of the ring, 5.027 mm long, are shorter than their beads are wide (up to 6.25 mm)".into()
        )),
        "{d:#?}"
    );
    // The example's 40 mm (25.1 mm segments) has neither.
    assert!(!diags("40 mm")
        .iter()
        .any(|(c, _)| *c == "lmd::ring-too-small" || *c == "lmd::short-track"));
}
