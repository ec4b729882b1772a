//! Tangential wheel-rail contact: the patch mesh, the per-step solution, and
//! the contact models (FASTSIM now; the transient models build on the same
//! interface).
//!
//! Conventions (Kalker; CONTACT): the contact frame (x, y) moves with the
//! patch centre, x along the rolling direction (+X of the rail), the wheel
//! rolling in +x at speed V. Creepages are rigid slip velocities of the wheel
//! relative to the rail divided by V; tractions are those acting on the wheel;
//! the friction law makes the traction oppose the local slip, so a positive
//! force on the wheel comes with a negative creepage.

pub mod fastsim;
pub mod friction;
pub mod grid;
pub mod gs_loop;
pub mod influence;
pub mod linear;
pub mod mesh;
pub mod transient;

pub use mesh::{EllipseMesh, PressureShape};

use crate::hertz::HertzPatch;
use grid::PotentialGrid;
use grid::surface::RailSurface;
use std::sync::Arc;

/// The elements a solver gives its fields on.
#[derive(Debug, Clone, PartialEq)]
pub enum Elements {
    /// The patch-adapted (Paul-Hashemi) mesh, in normalised coordinates.
    Adapted(EllipseMesh),
    /// The fixed potential-contact grid, in metres.
    Grid(PotentialGrid),
}

impl Elements {
    /// Number of elements (the length of every field).
    pub fn len(&self) -> usize {
        match self {
            Elements::Adapted(m) => m.len(),
            Elements::Grid(g) => g.len(),
        }
    }

    /// Whether there are no elements.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The adapted mesh, if that is what the fields are on.
    pub fn mesh(&self) -> Option<&EllipseMesh> {
        match self {
            Elements::Adapted(m) => Some(m),
            Elements::Grid(_) => None,
        }
    }
}

/// Rigid creepages.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Creepage {
    /// Longitudinal creepage xi_x (1).
    pub x: f64,
    /// Lateral creepage xi_y (1).
    pub y: f64,
    /// Spin creepage (1/m).
    pub spin: f64,
}

/// What one contact step needs to know.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepInput {
    /// Hertz patch of this step.
    pub patch: HertzPatch,
    /// Rolling speed V (m/s).
    pub speed: f64,
    /// Time step dt (s): the patch has moved by `speed * dt` since the
    /// previous step of the history (if the solver has one).
    pub dt: f64,
    /// Friction coefficient mu (1): at zero slip speed.
    pub friction: f64,
    /// How the friction coefficient varies with the local slip speed
    /// (`mu(|s|) = mu r(|s|)`; constant: Coulomb's).
    pub characteristic: friction::Characteristic,
    /// Friction memory (`None`: the coefficient follows the slip speed at
    /// once).
    pub memory: Option<friction::FrictionMemory>,
    /// Prescribed longitudinal force on the wheel F_x (N), unless the
    /// creepage is prescribed.
    pub force_x: f64,
    /// Prescribed longitudinal creepage (1) (`load.control = "creepage"`):
    /// the force is then the result, `force_x` unused; None: `force_x`
    /// prescribed and the creepage found.
    pub creepage_x: Option<f64>,
    /// Prescribed lateral creepage (1).
    pub creepage_y: f64,
    /// Prescribed spin (1/m).
    pub spin: f64,
    /// Patch-centre position along the rail X_c (m): where a model that
    /// takes the rail surface into its normal problem reads the profile.
    pub position: f64,
}

impl StepInput {
    /// The prescribed longitudinal force must stay below the friction limit
    /// mu N; at or beyond it the patch slides entirely and no creepage
    /// transmits the force. (A prescribed creepage has a solution at any
    /// value: full sliding at the limit.)
    pub fn check_friction_limit(&self) -> Result<(), ContactError> {
        if self.creepage_x.is_some() {
            return Ok(());
        }
        let limit = self.friction * self.characteristic.largest() * self.patch.normal_force;
        if self.force_x.abs() >= limit {
            return Err(ContactError::ForceExceedsFriction { force: self.force_x, limit });
        }
        Ok(())
    }
}

/// Contact fields and resultants of one step, on the mesh elements.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PatchSolution {
    /// The creepages found (x) and prescribed (y, spin).
    pub creepage: Creepage,
    /// Resultant longitudinal force on the wheel (N).
    pub force_x: f64,
    /// Resultant lateral force on the wheel (N).
    pub force_y: f64,
    /// Normal pressure p3 at element centres (Pa).
    pub pressure: Vec<f64>,
    /// Tangential traction on the wheel, x (Pa).
    pub traction_x: Vec<f64>,
    /// Tangential traction on the wheel, y (Pa).
    pub traction_y: Vec<f64>,
    /// Local slip velocity of the wheel relative to the rail, x (m/s).
    pub slip_x: Vec<f64>,
    /// Local slip velocity, y (m/s).
    pub slip_y: Vec<f64>,
    /// Element in stick (adhesion).
    pub stick: Vec<bool>,
    /// Iterations of the solve: Newton-Raphson iterations, Gauss-Seidel
    /// sweeps or the CG solver's FFT products (0 for FASTSIM).
    pub iterations: usize,
    /// Elements well inside the patch where the linear profile contact's
    /// pressure vanished (the patch splitting: the linearisation beyond its
    /// range; 0 for the other normal contacts).
    pub clipped: usize,
    /// Offset of the patch centre from the wheel's `X_c` along x (m): the
    /// adapted mesh moved with the contact point by the linear profile
    /// contact (0 otherwise; the fixed grid's patch moves on the grid).
    pub offset: f64,
    /// The semi-axes (a, b) of the adapted mesh when the linear profile
    /// contact moved its edges (m); `None`: the step's Hertz patch.
    pub semi_axes: Option<(f64, f64)>,
    /// The step's fast solver did not converge and the reference solver
    /// solved it (the fixed grid's Newton-Krylov solver handing the step to
    /// Gauss-Seidel).
    pub fallback: bool,
}

