//! How the friction coefficient varies with the local slip speed `|s|`
//! (m/s): `mu(|s|) = mu_0 r(|s|)`, `mu_0` the coefficient at zero slip
//! (`contact.friction`), `r` this characteristic's ratio.
//!
//! * Constant: `r = 1` (Coulomb's, the paper's law).
//! * Exponential (CONTACT's exponential falling friction, Vollebregt, *User
//!   guide for CONTACT*, friction law L = 4; Polach, Wear 258 (2005)
//!   992-1000, Eq. 9, with `A = mu_inf/mu_0`, `v_c = 1/B`):
//!   `r = A + (1 - A) exp(-|s| / v_c)`.
//! * Rational (CONTACT's law L = 3, first term): `r = A + (1 - A) / (1 +
//!   |s| / v_c)`.
//!
//! `A < 1` falls with slip speed; `A > 1` rises (a friction modifier's
//! positive characteristic: the exponential form from `mu_0` up to `A
//! mu_0`).

/// The characteristic's form.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Characteristic {
    /// `r = 1`.
    #[default]
    Constant,
    /// `r = A + (1 - A) exp(-|s| / v_c)`.
    Exponential {
        /// `A = mu_inf / mu_0`, the ratio at large slip speed (1).
        ratio: f64,
        /// `v_c`, the slip speed of the change (m/s).
        speed: f64,
    },
    /// `r = A + (1 - A) / (1 + |s| / v_c)`.
    Rational {
        /// `A = mu_inf / mu_0` (1).
        ratio: f64,
        /// `v_c` (m/s): `r` is half way at `|s| = v_c`.
        speed: f64,
    },
}

impl Characteristic {
    /// Whether `r = 1` everywhere.
    pub fn is_constant(self) -> bool {
        match self {
            Characteristic::Constant => true,
            Characteristic::Exponential { ratio, .. } | Characteristic::Rational { ratio, .. } => ratio == 1.0,
        }
    }

    /// `r(q)` and `r'(q)` (s/m) at slip speed `q` >= 0 (m/s).
    pub fn ratio(self, q: f64) -> (f64, f64) {
        match self {
            Characteristic::Constant => (1.0, 0.0),
            Characteristic::Exponential { ratio, speed } => {
                let e = (-q / speed).exp();
                (ratio + (1.0 - ratio) * e, -(1.0 - ratio) * e / speed)
            }
            Characteristic::Rational { ratio, speed } => {
                let d = 1.0 / (1.0 + q / speed);
                (ratio + (1.0 - ratio) * d, -(1.0 - ratio) * d * d / speed)
            }
        }
    }

    /// `int_0^q r(t) dt` (m/s): the Coulomb law's dissipation potential per
    /// unit bound.
    pub fn integral(self, q: f64) -> f64 {
        match self {
            Characteristic::Constant => q,
            Characteristic::Exponential { ratio, speed } => ratio * q + (1.0 - ratio) * speed * -(-q / speed).exp_m1(),
            Characteristic::Rational { ratio, speed } => ratio * q + (1.0 - ratio) * speed * (q / speed).ln_1p(),
        }
    }

    /// The steepest fall, `sup_q max(0, -r'(q))` (s/m): the element
    /// problem stays convex while `mu p3 K_max` times this is below 1.
    pub fn steepest_fall(self) -> f64 {
        match self {
            Characteristic::Constant => 0.0,
            Characteristic::Exponential { ratio, speed } | Characteristic::Rational { ratio, speed } => {
                ((1.0 - ratio) / speed).max(0.0)
            }
        }
    }

    /// The smallest ratio, `inf_q r(q)`: `min(1, A)`.
    pub fn smallest(self) -> f64 {
        match self {
            Characteristic::Constant => 1.0,
            Characteristic::Exponential { ratio, .. } | Characteristic::Rational { ratio, .. } => ratio.min(1.0),
        }
    }

    /// The largest ratio, `sup_q r(q)`: the bound of full sliding's
    /// traction, `max(1, A)`.
    pub fn largest(self) -> f64 {
        match self {
            Characteristic::Constant => 1.0,
            Characteristic::Exponential { ratio, .. } | Characteristic::Rational { ratio, .. } => ratio.max(1.0),
        }
    }
}

/// `int_0^q f` by the trapezoid rule on `n` intervals (the tests'
/// reference for the characteristics' integrals).
#[cfg(test)]
pub(crate) fn trapezoid(f: impl Fn(f64) -> f64, q: f64, n: usize) -> f64 {
    (0..n)
        .map(|i| {
            let (a, b) = (q * i as f64 / n as f64, q * (i + 1) as f64 / n as f64);
            0.5 * (b - a) * (f(a) + f(b))
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn laws() -> [Characteristic; 4] {
        [
            Characteristic::Exponential { ratio: 0.4, speed: 1.0 / 0.6 },
            Characteristic::Rational { ratio: 0.42, speed: 1.25 },
            Characteristic::Exponential { ratio: 1.2, speed: 0.05 },
            Characteristic::Rational { ratio: 1.5, speed: 0.3 },
        ]
    }

    /// r(0) = 1, r(inf) = A, the slope and the integral against central
    /// differences and the trapezoid rule.
    #[test]
    fn ratio_slope_and_integral_agree() {
        for law in laws() {
            let (Characteristic::Exponential { ratio, .. } | Characteristic::Rational { ratio, .. }) = law else {
                unreachable!()
            };
            assert_eq!(law.ratio(0.0).0, 1.0);
            assert!((law.ratio(1e9).0 - ratio).abs() < 1e-8);
            for q in [1e-4f64, 0.01, 0.3, 2.0, 7.0] {
                let h = 1e-6 * q.max(1e-3);
                let fd = (law.ratio(q + h).0 - law.ratio(q - h).0) / (2.0 * h);
                assert!((law.ratio(q).1 - fd).abs() <= 1e-6 * fd.abs().max(1e-6), "{law:?} at {q}");
                let trap = trapezoid(|t| law.ratio(t).0, q, 20_000);
                assert!((law.integral(q) - trap).abs() <= 1e-8 * q, "{law:?} integral at {q}");
                assert!(-law.ratio(q).1 <= law.steepest_fall() * (1.0 + 1e-12));
            }
        }
    }
}
