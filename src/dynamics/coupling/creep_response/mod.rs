//! The creep forces' small-signal response to a harmonic variation of the
//! creepages, the spin and the normal force at the variation's own
//! frequency: the frequency-dependent creep coefficients of Knothe and
//! Gross-Thebing (Vehicle System Dynamics 15 (1986) 133-153; Gross-Thebing,
//! VSD 18 (1989) 359-374), computed from the project's own transient
//! contact solvers on the grid and model a passage uses, to take the place
//! of the steady creep curve's slopes in the dynamics loops.
//!
//! # Definition and conventions
//!
//! About a steady mean state (normal force `N0`, creepages `xi_x0`,
//! `xi_y0`, spin `phi0`, speed `V`, friction `mu`) the inputs
//! `q = (xi_x, xi_y, phi, N)` vary as `q = q0 + Re(q^ exp(i w t))` and,
//! once the contact's history has forgotten the start, the forces on the
//! wheel as `F = F0 + Re(F^ exp(i w t)) + O(|q^|^2)` with
//!
//! ```text
//! F^_i = sum_j H_ij(w) q^_j,   i in (x, y),   j in (xi_x, xi_y, phi, N).    (1)
//! ```
//!
//! `H` is a 2 x 4 complex matrix per frequency: time dependence
//! `exp(+i w t)` as in the rest of [`crate::dynamics`] (a profile harmonic
//! `exp(i k X)` met at `X = V t` has `w = k V`); the forces are those on the
//! wheel (the project's convention, [`crate::contact`]: `F_x = -G a b C11
//! xi_x` in the linear theory, so `H_xx(0) < 0`). Units: `H_x,xi` and
//! `H_y,xi` in N (per unit creepage), `H_.,phi` in N m (the spin is in
//! 1/m), `H_.,N` dimensionless. The response depends on the frequency
//! through the reduced frequency `w a0 / V` (`a0` the mean patch's
//! semi-axis along the rolling direction): [`CreepResponse`] is tabulated
//! against it and converts with the speed of its mean state.
//!
//! At `w = 0`, `H` is the steady creep curve's Jacobian `dF/dq`: the
//! slopes `C_xi = dF_x/dxi_x` and `C_N = dF_x/dN` that
//! [`crate::dynamics::wheelset::torsion`] takes from FASTSIM are `H_xx(0)` and
//! `H_xN(0)`.
//!
//! # Method ([`measure`])
//!
//! The scene's own tangential solver rolls over a stretch: a run-in at the
//! mean state (under force control where the mean longitudinal force is
//! prescribed, so that the history settles in about one patch length; at
//! the prescribed creepage otherwise), then one input's multi-sine, all
//! harmonics `k_n = 2 pi n / L` of the measured period `L` up to the
//! largest reduced frequency asked at once, with Schroeder's phases (a
//! crest factor of about 1.7, against 3-4 for random phases at the same
//! power) and a constant offset (the steady slope), for a lead and the
//! measured period. Two runs of opposite sign per input: half their
//! difference holds the odd part of the response, so that the mean, what
//! the start-up leaves and the even orders of the nonlinearity cancel. `H`
//! is the ratio of the force's and the input's discrete Fourier
//! coefficients over the measured period. The runs go in parallel, each on
//! its own solver. Defaults, their measured convergence and the cost:
//! `build::creep_response` (the assembly, which measures a scene's
//! response with the scene's own solver) and
//! `docs/src/theory/creep-response.md`.
//!
//! The closed form of the simplified (Winkler) theory in full adhesion,
//! which tests the simplified-transient solver, is [`brush`].

pub mod brush;
mod measure;

pub use measure::{Excitation, input_scale, measure, steady_forces};

use num_complex::Complex64;
use std::f64::consts::PI;

