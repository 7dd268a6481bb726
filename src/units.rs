//! Physical quantities: dimensions, the unit table, and the typed values the rest of
//! the compiler works with (so a speed can never be passed where a length belongs).
//!
//! Canonical internal units: mm, g, s, rad. Everything the user writes is converted
//! to these when it is evaluated; the IR and the back ends convert once more to what
//! their formats want (deg, mm/min, m/s, g/min).

use std::fmt;

/// Exponents of the base dimensions length, mass, time, angle and
/// temperature. Angle is kept as a dimension of its own so that
/// `60 mm + 45 deg` is an error.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Dim {
    /// Length exponent.
    pub l: i8,
    /// Mass exponent.
    pub m: i8,
    /// Time exponent.
    pub t: i8,
    /// Angle exponent.
    pub a: i8,
    /// Temperature exponent (°C: temperatures are levels in °C, and a
    /// difference of one °C is one kelvin).
    pub k: i8,
}

impl Dim {
    /// A pure number.
    pub const NONE: Dim = Dim::new(0, 0, 0, 0);
    /// mm
    pub const LENGTH: Dim = Dim::new(1, 0, 0, 0);
    /// rad
    pub const ANGLE: Dim = Dim::new(0, 0, 0, 1);
    /// s
    pub const TIME: Dim = Dim::new(0, 0, 1, 0);
    /// g
    pub const MASS: Dim = Dim::new(0, 1, 0, 0);
    /// mm/s
    pub const SPEED: Dim = Dim::new(1, 0, -1, 0);
    /// g/s
    pub const MASS_FLOW: Dim = Dim::new(0, 1, -1, 0);
    /// W = g·mm²/s³ (scaled)
    pub const POWER: Dim = Dim::new(2, 1, -3, 0);
    /// g/mm³
    pub const DENSITY: Dim = Dim::new(-3, 1, 0, 0);
    /// mm/s²: a machine's path acceleration.
    pub const ACCELERATION: Dim = Dim::new(1, 0, -2, 0);
    /// rad/s: a robot axis's speed.
    pub const ANGULAR_SPEED: Dim = Dim::new(0, 0, -1, 1);
    /// g·mm²: a moment of inertia (a robot tool's load).
    pub const INERTIA: Dim = Dim::new(2, 1, 0, 0);
    /// °C: a temperature (an interpass limit, a preheat).
    pub const TEMPERATURE: Dim = Dim {
        l: 0,
        m: 0,
        t: 0,
        a: 0,
        k: 1,
    };
    /// W/(mm²·°C), scaled: a heat transfer coefficient.
    pub const HEAT_TRANSFER: Dim = Dim {
        l: 0,
        m: 1,
        t: -3,
        a: 0,
        k: -1,
    };

    /// g·mm/(s³·°C), scaled: a thermal conductivity (W/(m·°C)).
    pub const CONDUCTIVITY: Dim = Dim {
        l: 1,
        m: 1,
        t: -3,
        a: 0,
        k: -1,
    };
    /// mm²/(s²·°C): a specific heat capacity (J/(kg·°C)).
    pub const HEAT_CAPACITY: Dim = Dim {
        l: 2,
        m: 0,
        t: -2,
        a: 0,
        k: -1,
    };

    /// Builds a dimension from exponents.
    pub const fn new(l: i8, m: i8, t: i8, a: i8) -> Dim {
        Dim { l, m, t, a, k: 0 }
    }

    /// Product of two dimensions.
    pub fn times(self, o: Dim) -> Dim {
        Dim {
            l: self.l.saturating_add(o.l),
            m: self.m.saturating_add(o.m),
            t: self.t.saturating_add(o.t),
            a: self.a.saturating_add(o.a),
            k: self.k.saturating_add(o.k),
        }
    }

    /// Quotient of two dimensions.
    pub fn per(self, o: Dim) -> Dim {
        self.times(o.powi(-1))
    }

