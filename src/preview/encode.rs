//! The page's data: the kept moves as columns of little-endian integers,
//! base64 in a JSON object the viewer reads. Positions are 16-bit fractions
//! of the plan's bounding box (a 300 mm part to 5 µm), speed, height, power
//! and height error 16-bit fractions of their ranges over the deposits (the
//! error's over the deposits it is predicted for), style a byte, and a byte
//! of flags — laser on, a gap before, error predicted, and the path kind in
//! three bits: 16 bytes a move instead of 48 as floats, and no float
//! formatting to make the bytes depend on.

use super::{Decimation, Kind};
use crate::ir::Style;
use crate::plan::Where;
use serde::Serialize;

/// One kept move.
pub struct Row {
    /// Tool tip target, mm.
    pub pos: [f64; 3],
    /// Speed, mm/s (rapids at the machine's max).
    pub speed: f32,
    /// Layer height at the deposit, mm (0 off deposits).
    pub height: f32,
    /// Laser power, W (0 off deposits).
    pub power: f32,
    /// Style id.
    pub style: u16,
    /// Height error, per cent (`None`: none predicted, or the laser off).
    pub error: Option<f64>,
    /// What the move is part of.
    pub kind: Kind,
    /// Laser on.
    pub deposit: bool,
    /// No line leads to this move (layers between were left out).
    pub gap: bool,
}

/// A column's value of a move, if it has one (its range is over those that
/// have; the others store 0).
type Field = fn(&Row) -> Option<f64>;

/// The flag bits of a move.
const DEPOSIT: u8 = 1;
const GAP: u8 = 2;
const PREDICTED: u8 = 4;
/// The kind's number is stored from this bit up (three bits).
const KIND_SHIFT: u8 = 3;

/// The kept moves, column by column.
#[derive(Default)]
pub struct Columns {
    rows: Vec<Row>,
}

/// What the viewer is told besides the moves.
/// The thermal prediction the page plots layer by layer (docs/thermal.md).
#[derive(Serialize)]
pub struct Heat<'a> {
    /// The alloy.
    pub material: &'a str,
    /// The interpass limit, °C (`None`: not limited).
    pub limit: Option<f64>,
    /// Each layer's interpass temperature, °C.
    pub interpass: Vec<f64>,
    /// Each layer's temperature when laid, °C.
    pub peak: Vec<f64>,
    /// Each layer's wait before it, s.
    pub wait: Vec<f64>,
}

