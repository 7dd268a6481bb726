//! The thermal budget over random plans (docs/thermal.md): every plan lmdc
//! accepts with a `max_interpass` starts every layer within it; the wait
//! `cooling = dwell` chooses is the least (10 % less and the layer starts
//! above the limit); `cooling = power` lowers powers within the laser's
//! range and the plan still passes every rule, the deposit's among them;
//! `cooling = order` keeps every island of every layer within the limit
//! with no wait, its reordered layers passing every rule too; and the
//! levers together (`cooling = [order, power, dwell]`) keep the limit,
//! the free ones pulled first and the wait still the least.

use lmdc::lower::heat;
use lmdc::pipeline::compile;
use lmdc::thermal::predict;
use proptest::prelude::*;

/// The one-line tests' plate (flat raster layers, a CNC and a robot) with
/// `layers` layers of a `width` mm wide block and a thermal block.
fn plate(width: f64, layers: usize, process: &str, thermal: &str) -> String {
    std::fs::read_to_string("tests/codes/plate.lmd")
        .unwrap()
        .replace("width = 20 mm", &format!("width = {width} mm"))
        .replace("layers = 2\n", &format!("layers = {layers}\n"))
        .replace(
            "  defocus = -3 mm\n",
            &format!("  defocus = -3 mm\n  {process}\n  thermal {{ {thermal} }}\n"),
        )
}

/// The IR of `src`, or `None` when lmdc refuses it for its interpass
/// limit alone (any other error fails the test).
fn accepted(src: &str) -> Option<lmdc::ir::Program> {
    kept(compile(src, &mut ()), src)
}

/// The IR of the compiled `src`, or `None` when lmdc refused it for its
/// interpass limit alone (any other error fails the test).
fn kept(c: lmdc::pipeline::Compiled, src: &str) -> Option<lmdc::ir::Program> {
    match c.program {
        Some(v) => Some(v.ir().clone()),
        None => {
            let codes: Vec<_> = c.diagnostics.iter().map(|d| d.code.as_str()).collect();
            assert!(
                codes.iter().all(|c| *c == "lmd::interpass"),
                "{codes:?}\n{src}"
            );
            None
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(8))]

    #[test]
    fn waits_keep_the_limit_and_are_the_least(
        width in 12.0f64..30.0,
        layers in 3usize..7,
        limit in 120.0f64..400.0,
        thick in 5.0f64..20.0,
    ) {
        let src = plate(
            width.round(),
            layers,
            "",
            &format!("material = ss316l  plate = [80 mm, 80 mm, {thick:.1} mm]  max_interpass = {limit:.1} degC"),
        );
        let Some(p) = accepted(&src) else { return Ok(()) };
        let t = p.thermal.as_ref().unwrap();
        let limit = t.max_interpass.unwrap();
        for (i, l) in t.layers.iter().enumerate() {
            prop_assert!(l.interpass <= limit + 1e-9, "layer {i}: {l:?}");
        }
        // A wait the budget added is one an older reader would not wait.
        let added = t.layers.iter().any(|l| l.added > 0.0);
        let want = if added { lmdc::ir::VERSION_BUDGET } else { lmdc::ir::VERSION };
        prop_assert_eq!(p.version, want);
        let (material, cell) = heat::cell(t);
        let loads = heat::loads(&p);
        let waits: Vec<f64> = t.layers.iter().map(|l| l.wait).collect();
        for (i, l) in t.layers.iter().enumerate().filter(|(_, l)| l.added > 0.0) {
            let shorter = |j: usize| if j == i { cut(waits[j]) } else { waits[j] };
            let q = predict(material, cell, &loads[..=i], shorter, None).unwrap();
            prop_assert!(q[i].interpass > limit, "layer {i} with 90 % of {}: {}", l.wait, q[i].interpass);
        }
    }

    #[test]
    fn lower_powers_keep_the_limit_and_the_deposit(
        layers in 3usize..7,
        limit in 250.0f64..500.0,
        dwell in 10.0f64..40.0,
    ) {
        let src = plate(
            20.0,
            layers,
            &format!("power_range = 600 W .. 1500 W\n  dwell = {dwell:.0} s"),
            &format!("material = in718  max_interpass = {limit:.1} degC  cooling = power"),
        );
        // Accepted means verified: the deposit rule and the laser's range
        // hold at the powers chosen.
        let Some(p) = accepted(&src) else { return Ok(()) };
        let t = p.thermal.as_ref().unwrap();
        for (i, l) in t.layers.iter().enumerate() {
            prop_assert!(l.interpass <= t.max_interpass.unwrap() + 1e-9, "layer {i}: {l:?}");
            prop_assert!(l.added == 0.0 && (0.4 - 1e-6..=1.0).contains(&l.power), "{l:?}");
        }
        let powers = p.layers.iter().flat_map(|l| &l.paths).flat_map(|p| &p.points).filter(|p| p.laser_on);
        for q in powers {
            prop_assert!((600.0 - 1e-3..=1500.0).contains(&(q.power as f64)));
        }
    }
}

