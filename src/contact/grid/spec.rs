//! What a fixed-grid model is built from ([`FixedGridSpec`]), the choices
//! it takes (the difference scheme, the tangential solver) and its
//! tolerances; the model itself is [`super::solver::FixedGrid`].

use super::{Alignment, PotentialGrid};
use crate::contact::friction::FrictionLaw;
use crate::hertz::{Curvatures, Elastic};

/// Default tolerance on the kinematic residual of a step, in units of eps:
/// 1e-7 m/s at eps = 1e-5 m/s. Tighter tolerances change the steady
/// creepage and wear integral by less than 1e-6 relative on the paper's
/// scene (book: docs/src/theory/fixed-grid.md) and cost a third more sweeps.
pub const GRID_TOLERANCE: f64 = 1e-2;

/// Default tolerance on the force residual |F - F_x| / (mu N).
pub const GRID_FORCE_TOLERANCE: f64 = 1e-8;

impl GridScheme {
    /// Config name (`contact.scheme`).
    pub fn name(self) -> &'static str {
        self.into()
    }
}

/// The backward difference of the material derivative.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, strum::EnumString, strum::IntoStaticStr, strum::VariantNames)]
#[strum(serialize_all = "kebab-case")]
pub enum GridScheme {
    /// `(3 u - 4 u_o + u_oo)/(2 dt)`.
    #[default]
    SecondOrder,
    /// `(u - u_o)/dt` (CONTACT).
    FirstOrder,
    /// `(11 u - 18 u_o + 9 u_oo - 2 u_ooo)/(6 dt)`.
    ThirdOrder,
}

/// The tangential solver of the fixed grid (`contact.solver`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, strum::EnumString, strum::IntoStaticStr, strum::VariantNames)]
#[strum(serialize_all = "kebab-case")]
pub enum GridSolver {
    /// The cheaper of the two by the cost model (the config resolves it:
    /// `cost::auto_grid_solver`); a spec built without the config takes
    /// CG.
    #[default]
    Auto,
    /// Element-wise nonlinear Gauss-Seidel ([`super::tangential`]), the
    /// reference.
    GaussSeidel,
    /// Newton with projected CG inner solves, every iteration one FFT
    /// product ([`super::cg`]); exact Coulomb friction as the regularised
    /// law's limit ([`super::cg::COULOMB_LIMIT`]).
    Cg,
}

impl GridSolver {
    /// The solver that runs: `auto` (unresolved by the config) is `cg`,
    /// for both friction laws.
    pub fn resolve(self) -> GridSolver {
        match self {
            GridSolver::GaussSeidel => GridSolver::GaussSeidel,
            _ => GridSolver::Cg,
        }
    }

    /// Config name (`contact.solver`).
    pub fn name(self) -> &'static str {
        self.into()
    }
}

/// What a fixed-grid model is built from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FixedGridSpec {
    /// Curvature sums A, B (1/m): the gap `h = A x^2 + B y^2`.
    pub curvatures: Curvatures,
    /// Elastic constants.
    pub elastic: Elastic,
    /// Element length along x (m), equal to `V dt`.
    pub dx: f64,
    /// Element width along y (m).
    pub dy: f64,
    /// Largest Hertz semi-axes the grid must hold (m).
    pub a_max: f64,
    /// Largest lateral semi-axis (m).
    pub b_max: f64,
    /// Where element edges must fall along x (rail cells) at the first step.
    pub align_x: Alignment,
    /// Where element edges must fall along y.
    pub align_y: Alignment,
    /// Friction law.
    pub law: FrictionLaw,
    /// Regularisation velocity eps (m/s): the regularised law's, and the
    /// velocity scale of the tolerance and the stick test for both.
    pub eps: f64,
    /// Difference scheme.
    pub scheme: GridScheme,
    /// Tangential solver.
    pub solver: GridSolver,
}

impl FixedGridSpec {
    /// A grid of `cell = (dx, dy)` elements (m) for patches up to the
    /// semi-axes `(a_max, b_max)` (m), its element edges where they fall
    /// (no rail cells to align with), with the friction law, difference
    /// scheme and eps (m/s) given and `solver`.
    pub fn unaligned(
        (curvatures, elastic): (Curvatures, Elastic),
        (dx, dy): (f64, f64),
        (a_max, b_max): (f64, f64),
        (law, scheme, eps): (FrictionLaw, GridScheme, f64),
        solver: GridSolver,
    ) -> Self {
        let (align_x, align_y) = (Alignment::default(), Alignment::default());
        FixedGridSpec { curvatures, elastic, dx, dy, a_max, b_max, align_x, align_y, law, eps, scheme, solver }
    }

    /// Steps of history the difference uses: the leading columns kept out
    /// of contact (at least two).
    pub fn lead_columns(&self) -> usize {
        match self.scheme {
            GridScheme::ThirdOrder => 3,
            _ => 2,
        }
    }

    /// The potential-contact grid (without its influence coefficients).
    pub fn grid(&self) -> PotentialGrid {
        PotentialGrid::covering(
            self.a_max,
            self.b_max,
            (self.dx, self.dy),
            self.lead_columns(),
            self.align_x,
            self.align_y,
        )
    }
}
