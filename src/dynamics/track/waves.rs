//! The waves of a uniform rail (free, or on smeared supports) at one
//! frequency: its Green's matrix as a sum of exponentials, by residues,
//! and the lattice sums of the periodic structure in closed form.
//!
//! # Equations
//! With the section's dynamic stiffness `K(k) = A2 k^2 + A1 k + A0`
//! ([`super::section`]; `A2` diagonal and regular), the companion matrix
//! `C = [[0, I], [-A2^-1 A0, -A2^-1 A1]]` gives `K(k)^-1 = [I 0] (k I -
//! C)^-1 [0; A2^-1]`; with `C = V diag(lambda) V^-1`
//! ```text
//! G(x) = 1/(2 pi) int K(k)^-1 exp(i k x) dk = sum_{Im lambda_m > 0} exp(i lambda_m x) M_m,   x >= 0,
//! M_m = i V_m (V^-1 [0; A2^-1])_m,     G(-x) = G(x)^T                                        (1)
//! ```
//! (the contour closed in the upper half plane; `K^-1 ~ k^-2`, so also at
//! `x = 0`; `K(k)^T = K(-k)` gives the transpose, reciprocity). The roots
//! in the upper half plane are the waves that decay or travel away from
//! the load, the radiation condition of `exp(+i w t)`; damping keeps them
//! off the axis.
//!
//! The lattice sums of supports every `d` (Poisson's summation):
//! ```text
//! T(kappa, x) = sum_j K(kappa + 2 pi j / d)^-1 exp(i (kappa + 2 pi j / d) x) = d sum_n G(x - n d) exp(i kappa n d)
//!             = d sum_m [M_m exp(i lambda_m x) / (1 - z_m / zeta) + M_m^T exp(i lambda_m (d - x)) zeta / (1 - z_m zeta)]   (2)
//! ```
//! for `0 <= x < d`, `z_m = exp(i lambda_m d)`, `zeta = exp(i kappa d)`
//! (geometric series: `|z_m| < 1`), and `T(kappa, x + d) = zeta T(kappa,
//! x)`: exact, without the truncated harmonics and tails of
//! [`super::discrete`].

use super::section::Mat6;
use faer::Mat;
use faer::linalg::solvers::Solve;
use num_complex::Complex64;

/// A root on the real axis (an undamped wave): the rail's loss factor must
/// be positive.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error(
    "the rail's waves at {frequency} Hz: {upper} of 12 roots in the upper half plane (6 expected; the rail's loss \
     factor must be positive)"
)]
pub struct RootsError {
    /// Frequency (Hz).
    pub frequency: f64,
    /// Roots found in the upper half plane.
    pub upper: usize,
}

/// The six waves of eq. 1.
#[derive(Debug, Clone, PartialEq)]
pub struct Waves {
    /// Wavenumbers `lambda_m` (rad/m), `Im > 0`.
    pub lambda: [Complex64; 6],
    /// Their residues `M_m` (m/N and the section's other units).
    pub modes: [Mat6; 6],
    /// The residues' factors `M_m = phi_m psi_m^T`: `phi_m = i V_m`, `psi_m`
    /// the row `(V^-1 [0; A2^-1])_m`.
    pub factors: [(Vec6, Vec6); 6],
}

/// A vector in the section's freedoms.
pub type Vec6 = nalgebra::SVector<Complex64, 6>;

