//! The friction law of the transient tangential problem, for both
//! transient models and both grids: the traction of a slip, its Jacobian,
//! the element problem of a Gauss-Seidel sweep, and the stick test.
//!
//! * The paper's regularised Coulomb law (Baeza et al. 2008, Eq. 6):
//!   `p = -(2/pi) atan(|s|/eps) mu p3 s/|s|`, smooth, with the convex
//!   potential `Phi(s) = mu p3 (2/pi) (q atan(q/eps) - eps/2 ln(1 +
//!   q^2/eps^2))`, `q = |s|`, `p = -grad Phi`.
//! * Exact Coulomb friction, CONTACT's law (Kalker 1990, ch. 5): `|p| <= mu
//!   p3`, `s = 0` where `|p| < mu p3` (stick), `p = -mu p3 s/|s|` where
//!   `s != 0` (slip).
//!
//! The element problem `s = s0 + K p(s)` (the element's own 2 x 2
//! flexibility `K`, the others' tractions held) minimises a strictly convex
//! energy under either law and is solved to rounding ([`local_solve`],
//! [`coulomb_local`]).
//!
//! Either law may take a friction coefficient that varies with the slip
//! speed ([`Characteristic`]: `mu p3` is then the bound at zero slip and
//! `mu(|s|) p3 = mu p3 r(|s|)` the slip's): the regularised law `p = -(2/pi)
//! atan(|s|/eps) mu p3 r(|s|) s/|s|`, Coulomb's `|p| <= mu p3` in stick and
//! `p = -mu p3 r(|s|) s/|s|` in slip. A falling characteristic can make the
//! element problem non-convex ([`varying`]): the element then takes the
//! state of least energy. With friction memory ([`memory`], CONTACT's) an
//! element's coefficient within a step also depends on what its material
//! kept from the step before ([`Local`]); the element problems take it as
//! they take any characteristic.

pub mod characteristic;
pub mod memory;
pub mod varying;

pub use characteristic::Characteristic;
pub use memory::{FrictionMemory, Local, Memory};
pub use varying::{coulomb_local_with, local_solve_with, regularised_slip_with, regularised_with};

use crate::numerics::{Tolerance, brent};
use std::f64::consts::PI;

/// An element counts as stick when its slip speed is below this many eps
/// (its traction is then below (2/pi) atan(10) = 94 % of mu p3).
pub const STICK_SLIP_FACTOR: f64 = 10.0;

/// The friction law of a tangential problem, with its parameter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Law {
    /// The regularised Coulomb law with velocity `eps` (m/s).
    Regularised {
        /// Regularisation velocity (m/s).
        eps: f64,
    },
    /// Exact Coulomb friction.
    Coulomb,
}

impl Law {
    /// The traction of slip `s` (Coulomb: the slip direction's bound, zero
    /// for zero slip) with the bound `mu p3` at zero slip and the
    /// characteristic `ch`.
    pub fn traction(self, s: [f64; 2], mu_p3: f64, ch: impl Into<Local>) -> [f64; 2] {
        let ch = ch.into();
        match self {
            Law::Regularised { eps } => regularised_with(s, mu_p3, eps, ch).0,
            Law::Coulomb => {
                let q = s[0].hypot(s[1]);
                let g = mu_p3 * ch.ratio(q).0;
                if q == 0.0 { [0.0; 2] } else { [-g * s[0] / q, -g * s[1] / q] }
            }
        }
    }

    /// Solves the element problem `s = s0 + K p(s)` (`k` = `K`'s `(xx, xy,
    /// yy)`), from `start` (the regularised law's Newton start); returns the
    /// slip and its traction.
    pub fn element_solve(
        self,
        s0: [f64; 2],
        k: [f64; 3],
        mu_p3: f64,
        start: [f64; 2],
        ch: impl Into<Local>,
    ) -> ([f64; 2], [f64; 2]) {
        match self {
            Law::Regularised { eps } => local_solve_with(s0, k, mu_p3, eps, start, ch),
            Law::Coulomb => coulomb_local_with(s0, k, mu_p3, ch),
        }
    }

    /// Whether an element with slip `s` is in stick: below
    /// [`STICK_SLIP_FACTOR`] eps for the regularised law, zero slip for
    /// Coulomb.
    pub fn is_stick(self, s: [f64; 2]) -> bool {
        match self {
            Law::Regularised { eps } => s[0].hypot(s[1]) < STICK_SLIP_FACTOR * eps,
            Law::Coulomb => s[0] == 0.0 && s[1] == 0.0,
        }
    }
}

/// The friction law a config names (`contact.friction_law`), without its
/// parameter.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, strum::EnumString, strum::IntoStaticStr, strum::VariantNames)]
#[strum(serialize_all = "kebab-case")]
pub enum FrictionLaw {
    /// The paper's regularised Coulomb law (Eq. 6), with `contact.regularisation`.
    #[default]
    Regularised,
    /// Exact Coulomb friction (CONTACT's law).
    Coulomb,
}

