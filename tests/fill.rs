//! Planar layer fill (seed 001): contour passes and raster tracks over
//! outlines of lines and arcs, checked against closed-form geometry.

use lmdc::fill::{fill, FillError, FillSpec, Linking, Pattern, RasterSpec, Seam, Track, TrackKind};
use lmdc::geometry::profile::{Profile, Vertex};
use proptest::prelude::*;
use std::f64::consts::PI;

/// A `w` × `h` rectangle from the origin with corners rounded to radius `r`.
fn rounded(w: f64, h: f64, r: f64) -> Profile {
    Profile::rounded_rectangle(w, h, r)
}

/// Only a raster, at `angle` degrees, lines `d` apart, ends extended by at
/// most `extend`.
fn raster(angle: f64, d: f64, extend: f64, pattern: Pattern) -> FillSpec {
    FillSpec {
        inset: 0.0,
        contours: 0,
        offset: d,
        raster: Some(RasterSpec {
            angle_deg: angle,
            offset: d,
            pattern,
            extend,
            link: Linking::None,
            closing: f64::INFINITY,
        }),
        seam: Seam::Lowest,
    }
}

fn infill(tracks: &[Track]) -> Vec<[[f64; 2]; 2]> {
    tracks
        .iter()
        .filter(|t| t.kind == TrackKind::Infill)
        .map(|t| {
            assert_eq!(t.points.len(), 2);
            [t.points[0], t.points[1]]
        })
        .collect()
}

