//! The closed form of the simplified (Winkler) theory's frequency response
//! in full adhesion: what the simplified-transient solver must reproduce
//! at small creepage (Kalker's simplified theory, *Three-dimensional
//! elastic bodies in rolling contact*, 1990, ch. 3, with the non-steady
//! kinematics of Eq. 1 of Baeza et al. 2008).
//!
//! # Derivation
//!
//! Winkler: `u = L p` element by element (`L1` along x, `L2` across). In
//! full adhesion the slip `s = V w + Du/Dt` vanishes, `w = (xi_x - phi y,
//! xi_y + phi x)` the rigid slip per unit speed, `Du/Dt = du/dt - V du/dx`
//! the material derivative. A rail point at `(x, y)` at time `t` entered
//! the patch at its leading edge `a_y = a sqrt(1 - y^2/b^2)` with `u = 0`
//! an age `T = (a_y - x) / V` ago, and has moved as `x + V (t - tau)`
//! since, so
//!
//! ```text
//! u(x, y, t) = -V int_{t-T}^{t} w(x + V (t - tau), y, tau) dtau.          (1)
//! ```
//!
//! With `q(tau) = q^ exp(i w tau)` and `zeta = a_y - x` (the distance
//! from the leading edge), `kappa = w / V`, the force `F = int int u / L
//! dA` needs only the double integral over the strip `0 <= sigma <= zeta
//! <= Z = 2 a_y`, which swaps to a single one:
//!
//! ```text
//! creepage:  F^_x = -(q^ / L1) int dy int_0^Z (Z - s) exp(-i kappa s) ds,
//! spin:      F^_y = -(q^ / L2) int dy int_0^Z (s (Z - s) / 2) exp(-i kappa s) ds
//! ```
//!
//! (for the spin, `x + sigma = a_y - zeta + sigma` integrated over `zeta`
//! from `sigma` to `Z` is `sigma (Z - sigma) / 2`; its x-force vanishes by
//! symmetry in y). At `w = 0` these are the steady forces `-8 a^2 b xi /
//! (3 L1)` (`= -G a b C11 xi` with `L1 = 8 a / (3 C11 G)`) and `-pi a^3 b
//! phi / (4 L2)`. In reduced form, `W = w a / V`, `y = b cos(theta)`,
//! `Z = 2 a sin(theta)`, the ratios to the steady values are
//!
//! ```text
//! R_xi(W)  = (3/8) int_0^pi sin(t) int_0^{2 sin t} (2 sin t - s) e^{-i W s} ds dt,     (2)
//! R_phi(W) = (4/pi) int_0^pi sin(t) int_0^{2 sin t} s (2 sin t - s)/2 e^{-i W s} ds dt. (3)
//! ```
//!
//! The lateral creepage's ratio is `R_xi` too (same geometry, `L2`).
//! Limits: `R -> 1 - i c W` at low frequency (a lag: the force builds up
//! over the material's passage), `R_xi -> 3 pi / (8 i W)` at high frequency
//! (the adhering patch as a spring of stiffness `pi a b / L1` driven by the
//! slip velocity `V xi`), `R_phi = O(W^-2)` (a rotation about the normal
//! loads the patch with a moment, no net force). The integrals are
//! evaluated by Gauss-Legendre quadrature in `theta` and `s` (96 x 96
//! nodes: smooth integrands, error below 1e-12 up to `W = 20`).

use gauss_quad::legendre::GaussLegendre;
use num_complex::Complex64;
use std::f64::consts::PI;

/// Quadrature nodes per direction.
const NODES: usize = 96;

