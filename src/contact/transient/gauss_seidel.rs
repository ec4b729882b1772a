//! Nonlinear block Gauss-Seidel with Anderson acceleration: the exact
//! transient step of [`super`] (Baeza et al. 2008, Eq. 7) solved element by
//! element instead of by Newton-Raphson on the whole patch. The equations and
//! the convergence test are the reference solver's; only the way to the
//! solution differs.
//!
//! **Element problem.** With the tractions of the other elements held, the
//! slip of element k is `s = s0 + K p(s)` with `K = (a/dt) C1_kk` (its own
//! flexibility, 2 x 2) and `p(s) = -mu p3 f(|s|) s` the regularised Coulomb
//! law. Because `p = -grad Phi` with the convex potential
//!
//! ```text
//! Phi(s) = mu p3 (2/pi) (q atan(q/eps) - eps/2 ln(1 + q^2/eps^2)),   q = |s|,
//! ```
//!
//! `s` is the unique minimiser of the strictly convex
//! `E(s) = 1/2 (s - s0)^T K^-1 (s - s0) + Phi(s)`: Newton on grad E from the
//! last sweep's slip, or, where Newton stalls (the wrong side of the
//! stick/slip transition, where Phi ~ mu p3 |s| is a cone), a bracketed 1-D
//! root in |s| (`local_solve`).
//! This is Kalker's element-wise Gauss-Seidel of the tangential problem
//! (Kalker 1990, ch. 5; Vollebregt's ConvexGS) with the regularised law in
//! place of the Coulomb cone.
//!
//! **Sweep.** Strip by strip from the leading edge (material enters there and
//! carries its history backwards, as in Kalker's and Vollebregt's orderings),
//! each element solved and the displacements updated by its two columns of C:
//! one sweep costs one product with C, `O(N^2)`.
//!
//! **Creepage and acceleration.** The creepage update from the force
//! residual, Anderson mixing of depth [`DEPTH`] and the verdict are the
//! shared loop's ([`crate::contact::gs_loop`]); this module gives it the
//! adapted mesh's sweep and `kappa = dF/dxi`, estimated from the stick
//! area's mean flexibility (a uniform traction change that cancels a
//! uniform slip change) plus the slip elements' own response.

use super::FORCE_TOLERANCE;
use super::elastic::ExactElastic;
use crate::contact::friction::{
    Local, STICK_SLIP_FACTOR, local_solve_with, regularised_with, varying::frozen_jacobian,
};
use crate::contact::gs_loop::{self, Settings, Sweeper};
use multiversion::multiversion;

/// Anderson depth (previous iterates kept).
pub const DEPTH: usize = 6;

/// Elements from which a sweep runs in two parallel halves.
const PARALLEL_MIN: usize = 64;

/// The data of one step for the Gauss-Seidel solver.
pub(super) struct GsStep<'a> {
    /// The exact elastic model: C = a C1, interleaved (m/Pa per m of a).
    pub elastic: &'a ExactElastic,
    /// Semi-axis a (m).
    pub a: f64,
    /// Time step (s).
    pub dt: f64,
    /// Rolling speed (m/s).
    pub speed: f64,
    /// Regularisation (m/s).
    pub eps: f64,
    /// How the friction coefficient varies with the slip speed.
    /// The friction characteristic at each element (with its memory).
    pub local: &'a [Local],
    /// mu p3 per element (Pa).
    pub mu_p3: &'a [f64],
    /// Element areas (m^2).
    pub area: &'a [f64],
    /// Rigid slip per unit speed with xi_x = 0, interleaved (1).
    pub w0: &'a [f64],
    /// Earlier displacements (m), interleaved.
    pub u_o: &'a [f64],
    /// Prescribed F_x (N).
    pub force_x: f64,
    /// Whether the creepage is prescribed instead (the warm start's is
    /// kept; `force_x` unused).
    pub creepage_prescribed: bool,
    /// mu N (N), the force scale.
    pub mu_n: f64,
    /// Tolerance on the kinematic residual (m/s), as the Newton solver's.
    pub tol: f64,
    /// Most sweeps before giving up.
    pub max_sweeps: usize,
    /// First element of the second parallel half (a whole number of strips).
    pub split: usize,
}

