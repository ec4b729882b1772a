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

use super::solver::FixedGrid;
use super::{GRID_MARGIN, GridSolver, PotentialGrid};
use crate::contact::PatchSolution;

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
    /// with the grid's margins (`lead` columns ahead for the earlier
    /// displacements, one element elsewhere, and one more), its tangential solver
    /// `solver`; `None` when that is the whole grid.
    pub(super) fn new(outer: &FixedGrid, a: f64, b: f64, lead: usize, solver: GridSolver) -> Option<Window> {
        let g = outer.grid();
        // One element more than the grid's own margins: the linear
        // contact's pressure is a mean over each element, so an element the
        // edge only cuts is in contact.
        let half_x = a * (1.0 + GRID_MARGIN) + (lead + 1) as f64 * g.dx;
        let half_y = b * (1.0 + GRID_MARGIN) + 2.0 * g.dy;
        // Columns run from the front (x_front) backwards; rows upwards from
        // y_low, symmetric about the centre line.
        let ix0 = ((g.x_front - half_x) / g.dx).floor().max(0.0) as usize;
        let ix1 = (((g.x_front + half_x) / g.dx).ceil() as usize).min(g.nx);
        let iy0 = (((-half_y - g.y_low) / g.dy).floor().max(0.0) as usize).min(g.ny / 2);
        let (nx, ny) = (ix1.saturating_sub(ix0), g.ny - 2 * iy0);
        if nx * ny >= g.len() || nx == 0 || ny == 0 {
            return None;
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

    /// Whether the block covers a patch of semi-axes `a` x `b` (m) with
    /// the margins of [`Window::new`].
    pub(super) fn holds(&self, a: f64, b: f64) -> bool {
        let g = self.grid.grid();
        let lead = self.grid.lead_columns();
        let half_x = a * (1.0 + GRID_MARGIN) + (lead + 1) as f64 * g.dx;
        let half_y = b * (1.0 + GRID_MARGIN) + 2.0 * g.dy;
        g.x_front >= half_x && g.x_front - g.nx as f64 * g.dx <= -half_x && g.y_low <= -half_y
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
