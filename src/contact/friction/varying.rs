//! The friction laws with a friction coefficient that varies with the slip
//! speed ([`super::Characteristic`], with or without memory: [`super::Local`]),
//! and their element problems.
//!
//! The regularised law `p = -mu p3 r(q) h(q) s/q`, `h = (2/pi) atan(q/eps)`,
//! `q = |s|`, has the Jacobian `D = -dp/ds = mu p3 (f I + f' q u u^T)`, `f =
//! r h / q`, `u = s/q`: its eigenvalues are `mu p3 f` across the slip and
//! `mu p3 (r h)'` along it, negative where the characteristic falls faster
//! than `h` rises. The element problem `s = s0 + K p(s)` is the stationarity
//! of the energy `E(s) = 1/2 (s - s0)^T K^-1 (s - s0) + Phi(|s|)`, `Phi(q) =
//! mu p3 int_0^q r h` (Coulomb: `mu p3 int_0^q r`, plus the stick `s = 0`
//! where `|K^-1 s0| <= mu p3`), whose Hessian `K^-1 + D` is positive definite
//! wherever `mu p3 K_max sup(-r') < 1` (`K_max` the largest eigenvalue of
//! `K`). Then the solution is unique and found as for constant friction
//! (Newton, then the bracketed 1-D form `q = |(I + c(q) K)^-1 s0|`, `c = mu
//! p3 r h / q`). Otherwise the energy may have two minima (stick and slip,
//! the stick-slip bistability of a falling law): every root of the 1-D form
//! on a scan of 160 points in `ln q` is refined by Brent and the element
//! takes the state of least energy (the global minimum; two roots closer
//! than the scan's spacing, 0.25 in `ln q`, are seen as one or none).
//!
//! With a constant characteristic every function here is the constant law's
//! own ([`super::regularised`], [`super::local_solve`],
//! [`super::coulomb_local`], [`super::regularised_slip`]), bit for bit.

use super::{Local, coulomb_local, element_newton, local_solve, regularised, regularised_slip, symmetric_inverse};
use crate::numerics::{Tolerance, brent};
use crate::quadrature::integrate;
use nalgebra::SMatrix;
use num_complex::Complex64;
use std::f64::consts::PI;

/// Points of the scan for the roots of a non-convex element problem.
const SCAN: usize = 160;

/// Brent's tolerance on `ln q` (q to ~1e-14 relative).
const LN_TOL: Tolerance = Tolerance { residual: 1e-16, x_rel: 1e-15, x_abs: 1e-15, max_iter: 200 };

/// `h(q)/q` and its derivative, `h = (2/pi) atan(q/eps)` (series below
/// `q = 1e-4 eps`).
fn atan_share(q: f64, eps: f64) -> (f64, f64) {
    let z = q / eps;
    if z < 1e-4 {
        (2.0 / (PI * eps) * (1.0 - z * z / 3.0), -4.0 * q / (3.0 * PI * eps.powi(3)))
    } else {
        let g = 2.0 / PI * z.atan();
        let gp = 2.0 / (PI * eps) / (1.0 + z * z);
        (g / q, (gp * q - g) / (q * q))
    }
}

/// The regularised law with the characteristic `ch`: the traction and
/// `D = -dp/ds` (`(xx, xy, yy)`).
pub fn regularised_with(s: [f64; 2], mu_p3: f64, eps: f64, ch: impl Into<Local>) -> ([f64; 2], [f64; 3]) {
    let ch = ch.into();
    if ch.is_constant() {
        return regularised(s, mu_p3, eps);
    }
    law_and_jacobian(s, mu_p3, eps, ch, true)
}

/// A positive definite `D` for the Newton-Krylov solver's compliance: the
/// law's own where the characteristic rises at the slip (`r' >= 0`), else
/// with the coefficient frozen at the slip's (`r'` left out: `r(q)` times
/// the constant law's; a falling law's own `D` can be indefinite along the
/// slip).
pub fn frozen_jacobian(s: [f64; 2], mu_p3: f64, eps: f64, ch: impl Into<Local>) -> [f64; 3] {
    let ch = ch.into();
    if ch.is_constant() {
        return regularised(s, mu_p3, eps).1;
    }
    let rising = ch.ratio((s[0] * s[0] + s[1] * s[1]).sqrt()).1 >= 0.0;
    law_and_jacobian(s, mu_p3, eps, ch, rising).1
}

fn law_and_jacobian(s: [f64; 2], mu_p3: f64, eps: f64, ch: Local, slope: bool) -> ([f64; 2], [f64; 3]) {
    let q = (s[0] * s[0] + s[1] * s[1]).sqrt();
    let (hq, hq_slope) = atan_share(q, eps);
    let (r, rp) = ch.ratio(q);
    let f = r * hq;
    let p = [-mu_p3 * f * s[0], -mu_p3 * f * s[1]];
    if q == 0.0 {
        return (p, [mu_p3 * f, 0.0, mu_p3 * f]);
    }
    // f' q along the slip's direction u.
    let w = (if slope { rp * hq } else { 0.0 } + r * hq_slope) * q;
    let (ux, uy) = (s[0] / q, s[1] / q);
    (p, [mu_p3 * (f + w * ux * ux), mu_p3 * w * ux * uy, mu_p3 * (f + w * uy * uy)])
}

