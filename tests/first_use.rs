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

#[test]
fn a_styles_powder_warns_only_where_a_machine_cannot_program_it() {
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
            .filter(|(c, m, _)| *c == Code::Unused && m.contains("powder"))
            .map(|(_, m, _)| m)
            .collect()
    };
    // Both machines' feeders have a rate output: both program it.
    assert_eq!(powder(&styled), Vec::<String>::new());
    // Without the robot's, the warning names the robot alone.
    let robot_plain = styled.replacen(
        "    rate_output = 2  // $ANOUT[2]\n    full_scale = 40 g/min\n",
        "",
        1,
    );
    assert_ne!(robot_plain, styled);
    let w = powder(&robot_plain);
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(
        w[0].contains("not programmed on `kr30`") && !w[0].contains("mill3"),
        "{w:?}"
    );
    // Without either, the old warning: recorded, not programmed.
    let plain = robot_plain
        .replacen("    rate_output = 0", "    // rate_output = 0", 1)
        .replacen(
            "    full_scale = 40 g/min  //",
            "    // full_scale = 40 g/min  //",
            1,
        );
    let w = powder(&plain);
    assert!(
        w.len() == 1 && w[0].contains("recorded, not programmed"),
        "{w:?}"
    );
}
