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
//! **Creepage.** The prescribed force closes the system with `xi_x`. After
//! each sweep `xi <- xi - (F - F_x) / kappa`, `kappa = dF/dxi` estimated from
//! the stick area's mean flexibility (a uniform traction change that cancels a
//! uniform slip change) plus the slip elements' own response.
//!
//! **Acceleration.** The sweep-and-creepage map `x -> G(x)`, x the scaled
//! tractions and creepage, is a contraction whose fixed point is the
//! solution; Anderson mixing of depth [`DEPTH`] (Walker and Ni, SIAM J. Numer.
//! Anal. 49 (2011) 1715-1735) accelerates it (no restarts: restarting when
//! the residual grew made the hard steps ten times slower).

use super::elastic::ExactElastic;
use super::{FORCE_TOLERANCE, STICK_SLIP_FACTOR, friction};
use crate::numerics::{Tolerance, brent};
use multiversion::multiversion;
use nalgebra::{DMatrix, DVector};
use std::f64::consts::PI;

/// Anderson depth (previous iterates kept).
pub const DEPTH: usize = 6;

/// Elements from which a sweep runs in two parallel halves.
const PARALLEL_MIN: usize = 64;

/// Sweeps between fresh products `u = C p` (in between, u is mixed with p,
/// exactly up to rounding amplified by the mixing coefficients). Longer than
/// a typical step (23-38 sweeps): the products at 16 and 32 sweeps cost 6 %
/// of a 20 x 20 passage and changed nothing; the verdict is always taken on
/// a fresh product, and a failed verdict leaves it behind.
const REFRESH: usize = 64;

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
    let mut s = s.to_vec();
    let mut p: Vec<f64> = (0..n).flat_map(|k| friction([s[2 * k], s[2 * k + 1]], st.mu_p3[k], st.eps).0).collect();
    let mut u = vec![0.0; 2 * n];
    st.elastic.displacement(st.a, &p, &mut u);
    let kappa = creepage_stiffness(st, &s);
    // Scales: tractions by mu p0, the creepage by the traction it moves.
    let p_scale = st.mu_p3.iter().fold(0.0f64, |m, v| m.max(*v)).max(f64::MIN_POSITIVE);
    let area_total: f64 = st.area.iter().sum();
    let xi_scale = (kappa.abs() / (area_total * p_scale)).max(f64::MIN_POSITIVE);
    let pack = |p: &[f64], xi: f64| -> DVector<f64> {
        DVector::from_iterator(2 * n + 1, p.iter().map(|v| v / p_scale).chain(std::iter::once(xi * xi_scale)))
    };
    let mut xi = xi;
    let mut anderson = Anderson::new(DEPTH);
    let mut history = Vec::new();
    for sweep_no in 0..st.max_sweeps {
        let x = pack(&p, xi);
        let r_max = sweep(st, &mut p, &mut s, &mut u, xi);
        let force: f64 = (0..n).map(|k| p[2 * k] * st.area[k]).sum();
        let r_force = (force - st.force_x) / st.mu_n;
        history.push(r_max);
        if !r_max.is_finite() || !r_force.is_finite() {
            return Err(history);
        }
        if r_max < st.tol && r_force.abs() < FORCE_TOLERANCE {
            // The displacements were carried through the mixing (linear in
            // p); the verdict is checked on freshly computed ones.
            st.elastic.displacement(st.a, &p, &mut u);
            if residual(st, &s, &u, xi) < st.tol {
                return Ok(GsSolution { p, s, xi, sweeps: sweep_no + 1 });
            }
        }
        let xi_next = xi - (force - st.force_x) / kappa;
        let g = pack(&p, xi_next);
        let (mixed, u_mixed) = anderson.mix(&x, &g, DVector::from_column_slice(&u));
        for (pk, m) in p.iter_mut().zip(mixed.iter()) {
            *pk = m * p_scale;
        }
        xi = mixed[2 * n] / xi_scale;
        if (sweep_no + 1) % REFRESH == 0 {
            st.elastic.displacement(st.a, &p, &mut u);
        } else {
            u.copy_from_slice(u_mixed.as_slice());
        }
    }
    Err(history)
}

