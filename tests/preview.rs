//! The plan preview: self-contained, deterministic, decimated past its
//! budget, carrying each move's height error and path kind as the plan and
//! the IR give them, and drawn by a real browser — headless Chromium renders
//! the page of an example; the screenshot must show the part in colour and
//! the page's own account (its title and `#summary`) the layer count of the
//! plan; every colouring renders without a script error, and the scale bar
//! measures what the screenshot shows at three zooms. A robot arm's joint
//! plot carries the angles `Solver::solve` gives move by move, is drawn only
//! for an arm, and counts the layers near a limit. Without Chromium the
//! browser tests say they skipped; under CI they fail.
//! `LMDC_UPDATE_SCREENSHOTS=1` renders every example into docs/preview/.

use crate::support::{png, skip};

use lmdc::ir::{PathKind, Program};
use lmdc::pipeline::compile;
use lmdc::plan::{Move, Visit, Where};
use lmdc::preview;
use lmdc::verify::Verified;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn verified(example: &str) -> Verified {
    // The flange's raster ends all lie on round edges, where links are laid
    // with the laser off (fill::link); a square plate's are level, and turn.
    let src = match example {
        "square_plate" => std::fs::read_to_string("examples/flange.lmd")
            .unwrap()
            .replace(
                "  profile = ring\n",
                "  profile = rectangle(width = 80 mm, height = 60 mm)\n",
            ),
        _ => std::fs::read_to_string(format!("examples/{example}.lmd")).unwrap(),
    };
    compile(&src, &mut ()).program.expect("compiles")
}

/// The page of `example`'s first machine, and its layer count.
fn page(example: &str, budget: usize) -> (String, usize) {
    let p = verified(example);
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
    // 16 bytes a move and about 2 of its place, base64: about 25 bytes a
    // move on the page; the arm's links at most 36 bytes (48 in base64)
    // at each of `joints::POSES` moves.
    let kept = d["meta"]["kept"].as_u64().unwrap() as usize;
    let arm = 48 * kept.min(preview::joints::POSES);
    assert!(a.len() < 28 * kept + arm + 150_000, "{} bytes", a.len());
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

/// A move as the test sees it, from the plan and the IR (not the page).
struct Expected {
    to: [f64; 3],
    layer: usize,
    deposit: bool,
    /// `rise / layer_height − 1` of the point the deposit starts from, per
    /// cent, where a rise is predicted.
    error: Option<f64>,
    /// The IR's kind of the path the deposit is part of.
    path: Option<PathKind>,
}

struct Moves<'a> {
    ir: &'a Program,
    layer: usize,
    out: Vec<Expected>,
}

impl Visit for Moves<'_> {
    fn layer(&mut self, index: usize, _: &lmdc::ir::Layer) {
        self.layer = index;
    }

    fn motion(&mut self, m: &Move) {
        let deposit = m.deposits();
        let src = m.source();
        let point = src.point(self.ir).filter(|_| deposit);
        let path = match src {
            Where::Point { layer, path, .. } if deposit => {
                Some(self.ir.layers[layer].paths[path].kind)
            }
            _ => None,
        };
        self.out.push(Expected {
            to: m.to,
            layer: self.layer,
            deposit,
            error: point
                .filter(|p| p.rise > 0.0)
                .map(|p| (p.rise as f64 / p.layer_height as f64 - 1.0) * 100.0),
            path,
        });
    }
}

/// Every move of `example`'s first machine's plan.
fn expected(example: &str) -> (Vec<Expected>, usize) {
    let p = verified(example);
    let m = p.machines().next().unwrap();
    let mut v = Moves {
        ir: p.ir(),
        layer: 0,
        out: Vec::new(),
    };
    m.plan().walk(&mut v);
    (v.out, p.ir().layers.len())
}

/// Standard base64 (padded) back to bytes.
fn unbase64(text: &str) -> Vec<u8> {
    let value = |c: u8| match c {
        b'A'..=b'Z' => c - b'A',
        b'a'..=b'z' => c - b'a' + 26,
        b'0'..=b'9' => c - b'0' + 52,
        b'+' => 62,
        b'/' => 63,
        _ => panic!("not base64: {c}"),
    };
    let mut out = Vec::new();
    for quad in text.as_bytes().chunks(4) {
        let n = quad
            .iter()
            .take_while(|&&c| c != b'=')
            .fold(0u32, |n, &c| n << 6 | value(c) as u32);
        let digits = quad.iter().take_while(|&&c| c != b'=').count();
        let n = n << (6 * (4 - digits));
        out.extend_from_slice(&n.to_be_bytes()[1..digits]);
    }
    out
}

/// A 16-bit column of the page: each move's value, and half its step.
fn column(d: &Value, name: &str, k: usize) -> (Vec<f64>, f64) {
    let bytes = unbase64(d[name].as_str().unwrap());
    let lo = d["ranges"][k][0].as_f64().unwrap();
    let hi = d["ranges"][k][1].as_f64().unwrap();
    let step = (hi - lo) / 65535.0;
    let values = bytes
        .chunks(2)
        .map(|b| lo + u16::from_le_bytes([b[0], b[1]]) as f64 * step)
        .collect();
    (values, step / 2.0)
}

// The flag bits, as src/preview/encode.rs documents them.
const DEPOSIT: u8 = 1;
const PREDICTED: u8 = 4;
const KIND_SHIFT: u8 = 3;

#[test]
fn the_page_carries_each_moves_height_error() {
    // A variable top (errors of ±1.3 % along its speed segments), a flat
    // part laid at its plan (0), and a ring (nothing predicted).
    for example in ["ramp_cuboid", "flange", "segmented_ring"] {
        let (moves, layers) = expected(example);
        let (html, _) = page(example, preview::BUDGET);
        let d = data(&html);
        assert_eq!(d["meta"]["kept"], moves.len(), "{example}: every move");
        let flags = unbase64(d["flags"].as_str().unwrap());
        let (error, half_step) = column(&d, "error", 6);
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for (i, m) in moves.iter().enumerate() {
            assert_eq!(flags[i] & DEPOSIT != 0, m.deposit, "{example}: move {i}");
            assert_eq!(
                flags[i] & PREDICTED != 0,
                m.error.is_some(),
                "{example}: move {i} predicted"
            );
            if let Some(e) = m.error {
                assert!(
                    (error[i] - e).abs() <= half_step + 1e-9 * e.abs().max(1.0),
                    "{example}: move {i}: the page says {} %, the IR {e} %",
                    error[i]
                );
                (lo, hi) = (lo.min(e), hi.max(e));
            }
        }
        let predicted = moves.iter().filter(|m| m.error.is_some()).count();
        match example {
            "segmented_ring" => assert_eq!(predicted, 0, "a ring has no prediction"),
            _ => {
                assert_eq!(
                    predicted,
                    moves.iter().filter(|m| m.deposit).count(),
                    "{example}: every deposit predicted"
                );
                let r = &d["ranges"][6];
                assert!((r[0].as_f64().unwrap() - lo).abs() < 1e-9, "{example}: {r}");
                assert!((r[1].as_f64().unwrap() - hi).abs() < 1e-9, "{example}: {r}");
            }
        }
        if example == "ramp_cuboid" {
            assert!(hi > 0.5 && lo < -0.5, "errors to tell apart: {lo} .. {hi}");
        }

        // Each layer's mean, lowest and highest from every move.
        let per_layer = d["meta"]["layer_error"].as_array().unwrap();
        assert_eq!(per_layer.len(), layers, "{example}");
        for (l, row) in per_layer.iter().enumerate() {
            let errors: Vec<f64> = moves
                .iter()
                .filter(|m| m.layer == l)
                .filter_map(|m| m.error)
                .collect();
            if errors.is_empty() {
                assert!(row.is_null(), "{example}: layer {l}: {row}");
                continue;
            }
            let [mean, min, max] = [0, 1, 2].map(|k| row[k].as_f64().unwrap());
            let lowest = errors.iter().copied().fold(f64::INFINITY, f64::min);
            let highest = errors.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            assert!(
                (min - lowest).abs() <= 6e-4,
                "{example}: layer {l}: {min} {lowest}"
            );
            assert!(
                (max - highest).abs() <= 6e-4,
                "{example}: layer {l}: {max} {highest}"
            );
            assert!(min - 1e-3 <= mean && mean <= max + 1e-3, "{example}: {row}");
        }
        // The layers' numbers come from every move, decimated or not.
        let (small, _) = page(example, moves.len() / 5);
        let small = data(&small);
        assert_ne!(small["meta"]["decimation"], serde_json::json!([1, 1]));
        assert_eq!(small["meta"]["layer_error"], d["meta"]["layer_error"]);
    }
}

