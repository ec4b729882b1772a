//! Rail sections of the track models: per-length properties for bending in
//! the vertical plane (the vertical models), and for the rail's axial
//! motion, lateral bending and torsion with the heights of the head, the
//! neutral axis and the shear centre (the rail head's receptances in three
//! directions, [`super::section`]).
//!
//! Steel E = 210 GPa, G = 81 GPa, rho = 7850 kg/m^3; Timoshenko shear
//! coefficient kappa = 0.4 for a rail section in vertical bending (Thompson,
//! *Railway Noise and Vibration*, 2009, ch. 3, which uses 0.4; values from
//! 0.34 to 0.4 are found in the literature). Section data: EN 13674-1
//! (60E1 = UIC60: A = 76.70 cm^2, I = 3038 cm^4 in the standard, 3055 cm^4
//! in UIC leaflet 861-3, which the program has always used, I_z = 512.3
//! cm^4 about the vertical axis, height 172 mm, neutral axis 80.95 mm above
//! the foot; 54E1 = UIC54: A = 69.77 cm^2, I = 2346 cm^4, I_z = 418.6 cm^4,
//! 54.77 kg/m, height 159 mm, neutral axis 76.2 mm above the foot).
//!
//! Two properties the standard does not list are estimates (override them
//! with the `[track]` keys where a section analysis gives better values):
//! - the Saint-Venant torsion constant J, as the sum of the head's, web's
//!   and foot's (thick rectangles: Roark's Formulas, table 10.1): 215 cm^4
//!   for 60E1, 165 cm^4 for 54E1; AREMA's published constant of its 119 RE
//!   section (159 mm high, 59 kg/m) is 5.11 in^4 = 213 cm^4;
//! - the shear centre's height above the foot: where the head's and the
//!   foot's lateral second moments balance (the shear centre of an
//!   I-section with unequal flanges), 41 mm for 60E1 and 38 mm for 54E1;
//!   AREMA gives 1.51 in = 38 mm for 119 RE.
//!
//! The lateral Timoshenko shear coefficient is 0.6 (the flanges carry the
//! shear in lateral bending: head and foot are 0.75 of the area, times
//! 5/6 for a rectangle). Warping torsion is not modelled (Saint-Venant
//! torsion only: it stiffens the rail's torsion above about 1 kHz).

use crate::dynamics::receptance::{RAIL_YOUNG_MODULUS, UIC60_MASS, UIC60_SECOND_MOMENT};

/// Shear modulus of rail steel (Pa).
pub const RAIL_SHEAR_MODULUS: f64 = 81e9;
/// Density of rail steel (kg/m^3).
pub const RAIL_DENSITY: f64 = 7850.0;
/// Timoshenko shear coefficient of a rail section in vertical bending (1).
pub const RAIL_SHEAR_COEFFICIENT: f64 = 0.4;
/// Timoshenko shear coefficient of a rail section in lateral bending (1):
/// an estimate (module docs).
pub const RAIL_LATERAL_SHEAR_COEFFICIENT: f64 = 0.6;

/// A rail section's properties per length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RailSection {
    /// Bending stiffness EI in the vertical plane (N m^2).
    pub bending_stiffness: f64,
    /// Mass per length (kg/m).
    pub mass: f64,
    /// Shear stiffness kappa G A in the vertical plane (N).
    pub shear_stiffness: f64,
    /// Rotary inertia per length rho I in the vertical plane (kg m).
    pub rotary_inertia: f64,
    /// What the rail head's motion in three directions needs besides.
    pub transverse: RailTransverse,
}

/// A rail section's axial, lateral and torsional properties per length,
/// and the heights that couple them to the head (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RailTransverse {
    /// Axial stiffness EA (N).
    pub axial_stiffness: f64,
    /// Bending stiffness E I_z in the horizontal plane (N m^2).
    pub lateral_bending_stiffness: f64,
    /// Shear stiffness kappa_y G A in the horizontal plane (N).
    pub lateral_shear_stiffness: f64,
    /// Rotary inertia per length rho I_z in the horizontal plane (kg m).
    pub lateral_rotary_inertia: f64,
    /// Saint-Venant torsional stiffness G J (N m^2).
    pub torsional_stiffness: f64,
    /// Polar moment of inertia per length about the centroid, rho (I_y +
    /// I_z) (kg m).
    pub polar_inertia: f64,
    /// Height of the rail, foot to head top (m).
    pub height: f64,
    /// Height of the neutral axis (the centroid) above the foot (m).
    pub neutral_axis_height: f64,
    /// Height of the shear centre above the foot (m).
    pub shear_centre_height: f64,
}

impl RailTransverse {
    /// The head top (the contact) above the neutral axis (m).
    pub fn head_above_neutral_axis(&self) -> f64 {
        self.height - self.neutral_axis_height
    }

    /// The head top above the shear centre (m).
    pub fn head_above_shear_centre(&self) -> f64 {
        self.height - self.shear_centre_height
    }
}

impl RailSection {
    /// The names [`RailSection::preset`] knows.
    pub const PRESETS: [&'static str; 2] = ["UIC60", "54E1"];

    /// The section of a named rail (`UIC60` = 60E1, `54E1` = UIC54).
    pub fn preset(name: &str) -> Option<RailSection> {
        // (A m^2, I_y m^4, kg/m, I_z m^4, J m^4, height, neutral axis, shear centre m)
        let (area, second_moment, mass, lateral, torsion, height, neutral, shear_centre) = match name {
            "UIC60" => (76.70e-4, UIC60_SECOND_MOMENT, UIC60_MASS, 512.3e-8, 215e-8, 0.172, 0.08095, 0.041),
            "54E1" => (69.77e-4, 23.46e-6, 54.77, 418.6e-8, 165e-8, 0.159, 0.0762, 0.038),
            _ => return None,
        };
        Some(RailSection {
            bending_stiffness: RAIL_YOUNG_MODULUS * second_moment,
            mass,
            shear_stiffness: RAIL_SHEAR_COEFFICIENT * RAIL_SHEAR_MODULUS * area,
            rotary_inertia: RAIL_DENSITY * second_moment,
            transverse: RailTransverse {
                axial_stiffness: RAIL_YOUNG_MODULUS * area,
                lateral_bending_stiffness: RAIL_YOUNG_MODULUS * lateral,
                lateral_shear_stiffness: RAIL_LATERAL_SHEAR_COEFFICIENT * RAIL_SHEAR_MODULUS * area,
                lateral_rotary_inertia: RAIL_DENSITY * lateral,
                torsional_stiffness: RAIL_SHEAR_MODULUS * torsion,
                polar_inertia: RAIL_DENSITY * (second_moment + lateral),
                height,
                neutral_axis_height: neutral,
                shear_centre_height: shear_centre,
            },
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
        let t = u.transverse;
        assert!((t.axial_stiffness - 1.611e9).abs() < 1e6 && (t.lateral_bending_stiffness - 1.076e6).abs() < 1e3);
        assert!(
            (t.head_above_neutral_axis() - 0.09105).abs() < 1e-9 && (t.head_above_shear_centre() - 0.131).abs() < 1e-12
        );
        let r = RailSection::preset("54E1").unwrap();
        assert!((r.bending_stiffness - 4.927e6).abs() < 1e3 && r.mass == 54.77);
        assert!(RailSection::preset("S49").is_none());
    }
}