/// One Gauss-Seidel sweep at creepage `xi`; returns the largest kinematic
/// residual (m/s) after it, `|s_k - V w_k - (u_k - u_o,k)/dt|`.
fn sweep(st: &GsStep, p: &mut [f64], s: &mut [f64], u: &mut [f64], xi: f64) -> f64 {
    let n = p.len() / 2;
    if n < PARALLEL_MIN {
        sweep_block(st, 0, p, s, u, xi);
    } else {
        // Two halves of the patch in parallel, each sweeping its elements
        // against its own copy of u (Jacobi between the halves, Gauss-Seidel
        // within); then u = u_a + u_b - u_0. Fixed split, fixed sum order:
        // deterministic.
        let m = st.split.min(n);
        let (pa, pb) = p.split_at_mut(2 * m);
        let (sa, sb) = s.split_at_mut(2 * m);
        let (mut ua, mut ub) = (u.to_vec(), u.to_vec());
        rayon::join(|| sweep_block(st, 0, pa, sa, &mut ua, xi), || sweep_block(st, m, pb, sb, &mut ub, xi));
        for ((u0, a), b) in u.iter_mut().zip(&ua).zip(&ub) {
            *u0 = a + b - *u0;
        }
    }
    residual(st, s, u, xi)
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
        let (sk, pk) = local_solve(s0, kk, st.mu_p3[k], st.eps, [s[li], s[lj]]);
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

/// Solves the element problem `s = s0 + K p(s)` for the 2 x 2 symmetric
/// positive definite `K = [k0 k1; k1 k2]`. Returns the slip and its traction.
///
/// Newton from `start` (the last sweep's slip) while each full step halves
/// |grad E| (`grad E = K^-1 (s - s0) - p`, Hessian `K^-1 + D`), which is what
/// happens near the solution. Otherwise the 1-D form: with `p = -mu p3 f(q) s`
/// the solution is `s = (I + c K)^-1 s0` with `c = mu p3 f(q)`, `q = |s|`;
/// `Q(c) = |(I + c K)^-1 s0|` decreases with c and `f` with q, so `q` is the
/// root of `1 - Q(mu p3 f(q)) / q` on `[Q(mu p3 f(0)), |s0|]`, found by Brent
/// in `ln q` (relative accuracy on q, down to deep stick where q << eps).
pub(crate) fn local_solve(s0: [f64; 2], k: [f64; 3], mu_p3: f64, eps: f64, start: [f64; 2]) -> ([f64; 2], [f64; 2]) {
    let norm = |v: [f64; 2]| (v[0] * v[0] + v[1] * v[1]).sqrt();
    let q0 = norm(s0);
    if mu_p3 <= 0.0 || q0 == 0.0 {
        return (s0, [0.0; 2]);
    }
    let det = k[0] * k[2] - k[1] * k[1];
    let kinv = [k[2] / det, -k[1] / det, k[0] / det];
    let grad = |s: [f64; 2]| {
        let (p, d) = friction(s, mu_p3, eps);
        let (dx, dy) = (s[0] - s0[0], s[1] - s0[1]);
        ([kinv[0] * dx + kinv[1] * dy - p[0], kinv[1] * dx + kinv[2] * dy - p[1]], p, d)
    };
    let mut s = start;
    let (mut g, mut p, mut d) = grad(s);
    for _ in 0..8 {
        let h = [kinv[0] + d[0], kinv[1] + d[1], kinv[2] + d[2]];
        let hdet = h[0] * h[2] - h[1] * h[1];
        let step = [-(h[2] * g[0] - h[1] * g[1]) / hdet, -(h[0] * g[1] - h[1] * g[0]) / hdet];
        let size = norm(step);
        // Relative to |s| itself: in deep stick |s| << eps and p ~ s.
        let scale = norm(s).max(f64::MIN_POSITIVE);
        if size <= 1e-14 * scale {
            return (s, p);
        }
        let trial = [s[0] + step[0], s[1] + step[1]];
        let (gt, pt, dt) = grad(trial);
        if norm(gt) > 0.5 * norm(g) {
            break;
        }
        (s, g, p, d) = (trial, gt, pt, dt);
        // A full step this small leaves an error ~ its square: done.
        if size <= 1e-8 * scale {
            return (s, p);
        }
    }
    // The bracketed 1-D form.
    let shrink = |c: f64| {
        let m = [1.0 + c * k[0], c * k[1], 1.0 + c * k[2]];
        let mdet = m[0] * m[2] - m[1] * m[1];
        [(m[2] * s0[0] - m[1] * s0[1]) / mdet, (m[0] * s0[1] - m[1] * s0[0]) / mdet]
    };
    // f(q) = (2/pi) atan(q/eps)/q; series 2/(pi eps) (1 - z^2/3) for small z.
    let f = |q: f64| {
        let z = q / eps;
        if z < 1e-4 { 2.0 / (PI * eps) * (1.0 - z * z / 3.0) } else { 2.0 / PI * z.atan() / q }
    };
    let q_lo = norm(shrink(mu_p3 * f(0.0)));
    let r = |t: f64| {
        let q = t.exp();
        1.0 - norm(shrink(mu_p3 * f(q))) / q
    };
    // ln q to 1e-15 relative: q to ~1e-14 relative.
    let tol = Tolerance { residual: 1e-16, x_rel: 1e-15, x_abs: 1e-15, max_iter: 200 };
    let t = if q_lo >= q0 {
        q0.ln()
    } else if r(q_lo.ln()) >= -1e-15 {
        // Deep stick: f(q) = f(0) to rounding, the root is the bracket's end.
        q_lo.ln()
    } else {
        match brent(q_lo.ln(), q0.ln(), r, tol) {
            Ok(t) => t,
            // Not reached on a valid bracket; the sweep's residual test
            // decides convergence either way.
            Err(_) => return (s, p),
        }
    };
    let s = shrink(mu_p3 * f(t.exp()));
    (s, friction(s, mu_p3, eps).0)
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
            let (_, d) = friction([s[2 * k], s[2 * k + 1]], st.mu_p3[k], st.eps);
            kappa += st.area[k] * d[0] / (1.0 + scale * c1[(2 * k, 2 * k)] * d[0]);
        }
    }
    -st.speed * kappa.max(1e-30)
}

