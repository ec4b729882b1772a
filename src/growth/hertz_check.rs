//! The growth loop's check of the Hertz normal contact against the
//! measured validity map ([`crate::model_choice::hertz_validity`]).

use crate::model_choice::hertz_validity::{HERTZ_LIMIT, HertzValidity};

/// Tells the user, once per invocation, when the corrugation of a study
/// with the Hertz normal contact leaves the region where that contact is
/// good enough ([`HertzValidity`]).
pub(crate) struct HertzCheck {
    /// Still to check (Hertz normal contact, track dynamics, not yet told).
    pub active: bool,
    /// Whether the study runs on the fixed grid (the profile contact's).
    pub fixed: bool,
    /// The amplitude (m) from which the profile contact resolves the
    /// corrugation's own wear on the grid (below it the map's difference
    /// is the profile contact's noise, and there is nothing better to
    /// switch to).
    pub from: f64,
}

impl HertzCheck {
    /// The warning for the profile's spectrum (`amplitudes` at
    /// `wavelengths`), if its dominant harmonic has left the Hertz region.
    pub fn check(&mut self, wavelengths: &[f64], amplitudes: &[f64]) -> Option<String> {
        if !self.active {
            return None;
        }
        let (i, amplitude) =
            amplitudes.iter().copied().enumerate().fold((0, 0.0), |m, (i, a)| if a > m.1 { (i, a) } else { m });
        let wavelength = *wavelengths.get(i)?;
        if amplitude < self.from {
            return None;
        }
        let map = HertzValidity::builtin();
        if map.hertz_is_valid(wavelength, amplitude) {
            return None;
        }
        self.active = false;
        let d = map.difference(wavelength, amplitude);
        let by = if d.is_finite() { format!("by {:.0} %", 100.0 * d) } else { "beyond the map (full sliding)".into() };
        let how = if self.fixed {
            "set contact.normal = \"auto\" (the default; or \"profile\")"
        } else {
            "set contact.normal = \"auto\" (the default: the linear profile contact on this mesh)"
        };
        Some(format!(
            "the dominant harmonic of the corrugation ({:.1} mm, {:.3} um) has left the Hertz region: there the Hertz \
             and the profile normal contact differ {by} in the wear's first harmonic (limit {:.0} %, \
             scripts/validity_map.sh); {how} for the contact mechanics of the corrugated rail",
            wavelength * 1e3,
            amplitude * 1e6,
            100.0 * HERTZ_LIMIT
        ))
    }
}
