//! Kalker's discrete normal contact problem on the grid, with the normal
//! force prescribed:
//!
//! ```text
//! g_I = h_I + sum_J K_n(I - J) p_J - delta,   p_I >= 0,  g_I >= 0,  p_I g_I = 0,
//! A sum_I p_I = N,
//! ```
//!
//! `h` the undeformed gap at the element centres (an input: the quadratic gap
//! `A x^2 + B y^2` of the curvatures, or any profile), `K_n` the normal
//! influence coefficients ([`super::convolution`]), `delta` the approach and
//! `A` the element area. Solved by the conjugate-gradient method of Polonsky
//! and Keer (*A numerical method for solving rough contact problems based on
//! the multi-level multi-summation and conjugate gradient techniques*, Wear
//! 231 (1999) 206-219), the basis of Vollebregt's NormCG in CONTACT:
//! conjugate gradients on the elements in contact with the load kept by the
//! mean gap (the approach is its Lagrange multiplier), pressures clipped at
//! zero, and elements that penetrate re-admitted with a restart of the
//! conjugate directions. Every product with `K_n` is an FFT convolution.
//!
//! **Preconditioner** (Vollebregt, *A new solver for the elastic normal
//! contact problem using conjugate gradients, deflation, and an FFT-based
//! preconditioner*, J. Comput. Phys. 257 (2014) 333-351): the gap residual
//! on the contact area goes through the inverse of the kernel's circulant
//! on the unpadded grid ([`FftConvolution::circulant_inverse`]) and is made
//! mean-free over the contact area (the force constraint) before it enters
//! the conjugate directions, `z = Pi C^-1 Pi g`. From a cold start on the
//! quadratic gap at 100 kN: 36 / 52 / 75 iterations plain at 0.4 / 0.2 /
//! 0.1 mm, 15 / 15 / 19 preconditioned; warm-started along
//! paper_normal_30mm at 0.2 mm, 43.7 -> 13.8 per step.

use super::convolution::{FftConvolution, FftScratch};
use super::symmetric::{NormalScratch, SymmetricNormal};

/// The products of a normal solve.
#[derive(Debug, Clone, Copy)]
pub enum NormalProducts<'a> {
    /// Any gap: `K_n p` and the preconditioner (`None`: Polonsky and
    /// Keer's plain iteration).
    Full(&'a FftConvolution, Option<&'a FftConvolution>),
    /// A gap symmetric about the grid's centre line: the products of
    /// symmetric pressures ([`SymmetricNormal`], about two thirds of the
    /// cost) and their preconditioner; the start is made symmetric.
    Symmetric(&'a SymmetricNormal, &'a SymmetricNormal),
}

/// Relative change of the pressure (sum |dp| / sum p) below which the
/// iteration counts as stalled (its conjugate directions are restarted when
/// complementarity is not yet met).
pub const NORMAL_TOLERANCE: f64 = 1e-12;

/// Complementarity tolerance, relative to the approach: the gap varies by
/// less than this over the contact area and nowhere outside it is the
/// surface penetrated by more.
pub const GAP_TOLERANCE: f64 = 1e-10;

/// Iterations after which `u = K_n p`, updated step by step, is
/// recomputed from the pressure (bounds the rounding drift).
const REFRESH: usize = 25;

/// Iterations after which the normal solve gives up.
const MAX_ITERATIONS: usize = 2000;

/// The solution of one normal problem.
#[derive(Debug, Clone, PartialEq)]
pub struct NormalSolution {
    /// Pressure on every grid element (Pa).
    pub pressure: Vec<f64>,
    /// Approach of distant points (m).
    pub approach: f64,
    /// Conjugate-gradient iterations.
    pub iterations: usize,
}

