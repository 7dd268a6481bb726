//! `kill -9` during `lmdc build`, at random points, many times: the output
//! directory holds the previous build's files or the new build's, never a mix
//! of both (src/cli/sink.rs says how). After each kill:
//!
//! - right away, every program file in the directory is one of the old set
//!   (same bytes) or every one is of the new set; a set that is incomplete
//!   has the interrupted build's journal beside it;
//! - the next lmdc run in the directory (here a build that fails on a syntax
//!   error) leaves exactly the old set or exactly the new set, with a
//!   manifest listing it and no temporary file;
//! - a build after that succeeds and leaves exactly its own set.
//!
//! `LMDC_KILL_ROUNDS` sets the number of kills (default 6, CI runs 24: half at a random
//! moment of the build, half just after its commit point, in the middle of
//! the renames).
#![cfg(unix)]

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

type Files = BTreeMap<String, Vec<u8>>;

fn lmdc() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_lmdc"));
    c.env("NO_COLOR", "1");
    c
}

fn build(file: &Path, out: &Path) -> std::process::Output {
    lmdc()
        .args(["build", file.to_str().unwrap(), "-o", out.to_str().unwrap()])
        .output()
        .unwrap()
}

/// The program files of `dir` (not the hidden ones) and their bytes.
fn programs(dir: &Path) -> Files {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap())
        .filter(|e| !e.file_name().to_string_lossy().starts_with('.'))
        .map(|e| {
            (
                e.file_name().to_string_lossy().into_owned(),
                std::fs::read(e.path()).unwrap(),
            )
        })
        .collect()
}

fn hidden(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.'))
        .collect();
    v.sort();
    v
}

/// Whether every file of `seen` is in `set` with the same bytes.
fn within(seen: &Files, set: &Files) -> bool {
    seen.iter().all(|(n, b)| set.get(n) == Some(b))
}

/// The files the manifest of `dir` says lmdc wrote there.
fn manifest(dir: &Path) -> Vec<String> {
    let m: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join(".lmdc-manifest")).unwrap()).unwrap();
    let mut v: Vec<String> = m["sets"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|s| s["files"].as_array().unwrap().iter())
        .map(|f| f.as_str().unwrap().to_string())
        .collect();
    v.sort();
    v
}

fn copy_dir(from: &Path, to: &Path) {
    let _ = std::fs::remove_dir_all(to);
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        std::fs::copy(e.path(), to.join(e.file_name())).unwrap();
    }
}

/// xorshift64*: random kill points without a dependency; the seed is printed.
struct Rng(u64);

impl Rng {
    fn below(&mut self, n: u64) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) % n.max(1)
    }
}

/// The duct with few points (quick) and its robot's program in modules of
/// `lines` motions: hundreds of KRL files.
fn duct(dir: &Path, points: u32, lines: u32) -> PathBuf {
    let src = std::fs::read_to_string("examples/twisted_duct.lmd")
        .unwrap()
        .replace("points = 360", &format!("points = {points}"))
        .replace(
            "max_speed = 250 mm/s",
            &format!("max_speed = 250 mm/s\n  module_lines = {lines}"),
        );
    assert!(src.contains("module_lines") && src.contains(&format!("points = {points}")));
    let file = dir.join(format!("duct_{points}_{lines}.lmd"));
    std::fs::write(&file, src).unwrap();
    file
}

#[derive(Debug, Default)]
struct Seen {
    old: usize,
    new: usize,
    partial: usize,
}