impl<'a> Heat<'a> {
    /// The IR's prediction, if it has one.
    pub fn of(program: &'a crate::ir::Program) -> Option<Heat<'a>> {
        let t = program.thermal.as_ref()?;
        Some(Heat {
            material: &t.material,
            limit: t.max_interpass,
            interpass: t.layers.iter().map(|l| l.interpass).collect(),
            peak: t.layers.iter().map(|l| l.peak).collect(),
            wait: t.layers.iter().map(|l| l.wait).collect(),
        })
    }
}

#[derive(Serialize)]
pub struct Meta<'a> {
    /// Part name.
    pub part: &'a str,
    /// Machine name.
    pub machine: &'a str,
    /// Layers of the plan.
    pub layers: usize,
    /// Points of the IR.
    pub points: usize,
    /// Moves of the plan.
    pub moves: usize,
    /// Moves on the page.
    pub kept: usize,
    /// How they were chosen.
    #[serde(serialize_with = "strides")]
    pub decimation: Decimation,
    /// `(layer number, first move)` of each layer on the page.
    pub starts: &'a [(usize, usize)],
    /// The style table.
    pub styles: &'a [Style],
    /// The names of the path kinds, by the number the flags store.
    pub kinds: [&'static str; 5],
    /// How far a deposit's height error may go (`rise_tolerance`), per cent.
    pub tolerance: f64,
    /// How far the layers' mean errors may add up (`max_drift`), mm.
    pub max_drift: f64,
    /// Every layer's `[mean %, lowest %, highest %, drift mm]` height error
    /// (the drift the layers' mean rise minus height added up to it), from
    /// every move of the plan, or `None` where none is predicted.
    pub layer_error: &'a [Option<[f64; 4]>],
    /// A robot arm's axes layer by layer (`None`: no arm to solve).
    pub arm: Option<&'a super::joints::Arm>,
    /// A 5-axis CNC's tilt axis and C layer by layer (`None`: none).
    pub rotary: Option<&'a super::rotary::Rotary>,
    /// Each layer's predicted interpass and peak temperatures (`None`: no
    /// thermal block).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub thermal: Option<Heat<'a>>,
    /// The arm's errors where the plan was refused for them (`None`: the
    /// plan built).
    pub refused: Option<Vec<Failure>>,
    /// The closest each body came to each thing of the cell, where
    /// measured (docs/collision.md): the page marks each at its focus.
    pub approaches: &'a [crate::verify::approach::Approach],
    /// The page's move each approach happened on (by index, as
    /// `approaches`): the first kept move at or after the plan's move
    /// whose target it names and whose line passes nearest its focus;
    /// `exact` where that very move is kept.
    pub approach_moves: &'a [Option<ApproachMove>],
    /// The head the machine carries along the beam, as the collision
    /// checks take it (docs/collision.md): the page draws it at a move.
    pub head: &'a crate::ir::Head,
    /// The fixtures, as the page draws them.
    pub fixtures: Vec<FixtureBox<'a>>,
    /// The fixtures fixed to a machine whose table or positioner turns the
    /// part, drawn at the slider's move (`None`: none).
    pub moving: Option<super::moving::Moving<'a>>,
    /// A positioner's faceplate, where declared.
    pub faceplate: Option<Faceplate>,
    /// A part on a scan or up to a top: the scan and the finish.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub repair: Option<&'a super::repair::Overlay>,
    /// Who wrote the page.
    pub generator: &'static str,
}

/// A fixture as the page draws it, in the part's coordinates: the box
/// round it and what fills the box (`box`, an upright `cylinder` touching
/// its sides, a `mesh` drawn as its box).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FixtureBox<'a> {
    /// Its name from the source.
    pub name: &'a str,
    /// `box`, `cylinder` or `mesh`.
    pub kind: &'static str,
    /// The least corner, mm.
    pub lo: [f64; 3],
    /// The greatest corner, mm.
    pub hi: [f64; 3],
}

impl<'a> FixtureBox<'a> {
    /// The IR's fixture `f` as drawn.
    pub fn of(f: &'a crate::ir::Fixture) -> Self {
        let (lo, hi) = f.bounds();
        let kind = match f.shape {
            crate::ir::FixtureShape::Box { .. } => "box",
            crate::ir::FixtureShape::Cylinder { .. } => "cylinder",
            crate::ir::FixtureShape::Mesh { .. } => "mesh",
        };
        FixtureBox {
            name: &f.name,
            kind,
            lo,
            hi,
        }
    }
}

/// A positioner's faceplate as the page draws it, in the part's
/// coordinates (it turns with the part): a disc `diameter` across, its face
/// through `centre`, `thickness` behind it against `normal`, `u` and `v`
/// across it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Faceplate {
    /// mm.
    pub diameter: f64,
    /// mm.
    pub thickness: f64,
    /// The face's centre, mm.
    pub centre: [f64; 3],
    /// Out of the face, towards the part.
    pub normal: [f64; 3],
    /// Across the face.
    pub u: [f64; 3],
    /// Across the face, square to `u`.
    pub v: [f64; 3],
}

impl Faceplate {
    /// The faceplate of `machine`, a robot's positioner's where it declares
    /// one and its base has a value: in the part's coordinates the
    /// faceplate's frame is the base's inverse, as the arm's check takes it
    /// (`verify::arm::links`).
    pub fn of(machine: &crate::ir::Machine) -> Option<Faceplate> {
        let crate::ir::Machine::Robot(robot) = machine else {
            return None;
        };
        let diameter = robot.positioner.as_ref()?.faceplate?;
        let face = crate::plan::arm::frame(robot.base.value.as_ref()?).inverse();
        let axis = |v: nalgebra::Vector3<f64>| {
            let w = face * v;
            [w.x, w.y, w.z]
        };
        let c = face * nalgebra::Point3::origin();
        Some(Faceplate {
            diameter,
            thickness: crate::ir::FACEPLATE_THICKNESS_MM,
            centre: [c.x, c.y, c.z],
            normal: axis(nalgebra::Vector3::z()),
            u: axis(nalgebra::Vector3::x()),
            v: axis(nalgebra::Vector3::y()),
        })
    }
}

/// The page's move an approach happened on.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ApproachMove {
    /// The kept move's index on the page.
    pub kept: usize,
    /// Whether it is the plan's move of the approach (else the plan's move
    /// was thinned out and this is the next one kept).
    pub exact: bool,
}

