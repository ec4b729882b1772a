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
//! * [`GridScheme::FirstOrder`](super::spec::GridScheme::FirstOrder): `(u - u_o) / dt`, CONTACT's transient
//!   rolling; first order in dx (the slip sits half an element upstream of
//!   the traction it goes with);
//! * [`GridScheme::SecondOrder`](super::spec::GridScheme::SecondOrder): `(3 u - 4 u_o + u_oo) / (2 dt)`, the
//!   second-order backward difference along the material path (first order
//!   on the step after a virgin start).
//!
//! A virgin start (a new passage, or contact regained) is Cattaneo's shift
//! problem: `u_o = 0`, the rigid shift over the step `V xi dt`.

use super::convolution::{FftConvolution, FftScratch, ToeplitzKernel};
use super::coupling::FoldedKernel;
use super::normal::{self, NormalError, NormalProducts};
use super::spec::{FixedGridSpec, GRID_TOLERANCE, GridSolver};
use super::symmetric::{self, SymmetricConvolution, SymmetricNormal};
use super::tangential::Law;
mod block;
mod edge;
mod normal_block;
mod on_set;
mod pressure;
mod tangential_step;
mod window;

use super::PotentialGrid;
use crate::contact::linear::MeshResponse;
use crate::contact::mesh::EllipseMesh;
use crate::contact::{ContactError, Elements, PatchSolution, RailContact, StepInput, TangentialSolver};
use crate::hertz::HertzShape;
use pressure::{Ahead, Pressure};
use std::borrow::Cow;
use std::sync::Arc;
use tangential_step::Solved;
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
    /// With friction memory: the ratio `mu / mu_0` each element's
    /// material had at the end of the last step (1).
    kept: Option<Vec<f64>>,
}

/// The approaches of a chain of positions (m) and its last pressure (Pa).
type Chain = (Vec<f64>, Option<Vec<f64>>);

/// The tangential products of a folded grid's symmetric fields: as
/// `tangential`, `tangential_single` and `inverse_single`.
#[derive(Debug, Clone)]
struct SymmetricProducts {
    exact: SymmetricConvolution,
    single: SymmetricConvolution<f32>,
    inverse: SymmetricConvolution<f32>,
}

/// Under a falling friction characteristic the CG solver's Newton matrix
/// freezes the coefficient (its own slope is negative along the slip) and
/// can stall where much of the patch slides; each stalled step costs CG's
/// iterations and then Gauss-Seidel's. After a stall CG sits out the next
/// `next` steps (8, doubling with each stall in a row up to 64; back to 8
/// when it converges), which Gauss-Seidel solves directly. On
/// configs/growth_exact.toml (100 km/h) with Polach's law a passage takes
/// 2.30 s CPU this way, 7.22 s with Gauss-Seidel alone, 1.23 s under
/// constant friction (scripts/laws_cost.sh, medians); at 140 km/h 6.5-7.7
/// s, Gauss-Seidel alone 6.4-7.2 s (without the pause CG's stalls cost
/// about twice Gauss-Seidel's time there). Constant and rising
/// characteristics never pause (their results stay those of CG first, bit
/// for bit).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct CgPause {
    /// Steps left to sit out.
    skip: usize,
    /// Steps to sit out after the next stall.
    next: usize,
}

impl Default for CgPause {
    fn default() -> Self {
        CgPause { skip: 0, next: CG_PAUSE_FIRST }
    }
}

/// The first pause after a stall (steps).
const CG_PAUSE_FIRST: usize = 8;
/// The longest pause (steps).
const CG_PAUSE_LONGEST: usize = 64;

