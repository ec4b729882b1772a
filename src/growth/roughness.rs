//! Initial rail irregularity on the periodic stretch: none, explicit
//! harmonics, seeded random roughness band-limited in wavelength, seeded
//! random roughness with a one-third-octave level spectrum, or a measured
//! record (its harmonics: [`super::record`]).
//!
//! The stretch has length `L = nx dx` and is periodic, so only wavelengths
//! `L/n` (n integer) exist on it. Random roughness is a sum of all harmonics
//! whose wavelength lies in `[wavelength_min, wavelength_max]`, with equal
//! amplitudes (a flat amplitude spectrum over the band) and phases drawn
//! from a ChaCha8 generator seeded by `seed`, scaled to the requested rms.
//! A level spectrum gives, per one-third-octave band of centre wavelength
//! `lambda_c` (band `lambda_c 2^(-1/6) ... lambda_c 2^(1/6)`), the band's rms
//! roughness as a level `L` in dB re 1 um, `rms = 1e-6 10^(L/20)` m, the
//! way rail roughness is specified and measured (EN ISO 3095, EN 15610). Each
//! harmonic of the stretch belongs to the band whose centre is nearest in
//! log wavelength (if it lies inside it), and the `K` harmonics of a band
//! share its rms equally, `A = rms sqrt(2 / K)`, with seeded random phases.
//! The irregularity is uniform across the rail head.

use crate::levels::density::RoughnessDensity;
use crate::params::{LevelBand, ProfileHarmonic, Roughness};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::PI;

/// Harmonic numbers n of a stretch of length `length` (m) in each band of
/// `bands`: those whose wavelength L/n lies within a sixth of an octave of
/// the band's centre and is nearest (in log wavelength) to it.
pub fn band_harmonics(length: f64, bands: &[LevelBand]) -> Vec<Vec<usize>> {
    let mut out = vec![Vec::new(); bands.len()];
    let Some(longest) = bands.iter().map(|b| b.wavelength).reduce(f64::max) else { return out };
    let shortest = bands.iter().map(|b| b.wavelength).fold(f64::INFINITY, f64::min);
    let half = 2f64.powf(1.0 / 6.0);
    for n in band(length, shortest / half, longest * half) {
        let lambda = length / n as f64;
        let distance = |b: &LevelBand| (lambda / b.wavelength).ln().abs();
        let nearest = (0..bands.len()).min_by(|i, j| distance(&bands[*i]).total_cmp(&distance(&bands[*j])));
        if let Some(i) = nearest
            && distance(&bands[i]) <= half.ln() * (1.0 + 1e-12)
        {
            out[i].push(n);
        }
    }
    out
}

/// Harmonic numbers n (wavelength L/n) of the periodic stretch of length
/// `length` (m) inside [`wavelength_min`, `wavelength_max`].
pub fn band(length: f64, wavelength_min: f64, wavelength_max: f64) -> std::ops::RangeInclusive<usize> {
    let lo = (length / wavelength_max - 1e-9).ceil().max(1.0) as usize;
    let hi = (length / wavelength_min + 1e-9).floor() as usize;
    lo..=hi
}

/// The density of a study's initial roughness, with the record's length (m)
/// where it is measured ([`crate::levels::density`]): a measured record's
/// whole record ([`super::record::record_density`]); explicit harmonics as
/// lines (their phases set aside: a forecast takes every harmonic's phase
/// as unrelated to the others'); random roughness flat over its band; a
/// level spectrum band by band.
pub fn density(r: &Roughness) -> (RoughnessDensity, Option<f64>) {
    match r {
        Roughness::None => (RoughnessDensity::none(), None),
        Roughness::Harmonics(h) => {
            let lines: Vec<(f64, f64)> =
                h.iter().map(|h| (2.0 * PI / h.wavelength, h.amplitude.powi(2) / 2.0)).collect();
            (RoughnessDensity::from_lines(&lines), None)
        }
        Roughness::Random { rms, wavelength_min, wavelength_max, .. } => {
            (RoughnessDensity::flat(rms * rms, *wavelength_min, *wavelength_max), None)
        }
        Roughness::Levels { bands, .. } => (RoughnessDensity::from_levels(bands), None),
        Roughness::Measured(m) => {
            let (d, length) = super::record::record_density(m);
            (d, Some(length))
        }
    }
}

