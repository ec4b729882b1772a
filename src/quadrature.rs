//! Globally adaptive Gauss-Kronrod quadrature (the 7-point Gauss and
//! 15-point Kronrod pair of QUADPACK's QK15; Piessens, de Doncker-Kapenga,
//! Überhuber, Kahaner, *QUADPACK*, Springer 1983) of complex matrix-valued
//! integrands, for the Floquet integrals of the discrete track
//! ([`crate::dynamics::track::discrete3`]), whose peaks at weakly damped waves a
//! fixed rule does not resolve.
//!
//! The integrand returns several small matrices at once; the error of an
//! interval is the largest entry of `|K15 - G7|` over them; the interval
//! with the largest error is bisected until the errors sum below
//! `tolerance` times the largest entry of the integral. (quad-rs, the
//! maintained crate with vector outputs, builds on nalgebra 0.33 and
//! ndarray 0.15, a second copy of each beside the program's.)

use nalgebra::SMatrix;
use num_complex::Complex64;

/// Kronrod nodes of QK15 on [-1, 1], the non-negative half (the odd ones
/// are the 7-point Gauss rule's).
const XGK: [f64; 8] = [
    0.991_455_371_120_812_6,
    0.949_107_912_342_758_5,
    0.864_864_423_359_769_1,
    0.741_531_185_599_394_4,
    0.586_087_235_467_691_1,
    0.405_845_151_377_397_2,
    0.207_784_955_007_898_5,
    0.0,
];
/// Kronrod weights of QK15.
const WGK: [f64; 8] = [
    0.022_935_322_010_529_22,
    0.063_092_092_629_978_55,
    0.104_790_010_322_250_2,
    0.140_653_259_715_525_9,
    0.169_004_726_639_267_9,
    0.190_350_578_064_785_4,
    0.204_432_940_075_298_9,
    0.209_482_141_084_727_8,
];
/// Gauss weights of the 7-point rule at the nodes XGK[1], XGK[3], XGK[5], XGK[7].
const WG: [f64; 4] =
    [0.129_484_966_168_869_7, 0.279_705_391_489_276_7, 0.381_830_050_505_118_9, 0.417_959_183_673_469_4];

/// The quadrature did not converge.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error("adaptive quadrature: error {error:.3e} of the integral's {scale:.3e} after {evaluations} evaluations")]
pub struct QuadratureError {
    /// Estimated absolute error left.
    pub error: f64,
    /// Largest entry of the integral.
    pub scale: f64,
    /// Integrand evaluations made.
    pub evaluations: usize,
}

struct Interval<const R: usize, const C: usize> {
    a: f64,
    b: f64,
    value: Vec<SMatrix<Complex64, R, C>>,
    error: f64,
}

fn rule<const R: usize, const C: usize>(
    f: &mut impl FnMut(f64) -> Vec<SMatrix<Complex64, R, C>>,
    a: f64,
    b: f64,
) -> Interval<R, C> {
    let (centre, half) = (0.5 * (a + b), 0.5 * (b - a));
    let mid = f(centre);
    let n = mid.len();
    let c = |v: f64| Complex64::new(v, 0.0);
    let mut kronrod: Vec<SMatrix<Complex64, R, C>> = mid.iter().map(|m| m * c(WGK[7])).collect();
    let mut gauss: Vec<SMatrix<Complex64, R, C>> = mid.iter().map(|m| m * c(WG[3])).collect();
    for j in 0..7 {
        let (lo, hi) = (f(centre - half * XGK[j]), f(centre + half * XGK[j]));
        for k in 0..n {
            let sum = lo[k] + hi[k];
            kronrod[k] += sum * c(WGK[j]);
            if j % 2 == 1 {
                gauss[k] += sum * c(WG[j / 2]);
            }
        }
    }
    let mut error = 0.0f64;
    for k in 0..n {
        kronrod[k] *= c(half);
        gauss[k] *= c(half);
        error = error.max((kronrod[k] - gauss[k]).iter().fold(0.0f64, |m, v| m.max(v.norm())));
    }
    Interval { a, b, value: kronrod, error }
}

/// The integrals over `[a, b]` of the matrices `f` returns (the same
/// number at every point), starting from `pieces` equal intervals, to the
/// relative `tolerance` of the largest entry, with at most
/// `max_evaluations` evaluations of `f`.
pub fn integrate<const R: usize, const C: usize>(
    mut f: impl FnMut(f64) -> Vec<SMatrix<Complex64, R, C>>,
    a: f64,
    b: f64,
    pieces: usize,
    tolerance: f64,
    max_evaluations: usize,
) -> Result<Vec<SMatrix<Complex64, R, C>>, QuadratureError> {
    let h = (b - a) / pieces as f64;
    let mut intervals: Vec<Interval<R, C>> = (0..pieces)
        .map(|p| rule(&mut f, a + p as f64 * h, if p + 1 == pieces { b } else { a + (p + 1) as f64 * h }))
        .collect();
    let mut evaluations = 15 * pieces;
    loop {
        let n = intervals[0].value.len();
        let total: Vec<SMatrix<Complex64, R, C>> = (0..n).map(|k| intervals.iter().map(|i| i.value[k]).sum()).collect();
        let scale = total.iter().flat_map(|m| m.iter()).fold(0.0f64, |m, v| m.max(v.norm()));
        let error: f64 = intervals.iter().map(|i| i.error).sum();
        if error <= tolerance * scale {
            return Ok(total);
        }
        if evaluations + 30 > max_evaluations {
            return Err(QuadratureError { error, scale, evaluations });
        }
        let worst =
            (0..intervals.len()).max_by(|&x, &y| intervals[x].error.total_cmp(&intervals[y].error)).expect("intervals");
        let Interval { a, b, .. } = intervals.swap_remove(worst);
        let m = 0.5 * (a + b);
        intervals.push(rule(&mut f, a, m));
        intervals.push(rule(&mut f, m, b));
        evaluations += 30;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integrates_a_sharp_lorentzian_and_a_polynomial() {
        // int_{-pi}^{pi} 1 / (x - x0 - i e) dx for a pole e = 1e-4 off the
        // axis: log((pi - z0) / (-pi - z0)), z0 = x0 + i e.
        let z0 = Complex64::new(0.3, 1e-4);
        let f = |x: f64| vec![SMatrix::<Complex64, 1, 2>::new(1.0 / (x - z0), Complex64::new(x.powi(4), 0.0))];
        let v = integrate(f, -std::f64::consts::PI, std::f64::consts::PI, 8, 1e-10, 100_000).unwrap();
        let pi = std::f64::consts::PI;
        let exact = ((pi - z0) / (-pi - z0)).ln();
        assert!((v[0][(0, 0)] - exact).norm() < 1e-8, "{} vs {exact}", v[0][(0, 0)]);
        assert!((v[0][(0, 1)].re - 2.0 * pi.powi(5) / 5.0).abs() < 1e-9 * pi.powi(5));
    }

    #[test]
    fn says_when_it_does_not_converge() {
        let f = |x: f64| vec![SMatrix::<Complex64, 1, 1>::new(Complex64::new((1.0 / (x + 1e-300)).sin(), 0.0))];
        assert!(integrate(f, -1.0, 1.0, 2, 1e-12, 2000).is_err());
    }
}
