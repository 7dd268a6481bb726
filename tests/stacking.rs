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
