//! The tests' second method for the rail on a layout of supports
//! ([`super::layout`]), independent of the waves' scattering the program
//! uses ([`super::scattering`]): the periodic structure whose period holds
//! several supports, each with its own position and stiffness, by the
//! Floquet method of [`super::discrete3`] with the period's supports
//! solved together. Its cost grows as the square of the supports or faster
//! (every support against every other, per Bloch wavenumber).
//!
//! # Equations
//! With the free rail's Green's matrix `G(x)` and its lattice sums over
//! the period `L`, `T(kappa, x) = L sum_n G(x + n L) exp(-i kappa n L)` (in
//! closed form, [`super::waves`] eq. 2), supports `m = 1..M` at `x_m` of
//! stiffness `K_m`, the supports' displacements under a unit load at `x0`
//! have the Floquet transform `W = (L I + T K)^-1 t0`, `T_mn = T(kappa, x_m
//! - x_n)`, `K = diag(K_m)`, `(t0)_m = T(kappa, x_m - x0)`, and the rail's
//! response at `x1`
//! ```text
//! G(x1; x0) = G(x1 - x0) - 1/(2 pi) int_{-pi/L}^{pi/L} t1 K (L I + T K)^-1 t0 d kappa,   (t1)_m = T(kappa, x1 - x_m)   (1)
//! ```
//! (one support: eq. 1 of [`super::discrete3`]; the sum over the supports
//! and their images of the free rail's response to each reaction
//! `K_m w_m`, Floquet-transformed over the periods). The integral is
//! adaptive ([`crate::quadrature`]) to a relative tolerance of the largest
//! entry.

pub use super::scattering::{RailWaves, Supported};
use crate::quadrature::{QuadratureError, integrate};
use faer::Mat;
use faer::linalg::solvers::Solve;
use nalgebra::SMatrix;
use num_complex::Complex64;
use std::f64::consts::PI;

/// An offset `x = cells L + xr` (`0 <= xr < L`) in the lattice sums of
/// [`super::waves`] eq. 2: per wave `exp(i lambda_m xr)` and `exp(i
/// lambda_m (L - xr))`, which do not depend on `kappa`.
struct Offset {
    cells: f64,
    ahead: Vec<Complex64>,
    behind: Vec<Complex64>,
}

impl Offset {
    fn new(lambda: &[Complex64], x: f64, period: f64) -> Offset {
        let cells = (x / period).floor();
        let xr = (x - cells * period).clamp(0.0, period);
        let e = |l: f64| lambda.iter().map(|lm| (Complex64::i() * lm * l).exp()).collect();
        Offset { cells, ahead: e(xr), behind: e(period - xr) }
    }

    /// `T(kappa, x) F` for the waves' `forward_m = M_m F` and `backward_m
    /// = M_m^T F` (or the same left-multiplied), with the wave factors
    /// `(alpha_m, beta_m)` of `kappa` and `zeta = exp(i kappa L)`.
    fn sum<const R: usize, const C: usize>(
        &self,
        (alpha, beta): (&[Complex64], &[Complex64]),
        (forward, backward): (&[SMatrix<Complex64, R, C>], &[SMatrix<Complex64, R, C>]),
        (kappa, period): (f64, f64),
    ) -> SMatrix<Complex64, R, C> {
        let mut t = SMatrix::<Complex64, R, C>::zeros();
        for m in 0..alpha.len() {
            let (fa, fb) = (alpha[m] * self.ahead[m], beta[m] * self.behind[m]);
            for ((ti, f), b) in t.iter_mut().zip(forward[m].iter()).zip(backward[m].iter()) {
                *ti += f * fa + b * fb;
            }
        }
        t * Complex64::from_polar(period, kappa * period * self.cells)
    }
}

/// `(f(M_m), f(M_m^T))` over the waves.
type Pair<const R: usize, const C: usize> = (Vec<SMatrix<Complex64, R, C>>, Vec<SMatrix<Complex64, R, C>>);

fn both<const Q: usize, const R: usize, const C: usize>(
    modes: &[SMatrix<Complex64, Q, Q>],
    f: impl Fn(&SMatrix<Complex64, Q, Q>) -> SMatrix<Complex64, R, C>,
) -> Pair<R, C> {
    (modes.iter().map(&f).collect(), modes.iter().map(|mm| f(&mm.transpose())).collect())
}

