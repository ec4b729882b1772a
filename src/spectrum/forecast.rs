//! A roughness band's growth under traffic from the linear growth
//! spectrum: the mean square a random-phase roughness of a given spectral
//! density reaches in a band after `n` wheel passages, with the forced
//! pattern's deepening, at any wavelength the supercell's harmonics
//! sample (book: docs/src/guide/when-to-grind.md).
//!
//! Per Bloch class the update is `dR/dn = G R + F` (`G = -J`,
//! [`super::modes`]; `F = -W_0`, the smooth rail's forced wear, on class 0
//! alone), so with `G = U diag(mu) U^-1`
//!
//! ```text
//! R(n) = E(n) R0 + Phi(n) F,   E(n) = U diag(exp(mu n)) U^-1,
//!                              Phi(n) = U diag((exp(mu n) - 1) / mu) U^-1
//! ```
//!
//! A measured rail's harmonics have unrelated phases: its coefficients
//! `R0_s` are uncorrelated with `E|R0_s|^2 = P_s`, so the mean square at
//! harmonic `h` is
//!
//! ```text
//! E|R_h(n)|^2 = sum_s |E_hs(n)|^2 P_s + |(Phi(n) F)_h|^2
//! ```
//!
//! (the forced pattern is the track's, unrelated to the roughness's
//! phases: its mean square adds). `P_s` is the roughness's mean square in
//! the wavenumber interval the harmonic stands for, `2 pi / L_s` wide on a
//! supercell of length `L_s`, shared by the harmonic and its conjugate;
//! inside the band the harmonics' intervals are cut at the band's edges and
//! the outermost ones stretched to them, so that they tile the band. Across
//! its interval a harmonic's rate is taken linear in wavenumber, `mu_h +
//! mu' (k - k_h)` with the slope `mu'` of the harmonics' own rates (`-Re
//! J(h, h)`) between its neighbours, so that its roughness grows by the
//! interval's mean of `exp(2 mu' (k - k_h) n)` on top of `|E_hs(n)|^2`: the
//! band's integral over wavenumber by a rule that follows a rate varying
//! across the band, not by its values at the harmonics alone (a
//! fast-growing edge of a wide band decides its level after long traffic). A
//! band's mean square is the sum over its harmonics, each conjugate pair
//! once: a class that is not its own conjugate stands for its conjugate
//! too and counts twice. Where the sleepers couple the harmonics of a
//! class, roughness at one wavelength grows the others: the sum over `s`
//! holds it. This is the linear regime's forecast.

use super::Spectrum;
use faer::Mat;
use faer::c64;
use faer::linalg::solvers::DenseSolveCore;
use num_complex::Complex64;
use std::f64::consts::PI;

/// Largest exponent `Re(mu) n` evaluated; beyond it the band's mean square
/// is taken as infinite (`exp(700)` is near the largest f64).
const MAX_EXPONENT: f64 = 700.0;

/// One class's update in modal form.
#[derive(Debug, Clone)]
struct ClassUpdate {
    /// Eigenvectors, row major (`n x n`).
    u: Vec<Complex64>,
    /// Eigenvalues `mu` (1 per wheel passage).
    mu: Vec<Complex64>,
    /// `U^-1`, row major.
    u_inv: Vec<Complex64>,
    /// Wavenumber of each basis harmonic (1/m, positive).
    wavenumber: Vec<f64>,
    /// The rail of each basis harmonic.
    rail: Vec<usize>,
    /// How many times the class counts in a mean square: 2 where it stands
    /// for its conjugate too, 1 where it is its own.
    weight: f64,
    /// The forced wear's contribution to the update, `F = -W_0` (m per
    /// wheel passage), on the basis (zero off class 0).
    forcing: Vec<Complex64>,
    /// Each harmonic's rate alone, `-Re J(h, h)` (1 per wheel passage).
    diagonal: Vec<f64>,
}

/// Why the update could not be put in modal form.
#[derive(Debug, thiserror::Error)]
#[error("the growth matrix of Bloch class {class} ({size} harmonics) has no complete set of eigenvectors")]
pub struct DefectiveClass {
    /// The class.
    pub class: usize,
    /// Its size.
    pub size: usize,
}

