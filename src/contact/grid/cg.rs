//! A Newton-Krylov tangential solver for the fixed grid whose every
//! iteration costs one FFT product (`contact.solver = "cg"`): the step of
//! [`super::tangential`] (same equations, same [`GridStep`], same verdict)
//! solved for the whole contact area at once instead of element by element.
//!
//! **Equations.** With `A = (beta/dt) K` on the elements in contact, the
//! slips `s`, tractions `p` and the creepage `xi` solve
//!
//! ```text
//! G = s - V (w0 + xi e_x) - (beta K p - u~) / dt = 0,   p = law(s),
//! area sum_I w_I p_x,I = F_x,
//! ```
//!
//! with the paper's regularised Coulomb law `p = -(2/pi) atan(|s|/eps)
//! mu p3 s/|s|` (Baeza et al. 2008, Eq. 6). Exact Coulomb friction, with no
//! compliance in stick, as that law's limit ([`COULOMB_LIMIT`]).
//!
//! **Newton step.** Linearised about an iterate that satisfies the law at
//! every element, with `H = (-dp/ds)^-1` the law's compliance (2 x 2 blocks:
//! about `pi eps / (2 mu p3)` in stick; in slip `|s|/(mu p3)` along the
//! traction's tangent and very large along the traction, which the law
//! holds near its bound), the step `dp` and the multiplier `lambda = V
//! dxi` solve the saddle-point system
//!
//! ```text
//! (A + H) dp + e_x lambda = G,    area <e_x, dp>_w = F_x - F,
//! ```
//!
//! symmetric positive definite on the constraint's null space in the inner
//! product `<a, b>_w = sum_I w_I a_I . b_I` (`w_I` = 2 for an element that
//! stands for itself and its mirror on a folded grid): the Hessian of the
//! step's convex complementary energy, the system of Vollebregt's TangCG
//! (Zhao, Vollebregt & Oosterlee, J. Comput. Phys. 288 (2015) 86-100).
//!
//! **Inner solve.** Projected preconditioned conjugate gradients (Gould,
//! Hribar & Nocedal, SIAM J. Sci. Comput. 23 (2001) 1376-1395): the force
//! constraint by projecting the preconditioned residual onto its null
//! space, the multiplier from the residual's component along `e_x`; the
//! preconditioner the FFT inverse of the elastic coupling on the stick
//! area and along the slip elements' tangents, each slip element's own
//! stiff radial direction inverted on its own ([`Preconditioner`]: 58 ->
//! 28 products per step on paper_normal_30mm at 0.2 mm at FORCING 0.05,
//! 27 at 0.1, against each element's own 2 x 2 block of `A + H`,
//! inverted); every product `K dp` by the FFT ([`super::convolution`]),
//! O(N log N). Inexact Newton: each
//! solve to [`FORCING`] of the current largest residual; the force
//! constraint's feasible start `c e_x` takes one product per step.
//!
//! **Update (return mapping).** The law is nearly linear in the traction in
//! stick and in the slip in slip, so an element whose new traction `p +
//! dp` lies in the stick regime takes it (and the law's slip of it); one
//! beyond solves its own element problem `s = s0 + A_II p(s)` exactly for
//! the law (as a Gauss-Seidel sweep does), `s0` the kinematic slip the
//! linearised coupling predicts less its own share. Every iterate then
//! satisfies the law, and only the coupling residual `G` is left to
//! converge. A step not converged in [`MAX_NEWTON`] iterations is reported
//! (the caller hands it to Gauss-Seidel).

use super::tangential::{GridSolution, GridStep, Law, kinematic_residual};
use crate::contact::friction::{
    STICK_SLIP_FACTOR, local_solve_with, regularised_slip_with, regularised_with, stick_traction_share,
    symmetric_inverse as inverse2x2, varying::frozen_jacobian,
};

/// A product on the elements in contact, `(input, output)`: `K p` or the
/// preconditioner's FFT inverse.
type Product<'a> = dyn FnMut(&[f64], &mut [f64]) + 'a;

/// Exact Coulomb friction on this solver: the regularised law at this
/// fraction of the config's eps (1e-10 m/s at the default 1e-5 m/s), to
/// the same kinematic tolerance (1e-2 eps). Its solution is within the
/// tolerance of Gauss-Seidel's exact Coulomb solution: on
/// paper_normal_30mm at 0.4 / 0.2 mm, at 1e-3 / 1e-4 / 1e-5 eps, the
/// creepage within 6.0e-7 / 7.8e-8 / 6.4e-8 (0.4 mm) and 2.2e-7 / 7.1e-8 /
/// 5.8e-8 (0.2 mm) of its largest, the rail's wear within 8.7e-7 / 5.4e-7
/// / 5.6e-7 and 1.8e-6 / 8.7e-7 / 8.5e-7: below 1e-4 eps the difference is
/// the solvers' tolerance, not the law's. (Newton with the exact law's
/// switching between stick, with no compliance, and slip did not converge:
/// 73 of 75 steps of the Fig. 7 loads at 0.4 mm.)
pub const COULOMB_LIMIT: f64 = 1e-5;