#[test]
fn the_page_classes_each_move_by_its_path() {
    for example in ["twisted_duct", "styled_chord", "square_plate"] {
        let (moves, _) = expected(example);
        let (html, _) = page(example, preview::BUDGET);
        let d = data(&html);
        let names: Vec<&str> = d["meta"]["kinds"]
            .as_array()
            .unwrap()
            .iter()
            .map(|n| n.as_str().unwrap())
            .collect();
        let kinds: Vec<&str> = unbase64(d["flags"].as_str().unwrap())
            .iter()
            .map(|f| names[(f >> KIND_SHIFT) as usize])
            .collect();
        assert_eq!(kinds.len(), moves.len());
        for (i, m) in moves.iter().enumerate() {
            let want: &[&str] = match m.path {
                None => &["travel"],
                Some(PathKind::Wall) => &["wall"],
                Some(PathKind::Contour) => &["contour"],
                Some(PathKind::Infill) => &["infill", "link"],
                Some(PathKind::Travel | PathKind::Lead) => &["travel"],
            };
            assert!(
                want.contains(&kinds[i]),
                "{example}: move {i} is {}, its path {:?}",
                kinds[i],
                m.path
            );
        }
        let count = |k: &str| kinds.iter().filter(|&&n| n == k).count();
        match example {
            "twisted_duct" => assert_eq!(count("wall"), moves.iter().filter(|m| m.deposit).count()),
            // Contours and tracks, not linked: no link.
            "styled_chord" => {
                assert!(count("contour") > 0 && count("infill") > 0);
                assert_eq!(count("link"), 0);
            }
            _ => {
                assert!(count("contour") > 0 && count("infill") > 0 && count("link") > 0);
                flange_links_join_tracks(&moves, &kinds);
            }
        }
    }
}

