//! Amplitude spectrum of a periodic profile line (corrugation spectrum).
//!
//! For samples r_i, i = 0..N, of one period L = N dx, the amplitude of the
//! harmonic of wavelength L/n is `2 |R_n| / N` with `R_n = sum_i r_i
//! exp(-2 pi i n i / N)` (the discrete Fourier transform, rustfft), for
//! n = 1 .. N/2; the mean (n = 0) is left out.

use num_complex::Complex64;
use rustfft::FftPlanner;

/// Wavelengths L/n (m), n = 1 .. N/2, of a line of `n` samples spaced `dx`.
pub fn wavelengths(n: usize, dx: f64) -> Vec<f64> {
    (1..=n / 2).map(|k| n as f64 * dx / k as f64).collect()
}

/// Amplitudes (m) of the harmonics n = 1 .. N/2 of `line`.
pub fn amplitudes(line: &[f64]) -> Vec<f64> {
    let n = line.len();
    let mut buf: Vec<Complex64> = line.iter().map(|v| Complex64::new(*v, 0.0)).collect();
    FftPlanner::new().plan_fft_forward(n).process(&mut buf);
    (1..=n / 2).map(|k| 2.0 * buf[k].norm() / n as f64).collect()
}

/// Growth rate of each harmonic between two spectra `before` and `after`
/// (m) separated by `traffic` real passages, in dB per 1e5 passages:
/// `20 log10(after / before) * 1e5 / traffic`. Harmonics whose amplitude is
/// below `floor` (m) in either spectrum have no meaningful rate and get 0.
pub fn growth_rates(before: &[f64], after: &[f64], traffic: f64, floor: f64) -> Vec<f64> {
    before
        .iter()
        .zip(after)
        .map(|(b, a)| if *b > floor && *a > floor { 20.0 * (a / b).log10() * 1e5 / traffic } else { 0.0 })
        .collect()
}

/// A harmonic counts as one of the initial roughness where its filtered
/// amplitude after the first passage is at least this share of the
/// largest (a harmonic the roughness did not hold has no meaningful rate:
/// it grows from nothing).
const HELD_SHARE: f64 = 0.05;

/// What a growth study grew, in words: the harmonics of the initial
/// roughness with the highest and the lowest mean roughness-driven rate
/// over the run (the mean over the passages of each harmonic's rate, as
/// `corrugation-post figures` draws it). "what grew (...): 40 mm +1.07,
/// 33.3 mm +0.52; what wore down fastest: 10 mm -5.15", from a study's filtered amplitudes after its first
/// passage `first` (m, of the harmonics of `wavelengths` (m)) and each
/// passage's roughness-driven rates `rates` (dB per 1e5 wheel passages,
/// the same harmonics): at most `count` growing harmonics, fastest first,
/// and the fastest decaying one; None before the first passage.
pub fn what_grew(first: &[f64], rates: &[&[f64]], wavelengths: &[f64], count: usize) -> Option<String> {
    let largest = first.iter().fold(0.0f64, |m, a| m.max(*a));
    if rates.is_empty() || largest <= 0.0 {
        return None;
    }
    let mean = |n: usize| rates.iter().map(|r| r.get(n).copied().unwrap_or(0.0)).sum::<f64>() / rates.len() as f64;
    let mut held: Vec<(f64, f64)> = first
        .iter()
        .enumerate()
        .filter(|(_, a)| **a >= HELD_SHARE * largest)
        .map(|(n, _)| (wavelengths[n], mean(n)))
        .collect();
    held.sort_by(|a, b| b.1.total_cmp(&a.1));
    let words =
        |(wavelength, rate): &(f64, f64)| format!("{} mm {rate:+.2}", crate::numerics::round_sig(wavelength * 1e3, 3));
    let grew: Vec<String> = held.iter().filter(|h| h.1 > 0.0).take(count).map(words).collect();
    let grew = if grew.is_empty() { "nothing".to_string() } else { grew.join(", ") };
    let mut line = format!(
        "what grew (the mean roughness-driven rate over the run, dB per 1e5 wheel passages, of the initial \
         roughness's harmonics): {grew}"
    );
    if let Some(last) = held.last().filter(|h| h.1 < 0.0) {
        line.push_str(&format!("; what wore down fastest: {}", words(last)));
    }
    Some(line)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sine_amplitude_is_recovered() {
        let (n, dx) = (600, 1e-4);
        let line: Vec<f64> =
            (0..n).map(|i| 3e-6 + 2e-6 * (2.0 * std::f64::consts::PI * i as f64 * dx / 0.015 + 0.3).sin()).collect();
        let a = amplitudes(&line);
        let w = wavelengths(n, dx);
        let k = w.iter().position(|l| (l - 0.015).abs() < 1e-12).unwrap();
        assert!((a[k] - 2e-6).abs() < 1e-15);
        assert!(a.iter().enumerate().filter(|(i, _)| *i != k).all(|(_, v)| *v < 1e-15));
    }

    #[test]
    fn growth_rate_in_db_per_1e5_passages() {
        // Doubling over 1e5 passages is 20 log10(2) = 6.02 dB; halving over
        // 2e5 is -3.01 dB per 1e5; amplitudes under the floor give 0.
        let r = growth_rates(&[1e-6, 2e-6, 0.0], &[2e-6, 1e-6, 1e-6], 1e5, 1e-15);
        assert!((r[0] - 6.0206).abs() < 1e-4 && (r[1] + 6.0206).abs() < 1e-4 && r[2] == 0.0);
        let r = growth_rates(&[2e-6], &[1e-6], 2e5, 1e-15);
        assert!((r[0] + 3.0103).abs() < 1e-4);
    }

    #[test]
    fn the_fastest_held_harmonics_and_the_fastest_decaying_one() {
        // 0.6 m: harmonics 600, 300, 200, 150 mm; the 300 mm one below 5 %
        // of the largest (not held: its +40 is growth from nothing).
        let spectrum = [1e-7, 1e-10, 5e-8, 2e-8];
        let rates: [&[f64]; 2] = [&[0.5, 40.0, -2.0, 1.0], &[0.7, 40.0, -3.0, 1.2]];
        let line = what_grew(&spectrum, &rates, &[0.6, 0.3, 0.2, 0.15], 3).unwrap();
        assert!(line.ends_with(": 150 mm +1.10, 600 mm +0.60; what wore down fastest: 200 mm -2.50"), "{line}");
        assert_eq!(what_grew(&spectrum, &[], &[0.6, 0.3, 0.2, 0.15], 3), None);
        let decaying: [&[f64]; 1] = [&[-0.5, 0.0, -2.0, -1.0]];
        assert!(
            what_grew(&spectrum, &decaying, &[0.6, 0.3, 0.2, 0.15], 3)
                .unwrap()
                .contains("harmonics): nothing; what wore down fastest: 200 mm -2.00")
        );
    }
}
