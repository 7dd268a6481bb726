//! The test suite's RAPID reader (tests/support/rapid_check.rs) against the
//! samples of docs/rapid.md, read from the doc itself so the two cannot
//! drift: it accepts them and runs them into the trace the doc describes, and
//! it refuses each broken variant with a message naming the problem and its
//! file and line.

use crate::support::rapid_check::{self as rapid, Event, Files, Kind, Target};

/// The doc's modules: every fenced block that begins `MODULE <name>`, as
/// `<name>.mod`.
fn doc_modules() -> Files {
    let text = std::fs::read_to_string("docs/rapid.md").expect("docs/rapid.md");
    let mut files = Files::new();
    for (k, block) in text.split("```").enumerate() {
        // Odd pieces are inside fences; drop the info string's line.
        let Some((_, body)) = block.split_once('\n').filter(|_| k % 2 == 1) else {
            continue;
        };
        let Some(name) = body.strip_prefix("MODULE ").and_then(|r| r.lines().next()) else {
            continue;
        };
        files.insert(format!("{}.mod", name.trim()), body.to_string());
    }
    files
}

/// The doc's program made whole: its main calls `duct_m002`, which the doc
/// does not show; the second module is the first one renamed, its layer the
/// second, its move from the first module's end a MoveL at the first
/// module's first linear speed.
fn sample() -> Files {
    let mut files = doc_modules();
    let m1 = files.get("duct_m001.mod").expect("the doc's motion module");
    let m2 = m1
        .replace("duct_m001", "duct_m002")
        .replace("! layer 1 of 12", "! layer 2 of 12")
        .replace("v200, fine", "lmd_v1, fine")
        .replace("MoveJ", "MoveL");
    files.insert("duct_m002.mod".into(), m2);
    files
}

fn run(files: &Files) -> Result<rapid::Trace, String> {
    rapid::run(files, "duct", "do1", "ao2")
}

#[test]
fn the_doc_holds_both_samples() {
    let files = doc_modules();
    let names: Vec<&str> = files.keys().map(String::as_str).collect();
    assert_eq!(names, ["duct.mod", "duct_m001.mod"]);
    let e = run(&files).expect_err("main calls duct_m002, which is not given");
    assert!(e.starts_with("duct.mod:") && e.contains("duct_m002"), "{e}");
}