/// The spectrum's update, ready to carry a roughness over any traffic.
#[derive(Debug, Clone)]
pub struct BandGrowth {
    classes: Vec<ClassUpdate>,
    /// The wavenumber interval one harmonic stands for (1/m).
    spacing: f64,
    /// The stretch `L` (m).
    stretch: f64,
}

/// A band's mean square after some traffic, in its two parts (m^2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BandMeanSquare {
    /// The roughness's, carried by the update.
    pub roughness: f64,
    /// The forced pattern's, deepened from a smooth rail.
    pub forced: f64,
}

impl BandGrowth {
    /// The update of `spectrum` in modal form.
    pub fn new(spectrum: &Spectrum) -> Result<Self, DefectiveClass> {
        let supercell = spectrum.supercell();
        let mut classes = Vec::new();
        for (c, (class, j)) in spectrum.classes.iter().zip(&spectrum.matrices).enumerate() {
            let n = class.basis.len();
            let g = Mat::<c64>::from_fn(n, n, |r, k| {
                let v = -j[r * n + k];
                c64::new(v.re, v.im)
            });
            let evd = g.eigen().map_err(|_| DefectiveClass { class: c, size: n })?;
            let inverse = evd.U().partial_piv_lu().inverse();
            let at = |m: faer::MatRef<c64>, r: usize, k: usize| Complex64::new(m[(r, k)].re, m[(r, k)].im);
            let u: Vec<Complex64> = (0..n * n).map(|i| at(evd.U(), i / n, i % n)).collect();
            let u_inv: Vec<Complex64> = (0..n * n).map(|i| at(inverse.as_ref(), i / n, i % n)).collect();
            if u.iter().chain(&u_inv).any(|v| !v.is_finite()) {
                return Err(DefectiveClass { class: c, size: n });
            }
            let mu = (0..n).map(|k| Complex64::new(evd.S()[k].re, evd.S()[k].im)).collect();
            // The forced wear on the stretch's harmonic `k` (supercell index
            // `k M`, class 0): its coefficient at `+kM`, the conjugate at
            // `-kM`.
            let forcing = class
                .basis
                .iter()
                .map(|b| {
                    let cells = spectrum.cells as i64;
                    if class.j != 0 || b.index % cells != 0 {
                        return Complex64::default();
                    }
                    let k = (b.index / cells).unsigned_abs() as usize;
                    let w = spectrum.forced_coefficients.get(b.rail).and_then(|f| f.get(k - 1)).copied();
                    let w = w.unwrap_or_default();
                    -(if b.index > 0 { w } else { w.conj() })
                })
                .collect();
            classes.push(ClassUpdate {
                u,
                mu,
                u_inv,
                wavenumber: class.basis.iter().map(|b| 2.0 * PI * b.index.unsigned_abs() as f64 / supercell).collect(),
                rail: class.basis.iter().map(|b| b.rail).collect(),
                weight: if class.self_conjugate { 1.0 } else { 2.0 },
                forcing,
                diagonal: (0..n).map(|h| -j[h * n + h].re).collect(),
            });
        }
        Ok(BandGrowth { classes, spacing: 2.0 * PI / supercell, stretch: spectrum.stretch })
    }

    /// The Bloch classes `M` that put a harmonic of the supercell `M L` in
    /// every interval `(k_low, k_high]` (1/m): `2 pi / (M L) <= k_high -
    /// k_low`.
    pub fn classes_for(&self, k_low: f64, k_high: f64) -> usize {
        (2.0 * PI / (self.stretch * (k_high - k_low))).ceil().max(1.0) as usize
    }

    /// The harmonics of rail `rail` in the wavenumber band `(k_low, k_high]`
    /// (1/m), each conjugate pair once.
    pub fn lines(&self, rail: usize, k_low: f64, k_high: f64) -> f64 {
        self.classes
            .iter()
            .map(|c| {
                let inside =
                    c.wavenumber.iter().zip(&c.rail).filter(|(k, r)| **r == rail && in_band(**k, k_low, k_high));
                0.5 * c.weight * inside.count() as f64
            })
            .sum()
    }

