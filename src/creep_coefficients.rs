//! Kalker's creep coefficients C11, C22, C23 of the linear theory of rolling
//! contact for elliptic patches.
//!
//! Source: J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
//! Kluwer 1990, table E.3 (the same numbers as Kalker's 1967 thesis), given for
//! a/b = 0.1 ... 1 and b/a = 0.1 ... 1 at nu = 0, 0.25, 0.5.
//!
//! Interpolation rule (the one CONTACT's FASTSIM uses, which reproduces its
//! printed flexibilities to 0.3 %): in each half of the table the coefficients
//! are linear in the tabulated ratio `g = min(a/b, b/a)` (uniform 0.1 spacing),
//! and quadratic in nu through the three tabulated values (Lagrange). The table
//! covers 0.1 <= a/b <= 10 and 0 <= nu <= 0.5; outside it is an error.

/// Linear-theory coefficients (1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CreepCoefficients {
    /// Longitudinal creepage coefficient C11.
    pub c11: f64,
    /// Lateral creepage coefficient C22.
    pub c22: f64,
    /// Spin coefficient C23 of the lateral force.
    pub c23: f64,
}

/// Out-of-table request.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum CreepTableError {
    /// Semi-axis ratio outside Kalker's table.
    #[error("semi-axis ratio a/b = {0:.4} outside Kalker's table range [0.1, 10]")]
    Aspect(f64),
    /// Poisson's ratio outside Kalker's table.
    #[error("Poisson's ratio {0} outside Kalker's table range [0, 0.5]")]
    Poisson(f64),
}

#[allow(clippy::approx_constant)] // table values, not pi
/// Rows [nu = 0, 0.25, 0.5] x [C11, C22, C23], for a/b = 0.1, 0.2, ... 1.0.
const A_OVER_B: [[[f64; 3]; 3]; 10] = [
    [[2.51, 2.51, 0.334], [3.31, 2.52, 0.473], [4.85, 2.53, 0.731]],
    [[2.59, 2.59, 0.483], [3.37, 2.63, 0.603], [4.81, 2.66, 0.809]],
    [[2.68, 2.68, 0.607], [3.44, 2.75, 0.715], [4.8, 2.81, 0.889]],
    [[2.78, 2.78, 0.72], [3.53, 2.88, 0.823], [4.82, 2.98, 0.977]],
    [[2.88, 2.88, 0.827], [3.62, 3.01, 0.929], [4.83, 3.14, 1.07]],
    [[2.98, 2.98, 0.93], [3.72, 3.14, 1.03], [4.91, 3.31, 1.18]],
    [[3.09, 3.09, 1.03], [3.81, 3.28, 1.14], [4.97, 3.48, 1.29]],
    [[3.19, 3.19, 1.13], [3.91, 3.41, 1.25], [5.05, 3.65, 1.4]],
    [[3.29, 3.29, 1.23], [4.01, 3.54, 1.36], [5.12, 3.82, 1.51]],
    [[3.4, 3.4, 1.33], [4.12, 3.67, 1.47], [5.2, 3.98, 1.63]],
];

/// Same layout for b/a = 0.1, 0.2, ... 0.9 (b/a = 1 is the last row above).
const B_OVER_A: [[[f64; 3]; 3]; 9] = [
    [[10.7, 10.7, 12.2], [11.7, 12.8, 14.6], [12.9, 16.0, 18.0]],
    [[6.96, 6.96, 5.72], [7.78, 8.14, 6.63], [8.82, 9.79, 7.89]],
    [[5.57, 5.57, 3.79], [6.34, 6.4, 4.32], [7.34, 7.51, 5.01]],
    [[4.84, 4.84, 2.88], [5.57, 5.48, 3.24], [6.57, 6.31, 3.7]],
    [[4.37, 4.37, 2.35], [5.1, 4.9, 2.62], [6.11, 5.56, 2.96]],
    [[4.06, 4.06, 2.01], [4.78, 4.5, 2.23], [5.8, 5.04, 2.5]],
    [[3.82, 3.82, 1.76], [4.54, 4.21, 1.95], [5.58, 4.67, 2.18]],
    [[3.65, 3.65, 1.58], [4.36, 3.99, 1.75], [5.42, 4.39, 1.94]],
    [[3.51, 3.51, 1.44], [4.22, 3.81, 1.59], [5.3, 4.16, 1.77]],
];