    /// Integer power.
    pub fn powi(self, n: i32) -> Dim {
        let p = |e: i8| (e as i32 * n).clamp(-100, 100) as i8;
        Dim {
            l: p(self.l),
            m: p(self.m),
            t: p(self.t),
            a: p(self.a),
            k: p(self.k),
        }
    }

    /// A name a process engineer recognises, with an example unit.
    pub fn describe(self) -> String {
        let known = [
            (Dim::NONE, "a plain number"),
            (Dim::LENGTH, "a length (mm)"),
            (Dim::ANGLE, "an angle (deg)"),
            (Dim::TIME, "a time (s)"),
            (Dim::MASS, "a mass (kg)"),
            (Dim::SPEED, "a speed (mm/s)"),
            (Dim::ACCELERATION, "an acceleration (mm/s^2)"),
            (Dim::ANGULAR_SPEED, "an angular speed (deg/s)"),
            (Dim::MASS_FLOW, "a powder feed rate (g/min)"),
            (Dim::POWER, "a power (W)"),
            (Dim::DENSITY, "a density (g/cm^3)"),
            (Dim::INERTIA, "a moment of inertia (kg*m^2)"),
            (Dim::new(2, 0, 0, 0), "an area (mm^2)"),
            (Dim::new(3, 0, 0, 0), "a volume (mm^3)"),
            (Dim::new(2, 1, -2, 0), "an energy (J)"),
            (Dim::TEMPERATURE, "a temperature (degC)"),
            (
                Dim::HEAT_TRANSFER,
                "a heat transfer coefficient (W/m^2/degC)",
            ),
            (Dim::CONDUCTIVITY, "a thermal conductivity (W/m/degC)"),
            (Dim::HEAT_CAPACITY, "a specific heat capacity (J/kg/degC)"),
        ];
        for (d, name) in known {
            if d == self {
                return name.to_string();
            }
        }
        format!("a quantity in {}", self.unit_string())
    }

    /// The dimension spelled in canonical units, e.g. `mm/s`.
    pub fn unit_string(self) -> String {
        let mut num = Vec::new();
        let mut den = Vec::new();
        for (e, u) in [
            (self.m, "g"),
            (self.l, "mm"),
            (self.a, "rad"),
            (self.t, "s"),
            (self.k, "degC"),
        ] {
            let (list, e) = if e > 0 { (&mut num, e) } else { (&mut den, -e) };
            match e {
                0 => {}
                1 => list.push(u.to_string()),
                _ => list.push(format!("{u}^{e}")),
            }
        }
        let n = if num.is_empty() {
            "1".to_string()
        } else {
            num.join("·")
        };
        if den.is_empty() {
            n
        } else {
            format!("{n}/{}", den.join("·"))
        }
    }
}

/// A unit the language knows: its name, its size in canonical units, its dimension.
struct UnitDef {
    name: &'static str,
    factor: f64,
    dim: Dim,
}

const W_FACTOR: f64 = 1e9; // 1 W = 1 kg·m²/s³ = 1e9 g·mm²/s³