/// Converged state of one step.
pub(super) struct GsSolution {
    /// Tractions (Pa), interleaved.
    pub p: Vec<f64>,
    /// Slips (m/s), interleaved.
    pub s: Vec<f64>,
    /// Creepage xi_x.
    pub xi: f64,
    /// Sweeps done.
    pub sweeps: usize,
}

/// Solves the step from the warm start (slips `s`, creepage `xi`). Err holds
/// the history of the largest kinematic residual (m/s) per sweep.
pub(super) fn solve(st: &GsStep, s: &[f64], xi: f64) -> Result<GsSolution, Vec<f64>> {
    let n = st.mu_p3.len();
    let p: Vec<f64> =
        (0..n).flat_map(|k| regularised_with([s[2 * k], s[2 * k + 1]], st.mu_p3[k], st.eps, st.local[k]).0).collect();
    let kappa = creepage_stiffness(st, s);
    // Scales: tractions by mu p0, the creepage by the traction it moves.
    let p_scale = st.mu_p3.iter().fold(0.0f64, |m, v| m.max(*v)).max(f64::MIN_POSITIVE);
    let area_total: f64 = st.area.iter().sum();
    let settings = Settings {
        depth: DEPTH,
        max_sweeps: st.max_sweeps,
        tol: st.tol,
        force_tol: FORCE_TOLERANCE,
        force_x: st.force_x,
        creepage_prescribed: st.creepage_prescribed,
        mu_n: st.mu_n,
        kappa,
        p_scale,
        xi_scale: (kappa.abs() / (area_total * p_scale)).max(f64::MIN_POSITIVE),
    };
    let mut fresh = |p: &[f64], u: &mut [f64]| st.elastic.displacement(st.a, p, u);
    let solved = gs_loop::solve(st, &settings, p, s.to_vec(), xi, &mut fresh)?;
    Ok(GsSolution { p: solved.p, s: solved.s, xi: solved.xi, sweeps: solved.sweeps })
}

impl Sweeper for GsStep<'_> {
    /// One sweep; from [`PARALLEL_MIN`] elements two halves of the patch in
    /// parallel, each sweeping its elements against its own copy of u
    /// (Jacobi between the halves, Gauss-Seidel within); then u = u_a + u_b
    /// - u_0. Fixed split, fixed sum order: deterministic.
    fn sweep(&self, p: &mut [f64], s: &mut [f64], u: &mut [f64], xi: f64) {
        let n = p.len() / 2;
        if n < PARALLEL_MIN {
            sweep_block(self, 0, p, s, u, xi);
        } else {
            let m = self.split.min(n);
            let (pa, pb) = p.split_at_mut(2 * m);
            let (sa, sb) = s.split_at_mut(2 * m);
            let (mut ua, mut ub) = (u.to_vec(), u.to_vec());
            rayon::join(|| sweep_block(self, 0, pa, sa, &mut ua, xi), || sweep_block(self, m, pb, sb, &mut ub, xi));
            for ((u0, a), b) in u.iter_mut().zip(&ua).zip(&ub) {
                *u0 = a + b - *u0;
            }
        }
    }

    fn residual(&self, s: &[f64], u: &[f64], xi: f64) -> f64 {
        residual(self, s, u, xi)
    }

    fn force(&self, p: &[f64]) -> f64 {
        (0..self.mu_p3.len()).map(|k| p[2 * k] * self.area[k]).sum()
    }
}