impl Waves {
    /// The waves of `K(k) = a2 k^2 + a1 k + a0` (`a2` diagonal) at angular
    /// frequency `omega` (rad/s; for the error's message).
    pub fn new(a2: &Mat6, a1: &Mat6, a0: &Mat6, omega: f64) -> Result<Waves, RootsError> {
        let inv2: [Complex64; 6] = std::array::from_fn(|i| 1.0 / a2[(i, i)]);
        let c = Mat::<Complex64>::from_fn(12, 12, |i, j| match (i < 6, j < 6) {
            (true, true) => Complex64::new(0.0, 0.0),
            (true, false) => Complex64::new(if j - 6 == i { 1.0 } else { 0.0 }, 0.0),
            (false, true) => -inv2[i - 6] * a0[(i - 6, j)],
            (false, false) => -inv2[i - 6] * a1[(i - 6, j - 6)],
        });
        let eigen = c.eigen().expect("the companion matrix's eigendecomposition converges");
        let (v, lambda) = (eigen.U(), eigen.S());
        let rhs =
            Mat::<Complex64>::from_fn(
                12,
                6,
                |i, j| {
                    if i >= 6 && i - 6 == j { inv2[j] } else { Complex64::new(0.0, 0.0) }
                },
            );
        let x = v.partial_piv_lu().solve(&rhs);
        let upper: Vec<usize> = (0..12).filter(|&m| lambda[m].im > 0.0).collect();
        if upper.len() != 6 {
            return Err(RootsError { frequency: omega / (2.0 * std::f64::consts::PI), upper: upper.len() });
        }
        let factor = |m: usize| (Vec6::from_fn(|a, _| Complex64::i() * v[(a, m)]), Vec6::from_fn(|b, _| x[(m, b)]));
        let factors: [(Vec6, Vec6); 6] = std::array::from_fn(|k| factor(upper[k]));
        Ok(Waves {
            lambda: std::array::from_fn(|k| lambda[upper[k]]),
            modes: std::array::from_fn(|k| factors[k].0 * factors[k].1.transpose()),
            factors,
        })
    }

    /// The lattice sum `T(kappa, x)` of eq. 2 for supports every `d` (m),
    /// at `x` (m from a support, any sign).
    pub fn lattice(&self, kappa: f64, x: f64, d: f64) -> Mat6 {
        let cells = (x / d).floor();
        let xr = (x - cells * d).clamp(0.0, d);
        let zeta = Complex64::from_polar(1.0, kappa * d);
        let mut t = Mat6::zeros();
        for (l, m) in self.lambda.iter().zip(&self.modes) {
            let z = (Complex64::i() * l * d).exp();
            let ahead = (Complex64::i() * l * xr).exp() / (1.0 - z / zeta);
            let behind = (Complex64::i() * l * (d - xr)).exp() * zeta / (1.0 - z * zeta);
            t += m * ahead + m.transpose() * behind;
        }
        t * (Complex64::from_polar(1.0, kappa * d * cells) * d)
    }
}

impl super::scattering::RailWaves<6> for Waves {
    fn wavenumbers(&self) -> Vec<Complex64> {
        self.lambda.to_vec()
    }

    fn factors(&self) -> Vec<(Vec6, Vec6)> {
        self.factors.to_vec()
    }

    fn residues(&self) -> Vec<Mat6> {
        self.modes.to_vec()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::track::TrackConfig;
    use crate::dynamics::track::section::Section;

    #[test]
    fn lattice_sums_equal_the_truncated_harmonic_sums() {
        // The closed form (eq. 2) against sum_{|j| <= J} K(kappa_j)^-1
        // exp(i kappa_j x): the harmonics' tail decays as 1 / J (the
        // diagonal ~ 1 / (c k^2)), so J = 20000 leaves about 1e-5.
        let s = Section::new(&TrackConfig::default(), 0.01);
        let w = 2.0 * std::f64::consts::PI * 700.0;
        let (a2, a1, a0) = s.free_polynomial(w);
        let waves = Waves::new(&a2, &a1, &a0, w).unwrap();
        let d = 0.6;
        let g = 2.0 * std::f64::consts::PI / d;
        for (kappa, x) in [(1.3, 0.0), (-4.0, 0.17), (2.2, 0.6 + 0.31), (0.4, -0.25)] {
            let closed = waves.lattice(kappa, x, d);
            let mut sum = Mat6::zeros();
            for j in -20000i64..=20000 {
                let k = kappa + g * j as f64;
                sum += s.free_receptance(k, w) * Complex64::from_polar(1.0, k * x);
            }
            let e = (closed - sum).norm() / closed.norm();
            assert!(e < 1e-4, "kappa {kappa}, x {x}: {e:e}");
        }
    }
}
