//! A slab leaning off the part's axes, filled along its lean
//! (`direction = auto`, docs/repair.md, *Undercuts*): the directions are
//! tried a degree of arc apart, so a lean toward 37° is met (tried only
//! every 15° round the vertical, it was sent along a steeper tilt or
//! refused); the lines along its faces are allowed a twentieth of a bead.

use super::{compile, messages};
use std::collections::BTreeMap;

/// The slab's lean from vertical and the direction it leans toward (from
/// +x, counter-clockwise), deg.
const LEAN: [f64; 2] = [25.0, 37.0];

/// Its height over the block, mm (from z = 10 to 13.5).
const HEIGHT: f64 = 3.5;

/// Its foot on the block: x and y, mm.
const FOOT: [[f64; 2]; 2] = [[-12.0, 12.0], [-8.0, 8.0]];

/// The block, mm.
const BLOCK: [[f64; 2]; 2] = [[-40.0, 40.0], [-20.0, 20.0]];

/// How far the slab's top is shifted from its foot, mm.
fn shift() -> [f64; 2] {
    let run = HEIGHT * LEAN[0].to_radians().tan();
    let (s, c) = LEAN[1].to_radians().sin_cos();
    [run * c, run * s]
}

/// The corners of a rectangle counter-clockwise seen from above, at `z`,
/// moved by `by`.
fn rect(r: [[f64; 2]; 2], z: f64, by: [f64; 2]) -> [[f64; 3]; 4] {
    let [x, y] = r;
    [[x[0], y[0]], [x[1], y[0]], [x[1], y[1]], [x[0], y[1]]]
        .map(|p| [p[0] + by[0], p[1] + by[1], z])
}

/// The part as designed as one closed mesh, faces out: the block to
/// z = 10 with the slab on it (the block's top a frame round the foot).
fn triangles() -> Vec<[[f64; 3]; 3]> {
    let top = 10.0 + HEIGHT;
    let bottom = rect(BLOCK, 0.0, [0.0; 2]);
    let face = rect(BLOCK, 10.0, [0.0; 2]);
    let foot = rect(FOOT, 10.0, [0.0; 2]);
    let crown = rect(FOOT, top, shift());
    let mut t = Vec::new();
    // Quad a-b-c-d, counter-clockwise seen from outside.
    let mut quad = |a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]| {
        t.push([a, b, c]);
        t.push([a, c, d]);
    };
    quad(bottom[0], bottom[3], bottom[2], bottom[1]);
    for k in 0..4 {
        let n = (k + 1) % 4;
        quad(bottom[k], bottom[n], face[n], face[k]);
        quad(face[k], face[n], foot[n], foot[k]);
        quad(foot[k], foot[n], crown[n], crown[k]);
    }
    quad(crown[0], crown[1], crown[2], crown[3]);
    t
}

fn stl(tris: &[[[f64; 3]; 3]]) -> Vec<u8> {
    let mut out = vec![b' '; 80];
    out.extend((tris.len() as u32).to_le_bytes());
    for t in tris {
        out.extend([0u8; 12]);
        for v in t.iter().flatten() {
            out.extend((*v as f32).to_le_bytes());
        }
        out.extend([0u8; 2]);
    }
    out
}

/// Whether `q` is in the part as designed, tested on its own.
fn in_target(q: [f64; 3]) -> bool {
    let within = |v: f64, r: [f64; 2]| v >= r[0] && v <= r[1];
    let block = within(q[0], BLOCK[0]) && within(q[1], BLOCK[1]) && within(q[2], [0.0, 10.0]);
    let up = (q[2] - 10.0) / HEIGHT;
    let [sx, sy] = shift();
    let slab = within(up, [0.0, 1.0])
        && within(q[0] - up * sx, FOOT[0])
        && within(q[1] - up * sy, FOOT[1]);
    block || slab
}

/// The worn pad's surface (examples/repair/make_worn_pad.py), without its
/// noise.
fn worn(x: f64, y: f64) -> f64 {
    10.0 - 1.5 * (-((x - 5.0) / 15.0).powi(2)).exp() * (1.0 - (y / 14.0).powi(2))
}

/// The slab on the worn pad on a 5-axis head turning A ±35°, the profile
/// its top seen from above.
fn slab() -> lmdc::pipeline::Compiled {
    let src = include_str!("../../examples/leaning_slab.lmd");
    let src = &src[..src.find("machine kr30").unwrap()];
    let [sx, sy] = shift();
    let src = src.replace(
        "place(rectangle(width = 24 mm, height = 20 mm), at = [2.0207 mm, 0 mm])",
        &format!("place(rectangle(width = 24 mm, height = 16 mm), at = [{sx} mm, {sy} mm])"),
    );
    let files = BTreeMap::from([
        (
            "repair/worn_pad.ply".to_string(),
            std::fs::read("examples/repair/worn_pad.ply").unwrap(),
        ),
        ("repair/leaning_slab.stl".to_string(), stl(&triangles())),
    ]);
    compile(&src, files)
}

/// Planned along a direction within 2° of the lean (the least tilt that
/// builds it, its faces allowed a twentieth of a bead over its 3.5 mm),
/// every bead's middle in the part as designed and above the scan.
#[test]
fn a_slab_leaning_off_the_axes_is_filled_along_its_lean() {
    // The mesh is closed: its volume is the block's and the slab's.
    let volume: f64 = triangles()
        .iter()
        .map(|[a, b, c]| {
            (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0]))
                / 6.0
        })
        .sum();
    assert!((volume - (80.0 * 40.0 * 10.0 + 24.0 * 16.0 * HEIGHT)).abs() < 1e-6);
    let c = slab();
    let m = messages(&c);
    let v = c.program.unwrap_or_else(|| panic!("{m}"));
    let p = v.ir();
    let (st, ct) = LEAN[0].to_radians().sin_cos();
    let (sa, ca) = LEAN[1].to_radians().sin_cos();
    let lean = [st * ca, st * sa, ct];
    let z = p.layers[0].frame.z;
    let cos: f64 = z.iter().zip(lean).map(|(a, b)| a * b).sum();
    let off = cos.min(1.0).acos().to_degrees();
    // A face leaning `off` from the direction strays from the lines along
    // it by HEIGHT·tan(off): at most the twentieth of a 2.4 mm bead.
    let allowed = (2.4 / 20.0 / HEIGHT).atan().to_degrees();
    assert!(
        off <= allowed,
        "planned along {z:?}, {off}° from the lean ({allowed}° allowed)"
    );
    for l in &p.layers {
        assert_eq!(l.frame.z, z);
    }
    let moves = super::moves(p);
    assert!(moves.len() > 100, "{}", moves.len());
    for (a, b, h, _) in &moves {
        let mid = [0, 1, 2].map(|k| (a[k] + b[k]) / 2.0 + z[k] * h / 2.0);
        assert!(in_target(mid), "{mid:?} is not in the target");
        assert!(mid[2] > worn(mid[0], mid[1]), "{mid:?} is under the scan");
    }
}
