//! The normal problem on the contact's block: a symmetric normal solve
//! warm-started from a pressure runs on the block of the grid, symmetric
//! about the centre line, that holds the start's contact area with a
//! margin (the profile contact's grid is 1.5 times the largest patch both
//! ways). On the block the products are the grid's (a linear convolution
//! needs the block's padding alone); outside it the solution is checked on
//! the whole grid with one product (the gap open to the solver's
//! tolerance), and where an element outside would penetrate the problem
//! is solved on the whole grid from the block's solution.

use super::super::convolution::FftScratch;
use super::super::normal::{self, GAP_TOLERANCE, NormalError, NormalProducts, NormalSolution};
use super::super::symmetric::{NormalScratch, SymmetricNormal};
use super::FixedGrid;
use super::block::block_of;

/// Elements of margin around the start's contact area along x (the patch
/// moves by one element per step and grows with the load) and rows across.
const MARGIN: (usize, usize) = (3, 2);

/// Where a normal solve ran.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Path {
    /// The whole grid.
    Whole,
    /// The contact's block.
    Block,
    /// The block, then the whole grid (an element outside the block would
    /// penetrate, or the block's solve failed).
    BlockThenWhole,
}

impl FixedGrid {
    /// The normal problem for `gap` (m, on the whole grid) under `force`
    /// (N) from the pressure `start`: on the contact's block where the
    /// problem is symmetric and the block much smaller than the grid, else
    /// on the whole grid.
    pub(super) fn solve_normal(
        &self,
        scratch: &mut FftScratch,
        gap: &[f64],
        force: f64,
        start: Option<&[f64]>,
    ) -> Result<NormalSolution, NormalError> {
        self.solve_normal_on(scratch, gap, force, start).map(|(solution, _)| solution)
    }

    /// [`FixedGrid::solve_normal`] and where it ran.
    fn solve_normal_on(
        &self,
        scratch: &mut FftScratch,
        gap: &[f64],
        force: f64,
        start: Option<&[f64]>,
    ) -> Result<(NormalSolution, Path), NormalError> {
        let products = self.normal_products(gap);
        let area = self.grid.area();
        let whole_grid = |scratch: &mut FftScratch, start: Option<&[f64]>| {
            normal::solve(products, scratch, gap, area, force, start).map(|solution| (solution, Path::Whole))
        };
        let (NormalProducts::Symmetric(whole, _), Some(start)) = (products, start) else {
            return whole_grid(scratch, start);
        };
        let (nx, ny) = (self.grid.nx, self.grid.ny);
        let support = (0..nx * ny).filter(|&k| start[k] > 0.0);
        let (mut c_min, mut c_max, mut r_min) = (usize::MAX, 0, usize::MAX);
        for k in support {
            let (x, r) = (k % nx, (k / nx).min(ny - 1 - k / nx));
            (c_min, c_max, r_min) = (c_min.min(x), c_max.max(x), r_min.min(r));
        }
        if c_min == usize::MAX {
            return whole_grid(scratch, Some(start));
        }
        let columns = (c_min.saturating_sub(MARGIN.0), (c_max + MARGIN.0).min(nx - 1));
        let Some(((c0, r0), (bx, by))) = block_of(columns, r_min.saturating_sub(MARGIN.1), (nx, ny)) else {
            return whole_grid(scratch, Some(start));
        };
        let cut =
            |field: &[f64]| -> Vec<f64> { (0..bx * by).map(|k| field[(r0 + k / bx) * nx + c0 + k % bx]).collect() };
        let block = self.normal_blocks.get((bx, by), || {
            let kernel = self.normal_kernel.block((bx, by));
            (SymmetricNormal::padded(&kernel), SymmetricNormal::circulant_inverse(&kernel))
        });
        let Ok(on_block) = normal::solve(
            NormalProducts::Symmetric(&block.0, &block.1),
            scratch,
            &cut(gap),
            area,
            force,
            Some(&cut(start)),
        ) else {
            return whole_grid(scratch, Some(start)).map(|(solution, _)| (solution, Path::BlockThenWhole));
        };
        let mut pressure = vec![0.0; nx * ny];
        for (k, &p) in on_block.pressure.iter().enumerate() {
            pressure[(r0 + k / bx) * nx + c0 + k % bx] = p;
        }
        // The whole grid: no element penetrates.
        let mut u = vec![0.0; nx * ny];
        whole.normal(&mut NormalScratch::default(), &pressure, &mut u);
        let tol = GAP_TOLERANCE * on_block.approach.abs().max(f64::MIN_POSITIVE);
        if (0..nx * ny).all(|k| pressure[k] > 0.0 || u[k] + gap[k] - on_block.approach >= -tol) {
            return Ok((NormalSolution { pressure, ..on_block }, Path::Block));
        }
        let (mut again, _) = whole_grid(scratch, Some(&pressure))?;
        again.iterations += on_block.iterations;
        Ok((again, Path::BlockThenWhole))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::friction::FrictionLaw;
    use crate::contact::grid::spec::FixedGridSpec;
    use crate::contact::grid::{GridScheme, GridSolver};
    use crate::hertz::{Curvatures, Elastic, HertzShape};

    /// On the block and, where the contact grows out of it, with the
    /// fallback on the whole grid: the whole grid's solution (pressure
    /// within 1e-8 of its largest, approach within 1e-9).
    #[test]
    fn the_blocks_solution_is_the_whole_grids() {
        let (curvatures, elastic) =
            (Curvatures::wheel_on_rail(0.5, -0.409, 0.3), Elastic { young_modulus: 2.1e11, poisson_ratio: 0.3 });
        let patch = HertzShape::new(curvatures, elastic).unwrap().patch(1.45e5).unwrap();
        let grid = FixedGrid::new(FixedGridSpec::unaligned(
            (curvatures, elastic),
            (4e-4, 1e-3),
            (1.5 * patch.a, 1.5 * patch.b),
            (FrictionLaw::Regularised, GridScheme::SecondOrder, 1e-5),
            GridSolver::Auto,
        ));
        let gap = grid.gap(0.0);
        let mut scratch = FftScratch::default();
        let whole = |force: f64, start: &[f64], scratch: &mut FftScratch| {
            normal::solve(grid.normal_products(&gap), scratch, &gap, grid.grid.area(), force, Some(start)).unwrap()
        };
        let start = normal::solve(grid.normal_products(&gap), &mut scratch, &gap, grid.grid.area(), 5e4, None)
            .unwrap()
            .pressure;
        // 5 % more load: on the block; 2.9 times the load: the contact
        // leaves the block and the whole grid solves it.
        for (force, path) in [(5.25e4, Path::Block), (1.45e5, Path::BlockThenWhole)] {
            let reference = whole(force, &start, &mut scratch);
            let (sol, taken) = grid.solve_normal_on(&mut scratch, &gap, force, Some(&start)).unwrap();
            assert_eq!(taken, path, "{force} N");
            let p_max = reference.pressure.iter().fold(0.0f64, |m, v| m.max(*v));
            let dp = sol.pressure.iter().zip(&reference.pressure).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            assert!(dp < 1e-8 * p_max, "{force} N: {dp:e} of {p_max:e}");
            assert!((sol.approach - reference.approach).abs() < 1e-9 * reference.approach.abs(), "{force} N");
        }
    }
}
