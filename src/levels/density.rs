//! A roughness's mean square by wavenumber, independent of any stretch: the
//! input of a forecast from the linear growth spectrum
//! ([`crate::spectrum::forecast`]).
//!
//! It is held as the cumulative mean square `C(k)` (m^2) over wavenumber
//! `k` (1/m), piecewise linear, so the mean square between two wavenumbers
//! is `C(k2) - C(k1)` for any interval, whatever the lines it was built
//! from.
//!
//! * A measured record (EN 15610 sec. 7-8): the whole record, processed as
//!   the study processes it (spikes, curvature, detrend over the record),
//!   Hann-windowed, its discrete Fourier transform normalised so that the
//!   lines' mean squares sum to the windowed record's mean square over the
//!   window's mean square (`sum_k P_k = mean(h^2)` for a broadband record;
//!   a sine of amplitude `A` between lines gives `A^2 / 2` over the lines
//!   its window spreads it on). Each line (`k 2 pi / (N d)`) counts in the
//!   band that holds its wavenumber, as a band spectrum is summed from the
//!   lines of a DFT; lines outside the roughness's wavelength band are
//!   dropped, as the study drops them.
//! * A level spectrum: each band's mean square `r0^2 10^(L/10)` spread
//!   evenly in wavenumber over the band's edges (`lambda_c 2^(+-1/6)`).
//! * Random roughness: its mean square spread evenly in wavenumber over its
//!   band (the generator's equal amplitudes on evenly spaced harmonics).

use realfft::RealFftPlanner;
use std::f64::consts::PI;

/// One one-third-octave band of a roughness level spectrum.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LevelBand {
    /// Centre wavelength (m).
    pub wavelength: f64,
    /// rms roughness in the band, dB re 1 um.
    pub level: f64,
}
/// A roughness's cumulative mean square over wavenumber.
#[derive(Debug, Clone, PartialEq)]
pub struct RoughnessDensity {
    /// Wavenumbers of the knots (1/m), increasing.
    knots: Vec<f64>,
    /// The mean square below each knot (m^2), non-decreasing.
    cumulative: Vec<f64>,
}

impl RoughnessDensity {
    /// No roughness.
    pub fn none() -> Self {
        RoughnessDensity { knots: vec![0.0], cumulative: vec![0.0] }
    }

    /// Intervals `(k_low, k_high, mean square)` laid end to end (they may
    /// leave gaps; overlapping intervals add).
    pub fn from_intervals(intervals: &[(f64, f64, f64)]) -> Self {
        let mut edges: Vec<f64> = intervals.iter().flat_map(|(a, b, _)| [*a, *b]).collect();
        edges.push(0.0);
        edges.sort_by(f64::total_cmp);
        edges.dedup();
        let cumulative = edges
            .iter()
            .map(|&k| {
                intervals
                    .iter()
                    .map(|(a, b, ms)| if b > a { ms * ((k.min(*b) - a) / (b - a)).clamp(0.0, 1.0) } else { 0.0 })
                    .sum()
            })
            .collect();
        RoughnessDensity { knots: edges, cumulative }
    }

    /// A flat density of mean square `ms` (m^2) between the wavelengths
    /// `lambda_min` and `lambda_max` (m).
    pub fn flat(ms: f64, lambda_min: f64, lambda_max: f64) -> Self {
        Self::from_intervals(&[(2.0 * PI / lambda_max, 2.0 * PI / lambda_min, ms)])
    }

    /// A level spectrum's bands (one-third octaves of wavelength, levels in
    /// dB re 1 um), each flat in wavenumber over its edges.
    pub fn from_levels(bands: &[LevelBand]) -> Self {
        let half = 2f64.powf(1.0 / 6.0);
        let intervals: Vec<(f64, f64, f64)> = bands
            .iter()
            .map(|b| {
                let ms = (super::R0 * 10f64.powf(b.level / 20.0)).powi(2);
                (2.0 * PI / (b.wavelength * half), 2.0 * PI / (b.wavelength / half), ms)
            })
            .collect();
        Self::from_intervals(&intervals)
    }

