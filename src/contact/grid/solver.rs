//! The fixed-grid exact transient contact model, step by step along a
//! passage: the normal problem on the grid ([`super::normal`]), the
//! elements in contact, the earlier displacements by shifting the stored
//! displacement fields by whole columns, and the tangential problem
//! ([`super::tangential`]).
//!
//! **Material transport.** The patch moves by exactly one element per step
//! (`V dt = dx`, enforced by the config): the material at column `ix` was
//! at `ix - 1` one step earlier and at `ix - 2` two steps earlier, so
//! `u_o(ix) = u^{n-1}(ix - 1)` and `u_oo(ix) = u^{n-2}(ix - 2)` exactly, the
//! displacement fields being known on the whole grid (`u = K p` by FFT after
//! every step). The material derivative of the displacement is then
//!
//! * [`GridScheme::FirstOrder`]: `(u - u_o) / dt`, CONTACT's transient
//!   rolling; first order in dx (the slip sits half an element upstream of
//!   the traction it goes with);
//! * [`GridScheme::SecondOrder`]: `(3 u - 4 u_o + u_oo) / (2 dt)`, the
//!   second-order backward difference along the material path (first order
//!   on the step after a virgin start).
//!
//! A virgin start (a new passage, or contact regained) is Cattaneo's shift
//! problem: `u_o = 0`, the rigid shift over the step `V xi dt`.

use super::cg;
use super::convolution::{FftConvolution, FftScratch, ToeplitzKernel};
use super::coupling::{Coupling, FoldedKernel};
use super::normal::{self, NormalError};
use super::spec::{FixedGridSpec, GRID_FORCE_TOLERANCE, GRID_TOLERANCE, GridScheme, GridSolver};
use super::tangential::{self, ContactSet, GridStep, Law};
mod edge;
mod on_set;
mod pressure;
mod window;

use super::PotentialGrid;
use crate::contact::friction::{STICK_SLIP_FACTOR, regularised as friction};
use crate::contact::linear::MeshResponse;
use crate::contact::mesh::EllipseMesh;
use crate::contact::transient::GS_MAX_SWEEPS;
use crate::contact::{ContactError, Creepage, Elements, PatchSolution, RailContact, StepInput, TangentialSolver};
use crate::hertz::HertzShape;
use on_set::{Layout, OnSet};
use pressure::{Ahead, Pressure};
use std::borrow::Cow;
use std::sync::Arc;
use window::Window;

/// State carried from one step to the next, on the whole grid.
#[derive(Debug, Clone)]
struct History {
    /// Displacement field u = K p of the last step (x, y) (m).
    u: (Vec<f64>, Vec<f64>),
    /// That of the step before, if any (second-order scheme).
    older: Option<(Vec<f64>, Vec<f64>)>,
    /// That of the step before that (third-order scheme).
    oldest: Option<(Vec<f64>, Vec<f64>)>,
    /// Pressure of the last step (Pa).
    p3: Vec<f64>,
    /// Slips of the last step, interleaved (m/s).
    s: Vec<f64>,
    /// Tractions of the last step, interleaved (Pa).
    p: Vec<f64>,

    /// Creepage.
    xi: f64,
}

/// The approaches of a chain of positions (m) and its last pressure (Pa).
type Chain = (Vec<f64>, Option<Vec<f64>>);

/// A step's tangential solution.
struct Solved {
    /// On the whole grid.
    out: PatchSolution,
    /// Slips kept for the next warm start, interleaved (m/s).
    s_grid: Vec<f64>,
    /// The displacement field `K p` on the whole grid (x, y) (m).
    u: (Vec<f64>, Vec<f64>),
    /// Whether the CG solver handed the step to Gauss-Seidel.
    fell_back: bool,
}

/// The earlier-displacement term of a step and its warm start.
struct Earlier {
    /// `u~` at the elements in contact, interleaved (m).
    u_prev: Vec<f64>,
    /// Weight of the current displacement (1 or 3/2).
    beta: f64,
    /// Warm-start slips, interleaved (m/s).
    s0: Vec<f64>,
    /// Warm-start tractions, interleaved (Pa).
    p0: Vec<f64>,
    /// Warm-start creepage.
    xi0: f64,
}

