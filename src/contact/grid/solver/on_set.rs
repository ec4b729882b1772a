//! Products of a step on its elements in contact: a field given on the
//! elements in contact (interleaved x, y) scattered onto the grid (with its
//! mirror image on a folded grid: x the same, y negated), an FFT product
//! over the whole grid, gathered back.

use super::super::convolution::{FftConvolution, FftScratch, Real};
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
    set: &'a ContactSet,
    weight: &'a [f64],
    /// Grid columns and rows.
    shape: (usize, usize),
    layout: Layout,
    g: (Vec<f64>, Vec<f64>),
    /// The last product on the whole grid (x, y).
    pub u: (Vec<f64>, Vec<f64>),
}

impl<'a, T: Real> OnSet<'a, T> {
    pub fn new(
        conv: &'a FftConvolution<T>,
        set: &'a ContactSet,
        weight: &'a [f64],
        shape: (usize, usize),
        layout: Layout,
    ) -> Self {
        let n = shape.0 * shape.1;
        OnSet {
            conv,
            scratch: FftScratch::default(),
            set,
            weight,
            shape,
            layout,
            g: (vec![0.0; n], vec![0.0; n]),
            u: (vec![0.0; n], vec![0.0; n]),
        }
    }

    /// `out = conv (field)` on the elements in contact.
    pub fn product(&mut self, field: &[f64], out: &mut [f64]) {
        let (nx, ny) = self.shape;
        let mirror = |k: usize| (ny - 1 - k / nx) * nx + k % nx;
        let (gx, gy) = (&mut self.g.0, &mut self.g.1);
        gx.fill(0.0);
        gy.fill(0.0);
        for (c, &k) in self.set.element.iter().enumerate() {
            gx[k] = field[2 * c];
            gy[k] = field[2 * c + 1];
            if self.weight[c] == 2.0 {
                gx[mirror(k)] = field[2 * c];
                gy[mirror(k)] = -field[2 * c + 1];
            }
        }
        let (ux, uy) = (&mut self.u.0, &mut self.u.1);
        self.conv.tangential(&mut self.scratch, (gx, gy), (ux, uy));
        let nc = self.set.len();
        for (c, &k) in self.set.element.iter().enumerate() {
            match self.layout {
                Layout::Blocks => (out[c], out[nc + c]) = (ux[k], uy[k]),
                Layout::Interleaved => (out[2 * c], out[2 * c + 1]) = (ux[k], uy[k]),
            }
        }
    }
}
