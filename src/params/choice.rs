//! What `contact.model = "auto"` chose: the candidates of the measured
//! accuracy map ([`crate::model_choice`]) as the scene carries them.

use super::ContactModelKind;

/// A (model, mesh) with its predicted error and cost at one lambda / 2a.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Candidate {
    /// Contact model.
    pub model: ContactModelKind,
    /// The exact model on the fixed grid.
    pub fixed: bool,
    /// Elements per side, or the fixed grid's element length (um).
    pub mesh: usize,
    /// Predicted relative wear error (1).
    pub wear_error: f64,
    /// Predicted CPU time per 0.2 mm rolled (s).
    pub cpu_per_step: f64,
}

impl Candidate {
    /// "exact-transient 20 x 20" or "exact-transient fixed grid 0.20 mm".
    pub fn label(&self) -> String {
        if self.fixed {
            format!("{} fixed grid {:.2} mm", self.model.name(), self.mesh as f64 / 1e3)
        } else {
            format!("{} {} x {}", self.model.name(), self.mesh, self.mesh)
        }
    }

    /// The fixed grid's element length (m), when it is one.
    pub fn grid_dx(&self) -> Option<f64> {
        self.fixed.then(|| self.mesh as f64 / 1e6)
    }
}

/// What "auto" chose for a scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AutoChoice {
    /// `contact.tolerance`: relative wear error asked for (1).
    pub tolerance: f64,
    /// The scene's shortest wavelength over 2 a_max (1; inf without one).
    pub lambda_over_2a: f64,
    /// The shortest wavelength (m; inf without one).
    pub wavelength: f64,
    /// The chosen model and mesh with their predicted error and cost.
    pub chosen: Candidate,
    /// The cheapest exact-transient mesh within the tolerance.
    pub exact: Option<Candidate>,
    /// The validity map's difference between the Hertz and the profile
    /// normal contact at the initial corrugation of a growth study with
    /// track dynamics (1); such a study on the fixed grid takes
    /// `contact.normal = "auto"` (the profile once the corrugation leaves
    /// the Hertz region).
    pub hertz_difference: Option<f64>,
}
