//! Initial rail irregularity on the periodic stretch: none, explicit
//! harmonics, or seeded random roughness band-limited in wavelength.
//!
//! The stretch has length `L = nx dx` and is periodic, so only wavelengths
//! `L/n` (n integer) exist on it. Random roughness is a sum of all harmonics
//! whose wavelength lies in `[wavelength_min, wavelength_max]`, with equal
//! amplitudes (a flat amplitude spectrum over the band) and phases drawn
//! from a ChaCha8 generator seeded by `seed`, scaled to the requested rms.
//! The irregularity is uniform across the rail head.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::PI;

/// One harmonic of the rail profile.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProfileHarmonic {
    /// Amplitude (m).
    pub amplitude: f64,
    /// Wavelength (m).
    pub wavelength: f64,
    /// Phase (rad): height = amplitude sin(2 pi X / wavelength + phase).
    pub phase: f64,
}

/// The initial irregularity.
#[derive(Debug, Clone, PartialEq)]
pub enum Roughness {
    /// A smooth rail.
    None,
    /// Explicit harmonics.
    Harmonics(Vec<ProfileHarmonic>),
    /// Seeded random, band-limited roughness.
    Random {
        /// Seed of the generator.
        seed: u64,
        /// rms height (m).
        rms: f64,
        /// Shortest wavelength (m).
        wavelength_min: f64,
        /// Longest wavelength (m).
        wavelength_max: f64,
    },
}

/// Harmonic numbers n (wavelength L/n) of the periodic stretch of length
/// `length` (m) inside [`wavelength_min`, `wavelength_max`].
pub fn band(length: f64, wavelength_min: f64, wavelength_max: f64) -> std::ops::RangeInclusive<usize> {
    let lo = (length / wavelength_max - 1e-9).ceil().max(1.0) as usize;
    let hi = (length / wavelength_min + 1e-9).floor() as usize;
    lo..=hi
}

/// Height of the irregularity at the nodes `x` (m) of a stretch of length
/// `length` (m).
pub fn profile_line(r: &Roughness, x: &[f64], length: f64) -> Vec<f64> {
    let harmonics: Vec<ProfileHarmonic> = match r {
        Roughness::None => Vec::new(),
        Roughness::Harmonics(h) => h.clone(),
        Roughness::Random { seed, rms, wavelength_min, wavelength_max } => {
            let mut rng = ChaCha8Rng::seed_from_u64(*seed);
            let ns: Vec<usize> = band(length, *wavelength_min, *wavelength_max).collect();
            // Equal amplitudes A with sum A^2/2 = rms^2.
            let amplitude = if ns.is_empty() { 0.0 } else { rms * (2.0 / ns.len() as f64).sqrt() };
            ns.iter()
                .map(|n| ProfileHarmonic {
                    amplitude,
                    wavelength: length / *n as f64,
                    phase: rng.random_range(0.0..2.0 * PI),
                })
                .collect()
        }
    };
    x.iter()
        .map(|x| harmonics.iter().map(|h| h.amplitude * (2.0 * PI * x / h.wavelength + h.phase).sin()).sum())
        .collect()
}
