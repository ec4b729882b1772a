//! The linear profile contact's pressure on the fixed grid's elements:
//! the first-order pressure of [`super::MeshResponse`] averaged over each
//! element, so that an element's pressure changes smoothly as the patch's
//! edge moves over it (no element enters or leaves the contact with
//! pressure).

use super::{LinearFit, MeshResponse};
use crate::contact::grid::RailSurface;
use crate::hertz::HertzPatch;

impl MeshResponse {
    /// The step's first-order patch over `surface` with the Hertz pressure
    /// shape, averaged over rectangular elements: `centres` (x, y) relative
    /// to the wheel's `X_c` (m), each `2 hx` x `2 hy` (m) (the fixed grid's
    /// elements). The pressure (Pa) is the mean of the first-order pressure
    /// `p0' sqrt(max(0, G))`, `G = 1 - rho'^2 + 2 q_r / p0'`, over each
    /// element, scaled so that its sum times the element area is the
    /// normal force; the count is that of elements well inside the patch
    /// where it vanished ([`super::LinearPatch::clipped`]).
    ///
    /// The mean along x is that of `G` quadratic in x over the element (the
    /// moved ellipse's part is; the remainder's is fitted through the
    /// element's ends and centre), `int sqrt(c0 + c1 u + c2 u^2) du` between
    /// its roots with the square root's edge taken out
    /// (`sqrt_quadratic_mean`); across, Gauss-Legendre over the part of
    /// the element where `G > 0` somewhere along x. So the
    /// pressure of an element changes smoothly as the edge moves over it:
    /// sampled at the centres, an element near the edge changes its
    /// pressure as the square root of the edge's move, and the growth rate
    /// of one harmonic changed by 25 % between 0.2 and 2 um.
    pub fn pressure_on_cells(
        &self,
        surface: &RailSurface,
        position: f64,
        patch: &HertzPatch,
        centres: &[(f64, f64)],
        (hx, hy): (f64, f64),
    ) -> Result<(Vec<f64>, usize), crate::contact::ContactError> {
        let fit = self.fit(surface, position, patch, false, true)?;
        let flat = LinearFit::flat(patch);
        let f = fit.as_ref().unwrap_or(&flat);
        let (mut pressure, mut clipped) = f.cells(f.shift, centres, (hx, hy));
        if fit.is_some() {
            // The first moment is the fit's (exact to first order, by
            // reciprocity): the remainder, discretised, moves the centroid
            // too (by 13 % of the shift of a 15 mm wave under a 12 mm
            // patch); the ellipse is moved back by that much once.
            let total: f64 = pressure.iter().sum();
            let centroid = pressure.iter().zip(centres).map(|(p, c)| p * c.0).sum::<f64>() / total;
            if total > 0.0 && centroid.is_finite() {
                (pressure, clipped) = f.cells(2.0 * f.shift - centroid, centres, (hx, hy));
            }
        }
        let total: f64 = pressure.iter().sum::<f64>() * 4.0 * hx * hy;
        if total.is_nan() || total <= 0.0 {
            return Err(f.out_of_range());
        }
        pressure.iter_mut().for_each(|p| *p *= patch.normal_force / total);
        Ok((pressure, clipped))
    }
}

impl LinearFit {
    /// The Hertz patch itself (a flat surface).
    fn flat(patch: &HertzPatch) -> Self {
        LinearFit {
            shift: 0.0,
            a: patch.a,
            b: patch.b,
            hertz_a: patch.a,
            hertz_b: patch.b,
            p0: patch.p0,
            q_r: Vec::new(),
            normal_nx: 0,
            normal_ny: 0,
            stretch: 0.0,
        }
    }

    /// The mean of `sqrt(max(0, G))` over each element (see
    /// [`MeshResponse::pressure_on_cells`]) with the ellipse centred at
    /// `shift` (m) from `X_c` (the remainder stays where the fit put it),
    /// unscaled; and the elements well inside where it vanished.
    fn cells(&self, shift: f64, centres: &[(f64, f64)], (hx, hy): (f64, f64)) -> (Vec<f64>, usize) {
        let (a, b) = (self.a, self.b);
        let mut clipped = 0;
        let (ia2, ib2) = (1.0 / (a * a), 1.0 / (b * b));
        let pressure: Vec<f64> = centres
            .iter()
            .map(|&(xc, yc)| {
                // Outside the moved ellipse's box (with one element to spare
                // for the remainder's edge): no contact.
                if (xc - shift).abs() > a + 2.0 * hx || yc.abs() > b + 2.0 * hy {
                    return 0.0;
                }
                // G = 1 + g(x) - (x - s)^2 / a'^2 - y^2 / b'^2 over the
                // element, the remainder g quadratic in x through its ends
                // and centre (taken on the centre line across).
                let u = xc - shift;
                let rest = |x: f64| self.rest((x + shift - self.shift) / a, yc / b);
                let (gm, g0, gp) = (rest(u - hx), rest(u), rest(u + hx));
                let (g1, g2) = ((gp - gm) / (2.0 * hx), (gp - 2.0 * g0 + gm) / (2.0 * hx * hx));
                // Across: the part of the element where G > 0 somewhere
                // along x, Gauss-Legendre on it (the chord's mean is smooth
                // there).
                let (c1, c2) = (g1 - 2.0 * u * ia2, g2 - ia2);
                let c = 1.0 + g0 - u * u * ia2;
                let peak = if c2 < 0.0 { c - c1 * c1 / (4.0 * c2) } else { c + c1.abs() * hx + c2 * hx * hx };
                if peak <= 0.0 {
                    return 0.0;
                }
                let reach = b * peak.sqrt();
                let (lo, hi) = ((yc - hy).max(-reach), (yc + hy).min(reach));
                if hi <= lo {
                    return 0.0;
                }
                let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
                let mean: f64 = CELL_GAUSS
                    .iter()
                    .map(|&(t, w)| {
                        let y = mid + half * t;
                        w * sqrt_quadratic_mean(c - y * y * ib2, c1, c2, hx)
                    })
                    .sum::<f64>()
                    * half
                    / (4.0 * hx * hy);
                let inside = 1.0 - u * u * ia2 - yc * yc * ib2;
                if mean <= 0.0 && inside > 0.25 {
                    clipped += 1;
                }
                mean
            })
            .collect();
        (pressure, clipped)
    }
}

