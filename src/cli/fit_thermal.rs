//! `lmdc fit TEMPERATURES.csv --plan FILE.lmd`: fits the thermal model's
//! absorptivity and heat transfer coefficient to interpass temperatures
//! measured on a build of FILE's plan (docs/thermal.md, *Calibration*),
//! and prints them with the residuals and the `thermal { … }` to paste.

use super::messages::{self, MessageFormat};
use super::{data_reader, read_sheet, read_source, shown, EXIT_PROGRAM, EXIT_USAGE};
use lmdc::lower::heat;
use lmdc::pipeline;
use lmdc::thermal::fit::{self, Measured};
use serde::Serialize;
use std::fmt::Write as _;
use std::path::Path;

/// What the fit found, as `--json` writes it.
#[derive(Serialize)]
struct Report {
    /// The alloy the plan declares.
    material: String,
    /// The share of the laser's power the part takes up.
    absorptivity: f64,
    /// W/(m²·K).
    heat_transfer: f64,
    /// K.
    rms: f64,
    /// `[layer (1-based), measured °C, predicted °C]` per row.
    rows: Vec<[f64; 3]>,
    /// Each row's island (1-based, in the order the report lists them;
    /// `null`: the layer's start), where the sheet has an island column.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    islands: Vec<Option<usize>>,
    /// The first and last layer measured (1-based).
    layers: [usize; 2],
    /// Which ended at the edge of the range searched (absorptivity, heat
    /// transfer): the data do not settle it.
    at_edge: [bool; 2],
    /// The material's lines of the `thermal` block to paste.
    #[serde(skip)]
    material_lines: String,
}

/// The lines of a `thermal` block that give `t`'s material: its alloy,
/// and the properties declared over it or instead of one (all four, as
/// the plan took them).
fn material_lines(t: &lmdc::ir::Thermal) -> String {
    let key = t.material.split(',').next().unwrap_or_default();
    let mut out = String::new();
    if lmdc::thermal::alloy(key).is_some() {
        out.push_str(&format!("    material = {key}\n"));
        if key == t.material {
            return out;
        }
    }
    out.push_str(&format!(
        "    conductivity = {} W/m/degC\n    density = {} kg/m^3\n    heat_capacity = {} J/kg/degC\n    emissivity = {}\n",
        t.conductivity, t.density, t.heat_capacity, t.emissivity
    ));
    out
}

/// Runs the fit of `sheet` over the plan of `plan`; returns the exit code.
pub fn run(sheet: &Path, plan: &Path, json: bool, (color, format): (bool, MessageFormat)) -> u8 {
    let (Some(text), Some(source)) = (read_sheet(sheet), read_source(plan)) else {
        return EXIT_USAGE;
    };
    let measured = match read(&text) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("error: {}: {e}", shown(sheet));
            return EXIT_USAGE;
        }
    };
    let options = pipeline::Options {
        file: Some(plan.display().to_string()),
        machine: None,
        set: Vec::new(),
        data: Some(pipeline::DataFiles(data_reader(plan))),
        allow: Vec::new(),
    };
    let compiled = match pipeline::compile_with(&source, &options, &mut ()) {
        Ok(c) => c,
        Err(e) => return messages::fail(plan, lmdc::diag::usage::refused(&e)),
    };
    messages::print(&compiled.diagnostics, plan, &source, color, format);
    let Some(verified) = compiled.program else {
        return EXIT_PROGRAM;
    };
    let program = verified.ir();
    let Some(t) = &program.thermal else {
        eprintln!(
            "error: {} has no `thermal {{ … }}` in its process block: nothing to fit",
            shown(plan)
        );
        return EXIT_USAGE;
    };
    let (material, plate) = heat::cell(t);
    let waits: Vec<f64> = t.layers.iter().map(|l| l.wait).collect();
    // Each layer's islands as the plan predicted them, a column each.
    let (layers, orders, columns) = heat::island_loads(program);
    let cell = fit::Plan {
        columns: &columns,
        layers: &layers,
        orders: &orders,
        waits: &waits,
    };
    let Some(f) = fit::fit(material, plate, cell, &measured) else {
        eprintln!(
            "error: {} measures a layer or an island the plan does not have (it has {} layers)",
            shown(sheet),
            program.layers.len()
        );
        return EXIT_USAGE;
    };
    let rows: Vec<[f64; 3]> = measured
        .iter()
        .zip(&f.residuals)
        .map(|(m, r)| [(m.layer + 1) as f64, m.interpass, m.interpass + r])
        .collect();
    let islands: Vec<Option<usize>> = if measured.iter().any(|m| m.island.is_some()) {
        measured.iter().map(|m| m.island.map(|g| g + 1)).collect()
    } else {
        Vec::new()
    };
    let first = measured.iter().map(|m| m.layer + 1).min().unwrap_or(1);
    let last = measured.iter().map(|m| m.layer + 1).max().unwrap_or(1);
    let r = Report {
        material: t.material.clone(),
        absorptivity: f.absorptivity,
        heat_transfer: f.heat_transfer,
        rms: f.rms,
        rows,
        islands,
        layers: [first, last],
        at_edge: f.at_edge,
        material_lines: material_lines(t),
    };
    if json {
        println!("{}", serde_json::to_string(&r).expect("plain data"));
    } else {
        print!("{}", text_of(&r, program.layers.len(), &shown(sheet)));
    }
    0
}

