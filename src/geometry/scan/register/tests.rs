//! The best fit against known moves: a worn block scanned with noise and
//! stray returns, displaced by a known turn and shift, is brought back
//! within 0.02 mm and 0.01°, its residual the scan's noise; a flat nominal
//! is refused for the motions it leaves free; a wrong nominal shows in the
//! residual; a scan of a few points is refused.

use super::*;
use crate::geometry::mesh::Placement;
use crate::geometry::scan::nearest::block;

const PLACE: Placement = Placement {
    scale: 1.0,
    turn: [0.0; 3],
    at: [0.0; 3],
};

/// Gaussian numbers from a seeded LCG (Box–Muller): the same every run.
struct Noise(u64);

impl Noise {
    fn uniform(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }

    fn gauss(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    }
}

/// The worn top of the block x −30..30, y −15..15, z 0..10: a trough
/// 1.2 mm deep at (8, 2) mm, reaching 20 mm along x and 10 mm along y
/// (a cosine's square, 0 beyond: the rest is as designed).
fn worn(x: f64, y: f64) -> f64 {
    let r = (((x - 8.0) / 20.0).powi(2) + ((y - 2.0) / 10.0).powi(2)).sqrt();
    10.0 - 1.2 * (std::f64::consts::FRAC_PI_2 * r.min(1.0)).cos().powi(2)
}

/// A scan of the worn block: its top every 0.5 mm and its four sides from
/// z = 2 mm up every 0.5 mm, `sigma` mm of noise along each face's
/// normal, and one point in a hundred a stray return 2–4 mm above.
fn worn_block(sigma: f64, seed: u64) -> Vec<[f64; 3]> {
    let mut rng = Noise(seed);
    let mut pts = Vec::new();
    for j in 0..=60 {
        for i in 0..=120 {
            let (x, y) = (-30.0 + 0.5 * i as f64, -15.0 + 0.5 * j as f64);
            pts.push([x, y, worn(x, y) + sigma * rng.gauss()]);
        }
    }
    for k in 0..=16 {
        let z = 2.0 + 0.5 * k as f64;
        for i in 0..=120 {
            let x = -30.0 + 0.5 * i as f64;
            pts.push([x, -15.0 - sigma * rng.gauss(), z]);
            pts.push([x, 15.0 + sigma * rng.gauss(), z]);
        }
        for j in 0..=60 {
            let y = -15.0 + 0.5 * j as f64;
            pts.push([-30.0 - sigma * rng.gauss(), y, z]);
            pts.push([30.0 + sigma * rng.gauss(), y, z]);
        }
    }
    let n = pts.len();
    for k in (0..n).step_by(100) {
        pts[k][2] += 2.0 + 2.0 * rng.uniform();
    }
    pts
}

/// The move a scan was displaced by: 1.5° about z and 0.5° about x,
/// then (1.2, −0.8, 0.3) mm.
fn displacement() -> Rigid {
    Rigid {
        rot: Rotation3::from_euler_angles(0.5f64.to_radians(), 0.0, 1.5f64.to_radians()),
        shift: Vector3::new(1.2, -0.8, 0.3),
    }
}

fn raw(pts: &[[f64; 3]], m: &Rigid) -> Raw {
    Raw {
        vertices: pts.iter().map(|p| m.apply(*p).map(|c| c as f32)).collect(),
        triangles: Vec::new(),
    }
}

fn nominal() -> Nominal {
    Nominal::new(&block([-30.0, -15.0, 0.0], [30.0, 15.0, 10.0]))
}

/// What is left of `d` after `fit` (the identity when it undoes it): its
/// turn in degrees and its shift at the part's origin, mm.
fn left(d: &Rigid, fit: &Fit) -> (f64, f64) {
    let both = d.then(&fit.moved);
    (both.rot.angle().to_degrees(), both.shift.norm())
}

