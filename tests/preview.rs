//! The plan preview: self-contained, deterministic, decimated past its
//! budget, and drawn by a real browser — headless Chromium renders the page
//! of an example; the screenshot must show the part in colour and the page's
//! own account (its title and `#summary`) the layer count of the plan.
//! Without Chromium the browser test says it skipped; under CI it fails.
//! `LMDC_UPDATE_SCREENSHOTS=1` renders every example into docs/preview/.

#[path = "support/png.rs"]
mod png;
#[path = "support/skip.rs"]
mod skip;

use lmdc::pipeline::compile;
use lmdc::preview;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn page(example: &str, budget: usize) -> (String, usize) {
    let src = std::fs::read_to_string(format!("examples/{example}.lmd")).unwrap();
    let p = compile(&src, &mut ()).program.expect("compiles");
    let m = p.machines().next().unwrap();
    (preview::html_within(m, budget), p.ir().layers.len())
}

/// The JSON object the page carries.
fn data(page: &str) -> Value {
    let start = page
        .find(r#"<script id="data" type="application/json">"#)
        .unwrap();
    let rest = &page[start..];
    let json = &rest[rest.find('>').unwrap() + 1..rest.find("</script>").unwrap()];
    serde_json::from_str(json).expect("the page's data is JSON")
}

#[test]
fn the_page_is_self_contained_and_deterministic() {
    let (a, layers) = page("twisted_duct", preview::BUDGET);
    let (b, _) = page("twisted_duct", preview::BUDGET);
    assert!(a == b, "same plan, same bytes");
    for no in [
        "http://",
        "https://",
        "<script src",
        "<link",
        "@import",
        "url(",
    ] {
        assert!(!a.contains(no), "the page loads `{no}`");
    }
    let d = data(&a);
    assert_eq!(d["meta"]["layers"], layers);
    assert_eq!(d["meta"]["decimation"], serde_json::json!([1, 1]));
    assert_eq!(d["meta"]["kept"], d["meta"]["moves"]);
    // 70 000 points in about 1.3 MB.
    assert!(a.len() < 2_000_000, "{} bytes", a.len());
}

#[test]
fn past_the_budget_every_kth_layer_and_move_is_kept() {
    let (p, layers) = page("twisted_duct", 10_000);
    let d = data(&p);
    let moves = d["meta"]["moves"].as_u64().unwrap() as usize;
    // The same stride k across layers and along paths, the smallest with
    // moves / k² within 10 000 (the duct's plan changes with its slicing:
    // the test holds for any).
    let k = d["meta"]["decimation"][0].as_u64().unwrap() as usize;
    assert_eq!(d["meta"]["decimation"], serde_json::json!([k, k]));
    assert!(k > 1, "{moves} moves fit 10 000 undecimated");
    assert!(moves.div_ceil(k * k) <= 10_000 && moves.div_ceil((k - 1) * (k - 1)) > 10_000);
    // Every k-th layer from the first, and the last.
    let starts = d["meta"]["starts"].as_array().unwrap();
    let every_kth = (layers - 1) / k + 1;
    let last_extra = usize::from((layers - 1) % k != 0);
    assert_eq!(starts.len(), every_kth + last_extra);
    assert_eq!(starts.last().unwrap()[0], layers, "the last layer is kept");
    let kept = d["meta"]["kept"].as_u64().unwrap() as usize;
    assert!(kept <= 10_000 + 10 * starts.len(), "{kept}");
}

#[test]
fn the_command_writes_the_page_atomically_where_asked() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("sub/duct.html");
    let run = || {
        Command::new(env!("CARGO_BIN_EXE_lmdc"))
            .args(["preview", "examples/ramp_wall.lmd", "-o"])
            .arg(&out)
            .output()
            .unwrap()
    };
    let o = run();
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let first = std::fs::read(&out).unwrap();
    assert_eq!(run().status.code(), Some(0));
    assert_eq!(std::fs::read(&out).unwrap(), first, "deterministic bytes");
    let names: Vec<_> = std::fs::read_dir(out.parent().unwrap()).unwrap().collect();
    assert_eq!(names.len(), 1, "no temporary file left");
}

fn chromium() -> Option<PathBuf> {
    if let Some(p) = std::env::var_os("LMDC_CHROMIUM") {
        return Some(p.into());
    }
    ["/usr/bin/chromium", "/usr/bin/chromium-browser"]
        .iter()
        .map(PathBuf::from)
        .find(|p| p.exists())
}

