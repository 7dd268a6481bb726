//! A profile or section taken by its name inside another shape —
//! `place(NAME, …)`, a region's `outline = NAME` and `holes = [NAME, …]`,
//! `bolt_circle(NAME, …)`, `profile p = NAME` — plans exactly what the shape
//! written out in its place plans, on every layer (a named profile that
//! follows `layer` follows it where it is placed); a shape inside itself is
//! refused.

use lmdc::diag::Code;
use lmdc::pipeline::compile;

/// The layers of `src`'s plan, as JSON (the IR without its source places).
fn layers(what: &str, src: &str) -> String {
    let c = compile(src, &mut ());
    let p = c.program.unwrap_or_else(|| {
        panic!(
            "{what} does not build:\n{}",
            lmdc::diag::render(&c.diagnostics, what, src, false)
        )
    });
    serde_json::to_string(&p.ir().layers).unwrap()
}

fn flange(edits: &[(&str, &str)]) -> String {
    crate::support::example::edited("flange.lmd", edits)
}

#[test]
fn the_flange_with_its_holes_named_plans_what_it_plans_written_out() {
    let written = layers("flange", &flange(&[]));
    let named = flange(&[
        (
            "profile ring = region(",
            "section bore = circle(diameter = BORE)\nsection bolt = circle(diameter = BOLT)\nprofile rim = circle(diameter = OD)\nprofile ring = region(",
        ),
        ("outline = circle(diameter = OD)", "outline = rim"),
        ("    circle(diameter = BORE),", "    bore,"),
        ("bolt_circle(circle(diameter = BOLT),", "bolt_circle(bolt,"),
    ]);
    assert_eq!(layers("named", &named), written);
    // Placed: the same holes moved, by name or written out.
    let moved = |hole: &str| {
        flange(&[
            (
                "profile ring = region(",
                "section bore = circle(diameter = BORE)\nprofile ring = region(",
            ),
            (
                "    circle(diameter = BORE),",
                &format!("    place({hole}, at = [1.5 mm, -1 mm], turn = 0 deg),"),
            ),
        ])
    };
    let by_name = layers("by name", &moved("bore"));
    assert_eq!(
        by_name,
        layers("written", &moved("circle(diameter = BORE)"))
    );
    assert_ne!(by_name, written, "the bore moved");
}

#[test]
fn a_named_profile_that_follows_the_layer_follows_it_where_it_is_placed() {
    let block = |profile: &str| {
        flange(&[
            (
                "profile ring = region(",
                "profile grow = rectangle(width = 40 mm + layer * 2 mm, height = 30 mm)\nprofile p = place(grow, at = [5 mm, 0 mm], turn = 10 deg)\nprofile ring = region(",
            ),
            ("profile = ring", &format!("profile = {profile}")),
        ])
    };
    let named = layers("named", &block("p"));
    let written = layers(
        "written",
        &block("place(rectangle(width = 40 mm + layer * 2 mm, height = 30 mm), at = [5 mm, 0 mm], turn = 10 deg)"),
    );
    assert_eq!(named, written);
    // And it does grow: the last layer's tracks reach farther than the first's.
    let c = compile(&block("p"), &mut ());
    let p = c.program.unwrap();
    let reach = |l: &lmdc::ir::Layer| {
        l.paths
            .iter()
            .flat_map(|p| &p.points)
            .map(|q| q.pos[0])
            .fold(f64::NEG_INFINITY, f64::max)
    };
    let layers = &p.ir().layers;
    assert!(reach(&layers[layers.len() - 1]) > reach(&layers[0]) + 1.0);
}

#[test]
fn a_profile_named_as_a_whole_shape_is_the_shape() {
    let alias = flange(&[
        (
            "profile ring = region(",
            "profile other = ring\nprofile ring = region(",
        ),
        ("profile = ring", "profile = other"),
    ]);
    assert_eq!(layers("alias", &alias), layers("flange", &flange(&[])));
}

#[test]
fn a_shape_inside_itself_is_refused_once_for_each_time() {
    let src = flange(&[(
        "profile ring = region(",
        "profile a = place(b, at = [0 mm, 0 mm], turn = 0 deg)\nprofile b = region(outline = circle(diameter = 90 mm), holes = [a])\nprofile ring = region(",
    )]);
    let c = compile(&src, &mut ());
    assert!(c.program.is_none());
    let cycles: Vec<_> = c
        .diagnostics
        .iter()
        .filter(|d| d.code == Code::Cycle)
        .collect();
    assert_eq!(cycles.len(), 2, "{:#?}", c.diagnostics);
    for name in ["a", "b"] {
        let says = format!("`{name}` is placed inside itself");
        assert!(
            cycles.iter().any(|d| d.message.contains(&says)),
            "{cycles:#?}"
        );
    }
    // Nothing else is said of the names the cycle left.
    assert!(
        !c.diagnostics.iter().any(|d| d.code == Code::ExpectedShape),
        "{:#?}",
        c.diagnostics
    );
}