/// The regularised law inverted with the characteristic: the slip of the
/// traction `p` within the stick regime (`|p| < mu p3 r h` at `q = 10
/// eps`), by the fixed point `q = eps tan(pi |p| / (2 mu p3 r(q)))`, which
/// contracts there (`r` changes by `sup|r'| 10 eps` at most).
pub fn regularised_slip_with(p: [f64; 2], mu_p3: f64, eps: f64, ch: impl Into<Local>) -> [f64; 2] {
    let ch = ch.into();
    let start = regularised_slip(p, mu_p3, eps);
    if ch.is_constant() {
        return start;
    }
    let pm = p[0].hypot(p[1]);
    if pm == 0.0 {
        return [0.0; 2];
    }
    let mut q = start[0].hypot(start[1]);
    for _ in 0..100 {
        let next = eps * (0.5 * PI * pm / (mu_p3 * ch.ratio(q).0)).tan();
        let done = (next - q).abs() <= 1e-15 * next;
        q = next;
        if done {
            break;
        }
    }
    [-q * p[0] / pm, -q * p[1] / pm]
}

/// The largest eigenvalue of the symmetric `K = (xx, xy, yy)`.
fn largest_eigenvalue(k: [f64; 3]) -> f64 {
    let (m, d) = (0.5 * (k[0] + k[2]), 0.5 * (k[0] - k[2]));
    m + d.hypot(k[1])
}

/// Whether the element problem's energy is convex (see the module's doc).
fn convex(k: [f64; 3], mu_p3: f64, ch: Local) -> bool {
    mu_p3 * largest_eigenvalue(k) * ch.steepest_fall() < 1.0
}

/// `(I + c K)^-1 s0`.
fn shrink(s0: [f64; 2], k: [f64; 3], c: f64) -> [f64; 2] {
    let m = [1.0 + c * k[0], c * k[1], 1.0 + c * k[2]];
    let mdet = m[0] * m[2] - m[1] * m[1];
    [(m[2] * s0[0] - m[1] * s0[1]) / mdet, (m[0] * s0[1] - m[1] * s0[0]) / mdet]
}

fn norm(v: [f64; 2]) -> f64 {
    (v[0] * v[0] + v[1] * v[1]).sqrt()
}

/// `p^T K p / 2`: the elastic part of the energy at a stationary point
/// (`s - s0 = K p`).
fn elastic_energy(p: [f64; 2], k: [f64; 3]) -> f64 {
    0.5 * (k[0] * p[0] * p[0] + 2.0 * k[1] * p[0] * p[1] + k[2] * p[1] * p[1])
}

/// The roots of `r1` on `[lo, hi]` (in `ln q`): a scan of [`SCAN`] points,
/// each sign change refined by Brent.
fn roots(lo: f64, hi: f64, r1: impl Fn(f64) -> f64) -> Vec<f64> {
    let mut out = Vec::new();
    let t = |i: usize| lo + (hi - lo) * i as f64 / (SCAN - 1) as f64;
    let mut prev = (t(0), r1(t(0)));
    if prev.1 == 0.0 {
        out.push(prev.0);
    }
    for i in 1..SCAN {
        let cur = (t(i), r1(t(i)));
        if cur.1 == 0.0 {
            out.push(cur.0);
        } else if prev.1 * cur.1 < 0.0
            && let Ok(x) = brent(prev.0, cur.0, &r1, LN_TOL)
        {
            out.push(x);
        }
        prev = cur;
    }
    out
}

