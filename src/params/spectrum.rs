//! The linear growth spectrum's parameters (`[spectrum]`, validated): what
//! the spectrum kernel (`src/spectrum/`) measures. Here, with the other parameters, so that
//! the scene can hold them without the parameters importing the kernel.

/// How the linearisation is differenced (`spectrum.difference`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, strum::EnumString, strum::IntoStaticStr, strum::VariantNames)]
#[strum(serialize_all = "lowercase")]
pub enum Difference {
    /// `(W(r0 + eps d) - W(r0 - eps d)) / 2 eps`: two passages per round.
    Central,
    /// `(W(r0 + eps d) - W(r0)) / eps`: one passage per round.
    Forward,
}

/// The rail the passage is linearised about (`spectrum.base`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Base {
    /// The smooth rail: `J` about `r = 0`, `W(0)` the forced pattern.
    Smooth,
    /// The study's initial roughness (`[roughness]`: harmonics, random,
    /// levels or a measured record).
    Roughness,
}

/// What the spectrum measures (`[spectrum]`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpectrumParams {
    /// Shortest wavelength perturbed (m).
    pub wavelength_min: f64,
    /// Longest wavelength perturbed (m).
    pub wavelength_max: f64,
    /// Bloch classes `M`: the supercell's stretches (1: the stretch's own
    /// harmonics).
    pub classes: usize,
    /// Amplitude of a passage's perturbation (m): of its one harmonic
    /// with one class; a passage that measures `K` classes at once
    /// perturbs each by `perturbation / sqrt(K)`.
    pub perturbation: f64,
    /// The differences.
    pub difference: Difference,
    /// The rail it is linearised about.
    pub base: Base,
}

impl Default for SpectrumParams {
    fn default() -> Self {
        SpectrumParams {
            wavelength_min: 0.010,
            wavelength_max: 0.150,
            classes: 1,
            perturbation: DEFAULT_PERTURBATION,
            difference: Difference::Central,
            base: Base::Smooth,
        }
    }
}

/// Default `spectrum.perturbation` (m): 10 nm. On growth_exact.toml's
/// chain the central differences at 1 and 10 nm agree within 0.004 dB per
/// 1e5 at 10-60 mm; at 0.1 um the contact's third-order response moves the
/// 10 mm rate by 0.029 (docs/src/theory/growth-spectrum.md).
pub const DEFAULT_PERTURBATION: f64 = 1e-8;