    /// A measured record's heights `h` (m), `spacing` apart (m), already
    /// processed, with the lines whose wavelength lies in `[lambda_min,
    /// lambda_max]` (see the module doc).
    pub fn from_record(h: &[f64], spacing: f64, lambda_min: f64, lambda_max: f64) -> Self {
        let n = h.len();
        if n < 4 {
            return Self::none();
        }
        let mean = h.iter().sum::<f64>() / n as f64;
        // The periodic Hann window: w = sin^2(pi i / N), mean square 3/8.
        let window: Vec<f64> = (0..n).map(|i| (PI * i as f64 / n as f64).sin().powi(2)).collect();
        let w2 = window.iter().map(|w| w * w).sum::<f64>() / n as f64;
        let mut input: Vec<f64> = h.iter().zip(&window).map(|(v, w)| (v - mean) * w).collect();
        let fft = RealFftPlanner::<f64>::new().plan_fft_forward(n);
        let mut spectrum = fft.make_output_vec();
        fft.process(&mut input, &mut spectrum).expect("the buffers fit the plan");
        let step = 2.0 * PI / (n as f64 * spacing);
        let lines: Vec<(f64, f64)> = spectrum
            .iter()
            .enumerate()
            .skip(1)
            .filter_map(|(k, c)| {
                let lambda = n as f64 * spacing / k as f64;
                // Both signs, except at the Nyquist line of an even record.
                let sides = if 2 * k == n { 1.0 } else { 2.0 };
                let ms = sides * c.norm_sqr() / (n as f64).powi(2) / w2;
                (lambda >= lambda_min * (1.0 - 1e-9) && lambda <= lambda_max * (1.0 + 1e-9))
                    .then_some((k as f64 * step, ms))
            })
            .collect();
        Self::from_lines(&lines)
    }

    /// Spectral lines `(wavenumber (1/m), mean square (m^2))`, each as an
    /// interval a billionth of its wavenumber wide.
    pub fn from_lines(lines: &[(f64, f64)]) -> Self {
        let intervals: Vec<(f64, f64, f64)> =
            lines.iter().map(|&(k, ms)| (k * (1.0 - 1e-9), k * (1.0 + 1e-9), ms)).collect();
        Self::from_intervals(&intervals)
    }

    /// The mean square below wavenumber `k` (m^2).
    pub fn below(&self, k: f64) -> f64 {
        let i = self.knots.partition_point(|x| *x <= k);
        if i == 0 {
            return 0.0;
        }
        if i == self.knots.len() {
            return self.cumulative[i - 1];
        }
        let (a, b) = (self.knots[i - 1], self.knots[i]);
        let t = (k - a) / (b - a);
        self.cumulative[i - 1] + t * (self.cumulative[i] - self.cumulative[i - 1])
    }

    /// The mean square between the wavenumbers `k1 <= k2` (m^2).
    pub fn between(&self, k1: f64, k2: f64) -> f64 {
        (self.below(k2) - self.below(k1)).max(0.0)
    }

    /// The mean square between the wavelengths `lambda_min` and
    /// `lambda_max` (m^2).
    pub fn between_wavelengths(&self, lambda_min: f64, lambda_max: f64) -> f64 {
        self.between(2.0 * PI / lambda_max, 2.0 * PI / lambda_min)
    }

    /// The whole mean square (m^2).
    pub fn total(&self) -> f64 {
        self.cumulative.last().copied().unwrap_or(0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sine_of_a_record_lands_in_its_band_with_its_mean_square() {
        // 0.6 m at 1 mm: a 3 um, 50 mm sine (12 periods, on a line) and a
        // 1 um, 37 mm one (16.2 periods, between lines).
        let (n, d) = (600, 1e-3);
        let h: Vec<f64> = (0..n)
            .map(|i| {
                let x = i as f64 * d;
                3e-6 * (2.0 * PI * x / 0.05).sin() + 1e-6 * (2.0 * PI * x / 0.037 + 0.3).cos()
            })
            .collect();
        let c = RoughnessDensity::from_record(&h, d, 2e-3, 1.0);
        // The 50 mm one-third octave (44.7-56.2 mm): 4.5 um^2 within 0.02
        // dB (the window spreads the sine over its line and the two beside
        // it, 54.5 and 46.2 mm, all in the band).
        let ms = c.between_wavelengths(0.05 * 10f64.powf(-0.05), 0.05 * 10f64.powf(0.05));
        let db = 10.0 * (ms / 4.5e-12).log10();
        assert!(db.abs() < 0.02, "50 mm band {db} dB off");
        // The whole: the two sines' mean squares, within 2 %.
        assert!((c.total() / 5.0e-12 - 1.0).abs() < 0.02, "{}", c.total());
        // The band limits drop the lines outside.
        let short = RoughnessDensity::from_record(&h, d, 2e-3, 0.04);
        assert!((short.total() / 0.5e-12 - 1.0).abs() < 0.1, "{}", short.total());
    }

    #[test]
    fn intervals_add_and_interpolate() {
        let c = RoughnessDensity::from_intervals(&[(10.0, 20.0, 1.0), (15.0, 25.0, 2.0)]);
        assert!((c.between(0.0, 100.0) - 3.0).abs() < 1e-15);
        assert!((c.between(12.0, 17.0) - (0.5 + 0.4)).abs() < 1e-15);
        assert_eq!(c.between(30.0, 40.0), 0.0);
        let f = RoughnessDensity::flat(4.0, 0.01, 0.1);
        let half = f.between(2.0 * PI / 0.1, PI * (1.0 / 0.1 + 1.0 / 0.01));
        assert!((half - 2.0).abs() < 1e-12);
    }
}