/// Anderson mixing (type II) of a fixed-point map, carrying along an
/// auxiliary vector that depends linearly on the iterate (the displacements).
pub(crate) struct Anderson {
    depth: usize,
    /// Last residual f = G(x) - x, G(x) and the auxiliary vector of G(x).
    last: Option<(DVector<f64>, DVector<f64>, DVector<f64>)>,
    /// Differences of successive residuals, G values and auxiliary vectors.
    df: Vec<DVector<f64>>,
    dg: Vec<DVector<f64>>,
    daux: Vec<DVector<f64>>,
}

impl Anderson {
    pub(crate) fn new(depth: usize) -> Self {
        Anderson { depth, last: None, df: Vec::new(), dg: Vec::new(), daux: Vec::new() }
    }

    /// The next iterate from `x`, `g = G(x)` and `aux` (that of g), with its
    /// auxiliary vector.
    pub(crate) fn mix(
        &mut self,
        x: &DVector<f64>,
        g: &DVector<f64>,
        aux: DVector<f64>,
    ) -> (DVector<f64>, DVector<f64>) {
        let f = g - x;
        if let Some((f_old, g_old, aux_old)) = &self.last {
            self.df.push(&f - f_old);
            self.dg.push(g - g_old);
            self.daux.push(&aux - aux_old);
            if self.df.len() > self.depth {
                self.df.remove(0);
                self.dg.remove(0);
                self.daux.remove(0);
            }
        }
        self.last = Some((f.clone(), g.clone(), aux.clone()));
        if self.df.is_empty() {
            return (g.clone(), aux);
        }
        // Least squares min |f - F gamma| by the normal equations of the
        // column-normalised history F D (D = diag 1/|f_i|): (F D)^T F D is
        // depth x depth (an SVD of F costs more than the rest of the mixing).
        // Its directions below 1e-12 of the largest eigenvalue, singular
        // values of F D below 1e-6 of the largest (nearly dependent
        // differences, which rounding in the Gram matrix, ~1e-15, does not
        // resolve), are dropped. The normalisation keeps a short but new
        // difference from being dropped for its size alone.
        let scale: Vec<f64> = self.df.iter().map(|c| 1.0 / c.norm().max(f64::MIN_POSITIVE)).collect();
        let fm = DMatrix::from_fn(f.len(), self.df.len(), |r, c| self.df[c][r] * scale[c]);
        let eig = fm.tr_mul(&fm).symmetric_eigen();
        let cut = 1e-12 * eig.eigenvalues.amax();
        let proj = eig.eigenvectors.tr_mul(&fm.tr_mul(&f));
        let kept = DVector::from_fn(proj.len(), |i, _| {
            let l = eig.eigenvalues[i];
            if l > cut { proj[i] / l } else { 0.0 }
        });
        let gamma =
            DVector::from_iterator(scale.len(), (&eig.eigenvectors * kept).iter().zip(&scale).map(|(g, s)| g * s));
        if !gamma.iter().all(|v| v.is_finite()) {
            return (g.clone(), aux);
        }
        let (mut next, mut aux_next) = (g.clone(), aux);
        for i in 0..self.df.len() {
            next.axpy(-gamma[i], &self.dg[i], 1.0);
            aux_next.axpy(-gamma[i], &self.daux[i], 1.0);
        }
        (next, aux_next)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// The element problem s = s0 + K p(s) is solved to rounding from any
        /// start, from deep stick (|s| ~ 1e-7 |s0|) through full slip.
        #[test]
        fn local_solve_satisfies_the_element_equation(
            log_s0 in -9.0f64..1.0,
            angle in 0.0f64..std::f64::consts::TAU,
            log_k in -11.0f64..-8.0,
            anisotropy in 0.6f64..1.6,
            coupling in -0.2f64..0.2,
            log_start in -12.0f64..1.0,
            start_angle in 0.0f64..std::f64::consts::TAU,
            log_mu_p3 in 5.0f64..9.0,
            log_eps in -7.0f64..-3.0,
        ) {
            let (mu_p3, eps) = (10f64.powf(log_mu_p3), 10f64.powf(log_eps));
            let m = 10f64.powf(log_s0);
            let s0 = [m * angle.cos(), m * angle.sin()];
            let k0 = 10f64.powf(log_k);
            let k = [k0, coupling * k0, anisotropy * k0];
            let q = 10f64.powf(log_start);
            let (s, p) = local_solve(s0, k, mu_p3, eps, [q * start_angle.cos(), q * start_angle.sin()]);
            let r = [s[0] - s0[0] - (k[0] * p[0] + k[1] * p[1]), s[1] - s0[1] - (k[1] * p[0] + k[2] * p[1])];
            prop_assert!(r[0].hypot(r[1]) <= 1e-13 * m.max(eps), "residual {r:?} for s0 {s0:?}");
            let (law, _) = friction(s, mu_p3, eps);
            prop_assert_eq!(law, p);
            prop_assert!(p[0].hypot(p[1]) < mu_p3);
        }
    }