    /// The mean square (m^2) in the wavenumber band `(k_low, k_high]` (1/m)
    /// of rail `rail` after `n` wheel passages, from a random-phase
    /// roughness on rail `rail` whose mean square between two wavenumbers
    /// is `between(k1, k2)` (m^2) and from the forced pattern (see the
    /// module doc). Infinite where a growing mode's exponent exceeds the
    /// float range.
    pub fn mean_square(
        &self,
        rail: usize,
        between: &dyn Fn(f64, f64) -> f64,
        k_low: f64,
        k_high: f64,
        n: f64,
    ) -> BandMeanSquare {
        self.band(rail, between, k_low, k_high).at(n)
    }

    /// The band `(k_low, k_high]` (1/m) of rail `rail` under the roughness
    /// `between` (as [`Self::mean_square`]), ready to be evaluated at any
    /// traffic: per class the quadratic forms in the modal amplitudes,
    ///
    /// ```text
    /// sum_h sum_s |E_hs|^2 P_s = sum_mm' B_mm' g_m conj(g_m'),
    ///     B_mm' = sum_h U_hm conj(U_hm') sum_s V_ms conj(V_m's) P_s
    /// sum_h |(Phi F)_h|^2     = sum_mm' D_mm' f_m conj(f_m'),
    ///     D_mm' = sum_h U_hm conj(U_hm'),  f_m = phi_m (V F)_m
    /// ```
    ///
    /// (`V = U^-1`, `g_m = exp(mu_m n)`, `phi_m = (g_m - 1) / mu_m`, `h` over
    /// the band's harmonics).
    pub fn band(&self, rail: usize, between: &dyn Fn(f64, f64) -> f64, k_low: f64, k_high: f64) -> BandSeries {
        // The band's harmonics (every class's) tile it: each stands for the
        // interval to halfway to its neighbours, the outermost to the
        // band's edges, so that their roughness is the band's.
        let inside = self.classes.iter().flat_map(|c| {
            c.wavenumber
                .iter()
                .zip(&c.rail)
                .filter(|(k, r)| **r == rail && in_band(**k, k_low, k_high))
                .map(|(k, _)| *k)
        });
        let (lowest, highest) = inside.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), k| (a.min(k), b.max(k)));
        let half = 0.5 * self.spacing;
        let interval = |k: f64| {
            if !in_band(k, k_low, k_high) {
                return ((k - half).max(0.0), k + half);
            }
            let low = if k <= lowest { k_low } else { (k - half).max(k_low) };
            let high = if k >= highest { k_high } else { (k + half).min(k_high) };
            (low, high)
        };
        // The rate's slope in wavenumber at each harmonic of the rail, from
        // its neighbours' rates alone (every class's, sorted).
        let mut lattice: Vec<(f64, f64)> = self
            .classes
            .iter()
            .flat_map(|c| (0..c.mu.len()).filter(|&h| c.rail[h] == rail).map(|h| (c.wavenumber[h], c.diagonal[h])))
            .collect();
        lattice.sort_by(|a, b| a.0.total_cmp(&b.0));
        lattice.dedup_by(|a, b| (a.0 - b.0).abs() <= 1e-9 * b.0);
        let slope = |k: f64| {
            let i = lattice.partition_point(|p| p.0 < k * (1.0 - 1e-9));
            let (lo, hi) = (i.saturating_sub(1), (i + 1).min(lattice.len().saturating_sub(1)));
            if hi > lo { (lattice[hi].1 - lattice[lo].1) / (lattice[hi].0 - lattice[lo].0) } else { 0.0 }
        };
        let mut parts = Vec::new();
        for c in &self.classes {
            let size = c.mu.len();
            let targets: Vec<usize> =
                (0..size).filter(|&h| c.rail[h] == rail && in_band(c.wavenumber[h], k_low, k_high)).collect();
            if targets.is_empty() {
                continue;
            }
            let power: Vec<f64> = (0..size)
                .map(|s| {
                    if c.rail[s] != rail {
                        return 0.0;
                    }
                    let (low, high) = interval(c.wavenumber[s]);
                    0.5 * between(low, high)
                })
                .collect();
            let mut q = vec![Complex64::default(); size * size];
            let mut d = vec![Complex64::default(); size * size];
            for m in 0..size {
                for mp in 0..size {
                    q[m * size + mp] = (0..size)
                        .filter(|&s| power[s] != 0.0)
                        .map(|s| c.u_inv[m * size + s] * c.u_inv[mp * size + s].conj() * power[s])
                        .sum();
                    d[m * size + mp] = targets.iter().map(|&h| c.u[h * size + m] * c.u[h * size + mp].conj()).sum();
                }
            }
            let lines = targets
                .iter()
                .map(|&h| {
                    let b = (0..size * size)
                        .map(|i| q[i] * c.u[h * size + i / size] * c.u[h * size + i % size].conj())
                        .collect();
                    let k = c.wavenumber[h];
                    let (low, high) = interval(k);
                    (b, Tilt { slope: 2.0 * slope(k), low: low - k, high: high - k })
                })
                .collect();
            let modal_forcing: Vec<Complex64> =
                (0..size).map(|m| (0..size).map(|s| c.u_inv[m * size + s] * c.forcing[s]).sum()).collect();
            parts.push(BandClass { mu: c.mu.clone(), lines, d, modal_forcing, weight: c.weight });
        }
        BandSeries { parts }
    }
}

