//! The `lmdc` command as a user runs it: exit codes, what is written (and that
//! nothing is written on failure), determinism, `--emit ir`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn lmdc(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lmdc"))
        .args(args)
        .env("NO_COLOR", "1")
        .output()
        .expect("runs")
}

fn out_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("lmdc-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn listing(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn help_is_for_process_engineers() {
    let o = lmdc(&["--help"]);
    assert_eq!(o.status.code(), Some(0));
    let text = String::from_utf8_lossy(&o.stdout);
    for want in ["build", "check", "simulate", "Exit status"] {
        assert!(text.contains(want), "{text}");
    }
    let o = lmdc(&["build", "--help"]);
    let text = String::from_utf8_lossy(&o.stdout);
    for want in ["--machine", "--emit", "--templates", "--timings", "--out"] {
        assert!(text.contains(want), "{text}");
    }
}

#[test]
fn check_reports_success_and_failure() {
    let o = lmdc(&["check", "examples/twisted_duct.lmd"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let o = lmdc(&["check", "examples/errors/bend_too_tight.lmd"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("lmd::bend-too-tight"));
}

/// `check` runs the machines' own checks too (here the CNC's axis limits),
/// so a file `check` passes is one `build` writes.
#[test]
fn check_runs_the_machine_checks() {
    let src = std::fs::read_to_string("examples/sprocket_tooth.lmd")
        .unwrap()
        .replace("x = -50 mm .. 150 mm", "x = -50 mm .. 30 mm");
    let dir = out_dir("check-limits");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("tooth.lmd");
    std::fs::write(&file, src).unwrap();
    let o = lmdc(&["check", file.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("lmd::axis-limit"), "{}", stderr(&o));
    assert_eq!(listing(&dir), ["tooth.lmd"], "check writes nothing");

    // Two machines whose names differ only in what a file name drops.
    let src = std::fs::read_to_string("examples/sprocket_tooth.lmd")
        .unwrap()
        .replace("machine mill3 {", "machine \"mill 3\" {")
        .replace("machine kr30 {", "machine mill_3 {\n  kind = cnc\n  axes = 3\n  dialect = linuxcnc\n  max_speed = 50 mm/s\n}\nmachine kr30 {");
    std::fs::write(&file, src).unwrap();
    for cmd in ["check", "build"] {
        let o = lmdc(
            &[
                cmd,
                file.to_str().unwrap(),
                "--out",
                dir.join("out").to_str().unwrap(),
            ][..if cmd == "check" { 2 } else { 4 }],
        );
        assert_eq!(o.status.code(), Some(1), "{cmd}: {}", stderr(&o));
        assert!(
            stderr(&o).contains("lmd::name-clash"),
            "{cmd}: {}",
            stderr(&o)
        );
    }
    assert_eq!(listing(&dir), ["tooth.lmd"], "nothing written");
}

#[test]
fn build_writes_every_machine_deterministically() {
    let a = out_dir("a");
    let b = out_dir("b");
    for d in [&a, &b] {
        let o = lmdc(&[
            "build",
            "examples/twisted_duct.lmd",
            "-o",
            d.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    }
    let files = listing(&a);
    assert!(files.iter().any(|f| f.ends_with(".src")), "{files:?}");
    assert!(files.iter().any(|f| f.ends_with(".dat")), "{files:?}");
    assert!(files.iter().any(|f| f.ends_with(".ngc")), "{files:?}");
    assert!(
        !files
            .iter()
            .any(|f| f.starts_with('.') && f != ".lmdc-manifest"),
        "temporary files left: {files:?}"
    );
    assert_eq!(files, listing(&b));
    #[cfg(unix)]
    for f in &files {
        use std::os::unix::fs::PermissionsExt;
        let mode = std::fs::metadata(a.join(f)).unwrap().permissions().mode();
        assert_eq!(
            mode & 0o644,
            0o644,
            "{f} is not readable by the cell's operators: {mode:o}"
        );
    }
    for f in &files {
        assert_eq!(
            std::fs::read(a.join(f)).unwrap(),
            std::fs::read(b.join(f)).unwrap(),
            "{f} differs"
        );
    }
    let _ = std::fs::remove_dir_all(&a);
    let _ = std::fs::remove_dir_all(&b);
}

#[test]
fn machine_selection_and_ir() {
    let d = out_dir("ir");
    let o = lmdc(&[
        "build",
        "examples/twisted_duct.lmd",
        "-o",
        d.to_str().unwrap(),
        "--machine",
        "dmu5",
        "--emit",
        "ir",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let files = listing(&d);
    assert!(files.iter().all(|f| !f.ends_with(".src")), "{files:?}");
    assert!(
        files.contains(&"twisted_duct.ir.json".to_string()),
        "{files:?}"
    );
    let ir: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.join("twisted_duct.ir.json")).unwrap()).unwrap();
    assert_eq!(ir["format"], "lmdc-ir");
    // A plan with a bead model is written as version 4: its layer heights
    // are what the model stacks (A/pitch), each point says its pitch and rise.
    assert_eq!(ir["version"], lmdc::ir::VERSION);
    assert_eq!(ir["bead"]["basis"]["kind"], "track");
    assert!(
        ir["layers"][3]["paths"][0]["points"][0]["rise"]
            .as_f64()
            .unwrap()
            > 0.0
    );
    assert_eq!(ir["part"], "twisted_duct");
    assert_eq!(ir["units"]["speed"], "mm/s");
    let layer = &ir["layers"][3];
    assert_eq!(layer["index"], 3);
    for k in ["origin", "x", "y", "z"] {
        assert_eq!(layer["frame"][k].as_array().unwrap().len(), 3);
    }
    let p = &layer["paths"][0]["points"][0];
    for k in [
        "pos",
        "normal",
        "tangent",
        "layer_height",
        "speed",
        "power",
        "powder",
        "defocus",
        "laser_on",
    ] {
        assert!(!p[k].is_null(), "point lacks {k}");
    }
    // The IR reads back into the compiler's own type.
    let back: lmdc::ir::Program = serde_json::from_value(ir).unwrap();
    assert!(back.point_count() > 0);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn failures_write_nothing_and_exit_by_kind() {
    let d = out_dir("fail");
    let o = lmdc(&[
        "build",
        "examples/errors/unit_mismatch.lmd",
        "-o",
        d.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(!d.exists(), "output directory created for a failed build");

    let o = lmdc(&[
        "build",
        "examples/twisted_duct.lmd",
        "-o",
        d.to_str().unwrap(),
        "--machine",
        "nope",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("kr60"), "{}", stderr(&o));
    assert!(!d.exists());

    let o = lmdc(&["build", "no/such/file.lmd", "-o", d.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let o = lmdc(&["build", "examples", "-o", d.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let o = lmdc(&["frobnicate"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(!d.exists());
}

#[test]
fn bad_template_directory_override_is_a_usage_error() {
    let t = out_dir("tpl");
    std::fs::create_dir_all(t.join("gcode")).unwrap();
    std::fs::write(t.join("gcode/header.tera"), "{% if %}").unwrap();
    let d = out_dir("tplout");
    let o = lmdc(&[
        "build",
        "examples/twisted_duct.lmd",
        "-o",
        d.to_str().unwrap(),
        "--templates",
        t.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("gcode/header.tera"), "{}", stderr(&o));
    assert!(!d.exists());
    let _ = std::fs::remove_dir_all(&t);
}

#[test]
fn timings_report_every_stage() {
    let d = out_dir("timings");
    let o = lmdc(&[
        "build",
        "examples/twisted_duct.lmd",
        "-o",
        d.to_str().unwrap(),
        "--timings",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let text = stderr(&o);
    for stage in [
        "parse",
        "check",
        "slice",
        "verify",
        "emit KRL",
        "emit G-code",
        "write",
        "total",
    ] {
        assert!(
            text.lines().any(|l| l.starts_with(stage)),
            "no {stage} row in\n{text}"
        );
    }
    assert!(
        text.contains("peak heap") && text.contains("per point"),
        "{text}"
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// `--templates` that is not a template directory is a usage error: the
/// built-in templates in place of a site's own preamble must not pass
/// unnoticed.
#[test]
fn template_directory_that_is_no_template_directory() {
    let d = out_dir("tpl-missing-out");
    let empty = out_dir("tpl-empty");
    std::fs::create_dir_all(empty.join("krl")).unwrap();
    let misspelt = out_dir("tpl-misspelt");
    std::fs::create_dir_all(misspelt.join("krl")).unwrap();
    std::fs::write(misspelt.join("krl/main.tera"), "x").unwrap();
    let flat = out_dir("tpl-flat");
    std::fs::create_dir_all(&flat).unwrap();
    std::fs::write(flat.join("main.src.tera"), "x").unwrap();
    for (dir, want) in [
        (PathBuf::from("/no/such/dir"), "/no/such/dir"),
        (empty.clone(), "holds none of lmdc's templates"),
        (misspelt.clone(), "no template called krl/main.tera"),
        (flat.clone(), "no template called main.src.tera"),
    ] {
        let o = lmdc(&[
            "build",
            "examples/twisted_duct.lmd",
            "-o",
            d.to_str().unwrap(),
            "--templates",
            dir.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        assert!(stderr(&o).contains(want), "{}", stderr(&o));
        assert!(!d.exists());
    }
    for t in [empty, misspelt, flat] {
        let _ = std::fs::remove_dir_all(t);
    }
}

/// The input is read with a hard cap, whatever the file says its size is.
#[cfg(unix)]
#[test]
fn endless_input_is_cut_at_the_cap() {
    let start = std::time::Instant::now();
    let o = lmdc(&["check", "/dev/zero"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("larger than 16 MB"), "{}", stderr(&o));
    assert!(start.elapsed() < std::time::Duration::from_secs(30));
    // A pipe that never ends.
    let mut child = Command::new(env!("CARGO_BIN_EXE_lmdc"))
        .args(["check", "/dev/stdin"])
        .stdin(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut input = child.stdin.take().unwrap();
    let writer = std::thread::spawn(move || {
        use std::io::Write;
        let block = vec![b' '; 1 << 16];
        // Stops when lmdc closes the pipe.
        while input.write_all(&block).is_ok() {}
    });
    let o = child.wait_with_output().unwrap();
    writer.join().unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("larger than 16 MB"), "{}", stderr(&o));
}

/// A byte order mark, CRLF and CR-only line ends all compile to the same
/// programs.
#[test]
fn bom_and_every_line_end_compile() {
    let lf = std::fs::read_to_string("examples/sprocket_tooth.lmd").unwrap();
    let dir = out_dir("line-ends");
    std::fs::create_dir_all(&dir).unwrap();
    let mut outputs = Vec::new();
    for (tag, src) in [
        ("lf", lf.clone()),
        ("bom", format!("\u{feff}{lf}")),
        ("crlf", lf.replace('\n', "\r\n")),
        ("cr", format!("\u{feff}{}", lf.replace('\n', "\r"))),
    ] {
        let file = dir.join(format!("{tag}.lmd"));
        std::fs::write(&file, src).unwrap();
        let out = dir.join(tag);
        let o = lmdc(&["build", file.to_str().unwrap(), "-o", out.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(0), "{tag}: {}", stderr(&o));
        let files: Vec<(String, Vec<u8>)> = listing(&out)
            .into_iter()
            .filter(|f| !f.starts_with('.'))
            .map(|f| {
                let bytes = std::fs::read(out.join(&f)).unwrap();
                (f, without_provenance(bytes))
            })
            .collect();
        outputs.push((tag, files));
    }
    for (tag, files) in &outputs[1..] {
        assert!(
            *files == outputs[0].1,
            "{tag} builds other programs than LF"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Escape sequences in the source never reach the terminal, from the snippet
/// or from a message that quotes a name.
#[test]
fn diagnostics_print_no_control_characters() {
    let dir = out_dir("escapes");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("bad.lmd");
    std::fs::write(
        &file,
        "part \"\x1b]0;pwned\x07\"\nlet a = \"\x1b[2J\" + 1 mm\n\x1b[31m = 2\n",
    )
    .unwrap();
    let o = lmdc(&["check", file.to_str().unwrap(), "--color", "never"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let text = stderr(&o);
    assert!(
        !text.chars().any(|c| c.is_control() && c != '\n'),
        "{text:?}"
    );
    assert!(text.contains("␛[2J"), "{text}");
    // Nor from a file name.
    let o = lmdc(&["check", "no\x1b[31msuch\x07.lmd"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("no␛[31msuch␇.lmd"), "{}", stderr(&o));
    let _ = std::fs::remove_dir_all(&dir);
}

/// The non-hidden files of `dir` and their bytes.
fn contents(dir: &Path) -> Vec<(String, Vec<u8>)> {
    listing(dir)
        .into_iter()
        .filter(|f| !f.starts_with('.'))
        .map(|f| {
            let bytes = std::fs::read(dir.join(&f)).unwrap();
            (f, without_provenance(bytes))
        })
        .collect()
}

/// A program without its header's provenance line (which names the source
/// file and its sha256: other files, other lines): the rest is what the
/// machine runs. tests/cli_ci.rs tests that line.
fn without_provenance(bytes: Vec<u8>) -> Vec<u8> {
    let Ok(text) = String::from_utf8(bytes.clone()) else {
        return bytes;
    };
    text.split_inclusive('\n')
        .filter(|l| !l.contains(", sha256 "))
        .collect::<String>()
        .into_bytes()
}

/// The twisted duct, quick to build, its robot's program cut into modules of
/// `lines` motions.
fn duct_in_modules(dir: &Path, lines: u32) -> PathBuf {
    let src = std::fs::read_to_string("examples/twisted_duct.lmd")
        .unwrap()
        .replace("points = 360", "points = 24")
        .replace(
            "max_speed = 250 mm/s",
            &format!("max_speed = 250 mm/s\n  module_lines = {lines}"),
        );
    assert!(src.contains("module_lines"));
    std::fs::create_dir_all(dir).unwrap();
    let file = dir.join(format!("duct{lines}.lmd"));
    std::fs::write(&file, src).unwrap();
    file
}

/// A rebuild replaces a machine's whole set of files: with fewer KRL modules
/// the old extra modules go; another machine's files, files the user put
/// there and files of another part stay; temporary files a killed build of
/// an older lmdc left are removed.
#[test]
fn a_rebuild_replaces_the_whole_set() {
    let work = out_dir("sets");
    let many = duct_in_modules(&work, 10);
    let few = duct_in_modules(&work, 40);
    let out = work.join("out");
    let fresh = work.join("fresh");
    let build = |file: &Path, dir: &Path, extra: &[&str]| {
        let mut args = vec!["build", file.to_str().unwrap(), "-o", dir.to_str().unwrap()];
        args.extend_from_slice(extra);
        let o = lmdc(&args);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    };
    build(&many, &out, &[]);
    let before = listing(&out);
    assert!(
        before.iter().any(|f| f.ends_with("_m500.src")),
        "{} files",
        before.len()
    );
    std::fs::write(out.join("notes.txt"), "the operator's").unwrap();
    std::fs::write(out.join("twisted_duct_kr60_m9999.src"), "not lmdc's").unwrap();
    std::fs::write(out.join(".lmdc-a1b2c3.tmp"), vec![0u8; 4096]).unwrap();
    let other = work.join("other.lmd");
    std::fs::write(
        &other,
        std::fs::read_to_string(&few)
            .unwrap()
            .replace("part twisted_duct", "part other_duct"),
    )
    .unwrap();
    build(&other, &out, &["--machine", "dmu5"]);

    // Only the robot, with a quarter of the modules.
    build(&few, &out, &["--machine", "kr60"]);
    build(&few, &fresh, &[]);
    let mut want = contents(&fresh);
    want.push((
        "notes.txt".into(),
        std::fs::read(out.join("notes.txt")).unwrap(),
    ));
    want.push((
        "other_duct_dmu5.ngc".into(),
        without_provenance(std::fs::read(out.join("other_duct_dmu5.ngc")).unwrap()),
    ));
    want.push(("twisted_duct_kr60_m9999.src".into(), b"not lmdc's".to_vec()));
    want.sort();
    // The CNC program of the first build is still the first build's: the
    // same bytes as the fresh one's but for the provenance line (the
    // sources differ), since only module_lines changed.
    assert_eq!(contents(&out), want);
    assert_eq!(
        listing(&out)
            .iter()
            .filter(|f| f.starts_with('.'))
            .collect::<Vec<_>>(),
        [".lmdc-manifest"],
        "temporary files left"
    );
    let _ = std::fs::remove_dir_all(&work);
}

/// `lmdc simulate`: the loop's numbers on stdout, the CSV where asked, exit 1
/// for a loop the build refuses (still simulated) and for a file with no loop.
#[test]
fn simulate_prints_the_loop_and_writes_its_csv() {
    let dir = out_dir("simulate");
    std::fs::create_dir_all(&dir).unwrap();
    let csv = dir.join("loop.csv");
    let o = lmdc(&[
        "simulate",
        "examples/segmented_ring.lmd",
        "--csv",
        csv.to_str().unwrap(),
        "--every",
        "65",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout);
    for want in [
        "130 layers × 10 segments",
        "kp = -3 (mm/s)/mm, ki = -0.35 (mm/s)/mm",
        "after 130 layers (target 29.900 mm):",
        "largest error: segment 5, +0.038 mm",
    ] {
        assert!(text.contains(want), "{want:?} in\n{text}");
    }
    // Layers 1, 65 and 130, ten segments each.
    let rows = text
        .lines()
        .filter(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            w.len() == 6 && w[0].parse::<usize>().is_ok()
        })
        .count();
    assert_eq!(rows, 30, "{text}");
    let data = std::fs::read_to_string(&csv).unwrap();
    assert_eq!(data.lines().count(), 1 + 130 * 10);
    assert!(stderr(&o).contains("wrote"), "{}", stderr(&o));
    assert_eq!(
        listing(&dir),
        vec!["loop.csv".to_string()],
        "no temporary file left"
    );

    // A loop the build refuses: simulated and shown, exit 1, no CSV.
    let refused = dir.join("refused.csv");
    let unstable = lmdc(&[
        "simulate",
        "examples/errors/unstable_loop.lmd",
        "--csv",
        refused.to_str().unwrap(),
    ]);
    assert_eq!(unstable.status.code(), Some(1));
    let text = String::from_utf8_lossy(&unstable.stdout);
    assert!(text.contains("error: unstable"), "{text}");
    assert!(!refused.exists(), "a refused loop writes no CSV");
    assert!(
        stderr(&unstable).contains("refused.csv not written"),
        "{}",
        stderr(&unstable)
    );

    // A valid file without a ring: a usage error, not an error in the file.
    let none = lmdc(&["simulate", "examples/wedge.lmd"]);
    assert_eq!(none.status.code(), Some(2));
    assert!(
        stderr(&none).contains("nothing to simulate"),
        "{}",
        stderr(&none)
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Two parts whose KRL names come out the same (a name keeps 24
/// characters, the part's shortened first) are not built into one folder:
/// the second build is refused (exit 2) naming both parts, and the first
/// part's programs and the manifest stay as they were, byte for byte.
#[test]
fn a_part_whose_krl_names_clash_with_another_s_is_refused() {
    let work = out_dir("clash");
    std::fs::create_dir_all(&work).unwrap();
    let src = std::fs::read_to_string("examples/flange.lmd").unwrap();
    let file = |name: &str| {
        let f = work.join(format!("{name}.lmd"));
        std::fs::write(&f, src.replacen("part flange", &format!("part {name}"), 1)).unwrap();
        f
    };
    let (x, y) = (
        file("a_very_long_part_name_x"),
        file("a_very_long_part_name_y"),
    );
    let out = work.join("out");
    let build = |f: &Path| {
        lmdc(&[
            "build",
            f.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--machine",
            "kr30",
        ])
    };
    let first = build(&x);
    assert_eq!(first.status.code(), Some(0), "{}", stderr(&first));
    let files = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| {
            let p = e.unwrap().path();
            (p.clone(), std::fs::read(&p).unwrap())
        })
        .collect::<Vec<_>>();
    assert!(files.len() >= 3, "{files:?}");
    let second = build(&y);
    assert_eq!(second.status.code(), Some(2), "{}", stderr(&second));
    let e = stderr(&second);
    assert!(
        e.contains("holds the programs of part `a_very_long_part_name_x` on `kr30`")
            && e.contains("part `a_very_long_part_name_y` on `kr30` would replace them"),
        "{e}"
    );
    for (p, bytes) in &files {
        assert_eq!(&std::fs::read(p).unwrap(), bytes, "{} changed", p.display());
    }
    assert_eq!(listing(&out).len(), files.len(), "{:?}", listing(&out));
    let _ = std::fs::remove_dir_all(&work);
}
