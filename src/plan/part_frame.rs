//! Where the part's coordinates lie in a machine's own, pose by pose: what
//! a fixture fixed to the machine (`fixture { machine = NAME }`,
//! docs/collision.md) is checked in.
//!
//! - A CNC whose part does not turn (3 axes, a tilting head): the part's
//!   origin at the placement's `origin`, the work offset's value.
//! - A CNC with a tilting table: the machine's coordinates at every rotary
//!   axis 0, the table turning the part by [`super::table`]'s kinematics
//!   (`q = c + Rz(−C)·(w − c)`, then `p + Rt(−T)·(q − p)`).
//! - A robot: its own frame (its foot), the part's `base` in it; on a
//!   positioner, the base on the positioner's flange at E1 and E2.

use super::kinematics::Rotary;
use super::positioner::Kin;
use crate::ir::{Kinematics, Machine};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

/// The part's frame in a machine's coordinates.
#[derive(Clone, Debug)]
pub enum PartFrame {
    /// The same at every pose.
    Fixed(Isometry3<f64>),
    /// A tilting table's, turning with its axes.
    Table {
        /// A or B.
        kin: Kinematics,
        /// The C axis's point, mm.
        c: Vector3<f64>,
        /// The tilt axis's point, mm.
        tilt: Vector3<f64>,
        /// The placement's origin, mm.
        origin: Vector3<f64>,
    },
    /// A robot's positioner's, turning with E1 and E2.
    Positioner(Kin),
}

impl PartFrame {
    /// The part's frame in `machine`'s coordinates; `None` for a robot
    /// whose base has no value (an index alone places nothing).
    pub fn of(machine: &Machine) -> Option<PartFrame> {
        match machine {
            Machine::Cnc(c) => {
                let kin = c.effective_kinematics();
                let origin = Vector3::from(c.placement.origin);
                if !kin.is_table() {
                    return Some(PartFrame::Fixed(Isometry3::from_parts(
                        Translation3::from(origin),
                        UnitQuaternion::identity(),
                    )));
                }
                let t = c.table.unwrap_or_default();
                Some(PartFrame::Table {
                    kin,
                    c: Vector3::from(t.c_axis),
                    tilt: Vector3::from(t.tilt_axis),
                    origin,
                })
            }
            Machine::Robot(r) => match Kin::of(r) {
                Some(k) => Some(PartFrame::Positioner(k)),
                None => Some(PartFrame::Fixed(super::arm::frame(r.base.value.as_ref()?))),
            },
        }
    }

    /// The frame where it does not turn with the axes.
    pub fn fixed(&self) -> Option<&Isometry3<f64>> {
        match self {
            PartFrame::Fixed(f) => Some(f),
            _ => None,
        }
    }

    /// The part's frame in the machine's coordinates with the rotary axes
    /// (a table's, a positioner's E1 and E2) at `axes`; with `tilts`, in
    /// the tilt axis's body's (a table's cradle, a positioner's tilting
    /// arm) as it stands with every rotary axis at 0: the C axis (E2)
    /// alone turns the part in it.
    pub fn at(&self, axes: Rotary, tilts: bool) -> Isometry3<f64> {
        if tilts {
            let c_only = Rotary { tilt: 0.0, ..axes };
            return match self {
                PartFrame::Positioner(k) => k.part_on_tilt([axes.tilt, axes.c]),
                _ => self.at(c_only, false),
            };
        }
        match self {
            PartFrame::Fixed(f) => *f,
            PartFrame::Table {
                kin,
                c,
                tilt,
                origin,
            } => {
                let axis = if *kin == Kinematics::TableBc {
                    Vector3::y_axis()
                } else {
                    Vector3::x_axis()
                };
                let about = |p: &Vector3<f64>, r: UnitQuaternion<f64>| {
                    Translation3::from(*p) * r * Translation3::from(-*p)
                };
                about(
                    tilt,
                    UnitQuaternion::from_axis_angle(&axis, -axes.tilt.to_radians()),
                ) * about(
                    c,
                    UnitQuaternion::from_axis_angle(&Vector3::z_axis(), -axes.c.to_radians()),
                ) * Translation3::from(*origin)
            }
            PartFrame::Positioner(k) => k.part([axes.tilt, axes.c]),
        }
    }
}

