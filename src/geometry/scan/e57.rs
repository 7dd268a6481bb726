//! E57 scans (ASTM E2807), the exchange format of laser scanners, read
//! with the `e57` crate: every point cloud's valid Cartesian points, each
//! cloud's own pose applied and spherical coordinates converted (the
//! crate's simple reader), in mm. The standard's unit is the metre, so an
//! E57's numbers are metres whatever `units` says (as a 3MF's unit is its
//! own). A scan's points only: E57 holds no faces. Like every scan's,
//! its points are kept as `f32` in mm: to a micrometre within 10 m of the
//! file's origin, 0.06 mm at 1 km; a georeferenced scan far from its
//! origin loses that much before `at` moves it.

use super::{Raw, ScanError, MAX_POINTS};
use e57::{CartesianCoordinate, E57Reader};
use std::io::Cursor;

/// mm per metre, the E57 standard's unit.
pub const MM_PER_UNIT: f64 = 1000.0;

/// The points of the E57 file `bytes`, in mm.
pub fn read(bytes: &[u8]) -> Result<Raw, ScanError> {
    let why = |e: e57::Error| ScanError::E57(e.to_string());
    let mut reader = E57Reader::new(Cursor::new(bytes)).map_err(why)?;
    let clouds = reader.pointclouds();
    // The header's counts, before any point is read.
    let count: u64 = clouds
        .iter()
        .map(|pc| pc.records)
        .fold(0, u64::saturating_add);
    if count > MAX_POINTS as u64 {
        return Err(ScanError::TooMany {
            what: "points",
            count,
            max: MAX_POINTS,
        });
    }
    // A header may claim more than the file holds: reserve no more than
    // its bytes could.
    let mut vertices = Vec::with_capacity((count as usize).min(bytes.len() / 12));
    for pc in &clouds {
        for p in reader.pointcloud_simple(pc).map_err(why)? {
            if let CartesianCoordinate::Valid { x, y, z } = p.map_err(why)?.cartesian {
                if vertices.len() == MAX_POINTS {
                    return Err(ScanError::TooMany {
                        what: "points",
                        count: count.max(MAX_POINTS as u64 + 1),
                        max: MAX_POINTS,
                    });
                }
                let mm = [x, y, z].map(|c| (c * MM_PER_UNIT) as f32);
                vertices.push(mm);
            }
        }
    }
    let raw = Raw {
        vertices,
        triangles: Vec::new(),
    };
    super::check_points(&raw)?;
    Ok(raw)
}

#[cfg(test)]
mod tests {
    use super::*;
    use e57::{E57Writer, Record, RecordValue};

    /// An E57 of `points` (metres) in one cloud, as a scanner writes it.
    pub(crate) fn e57_of(points: &[[f64; 3]]) -> Vec<u8> {
        let mut buf = Cursor::new(Vec::new());
        {
            let mut w = E57Writer::new(&mut buf, "lmdc-test").unwrap();
            let proto = vec![
                Record::CARTESIAN_X_F64,
                Record::CARTESIAN_Y_F64,
                Record::CARTESIAN_Z_F64,
            ];
            let mut pc = w.add_pointcloud("cloud", proto).unwrap();
            for p in points {
                pc.add_point(p.iter().map(|&c| RecordValue::Double(c)).collect())
                    .unwrap();
            }
            pc.finalize().unwrap();
            w.finalize().unwrap();
        }
        buf.into_inner()
    }

    #[test]
    fn its_points_are_read_in_mm() {
        let pts = [[0.001, 0.002, 0.010], [-0.0305, 0.0, 0.0099]];
        let raw = read(&e57_of(&pts)).unwrap();
        assert!(raw.triangles.is_empty());
        assert_eq!(raw.vertices.len(), 2);
        for (v, p) in raw.vertices.iter().zip(pts) {
            for k in 0..3 {
                assert!(
                    (f64::from(v[k]) - p[k] * 1000.0).abs() < 1e-4,
                    "{v:?} {p:?}"
                );
            }
        }
    }

    /// A scanner's own frame: points written as range, azimuth and
    /// elevation, the cloud's pose 90° about z and 1, 2, 3 m along x, y,
    /// z. Each is read at `R·p + t`, in mm, with
    /// `p = r·(cos e·cos a, cos e·sin a, sin e)`.
    #[test]
    fn spherical_points_under_a_pose_are_placed() {
        let spherical = [[0.5f64, 0.0, 0.0], [0.25, 1.0, 0.3], [0.1, -2.0, -0.7]];
        let mut buf = Cursor::new(Vec::new());
        {
            let mut w = E57Writer::new(&mut buf, "lmdc-test").unwrap();
            let proto = vec![
                Record::SPHERICAL_RANGE_F64,
                Record::SPHERICAL_AZIMUTH_F64,
                Record::SPHERICAL_ELEVATION_F64,
            ];
            let mut pc = w.add_pointcloud("cloud", proto).unwrap();
            let h = std::f64::consts::FRAC_PI_4;
            pc.set_transform(Some(e57::Transform {
                rotation: e57::Quaternion {
                    w: h.cos(),
                    x: 0.0,
                    y: 0.0,
                    z: h.sin(),
                },
                translation: e57::Translation {
                    x: 1.0,
                    y: 2.0,
                    z: 3.0,
                },
            }));
            for p in spherical {
                pc.add_point(p.iter().map(|&c| RecordValue::Double(c)).collect())
                    .unwrap();
            }
            pc.finalize().unwrap();
            w.finalize().unwrap();
        }
        let raw = read(&buf.into_inner()).unwrap();
        assert_eq!(raw.vertices.len(), 3);
        for (v, [r, a, e]) in raw.vertices.iter().zip(spherical) {
            let p = [r * e.cos() * a.cos(), r * e.cos() * a.sin(), r * e.sin()];
            // 90° about z: (x, y) → (−y, x).
            let want = [-p[1] + 1.0, p[0] + 2.0, p[2] + 3.0].map(|c| c * 1000.0);
            for k in 0..3 {
                assert!(
                    (f64::from(v[k]) - want[k]).abs() < 1e-3,
                    "{v:?} vs {want:?}"
                );
            }
        }
    }

    #[test]
    fn broken_files_are_errors_not_panics() {
        let good = e57_of(&[[0.0, 0.0, 0.01]; 50]);
        assert!(matches!(read(b"ASTM-E57"), Err(ScanError::E57(_))));
        assert!(matches!(read(&[]), Err(ScanError::E57(_))));
        // Cut anywhere, or a byte flipped anywhere: an error, or the
        // points the file still holds; never a panic.
        for cut in (0..good.len()).step_by(97) {
            let _ = read(&good[..cut]);
        }
        for at in (0..good.len()).step_by(61) {
            let mut bad = good.clone();
            bad[at] ^= 0x5a;
            let _ = read(&bad);
        }
        assert!(matches!(read(&e57_of(&[])), Err(ScanError::Empty)));
    }
}