/// Table row at g = 0.1 (i + 1) of the lower (a/b <= 1) or upper half.
fn row(upper: bool, i: usize) -> &'static [[f64; 3]; 3] {
    if upper && i < 9 { &B_OVER_A[i] } else { &A_OVER_B[i] }
}

/// Quadratic Lagrange interpolation in nu through nu = 0, 0.25, 0.5.
fn in_nu(row: &[[f64; 3]; 3], nu: f64, c: usize) -> f64 {
    let (f0, f1, f2) = (row[0][c], row[1][c], row[2][c]);
    let l0 = (nu - 0.25) * (nu - 0.5) / (0.25 * 0.5);
    let l1 = nu * (nu - 0.5) / (0.25 * -0.25);
    let l2 = nu * (nu - 0.25) / (0.5 * 0.25);
    f0 * l0 + f1 * l1 + f2 * l2
}

/// Kalker's C11, C22, C23 for semi-axis ratio `a_over_b` (a along rolling)
/// and Poisson's ratio `nu`, interpolated as described in the module docs.
pub fn creep_coefficients(a_over_b: f64, nu: f64) -> Result<CreepCoefficients, CreepTableError> {
    if !(0.1 - 1e-12..=10.0 + 1e-9).contains(&a_over_b) {
        return Err(CreepTableError::Aspect(a_over_b));
    }
    if !(0.0..=0.5).contains(&nu) {
        return Err(CreepTableError::Poisson(nu));
    }
    let upper = a_over_b > 1.0;
    let g = if upper { 1.0 / a_over_b } else { a_over_b };
    let pos = (g * 10.0 - 1.0).clamp(0.0, 9.0);
    let i = (pos.floor() as usize).min(8);
    let t = pos - i as f64;
    let c = |k: usize| (1.0 - t) * in_nu(row(upper, i), nu, k) + t * in_nu(row(upper, i + 1), nu, k);
    Ok(CreepCoefficients { c11: c(0), c22: c(1), c23: c(2) })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reproduces_table_nodes() {
        let c = creep_coefficients(0.5, 0.25).unwrap();
        assert!((c.c11 - 3.62).abs() < 1e-12 && (c.c22 - 3.01).abs() < 1e-12 && (c.c23 - 0.929).abs() < 1e-12);
        let c = creep_coefficients(2.0, 0.5).unwrap();
        assert!((c.c11 - 6.11).abs() < 1e-12 && (c.c23 - 2.96).abs() < 1e-12);
        let c = creep_coefficients(1.0, 0.0).unwrap();
        assert!((c.c11 - 3.4).abs() < 1e-12);
    }

    #[test]
    fn continuous_across_circle() {
        let lo = creep_coefficients(1.0 - 1e-9, 0.3).unwrap();
        let hi = creep_coefficients(1.0 + 1e-9, 0.3).unwrap();
        assert!((lo.c11 - hi.c11).abs() < 1e-6 && (lo.c23 - hi.c23).abs() < 1e-6);
    }

    #[test]
    fn matches_contact_flexibilities() {
        // CONTACT (shared reference README) prints L1, L2, L3 for the paper's
        // patches; L1 = 8a/(3 C11 G), L2 = 8a/(3 C22 G), L3 = pi a sqrt(a/b)/(4 C23 G).
        let g = 80769.23; // N/mm^2
        for (a, b, l1, l2, l3) in
            [(8.067, 3.991, 5.026e-5, 5.272e-5, 4.107e-5), (5.957, 10.22, 5.049e-5, 6.243e-5, 4.261e-5)]
        {
            let c = creep_coefficients(a / b, 0.3).unwrap();
            let rel = |x: f64, y: f64| ((x - y) / y).abs();
            assert!(rel(8.0 * a / (3.0 * c.c11 * g), l1) < 0.005, "L1 {a}");
            assert!(rel(8.0 * a / (3.0 * c.c22 * g), l2) < 0.005, "L2 {a}");
            let l3m = std::f64::consts::PI * a * (a / b).sqrt() / (4.0 * c.c23 * g);
            assert!(rel(l3m, l3) < 0.005, "L3 {a}");
        }
    }

    #[test]
    fn out_of_range_is_error() {
        assert_eq!(creep_coefficients(0.05, 0.3), Err(CreepTableError::Aspect(0.05)));
        assert_eq!(creep_coefficients(1.0, 0.6), Err(CreepTableError::Poisson(0.6)));
    }
}