#[test]
fn a_killed_build_leaves_the_old_set_or_the_new_set() {
    let work = std::env::temp_dir().join(format!("lmdc-kill-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&work);
    std::fs::create_dir_all(&work).unwrap();
    // Every file differs between the two (fewer points), and the new build
    // writes fewer KRL modules than the old one.
    let old_src = duct(&work, 24, 10);
    let new_src = duct(&work, 20, 14);
    let broken = work.join("broken.lmd");
    std::fs::write(&broken, "part p\nlet = 1\n").unwrap();

    let reference_old = work.join("old");
    let reference_new = work.join("new");
    let o = build(&old_src, &reference_old);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let start = Instant::now();
    let o = build(&new_src, &reference_new);
    let full = start.elapsed();
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let old = programs(&reference_old);
    let new = programs(&reference_new);
    assert!(
        old.len() > 600 && new.len() < old.len(),
        "{} {}",
        old.len(),
        new.len()
    );
    assert!(old
        .iter()
        .all(|(n, b)| new.get(n) != Some(b) || n.ends_with(".dat")));

    let rounds: u64 = std::env::var("LMDC_KILL_ROUNDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(6);
    let seed = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .unwrap()
        .as_nanos() as u64
        | 1;
    eprintln!("kill test: seed {seed}, {rounds} rounds, a full build takes {full:?}");
    let mut rng = Rng(seed);
    let dir = work.join("out");
    let journal = dir.join(".lmdc-staging").join("journal");
    let mut seen = Seen::default();
    for round in 0..rounds {
        copy_dir(&reference_old, &dir);
        let mut child = lmdc()
            .args([
                "build",
                new_src.to_str().unwrap(),
                "-o",
                dir.to_str().unwrap(),
            ])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        let t0 = Instant::now();
        if round % 2 == 0 {
            // Anywhere in the build.
            let at = Duration::from_micros(rng.below(full.as_micros() as u64 + 1));
            while t0.elapsed() < at && child.try_wait().unwrap().is_none() {
                std::thread::sleep(Duration::from_micros(200));
            }
        } else {
            // Just after the commit point, among the removals and renames.
            while !journal.exists() && child.try_wait().unwrap().is_none() {
                if t0.elapsed() > full * 20 + Duration::from_secs(60) {
                    panic!("the build never wrote its journal");
                }
            }
            let spin = Duration::from_micros(rng.below(4000));
            let t1 = Instant::now();
            while t1.elapsed() < spin {}
        }
        let _ = child.kill();
        let _ = child.wait();

        let now = programs(&dir);
        let tag = format!("round {round} (seed {seed})");
        if now == old {
            seen.old += 1;
        } else if now == new {
            seen.new += 1;
        } else {
            seen.partial += 1;
            assert!(
                within(&now, &old) || within(&now, &new),
                "{tag}: old and new files mixed: {} files, {} of the old set, {} of the new",
                now.len(),
                now.iter().filter(|(n, b)| old.get(*n) == Some(*b)).count(),
                now.iter().filter(|(n, b)| new.get(*n) == Some(*b)).count(),
            );
            assert!(
                journal.exists(),
                "{tag}: an incomplete set without a journal to finish it"
            );
        }

        // The next run finishes or undoes the killed build, even though it
        // fails itself.
        let o = build(&broken, &dir);
        assert_eq!(
            o.status.code(),
            Some(1),
            "{tag}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let after = programs(&dir);
        assert!(
            after == old || after == new,
            "{tag}: not a whole set after recovery"
        );
        assert_eq!(
            hidden(&dir),
            [".lmdc-manifest"],
            "{tag}: temporary files left"
        );
        assert_eq!(
            manifest(&dir),
            after.keys().cloned().collect::<Vec<_>>(),
            "{tag}: the manifest does not list the set"
        );
        if round % 4 == 3 {
            let o = build(&new_src, &dir);
            assert_eq!(
                o.status.code(),
                Some(0),
                "{tag}: {}",
                String::from_utf8_lossy(&o.stderr)
            );
            assert!(programs(&dir) == new, "{tag}: the next build's set");
            assert_eq!(
                hidden(&dir),
                [".lmdc-manifest"],
                "{tag}: temporary files left"
            );
        }
    }
    eprintln!("kill test: {seen:?}");
    assert!(
        seen.new < rounds as usize,
        "every build finished before it was killed: the test killed nothing"
    );
    let _ = std::fs::remove_dir_all(&work);
}

/// A build stages its programs while the arm's checks are still solving
/// every move (`pipeline::compile_then`): when those find an error, the
/// staged files go and the directory keeps the previous build's set, its
/// manifest, and nothing else.
#[test]
fn an_arm_error_found_while_staging_leaves_the_old_set() {
    let dir = std::env::temp_dir().join(format!("lmdc-arm-stage-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("out");
    let pinned = std::fs::read_to_string("examples/errors/arm_joint_limit.lmd").unwrap();
    // The same cell with the turn about the beam left to lmdc: it builds.
    let auto = pinned.replace("spin = 0 deg", "spin = auto");
    assert_ne!(auto, pinned);
    let (good, bad) = (dir.join("auto.lmd"), dir.join("pinned.lmd"));
    std::fs::write(&good, auto).unwrap();
    std::fs::write(&bad, pinned).unwrap();

    let first = build(&good, &out);
    assert!(
        first.status.success(),
        "{}",
        String::from_utf8_lossy(&first.stderr)
    );
    let before = programs(&out);
    assert!(before.keys().any(|n| n.ends_with(".src")), "{before:?}");
    let listed = manifest(&out);

    let second = build(&bad, &out);
    let err = String::from_utf8_lossy(&second.stderr);
    assert_eq!(second.status.code(), Some(1), "{err}");
    assert!(err.contains("lmd::joint-limit"), "{err}");
    assert!(!err.contains("wrote "), "{err}");
    assert_eq!(programs(&out), before);
    assert_eq!(manifest(&out), listed);
    assert_eq!(hidden(&out), [".lmdc-manifest"]);
    let _ = std::fs::remove_dir_all(&dir);
}
