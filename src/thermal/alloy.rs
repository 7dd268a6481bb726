//! The alloys lmdc knows the thermal data of (`material = …`), with where
//! each number comes from.
//!
//! A lumped model takes one value for each property, so each is the mean
//! over the range an interpass temperature lives in, 20–800 °C, of the
//! values the source tabulates (conductivity and heat capacity roughly
//! double from room temperature to 1000 °C; a mean over 20–800 °C is within
//! about 20 % of the true value from 100 °C to 700 °C). The absorptivity
//! is the share of the laser's power that ends up in the part in blown
//! powder DED — the powder caught and the melt pool together — which is
//! the model's least certain number: `absorptivity = …` overrides it, and
//! a calibration build should fit it.

use super::Material;

/// An alloy's thermal data, SI units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Alloy {
    /// The word `material = …` takes.
    pub key: &'static str,
    /// The alloy's usual name.
    pub name: &'static str,
    /// The data.
    pub material: Material,
    /// Where the numbers come from.
    pub source: &'static str,
}

/// The heat transfer coefficient to the cell's gas lmdc takes by default,
/// W/(m²·K): free convection from a hot wall (5–15) with the nozzle's
/// shielding and carrier gas blowing past the top layers, which Heigel,
/// Michaleris & Reutzel (Additive Manufacturing 5, 2015) found raises it
/// near the nozzle; `heat_transfer = …` overrides it, and a calibration
/// build should fit it.
pub const HEAT_TRANSFER: f64 = 20.0;

/// The absorptivity taken for blown-powder DED of steels and nickel and
/// titanium alloys with a 1 µm laser, within the 0.3–0.5 usually reported
/// (e.g. DebRoy et al., Progress in Materials Science 92, 2018).
const ABSORPTIVITY: f64 = 0.35;

/// The alloys, by `material = …`'s word.
pub static ALLOYS: [Alloy; 4] = [
    Alloy {
        key: "ss316l",
        name: "316L stainless steel",
        material: Material {
            conductivity: 20.0,
            density: 7950.0,
            heat_capacity: 560.0,
            emissivity: 0.5,
            absorptivity: ABSORPTIVITY,
            heat_transfer: HEAT_TRANSFER,
        },
        source: "K. C. Mills, Recommended values of thermophysical properties for selected commercial alloys, Woodhead 2002, '316 stainless steel' (k about 14 → 25 W/m·K, c about 470 → 600 J/kg·K over 20–800 °C); emissivity of an oxidised DED surface 0.4–0.6",
    },
    Alloy {
        key: "ti64",
        name: "Ti-6Al-4V",
        material: Material {
            conductivity: 12.0,
            density: 4420.0,
            heat_capacity: 620.0,
            emissivity: 0.45,
            absorptivity: ABSORPTIVITY,
            heat_transfer: HEAT_TRANSFER,
        },
        source: "K. C. Mills 2002, 'Ti-6Al-4V' (k about 7 → 17 W/m·K, c about 550 → 690 J/kg·K over 20–800 °C); emissivity of an oxidised surface 0.4–0.5",
    },
    Alloy {
        key: "in718",
        name: "Inconel 718",
        material: Material {
            conductivity: 17.0,
            density: 8190.0,
            heat_capacity: 520.0,
            emissivity: 0.5,
            absorptivity: ABSORPTIVITY,
            heat_transfer: HEAT_TRANSFER,
        },
        source: "K. C. Mills 2002, 'Inconel 718' (k about 11 → 23 W/m·K, c about 435 → 600 J/kg·K over 20–800 °C); Special Metals, Inconel alloy 718 data sheet (density 8.19 g/cm³)",
    },
    Alloy {
        key: "ph17_4",
        name: "17-4PH stainless steel",
        material: Material {
            conductivity: 20.0,
            density: 7780.0,
            heat_capacity: 540.0,
            emissivity: 0.5,
            absorptivity: ABSORPTIVITY,
            heat_transfer: HEAT_TRANSFER,
        },
        source: "AK Steel, 17-4 PH stainless steel product data bulletin (density 7.78 g/cm³, k 18.3 W/m·K at 100 °C and 22.7 at 500 °C, c 460 J/kg·K at 20 °C); heat capacity above 100 °C as 316's rise (Mills 2002)",
    },
];

/// The alloy `material = key` names.
pub fn alloy(key: &str) -> Option<&'static Alloy> {
    ALLOYS.iter().find(|a| a.key == key)
}

/// Every `material = …` word, in the table's order.
pub const KEYS: &[&str] = &["ss316l", "ti64", "in718", "ph17_4"];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_follow_the_table() {
        let keys: Vec<_> = ALLOYS.iter().map(|a| a.key).collect();
        assert_eq!(keys, KEYS);
        for a in &ALLOYS {
            let m = a.material;
            // Diffusivity of these alloys: 3–5 mm²/s.
            let alpha = m.conductivity / (m.density * m.heat_capacity) * 1e6;
            assert!((2.0..6.0).contains(&alpha), "{}: {alpha}", a.key);
            assert!(alloy(a.key).is_some());
        }
    }
}
