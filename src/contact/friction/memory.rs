//! Friction memory: the coefficient of a material point relaxing towards
//! the characteristic's steady value over a slip distance, as in CONTACT
//! (Vollebregt, *User guide for CONTACT*, velocity-dependent friction with
//! memory, parameters `memdst` = `d_c` and `mem_s0` = `s_0`; the
//! implementation in CONTACT's `m_stang`).
//!
//! `d mu / dt = -(max(|s|, s_0) / d_c) (mu - mu_ss(|s|))` along a material
//! point, by implicit Euler over a time step `dt`:
//!
//! `mu = theta mu_kept + (1 - theta) mu_ss(|s|)`, `theta = d_c / (d_c + dt
//! max(|s|, s_0))`,
//!
//! `mu_kept` the coefficient the point had one step earlier (upstream),
//! `s_0` keeping the relaxation going in stick (towards the static
//! coefficient). Within a step the element's coefficient is therefore a
//! function of its own slip speed, `r_m(q) = theta(q) r_kept + (1 -
//! theta(q)) r(q)` (ratios to `mu_0`), and the element problems solve with
//! it as with any characteristic ([`Local`]).

use super::Characteristic;
use crate::quadrature::integrate;
use nalgebra::SMatrix;
use num_complex::Complex64;

/// CONTACT's memory parameters (a material's).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionMemory {
    /// `d_c` (m): the slip distance over which the coefficient relaxes
    /// (CONTACT's `memdst`).
    pub distance: f64,
    /// `s_0` (m/s): the least slip speed of the relaxation (CONTACT's
    /// `mem_s0`).
    pub floor: f64,
}

impl FrictionMemory {
    /// CONTACT's defaults: `d_c` = 1 um, `s_0` = 10 mm/s.
    pub const CONTACT: FrictionMemory = FrictionMemory { distance: 1e-6, floor: 0.01 };

    /// The memory of an element that kept the ratio `kept` one step `dt`
    /// (s) earlier.
    pub fn at(self, kept: f64, dt: f64) -> Memory {
        Memory { kept, reach: self.distance / dt, floor: self.floor }
    }
}

/// The memory of one element in one step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Memory {
    /// The ratio `mu_kept / mu_0` the material had one step earlier (1).
    pub kept: f64,
    /// `d_c / dt` (m/s): the slip speed at which half of the kept
    /// coefficient is forgotten in one step.
    pub reach: f64,
    /// `s_0` (m/s): the least slip speed of the relaxation.
    pub floor: f64,
}

impl Memory {
    /// `theta(q)` and `theta'(q)` (s/m).
    fn theta(self, q: f64) -> (f64, f64) {
        if q <= self.floor {
            (self.reach / (self.reach + self.floor), 0.0)
        } else {
            let d = self.reach + q;
            (self.reach / d, -self.reach / (d * d))
        }
    }
}

/// The friction characteristic at one element in one step: the steady
/// characteristic, with or without memory. Without memory every method is
/// the steady characteristic's own, bit for bit.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Local {
    /// The steady characteristic `r(q)`.
    pub steady: Characteristic,
    /// The memory, if any.
    pub memory: Option<Memory>,
}

impl Local {
    /// The characteristic `steady` at an element whose material kept the
    /// ratio `kept` one step `dt` (s) earlier, with `memory` where there is
    /// one.
    pub fn new(steady: Characteristic, memory: Option<FrictionMemory>, kept: f64, dt: f64) -> Self {
        Local { steady, memory: memory.map(|m| m.at(kept, dt)) }
    }
}

impl From<Characteristic> for Local {
    fn from(steady: Characteristic) -> Self {
        Local { steady, memory: None }
    }
}

impl Local {
    /// The memory's effect is nil: no memory, or a constant characteristic
    /// (whose kept ratio is 1).
    fn plain(self) -> Option<Memory> {
        self.memory.filter(|_| !self.steady.is_constant())
    }

