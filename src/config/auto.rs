//! `contact.model = "auto"`: the scene's shortest wavelength against the
//! largest patch, and the choice from the measured map
//! ([`crate::model_choice`]), with its refusals as config errors.

use super::ConfigError;
use crate::growth::roughness::profile_line;
use crate::harmonics::{amplitudes, wavelengths};
use crate::hertz::HertzShape;
use crate::loads::ImposedLoads;
use crate::model_choice::hertz_validity::HertzValidity;
use crate::model_choice::{AccuracyMap, ChoiceError, SAFETY};
use crate::params::AutoChoice;
use crate::params::Roughness;
use crate::params::{DynamicsKind, GrowthParams};

/// The config name of the automatic choice.
pub const AUTO: &str = "auto";

/// Shortest wavelength (m) of the imposed loads and of the initial rail
/// profile of a growth study; infinite when there is none.
pub fn shortest_wavelength(loads: &ImposedLoads, growth: Option<&GrowthParams>) -> f64 {
    let mut shortest = loads.harmonics.iter().map(|h| h.wavelength).fold(f64::INFINITY, f64::min);
    if let Some(g) = growth {
        let profile = match &g.roughness {
            Roughness::None => f64::INFINITY,
            Roughness::Harmonics(hs) => hs.iter().map(|h| h.wavelength).fold(f64::INFINITY, f64::min),
            Roughness::Measured(m) => m.harmonics.iter().map(|h| h.wavelength).fold(f64::INFINITY, f64::min),
            Roughness::Random { wavelength_min, .. } => *wavelength_min,
            // The lower edge of the shortest one-third-octave band.
            Roughness::Levels { bands, .. } => {
                bands.iter().map(|b| b.wavelength).fold(f64::INFINITY, f64::min) / 2f64.powf(1.0 / 6.0)
            }
        };
        shortest = shortest.min(profile);
    }
    shortest
}

/// The choice for a scene, or a config error on `contact.tolerance` or
/// `contact.model` saying why there is none.
pub fn resolve(
    tolerance: f64,
    loads: &ImposedLoads,
    growth: Option<&GrowthParams>,
    shape: &HertzShape,
    errors: &mut Vec<ConfigError>,
) -> Option<AutoChoice> {
    let a_max = shape.patch(loads.max_normal_force()).ok()?.a;
    let wavelength = shortest_wavelength(loads, growth);
    let lambda_over_2a = wavelength / (2.0 * a_max);
    match AccuracyMap::builtin().choose(lambda_over_2a, tolerance) {
        Ok(c) => Some(AutoChoice {
            tolerance,
            lambda_over_2a,
            wavelength,
            chosen: c.chosen,
            exact: c.exact,
            hertz_difference: None,
        }),
        Err(e @ ChoiceError::OutsideMap { .. }) => {
            errors.push(ConfigError::new(
                "contact.model",
                format!(
                    "= \"auto\": the shortest wavelength {wavelength:.4e} m over 2a_max = {:.4e} m gives {e}; \
                     name a model (exact-transient is valid at any lambda / 2a)",
                    2.0 * a_max
                ),
            ));
            None
        }
        Err(e @ ChoiceError::Unreachable { best, .. }) => {
            errors.push(ConfigError::new(
                "contact.tolerance",
                format!(
                    "= {tolerance}: {e} at lambda / 2a = {lambda_over_2a:.3}; allowed here: [{:.4}, 1]",
                    best / SAFETY
                ),
            ));
            None
        }
    }
}

/// The validity map's difference between the Hertz and the profile normal
/// contact ([`HertzValidity`]) at the initial profile of a growth study
/// with track dynamics (over a stretch of `length` m sampled every `dx` m):
/// the largest over its harmonics of at least half the dominant amplitude.
/// None without a growth study, dynamics or roughness.
pub fn hertz_difference(growth: Option<&GrowthParams>, length: f64, dx: f64) -> Option<f64> {
    let g = growth?;
    if g.dynamics == DynamicsKind::Imposed || !(length > 0.0 && dx > 0.0) {
        return None;
    }
    let n = (length / dx).round() as usize;
    let xs: Vec<f64> = (0..n).map(|i| i as f64 * length / n as f64).collect();
    let spectrum = amplitudes(&profile_line(&g.roughness, &xs, length));
    let waves = wavelengths(n, length / n as f64);
    let top = spectrum.iter().cloned().fold(0.0f64, f64::max);
    if top <= 0.0 {
        return None;
    }
    let map = HertzValidity::builtin();
    spectrum.iter().zip(&waves).filter(|(a, _)| **a >= 0.5 * top).map(|(a, w)| map.difference(*w, *a)).reduce(f64::max)
}