/// How a harmonic's mean square grows across the interval it stands for:
/// with the rate `mu_h + mu' (k - k_h)`, linear between its neighbours, the
/// mean of `exp(2 mu' (k - k_h) n)` over the interval.
#[derive(Debug, Clone, Copy)]
struct Tilt {
    /// `2 mu'` (1 per wheel passage per 1/m).
    slope: f64,
    /// The interval's edges from the harmonic (1/m).
    low: f64,
    high: f64,
}

impl Tilt {
    /// The factor after `n` wheel passages.
    fn at(&self, n: f64) -> f64 {
        let (a, b) = (self.slope * n * self.low, self.slope * n * self.high);
        if (b - a).abs() < 1e-9 { (0.5 * (a + b)).exp() } else { (b.exp() - a.exp()) / (b - a) }
    }
}

/// One class's share of a band.
#[derive(Debug, Clone)]
struct BandClass {
    mu: Vec<Complex64>,
    /// Per harmonic of the band, `B_h` (m^2, row major; `B = sum_h B_h`)
    /// and its tilt.
    lines: Vec<(Vec<Complex64>, Tilt)>,
    /// `D` (1), row major.
    d: Vec<Complex64>,
    /// `(U^-1 F)_m` (m per wheel passage).
    modal_forcing: Vec<Complex64>,
    weight: f64,
}

/// A band's mean square as a function of traffic ([`BandGrowth::band`]).
#[derive(Debug, Clone)]
pub struct BandSeries {
    parts: Vec<BandClass>,
}

impl BandSeries {
    /// The band's mean square after `n` wheel passages (m^2).
    pub fn at(&self, n: f64) -> BandMeanSquare {
        let mut out = BandMeanSquare { roughness: 0.0, forced: 0.0 };
        for c in &self.parts {
            let size = c.mu.len();
            if c.mu.iter().any(|m| m.re * n > MAX_EXPONENT) {
                return BandMeanSquare { roughness: f64::INFINITY, forced: f64::INFINITY };
            }
            let grow: Vec<Complex64> = c.mu.iter().map(|m| (m * n).exp()).collect();
            let f: Vec<Complex64> =
                c.mu.iter().zip(&grow).zip(&c.modal_forcing).map(|((m, g), a)| integral(*m, *g, n) * a).collect();
            let (mut rough, mut forced) = (0.0, 0.0);
            for (b, tilt) in &c.lines {
                let mut line = 0.0;
                for m in 0..size {
                    for mp in 0..size {
                        line += (b[m * size + mp] * grow[m] * grow[mp].conj()).re;
                    }
                }
                rough += tilt.at(n) * line;
            }
            for m in 0..size {
                for mp in 0..size {
                    forced += (c.d[m * size + mp] * f[m] * f[mp].conj()).re;
                }
            }
            out.roughness += c.weight * rough.max(0.0);
            out.forced += c.weight * forced.max(0.0);
        }
        out
    }
}

/// `(exp(mu n) - 1) / mu` given `grow = exp(mu n)`: `n` as `mu n` goes to 0.
fn integral(mu: Complex64, grow: Complex64, n: f64) -> Complex64 {
    let z = mu * n;
    if z.norm() < 1e-6 {
        // exp(z) - 1 = z (1 + z/2 + z^2/6 + ...).
        Complex64::new(n, 0.0) * (1.0 + z / 2.0 + z * z / 6.0)
    } else {
        (grow - 1.0) / mu
    }
}

