//! Planar fills of regions with holes, linked raster and seams, checked
//! against the exact geometry: no track point inside a hole grown by half a
//! bead, raster tracks never across a hole, links never outside the part
//! less half a bead, seams where the rule puts them.

use lmdc::fill::{
    fill_region, gap_in, FillError, FillSpec, Linking, Pattern, RasterSpec, Seam, Track, TrackKind,
};
use lmdc::geometry::profile::Profile;
use lmdc::geometry::region::{Fault, Region};
use proptest::prelude::*;
use std::f64::consts::PI;

fn circle_at(r: f64, x: f64, y: f64) -> Profile {
    Profile::circle(r).placed(0.0, [x, y])
}

/// The flange of examples/flange.lmd: 120 mm across, a 50 mm bore, six
/// 12 mm bolt holes on an 85 mm circle.
fn flange() -> Region {
    let mut holes = vec![Profile::circle(25.0)];
    for k in 0..6 {
        let a = k as f64 * PI / 3.0;
        holes.push(circle_at(6.0, 42.5 * a.cos(), 42.5 * a.sin()));
    }
    Region::new(Profile::circle(60.0), holes)
}

/// `size = outer` with bead width `w`: inset w/2, tracks `d` apart.
pub(super) fn spec(w: f64, d: f64, contours: usize, angle: f64, link: Linking) -> FillSpec {
    FillSpec {
        inset: w / 2.0,
        contours,
        offset: d,
        raster: Some(RasterSpec {
            angle_deg: angle,
            offset: d,
            pattern: Pattern::Serpentine,
            extend: d,
            link,
            closing: f64::INFINITY,
        }),
        seam: Seam::Lowest,
    }
}

/// Each path the nozzle follows without stopping: linked tracks together,
/// with their link points.
fn paths(tracks: &[Track]) -> Vec<Vec<[f64; 2]>> {
    let mut out: Vec<Vec<[f64; 2]>> = Vec::new();
    let mut open = false;
    for t in tracks {
        if !open {
            out.push(Vec::new());
        }
        let path = out.last_mut().unwrap();
        path.extend_from_slice(&t.points);
        open = t.link.is_some();
        if let Some(l) = &t.link {
            path.extend_from_slice(&l.via);
        }
    }
    out
}

/// Every link as the polyline the nozzle follows, from a track's last point
/// through the link to the next track's first point, with the two tracks.
fn links(tracks: &[Track]) -> Vec<(&Track, Vec<[f64; 2]>, &Track)> {
    tracks
        .windows(2)
        .filter_map(|w| {
            let l = w[0].link.as_ref()?;
            let mut poly = vec![*w[0].points.last()?];
            poly.extend_from_slice(&l.via);
            poly.push(w[1].points[0]);
            Some((&w[0], poly, &w[1]))
        })
        .collect()
}

/// Whether the segment a–b lies on the straight track `t` (a link that runs
/// back along its own track, laser off, over the track's extension).
fn on_track(t: &Track, a: [f64; 2], b: [f64; 2]) -> bool {
    let (p, q) = (t.points[0], t.points[t.points.len() - 1]);
    let dist = |x: [f64; 2]| {
        let d = [q[0] - p[0], q[1] - p[1]];
        let len2 = d[0] * d[0] + d[1] * d[1];
        let f = (((x[0] - p[0]) * d[0] + (x[1] - p[1]) * d[1]) / len2).clamp(0.0, 1.0);
        (x[0] - p[0] - f * d[0]).hypot(x[1] - p[1] - f * d[1])
    };
    dist(a) < 1e-9 && dist(b) < 1e-9
}

/// Whether every segment of every link stays in the region less `inset`
/// (or runs along one of its own two tracks).
fn links_inside(region: &Region, tracks: &[Track], inset: f64, tol: f64) -> Result<(), String> {
    for (a, poly, b) in links(tracks) {
        for w in poly.windows(2) {
            let ok = segment_inside(region, w[0], w[1], inset, tol)
                || on_track(a, w[0], w[1])
                || on_track(b, w[0], w[1]);
            if !ok {
                return Err(format!(
                    "link segment {:?}–{:?} leaves the part",
                    w[0], w[1]
                ));
            }
        }
    }
    Ok(())
}

/// How far `p` is inside `region` less `inset` (negative: outside it).
fn depth(region: &Region, p: [f64; 2]) -> f64 {
    let d = region.distance_to_boundary(p);
    if region.contains(p) {
        d
    } else {
        -d
    }
}