/// Infill tracks of a 0° raster as `(y, x_min, x_max)`, bottom up.
fn rows(tracks: &[Track]) -> Vec<(f64, f64, f64)> {
    infill(tracks)
        .into_iter()
        .map(|[a, b]| {
            assert_eq!(a[1], b[1], "a 0° track is horizontal");
            (a[1], a[0].min(b[0]), a[0].max(b[0]))
        })
        .collect()
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

#[test]
fn raster_over_a_circle_starts_at_seed_001_x_n() {
    let (r, d) = (10.0, 1.6);
    let tracks = fill(
        &Profile::circle(r),
        &raster(0.0, d, 0.0, Pattern::OneWay),
        0.01,
    )
    .unwrap();
    let rows = rows(&tracks);
    // Lines at −R + n·d for n = 0..=12; line 0 only touches the circle and,
    // without extension, is dropped.
    assert_eq!(rows.len(), 12);
    for (k, &(y, x0, x1)) in rows.iter().enumerate() {
        let n = (k + 1) as f64;
        assert!(close(y, -r + n * d, 1e-12), "line {n} at {y}");
        let x_n = (r * r - (r - n * d).powi(2)).sqrt();
        assert!(
            close(x0, -x_n, 1e-9) && close(x1, x_n, 1e-9),
            "line {n}: {x0} {x1} vs {x_n}"
        );
    }
}

#[test]
fn raster_over_a_rounded_corner_starts_at_r_minus_the_half_chord() {
    let (w, h, r, d) = (40.0, 20.0, 6.0, 1.5);
    let tracks = fill(
        &rounded(w, h, r),
        &raster(0.0, d, 0.0, Pattern::OneWay),
        0.01,
    )
    .unwrap();
    for &(y, x0, x1) in &rows(&tracks) {
        let n = (y / d).round();
        assert!(close(y, n * d, 1e-12));
        // Below the corner arcs' centres the arcs clip; above, the straight sides.
        let q = (r - y).max(y - (h - r)).max(0.0);
        let expect = r - (r * r - q * q).sqrt();
        assert!(
            close(x0, expect, 1e-9),
            "y {y}: starts at {x0}, expected {expect}"
        );
        assert!(close(x1, w - expect, 1e-9), "y {y}: ends at {x1}");
    }
}

#[test]
fn extension_fills_the_corner_staircase_up_to_the_limit() {
    let (w, h, r, d) = (40.0, 20.0, 6.0, 1.5);
    let p = rounded(w, h, r);
    let bare = rows(&fill(&p, &raster(0.0, d, 0.0, Pattern::OneWay), 0.01).unwrap());
    let ext = rows(&fill(&p, &raster(0.0, d, d, Pattern::OneWay), 0.01).unwrap());
    // Line 0 touches the bottom edge along its whole straight part, so no line is
    // dropped without extension and the rows pair up.
    assert_eq!(bare.len(), ext.len());
    let x = |n: usize| {
        let q = (r - n as f64 * d).max(n as f64 * d - (h - r)).max(0.0);
        r - (r * r - q * q).sqrt()
    };
    let lines = bare.len();
    for (n, (b, e)) in bare.iter().zip(&ext).enumerate() {
        assert_eq!(b.0, e.0);
        let (grow_start, grow_end) = (b.1 - e.1, e.2 - b.2);
        // The neighbour reaching furthest decides, within the limit d.
        let mut reach: f64 = 0.0;
        for m in [n.wrapping_sub(1), n + 1] {
            if m < lines {
                reach = reach.max(x(n) - x(m));
            }
        }
        let expect = if reach > 1e-9 { reach.min(d) } else { 0.0 };
        assert!(
            close(grow_start, expect, 1e-9),
            "line {n}: {grow_start} vs {expect}"
        );
        assert!(
            close(grow_end, expect, 1e-9),
            "line {n}: {grow_end} vs {expect}"
        );
        assert!(grow_start <= d + 1e-12);
        // Along the straight sides nothing is extended.
        if e.0 > r + d && e.0 < h - r - d {
            assert_eq!((grow_start, grow_end), (0.0, 0.0));
        }
    }
    // The corners were extended somewhere, and by the full d at the bottom.
    assert!(close(bare[0].1 - ext[0].1, d, 1e-9));
}

#[test]
fn extension_grows_the_circle_touch_points_into_tracks() {
    let (r, d) = (10.0, 1.6);
    let tracks = fill(
        &Profile::circle(r),
        &raster(0.0, d, d, Pattern::OneWay),
        0.01,
    )
    .unwrap();
    let rows = rows(&tracks);
    // Line 0 touches the circle at its bottom; line 1 reaches X_1 = 5.44 further,
    // so line 0 grows by d each way.
    assert_eq!(rows.len(), 13);
    assert!(close(rows[0].0, -r, 1e-12));
    assert!(close(rows[0].1, -d, 1e-12) && close(rows[0].2, d, 1e-12));
}

#[test]
fn a_rectangle_gets_floor_h_over_d_plus_one_full_lines() {
    for (w, h, d) in [
        (30.0, 10.0, 1.6),
        (30.0, 9.6, 1.6),
        (12.5, 4.8, 1.6),
        (7.0, 3.0, 0.1),
    ] {
        for extend in [0.0, d] {
            let tracks = fill(
                &Profile::rectangle(w, h),
                &raster(0.0, d, extend, Pattern::Serpentine),
                0.01,
            )
            .unwrap();
            let rows = rows(&tracks);
            let lines = (h / d + 1e-9).floor() as usize + 1;
            assert_eq!(rows.len(), lines, "{w}×{h} at {d}");
            for (n, &(y, x0, x1)) in rows.iter().enumerate() {
                assert!(close(y, n as f64 * d, 1e-9), "line {n} at {y}");
                assert_eq!((x0, x1), (0.0, w), "line {n} of {w}×{h} at {d}");
            }
        }
    }
}

#[test]
fn lines_along_slanted_edges_are_the_edges() {
    // A 20 × 6 rectangle turned 30°, rastered along its long sides: the first
    // and the last line lie exactly on them.
    let (w, h, d, angle) = (20.0, 6.0, 1.5, 30.0f64);
    let (s, c) = angle.to_radians().sin_cos();
    let turn = |x: f64, y: f64| Vertex::line(x * c - y * s, x * s + y * c);
    let p = Profile::new(vec![turn(0.0, 0.0), turn(w, 0.0), turn(w, h), turn(0.0, h)]);
    let tracks = fill(&p, &raster(angle, d, d, Pattern::Serpentine), 0.01).unwrap();
    let lines = infill(&tracks);
    assert_eq!(lines.len(), 5);
    for [a, b] in &lines {
        assert!(close((b[0] - a[0]).hypot(b[1] - a[1]), w, 1e-9));
    }
    for [a, b] in [lines[0], lines[4]] {
        for t in [0.0, 0.5, 1.0] {
            let q = [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
            assert!(p.distance_to_boundary(q) < 1e-9, "{q:?} is off the edge");
        }
    }
}

#[test]
fn serpentine_alternates_and_one_way_does_not() {
    let p = rounded(30.0, 12.0, 4.0);
    for angle in [0.0f64, 45.0, 90.0, 200.0] {
        let (s, c) = angle.to_radians().sin_cos();
        let along = |[a, b]: [[f64; 2]; 2]| (b[0] - a[0]) * c + (b[1] - a[1]) * s;
        let serp = infill(&fill(&p, &raster(angle, 1.0, 1.0, Pattern::Serpentine), 0.01).unwrap());
        assert!(serp.len() > 5);
        for (k, t) in serp.iter().enumerate() {
            let dir = along(*t);
            assert!(
                if k % 2 == 0 { dir > 0.0 } else { dir < 0.0 },
                "{angle}° track {k}"
            );
        }
        let one = infill(&fill(&p, &raster(angle, 1.0, 1.0, Pattern::OneWay), 0.01).unwrap());
        assert_eq!(one.len(), serp.len());
        assert!(one.iter().all(|t| along(*t) > 0.0));
        // Lines come in increasing s, across the direction (its left normal).
        let across = |[a, _]: [[f64; 2]; 2]| -a[0] * s + a[1] * c;
        assert!(one.windows(2).all(|w| across(w[1]) > across(w[0]) + 0.999));
    }
}

#[test]
fn a_u_shape_gives_two_intervals_on_lines_through_both_arms() {
    // 30 × 20 with a 10 mm wide notch down to y = 5, open at the top.
    let u = Profile::new(
        [
            (0.0, 0.0),
            (30.0, 0.0),
            (30.0, 20.0),
            (20.0, 20.0),
            (20.0, 5.0),
            (10.0, 5.0),
            (10.0, 20.0),
            (0.0, 20.0),
        ]
        .iter()
        .map(|&(x, y)| Vertex::line(x, y))
        .collect(),
    );
    let d = 1.25;
    let rows = rows(&fill(&u, &raster(0.0, d, d, Pattern::OneWay), 0.01).unwrap());
    let mut lines = 0;
    for n in 0..=16 {
        let y = n as f64 * d;
        let on: Vec<_> = rows
            .iter()
            .filter(|r| r.0 == y)
            .map(|r| (r.1, r.2))
            .collect();
        if y <= 5.0 {
            // Up to and along the notch's floor: one interval across.
            assert_eq!(on, vec![(0.0, 30.0)], "y = {y}");
        } else {
            // The notch's straight walls extend nothing.
            assert_eq!(on, vec![(0.0, 10.0), (20.0, 30.0)], "y = {y}");
        }
        lines += 1;
    }
    assert_eq!(lines, 17);
    assert_eq!(rows.len(), 5 + 2 * 12);
}

#[test]
fn contours_lie_at_their_offsets_and_come_first() {
    let p = rounded(40.0, 24.0, 6.0);
    let spec = FillSpec {
        inset: 0.8,
        contours: 3,
        offset: 1.6,
        raster: Some(RasterSpec {
            angle_deg: 0.0,
            offset: 1.6,
            pattern: Pattern::Serpentine,
            extend: 1.6,
            link: Linking::None,
            closing: f64::INFINITY,
        }),
        seam: Seam::Lowest,
    };
    let tracks = fill(&p, &spec, 0.01).unwrap();
    let kinds: Vec<TrackKind> = tracks.iter().map(|t| t.kind).collect();
    assert_eq!(
        kinds[..3],
        [0, 1, 2].map(|index| TrackKind::Contour { index })
    );
    assert!(kinds[3..].iter().all(|k| *k == TrackKind::Infill));
    for t in &tracks[..3] {
        let TrackKind::Contour { index } = t.kind else {
            unreachable!()
        };
        let depth = 0.8 + index as f64 * 1.6;
        assert_eq!(t.points.first(), t.points.last(), "a contour is closed");
        let start = t.points[0];
        assert!(t
            .points
            .iter()
            .all(|q| (q[1], q[0]) >= (start[1], start[0])));
        for q in &t.points {
            assert!(close(p.distance_to_boundary(*q), depth, 1e-9), "{q:?}");
        }
    }
    // The raster fills what the contours leave: from 0.8 + 3·1.6 = 5.6 in.
    let rows = rows(&tracks);
    assert!(close(rows[0].0, 5.6, 1e-9));
    assert!(close(rows.last().unwrap().0, 24.0 - 5.6, 1e-9));
}

#[test]
fn a_waist_splits_a_contour_pass_into_loops() {
    // Two 10 × 10 squares joined by a 2 mm neck: the second pass no longer fits
    // through it.
    let p = Profile::new(
        [
            (0.0, 0.0),
            (10.0, 0.0),
            (10.0, 4.0),
            (20.0, 4.0),
            (20.0, 0.0),
            (30.0, 0.0),
            (30.0, 10.0),
            (20.0, 10.0),
            (20.0, 6.0),
            (10.0, 6.0),
            (10.0, 10.0),
            (0.0, 10.0),
        ]
        .iter()
        .map(|&(x, y)| Vertex::line(x, y))
        .collect(),
    );
    let spec = FillSpec {
        inset: 0.5,
        contours: 2,
        offset: 1.0,
        raster: None,
        seam: Seam::Lowest,
    };
    let tracks = fill(&p, &spec, 0.01).unwrap();
    let index: Vec<usize> = tracks
        .iter()
        .map(|t| match t.kind {
            TrackKind::Contour { index } => index,
            TrackKind::Infill => panic!("no raster asked for"),
        })
        .collect();
    assert_eq!(index, vec![0, 1, 1]);
    // Loops of one pass in order of their start points: left square first.
    assert!(tracks[1].points[0][0] < tracks[2].points[0][0]);
}

#[test]
fn a_bow_tie_is_rejected_at_its_crossing() {
    let p = Profile::new(vec![
        Vertex::line(0.0, 0.0),
        Vertex::line(2.0, 2.0),
        Vertex::line(2.0, 0.0),
        Vertex::line(0.0, 2.0),
    ]);
    match fill(&p, &raster(0.0, 0.5, 0.5, Pattern::Serpentine), 0.01) {
        Err(FillError::SelfIntersecting { at }) => {
            assert!(close(at[0], 1.0, 1e-6) && close(at[1], 1.0, 1e-6), "{at:?}")
        }
        other => panic!("expected a self-intersection, got {other:?}"),
    }
}

#[test]
fn bad_numbers_are_errors_not_panics() {
    let p = rounded(20.0, 10.0, 3.0);
    let ok = raster(0.0, 1.0, 1.0, Pattern::Serpentine);
    let with = |f: &dyn Fn(&mut FillSpec)| {
        let mut s = ok;
        f(&mut s);
        s
    };
    let r = |f: &dyn Fn(&mut RasterSpec)| {
        with(&|s: &mut FillSpec| {
            let mut rs = s.raster.unwrap();
            f(&mut rs);
            s.raster = Some(rs);
        })
    };
    let cases: Vec<(Profile, FillSpec, f64, &str)> = vec![
        (p.clone(), r(&|r| r.angle_deg = f64::NAN), 0.01, "NonFinite"),
        (
            p.clone(),
            r(&|r| r.offset = f64::INFINITY),
            0.01,
            "NonFinite",
        ),
        (p.clone(), ok, f64::NAN, "NonFinite"),
        (
            p.clone(),
            with(&|s| s.inset = f64::NEG_INFINITY),
            0.01,
            "NonFinite",
        ),
        (p.clone(), r(&|r| r.offset = 0.0), 0.01, "OutOfRange"),
        (p.clone(), r(&|r| r.offset = -1.6), 0.01, "OutOfRange"),
        (p.clone(), r(&|r| r.offset = 1e300), 0.01, "OutOfRange"),
        (p.clone(), r(&|r| r.extend = -1.0), 0.01, "OutOfRange"),
        (p.clone(), with(&|s| s.inset = -0.5), 0.01, "OutOfRange"),
        (p.clone(), ok, 0.0, "OutOfRange"),
        (p.clone(), ok, -1.0, "OutOfRange"),
        (
            p.clone(),
            with(&|s| {
                s.contours = 2;
                s.offset = 0.0
            }),
            0.01,
            "OutOfRange",
        ),
        (p.clone(), r(&|r| r.offset = 1e-7), 0.01, "TooManyLines"),
        (
            p.clone(),
            with(&|s| {
                s.contours = usize::MAX;
                s.offset = 1.0
            }),
            0.01,
            "TooManyContours",
        ),
        (Profile::circle(1e9), ok, 0.01, "OutOfRange"),
        (Profile::circle(f64::NAN), ok, 0.01, "NonFinite"),
        (
            Profile::new(vec![Vertex::arc(0.0, 0.0, 1e300), Vertex::line(1.0, 0.0)]),
            ok,
            0.01,
            "OutOfRange",
        ),
        (Profile::new(vec![]), ok, 0.01, "Empty"),
        (p.clone(), with(&|s| s.inset = 5.5), 0.01, "Empty"),
        (p.clone(), with(&|s| s.raster = None), 0.01, "Empty"),
    ];
    for (i, (profile, spec, chord, want)) in cases.iter().enumerate() {
        let got = fill(profile, spec, *chord);
        let name = match &got {
            Ok(_) => "Ok",
            Err(FillError::NonFinite) => "NonFinite",
            Err(FillError::OutOfRange(_)) => "OutOfRange",
            Err(FillError::TooManyLines(_)) => "TooManyLines",
            Err(FillError::TooManyContours(_)) => "TooManyContours",
            Err(FillError::TooManyPoints(_)) => "TooManyPoints",
            Err(FillError::Empty) => "Empty",
            Err(FillError::SelfIntersecting { .. }) => "SelfIntersecting",
            Err(FillError::Region(_)) => "Region",
        };
        assert_eq!(name, *want, "case {i}: {got:?}");
        if let Err(e) = got {
            // Every message is short and shows no NaN, inf or 300-digit value.
            let m = e.to_string();
            assert!(
                m.len() < 200 && !m.contains("NaN mm") && !m.contains("inf mm"),
                "{m}"
            );
        }
    }
}

#[test]
fn a_comb_with_fine_lines_is_too_many_points_not_a_hang() {
    // 2000 teeth, each 100 mm tall; 50 000 lines would cross 4000 edges each.
    let mut v = vec![Vertex::line(0.0, -1.0), Vertex::line(3999.0, -1.0)];
    for k in (0..2000).rev() {
        let x = 2.0 * k as f64;
        v.extend([
            Vertex::line(x + 1.0, 0.0),
            Vertex::line(x + 1.0, 100.0),
            Vertex::line(x, 100.0),
            Vertex::line(x, 0.0),
        ]);
    }
    let comb = Profile::new(v);
    let spec = raster(0.0, 0.002, 0.0, Pattern::Serpentine);
    assert!(matches!(
        fill(&comb, &spec, 0.01),
        Err(FillError::TooManyPoints(_))
    ));
    // Across the teeth, 8000 lines meet a few edges each: fine.
    let spec = raster(90.0, 0.5, 0.0, Pattern::Serpentine);
    assert!(fill(&comb, &spec, 0.01).is_ok());
}

#[test]
fn eighty_thousand_lines_are_quick() {
    let start = std::time::Instant::now();
    let tracks = fill(
        &Profile::circle(400.0),
        &raster(17.0, 0.01, 0.01, Pattern::Serpentine),
        0.01,
    )
    .unwrap();
    assert_eq!(tracks.len(), 80_001);
    assert!(start.elapsed().as_secs_f64() < 5.0, "{:?}", start.elapsed());
}

#[test]
fn output_is_deterministic() {
    let p = rounded(33.0, 21.0, 7.5);
    let spec = FillSpec {
        inset: 0.3,
        contours: 2,
        offset: 1.1,
        raster: Some(RasterSpec {
            angle_deg: 37.0,
            offset: 0.9,
            pattern: Pattern::Serpentine,
            extend: 0.9,
            link: Linking::None,
            closing: f64::INFINITY,
        }),
        seam: Seam::Lowest,
    };
    let a = fill(&p, &spec, 0.02).unwrap();
    let b = fill(&p, &spec, 0.02).unwrap();
    let pts = |t: &[Track]| {
        t.iter()
            .map(|t| (t.kind, t.points.clone()))
            .collect::<Vec<_>>()
    };
    assert_eq!(pts(&a), pts(&b));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Every track lies within the outline grown by the extension (raster) or
    /// the chord error (contours); contour i lies at inset + i·offset; raster
    /// lines sit whole offsets apart, but for the closing line on the far
    /// extreme and closing tracks on the region's edges within
    /// `PARALLEL_DEG` of the lines.
    #[test]
    fn tracks_stay_inside_the_outline(
        w in 4.0f64..60.0,
        h in 4.0f64..60.0,
        rf in 0.0f64..0.5,
        angle in -360.0f64..360.0,
        d in 0.4f64..3.0,
        ef in 0.0f64..1.2,
        inset in 0.0f64..2.0,
        contours in 0usize..3,
    ) {
        let r = rf * w.min(h);
        let p = rounded(w, h, r);
        let extend = ef * d;
        let chord = 0.01;
        let spec = FillSpec {
            inset,
            contours,
            offset: d,
            raster: Some(RasterSpec { angle_deg: angle, offset: d, pattern: Pattern::Serpentine, extend, link: Linking::None, closing: f64::INFINITY }),
            seam: Seam::Lowest,
        };
        let tracks = match fill(&p, &spec, chord) {
            Ok(t) => t,
            Err(FillError::Empty) => return Ok(()),
            Err(e) => return Err(TestCaseError::fail(format!("{e}"))),
        };
        let slack = extend.max(d) + chord + 1e-9;
        let (s, c) = angle.to_radians().sin_cos();
        let mut across = Vec::new();
        for t in &tracks {
            for pair in t.points.windows(2) {
                for k in 0..=4 {
                    let f = k as f64 / 4.0;
                    let q = [pair[0][0] + f * (pair[1][0] - pair[0][0]), pair[0][1] + f * (pair[1][1] - pair[0][1])];
                    prop_assert!(p.contains(q) || p.distance_to_boundary(q) <= slack, "{q:?} of {t:?}");
                }
            }
            match t.kind {
                TrackKind::Contour { index } => {
                    let depth = inset + index as f64 * d;
                    for q in &t.points {
                        prop_assert!((p.distance_to_boundary(*q) - depth).abs() < 1e-7, "contour {index} at {q:?}");
                    }
                }
                TrackKind::Infill => {
                    let [a, b] = [t.points[0], t.points[1]];
                    // Extension is at most `extend` beyond the raster region.
                    let region_depth = inset + contours as f64 * d;
                    for q in [a, b] {
                        prop_assert!(p.distance_to_boundary(q) >= region_depth - extend - 1e-7 || !p.contains(q));
                    }
                    // A closing track along an edge within PARALLEL_DEG of the
                    // lines lies on the raster region's edge, off the
                    // lines' spacing.
                    let mid = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
                    let on_edge = [a, b, mid].iter().all(|q| (p.distance_to_boundary(*q) - region_depth).abs() < 1e-7);
                    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                    let off = ((dx * c + dy * s).abs() / dx.hypot(dy)).min(1.0).acos().to_degrees();
                    if !(on_edge && off <= lmdc::fill::PARALLEL_DEG + 1e-9) {
                        across.push(-a[0] * s + a[1] * c);
                    }
                }
            }
        }
        // Lines sit whole offsets from the first, but for a closing line on
        // the far extreme, between half an offset and one past the last.
        let first = across.iter().copied().fold(f64::INFINITY, f64::min);
        let last = across.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let whole: Vec<f64> = across
            .iter()
            .map(|a| (a - first) / d)
            .filter(|n| (n - n.round()).abs() < 1e-6)
            .collect();
        let top = whole.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        for a in &across {
            let n = (a - first) / d;
            if (n - n.round()).abs() >= 1e-6 {
                prop_assert!((a - last).abs() < 1e-9, "line at {n} offsets is not the last");
                let gap = n - top;
                prop_assert!(gap > lmdc::fill::CLOSING - 1e-9 && gap < 1.0, "closing line {gap} offsets past the last");
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// Star-shaped outlines with bulging (often concave) pieces: every fill
    /// either succeeds within the grown outline or says why not, and contour
    /// points sit at their depth.
    #[test]
    fn star_outlines_fill_or_fail_cleanly(
        pts in prop::collection::vec((0.0f64..1.0, 1.0f64..30.0, -1.5f64..1.5), 3..14),
        angle in -360.0f64..360.0,
        d in 0.2f64..3.0,
        ef in 0.0f64..1.2,
        inset in 0.0f64..3.0,
        contours in 0usize..4,
    ) {
        let n = pts.len();
        let p = Profile::new(pts.iter().enumerate().map(|(i, &(a, r, b))| {
            let phi = (i as f64 + 0.9 * a) / n as f64 * 2.0 * PI;
            Vertex::arc(r * phi.cos(), r * phi.sin(), b)
        }).collect());
        let extend = ef * d;
        let spec = FillSpec {
            inset,
            contours,
            offset: d,
            raster: Some(RasterSpec { angle_deg: angle, offset: d, pattern: Pattern::OneWay, extend, link: Linking::None, closing: f64::INFINITY }),
            seam: Seam::Lowest,
        };
        let tracks = match fill(&p, &spec, 0.01) {
            Ok(t) => t,
            Err(FillError::Empty | FillError::SelfIntersecting { .. }) => return Ok(()),
            Err(e) => return Err(TestCaseError::fail(format!("{e}"))),
        };
        let slack = extend.max(d) + 0.01 + 1e-7;
        for t in &tracks {
            for q in &t.points {
                prop_assert!(p.contains(*q) || p.distance_to_boundary(*q) <= slack, "{q:?}");
                if let TrackKind::Contour { index } = t.kind {
                    let depth = inset + index as f64 * d;
                    prop_assert!((p.distance_to_boundary(*q) - depth).abs() < 1e-6, "contour {index} at {q:?}");
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// On convex profiles a raster whose lines are at most a bead apart, ends
    /// extended by up to the offset, leaves no spot a bead width from every
    /// track — with or without contour passes round it — as long as the raster
    /// region has an inside: two offsets across. A strip narrower than one
    /// offset, crossed by oblique lines, really is left in pieces (w = 4 mm,
    /// inset 1.83 mm: a 0.35 mm strip, lines at −99°, 11 mm apart along it),
    /// and the check rightly says so.
    #[test]
    fn convex_fills_leave_no_gap(
        w in 4.0f64..60.0,
        h in 4.0f64..60.0,
        rf in 0.0f64..0.5,
        angle in -360.0f64..360.0,
        d in 0.4f64..3.0,
        overlap in 0.0f64..0.7,
        inset in 0.0f64..2.0,
        contours in 0usize..3,
    ) {
        let bead = d / (1.0 - overlap);
        if w.min(h) - 2.0 * (inset + contours as f64 * d) < 2.0 * d {
            return Ok(());
        }
        let p = rounded(w, h, rf * w.min(h));
        let spec = FillSpec {
            inset,
            contours,
            offset: d,
            raster: Some(RasterSpec { angle_deg: angle, offset: d, pattern: Pattern::Serpentine, extend: d, link: Linking::None, closing: f64::INFINITY }),
            seam: Seam::Lowest,
        };
        let tracks = match fill(&p, &spec, 0.01) {
            Ok(t) => t,
            Err(FillError::Empty) => return Ok(()),
            Err(e) => return Err(TestCaseError::fail(format!("{e}"))),
        };
        prop_assert_eq!(lmdc::fill::gap(&p, inset, &tracks, bead, lmdc::fill::MAX_SAMPLES), None);
        // Without the raster only the contours are left: a profile wider than
        // the passes then has an unfilled middle, and the check sees it.
        let walls: Vec<_> = tracks.iter().filter(|t| t.kind != TrackKind::Infill).cloned().collect();
        if contours > 0 && w.min(h) - 2.0 * inset > 2.0 * (contours as f64 * d + 2.0 * bead) {
            prop_assert!(lmdc::fill::gap(&p, inset, &walls, bead, lmdc::fill::MAX_SAMPLES).is_some());
        }
    }
}

/// A 60 × 40 mm U whose notch's walls run along a 90° raster's lines, one
/// contour (offset 1.4 mm, bead 2 mm, inset 1 mm): the raster's region is
/// the U 2.4 mm in, its notch walls at x = 17.9 and 42.7 mm. The lines,
/// 1.4 mm apart from x = 57.6, pass 0.9 mm beside each wall (at 17.0 and
/// 43.6), so with the contour 1.4 mm beyond the wall a strip 2.3 mm wide
/// lay between line and contour, wider than the bead. A closing track runs
/// on each wall, from the arc round the notch's corner (y = 15) to the top
/// (y = 37.6), and no two neighbours are left farther apart than the bead.
fn notched_u(notch: [f64; 2]) -> Profile {
    Profile::new(
        [
            (0.0, 0.0),
            (60.0, 0.0),
            (60.0, 40.0),
            (notch[1], 40.0),
            (notch[1], 15.0),
            (notch[0], 15.0),
            (notch[0], 40.0),
            (0.0, 40.0),
        ]
        .iter()
        .map(|&(x, y)| Vertex::line(x, y))
        .collect(),
    )
}

/// One contour and a raster at `angle`, `d` apart, for a bead `w` wide
/// (inset half a bead, the closing threshold `w − d`, or half an offset
/// where that is less), laser-on links or none.
fn contour_and_raster(angle: f64, d: f64, w: f64, link: Linking) -> FillSpec {
    let mut spec = super::holes::spec(w, d, 1, angle, link);
    if let Some(r) = spec.raster.as_mut() {
        r.closing = w - d;
    }
    spec
}

/// The strips `tracks` fill (lmd::fill-gap's measure: `apart`, the widest
/// gap between neighbouring deposits, if any are farther apart than `w`).
fn strips(p: &Profile, tracks: &[Track], [w, d]: [f64; 2]) -> lmdc::fill::pitch::Strips {
    let strands: Vec<_> = tracks
        .iter()
        .enumerate()
        .map(|(chain, t)| lmdc::fill::pitch::Strand {
            points: &t.points,
            chain,
        })
        .collect();
    lmdc::fill::pitch::strips(&strands, [w, d], 50_000, |q| p.contains(q))
}

/// [`strips`]'s widest gap.
fn apart(p: &Profile, tracks: &[Track], wd: [f64; 2]) -> Option<lmdc::fill::pitch::Apart> {
    strips(p, tracks, wd).apart
}

#[test]
fn walls_along_the_lines_get_a_closing_track() {
    let u = notched_u([20.3, 40.3]);
    let (w, d) = (2.0, 1.4);
    let tracks = fill(&u, &contour_and_raster(90.0, d, w, Linking::None), 0.01).unwrap();
    let on = |x: f64| {
        infill(&tracks)
            .into_iter()
            .filter(|[a, b]| close(a[0], x, 1e-9) && close(b[0], x, 1e-9))
            .map(|[a, b]| (a[1].min(b[1]), a[1].max(b[1])))
            .collect::<Vec<_>>()
    };
    for x in [17.9, 42.7] {
        let got = on(x);
        assert_eq!(got.len(), 1, "x = {x}: {got:?}");
        assert!(
            close(got[0].0, 15.0, 1e-9) && close(got[0].1, 37.6, 1e-9),
            "x = {x}: {got:?}"
        );
    }
    // The lines beside them are where the spacing puts them.
    assert_eq!(on(17.0).len(), 1);
    assert_eq!(on(43.6).len(), 1);
    assert_eq!(apart(&u, &tracks, [w, d]), None);
    // Without them the strips are left: what the closing tracks are for.
    let without: Vec<Track> = tracks
        .iter()
        .filter(|t| !(close(t.points[0][0], 17.9, 1e-9) || close(t.points[0][0], 42.7, 1e-9)))
        .cloned()
        .collect();
    let gap = apart(&u, &without, [w, d]).expect("a strip wider than the bead");
    assert!(close(gap.apart, 2.3, 1e-6), "{gap:?}");
}

/// The same U with its walls split into collinear pieces 1 mm long, as a
/// mesh's section or a drawing with points along a side gives them, each
/// shorter than the two offsets a closing track needs: the walls get the
/// same tracks, one each, as whole walls do.
#[test]
fn walls_split_into_short_collinear_pieces_get_the_same_closing_track() {
    let whole = notched_u([20.3, 40.3]);
    let mut v: Vec<(f64, f64)> = vec![(0.0, 0.0), (60.0, 0.0), (60.0, 40.0)];
    v.extend((0..=25).map(|k| (40.3, 40.0 - k as f64)));
    v.extend((0..=25).map(|k| (20.3, 15.0 + k as f64)));
    v.push((0.0, 40.0));
    let split = Profile::new(v.iter().map(|&(x, y)| Vertex::line(x, y)).collect());
    let spec = contour_and_raster(90.0, 1.4, 2.0, Linking::None);
    let closing = |p: &Profile| {
        let tracks = fill(p, &spec, 0.01).unwrap();
        let mut on: Vec<[[f64; 2]; 2]> = infill(&tracks)
            .into_iter()
            .filter(|[a, b]| {
                [17.9, 42.7]
                    .iter()
                    .any(|&x| close(a[0], x, 1e-9) && close(b[0], x, 1e-9))
            })
            .collect();
        on.sort_by(|a, b| a[0][0].total_cmp(&b[0][0]));
        on
    };
    let want = closing(&whole);
    assert_eq!(want.len(), 2, "{want:?}");
    let got = closing(&split);
    assert_eq!(got.len(), 2, "{got:?}");
    for (g, w) in got.iter().zip(&want) {
        let (gy, wy) = (
            [g[0][1].min(g[1][1]), g[0][1].max(g[1][1])],
            [w[0][1].min(w[1][1]), w[0][1].max(w[1][1])],
        );
        assert!(
            close(gy[0], wy[0], 1e-6) && close(gy[1], wy[1], 1e-6),
            "{g:?} against {w:?}"
        );
    }
}

/// A wall whose line beside it lies within the closing threshold (the bead
/// less the offset, 0.6 mm) gets none: the notch from x = 19.9 puts the
/// left wall at 17.5, 0.5 mm from the line at 17.0; the right wall, 0.9 mm
/// from its line, still gets one.
#[test]
fn a_closing_track_only_where_the_line_beside_is_too_far() {
    let u = notched_u([19.9, 40.3]);
    let tracks = fill(&u, &contour_and_raster(90.0, 1.4, 2.0, Linking::None), 0.01).unwrap();
    let at = |x: f64| {
        infill(&tracks)
            .iter()
            .filter(|[a, b]| close(a[0], x, 1e-9) && close(b[0], x, 1e-9))
            .count()
    };
    assert_eq!(at(17.5), 0);
    assert_eq!(at(17.0), 1);
    assert_eq!(at(42.7), 1);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Notched plates at any raster angle, the lines any distance from the
    /// notch's walls and the plate's sides (angles within a hundredth of a
    /// degree of them among the cases), linked or not: no two neighbouring
    /// deposits are left farther apart than the bead, and none is laid on
    /// another (every move's strip at least 30 % of the bead: a closing
    /// track on a line would halve both).
    #[test]
    fn no_strip_is_left_beside_an_edge_along_the_lines(
        left in 12.0f64..25.0,
        width in 8.0f64..20.0,
        angle in prop_oneof![0.0f64..180.0, (0usize..4, -0.02f64..0.02).prop_map(|(k, e)| k as f64 * 90.0 + e)],
        d in 1.2f64..1.9,
        link in prop_oneof![Just(Linking::None), Just(Linking::LaserOn), Just(Linking::LaserOff)],
    ) {
        let (w, u) = (2.2, notched_u([left, left + width]));
        let tracks = fill(&u, &contour_and_raster(angle, d, w, link), 0.01)
            .map_err(|e| TestCaseError::fail(format!("{e}")))?;
        let found = strips(&u, &tracks, [w, d]);
        prop_assert_eq!(found.apart, None);
        let least = found.pitch.iter().flatten().copied().fold(f64::INFINITY, f64::min);
        prop_assert!(least >= 0.3 * w, "a strip {} mm wide", least);
    }
}