/// Largest Newton iterations of a step.
pub const MAX_NEWTON: usize = 30;

/// Largest CG iterations of one Newton solve.
const MAX_CG: usize = 200;

/// The inner solve's target: this fraction of the current largest residual
/// (with the FFT preconditioner, 0.005 / 0.02 / 0.05 / 0.1 / 0.2 take 33.0
/// / 30.1 / 28.1 / 26.6 / 25.3 products per step on paper_normal_30mm at
/// 0.2 mm, 5.06 / 4.79 / 4.60 / 4.54 / 4.46 s wall; with the element
/// blocks alone 57-73, 0.02-0.05 the fewest).
pub const FORCING: f64 = 0.1;

/// Why the Newton-Krylov solve stopped without a solution.
#[derive(Debug, Clone, PartialEq)]
pub enum CgFailure {
    /// Exact Coulomb friction passed as such: the caller gives the
    /// regularised law's limit instead ([`COULOMB_LIMIT`]).
    Coulomb,
    /// Not converged.
    NoConvergence {
        /// The largest kinematic residual (m/s) after each Newton
        /// iteration.
        history: Vec<f64>,
        /// FFT products used.
        products: usize,
    },
}

/// An iterate: slips and tractions that satisfy the law element by
/// element, their displacements, and the residuals of the coupling.
struct State {
    /// Slips (m/s), interleaved.
    s: Vec<f64>,
    /// Tractions (Pa), interleaved.
    p: Vec<f64>,
    /// Creepage.
    xi: f64,
    /// `K p` (m), x block then y block.
    u: Vec<f64>,
    /// Kinematic residual `G = s - s_kin` (m/s), interleaved.
    g: Vec<f64>,
    /// Largest |G| (m/s).
    r_max: f64,
    /// F - F_x (N).
    f_res: f64,
}

/// Solves the step from the warm start (slips `s`, creepage `xi`) as
/// [`super::tangential::solve`] does, for the regularised law. `fresh(p, u)`
/// computes `u = K p` at the elements in contact (x block then y block) for
/// the residuals; `inner` the same in single precision for the Newton
/// systems (solved to [`FORCING`] of the residual, far above its
/// rounding); `inverse(r, z)` the preconditioner's FFT inverse
/// (interleaved). The returned solution's `sweeps` counts the products
/// `K p` of both precisions.
pub fn solve(
    st: &GridStep,
    s: &[f64],
    p0: &[f64],
    xi: f64,
    fresh: &mut Product,
    (inner, inverse): (&mut Product, &mut Product),
) -> Result<GridSolution, CgFailure> {
    let Law::Regularised { eps } = st.law else {
        return Err(CgFailure::Coulomb);
    };
    let n = st.set.len();
    let mut products = 0;
    let own: Vec<[f64; 3]> = (0..n).map(|c| st.coupling.own(st.set.iy[c]).map(|v| st.beta / st.dt * v)).collect();
    // The warm start: a sliding element (|s| >= 10 eps) keeps its slip and
    // takes the law's traction; one in stick keeps its traction (within
    // the stick regime of the new bound) and takes the law's slip.
    let (mut s, mut p) = (s.to_vec(), vec![0.0; 2 * n]);
    for c in 0..n {
        let ch = st.local(c);
        let theta = stick_traction_share() * ch.ratio(STICK_SLIP_FACTOR * eps).0;
        let (i, j) = (2 * c, 2 * c + 1);
        let g = st.mu_p3[c];
        let q = s[i].hypot(s[j]);
        if q >= STICK_SLIP_FACTOR * eps {
            let pc = regularised_with([s[i], s[j]], g, eps, ch).0;
            (p[i], p[j]) = (pc[0], pc[1]);
        } else {
            let pm = p0[i].hypot(p0[j]);
            let cut = if pm > theta * g { theta * g / pm } else { 1.0 };
            let pc = [cut * p0[i], cut * p0[j]];
            let sc = regularised_slip_with(pc, g, eps, ch);
            (s[i], s[j], p[i], p[j]) = (sc[0], sc[1], pc[0], pc[1]);
        }
    }
    let mut state = evaluate(st, s, p, xi, fresh, &mut products);
    let mut history = Vec::new();
    // `A e` (m/s per Pa, interleaved), the feasible starts' product, once
    // per step.
    let mut ae = None;
    for _ in 0..MAX_NEWTON {
        if !state.r_max.is_finite() || !state.f_res.is_finite() {
            break;
        }
        if state.r_max < st.tol && (st.creepage_prescribed || (state.f_res / st.mu_n).abs() < st.force_tol) {
            let State { p, s, xi, u, .. } = state;
            return Ok(GridSolution { p, s, xi, u, sweeps: products });
        }
        // H = (-dp/ds)^-1, the law's compliance (the coefficient frozen at
        // the iterate's slip speed: a falling law's own is indefinite along
        // the slip; the update below keeps the law exact).
        let h: Vec<[f64; 3]> = (0..n)
            .map(|c| inverse2x2(frozen_jacobian([state.s[2 * c], state.s[2 * c + 1]], st.mu_p3[c], eps, st.local(c))))
            .collect();
        let target = (FORCING * state.r_max).max(0.3 * st.tol);
        let pre = Preconditioner::new(st, eps, &own, &h, &state.s);
        let (dp, adp, lambda) =
            newton_system(st, (&h, &pre), &state, target, &mut ae, (&mut *inner, &mut *inverse), &mut products);
        state = correct(st, eps, &own, &state, (&dp, &adp, lambda), fresh, &mut products);
        history.push(state.r_max);
    }
    Err(CgFailure::NoConvergence { history, products })
}