/// Whether the segment a–b keeps at least `inset − tol` from the region's
/// boundary and inside it, sampled finely (an independent check of the
/// exact one the links pass).
fn segment_inside(region: &Region, a: [f64; 2], b: [f64; 2], inset: f64, tol: f64) -> bool {
    let n = (((b[0] - a[0]).hypot(b[1] - a[1])) / 0.01).ceil().max(1.0) as usize;
    (0..=n).all(|k| {
        let f = k as f64 / n as f64;
        let p = [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])];
        depth(region, p) >= inset - tol
    })
}

#[test]
fn the_flange_gets_contours_round_every_hole_and_a_raster_between() {
    let r = flange();
    let tracks = fill_region(&r, &spec(3.0, 2.0, 1, 0.0, Linking::None), 0.02).unwrap();
    let contours: Vec<&Track> = tracks
        .iter()
        .filter(|t| matches!(t.kind, TrackKind::Contour { .. }))
        .collect();
    // The outline and seven holes, each its own loop 1.5 mm from the face.
    assert_eq!(contours.len(), 8);
    for t in &contours {
        for &p in &t.points {
            assert!((r.distance_to_boundary(p) - 1.5).abs() < 1e-9, "{p:?}");
        }
    }
    // Round a hole the loop runs clockwise: the part on its left.
    let around_bore = contours
        .iter()
        .find(|t| t.points[0][0].hypot(t.points[0][1]) < 30.0)
        .unwrap();
    let twice: f64 = around_bore
        .points
        .windows(2)
        .map(|w| w[0][0] * w[1][1] - w[1][0] * w[0][1])
        .sum();
    assert!(twice < 0.0);
    // Raster tracks never cross a hole: every point of every track is in
    // the part at least half a bead from every face.
    for t in tracks.iter().filter(|t| t.kind == TrackKind::Infill) {
        assert!(segment_inside(&r, t.points[0], t.points[1], 1.5, 1e-9));
    }
    // And they cover it.
    assert_eq!(gap_in(&r, 0.0, &tracks, 2.25, 40_000), None);
}

#[test]
fn linking_makes_a_few_chains_that_stay_inside() {
    let r = flange();
    let plain = fill_region(&r, &spec(3.0, 2.0, 1, 0.0, Linking::None), 0.02).unwrap();
    let linked = fill_region(&r, &spec(3.0, 2.0, 1, 0.0, Linking::LaserOn), 0.02).unwrap();
    let raster = |ts: &[Track]| ts.iter().filter(|t| t.kind == TrackKind::Infill).count();
    // The same tracks, reordered and linked.
    assert_eq!(raster(&plain), raster(&linked));
    let starts_before = raster(&plain);
    let chains = paths(&linked[8..]);
    assert!(
        chains.len() * 4 < starts_before,
        "{} chains for {} tracks",
        chains.len(),
        starts_before
    );
    links_inside(&r, &linked, 1.5, 1e-9).unwrap();
    assert_eq!(gap_in(&r, 0.0, &linked, 2.25, 40_000), None);
}

#[test]
fn without_contours_the_links_follow_the_hole_edges() {
    let r = flange();
    let tracks = fill_region(&r, &spec(3.0, 2.0, 0, 30.0, Linking::LaserOff), 0.02).unwrap();
    let linked = tracks.iter().filter(|t| t.link.is_some()).count();
    assert!(linked * 2 > tracks.len(), "{linked} of {}", tracks.len());
    // Concave edges are followed by tangents: never into a hole.
    links_inside(&r, &tracks, 1.5, 1e-9).unwrap();
}

#[test]
fn holes_that_meet_the_outline_or_each_other_are_errors() {
    let outline = Profile::rectangle(40.0, 20.0);
    let s = spec(2.0, 1.5, 1, 0.0, Linking::None);
    let crossing = Region::new(outline.clone(), vec![circle_at(3.0, 39.0, 10.0)]);
    assert!(matches!(
        fill_region(&crossing, &s, 0.02),
        Err(FillError::Region(Fault::HoleOutline { hole: 0, .. }))
    ));
    let apart = Region::new(
        outline.clone(),
        vec![circle_at(3.0, 10.0, 10.0), circle_at(3.0, 15.0, 10.0)],
    );
    let e = fill_region(&apart, &s, 0.02).unwrap_err();
    assert_eq!(
        e.to_string(),
        "holes 1 and 2 cross or touch near x = 12.5 mm, y = 11.6583 mm"
    );
    let outside = Region::new(outline, vec![circle_at(3.0, 100.0, 10.0)]);
    assert_eq!(
        fill_region(&outside, &s, 0.02).unwrap_err().to_string(),
        "hole 1 lies outside the outline"
    );
}