/// The element problem `s = s0 + K p(s)` of the regularised law with the
/// characteristic `ch` (`local_solve` for a constant one): the slip and its
/// traction.
pub fn local_solve_with(
    s0: [f64; 2],
    k: [f64; 3],
    mu_p3: f64,
    eps: f64,
    start: [f64; 2],
    ch: impl Into<Local>,
) -> ([f64; 2], [f64; 2]) {
    let ch = ch.into();
    if ch.is_constant() {
        return local_solve(s0, k, mu_p3, eps, start);
    }
    let q0 = norm(s0);
    if mu_p3 <= 0.0 || q0 == 0.0 {
        return (s0, [0.0; 2]);
    }
    let law = |s: [f64; 2]| law_and_jacobian(s, mu_p3, eps, ch, true);
    let convex = convex(k, mu_p3, ch);
    // Newton on the convex energy.
    if convex && let Ok(done) = element_newton(s0, k, start, law) {
        return done;
    }
    // The 1-D form: c(q) = mu p3 r(q) h(q)/q <= mu p3 r_max 2/(pi eps).
    let f = |q: f64| ch.ratio(q).0 * atan_share(q, eps).0;
    let at = |q: f64| shrink(s0, k, mu_p3 * f(q));
    let q_lo = norm(shrink(s0, k, mu_p3 * ch.largest() * 2.0 / (PI * eps)));
    let r1 = |t: f64| {
        let q = t.exp();
        1.0 - norm(at(q)) / q
    };
    if q_lo >= q0 {
        return (s0, law(s0).0);
    }
    let ts = if convex {
        if r1(q_lo.ln()) >= -1e-15 {
            vec![q_lo.ln()]
        } else {
            vec![brent(q_lo.ln(), q0.ln(), r1, LN_TOL).unwrap_or(q0.ln())]
        }
    } else {
        roots(q_lo.ln(), q0.ln(), r1)
    };
    // The least energy among the stationary points (one when convex):
    // Phi's differences from the first root by quadrature in ln q.
    let candidates: Vec<([f64; 2], [f64; 2])> = ts
        .iter()
        .map(|t| {
            let s = at(t.exp());
            (s, law(s).0)
        })
        .collect();
    let Some(first) = candidates.first() else {
        // Not reached: r1 <= 0 at q_lo and >= 0 at q0 bracket a root.
        return (s0, law(s0).0);
    };
    let q_first = norm(first.0);
    let phi = |q: f64| {
        if q == q_first {
            return 0.0;
        }
        let density = |t: f64| {
            let v = t.exp();
            vec![SMatrix::<Complex64, 1, 1>::from_element(Complex64::new(mu_p3 * f(v) * v * v, 0.0))]
        };
        let (a, b) = (q_first.ln(), q.ln());
        integrate(density, a.min(b), a.max(b), 8, 1e-12, 100_000)
            .map(|v| v[0][(0, 0)].re * (b - a).signum())
            .unwrap_or(f64::NAN)
    };
    let energy = |c: &([f64; 2], [f64; 2])| elastic_energy(c.1, k) + phi(norm(c.0));
    least(&candidates, energy)
}

/// The candidate of least energy (the first of equals); NaN energies lose.
fn least(candidates: &[([f64; 2], [f64; 2])], energy: impl Fn(&([f64; 2], [f64; 2])) -> f64) -> ([f64; 2], [f64; 2]) {
    if candidates.len() == 1 {
        return candidates[0];
    }
    let mut best = (candidates[0], energy(&candidates[0]));
    for c in &candidates[1..] {
        let e = energy(c);
        if e < best.1 || best.1.is_nan() {
            best = (*c, e);
        }
    }
    best.0
}

/// The element problem under exact Coulomb friction with the
/// characteristic `ch` (`coulomb_local` for a constant one): stick where
/// `|K^-1 s0| <= mu p3` and the energy is convex; otherwise the slip roots
/// of `q = |(I + (mu p3 r(q)/q) K)^-1 s0|`, and where the energy is not
/// convex the least energy among them and the stick.
pub fn coulomb_local_with(s0: [f64; 2], k: [f64; 3], mu_p3: f64, ch: impl Into<Local>) -> ([f64; 2], [f64; 2]) {
    let ch = ch.into();
    if ch.is_constant() {
        return coulomb_local(s0, k, mu_p3);
    }
    let kinv = symmetric_inverse(k);
    let p_stick = [-(kinv[0] * s0[0] + kinv[1] * s0[1]), -(kinv[1] * s0[0] + kinv[2] * s0[1])];
    // The bound in stick, `mu p3 r(0)` (1 without memory).
    let stick_ok = norm(p_stick) <= mu_p3 * ch.ratio(0.0).0;
    let q0 = norm(s0);
    let convex = convex(k, mu_p3, ch);
    if q0 == 0.0 || (stick_ok && convex) {
        return ([0.0; 2], p_stick);
    }
    let at = |q: f64| shrink(s0, k, mu_p3 * ch.ratio(q).0 / q);
    let r1 = |t: f64| {
        let q = t.exp();
        1.0 - norm(at(q)) / q
    };
    let traction = |s: [f64; 2]| {
        let q = norm(s);
        let g = mu_p3 * ch.ratio(q).0;
        [-g * s[0] / q, -g * s[1] / q]
    };
    let hi = q0.ln();
    let ts = if convex {
        let mut lo = (q0 * 1e-3).ln();
        while r1(lo) > 0.0 && lo > hi - 200.0 {
            lo -= 7.0;
        }
        vec![brent(lo, hi, r1, LN_TOL).unwrap_or(hi)]
    } else {
        roots(hi - 40.0, hi, r1)
    };
    let mut candidates: Vec<([f64; 2], [f64; 2])> =
        ts.iter().map(|t| at(t.exp())).filter(|s| norm(*s) > 0.0).map(|s| (s, traction(s))).collect();
    if stick_ok {
        candidates.insert(0, ([0.0; 2], p_stick));
    }
    if candidates.is_empty() {
        // Not reached: without stick, r1 < 0 near q = 0 and > 0 at |s0|.
        return ([0.0; 2], p_stick);
    }
    least(&candidates, |c| elastic_energy(c.1, k) + mu_p3 * ch.integral(norm(c.0)))
}

#[cfg(test)]
mod tests;