/// `lmdc fit --plan`: temperatures the plan's own prediction gives come
/// back as the alloy's absorptivity and the default heat transfer
/// coefficient, with residuals of a fraction of a kelvin.
#[test]
fn fit_finds_the_values_that_made_the_temperatures() {
    // The wall without its limit and with a dwell: layers that warm up
    // from the plate's temperature, which both numbers shape.
    let src = std::fs::read_to_string("examples/thin_wall.lmd")
        .unwrap()
        .replace("    max_interpass = 250 degC\n", "")
        .replace("  defocus = -1 mm\n", "  defocus = -1 mm\n  dwell = 10 s\n");
    let dir = tempfile::tempdir().unwrap();
    let plan = dir.path().join("wall.lmd");
    std::fs::write(&plan, &src).unwrap();
    let c = compile(&src, &mut ());
    let p = c.program.expect("the example compiles");
    let t = p.ir().thermal.as_ref().unwrap();
    let r = fit_every(dir.path(), t, 4, &plan);
    let eta = r["absorptivity"].as_f64().unwrap();
    let h = r["heat_transfer"].as_f64().unwrap();
    assert!(t.max_interpass.is_none() && t.layers[39].interpass > 200.0);
    assert!((eta - t.absorptivity).abs() < 0.005, "{r}");
    assert!((h - t.heat_transfer).abs() < 1.0, "{r}");
    assert!(r["rms"].as_f64().unwrap() < 0.05, "{r}");
}

/// The triangles of a box from `lo` to `hi` (mm), facing out.
fn cuboid(lo: [f64; 3], hi: [f64; 3]) -> Vec<lmdc::geometry::mesh::stl::Triangle> {
    let p = |i: usize| {
        let c = |k: usize| if i >> k & 1 == 1 { hi[k] } else { lo[k] } as f32;
        [c(0), c(1), c(2)]
    };
    // Corners by bits (x, y, z); each face counter-clockwise from outside.
    let faces = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [1, 3, 7, 5],
        [3, 2, 6, 7],
        [2, 0, 4, 6],
    ];
    faces
        .iter()
        .flat_map(|[a, b, c, d]| [[p(*a), p(*b), p(*c)], [p(*a), p(*c), p(*d)]])
        .collect()
}

/// examples/two_pillars.lmd with its STL, `cooling` for its cooling and
/// `limit` °C for its limit: the plan, or `None` where lmdc refuses it
/// for its limit alone.
fn pillars(src: &str, tris: &[lmdc::geometry::mesh::stl::Triangle]) -> Option<lmdc::ir::Program> {
    let stl = lmdc::geometry::mesh::stl::to_binary(tris);
    kept(
        crate::support::data::compile_with_files(src, [("mesh/two_pillars.stl", stl)]),
        src,
    )
}

/// `src` and its pillars' STL written where `lmdc` reads them (the STL as
/// `mesh/two_pillars.stl` beside the plan): the folder, kept while it is
/// held, and the plan's path.
fn pillars_on_disk(
    src: &str,
    tris: &[lmdc::geometry::mesh::stl::Triangle],
) -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("mesh")).unwrap();
    std::fs::write(
        dir.path().join("mesh/two_pillars.stl"),
        lmdc::geometry::mesh::stl::to_binary(tris),
    )
    .unwrap();
    let plan = dir.path().join("pillars.lmd");
    std::fs::write(&plan, src).unwrap();
    (dir, plan)
}

/// The hottest start of an island of the plan, °C.
fn hottest_island(p: &lmdc::ir::Program) -> f64 {
    let t = p.thermal.as_ref().unwrap();
    t.layers
        .iter()
        .flat_map(|l| l.islands.iter().map(|i| i.interpass))
        .fold(f64::MIN, f64::max)
}

/// The two pillars of examples/two_pillars.lmd: `cooling = order` keeps
/// 320 °C with no wait (the pillar that has cooled longest first, the same
/// pillar first every layer), where `cooling = dwell` in the slicer's
/// order (turn about) waits 19.6 s in all; the IR says so (`dwell_alone`),
/// every island of every layer within the limit, and the plan's version
/// is the islands' (9).
#[test]
fn the_pillars_keep_their_limit_by_their_order() {
    let src = std::fs::read_to_string("examples/two_pillars.lmd").unwrap();
    let tris = two_pillars();
    let order = pillars(&src, &tris).expect("order keeps 320 °C");
    let dwell = pillars(&src.replace("cooling = order", "cooling = dwell"), &tris).unwrap();
    let (to, td) = (
        order.thermal.as_ref().unwrap(),
        dwell.thermal.as_ref().unwrap(),
    );
    let added = |t: &lmdc::ir::Thermal| t.layers.iter().map(|l| l.added).sum::<f64>();
    assert_eq!(added(to), 0.0);
    assert!((added(td) - 19.6).abs() < 0.05, "dwell adds {}", added(td));
    assert!((to.dwell_alone.unwrap() - added(td)).abs() < 1e-9);
    assert!(hottest_island(&order) <= 320.0 && hottest_island(&order) > 280.0);
    let h = hottest_island(&dwell);
    assert!(h <= 320.0 + 1e-9 && h > 319.0, "{h}");
    assert_eq!(order.version, lmdc::ir::VERSION_ORDER);
    // The same pillar first every layer (x below 20 mm: the first).
    let first: Vec<bool> = to
        .layers
        .iter()
        .map(|l| l.islands[0].at[0] < 20.0)
        .collect();
    assert!(first.iter().all(|f| *f == first[0]), "{first:?}");
    // The slicer's order turns about: layer 2 starts on the other pillar.
    let firsts: Vec<bool> = td
        .layers
        .iter()
        .map(|l| l.islands[0].at[0] < 20.0)
        .collect();
    assert_ne!(firsts[0], firsts[1]);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    /// Random plans of two to three pillars (sizes, gaps, heights — some
    /// ending below the top, whose columns then cool as the others rise —,
    /// power, limit): every plan lmdc accepts with `cooling = order`
    /// starts every island of every layer within the limit, adds no wait,
    /// never has more islands than the layer below, and passes every rule
    /// of the verifier with its layers reordered (accepted means
    /// verified: the deposit, stacking and collision rules among them);
    /// the order never starts an island hotter than the slicer's own order
    /// would.
    #[test]
    fn the_order_keeps_every_island_within_the_limit(
        sides in proptest::collection::vec(8.0f64..16.0, 2..4),
        heights in proptest::collection::vec(2.0f64..8.0, 3),
        gap in 10.0f64..30.0,
        power in 400.0f64..600.0,
        limit in 120.0f64..330.0,
    ) {
        let mut x = 0.0;
        let mut tris = Vec::new();
        // The first pillar 6 mm tall (the ten layers' 5.4 mm under its
        // top), the others from 2 mm to 8 mm: some end below the top.
        for (s, h) in sides.iter().zip(std::iter::once(&6.0).chain(&heights)) {
            tris.extend(cuboid([x, 0.0, 0.0], [x + s.round(), s.round(), h.round()]));
            x += s.round() + gap.round();
        }
        let src = std::fs::read_to_string("examples/two_pillars.lmd")
            .unwrap()
            .replace("  power = 400 W", &format!("  power = {power:.0} W"))
            .replace("max_interpass = 320 degC", &format!("max_interpass = {limit:.0} degC"))
            .replace("layers = 18", "layers = 10");
        let Some(p) = pillars(&src, &tris) else { return Ok(()) };
        if std::env::var("LMDC_SHOW_ACCEPTED").is_ok() {
            eprintln!("accepted: {} pillars, {power:.0} W, {limit:.0} °C", sides.len());
        }
        let t = p.thermal.as_ref().unwrap();
        // The pillars standing at each layer (a layer of one: no islands).
        prop_assert!(t.layers[0].islands.len() == sides.len());
        for (i, l) in t.layers.iter().enumerate() {
            let below = if i == 0 { sides.len() } else { t.layers[i - 1].islands.len() };
            prop_assert!(l.islands.len() <= below, "layer {}", i);
            prop_assert!(l.interpass <= limit.round() + 1e-9, "layer {}", i);
            prop_assert!(l.added == 0.0);
            for isl in &l.islands {
                prop_assert!(isl.interpass <= limit.round() + 1e-9, "layer {}: {:?}", i, isl);
            }
        }
        let free = pillars(&src.replace("    max_interpass", "    // max_interpass"), &tris).unwrap();
        prop_assert!(hottest_island(&p) <= hottest_island(&free) + 1e-9);
    }
}