#[test]
fn seams_go_where_the_rule_puts_them() {
    let r = flange();
    let mut s = spec(3.0, 2.0, 1, 0.0, Linking::None);
    for k in 0..8 {
        let a = k as f64 * 137.5f64.to_radians();
        s.seam = Seam::Toward(a);
        let tracks = fill_region(&r, &s, 0.02).unwrap();
        let outer = tracks
            .iter()
            .find(|t| t.points[0][0].hypot(t.points[0][1]) > 50.0)
            .unwrap();
        let p = outer.points[0];
        assert!((p[0] - 58.5 * a.cos()).abs() < 1e-9 && (p[1] - 58.5 * a.sin()).abs() < 1e-9);
        assert_eq!(outer.points.last(), Some(&p));
    }
}

/// A random region: a rounded rectangle with up to 5 round or square holes
/// kept apart from each other and the edge by at least `gap`.
fn region_strategy() -> impl Strategy<Value = Region> {
    let hole = (
        0.05f64..0.95,
        0.05f64..0.95,
        0.5f64..6.0,
        any::<bool>(),
        0.0f64..1.0,
    );
    (
        30.0f64..80.0,
        30.0f64..80.0,
        0.0f64..0.4,
        prop::collection::vec(hole, 0..6),
    )
        .prop_map(|(w, h, rf, holes)| {
            let outline = Profile::rounded_rectangle(w, h, rf * w.min(h) / 2.0);
            let mut kept: Vec<(f64, f64, f64)> = Vec::new();
            let mut loops = Vec::new();
            for (fx, fy, r, square, turn) in holes {
                let (x, y) = (fx * w, fy * h);
                // A square's corners reach r·√2 from its centre.
                let reach = if square { r * 2f64.sqrt() } else { r };
                let margin = 0.5;
                let fits = x - reach > margin
                    && y - reach > margin
                    && x + reach < w - margin
                    && y + reach < h - margin
                    && outline.distance_to_boundary([x, y]) > reach + margin
                    && outline.contains([x, y])
                    && kept
                        .iter()
                        .all(|&(a, b, c)| (x - a).hypot(y - b) > reach + c + margin);
                if !fits {
                    continue;
                }
                kept.push((x, y, reach));
                loops.push(if square {
                    Profile::rectangle(2.0 * r, 2.0 * r).placed(turn * PI, [0.0, 0.0])
                } else {
                    Profile::circle(r)
                });
                let l = loops.pop().unwrap();
                let l = if square {
                    // Centre the square on the origin before placing it.
                    let c = l.placed(0.0, [0.0, 0.0]);
                    let [lo, hi] = c.bounds().unwrap();
                    let mid = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
                    c.placed(0.0, [x - mid[0], y - mid[1]])
                } else {
                    l.placed(0.0, [x, y])
                };
                loops.push(l);
            }
            Region::new(outline, loops)
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn no_track_point_lies_inside_a_hole_grown_by_half_a_bead(
        region in region_strategy(),
        w in 1.0f64..4.0,
        df in 0.6f64..1.0,
        contours in 0usize..3,
        angle in 0.0f64..180.0,
        link in prop::sample::select(vec![Linking::None, Linking::LaserOn, Linking::LaserOff]),
    ) {
        let d = df * w;
        let s = spec(w, d, contours, angle, link);
        let tracks = match fill_region(&region, &s, 0.02) {
            Ok(t) => t,
            Err(FillError::Empty) => return Ok(()),
            Err(e) => return Err(TestCaseError::fail(format!("{e}"))),
        };
        let half = w / 2.0;
        for t in &tracks {
            for &p in &t.points {
                for h in region.holes() {
                    let inside = h.contains(p) && h.distance_to_boundary(p) > 1e-9;
                    prop_assert!(!inside, "{p:?} inside a hole");
                    prop_assert!(h.distance_to_boundary(p) >= half - 1e-7,
                        "{p:?} is {} from a hole", h.distance_to_boundary(p));
                }
            }
            if t.kind == TrackKind::Infill {
                // Raster tracks never cross a hole (grown by the inset).
                for h in region.holes() {
                    let grown = h.offset_inward(-half);
                    for g in &grown {
                        let (a, b) = (t.points[0], t.points[1]);
                        let n = (((b[0] - a[0]).hypot(b[1] - a[1])) / 0.02).ceil().max(1.0) as usize;
                        for k in 0..=n {
                            let f = k as f64 / n as f64;
                            let q = [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])];
                            prop_assert!(!(g.contains(q) && g.distance_to_boundary(q) > 1e-7),
                                "track {a:?}–{b:?} crosses a hole at {q:?}");
                        }
                    }
                }
            }
        }
        // Links never leave the part less half a bead.
        if let Err(e) = links_inside(&region, &tracks, half, 1e-7) {
            return Err(TestCaseError::fail(e));
        }
    }
}