    /// Whether `r = 1` everywhere.
    pub fn is_constant(self) -> bool {
        self.steady.is_constant() && self.plain().is_none()
    }

    /// `r_m(q)` and `r_m'(q)` (s/m) at slip speed `q` >= 0 (m/s).
    pub fn ratio(self, q: f64) -> (f64, f64) {
        let Some(m) = self.plain() else {
            return self.steady.ratio(q);
        };
        let (r, rp) = self.steady.ratio(q);
        let (t, tp) = m.theta(q);
        (t * m.kept + (1.0 - t) * r, (1.0 - t) * rp + tp * (m.kept - r))
    }

    /// `int_0^q r_m(t) dt` (m/s). With memory, beyond `s_0`:
    /// `theta (kept - r) dt = R (kept - r(t)) d ln(R + t)` (`R = d_c/dt`),
    /// the kept part in closed form, `R kept ln((R + q)/(R + s_0))`, and
    /// `R int r d ln(R + t)` (positive) by adaptive quadrature.
    pub fn integral(self, q: f64) -> f64 {
        let Some(m) = self.plain() else {
            return self.steady.integral(q);
        };
        let a = q.min(m.floor);
        let (t0, _) = m.theta(0.0);
        let mut total = self.steady.integral(q) + t0 * (m.kept * a - self.steady.integral(a));
        if q > m.floor {
            let (lo, hi) = ((m.reach + m.floor).ln(), (m.reach + q).ln());
            let density = |v: f64| {
                let t = (v.exp() - m.reach).max(0.0);
                vec![SMatrix::<Complex64, 1, 1>::from_element(Complex64::new(self.steady.ratio(t).0, 0.0))]
            };
            let steady = integrate(density, lo, hi, 8, 1e-13, 100_000).map(|v| v[0][(0, 0)].re).unwrap_or(f64::NAN);
            total += m.reach * (m.kept * (hi - lo) - steady);
        }
        total
    }

    /// An upper bound of the steepest fall, `sup_q max(0, -r_m'(q))` (s/m).
    /// `-r_m' = -(1 - theta) r' - theta' (r_kept - r(q))` with `-theta' =
    /// R/(R + q)^2` beyond `s_0` (`R = d_c/dt`): with `F` the steady law's
    /// steepest fall, `r(q) >= 1 - F q` and `r(q) >= r_min`, so the second
    /// term is at most `R/(R + s_0)^2 max(0, r_kept - 1) + F/4` and at most
    /// `R/(R + s_0)^2 max(0, r_kept - r_min)`.
    pub fn steepest_fall(self) -> f64 {
        let Some(m) = self.plain() else {
            return self.steady.steepest_fall();
        };
        let fall = self.steady.steepest_fall();
        let d = m.reach + m.floor;
        let peak = m.reach / (d * d);
        let by_slope = peak * (m.kept - 1.0).max(0.0) + 0.25 * fall;
        let by_level = peak * (m.kept - self.steady.smallest()).max(0.0);
        fall + by_slope.min(by_level)
    }