/// The time the budget added to the waits of `t`, s.
fn added(t: &lmdc::ir::Thermal) -> f64 {
    t.layers.iter().map(|l| l.added).sum()
}

/// A wait the budget chose, cut to what must break the limit if it is the
/// least: 90 % of it; a wait under a millisecond to none instead (it is
/// found to a thousandth of the model's first time step, 50 µs, so 90 %
/// of it may still keep the limit, and no controller times a dwell that
/// finely): for those only that the wait was needed is checked, not that
/// it was the least.
fn cut(wait: f64) -> f64 {
    if wait < 1e-3 {
        0.0
    } else {
        0.9 * wait
    }
}

/// Layer `i`'s hottest island start when the plan `p` is run again with
/// the waits it planned, the one before layer `i` cut ([`cut`]): the wait
/// the budget chose is the least that keeps the limit where this is above
/// it.
fn hottest_with_a_shorter_wait(p: &lmdc::ir::Program, i: usize) -> f64 {
    let t = p.thermal.as_ref().unwrap();
    let (material, cell) = heat::cell(t);
    let (loads, orders, columns) = heat::island_loads(p);
    let waits: Vec<f64> = t.layers.iter().map(|l| l.wait).collect();
    let shorter = |j: usize| if j == i { cut(waits[j]) } else { waits[j] };
    let (loads, orders) = (&loads[..=i], &orders[..=i]);
    let q = lmdc::thermal::predict_tree(material, cell, &columns, loads, orders, shorter, None)
        .unwrap();
    q[i].islands
        .iter()
        .map(|s| s.interpass)
        .fold(q[i].layer.interpass, f64::max)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(8))]

    /// `cooling = [power, dwell]` (and with `order`, which a wall of one
    /// piece has none of) on random plates: every plan lmdc accepts
    /// starts every layer within the limit, at powers within the laser's
    /// range (accepted means verified: the deposit rule holds at them);
    /// the power is pulled before the wait (a layer waits longer than
    /// declared only after one laid at the least power); and every wait
    /// the budget added is the least: 10 % less, at the powers chosen,
    /// and the layer starts above the limit. The plan is version 10.
    #[test]
    fn power_then_the_least_wait_keep_the_limit(
        layers in 3usize..7,
        limit in 120.0f64..300.0,
        dwell in 0.0f64..10.0,
        all in any::<bool>(),
    ) {
        let cooling = if all { "[order, power, dwell]" } else { "[power, dwell]" };
        let src = plate(
            20.0,
            layers,
            &format!("power_range = 600 W .. 1500 W\n  dwell = {dwell:.0} s"),
            &format!("material = in718  max_interpass = {limit:.1} degC  cooling = {cooling}"),
        );
        let Some(p) = accepted(&src) else { return Ok(()) };
        if std::env::var("LMDC_SHOW_ACCEPTED").is_ok() {
            let t = p.thermal.as_ref().unwrap();
            eprintln!("accepted: {cooling} {limit:.0} °C, {:.1} s added, {} layers at less power", added(t), t.layers.iter().filter(|l| l.power < 1.0).count());
        }
        prop_assert_eq!(p.version, lmdc::ir::VERSION_LEVERS);
        let t = p.thermal.as_ref().unwrap();
        let limit = t.max_interpass.unwrap();
        for (i, l) in t.layers.iter().enumerate() {
            prop_assert!(l.interpass <= limit + 1e-9, "layer {i}: {l:?}");
            prop_assert!((0.4 - 1e-6..=1.0).contains(&l.power), "{l:?}");
            if l.added > 0.0 {
                prop_assert!(t.layers[i - 1].power < 0.4 + 1e-6, "layer {i} waits after full power: {:?}", t.layers.iter().map(|l| (l.power, l.added, l.wait)).collect::<Vec<_>>());
                let h = hottest_with_a_shorter_wait(&p, i);
                prop_assert!(h > limit, "layer {i} with 90 % of {}: {h}", l.wait);
            }
        }
        let powers = p.layers.iter().flat_map(|l| &l.paths).flat_map(|p| &p.points).filter(|p| p.laser_on);
        for q in powers {
            prop_assert!((600.0 - 1e-3..=1500.0).contains(&(q.power as f64)));
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    /// Random plans of two to three pillars with `cooling = [order, dwell]`
    /// or `[order, power, dwell]`: every plan lmdc accepts starts every
    /// island of every layer within the limit, passes every rule of the
    /// verifier with its layers reordered and its powers lowered; every
    /// wait the budget added is the least for the order chosen (10 % less
    /// and an island of the layer starts above the limit).
    #[test]
    fn the_levers_together_keep_every_island_with_the_least_wait(
        sides in proptest::collection::vec(8.0f64..16.0, 2..4),
        heights in proptest::collection::vec(2.0f64..8.0, 3),
        gap in 10.0f64..30.0,
        power in 400.0f64..600.0,
        limit in 150.0f64..330.0,
        all in any::<bool>(),
    ) {
        let mut x = 0.0;
        let mut tris = Vec::new();
        // The first pillar 6 mm tall (the ten layers' 5.4 mm under its
        // top), the others from 2 mm to 8 mm: some end below the top.
        for (s, h) in sides.iter().zip(std::iter::once(&6.0).chain(&heights)) {
            tris.extend(cuboid([x, 0.0, 0.0], [x + s.round(), s.round(), h.round()]));
            x += s.round() + gap.round();
        }
        let cooling = if all { "[order, power, dwell]" } else { "[order, dwell]" };
        let src = std::fs::read_to_string("examples/two_pillars.lmd")
            .unwrap()
            .replace("  power = 400 W", &format!("  power = {power:.0} W"))
            .replace("max_interpass = 320 degC", &format!("max_interpass = {limit:.0} degC"))
            .replace("cooling = order", &format!("cooling = {cooling}"))
            .replace("layers = 18", "layers = 10");
        let Some(p) = pillars(&src, &tris) else { return Ok(()) };
        if std::env::var("LMDC_SHOW_ACCEPTED").is_ok() {
            let t = p.thermal.as_ref().unwrap();
            eprintln!("accepted: {} pillars {cooling} {limit:.0} °C, {:.1} s added, {} reordered", sides.len(), added(t), t.layers.iter().filter(|l| l.reordered).count());
        }
        prop_assert_eq!(p.version, lmdc::ir::VERSION_LEVERS);
        let t = p.thermal.as_ref().unwrap();
        prop_assert!(t.layers[0].islands.len() == sides.len());
        for (i, l) in t.layers.iter().enumerate() {
            let below = if i == 0 { sides.len() } else { t.layers[i - 1].islands.len() };
            prop_assert!(l.islands.len() <= below, "layer {}", i);
            for isl in &l.islands {
                prop_assert!(isl.interpass <= limit.round() + 1e-9, "layer {}: {:?}", i, isl);
            }
            if l.added > 0.0 {
                let h = hottest_with_a_shorter_wait(&p, i);
                prop_assert!(h > limit.round(), "layer {} with 90 % of {}: {}", i, l.wait, h);
            }
        }
    }
}

/// The two pillars of examples/two_pillars.lmd under 250 °C, a limit
/// their order alone cannot keep (case errors/thermal/order_too_hot):
/// `cooling = [order, dwell]` keeps it, its islands coolest first and
/// only the waits the order cannot spare, less time than `cooling =
/// dwell` adds in the slicer's order, which the IR says (`dwell_alone`)
/// and the report weighs.
#[test]
fn order_and_dwell_wait_less_than_dwell_alone() {
    let src = std::fs::read_to_string("examples/two_pillars.lmd")
        .unwrap()
        .replace("max_interpass = 320 degC", "max_interpass = 250 degC");
    let tris = two_pillars();
    assert!(pillars(&src, &tris).is_none(), "order alone keeps 250 °C");
    let both = pillars(
        &src.replace("cooling = order", "cooling = [order, dwell]"),
        &tris,
    )
    .expect("order and dwell keep 250 °C");
    let dwell = pillars(&src.replace("cooling = order", "cooling = dwell"), &tris).unwrap();
    let (tb, td) = (
        both.thermal.as_ref().unwrap(),
        dwell.thermal.as_ref().unwrap(),
    );
    eprintln!(
        "[order, dwell] adds {:.2} s, dwell alone {:.2} s",
        added(tb),
        added(td)
    );
    assert!(
        added(tb) > 0.0 && added(tb) < 0.5 * added(td),
        "{} against {}",
        added(tb),
        added(td)
    );
    assert!((tb.dwell_alone.unwrap() - added(td)).abs() < 1e-9);
    assert!(hottest_island(&both) <= 250.0 + 1e-9);
    assert!(tb.layers.iter().any(|l| l.reordered));
    assert!(!td.layers.iter().any(|l| l.reordered));
    assert_eq!(both.version, lmdc::ir::VERSION_LEVERS);
    // Each wait it added is the least for the order chosen.
    for (i, _) in tb.layers.iter().enumerate().filter(|(_, l)| l.added > 0.0) {
        assert!(
            hottest_with_a_shorter_wait(&both, i) > 250.0,
            "layer {}",
            i + 1
        );
    }
    // The report says which levers it pulled and what waits alone cost.
    let (_dir, plan) = pillars_on_disk(
        &src.replace("cooling = order", "cooling = [order, dwell]"),
        &tris,
    );
    let report = |json: bool| {
        let mut c = std::process::Command::new(env!("CARGO_BIN_EXE_lmdc"));
        c.arg("report").arg(&plan).arg("--machine").arg("mill3");
        if json {
            c.arg("--json");
        }
        let o = c.env("NO_COLOR", "1").output().unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8(o.stdout).unwrap()
    };
    let text = report(false);
    assert!(
        text.contains("kept by the order of the islands in ")
            && text.contains(" longer, where waiting alone would add "),
        "{text}"
    );
    let r: serde_json::Value = serde_json::from_str(report(true).trim()).unwrap();
    let h = &r["thermal"];
    assert_eq!(h["cooling"], serde_json::json!(["order", "dwell"]));
    let reordered = tb.layers.iter().filter(|l| l.reordered).count();
    assert_eq!(h["layers_reordered"].as_u64(), Some(reordered as u64));
    let saved = h["saved_s"].as_f64().unwrap();
    assert!((saved - (added(td) - added(tb))).abs() < 1e-6, "{h}");
}

/// `lmdc fit --plan` over a plan of islands runs the model with a column
/// per island, in the order the plan lays them: the temperatures the two
/// pillars' own prediction gives (where each layer starts, on its first
/// island) come back as the alloy's absorptivity and the default heat
/// transfer coefficient, with residuals of a fraction of a kelvin.
#[test]
fn fit_over_islands_finds_the_values_that_made_the_temperatures() {
    let src = std::fs::read_to_string("examples/two_pillars.lmd").unwrap();
    let tris = two_pillars();
    let p = pillars(&src, &tris).expect("order keeps 320 °C");
    let t = p.thermal.as_ref().unwrap();
    assert!(t.layers.iter().all(|l| l.islands.len() == 2));
    let (dir, plan) = pillars_on_disk(&src, &tris);
    let r = fit_every(dir.path(), t, 2, &plan);
    let eta = r["absorptivity"].as_f64().unwrap();
    let h = r["heat_transfer"].as_f64().unwrap();
    assert!((eta - t.absorptivity).abs() < 0.005, "{r}");
    assert!((h - t.heat_transfer).abs() < 1.0, "{r}");
    assert!(r["rms"].as_f64().unwrap() < 0.05, "{r}");
}

/// `lmdc fit` over a sheet of `t`'s interpass temperatures, every
/// `step`-th layer from the second, written into `dir`, with `--plan PLAN`.
fn fit_every(
    dir: &std::path::Path,
    t: &lmdc::ir::Thermal,
    step: usize,
    plan: &std::path::Path,
) -> serde_json::Value {
    let mut sheet = String::from("layer, interpass (degC)\n");
    for (i, l) in t.layers.iter().enumerate().skip(1).step_by(step) {
        sheet.push_str(&format!("{}, {:.3}\n", i + 1, l.interpass));
    }
    let file = dir.join("temperatures.csv");
    std::fs::write(&file, sheet).unwrap();
    fit_plan(&file, plan)
}

/// `lmdc fit SHEET --plan PLAN --json`, which must succeed: its object.
fn fit_plan(sheet: &std::path::Path, plan: &std::path::Path) -> serde_json::Value {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_lmdc"))
        .arg("fit")
        .arg(sheet)
        .arg("--plan")
        .arg(plan)
        .arg("--json")
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    serde_json::from_slice(&o.stdout).unwrap()
}

/// The mesh of examples/two_pillars.lmd: two 12 mm pillars 10 mm tall,
/// 28 mm apart.
fn two_pillars() -> Vec<lmdc::geometry::mesh::stl::Triangle> {
    [
        cuboid([0.0, 0.0, 0.0], [12.0, 12.0, 10.0]),
        cuboid([40.0, 0.0, 0.0], [52.0, 12.0, 10.0]),
    ]
    .concat()
}

/// Two pillars of different heights (10 mm and 5 mm): a column each while
/// both stand (each layer of the two lists both islands: the part is not
/// taken as one column), then one piece. Each pillar's interpass rises
/// to the shorter's last layer, and the taller's keeps rising after the
/// shorter ends.
#[test]
fn a_pillar_that_ends_keeps_a_column_each_while_both_stand() {
    let src = std::fs::read_to_string("examples/two_pillars.lmd")
        .unwrap()
        .replace("    max_interpass = 320 degC\n", "")
        .replace("    cooling = order\n", "");
    let tris = [
        cuboid([0.0, 0.0, 0.0], [12.0, 12.0, 10.0]),
        cuboid([40.0, 0.0, 0.0], [52.0, 12.0, 5.0]),
    ]
    .concat();
    let p = pillars(&src, &tris).expect("no limit");
    let t = p.thermal.as_ref().unwrap();
    let two: Vec<usize> = (0..t.layers.len())
        .filter(|&i| t.layers[i].islands.len() == 2)
        .collect();
    // 5 mm of 0.54 mm layers: nine under the shorter's top.
    assert_eq!(two, (0..9).collect::<Vec<_>>(), "{:?}", t.layers);
    assert!(t.layers[9..].iter().all(|l| l.islands.is_empty()));
    // Each pillar's interpass layer by layer while both stand: laid turn
    // about (first in one layer, second in the next), each rises from
    // every layer to the next but one, the shorter to its last.
    let of = |right: bool| -> Vec<f64> {
        t.layers[..9]
            .iter()
            .filter_map(|l| l.islands.iter().find(|i| (i.at[0] > 20.0) == right))
            .map(|i| i.interpass)
            .collect()
    };
    let (tall, short) = (of(false), of(true));
    let rises = |v: &[f64]| v.iter().zip(&v[2..]).all(|(a, b)| b > a);
    assert!(rises(&short) && short.len() == 9, "{short:?}");
    assert!(rises(&tall) && tall.len() == 9, "{tall:?}");
    let after: Vec<f64> = t.layers[9..].iter().map(|l| l.interpass).collect();
    assert!(after.windows(2).all(|w| w[1] > w[0]), "{after:?}");
}

/// `lmdc fit --plan` over a sheet with an island column (`layer, island,
/// interpass`, islands from 1 in the order the report lists them): the
/// two pillars' own prediction, every island of every other layer, comes
/// back as the absorptivity and heat transfer coefficient that made it,
/// to a thousandth; the report lists each row's island.
#[test]
fn fit_per_island_finds_the_values_that_made_the_temperatures() {
    let src = std::fs::read_to_string("examples/two_pillars.lmd").unwrap();
    let tris = two_pillars();
    let p = pillars(&src, &tris).expect("order keeps 320 °C");
    let t = p.thermal.as_ref().unwrap();
    let (dir, plan) = pillars_on_disk(&src, &tris);
    let mut sheet = String::from("layer, island, interpass (degC)\n");
    for (i, l) in t.layers.iter().enumerate().skip(1).step_by(2) {
        for (g, isl) in l.islands.iter().enumerate() {
            sheet.push_str(&format!("{}, {}, {:.4}\n", i + 1, g + 1, isl.interpass));
        }
    }
    let file = dir.path().join("temperatures.csv");
    std::fs::write(&file, sheet).unwrap();
    let r = fit_plan(&file, &plan);
    let eta = r["absorptivity"].as_f64().unwrap();
    let h = r["heat_transfer"].as_f64().unwrap();
    assert!((eta - t.absorptivity).abs() < 1e-3, "{r}");
    assert!((h - t.heat_transfer).abs() < 1e-3 * t.heat_transfer, "{r}");
    assert!(r["rms"].as_f64().unwrap() < 0.01, "{r}");
    let islands = r["islands"].as_array().unwrap();
    assert_eq!(islands.len(), r["rows"].as_array().unwrap().len());
    assert_eq!(islands[0].as_u64(), Some(1));
    assert_eq!(islands[1].as_u64(), Some(2));
}

/// A field of 17 × 17 pins (3 mm square, 8 mm apart): more islands a
/// layer than lmdc tells apart (256), so the part is taken as one column
/// (each layer one temperature, no island listed) and the plan is made
/// quickly; 4 × 4 of the same pins are told apart, a column each.
#[test]
fn a_field_of_pins_past_the_island_cap_is_one_column() {
    let src = std::fs::read_to_string("examples/two_pillars.lmd")
        .unwrap()
        .replace("    max_interpass = 320 degC\n", "")
        .replace("    cooling = order\n", "")
        .replace("layers = 18", "layers = 2");
    let field = |n: usize| -> Vec<lmdc::geometry::mesh::stl::Triangle> {
        (0..n * n)
            .flat_map(|k| {
                let (x, y) = ((k % n) as f64 * 8.0, (k / n) as f64 * 8.0);
                cuboid([x, y, 0.0], [x + 3.0, y + 3.0, 1.2])
            })
            .collect()
    };
    let few = pillars(&src, &field(4)).expect("no limit");
    let t = few.thermal.as_ref().unwrap();
    assert!(
        t.layers.iter().all(|l| l.islands.len() == 16),
        "{:?}",
        t.layers
    );
    let many = pillars(&src, &field(17)).expect("no limit");
    let t = many.thermal.as_ref().unwrap();
    assert_eq!(t.layers.len(), 2);
    assert!(
        t.layers.iter().all(|l| l.islands.is_empty()),
        "{:?}",
        t.layers[0].islands.len()
    );
}

/// The triangles of a prism from `y0` to `y1` (mm) over the polygon
/// `outline` in the xz plane (counter-clockwise, x right, z up), its
/// faces `fan`, triangles of the outline's corners (counter-clockwise),
/// facing out.
fn prism(
    outline: &[[f64; 2]],
    fan: &[[usize; 3]],
    y: [f64; 2],
) -> Vec<lmdc::geometry::mesh::stl::Triangle> {
    let p = |i: usize, y: f64| {
        let [x, z] = outline[i % outline.len()];
        [x as f32, y as f32, z as f32]
    };
    let n = outline.len();
    let mut tris: Vec<_> = fan
        .iter()
        .flat_map(|&[a, b, c]| {
            [
                [p(a, y[0]), p(b, y[0]), p(c, y[0])],
                [p(a, y[1]), p(c, y[1]), p(b, y[1])],
            ]
        })
        .collect();
    for i in 0..n {
        let (a, b) = (i, i + 1);
        tris.push([p(a, y[0]), p(b, y[1]), p(b, y[0])]);
        tris.push([p(a, y[0]), p(a, y[1]), p(b, y[1])]);
    }
    tris
}

/// Two 12 mm pillars 10 mm apart whose inner faces lean in from 4 mm up
/// (40° from the vertical) until they meet 10 mm up, then one block to
/// 14 mm: an arch, two islands a layer that merge into one part way up.
fn arch() -> Vec<lmdc::geometry::mesh::stl::Triangle> {
    arch_of(10.0, 6.0)
}

/// An arch of two 12 mm pillars `gap` mm apart whose inner faces lean in
/// from 4 mm up until they meet `rise` mm higher, then one block to 4 mm
/// above that.
fn arch_of(gap: f64, rise: f64) -> Vec<lmdc::geometry::mesh::stl::Triangle> {
    let (right, top) = (12.0 + gap, 8.0 + rise);
    let outline = [
        [0.0, 0.0],
        [12.0, 0.0],
        [12.0, 4.0],
        [12.0 + 0.5 * gap, 4.0 + rise],
        [right, 4.0],
        [right, 0.0],
        [right + 12.0, 0.0],
        [right + 12.0, top],
        [0.0, top],
    ];
    let fan = [
        [0, 1, 2],
        [0, 2, 8],
        [2, 3, 8],
        [3, 7, 8],
        [3, 4, 7],
        [4, 6, 7],
        [4, 5, 6],
    ];
    prism(&outline, &fan, [0.0, 12.0])
}

/// The plan of an arch's first `layers` layers: examples/two_pillars.lmd
/// with no limit.
fn arch_plan(layers: usize) -> String {
    std::fs::read_to_string("examples/two_pillars.lmd")
        .unwrap()
        .replace("    max_interpass = 320 degC\n", "")
        .replace("    cooling = order\n", "")
        .replace("layers = 18", &format!("layers = {layers}"))
}

/// Of a plan whose two islands a layer merge into one at layer `m`
/// (returned), the bridge's first interpass temperature and the two
/// pillars' tops at that moment, each found by laying the bridge's first
/// layer as two halves, one on each pillar, first the one then the other.
fn bridge_and_tops(p: &lmdc::ir::Program) -> (usize, f64, [f64; 2]) {
    let t = p.thermal.as_ref().unwrap();
    let (loads, orders, columns) = heat::island_loads(p);
    let m = (0..loads.len()).find(|&i| loads[i].len() == 1).unwrap();
    let (material, cell) = heat::cell(t);
    let waits: Vec<f64> = t.layers.iter().map(|l| l.wait).collect();
    let mut halves = loads[..=m].to_vec();
    let half = lmdc::thermal::Load {
        energy: 0.5 * loads[m][0].energy,
        time: 0.5 * loads[m][0].time,
        volume: 0.5 * loads[m][0].volume,
        ..loads[m][0]
    };
    halves[m] = vec![half; 2];
    let apart = lmdc::thermal::Columns {
        stands: columns.stands[..2].to_vec(),
        joins: Vec::new(),
        of: columns.of[..m]
            .iter()
            .cloned()
            .chain([columns.of[m - 1].clone()])
            .collect(),
    };
    let top = |order: Vec<usize>| {
        let mut o = orders[..m].to_vec();
        o.push(order);
        let q =
            lmdc::thermal::predict_tree(material, cell, &apart, &halves, &o, |j| waits[j], None);
        q.unwrap()[m].layer.interpass
    };
    (m, t.layers[m].interpass, [top(vec![0, 1]), top(vec![1, 0])])
}

/// Islands that merge (issue 36): the arch's two pillars are a column
/// each until they join, and the part is not taken as one column: every
/// layer below the join lists both pillars, each starting as in the same
/// plan cut before the join (the pillars with no bridge after them); the
/// bridge's layers are one island on a column standing on both pillars'
/// (a join), its first layer starting between the two pillars' tops at
/// that moment (each found by laying the bridge's first layer as two
/// halves, one on each pillar, first the one then the other).
#[test]
fn an_arch_stands_on_both_its_pillars() {
    let src = arch_plan(24);
    let p = pillars(&src, &arch()).expect("no limit");
    let t = p.thermal.as_ref().unwrap();
    let (loads, _, columns) = heat::island_loads(&p);
    let (m, bridge, [a, b]) = bridge_and_tops(&p);
    assert!((8..20).contains(&m), "merged at layer {m}");
    assert!(loads[m..].iter().all(|l| l.len() == 1));
    assert!(t.layers[..m].iter().all(|l| l.islands.len() == 2));
    assert_eq!(columns.stands.len(), 3, "{columns:?}");
    assert_eq!(columns.joins.len(), 1, "{columns:?}");
    // Cut before the join: the same pillars, the same starts.
    let cut = pillars(&arch_plan(m), &arch()).unwrap();
    let c = cut.thermal.as_ref().unwrap();
    for (x, y) in t.layers.iter().zip(&c.layers) {
        for (x, y) in x.islands.iter().zip(&y.islands) {
            assert!((x.interpass - y.interpass).abs() < 1e-9, "{x:?} vs {y:?}");
        }
    }
    eprintln!("bridge starts at {bridge} °C, the pillars' tops {a} and {b} °C");
    assert!(
        a.min(b) < bridge && bridge < a.max(b),
        "{bridge} not between {a} and {b}"
    );
    assert!(t
        .layers
        .iter()
        .all(|l| l.interpass.is_finite() && l.peak.is_finite()));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(4))]

    /// Arches of random gaps and leans (40° at most): the pillars are a
    /// column each up to the join and the bridge one island joined to
    /// both, which starts between the two pillars' tops; every
    /// temperature is finite.
    #[test]
    fn arches_start_their_bridge_between_their_pillars(
        gap in 8.0f64..12.0,
        lean in 0.6f64..0.83,
    ) {
        let rise = 0.5 * gap / lean;
        // Whole layers of 0.54 mm within the arch's 8 mm + rise.
        let layers = ((8.0 + rise - 0.3) / 0.54).floor() as usize;
        let p = pillars(&arch_plan(layers), &arch_of(gap, rise)).expect("no limit");
        let t = p.thermal.as_ref().unwrap();
        let (m, bridge, [a, b]) = bridge_and_tops(&p);
        let (_, _, columns) = heat::island_loads(&p);
        prop_assert!(t.layers[..m].iter().all(|l| l.islands.len() == 2));
        prop_assert!(!columns.joins.is_empty(), "{:?}", columns);
        prop_assert!(a.min(b) < bridge && bridge < a.max(b), "{} not between {} and {}", bridge, a, b);
        prop_assert!(t.layers.iter().all(|l| l.interpass.is_finite() && l.peak.is_finite()));
    }
}

