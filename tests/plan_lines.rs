//! `--emit plan`: every machine's plan as JSON lines, checked against the
//! plan the library walks, with the laser and cell states each move carries
//! following the `laser` and `io` lines before it.

use lmdc::plan::{Move, Speed};
use serde_json::Value;
use std::process::Command;

fn build(file: &str, name: &str, extra: &[&str]) -> std::path::PathBuf {
    let out = std::env::temp_dir().join(format!("lmdc-plan-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let o = Command::new(env!("CARGO_BIN_EXE_lmdc"))
        .args([
            "build",
            file,
            "-o",
            out.to_str().unwrap(),
            "--emit",
            "plan",
            "-q",
        ])
        .args(extra)
        .output()
        .unwrap();
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    out
}

/// Equal but for the last bit serde_json's float reading may round.
fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * (1.0 + a.abs().max(b.abs()))
}

/// Checks the lines of `text` against `moves` (the library's walk).
fn check(text: &str, moves: &[Move], tilt: Option<&str>) {
    let (mut laser, mut gas, mut powder) = (false, false, Value::Null);
    let mut k = 0;
    for line in text.lines() {
        let v: Value = serde_json::from_str(line).unwrap();
        match v["type"].as_str().unwrap() {
            "laser" => laser = v["on"].as_bool().unwrap(),
            "io" => match v["event"].as_str().unwrap() {
                "gas_on" => gas = true,
                "gas_off" => gas = false,
                "powder_on" | "powder_rate" => powder = v["rate"].clone(),
                "powder_off" => powder = Value::Null,
                e => panic!("{e}"),
            },
            "move" => {
                let m = &moves[k];
                k += 1;
                let to: Vec<f64> = v["to"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|x| x.as_f64().unwrap())
                    .collect();
                assert!(
                    to.iter().zip(m.to).all(|(a, b)| close(*a, b)),
                    "move {k}: {to:?} {:?}",
                    m.to
                );
                assert_eq!(v["laser"], laser, "move {k}: {line}");
                assert_eq!(
                    m.deposits(),
                    laser,
                    "move {k}: deposits iff the laser is on"
                );
                assert_eq!(v["kind"] == "deposit", m.deposits());
                assert_eq!(v["gas"], gas);
                assert_eq!(v["powder"], powder);
                match m.speed {
                    Speed::Rapid => assert_eq!(v["speed"], "rapid"),
                    Speed::Feed(s) => assert!(close(v["speed"].as_f64().unwrap(), s as f64)),
                }
                match tilt {
                    None => assert!(v["axes"].is_null()),
                    Some(t) => {
                        assert!(close(v["axes"][t].as_f64().unwrap(), m.axes.tilt));
                        assert!(close(v["axes"]["C"].as_f64().unwrap(), m.axes.c));
                    }
                }
            }
            "layer" | "dwell" | "segment_end" => {}
            t => panic!("type {t}"),
        }
    }
    assert_eq!(k, moves.len(), "one line a move");
}

fn moves(src: &str, machine: Option<&str>) -> Vec<(String, Vec<Move>)> {
    let options = lmdc::Options {
        machine: machine.map(str::to_string),
        ..Default::default()
    };
    let p = lmdc::compile(src, &options).unwrap();
    p.machines()
        .map(|m| {
            let mut v = Vec::new();
            m.plan().walk(&mut |mv: &Move| v.push(*mv));
            (m.machine().name().to_string(), v)
        })
        .collect()
}

#[test]
fn the_lines_are_the_plan_with_its_laser_and_cell_states() {
    let out = build("examples/flange.lmd", "flange", &[]);
    let src = std::fs::read_to_string("examples/flange.lmd").unwrap();
    let mut gas_seen = false;
    for (name, mv) in moves(&src, None) {
        let text = std::fs::read_to_string(out.join(format!("flange_{name}.plan.jsonl"))).unwrap();
        gas_seen |= text.contains("\"gas\":true");
        check(&text, &mv, None);
    }
    assert!(gas_seen, "the flange's cell switches gas");
    // A tilting head writes its axes.
    let file = "tests/cases/duct/small_duct/input.lmd";
    let out = build(file, "duct", &["--machine", "dmu5"]);
    let src = std::fs::read_to_string(file).unwrap();
    let (name, mv) = moves(&src, Some("dmu5")).remove(0);
    let stem = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .find(|f| f.ends_with(&format!("{name}.plan.jsonl")))
        .unwrap();
    let text = std::fs::read_to_string(out.join(stem)).unwrap();
    assert!(mv.iter().any(|m| m.axes.tilt.abs() > 1.0), "the duct tilts");
    check(&text, &mv, Some("A"));
}

/// A visitor that has seen what it needs (`Visit::done`, a help's probe
/// that met what refuses it) stops the walk before the next path: the
/// thin wall's walk stopped once its first deposit is told ends with the
/// moves of the first path, every one of them as the whole walk tells it.
#[test]
fn a_visitor_that_is_done_stops_the_walk_before_the_next_path() {
    use lmdc::plan::{MoveKind, Visit, Where};
    struct Until {
        moves: Vec<Move>,
    }
    impl Visit for Until {
        fn motion(&mut self, m: &Move) {
            self.moves.push(*m);
        }
        fn done(&self) -> bool {
            self.moves.iter().any(|m| m.kind == MoveKind::Deposit)
        }
    }
    let src = std::fs::read_to_string("examples/thin_wall.lmd").unwrap();
    let p = lmdc::compile(&src, &lmdc::Options::default()).unwrap();
    let m = p.machines().next().unwrap();
    let mut until = Until { moves: Vec::new() };
    m.plan().walk(&mut until);
    let mut all = Vec::new();
    m.plan().walk(&mut |mv: &Move| all.push(*mv));
    let n = until.moves.len();
    assert!(n > 1 && n < all.len() / 4, "{n} of {}", all.len());
    assert_eq!(until.moves[..], all[..n]);
    let path = |m: &Move| match m.at {
        Where::Point { layer, path, .. } => Some((layer, path)),
        _ => None,
    };
    let seen: Vec<_> = until.moves.iter().filter_map(path).collect();
    assert!(seen.iter().all(|&p| p == seen[0]), "{seen:?}");
    // The next move of the whole walk belongs to another path, or is none
    // of one (a travel to it).
    assert!(all[n..].iter().filter_map(path).all(|p| p != seen[0]));
}