/// `int_0^pi sin(t) int_0^{2 sin t} k(s, 2 sin t) e^{-i W s} ds dt`.
fn integral(w: f64, kernel: impl Fn(f64, f64) -> f64) -> Complex64 {
    let rule = GaussLegendre::new(NODES.try_into().expect("nonzero"));
    let nodes = rule.as_node_weight_pairs();
    let mut total = Complex64::new(0.0, 0.0);
    for &(u, wu) in nodes {
        let t = 0.5 * PI * (u + 1.0);
        let z = 2.0 * t.sin();
        let mut inner = Complex64::new(0.0, 0.0);
        for &(v, wv) in nodes {
            let s = 0.5 * z * (v + 1.0);
            inner += wv * kernel(s, z) * Complex64::from_polar(1.0, -w * s);
        }
        total += wu * t.sin() * 0.5 * z * inner;
    }
    total * 0.5 * PI
}

/// The factor by which a scheme that accumulates a point's slip over whole
/// steps `dt` (the backward difference of the transient solvers) changes a
/// harmonic response: `dt sum_{k<m} exp(-i w k dt)` against `int_0^{m dt}
/// exp(-i w s) ds`, `D = i theta / (1 - exp(-i theta))`, `theta = w dt = W h
/// / a` (`h` the step, `W` the reduced frequency); `D = 1 + i theta / 2 +
/// O(theta^2)`, a phase lead of half a step.
pub fn backward_difference_factor(theta: f64) -> Complex64 {
    if theta.abs() < 1e-8 {
        return Complex64::new(1.0, 0.5 * theta);
    }
    let i_theta = Complex64::new(0.0, theta);
    i_theta / (1.0 - (-i_theta).exp())
}

/// `R_xi(W)` of eq. 2: the creepage response over its steady value at the
/// reduced frequency `W = w a / V` (1).
pub fn creepage_ratio(w: f64) -> Complex64 {
    0.375 * integral(w, |s, z| z - s)
}

/// `R_phi(W)` of eq. 3: the spin's lateral-force response over its steady
/// value.
pub fn spin_ratio(w: f64) -> Complex64 {
    4.0 / PI * integral(w, |s, z| 0.5 * s * (z - s))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ratios_are_one_at_zero_frequency() {
        assert!((creepage_ratio(0.0) - 1.0).norm() < 1e-13);
        assert!((spin_ratio(0.0) - 1.0).norm() < 1e-13);
    }

    #[test]
    fn creepage_ratio_is_the_closed_inner_integral() {
        // int_0^Z (Z - s) e^{-iWs} ds = Z/(iW) - (1 - e^{-iWZ})/(iW)^2, and
        // its mean over the ellipse's strips.
        for w in [0.3, 1.0, 2.5, 7.0] {
            let iw = Complex64::new(0.0, w);
            let inner = |z: f64| z / iw - (1.0 - (-iw * z).exp()) / (iw * iw);
            // Composite Simpson in theta, fine enough for 1e-9.
            let n = 20_000;
            let h = PI / n as f64;
            let f = |t: f64| t.sin() * inner(2.0 * t.sin());
            let sum: Complex64 = (0..=n)
                .map(|k| {
                    let c = if k == 0 || k == n {
                        1.0
                    } else if k % 2 == 1 {
                        4.0
                    } else {
                        2.0
                    };
                    c * f(k as f64 * h)
                })
                .sum();
            let expect = 0.375 * sum * h / 3.0;
            assert!((creepage_ratio(w) - expect).norm() < 1e-9, "{w}: {} vs {expect}", creepage_ratio(w));
        }
    }

    #[test]
    fn limits() {
        // Low frequency: R = 1 - i W <s>_F + O(W^2) with the force-weighted
        // mean age; high frequency: 3 pi / (8 i W) for the creepage,
        // O(W^-2) for the spin.
        let r = creepage_ratio(1e-4);
        assert!((r.re - 1.0).abs() < 1e-7 && r.im < 0.0, "{r}");
        let w = 40.0;
        let hi = creepage_ratio(w) * Complex64::new(0.0, w) / (3.0 * PI / 8.0);
        assert!((hi - 1.0).norm() < 0.03, "{hi}");
        assert!(spin_ratio(w).norm() * w < 0.05, "{}", spin_ratio(w));
    }
}