/// The fixed-grid exact transient model.
#[derive(Debug, Clone)]
pub struct FixedGrid {
    spec: FixedGridSpec,
    grid: PotentialGrid,
    gap: Vec<f64>,
    normal: FftConvolution,
    kernel: ToeplitzKernel,
    tangential: FftConvolution,
    /// The CG solver's inner products in single precision, and its
    /// preconditioner, the FFT inverse of the tangential kernel's
    /// circulant on the unpadded grid.
    tangential_single: FftConvolution<f32>,
    inverse_single: FftConvolution<f32>,
    /// The normal CG's preconditioner, that of the normal kernel.
    normal_inverse: FftConvolution,
    scratch: FftScratch,
    /// The next step's pressure, computed while this step's tangential
    /// problem was solved, and its own work buffers.
    ahead: Option<Ahead>,
    ahead_scratch: FftScratch,
    history: Option<History>,
    /// Tolerance on the kinematic residual, in units of eps.
    tolerance: f64,
    /// The folded coupling of a grid symmetric about y = 0.
    folded: Option<FoldedKernel>,
    /// The rail surface in the gap (`None`: the quadratic gap alone).
    surface: Option<RailContact>,
    /// Warm start of [`FixedGrid::approach`]'s normal solves (Pa).
    approach_start: Option<Vec<f64>>,
    /// Steps the Newton-Krylov solver handed to Gauss-Seidel since the last
    /// reset.
    fallbacks: usize,
    /// The linear profile contact's response, built when a linear surface
    /// is first set (shared with the window's block).
    linear: Option<Arc<MeshResponse>>,
    /// The linear contact's window ([`FixedGrid::with_linear_window`]):
    /// the largest normal force (N) and the solver, and the block of the
    /// grid the linear surface set now runs on (`None`: the whole grid).
    window: Option<(f64, GridSolver)>,
    active: Option<Window>,
}

/// Strips along the rail of the Paul-Hashemi mesh the fixed grid's linear
/// profile contact solves its normal response on (resolution a / 2, see
/// [`MeshResponse::resolution`]).
pub const LINEAR_NORMAL_NX: usize = 32;
/// Its rows across (32 x 18 = 576 elements, within
/// [`crate::contact::linear::MAX_NORMAL_ELEMENTS`]).
pub const LINEAR_NORMAL_NY: usize = 18;

impl FixedGrid {
    /// Builds the grid, its influence coefficients and transforms.
    pub fn new(spec: FixedGridSpec) -> Self {
        let grid = spec.grid();
        Self::build(spec, grid)
    }

    fn build(spec: FixedGridSpec, grid: PotentialGrid) -> Self {
        let (g, nu) = (spec.elastic.shear_modulus(), spec.elastic.poisson_ratio);
        let normal_kernel = ToeplitzKernel::normal(&grid, g, nu);
        let kernel = ToeplitzKernel::tangential(&grid, g, nu);
        let (xs, ys) = grid.centres();
        let c = spec.curvatures;
        let gap = xs.iter().zip(&ys).map(|(x, y)| c.a * x * x + c.b * y * y).collect();
        FixedGrid {
            spec,
            normal: FftConvolution::new(&normal_kernel),
            tangential: FftConvolution::new(&kernel),
            tangential_single: FftConvolution::single(&kernel),
            inverse_single: FftConvolution::circulant_inverse_single(&kernel),
            normal_inverse: FftConvolution::circulant_inverse(&normal_kernel),
            kernel,
            grid,
            gap,
            scratch: FftScratch::default(),
            ahead: None,
            ahead_scratch: FftScratch::default(),
            history: None,
            tolerance: GRID_TOLERANCE,
            folded: None,
            surface: None,
            approach_start: None,
            fallbacks: 0,
            linear: None,
            window: None,
            active: None,
        }
        .fold_if_symmetric()
    }