/// The next iterate from the Newton step `(dp, A dp, lambda)`: the
/// kinematic slip the linearised coupling predicts, `s_kin + A dp + e_x
/// lambda`, then each element's own problem solved exactly for its law
/// with the others' tractions at their predicted values (the local
/// correction of a return mapping: `s = s0 + A_II p(s)`, `s0` the
/// prediction less the element's own share), then one product.
fn correct(
    st: &GridStep,
    eps: f64,
    own: &[[f64; 3]],
    x: &State,
    (dp, adp, lambda): (&[f64], &[f64], f64),
    fresh: &mut dyn FnMut(&[f64], &mut [f64]),
    products: &mut usize,
) -> State {
    let n = st.set.len();
    let mut s = vec![0.0; 2 * n];
    let mut p = vec![0.0; 2 * n];
    for (c, &k) in own.iter().enumerate() {
        let ch = st.local(c);
        let theta = stick_traction_share() * ch.ratio(STICK_SLIP_FACTOR * eps).0;
        let (i, j) = (2 * c, 2 * c + 1);
        let kin = [x.s[i] - x.g[i] + adp[i] + lambda, x.s[j] - x.g[j] + adp[j]];
        let pn = [x.p[i] + dp[i], x.p[j] + dp[j]];
        let g = st.mu_p3[c];
        let pm = pn[0].hypot(pn[1]);
        // Within the stick regime the traction is the linear variable.
        let (sc, pc) = if pm < theta * g {
            (regularised_slip_with(pn, g, eps, ch), pn)
        } else {
            let s0 = [kin[0] - (k[0] * pn[0] + k[1] * pn[1]), kin[1] - (k[1] * pn[0] + k[2] * pn[1])];
            local_solve_with(s0, k, g, eps, [x.s[i], x.s[j]], ch)
        };
        (s[i], s[j], p[i], p[j]) = (sc[0], sc[1], pc[0], pc[1]);
    }
    evaluate(st, s, p, x.xi + lambda / st.speed, fresh, products)
}

/// `<a, b>_w` of two interleaved fields.
fn dot(w: &[f64], a: &[f64], b: &[f64]) -> f64 {
    w.iter().enumerate().map(|(c, wc)| wc * (a[2 * c] * b[2 * c] + a[2 * c + 1] * b[2 * c + 1])).sum()
}

/// One product and the residuals at `(s, p, xi)`.
fn evaluate(
    st: &GridStep,
    s: Vec<f64>,
    p: Vec<f64>,
    xi: f64,
    fresh: &mut dyn FnMut(&[f64], &mut [f64]),
    products: &mut usize,
) -> State {
    let n = st.set.len();
    let mut u = vec![0.0; 2 * n];
    fresh(&p, &mut u);
    *products += 1;
    let g: Vec<f64> = (0..n).flat_map(|c| kinematic_residual(st, &s, &u, xi, c)).collect();
    let mut r_max = g.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let force: f64 = (0..n).map(|c| st.weight[c] * p[2 * c]).sum::<f64>() * st.area;
    // f64::max passes over NaN: a non-finite iterate never counts as
    // converged.
    if !xi.is_finite() || g.iter().any(|v| !v.is_finite()) {
        r_max = f64::INFINITY;
    }
    State { s, p, xi, u, g, r_max, f_res: force - st.force_x }
}