#[test]
fn a_displaced_worn_scan_is_brought_back() {
    let sigma = 0.02;
    let d = displacement();
    let pts = worn_block(sigma, 7);
    let fit = register(&raw(&pts, &d), &PLACE.into(), &nominal()).unwrap();
    let (angle, shift) = left(&d, &fit);
    assert!(angle < 0.01, "{angle}° left, {fit:?}");
    assert!(shift < 0.02, "{shift} mm left, {fit:?}");
    // The kept points' residual is the noise (3σ̂ keeps all but 0.3 % of
    // it: their RMS 0.986 σ), the trough and the strays left out.
    assert!((fit.rms / sigma - 1.0).abs() < 0.1, "{fit:?}");
    assert!(fit.max < 5.0 * sigma, "{fit:?}");
    let worn_share = pts
        .iter()
        .filter(|p| p[2] > 9.0 && 10.0 - worn(p[0], p[1]) > 5.0 * sigma)
        .count() as f64
        / pts.len() as f64;
    assert!(
        fit.share() < 1.0 - worn_share && fit.share() > 1.0 - worn_share - 0.08,
        "kept {} of the points, worn {worn_share}",
        fit.share()
    );
    assert!(fit.iterations < MAX_ITERATIONS, "{fit:?}");
}

/// A fit still moving when its iterations run out is refused, with the
/// iterations taken and its last step, not returned half way: the
/// displaced scan above takes more than three.
#[test]
fn a_fit_that_has_not_settled_is_refused() {
    let d = displacement();
    let pts = worn_block(0.02, 7);
    let fault = register_within(&raw(&pts, &d), &PLACE.into(), &nominal(), 3).unwrap_err();
    let FitFault::NotSettled { iterations, step } = fault else {
        panic!("{fault:?}");
    };
    assert_eq!(iterations, 3);
    assert!(step > SETTLED && step.is_finite(), "{step}");
}

#[test]
fn a_noiseless_scan_comes_back_to_float_precision() {
    let d = displacement();
    let pts = worn_block(0.0, 1);
    let fit = register(&raw(&pts, &d), &PLACE.into(), &nominal()).unwrap();
    let (angle, shift) = left(&d, &fit);
    assert!(angle < 1e-3 && shift < 1e-3, "{angle}° {shift} mm {fit:?}");
    assert!(fit.rms < 0.002, "{fit:?}");
}

#[test]
fn the_declared_placement_is_the_start_and_the_fit_is_after_it() {
    // The scan in inches, turned a quarter about z: the declared placement
    // undoes that, the fit the rest.
    let d = displacement();
    let quarter = Rigid {
        rot: Rotation3::from_euler_angles(0.0, 0.0, -std::f64::consts::FRAC_PI_2),
        shift: Vector3::zeros(),
    };
    let pts: Vec<[f64; 3]> = worn_block(0.01, 3)
        .iter()
        .map(|p| quarter.apply(d.apply(*p)).map(|c| c / 25.4))
        .collect();
    let place = Placement {
        scale: 25.4,
        turn: [0.0, 0.0, std::f64::consts::FRAC_PI_2],
        at: [0.0; 3],
    };
    let fit = register(&raw(&pts, &Rigid::identity()), &place.into(), &nominal()).unwrap();
    let (angle, shift) = left(&d, &fit);
    assert!(angle < 0.01 && shift < 0.02, "{angle}° {shift} mm {fit:?}");
}

#[test]
fn a_flat_nominal_leaves_the_scan_free_to_slide_and_turn() {
    let top: Vec<[f64; 3]> = worn_block(0.01, 2)
        .into_iter()
        .filter(|p| p[2] > 5.0)
        .collect();
    let plane = Nominal::new(&[
        [
            [-40.0, -20.0, 10.0],
            [40.0, -20.0, 10.0],
            [40.0, 20.0, 10.0],
        ],
        [
            [-40.0, -20.0, 10.0],
            [40.0, 20.0, 10.0],
            [-40.0, 20.0, 10.0],
        ],
    ]);
    let Err(FitFault::Undetermined { free, .. }) =
        register(&raw(&top, &Rigid::identity()), &PLACE.into(), &plane)
    else {
        panic!("a plane fixes no x, y or turn about z");
    };
    let near = |a: [f64; 3], b: [f64; 3]| (0..3).all(|k| (a[k] - b[k]).abs() < 1e-6);
    let slides: Vec<_> = free
        .iter()
        .filter_map(|f| match f {
            Freedom::Slide(d) => Some(*d),
            Freedom::Turn(_) => None,
        })
        .collect();
    assert_eq!(slides.len(), 2, "{free:?}");
    assert!(slides.iter().all(|d| d[2].abs() < 1e-6), "{free:?}");
    assert!(
        free.iter()
            .any(|f| matches!(f, Freedom::Turn(a) if near(*a, [0.0, 0.0, 1.0]))),
        "{free:?}"
    );
}