#[test]
fn the_samples_run_as_the_doc_says() {
    let t = run(&sample()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(t.calls, ["duct_m001", "duct_m002"]);
    let kinds: Vec<Kind> = t.motions.iter().map(|m| m.kind).collect();
    use Kind::*;
    let mut want = vec![MoveAbsJ, MoveJ];
    want.extend([MoveL, TriggL, MoveL, TriggL, MoveL, MoveL]);
    want.extend([MoveL, TriggL, MoveL, TriggL, MoveL, MoveAbsJ]);
    assert_eq!(kinds, want);
    // Each move of a module: x, z; laser, power, speed, zone, switch at its end.
    let per_move = [
        ([100.0, 20.0], (false, 0.0, 200.0, None, false)),
        ([100.0, 0.5], (false, 0.0, 250.0, None, false)),
        ([101.0, 0.5], (true, 0.5, 8.0, Some(0.2), false)),
        ([102.0, 0.5], (true, 0.5, 8.0, Some(0.2), false)),
        ([103.0, 0.5], (true, 0.5, 8.0, Some(0.2), true)),
        ([103.0, 10.5], (false, 0.5, 7.25, None, false)),
    ];
    for (k, m) in t.motions[1..13].iter().enumerate() {
        let ([x, z], (laser, power, speed, zone, at_end)) = per_move[k % 6];
        let at = format!("motion {}: {m:?}", k + 1);
        // The second module starts with the power the first left, its first
        // move a MoveL at lmd_v1.
        let (power, speed) = match k {
            6 => (0.5, 250.0),
            7.. => (0.5, speed),
            _ => (power, speed),
        };
        let got = (m.laser, m.power, m.speed, m.zone, m.switch_at_end);
        assert_eq!(got, (laser, power, speed, zone, at_end), "{at}");
        let p = m.pose().expect("a Cartesian move");
        assert_eq!(p.pos, [x, 0.0, z], "{at}");
        let pose = (p.quat, p.conf, p.extax);
        assert_eq!(pose, ([0.0, 0.0, 1.0, 0.0], [0, 0, -1, 0], [None; 6]));
        assert_eq!(m.module, if k < 6 { "duct_m001" } else { "duct_m002" });
    }
    for m in [&t.motions[0], &t.motions[13]] {
        let got = (m.speed, m.zone, m.laser, m.module.as_str());
        assert_eq!(got, (200.0, None, false, "duct"));
        let home = [0.0, 0.0, 0.0, 0.0, 30.0, 0.0];
        assert!(matches!(&m.target, Target::Joints(j) if j.robax == home));
    }
    assert!(!t.laser_at_end && t.power_at_end == 0.0);
    assert_eq!(t.dwells, [(7, 2.5), (13, 2.5)]);
    assert_eq!(t.layers.len(), 2);
    assert_eq!((t.layers[0].0, t.layers[1].0), (1, 7));
    assert_eq!(t.moves_per_module["duct_m001"], 6);
    assert_eq!(t.speeds["lmd_v1"], 250.0);
    assert_eq!(t.speeds["lmd_v2"], 8.0);
    assert_eq!((t.conf_j, t.conf_l), (Some(true), Some(false)));
    assert_the_cell(&t);
}

/// The data and the outputs' timeline of the samples.
fn assert_the_cell(t: &rapid::Trace) {
    let tool = t.tool.as_ref().expect("a tool");
    assert_eq!(
        (tool.tframe.pos, tool.mass, tool.cog),
        ([0.0, 0.0, 250.0], 8.0, [0.0, 0.0, 120.0])
    );
    let wobj = t.wobj.as_ref().expect("a work object");
    assert_eq!(
        (wobj.uframe.pos, wobj.ufmec.as_str()),
        ([1200.0, 0.0, 400.0], "")
    );
    let home = t.home.as_ref().expect("a home");
    assert_eq!(home.extax, [None; 6]);
    use Event::*;
    let module = |first: usize| {
        let mut v: Vec<Event> = (first..first + 6).map(Motion).collect();
        v.extend([Dwell(2.5), WaitRob, SetDO("do3".into(), true)]);
        v
    };
    let mut want = vec![
        SetDO("do1".into(), false),
        SetAO("ao2".into(), 0.0),
        Motion(0),
    ];
    want.extend(module(1));
    want.extend(module(7));
    want.extend([
        WaitRob,
        SetDO("do1".into(), false),
        SetAO("ao2".into(), 0.0),
        Motion(13),
    ]);
    assert_eq!(t.events, want);
}

/// One way to break the sample: in `file` (`ALL`: every file) each `from`
/// becomes its `to`, and the reader's message holds `says` and names the
/// file and the line of the last line holding `at` (in the main module for
/// edits of every file; `<file>|<text>` names the file).
struct Broken {
    what: &'static str,
    file: &'static str,
    edits: &'static [(&'static str, &'static str)],
    says: &'static str,
    at: &'static str,
}

const M1: &str = "duct_m001.mod";
const MAIN: &str = "duct.mod";
const ALL: &str = "*";
const LONG: &str = "lmd_v1_a_name_of_33_characters___";

/// The sample's move to 102 made a TriggL switching the laser on again.
const ON_AGAIN: &str = "    TriggIO lmd_on_end, 0 \\DOp:=do1, 1;\n    TriggL [[102";
/// A move home at the end of a motion module.
const HOME_AGAIN: &str =
    "    MoveAbsJ lmd_home \\NoEOffs, v200, fine, lmd_tool \\WObj:=lmd_wobj;\n  ENDPROC";

const BROKEN: [Broken; 21] = [
    Broken {
        what: "an exponent",
        file: M1,
        edits: &[("[[101,0,0.5]", "[[1.01E+02,0,0.5]")],
        says: "`1.01E+02` is not a plain decimal",
        at: "1.01E+02",
    },
    Broken {
        what: "9E+09 in a position",
        file: M1,
        edits: &[("[[100,0,20]", "[[100,0,9E+09]")],
        says: "`9E+09` is not a plain decimal",
        at: "[100,0,9E+09]",
    },
    Broken {
        what: "NaN",
        file: M1,
        edits: &[("[[102,0,0.5]", "[[102,0,NaN]")],
        says: "`NaN`: NaN and inf are not numbers",
        at: "NaN",
    },
    Broken {
        what: "a name of 33 characters",
        file: ALL,
        edits: &[("lmd_v1", LONG)],
        says: "has 33 characters, more than 32",
        at: "CONST speeddata lmd_v1_a",
    },
    Broken {
        what: "a reserved word",
        file: ALL,
        edits: &[("lmd_z", "ENDIF")],
        says: "`ENDIF` is a RAPID reserved word",
        at: "CONST zonedata",
    },
    Broken {
        what: "an unnormalised quaternion",
        file: M1,
        edits: &[("[[101,0,0.5],[0,0,1,0]", "[[101,0,0.5],[0,0,1.0001,0]")],
        says: "has norm 1.0001",
        at: "1.0001",
    },
    Broken {
        what: "a trigger not used",
        file: M1,
        edits: &[("lmd_on \\T2:=lmd_power", "lmd_on")],
        says: "TriggIO lmd_power is not used by the TriggL",
        at: "TriggIO lmd_power",
    },
    Broken {
        what: "a redundant laser switch",
        file: M1,
        edits: &[
            ("    MoveL [[102", ON_AGAIN),
            ("lmd_v2, lmd_z,", "lmd_v2, lmd_on_end, lmd_z,"),
        ],
        says: "TriggIO lmd_on_end switches the laser on, and it is on already",
        at: "TriggIO lmd_on_end",
    },
    Broken {
        what: "a trigger named for another switch",
        file: M1,
        edits: &[("TriggIO lmd_power, 0 \\Start", "TriggIO lmd_power, 0")],
        says: "where its move ends, is lmd_power_end, not lmd_power",
        at: "TriggIO lmd_power",
    },
    Broken {
        what: "a switch at the start after a blended motion",
        file: M1,
        edits: &[("lmd_v1, fine", "lmd_v1, lmd_z")],
        says: "the move before (duct_m001.mod:5) is blended",
        at: "TriggL [[101",
    },
    Broken {
        what: "an undeclared speeddata",
        file: M1,
        edits: &[("lmd_v1", "lmd_v3")],
        says: "`lmd_v3` is not declared (want a speeddata)",
        at: "lmd_v3",
    },
    Broken {
        what: "v200 on a linear move",
        file: M1,
        edits: &[("lmd_v1, fine", "v200, fine")],
        says: "`v200` is not declared (want a speeddata)",
        at: "[[100,0,0.5]",
    },
    Broken {
        what: "a speeddata unlike ABB's",
        file: M1,
        edits: &[("[7.25,500,5000,1000]", "[7.25,500,5000,100]")],
        says: "a speeddata is [v_tcp,500,5000,1000]",
        at: "7.25",
    },
    Broken {
        what: "MoveAbsJ in a motion module",
        file: M1,
        edits: &[("  ENDPROC", HOME_AGAIN)],
        says: "MoveAbsJ in the motion module duct_m001",
        at: "MoveAbsJ",
    },
    Broken {
        what: "a wrong module name",
        file: M1,
        edits: &[("MODULE duct_m001", "MODULE duct_m01")],
        says: "the file duct_m001.mod holds `MODULE duct_m01`",
        at: "MODULE duct_m01",
    },
    Broken {
        what: "cfx 8",
        file: M1,
        edits: &[(
            "[[100,0,20],[0,0,1,0],[0,0,-1,0]",
            "[[100,0,20],[0,0,1,0],[0,0,-1,8]",
        )],
        says: "cfx 8 outside 0..7",
        at: "MoveJ",
    },
    Broken {
        what: "a configuration without an arm",
        file: MAIN,
        edits: &[("ConfJ \\On", "ConfJ \\Off")],
        says: "under ConfJ \\Off (no arm declared) the confdata is [0,0,0,0]",
        at: "duct_m001.mod|MoveJ",
    },
    Broken {
        what: "an analog value 1.5",
        file: M1,
        edits: &[("\\AOp:=ao2, 0.5", "\\AOp:=ao2, 1.5")],
        says: "the analog value 1.5 is outside 0..1",
        at: "AOp",
    },
    Broken {
        what: "a wait after a blended motion",
        file: M1,
        edits: &[("[7.25,500,5000,1000], fine", "[7.25,500,5000,1000], lmd_z")],
        says: "WaitTime after a blended motion (duct_m001.mod:12)",
        at: "WaitTime",
    },
    Broken {
        what: "a layer comment out of order",
        file: M1,
        edits: &[("! layer 1 of 12", "! layer 2 of 12")],
        says: "`layer 2 of 12` after layer 0 of 0",
        at: "! layer",
    },
    Broken {
        what: "the laser switched by SetDO in a motion module",
        file: M1,
        edits: &[("SetDO do3, 1;", "SetDO do1, 1;")],
        says: "the laser and its power switch only by TriggIO",
        at: "SetDO",
    },
];

#[test]
fn broken_samples_are_refused_with_the_problem_and_its_line() {
    let mut failures = Vec::new();
    for b in &BROKEN {
        let mut files = sample();
        for (name, text) in files.iter_mut() {
            if b.file == ALL || name == b.file {
                for (from, to) in b.edits {
                    *text = text.replace(from, to);
                }
            }
        }
        assert_ne!(files, sample(), "{}: the edits change nothing", b.what);
        // Where the problem is: the last line holding `at`, in the edited file
        // (the main module's for edits of every file).
        let (file, at) = match b.at.split_once('|') {
            Some((file, at)) => (file, at),
            None if b.file == ALL => (MAIN, b.at),
            None => (b.file, b.at),
        };
        let line = files[file]
            .lines()
            .enumerate()
            .filter(|(_, l)| l.contains(at))
            .map(|(i, _)| i + 1)
            .last()
            .unwrap_or_else(|| panic!("{}: no line holds `{at}`", b.what));
        let place = format!("{file}:{line}:");
        match run(&files) {
            Ok(_) => failures.push(format!("{}: accepted", b.what)),
            Err(e) if e.starts_with(&place) && e.contains(b.says) => {}
            Err(e) => failures.push(format!(
                "{}: want `{place} … {} …`, got `{e}`",
                b.what, b.says
            )),
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