    /// The largest ratio, `sup_q r_m(q)`: at most `max(r_kept, sup r)`.
    pub fn largest(self) -> f64 {
        match self.plain() {
            Some(m) => self.steady.largest().max(m.kept),
            None => self.steady.largest(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn polach() -> Characteristic {
        Characteristic::Exponential { ratio: 0.4, speed: 1.0 / 0.6 }
    }

    fn locals() -> Vec<Local> {
        let mut out = Vec::new();
        for steady in [
            polach(),
            Characteristic::Rational { ratio: 0.42, speed: 1.25 },
            Characteristic::Exponential { ratio: 1.25, speed: 0.1 },
        ] {
            for (kept, reach, floor) in [(1.0, 0.06, 0.01), (0.45, 0.06, 0.01), (0.8, 2.0, 0.001), (1.2, 0.3, 0.05)] {
                out.push(Local { steady, memory: Some(Memory { kept, reach, floor }) });
            }
        }
        out
    }

    /// `r_m` is the implicit-Euler blend; its slope and integral agree
    /// with central differences and the trapezoid rule; the fall's bound
    /// and the largest ratio hold.
    #[test]
    fn ratio_slope_integral_and_bounds() {
        for law in locals() {
            let m = law.memory.unwrap();
            for q in [0.0, 1e-4, 0.005, 0.02, 0.3, 2.0, 7.0] {
                let (r, _) = law.steady.ratio(q);
                let theta = m.reach / (m.reach + q.max(m.floor));
                assert!((law.ratio(q).0 - (theta * m.kept + (1.0 - theta) * r)).abs() < 1e-15, "{law:?} at {q}");
                assert!(law.ratio(q).0 <= law.largest() * (1.0 + 1e-15));
                assert!(-law.ratio(q).1 <= law.steepest_fall() * (1.0 + 1e-12) + 1e-15, "{law:?} at {q}");
                if q > 0.0 && (q - m.floor).abs() > 1e-3 * m.floor {
                    let h = 1e-4 * q.min((q - m.floor).abs());
                    let fd = (law.ratio(q + h).0 - law.ratio(q - h).0) / (2.0 * h);
                    assert!((law.ratio(q).1 - fd).abs() <= 1e-6 * fd.abs().max(1.0), "{law:?} slope at {q}");
                }
                let trap = super::super::characteristic::trapezoid(|t| law.ratio(t).0, q, 200_000);
                assert!((law.integral(q) - trap).abs() <= 1e-8 * q.max(1e-12), "{law:?} integral at {q}");
            }
        }
    }

    /// No memory, or a constant law with memory: the steady law's values,
    /// bit for bit.
    #[test]
    fn without_memory_the_steady_law() {
        let plain = Local::from(polach());
        let constant =
            Local { steady: Characteristic::Constant, memory: Some(Memory { kept: 1.0, reach: 1.0, floor: 0.01 }) };
        assert!(constant.is_constant() && !plain.is_constant());
        for q in [0.0, 0.01, 1.0, 5.0] {
            assert_eq!(plain.ratio(q), polach().ratio(q));
            assert_eq!(plain.integral(q), polach().integral(q));
            assert_eq!(constant.ratio(q), (1.0, 0.0));
        }
        assert_eq!(plain.steepest_fall(), polach().steepest_fall());
    }

    /// Repeating the step at a fixed slip speed relaxes the coefficient
    /// to the steady value as the ODE's implicit Euler solution:
    /// `(mu_n - mu_ss) = (mu_0 - mu_ss) theta^n`; and for `dt -> 0` at a
    /// fixed time `T` to `exp(-q T / d_c)`.
    #[test]
    fn repeated_steps_relax_as_the_ode() {
        let (q, d_c, big_t) = (0.2f64, 1e-6, 2e-5);
        let ss = polach().ratio(q).0;
        let exact = ss + (1.0 - ss) * (-q * big_t / d_c).exp();
        let mut errors = Vec::new();
        for steps in [16usize, 32, 64, 128] {
            let dt = big_t / steps as f64;
            let mut kept = 1.0;
            for _ in 0..steps {
                kept =
                    Local { steady: polach(), memory: Some(Memory { kept, reach: d_c / dt, floor: 0.01 }) }.ratio(q).0;
            }
            let theta = d_c / (d_c + dt * q);
            assert!((kept - (ss + (1.0 - ss) * theta.powi(steps as i32))).abs() < 1e-14);
            errors.push((kept - exact).abs());
        }
        // First order: each halving of dt halves the error (to 10 %).
        for w in errors.windows(2) {
            assert!((w[0] / w[1] - 2.0).abs() < 0.2, "{errors:?}");
        }
    }
}