/// A turn about an axis by its angle: what a moving part's frame is made
/// of ([`PartFrame::turns`]).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Turn {
    /// The axis's direction, unit.
    pub dir: [f64; 3],
    /// A point of the axis, mm.
    pub point: [f64; 3],
    /// The axis's angle times this is the turn (right-handed about
    /// `dir`): a table's turns the part against its angle.
    pub sign: f64,
}

impl Turn {
    /// The turn by the axis's angle `deg`.
    pub fn by(&self, deg: f64) -> Isometry3<f64> {
        let axis = nalgebra::Unit::new_normalize(Vector3::from(self.dir));
        let p = Vector3::from(self.point);
        Translation3::from(p)
            * UnitQuaternion::from_axis_angle(&axis, (self.sign * deg).to_radians())
            * Translation3::from(-p)
    }
}

impl PartFrame {
    /// A moving frame as what it is made of: the tilt axis's turn, then
    /// the C axis's (E2's), then a constant, so that
    /// `at(axes, false) = tilt.by(axes.tilt) · c.by(axes.c) · then` and
    /// `at(axes, true) = c.by(axes.c) · then`. `None` where it does not
    /// move.
    pub fn turns(&self) -> Option<([Turn; 2], Isometry3<f64>)> {
        match self {
            PartFrame::Fixed(_) => None,
            PartFrame::Table {
                kin,
                c,
                tilt,
                origin,
            } => {
                let x = if *kin == Kinematics::TableBc {
                    [0.0, 1.0, 0.0]
                } else {
                    [1.0, 0.0, 0.0]
                };
                let turn = |dir, p: &Vector3<f64>| Turn {
                    dir,
                    point: [p.x, p.y, p.z],
                    sign: -1.0,
                };
                let then =
                    Isometry3::from_parts(Translation3::from(*origin), UnitQuaternion::identity());
                Some(([turn(x, tilt), turn([0.0, 0.0, 1.0], c)], then))
            }
            PartFrame::Positioner(k) => {
                let ([t, r], then) = k.parts();
                let turn = |(dir, point)| Turn {
                    dir,
                    point,
                    sign: 1.0,
                };
                Some(([turn(t), turn(r)], then))
            }
        }
    }
}

/// A box's least and greatest corners, mm.
pub type Bounds = ([f64; 3], [f64; 3]);

/// A fixture a machine's head meets, where it stands from the part.
#[derive(Clone, Copy, Debug)]
pub struct Placed<'a> {
    /// The fixture.
    pub fixture: &'a crate::ir::Fixture,
    /// The box round it, in the part's coordinates.
    pub bounds: Bounds,
    /// Whether its box was turned into the part's coordinates (the box
    /// round the turned box: larger than the fixture's own).
    pub turned: bool,
}