/// Why a normal solve failed.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum NormalError {
    /// The iteration did not reach the tolerance.
    #[error(
        "normal problem (N = {force:.6e} N) not converged in {iterations} iterations: complementarity not met to {tolerance:.1e} of the approach (last relative pressure change {change:.3e})"
    )]
    NoConvergence {
        /// Normal force (N).
        force: f64,
        /// Iterations done.
        iterations: usize,
        /// Last relative pressure change.
        change: f64,
        /// The tolerance.
        tolerance: f64,
    },
    /// No element has a negative gap relative to the others: nothing to load.
    #[error("normal problem (N = {0:.6e} N): the force must be positive and finite")]
    BadForce(f64),
}

/// Solves the normal problem with the products `products` for
/// the gap `h` (m, on every element), element
/// area `area` (m^2) and force `force` (N), from the pressure `start` (any
/// non-negative field; scaled to the force) or, without one, from a uniform
/// pressure where `h` is below its mean.
pub fn solve(
    products: NormalProducts,
    scratch: &mut FftScratch,
    h: &[f64],
    area: f64,
    force: f64,
    start: Option<&[f64]>,
) -> Result<NormalSolution, NormalError> {
    if !(force > 0.0 && force.is_finite()) {
        return Err(NormalError::BadForce(force));
    }
    let n = h.len();
    let mut p: Vec<f64> = match start {
        Some(s) if s.iter().any(|v| *v > 0.0) => s.iter().map(|v| v.max(0.0)).collect(),
        _ => {
            let mean = h.iter().sum::<f64>() / n as f64;
            h.iter().map(|v| if *v <= mean { 1.0 } else { 0.0 }).collect()
        }
    };
    let mut ops = Ops { products, full: scratch, symmetric: NormalScratch::default() };
    // A symmetric problem runs its loops over the lower half of the grid
    // (`m` elements, each standing for itself and its mirror image: weight
    // 2, the middle row of an odd grid 1), the products reading that half.
    let weight = match products {
        NormalProducts::Symmetric(conv, _) => {
            conv.symmetrize(&mut p);
            conv.lower_half_weights()
        }
        NormalProducts::Full(..) => vec![1.0; n],
    };
    let m = weight.len();
    let w = &weight;
    let rescale = |p: &mut [f64]| {
        let total = area * (0..m).map(|k| w[k] * p[k]).sum::<f64>();
        p[..m].iter_mut().for_each(|v| *v *= force / total);
    };
    rescale(&mut p);
    let (mut u, mut r, mut t) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let (mut g, mut p_old) = (vec![0.0; n], vec![0.0; n]);
    let (mut gc, mut z) = (vec![0.0; n], vec![0.0; n]);
    let (mut conjugate, mut g_old) = (false, 1.0);
    let mut change = f64::INFINITY;
    // `u = K_n p` is kept up to date by the step's own product where the
    // step is linear (no element clipped or readmitted): one product per
    // iteration instead of two. It is recomputed from `p` after a nonlinear
    // step, every REFRESH iterations, and before the verdict is accepted
    // (`updated` counts the steps since the last exact product).
    let mut updated = 0usize;
    for it in 0..MAX_ITERATIONS {
        let exact = updated == 0 || updated >= REFRESH;
        if exact {
            ops.product(&p, &mut u);
            updated = 0;
        }
        let (mut sum, mut count) = (0.0, 0.0);
        for k in 0..m {
            g[k] = u[k] + h[k];
            if p[k] > 0.0 {
                sum += w[k] * g[k];
                count += w[k];
            }
        }
        let count = f64::max(count, 1.0);
        let g_mean = sum / count;
        // The verdict is complementarity itself: the gap uniform over the
        // contact area and open outside it, to GAP_TOLERANCE of the approach.
        let tol_gap = GAP_TOLERANCE * g_mean.abs().max(f64::MIN_POSITIVE);
        // The gap relative to its mean over the contact area (the residual),
        // its spread there and the penetration outside, in one pass.
        let (mut spread, mut penetration, mut big_g) = (0.0f64, 0.0f64, 0.0f64);
        for k in 0..m {
            let d = g[k] - g_mean;
            g[k] = d;
            if p[k] > 0.0 {
                spread = spread.max(d.abs());
                big_g += w[k] * d * d;
            } else {
                penetration = penetration.max(-d);
            }
        }
        if spread <= tol_gap && penetration <= tol_gap {
            if exact {
                if let NormalProducts::Symmetric(conv, _) = products {
                    conv.mirror_lower(&mut p);
                }
                return Ok(NormalSolution { pressure: p, approach: g_mean, iterations: it });
            }
            // Converged on the updated product: check on an exact one.
            updated = 0;
            continue;
        }
        if change < NORMAL_TOLERANCE {
            // Stalled short of complementarity: restart the directions.
            conjugate = false;
        }
        // The preconditioned residual on the contact area, mean-free (the
        // force constraint): z = Pi C^-1 Pi g.
        let big_g = match ops.preconditioned() {
            false => {
                z[..m].copy_from_slice(&g[..m]);
                big_g
            }
            true => {
                for k in 0..m {
                    gc[k] = if p[k] > 0.0 { g[k] } else { 0.0 };
                }
                ops.precondition(&gc, &mut z);
                let z_mean = (0..m).filter(|&k| p[k] > 0.0).map(|k| w[k] * z[k]).sum::<f64>() / count;
                let mut gz = 0.0;
                for k in 0..m {
                    z[k] = if p[k] > 0.0 { z[k] - z_mean } else { 0.0 };
                    gz += w[k] * gc[k] * z[k];
                }
                gz
            }
        };
        let beta = if conjugate { big_g / g_old } else { 0.0 };
        let mut gt = 0.0;
        for k in 0..m {
            t[k] = if p[k] > 0.0 { z[k] + beta * t[k] } else { 0.0 };
            gt += w[k] * g[k] * t[k];
        }
        g_old = big_g;
        ops.product(&t, &mut r);
        let r_mean = (0..m).filter(|&k| p[k] > 0.0).map(|k| w[k] * r[k]).sum::<f64>() / count;
        let rt: f64 = (0..m).filter(|&k| p[k] > 0.0).map(|k| w[k] * (r[k] - r_mean) * t[k]).sum();
        let tau = if rt > 0.0 { gt / rt } else { 0.0 };
        p_old[..m].copy_from_slice(&p[..m]);
        let (mut readmitted, mut clipped, mut total) = (false, false, 0.0);
        for k in 0..m {
            if p[k] > 0.0 {
                let v = p[k] - tau * t[k];
                clipped |= v <= 0.0;
                p[k] = v.max(0.0);
            }
            if p[k] == 0.0 && g[k] < 0.0 && tau > 0.0 {
                // Penetrates: back into contact, steepest descent.
                p[k] = -tau * g[k];
                readmitted = true;
            }
            total += w[k] * p[k];
        }
        conjugate = !readmitted;
        let scale = force / (area * total);
        let linear = !(clipped || readmitted);
        let (mut moved, mut sum_p) = (0.0, 0.0);
        for k in 0..m {
            p[k] *= scale;
            moved += w[k] * (p[k] - p_old[k]).abs();
            sum_p += w[k] * p[k];
            if linear {
                // Linear step: K_n p_new = scale (u - tau K_n t).
                u[k] = scale * (u[k] - tau * r[k]);
            }
        }
        updated = if linear { updated + 1 } else { 0 };
        change = moved / sum_p;
    }
    Err(NormalError::NoConvergence { force, iterations: MAX_ITERATIONS, change, tolerance: GAP_TOLERANCE })
}