    /// Folds the coupling when the grid is symmetric about y = 0 (it is used
    /// on the steps whose loads are: no lateral creepage, no spin).
    fn fold_if_symmetric(mut self) -> Self {
        let g = &self.grid;
        if (g.y_low + 0.5 * g.ny as f64 * g.dy).abs() <= 1e-9 * g.dy {
            self.folded = Some(FoldedKernel::new(&self.kernel));
        }
        self
    }

    /// Sets the convergence tolerance on the kinematic residual to
    /// `relative` eps (default [`GRID_TOLERANCE`]).
    pub fn with_tolerance(mut self, relative: f64) -> Self {
        self.tolerance = relative;
        self
    }

    /// Steps the Newton-Krylov solver did not converge and Gauss-Seidel
    /// solved, since the last reset.
    pub fn fallbacks(&self) -> usize {
        self.fallbacks + self.active.as_ref().map_or(0, |w| w.grid.fallbacks())
    }

    /// The potential-contact grid.
    pub fn grid(&self) -> &PotentialGrid {
        &self.grid
    }

    /// Padded FFT size of the products (mx, my).
    pub fn padded(&self) -> (usize, usize) {
        self.tangential.padded()
    }

    /// The undeformed gap on the grid with the patch centre at `position`:
    /// the quadratic gap less the rail surface's height (module
    /// [`super::surface`]).
    fn gap_at(&self, position: f64) -> Cow<'_, [f64]> {
        let Some(RailContact::Profile(surface)) = &self.surface else {
            return Cow::Borrowed(&self.gap);
        };
        let (nx, g) = (self.grid.nx, &self.grid);
        Cow::Owned(
            self.gap.iter().enumerate().map(|(k, h)| h - surface.height(position + g.x(k % nx), g.y(k / nx))).collect(),
        )
    }

    /// The normal problem alone with the patch centre at `position` (m) and
    /// the normal force `force` (N), on the surface set (if any), warm
    /// started from the previous call's pressure: the pressure on the grid
    /// and the approach (h + u over the contact area, m).
    pub fn normal_solution(&mut self, position: f64, force: f64) -> Result<normal::NormalSolution, ContactError> {
        let start = self.approach_start.take();
        let mut scratch = std::mem::take(&mut self.scratch);
        let sol = self.normal_at(&mut scratch, position, force, start.as_deref());
        self.scratch = scratch;
        let sol = sol?;
        self.approach_start = Some(sol.pressure.clone());
        Ok(sol)
    }

    /// The normal problem alone at `position` (m) under `force` (N) from
    /// the pressure `start`.
    fn normal_at(
        &self,
        scratch: &mut FftScratch,
        position: f64,
        force: f64,
        start: Option<&[f64]>,
    ) -> Result<normal::NormalSolution, ContactError> {
        let gap = self.gap_at(position);
        normal::solve(self.normal_products(), scratch, &gap, self.grid.area(), force, start)
            .map_err(|e| ContactError::NoConvergence { force, reason: normal_reason(e) })
    }

    /// The normal solves of one chain of positions, each warm-started from
    /// the last (the first cold): the approaches and the last pressure.
    fn approach_chain(&self, positions: &[f64], force: f64) -> Result<Chain, (usize, ContactError)> {
        let mut scratch = FftScratch::default();
        let mut last: Option<Vec<f64>> = None;
        let mut out = Vec::with_capacity(positions.len());
        for (j, &x) in positions.iter().enumerate() {
            let sol = self.normal_at(&mut scratch, x, force, last.as_deref()).map_err(|e| (j, e))?;
            out.push(sol.approach);
            last = Some(sol.pressure);
        }
        Ok((out, last))
    }

    /// The undeformed gap (m) on the grid with the patch centre at
    /// `position` (m).
    pub fn gap(&self, position: f64) -> Vec<f64> {
        self.gap_at(position).into_owned()
    }

    /// Whether a gap is symmetric about y = 0 (to rounding), so that the
    /// folded coupling may solve its symmetric problems.
    fn symmetric(&self, gap: &[f64]) -> bool {
        let (nx, ny) = (self.grid.nx, self.grid.ny);
        let scale = gap.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        (0..gap.len()).all(|k| (gap[k] - gap[(ny - 1 - k / nx) * nx + k % nx]).abs() <= 1e-12 * scale)
    }

    /// The normal problem's products and preconditioner.
    fn normal_products(&self) -> (&FftConvolution, Option<&FftConvolution>) {
        (&self.normal, Some(&self.normal_inverse))
    }

    fn law(&self) -> Law {
        self.spec.law.with(self.spec.eps)
    }

    /// One step, told the next step's input: the next step's pressure is
    /// computed on a second thread while this step's tangential problem is
    /// solved (`rayon::join`), warm-started from this step's pressure as it
    /// would be sequentially (same result bit for bit).
    fn solve_step(&mut self, input: &StepInput, next: Option<&StepInput>) -> Result<PatchSolution, ContactError> {
        input.check_friction_limit()?;
        let force = input.force_x;
        if input.dt.is_nan() || input.dt <= 0.0 {
            return Err(ContactError::NoConvergence {
                force,
                reason: format!("transient models need a time step > 0, got {}", input.dt),
            });
        }
        let shift_ok = ((input.speed * input.dt - self.grid.dx) / self.grid.dx).abs() < 1e-6;
        if !shift_ok {
            return Err(ContactError::NoConvergence {
                force,
                reason: format!(
                    "the fixed grid needs V dt = dx = {:.6e} m, got {:.6e} m",
                    self.grid.dx,
                    input.speed * input.dt
                ),
            });
        }
        let (nx, ny, n) = (self.grid.nx, self.grid.ny, self.grid.len());
        let Pressure { mut p3, clipped, symmetric: symmetric_load } = match self.ahead.take() {
            Some(ahead) if ahead.key == Ahead::key(input) => ahead.result?,
            _ => {
                let mut scratch = std::mem::take(&mut self.scratch);
                let start = self.history.as_ref().map(|h| h.p3.as_slice());
                let pressure = self.pressure(&mut scratch, input, start);
                self.scratch = scratch;
                pressure?
            }
        };
        // A problem symmetric about y = 0 is solved on the lower half of the
        // grid (coupling): the pressure, symmetric to rounding, made exactly
        // so.
        let symmetric = input.creepage_y == 0.0 && input.spin == 0.0 && symmetric_load;
        let folded = self.folded.as_ref().filter(|_| symmetric);
        let mirror = |k: usize| (ny - 1 - k / nx) * nx + k % nx;
        if folded.is_some() {
            for k in 0..n {
                let m = mirror(k);
                if m > k {
                    let v = 0.5 * (p3[k] + p3[m]);
                    (p3[k], p3[m]) = (v, v);
                }
            }
        }
        let mut ahead_scratch = std::mem::take(&mut self.ahead_scratch);
        let this = &*self;
        let (solved, ahead) = rayon::join(
            || this.tangential_step(input, &p3, folded.is_some()),
            || {
                next.map(|next| Ahead {
                    key: Ahead::key(next),
                    result: this.pressure(&mut ahead_scratch, next, Some(&p3)),
                })
            },
        );
        self.ahead_scratch = ahead_scratch;
        let Solved { mut out, s_grid, u, fell_back } = solved?;
        self.ahead = ahead;
        self.fallbacks += usize::from(fell_back);
        out.clipped = clipped;
        let (older, oldest) = match self.history.take() {
            Some(h) => (Some(h.u), h.older),
            None => (None, None),
        };
        let p_grid = out.traction_x.iter().zip(&out.traction_y).flat_map(|(x, y)| [*x, *y]).collect();
        self.history = Some(History { u, older, oldest, p3, s: s_grid, p: p_grid, xi: out.creepage.x });
        Ok(out)
    }

    /// The tangential problem of a step on the pressure `p3` (symmetric
    /// about y = 0 where `folded`): the solution on the whole grid, the
    /// slips kept for the next warm start, the displacement field.
    fn tangential_step(&self, input: &StepInput, p3: &[f64], folded: bool) -> Result<Solved, ContactError> {
        let force = input.force_x;
        let n_force = input.patch.normal_force;
        let (nx, ny, n) = (self.grid.nx, self.grid.ny, self.grid.len());
        let area = self.grid.area();
        let folded = self.folded.as_ref().filter(|_| folded);
        let mirror = |k: usize| (ny - 1 - k / nx) * nx + k % nx;
        let whole = ContactSet::new(nx, n, |k| p3[k] > 0.0);
        self.check_inside(&whole, input.position, n_force)
            .map_err(|reason| ContactError::NoConvergence { force, reason })?;
        let set = match folded {
            Some(f) => ContactSet::new(nx, f.half_rows() * nx, |k| p3[k] > 0.0),
            None => whole,
        };
        let weight: Vec<f64> =
            set.element.iter().map(|&k| if folded.is_some() && mirror(k) != k { 2.0 } else { 1.0 }).collect();
        let nc = set.len();
        let mu = input.friction;
        let mu_p3: Vec<f64> = set.element.iter().map(|&k| mu * p3[k]).collect();
        let w0: Vec<f64> = set
            .element
            .iter()
            .flat_map(|&k| {
                let (x, y) = (self.grid.x(k % nx), self.grid.y(k / nx));
                [-input.spin * y, input.creepage_y + input.spin * x]
            })
            .collect();
        let Earlier { u_prev, beta, s0, p0, xi0 } = self.earlier(&set);
        let law = self.law();
        let coupling = match folded {
            Some(f) => Coupling::Folded(f),
            None => Coupling::Full(&self.kernel),
        };
        let mut step = GridStep {
            coupling,
            weight: &weight,
            set: &set,
            dt: input.dt,
            speed: input.speed,
            beta,
            law,
            mu_p3: &mu_p3,
            area,
            w0: &w0,
            u_prev: &u_prev,
            force_x: force,
            mu_n: mu * n_force,
            // Gauss-Seidel's creepage stiffness, set below where it runs.
            kappa: f64::NAN,
            tol: self.tolerance * self.spec.eps,
            max_sweeps: GS_MAX_SWEEPS,
            force_tol: GRID_FORCE_TOLERANCE,
        };
        // Exact products on the whole grid; the last one (the verdict's) is
        // the field the next step shifts.
        let shape = (nx, ny);
        let mut exact = OnSet::new(&self.tangential, &set, &weight, shape, Layout::Blocks);
        let mut fresh = |p: &[f64], u: &mut [f64]| exact.product(p, u);
        // The CG solver's inner products in single precision; its
        // preconditioner, the FFT inverse on the unpadded grid.
        let mut single = OnSet::new(&self.tangential_single, &set, &weight, shape, Layout::Blocks);
        let mut inner = |p: &[f64], u: &mut [f64]| single.product(p, u);
        let mut pre = OnSet::new(&self.inverse_single, &set, &weight, shape, Layout::Interleaved);
        let mut inverse = |r: &[f64], z: &mut [f64]| pre.product(r, z);
        let newton_krylov = self.spec.solver.resolve() == GridSolver::Cg;
        // The CG solver's law: exact Coulomb friction as the regularised
        // law's limit.
        let cg_step = match law {
            Law::Coulomb => GridStep { law: Law::Regularised { eps: cg::COULOMB_LIMIT * self.spec.eps }, ..step },
            Law::Regularised { .. } => GridStep { ..step },
        };
        // A step CG does not converge goes to Gauss-Seidel; its products
        // count in the step's iterations, and its failure in the report.
        let mut cg_failed: Option<(Vec<f64>, usize)> = None;
        let mut solved =
            match newton_krylov.then(|| cg::solve(&cg_step, &s0, &p0, xi0, &mut fresh, (&mut inner, &mut inverse))) {
                Some(Ok(sol)) => Some(Ok(sol)),
                Some(Err(failure)) => {
                    cg_failed = Some(match failure {
                        cg::CgFailure::NoConvergence { history, products } => (history, products),
                        cg::CgFailure::Coulomb => (Vec::new(), 0),
                    });
                    None
                }
                None => None,
            };
        if solved.is_none() {
            step.kappa = self.creepage_stiffness(&mut fresh, &set, &weight, &mu_p3, &s0, beta, input);
            let before = cg_failed.as_ref().map_or(0, |f| f.1);
            solved = Some(tangential::solve(&step, &s0, xi0, &mut fresh).map(|mut sol| {
                sol.sweeps += before;
                sol
            }));
        }
        let solved = solved.expect("one of the solvers ran");
        let fell_back = cg_failed.is_some();
        let sol = solved.map_err(|history| {
            let last = history.last().copied().unwrap_or(f64::NAN);
            let cg = match &cg_failed {
                Some((h, products)) => format!(
                    "the CG solver did not converge in {} Newton iterations ({products} products, max |R| {:.3e} -> {:.3e} m/s), then ",
                    h.len(),
                    h.first().copied().unwrap_or(f64::NAN),
                    h.last().copied().unwrap_or(f64::NAN)
                ),
                None => String::new(),
            };
            ContactError::NoConvergence {
                force,
                reason: format!(
                    "{cg}Gauss-Seidel on the fixed grid ({nc} elements in contact) did not converge in {} sweeps: max |R| {:.3e} -> {:.3e} m/s (tolerance {:.1e})",
                    history.len(),
                    history.first().copied().unwrap_or(f64::NAN),
                    last,
                    step.tol
                ),
            }
        })?;
        // The stick test of the law that solved the step: CG's limit of
        // exact Coulomb friction leaves stick slips of up to hundreds of its
        // eps (where |p| nears mu p3); below the kinematic tolerance a slip
        // is zero to the solver's precision.
        let solved_law = match (law, newton_krylov && !fell_back) {
            (Law::Coulomb, true) => Law::Regularised { eps: step.tol / STICK_SLIP_FACTOR },
            _ => law,
        };
        let (mut out, s_grid) = self.expand((input, solved_law), &set, &weight, p3, &sol);
        out.fallback = fell_back;
        Ok(Solved { out, s_grid, u: exact.u, fell_back })
    }

    /// The earlier-displacement term `u~` and weight `beta` of the
    /// difference at the elements of `set` (the stored fields shifted by
    /// one and two columns), and the warm start (the last step's slips at
    /// the same elements, its creepage). A virgin start: zeros, beta = 1.
    fn earlier(&self, set: &ContactSet) -> Earlier {
        let (nx, nc) = (self.grid.nx, set.len());
        let mut e =
            Earlier { u_prev: vec![0.0; 2 * nc], beta: 1.0, s0: vec![0.0; 2 * nc], p0: vec![0.0; 2 * nc], xi0: 0.0 };
        let Some(h) = &self.history else {
            return e;
        };
        let at = |f: &(Vec<f64>, Vec<f64>), k: usize, back: usize| (f.0[k - back], f.1[k - back]);
        let order = match self.spec.scheme {
            GridScheme::FirstOrder => 1,
            GridScheme::SecondOrder => 2,
            GridScheme::ThirdOrder => 3,
        };
        let level = match (&h.older, &h.oldest) {
            (Some(_), Some(_)) => order.min(3),
            (Some(_), None) => order.min(2),
            _ => 1,
        };
        for (c, &k) in set.element.iter().enumerate() {
            debug_assert!(k % nx >= level, "kept off the leading edge by check_inside");
            let (ox, oy) = at(&h.u, k, 1);
            let (ux, uy) = match level {
                3 => {
                    let (qx, qy) = at(h.older.as_ref().expect("level 3"), k, 2);
                    let (rx, ry) = at(h.oldest.as_ref().expect("level 3"), k, 3);
                    (3.0 * ox - 1.5 * qx + rx / 3.0, 3.0 * oy - 1.5 * qy + ry / 3.0)
                }
                2 => {
                    let (qx, qy) = at(h.older.as_ref().expect("level 2"), k, 2);
                    (2.0 * ox - 0.5 * qx, 2.0 * oy - 0.5 * qy)
                }
                _ => (ox, oy),
            };
            e.u_prev[2 * c] = ux;
            e.u_prev[2 * c + 1] = uy;
            e.s0[2 * c] = h.s[2 * k];
            e.s0[2 * c + 1] = h.s[2 * k + 1];
            e.p0[2 * c] = h.p[2 * k];
            e.p0[2 * c + 1] = h.p[2 * k + 1];
        }
        e.beta = [1.0, 1.5, 11.0 / 6.0][level - 1];
        e.xi0 = h.xi;
        e
    }

    /// The step's solution on the whole grid (zero outside contact; a
    /// folded element and its mirror image, y components negated; stick by
    /// `law`, the law that solved it) and the slips kept for the next warm
    /// start.
    fn expand(
        &self,
        (input, law): (&StepInput, Law),
        set: &ContactSet,
        weight: &[f64],
        p3: &[f64],
        sol: &tangential::GridSolution,
    ) -> (PatchSolution, Vec<f64>) {
        let (nx, ny, n) = (self.grid.nx, self.grid.ny, self.grid.len());
        let mut out = PatchSolution {
            creepage: Creepage { x: sol.xi, y: input.creepage_y, spin: input.spin },
            pressure: p3.to_vec(),
            traction_x: vec![0.0; n],
            traction_y: vec![0.0; n],
            slip_x: vec![0.0; n],
            slip_y: vec![0.0; n],
            stick: vec![false; n],
            iterations: sol.sweeps,
            ..Default::default()
        };
        let mut s_grid = vec![0.0; 2 * n];
        for (c, &k) in set.element.iter().enumerate() {
            let (sx, sy) = (sol.s[2 * c], sol.s[2 * c + 1]);
            let stick = law.is_stick([sx, sy]);
            let mirror = (ny - 1 - k / nx) * nx + k % nx;
            let images: &[(usize, f64)] = if weight[c] == 2.0 { &[(k, 1.0), (mirror, -1.0)] } else { &[(k, 1.0)] };
            for &(e, sign) in images {
                out.traction_x[e] = sol.p[2 * c];
                out.traction_y[e] = sign * sol.p[2 * c + 1];
                out.slip_x[e] = sx;
                out.slip_y[e] = sign * sy;
                out.stick[e] = stick;
                s_grid[2 * e] = sx;
                s_grid[2 * e + 1] = sign * sy;
            }
        }
        let area = self.grid.area();
        out.force_x = out.traction_x.iter().sum::<f64>() * area;
        out.force_y = out.traction_y.iter().sum::<f64>() * area;
        (out, s_grid)
    }

    /// dF_x/dxi_x estimate (N), as the adapted solver's: the stick area
    /// (|s| < 10 eps at the warm start) answers a uniform slip change with
    /// the uniform traction change that cancels it through its mean row sum
    /// of `(beta/dt) K_xx` (one product, `product(p, u)` as the step's:
    /// interleaved tractions on `set`, displacements x block then y block);
    /// slip elements answer through their own law's derivative.
    #[allow(clippy::too_many_arguments)]
    fn creepage_stiffness(
        &self,
        product: &mut dyn FnMut(&[f64], &mut [f64]),
        set: &ContactSet,
        weight: &[f64],
        mu_p3: &[f64],
        s: &[f64],
        beta: f64,
        input: &StepInput,
    ) -> f64 {
        let nc = set.len();
        let eps = self.spec.eps;
        let scale = beta / input.dt;
        let stick: Vec<bool> = (0..nc).map(|c| s[2 * c].hypot(s[2 * c + 1]) < STICK_SLIP_FACTOR * eps).collect();
        let unit: Vec<f64> = stick.iter().flat_map(|&st| [if st { 1.0 } else { 0.0 }, 0.0]).collect();
        let mut u = vec![0.0; 2 * nc];
        product(&unit, &mut u);
        let count: f64 = (0..nc).filter(|&c| stick[c]).map(|c| weight[c]).sum();
        let mut kappa = 0.0;
        let area = self.grid.area();
        if count > 0.0 {
            let rows: f64 = (0..nc).filter(|&c| stick[c]).map(|c| weight[c] * scale * u[c]).sum();
            kappa += count * area / (rows / count);
        }
        let k0 = scale * self.kernel.at(0, 0, 0);
        for c in 0..nc {
            if !stick[c] {
                let (_, d) = friction([s[2 * c], s[2 * c + 1]], mu_p3[c], eps);
                kappa += weight[c] * area * d[0] / (1.0 + k0 * d[0]);
            }
        }
        -input.speed * kappa.max(1e-30)
    }
}

