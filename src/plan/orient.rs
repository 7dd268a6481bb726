//! Tool orientation: from a point's normal to KUKA's `A B C`.
//!
//! The IR fixes only the beam direction (along −normal); the rotation of the tool
//! about the beam is free for a coaxial powder nozzle. lmdc chooses it so that the
//! wrist moves as little as possible: the tool's *reference axis* (the axis after
//! the beam axis, cyclically: beam Z → X, beam X → Y, beam Y → Z) starts along the
//! base's X projected onto the layer plane and is then carried from normal to
//! normal by parallel transport (turned by the smallest rotation between the two
//! normals, never spun about the beam). A nozzle pointing straight down with beam +Z is then the familiar
//! `A 0, B 0, C 180`.
//!
//! `A B C` are KUKA's ZYX Euler angles, R = Rz(A)·Ry(B)·Rx(C), the columns of R
//! being the tool axes in base coordinates. At B = ±90° (gimbal lock) A and C
//! turn about one axis and only their difference (or sum) matters; the split
//! is nalgebra's (beam `x` pointing down: `A 0, B 90, C 90`).

use crate::ir::ToolAxis;
use nalgebra::{Matrix3, Rotation3, Vector3};

/// `A B C` in degrees, each in (−180, 180] (B in [−90, 90]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Abc {
    /// Rotation about Z, deg.
    pub a: f64,
    /// Rotation about the new Y, deg.
    pub b: f64,
    /// Rotation about the new X, deg.
    pub c: f64,
}

/// Carries the reference axis from normal to normal.
#[derive(Clone, Debug)]
pub struct Orienter {
    /// Beam axis index (0 = X, 1 = Y, 2 = Z) and its sign.
    axis: usize,
    sign: f64,
    /// The reference axis' direction in the base, unit, ⊥ the last normal.
    reference: Vector3<f64>,
    /// The last normal, once there is one.
    normal: Option<Vector3<f64>>,
    /// The turn about the beam added to the carried one (`spin`): cos, sin.
    spin: (f64, f64),
}

impl Orienter {
    /// An orienter for a tool whose beam leaves along `beam`.
    pub fn new(beam: ToolAxis) -> Self {
        let (axis, sign) = match beam {
            ToolAxis::PlusX => (0, 1.0),
            ToolAxis::MinusX => (0, -1.0),
            ToolAxis::PlusY => (1, 1.0),
            ToolAxis::MinusY => (1, -1.0),
            ToolAxis::PlusZ => (2, 1.0),
            ToolAxis::MinusZ => (2, -1.0),
        };
        Orienter {
            axis,
            sign,
            reference: Vector3::x(),
            normal: None,
            spin: (1.0, 0.0),
        }
    }

    /// The orienter of `robot`'s tool, turned by its `spin` about the beam.
    pub fn for_robot(robot: &crate::ir::Robot) -> Self {
        Orienter::new(robot.beam).spun(robot.spin.deg())
    }

    /// This orienter with the tool turned by `deg` about the beam, on top of
    /// the carried turn (the reference axis itself is carried as before, so
    /// the turn is the same at every point).
    pub fn spun(mut self, deg: f64) -> Self {
        let (s, c) = deg.to_radians().sin_cos();
        self.spin = (c, s);
        self
    }

    /// The tool rotation for a point with `normal` (need not be exactly unit),
    /// moving the reference axis along.
    pub fn rotation(&mut self, normal: [f32; 3]) -> Matrix3<f64> {
        let n = Vector3::new(normal[0] as f64, normal[1] as f64, normal[2] as f64).normalize();
        // Parallel transport: the smallest rotation that takes the last
        // normal to this one carries the reference axis along, so the tool
        // turns by exactly the angle between the normals.
        let carried = match self.normal {
            Some(p) => carry(self.reference, p, n),
            None => self.reference,
        };
        let r = transport(carried, n);
        self.reference = r;
        self.normal = Some(n);
        let beam = -n * self.sign;
        // Turned about the beam by the spin: r, beam × r → r', beam × r'.
        let (c, s) = self.spin;
        let r = r * c + beam.cross(&r) * s;
        let third = beam.cross(&r);
        let mut m = Matrix3::zeros();
        m.set_column(self.axis, &beam);
        m.set_column((self.axis + 1) % 3, &r);
        m.set_column((self.axis + 2) % 3, &third);
        m
    }

    /// [`Self::rotation`] as `A B C`.
    pub fn abc(&mut self, normal: [f32; 3]) -> Abc {
        abc(&self.rotation(normal))
    }
}