    #[test]
    fn anderson_solves_a_linear_fixed_point_in_few_steps() {
        // x = G(x) = M x + c with a contraction M of spectral radius 0.9: plain
        // iteration needs ~300 steps for 1e-14; Anderson(6) on a 5-dimensional
        // problem is exact (to rounding) once its history spans the space.
        let m = DMatrix::from_fn(5, 5, |i, j| if i == j { 0.9 - 0.1 * i as f64 } else { 0.01 * (i + 2 * j) as f64 });
        let c = DVector::from_fn(5, |i, _| 1.0 + i as f64);
        let exact = (DMatrix::identity(5, 5) - &m).lu().solve(&c).unwrap();
        // The carried vector is a linear image of the iterate (as u = C p).
        let image = DMatrix::from_fn(3, 5, |i, j| (1 + i + 2 * j) as f64 * 0.1);
        let mut a = Anderson::new(DEPTH);
        let mut x = DVector::zeros(5);
        for _ in 0..8 {
            let g = &m * &x + &c;
            let (next, carried) = a.mix(&x, &g, &image * &g);
            assert!((&carried - &image * &next).norm() < 1e-12 * carried.norm().max(1.0), "carried = image of next");
            x = next;
        }
        assert!((&x - &exact).norm() < 1e-10 * exact.norm(), "{x} vs {exact}");
    }
}
