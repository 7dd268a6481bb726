//! What the seed-004 ring tests share: compiling a ring, the files a machine
//! gets, and `lmdc simulate --csv` run as a user runs it.
#![allow(dead_code)]

use lmdc::back::{MemorySink, Templates};
use lmdc::ir::Machine;
use lmdc::verify::Verified;
use std::collections::BTreeMap;
use std::process::Command;

/// The example of seed 004.
pub const EXAMPLE: &str = "examples/segmented_ring.lmd";

/// One row of `lmdc simulate --csv`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Row {
    /// From 1.
    pub layer: usize,
    /// From 1.
    pub segment: usize,
    /// mm/s.
    pub speed: f64,
    /// mm.
    pub height: f64,
    /// mm.
    pub total: f64,
    /// mm.
    pub target: f64,
}

/// `source` compiled, with every diagnostic rendered when it does not.
pub fn compile(name: &str, source: &str) -> Verified {
    let c = lmdc::pipeline::compile(source, &mut ());
    c.program.unwrap_or_else(|| {
        panic!(
            "{name} does not compile:\n{}",
            lmdc::diag::render(&c.diagnostics, name, source, false)
        )
    })
}

/// The files written for the machine called `machine`: name → text.
pub fn files(p: &Verified, machine: &str) -> BTreeMap<String, String> {
    let m = p
        .machines()
        .find(|m| m.machine().name() == machine)
        .unwrap_or_else(|| panic!("no machine {machine}"));
    let mut sink = MemorySink::default();
    lmdc::back::emit(m, &Templates::builtin().unwrap(), &mut sink).expect("emits");
    sink.files
        .into_iter()
        .map(|(n, b)| (n, String::from_utf8(b).expect("UTF-8")))
        .collect()
}

/// The sensor reading (a fraction of its full scale) that reports the loop's
/// target height to machine `machine`: what a ring built exactly on target
/// reads, so the program lays the IR's nominal plan.
pub fn on_target_reading(p: &Verified, machine: &str) -> f64 {
    let ir = p.ir();
    let m = ir
        .machines
        .iter()
        .find(|m| m.name() == machine)
        .unwrap_or_else(|| panic!("no machine {machine}"));
    let sensor = match m {
        Machine::Robot(r) => r.height_sensor,
        Machine::Cnc(c) => c.height_sensor,
    }
    .unwrap_or_else(|| panic!("machine {machine} has no height sensor"));
    let (_, law) = ir.loop_on_machine().expect("the loop runs on the machine");
    law.target / sensor.full_scale
}

/// `lmdc simulate FILE --csv …`, parsed; `source` is written to a temporary
/// file first.
pub fn simulate_csv(tag: &str, source: &str) -> Vec<Row> {
    let dir = std::env::temp_dir().join(format!("lmdc-ring-{}-{tag}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let lmd = dir.join("ring.lmd");
    let csv = dir.join("loop.csv");
    std::fs::write(&lmd, source).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_lmdc"))
        .arg("simulate")
        .arg(&lmd)
        .arg("--csv")
        .arg(&csv)
        .env("NO_COLOR", "1")
        .output()
        .expect("runs");
    assert!(
        out.status.success(),
        "lmdc simulate failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&csv).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("layer,segment,speed_mm_s,height_mm,total_mm,target_mm")
    );
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            assert_eq!(f.len(), 6, "{l}");
            let n = |i: usize| f[i].parse::<f64>().unwrap_or_else(|_| panic!("{l}"));
            Row {
                layer: f[0].parse().unwrap(),
                segment: f[1].parse().unwrap(),
                speed: n(2),
                height: n(3),
                total: n(4),
                target: n(5),
            }
        })
        .collect()
}

