//! The linear profile contact's steps on a window of the fixed grid.
//!
//! `contact.normal = "auto"` sizes the grid for the nonlinear profile
//! contact (troughs lengthen its patch: `contact.profile_grid_scale` 1.5),
//! but a passage in the linear range moves and stretches the patch by a
//! few per cent only. Its steps run on the block of the grid's elements
//! that covers the patch as the linear contact's own grid would (the same
//! elements at the same places, fewer of them), and the fields are put
//! back on the whole grid: the same discretisation at the cost of the
//! smaller grid (the FFT products scale with the grid, not with the
//! contact).

use super::FixedGrid;
use crate::contact::PatchSolution;
use crate::contact::grid::spec::{FixedGridSpec, GridSolver};
use crate::contact::grid::{GRID_MARGIN, PotentialGrid, RailSurface};
use crate::hertz::HertzShape;

/// The half-extents (m) a block must cover for a patch of semi-axes `a` x
/// `b` (m): the grid's own margins (5 %, `lead` columns ahead, one element
/// across) and one element more each way, and half an element along x as a
/// grid of the element's lattice has: an element the patch's edge only
/// cuts is in contact (the linear contact's pressure is a mean over the
/// element), and the centroid's correction moves the ellipse a little
/// beyond the fit's shift.
fn margins(a: f64, b: f64, lead: usize, g: &PotentialGrid) -> (f64, f64) {
    (a * (1.0 + GRID_MARGIN) + (lead as f64 + 1.5) * g.dx, b * (1.0 + GRID_MARGIN) + 2.0 * g.dy)
}

/// A block of the grid's elements and the model on it.
#[derive(Debug, Clone)]
pub(super) struct Window {
    /// The model on the block.
    pub(super) grid: Box<FixedGrid>,
    /// Column and row of the whole grid where the block starts.
    ix0: usize,
    iy0: usize,
}

impl Window {
    /// The block of `outer` that covers a patch of semi-axes `a` x `b` (m)
    /// with the margins of [`margins`], its tangential solver `solver`;
    /// `None` when that is the whole grid. `reuse` is kept if it is that
    /// block (its model's transforms are built once): the block depends on
    /// the patch alone, not on earlier passages, so a resumed study runs on
    /// the same block.
    pub(super) fn new(
        outer: &FixedGrid,
        (a, b): (f64, f64),
        lead: usize,
        solver: GridSolver,
        reuse: Option<Window>,
    ) -> Option<Window> {
        let g = outer.grid();
        let (half_x, half_y) = margins(a, b, lead, g);
        // Columns run from the front (x_front) backwards; rows upwards from
        // y_low, symmetric about the centre line.
        let ix0 = ((g.x_front - half_x) / g.dx).floor().max(0.0) as usize;
        let ix1 = (((g.x_front + half_x) / g.dx).ceil() as usize).min(g.nx);
        let iy0 = (((-half_y - g.y_low) / g.dy).floor().max(0.0) as usize).min(g.ny / 2);
        let (nx, ny) = (ix1.saturating_sub(ix0), g.ny - 2 * iy0);
        if nx * ny >= g.len() || nx == 0 || ny == 0 {
            return None;
        }
        if let Some(w) = reuse.filter(|w| (w.ix0, w.iy0, w.grid.grid().nx, w.grid.grid().ny) == (ix0, iy0, nx, ny)) {
            return Some(w);
        }
        let block = PotentialGrid {
            nx,
            ny,
            dx: g.dx,
            dy: g.dy,
            x_front: g.x_front - ix0 as f64 * g.dx,
            y_low: g.y_low + iy0 as f64 * g.dy,
        };
        Some(Window { grid: Box::new(outer.on_block(block, solver)), ix0, iy0 })
    }

    /// A step's fields on the block, put back on the whole grid `outer`
    /// (zero outside the block).
    pub(super) fn embed(&self, sol: PatchSolution, outer: &PotentialGrid) -> PatchSolution {
        let inner = self.grid.grid();
        let n = outer.len();
        let at = |k: usize| (k / inner.nx + self.iy0) * outer.nx + k % inner.nx + self.ix0;
        let spread = |v: &[f64]| {
            let mut out = vec![0.0; n];
            v.iter().enumerate().for_each(|(k, x)| out[at(k)] = *x);
            out
        };
        let mut stick = vec![false; n];
        sol.stick.iter().enumerate().for_each(|(k, s)| stick[at(k)] = *s);
        PatchSolution {
            pressure: spread(&sol.pressure),
            traction_x: spread(&sol.traction_x),
            traction_y: spread(&sol.traction_y),
            slip_x: spread(&sol.slip_x),
            slip_y: spread(&sol.slip_y),
            stick,
            ..sol
        }
    }
}

impl FixedGrid {
    /// The same model on a block of this grid's elements, with the
    /// tangential solver `solver`.
    fn on_block(&self, block: PotentialGrid, solver: GridSolver) -> Self {
        Self::build(FixedGridSpec { solver, ..self.spec }, block).with_tolerance(self.tolerance)
    }

    /// Runs the steps of the linear profile contact on a block of the grid
    /// (this module) with the tangential solver `solver`; the
    /// grid holds the nonlinear contact's larger patches. Each linear
    /// surface set sizes the block for the patch it moves and stretches
    /// under the largest normal force `n_max` (N) (`window_for`).
    pub fn with_linear_window(mut self, n_max: f64, solver: GridSolver) -> Self {
        self.window = Some((n_max, solver));
        self
    }

    /// The block a linear `surface` runs on: the largest extent of the
    /// linear contact's moved and stretched ellipse under the largest load
    /// with the patch centre at any node of the surface
    /// ([`MeshResponse::extent`]; the surface is a growth study's periodic
    /// stretch), with the grid's margins and one element more; `None` when
    /// that is the whole grid.
    pub(super) fn window_for(&mut self, surface: &RailSurface) -> Option<Window> {
        let (n_max, solver) = self.window?;
        let patch = HertzShape::new(self.spec.curvatures, self.spec.elastic).ok()?.patch(n_max).ok()?;
        let nodes = surface.heights.dim().1;
        let positions = (0..nodes).map(|i| surface.x0 + i as f64 * surface.dx);
        let extent = self.linear.as_ref()?.extent(surface, positions, &patch);
        let reuse = self.active.take();
        Window::new(self, extent, self.spec.lead_columns(), solver, reuse)
    }
}
