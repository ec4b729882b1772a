//! The contact block: the CG solver's inner products and preconditioner
//! of a folded step on the smallest block of the grid, symmetric about the
//! centre line, that holds the elements in contact (the profile contact's
//! grid is 1.5 times the largest patch both ways: on growth_discrete.toml
//! the block is about a quarter of the grid). On the set the block's
//! zero-padded product is the grid's (a linear convolution needs the
//! padding of the block alone); the preconditioner is the block's
//! circulant inverse. The products of each block size are built once and
//! kept. An unfolded step (a lateral creepage or a spin: the traction is
//! not symmetric) takes the block that holds its elements in contact, its
//! rows no longer symmetric about the centre line, with the general
//! products of that size.

use super::super::convolution::{FftConvolution, ToeplitzKernel};
use super::super::symmetric::SymmetricConvolution;
use super::super::tangential::ContactSet;
use std::collections::HashMap;
use std::sync::{Arc, Mutex};

/// A block's single-precision products: the zero-padded kernel and its
/// circulant inverse.
pub(super) type BlockProducts = (SymmetricConvolution<f32>, SymmetricConvolution<f32>);

/// An unfolded block's single-precision products: the zero-padded kernel
/// and its circulant inverse.
pub(super) type FullBlockProducts = (FftConvolution<f32>, FftConvolution<f32>);

/// Blocks used where the block has at most this fraction of the grid's
/// elements (its transforms are then shorter by enough to pay): on the
/// default passage (paper_normal_30mm, 0.2 mm, the grid sized for 145 kN)
/// 0.6 / 0.85 / 1.0 took 1.48 / 1.37 / 1.38 s.
pub(super) const BLOCK_FRACTION: f64 = 0.85;

/// Block widths are rounded up to multiples of this many columns (and
/// heights to as many rows), so that a passage builds few sizes.
const BLOCK_QUANTUM: usize = 4;

/// The products of the block sizes built so far.
#[derive(Debug)]
pub(super) struct Blocks<P>(Mutex<HashMap<(usize, usize), Arc<P>>>);

impl<P> Default for Blocks<P> {
    fn default() -> Self {
        Blocks(Mutex::new(HashMap::new()))
    }
}

impl<P> Clone for Blocks<P> {
    fn clone(&self) -> Self {
        Blocks(Mutex::new(self.0.lock().expect("not poisoned").clone()))
    }
}

impl<P> Blocks<P> {
    /// The products of blocks of `size`, built by `build` the first time,
    /// outside the lock (a build that used the thread pool could otherwise
    /// wait on a thread waiting for the lock). Two threads that build the
    /// same size at once build the same products; the first kept is used.
    pub fn get(&self, size: (usize, usize), build: impl FnOnce() -> P) -> Arc<P> {
        if let Some(products) = self.0.lock().expect("not poisoned").get(&size) {
            return products.clone();
        }
        let built = Arc::new(build());
        self.0.lock().expect("not poisoned").entry(size).or_insert(built).clone()
    }
}

/// A block's first column and width for columns `c_min ..= c_max` of a
/// grid `nx` wide (the width widened to the quanta).
fn columns((c_min, c_max): (usize, usize), nx: usize) -> (usize, usize) {
    let bx = (c_max - c_min + 1).next_multiple_of(BLOCK_QUANTUM).min(nx);
    (c_min.min(nx - bx), bx)
}

/// The block from `origin` of `size`, where it has at most
/// [`BLOCK_FRACTION`] of the `nx x ny` grid's elements.
fn worth(
    origin: (usize, usize),
    (bx, by): (usize, usize),
    (nx, ny): (usize, usize),
) -> Option<((usize, usize), (usize, usize))> {
    (((bx * by) as f64) <= BLOCK_FRACTION * (nx * ny) as f64).then_some((origin, (bx, by)))
}

/// The columns and rows the set's elements span.
fn extent(set: &ContactSet) -> Option<((usize, usize), (usize, usize))> {
    let (&c_min, &c_max) = (set.ix.iter().min()?, set.ix.iter().max()?);
    let (&r_min, &r_max) = (set.iy.iter().min()?, set.iy.iter().max()?);
    Some(((c_min, c_max), (r_min, r_max)))
}