/// The inputs of eq. 1, in the order of `H`'s columns.
#[derive(Debug, Clone, Copy, PartialEq, Eq, strum::IntoStaticStr)]
#[strum(serialize_all = "snake_case")]
pub enum Input {
    /// Longitudinal creepage xi_x (1).
    CreepageX = 0,
    /// Lateral creepage xi_y (1).
    CreepageY = 1,
    /// Spin phi (1/m).
    Spin = 2,
    /// Normal force N (N).
    NormalForce = 3,
}

impl Input {
    /// The four inputs in column order.
    pub const ALL: [Input; 4] = [Input::CreepageX, Input::CreepageY, Input::Spin, Input::NormalForce];

    /// The column of `H`.
    pub fn index(self) -> usize {
        self as usize
    }

    /// Name (snake case) for tables.
    pub fn name(self) -> &'static str {
        self.into()
    }
}

/// How the mean longitudinal state is prescribed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Longitudinal {
    /// The mean longitudinal force on the wheel (N): the mean creepage is
    /// the solver's steady answer to it.
    Force(f64),
    /// The mean longitudinal creepage (1).
    Creepage(f64),
}

/// The contact's mean state (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeanState {
    /// Mean normal force N0 (N, > 0).
    pub normal_force: f64,
    /// Mean longitudinal force or creepage.
    pub longitudinal: Longitudinal,
    /// Mean lateral creepage xi_y0 (1).
    pub creepage_y: f64,
    /// Mean spin phi0 (1/m).
    pub spin: f64,
    /// Rolling speed V (m/s, > 0).
    pub speed: f64,
    /// Friction coefficient mu (1) at zero slip speed.
    pub friction: f64,
    /// How the friction coefficient varies with the slip speed.
    pub characteristic: crate::contact::friction::Characteristic,
    /// Friction memory.
    pub memory: Option<crate::contact::friction::FrictionMemory>,
}

/// One frequency's response, `h[i][j] = dF_i / dq_j` (eq. 1): rows
/// `(F_x, F_y)` on the wheel, columns [`Input`].
pub type Matrix = [[Complex64; 4]; 2];

/// The creep forces' frequency response about a mean state (eq. 1),
/// tabulated against the reduced frequency and interpolated.
#[derive(Debug, Clone, PartialEq)]
pub struct CreepResponse {
    /// Rolling speed V of the mean state (m/s).
    pub speed: f64,
    /// Semi-axis a0 of the mean patch along the rolling direction (m).
    pub semi_axis: f64,
    /// Mean longitudinal creepage xi_x0 (1), found or prescribed.
    pub creepage_x: f64,
    /// Mean forces on the wheel (F_x0, F_y0) at the end of the run-in (N).
    pub force: [f64; 2],
    /// Reduced frequencies `w a0 / V` of the table (1): 0, then the
    /// harmonics of the measured period, uniformly spaced.
    pub reduced: Vec<f64>,
    /// `H` at each reduced frequency (units of eq. 1).
    pub table: Vec<Matrix>,
    /// Which inputs were measured (the other columns are zero).
    pub measured: [bool; 4],
}

impl CreepResponse {
    /// `H` at frequency `f_hz` (Hz, >= 0) for the mean state's speed.
    pub fn at(&self, f_hz: f64) -> Matrix {
        self.at_reduced(2.0 * PI * f_hz * self.semi_axis / self.speed)
    }