/// A material declared property by property: the same numbers as an
/// alloy's give its prediction to the bit; one property over an alloy's
/// changes only what it should (a plate that holds twice the heat per
/// kelvin warms the first layer's start less); one left out without
/// `material` is named, as are a wrong unit and an emissivity above 1.
#[test]
fn a_material_declared_property_by_property() {
    let ss316l = "conductivity = 20 W/m/degC  density = 7950 kg/m^3  heat_capacity = 560 J/kg/degC  emissivity = 0.5  absorptivity = 0.35";
    let temps = |thermal: &str| -> (String, Vec<f64>) {
        let c = compile(&plate(20.0, 6, "", thermal), &mut ());
        let p = c
            .program
            .unwrap_or_else(|| panic!("{thermal}: {:?}", c.diagnostics));
        let t = p.ir().thermal.clone().unwrap();
        (t.material, t.layers.iter().map(|l| l.interpass).collect())
    };
    let (name, alloy) = temps("material = ss316l");
    assert_eq!(name, "ss316l");
    let (name, declared) = temps(ss316l);
    assert_eq!(name, "declared material");
    assert_eq!(declared, alloy);
    assert!(alloy[1] > alloy[0] + 5.0, "{alloy:?}");
    let (name, heavy) = temps("material = ss316l  heat_capacity = 1120 J/kg/degC");
    assert_eq!(name, "ss316l, with declared properties");
    for (h, a) in heavy.iter().zip(&alloy).skip(1) {
        assert!(h < a, "{heavy:?} vs {alloy:?}");
    }
    let errors = |thermal: &str| -> Vec<(String, String)> {
        compile(&plate(20.0, 6, "", thermal), &mut ())
            .diagnostics
            .iter()
            .map(|d| (d.code.as_str().to_string(), d.message.clone()))
            .collect()
    };
    let e = errors("conductivity = 20 W/m/degC  density = 7950 kg/m^3  emissivity = 0.5");
    assert_eq!(e.len(), 1, "{e:?}");
    assert_eq!(e[0].0, "lmd::missing-field");
    assert!(
        e[0].1.ends_with("`heat_capacity`, `absorptivity` missing"),
        "{e:?}"
    );
    let e = errors(&ss316l.replace("20 W/m/degC", "20 W/m^2/degC"));
    assert!(
        e.iter()
            .any(|(_, m)| m.contains("conductivity")
                && m.contains("a thermal conductivity (W/m/degC)")),
        "{e:?}"
    );
    let e = errors(&ss316l.replace("emissivity = 0.5", "emissivity = 1.5"));
    assert!(
        e.iter()
            .any(|(c, m)| c == "lmd::out-of-range" && m.starts_with("`emissivity` is a share")),
        "{e:?}"
    );
}

