//! Nothing unsafe reaches a program through the texts and values a machine block
//! declares: every text written verbatim is one printable line, the laser can
//! always be switched, the program always ends, long names stay within a
//! control's line length, declared angles are angles.

use crate::support::rs274;
use crate::support::skip;

use crate::support::example;

use example::tooth;
use lmdc::pipeline::compile;

fn codes(src: &str) -> Vec<(String, String)> {
    let c = compile(src, &mut ());
    assert!(c.program.is_none(), "want errors");
    c.diagnostics
        .iter()
        .filter(|d| d.is_error())
        .map(|d| (d.code.as_str().to_string(), d.message.clone()))
        .collect()
}

fn cnc(extra: &str) -> String {
    tooth(&[(
        "dialect = linuxcnc",
        &format!("dialect = linuxcnc\n  {extra}"),
    )])
}

#[test]
fn a_carriage_return_cannot_inject_a_move() {
    // LinuxCNC reads the CR as a line end and ran G0 Z-500 with the laser on.
    // lmdc reads it as a line end too: the text is not closed on its line.
    let d = codes(&cnc("laser_on = \"M3\rG0 Z-500\""));
    assert_eq!(d.len(), 1, "{d:?}");
    assert_eq!(d[0].0, "lmd::syntax");
    assert!(d[0].1.contains("not closed on its line"), "{}", d[0].1);
    // Any other control character in a program line is refused where declared.
    let d = codes(&cnc("laser_on = \"M3\u{b}G0 Z-500\""));
    assert_eq!(d[0].0, "lmd::program-text", "{d:?}");
    for bad in ["\u{1b}[2J", "\t", "é"] {
        let d = codes(&cnc(&format!("preamble = [\"G21\", \"G90{bad}\"]")));
        assert_eq!(d[0].0, "lmd::program-text", "{bad:?}: {d:?}");
    }
}

#[test]
fn the_laser_can_always_be_switched_off_and_the_program_ends() {
    let d = codes(&cnc("laser_off = \"\""));
    assert_eq!(d[0].0, "lmd::program-text");
    assert!(d[0].1.contains("`laser_off` is empty"), "{}", d[0].1);
    for post in ["[]", "[\"M5\"]", "\"M5\""] {
        let d = codes(&cnc(&format!("postamble = {post}")));
        assert_eq!(d.len(), 1, "{post}: {d:?}");
        assert!(d[0].1.contains("does not end the program"), "{}", d[0].1);
    }
    // Every fault of the block at once.
    let d = codes(&cnc(
        "laser_off = \"\"\n  laser_on = \"M3\tM4\"\n  postamble = [\"M5\"]",
    ));
    assert_eq!(d.len(), 3, "{d:?}");
}

#[test]
fn home_angles_and_frames_are_angles_and_offsets_a_cell_has() {
    let d = codes(&tooth(&[(
        "max_speed = 100 mm/s",
        "max_speed = 100 mm/s\n  home = [1e17 deg, -90 deg, 90 deg, 0 deg, 0 deg, 0 deg]",
    )]));
    assert_eq!(d.len(), 1, "{d:?}");
    assert!(d[0].1.contains("home axis A1"), "{}", d[0].1);
    let d = codes(&tooth(&[(
        "tool = frame(1, z = 300 mm)",
        "tool = frame(1, z = 1e12 mm)",
    )]));
    assert_eq!(d.len(), 1, "{d:?}");
    assert!(d[0].1.contains("`z`"), "{}", d[0].1);
}

#[test]
fn long_names_keep_comment_lines_short_enough_for_linuxcnc() {
    let long = "a".repeat(300);
    let src = tooth(&[
        ("part sprocket_tooth", &format!("part {long}")),
        ("machine mill3", &format!("machine mill3{long}")),
    ]);
    let c = compile(&src, &mut ());
    let p = c.program.unwrap_or_else(|| panic!("{:?}", c.diagnostics));
    let mut sink = lmdc::back::MemorySink::default();
    for m in p.machines() {
        lmdc::back::emit(m, &lmdc::back::Templates::builtin().unwrap(), &mut sink).unwrap();
    }
    for (name, bytes) in &sink.files {
        let text = std::str::from_utf8(bytes).unwrap();
        let longest = text.lines().map(str::len).max().unwrap();
        assert!(longest < 200, "{name}: a line of {longest} characters");
    }
    let (name, ngc) = sink
        .files
        .iter()
        .find(|(n, _)| n.ends_with(".ngc"))
        .expect("a G-code program");
    assert!(name.len() <= 28, "{name}");
    if rs274::find_rs274().is_none() {
        skip::skip(
            "long_names_keep_comment_lines_short_enough_for_linuxcnc",
            "LinuxCNC's rs274",
            "run `bash .ci/install-rs274.sh` and export LMDC_RS274=<the path it prints>",
        );
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, ngc).unwrap();
    rs274::interpret(&path).unwrap_or_else(|e| panic!("rs274 refuses it: {e}"));
}