impl FrictionLaw {
    /// Config name (`contact.friction_law`).
    pub fn name(self) -> &'static str {
        self.into()
    }
}

impl FrictionLaw {
    /// The law with regularisation velocity `eps` (m/s) where it has one.
    pub fn with(self, eps: f64) -> Law {
        match self {
            FrictionLaw::Regularised => Law::Regularised { eps },
            FrictionLaw::Coulomb => Law::Coulomb,
        }
    }
}

/// The friction law p = -mu p3 f(|s|) s with f(q) = (2/pi) atan(q/eps) / q,
/// and its Jacobian D = -dp/ds = mu p3 (f I + f'(q)/q s s^T).
pub fn regularised(s: [f64; 2], mu_p3: f64, eps: f64) -> ([f64; 2], [f64; 3]) {
    // |s| without hypot's overflow guard (slips stay far from 1e150 m/s).
    let q = (s[0] * s[0] + s[1] * s[1]).sqrt();
    let z = q / eps;
    let (f, fp_over_q) = if z < 1e-4 {
        // Series: f = 2/(pi eps) (1 - z^2/3), f'/q = -4/(3 pi eps^3).
        (2.0 / (PI * eps) * (1.0 - z * z / 3.0), -4.0 / (3.0 * PI * eps.powi(3)))
    } else {
        let g = 2.0 / PI * z.atan();
        let gp = 2.0 / (PI * eps) / (1.0 + z * z);
        (g / q, (gp * q - g) / (q * q * q))
    };
    let p = [-mu_p3 * f * s[0], -mu_p3 * f * s[1]];
    let d =
        [mu_p3 * (f + fp_over_q * s[0] * s[0]), mu_p3 * fp_over_q * s[0] * s[1], mu_p3 * (f + fp_over_q * s[1] * s[1])];
    (p, d)
}

/// The inverse of a symmetric 2 x 2 block `(xx, xy, yy)`.
pub fn symmetric_inverse(k: [f64; 3]) -> [f64; 3] {
    let det = k[0] * k[2] - k[1] * k[1];
    [k[2] / det, -k[1] / det, k[0] / det]
}

/// The share of its bound `mu p3` below which the regularised law's
/// traction is in the stick regime: `(2/pi) atan(10)`, the traction of a
/// slip of [`STICK_SLIP_FACTOR`] eps.
pub fn stick_traction_share() -> f64 {
    2.0 / PI * STICK_SLIP_FACTOR.atan()
}

/// The regularised law inverted: the slip of traction `p` (|p| < `mu_p3`),
/// `eps tan(pi |p| / (2 mu p3))` against `p`.
pub fn regularised_slip(p: [f64; 2], mu_p3: f64, eps: f64) -> [f64; 2] {
    let pm = p[0].hypot(p[1]);
    if pm == 0.0 {
        return [0.0; 2];
    }
    let q = eps * (0.5 * PI * pm / mu_p3).tan();
    [-q * p[0] / pm, -q * p[1] / pm]
}

/// An element's slip (m/s) and traction (Pa).
pub(crate) type SlipTraction = ([f64; 2], [f64; 2]);

/// Newton on the element problem `s = s0 + K p(s)` (`law(s)` = the
/// traction and `D = -dp/ds`; the Hessian `K^-1 + D` positive definite)
/// from `start`, while each full step halves |grad E| (`grad E = K^-1 (s -
/// s0) - p`), which is what happens near the solution. Ok: the converged
/// slip and traction; Err: the last accepted iterate's, where a step did
/// not halve it (the caller's 1-D form takes over).
pub(crate) fn element_newton(
    s0: [f64; 2],
    k: [f64; 3],
    start: [f64; 2],
    law: impl Fn([f64; 2]) -> ([f64; 2], [f64; 3]),
) -> Result<SlipTraction, SlipTraction> {
    let norm = |v: [f64; 2]| (v[0] * v[0] + v[1] * v[1]).sqrt();
    let kinv = symmetric_inverse(k);
    let grad = |s: [f64; 2]| {
        let (p, d) = law(s);
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
            return Ok((s, p));
        }
        let trial = [s[0] + step[0], s[1] + step[1]];
        let (gt, pt, dt) = grad(trial);
        if norm(gt) > 0.5 * norm(g) {
            break;
        }
        (s, g, p, d) = (trial, gt, pt, dt);
        // A full step this small leaves an error ~ its square: done.
        if size <= 1e-8 * scale {
            return Ok((s, p));
        }
    }
    Err((s, p))
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
pub fn local_solve(s0: [f64; 2], k: [f64; 3], mu_p3: f64, eps: f64, start: [f64; 2]) -> ([f64; 2], [f64; 2]) {
    let norm = |v: [f64; 2]| (v[0] * v[0] + v[1] * v[1]).sqrt();
    let q0 = norm(s0);
    if mu_p3 <= 0.0 || q0 == 0.0 {
        return (s0, [0.0; 2]);
    }
    let (s, p) = match element_newton(s0, k, start, |s| regularised(s, mu_p3, eps)) {
        Ok(done) => return done,
        Err(last) => last,
    };
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
    (s, regularised(s, mu_p3, eps).0)
}

