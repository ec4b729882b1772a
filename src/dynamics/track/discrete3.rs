//! The rail on discrete supports, moving in every direction: the
//! periodic-structure (Floquet) method of [`super::discrete`] with the
//! section's six freedoms ([`super::section`]) in place of the vertical
//! displacement alone, so that the rail head's receptances in three
//! directions, and their cross terms, vary across the sleeper bay.
//!
//! # Equations
//! With the lattice sums `T(kappa, x)` of the free rail (6 x 6, in closed
//! form: [`super::waves`] eq. 2) and one support's stiffness `K_s`
//! ([`super::section`] eq. 2), the supports' displacements under a unit
//! load at `x0` have the Floquet transform `(d I + T(kappa, 0) K_s)^-1
//! T(kappa, -x0)`, and the section's response at `x1`
//! ```text
//! G(x1; x0) = G_free(x1 - x0) - 1/(2 pi) int_{-pi/d}^{pi/d} T(kappa, x1) K_s (d I + T(kappa, 0) K_s)^-1 T(kappa, -x0) d kappa   (1)
//! ```
//! (the scalar eq. 4 of [`super::discrete`] with matrices, the free term
//! integrated in closed form: the free rail's response less what the
//! supports take back). `G(x0; x1) = G(x1; x0)^T` (reciprocity). The
//! integrand peaks where the supported rail's Bloch waves travel with
//! little damping (the rail's longitudinal, lateral and torsional waves
//! above their cut-on carry only the rail's loss factor): the integral is
//! adaptive ([`crate::quadrature`], to [`TOLERANCE`] of the head's largest
//! receptance). The head's receptance is `B^T G B`.

use super::TrackConfig;
use super::layout::Layout;
use super::scattering::{self, RailWaves, ScatteringError, Supported};
use super::section::{Map64, Mat3, Mat4, Mat6, Section, pad, project};
use super::waves::{RootsError, Waves};
use crate::quadrature::{QuadratureError, integrate};
use nalgebra::SMatrix;
use num_complex::Complex64;
use std::f64::consts::PI;

/// Relative tolerance of the zone integral (of the largest entry of the
/// heads' receptances integrated together).
pub const TOLERANCE: f64 = 1e-5;

/// The arm (m) on which [`Discrete3::head_receptances4`] integrates the
/// head's rotation about `z` and the moment about it.
pub const ROTATION_ARM: f64 = 0.1;

/// The most integrand evaluations per frequency.
const MAX_EVALUATIONS: usize = 200_000;

/// Why the discrete track's receptance was not computed.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum Discrete3Error {
    /// The free rail's waves.
    #[error(transparent)]
    Roots(#[from] RootsError),
    /// The zone integral did not converge.
    #[error("the discrete track's Floquet integral at {frequency} Hz: {source}")]
    Quadrature {
        /// Frequency (Hz).
        frequency: f64,
        /// Why.
        source: QuadratureError,
    },
    /// A layout's semi-infinite track did not converge.
    #[error("the track layout's response at {frequency} Hz: {source}")]
    Layout {
        /// Frequency (Hz).
        frequency: f64,
        /// Why.
        source: ScatteringError,
    },
}

/// The error of a layout's response at angular frequency `omega` (rad/s)
/// that did not converge.
pub fn layout_at(omega: f64) -> impl Fn(ScatteringError) -> Discrete3Error {
    move |source| Discrete3Error::Layout { frequency: omega / (2.0 * PI), source }
}

/// The error of a Floquet integral at angular frequency `omega` (rad/s)
/// that did not converge.
pub fn quadrature_at(omega: f64) -> impl Fn(QuadratureError) -> Discrete3Error {
    move |source| Discrete3Error::Quadrature { frequency: omega / (2.0 * PI), source }
}

/// A place's factors in the lattice sums (eq. 2 of [`super::waves`]):
/// `x = cells d + xr`, `exp(i lambda_m xr)` and `exp(i lambda_m (d - xr))`.
struct Place {
    cells: f64,
    ahead: [Complex64; 6],
    behind: [Complex64; 6],
}