/// `r` turned by the smallest rotation taking the unit `from` to the unit `to`:
/// R = I + [v]× + [v]×²/(1 + c) with v = from × to, c = from · to (no
/// trigonometry: this runs for every point). Unchanged when the two are
/// opposite, where no rotation is smallest.
fn carry(r: Vector3<f64>, from: Vector3<f64>, to: Vector3<f64>) -> Vector3<f64> {
    let v = from.cross(&to);
    let c = from.dot(&to);
    if 1.0 + c < 1e-9 {
        return r;
    }
    let vr = v.cross(&r);
    r + vr + v.cross(&vr) / (1.0 + c)
}

/// `r` projected onto the plane ⊥ `n`, normalised (after transport it lies
/// there already, up to rounding). When `r` is (nearly) along `n` — only for
/// the first normal, or after the normal flips — the base's X or Y, whichever
/// lies more in the plane, is projected instead.
fn transport(r: Vector3<f64>, n: Vector3<f64>) -> Vector3<f64> {
    let p = r - n * r.dot(&n);
    if p.norm() > 1e-6 {
        return p.normalize();
    }
    let x = Vector3::x() - n * n.x;
    let y = Vector3::y() - n * n.y;
    if x.norm() >= y.norm() {
        x.normalize()
    } else {
        y.normalize()
    }
}

/// KUKA `A B C` (deg) of a rotation matrix.
pub fn abc(m: &Matrix3<f64>) -> Abc {
    // nalgebra's (roll, pitch, yaw) are R = Rz(yaw)·Ry(pitch)·Rx(roll): KUKA's C B A.
    let (roll, pitch, yaw) = Rotation3::from_matrix_unchecked(*m).euler_angles();
    Abc {
        a: canonical(yaw.to_degrees()),
        b: pitch.to_degrees(),
        c: canonical(roll.to_degrees()),
    }
}

/// The angle in (−180, 180].
fn canonical(deg: f64) -> f64 {
    if deg <= -180.0 {
        deg + 360.0
    } else {
        deg
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn straight_down_is_c180() {
        let mut o = Orienter::new(ToolAxis::PlusZ);
        let abc = o.abc([0.0, 0.0, 1.0]);
        assert!(abc.a.abs() < 1e-9 && abc.b.abs() < 1e-9, "{abc:?}");
        assert!((abc.c - 180.0).abs() < 1e-9, "{abc:?}");
    }

    /// A spin turns the tool about the beam and nothing else: the beam axis
    /// stays, the reference axis turns by the spin (right-handed about the
    /// beam), at every point of a path whose normal changes.
    #[test]
    fn spin_turns_about_the_beam() {
        for beam in [ToolAxis::PlusZ, ToolAxis::MinusX, ToolAxis::PlusY] {
            let mut plain = Orienter::new(beam);
            let mut spun = Orienter::new(beam).spun(35.0);
            for k in 0..5 {
                let t = k as f32 * 0.2;
                let n = [0.3 * t, -0.1 * t, 1.0];
                let (a, b) = (plain.rotation(n), spun.rotation(n));
                let axis = (0..3)
                    .find(|&i| (a.column(i) - b.column(i)).norm() < 1e-12)
                    .unwrap();
                let beam_dir = a.column(axis).into_owned();
                let (ra, rb) = (a.column((axis + 1) % 3), b.column((axis + 1) % 3));
                let angle = ra.dot(&rb).clamp(-1.0, 1.0).acos().to_degrees();
                assert!((angle - 35.0).abs() < 1e-9, "{beam:?}: {angle}");
                assert!(ra.cross(&rb).dot(&beam_dir) > 0.0, "{beam:?}");
                assert!((b.determinant() - 1.0).abs() < 1e-9);
            }
        }
    }

    #[test]
    fn beam_axis_follows_the_normal_for_every_tool_axis() {
        for (beam, axis, sign) in [
            (ToolAxis::PlusX, 0, 1.0),
            (ToolAxis::MinusX, 0, -1.0),
            (ToolAxis::PlusY, 1, 1.0),
            (ToolAxis::MinusY, 1, -1.0),
            (ToolAxis::PlusZ, 2, 1.0),
            (ToolAxis::MinusZ, 2, -1.0),
        ] {
            let mut o = Orienter::new(beam);
            let n = Vector3::new(0.3, -0.2, 0.9).normalize();
            let m = o.rotation([n.x as f32, n.y as f32, n.z as f32]);
            assert!((m.determinant() - 1.0).abs() < 1e-9);
            let beam_dir = m.column(axis) * sign;
            assert!((beam_dir + n).norm() < 1e-6, "{beam:?}");
        }
    }
}
