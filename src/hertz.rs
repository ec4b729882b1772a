//! Hertz normal contact of two quasi-identical elastic bodies with an elliptic
//! contact patch.
//!
//! Gap between the undeformed surfaces: `h(x, y) = A x^2 + B y^2` with `x` the
//! rolling direction. With `E* = E / (2 (1 - nu^2))` (two identical bodies),
//! the patch is an ellipse with semi-axes `a` (along x) and `b` (along y) and
//! pressure `p3 = p0 sqrt(1 - (x/a)^2 - (y/b)^2)`, `p0 = 3 N / (2 pi a b)`
//! (Johnson, *Contact Mechanics*, 1985, section 4.2, eqs. 4.39-4.40).
//!
//! With `k' = short/long` axis ratio and Carlson's symmetric integral
//! `R_D`, the shape and size equations are written in a form that stays
//! accurate in the circular limit (`K - E = (k^2/3) R_D(0, k'^2, 1)`,
//! `E - k'^2 K = (k^2 k'^2 / 3) R_D(0, 1, k'^2)`; Carlson, *Numer. Algorithms*
//! 10 (1995) 13-26; DLMF 19.25):
//!
//! ```text
//! C_long / C_short = R_D(0, 1, k'^2) / R_D(0, k'^2, 1)        (shape)
//! long^3          = N R_D(0, k'^2, 1) / (2 pi E* C_long)       (size)
//! approach        = p0 * short * K(k^2) / E*
//! ```
//! where `C_long` is the curvature sum (A or B) along the long semi-axis.

use ellip::{ellipk, elliprd};
use roots::{Convergency, find_root_brent};
use std::f64::consts::PI;

/// Errors of the Hertz solution.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum HertzError {
    /// A curvature sum is not positive (the surfaces do not form a
    /// non-conformal convex gap).
    #[error("curvature sum {name} = {value} 1/m must be > 0 (non-conformal contact)")]
    NonPositiveCurvature {
        /// "A" or "B".
        name: &'static str,
        /// The offending value (1/m).
        value: f64,
    },
    /// The normal force must be positive for a contact patch to exist.
    #[error("normal force {0} N must be > 0 for a Hertz patch")]
    NoContact(f64),
    /// The semi-axis ratio leaves the range the solver handles.
    #[error("Hertz ellipse too elongated: curvature ratio {0} outside [1e-6, 1e6]")]
    TooElongated(f64),
}

/// Elastic constants of the (identical) bodies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Elastic {
    /// Young's modulus E (Pa).
    pub young_modulus: f64,
    /// Poisson's ratio nu (1).
    pub poisson_ratio: f64,
}

impl Elastic {
    /// Shear modulus G = E / (2 (1 + nu)) (Pa).
    pub fn shear_modulus(&self) -> f64 {
        self.young_modulus / (2.0 * (1.0 + self.poisson_ratio))
    }

    /// Contact modulus of two identical bodies, E* = E / (2 (1 - nu^2)) (Pa).
    pub fn contact_modulus(&self) -> f64 {
        self.young_modulus / (2.0 * (1.0 - self.poisson_ratio * self.poisson_ratio))
    }

    /// Elastic constants from shear modulus G (Pa) and Poisson's ratio.
    pub fn from_shear(shear_modulus: f64, poisson_ratio: f64) -> Self {
        Elastic { young_modulus: 2.0 * shear_modulus * (1.0 + poisson_ratio), poisson_ratio }
    }
}

/// Curvature sums of the undeformed gap `h = A x^2 + B y^2`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Curvatures {
    /// A (1/m), rolling direction.
    pub a: f64,
    /// B (1/m), lateral direction.
    pub b: f64,
}

impl Curvatures {
    /// Curvatures of a wheel on a straight rail.
    ///
    /// `A = 1 / (2 R_wheel)`; `B = (1/R_rail_head + 1/R_wheel_profile) / 2`,
    /// with radii signed: positive convex, negative concave, infinite flat.
    /// Radii in m, curvatures in 1/m.
    pub fn wheel_on_rail(wheel_radius: f64, wheel_profile_radius: f64, rail_head_radius: f64) -> Self {
        Curvatures { a: 0.5 / wheel_radius, b: 0.5 * (1.0 / rail_head_radius + 1.0 / wheel_profile_radius) }
    }

    /// Checks that both curvature sums are positive.
    pub fn validate(&self) -> Result<(), HertzError> {
        for (name, value) in [("A", self.a), ("B", self.b)] {
            if !(value > 0.0 && value.is_finite()) {
                return Err(HertzError::NonPositiveCurvature { name, value });
            }
        }
        let ratio = self.a / self.b;
        if !(1e-6..=1e6).contains(&ratio) {
            return Err(HertzError::TooElongated(ratio));
        }
        Ok(())
    }
}

/// The Hertz solution for one normal force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzPatch {
    /// Semi-axis along the rolling direction x (m).
    pub a: f64,
    /// Semi-axis along the lateral direction y (m).
    pub b: f64,
    /// Maximum pressure p0 = 3 N / (2 pi a b) (Pa).
    pub p0: f64,
    /// Approach of distant points of the two bodies (m).
    pub approach: f64,
    /// Normal force N (N).
    pub normal_force: f64,
}