const UNITS: &[UnitDef] = &[
    UnitDef {
        name: "mm",
        factor: 1.0,
        dim: Dim::LENGTH,
    },
    UnitDef {
        name: "cm",
        factor: 10.0,
        dim: Dim::LENGTH,
    },
    UnitDef {
        name: "m",
        factor: 1000.0,
        dim: Dim::LENGTH,
    },
    UnitDef {
        name: "um",
        factor: 1e-3,
        dim: Dim::LENGTH,
    },
    UnitDef {
        name: "µm",
        factor: 1e-3,
        dim: Dim::LENGTH,
    },
    UnitDef {
        name: "in",
        factor: 25.4,
        dim: Dim::LENGTH,
    },
    UnitDef {
        name: "deg",
        factor: std::f64::consts::PI / 180.0,
        dim: Dim::ANGLE,
    },
    UnitDef {
        name: "°",
        factor: std::f64::consts::PI / 180.0,
        dim: Dim::ANGLE,
    },
    UnitDef {
        name: "rad",
        factor: 1.0,
        dim: Dim::ANGLE,
    },
    UnitDef {
        name: "s",
        factor: 1.0,
        dim: Dim::TIME,
    },
    UnitDef {
        name: "ms",
        factor: 1e-3,
        dim: Dim::TIME,
    },
    UnitDef {
        name: "min",
        factor: 60.0,
        dim: Dim::TIME,
    },
    UnitDef {
        name: "h",
        factor: 3600.0,
        dim: Dim::TIME,
    },
    UnitDef {
        name: "g",
        factor: 1.0,
        dim: Dim::MASS,
    },
    UnitDef {
        name: "kg",
        factor: 1000.0,
        dim: Dim::MASS,
    },
    UnitDef {
        name: "mg",
        factor: 1e-3,
        dim: Dim::MASS,
    },
    UnitDef {
        name: "W",
        factor: W_FACTOR,
        dim: Dim::POWER,
    },
    UnitDef {
        name: "kW",
        factor: 1e3 * W_FACTOR,
        dim: Dim::POWER,
    },
    UnitDef {
        name: "J",
        factor: W_FACTOR,
        dim: Dim::new(2, 1, -2, 0),
    },
    UnitDef {
        name: "Hz",
        factor: 1.0,
        dim: Dim::new(0, 0, -1, 0),
    },
    // Temperatures are levels in °C (no kelvin: a level in K is not a
    // factor of one in °C, and lmdc has no offsets in its units); in a
    // compound unit (`W/m^2/degC`) one °C is a kelvin's difference.
    UnitDef {
        name: "degC",
        factor: 1.0,
        dim: Dim::TEMPERATURE,
    },
    UnitDef {
        name: "°C",
        factor: 1.0,
        dim: Dim::TEMPERATURE,
    },
    UnitDef {
        name: "%",
        factor: 0.01,
        dim: Dim::NONE,
    },
];

/// A number with a dimension, in canonical units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quantity {
    /// Value in canonical units (mm, g, s, rad).
    pub value: f64,
    /// Its dimension.
    pub dim: Dim,
}

impl Quantity {
    /// A pure number.
    pub fn number(value: f64) -> Self {
        Quantity {
            value,
            dim: Dim::NONE,
        }
    }
}

/// Error from [`parse_unit`]: the unit atom that is not known.
#[derive(Debug, Clone, PartialEq)]
pub struct UnknownUnit(pub String);

/// Words people write for units lmdc knows by another name: the unit meant.
const UNIT_ALIASES: &[(&str, &str)] = &[
    ("sec", "s"),
    ("secs", "s"),
    ("second", "s"),
    ("seconds", "s"),
    ("mins", "min"),
    ("minute", "min"),
    ("minutes", "min"),
    ("hr", "h"),
    ("hrs", "h"),
    ("hour", "h"),
    ("hours", "h"),
    ("watt", "W"),
    ("watts", "W"),
    ("kilowatt", "kW"),
    ("kilowatts", "kW"),
    ("degree", "deg"),
    ("degrees", "deg"),
    ("degs", "deg"),
    ("gram", "g"),
    ("grams", "g"),
    ("gr", "g"),
    ("micron", "um"),
    ("microns", "um"),
    ("mms", "mm/s"),
    ("mmps", "mm/s"),
    ("mmpm", "mm/min"),
];

/// The unit someone writing `atom` most likely meant: a known unit that
/// differs only in case (`KW` → `kW`), or the usual name for a word such as
/// `sec` or `watts`.
pub fn unit_meant(atom: &str) -> Option<&'static str> {
    let lower = atom.to_lowercase();
    UNIT_ALIASES
        .iter()
        .find(|(a, _)| *a == lower)
        .map(|&(_, u)| u)
        .or_else(|| {
            UNITS
                .iter()
                .find(|u| u.name.to_lowercase() == lower)
                .map(|u| u.name)
        })
}

