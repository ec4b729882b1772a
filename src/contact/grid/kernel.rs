//! Influence coefficients on a uniform grid as functions of the index
//! offset: the block-Toeplitz influence matrix as one table per component
//! ([`ToeplitzKernel`]), the closed-form rectangle integrals of
//! [`crate::contact::influence`]; its products by direct summation (the
//! FFT products' reference).

use super::PotentialGrid;
use crate::contact::influence::{Rect, influence, normal_influence};

/// Influence coefficients of a grid as functions of the index offset.
#[derive(Debug, Clone)]
pub struct ToeplitzKernel {
    nx: usize,
    ny: usize,
    /// Components, each on offsets `(dix, diy)` at
    /// `(dix + nx - 1) + (diy + ny - 1) (2 nx - 1)` (m/Pa).
    comps: Vec<Vec<f64>>,
}

impl ToeplitzKernel {
    /// The normal kernel `K_n`: approach of the two surfaces per unit
    /// pressure (m/Pa).
    pub fn normal(grid: &PotentialGrid, g: f64, nu: f64) -> Self {
        Self::build(grid, 1, |rect, x, y| [normal_influence(rect, x, y, g, nu), 0.0, 0.0])
    }

    /// The tangential kernels `(K_xx, K_xy, K_yy)` of the displacement
    /// difference (m/Pa).
    pub fn tangential(grid: &PotentialGrid, g: f64, nu: f64) -> Self {
        Self::build(grid, 3, |rect, x, y| {
            let c = influence(rect, x, y, g, nu);
            [c.xx, c.xy, c.yy]
        })
    }

    fn build(grid: &PotentialGrid, n_comps: usize, f: impl Fn(&Rect, f64, f64) -> [f64; 3]) -> Self {
        let (nx, ny) = (grid.nx, grid.ny);
        let (wx, wy) = (2 * nx - 1, 2 * ny - 1);
        let rect = Rect { x: 0.0, y: 0.0, hx: 0.5 * grid.dx, hy: 0.5 * grid.dy };
        let mut comps = vec![vec![0.0; wx * wy]; n_comps];
        for j in 0..wy {
            let diy = j as f64 - (ny - 1) as f64;
            for i in 0..wx {
                let dix = i as f64 - (nx - 1) as f64;
                // Columns run against x: x_I - x_J = -(ix_I - ix_J) dx.
                let v = f(&rect, -dix * grid.dx, diy * grid.dy);
                for (c, comp) in comps.iter_mut().enumerate() {
                    comp[i + j * wx] = v[c];
                }
            }
        }
        ToeplitzKernel { nx, ny, comps }
    }

    /// The kernel of a block of `bx x by` elements of the same grid (the
    /// offsets within the block).
    pub fn block(&self, (bx, by): (usize, usize)) -> Self {
        assert!(bx <= self.nx && by <= self.ny, "a block within the grid");
        let (wx, wy) = (2 * bx - 1, 2 * by - 1);
        let comps = self
            .comps
            .iter()
            .enumerate()
            .map(|(c, _)| {
                (0..wx * wy)
                    .map(|t| self.at(c, (t % wx) as isize - (bx as isize - 1), (t / wx) as isize - (by as isize - 1)))
                    .collect()
            })
            .collect();
        ToeplitzKernel { nx: bx, ny: by, comps }
    }

    /// Grid columns and rows.
    pub fn shape(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// Number of components (1 normal, 3 tangential).
    pub fn components(&self) -> usize {
        self.comps.len()
    }

    /// Component `c` at offset `(dix, diy)`.
    pub fn at(&self, c: usize, dix: isize, diy: isize) -> f64 {
        self.comps[c][self.offset_index(dix, diy)]
    }

    /// Index of offset `(dix, diy)` in a component's table; offsets along x
    /// are contiguous.
    pub fn offset_index(&self, dix: isize, diy: isize) -> usize {
        (dix + self.nx as isize - 1) as usize + (diy + self.ny as isize - 1) as usize * (2 * self.nx - 1)
    }

    /// The table of component `c`.
    pub fn table(&self, c: usize) -> &[f64] {
        &self.comps[c]
    }

    /// Normal product by direct summation: `u_I = sum_J K(I - J) p_J` at
    /// every element (m), `p` on the grid (Pa).
    pub fn normal_direct(&self, p: &[f64], u: &mut [f64]) {
        let nx = self.nx as isize;
        for (k, uk) in u.iter_mut().enumerate() {
            let (ix, iy) = (k as isize % nx, k as isize / nx);
            let mut sum = 0.0;
            for (j, pj) in p.iter().enumerate() {
                if *pj != 0.0 {
                    sum += self.at(0, ix - j as isize % nx, iy - j as isize / nx) * pj;
                }
            }
            *uk = sum;
        }
    }

    /// Tangential product by direct summation (`p`, `u` with x and y
    /// components in separate slices).
    pub fn tangential_direct(&self, (px, py): (&[f64], &[f64]), (ux, uy): (&mut [f64], &mut [f64])) {
        let nx = self.nx as isize;
        for k in 0..ux.len() {
            let (ix, iy) = (k as isize % nx, k as isize / nx);
            let (mut sx, mut sy) = (0.0, 0.0);
            for j in 0..px.len() {
                if px[j] != 0.0 || py[j] != 0.0 {
                    let o = self.offset_index(ix - j as isize % nx, iy - j as isize / nx);
                    let (xx, xy, yy) = (self.comps[0][o], self.comps[1][o], self.comps[2][o]);
                    sx += xx * px[j] + xy * py[j];
                    sy += xy * px[j] + yy * py[j];
                }
            }
            ux[k] = sx;
            uy[k] = sy;
        }
    }
}
