//! Builds .lmd sources for ducts with given parameters, for property tests.
#![allow(dead_code)]

/// Parameters of a bent, twisted duct from a circle to a square.
#[derive(Clone, Debug)]
pub struct Duct {
    pub diameter: f64,
    pub side: f64,
    pub radius: f64,
    pub bend_deg: f64,
    pub twist_deg: f64,
    pub points: usize,
    pub outer: bool,
    pub seam_deg: f64,
}

impl Duct {
    /// The seed 000 part at the example's radius, small enough for fast tests.
    pub fn seed() -> Self {
        Duct {
            diameter: 60.0,
            side: 60.0,
            radius: 250.0,
            bend_deg: 45.0,
            twist_deg: 45.0,
            points: 64,
            outer: true,
            seam_deg: 90.0,
        }
    }

    pub fn source(&self) -> String {
        format!(
            "part duct
section inlet = circle(diameter = {d} mm)
section outlet = square(side = {s} mm)
bead b {{
  width = 6 mm
  speed = 7 mm/s .. 10 mm/s
  model = mass_balance(feed = 45.9 g/min, efficiency = 35 %, density = 7.9 g/cm^3)
  tilt = 0 deg .. {tilt} deg  // the nozzle follows the bend (lmd::bead-tilt)
}}
loft duct {{
  from = inlet
  to = outlet
  spine = arc(radius = {r} mm, angle = {a} deg)
  twist = {t} deg
  size = {size}
  wall = b
}}
slicing normal {{ layers = auto
  points = {k}
  seam = {seam} deg }}
process {{
  powder = 45.9 g/min
  defocus = -8.57 mm
  power = ramp(from = 4000 W, to = 2100 W, layers = 20)
}}
machine kr60 {{
  kind = robot
  head {{ standoff = 15 mm  nozzle = frustum(length = 45 mm, tip = 12 mm, top = 40 mm) }}
  load = load(mass = 18 kg, cog = [0 mm, 0 mm, 160 mm])
  laser = 1
  power_output = 1
  full_scale = 4000 W
  max_speed = 250 mm/s
}}
",
            d = self.diameter,
            s = self.side,
            r = self.radius,
            a = self.bend_deg,
            tilt = self.bend_deg.clamp(0.0, 90.0),
            t = self.twist_deg,
            size = if self.outer { "outer" } else { "centre" },
            k = self.points,
            seam = self.seam_deg,
        )
    }
}
