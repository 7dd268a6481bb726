//! The KUKA and ABB arms lmdc knows by name (`arm = kr16_2`,
//! `arm = irb4600_60_205`): their kinematics as OPW parameters (an
//! ortho-parallel base and a spherical wrist, solved in closed form by
//! rs-opw-kinematics), their axis limits and axis speeds.
//!
//! Every number is ROS-Industrial's. KUKA's (`ros-industrial/kuka_experimental`):
//! the OPW parameters from the support package's
//! `config/opw_parameters_*.yaml`, the limits and speeds from the `<limit>`
//! of each joint in its `urdf/*_macro.xacro`, where the joints are KUKA's
//! axes A1–A6 in the controller's own angles and `tool0` is KUKA's `$FLANGE`.
//! ABB's (`ros-industrial/abb_experimental`): the OPW parameters read off
//! the joint origins of `urdf/*_macro.xacro` (the same sets rs-opw-kinematics
//! ships), the limits and speeds from its `<limit>`s, where the joints are
//! ABB's axes 1–6 as the controller shows them and `tool0` is ABB's `tool0`
//! (docs/robots.md cites each file; `tests/arm.rs` rebuilds each arm from
//! the URDF's joint origins and checks the two agree). lmdc's own units:
//! mm, deg, deg/s.

/// An arm's geometry in the OPW convention (Brandstötter, Angerer and
/// Hofbaur, 2014), mm and deg, with the offsets and signs that turn the
/// solver's angles into the controller's axis angles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Opw {
    /// A1 axis to A2 axis, along the arm's X, mm.
    pub a1: f64,
    /// The forearm's offset from the A3 axis, mm.
    pub a2: f64,
    /// Sideways offset, mm (0 on every arm here).
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

/// Who makes an arm: whose controller runs it, whose axis angles and
/// configuration its joints are in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Maker {
    /// KUKA (KR C4/C5, KRL): axes A1–A6 in [`KUKA`]'s convention, the
    /// configuration as Status and Turn.
    Kuka,
    /// ABB (IRC5/OmniCore, RAPID): axes 1–6 in [`ABB`]'s convention, the
    /// configuration as `confdata` (`plan::arm::Solver::confdata`).
    Abb,
}

/// An arm of the catalogue.
#[derive(Clone, Copy, Debug)]
pub struct Model {
    /// The word a robot declares it by: `arm = kr16_2`.
    pub key: &'static str,
    /// Its maker's name for it.
    pub name: &'static str,
    /// Who makes it: the convention its axis angles are in.
    pub maker: Maker,
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
    /// each link's envelope from the maker's dimensioned drawings, rounded
    /// up (docs/collision.md, *The arm*; docs/robots.md, *ABB arms*).
    pub links: [f64; 3],
    /// The radius of the capsule the collision checks take its column
    /// as — from the foot up A1's axis to the shoulder's height, then to
    /// the A2 axis — mm: an estimate like the links', of the rotating
    /// column's envelope with A1's and A2's drives (docs/collision.md).
    pub column: f64,
}