/// One error of a refused plan, as the page lists it.
#[derive(Serialize)]
pub struct Failure {
    /// Its code (`lmd::joint-limit`).
    pub code: String,
    /// What is wrong, and where (layer, path, point).
    pub message: String,
    /// What would fix it.
    pub help: Option<String>,
}

fn strides<S: serde::Serializer>(d: &Decimation, s: S) -> Result<S::Ok, S::Error> {
    [d.layers, d.moves].serialize(s)
}

#[derive(Serialize)]
struct Data<'a> {
    meta: &'a Meta<'a>,
    /// `[min, max]` of x, y, z, speed, height, power, error.
    ranges: [[f64; 2]; 7],
    x: String,
    y: String,
    z: String,
    speed: String,
    height: String,
    power: String,
    error: String,
    style: String,
    flags: String,
    /// Where each move is, its beam and its place in the plan
    /// ([`Poses`]).
    poses: String,
}

impl Columns {
    /// Adds a move.
    pub fn push(&mut self, r: Row) {
        self.rows.push(r);
    }

    /// Moves so far.
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    /// The JSON object the page's viewer reads (safe inside `<script>`),
    /// with `poses` the moves' places and beams.
    pub fn encode(&self, meta: &Meta<'_>, poses: &Poses) -> String {
        let range = |f: Field| {
            let mut r = [f64::INFINITY, f64::NEG_INFINITY];
            for v in self.rows.iter().filter_map(f) {
                if v.is_finite() {
                    r = [r[0].min(v), r[1].max(v)];
                }
            }
            if r[0] > r[1] {
                [0.0, 0.0]
            } else {
                r
            }
        };
        let fields: [Field; 7] = [
            |r| Some(r.pos[0]),
            |r| Some(r.pos[1]),
            |r| Some(r.pos[2]),
            |r| r.deposit.then_some(r.speed as f64),
            |r| r.deposit.then_some(r.height as f64),
            |r| r.deposit.then_some(r.power as f64),
            |r| r.error.filter(|_| r.deposit),
        ];
        let ranges = fields.map(range);
        let column = |k: usize| {
            let [lo, hi] = ranges[k];
            let mut bytes = Vec::with_capacity(self.rows.len() * 2);
            for r in &self.rows {
                let q = fields[k](r).map_or(0, |v| quantise(v, lo, hi));
                bytes.extend_from_slice(&q.to_le_bytes());
            }
            base64(&bytes)
        };
        let data = Data {
            meta,
            ranges,
            x: column(0),
            y: column(1),
            z: column(2),
            speed: column(3),
            height: column(4),
            power: column(5),
            error: column(6),
            style: base64(
                &self
                    .rows
                    .iter()
                    .map(|r| r.style.min(255) as u8)
                    .collect::<Vec<_>>(),
            ),
            flags: base64(
                &self
                    .rows
                    .iter()
                    .map(|r| {
                        let mut f = (r.kind as u8) << KIND_SHIFT;
                        if r.deposit {
                            f |= DEPOSIT;
                        }
                        if r.gap {
                            f |= GAP;
                        }
                        if r.deposit && r.error.is_some() {
                            f |= PREDICTED;
                        }
                        f
                    })
                    .collect::<Vec<_>>(),
            ),
            poses: base64(&poses.bytes),
        };
        // '<' only occurs inside JSON strings, where \u003c means the same:
        // no name can close the script element.
        serde_json::to_string(&data)
            .unwrap_or_else(|_| "{}".into())
            .replace('<', "\\u003c")
    }
}

/// Where a kept move lies: its target's place, and how many moves of the
/// plan lie between it and the kept move before.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Place {
    /// The plan's move index (from 0, every move counted).
    pub index: usize,
    /// Deposit moves of the plan up to this one, itself included.
    pub laid: usize,
    /// Where its target comes from.
    pub at: Where,
    /// Up the beam, unit.
    pub beam: [f64; 3],
    /// Whether it deposits.
    pub deposit: bool,
}