/// The inner solve's preconditioner, an approximate inverse of `A + H`:
/// the elastic coupling's inverse by the FFT ([`FftConvolution::circulant_inverse`]
/// on the grid, `A^-1 = (dt/beta) K^-1`) on every stick element and along
/// the tangent of the traction bound of every slip element (scaled there
/// by `sqrt(a_tt / (a_tt + h_tt))` for the law's compliance along it, `a`
/// the element's own block of `A`), and each slip element's own
/// `1 / (A + H)_nn` along its traction, the direction the law holds stiff:
///
/// ```text
/// P = S K~^-1 S dt/beta + sum_slip n n^T / (A + H)_nn,
/// S = I (stick), sigma t t^T (slip),
/// ```
///
/// symmetric positive definite in `<., .>_w` (the FFT inverse acts on the
/// mirror-extended field of a folded grid). Zhao, Vollebregt & Oosterlee
/// (2015) precondition TangCG with the same FFT inverse on the stick area
/// and treat the slip area along the bound's tangent.
///
/// [`FftConvolution::circulant_inverse`]: super::convolution::FftConvolution::circulant_inverse
struct Preconditioner {
    /// Per element: `None` in stick; in slip the traction's direction `n`,
    /// the tangent's scale `sigma` and `1 / (A + H)_nn`.
    slip: Vec<Option<([f64; 2], f64, f64)>>,
    /// `dt / beta` (s).
    inv_scale: f64,
}

impl Preconditioner {
    fn new(st: &GridStep, eps: f64, own: &[[f64; 3]], h: &[[f64; 3]], s: &[f64]) -> Self {
        let quad = |m: [f64; 3], v: [f64; 2]| m[0] * v[0] * v[0] + 2.0 * m[1] * v[0] * v[1] + m[2] * v[1] * v[1];
        let slip = (0..own.len())
            .map(|c| {
                let (sx, sy) = (s[2 * c], s[2 * c + 1]);
                let q = sx.hypot(sy);
                (q >= STICK_SLIP_FACTOR * eps).then(|| {
                    let (n, t) = ([sx / q, sy / q], [-sy / q, sx / q]);
                    let m = [own[c][0] + h[c][0], own[c][1] + h[c][1], own[c][2] + h[c][2]];
                    let a_tt = quad(own[c], t);
                    (n, (a_tt / quad(m, t)).sqrt(), 1.0 / quad(m, n))
                })
            })
            .collect();
        Preconditioner { slip, inv_scale: st.dt / st.beta }
    }

    /// `out = P v`; `y` a work field.
    fn apply(&self, inverse: &mut Product, v: &[f64], y: &mut [f64], out: &mut [f64]) {
        for (c, slip) in self.slip.iter().enumerate() {
            let (a, b) = (v[2 * c], v[2 * c + 1]);
            (y[2 * c], y[2 * c + 1]) = match slip {
                None => (a, b),
                Some((n, sigma, _)) => {
                    let vt = sigma * (-n[1] * a + n[0] * b);
                    (-n[1] * vt, n[0] * vt)
                }
            };
        }
        inverse(y, out);
        for (c, slip) in self.slip.iter().enumerate() {
            let (a, b) = (v[2 * c], v[2 * c + 1]);
            let (qx, qy) = (self.inv_scale * out[2 * c], self.inv_scale * out[2 * c + 1]);
            (out[2 * c], out[2 * c + 1]) = match slip {
                None => (qx, qy),
                Some((n, sigma, rad)) => {
                    let qt = sigma * (-n[1] * qx + n[0] * qy);
                    let vn = rad * (n[0] * a + n[1] * b);
                    (-n[1] * qt + n[0] * vn, n[0] * qt + n[1] * vn)
                }
            };
        }
    }
}

