//! Rail sections of the track models: bending stiffness, mass, shear
//! stiffness and rotary inertia per length, for the named profiles.
//!
//! Steel E = 210 GPa, G = 81 GPa, rho = 7850 kg/m^3; Timoshenko shear
//! coefficient kappa = 0.4 for a rail section in vertical bending (Thompson,
//! *Railway Noise and Vibration*, 2009, ch. 3, which uses 0.4; values from
//! 0.34 to 0.4 are found in the literature). Section data: EN 13674-1
//! (60E1 = UIC60: A = 76.70 cm^2, I = 3038 cm^4 in the standard, 3055 cm^4
//! in UIC leaflet 861-3, which the program has always used; 54E1 = UIC54:
//! A = 69.77 cm^2, I = 2346 cm^4, 54.77 kg/m).

use super::receptance::{RAIL_YOUNG_MODULUS, UIC60_MASS, UIC60_SECOND_MOMENT};

/// Shear modulus of rail steel (Pa).
pub const RAIL_SHEAR_MODULUS: f64 = 81e9;
/// Density of rail steel (kg/m^3).
pub const RAIL_DENSITY: f64 = 7850.0;
/// Timoshenko shear coefficient of a rail section in vertical bending (1).
pub const RAIL_SHEAR_COEFFICIENT: f64 = 0.4;

/// A rail section's properties per length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RailSection {
    /// Bending stiffness EI (N m^2).
    pub bending_stiffness: f64,
    /// Mass per length (kg/m).
    pub mass: f64,
    /// Shear stiffness kappa G A (N).
    pub shear_stiffness: f64,
    /// Rotary inertia per length rho I (kg m).
    pub rotary_inertia: f64,
}

impl RailSection {
    /// The names [`RailSection::preset`] knows.
    pub const PRESETS: [&'static str; 2] = ["UIC60", "54E1"];

    /// The section of a named rail (`UIC60` = 60E1, `54E1` = UIC54).
    pub fn preset(name: &str) -> Option<RailSection> {
        let (area, second_moment, mass) = match name {
            "UIC60" => (76.70e-4, UIC60_SECOND_MOMENT, UIC60_MASS),
            "54E1" => (69.77e-4, 23.46e-6, 54.77),
            _ => return None,
        };
        Some(RailSection {
            bending_stiffness: RAIL_YOUNG_MODULUS * second_moment,
            mass,
            shear_stiffness: RAIL_SHEAR_COEFFICIENT * RAIL_SHEAR_MODULUS * area,
            rotary_inertia: RAIL_DENSITY * second_moment,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets() {
        let u = RailSection::preset("UIC60").unwrap();
        assert_eq!((u.bending_stiffness, u.mass), (RAIL_YOUNG_MODULUS * UIC60_SECOND_MOMENT, UIC60_MASS));
        assert!((u.shear_stiffness - 2.485e8).abs() < 1e6 && (u.rotary_inertia - 0.2398).abs() < 1e-3);
        let r = RailSection::preset("54E1").unwrap();
        assert!((r.bending_stiffness - 4.927e6).abs() < 1e3 && r.mass == 54.77);
        assert!(RailSection::preset("S49").is_none());
    }
}