/// The kept moves' places as one byte stream, each move a tag byte and
/// what changed since the move before, in LEB128 varints: `at`'s kind in
/// the tag's two low bits (0 a point, 1 a clearance move, 2 the end);
/// bit 2: the layer changed (its index follows); bit 3: the path changed
/// (its index follows, and the point counts from 0 again); bit 4: plan
/// moves were left out before it (how many, and how many of them
/// deposit, follow); bit 5: the beam turned (three little-endian `i16`
/// of the unit vector times 32767 follow, after the varints). A point's
/// index follows last, zigzag-coded from the point before. Most moves
/// take two bytes: the moves of a path are one point apart and keep
/// their beam.
#[derive(Default)]
pub struct Poses {
    bytes: Vec<u8>,
    layer: usize,
    path: usize,
    point: usize,
    beam: Option<[i16; 3]>,
    next: usize,
    laid: usize,
}

/// The tag bits of [`Poses`].
const LAYER_CHANGED: u8 = 4;
const PATH_CHANGED: u8 = 8;
const SKIPPED: u8 = 16;
const BEAM_TURNED: u8 = 32;

impl Poses {
    /// Adds the next kept move.
    pub fn push(&mut self, p: &Place) {
        let (kind, layer, path, point) = match p.at {
            Where::Point { layer, path, point } => (0, layer, path, Some(point)),
            Where::Clearance { layer, path } => (1, layer, path, None),
            Where::End => (2, self.layer, self.path, None),
        };
        let beam = p
            .beam
            .map(|c| (c.clamp(-1.0, 1.0) * 32767.0).round() as i16);
        let mut tag = kind;
        let mut tail = Vec::new();
        if layer != self.layer {
            tag |= LAYER_CHANGED;
            varint(&mut tail, layer as u64);
        }
        if path != self.path || layer != self.layer {
            tag |= PATH_CHANGED;
            varint(&mut tail, path as u64);
            self.point = 0;
        }
        let skipped = p.index.saturating_sub(self.next);
        if skipped > 0 {
            tag |= SKIPPED;
            let own = usize::from(p.deposit);
            varint(&mut tail, skipped as u64);
            varint(&mut tail, p.laid.saturating_sub(own + self.laid) as u64);
        }
        if let Some(point) = point {
            let d = point as i64 - self.point as i64;
            varint(&mut tail, ((d << 1) ^ (d >> 63)) as u64);
            self.point = point;
        }
        if self.beam != Some(beam) {
            tag |= BEAM_TURNED;
            for c in beam {
                tail.extend_from_slice(&c.to_le_bytes());
            }
        }
        self.bytes.push(tag);
        self.bytes.extend_from_slice(&tail);
        (self.layer, self.path, self.beam) = (layer, path, Some(beam));
        (self.next, self.laid) = (p.index + 1, p.laid);
    }
}

/// `v` as an LEB128 varint.
fn varint(out: &mut Vec<u8>, mut v: u64) {
    while v >= 0x80 {
        out.push((v as u8 & 0x7f) | 0x80);
        v >>= 7;
    }
    out.push(v as u8);
}

/// `v` as a 16-bit fraction of `[lo, hi]` (0 outside, or for a flat range).
pub(super) fn quantise(v: f64, lo: f64, hi: f64) -> u16 {
    if !(v.is_finite() && hi > lo) {
        return 0;
    }
    ((v - lo) / (hi - lo) * 65535.0).round().clamp(0.0, 65535.0) as u16
}

/// Standard base64 with padding.
pub fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for c in bytes.chunks(3) {
        let n = (c[0] as u32) << 16
            | (*c.get(1).unwrap_or(&0) as u32) << 8
            | *c.get(2).unwrap_or(&0) as u32;
        for (i, shift) in [18, 12, 6, 0].into_iter().enumerate() {
            if i <= c.len() {
                out.push(A[(n >> shift & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// `text` safe inside HTML text.
pub fn escape_html(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_as_the_rfc_says() {
        assert_eq!(base64(b""), "");
        assert_eq!(base64(b"f"), "Zg==");
        assert_eq!(base64(b"fo"), "Zm8=");
        assert_eq!(base64(b"foo"), "Zm9v");
        assert_eq!(base64(b"foobar"), "Zm9vYmFy");
    }

    #[test]
    fn quantised_ends_and_flat_ranges() {
        assert_eq!(quantise(1.0, 1.0, 3.0), 0);
        assert_eq!(quantise(3.0, 1.0, 3.0), 65535);
        assert_eq!(quantise(2.0, 2.0, 2.0), 0);
        assert_eq!(quantise(f64::NAN, 0.0, 1.0), 0);
    }
}