/// The error case of a contour laid as a lone bead beside a hole's crest
/// (one contour, a narrow speed range): the message says why and what
/// builds it, and both fixes it names do build the plate.
#[test]
fn a_lone_contour_beside_a_hole_is_explained_and_both_fixes_build() {
    let path = std::path::Path::new("tests/cases/errors/holes/lone_contour_at_a_hole/input.lmd");
    let src = std::fs::read_to_string(path).expect("the case's input");
    let c = crate::support::example::compile_file(path, &src);
    let d = c
        .diagnostics
        .iter()
        .find(|d| d.code == lmdc::diag::Code::PointSpeed)
        .expect("the contour is refused as too slow");
    let help = d.help.as_deref().expect("a help");
    assert!(
        help.contains("lone bead") && help.contains("3 mm wide"),
        "{help}"
    );
    // The speed the help names is what the lone bead needs: a range that
    // reaches it builds the plate, one that stops short of it does not.
    let needs: f64 = help
        .split("down to ")
        .nth(1)
        .and_then(|s| s.split(' ').next())
        .and_then(|s| s.parse().ok())
        .expect("a speed in the help");
    assert!(needs < 6.0 && needs > 4.0, "{needs}");
    for fix in [
        src.replace("contours = 1", "contours = 2"),
        src.replace(
            "speed = 6 mm/s .. 14 mm/s",
            &format!("speed = {:.2} mm/s .. 14 mm/s", needs - 0.01),
        ),
    ] {
        let c = crate::support::example::compile_file(path, &fix);
        let errors: Vec<String> = c
            .diagnostics
            .iter()
            .filter(|d| d.is_error())
            .map(|d| d.to_string())
            .collect();
        assert!(errors.is_empty(), "{errors:?}");
    }
    let short = src.replace(
        "speed = 6 mm/s .. 14 mm/s",
        &format!("speed = {:.2} mm/s .. 14 mm/s", needs + 0.02),
    );
    let c = crate::support::example::compile_file(path, &short);
    assert!(c
        .diagnostics
        .iter()
        .any(|d| d.code == lmdc::diag::Code::PointSpeed));
}

/// The longest stretch (mm) of any contour of `tracks` farther than `w`
/// from every other track, sampled every 0.05 mm; a place within two beads
/// of a corner of its contour (turning by more than 30° within half a bead) ends a
/// stretch: a corner's point lies an offset times √2 or more from the
/// raster's corner, whatever is laid.
fn longest_lone_stretch(tracks: &[Track], w: f64) -> f64 {
    let segments =
        |t: &Track| -> Vec<[[f64; 2]; 2]> { t.points.windows(2).map(|s| [s[0], s[1]]).collect() };
    let mut longest: f64 = 0.0;
    for (i, t) in tracks.iter().enumerate() {
        if !matches!(t.kind, TrackKind::Contour { .. }) {
            continue;
        }
        let others: Vec<[[f64; 2]; 2]> = tracks
            .iter()
            .enumerate()
            .filter(|&(j, _)| j != i)
            .flat_map(|(_, o)| segments(o))
            .collect();
        let near = |p: [f64; 2]| {
            others.iter().any(|&[a, b]| {
                let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                let l2 = dx * dx + dy * dy;
                let f = if l2 > 0.0 {
                    (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                (p[0] - a[0] - f * dx).hypot(p[1] - a[1] - f * dy) <= w
            })
        };
        let n = t.points.len();
        // A corner: the contour turns by more than 30° within half a bead
        // either side of a point (a tight fillet counts as one).
        let m = n - 1;
        let dist = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
        let reach = |k: usize, forward: bool| {
            let mut j = k;
            for _ in 0..m {
                j = if forward {
                    (j + 1) % m
                } else {
                    (j + m - 1) % m
                };
                if dist(t.points[j], t.points[k]) >= w / 2.0 {
                    break;
                }
            }
            t.points[j]
        };
        let corners: Vec<[f64; 2]> = (0..m)
            .filter(|&k| {
                let (a, b, c) = (reach(k, false), t.points[k], reach(k, true));
                let (u, v) = ([b[0] - a[0], b[1] - a[1]], [c[0] - b[0], c[1] - b[1]]);
                let cos = (u[0] * v[0] + u[1] * v[1]) / (u[0].hypot(u[1]) * v[0].hypot(v[1]));
                cos < 30f64.to_radians().cos()
            })
            .map(|k| t.points[k])
            .collect();
        let cornered = |p: [f64; 2]| {
            corners
                .iter()
                .any(|c| (c[0] - p[0]).hypot(c[1] - p[1]) < 2.0 * w)
        };
        let mut run = 0.0;
        // Twice round, so a stretch across the seam is measured whole.
        for k in 0..2 * (n - 1) {
            let (a, b) = (t.points[k % (n - 1)], t.points[k % (n - 1) + 1]);
            let len = (b[0] - a[0]).hypot(b[1] - a[1]);
            let steps = (len / 0.05).ceil().max(1.0) as usize;
            for j in 0..steps {
                let f = (j as f64 + 0.5) / steps as f64;
                let p = [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])];
                if near(p) || cornered(p) {
                    run = 0.0;
                } else {
                    run += len / steps as f64;
                    longest = longest.max(run);
                }
            }
        }
    }
    longest
}

