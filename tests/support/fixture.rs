//! Hand-built IR for back-end tests: a small bent tube of circular layers whose
//! planes fan about an axis parallel to Y (like seed 000's duct, without the morph).
#![allow(dead_code)]

use lmdc::ir::*;

/// A robot as a cell would declare it.
pub fn robot() -> Robot {
    Robot {
        controller: Controller::Kuka,
        common: MachineCommon {
            name: "kr60".into(),
            max_speed: 250.0,
            clearance: 10.0,
            cell: Cell::default(),
            height_sensor: None,
            acceleration: None,
            blending: None,
            ramp: Ramp::None,
            head: Head::typical(),
        },
        tool: FrameRef {
            index: 1,
            value: Some(Pose {
                x: 0.0,
                y: 0.0,
                z: 250.0,
                a: 0.0,
                b: 0.0,
                c: 0.0,
            }),
        },
        load: Some(Load {
            mass: 12.5,
            cog: [0.0, 0.0, 140.0],
            inertia_axes: [0.0; 3],
            inertia: [0.2, 0.2, 0.05],
        }),
        base: FrameRef {
            index: 1,
            value: None,
        },
        beam: ToolAxis::PlusZ,
        laser_out: lmdc::ir::Signal::Number(5),
        power_out: lmdc::ir::Signal::Number(1),
        full_scale_power: 4000.0,
        home: [0.0, -90.0, 90.0, 0.0, 0.0, 0.0],
        max_points_per_module: 5000,
        arm: None,
        spin: Default::default(),
        positioner: None,
    }
}

/// A LinuxCNC 5-axis A/C head.
pub fn cnc5() -> Cnc {
    Cnc {
        common: MachineCommon {
            name: "mill5".into(),
            max_speed: 200.0,
            clearance: 10.0,
            cell: Cell::default(),
            height_sensor: None,
            acceleration: None,
            blending: None,
            ramp: Ramp::None,
            head: Head::typical(),
        },
        axes: 5,
        kinematics: Kinematics::HeadAc,
        dialect: Dialect {
            profile: "linuxcnc".into(),
            laser_on: "M3".into(),
            laser_off: "M5".into(),
            s_per_watt: 1.0,
            s_decimals: 0,
            preamble: vec!["G21 G90 G94 G17".into()],
            postamble: vec!["M2".into()],
            dwell: "G4 P{s}".into(),
            tcp_on: String::new(),
            tcp_off: String::new(),
            comment: CommentStyle::Parens,
            padded_g: false,
            extension: "ngc".into(),
            feed: FeedUnit::MmPerMin,
        },
        limits: AxisLimits {
            x: [-500.0, 500.0],
            y: [-500.0, 500.0],
            z: [-100.0, 600.0],
            tilt: [-120.0, 120.0],
            rotary: [-3600.0, 3600.0],
        },
        placement: Placement::default(),
        safe_height: None,
        table: None,
        rotary_speed: None,
    }
}

/// `layers` circular layers of `k` segments (k+1 points, closed), radius 20 mm,
/// fanned about the axis through (R, 0, 0) parallel to Y by `bend_deg` in total.
/// The last point of every layer has the laser off; a travel path joins layers.
pub fn bent_tube(layers: usize, k: usize, bend_deg: f64, machines: Vec<Machine>) -> Program {
    let big_r = 150.0;
    let r = 20.0;
    let dphi = bend_deg.to_radians() / layers as f64;
    let mut out = Vec::new();
    for i in 0..layers {
        let phi = i as f64 * dphi;
        let t = [phi.sin(), 0.0, phi.cos()];
        let u = [phi.cos(), 0.0, -phi.sin()];
        let c = [big_r - big_r * phi.cos(), 0.0, big_r * phi.sin()];
        let mut pts = Vec::new();
        for j in 0..=k {
            let th = j as f64 / k as f64 * std::f64::consts::TAU;
            let (s, co) = th.sin_cos();
            let pos = [c[0] + r * co * u[0], r * s, c[2] + r * co * u[2]];
            let tan = [-s * u[0], co, -s * u[2]];
            let rho = big_r - r * co;
            pts.push(Point {
                pos,
                normal: [t[0] as f32, t[1] as f32, t[2] as f32],
                tangent: [tan[0] as f32, tan[1] as f32, tan[2] as f32],
                layer_height: (rho * dphi.max(1e-9)) as f32,
                speed: (6.0 + 2.0 * co) as f32,
                power: (3000.0 - 20.0 * i as f64) as f32,
                powder: 45.9,
                defocus: -8.57,
                laser_on: j < k,
                style: 0,
                pitch: 0.0,
                rise: 0.0,
            });
        }
        let mut paths = vec![Path {
            kind: PathKind::Wall,
            points: pts,
        }];
        if i + 1 < layers {
            // A short laser-off move to the next layer's start.
            let mut last = *paths[0].points.last().unwrap();
            last.laser_on = false;
            last.speed = 20.0;
            paths.push(Path {
                kind: PathKind::Travel,
                points: vec![last],
            });
        }
        out.push(Layer {
            index: i,
            station: i as f64 / layers as f64,
            frame: Frame {
                origin: c,
                x: u,
                y: [0.0, 1.0, 0.0],
                z: t,
            },
            paths,
            label: String::new(),
            on_plate: false,
        });
    }
    Program {
        fixtures: Vec::new(),
        format: FORMAT.into(),
        version: VERSION_BASIC,
        part: "bent tube".into(),
        units: Units::default(),
        limits: Limits {
            layer_height: [0.0, 100.0],
            speed: [1.0, 50.0],
            power: [0.0, 4000.0],
            bead_width: 0.0,
            rise_tolerance: lmdc::ir::RISE_TOLERANCE,
            max_drift: lmdc::ir::MAX_DRIFT,
            max_overhang: None,
        },
        machines,
        styles: Vec::new(),
        heat: Heat::default(),
        thermal: None,
        continuous: false,
        ring: None,
        bead: None,
        layers: out,
        origins: Origins::default(),
    }
}