/// The flange's raster runs at 0° and 90° layer by layer, so a track moves
/// along x or along y only; a link goes from one raster line to the next,
/// across the raster, between two tracks. Told apart by geometry here, not
/// by the preview's rule.
fn flange_links_join_tracks(moves: &[Expected], kinds: &[&str]) {
    let delta = |i: usize| {
        let (a, b) = (moves[i - 1].to, moves[i].to);
        [b[0] - a[0], b[1] - a[1]]
    };
    let layers = moves.last().unwrap().layer + 1;
    for l in 0..layers {
        let in_layer = |i: &usize| moves[*i].layer == l && *i > 0;
        let tracks: Vec<usize> = (0..moves.len())
            .filter(in_layer)
            .filter(|&i| kinds[i] == "infill")
            .collect();
        // The axis the raster lines run along: every track move's other
        // coordinate stays put.
        let along = (0..2)
            .find(|&a| tracks.iter().all(|&i| delta(i)[1 - a].abs() < 1e-6))
            .unwrap_or_else(|| panic!("layer {l}: a track move crosses the raster"));
        let mut i = 1;
        while i < moves.len() {
            if !(in_layer(&i) && kinds[i] == "link") {
                i += 1;
                continue;
            }
            let start = i;
            let mut across = 0.0;
            while i < moves.len() && kinds[i] == "link" {
                across += delta(i)[1 - along];
                i += 1;
            }
            assert!(
                across.abs() > 0.1,
                "layer {l}: the link ending at move {i} stays on its raster line"
            );
            assert_eq!(
                kinds[start - 1],
                "infill",
                "layer {l}: a link follows a track"
            );
            assert_eq!(kinds[i], "infill", "layer {l}: a track follows a link");
        }
    }
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

/// Chromium, or `None` (the test `test` skipped; under CI a missing one
/// fails it).
fn chromium(test: &str) -> Option<PathBuf> {
    let found = match std::env::var_os("LMDC_CHROMIUM") {
        Some(p) => Some(p.into()),
        None => ["/usr/bin/chromium", "/usr/bin/chromium-browser"]
            .iter()
            .map(PathBuf::from)
            .find(|p| p.exists()),
    };
    if found.is_none() {
        skip::skip(
            test,
            "chromium",
            "apt-get install chromium, or set LMDC_CHROMIUM",
        );
    }
    found
}

/// Runs headless Chromium on `page` (at `#hash` when not empty) with
/// `args`, in a fresh profile, with every background connection off (the
/// machine has no network), for at most two minutes. Its output goes
/// through files: the DOM of a page with its data inline is megabytes, more
/// than a pipe holds unread.
fn browse(chromium: &Path, page: &Path, hash: &str, args: &[&str]) -> Output {
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
        .arg(format!(
            "file://{}{}{hash}",
            page.display(),
            if hash.is_empty() { "" } else { "#" }
        ))
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

    let (dom, bytes, img) = dom_and_screenshot(chromium, &file, "");
    assert!(
        dom.contains(&format!(": {layers} layers</title>")),
        "{example}: the title does not give {layers} layers:\n{}",
        &dom[..dom.len().min(400)]
    );
    assert!(
        dom.contains(&format!(r#"data-layers="{layers}""#)),
        "{example}"
    );
    let painted: usize = attr(&dom, "data-painted")
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("{example}: the view reported nothing painted"));
    assert!(painted > 1000, "{example}: {painted} pixels painted");

    // Coloured pixels (not white, grey or black text) in the view.
    let coloured = img.rgb.iter().filter(|p| coloured(p)).count();
    assert!(
        coloured > 5000,
        "{example}: the screenshot is blank ({coloured} coloured pixels)"
    );
    bytes
}

/// Not white, grey or black: the moves' colours (the substrate, travel,
/// text and the scale bar are greys).
fn coloured(p: &[u8; 3]) -> bool {
    p.iter().max().unwrap() - p.iter().min().unwrap() > 40
}

/// The DOM of `file` at `#hash` (checked as [`dom`] checks it) and its
/// screenshot, bytes and decoded, from one run of the browser (a run costs
/// most of a second to start).
fn dom_and_screenshot(chromium: &Path, file: &Path, hash: &str) -> (String, Vec<u8>, png::Image) {
    let dir = tempfile::tempdir().unwrap();
    let shot = dir.path().join("shot.png");
    let o = browse(
        chromium,
        file,
        hash,
        &["--dump-dom", &format!("--screenshot={}", shot.display())],
    );
    let bytes = std::fs::read(&shot).unwrap_or_else(|e| {
        panic!(
            "{}#{hash}: no screenshot ({e}): {}",
            file.display(),
            String::from_utf8_lossy(&o.stderr)
        )
    });
    let img = png::decode(&bytes).unwrap();
    assert_eq!((img.width, img.height), (1280, 1000));
    (checked_dom(o, file, hash), bytes, img)
}

/// The DOM of `file` at `#hash` after its scripts ran, checked for a script
/// error and for having run to its end.
fn dom(chromium: &Path, file: &Path, hash: &str) -> String {
    checked_dom(browse(chromium, file, hash, &["--dump-dom"]), file, hash)
}

/// The DOM a run of the browser dumped, checked as [`dom`] says.
fn checked_dom(o: Output, file: &Path, hash: &str) -> String {
    let dom = String::from_utf8_lossy(&o.stdout).into_owned();
    let at = format!("{}#{hash}", file.display());
    assert!(
        attr(&dom, "data-js-error").is_none(),
        "{at}: a script error: {:?}",
        attr(&dom, "data-js-error")
    );
    assert!(
        attr(&dom, "data-ready").is_some(),
        "{at}: the viewer did not run to its end:\n{}",
        &dom[..dom.len().min(400)]
    );
    dom
}

/// The value of the first attribute `name` in `dom`.
fn attr(dom: &str, name: &str) -> Option<String> {
    let rest = dom.split(&format!(r#" {name}=""#)).nth(1)?;
    Some(rest.split('"').next()?.to_string())
}

/// The number an attribute of `dom` holds.
fn number(dom: &str, name: &str) -> f64 {
    attr(dom, name)
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("no number {name}"))
}

/// The text of `dom`'s element whose opening tag starts with `open`, its
/// tags left out (up to the next `</div>` that closes it, approximately:
/// enough for the legend).
fn text_of(dom: &str, open: &str) -> String {
    let rest = &dom[dom.find(open).unwrap_or_else(|| panic!("no {open}"))..];
    let end = rest.find(r#"<div id="plots">"#).unwrap_or(rest.len());
    let mut out = String::new();
    let mut in_tag = false;
    for c in rest[..end].chars() {
        match c {
            '<' => in_tag = true,
            '>' => {
                in_tag = false;
                out.push(' ');
            }
            c if !in_tag => out.push(c),
            _ => {}
        }
    }
    out.replace("&amp;", "&")
}

#[test]
fn chromium_draws_every_colouring_without_a_script_error() {
    let Some(chromium) = chromium("chromium_draws_every_colouring_without_a_script_error") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    // The square plate (the flange's layers on a rectangle) has contours,
    // tracks and laser-on links; the flange every deposit laid at plan; the
    // ramp cuboid's errors vary; the ring has no prediction.
    for (example, mode) in [
        ("square_plate", "kind"),
        ("flange", "error"),
        ("ramp_cuboid", "error"),
        ("segmented_ring", "error"),
        ("segmented_ring", "kind"),
    ] {
        let (html, _) = page(example, preview::BUDGET);
        let file = dir.path().join(format!("{example}.html"));
        std::fs::write(&file, html).unwrap();
        let dom = dom(&chromium, &file, &format!("colour={mode}"));
        assert_eq!(attr(&dom, "data-ready").as_deref(), Some(mode), "{example}");
        assert_eq!(attr(&dom, "data-mode").as_deref(), Some(mode), "{example}");
        assert!(number(&dom, "data-painted") > 1000.0, "{example} {mode}");
        let legend = text_of(&dom, r#"<div id="legend""#);
        let (moves, _) = expected(example);
        let deposits = moves.iter().filter(|m| m.deposit).count();
        let travel = moves.len() - deposits;
        let want: Vec<String> = match (example, mode) {
            ("square_plate", "kind") => ["contour (", "infill (", "link ("]
                .iter()
                .map(|s| s.to_string())
                .chain([format!("travel, laser off ({travel} moves)")])
                .collect(),
            ("segmented_ring", "kind") => vec![
                format!("wall ({deposits} moves)"),
                format!("travel, laser off ({travel} moves)"),
            ],
            ("segmented_ring", "error") => vec![
                "−5 %".into(),
                "+5 %".into(),
                format!("no prediction ({deposits} moves)"),
            ],
            // At least ±5 %, symmetric; the plan's own extremes and bound.
            (_, _) => vec![
                "height error".into(),
                "−5 %".into(),
                "+5 %".into(),
                "lmd::deposit allows ±3.00 %".into(),
            ],
        };
        for w in want {
            assert!(
                legend.contains(&w),
                "{example} {mode}: no `{w}` in {legend}"
            );
        }
        if mode == "error" && example != "segmented_ring" {
            assert!(!legend.contains("no prediction"), "{example}: {legend}");
        }
    }
}

/// Whether `mm` is 1, 2 or 5 times a power of ten, within `tol` of it.
fn round_length(mm: f64, tol: f64) -> bool {
    let mantissa = mm / 10f64.powf(mm.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .iter()
        .any(|m| (mantissa / m - 1.0).abs() <= tol)
}

#[test]
fn the_scale_bar_measures_the_view_at_every_zoom() {
    let Some(chromium) = chromium("the_scale_bar_measures_the_view_at_every_zoom") else {
        return;
    };
    // Seen from the top, the flange's deposits span this much in x.
    let (moves, _) = expected("flange");
    let xs: Vec<f64> = (1..moves.len())
        .filter(|&i| moves[i].deposit)
        .flat_map(|i| [moves[i - 1].to[0], moves[i].to[0]])
        .collect();
    let span = xs.iter().copied().fold(f64::NEG_INFINITY, f64::max)
        - xs.iter().copied().fold(f64::INFINITY, f64::min);
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("flange.html");
    std::fs::write(&file, page("flange", preview::BUDGET).0).unwrap();
    let mut part = Vec::new();
    // Zooms whose bars differ (50, 20 and 10 mm here): a bar left as the
    // last zoom drew it would not measure a round length at the next.
    for zoom in [0.5, 1.0, 1.5] {
        let hash = format!("view=top&zoom={zoom}");
        // What the page says it drew, and what the screenshot shows.
        let (dom, _, img) = dom_and_screenshot(&chromium, &file, &hash);
        let (mm, px, ppm) = (
            number(&dom, "data-scale-mm"),
            number(&dom, "data-scale-px"),
            number(&dom, "data-px-per-mm"),
        );
        assert!(round_length(mm, 1e-9), "zoom {zoom}: a bar of {mm} mm");
        assert!((48.0..=120.5).contains(&px), "zoom {zoom}: {px} px");
        assert!(
            (px - mm * ppm).abs() < 0.1,
            "zoom {zoom}: {px} px for {mm} mm at {ppm}"
        );

        // What the screenshot shows: the view's rows (white, from its top
        // to the plots' grey), the deposits' coloured pixels in them left
        // of the legend, and the longest dark row near the left edge: the
        // bar.
        let top = number(&dom, "data-view-top") as usize;
        let at = |x: usize, y: usize| img.rgb[y * img.width + x];
        let bottom = (top + 1..img.height)
            .find(|&y| at(5, y) != [255; 3])
            .unwrap_or(img.height);
        let (mut lo, mut hi, mut bar) = (usize::MAX, 0, 0);
        for y in top..bottom {
            for x in 0..1000 {
                if coloured(&at(x, y)) {
                    (lo, hi) = (lo.min(x), hi.max(x));
                }
            }
            let dark = |x: usize| at(x, y).iter().all(|&c| c < 90);
            if let Some(start) = (8..30).find(|&x| dark(x)) {
                let end = (start..img.width).find(|&x| !dark(x)).unwrap();
                bar = bar.max(end - start);
            }
        }
        assert!(hi > lo, "zoom {zoom}: nothing coloured in the view");
        // Lines 1.6 px wide: the span is that much wider than the path.
        let drawn = (hi - lo + 1) as f64 - 1.6;
        let per_mm = drawn / span;
        // The bar's round caps add a pixel.
        let bar_mm = (bar as f64 - 1.0) / per_mm;
        assert!(
            (46..=124).contains(&bar) && round_length(bar_mm, 0.04),
            "zoom {zoom}: a bar {bar} px long is {bar_mm:.2} mm at the {per_mm:.3} px/mm \
             the deposits ({span:.1} mm, {drawn} px) are drawn at"
        );
        part.push(per_mm);
    }
    for (k, zoom) in [(1, 2.0), (2, 3.0)] {
        let ratio = part[k] / part[0];
        assert!((ratio / zoom - 1.0).abs() < 0.02, "zoom ×{zoom}: ×{ratio}");
    }
}

#[test]
fn chromium_draws_the_examples() {
    let Some(chromium) = chromium("chromium_draws_the_examples") else {
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
    // And the colourings docs/preview.md shows besides speed.
    if update {
        let dir = tempfile::tempdir().unwrap();
        for (example, mode) in [("flange", "kind"), ("ramp_cuboid", "error")] {
            let file = dir.path().join(format!("{example}.html"));
            std::fs::write(&file, page(example, preview::BUDGET).0).unwrap();
            let hash = format!("colour={mode}");
            let (_, shot, _) = dom_and_screenshot(&chromium, &file, &hash);
            std::fs::write(format!("docs/preview/{example}_{mode}.png"), shot).unwrap();
        }
        // And the bodies at a move, mid-build.
        let file = dir.path().join("flange.html");
        std::fs::write(&file, page("flange", preview::BUDGET).0).unwrap();
        let (_, shot, _) = dom_and_screenshot(&chromium, &file, "move=1200");
        std::fs::write("docs/preview/flange_bodies.png", shot).unwrap();
    }
}

/// The page of `example`'s machine `name`.
fn page_of(example: &str, name: &str) -> String {
    let p = verified(example);
    let m = p
        .machines()
        .find(|m| m.machine().name() == name)
        .expect("the machine is checked");
    preview::html(m)
}

/// Each layer's lowest and highest axis angles, solved here move by move as
/// the KRL writer solves a program: the tool turned where the normal
/// changes, each pose by `Solver::solve` from the solution before (from
/// home for the first), and on a LIN every 5 mm and 2° of turn between its
/// ends, as the controller moves along it — not the preview's chunked
/// `Follow`.
struct Angles {
    solver: lmdc::plan::arm::Solver,
    orient: lmdc::plan::orient::Orienter,
    normal: Option<[f32; 3]>,
    rot: nalgebra::Matrix3<f64>,
    prev: [f64; 6],
    last: Option<([f64; 3], nalgebra::UnitQuaternion<f64>)>,
    layer: usize,
    layers: Vec<Option<[[f64; 2]; 6]>>,
}

impl Angles {
    fn pose(&mut self, to: [f64; 3], rot: &nalgebra::Matrix3<f64>) {
        // The PTP from home takes the nearest solution, ties by the
        // documented rule (`Solver::home_solution`); every later pose the
        // nearest the one before.
        let j = match self.last {
            None => self.solver.home_solution(to, rot, &self.prev),
            Some(_) => self.solver.solve(to, rot, &self.prev).first().copied(),
        }
        .expect("a plan that built is within reach");
        self.prev = j;
        let r = self.layers[self.layer].get_or_insert([[f64::INFINITY, f64::NEG_INFINITY]; 6]);
        for (r, a) in r.iter_mut().zip(j) {
            *r = [r[0].min(a), r[1].max(a)];
        }
    }
}

impl Visit for Angles {
    fn layer(&mut self, index: usize, _: &lmdc::ir::Layer) {
        self.layer = index;
    }
    fn motion(&mut self, m: &Move) {
        if m.kind == lmdc::plan::MoveKind::Home {
            // Back to the home axes: no pose.
            return;
        }
        if self.normal != Some(m.normal) {
            self.normal = Some(m.normal);
            self.rot = self.orient.rotation(m.normal);
        }
        let q = nalgebra::UnitQuaternion::from_rotation_matrix(
            &nalgebra::Rotation3::from_matrix_unchecked(self.rot),
        );
        if let Some((from, q0)) = self.last {
            let d = nalgebra::distance(&from.into(), &m.to.into());
            let n = ((d / 5.0).max(q0.angle_to(&q).to_degrees() / 2.0) - 1e-9).ceil() as usize;
            for k in 1..n {
                let t = k as f64 / n as f64;
                let to = std::array::from_fn(|i| from[i] + t * (m.to[i] - from[i]));
                let rot = q0.slerp(&q, t).to_rotation_matrix().into_inner();
                self.pose(to, &rot);
            }
        }
        self.last = Some((m.to, q));
        let rot = self.rot;
        self.pose(m.to, &rot);
    }
}

#[test]
fn the_joint_plot_carries_the_angles_the_solver_gives() {
    // The duct's normal turns layer by layer (A4 to A6 move); the ramp wall
    // is flat. Both on a KR 60 HA.
    for (example, name) in [("twisted_duct", "kr60"), ("ramp_wall", "kr30")] {
        let p = verified(example);
        let m = p.machines().find(|m| m.machine().name() == name).unwrap();
        let lmdc::ir::Machine::Robot(r) = m.machine() else {
            panic!("{name} is a robot")
        };
        let mut want = Angles {
            solver: lmdc::plan::arm::Solver::new(r).expect("an arm"),
            orient: lmdc::plan::orient::Orienter::new(r.beam),
            normal: None,
            rot: nalgebra::Matrix3::identity(),
            prev: r.home,
            last: None,
            layer: 0,
            layers: vec![None; p.ir().layers.len()],
        };
        m.plan().walk(&mut want);
        let d = data(&preview::html(m));
        let arm = &d["meta"]["arm"];
        assert_eq!(arm["name"], "KR 60 HA", "{example}");
        assert_eq!(arm["limits"][4], serde_json::json!([-119.0, 119.0]));
        let got = arm["layers"].as_array().unwrap();
        assert_eq!(got.len(), want.layers.len(), "{example}: a range a layer");
        let mut turned = [0.0f64; 6];
        for (k, (g, w)) in got.iter().zip(&want.layers).enumerate() {
            let w = w.expect("every layer has moves");
            for a in 0..6 {
                for e in 0..2 {
                    let v = g[a][e].as_f64().unwrap();
                    assert!(
                        (v - w[a][e]).abs() < 1e-6,
                        "{example} layer {} A{}: page {v}, solver {}",
                        k + 1,
                        a + 1,
                        w[a][e]
                    );
                }
                turned[a] = turned[a].max(w[a][1] - w[a][0]);
            }
        }
        // The plot is not flat: the arm moves within layers.
        assert!(turned.iter().any(|t| *t > 1.0), "{example}: {turned:?}");
        assert_eq!(arm["unreachable"], 0);
    }
}

#[test]
fn a_robot_without_an_arm_has_no_joint_plot() {
    // The sleeve's kr30 declares no arm; a CNC has none either.
    for (example, name) in [("sleeve", "kr30"), ("sleeve", "mill5")] {
        let d = data(&page_of(example, name));
        assert!(d["meta"]["arm"].is_null(), "{example} {name}");
    }
    assert!(data(&page_of("ramp_wall", "kr30"))["meta"]["arm"].is_object());
}

#[test]
fn chromium_draws_the_joint_plot_only_for_an_arm() {
    let Some(chromium) = chromium("chromium_draws_the_joint_plot_only_for_an_arm") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    for (example, name, arm) in [("ramp_wall", "kr30", true), ("sleeve", "kr30", false)] {
        let file = dir.path().join(format!("{example}_{name}.html"));
        std::fs::write(&file, page_of(example, name)).unwrap();
        let dom = dom(&chromium, &file, "");
        assert_eq!(
            attr(&dom, "data-ready").as_deref(),
            Some("speed"),
            "{example}"
        );
        assert!(attr(&dom, "data-js-error").is_none(), "{example}");
        let section = dom.contains(r#"<section id="armplots">"#);
        assert_eq!(section, arm, "{example} {name}: the joint plot shown");
        assert_eq!(attr(&dom, "data-joints").is_some(), arm, "{example} {name}");
        if arm {
            // The ramp wall's axes stay far inside their limits.
            assert_eq!(attr(&dom, "data-near-limit").as_deref(), Some("0"));
            let note = text_of(&dom, r#"<p id="joints-note""#);
            assert!(note.contains("more than 10° inside"), "{note}");
        }
    }
    // The joint-limit error's part with the nozzle tilted 70° instead of
    // 80° on the flange: it builds, A5 down to about −113°, within 10° of
    // −117° (−119° less the 2° margin) on every layer.
    let src = std::fs::read_to_string("examples/errors/arm_joint_limit.lmd")
        .unwrap()
        .replace("b = 80 deg", "b = 70 deg");
    let p = compile(&src, &mut ())
        .program
        .expect("tilted 70°, it builds");
    let html = preview::html(p.machines().next().unwrap());
    let arm = data(&html)["meta"]["arm"].clone();
    let mut near = 0;
    for layer in arm["layers"].as_array().unwrap() {
        for a in 0..6 {
            let lim = |e: usize| arm["limits"][a][e].as_f64().unwrap();
            let v = |e: usize| layer[a][e].as_f64().unwrap();
            let margin = arm["margin"].as_f64().unwrap();
            if v(0) < lim(0) + margin + 10.0 || v(1) > lim(1) - margin - 10.0 {
                near += 1;
            }
        }
    }
    assert!(near >= 5, "A5 near its limit on every layer: {near}");
    let file = dir.path().join("near.html");
    std::fs::write(&file, html).unwrap();
    let dom = dom(&chromium, &file, "");
    assert_eq!(number(&dom, "data-near-limit"), near as f64);
    let note = text_of(&dom, r#"<p id="joints-note""#);
    assert!(
        note.contains(&format!("{near} layer-axis pairs come within 10°")),
        "{note}"
    );
}

/// A 5-axis CNC's page draws its tilt and C plot (the elbow's table, the
/// sleeve's head) without a script error; a robot's has none.
#[test]
fn chromium_draws_the_rotary_plot_only_for_five_axes() {
    let Some(chromium) = chromium("chromium_draws_the_rotary_plot_only_for_five_axes") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    for (example, name, rotary) in [
        ("ring_table", "trt_machine", true),
        ("sleeve", "mill5", true),
        ("sleeve", "kr30", false),
    ] {
        let file = dir.path().join(format!("{example}_{name}.html"));
        let html = page_of(example, name);
        let layers = verified(example).ir().layers.len();
        std::fs::write(&file, html).unwrap();
        let dom = dom(&chromium, &file, "");
        assert_eq!(
            attr(&dom, "data-ready").as_deref(),
            Some("speed"),
            "{example}"
        );
        assert!(attr(&dom, "data-js-error").is_none(), "{example}");
        let section = dom.contains(r#"<section id="rotaryplots">"#);
        assert_eq!(section, rotary, "{example} {name}: the rotary plot shown");
        if rotary {
            assert_eq!(
                number(&dom, "data-layers"),
                layers as f64,
                "{example} {name}"
            );
            let title = text_of(&dom, r#"<h2 id="rotary-title""#);
            assert!(title.contains("and C layer by layer"), "{title}");
        }
    }
}

/// A plan with a thermal block plots each layer's predicted temperatures
/// and waits (docs/thermal.md), and colours its moves by their layer's
/// interpass temperature, without a script error; one without has no such
/// plot.
#[test]
fn chromium_draws_the_thermal_plot_only_with_a_thermal_block() {
    let Some(chromium) = chromium("chromium_draws_the_thermal_plot_only_with_a_thermal_block")
    else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    for (example, name, thermal) in [("thin_wall", "mill3", true), ("rib", "mill3", false)] {
        let file = dir.path().join(format!("{example}_{name}.html"));
        std::fs::write(&file, page_of(example, name)).unwrap();
        let dom = dom(&chromium, &file, "");
        assert_eq!(
            attr(&dom, "data-ready").as_deref(),
            Some("speed"),
            "{example}"
        );
        assert!(attr(&dom, "data-js-error").is_none(), "{example}");
        let section = dom.contains(r#"<section id="thermalplots">"#);
        assert_eq!(section, thermal, "{example}: the thermal plot shown");
        if thermal {
            let layers = verified(example).ir().layers.len();
            assert_eq!(number(&dom, "data-layers"), layers as f64, "{example}");
            let title = text_of(&dom, r#"<h2 id="thermal-title""#);
            assert!(title.contains("the interpass limit 250 °C"), "{title}");
            // The moves coloured by their layer's interpass temperature.
            let dom = self::dom(&chromium, &file, "colour=interpass");
            assert_eq!(attr(&dom, "data-ready").as_deref(), Some("interpass"));
            assert!(attr(&dom, "data-js-error").is_none());
        }
    }
}

/// A plan refused by its arm alone (A5 past its margin) is previewed: the
/// command exits 1 and writes the page, which lists the error with its
/// place and fix, and whose axis plot ticks as past the margin exactly the
/// (layer, axis) pairs whose band leaves it. A plan refused for another
/// reason is not drawn.
#[test]
fn a_plan_refused_for_its_arm_is_drawn_with_its_errors() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("refused.html");
    let o = Command::new(env!("CARGO_BIN_EXE_lmdc"))
        .args(["preview", "examples/errors/arm_joint_limit.lmd", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("lmd::joint-limit") && err.contains("the refused plan"),
        "{err}"
    );
    let html = std::fs::read_to_string(&out).unwrap();
    let d = data(&html);
    let refused = d["meta"]["refused"].as_array().expect("the errors");
    assert_eq!(refused.len(), 1, "{refused:?}");
    assert_eq!(refused[0]["code"], "lmd::joint-limit");
    let msg = refused[0]["message"].as_str().unwrap();
    assert!(msg.contains("axis A5") && msg.contains("at layer"), "{msg}");
    assert!(refused[0]["help"].as_str().unwrap().contains("spin"));
    // The pairs past the margin, from the page's own numbers.
    let arm = &d["meta"]["arm"];
    let margin = arm["margin"].as_f64().unwrap();
    let mut past = 0;
    for layer in arm["layers"].as_array().unwrap() {
        for a in 0..6 {
            let lim = |e: usize| arm["limits"][a][e].as_f64().unwrap();
            let v = |e: usize| layer[a][e].as_f64().unwrap();
            if v(0) < lim(0) + margin || v(1) > lim(1) - margin {
                past += 1;
            }
        }
    }
    assert!(past >= 1, "A5 goes past its margin");
    // The refused machine is drawn, not the first one declared: the
    // bracket's CNC passes, its robot (based out of reach) does not.
    let far = std::fs::read_to_string("examples/bracket.lmd")
        .unwrap()
        .replacen("x = 1200 mm, y = -300 mm", "x = 3500 mm, y = -300 mm", 1);
    assert!(far.find("machine mill3") < far.find("machine kr30"));
    std::fs::create_dir_all(dir.path().join("mesh")).unwrap();
    std::fs::copy(
        "examples/mesh/bracket.stl",
        dir.path().join("mesh/bracket.stl"),
    )
    .unwrap();
    let far_file = dir.path().join("far.lmd");
    std::fs::write(&far_file, far).unwrap();
    let far_page = dir.path().join("far.html");
    let o = Command::new(env!("CARGO_BIN_EXE_lmdc"))
        .args(["preview", far_file.to_str().unwrap(), "-o"])
        .arg(&far_page)
        .output()
        .unwrap();
    assert_eq!(
        o.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let d = data(&std::fs::read_to_string(&far_page).unwrap());
    assert_eq!(d["meta"]["machine"], "kr30", "{}", d["meta"]);
    assert_eq!(d["meta"]["refused"][0]["code"], "lmd::reach");
    // A built plan carries no list; another error leaves nothing to draw.
    assert!(data(&page_of("ramp_wall", "kr30"))["meta"]["refused"].is_null());
    let slow = std::fs::read_to_string("examples/errors/arm_joint_limit.lmd")
        .unwrap()
        .replace("max_speed = 250 mm/s", "max_speed = 5 mm/s");
    let bad = dir.path().join("slow.lmd");
    std::fs::write(&bad, slow).unwrap();
    let none = dir.path().join("none.html");
    let o = Command::new(env!("CARGO_BIN_EXE_lmdc"))
        .args(["preview", bad.to_str().unwrap(), "-o"])
        .arg(&none)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    assert!(!none.exists());

    let Some(chromium) = chromium("a_plan_refused_for_its_arm_is_drawn_with_its_errors") else {
        return;
    };
    let dom = dom(&chromium, &out, "");
    assert_eq!(attr(&dom, "data-ready").as_deref(), Some("speed"));
    assert!(attr(&dom, "data-js-error").is_none());
    assert_eq!(number(&dom, "data-errors"), 1.0);
    assert_eq!(number(&dom, "data-past-limit"), past as f64);
    let banner = text_of(&dom, r#"<div id="refused""#);
    assert!(
        banner.contains("Refused") && banner.contains("axis A5"),
        "{banner}"
    );
    let note = text_of(&dom, r#"<p id="joints-note""#);
    assert!(
        note.contains(&format!("{past} layer-axis pairs go past the margin")),
        "{note}"
    );
}

/// A robot's positioner is plotted as a 5-axis CNC's rotary axes are: E1
/// and E2 layer by layer against their limits, each layer's band the one
/// pair of angles the IR gives that layer (the travel into a layer turns
/// them, counted with the layer it goes to); a robot without one has none.
#[test]
fn the_positioners_angles_are_plotted_layer_by_layer() {
    let p = verified("duct_positioner");
    let m = p.machines().find(|m| m.machine().name() == "kr60").unwrap();
    let lmdc::ir::Machine::Robot(r) = m.machine() else {
        panic!("kr60 is a robot")
    };
    let pos = r.positioner.as_deref().expect("a positioner");
    let d = data(&preview::html(m));
    let rot = &d["meta"]["rotary"];
    assert_eq!(rot["kinematics"], "positioner");
    assert_eq!(rot["axes"], serde_json::json!(["E1", "E2"]));
    assert_eq!(rot["limits"][0], serde_json::json!(pos.tilt.limits));
    let layers = rot["layers"].as_array().unwrap();
    assert_eq!(layers.len(), pos.angles.len());
    for (k, (band, e)) in layers.iter().zip(&pos.angles).enumerate() {
        for a in 0..2 {
            let [lo, hi] = [0, 1].map(|i| band[a][i].as_f64().unwrap());
            // The layer's own angle is inside its band, and the band reaches
            // no further than the previous layer's angle (the travel in).
            assert!(
                lo <= e[a] + 1e-9 && e[a] <= hi + 1e-9,
                "layer {k} E{}: {lo}..{hi} vs {}",
                a + 1,
                e[a]
            );
            let prev = if k == 0 {
                pos.home[a]
            } else {
                pos.angles[k - 1][a]
            };
            // The last layer ends with the PTP back home.
            let after = if k + 1 == layers.len() {
                pos.home[a]
            } else {
                e[a]
            };
            let (lo_ok, hi_ok) = (e[a].min(prev).min(after), e[a].max(prev).max(after));
            assert!(
                lo >= lo_ok - 1e-9 && hi <= hi_ok + 1e-9,
                "layer {k} E{}",
                a + 1
            );
        }
    }
    // E1 tilts the duct's bend away: 0° at the start, tens of degrees at the end.
    let top = pos.angles.last().unwrap()[0];
    assert!(top.abs() > 30.0, "{top}");
    assert!(data(&page_of("twisted_duct", "kr60"))["meta"]["rotary"].is_null());
}

/// A move of the plan as the bodies' tests see it.
struct Pose {
    to: [f64; 3],
    normal: [f64; 3],
    at: Where,
    deposit: bool,
    home: bool,
}

struct Poses(Vec<Pose>);

impl Visit for Poses {
    fn motion(&mut self, m: &Move) {
        let n = m.normal.map(f64::from);
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        self.0.push(Pose {
            to: m.to,
            normal: n.map(|c| c / len),
            at: m.at,
            deposit: m.deposits(),
            home: m.kind == lmdc::plan::MoveKind::Home,
        });
    }
}

/// Every move of `example`'s machine `name`, and its page at `budget`.
fn poses_and_page(example: &str, name: &str, budget: usize) -> (Vec<Pose>, String, Value) {
    let p = verified(example);
    let m = p
        .machines()
        .find(|m| m.machine().name() == name)
        .expect("the machine is checked");
    let mut v = Poses(Vec::new());
    m.plan().walk(&mut v);
    let html = preview::html_within(m, budget);
    let head = serde_json::to_value(&m.machine().common().head).unwrap();
    (v.0, html, head)
}

/// `(layer, path, point)` from 1 as the page's `#pose` says them, of `at`.
fn place(at: Where) -> (String, String, String) {
    match at {
        Where::Point { layer, path, point } => (
            (layer + 1).to_string(),
            (path + 1).to_string(),
            (point + 1).to_string(),
        ),
        Where::Clearance { layer, path } => (
            (layer + 1).to_string(),
            (path + 1).to_string(),
            String::new(),
        ),
        Where::End => unreachable!("the end is not asked for"),
    }
}

/// Three numbers an attribute holds, comma-separated.
fn triple(dom: &str, name: &str) -> [f64; 3] {
    let s = attr(dom, name).unwrap_or_else(|| panic!("no {name}"));
    let v: Vec<f64> = s.split(',').map(|x| x.parse().unwrap()).collect();
    [v[0], v[1], v[2]]
}

/// The page carries the head each machine declares, number for number,
/// and lmdc's typical one for a machine that declares none.
#[test]
fn the_page_carries_the_heads_geometry_as_the_ir_gives_it() {
    for (example, name) in [
        ("ramp_wall", "kr30"),
        ("flange", "mill3"),
        ("sleeve", "mill5"),
    ] {
        let (_, html, head) = poses_and_page(example, name, preview::BUDGET);
        let d = data(&html);
        let got = &d["meta"]["head"];
        assert_eq!(got, &head, "{example} {name}");
        let bodies = got["bodies"].as_array().unwrap();
        assert!(!bodies.is_empty(), "{example}");
        if example == "ramp_wall" {
            // As examples/ramp_wall.lmd declares it.
            assert_eq!(got["standoff"], 15.0);
            assert_eq!(bodies[0]["name"], "nozzle");
            assert_eq!(bodies[0]["length"], 45.0);
            assert_eq!(bodies[0]["diameters"], serde_json::json!([12.0, 40.0]));
            assert_eq!(bodies[1]["diameters"], serde_json::json!([60.0, 60.0]));
            assert_eq!(got["declared"], true);
        }
    }
    // Without its head block the robot carries the typical head.
    let src = std::fs::read_to_string("examples/ramp_wall.lmd").unwrap();
    let start = src.find("machine kr30").unwrap();
    let open = start + src[start..].find("  head {").unwrap();
    let close = open + src[open..].find("\n  }\n").unwrap() + 5;
    let src = format!("{}{}", &src[..open], &src[close..]);
    let p = compile(&src, &mut ())
        .program
        .expect("builds without a head");
    let m = p.machines().find(|m| m.machine().name() == "kr30").unwrap();
    let d = data(&preview::html(m));
    let typical = serde_json::to_value(lmdc::ir::Head::typical()).unwrap();
    assert_eq!(d["meta"]["head"], typical);
    assert_eq!(d["meta"]["head"]["declared"], false);
}

/// The quantisation step of the page's positions: the largest of x, y, z.
fn position_step(d: &Value) -> f64 {
    (0..3)
        .map(|k| {
            let r = &d["ranges"][k];
            (r[1].as_f64().unwrap() - r[0].as_f64().unwrap()) / 65535.0
        })
        .fold(0.0, f64::max)
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt()
}

/// Each approach's page move is the plan's move it happened on: its
/// target is the approach's place and its line passes through the
/// approach's focus `way` along it. A robot's links hang at every move of
/// a small page, in the part's coordinates: A1's height stays where the
/// base puts it, and the flange is the tool's 300 mm from the focus.
#[test]
fn the_page_finds_each_approachs_move_and_hangs_the_arm_at_each() {
    let (poses, html, _) = poses_and_page("ramp_wall", "kr30", preview::BUDGET);
    let d = data(&html);
    let n = d["meta"]["kept"].as_u64().unwrap() as usize;
    assert_eq!(n, poses.len(), "undecimated");
    let approaches = d["meta"]["approaches"].as_array().unwrap();
    let moves = d["meta"]["approach_moves"].as_array().unwrap();
    assert!(!approaches.is_empty());
    assert_eq!(approaches.len(), moves.len());
    for (a, m) in approaches.iter().zip(moves) {
        let k = m["kept"].as_u64().unwrap() as usize;
        assert_eq!(m["exact"], true, "{a}");
        let at = |f: &str| a[f].as_u64().map(|v| v as usize - 1);
        let want = match (at("layer"), at("path"), at("point")) {
            (Some(layer), Some(path), Some(point)) => Where::Point { layer, path, point },
            (Some(layer), Some(path), None) => Where::Clearance { layer, path },
            _ => Where::End,
        };
        assert_eq!(poses[k].at, want, "{a}");
        let way = a["way"].as_f64().unwrap();
        let from = poses[k.saturating_sub(1)].to;
        let focus: [f64; 3] = std::array::from_fn(|i| a["focus"][i].as_f64().unwrap());
        let on = std::array::from_fn(|i| from[i] + way * (poses[k].to[i] - from[i]));
        assert!(distance(on, focus) < 1e-6, "{a}: the move passes {on:?}");
    }

    let links = &d["meta"]["arm"]["links"];
    assert_eq!(links["radii"], serde_json::json!([190.0, 140.0, 100.0]));
    let posed: Vec<usize> = links["moves"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_u64().unwrap() as usize)
        .collect();
    assert_eq!(
        posed,
        (0..n).collect::<Vec<_>>(),
        "every move of a small page"
    );
    let bytes = unbase64(links["points"].as_str().unwrap());
    assert_eq!(bytes.len(), n * 36);
    let mut step = 0.0f64;
    let value = |i: usize, k: usize| {
        let r = &links["ranges"][k];
        let (lo, hi) = (r[0].as_f64().unwrap(), r[1].as_f64().unwrap());
        lo + u16::from_le_bytes([bytes[2 * i], bytes[2 * i + 1]]) as f64 * (hi - lo) / 65535.0
    };
    for k in 0..3 {
        let r = &links["ranges"][k];
        step = step.max((r[1].as_f64().unwrap() - r[0].as_f64().unwrap()) / 65535.0);
    }
    let point =
        |m: usize, j: usize| -> [f64; 3] { std::array::from_fn(|k| value(18 * m + 3 * j + k, k)) };
    let a1 = point(0, 0);
    for (m, pose) in poses.iter().enumerate() {
        assert!(distance(point(m, 0), a1) < 2.0 * step, "move {m}: A1 moved");
        if pose.home {
            continue;
        }
        let tool = distance(point(m, 5), pose.to);
        assert!(
            (tool - 300.0).abs() < 2.0 * step,
            "move {m}: the flange {tool} mm from the focus"
        );
    }
    // The shoulder is the base's 1.3 m from the part's origin, or about.
    assert!(a1[0] < -1000.0, "{a1:?}");
}

/// Headless Chromium at `#move=K`: the page's `#pose` says move K's place,
/// focus, beam and the deposits laid by then, and the head's tip stands
/// `standoff` up the beam; ← steps back; on a thinned page the move's
/// place in the plan is the plan's; the closest approach's button lands on
/// its move.
#[test]
fn chromium_shows_the_bodies_at_the_sliders_move() {
    let Some(chromium) = chromium("chromium_shows_the_bodies_at_the_sliders_move") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    // A 3-axis CNC whole, and the twisted duct's robot thinned (its beam
    // turns layer by layer).
    for (example, name, budget) in [
        ("flange", "mill3", preview::BUDGET),
        ("twisted_duct", "kr60", 20_000),
    ] {
        let (poses, html, head) = poses_and_page(example, name, budget);
        let d = data(&html);
        let n = d["meta"]["kept"].as_u64().unwrap() as usize;
        let step = position_step(&d);
        let standoff = head["standoff"].as_f64().unwrap();
        let file = dir.path().join(format!("{example}.html"));
        std::fs::write(&file, &html).unwrap();
        let first_deposit = (0..poses.len()).find(|&i| poses[i].deposit).unwrap();
        let mut checked = 0;
        for k in [first_deposit, n / 2, n - 3] {
            let dom = dom(&chromium, &file, &format!("move={k}"));
            assert_eq!(number(&dom, "data-move"), k as f64, "{example}");
            let j = number(&dom, "data-plan-move") as usize;
            if budget == preview::BUDGET {
                assert_eq!(j, k, "{example}: undecimated");
            }
            let want = &poses[j];
            let focus = triple(&dom, "data-focus");
            assert!(
                distance(focus, want.to) <= 2.0 * step + 1e-3,
                "{example} {k}: {focus:?} vs {:?}",
                want.to
            );
            let beam = triple(&dom, "data-beam");
            assert!(
                distance(beam, want.normal) < 1e-3,
                "{example} {k}: {beam:?} vs {:?}",
                want.normal
            );
            let tip = triple(&dom, "data-tip");
            let up: [f64; 3] = std::array::from_fn(|i| focus[i] + standoff * beam[i]);
            assert!(distance(tip, up) < 2e-3, "{example} {k}: the tip {tip:?}");
            let (layer, path, point) = place(want.at);
            assert_eq!(attr(&dom, "data-layer").unwrap(), layer, "{example} {k}");
            assert_eq!(attr(&dom, "data-path").unwrap(), path, "{example} {k}");
            assert_eq!(attr(&dom, "data-point").unwrap(), point, "{example} {k}");
            let laid = poses[..=j].iter().filter(|p| p.deposit).count();
            assert_eq!(number(&dom, "data-laid-plan"), laid as f64, "{example} {k}");
            if budget == preview::BUDGET {
                assert_eq!(number(&dom, "data-laid"), laid as f64, "{example} {k}");
            }
            if name == "kr60" {
                // The arm at this move or the last posed before it.
                let arm = number(&dom, "data-arm-move");
                assert!(
                    arm <= k as f64 && arm >= k as f64 - 20.0,
                    "{example} {k}: arm at {arm}"
                );
            }
            checked += 1;
        }
        assert_eq!(checked, 3);
        // Three presses of ← from the middle.
        let dom = dom(&chromium, &file, &format!("move={}&step=-3", n / 2));
        assert_eq!(number(&dom, "data-move"), (n / 2 - 3) as f64, "{example}");
    }

    // The button lands on the tightest approach's move, at its pose.
    let (poses, html, _) = poses_and_page("ramp_wall", "kr30", preview::BUDGET);
    let d = data(&html);
    let approaches = d["meta"]["approaches"].as_array().unwrap();
    let room = |a: &Value| a["distance_mm"].as_f64().unwrap() - a["gap_mm"].as_f64().unwrap();
    let tightest = (0..approaches.len())
        .min_by(|&a, &b| room(&approaches[a]).total_cmp(&room(&approaches[b])))
        .unwrap();
    let k = d["meta"]["approach_moves"][tightest]["kept"]
        .as_u64()
        .unwrap() as usize;
    let file = dir.path().join("ramp_wall.html");
    std::fs::write(&file, &html).unwrap();
    let dom = dom(&chromium, &file, "jump=closest");
    assert_eq!(number(&dom, "data-move"), k as f64);
    assert_eq!(
        number(&dom, "data-way"),
        approaches[tightest]["way"].as_f64().unwrap()
    );
    assert!(poses[k].at != Where::End || approaches[tightest]["layer"].is_null());
}

/// The fixtures are on the page as the IR places them, and drawn where they
/// stand: the post in the ring's bore (tests/cases/collision/
/// travel_over_post), seen from the top, is a circle of its 20 mm diameter
/// round the point the page says its top's centre is drawn at, in the
/// fixtures' colour, with nothing of that colour between it and the ring.
#[test]
fn chromium_draws_the_fixtures_where_they_stand() {
    let Some(chromium) = chromium("chromium_draws_the_fixtures_where_they_stand") else {
        return;
    };
    let src = std::fs::read_to_string("tests/cases/collision/travel_over_post/input.lmd").unwrap();
    let p = compile(&src, &mut ()).program.expect("builds");
    let m = p.machines().find(|m| m.machine().name() == "mill").unwrap();
    let html = preview::html(m);
    let f = &data(&html)["meta"]["fixtures"];
    assert_eq!(
        f,
        &serde_json::json!([{ "name": "post", "kind": "cylinder",
            "lo": [-10.0, -10.0, 0.0], "hi": [10.0, 10.0, 40.0] }])
    );
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("post.html");
    std::fs::write(&file, html).unwrap();
    let (dom, _, img) = dom_and_screenshot(&chromium, &file, "view=top&bodies=0");
    assert_eq!(number(&dom, "data-fixtures"), 1.0);
    // The view's rows (white, from its top to the plots' grey) left of
    // the legend; the DOM's numbers are from another viewport than the
    // screenshot's (a few tens of pixels off), so the scale is measured
    // here: the ring's outer track, 100 − 2.2 mm across its centre line,
    // centred on the post.
    let view_top = number(&dom, "data-view-top") as usize;
    let at = |x: usize, y: usize| img.rgb[y * img.width + x];
    let bottom = (view_top + 1..img.height)
        .find(|&y| at(5, y) != [255; 3])
        .unwrap_or(img.height);
    // The fixtures' brown-orange (170, 90, 20): not the X axis's red, the
    // ring's speed colours or the travels' grey.
    let orange = |p: &[u8; 3]| {
        let [r, g, b] = p.map(f64::from);
        r > 120.0 && (0.4..0.7).contains(&(g / r)) && b < 0.35 * r
    };
    let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
    let mut pixels = Vec::new();
    for y in view_top..bottom {
        for x in 0..1000 {
            let p = at(x, y);
            if orange(&p) {
                pixels.push((x as f64, y as f64));
            } else if coloured(&p) {
                for (k, v) in [x as f64, y as f64].into_iter().enumerate() {
                    lo[k] = lo[k].min(v);
                    hi[k] = hi[k].max(v);
                }
            }
        }
    }
    let top = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
    // Lines 1.6 px wide: the span is that much wider than the path.
    let r = 10.0 * (hi[0] - lo[0] + 1.0 - 1.6) / 97.8;
    // The rim's pixels by quadrant: a circle of the post's radius, not a
    // mark beside the point.
    let (mut rim, mut between) = ([0; 4], Vec::new());
    for &(x, y) in &pixels {
        let (dx, dy) = (x - top[0], y - top[1]);
        let d = dx.hypot(dy);
        if (0.8 * r..=1.2 * r).contains(&d) {
            rim[usize::from(dx > 0.0) + 2 * usize::from(dy > 0.0)] += 1;
        } else if (1.6 * r..=2.4 * r).contains(&d) {
            between.push((x, y));
        }
    }
    assert!(
        rim.iter().all(|&n| n as f64 > r / 3.0),
        "{rim:?} pixels on the post's rim by quadrant (radius {r:.1} px about {top:?})"
    );
    assert!(
        between.len() < 5,
        "fixture pixels between the post and the ring (about {top:?}, r {r:.1}): {between:?}"
    );
}

/// A positioner's faceplate is on the page where the part stands on it:
/// the forearm case's base turns the part about Z only, so the face is the
/// part's plane z = 0 through its origin, facing up, as wide as declared;
/// the browser draws it without a script error.
#[test]
fn the_page_carries_the_faceplate_the_part_stands_on() {
    let src = std::fs::read_to_string("tests/cases/errors/collision/forearm_faceplate/input.lmd")
        .unwrap()
        .replace("faceplate = 1300 mm", "faceplate = 1281.1 mm");
    let p = compile(&src, &mut ()).program.expect("builds");
    let html = preview::html(p.machines().next().unwrap());
    let f = &data(&html)["meta"]["faceplate"];
    let v = |k: &str| -> Vec<f64> {
        f[k].as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    assert_eq!(f["diameter"].as_f64(), Some(1281.1));
    assert_eq!(f["thickness"].as_f64(), Some(40.0));
    for (got, want) in [
        (v("centre"), [0.0, 0.0, 0.0]),
        (v("normal"), [0.0, 0.0, 1.0]),
    ] {
        assert!(
            got.iter().zip(want).all(|(g, w)| (g - w).abs() < 1e-9),
            "{got:?} vs {want:?}"
        );
    }
    // `u` and `v` across the face: square to the normal and to each other.
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let (u, w, n) = (v("u"), v("v"), v("normal"));
    assert!(dot(&u, &n).abs() < 1e-9 && dot(&w, &n).abs() < 1e-9 && dot(&u, &w).abs() < 1e-9);
    // A robot without a positioner has none.
    let kr30 = page_of("ramp_wall", "kr30");
    assert!(data(&kr30)["meta"]["faceplate"].is_null());

    let Some(chromium) = chromium("the_page_carries_the_faceplate_the_part_stands_on") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("faceplate.html");
    std::fs::write(&file, html).unwrap();
    let dom = dom(&chromium, &file, "");
    assert_eq!(number(&dom, "data-faceplate"), 1281.1);
}

/// A probe fixed beside an A/C table (the case errors/collision/
/// machine_fixture, moved where its help says, so it builds) is on the
/// page as declared, in the machine's coordinates, with the table's turns;
/// at a deposit move the browser brings it into the part's coordinates by
/// the table's angles there: its least corner where lmdc's own frame
/// (`PartFrame`) puts it at those angles, and the angles the plan's at
/// some move.
#[test]
fn chromium_draws_a_machines_fixture_where_the_table_takes_it() {
    let Some(chromium) = chromium("chromium_draws_a_machines_fixture_where_the_table_takes_it")
    else {
        return;
    };
    let src = std::fs::read_to_string("tests/cases/errors/collision/machine_fixture/input.lmd")
        .unwrap()
        .replace(
            "at = [250 mm, 310 mm, 100 mm]",
            "at = [250 mm, 349.9 mm, 100 mm]",
        );
    let p = compile(&src, &mut ())
        .program
        .expect("builds with the help's move");
    let m = p.machines().next().unwrap();
    let html = preview::html(m);
    let d = data(&html);
    let moving = &d["meta"]["moving"];
    assert_eq!(moving["fixtures"][0]["name"], "probe", "{moving}");
    assert_eq!(
        moving["fixtures"][0]["lo"],
        serde_json::json!([235.0, 334.9, 100.0])
    );
    assert_eq!(
        d["meta"]["fixtures"],
        serde_json::json!([]),
        "not among those that stand still"
    );
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("probe.html");
    std::fs::write(&file, html).unwrap();
    let n = d["meta"]["kept"].as_u64().unwrap() as usize;
    let dom = dom(&chromium, &file, &format!("move={}&view=top", n / 2));
    let said = attr(&dom, "data-moving").expect("data-moving");
    let (axes, corner) = said.split_once('|').unwrap();
    let axes: Vec<f64> = axes.split(',').map(|v| v.parse().unwrap()).collect();
    let corner: Vec<f64> = corner.split(',').map(|v| v.parse().unwrap()).collect();
    let mut seen = Vec::new();
    struct Axes<'a>(&'a mut Vec<[f64; 2]>);
    impl Visit for Axes<'_> {
        fn motion(&mut self, m: &Move) {
            self.0.push([m.axes.tilt, m.axes.c]);
        }
    }
    m.plan().walk(&mut Axes(&mut seen));
    assert!(
        seen.iter()
            .any(|a| (a[0] - axes[0]).abs() < 1e-9 && (a[1] - axes[1]).abs() < 1e-9),
        "{axes:?} is no move's"
    );
    assert!((axes[0] - 60.0).abs() < 0.1, "the cone's tilt: {axes:?}");
    let frame = lmdc::plan::part_frame::PartFrame::of(m.machine()).unwrap();
    let r = lmdc::plan::kinematics::Rotary {
        tilt: axes[0],
        c: axes[1],
    };
    let want = frame.at(r, false).inverse() * nalgebra::Point3::new(235.0, 334.9, 100.0);
    for k in 0..3 {
        assert!(
            (corner[k] - want[k]).abs() < 1e-3,
            "{corner:?} vs {want:?} at {axes:?}"
        );
    }
}

/// A repair's page (docs/repair.md, *The preview*): the worn pad levelled
/// to its face carries its scan as the scan's surface (every point on the
/// surface the report's base reads, within the float's rounding) and its
/// finish as the report's (the same extremes, and the places' departures
/// reaching them); Chromium draws them and says so on the canvas.
#[test]
fn a_repairs_page_draws_its_scan_and_its_finish() {
    let bytes = std::fs::read("examples/repair/worn_pad.ply").unwrap();
    let files = std::collections::BTreeMap::from([("repair/worn_pad.ply".to_string(), bytes)]);
    let src = std::fs::read_to_string("tests/cases/repair/worn_pad_level/input.lmd").unwrap();
    let (c, model) = crate::support::data::compile_with_files_and_model(&src, files);
    let (p, model) = (c.program.expect("builds"), model.unwrap());
    let m = p.machines().next().unwrap();
    let finish = lmdc::report::finish::of(m.ir(), &model).expect("a finish");
    let overlay = lmdc::pipeline::repair_overlay(m.ir(), &model);
    let html = preview::html_with(m, overlay.as_ref());
    let d = data(&html);
    let repair = &d["meta"]["repair"];
    let scan = repair["scan"].as_array().unwrap();
    assert!(scan.len() > 1000, "{}", scan.len());
    let lmdc::sema::model::Build::Variable { extrusion, .. } = &model.build else {
        panic!("a variable top")
    };
    let surface = &extrusion.base.as_ref().unwrap().surface;
    for q in scan {
        let q: Vec<f64> = q
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        let z = surface.at([q[0], q[1]]).expect("on the scan");
        assert!((q[2] - z).abs() <= 1e-5 * z.abs().max(1.0), "{q:?} vs {z}");
    }
    // (serde_json reads a float back within its last bit)
    assert!((repair["below"].as_f64().unwrap() - finish.below_mm).abs() <= 1e-12);
    assert!((repair["above"].as_f64().unwrap() - finish.above_mm).abs() <= 1e-12);
    let offs: Vec<f64> = repair["finish"]
        .as_array()
        .unwrap()
        .iter()
        .map(|q| q[3].as_f64().unwrap())
        .collect();
    assert_eq!(offs.len(), finish.points);
    let lowest = offs.iter().copied().fold(f64::INFINITY, f64::min);
    let highest = offs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    assert!((lowest + finish.below_mm).abs() <= 1e-6, "{lowest}");
    assert!((highest - finish.above_mm).abs() <= 1e-6, "{highest}");
    let Some(chromium) = chromium("a_repairs_page_draws_its_scan_and_its_finish") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("repair.html");
    std::fs::write(&file, html).unwrap();
    let dom = dom(&chromium, &file, "");
    assert_eq!(number(&dom, "data-scan") as usize, scan.len());
    assert_eq!(number(&dom, "data-finish") as usize, offs.len());
}