impl Place {
    fn new(waves: &Waves, x: f64, d: f64) -> Place {
        let cells = (x / d).floor();
        let xr = (x - cells * d).clamp(0.0, d);
        let e = |l: f64| -> [Complex64; 6] { std::array::from_fn(|m| (Complex64::i() * waves.lambda[m] * l).exp()) };
        Place { cells, ahead: e(xr), behind: e(d - xr) }
    }
}

/// The rail on discrete supports, and the contact on its head.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Discrete3 {
    /// The rail, its supports and the contact's offset.
    pub section: Section,
}

impl Discrete3 {
    /// The configured track, the contact `contact_offset` (m) right of the
    /// centre line.
    pub fn new(track: &TrackConfig, contact_offset: f64) -> Self {
        Discrete3 { section: Section::new(track, contact_offset) }
    }

    /// The free rail's waves at `omega` (rad/s).
    pub fn free_waves(&self, omega: f64) -> Result<Waves, RootsError> {
        let (a2, a1, a0) = self.section.free_polynomial(omega);
        Waves::new(&a2, &a1, &a0, omega)
    }

    /// The head's receptances `B^T G(x1; x0) B` (m/N; x along, y across, z
    /// down; eq. 1) for each pair `(x0, x1)` of `pairs` (m from a support:
    /// the load's place and the watched place) at angular frequency
    /// `omega` (rad/s): the head's displacement at `x1` per unit force on
    /// the head at `x0`.
    pub fn head_receptances(&self, pairs: &[(f64, f64)], omega: f64) -> Result<Vec<Mat3>, Discrete3Error> {
        self.projected(&self.section.head_map(), pairs, omega)
    }

    /// As [`Self::head_receptances`] with the head's rotation about `z` and
    /// the moment about it (4 x 4, [`super::section::Mat4`]).
    ///
    /// The integral's error is controlled on the largest entry, so the
    /// moment is integrated per [`ROTATION_ARM`] (a force on that arm) and
    /// the rotation as the displacement it gives there: every entry in
    /// m/N, of one size (the rail's bending wavenumbers are a few per
    /// metre), then scaled back.
    pub fn head_receptances4(&self, pairs: &[(f64, f64)], omega: f64) -> Result<Vec<Mat4>, Discrete3Error> {
        let (b, scale) = self.arm_map();
        Ok(self
            .projected(&b, pairs, omega)?
            .into_iter()
            .map(|a| Mat4::from_fn(|r, c| a[(r, c)] * (scale[r] * scale[c])))
            .collect())
    }

    /// [`Self::head_receptances4`] with the rotation about `z`, or without
    /// it the 3 x 3 receptances (their own integral, whose error control
    /// sees the translations alone) with a zero fourth row and column.
    pub fn heads(&self, pairs: &[(f64, f64)], omega: f64, rotation: bool) -> Result<Vec<Mat4>, Discrete3Error> {
        if rotation {
            self.head_receptances4(pairs, omega)
        } else {
            Ok(self.head_receptances(pairs, omega)?.iter().map(pad).collect())
        }
    }

    /// [`Self::heads`] on `layout` (its supports each with their own pad,
    /// sleeper and ballast, [`Layout::track_of`]; places in m from the layout's
    /// start), by the waves' scattering ([`super::scattering`]).
    pub fn layout_heads(
        &self,
        layout: &Layout,
        pairs: &[(f64, f64)],
        omega: f64,
        rotation: bool,
    ) -> Result<Vec<Mat4>, Discrete3Error> {
        let waves = self.free_waves(omega)?;
        let s = &self.section;
        let supports = self.layout_supports(layout, omega);
        let fail = layout_at(omega);
        if rotation {
            let (b, scale) = self.arm_map();
            let out = scattering::response(&waves, &supports, layout.period, &b, pairs).map_err(fail)?;
            Ok(out.into_iter().map(|a| Mat4::from_fn(|r, c| a[(r, c)] * (scale[r] * scale[c]))).collect())
        } else {
            let out = scattering::response(&waves, &supports, layout.period, &s.head_map(), pairs).map_err(fail)?;
            Ok(out.iter().map(pad).collect())
        }
    }