impl CgPause {
    /// After a step: whether CG tried it and whether it stalled.
    fn update(&mut self, tried: bool, stalled: bool) {
        if !tried {
            self.skip = self.skip.saturating_sub(1);
        } else if stalled {
            self.skip = self.next;
            self.next = (2 * self.next).min(CG_PAUSE_LONGEST);
        } else {
            self.next = CG_PAUSE_FIRST;
        }
    }
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
    /// Its products of symmetric fields: tangential, and normal with the
    /// normal CG's preconditioner.
    symmetric: Option<SymmetricProducts>,
    normal_symmetric: Option<(SymmetricNormal, SymmetricNormal)>,
    /// The contact blocks' products of a folded grid, by size: the CG
    /// solver's, and the normal solves' (with the normal kernel they are
    /// cut from).
    blocks: block::Blocks<block::BlockProducts>,
    /// The contact blocks' products of an unfolded step, by size.
    full_blocks: block::Blocks<block::FullBlockProducts>,
    normal_blocks: block::Blocks<(SymmetricNormal, SymmetricNormal)>,
    normal_kernel: ToeplitzKernel,
    /// The rail surface in the gap (`None`: the quadratic gap alone).
    surface: Option<RailContact>,
    /// Warm start of [`FixedGrid::approach`]'s normal solves (Pa).
    approach_start: Option<Vec<f64>>,
    /// Steps the Newton-Krylov solver handed to Gauss-Seidel since the last
    /// reset.
    fallbacks: usize,
    /// Steps on which CG is not tried after it stalled under a falling
    /// friction characteristic.
    cg_pause: CgPause,
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
            symmetric: None,
            normal_symmetric: None,
            blocks: block::Blocks::default(),
            full_blocks: block::Blocks::default(),
            normal_blocks: block::Blocks::default(),
            normal_kernel: normal_kernel.clone(),
            surface: None,
            approach_start: None,
            fallbacks: 0,
            cg_pause: CgPause::default(),
            linear: None,
            window: None,
            active: None,
        }
        .fold_if_symmetric(&normal_kernel)
    }

    /// Folds the coupling when the grid is symmetric about y = 0 (it is used
    /// on the steps whose loads are: no lateral creepage, no spin).
    fn fold_if_symmetric(mut self, normal_kernel: &ToeplitzKernel) -> Self {
        let g = &self.grid;
        if (g.y_low + 0.5 * g.ny as f64 * g.dy).abs() <= 1e-9 * g.dy {
            self.normal_symmetric =
                Some((SymmetricNormal::padded(normal_kernel), SymmetricNormal::circulant_inverse(normal_kernel)));
            self.folded = Some(FoldedKernel::new(&self.kernel));
            self.symmetric = Some(SymmetricProducts {
                exact: SymmetricConvolution::padded(&self.kernel),
                single: SymmetricConvolution::padded(&self.kernel).to_single(),
                inverse: SymmetricConvolution::circulant_inverse(&self.kernel).to_single(),
            });
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
        let g = &self.grid;
        let xs: Vec<f64> = (0..g.nx).map(|i| position + g.x(i)).collect();
        let ys: Vec<f64> = (0..g.ny).map(|j| g.y(j)).collect();
        debug_assert_eq!(self.gap.len(), xs.len() * ys.len(), "the gap covers the grid");
        Cow::Owned(self.gap.iter().zip(surface.heights_on(&xs, &ys)).map(|(h, r)| h - r).collect())
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
        self.solve_normal(scratch, &gap, force, start)
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

    /// The normal problem's products and preconditioner for the gap
    /// `gap`: those of symmetric fields where the grid and the gap are
    /// symmetric about y = 0.
    fn normal_products(&self, gap: &[f64]) -> NormalProducts<'_> {
        match &self.normal_symmetric {
            Some((conv, pre)) if self.surface.is_none() || self.symmetric(gap) => NormalProducts::Symmetric(conv, pre),
            _ => NormalProducts::Full(&self.normal, Some(&self.normal_inverse)),
        }
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
        let (nx, ny) = (self.grid.nx, self.grid.ny);
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
        if folded.is_some() {
            symmetric::symmetrize(&mut p3, (nx, ny));
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
        let Solved { mut out, s_grid, u, fell_back, tried_cg, kept } = solved?;
        self.ahead = ahead;
        self.fallbacks += usize::from(fell_back);
        // A falling law, or any varying law with memory (a kept coefficient
        // above the characteristic's falls with the slip speed within the
        // step).
        let may_fall = input.characteristic.steepest_fall() > 0.0
            || (input.memory.is_some() && !input.characteristic.is_constant());
        if may_fall {
            self.cg_pause.update(tried_cg, fell_back);
        }
        out.clipped = clipped;
        let (older, oldest) = match self.history.take() {
            Some(h) => (Some(h.u), h.older),
            None => (None, None),
        };
        let p_grid = out.traction_x.iter().zip(&out.traction_y).flat_map(|(x, y)| [*x, *y]).collect();
        self.history = Some(History { u, older, oldest, p3, s: s_grid, p: p_grid, xi: out.creepage.x, kept });
        Ok(out)
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
        self.cg_pause = CgPause::default();
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

#[cfg(test)]
mod pause_tests {
    use super::CgPause;

    /// CG sits out 8 steps after a stall, 16, 32 and at most 64 after
    /// stalls in a row, and 8 again once it converges.
    #[test]
    fn cg_pause_doubles_and_resets() {
        let mut p = CgPause::default();
        let mut sat_out = Vec::new();
        for stall in [true, true, true, true, true, false, true] {
            assert_eq!(p.skip, 0);
            p.update(true, stall);
            let mut n = 0;
            while p.skip > 0 {
                p.update(false, false);
                n += 1;
            }
            sat_out.push(n);
        }
        assert_eq!(sat_out, vec![8, 16, 32, 64, 64, 0, 8]);
    }
}
