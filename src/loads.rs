//! Imposed wheel-rail loads along the rail: a mean plus harmonics,
//! `value(X) = mean + sum_i amplitude_i sin(2 pi X / wavelength_i + phase_i)`
//! with X the patch-centre position in rail coordinates (Baeza et al. 2008,
//! section 4: N = 100 kN + 45 kN sin(2 pi X/lambda), F_x = 20 kN + 10 kN sin(...)).

use std::f64::consts::PI;

/// Which load a harmonic modulates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LoadQuantity {
    /// Normal force N.
    NormalForce,
    /// Longitudinal force F_x on the wheel.
    LongitudinalForce,
}

/// One imposed harmonic variation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Harmonic {
    /// The modulated load.
    pub quantity: LoadQuantity,
    /// Amplitude (N).
    pub amplitude: f64,
    /// Wavelength along the rail (m).
    pub wavelength: f64,
    /// Phase (rad).
    pub phase: f64,
}

impl Harmonic {
    fn at(&self, x: f64) -> f64 {
        self.amplitude * (2.0 * PI * x / self.wavelength + self.phase).sin()
    }
}

/// Normal and longitudinal force as functions of the patch position.
#[derive(Debug, Clone, PartialEq)]
pub struct ImposedLoads {
    /// Mean normal force (N).
    pub normal_force: f64,
    /// Mean longitudinal force on the wheel (N).
    pub longitudinal_force: f64,
    /// Imposed harmonics.
    pub harmonics: Vec<Harmonic>,
}

impl ImposedLoads {
    fn sum(&self, q: LoadQuantity, x: f64) -> f64 {
        self.harmonics.iter().filter(|h| h.quantity == q).map(|h| h.at(x)).sum()
    }

    /// Normal force N at patch position `x` (m), in N.
    pub fn normal_force_at(&self, x: f64) -> f64 {
        self.normal_force + self.sum(LoadQuantity::NormalForce, x)
    }

    /// Longitudinal force F_x at patch position `x` (m), in N.
    pub fn longitudinal_force_at(&self, x: f64) -> f64 {
        self.longitudinal_force + self.sum(LoadQuantity::LongitudinalForce, x)
    }

    /// Lower bound of N over any stretch: mean minus the sum of amplitudes (N).
    pub fn min_normal_force(&self) -> f64 {
        self.normal_force - self.amplitude_sum(LoadQuantity::NormalForce)
    }

    /// Upper bound of N (N).
    pub fn max_normal_force(&self) -> f64 {
        self.normal_force + self.amplitude_sum(LoadQuantity::NormalForce)
    }

    /// Upper bound of |F_x| (N).
    pub fn max_longitudinal_force(&self) -> f64 {
        self.longitudinal_force.abs() + self.amplitude_sum(LoadQuantity::LongitudinalForce)
    }

    fn amplitude_sum(&self, q: LoadQuantity) -> f64 {
        self.harmonics.iter().filter(|h| h.quantity == q).map(|h| h.amplitude.abs()).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paper_normal_force_scene() {
        let l = ImposedLoads {
            normal_force: 1e5,
            longitudinal_force: 2e4,
            harmonics: vec![Harmonic {
                quantity: LoadQuantity::NormalForce,
                amplitude: 4.5e4,
                wavelength: 0.03,
                phase: 0.0,
            }],
        };
        assert!((l.normal_force_at(0.0075) - 1.45e5).abs() < 1e-6);
        assert!((l.normal_force_at(0.0225) - 0.55e5).abs() < 1e-6);
        assert_eq!(l.longitudinal_force_at(0.01), 2e4);
        assert_eq!((l.min_normal_force(), l.max_normal_force()), (0.55e5, 1.45e5));
    }
}
