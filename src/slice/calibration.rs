//! A calibration file's coupons → IR layers: each coupon its own layers,
//! laid one after another — a track one straight path at its speed, power
//! and powder feed; a wall the same path `layers` times, `layer_height`
//! apart; a pad `tracks` parallel paths `offset` apart. Every coupon's
//! first layer is labelled with its parameters, which the programs write as
//! a comment before it.

use crate::ir::{Frame, Layer, Path, PathKind, Point};
use crate::sema::model::{Calibration, Coupon, CouponKind, Process};
use crate::units::short;

/// The layers that lay `c`'s coupons, in the order laid.
pub fn build(c: &Calibration, process: &Process) -> Vec<Layer> {
    let per = c.kind.layers();
    let total = c.coupons.len() * per;
    let mut layers = Vec::with_capacity(total);
    for coupon in &c.coupons {
        for j in 0..per {
            let index = layers.len();
            layers.push(Layer {
                index,
                station: index as f64 / total as f64,
                frame: Frame {
                    origin: [0.0, 0.0, j as f64 * c.layer_height.0],
                    x: [1.0, 0.0, 0.0],
                    y: [0.0, 1.0, 0.0],
                    z: [0.0, 0.0, 1.0],
                },
                paths: tracks(c, coupon, j, process),
                label: label(c.kind, coupon, j),
                on_plate: j == 0,
            });
        }
    }
    layers
}

/// The comment before layer `j` of `coupon`: its id, speed, power,
/// powder and kind on its first layer; which layer it is on the others.
pub fn label(kind: CouponKind, coupon: &Coupon, j: usize) -> String {
    if j > 0 {
        return format!("coupon {}: layer {} of {}", coupon.id, j + 1, kind.layers());
    }
    format!(
        "coupon {}: speed {} mm/s, power {} W, powder {} g/min, {}",
        coupon.id,
        short(coupon.speed.0),
        short(coupon.power.watts()),
        short(coupon.powder.g_min()),
        kind.name()
    )
}

/// Layer `j`'s tracks of `coupon`: straight along +x, `length` long.
fn tracks(c: &Calibration, coupon: &Coupon, j: usize, process: &Process) -> Vec<Path> {
    let z = j as f64 * c.layer_height.0;
    let pitch = match c.kind {
        CouponKind::Pad { offset, .. } => offset.0,
        _ => c.width.0,
    };
    (0..c.kind.tracks())
        .map(|t| {
            let [x, y] = coupon.start;
            let y = y + t as f64 * c.kind.offset().0;
            let point = |x: f64, on: bool| Point {
                pos: [x, y, z],
                normal: [0.0, 0.0, 1.0],
                tangent: [1.0, 0.0, 0.0],
                layer_height: c.layer_height.0 as f32,
                speed: coupon.speed.0 as f32,
                power: coupon.power.watts() as f32,
                powder: coupon.powder.g_min() as f32,
                defocus: process.defocus.0 as f32,
                laser_on: on,
                style: 0,
                pitch: pitch as f32,
                rise: 0.0,
            };
            Path {
                kind: match c.kind {
                    CouponKind::Pad { .. } => PathKind::Infill,
                    _ => PathKind::Wall,
                },
                points: vec![point(x, true), point(x + c.length.0, false)],
            }
        })
        .collect()
}

/// The measurement sheet of `c`'s coupons (`<part>.coupons.csv`), in the
/// format `lmdc fit` reads: one row a coupon — its id, kind, parameters,
/// its centre on the plate and the length it lays (for a mass) — and
/// empty `width`, `height`, `area` and `mass` cells to fill in, units in
/// the header.
pub fn sheet(part: &str, c: &Calibration) -> String {
    use crate::numbers::trimmed;
    let mut out = format!(
        "# lmdc calibrate: part {part}, bead {} ({} mm wide), coupons {} mm long along +x\n\
         # x, y: the coupon's centre on the plate; length: the track length it lays\n\
         # fill in width and height (area or mass for a mass balance), then: lmdc fit this.csv\n\
         id,kind,speed (mm/s),power (W),feed (g/min),x (mm),y (mm),length (mm),width (mm),height (mm),area (mm^2),mass (g)\n",
        c.bead,
        trimmed(c.width.0, 4),
        trimmed(c.length.0, 4),
    );
    let footprint = c.kind.footprint(c.width).0;
    let laid = c.length.0 * (c.kind.tracks() * c.kind.layers()) as f64;
    for k in &c.coupons {
        let centre = [
            k.start[0] + c.length.0 / 2.0,
            k.start[1] - c.width.0 / 2.0 + footprint / 2.0,
        ];
        out.push_str(&format!(
            "{},{},{},{},{},{},{},{},,,,\n",
            k.id,
            c.kind.name(),
            trimmed(k.speed.0, 4),
            trimmed(k.power.watts(), 3),
            trimmed(k.powder.g_min(), 4),
            trimmed(centre[0], 3),
            trimmed(centre[1], 3),
            trimmed(laid, 3),
        ));
    }
    out
}