/// Solves `(A + H) dp + e_x lambda = G`, `area <e_x, dp>_w = -(F - F_x)` by
/// projected preconditioned CG to `max |(A + H) dp + e_x lambda - G| <=
/// target`; returns `dp` (Pa), `A dp` (m/s), both interleaved, and
/// `lambda` (m/s). The start `dp0 = c e_x` meets the constraint; its
/// product `A e_x` is computed at the step's first need and kept in `ae`.
/// `inner`: `K p` in single precision (counted in `products`); `inverse`
/// the preconditioner's FFT inverse.
fn newton_system(
    st: &GridStep,
    (h, pre): (&[[f64; 3]], &Preconditioner),
    x: &State,
    target: f64,
    ae: &mut Option<Vec<f64>>,
    (inner, inverse): (&mut Product, &mut Product),
    products: &mut usize,
) -> (Vec<f64>, Vec<f64>, f64) {
    let n = st.set.len();
    let w = st.weight;
    let scale = st.beta / st.dt;
    let mut work = vec![0.0; 2 * n];
    let mut apply_pre = |v: &[f64], out: &mut [f64]| pre.apply(inverse, v, &mut work, out);
    let mut ku = vec![0.0; 2 * n];
    // (A v, (A + H) v).
    let mut apply_m = |v: &[f64], a: &mut [f64], out: &mut [f64], products: &mut usize| {
        inner(v, &mut ku);
        *products += 1;
        for c in 0..n {
            let (vx, vy) = (v[2 * c], v[2 * c + 1]);
            a[2 * c] = scale * ku[c];
            a[2 * c + 1] = scale * ku[n + c];
            out[2 * c] = a[2 * c] + h[c][0] * vx + h[c][1] * vy;
            out[2 * c + 1] = a[2 * c + 1] + h[c][1] * vx + h[c][2] * vy;
        }
    };
    // With the creepage prescribed there is no constraint: e = 0, no
    // projection, lambda = 0, the start dp0 = 0.
    let free = st.creepage_prescribed;
    let e: Vec<f64> = (0..n).flat_map(|_| [if free { 0.0 } else { 1.0 }, 0.0]).collect();
    let mut pe = vec![0.0; 2 * n];
    let epe = if free {
        1.0
    } else {
        apply_pre(&e, &mut pe);
        dot(w, &e, &pe)
    };
    // A feasible start: dp0 = c e, area <e, dp0>_w = F_x - F.
    let c0 = if free { 0.0 } else { -x.f_res / st.area / dot(w, &e, &e) };
    let mut dp: Vec<f64> = e.iter().map(|v| c0 * v).collect();
    let mut adp = vec![0.0; 2 * n];
    if c0 != 0.0 {
        let ae = ae.get_or_insert_with(|| {
            let (mut a, mut out) = (vec![0.0; 2 * n], vec![0.0; 2 * n]);
            apply_m(&e, &mut a, &mut out, products);
            a
        });
        adp.iter_mut().zip(ae.iter()).for_each(|(d, a)| *d = c0 * a);
    }
    // r = (A + H) dp - G (the gradient).
    let mut r: Vec<f64> = (0..n)
        .flat_map(|c| {
            let (vx, vy) = (dp[2 * c], dp[2 * c + 1]);
            [
                adp[2 * c] + h[c][0] * vx + h[c][1] * vy - x.g[2 * c],
                adp[2 * c + 1] + h[c][1] * vx + h[c][2] * vy - x.g[2 * c + 1],
            ]
        })
        .collect();
    let mut project = |r: &[f64], z: &mut [f64]| -> f64 {
        apply_pre(r, z);
        let k = dot(w, &e, z) / epe;
        for (zi, pei) in z.iter_mut().zip(&pe) {
            *zi -= k * pei;
        }
        // The multiplier of r: lambda = -<e, P r> / <e, P e>.
        -k
    };
    let off_e = |r: &[f64], lambda: f64| -> f64 {
        (0..n).map(|c| (r[2 * c] + lambda).abs().max(r[2 * c + 1].abs())).fold(0.0, f64::max)
    };
    let mut z = vec![0.0; 2 * n];
    let mut lambda = project(&r, &mut z);
    let mut dir: Vec<f64> = z.iter().map(|v| -v).collect();
    let mut rz = dot(w, &r, &z);
    let (mut q, mut adir) = (vec![0.0; 2 * n], vec![0.0; 2 * n]);
    for _ in 0..MAX_CG {
        if off_e(&r, lambda) <= target || rz <= 0.0 {
            break;
        }
        apply_m(&dir, &mut adir, &mut q, products);
        let curvature = dot(w, &dir, &q);
        if curvature <= 0.0 {
            break;
        }
        let alpha = rz / curvature;
        for k in 0..2 * n {
            dp[k] += alpha * dir[k];
            adp[k] += alpha * adir[k];
            r[k] += alpha * q[k];
        }
        lambda = project(&r, &mut z);
        let rz_next = dot(w, &r, &z);
        let beta = rz_next / rz;
        rz = rz_next;
        for k in 0..2 * n {
            dir[k] = -z[k] + beta * dir[k];
        }
    }
    (dp, adp, lambda)
}