/// `B^T G(x1; x0) B` of eq. 1 (the rail's freedoms mapped by `b` to the
/// loads' `N`) for each pair `(x0, x1)` of `pairs` (m: the load's place
/// and the watched place) on the supports `supports` repeated every
/// `period` (m), to the relative `tolerance` with at most
/// `max_evaluations` evaluations. The waves' residues are projected and
/// the places' wave factors taken once; per `kappa` the `M x M` system of
/// the supports is solved once for every load.
///
/// # Errors
/// Where the integral does not converge.
///
/// # Panics
/// If the supports' system is singular (a passive track's is not).
pub fn response<const Q: usize, const N: usize>(
    waves: &impl RailWaves<Q>,
    supports: &[Supported<Q>],
    period: f64,
    b: &SMatrix<Complex64, Q, N>,
    pairs: &[(f64, f64)],
    (tolerance, max_evaluations): (f64, usize),
) -> Result<Vec<SMatrix<Complex64, N, N>>, QuadratureError> {
    let m = supports.len();
    let bt = b.transpose();
    let lambda = waves.wavenumbers();
    let modes = waves.residues();
    let z: Vec<Complex64> = lambda.iter().map(|l| (Complex64::i() * l * period).exp()).collect();
    // The distinct places loaded and watched, and each pair's.
    let mut loads: Vec<f64> = Vec::new();
    let mut watched: Vec<f64> = Vec::new();
    let index = |list: &mut Vec<f64>, x: f64| match list.iter().position(|&v| v == x) {
        Some(i) => i,
        None => {
            list.push(x);
            list.len() - 1
        }
    };
    let pair_index: Vec<(usize, usize)> =
        pairs.iter().map(|&(x0, x1)| (index(&mut loads, x0), index(&mut watched, x1))).collect();
    // The residues as each product needs them: M K_c (the supports'
    // system), M B (the loads), B^T M K_c (the watched places).
    let system: Vec<Pair<Q, Q>> = supports.iter().map(|(_, k)| both(&modes, |mm| mm * k)).collect();
    let load_modes: Pair<Q, N> = both(&modes, |mm| mm * b);
    let watched_modes: Vec<Pair<N, Q>> = supports.iter().map(|(_, k)| both(&modes, |mm| bt * mm * k)).collect();
    let lambda = lambda.as_slice();
    // The offsets: between supports, from each load to each support, from
    // each support to each watched place.
    let between: Vec<Offset> = supports
        .iter()
        .flat_map(|&(xr, _)| supports.iter().map(move |(xc, _)| Offset::new(lambda, xr - xc, period)))
        .collect();
    let to_support: Vec<Offset> =
        loads.iter().flat_map(|&x0| supports.iter().map(move |(xr, _)| Offset::new(lambda, xr - x0, period))).collect();
    let to_watched: Vec<Offset> = watched
        .iter()
        .flat_map(|&x1| supports.iter().map(move |(xc, _)| Offset::new(lambda, x1 - xc, period)))
        .collect();
    let integrand = |kappa: f64| -> Vec<SMatrix<Complex64, N, N>> {
        let zeta = Complex64::from_polar(1.0, kappa * period);
        let alpha: Vec<Complex64> = z.iter().map(|zm| 1.0 / (1.0 - zm / zeta)).collect();
        let beta: Vec<Complex64> = z.iter().map(|zm| zeta / (1.0 - zm * zeta)).collect();
        let factors = (alpha.as_slice(), beta.as_slice());
        let mut a = Mat::<Complex64>::zeros(Q * m, Q * m);
        let put = |target: &mut Mat<Complex64>, (r0, c0): (usize, usize), block: &[Complex64], rows: usize| {
            // nalgebra stores by column.
            for (k, v) in block.iter().enumerate() {
                target[(r0 + k % rows, c0 + k / rows)] = *v;
            }
        };
        for r in 0..m {
            for (c, (fwd, bwd)) in system.iter().enumerate() {
                let block = between[r * m + c].sum(factors, (fwd, bwd), (kappa, period));
                put(&mut a, (Q * r, Q * c), block.as_slice(), Q);
            }
            for q in 0..Q {
                a[(Q * r + q, Q * r + q)] += period;
            }
        }
        let mut rhs = Mat::<Complex64>::zeros(Q * m, N * loads.len());
        for l in 0..loads.len() {
            for r in 0..m {
                let block = to_support[l * m + r].sum(factors, (&load_modes.0, &load_modes.1), (kappa, period));
                put(&mut rhs, (Q * r, N * l), block.as_slice(), Q);
            }
        }
        let y = a.partial_piv_lu().solve(&rhs);
        // B^T t1 K (N x QM) of every watched place, stacked.
        let mut left = Mat::<Complex64>::zeros(N * watched.len(), Q * m);
        for w in 0..watched.len() {
            for (c, (fwd, bwd)) in watched_modes.iter().enumerate() {
                let block = to_watched[w * m + c].sum(factors, (fwd, bwd), (kappa, period));
                put(&mut left, (N * w, Q * c), block.as_slice(), N);
            }
        }
        pair_index
            .iter()
            .map(|&(l, w)| {
                let v = left.subrows(N * w, N) * y.subcols(N * l, N);
                SMatrix::<Complex64, N, N>::from_fn(|r, c| v[(r, c)])
            })
            .collect()
    };
    let taken = integrate(integrand, -PI / period, PI / period, 16, tolerance, max_evaluations)?;
    Ok(pairs
        .iter()
        .zip(taken)
        .map(|(&(x0, x1), t)| bt * waves.green(x1 - x0) * b - t / Complex64::new(2.0 * PI, 0.0))
        .collect())
}