impl HertzPatch {
    /// Hertz pressure at (x, y) in patch coordinates (m); zero outside (Pa).
    pub fn pressure(&self, x: f64, y: f64) -> f64 {
        let r2 = (x / self.a).powi(2) + (y / self.b).powi(2);
        if r2 < 1.0 { self.p0 * (1.0 - r2).sqrt() } else { 0.0 }
    }

    /// Semi-axis ratio a/b (1).
    pub fn aspect(&self) -> f64 {
        self.a / self.b
    }
}

/// Shape of the Hertz ellipse, independent of the normal force: with fixed
/// curvatures, `a` and `b` scale as `N^(1/3)` with a fixed ratio.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzShape {
    curv: Curvatures,
    elastic: Elastic,
    /// k'^2 = (short / long)^2 (1).
    kp2: f64,
    /// true when the long axis is along x (A <= B).
    long_is_x: bool,
}

/// Brent tolerance on k'^2 and on the relative shape residual.
struct ShapeTolerance {
    iterations: usize,
}

impl Convergency<f64> for ShapeTolerance {
    fn is_root_found(&mut self, y: f64) -> bool {
        y.abs() < 1e-15
    }
    fn is_converged(&mut self, x1: f64, x2: f64) -> bool {
        (x1 - x2).abs() < 1e-15 * (1.0 + x1.abs())
    }
    fn is_iteration_limit_reached(&mut self, iter: usize) -> bool {
        self.iterations = iter;
        iter >= 200
    }
}

fn rd(x: f64, y: f64, z: f64) -> f64 {
    // Arguments are always valid here (x = 0, y, z in (0, 1]).
    elliprd(x, y, z).expect("R_D arguments in range")
}

impl HertzShape {
    /// The curvature sums A, B (1/m).
    pub fn curvatures(&self) -> Curvatures {
        self.curv
    }

    /// The elastic constants.
    pub fn elastic(&self) -> Elastic {
        self.elastic
    }

    /// Solves the shape equation for the given curvatures and materials.
    pub fn new(curv: Curvatures, elastic: Elastic) -> Result<Self, HertzError> {
        curv.validate()?;
        let long_is_x = curv.a <= curv.b;
        // ratio = C_short / C_long >= 1 (the long axis has the smaller curvature).
        let ratio = if long_is_x { curv.b / curv.a } else { curv.a / curv.b };
        let kp2 = if (ratio - 1.0).abs() < 1e-14 {
            1.0
        } else {
            // g(k'^2) = R_D(0,1,k'^2)/R_D(0,k'^2,1) decreases from +inf (k'->0) to 1.
            let f = |kp2: f64| (rd(0.0, 1.0, kp2) / rd(0.0, kp2, 1.0)).ln() - ratio.ln();
            let mut tol = ShapeTolerance { iterations: 0 };
            find_root_brent(1e-14, 1.0, f, &mut tol).map_err(|_| HertzError::TooElongated(ratio))?
        };
        Ok(HertzShape { curv, elastic, kp2, long_is_x })
    }

    /// Semi-axis ratio a/b (1), independent of N.
    pub fn aspect(&self) -> f64 {
        let k = self.kp2.sqrt();
        if self.long_is_x { 1.0 / k } else { k }
    }

    /// The Hertz patch for normal force `normal_force` (N, > 0).
    pub fn patch(&self, normal_force: f64) -> Result<HertzPatch, HertzError> {
        if !(normal_force > 0.0 && normal_force.is_finite()) {
            return Err(HertzError::NoContact(normal_force));
        }
        let e_star = self.elastic.contact_modulus();
        let c_long = if self.long_is_x { self.curv.a } else { self.curv.b };
        let long = (normal_force * rd(0.0, self.kp2, 1.0) / (2.0 * PI * e_star * c_long)).cbrt();
        let short = long * self.kp2.sqrt();
        let (a, b) = if self.long_is_x { (long, short) } else { (short, long) };
        let p0 = 3.0 * normal_force / (2.0 * PI * a * b);
        let k_integral = ellipk(1.0 - self.kp2).expect("K argument in range");
        let approach = p0 * short * k_integral / e_star;
        Ok(HertzPatch { a, b, p0, approach, normal_force })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn steel() -> Elastic {
        Elastic { young_modulus: 2.1e11, poisson_ratio: 0.3 }
    }

    fn rel(x: f64, y: f64) -> f64 {
        (x - y).abs() / y.abs()
    }

    #[test]
    fn circle_matches_closed_form() {
        // a^3 = 3 N R / (4 E*), R = 1/(2A); approach = a^2 / R.
        let el = steel();
        let shape = HertzShape::new(Curvatures { a: 2.0, b: 2.0 }, el).unwrap();
        let p = shape.patch(1e4).unwrap();
        let r = 0.25;
        let a = (3.0 * 1e4 * r / (4.0 * el.contact_modulus())).cbrt();
        assert!(rel(p.a, a) < 1e-12 && rel(p.b, a) < 1e-12);
        assert!(rel(p.approach, a * a / r) < 1e-12);
    }

    #[test]
    fn nearly_circular_is_continuous() {
        let el = steel();
        let c = HertzShape::new(Curvatures { a: 2.0, b: 2.0 }, el).unwrap().patch(1e4).unwrap();
        let n = HertzShape::new(Curvatures { a: 2.0, b: 2.0 * (1.0 + 1e-9) }, el).unwrap().patch(1e4).unwrap();
        assert!(rel(n.a, c.a) < 1e-8 && rel(n.approach, c.approach) < 1e-8);
    }
}