#[test]
fn a_wrong_nominal_shows_in_the_residual() {
    // The scan of the 60 × 30 block fitted to one 5 mm wider and 2 mm
    // lower: no move lays its sides and top on the other's.
    let pts = worn_block(0.02, 5);
    let wrong = Nominal::new(&block([-32.5, -15.0, 0.0], [32.5, 15.0, 8.0]));
    let fit = register(&raw(&pts, &Rigid::identity()), &PLACE.into(), &wrong);
    match fit {
        Ok(f) => assert!(f.rms > 0.1, "{f:?}"),
        Err(e) => assert!(!matches!(e, FitFault::NoNominal), "{e:?}"),
    }
}

#[test]
fn too_few_points_or_no_nominal_are_refused() {
    let pts: Vec<[f64; 3]> = worn_block(0.0, 1).into_iter().take(40).collect();
    assert!(matches!(
        register(&raw(&pts, &Rigid::identity()), &PLACE.into(), &nominal()),
        Err(FitFault::TooFewInliers { .. })
    ));
    let none = Nominal::new(&[[[0.0; 3], [1.0, 1.0, 1.0], [2.0, 2.0, 2.0]]]);
    assert_eq!(
        register(&raw(&pts, &Rigid::identity()), &PLACE.into(), &none),
        Err(FitFault::NoNominal)
    );
}

#[test]
fn the_fit_is_the_same_every_run() {
    let d = displacement();
    let r = raw(&worn_block(0.02, 9), &d);
    let a = register(&r, &PLACE.into(), &nominal()).unwrap();
    let b = register(&r, &PLACE.into(), &nominal()).unwrap();
    assert_eq!(a, b);
}

/// The faces the fit looks at: a sliver 100 m long (what earcut leaves
/// between far holes of a plate) is cut, across its longest edge, into
/// pieces no longer than half the reach where it passes the scan, and
/// the rest of it dropped. Nearest points over the scan lie at the exact
/// distances, which the whole sliver's, in floating point, need not (one
/// point 0.5 mm over it came out 7.2 mm away).
#[test]
fn a_long_sliver_is_cut_near_the_scan_and_dropped_away_from_it() {
    let sliver: Tri = [[-5e4, -0.02, 0.0], [5e4, 0.0, 0.0], [5e4, 0.04, 0.0]];
    // Over the sliver, the height; beside it, across to its nearer long
    // edge (the lines from its far corner, a cross product over a length).
    let exact = |p: [f64; 3]| {
        let [a, b, c] = sliver;
        let off = |u: [f64; 3]| {
            let (dx, dy) = (u[0] - a[0], u[1] - a[1]);
            (dx * (p[1] - a[1]) - dy * (p[0] - a[0])) / dx.hypot(dy)
        };
        let (right, left) = (off(b), off(c));
        let across = if right >= 0.0 && left <= 0.0 {
            0.0
        } else {
            right.abs().min(left.abs())
        };
        across.hypot(p[2])
    };
    let pts: Vec<[f64; 3]> = (0..100)
        .map(|i| [-20.0 + 0.4 * i as f64, 0.01 * (i % 3) as f64, 0.5])
        .collect();
    let (lo, hi, reach) = near_box(&pts).unwrap();
    // The points' box is 39.6 × 0.02 mm: half its diagonal.
    assert!((reach - 39.6f64.hypot(0.02) / 2.0).abs() < 1e-9, "{reach}");
    let tree = Nominal::new(&[sliver]).near(&pts);
    // Some hundreds of needles along the box's 119 mm, not the sliver's
    // 100 m.
    assert!(tree.len() > 1 && tree.len() < 1000, "{} pieces", tree.len());
    let (a, b) = tree.bounds();
    assert!(
        a[0] >= lo[0] - reach && b[0] <= hi[0] + reach,
        "{a:?} {b:?}"
    );
    for p in &pts {
        let n = tree.nearest(*p).unwrap().distance;
        assert!((n - exact(*p)).abs() < 1e-9, "{p:?}: {n} vs {}", exact(*p));
    }
    // A scan nowhere near it finds no face.
    let far: Vec<[f64; 3]> = pts.iter().map(|p| [p[0], p[1] + 1000.0, p[2]]).collect();
    assert!(Nominal::new(&[sliver]).near(&far).is_empty());
}