/// Solves the element problem `s = s0 + K p` under exact Coulomb friction
/// for the 2 x 2 symmetric positive definite `K = [k0 k1; k1 k2]` and the
/// bound `mu p3`. Stick (`s = 0`) when the traction that cancels `s0`,
/// `-K^-1 s0`, lies within the bound; otherwise slip with `p = -mu p3
/// s/|s|`, so `s = (I + c K)^-1 s0` with `c = mu p3 / q`, `q = |s|`, and `q`
/// the root of `q - |(I + (mu p3/q) K)^-1 s0|`, which is negative near 0
/// (the stick traction exceeds the bound) and positive at `|s0|`.
pub fn coulomb_local(s0: [f64; 2], k: [f64; 3], mu_p3: f64) -> ([f64; 2], [f64; 2]) {
    let det = k[0] * k[2] - k[1] * k[1];
    let p_stick = [-(k[2] * s0[0] - k[1] * s0[1]) / det, -(k[0] * s0[1] - k[1] * s0[0]) / det];
    if p_stick[0].hypot(p_stick[1]) <= mu_p3 {
        return ([0.0; 2], p_stick);
    }
    let shrink = |q: f64| {
        let c = mu_p3 / q;
        let m = [1.0 + c * k[0], c * k[1], 1.0 + c * k[2]];
        let mdet = m[0] * m[2] - m[1] * m[1];
        [(m[2] * s0[0] - m[1] * s0[1]) / mdet, (m[0] * s0[1] - m[1] * s0[0]) / mdet]
    };
    let q0 = s0[0].hypot(s0[1]);
    // Isotropic K: q = |s0| - mu p3 k exactly.
    if k[1] == 0.0 && k[0] == k[2] {
        let q = q0 - mu_p3 * k[0];
        let s = [s0[0] * q / q0, s0[1] * q / q0];
        return (s, [-mu_p3 * s0[0] / q0, -mu_p3 * s0[1] / q0]);
    }
    let r = |t: f64| {
        let q = t.exp();
        let v = shrink(q);
        1.0 - v[0].hypot(v[1]) / q
    };
    let tol = Tolerance { residual: 1e-16, x_rel: 1e-15, x_abs: 1e-15, max_iter: 200 };
    // The root lies in (0, |s0|): bracket from below by halving.
    let (mut lo, hi) = ((q0 * 1e-3).ln(), q0.ln());
    while r(lo) > 0.0 && lo > hi - 200.0 {
        lo -= 7.0;
    }
    let t = brent(lo, hi, r, tol).unwrap_or(hi);
    let s = shrink(t.exp());
    let q = s[0].hypot(s[1]);
    (s, [-mu_p3 * s[0] / q, -mu_p3 * s[1] / q])
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
            let (law, _) = regularised(s, mu_p3, eps);
            prop_assert_eq!(law, p);
            prop_assert!(p[0].hypot(p[1]) < mu_p3);
        }
    }

    proptest! {
        /// The Coulomb element problem: s = s0 + K p with |p| <= mu p3, s = 0
        /// or p = -mu p3 s/|s|, solved to rounding.
        #[test]
        fn coulomb_local_satisfies_the_element_problem(
            log_s0 in -6.0f64..1.0,
            angle in 0.0f64..std::f64::consts::TAU,
            log_k in -11.0f64..-8.0,
            anisotropy in 0.6f64..1.6,
            coupling in -0.2f64..0.2,
            log_mu_p3 in 5.0f64..9.0,
        ) {
            let mu_p3 = 10f64.powf(log_mu_p3);
            let m = 10f64.powf(log_s0);
            let s0 = [m * angle.cos(), m * angle.sin()];
            let k0 = 10f64.powf(log_k);
            let k = [k0, coupling * k0, anisotropy * k0];
            let (s, p) = coulomb_local(s0, k, mu_p3);
            let r = [s[0] - s0[0] - (k[0] * p[0] + k[1] * p[1]), s[1] - s0[1] - (k[1] * p[0] + k[2] * p[1])];
            prop_assert!(r[0].hypot(r[1]) <= 1e-12 * m, "residual {r:?}");
            let (q, pn) = (s[0].hypot(s[1]), p[0].hypot(p[1]));
            prop_assert!(pn <= mu_p3 * (1.0 + 1e-12));
            if q > 0.0 {
                prop_assert!((pn - mu_p3).abs() <= 1e-12 * mu_p3);
                // Traction against the slip.
                prop_assert!((p[0] * s[1] - p[1] * s[0]).abs() <= 1e-9 * pn * q);
                prop_assert!(p[0] * s[0] + p[1] * s[1] < 0.0);
            }
        }
    }
}