/// The block of a folded grid of `nx x ny` elements, symmetric about the
/// centre line, that holds columns `c_min ..= c_max` and rows `r_min ..
/// ny - r_min` (widened to the quanta): its first column and row and its
/// size, or `None` where it is not much smaller than the grid.
pub(super) fn block_of(
    columns_held: (usize, usize),
    r_min: usize,
    (nx, ny): (usize, usize),
) -> Option<((usize, usize), (usize, usize))> {
    let (c0, bx) = columns(columns_held, nx);
    // Rows r0 .. ny - r0, symmetric: r0 down to an even count below.
    let r0 = r_min - r_min % (BLOCK_QUANTUM / 2);
    worth((c0, r0), (bx, ny - 2 * r0), (nx, ny))
}

/// The block of a grid of `nx x ny` elements that holds columns `c_min
/// ..= c_max` and rows `r_min ..= r_max` (widened to the quanta): its first
/// column and row and its size, or `None` where it is not much smaller
/// than the grid.
pub(super) fn full_block_of(
    columns_held: (usize, usize),
    (r_min, r_max): (usize, usize),
    (nx, ny): (usize, usize),
) -> Option<((usize, usize), (usize, usize))> {
    let (c0, bx) = columns(columns_held, nx);
    let by = (r_max - r_min + 1).next_multiple_of(BLOCK_QUANTUM).min(ny);
    worth((c0, r_min.min(ny - by)), (bx, by), (nx, ny))
}

impl Blocks<FullBlockProducts> {
    /// The block of a grid of `nx x ny` elements (unfolded) for the set:
    /// its first column and row and its products, or `None` where the whole
    /// grid is as cheap.
    pub fn for_full_set(
        &self,
        kernel: &ToeplitzKernel,
        set: &ContactSet,
        shape: (usize, usize),
    ) -> Option<((usize, usize), Arc<FullBlockProducts>)> {
        let (columns, rows) = extent(set)?;
        let (origin, size) = full_block_of(columns, rows, shape)?;
        let products = self.get(size, || {
            let block = kernel.block(size);
            (FftConvolution::single(&block), FftConvolution::circulant_inverse_single(&block))
        });
        Some((origin, products))
    }
}