/// The loop of `source` run by the library's `pipeline::simulate` (what
/// `lmdc simulate` prints), at full precision, as `[layer][segment]`.
pub fn simulation(source: &str) -> Vec<Vec<Row>> {
    let s = lmdc::pipeline::simulate(source, &[]).expect("nothing set");
    let run = s.run.expect("a loop to simulate");
    let h = run.controller.target().0;
    let rows: Vec<Row> = run
        .simulation
        .samples()
        .iter()
        .map(|x| Row {
            layer: x.layer + 1,
            segment: x.segment + 1,
            speed: x.speed.0,
            height: x.height.0,
            total: x.total.0,
            target: h * (x.layer + 1) as f64,
        })
        .collect();
    by_layer(&rows, run.start.len())
}

/// The rows as `[layer][segment]` (both from 0).
pub fn by_layer(rows: &[Row], segments: usize) -> Vec<Vec<Row>> {
    let layers = rows.len() / segments;
    assert_eq!(layers * segments, rows.len());
    let mut out = vec![Vec::with_capacity(segments); layers];
    for r in rows {
        assert!(r.layer >= 1 && r.segment >= 1 && r.segment <= segments);
        out[r.layer - 1].push(*r);
    }
    for (l, layer) in out.iter().enumerate() {
        for (j, r) in layer.iter().enumerate() {
            assert_eq!((r.layer, r.segment), (l + 1, j + 1), "rows in order");
        }
    }
    out
}

/// A ring of `segments` segments over `layers` layers with a loop strong
/// enough to settle in a few, a robot whose beam leaves along `beam` (with
/// two segments or more: one cannot run the loop on a robot) and a LinuxCNC
/// mill (a 5-axis A/C head when `five`), both running the loop.
pub fn variant(
    segments: usize,
    layers: usize,
    transition_deg: f64,
    step_deg: f64,
    beam: &str,
    five: bool,
) -> String {
    let list = |f: &dyn Fn(usize) -> String| (0..segments).map(f).collect::<Vec<_>>().join(", ");
    let defocus = list(&|j| format!("{} mm", -8 + (j % 4) as i64));
    let power = list(&|j| format!("{} W", 900 + 50 * (j % 5)));
    let width = list(&|j| format!("{} mm", 3.0 + 0.5 * (j % 3) as f64));
    let speed = list(&|j| format!("{} mm/s", 4 + (j % 7)));
    let head = if five {
        "  axes = 5\n  kinematics = head_ac\n"
    } else {
        "  axes = 3\n"
    };
    let rotary = if five {
        "    a = -110 deg .. 110 deg\n    c = -360 deg .. 360 deg\n"
    } else {
        ""
    };
    // One segment: the robot is left out, in a comment.
    let (robot_start, robot_end) = if segments >= 2 {
        ("", "")
    } else {
        ("/*\n", "*/\n")
    };
    format!(
        "part ring_variant
ring wall {{
  radius = 40 mm
  segments = {segments}
  transition = {transition_deg} deg
  table {{
    defocus = [{defocus}]
    power = [{power}]
    width = [{width}]
    speed = [{speed}]
  }}
}}
slicing continuous {{
  layers = {layers}
  layer_height = 0.23 mm
  step = {step_deg} deg
}}
control height {{
  kp = -25 mm/s/mm
  ki = -8 mm/s/mm
  clamp = 1.9 mm/s .. 20 mm/s
}}
process {{
  powder = 6 g/min
}}
{robot_start}machine kr60 {{
  kind = robot
  load = load(mass = 18 kg, cog = [0 mm, 0 mm, 160 mm])
  tool = frame(1, z = 350 mm)
  base = 1
  beam = {beam}
  laser = 1
  power_output = 1
  full_scale = 2000 W
  max_speed = 60 mm/s
  height_input = 3
  height_full_scale = 2 mm
  height_delay = 150 ms
}}
{robot_end}machine mill3 {{
  kind = cnc
{head}  dialect = linuxcnc
  max_speed = 60 mm/s
  height_input = 3
  height_full_scale = 2 mm
  height_delay = 100 ms
  limits {{
    x = -60 mm .. 60 mm
    y = -60 mm .. 60 mm
    z = -20 mm .. 60 mm
{rotary}  }}
}}
"
    )
}
