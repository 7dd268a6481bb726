//! The KUKA arms lmdc knows by name (`arm = kr16_2`): their kinematics as
//! OPW parameters (an ortho-parallel base and a spherical wrist, solved in
//! closed form by rs-opw-kinematics), their axis limits and axis speeds.
//!
//! Every number is ROS-Industrial's (`ros-industrial/kuka_experimental`):
//! the OPW parameters from the support package's
//! `config/opw_parameters_*.yaml`, the limits and speeds from the `<limit>`
//! of each joint in its `urdf/*_macro.xacro`, where the joints are KUKA's
//! axes A1–A6 in the controller's own angles and `tool0` is KUKA's `$FLANGE`
//! (docs/robots.md cites each file; `tests/arm.rs` rebuilds each arm
//! from the URDF's joint origins and checks the two agree). lmdc's own
//! units: mm, deg, deg/s.

/// An arm's geometry in the OPW convention (Brandstötter, Angerer and
/// Hofbaur, 2014), mm and deg, with the offsets and signs that turn the
/// solver's angles into the controller's axis angles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Opw {
    /// A1 axis to A2 axis, along the arm's X, mm.
    pub a1: f64,
    /// The forearm's offset from the A3 axis, mm.
    pub a2: f64,
    /// Sideways offset, mm (0 on every KUKA arm here).
    pub b: f64,
    /// Floor of the base to the A2 axis, mm.
    pub c1: f64,
    /// A2 axis to A3 axis (the upper arm), mm.
    pub c2: f64,
    /// A3 axis to the wrist centre (the forearm), mm.
    pub c3: f64,
    /// Wrist centre to the flange, mm.
    pub c4: f64,
    /// The solver's angle at the controller's zero, deg.
    pub offsets: [f64; 6],
    /// The direction of each axis against the solver's, ±1.
    pub signs: [i8; 6],
}

/// An arm of the catalogue.
#[derive(Clone, Copy, Debug)]
pub struct Model {
    /// The word a robot declares it by: `arm = kr16_2`.
    pub key: &'static str,
    /// KUKA's name for it.
    pub name: &'static str,
    /// Its kinematics.
    pub opw: Opw,
    /// Each axis's software limits, deg.
    pub limits: [[f64; 2]; 6],
    /// Each axis's top speed, deg/s.
    pub speeds: [f64; 6],
    /// The ROS-Industrial support package its numbers come from.
    pub source: &'static str,
    /// The radii of the capsules the collision checks take its links as —
    /// the upper arm, the forearm, the wrist — mm: lmdc's estimates of
    /// each link's envelope from KUKA's dimensioned drawings, rounded up
    /// (docs/collision.md, *The arm*).
    pub links: [f64; 3],
    /// The radius of the capsule the collision checks take its column
    /// as — from the foot up A1's axis to the shoulder's height, then to
    /// the A2 axis — mm: an estimate like the links', of the rotating
    /// column's envelope with A1's and A2's drives (docs/collision.md).
    pub column: f64,
}

impl Model {
    /// The IR's arm of this model, checked with `margin` and `singularity`
    /// (deg).
    pub fn arm(&self, margin: f64, singularity: f64) -> crate::ir::Arm {
        let o = self.opw;
        crate::ir::Arm {
            model: Some(self.key.to_string()),
            opw: [o.a1, o.a2, o.b, o.c1, o.c2, o.c3, o.c4],
            offsets: o.offsets,
            signs: o.signs,
            limits: self.limits,
            speeds: self.speeds,
            margin,
            singularity,
            links: Some(self.links),
            column: Some(self.column),
        }
    }
}

/// ROS-Industrial's KUKA convention, every arm's here and an `opw(…)`
/// arm's: A2's zero is the upper arm level (OPW's is upright), and A1, A4,
/// A6 turn the other way from OPW's (the lengths are zero: only the
/// offsets and signs are read from it).
pub const KUKA: Opw = kuka(0.0, 0.0, 0.0, 0.0, 0.0, 0.0);