/// The flange with one contour and the closing threshold the slicer sets
/// (the bead less the offset): where a raster line runs past a bolt hole's
/// crest, or past the outline's arc between two holes, the contour beyond
/// would be left without a track within a bead over more than a bead's
/// length; a closing track runs there along the raster's margin, an offset
/// inside the contour, and no such stretch is left.
#[test]
fn no_contour_is_left_without_a_track_within_a_bead_over_a_bead() {
    let r = flange();
    let (w, d) = (3.0, 2.17);
    for angle in [0.0, 30.0, 45.0, 90.0, 137.5] {
        let mut s = spec(w, d, 1, angle, Linking::None);
        s.raster.as_mut().unwrap().closing = w - d;
        let tracks = fill_region(&r, &s, 0.02).unwrap();
        let on_margin = |t: &Track| {
            t.kind == TrackKind::Infill
                && t.points.windows(2).all(|s| {
                    let mid = [(s[0][0] + s[1][0]) / 2.0, (s[0][1] + s[1][1]) / 2.0];
                    [s[0], mid]
                        .iter()
                        .all(|&p| (r.distance_to_boundary(p) - (1.5 + d)).abs() < 0.01)
                })
        };
        let margin = tracks.iter().filter(|t| on_margin(t)).count();
        let with = longest_lone_stretch(&tracks, w);
        let without: Vec<Track> = tracks.iter().filter(|t| !on_margin(t)).cloned().collect();
        let before = longest_lone_stretch(&without, w);
        // 8 mm at every angle without them, under 2.4 mm with them.
        assert!(
            margin > 0 && before > 2.0 * w,
            "{angle}°: {margin}, {before}"
        );
        assert!(with < w, "{angle}°: a contour {with} mm from every track");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Random plates with round and square holes, one or two contours
    /// and the slicer's closing threshold, at any raster angle: every
    /// raster track, the margin's closing tracks among them, lies in the
    /// part at least half a bead from every face (a closing track runs on
    /// the raster's margin, an offset inside the innermost contour).
    #[test]
    fn closing_tracks_on_the_margin_stay_half_a_bead_inside(
        region in region_strategy(),
        w in 1.0f64..4.0,
        df in 0.6f64..1.0,
        contours in 1usize..3,
        angle in 0.0f64..180.0,
    ) {
        let d = df * w;
        let mut s = spec(w, d, contours, angle, Linking::None);
        s.raster.as_mut().unwrap().closing = w - d;
        let tracks = match fill_region(&region, &s, 0.02) {
            Ok(t) => t,
            Err(FillError::Empty) => return Ok(()),
            Err(e) => return Err(TestCaseError::fail(format!("{e}"))),
        };
        for t in tracks.iter().filter(|t| t.kind == TrackKind::Infill) {
            for &p in &t.points {
                prop_assert!(region.distance_to_boundary(p) >= w / 2.0 - 1e-7 && region.contains(p),
                    "{p:?} is {} from a face", region.distance_to_boundary(p));
            }
        }
    }
}