/// `lmdc fit` over a plan whose material is declared prints the
/// properties to paste, not an alloy's word: the block it prints, pasted
/// into the plan, compiles to the same material.
#[test]
fn fit_prints_a_declared_material_to_paste() {
    let dir = tempfile::tempdir().unwrap();
    let src = include_str!("../examples/thin_wall.lmd").replace(
        "material = ss316l",
        "conductivity = 40 W/m/degC  density = 7850 kg/m^3  heat_capacity = 600 J/kg/degC  emissivity = 0.7  absorptivity = 0.3",
    );
    let plan = dir.path().join("wall.lmd");
    std::fs::write(&plan, &src).unwrap();
    let sheet = dir.path().join("t.csv");
    std::fs::write(&sheet, "layer, interpass (degC)\n2, 60\n6, 120\n10, 160\n").unwrap();
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_lmdc"))
        .arg("fit")
        .arg(&sheet)
        .arg("--plan")
        .arg(&plan)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{text}");
    let block = text
        .split_once("in the process block:\n")
        .map(|(_, b)| b.split_once("  }").unwrap().0)
        .unwrap_or_else(|| panic!("{text}"));
    assert!(!block.contains("material"), "{block}");
    for line in [
        "conductivity = 40 W/m/degC",
        "density = 7850 kg/m^3",
        "heat_capacity = 600 J/kg/degC",
        "emissivity = 0.7",
    ] {
        assert!(block.contains(line), "{block}");
    }
    let pasted = include_str!("../examples/thin_wall.lmd")
        .replace("  thermal {\n    material = ss316l\n", block);
    let t = |s: &str| {
        let c = compile(s, &mut ());
        let p = c.program.unwrap_or_else(|| panic!("{:?}", c.diagnostics));
        let t = p.ir().thermal.clone().unwrap();
        [t.conductivity, t.density, t.heat_capacity, t.emissivity]
    };
    assert_eq!(t(&pasted), t(&src));
}