const fn kuka(a1: f64, a2: f64, c1: f64, c2: f64, c3: f64, c4: f64) -> Opw {
    Opw {
        a1,
        a2,
        b: 0.0,
        c1,
        c2,
        c3,
        c4,
        offsets: [0.0, -90.0, 0.0, 0.0, 0.0, 0.0],
        signs: [-1, 1, 1, -1, 1, -1],
    }
}

/// Every arm lmdc knows by name, smallest first.
pub const CATALOGUE: &[Model] = &[
    Model {
        key: "kr6_r900_2",
        name: "KR 6 R900-2 (KR AGILUS)",
        opw: kuka(25.0, -25.0, 400.0, 455.0, 420.0, 90.0),
        limits: [
            [-170.0, 170.0],
            [-190.0, 45.0],
            [-120.0, 156.0],
            [-185.0, 185.0],
            [-120.0, 120.0],
            [-350.0, 350.0],
        ],
        speeds: [360.0, 300.0, 360.0, 450.0, 450.0, 540.0],
        source: "kuka_kr6_support: opw_parameters_kr6r900_2.yaml, kr6r900_2_macro.xacro",
        links: [80.0, 70.0, 55.0],
        column: 110.0,
    },
    Model {
        key: "kr16_2",
        name: "KR 16-2",
        opw: kuka(260.0, 35.0, 675.0, 680.0, 670.0, 158.0),
        limits: [
            [-185.0, 185.0],
            [-155.0, 35.0],
            [-130.0, 154.0],
            [-350.0, 350.0],
            [-130.0, 130.0],
            [-350.0, 350.0],
        ],
        speeds: [156.0, 156.0, 156.0, 330.0, 330.0, 615.0],
        source: "kuka_kr16_support: opw_parameters_kr16_2.yaml, kr16_2_macro.xacro",
        links: [130.0, 100.0, 75.0],
        column: 200.0,
    },
    Model {
        key: "kr60ha",
        name: "KR 60 HA",
        opw: kuka(350.0, -145.0, 815.0, 850.0, 820.0, 170.0),
        limits: [
            [-185.0, 185.0],
            [-135.0, 35.0],
            [-120.0, 158.0],
            [-350.0, 350.0],
            [-119.0, 119.0],
            [-350.0, 350.0],
        ],
        speeds: [128.0, 102.0, 128.0, 260.0, 245.0, 322.0],
        source: "kuka_kr60_support: opw_parameters_kr60ha.yaml, kr60ha_macro.xacro",
        links: [190.0, 140.0, 100.0],
        column: 260.0,
    },
    Model {
        key: "kr150_r3100_2",
        name: "KR 150 R3100-2 (KR QUANTEC)",
        opw: kuka(330.0, -115.0, 645.0, 1350.0, 1420.0, 215.0),
        limits: [
            [-185.0, 185.0],
            [-140.0, -5.0],
            [-120.0, 168.0],
            [-350.0, 350.0],
            [-125.0, 125.0],
            [-350.0, 350.0],
        ],
        speeds: [105.0, 107.0, 114.0, 190.0, 180.0, 260.0],
        source: "kuka_kr150_support: opw_parameters_kr150_r3100-2.yaml, kr150_r3100-2_macro.xacro",
        links: [260.0, 200.0, 130.0],
        column: 340.0,
    },
];

/// The words `arm = …` takes: the catalogue's keys.
pub const KEYS: &[&str] = &["kr6_r900_2", "kr16_2", "kr60ha", "kr150_r3100_2"];

/// The catalogue's arm named `key`.
pub fn model(key: &str) -> Option<&'static Model> {
    CATALOGUE.iter().find(|m| m.key == key)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_are_the_catalogue() {
        let keys: Vec<_> = CATALOGUE.iter().map(|m| m.key).collect();
        assert_eq!(keys, KEYS);
    }
}
