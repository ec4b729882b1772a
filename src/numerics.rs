//! Small numerical helpers shared by the kernels: a Brent root finder with
//! separate tolerances on the unknown and on the residual (wrapping the
//! `roots` crate, whose built-in convergence test uses one tolerance for both),
//! and a number rounded to significant digits for the terminal.

use roots::{Convergency, SearchError, find_root_brent};

/// Convergence test for [`brent`].
#[derive(Debug, Clone, Copy)]
pub struct Tolerance {
    /// Absolute tolerance on the residual.
    pub residual: f64,
    /// Relative tolerance on the unknown.
    pub x_rel: f64,
    /// Absolute tolerance on the unknown.
    pub x_abs: f64,
    /// Maximum number of iterations.
    pub max_iter: usize,
}

impl Convergency<f64> for Tolerance {
    fn is_root_found(&mut self, y: f64) -> bool {
        y.abs() <= self.residual
    }
    fn is_converged(&mut self, x1: f64, x2: f64) -> bool {
        (x1 - x2).abs() <= self.x_abs + self.x_rel * x1.abs().max(x2.abs())
    }
    fn is_iteration_limit_reached(&mut self, iter: usize) -> bool {
        iter >= self.max_iter
    }
}

/// `x` to `digits` significant digits, as a short number (33.3, 120, 10:
/// a wavelength in mm as the terminal writes it).
pub fn round_sig(x: f64, digits: i32) -> f64 {
    if x == 0.0 {
        return 0.0;
    }
    let scale = 10f64.powi(digits - 1 - x.abs().log10().floor() as i32);
    (x * scale).round() / scale
}

/// Brent's method on a bracket `[lo, hi]` (Brent, *Algorithms for
/// Minimization without Derivatives*, 1973, ch. 4).
pub fn brent<F: FnMut(f64) -> f64>(lo: f64, hi: f64, f: F, tol: Tolerance) -> Result<f64, SearchError> {
    let mut tol = tol;
    find_root_brent(lo, hi, f, &mut tol)
}