impl PatchSolution {
    /// Fraction of elements in stick (1).
    pub fn stick_fraction(&self) -> f64 {
        self.stick.iter().filter(|s| **s).count() as f64 / self.stick.len().max(1) as f64
    }
}

/// Failure of a contact solve.
#[derive(Debug, Clone, thiserror::Error, PartialEq)]
pub enum ContactError {
    /// The prescribed force cannot be transmitted by friction.
    #[error("longitudinal force {force:.6e} N reaches the friction limit mu N = {limit:.6e} N (full sliding)")]
    ForceExceedsFriction {
        /// Prescribed force (N).
        force: f64,
        /// mu N (N).
        limit: f64,
    },
    /// The model takes the Hertz contact only, not a rail surface.
    #[error(
        "this contact model cannot take the rail profile this way (contact.normal = \"profile\" needs contact.grid = \"fixed\")"
    )]
    NoSurface,
    /// The linear profile contact would move or stretch the patch by a
    /// large part of itself: the corrugation is far beyond its range.
    #[error(
        "the linear profile contact would move the patch by {shift:.3e} m and stretch it by {stretch:.0} % (semi-axis a = {a:.3e} m): the corrugation is far beyond the linearisation's range (contact.normal = \"profile\", the nonlinear profile contact of the fixed grid, solves it)"
    )]
    LinearRange {
        /// Shift of the patch centre (m).
        shift: f64,
        /// Largest relative change of a semi-axis (%).
        stretch: f64,
        /// The Hertz semi-axis along the rail (m).
        a: f64,
    },
    /// The creepage search did not converge.
    #[error("creepage search for F_x = {force:.6e} N did not converge: {reason}")]
    NoConvergence {
        /// Prescribed force (N).
        force: f64,
        /// What went wrong.
        reason: String,
    },
}

/// How the rail surface under the patch enters the normal problem.
#[derive(Debug, Clone, PartialEq)]
pub enum RailContact {
    /// Linearised about the Hertz contact of the step ([`linear`]): the
    /// patch moved and stretched to first order with the surface, the rest
    /// of the normal problem's linear response on it. The adapted mesh's
    /// models take it.
    Linear(Arc<RailSurface>),
    /// The full (nonlinear) normal problem of the gap less the surface: the
    /// fixed grid only.
    Profile(Arc<RailSurface>),
}

impl RailContact {
    /// The surface.
    pub fn surface(&self) -> &Arc<RailSurface> {
        match self {
            RailContact::Linear(s) | RailContact::Profile(s) => s,
        }
    }
}

/// A tangential contact model advanced step by step along a passage.
///
/// Steady models ignore `dt` and the history; transient models keep the
/// previous step's state and must be [`reset`](TangentialSolver::reset) when
/// the contact history restarts (new passage, contact loss).
pub trait TangentialSolver: Send {
    /// Solves the tangential problem of one step with the force prescribed.
    fn step(&mut self, input: &StepInput) -> Result<PatchSolution, ContactError>;
    /// Solves the step as [`step`](TangentialSolver::step) does, told the
    /// next step's input (`None`: none follows, or the contact is lost
    /// before it): a model may prepare that step meanwhile (the fixed grid
    /// solves its normal problem on a second thread). Same result bit for
    /// bit.
    fn step_ahead(&mut self, input: &StepInput, next: Option<&StepInput>) -> Result<PatchSolution, ContactError> {
        let _ = next;
        self.step(input)
    }
    /// Forgets the contact history.
    fn reset(&mut self);
    /// The elements the fields are given on.
    fn elements(&self) -> Elements;
    /// Puts the rail surface into the normal problem of the following steps
    /// (`None`: the Hertz contact of the curvatures). Models that cannot
    /// take it as asked refuse.
    fn set_surface(&mut self, surface: Option<RailContact>) -> Result<(), ContactError> {
        match surface {
            None => Ok(()),
            Some(_) => Err(ContactError::NoSurface),
        }
    }
    /// The shortest wavelength (m) of the rail surface the model's linear
    /// profile contact resolves on a patch of semi-axis `a` (m) along the
    /// rail: eight elements of its normal mesh. `None`: no linear contact.
    fn linear_resolution(&self, a: f64) -> Option<f64> {
        let _ = a;
        None
    }
    /// The rigid approach (m) of wheel and rail that holds the normal force
    /// `force` (N) with the patch centre at `position` (m) on the surface
    /// set by [`set_surface`](TangentialSolver::set_surface): the normal
    /// problem alone, without history. Models without a surface refuse.
    fn approach(&mut self, position: f64, force: f64) -> Result<f64, ContactError> {
        let _ = (position, force);
        Err(ContactError::NoSurface)
    }
    /// [`approach`](TangentialSolver::approach) at every position of
    /// `positions` (m) under the same force (N), in order; an error names
    /// the index of the position that failed. A model may solve them in
    /// parallel (the fixed grid: two warm-started chains, one per half,
    /// whatever the thread count).
    fn approaches(&mut self, positions: &[f64], force: f64) -> Result<Vec<f64>, (usize, ContactError)> {
        positions.iter().enumerate().map(|(j, &x)| self.approach(x, force).map_err(|e| (j, e))).collect()
    }
}