    /// `H` at the reduced frequency `w a0 / V` (1); `H(-w) = conj H(w)` for
    /// negative arguments.
    ///
    /// Within the table: cubic Hermite interpolation of the real and
    /// imaginary parts with slopes by central differences (at 0 through
    /// the mirrored point `H(-w) = conj H(w)`), of `1 / H` for an entry
    /// whose magnitude stays above [`INVERSE_FLOOR`] of its largest over
    /// the table, of `H` otherwise (the entries that vanish by symmetry).
    /// `1 / H` is nearly linear in `w` where the force lags the input like a
    /// first-order system and where it falls as `1 / w`: on the paper's
    /// scene its interpolation is within 6e-4 of `|H(0)|` of a table twice
    /// as dense, that of `H` within 2.2e-2 (between 0 and the first
    /// harmonic). Beyond the last point `w_M`: `H(w_M) w_M / w` for the
    /// creepage columns (the high-frequency limit of an adhering patch, a
    /// spring driven by the slip velocity, `F^ = -K V xi^ / (i w)`),
    /// `H(w_M) (w_M / w)^2` for the spin's (a rotation about the normal
    /// loads the adhering patch with a moment, no net force), `H(w_M)` for
    /// the normal force's (its limit is the slip area's share `mu dN_slip /
    /// dN`, a constant).
    pub fn at_reduced(&self, w: f64) -> Matrix {
        if w < 0.0 {
            return conj(&self.at_reduced(-w));
        }
        let m = self.reduced.len() - 1;
        let last = self.reduced[m];
        if w >= last {
            let mut h = self.table[m];
            for row in h.iter_mut() {
                for (j, c) in row.iter_mut().enumerate() {
                    *c *= match j {
                        3 => 1.0,
                        2 => (last / w).powi(2),
                        _ => last / w,
                    };
                }
            }
            return h;
        }
        let d = self.reduced[1] - self.reduced[0];
        let i = ((w / d).floor() as usize).min(m - 1);
        let t = (w - self.reduced[i]) / d;
        let (t2, t3) = (t * t, t * t * t);
        let (h00, h10, h01, h11) = (2.0 * t3 - 3.0 * t2 + 1.0, t3 - 2.0 * t2 + t, -2.0 * t3 + 3.0 * t2, t3 - t2);
        let mut out = [[Complex64::new(0.0, 0.0); 4]; 2];
        for (r, row) in out.iter_mut().enumerate() {
            for (c, v) in row.iter_mut().enumerate() {
                let largest = self.table.iter().map(|h| h[r][c].norm()).fold(0.0, f64::max);
                let inverse = largest > 0.0 && self.table.iter().all(|h| h[r][c].norm() >= INVERSE_FLOOR * largest);
                let f = |h: Complex64| if inverse { 1.0 / h } else { h };
                // Point k of the entry, mirrored below 0.
                let point = |k: isize| {
                    f(if k < 0 { self.table[(-k) as usize][r][c].conj() } else { self.table[k as usize][r][c] })
                };
                let slope = |k: usize| {
                    let k = k as isize;
                    if k as usize == m { point(k) - point(k - 1) } else { 0.5 * (point(k + 1) - point(k - 1)) }
                };
                let i = i as isize;
                let y = h00 * point(i) + h10 * slope(i as usize) + h01 * point(i + 1) + h11 * slope(i as usize + 1);
                *v = f(y);
            }
        }
        out
    }

    /// The steady Jacobian `dF/dq` (`H` at zero frequency).
    pub fn steady(&self) -> [[f64; 4]; 2] {
        self.table[0].map(|row| row.map(|c| c.re))
    }

    /// The largest reduced frequency of the table.
    pub fn max_reduced(&self) -> f64 {
        *self.reduced.last().expect("a table has points")
    }
}

/// The smallest magnitude, relative to the largest over the table, at
/// which an entry is interpolated through its inverse.
pub const INVERSE_FLOOR: f64 = 1e-2;

fn conj(h: &Matrix) -> Matrix {
    h.map(|row| row.map(|c| c.conj()))
}

