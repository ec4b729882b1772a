//! Wear of the fixed-grid model on the rail grid, exactly conservative.
//!
//! The slip of an element of the fixed grid at step n is the mean slip of
//! the rail material that element covers over the step (the material moved
//! by exactly one element, [`crate::contact::grid::solver`]), so its Archard
//! rate `r` (m/s) belongs to that material for the step's `dt`: the
//! element's footprint on the rail at `X_c(n)` receives the volume `r dt dx
//! dy`, spread over the rail cells (a rail node `(x_i, y_j)` stands for the
//! cell `x_i +- rail.dx/2`, `y_j +- rail.dy/2`) in proportion to their
//! overlap with the footprint:
//!
//! ```text
//! W_ij += r dt * overlap_x(i) overlap_y(j) / (rail.dx rail.dy)
//! ```
//!
//! No interpolation: the volume deposited is `sum_n dt sum_k r_k dx dy`, the
//! time integral of the patch's wear rate, to rounding. When the rail cells
//! line up with the elements (the contact grid is placed so, for
//! `contact.dx` a whole multiple of `rail.dx`, likewise in y), every
//! overlap is 0 or a whole cell: each element's wear goes onto exactly the
//! cells it covers.

use super::deposit::{PatchWear, WearKernel};
use crate::contact::grid::PotentialGrid;
use crate::rail_grid::RailGrid;
use ndarray::Array2;

/// The conservative deposit of the fixed grid's elements.
#[derive(Debug, Clone)]
pub struct CellDeposit {
    grid: PotentialGrid,
}

/// Overlaps below this fraction of a cell are rounding slivers of lined-up
/// grids (set to zero; the weights are renormalised to the element length).
const SLIVER: f64 = 1e-9;

/// The rail cells (index, overlap in m) of the interval `[lo, hi]` on the
/// lattice `origin + i d`, `i < n`: overlaps exact to rounding, slivers
/// removed and the total kept at `hi - lo` before cells outside the lattice
/// are dropped.
fn overlaps(lo: f64, hi: f64, origin: f64, d: f64, n: usize, out: &mut Vec<(usize, f64)>) {
    out.clear();
    let first = ((lo - origin) / d - 0.5).floor() as i64;
    let last = ((hi - origin) / d + 0.5).ceil() as i64;
    let mut cells: Vec<(i64, f64)> = (first..=last)
        .map(|i| {
            let c = origin + i as f64 * d;
            (i, (hi.min(c + 0.5 * d) - lo.max(c - 0.5 * d)).max(0.0))
        })
        .filter(|(_, w)| *w > SLIVER * d)
        .collect();
    let total: f64 = cells.iter().map(|(_, w)| w).sum();
    if total > 0.0 {
        let f = (hi - lo) / total;
        cells.iter_mut().for_each(|(_, w)| *w *= f);
    }
    out.extend(cells.into_iter().filter(|(i, _)| *i >= 0 && (*i as usize) < n).map(|(i, w)| (i as usize, w)));
}

impl CellDeposit {
    /// The deposit of the elements of `grid` (contact frame).
    pub fn new(grid: PotentialGrid) -> Self {
        CellDeposit { grid }
    }
}

impl WearKernel for CellDeposit {
    /// Deposits the rates of `to` (on the grid elements) for `dt` at the
    /// footprint of the grid at `to.x_c`; `from` and `substeps` play no part
    /// (the rate is the step's mean over the material it names).
    fn accumulate(
        &self,
        rail: &RailGrid,
        wear: &mut Array2<f64>,
        _from: &PatchWear,
        to: &PatchWear,
        dt: f64,
        _substeps: usize,
    ) {
        let g = &self.grid;
        let (mut wx, mut wy) = (Vec::new(), Vec::new());
        let rows: Vec<Vec<(usize, f64)>> = (0..g.ny)
            .map(|iy| {
                let (lo, hi) = (g.y_low + iy as f64 * g.dy, g.y_low + (iy + 1) as f64 * g.dy);
                overlaps(lo, hi, -rail.half_width, rail.dy, rail.ny, &mut wy);
                wy.clone()
            })
            .collect();
        let cell_area = rail.dx * rail.dy;
        for ix in 0..g.nx {
            let hi = to.x_c + g.x_front - ix as f64 * g.dx;
            overlaps(hi - g.dx, hi, rail.x_min, rail.dx, rail.nx, &mut wx);
            if wx.is_empty() {
                continue;
            }
            for (iy, row) in rows.iter().enumerate() {
                let r = to.rates[iy * g.nx + ix];
                if r == 0.0 {
                    continue;
                }
                let depth = r * dt / cell_area;
                for &(j, oy) in row {
                    for &(i, ox) in &wx {
                        wear[[j, i]] += depth * ox * oy;
                    }
                }
            }
        }
    }

    fn integral(&self, rates: &[f64], _a: f64, _b: f64) -> f64 {
        rates.iter().sum::<f64>() * self.grid.area()
    }

    /// The elements' length: one element per step.
    fn pitch(&self) -> Option<f64> {
        Some(self.grid.dx)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overlaps_of_lined_up_and_shifted_intervals() {
        let mut out = Vec::new();
        // An element of 0.2 over cells of 0.1 centred on the lattice: two
        // whole cells.
        overlaps(0.05, 0.25, 0.0, 0.1, 10, &mut out);
        assert_eq!(out.len(), 2);
        assert!(out.iter().all(|(_, w)| (w - 0.1).abs() < 1e-15));
        assert_eq!((out[0].0, out[1].0), (1, 2));
        // Shifted by a quarter cell: three cells, 0.075 + 0.1 + 0.025.
        overlaps(0.075, 0.275, 0.0, 0.1, 10, &mut out);
        let w: Vec<f64> = out.iter().map(|(_, w)| *w).collect();
        assert_eq!(out.iter().map(|(i, _)| *i).collect::<Vec<_>>(), vec![1, 2, 3]);
        assert!((w[0] - 0.075).abs() < 1e-15 && (w[1] - 0.1).abs() < 1e-15 && (w[2] - 0.025).abs() < 1e-15);
        // Off the lattice: dropped.
        overlaps(-0.3, -0.2, 0.0, 0.1, 10, &mut out);
        assert!(out.is_empty());
    }
}
