//! The rail on a layout of supports ([`super::layout`]): the periodic
//! structure whose period holds several supports, each with its own
//! position and stiffness, by the Floquet method of
//! [`super::discrete3`] with the period's supports solved together.
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

use crate::quadrature::{QuadratureError, integrate};
use faer::Mat;
use faer::linalg::solvers::Solve;
use nalgebra::SMatrix;
use num_complex::Complex64;
use std::f64::consts::PI;

/// The free rail's waves in `Q` freedoms at one frequency: `G(x) = sum_m
/// M_m exp(i lambda_m x)` for `x >= 0`, `G(-x) = G(x)^T` ([`super::waves`]
/// eq. 1).
pub trait RailWaves<const Q: usize> {
    /// The wavenumbers `lambda_m` (rad/m, `Im > 0`).
    fn wavenumbers(&self) -> Vec<Complex64>;
    /// Their residues `M_m`.
    fn residues(&self) -> Vec<SMatrix<Complex64, Q, Q>>;

    /// `G(x)`: the response at `x` (m) to a unit load at 0.
    fn green(&self, x: f64) -> SMatrix<Complex64, Q, Q> {
        let mut g = SMatrix::<Complex64, Q, Q>::zeros();
        for (l, m) in self.wavenumbers().iter().zip(self.residues()) {
            g += m * (Complex64::i() * l * x.abs()).exp();
        }
        if x < 0.0 { g.transpose() } else { g }
    }
}

/// A support of the period: its position (m from the period's start) and
/// dynamic stiffness in the rail's freedoms (N/m for the displacements,
/// N m/rad for the rotations).
pub type Supported<const Q: usize> = (f64, SMatrix<Complex64, Q, Q>);

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

#[cfg(test)]
mod tests {
    use super::super::TrackConfig;
    use super::super::discrete::DiscreteTrack;
    use super::super::discrete3::Discrete3;
    use super::super::layout::Layout;
    use super::super::section::{Mat4, Mat6, translations};
    use super::*;
    use nalgebra::DMatrix;

    const HZ: [f64; 4] = [150.0, 600.0, 1500.0, 3000.0];

    fn omega(hz: f64) -> f64 {
        2.0 * PI * hz
    }

    /// An irregular layout of three bays: spacings 0.55, 0.70 and 0.55 m,
    /// the second pad twice as stiff, the third sleeper lighter.
    fn irregular(t: &TrackConfig) -> Layout {
        let mut l = Layout::at_positions(t, 1.8, &[0.0, 0.55, 1.25]).unwrap();
        l.supports[1].pad_stiffness *= 2.0;
        l.supports[2].sleeper_mass *= 0.7;
        l
    }

    fn relative(a: Complex64, b: Complex64) -> f64 {
        (a - b).norm() / b.norm()
    }

    #[test]
    fn one_support_per_period_is_the_discrete_track() {
        // Vertically against the lattice sums of discrete.rs (their own
        // truncation and midpoint rule); in every direction against
        // discrete3.rs's one-support integral.
        let t = TrackConfig::default();
        let layout = Layout::uniform(&t);
        let vertical = DiscreteTrack::new(&t);
        let head = Discrete3::new(&t, 0.01);
        let pairs = [(0.0, 0.0), (0.15, 0.15), (0.3, 0.3), (0.1, 0.45)];
        let (mut ev, mut eh) = (0.0f64, 0.0f64);
        for hz in HZ {
            let w = omega(hz);
            let lay = vertical.layout_receptances(&layout, &pairs, w).unwrap();
            let own: Vec<Complex64> =
                pairs.iter().map(|&(x0, x1)| vertical.transfer_receptances(x0, &[x1 - x0], w)[0]).collect();
            for (a, b) in lay.iter().zip(&own) {
                ev = ev.max(relative(*a, *b));
            }
            let lay = head.layout_heads(&layout, &pairs, w, true).unwrap();
            let own = head.heads(&pairs, w, true).unwrap();
            for (a, b) in lay.iter().zip(&own) {
                eh = eh.max((a - b).norm() / b.norm());
            }
        }
        // Vertically 1.5e-4: the lattice sums' truncation (a few 1e-4 of
        // the receptance, discrete.rs); in every direction one integral,
        // to rounding.
        assert!(ev < 1e-3, "vertical: {ev:e}");
        assert!(eh < 1e-10, "every direction: {eh:e}");
    }

    #[test]
    fn identical_bays_are_one_bay() {
        let t = TrackConfig::default();
        let three = Layout::at_positions(&t, 1.8, &[0.0, 0.6, 1.2]).unwrap();
        let one = Layout::uniform(&t);
        let vertical = DiscreteTrack::new(&t);
        let head = Discrete3::new(&t, 0.01);
        // The same places seen from another bay of the three.
        let pairs = [(0.1, 0.1), (0.2, 0.5), (0.3, 1.0)];
        let shifted: Vec<(f64, f64)> = pairs.iter().map(|&(a, b)| (a + 0.6, b + 0.6)).collect();
        let (mut ev, mut eh) = (0.0f64, 0.0f64);
        for hz in HZ {
            let w = omega(hz);
            let a = vertical.layout_receptances(&three, &shifted, w).unwrap();
            let b = vertical.layout_receptances(&one, &pairs, w).unwrap();
            for (a, b) in a.iter().zip(&b) {
                ev = ev.max(relative(*a, *b));
            }
            let a = head.layout_heads(&three, &shifted, w, false).unwrap();
            let b = head.layout_heads(&one, &pairs, w, false).unwrap();
            for (a, b) in a.iter().zip(&b) {
                eh = eh.max((a - b).norm() / b.norm());
            }
        }
        assert!(ev < 1e-5 && eh < 1e-5, "vertical {ev:e}, every direction {eh:e}");
    }

