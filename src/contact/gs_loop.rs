//! The outer loop of a nonlinear Gauss-Seidel solve of the transient
//! tangential problem, one for the adapted mesh
//! ([`crate::contact::transient::gauss_seidel`]) and the fixed grid
//! ([`crate::contact::grid::tangential`]): sweep, residual, creepage update
//! from the force residual, Anderson acceleration of the whole, and the
//! verdict on an exact product.
//!
//! **Creepage.** The prescribed force closes the system with `xi_x`. After
//! each sweep `xi <- xi - (F - F_x) / kappa`, `kappa = dF/dxi` estimated by
//! the discretisation (the stick area's mean flexibility plus the slip
//! elements' own response).
//!
//! **Acceleration.** The sweep-and-creepage map `x -> G(x)`, x the scaled
//! tractions and creepage, is a contraction whose fixed point is the
//! solution; Anderson mixing (Walker and Ni, SIAM J. Numer. Anal. 49 (2011)
//! 1715-1735) accelerates it (no restarts: restarting when the residual grew
//! made the hard steps ten times slower). The displacements `u = K p`,
//! linear in the tractions, are carried through the mixing and refreshed by
//! an exact product every [`REFRESH`] sweeps and before the verdict.

use nalgebra::{DMatrix, DVector};

/// Sweeps between fresh products `u = K p` (in between, u is mixed with p,
/// exactly up to rounding amplified by the mixing coefficients). Longer than
/// a typical step (23-38 sweeps): the products at 16 and 32 sweeps cost 6 %
/// of a 20 x 20 passage and changed nothing; the verdict is always taken on
/// a fresh product, and a failed verdict leaves it behind.
pub const REFRESH: usize = 64;

/// One discretisation's sweep, residual and force.
pub(crate) trait Sweeper {
    /// One sweep at creepage `xi`: every element's problem solved in turn
    /// with the others held, the tractions `p`, slips `s` and displacements
    /// `u` updated.
    fn sweep(&self, p: &mut [f64], s: &mut [f64], u: &mut [f64], xi: f64);
    /// Largest kinematic residual (m/s) of slips `s` and displacements `u`.
    fn residual(&self, s: &[f64], u: &[f64], xi: f64) -> f64;
    /// The longitudinal force of the tractions (N).
    fn force(&self, p: &[f64]) -> f64;
}

/// The loop's constants for one step.
pub(crate) struct Settings {
    /// Anderson depth (previous iterates kept).
    pub depth: usize,
    /// Most sweeps before giving up.
    pub max_sweeps: usize,
    /// Tolerance on the kinematic residual (m/s).
    pub tol: f64,
    /// Tolerance on the force residual |F - F_x| / (mu N).
    pub force_tol: f64,
    /// Prescribed F_x (N).
    pub force_x: f64,
    /// Whether the creepage is prescribed instead: it stays at the start's
    /// and the force is not a condition (`force_x` unused).
    pub creepage_prescribed: bool,
    /// mu N (N), the force scale.
    pub mu_n: f64,
    /// dF_x / dxi_x estimate (N), negative.
    pub kappa: f64,
    /// Traction scale (Pa), mu p3 max.
    pub p_scale: f64,
    /// Creepage scale: the traction it moves over the traction scale.
    pub xi_scale: f64,
}

/// A converged solve.
pub(crate) struct Solved {
    /// Tractions (Pa), interleaved.
    pub p: Vec<f64>,
    /// Slips (m/s), interleaved.
    pub s: Vec<f64>,
    /// Creepage xi_x.
    pub xi: f64,
    /// Displacements of an exact product (m), in the discretisation's layout.
    pub u: Vec<f64>,
    /// Sweeps done.
    pub sweeps: usize,
}

/// Solves from the tractions `p`, slips `s` and creepage `xi`; `fresh(p,
/// u)` computes `u = K p` exactly. Err holds the largest kinematic residual
/// (m/s) of every sweep.
pub(crate) fn solve(
    sw: &impl Sweeper,
    set: &Settings,
    mut p: Vec<f64>,
    mut s: Vec<f64>,
    xi: f64,
    fresh: &mut dyn FnMut(&[f64], &mut [f64]),
) -> Result<Solved, Vec<f64>> {
    let m = p.len();
    let mut u = vec![0.0; m];
    fresh(&p, &mut u);
    let (p_scale, xi_scale) = (set.p_scale, set.xi_scale);
    let pack = |p: &[f64], xi: f64| -> DVector<f64> {
        DVector::from_iterator(m + 1, p.iter().map(|v| v / p_scale).chain(std::iter::once(xi * xi_scale)))
    };
    let mut xi = xi;
    let mut anderson = Anderson::new(set.depth);
    let mut history = Vec::new();
    for sweep_no in 0..set.max_sweeps {
        let x = pack(&p, xi);
        sw.sweep(&mut p, &mut s, &mut u, xi);
        let r_max = sw.residual(&s, &u, xi);
        let force = sw.force(&p);
        let r_force = if set.creepage_prescribed { 0.0 } else { (force - set.force_x) / set.mu_n };
        history.push(r_max);
        if !r_max.is_finite() || !r_force.is_finite() {
            return Err(history);
        }
        if r_max < set.tol && r_force.abs() < set.force_tol {
            // The displacements were carried through the mixing (linear in
            // p); the verdict is checked on freshly computed ones.
            fresh(&p, &mut u);
            if sw.residual(&s, &u, xi) < set.tol {
                return Ok(Solved { p, s, xi, u, sweeps: sweep_no + 1 });
            }
        }
        let xi_next = if set.creepage_prescribed { xi } else { xi - (force - set.force_x) / set.kappa };
        let g = pack(&p, xi_next);
        let (mixed, u_mixed) = anderson.mix(&x, &g, DVector::from_column_slice(&u));
        for (pk, v) in p.iter_mut().zip(mixed.iter()) {
            *pk = v * p_scale;
        }
        // (A prescribed creepage is kept exactly: scaling is not.)
        if !set.creepage_prescribed {
            xi = mixed[m] / xi_scale;
        }
        if (sweep_no + 1) % REFRESH == 0 {
            fresh(&p, &mut u);
        } else {
            u.copy_from_slice(u_mixed.as_slice());
        }
    }
    Err(history)
}

/// Anderson mixing (type II) of a fixed-point map, carrying along an
/// auxiliary vector that depends linearly on the iterate (the displacements).
struct Anderson {
    depth: usize,
    /// Last residual f = G(x) - x, G(x) and the auxiliary vector of G(x).
    last: Option<(DVector<f64>, DVector<f64>, DVector<f64>)>,
    /// Differences of successive residuals, G values and auxiliary vectors.
    df: Vec<DVector<f64>>,
    dg: Vec<DVector<f64>>,
    daux: Vec<DVector<f64>>,
}

impl Anderson {
    fn new(depth: usize) -> Self {
        Anderson { depth, last: None, df: Vec::new(), dg: Vec::new(), daux: Vec::new() }
    }

    /// The next iterate from `x`, `g = G(x)` and `aux` (that of g), with its
    /// auxiliary vector.
    fn mix(&mut self, x: &DVector<f64>, g: &DVector<f64>, aux: DVector<f64>) -> (DVector<f64>, DVector<f64>) {
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
        let mut a = Anderson::new(6);
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