/// The sheet: a header, then `layer, interpass` a row (the layer from 1,
/// the temperature in °C), or `layer, island, interpass` (the island from
/// 1, in the order the report lists the layer's islands); `#` starts a
/// comment.
fn read(text: &str) -> Result<Vec<Measured>, String> {
    let mut out = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() || (out.is_empty() && !line.starts_with(|c: char| c.is_ascii_digit())) {
            continue;
        }
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        let count = |c: &str| c.parse::<usize>().ok().filter(|&l| l >= 1);
        let (layer, island, t) = match cells[..] {
            [l, t] => (count(l), Some(None), t),
            [l, i, t] => (count(l), count(i).map(Some), t),
            _ => (None, None, ""),
        };
        let t = t.parse::<f64>().ok().filter(|t| t.is_finite());
        let (Some(layer), Some(island), Some(t)) = (layer, island, t) else {
            return Err(format!(
                "line {}: a row is `layer, interpass (degC)` or `layer, island, interpass (degC)`, the layer and the island from 1: `{line}`",
                n + 1
            ));
        };
        out.push(Measured {
            layer: layer - 1,
            island: island.map(|i| i - 1),
            interpass: t,
        });
    }
    if out.len() < 3 {
        return Err("fewer than three measurements: two numbers are fitted".into());
    }
    Ok(out)
}

/// The fit in words.
fn text_of(r: &Report, layers: usize, sheet: &str) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "thermal model fitted to {sheet}: {} interpass temperatures of layers {}–{} ({}'s data otherwise)\n",
        r.rows.len(),
        r.layers[0],
        r.layers[1],
        r.material
    );
    let edge = |e: bool| {
        if e {
            "  (at the edge of the range searched: the data do not settle it)"
        } else {
            ""
        }
    };
    let _ = writeln!(
        out,
        "absorptivity    {:.3}{}",
        r.absorptivity,
        edge(r.at_edge[0])
    );
    let _ = writeln!(
        out,
        "heat_transfer   {:.1} W/m^2/degC{}",
        r.heat_transfer,
        edge(r.at_edge[1])
    );
    let _ = writeln!(out, "residuals       RMS {:.1} K\n", r.rms);
    let island = if r.islands.is_empty() { "" } else { " island" };
    let _ = writeln!(
        out,
        "{:>6}{island} {:>12} {:>13} {:>10}",
        "layer", "measured °C", "predicted °C", "residual K"
    );
    for (k, [l, m, p]) in r.rows.iter().enumerate() {
        let g = match r.islands.get(k) {
            Some(Some(g)) => format!(" {g:>6}"),
            Some(None) => format!(" {:>6}", "-"),
            None => String::new(),
        };
        let _ = writeln!(out, "{:>6}{g} {:>12.1} {:>13.1} {:>10.1}", l, m, p, p - m);
    }
    let _ = writeln!(
        out,
        "\nin the process block:\n  thermal {{\n{}    absorptivity = {:.3}\n    heat_transfer = {:.1} W/m^2/degC\n  }}",
        r.material_lines, r.absorptivity, r.heat_transfer
    );
    if r.layers[1] < layers {
        let _ = writeln!(
            out,
            "\nmeasured up to layer {} of {layers}: the later layers' predictions extrapolate the fit",
            r.layers[1]
        );
    }
    out
}