/// Gauss-Seidel over the elements `first ..` whose tractions and slips are
/// `p` and `s`, updating the displacements `u` of the whole patch.
fn sweep_block(st: &GsStep, first: usize, p: &mut [f64], s: &mut [f64], u: &mut [f64], xi: f64) {
    let (scale, c1) = (st.a / st.dt, st.elastic.unit_matrix());
    for local in 0..p.len() / 2 {
        let k = first + local;
        let (i, j) = (2 * k, 2 * k + 1);
        let (li, lj) = (2 * local, 2 * local + 1);
        let kk = [scale * c1[(i, i)], scale * c1[(i, j)], scale * c1[(j, j)]];
        let own = [kk[0] * p[li] + kk[1] * p[lj], kk[1] * p[li] + kk[2] * p[lj]];
        let s0 = [
            st.speed * (st.w0[i] + xi) + (u[i] - st.u_o[i]) / st.dt - own[0],
            st.speed * st.w0[j] + (u[j] - st.u_o[j]) / st.dt - own[1],
        ];
        let (sk, pk) = local_solve_with(s0, kk, st.mu_p3[k], st.eps, [s[li], s[lj]], st.local[k]);
        s[li] = sk[0];
        s[lj] = sk[1];
        let (dx, dy) = (pk[0] - p[li], pk[1] - p[lj]);
        p[li] = pk[0];
        p[lj] = pk[1];
        if dx != 0.0 || dy != 0.0 {
            add_columns(u, (c1.col_as_slice(i), c1.col_as_slice(j)), st.a * dx, st.a * dy);
        }
    }
}

/// `u += fx c_x + fy c_y` for the two columns `(c_x, c_y)` of one element:
/// the inner loop of a sweep. Compiled also for AVX2 and picked at run time
/// (`multiversion`); the AVX2 clone only widens the lanes (no fused
/// multiply-add, which would round differently), so every target gives the
/// same bits.
#[multiversion(targets("x86_64+avx2"))]
fn add_columns(u: &mut [f64], (cx, cy): (&[f64], &[f64]), fx: f64, fy: f64) {
    for ((ur, x), y) in u.iter_mut().zip(cx).zip(cy) {
        *ur += x * fx + y * fy;
    }
}

/// Largest kinematic residual (m/s) of slips `s` and displacements `u`.
fn residual(st: &GsStep, s: &[f64], u: &[f64], xi: f64) -> f64 {
    (0..s.len())
        .map(|i| {
            let w = st.w0[i] + if i % 2 == 0 { xi } else { 0.0 };
            (s[i] - st.speed * w - (u[i] - st.u_o[i]) / st.dt).abs()
        })
        .fold(0.0, f64::max)
}

/// dF_x/dxi_x estimate (N): the stick area (|s| < 10 eps at the warm start)
/// answers a uniform slip change `V dxi` with the uniform traction change
/// that cancels it through its mean row sum of `(a/dt) C_xx`; slip elements
/// answer through their own law derivative.
fn creepage_stiffness(st: &GsStep, s: &[f64]) -> f64 {
    let n = st.mu_p3.len();
    let (scale, c1) = (st.a / st.dt, st.elastic.unit_matrix());
    let stick: Vec<usize> =
        (0..n).filter(|&k| s[2 * k].hypot(s[2 * k + 1]) < STICK_SLIP_FACTOR * st.eps && st.mu_p3[k] > 0.0).collect();
    let mut kappa = 0.0;
    if !stick.is_empty() {
        let rows: f64 = stick.iter().map(|&k| stick.iter().map(|&j| scale * c1[(2 * k, 2 * j)]).sum::<f64>()).sum();
        let rho = rows / stick.len() as f64;
        let area: f64 = stick.iter().map(|&k| st.area[k]).sum();
        kappa += area / rho;
    }
    for k in 0..n {
        if stick.binary_search(&k).is_err() {
            let d = frozen_jacobian([s[2 * k], s[2 * k + 1]], st.mu_p3[k], st.eps, st.local[k]);
            kappa += st.area[k] * d[0] / (1.0 + scale * c1[(2 * k, 2 * k)] * d[0]);
        }
    }
    -st.speed * kappa.max(1e-30)
}