    /// `layout`'s supports at `omega` (rad/s): each one's place (m) and
    /// dynamic stiffness in the section's freedoms (eq. 2 of
    /// [`super::section`] with its own pad, sleeper and ballast).
    pub fn layout_supports(&self, layout: &Layout, omega: f64) -> Vec<Supported<6>> {
        let s = &self.section;
        (0..layout.len())
            .map(|m| {
                (layout.supports[m].x, Section::new(&layout.track_of(&s.track, m), s.contact_offset).support(omega))
            })
            .collect()
    }

    /// The head map with the rotation about `z` per [`ROTATION_ARM`], and
    /// the scales that undo it.
    fn arm_map(&self) -> (Map64, [f64; 4]) {
        let mut b = self.section.head_map4();
        for r in 0..6 {
            b[(r, 3)] *= ROTATION_ARM;
        }
        (b, [1.0, 1.0, 1.0, 1.0 / ROTATION_ARM])
    }

    /// `B^T G(x1; x0) B` of eq. 1 for the head map `b`.
    fn projected<const N: usize>(
        &self,
        b: &SMatrix<Complex64, 6, N>,
        pairs: &[(f64, f64)],
        omega: f64,
    ) -> Result<Vec<SMatrix<Complex64, N, N>>, Discrete3Error> {
        let s = &self.section;
        let d = s.track.sleeper_spacing;
        let waves = self.free_waves(omega)?;
        let ks = s.support(omega);
        let b = *b;
        let bt = b.transpose();
        let identity_d = SMatrix::<Complex64, 6, 6>::identity() * Complex64::new(d, 0.0);
        // The head's projections of the waves' residues, P_m = B^T M_m and
        // Q_m = M_m B (B^T M_m^T = Q_m^T, M_m^T B = P_m^T), and each place's
        // factors of eq. 2 of [`super::waves`], which do not depend on kappa.
        let p: Vec<SMatrix<Complex64, N, 6>> = waves.modes.iter().map(|m| bt * m).collect();
        let q: Vec<SMatrix<Complex64, 6, N>> = waves.modes.iter().map(|m| m * b).collect();
        let watched: Vec<Place> = pairs.iter().map(|&(_, x1)| Place::new(&waves, x1, d)).collect();
        let loads: Vec<Place> = pairs.iter().map(|&(x0, _)| Place::new(&waves, -x0, d)).collect();
        let z: [Complex64; 6] = std::array::from_fn(|m| (Complex64::i() * waves.lambda[m] * d).exp());
        let integrand = |kappa: f64| -> Vec<SMatrix<Complex64, N, N>> {
            let zeta = Complex64::from_polar(1.0, kappa * d);
            let alpha: [Complex64; 6] = std::array::from_fn(|m| 1.0 / (1.0 - z[m] / zeta));
            let beta: [Complex64; 6] = std::array::from_fn(|m| zeta / (1.0 - z[m] * zeta));
            let mut t0 = Mat6::zeros();
            for (m, modes) in waves.modes.iter().enumerate() {
                t0 += modes * (alpha[m] * d) + modes.transpose() * (beta[m] * z[m] * d);
            }
            let reaction = ks * (identity_d + t0 * ks).lu().solve(&Mat6::identity()).expect("regular supports");
            watched
                .iter()
                .zip(&loads)
                .map(|(w, l)| {
                    let mut tp = SMatrix::<Complex64, N, 6>::zeros();
                    let mut tm = SMatrix::<Complex64, 6, N>::zeros();
                    for m in 0..6 {
                        tp += p[m] * (alpha[m] * w.ahead[m]) + q[m].transpose() * (beta[m] * w.behind[m]);
                        tm += q[m] * (alpha[m] * l.ahead[m]) + p[m].transpose() * (beta[m] * l.behind[m]);
                    }
                    let phase = Complex64::from_polar(d * d, kappa * d * (w.cells + l.cells));
                    tp * reaction * tm * phase
                })
                .collect()
        };
        let taken = integrate(integrand, -PI / d, PI / d, 16, TOLERANCE, MAX_EVALUATIONS)
            .map_err(|source| Discrete3Error::Quadrature { frequency: omega / (2.0 * PI), source })?;
        Ok(pairs
            .iter()
            .zip(taken)
            .map(|(&(x0, x1), t)| project(&b, &waves.green(x1 - x0)) - t / Complex64::new(2.0 * PI, 0.0))
            .collect())
    }
}
