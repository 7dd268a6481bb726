//! Layers lie on each other: a deposit more than ¾ of a bead across the nozzle
//! from every bead of the layer below is refused (issue: a twist of 10⁶° built points 10.9 mm
//! off a 6 mm bead), measured against real parts that step out too fast, while
//! every example passes (it is built layer on layer).

use crate::support::example;

use lmdc::pipeline::compile;

fn edited(path: &str, from: &str, to: &str) -> String {
    example::edited(path.trim_start_matches("examples/"), &[(from, to)])
}

fn stacking(src: &str) -> Vec<String> {
    compile(src, &mut ())
        .diagnostics
        .iter()
        .filter(|d| d.code == "lmd::stacking")
        .map(|d| d.message.clone())
        .collect()
}

#[test]
fn a_twist_that_jumps_between_layers_is_refused() {
    let d = stacking(&edited(
        "examples/twisted_duct.lmd",
        "twist = 45 deg",
        "twist = 1e6 deg",
    ));
    assert_eq!(d.len(), 1);
    assert!(d[0].contains("¾ of the bead width (4.5 mm)"), "{}", d[0]);
    // 90° over the same bend is a real part: layers still lie on each other.
    assert!(stacking(&edited(
        "examples/twisted_duct.lmd",
        "twist = 45 deg",
        "twist = 90 deg"
    ))
    .is_empty());
}

#[test]
fn a_block_that_grows_faster_than_half_a_bead_a_layer_is_refused() {
    // The tooth gets 3 mm longer each layer: its tracks' far ends overhang the
    // layer below by 3 mm, more than ¾ of the 2.2 mm bead.
    let d = stacking(&edited(
        "examples/sprocket_tooth.lmd",
        "let L = 40 mm",
        "let L = 40 mm + layer * 3 mm",
    ));
    assert_eq!(d.len(), 1, "{d:?}");
    assert!(d[0].contains("1.65 mm"), "{}", d[0]);
    // 0.5 mm a layer is an overhang a bead bridges.
    assert!(stacking(&edited(
        "examples/sprocket_tooth.lmd",
        "let L = 40 mm",
        "let L = 40 mm + layer * 0.5 mm"
    ))
    .is_empty());
}

#[test]
fn every_example_lies_layer_on_layer() {
    for e in std::fs::read_dir("examples").unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x == "lmd") {
            let src = std::fs::read_to_string(&p).unwrap();
            assert!(stacking(&src).is_empty(), "{}", p.display());
        }
    }
}

/// A wall one bead of the seed 003 map wide, lofted 20 mm up from a circle
/// of diameter `from` to one of `to` (both outer faces): a cone.
fn cone(from: f64, to: f64, layers: &str) -> String {
    format!(
        "part cone
bead b316 {{
  width = 2.4 mm
  speed = 4 mm/s .. 8.7 mm/s
  model = linear(slope = -0.135 mm / (1 mm/s), intercept = 1.82 mm)
}}
loft c {{
  from = circle(diameter = {from} mm)
  to = circle(diameter = {to} mm)
  spine = line(length = 20 mm)
  size = outer
  wall = b316
}}
slicing normal {{
  layers = {layers}
  points = 360
}}
process {{
  power = 1000 W
  powder = 12 g/min
  defocus = 0 mm
}}
machine mill3 {{
  kind = cnc
  head {{ standoff = 15 mm  nozzle = frustum(length = 45 mm, tip = 12 mm, top = 40 mm) }}
  axes = 3
  dialect = linuxcnc
  max_speed = 50 mm/s
  clearance = 5 mm
}}
"
    )
}

/// The help of the stacking error of `src`.
fn stacking_help(src: &str) -> String {
    let c = compile(src, &mut ());
    let d = c.diagnostics.iter().find(|d| d.code == "lmd::stacking");
    d.and_then(|d| d.help.clone())
        .unwrap_or_else(|| panic!("no stacking error: {:#?}", c.diagnostics))
}

/// The number in `text` between `before` and `after`.
fn number(text: &str, before: &str, after: &str) -> f64 {
    let r = text
        .split(before)
        .nth(1)
        .unwrap_or_else(|| panic!("no {before:?} in {text}"));
    r.split(after).next().unwrap().parse().unwrap()
}

#[test]
fn two_cones_print_their_own_step_and_the_count_and_lean_that_land() {
    // 20 layers of 1 mm; the wall leans 63° (steps 1.963 mm a layer) or 73°
    // (3.271 mm): both printed "more than 2.092 mm" (the search radius).
    let tan = |deg: f64| deg.to_radians().tan();
    for (deg, from) in [(63.0, 100.0), (73.0, 140.0)] {
        let to = from - 2.0 * 20.0 * tan(deg);
        let src = cone(from, to, "auto");
        let d = stacking(&src);
        let step = format!("lands {} mm across", (tan(deg) * 1000.0).round() / 1000.0);
        assert!(d.len() == 1 && d[0].contains(&step), "{deg}°: {d:?}");
        let help = stacking_help(&src);
        assert!(help.contains(&format!("a lean of {deg}°")), "{help}");
        // The count named builds: thinner layers step less.
        let n = number(&help, "`layers = ", "`") as usize;
        let c = compile(&cone(from, to, &n.to_string()), &mut ());
        let p = c
            .program
            .unwrap_or_else(|| panic!("{n} layers: {:#?}", c.diagnostics));
        assert_eq!(p.ir().layers.len(), n);
        // So does a wall leaning the angle named, at these layers.
        let lean = number(&help, "leaning at most ", "°");
        let c = compile(&cone(from, from - 40.0 * tan(lean), "auto"), &mut ());
        assert!(c.program.is_some(), "{lean}°: {:#?}", c.diagnostics);
    }
}

#[test]
fn a_cone_of_flat_layers_prints_its_own_step() {
    // A disc growing with `layer_z` on 0.691 mm layers: the farther it
    // leans, the farther its deposits land.
    let step = |growth: &str| {
        let d = stacking(&edited(
            "examples/sprocket_tooth.lmd",
            "let L = 40 mm",
            &format!("let L = 40 mm + {growth} * layer_z"),
        ));
        assert_eq!(d.len(), 1, "{d:?}");
        let r = d[0].split("lands ").nth(1).unwrap();
        r.split(" mm").next().unwrap().parse::<f64>().unwrap()
    };
    let (a, b) = (step("3.5"), step("5"));
    // Each tooth's far end steps its growth a layer: 2.419 and 3.455 mm.
    assert!(
        (a - 3.5 * 0.691).abs() < 0.01 && (b - 5.0 * 0.691).abs() < 0.01,
        "{a} {b}"
    );
}
