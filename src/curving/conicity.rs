//! Equivalent conicity from the rolling-radius difference, by the
//! integration of the wheelset's nonlinear kinematic oscillation (EN 15302
//! annex B's method; Klingel's formula defines the conicity from the
//! wavelength).
//!
//! A wheelset rolling without slip follows `y'' = -dr(y) / (e r0)` along
//! the track (`dr` the rolling-radius difference, left minus right, `e`
//! the contact points' spacing, `r0` the rolling radius). With `S(y) =
//! int_0^y dr`, the motion between the turning points `y1 < y2` (`S(y1) =
//! S(y2)`, `y2 - y1 = 2 A` for the amplitude `A`) has
//! `y'^2 = 2 (S(y2) - S(y)) / (e r0)`, and its wavelength is
//! `lambda = 2 int_{y1}^{y2} dy / y'`. The equivalent conicity is the cone
//! with the same wavelength, Klingel's `lambda = 2 pi sqrt(e r0 / (2
//! tan(gamma)))`, so `tan(gamma_e) = 2 pi^2 e r0 / lambda^2`; `e r0` cancels.
//! The integral is taken in `y = c + A sin(theta)`, where its ends are
//! regular, by the midpoint rule.

use crate::numerics::{Tolerance, brent};
use std::f64::consts::PI;

/// Points of the midpoint rule in theta.
const POINTS: usize = 4000;

/// A rolling-radius difference tabulated over the lateral shift, linear
/// between the points.
#[derive(Debug, Clone, PartialEq)]
pub struct RadiusDifference {
    /// Lateral shifts (m), increasing.
    pub shift: Vec<f64>,
    /// Rolling-radius difference, left minus right (m).
    pub difference: Vec<f64>,
}

impl RadiusDifference {
    /// The integral `S(y) = int_{shift[0]}^y dr` (m^2), exact for the
    /// linear interpolation; None outside the table.
    fn integral(&self, y: f64, cumulative: &[f64]) -> Option<f64> {
        let (x, d) = (&self.shift, &self.difference);
        let (first, last) = (x[0], x[x.len() - 1]);
        // (Rounding in c -+ A may step a hair outside the table.)
        let slack = 1e-9 * (last - first);
        if !(first - slack..=last + slack).contains(&y) {
            return None;
        }
        let y = y.clamp(first, last);
        let i = x.partition_point(|&v| v <= y).clamp(1, x.len() - 1) - 1;
        let t = y - x[i];
        let slope = (d[i + 1] - d[i]) / (x[i + 1] - x[i]);
        Some(cumulative[i] + d[i] * t + 0.5 * slope * t * t)
    }

    fn cumulative(&self) -> Vec<f64> {
        let mut c = vec![0.0; self.shift.len()];
        for i in 1..c.len() {
            c[i] = c[i - 1] + 0.5 * (self.difference[i] + self.difference[i - 1]) * (self.shift[i] - self.shift[i - 1]);
        }
        c
    }

    /// The equivalent conicity (1) at amplitude `amplitude` (m): None where
    /// the oscillation leaves the table.
    pub fn equivalent_conicity(&self, amplitude: f64) -> Option<f64> {
        let cumulative = self.cumulative();
        let s = |y: f64| self.integral(y, &cumulative);
        let (lo, hi) = (self.shift[0] + amplitude, self.shift[self.shift.len() - 1] - amplitude);
        if lo >= hi {
            return None;
        }
        // The centre c with S(c + A) = S(c - A).
        let balance = |c: f64| s(c + amplitude).unwrap_or(f64::NAN) - s(c - amplitude).unwrap_or(f64::NAN);
        let (blo, bhi) = (balance(lo), balance(hi));
        if blo.abs() < 1e-300 && bhi.abs() < 1e-300 {
            return Some(0.0); // no restoring difference at all
        }
        if blo * bhi > 0.0 {
            return None;
        }
        let tol = Tolerance { residual: 0.0, x_rel: 0.0, x_abs: 1e-13, max_iter: 200 };
        let centre = brent(lo, hi, balance, tol).ok()?;
        let top = s(centre + amplitude)?;
        let mut sum = 0.0;
        for k in 0..POINTS {
            let theta = -0.5 * PI + PI * (k as f64 + 0.5) / POINTS as f64;
            let y = centre + amplitude * theta.sin();
            let energy = 2.0 * (top - s(y)?);
            if energy <= 0.0 {
                return Some(0.0); // the motion does not cross: no oscillation
            }
            sum += amplitude * theta.cos() / energy.sqrt();
        }
        let wavelength = 2.0 * sum * PI / POINTS as f64; // with e r0 = 1
        Some(2.0 * PI * PI / (wavelength * wavelength))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cone_is_its_own_equivalent() {
        // dr = 2 gamma y: the conicity at every amplitude.
        let shift: Vec<f64> = (0..=200).map(|i| -0.01 + 1e-4 * i as f64).collect();
        let difference = shift.iter().map(|y| 2.0 * 0.15 * y).collect();
        let dr = RadiusDifference { shift, difference };
        for a in [1e-3, 3e-3, 6e-3] {
            let g = dr.equivalent_conicity(a).unwrap();
            assert!((g - 0.15).abs() < 1e-6, "{a}: {g}");
        }
        // An offset (wheels of unequal radii) moves the centre, not the conicity.
        let offset =
            RadiusDifference { shift: dr.shift.clone(), difference: dr.difference.iter().map(|d| d + 5e-4).collect() };
        assert!((offset.equivalent_conicity(3e-3).unwrap() - 0.15).abs() < 1e-6);
        assert_eq!(dr.equivalent_conicity(0.011), None);
    }
}