/// Parses a unit expression such as `mm/s`, `g/cm^3`, `kW` into (factor, dimension).
/// Units are multiplied and divided left to right: `g/cm^3` is g·cm⁻³.
pub fn parse_unit(text: &str) -> Result<(f64, Dim), UnknownUnit> {
    let mut factor = 1.0;
    let mut dim = Dim::NONE;
    let mut divide = false;
    let mut rest = text;
    loop {
        let end = rest.find(['/', '*', '·']).unwrap_or(rest.len());
        let (atom, exp) = match rest[..end].split_once('^') {
            Some((a, e)) => (a, e.parse::<i32>().map_err(|_| UnknownUnit(text.into()))?),
            None => (&rest[..end], 1),
        };
        let def = UNITS
            .iter()
            .find(|u| u.name == atom)
            .ok_or_else(|| UnknownUnit(atom.to_string()))?;
        let exp = if divide { -exp } else { exp };
        factor *= def.factor.powi(exp);
        dim = dim.times(def.dim.powi(exp));
        if end == rest.len() {
            break;
        }
        let sep = rest[end..].chars().next().unwrap_or('*');
        divide = sep == '/';
        rest = &rest[end + sep.len_utf8()..];
    }
    Ok((factor, dim))
}

macro_rules! typed_quantity {
    ($(#[$doc:meta])* $name:ident, $dim:expr, $unit:literal) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq, PartialOrd, Default)]
        pub struct $name(pub f64);

        impl $name {
            /// The dimension values of this type have.
            pub const DIM: Dim = $dim;

            /// From a checked quantity, if the dimension matches.
            pub fn from_quantity(q: Quantity) -> Option<Self> {
                (q.dim == Self::DIM).then_some($name(q.value))
            }
        }

        impl fmt::Display for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "{} {}", crate::units::short(self.display_value()), $unit)
            }
        }
    };
}

typed_quantity!(
    /// A length in mm.
    Length, Dim::LENGTH, "mm");
typed_quantity!(
    /// An angle in radians (shown in degrees).
    Angle, Dim::ANGLE, "deg");
typed_quantity!(
    /// A speed in mm/s.
    Speed, Dim::SPEED, "mm/s");
typed_quantity!(
    /// A power in canonical units (shown in W).
    Power, Dim::POWER, "W");
typed_quantity!(
    /// A powder feed rate in g/s (shown in g/min).
    MassFlow, Dim::MASS_FLOW, "g/min");
typed_quantity!(
    /// A density in g/mm³ (shown in g/cm³).
    Density, Dim::DENSITY, "g/cm^3");
typed_quantity!(
    /// A time in s.
    Time, Dim::TIME, "s");
typed_quantity!(
    /// A mass in g (shown in kg: a robot tool's load).
    Mass, Dim::MASS, "kg");
typed_quantity!(
    /// A temperature in °C.
    Temperature, Dim::TEMPERATURE, "°C");
typed_quantity!(
    /// A moment of inertia in g·mm² (shown in kg·m², as KUKA's `$LOAD.J`).
    Inertia, Dim::INERTIA, "kg*m^2");

impl Temperature {
    fn display_value(self) -> f64 {
        self.0
    }
}
impl Length {
    fn display_value(self) -> f64 {
        self.0
    }
    /// In mm.
    pub fn mm(self) -> f64 {
        self.0
    }
}
impl Angle {
    fn display_value(self) -> f64 {
        self.0.to_degrees()
    }
    /// From degrees.
    pub fn from_deg(d: f64) -> Self {
        Angle(d.to_radians())
    }
    /// In radians.
    pub fn rad(self) -> f64 {
        self.0
    }
    /// In degrees.
    pub fn deg(self) -> f64 {
        self.0.to_degrees()
    }
}
impl Speed {
    fn display_value(self) -> f64 {
        self.0
    }
    /// In mm/s.
    pub fn mm_s(self) -> f64 {
        self.0
    }
}
impl Power {
    fn display_value(self) -> f64 {
        self.watts()
    }
    /// From watts.
    pub fn from_watts(w: f64) -> Self {
        Power(w * W_FACTOR)
    }
    /// In watts.
    pub fn watts(self) -> f64 {
        self.0 / W_FACTOR
    }
}
impl MassFlow {
    fn display_value(self) -> f64 {
        self.g_min()
    }
    /// In g/min.
    pub fn g_min(self) -> f64 {
        self.0 * 60.0
    }
}
impl Density {
    fn display_value(self) -> f64 {
        self.0 * 1000.0
    }
}
impl Time {
    fn display_value(self) -> f64 {
        self.0
    }
}
impl Mass {
    fn display_value(self) -> f64 {
        self.kg()
    }
    /// In kg.
    pub fn kg(self) -> f64 {
        self.0 / 1000.0
    }
}
impl Inertia {
    fn display_value(self) -> f64 {
        self.kg_m2()
    }
    /// In kg·m² (1 kg·m² = 10⁹ g·mm²).
    pub fn kg_m2(self) -> f64 {
        self.0 * 1e-9
    }
}