impl Model {
    /// The arm's upright pose in its own axis angles ([`upright`]): KUKA's
    /// home `{0, −90, 90, 0, 0, 0}`, ABB's calibration position (every axis 0).
    pub fn upright(&self) -> [f64; 6] {
        upright(&self.opw.offsets, &self.opw.signs)
    }

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

/// ROS-Industrial's KUKA convention, every KUKA arm's here and an `opw(…)`
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

/// ROS-Industrial's ABB convention, every ABB arm's here: OPW's angles but
/// axis 3's zero with the forearm level (OPW's is upright); every axis turns
/// as OPW's (A1 about +Z, A2 and A3 tilting forward, A4 and A6 about the
/// forearm and the flange's normal, outwards), as rs-opw-kinematics'
/// `Parameters::irb2400_10` and its other ABB sets have it.
pub const ABB: Opw = abb(0.0, 0.0, 0.0, 0.0, 0.0, 0.0);

const fn abb(a1: f64, a2: f64, c1: f64, c2: f64, c3: f64, c4: f64) -> Opw {
    Opw {
        a1,
        a2,
        b: 0.0,
        c1,
        c2,
        c3,
        c4,
        offsets: [0.0, 0.0, -90.0, 0.0, 0.0, 0.0],
        signs: [1, 1, 1, 1, 1, 1],
    }
}

/// The axis angles (deg) of an arm with `offsets` and `signs` where it
/// stands upright: the upper arm plumb, the forearm level and ahead, the
/// wrist straight (OPW's angles `0, 0, 90°, 0, 0, 0`; an axis angle is
/// `(θ + offset)·sign`). KUKA's home `{0, −90, 90, 0, 0, 0}` and ABB's
/// calibration position, every axis 0, are both this pose.
pub fn upright(offsets: &[f64; 6], signs: &[i8; 6]) -> [f64; 6] {
    let theta = [0.0, 0.0, 90.0, 0.0, 0.0, 0.0];
    std::array::from_fn(|i| (theta[i] + offsets[i]) * f64::from(signs[i]))
}

/// Every arm lmdc knows by name: KUKA's, then ABB's, smallest first.
pub const CATALOGUE: &[Model] = &[
    Model {
        key: "kr6_r900_2",
        name: "KR 6 R900-2 (KR AGILUS)",
        maker: Maker::Kuka,
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
        maker: Maker::Kuka,
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
        maker: Maker::Kuka,
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
        maker: Maker::Kuka,
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
    Model {
        key: "irb2600_12_165",
        name: "IRB 2600-12/1.65",
        maker: Maker::Abb,
        opw: abb(150.0, -115.0, 445.0, 700.0, 795.0, 85.0),
        limits: [
            [-180.0, 180.0],
            [-155.0, 95.0],
            [-155.0, 75.0],
            [-400.0, 400.0],
            [-120.0, 120.0],
            [-400.0, 400.0],
        ],
        speeds: [175.0, 175.0, 175.0, 360.0, 360.0, 500.0],
        source: "abb_irb2600_support: irb2600_12_165_macro.xacro",
        links: [130.0, 100.0, 75.0],
        column: 220.0,
    },
    Model {
        key: "irb4600_60_205",
        name: "IRB 4600-60/2.05",
        maker: Maker::Abb,
        opw: abb(175.0, -175.0, 495.0, 900.0, 960.0, 135.0),
        limits: [
            [-180.0, 180.0],
            [-90.0, 150.0],
            [-180.0, 75.0],
            [-400.0, 400.0],
            [-125.0, 120.0],
            [-400.0, 400.0],
        ],
        speeds: [175.0, 175.0, 175.0, 250.0, 250.0, 360.0],
        source: "abb_irb4600_support: irb4600_60_205_macro.xacro",
        links: [190.0, 140.0, 100.0],
        column: 280.0,
    },
    Model {
        key: "irb4600_40_255",
        name: "IRB 4600-40/2.55",
        maker: Maker::Abb,
        opw: abb(175.0, -175.0, 495.0, 1095.0, 1270.0, 135.0),
        limits: [
            [-180.0, 180.0],
            [-90.0, 150.0],
            [-180.0, 75.0],
            [-400.0, 400.0],
            [-125.0, 120.0],
            [-400.0, 400.0],
        ],
        speeds: [175.0, 175.0, 175.0, 250.0, 250.0, 360.0],
        source: "abb_irb4600_support: irb4600_40_255_macro.xacro",
        links: [180.0, 130.0, 100.0],
        column: 280.0,
    },
    Model {
        key: "irb6700_200_260",
        name: "IRB 6700-200/2.60",
        maker: Maker::Abb,
        opw: abb(320.0, -200.0, 780.0, 1125.0, 1142.5, 200.0),
        limits: [
            [-170.0, 170.0],
            [-65.0, 85.0],
            [-180.0, 70.0],
            [-300.0, 300.0],
            [-130.0, 130.0],
            [-360.0, 360.0],
        ],
        speeds: [110.0, 110.0, 110.0, 190.0, 150.0, 210.0],
        source: "abb_irb6700_support: irb6700_200_260_macro.xacro",
        links: [280.0, 220.0, 150.0],
        column: 400.0,
    },
];

/// The words `arm = …` takes: the catalogue's keys.
pub const KEYS: &[&str] = &[
    "kr6_r900_2",
    "kr16_2",
    "kr60ha",
    "kr150_r3100_2",
    "irb2600_12_165",
    "irb4600_60_205",
    "irb4600_40_255",
    "irb6700_200_260",
];

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

    /// Each maker's arms share its convention, and the upright pose is
    /// KUKA's home and ABB's zero.
    #[test]
    fn makers_have_their_conventions() {
        for m in CATALOGUE {
            let (c, up) = match m.maker {
                Maker::Kuka => (KUKA, [0.0, -90.0, 90.0, 0.0, 0.0, 0.0]),
                Maker::Abb => (ABB, [0.0; 6]),
            };
            assert_eq!(
                (m.opw.offsets, m.opw.signs),
                (c.offsets, c.signs),
                "{}",
                m.key
            );
            assert_eq!(m.upright(), up, "{}", m.key);
            assert_eq!(m.opw.b, 0.0);
        }
    }
}
