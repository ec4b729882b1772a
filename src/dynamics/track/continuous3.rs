//! The rail on continuous supports, moving in every direction: the
//! section's ([`super::section`]) Green's matrices and the rail head's
//! receptances in three directions, point and transfer, by residues.
//!
//! # Equations
//! The supports smeared along the rail (each support's stiffness of
//! [`super::section`] eq. 2 divided by the spacing `d`) add to the free
//! rail's: `K(k) = A2 k^2 + A1 k + A0 + K_s / d`. The section's response at
//! distance `L` from a unit load is
//! ```text
//! G(L) = 1/(2 pi) int K(k)^-1 exp(i k L) dk.                         (1)
//! ```
//! is the sum of its six waves by residues (eq. 1 of [`super::waves`]; the
//! companion matrix of the quadratic eigenvalue problem, the roots in the
//! upper half plane), `G(-L) = G(L)^T`                                   (2)
//!
//! In the limits where the directions uncouple (longitudinal pads at the
//! neutral axis, no pitch or roll restraint, Euler-Bernoulli bending) the
//! head's longitudinal receptance is the rod on an elastic foundation plus
//! the head height squared times the beam's rotational receptance to a
//! moment, `1 / (2 EA gamma) + h^2 / (4 EI beta)` (Hetenyi, *Beams on
//! Elastic Foundation*, 1946), and the lateral one the lateral beam's plus
//! the torsion rod's, `1 / (8 EI_z beta_y^3) + h_s^2 / (2 GJ gamma_t)`
//! (tests/rail_head.rs).

use super::TrackConfig;
use super::scattering::RailWaves;
use super::section::{Mat3, Mat4, Mat6, Section, pad};
use super::waves::{RootsError, Waves};
use num_complex::Complex64;

/// The rail on continuous supports, and the contact on its head.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Continuous3 {
    /// The rail, its supports (smeared) and the contact's offset.
    pub section: Section,
}

impl Continuous3 {
    /// The configured track (supports smeared over the spacing), the
    /// contact `contact_offset` (m) right of the centre line.
    pub fn new(track: &TrackConfig, contact_offset: f64) -> Self {
        Continuous3 { section: Section::new(track, contact_offset) }
    }

    /// The waves of the rail on its smeared supports at `omega` (rad/s).
    pub fn waves(&self, omega: f64) -> Result<Waves, RootsError> {
        let (a2, a1, mut a0) = self.section.free_polynomial(omega);
        a0 += self.section.support(omega) / Complex64::new(self.section.track.sleeper_spacing, 0.0);
        Waves::new(&a2, &a1, &a0, omega)
    }

    /// The section's Green's matrices `G(L)` (eq. 2) at each distance of
    /// `distances` (m, either sign) at angular frequency `omega` (rad/s).
    pub fn section_receptances(&self, omega: f64, distances: &[f64]) -> Result<Vec<Mat6>, RootsError> {
        let waves = self.waves(omega)?;
        Ok(distances.iter().map(|&l| waves.green(l)).collect())
    }

    /// The head's receptances `B^T G(L) B` (m/N; x along, y across, z
    /// down): the head's displacement at `L` (m) from a unit force on the
    /// head, for each distance of `distances`; `L = 0` the point
    /// receptance.
    pub fn head_receptances(&self, omega: f64, distances: &[f64]) -> Result<Vec<Mat3>, RootsError> {
        Ok(self.section_receptances(omega, distances)?.iter().map(|g| self.section.head(g)).collect())
    }

    /// As [`Self::head_receptances`] with the head's rotation about `z` and
    /// the moment about it (4 x 4, [`super::section::Mat4`]).
    pub fn head_receptances4(&self, omega: f64, distances: &[f64]) -> Result<Vec<Mat4>, RootsError> {
        Ok(self.section_receptances(omega, distances)?.iter().map(|g| self.section.head4(g)).collect())
    }

    /// [`Self::head_receptances4`] with the rotation about `z`, or without
    /// it the 3 x 3 receptances with a zero fourth row and column.
    pub fn heads(&self, omega: f64, distances: &[f64], rotation: bool) -> Result<Vec<Mat4>, RootsError> {
        if rotation {
            self.head_receptances4(omega, distances)
        } else {
            Ok(self.head_receptances(omega, distances)?.iter().map(pad).collect())
        }
    }
}