/// Whether the wavenumber `k` lies in `(low, high]`.
fn in_band(k: f64, low: f64, high: f64) -> bool {
    k > low && k <= high
}

/// Spectra built by hand for the tests of the forecasts.
#[cfg(test)]
pub(crate) mod fixture {
    use super::*;
    use crate::spectrum::bloch::{Class, Harmonic};

    /// A spectrum of one self-conjugate class on a `length` stretch with
    /// the harmonics `first..=last` (both signs), each decoupled and
    /// growing at `rate(k)` per wheel passage (`k` its wavenumber, 1/m).
    pub fn smooth(length: f64, first: usize, last: usize, rate: &dyn Fn(f64) -> f64) -> Spectrum {
        let mu: Vec<f64> =
            (1..=last).map(|n| if n < first { 0.0 } else { rate(2.0 * PI * n as f64 / length) }).collect();
        let mut s = diagonal(length, &mu, &vec![Complex64::default(); last]);
        let keep: Vec<bool> = s.classes[0].basis.iter().map(|b| b.index.unsigned_abs() as usize >= first).collect();
        let n = keep.len();
        let rows: Vec<usize> = (0..n).filter(|&r| keep[r]).collect();
        let j = &s.matrices[0];
        s.matrices[0] =
            rows.iter().flat_map(|&r| rows.iter().map(move |&c| (r, c))).map(|(r, c)| j[r * n + c]).collect();
        s.classes[0].basis = rows.iter().map(|&r| s.classes[0].basis[r]).collect();
        s
    }