/// Gauss-Legendre points and weights on [-1, 1] (4 points) of the cell
/// means across.
const CELL_GAUSS: [(f64, f64); 4] = [
    (-0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
    (-0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
    (0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
    (0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
];

/// Gauss-Legendre points and weights on [-1, 1] (8 points) of the cell
/// integral along x.
const SEGMENT_GAUSS: [(f64, f64); 8] = [
    (-0.960_289_856_497_536_3, 0.101_228_536_290_376_26),
    (-0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (-0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (-0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (0.960_289_856_497_536_3, 0.101_228_536_290_376_26),
];

/// `int_{-h}^{h} sqrt(max(0, G(u))) du` for `G(u) = c0 + c1 u + c2 u^2`:
/// the roots of `G` in the interval (stable quadratic formula), and a
/// convex one's vertex, split it;
/// on each part where `G > 0`, `u = m + l sin(theta)` takes the square
/// root's edge at a root into a smooth integrand (`sqrt(G) cos(theta)`
/// vanishes there like `(theta -+ pi/2)^2`), integrated by Gauss-Legendre.
/// Smooth in the coefficients as a root moves over the interval, and
/// accurate for either sign of `c2` and for `c2` near zero (the closed form
/// of a circular segment cancels there).
fn sqrt_quadratic_mean(c0: f64, c1: f64, c2: f64, h: f64) -> f64 {
    let g = |u: f64| c0 + c1 * u + c2 * u * u;
    let mut cuts = [-h, h, h, h, h];
    let mut n = 1;
    let mut root = |u: f64| {
        if u.is_finite() && u > -h && u < h {
            cuts[n] = u;
            n += 1;
        }
    };
    if c2 != 0.0 {
        let disc = c1 * c1 - 4.0 * c2 * c0;
        if disc > 0.0 {
            let q = -0.5 * (c1 + c1.signum() * disc.sqrt());
            if q != 0.0 {
                root(q / c2);
                root(c0 / q);
            }
        }
        // A convex quadratic's vertex: where it touches zero, the square
        // root has a kink there.
        if c2 > 0.0 {
            root(-c1 / (2.0 * c2));
        }
    } else if c1 != 0.0 {
        root(-c0 / c1);
    }
    cuts[n] = h;
    cuts[1..n].sort_by(f64::total_cmp);
    let mut total = 0.0;
    for k in 0..n {
        let (p, q) = (cuts[k], cuts[k + 1]);
        if q <= p || g(0.5 * (p + q)) < 0.0 {
            continue;
        }
        let (m, l) = (0.5 * (p + q), 0.5 * (q - p));
        let part: f64 = SEGMENT_GAUSS
            .iter()
            .map(|&(t, w)| {
                let theta = 0.5 * std::f64::consts::PI * t;
                w * g(m + l * theta.sin()).max(0.0).sqrt() * theta.cos()
            })
            .sum();
        total += part * l * 0.5 * std::f64::consts::PI;
    }
    // (A NaN coefficient stays NaN, for the caller's check.)
    if total.is_nan() { total } else { total.max(0.0) }
}

#[cfg(test)]
mod segment_tests {
    use super::sqrt_quadratic_mean;

    /// A fine midpoint rule of the same integral.
    fn reference(c0: f64, c1: f64, c2: f64, h: f64) -> f64 {
        let n = 200_000;
        let du = 2.0 * h / n as f64;
        (0..n).map(|i| -h + (i as f64 + 0.5) * du).map(|u| (c0 + c1 * u + c2 * u * u).max(0.0).sqrt() * du).sum()
    }

    #[test]
    fn the_cell_integral_holds_for_every_kind_of_quadratic() {
        // Elements at u = 5.5 mm (inside), 6.0 and 6.1 mm (the edge of a
        // 6 mm patch inside the element) with h = 0.2 mm, c2 from a strongly
        // concave quadratic through zero to convex ones, and a chord wholly
        // inside (both roots).
        let h = 2e-4;
        for u in [5.5e-3, 6.0e-3, 6.1e-3] {
            for c2 in [-1.0 / 36e-6, -1e-2, -1e-4, -1e-6, 0.0, 1e-6, 1e3] {
                let (c1, c0) = (-2.0 * u / 36e-6, 1.0 - u * u / 36e-6);
                let (v, r) = (sqrt_quadratic_mean(c0, c1, c2, h), reference(c0, c1, c2, h));
                assert!(r > 0.0 && (v - r).abs() < 1e-4 * r, "u {u}, c2 {c2}: {v:e} vs {r:e}");
            }
        }
        // A double root at the element's centre: sqrt(c2) h^2.
        let v = sqrt_quadratic_mean(0.0, 0.0, 4.0, h);
        assert!((v - 2.0 * h * h).abs() < 1e-12, "{v}");
        let (v, r) = (sqrt_quadratic_mean(1e-4, 0.0, -1e4, h), reference(1e-4, 0.0, -1e4, h));
        assert!((v - r).abs() < 1e-4 * r, "chord inside: {v:e} vs {r:e}");
        assert_eq!(sqrt_quadratic_mean(-1.0, 0.0, -1.0, h), 0.0);
    }
}