/// Why a response could not be computed.
#[derive(Debug, thiserror::Error)]
pub enum CreepResponseError {
    /// The excitation or mean state is out of range.
    #[error("creep response: {0}")]
    Input(String),
    /// The normal problem of a step has no solution.
    #[error("creep response, {input} run, step {step}: {source}")]
    Normal {
        /// The run's input (or "reference").
        input: &'static str,
        /// Step index.
        step: usize,
        /// Cause.
        source: crate::hertz::HertzError,
    },
    /// The tangential solver failed.
    #[error("creep response, {input} run, step {step}: {source}")]
    Contact {
        /// The run's input (or "reference").
        input: &'static str,
        /// Step index.
        step: usize,
        /// Cause.
        source: crate::contact::ContactError,
    },
    /// A force came out non-finite.
    #[error("creep response, {input} run: non-finite force at step {step}")]
    NonFinite {
        /// The run's input (or "reference").
        input: &'static str,
        /// Step index.
        step: usize,
    },
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A table of `f` at `0, d, ..., m d` in every entry, `g` in the
    /// entries that vanish by symmetry (row x, columns y and spin).
    fn table(f: impl Fn(f64) -> Complex64, g: impl Fn(f64) -> Complex64, d: f64, m: usize) -> CreepResponse {
        let reduced: Vec<f64> = (0..=m).map(|k| k as f64 * d).collect();
        let table = reduced
            .iter()
            .map(|&w| {
                let (v, z) = (f(w), g(w));
                [[v, z, z, v], [v, v, v, v]]
            })
            .collect();
        CreepResponse {
            speed: 10.0,
            semi_axis: 5e-3,
            creepage_x: 0.0,
            force: [0.0; 2],
            reduced,
            table,
            measured: [true; 4],
        }
    }

    #[test]
    fn a_first_order_lag_is_interpolated_exactly_through_its_inverse() {
        // 1 / H = (1 + i w tau) / H0 is linear in w: the cubic of 1 / H is
        // exact, also below the first point (mirrored, H(-w) = conj H(w)).
        let lag = |w: f64| Complex64::new(-2.0, 0.0) / Complex64::new(1.0, 0.7 * w);
        let r = table(lag, |_| Complex64::new(0.0, 0.0), 0.4, 15);
        for k in 0..=600 {
            let w = k as f64 * 0.01;
            let h = r.at_reduced(w);
            assert!((h[0][0] - lag(w)).norm() < 1e-12, "{w}");
            assert_eq!(h[0][1], Complex64::new(0.0, 0.0));
        }
        assert_eq!(r.at_reduced(-1.3)[1][1], r.at_reduced(1.3)[1][1].conj());
        let hz = 1.3 * r.speed / (2.0 * PI * r.semi_axis);
        assert!((r.at(hz)[0][0] - r.at_reduced(1.3)[0][0]).norm() < 1e-14);
    }

    #[test]
    fn the_brush_response_is_interpolated_within_its_tolerance() {
        // The simplified theory's creepage response on the default spacing
        // (pi / 4): the interpolation of 1 / H within 5e-3 of H(0) (3.7e-3;
        // the exact model's tables 1.3e-3, docs); an entry
        // through zero (odd in w, 0 at w = 0) is interpolated directly,
        // exact at the points.
        let odd = |w: f64| Complex64::new(0.0, w * (-0.3 * w).exp());
        let r = table(brush::creepage_ratio, odd, PI / 4.0, 8);
        let worst = (0..620)
            .map(|k| k as f64 * 0.01)
            .map(|w| (r.at_reduced(w)[1][0] - brush::creepage_ratio(w)).norm())
            .fold(0.0, f64::max);
        eprintln!("brush interpolated on pi / 4: worst {worst:.2e}");
        assert!(worst < 5e-3, "{worst}");
        for k in 0..=8 {
            let w = k as f64 * PI / 4.0;
            assert!((r.at_reduced(w)[0][1] - odd(w)).norm() < 1e-14, "{w}");
        }
    }

    #[test]
    fn beyond_the_table_creepage_falls_as_one_over_w_spin_as_its_square_and_the_normal_force_holds() {
        let r = table(|w| Complex64::new(1.0 + w, -w), |_| Complex64::new(0.5, 0.0), 0.5, 4);
        let h = r.at_reduced(2.0);
        let far = r.at_reduced(4.0);
        for row in 0..2 {
            for c in 0..4 {
                let factor = [0.5, 0.5, 0.25, 1.0][c];
                assert!((far[row][c] - factor * h[row][c]).norm() < 1e-14, "{row} {c}");
            }
        }
    }
}