    /// The rail's response on `periods` copies each side of the layout's
    /// supports, solved in space: `w_s + sum_t G(p_s - p_t) K_t w_t = G(p_s
    /// - x0)`, the response at `x1` `G(x1 - x0) - sum_t G(x1 - p_t) K_t w_t`.
    fn in_space<const Q: usize>(
        waves: &impl RailWaves<Q>,
        supports: &[Supported<Q>],
        period: f64,
        periods: i32,
        (x0, x1): (f64, f64),
    ) -> SMatrix<Complex64, Q, Q> {
        let all: Vec<&Supported<Q>> = (-periods..=periods).flat_map(|_| supports.iter()).collect();
        let place: Vec<f64> =
            (-periods..=periods).flat_map(|n| supports.iter().map(move |(x, _)| x + n as f64 * period)).collect();
        let n = all.len();
        let mut a = DMatrix::<Complex64>::identity(Q * n, Q * n);
        let mut rhs = DMatrix::<Complex64>::zeros(Q * n, Q);
        for s in 0..n {
            for t in 0..n {
                let block = waves.green(place[s] - place[t]) * all[t].1;
                let mut v = a.view_mut((Q * s, Q * t), (Q, Q));
                v += block;
            }
            rhs.view_mut((Q * s, 0), (Q, Q)).copy_from(&waves.green(place[s] - x0));
        }
        let w = a.lu().solve(&rhs).unwrap();
        let mut g = waves.green(x1 - x0);
        for t in 0..n {
            let wt = SMatrix::<Complex64, Q, Q>::from_fn(|r, c| w[(Q * t + r, c)]);
            g -= waves.green(x1 - place[t]) * all[t].1 * wt;
        }
        g
    }

    #[test]
    fn an_irregular_layout_against_its_supports_solved_in_space() {
        let t = TrackConfig::default();
        let layout = irregular(&t);
        let vertical = DiscreteTrack::new(&t);
        let pairs = [(0.0, 0.0), (0.3, 0.3), (0.9, 0.9), (0.2, 1.4)];
        let mut e = 0.0f64;
        for hz in HZ {
            let w = omega(hz);
            let waves = vertical.waves(w);
            let supports = vertical.layout_supports(&layout, w);
            let floquet = vertical.layout_receptances(&layout, &pairs, w).unwrap();
            for (p, f) in pairs.iter().zip(&floquet) {
                let s = in_space(&waves, &supports, layout.period, 60, *p)[(0, 0)];
                e = e.max(relative(*f, s));
            }
        }
        // Measured 1.6e-10 (the integral's tolerance is 1e-6).
        assert!(e < 1e-6, "vertical: {e:e}");
    }

    #[test]
    fn an_irregular_layout_in_every_direction_against_its_supports_solved_in_space() {
        let t = TrackConfig::default();
        let layout = irregular(&t);
        let head = Discrete3::new(&t, 0.01);
        // The lateral and longitudinal waves carry little damping: the
        // sum in space converges slowly with its length (7.0e-3, 1.2e-3,
        // 5.6e-4 at 10, 20, 30 periods each side).
        let pairs = [(0.3, 0.3), (0.2, 1.4)];
        let mut e = 0.0f64;
        for hz in [600.0, 1500.0] {
            let w = omega(hz);
            let waves = head.free_waves(w).unwrap();
            let supports = head.layout_supports(&layout, w);
            let floquet = head.layout_heads(&layout, &pairs, w, false).unwrap();
            for (p, f) in pairs.iter().zip(&floquet) {
                let g: Mat6 = in_space(&waves, &supports, layout.period, 30, *p);
                let s = head.section.head(&g);
                e = e.max((translations(f) - s).norm() / s.norm());
            }
        }
        assert!(e < 1e-3, "every direction: {e:e}");
    }

    #[test]
    fn an_irregular_layout_is_reciprocal_and_passive_in_every_direction() {
        let t = TrackConfig::default();
        let layout = irregular(&t);
        let head = Discrete3::new(&t, 0.01);
        let places = [0.0, 0.2, 0.55, 0.9, 1.6];
        for hz in HZ {
            let w = omega(hz);
            let pairs: Vec<(f64, f64)> = places.iter().flat_map(|&a| places.iter().map(move |&b| (a, b))).collect();
            let g = head.layout_heads(&layout, &pairs, w, true).unwrap();
            let n = places.len();
            for i in 0..n {
                for j in 0..n {
                    let (a, b) = (&g[i * n + j], &g[j * n + i]);
                    let e = (a - b.transpose()).norm() / a.norm();
                    assert!(e < 1e-9, "{hz} Hz, places {i}, {j}: G(x1; x0) - G(x0; x1)^T at {e:e}");
                }
                // Passive (exp(+i w t)): (A - A^H) / 2i is negative
                // semidefinite at a point.
                let a: &Mat4 = &g[i * n + i];
                let h = (a - a.adjoint()) / Complex64::new(0.0, 2.0);
                let top = h.map(|v| v.re).symmetric_eigenvalues().max();
                assert!(top <= 1e-9 * a.norm(), "{hz} Hz at {} m: the dissipation's eigenvalue {top:e}", places[i]);
            }
        }
    }
}