/// The fixtures of `program` that `machine`'s head meets, with their boxes
/// in the part's coordinates: those on the plate, and those fixed to the
/// machine where the part does not turn (their box's corners brought into
/// the part's coordinates). Where a table or a positioner turns the part,
/// where a fixture fixed to the machine stands from it changes pose by
/// pose: it is left out, and only the collision check follows it.
pub fn fixture_boxes<'a>(program: &'a crate::ir::Program, machine: &Machine) -> Vec<Placed<'a>> {
    let frame = PartFrame::of(machine);
    let inv = frame
        .as_ref()
        .and_then(PartFrame::fixed)
        .map(|f| f.inverse());
    (program.fixtures.iter())
        .filter_map(|f| {
            let bounds = f.bounds();
            if !f.fixed_to(machine.name())? {
                return Some(Placed {
                    fixture: f,
                    bounds,
                    turned: false,
                });
            }
            let inv = inv?;
            let (lo, hi) = bounds;
            let mut out = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
            for k in 0..8 {
                let c = [0, 1, 2].map(|a| if k >> a & 1 == 0 { lo[a] } else { hi[a] });
                let p = inv * nalgebra::Point3::from(c);
                for a in 0..3 {
                    out.0[a] = out.0[a].min(p[a]);
                    out.1[a] = out.1[a].max(p[a]);
                }
            }
            Some(Placed {
                fixture: f,
                bounds: out,
                turned: inv.rotation.angle() > 1e-9,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::RotaryTable;
    use nalgebra::Point3;
    use proptest::prelude::*;

    /// The frame made again from its turns, on or off the tilt axis.
    fn composed(f: &PartFrame, axes: Rotary, tilts: bool) -> Isometry3<f64> {
        let ([t, c], then) = f.turns().expect("a moving frame");
        let on_c = c.by(axes.c) * then;
        if tilts {
            on_c
        } else {
            t.by(axes.tilt) * on_c
        }
    }

    fn close(a: &Isometry3<f64>, b: &Isometry3<f64>) -> bool {
        (a.to_homogeneous() - b.to_homogeneous()).abs().max() < 1e-9
    }

    /// What the preview draws from (the turns) is the frame the check
    /// takes, for a table and a positioner, on or off the tilt axis.
    #[test]
    fn the_turns_make_the_frame() {
        let table = PartFrame::Table {
            kin: Kinematics::TableBc,
            c: Vector3::new(12.0, -7.0, 30.0),
            tilt: Vector3::new(0.0, -20.0, 95.0),
            origin: Vector3::new(40.0, 5.0, -3.0),
        };
        let p = crate::ir::Positioner {
            tilt: crate::ir::PositionerAxis {
                direction: [1.0, 0.0, 0.0],
                point: [1500.0, 0.0, 500.0],
                limits: [-90.0, 90.0],
                speed: 90.0,
            },
            rotate: crate::ir::PositionerAxis {
                direction: [0.0, 0.0, 1.0],
                point: [1500.0, 0.0, 700.0],
                limits: [-360.0, 360.0],
                speed: 90.0,
            },
            keep: crate::ir::Keep::Vertical,
            home: [0.0; 2],
            angles: Vec::new(),
            faceplate: None,
        };
        let base = crate::ir::Pose {
            x: 10.0,
            y: -20.0,
            z: 30.0,
            a: 90.0,
            b: 0.0,
            c: 0.0,
        };
        let pos = PartFrame::Positioner(Kin::new(&p, &base));
        for f in [&table, &pos] {
            for axes in [
                Rotary {
                    tilt: 37.0,
                    c: -123.0,
                },
                Rotary {
                    tilt: -80.0,
                    c: 400.0,
                },
            ] {
                for tilts in [false, true] {
                    assert!(
                        close(&composed(f, axes, tilts), &f.at(axes, tilts)),
                        "{f:?} {axes:?} {tilts}"
                    );
                }
            }
        }
    }

    proptest! {
        /// A table's frame puts every point of the part where the
        /// table's own kinematics ([`super::super::table::machine_point`])
        /// does.
        #[test]
        fn a_tables_frame_is_its_kinematics(
            w in prop::array::uniform3(-500.0f64..500.0),
            origin in prop::array::uniform3(-300.0f64..300.0),
            tilt in -120.0f64..120.0,
            c in -400.0f64..400.0,
            bc in any::<bool>(),
        ) {
            let kin = if bc { Kinematics::TableBc } else { Kinematics::TableAc };
            let t = RotaryTable {
                c_axis: [12.0, -7.0, 30.0],
                tilt_axis: [0.0, -20.0, 95.0],
                output: Default::default(),
            };
            let frame = PartFrame::Table {
                kin,
                c: Vector3::from(t.c_axis),
                tilt: Vector3::from(t.tilt_axis),
                origin: Vector3::from(origin),
            };
            let r = Rotary { tilt, c };
            let got = frame.at(r, false) * Point3::from(w);
            let plus = [w[0] + origin[0], w[1] + origin[1], w[2] + origin[2]];
            let want = super::super::table::machine_point(kin, &t, plus, r);
            for k in 0..3 {
                prop_assert!((got[k] - want[k]).abs() < 1e-9, "{got:?} vs {want:?}");
            }
        }
    }
}
