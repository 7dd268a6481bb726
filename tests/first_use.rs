//! The messages a new user stumbled on (issue 24, item 7): each help names
//! what works on this file, and the tests write it in and build it.

use lmdc::diag::Code;
use lmdc::pipeline::compile;

fn codes(src: &str) -> Vec<(Code, String, Option<String>)> {
    compile(src, &mut ())
        .diagnostics
        .iter()
        .map(|d| (d.code, d.message.clone(), d.help.clone()))
        .collect()
}

/// The number after `prefix` in `text`.
fn after(text: &str, prefix: &str) -> String {
    let at = text
        .find(prefix)
        .unwrap_or_else(|| panic!("no `{prefix}` in {text}"))
        + prefix.len();
    text[at..]
        .chars()
        .take_while(|c| c.is_ascii_digit() || *c == '.')
        .collect()
}

#[test]
fn transition_speed_names_the_max_speed_and_the_radius_that_work() {
    let src = std::fs::read_to_string("examples/errors/transition_too_fast.lmd").unwrap();
    let found = codes(&src);
    let (_, _, help) = found
        .iter()
        .find(|(c, ..)| *c == Code::TransitionSpeed)
        .expect("the example's error");
    let help = help.clone().unwrap().replace('\n', " ");
    let help = help.split_whitespace().collect::<Vec<_>>().join(" ");
    let speed = after(&help, "a max_speed of at least ");
    let radius = after(&help, "a ring radius of at least ");
    // Each, written into the file, clears the error (and not much less).
    let faster = src.replacen(
        "max_speed = 22 mm/s",
        &format!("max_speed = {speed} mm/s"),
        1,
    );
    assert!(
        !codes(&faster)
            .iter()
            .any(|(c, ..)| *c == Code::TransitionSpeed),
        "{speed}"
    );
    let wider = src.replacen("radius = 40 mm", &format!("radius = {radius} mm"), 1);
    assert!(
        !codes(&wider)
            .iter()
            .any(|(c, ..)| *c == Code::TransitionSpeed),
        "{radius}"
    );
    let v: f64 = speed.parse().unwrap();
    let slower = src.replacen(
        "max_speed = 22 mm/s",
        &format!("max_speed = {} mm/s", v - 0.1),
        1,
    );
    assert!(codes(&slower)
        .iter()
        .any(|(c, ..)| *c == Code::TransitionSpeed));
    let r: f64 = radius.parse().unwrap();
    let narrower = src.replacen("radius = 40 mm", &format!("radius = {} mm", r - 0.5), 1);
    assert!(codes(&narrower)
        .iter()
        .any(|(c, ..)| *c == Code::TransitionSpeed));
}

#[test]
fn the_io_help_speaks_the_dialects_language() {
    let plate = include_str!("codes/plate.lmd");
    for (dialect, want, not) in [
        ("sinumerik840d", "$A_OUT[{n}]=1", "M64"),
        ("fagor8070", "integrator", "M64"),
    ] {
        let src = plate.replace(
            "  max_speed = 50 mm/s\n}",
            &format!("  max_speed = 50 mm/s\n  dialect = {dialect}\n  gas {{ output = 2 }}\n}}"),
        );
        let found = codes(&src);
        let helps: Vec<String> = found
            .iter()
            .filter(|(c, ..)| *c == Code::IoDialect)
            .map(|(_, m, h)| format!("{m} {}", h.clone().unwrap()))
            .collect();
        assert!(!helps.is_empty(), "{dialect}: {found:?}");
        assert!(
            helps.iter().any(|h| h.contains(want)),
            "{dialect}: {helps:?}"
        );
        assert!(
            helps
                .iter()
                .all(|h| !h.contains(not) && h.contains(dialect)),
            "{dialect}: {helps:?}"
        );
    }
}

/// Issue 33 item 3: a style's powder is programmed (the feeder's rate
/// output) or refused where the machine cannot program it (it was a warning,
/// "recorded, not programmed", and the plan credited the style's feed).
#[test]
fn a_styles_powder_is_refused_where_a_machine_cannot_program_it() {
    let src = std::fs::read_to_string("examples/flange.lmd").unwrap();
    assert!(
        src.contains("rate_output"),
        "flange's mill programs the feed rate"
    );
    let styled = format!(
        "{src}\nstyle slow_edge {{\n  power = 1400 W\n  powder = 10 g/min\n  when {{ paths = outer_contour }}\n}}\n"
    );
    let powder = |src: &str| -> Vec<String> {
        codes(src)
            .into_iter()
            .filter(|(c, _, _)| *c == Code::PowderRate)
            .map(|(_, m, _)| m)
            .collect()
    };
    // Both machines' feeders have a rate output: both program it.
    assert_eq!(powder(&styled), Vec::<String>::new());
    // Without the robot's, the robot alone refuses it.
    let robot_plain = styled.replacen(
        "    rate_output = 2  // $ANOUT[2]\n    full_scale = 40 g/min\n",
        "",
        1,
    );
    assert_ne!(robot_plain, styled);
    let w = powder(&robot_plain);
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(
        w[0].contains("style `slow_edge` feeds 10 g/min, which machine `kr30` cannot program"),
        "{w:?}"
    );
    let c = lmdc::pipeline::compile(&robot_plain, &mut ());
    assert!(c.program.is_none(), "refused");
}

/// Case errors/styles/style_powder_unfed, refused: following its help — a
/// rate output on the feeder — builds, and the plan sets the rim's feed
/// before its run and waits the powder's arrival there.
#[test]
fn following_the_unfed_powder_help_builds() {
    let src =
        std::fs::read_to_string("tests/cases/errors/styles/style_powder_unfed/input.lmd").unwrap();
    assert!(lmdc::pipeline::compile(&src, &mut ()).program.is_none());
    let fixed = src.replacen(
        "    arrival = 2.5 s\n",
        "    arrival = 2.5 s\n    rate_output = 2\n    full_scale = 40 g/min\n",
        1,
    );
    let c = lmdc::pipeline::compile(&fixed, &mut ());
    assert!(
        c.diagnostics.iter().all(|d| d.code != Code::PowderRate),
        "{:?}",
        c.diagnostics
    );
    let ir = c.program.expect("builds").into_ir();
    let fed: Vec<f32> = ir.layers[0]
        .paths
        .iter()
        .map(|p| p.points[0].powder)
        .collect();
    assert!(fed.contains(&9.6) && fed.contains(&8.0), "{fed:?}");
}
