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
}