/// Relative slack of every range rule, in the checker (declared values) and the
/// verifier (planned points) alike: the IR stores process values as `f32`
/// (about 6·10⁻⁸ relative), so a value computed at the edge of its range may
/// land a rounding outside it.
pub const RANGE_SLACK: f64 = 1e-6;

/// How far (relative) a quotient may lie past a whole number and still be
/// that many: a mesh's coordinates are `f32` (about 6·10⁻⁸ relative each),
/// and a unit conversion and a turn add roundings of their own, so a part
/// drawn 15 mm tall in inches reads back as 15.0000019 mm. A millionth of
/// the count is a nanometre a layer on millimetre layers: no machine builds
/// it, and a whole layer (of a millimetre of metal) for it is a defect.
pub const COUNT_SLACK: f64 = 1e-6;

/// The whole number of pieces of `q` units (layers of a height): `⌈q⌉`,
/// except that `q` within [`COUNT_SLACK`] of a whole number is that number.
pub fn whole_count(q: f64) -> f64 {
    let r = q.round();
    if (q - r).abs() <= COUNT_SLACK * r.abs().max(1.0) {
        r
    } else {
        q.ceil()
    }
}

/// Whether `x` lies in `lo ..= hi`, allowing [`RANGE_SLACK`] of each end.
pub fn in_range(x: f64, [lo, hi]: [f64; 2]) -> bool {
    x >= lo - RANGE_SLACK * lo.abs() && x <= hi + RANGE_SLACK * hi.abs()
}

/// `v` rounded up to the digits [`short`] prints, so that advice to raise a
/// value to at least it is enough when followed as printed.
pub fn short_up(v: f64) -> String {
    let decimals = if v.abs() >= 100.0 {
        1
    } else if v.abs() >= 1.0 {
        3
    } else {
        4
    };
    let p = 10f64.powi(decimals);
    // A hair of slack: a value already printed exactly stays as it is.
    short(((v * p) - 1e-9).ceil() / p)
}

/// How many mm one `unit` of length is (`mm`, `cm`, `m`, `in`, … as the
/// unit table reads them; 1 for a word it does not know): what a mesh's
/// `units` scale its coordinates by.
pub fn mm_per(unit: &str) -> f64 {
    parse_unit(unit)
        .ok()
        .filter(|(_, d)| *d == Dim::LENGTH)
        .map_or(1.0, |(f, _)| f)
}

/// A value of dimension `dim` for a message, in the unit that kind of value
/// is written in (W, g/min, deg, …), not in lmdc's internal units.
pub fn shown(value: f64, dim: Dim) -> String {
    match dim {
        Dim::NONE => short(value),
        Dim::LENGTH => Length(value).to_string(),
        Dim::ANGLE => Angle(value).to_string(),
        Dim::SPEED => Speed(value).to_string(),
        Dim::POWER => Power(value).to_string(),
        Dim::MASS_FLOW => MassFlow(value).to_string(),
        Dim::DENSITY => Density(value).to_string(),
        Dim::TIME => Time(value).to_string(),
        Dim::MASS => Mass(value).to_string(),
        Dim::INERTIA => Inertia(value).to_string(),
        Dim::TEMPERATURE => Temperature(value).to_string(),
        other => format!("{} {}", short(value), other.unit_string()),
    }
}