fn normal_reason(e: NormalError) -> String {
    format!("normal problem on the fixed grid: {e}")
}

impl TangentialSolver for FixedGrid {
    fn step(&mut self, input: &StepInput) -> Result<PatchSolution, ContactError> {
        self.step_ahead(input, None)
    }

    fn step_ahead(&mut self, input: &StepInput, next: Option<&StepInput>) -> Result<PatchSolution, ContactError> {
        match (&self.surface, &mut self.active) {
            (Some(RailContact::Linear(_)), Some(window)) => {
                let sol = window.grid.solve_step(input, next)?;
                Ok(window.embed(sol, &self.grid))
            }
            _ => self.solve_step(input, next),
        }
    }

    fn reset(&mut self) {
        self.history = None;
        self.ahead = None;
        self.fallbacks = 0;
        if let Some(w) = &mut self.active {
            w.grid.reset();
        }
    }

    fn elements(&self) -> Elements {
        Elements::Grid(self.grid.clone())
    }

    fn set_surface(&mut self, surface: Option<RailContact>) -> Result<(), ContactError> {
        // The linear contact's response, once: its operator depends on the
        // Hertz shape alone.
        if matches!(surface, Some(RailContact::Linear(_))) && self.linear.is_none() {
            let shape =
                HertzShape::new(self.spec.curvatures, self.spec.elastic).map_err(|_| ContactError::NoSurface)?;
            let mesh = EllipseMesh::new(LINEAR_NORMAL_NX, LINEAR_NORMAL_NY);
            self.linear = Some(Arc::new(MeshResponse::new(&mesh, &shape)));
        }
        // A linear surface goes to the window, if any holds it.
        self.active = match &surface {
            Some(RailContact::Linear(s)) => self.window_for(s),
            _ => None,
        };
        if let Some(w) = &mut self.active {
            w.grid.linear = self.linear.clone();
            w.grid.set_surface(surface.clone())?;
        }
        self.surface = surface;
        self.approach_start = None;
        self.ahead = None;
        Ok(())
    }

    fn linear_resolution(&self, a: f64) -> Option<f64> {
        Some(8.0 * 2.0 * a / LINEAR_NORMAL_NX as f64)
    }

    fn approach(&mut self, position: f64, force: f64) -> Result<f64, ContactError> {
        Ok(self.normal_solution(position, force)?.approach)
    }

    fn approaches(&mut self, positions: &[f64], force: f64) -> Result<Vec<f64>, (usize, ContactError)> {
        // Two chains, one per half, each warm-started along itself from a
        // cold start: the same result on any number of threads.
        let (first, second) = positions.split_at(positions.len() / 2);
        let this = &*self;
        let (a, b) = rayon::join(|| this.approach_chain(first, force), || this.approach_chain(second, force));
        let (mut out, _) = a?;
        let (rest, last) = b.map_err(|(j, e)| (first.len() + j, e))?;
        out.extend(rest);
        self.approach_start = last;
        Ok(out)
    }
}
