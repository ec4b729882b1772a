//! Products of a step on its elements in contact: a field given on the
//! elements in contact (interleaved x, y) scattered onto the grid (with its
//! mirror image on a folded grid: x the same, y negated), an FFT product
//! over the whole grid, gathered back. On a folded grid the symmetric
//! product ([`SymmetricConvolution`]) reads the lower half alone, at about
//! half the cost. Either product may run on a block of the grid that holds
//! the elements in contact ([`super::block`]): symmetric about the centre
//! line on a folded grid, the general product's block on an unfolded one.

use super::super::convolution::{FftConvolution, FftScratch, Real};
use super::super::symmetric::{SymmetricConvolution, SymmetricScratch};
use super::super::tangential::ContactSet;

/// Whether the output comes back as an x block then a y block (`K p`, as
/// the tangential solvers take it) or interleaved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Layout {
    Blocks,
    Interleaved,
}

/// Work fields of one kind of product.
pub(super) struct OnSet<'a, T: Real> {
    conv: &'a FftConvolution<T>,
    scratch: FftScratch<T>,
    /// The same product for symmetric fields, used on a folded grid.
    symmetric: Option<(&'a SymmetricConvolution<T>, SymmetricScratch<T>)>,
    /// The set's columns and rows in the block the symmetric product runs
    /// on (`None`: the whole grid).
    place: Option<(Vec<usize>, Vec<usize>)>,
    /// The set's elements in the block the general product runs on
    /// (`None`: the whole grid's `set.element`).
    block: Option<Vec<usize>>,
    set: &'a ContactSet,
    weight: &'a [f64],
    /// Grid columns and rows.
    shape: (usize, usize),
    layout: Layout,
    /// The field on the whole grid (x, y), allocated by the first full
    /// product (the symmetric products need none).
    g: (Vec<f64>, Vec<f64>),
    /// The last product on the whole grid (x, y); on a folded grid, from
    /// the symmetric product's scratch once `stale` (allocated where first
    /// needed).
    u: (Vec<f64>, Vec<f64>),
    stale: bool,
}

impl<'a, T: Real> OnSet<'a, T> {
    pub fn new(
        conv: &'a FftConvolution<T>,
        set: &'a ContactSet,
        weight: &'a [f64],
        shape: (usize, usize),
        layout: Layout,
    ) -> Self {
        OnSet {
            conv,
            scratch: FftScratch::default(),
            symmetric: None,
            place: None,
            block: None,
            set,
            weight,
            shape,
            layout,
            g: Default::default(),
            u: Default::default(),
            stale: false,
        }
    }

    /// Products of a folded grid's symmetric fields by `symmetric` (the
    /// set on the lower half of the grid).
    pub fn symmetric(mut self, symmetric: Option<&'a SymmetricConvolution<T>>) -> Self {
        self.symmetric = symmetric.map(|conv| (conv, SymmetricScratch::default()));
        self
    }

    /// Products of a folded grid's symmetric fields by `conv`, the
    /// products of the block of the grid from column `c0` and row `r0` (a
    /// block symmetric about the centre line that holds the set: the same
    /// products on the set, on shorter transforms).
    pub fn on_block(mut self, conv: &'a SymmetricConvolution<T>, (c0, r0): (usize, usize)) -> Self {
        self.symmetric = Some((conv, SymmetricScratch::default()));
        let ix = self.set.ix.iter().map(|&x| x - c0).collect();
        let iy = self.set.iy.iter().map(|&r| r - r0).collect();
        self.place = Some((ix, iy));
        self
    }

    /// Products of an unfolded step's fields by `conv`, the products of
    /// the block of the grid from column `c0` and row `r0` that holds the
    /// set (the same products on the set, on shorter transforms).
    pub fn on_full_block(mut self, conv: &'a FftConvolution<T>, (c0, r0): (usize, usize)) -> Self {
        debug_assert!(self.weight.iter().all(|&w| w == 1.0), "an unfolded set");
        let (bx, by) = conv.shape();
        self.conv = conv;
        self.shape = (bx, by);
        self.block = Some(self.set.ix.iter().zip(&self.set.iy).map(|(&x, &y)| (y - r0) * bx + (x - c0)).collect());
        self
    }

    /// `out = conv (field)` on the elements in contact.
    pub fn product(&mut self, field: &[f64], out: &mut [f64]) {
        let nc = self.set.len();
        let layout = self.layout;
        let mut store = |c: usize, x: f64, y: f64| match layout {
            Layout::Blocks => (out[c], out[nc + c]) = (x, y),
            Layout::Interleaved => (out[2 * c], out[2 * c + 1]) = (x, y),
        };
        if let Some((conv, scratch)) = &mut self.symmetric {
            let (ix, iy) = self.place.as_ref().map_or((&self.set.ix, &self.set.iy), |(x, y)| (x, y));
            conv.product_on(scratch, (ix, iy), |c| (field[2 * c], field[2 * c + 1]), store);
            self.stale = true;
            return;
        }
        let (nx, ny) = self.shape;
        let mirror = |k: usize| (ny - 1 - k / nx) * nx + k % nx;
        let (gx, gy) = (&mut self.g.0, &mut self.g.1);
        for v in [&mut *gx, &mut *gy, &mut self.u.0, &mut self.u.1] {
            v.resize(nx * ny, 0.0);
        }
        gx.fill(0.0);
        gy.fill(0.0);
        let elements = self.block.as_ref().unwrap_or(&self.set.element);
        for (c, &k) in elements.iter().enumerate() {
            gx[k] = field[2 * c];
            gy[k] = field[2 * c + 1];
            if self.weight[c] == 2.0 {
                gx[mirror(k)] = field[2 * c];
                gy[mirror(k)] = -field[2 * c + 1];
            }
        }
        let (ux, uy) = (&mut self.u.0, &mut self.u.1);
        self.conv.tangential(&mut self.scratch, (gx, gy), (ux, uy));
        for (c, &k) in elements.iter().enumerate() {
            store(c, ux[k], uy[k]);
        }
    }

    /// The last product on the whole grid (x, y).
    pub fn whole(mut self) -> (Vec<f64>, Vec<f64>) {
        debug_assert!(self.place.is_none() && self.block.is_none(), "a block's product is not the grid's");
        let n = self.shape.0 * self.shape.1;
        self.u.0.resize(n, 0.0);
        self.u.1.resize(n, 0.0);
        if let (Some((conv, scratch)), true) = (&self.symmetric, self.stale) {
            conv.whole_grid(scratch, (&mut self.u.0, &mut self.u.1));
        }
        self.u
    }
}