    /// A spectrum of one self-conjugate class on a `length` stretch with
    /// the harmonics `1..=h` (both signs) and the diagonal update `-J =
    /// diag(mu_h)` (the same for `+h` and `-h`), forced wear `w` on each.
    pub fn diagonal(length: f64, mu: &[f64], w: &[Complex64]) -> Spectrum {
        let h = mu.len();
        let basis: Vec<Harmonic> =
            (1..=h as i64).flat_map(|i| [i, -i]).map(|index| Harmonic { rail: 0, index }).collect();
        let n = basis.len();
        let mut j = vec![Complex64::default(); n * n];
        for (r, b) in basis.iter().enumerate() {
            j[r * n + r] = Complex64::new(-mu[b.index.unsigned_abs() as usize - 1], 0.0);
        }
        Spectrum {
            stretch: length,
            cells: 1,
            speed: 20.0,
            classes: vec![Class { j: 0, self_conjugate: true, basis }],
            matrices: vec![j],
            modes: Vec::new(),
            wavelengths: (1..=h).map(|k| length / k as f64).collect(),
            forced_wear: vec![w.iter().map(|c| 2.0 * c.norm()).collect()],
            forced_coefficients: vec![w.to_vec()],
            base_wear: vec![vec![0.0; h]],
            mean_wear: vec![0.0],
            positions: Vec::new(),
            supports: Vec::new(),
            rails: 1,
            linear_contact: true,
            passage_equivalents: 0.0,
            cpu_seconds: 0.0,
            wall_seconds: 0.0,
            warnings: Vec::new(),
            resonances: Vec::new(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::fixture::diagonal;
    use super::*;

    #[test]
    fn a_band_of_one_harmonic_grows_at_its_rate_and_the_forced_pattern_deepens_linearly() {
        // 0.1 m stretch, harmonics 100, 50, 33.3 mm growing at 2e-6, -1e-6,
        // 0 per passage; a flat density of 1e-12 m^2 per 1/m.
        let (l, density) = (0.1, 1e-12);
        let mu = [2e-6, -1e-6, 0.0];
        let g = BandGrowth::new(&diagonal(l, &mu, &[Complex64::default(); 3])).unwrap();
        let between = |a: f64, b: f64| density * (b - a);
        let k = |lambda: f64| 2.0 * PI / lambda;
        // The 50 mm harmonic alone: the band 45-55 mm.
        let band = (k(0.055), k(0.045));
        assert_eq!(g.lines(0, band.0, band.1), 1.0);
        let ms0 = g.mean_square(0, &between, band.0, band.1, 0.0).roughness;
        // It stands for the whole band.
        assert!((ms0 / (density * (band.1 - band.0)) - 1.0).abs() < 1e-12, "{ms0}");
        // It grows at its rate, tilted across the band by the slope of the
        // rates between its neighbours (100 mm at 2e-6, 33.3 mm at 0).
        let slope = (mu[2] - mu[0]) / (k(0.1 / 3.0) - k(0.1));
        for n in [1e4, 3e5, 1e6] {
            let ms = g.mean_square(0, &between, band.0, band.1, n).roughness;
            let (a, b) = (2.0 * slope * n * (band.0 - k(0.05)), 2.0 * slope * n * (band.1 - k(0.05)));
            let want = (2.0 * mu[1] * n).exp() * (b.exp() - a.exp()) / (b - a);
            assert!((ms / ms0 / want - 1.0).abs() < 1e-10, "n = {n}: {} vs {want}", ms / ms0);
        }
        // The forced pattern on the 33.3 mm harmonic (mu = 0): amplitude 2|w|
        // per passage, mean square (2 |w| n)^2 / 2 after n passages.
        let w = Complex64::new(3e-12, -4e-12);
        let g = BandGrowth::new(&diagonal(l, &mu, &[Complex64::default(), Complex64::default(), w])).unwrap();
        let band = (k(0.036), k(0.031));
        for n in [1e3, 1e5] {
            let f = g.mean_square(0, &|_, _| 0.0, band.0, band.1, n).forced;
            let want = 0.5 * (2.0 * w.norm() * n).powi(2);
            assert!((f / want - 1.0).abs() < 1e-9, "n = {n}: {f} against {want}");
        }
        // On the growing 100 mm harmonic it grows as (e^(mu n) - 1) / mu.
        let g = BandGrowth::new(&diagonal(l, &mu, &[w, Complex64::default(), Complex64::default()])).unwrap();
        let band = (k(0.11), k(0.09));
        let n = 5e5;
        let f = g.mean_square(0, &|_, _| 0.0, band.0, band.1, n).forced;
        let want = 0.5 * (2.0 * w.norm() * (mu[0] * n).exp_m1() / mu[0]).powi(2);
        assert!((f / want - 1.0).abs() < 1e-9, "{f} against {want}");
        // Beyond the float range: infinite, not NaN.
        let ms = g.mean_square(0, &between, band.0, band.1, 1e9).roughness;
        assert!(ms.is_infinite());
    }

    #[test]
    fn coupled_harmonics_carry_roughness_from_one_wavelength_into_another() {
        // Two harmonics of one class coupled by J = [[a, c], [c, a]] (both
        // signs alike): roughness only at the first reaches the second as
        // |E_21|^2 = (e^{l1 n} - e^{l2 n})^2 / 4, l = -(a +- c).
        let (l, a, c) = (0.1, -1e-6, 5e-7);
        let mut s = diagonal(l, &[0.0, 0.0], &[Complex64::default(); 2]);
        let n = 4;
        let basis = s.classes[0].basis.clone();
        let mut j = vec![Complex64::default(); n * n];
        for r in 0..n {
            for k in 0..n {
                let same_sign = basis[r].index.signum() == basis[k].index.signum();
                j[r * n + k] = Complex64::new(
                    if r == k {
                        a
                    } else if same_sign {
                        c
                    } else {
                        0.0
                    },
                    0.0,
                );
            }
        }
        s.matrices = vec![j];
        let g = BandGrowth::new(&s).unwrap();
        let k = |lambda: f64| 2.0 * PI / lambda;
        // Roughness in the 100 mm harmonic's interval only.
        let first = (k(0.1) - 0.5 * 2.0 * PI / l, k(0.1) + 0.5 * 2.0 * PI / l);
        let between = |x: f64, y: f64| if x >= first.0 - 1e-9 && y <= first.1 + 1e-9 { 1e-12 } else { 0.0 };
        let p = 0.5 * 1e-12;
        let steps = 2e5;
        let ms = g.mean_square(0, &between, k(0.055), k(0.045), steps).roughness;
        let (l1, l2) = (-(a + c), -(a - c));
        let want = 2.0 * p * ((l1 * steps).exp() - (l2 * steps).exp()).powi(2) / 4.0;
        assert!((ms / want - 1.0).abs() < 1e-8, "{ms} against {want}");
    }
}
