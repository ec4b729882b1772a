//! Eq. 2 of [`super`]: each wheel's channels along the stretch from the
//! tabulated responses and the profiles the wheels see. On the continuous
//! track (one place) it is a product per harmonic and one inverse FFT per
//! channel; on the discrete track a sum over the harmonics at every node
//! with the responses interpolated linearly between the bay's places.
//!
//! A real input: harmonic `k` and its mirror `N - k` carry `G` and
//! `conj G` (`G(-w) = conj G(w)`), the Nyquist harmonic of an even `N` (a
//! sampled `cos(pi X / dx)` whose phase the samples cannot resolve) `Re G`,
//! the mean is dropped. A wheel running backwards (`V < 0`) meets harmonic
//! `k` at `-w`: `conj G`.

use super::places::Places;
use nalgebra::DMatrix;
use num_complex::Complex64;
use rustfft::FftPlanner;
use std::f64::consts::PI;

/// The channels (`channels` per wheel) of each wheel `[wheel][channel][node]`
/// from the responses `table[k - 1][place]`, the wheels' distances behind
/// the leading one `behind` (m), the profiles they see and their
/// parametric paths (m, `nodes` samples every `dx`), on the discrete
/// track's tabulated places (`None` on the continuous track), at `speed`
/// (m/s).
#[allow(clippy::too_many_arguments)]
pub(super) fn channels(
    table: &[Vec<DMatrix<Complex64>>],
    channels: usize,
    behind: &[f64],
    profiles: &[Vec<f64>],
    paths: &[Vec<f64>],
    places: Option<&Places>,
    dx: f64,
    speed: f64,
) -> Vec<Vec<Vec<f64>>> {
    let nodes = profiles[0].len();
    if nodes < 2 {
        return vec![vec![vec![0.0; nodes]; channels]; behind.len()];
    }
    let fft = FftPlanner::<f64>::new().plan_fft_forward(nodes);
    let spectra: Vec<Vec<Complex64>> = profiles
        .iter()
        .zip(paths)
        .map(|(profile, path)| {
            let mut buf: Vec<Complex64> = profile.iter().zip(path).map(|(r, p)| Complex64::new(r + p, 0.0)).collect();
            fft.process(&mut buf);
            buf
        })
        .collect();
    let length = nodes as f64 * dx;
    // A wheel's response to the input at wheel j as wheel i meets it:
    // G exp(i k (s_i - s_j)), conjugated backwards.
    let as_met = |g: Complex64, k: usize, i: usize, j: usize| -> Complex64 {
        let g = if speed >= 0.0 { g } else { g.conj() };
        if behind[i] == behind[j] {
            g
        } else {
            g * Complex64::from_polar(1.0, 2.0 * PI * k as f64 / length * (behind[i] - behind[j]))
        }
    };
    match places {
        None => continuous(table, channels, &spectra, nodes, as_met),
        Some(places) => discrete(table, channels, behind, &spectra, places, dx, length, speed),
    }
}

/// One place: per wheel and channel the spectrum `sum_j G_ij S_j` and its
/// inverse FFT.
fn continuous(
    table: &[Vec<DMatrix<Complex64>>],
    channels: usize,
    spectra: &[Vec<Complex64>],
    nodes: usize,
    as_met: impl Fn(Complex64, usize, usize, usize) -> Complex64,
) -> Vec<Vec<Vec<f64>>> {
    let wheels = spectra.len();
    let inverse = FftPlanner::<f64>::new().plan_fft_inverse(nodes);
    // rustfft does not normalise: the inverse of the forward is N times the input.
    let scale = 1.0 / nodes as f64;
    (0..wheels)
        .map(|i| {
            (0..channels)
                .map(|c| {
                    let mut buf = vec![Complex64::new(0.0, 0.0); nodes];
                    for (k, places) in table.iter().enumerate().map(|(m, p)| (m + 1, p)) {
                        let (mut up, mut down) = (Complex64::new(0.0, 0.0), Complex64::new(0.0, 0.0));
                        for (j, s) in spectra.iter().enumerate() {
                            let g = as_met(places[0][(channels * i + c, j)], k, i, j);
                            if 2 * k == nodes {
                                up += s[k] * Complex64::new(g.re, 0.0);
                            } else {
                                up += s[k] * g;
                                down += s[nodes - k] * g.conj();
                            }
                        }
                        buf[k] = up;
                        if 2 * k != nodes {
                            buf[nodes - k] = down;
                        }
                    }
                    inverse.process(&mut buf);
                    buf.iter().map(|v| v.re * scale).collect()
                })
                .collect()
        })
        .collect()
}

/// Places across the period: at every node the responses interpolated
/// between the leading wheel's places and summed over the harmonics.
#[allow(clippy::too_many_arguments)]
fn discrete(
    table: &[Vec<DMatrix<Complex64>>],
    channels: usize,
    behind: &[f64],
    spectra: &[Vec<Complex64>],
    places: &Places,
    dx: f64,
    length: f64,
    speed: f64,
) -> Vec<Vec<Vec<f64>>> {
    let (wheels, nodes) = (spectra.len(), spectra[0].len());
    (0..wheels)
        .map(|i| {
            // Each wheel's input as wheel i meets it, per harmonic:
            // r_j,k exp(i k (s_i - s_j)).
            let met: Vec<Vec<Complex64>> = (1..=table.len())
                .map(|k| {
                    let wave = 2.0 * PI * k as f64 / length;
                    (0..wheels)
                        .map(|j| spectra[j][k] * Complex64::from_polar(1.0, wave * (behind[i] - behind[j])))
                        .collect()
                })
                .collect();
            let mut out = vec![vec![0.0; nodes]; channels];
            for m in 0..nodes {
                let x = m as f64 * dx;
                let (p, q, t) = places.locate(places.start() + x + behind[i]);
                for (k, (responses, seen)) in table.iter().zip(&met).enumerate().map(|(h, v)| (h + 1, v)) {
                    let phase = Complex64::from_polar(1.0, 2.0 * PI * k as f64 * x / length);
                    let weight = if 2 * k == nodes { 1.0 } else { 2.0 } / nodes as f64;
                    for (c, channel) in out.iter_mut().enumerate() {
                        let row = channels * i + c;
                        let mut sum = Complex64::new(0.0, 0.0);
                        for (j, r) in seen.iter().enumerate() {
                            let g = (1.0 - t) * responses[p][(row, j)] + t * responses[q][(row, j)];
                            sum += if speed >= 0.0 { g } else { g.conj() } * r;
                        }
                        channel[m] += weight * (sum * phase).re;
                    }
                }
            }
            out
        })
        .collect()
}