/// Runs headless Chromium on `page` with `args`, in a fresh profile, with
/// every background connection off (the machine has no network), for at
/// most two minutes. Its output goes through files: the DOM of a page with
/// its data inline is megabytes, more than a pipe holds unread.
fn browse(chromium: &Path, page: &Path, args: &[&str]) -> Output {
    let profile = tempfile::tempdir().unwrap();
    let out = profile.path().join("stdout");
    let err = profile.path().join("stderr");
    let mut child = Command::new(chromium)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--hide-scrollbars",
            "--window-size=1280,1000",
        ])
        .arg(format!("--user-data-dir={}", profile.path().display()))
        .args(args)
        .arg(format!("file://{}", page.display()))
        .stdout(Stdio::from(std::fs::File::create(&out).unwrap()))
        .stderr(Stdio::from(std::fs::File::create(&err).unwrap()))
        .spawn()
        .expect("chromium starts");
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(120) {
            let _ = child.kill();
            panic!("chromium did not finish in 2 minutes");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    Output {
        status: child.wait().unwrap(),
        stdout: std::fs::read(&out).unwrap_or_default(),
        stderr: std::fs::read(&err).unwrap_or_default(),
    }
}

/// Renders `example`'s preview; checks the DOM and the screenshot; returns
/// the screenshot's bytes.
fn render(chromium: &Path, example: &str) -> Vec<u8> {
    let dir = tempfile::tempdir().unwrap();
    let (html, layers) = page(example, preview::BUDGET);
    let file = dir.path().join(format!("{example}.html"));
    std::fs::write(&file, html).unwrap();

    let o = browse(chromium, &file, &["--dump-dom"]);
    let dom = String::from_utf8_lossy(&o.stdout);
    assert!(
        dom.contains(&format!(": {layers} layers</title>")),
        "{example}: the title does not give {layers} layers:\n{}",
        &dom[..dom.len().min(400)]
    );
    assert!(
        dom.contains(&format!(r#"data-layers="{layers}""#)),
        "{example}"
    );
    let painted: usize = dom
        .split(r#"data-painted=""#)
        .nth(1)
        .and_then(|s| s.split('"').next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("{example}: the view reported nothing painted"));
    assert!(painted > 1000, "{example}: {painted} pixels painted");

    let shot = dir.path().join("shot.png");
    let o = browse(
        chromium,
        &file,
        &[&format!("--screenshot={}", shot.display())],
    );
    let bytes = std::fs::read(&shot).unwrap_or_else(|e| {
        panic!(
            "{example}: no screenshot ({e}): {}",
            String::from_utf8_lossy(&o.stderr)
        )
    });
    let img = png::decode(&bytes).unwrap();
    assert_eq!((img.width, img.height), (1280, 1000));
    // Coloured pixels (not white, grey or black text) in the view.
    let coloured = img
        .rgb
        .iter()
        .filter(|p| p.iter().max().unwrap() - p.iter().min().unwrap() > 40)
        .count();
    assert!(
        coloured > 5000,
        "{example}: the screenshot is blank ({coloured} coloured pixels)"
    );
    bytes
}

#[test]
fn chromium_draws_the_examples() {
    let Some(chromium) = chromium() else {
        skip::skip(
            "chromium_draws_the_examples",
            "chromium",
            "apt-get install chromium, or set LMDC_CHROMIUM",
        );
        return;
    };
    let update = std::env::var_os("LMDC_UPDATE_SCREENSHOTS").is_some();
    // Updating draws every example (one screenshot each in docs/preview/);
    // a test run draws two.
    let all: Vec<String> = {
        let mut v: Vec<String> = std::fs::read_dir("examples")
            .unwrap()
            .filter_map(|e| {
                let name = e.ok()?.file_name().into_string().ok()?;
                name.strip_suffix(".lmd").map(str::to_string)
            })
            .collect();
        v.sort();
        v
    };
    let examples: Vec<&str> = if update {
        all.iter().map(String::as_str).collect()
    } else {
        vec!["twisted_duct", "styled_chord"]
    };
    for example in examples {
        let shot = render(&chromium, example);
        if update {
            std::fs::create_dir_all("docs/preview").unwrap();
            std::fs::write(format!("docs/preview/{example}.png"), shot).unwrap();
        }
    }
}
