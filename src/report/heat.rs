//! The thermal prediction in the report: each layer's interpass and peak
//! temperatures as the IR carries them (docs/thermal.md), and what keeping
//! `max_interpass` cost.

use crate::ir::{Levers, Program};
use serde::Serialize;

/// One layer's predicted temperatures.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct HeatRow {
    /// 1-based layer number.
    pub layer: usize,
    /// When it starts, s from the build's start (deposits and waits; rapid
    /// moves counted as instant).
    pub start_s: f64,
    /// The temperature of the part where and when it starts, °C.
    pub interpass_c: f64,
    /// The layer's own temperature when laid, °C.
    pub peak_c: f64,
    /// The wait before it, s.
    pub wait_s: f64,
    /// What `max_interpass` added to that wait, s.
    pub added_s: f64,
    /// The share of its declared power it is laid at (`cooling = power`).
    pub power_share: f64,
    /// A layer of several islands: each island's, in the order they are
    /// laid (empty: a layer of one piece).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub islands: Vec<IslandRow>,
}

/// One island of a layer of several.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct IslandRow {
    /// Where it starts (its first deposit point's x and y), mm.
    pub at_mm: [f64; 2],
    /// When it starts, s from the build's start.
    pub start_s: f64,
    /// The temperature of the island below where and when it starts, °C.
    pub interpass_c: f64,
    /// The island's own temperature when laid, °C.
    pub peak_c: f64,
}

/// The thermal prediction of the plan.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Heat {
    /// The alloy (`material = …`).
    pub material: String,
    /// The limit, °C (absent: predicted, not limited).
    pub max_interpass_c: Option<f64>,
    /// The levers it may be kept by (one word, or a list).
    pub cooling: Levers,
    /// The hottest start of a layer, °C, and the layer (1-based).
    pub hottest_interpass_c: f64,
    /// Which layer starts the hottest (1-based).
    pub hottest_layer: usize,
    /// The hottest layer when laid, °C.
    pub peak_c: f64,
    /// Which layer (1-based).
    pub peak_layer: usize,
    /// The time the limit added to the waits, s.
    pub added_s: f64,
    /// `cooling` with another lever than `dwell`: what waits alone
    /// (`cooling = dwell`, the islands in the slicer's order) would have
    /// added, s (absent: waits alone, or waits of at most an hour would
    /// not keep the limit).
    pub dwell_alone_s: Option<f64>,
    /// The time the levers save against waits alone, s.
    pub saved_s: Option<f64>,
    /// How many layers laid at less than their power.
    pub layers_at_less_power: usize,
    /// How many layers laid their islands in another order than the
    /// slicer's.
    pub layers_reordered: usize,
    /// Per layer.
    pub layers: Vec<HeatRow>,
}

impl Heat {
    /// The IR's prediction, if it has one.
    pub fn of(program: &Program) -> Option<Heat> {
        let t = program.thermal.as_ref()?;
        let layers: Vec<HeatRow> = t
            .layers
            .iter()
            .enumerate()
            .map(|(i, l)| HeatRow {
                layer: i + 1,
                start_s: l.time,
                interpass_c: l.interpass,
                peak_c: l.peak,
                wait_s: l.wait,
                added_s: l.added,
                power_share: l.power,
                islands: l
                    .islands
                    .iter()
                    .map(|i| IslandRow {
                        at_mm: [i.at[0], i.at[1]],
                        start_s: i.time,
                        interpass_c: i.interpass,
                        peak_c: i.peak,
                    })
                    .collect(),
            })
            .collect();
        // The first layer that is the hottest (many start at the limit).
        let hottest = |key: fn(&HeatRow) -> f64| {
            layers.iter().fold((f64::NEG_INFINITY, 0), |(t, at), r| {
                if key(r) > t {
                    (key(r), r.layer)
                } else {
                    (t, at)
                }
            })
        };
        let finite = |(t, at): (f64, usize)| if t.is_finite() { (t, at) } else { (0.0, 0) };
        // A layer of islands starts as hot as its hottest island.
        let (hottest_interpass_c, hottest_layer) = finite(hottest(|r| {
            r.islands
                .iter()
                .map(|i| i.interpass_c)
                .fold(r.interpass_c, f64::max)
        }));
        let (peak_c, peak_layer) = finite(hottest(|r| r.peak_c));
        Some(Heat {
            material: t.material.clone(),
            max_interpass_c: t.max_interpass,
            cooling: t.cooling.clone(),
            hottest_interpass_c,
            hottest_layer,
            peak_c,
            peak_layer,
            added_s: layers.iter().map(|r| r.added_s).sum(),
            dwell_alone_s: t.dwell_alone,
            saved_s: t
                .dwell_alone
                .map(|d| d - layers.iter().map(|r| r.added_s).sum::<f64>()),
            layers_at_less_power: layers.iter().filter(|r| r.power_share < 1.0).count(),
            layers_reordered: t.layers.iter().filter(|l| l.reordered).count(),
            layers,
        })
    }
}