/// The products of one solve and their work buffers.
struct Ops<'a> {
    products: NormalProducts<'a>,
    full: &'a mut FftScratch,
    symmetric: NormalScratch,
}

impl Ops<'_> {
    /// `u = K_n p`.
    fn product(&mut self, p: &[f64], u: &mut [f64]) {
        match self.products {
            NormalProducts::Full(conv, _) => conv.normal(self.full, p, u),
            NormalProducts::Symmetric(conv, _) => conv.normal_lower(&mut self.symmetric, p, u),
        }
    }

    fn preconditioned(&self) -> bool {
        !matches!(self.products, NormalProducts::Full(_, None))
    }

    /// `z = C^-1 g` by the preconditioner.
    fn precondition(&mut self, g: &[f64], z: &mut [f64]) {
        match self.products {
            NormalProducts::Full(_, Some(pre)) => pre.normal(self.full, g, z),
            NormalProducts::Full(_, None) => z.copy_from_slice(g),
            NormalProducts::Symmetric(_, pre) => pre.normal_lower(&mut self.symmetric, g, z),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::PotentialGrid;
    use super::super::convolution::ToeplitzKernel;
    use super::*;
    use crate::hertz::{Curvatures, Elastic, HertzShape};

    #[test]
    fn complementarity_and_force_balance() {
        let el = Elastic { young_modulus: 2.1e11, poisson_ratio: 0.3 };
        let curv = Curvatures { a: 1.0, b: 0.444 };
        let shape = HertzShape::new(curv, el).unwrap();
        let hz = shape.patch(1e5).unwrap();
        let grid = PotentialGrid::covering(hz.a, hz.b, (5e-4, 1e-3), 2, Default::default(), Default::default());
        let kernel = ToeplitzKernel::normal(&grid, el.shear_modulus(), el.poisson_ratio);
        let conv = FftConvolution::new(&kernel);
        let (xs, ys) = grid.centres();
        let h: Vec<f64> = xs.iter().zip(&ys).map(|(x, y)| curv.a * x * x + curv.b * y * y).collect();
        let mut s = FftScratch::default();
        let sol = solve(NormalProducts::Full(&conv, None), &mut s, &h, grid.area(), 1e5, None).unwrap();
        let total: f64 = sol.pressure.iter().sum::<f64>() * grid.area();
        assert!((total - 1e5).abs() < 1e-9 * 1e5);
        let mut u = vec![0.0; grid.len()];
        kernel.normal_direct(&sol.pressure, &mut u);
        let scale = sol.approach;
        for k in 0..grid.len() {
            let gap = h[k] + u[k] - sol.approach;
            assert!(sol.pressure[k] >= 0.0);
            if sol.pressure[k] > 0.0 {
                assert!(gap.abs() < 1e-8 * scale, "gap {gap} in contact at {k}");
            } else {
                assert!(gap > -1e-8 * scale, "penetration {gap} at {k}");
            }
        }
        // The same problem on the lower half with the symmetric products,
        // on grids with an even and an odd number of rows: the same
        // pressure (1e-8 of its largest) and approach (1e-9).
        for cell in [(5e-4, 1e-3), (5e-4, 0.95e-3)] {
            let grid = PotentialGrid::covering(hz.a, hz.b, cell, 2, Default::default(), Default::default());
            let kernel = ToeplitzKernel::normal(&grid, el.shear_modulus(), el.poisson_ratio);
            let (xs, ys) = grid.centres();
            let h: Vec<f64> = xs.iter().zip(&ys).map(|(x, y)| curv.a * x * x + curv.b * y * y).collect();
            let (conv, pre) = (FftConvolution::new(&kernel), FftConvolution::circulant_inverse(&kernel));
            let full = solve(NormalProducts::Full(&conv, Some(&pre)), &mut s, &h, grid.area(), 1e5, None).unwrap();
            let (sym, sym_pre) = (SymmetricNormal::padded(&kernel), SymmetricNormal::circulant_inverse(&kernel));
            let half = solve(NormalProducts::Symmetric(&sym, &sym_pre), &mut s, &h, grid.area(), 1e5, None).unwrap();
            let p_max = full.pressure.iter().fold(0.0f64, |m, v| m.max(*v));
            let dp = full.pressure.iter().zip(&half.pressure).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            assert!(dp < 1e-8 * p_max, "{} rows: {dp:e} of {p_max:e}", grid.ny);
            assert!((full.approach - half.approach).abs() < 1e-9 * full.approach.abs(), "{} rows", grid.ny);
        }
        // Warm start from the solution: converged at once.
        let again =
            solve(NormalProducts::Full(&conv, None), &mut s, &h, grid.area(), 1e5, Some(&sol.pressure)).unwrap();
        assert!(again.iterations <= 2, "{}", again.iterations);
    }
}