/// Formats a number for messages: at most 4 significant decimals, no trailing zeros.
pub fn short(v: f64) -> String {
    if !v.is_finite() {
        return format!("{v}");
    }
    // Beyond any part's size: a mistake's number, readable in exponent form.
    if v.abs() >= 1e9 {
        return format!("{v:.3e}");
    }
    // Too small for four decimals, but not nothing: never print it as 0,
    // but with its first two significant digits (`-0.000022`; below 1e-12
    // it is a computation's rounding, and 0 is what it means).
    if v.abs() >= 1e-12 && v.abs() < 5e-5 {
        let d = (-v.abs().log10()).floor() as usize + 2;
        let s = format!("{v:.d$}");
        return s.trim_end_matches('0').trim_end_matches('.').to_string();
    }
    let s = if v.abs() >= 100.0 {
        format!("{v:.1}")
    } else if v.abs() >= 1.0 {
        format!("{v:.3}")
    } else {
        format!("{v:.4}")
    };
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    };
    if s == "-0" {
        "0".into()
    } else {
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn float_noise_is_no_extra_layer() {
        // 15 mm drawn in inches, stored as f32: 0.59055126 in.
        let top = f64::from(0.590_551_26_f32) * 25.4;
        assert!(top > 15.0 && top < 15.00001, "{top}");
        assert_eq!(whole_count(top / 1.0), 15.0);
        assert_eq!(whole_count(8.4 / 1.2), 7.0);
        // A real remainder is a layer, however thin.
        assert_eq!(whole_count(15.001), 16.0);
        assert_eq!(whole_count(14.2), 15.0);
        assert_eq!(whole_count(0.3), 1.0);
    }

    #[test]
    fn short_never_prints_a_value_as_another() {
        assert_eq!(short(1e-9), "0.000000001");
        assert_eq!(short(-0.000_022_04), "-0.000022");
        assert_eq!(short(0.000_001_1), "0.0000011");
        assert_eq!(short(-3e-6), "-0.000003");
        assert_eq!(short(0.0), "0");
        assert_eq!(short(4.7e-17), "0");
        assert_eq!(short(0.00012), "0.0001");
        assert_eq!(short(197.14), "197.1");
        // Rounded up at the digits printed: followed as printed, enough.
        for v in [207.14, 207.1, 34.9381, 7.69101, 0.00012, 1e-9] {
            let up: f64 = short_up(v).parse().unwrap();
            assert!(up >= v - 1e-9 * v.abs(), "{v}: {up}");
            assert!(up - v < 0.1, "{v}: {up}");
        }
        assert_eq!(short_up(207.14), "207.2");
        assert_eq!(short_up(34.9381), "34.939");
    }

    #[test]
    fn compound_units() {
        let (f, d) = parse_unit("mm/s").unwrap();
        assert_eq!((f, d), (1.0, Dim::SPEED));
        let (f, d) = parse_unit("g/min").unwrap();
        assert!((f - 1.0 / 60.0).abs() < 1e-15);
        assert_eq!(d, Dim::MASS_FLOW);
        let (f, d) = parse_unit("g/cm^3").unwrap();
        assert!((f - 1e-3).abs() < 1e-18);
        assert_eq!(d, Dim::DENSITY);
        let (f, d) = parse_unit("kW").unwrap();
        assert_eq!(Power(f).watts(), 1000.0);
        assert_eq!(d, Dim::POWER);
        assert!(parse_unit("furlong").is_err());
        // A machine's acceleration, in mm/s² or m/s².
        assert_eq!(parse_unit("mm/s^2").unwrap(), (1.0, Dim::ACCELERATION));
        let (f, d) = parse_unit("m/s^2").unwrap();
        assert_eq!((f, d), (1000.0, Dim::ACCELERATION));
    }

    #[test]
    fn describes_dimensions() {
        assert_eq!(Dim::SPEED.describe(), "a speed (mm/s)");
        assert_eq!(Dim::new(1, 0, -2, 0).unit_string(), "mm/s^2");
        assert_eq!(Dim::ACCELERATION.describe(), "an acceleration (mm/s^2)");
    }
}