impl Blocks<BlockProducts> {
    /// The block of a folded grid of `nx x ny` elements for the set (on the
    /// lower half): its first column and row and its products, or `None`
    /// where the whole grid is as cheap.
    pub fn for_set(
        &self,
        kernel: &ToeplitzKernel,
        set: &ContactSet,
        shape: (usize, usize),
    ) -> Option<((usize, usize), Arc<BlockProducts>)> {
        let (columns, (r_min, _)) = extent(set)?;
        let (origin, size) = block_of(columns, r_min, shape)?;
        let products = self.get(size, || {
            let block = kernel.block(size);
            (
                SymmetricConvolution::padded(&block).to_single(),
                SymmetricConvolution::circulant_inverse(&block).to_single(),
            )
        });
        Some((origin, products))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::grid::PotentialGrid;
    use crate::contact::grid::symmetric::SymmetricScratch;

    /// The tangential kernel of a 58 x 38 grid of 0.4 x 1 mm elements
    /// centred on the origin, and the grid's shape.
    fn test_kernel() -> (ToeplitzKernel, (usize, usize)) {
        let (nx, ny) = (58, 38);
        let grid = PotentialGrid {
            nx,
            ny,
            dx: 4e-4,
            dy: 1e-3,
            x_front: 0.5 * nx as f64 * 4e-4,
            y_low: -0.5 * ny as f64 * 1e-3,
        };
        (ToeplitzKernel::tangential(&grid, 8.1e10, 0.28), (nx, ny))
    }

    /// On the elements in contact the block's product equals the whole
    /// grid's (single precision: within 1e-5 of the largest), and a set
    /// that fills the grid gets no block.
    #[test]
    fn the_block_product_is_the_grids_on_the_set() {
        let (kernel, (nx, ny)) = test_kernel();
        // An ellipse of 30 x 20 elements off the grid's centre along x, on
        // the lower half.
        let inside = |k: usize| {
            let (x, r) = ((k % nx) as f64 - 25.0, (k / nx) as f64 - 18.5);
            (x / 15.0).powi(2) + (r / 10.0).powi(2) < 1.0
        };
        let set = ContactSet::new(nx, ny.div_ceil(2) * nx, inside);
        let blocks = Blocks::<BlockProducts>::default();
        let ((c0, r0), products) = blocks.for_set(&kernel, &set, (nx, ny)).expect("a block");
        let field: Vec<(f64, f64)> =
            (0..set.len()).map(|c| ((c as f64 * 0.37).sin(), (c as f64 * 0.11).cos())).collect();
        let mut whole = vec![(0.0, 0.0); set.len()];
        SymmetricConvolution::padded(&kernel).product_on(
            &mut SymmetricScratch::default(),
            (&set.ix, &set.iy),
            |c| field[c],
            |c, x, y| whole[c] = (x, y),
        );
        let ix: Vec<usize> = set.ix.iter().map(|x| x - c0).collect();
        let iy: Vec<usize> = set.iy.iter().map(|r| r - r0).collect();
        let mut on_block = vec![(0.0, 0.0); set.len()];
        products.0.product_on(
            &mut SymmetricScratch::default(),
            (&ix, &iy),
            |c| field[c],
            |c, x, y| on_block[c] = (x, y),
        );
        let scale = whole.iter().fold(0.0f64, |m, v| m.max(v.0.abs()).max(v.1.abs()));
        let err = whole.iter().zip(&on_block).fold(0.0f64, |m, (a, b)| m.max((a.0 - b.0).abs()).max((a.1 - b.1).abs()));
        assert!(err < 1e-5 * scale, "{err:e} of {scale:e}");
        assert_eq!(blocks.0.lock().unwrap().len(), 1);
        let full = ContactSet::new(nx, ny.div_ceil(2) * nx, |_| true);
        assert!(blocks.for_set(&kernel, &full, (nx, ny)).is_none());
    }

    /// An unfolded set (an ellipse off the centre line both ways): on its
    /// elements the block's general product equals the whole grid's
    /// (single precision: within 1e-5 of the largest); the block is not
    /// symmetric about the centre line.
    #[test]
    fn the_unfolded_block_product_is_the_grids_on_the_set() {
        use crate::contact::grid::convolution::FftScratch;
        let (kernel, (nx, ny)) = test_kernel();
        let inside = |k: usize| {
            let (x, r) = ((k % nx) as f64 - 25.0, (k / nx) as f64 - 22.0);
            (x / 15.0).powi(2) + (r / 10.0).powi(2) < 1.0
        };
        let set = ContactSet::new(nx, nx * ny, inside);
        let blocks = Blocks::<FullBlockProducts>::default();
        let ((c0, r0), products) = blocks.for_full_set(&kernel, &set, (nx, ny)).expect("a block");
        let (bx, by) = products.0.shape();
        assert!(r0 + by / 2 != ny / 2, "the block is off the centre line");
        let field: Vec<(f64, f64)> =
            (0..set.len()).map(|c| ((c as f64 * 0.37).sin(), (c as f64 * 0.11).cos())).collect();
        let product = |conv: &FftConvolution<f32>, (w, h): (usize, usize), index: &dyn Fn(usize) -> usize| {
            let (mut gx, mut gy) = (vec![0.0; w * h], vec![0.0; w * h]);
            for c in 0..set.len() {
                (gx[index(c)], gy[index(c)]) = field[c];
            }
            let (mut ux, mut uy) = (vec![0.0; w * h], vec![0.0; w * h]);
            conv.tangential(&mut FftScratch::default(), (&gx, &gy), (&mut ux, &mut uy));
            (0..set.len()).map(|c| (ux[index(c)], uy[index(c)])).collect::<Vec<_>>()
        };
        let whole = product(&FftConvolution::single(&kernel), (nx, ny), &|c| set.element[c]);
        let on_block = product(&products.0, (bx, by), &|c| (set.iy[c] - r0) * bx + set.ix[c] - c0);
        let scale = whole.iter().fold(0.0f64, |m, v| m.max(v.0.abs()).max(v.1.abs()));
        let err = whole.iter().zip(&on_block).fold(0.0f64, |m, (a, b)| m.max((a.0 - b.0).abs()).max((a.1 - b.1).abs()));
        assert!(err < 1e-5 * scale, "{err:e} of {scale:e}");
        let full = ContactSet::new(nx, nx * ny, |_| true);
        assert!(blocks.for_full_set(&kernel, &full, (nx, ny)).is_none());
    }
}