/// Height of the irregularity at the nodes `x` (m) of a stretch of length
/// `length` (m).
pub fn profile_line(r: &Roughness, x: &[f64], length: f64) -> Vec<f64> {
    let harmonics: Vec<ProfileHarmonic> = match r {
        Roughness::None => Vec::new(),
        Roughness::Harmonics(h) => h.clone(),
        Roughness::Measured(m) => m.harmonics.clone(),
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
        Roughness::Levels { seed, bands } => {
            let mut rng = ChaCha8Rng::seed_from_u64(*seed);
            let mut out = Vec::new();
            for (b, ns) in bands.iter().zip(band_harmonics(length, bands)) {
                if ns.is_empty() {
                    continue;
                }
                let amplitude = 1e-6 * 10f64.powf(b.level / 20.0) * (2.0 / ns.len() as f64).sqrt();
                for n in ns {
                    let phase = rng.random_range(0.0..2.0 * PI);
                    out.push(ProfileHarmonic { amplitude, wavelength: length / n as f64, phase });
                }
            }
            out
        }
    };
    x.iter()
        .map(|x| harmonics.iter().map(|h| h.amplitude * (2.0 * PI * x / h.wavelength + h.phase).sin()).sum())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::harmonics::amplitudes;

    #[test]
    fn level_spectrum_gives_each_band_its_rms() {
        // 0.24 m stretch, 1 mm nodes; bands at 10, 16 and 25 mm (one third
        // of an octave is 2^(1/3) = 1.26: 12.5 and 20 mm are left out, so
        // their harmonics must stay empty).
        let (length, n) = (0.24, 240);
        let x: Vec<f64> = (0..n).map(|i| i as f64 * length / n as f64).collect();
        let bands = vec![
            LevelBand { wavelength: 0.010, level: 0.0 },
            LevelBand { wavelength: 0.016, level: -6.0 },
            LevelBand { wavelength: 0.025, level: 6.0 },
        ];
        let line = profile_line(&Roughness::Levels { seed: 7, bands: bands.clone() }, &x, length);
        let a = amplitudes(&line);
        let members = band_harmonics(length, &bands);
        for (b, ns) in bands.iter().zip(&members) {
            assert!(!ns.is_empty());
            let rms = (ns.iter().map(|k| a[k - 1].powi(2) / 2.0).sum::<f64>()).sqrt();
            let expected = 1e-6 * 10f64.powf(b.level / 20.0);
            assert!((rms - expected).abs() < 1e-12 * expected, "band {} m: {rms} vs {expected}", b.wavelength);
            for k in ns {
                let lambda = length / *k as f64;
                assert!((lambda / b.wavelength).log2().abs() <= 1.0 / 6.0 + 1e-12);
            }
        }
        let counted: Vec<usize> = members.concat();
        for (k, amp) in a.iter().enumerate() {
            if !counted.contains(&(k + 1)) {
                assert!(*amp < 1e-18, "harmonic {} ({} m) outside the bands: {amp}", k + 1, length / (k + 1) as f64);
            }
        }
        let again = profile_line(&Roughness::Levels { seed: 7, bands: bands.clone() }, &x, length);
        assert_eq!(line, again, "seeded");
        let other = profile_line(&Roughness::Levels { seed: 8, bands }, &x, length);
        assert_ne!(line, other);
    }

    #[test]
    fn a_harmonic_goes_to_the_nearest_band_only() {
        // Bands 1/6 octave apart overlap; a harmonic in both goes to the
        // nearer centre in log wavelength. L = 1 m: 1/85 = 0.01176 m is
        // 0.049 from 0.0112 and 0.061 from 0.0125; 1/84 = 0.01190 m is 0.061
        // and 0.049.
        let bands = [LevelBand { wavelength: 0.0112, level: 0.0 }, LevelBand { wavelength: 0.0125, level: 0.0 }];
        let members = band_harmonics(1.0, &bands);
        let n85 = |m: &Vec<usize>| m.contains(&85);
        assert!(n85(&members[0]) && !n85(&members[1]), "{members:?}");
        assert!(members[1].contains(&84) && !members[0].contains(&84), "{members:?}");
    }

    #[test]
    fn adjacent_bands_share_no_harmonic() {
        let bands: Vec<LevelBand> =
            [0.008, 0.010, 0.0125, 0.016, 0.020].iter().map(|w| LevelBand { wavelength: *w, level: 0.0 }).collect();
        let members = band_harmonics(1.0, &bands);
        let all: Vec<usize> = members.concat();
        let mut unique = all.clone();
        unique.sort();
        unique.dedup();
        assert_eq!(all.len(), unique.len());
        assert!(members.iter().all(|m| !m.is_empty()));
    }
}
