//! How a traction change on one element reaches the displacements of the
//! elements in contact during a Gauss-Seidel sweep: the Toeplitz kernel on
//! the whole contact area, or its folded form on half of a problem that is
//! symmetric about the centre line y = 0.
//!
//! **Folding.** With the grid, the gap and the loads symmetric about y = 0
//! (no lateral creepage, no spin), the solution is too: `p_x(x, -y) =
//! p_x(x, y)`, `p_y(x, -y) = -p_y(x, y)`. Only the elements of the lower
//! half (rows `iy <= (ny - 1)/2`) are unknowns; element J stands for itself
//! and its mirror J' = (ix, ny - 1 - iy) with traction `M p_J`, `M =
//! diag(1, -1)`, so the influence on I is `F(I, J) = K(I - J) + K(I - J') M`
//! (just `K(I - J)` on the middle row of an odd grid, its own mirror):
//!
//! ```text
//! F_xx = K_xx(d) + K_xx(d'),   F_x<-y = K_xy(d) - K_xy(d'),
//! F_y<-x = K_xy(d) + K_xy(d'), F_yy = K_yy(d) - K_yy(d'),
//! ```
//!
//! `d`, `d'` the offsets of I from J and from J'. Toeplitz in x only, so the
//! table holds one row of `2 nx - 1` offsets per pair of half rows. A sweep
//! then solves half the elements against half the displacements: a quarter
//! of the work of the whole area, for the same solution.

use super::convolution::ToeplitzKernel;

/// The four coupling rows `(F_xx, F_x<-y, F_y<-x, F_yy)` between two grid
/// rows, each over the x-offsets `-(nx - 1) ..= nx - 1`.
pub type Rows<'a> = [&'a [f64]; 4];

/// The influence table of a sweep.
#[derive(Debug, Clone, Copy)]
pub enum Coupling<'a> {
    /// The whole contact area.
    Full(&'a ToeplitzKernel),
    /// The lower half of a problem symmetric about y = 0.
    Folded(&'a FoldedKernel),
}

impl Coupling<'_> {
    /// Grid columns.
    pub fn nx(&self) -> usize {
        match self {
            Coupling::Full(k) => k.shape().0,
            Coupling::Folded(f) => f.nx,
        }
    }

    /// Coupling rows from (source) row `iy_j` to (receiving) row `iy_i`; the
    /// entry for x-offset `dix = ix_i - ix_j` is at `dix + nx - 1`.
    pub fn rows(&self, iy_i: usize, iy_j: usize) -> Rows<'_> {
        match self {
            Coupling::Full(k) => {
                let nx = k.shape().0;
                let start = k.offset_index(-(nx as isize - 1), iy_i as isize - iy_j as isize);
                let row = |c: usize| &k.table(c)[start..start + 2 * nx - 1];
                [row(0), row(1), row(1), row(2)]
            }
            Coupling::Folded(f) => f.rows(iy_i, iy_j),
        }
    }

    /// An element's own 2 x 2 flexibility `(xx, xy, yy)` in row `iy` (m/Pa):
    /// symmetric (the x-y coupling of an element on itself, and on its
    /// mirror at the same x, vanishes).
    pub fn own(&self, iy: usize) -> [f64; 3] {
        let nx = self.nx();
        let r = self.rows(iy, iy);
        [r[0][nx - 1], r[1][nx - 1], r[3][nx - 1]]
    }
}

/// The folded coupling table of a symmetric grid.
#[derive(Debug, Clone)]
pub struct FoldedKernel {
    nx: usize,
    /// Rows of the lower half, the middle row of an odd grid included.
    half: usize,
    /// `[iy_i][iy_j][component][dix + nx - 1]`.
    table: Vec<f64>,
}

impl FoldedKernel {
    /// Folds the tangential kernel of a grid of `ny` rows symmetric about
    /// y = 0.
    pub fn new(kernel: &ToeplitzKernel) -> Self {
        let (nx, ny) = kernel.shape();
        let half = ny.div_ceil(2);
        let w = 2 * nx - 1;
        let mut table = vec![0.0; half * half * 4 * w];
        for iy_i in 0..half {
            for iy_j in 0..half {
                let mirror = ny - 1 - iy_j;
                let base = ((iy_i * half + iy_j) * 4) * w;
                for t in 0..w {
                    let dix = t as isize - (nx as isize - 1);
                    let d = kernel.offset_index(dix, iy_i as isize - iy_j as isize);
                    let (xx, xy, yy) = (kernel.table(0)[d], kernel.table(1)[d], kernel.table(2)[d]);
                    let (mxx, mxy, myy) = if mirror == iy_j {
                        (0.0, 0.0, 0.0)
                    } else {
                        let m = kernel.offset_index(dix, iy_i as isize - mirror as isize);
                        (kernel.table(0)[m], kernel.table(1)[m], kernel.table(2)[m])
                    };
                    table[base + t] = xx + mxx;
                    table[base + w + t] = xy - mxy;
                    table[base + 2 * w + t] = xy + mxy;
                    table[base + 3 * w + t] = yy - myy;
                }
            }
        }
        FoldedKernel { nx, half, table }
    }

    /// Rows of the lower half (the unknowns).
    pub fn half_rows(&self) -> usize {
        self.half
    }

    fn rows(&self, iy_i: usize, iy_j: usize) -> Rows<'_> {
        let w = 2 * self.nx - 1;
        let base = ((iy_i * self.half + iy_j) * 4) * w;
        let row = |c: usize| &self.table[base + c * w..base + (c + 1) * w];
        [row(0), row(1), row(2), row(3)]
    }
}

#[cfg(test)]
mod tests {
    use super::super::PotentialGrid;
    use super::*;

    #[test]
    fn folded_coupling_equals_the_sum_over_an_element_and_its_mirror() {
        for ny in [6, 7] {
            let grid = PotentialGrid { nx: 5, ny, dx: 2e-4, dy: 5e-4, x_front: 5e-4, y_low: -0.5 * ny as f64 * 5e-4 };
            let k = ToeplitzKernel::tangential(&grid, 8e10, 0.3);
            let f = FoldedKernel::new(&k);
            let (full, folded) = (Coupling::Full(&k), Coupling::Folded(&f));
            let (px, py) = (1.3e8, -0.7e8);
            for iy_j in 0..f.half_rows() {
                for iy_i in 0..f.half_rows() {
                    let m = ny - 1 - iy_j;
                    let direct = full.rows(iy_i, iy_j);
                    let mirror = full.rows(iy_i, m);
                    let fold = folded.rows(iy_i, iy_j);
                    for t in 0..2 * grid.nx - 1 {
                        // u at I from p at J and M p at J' (once on the middle row).
                        let (mx, my) = if m == iy_j { (0.0, 0.0) } else { (px, -py) };
                        let ux = direct[0][t] * px + direct[1][t] * py + mirror[0][t] * mx + mirror[1][t] * my;
                        let uy = direct[2][t] * px + direct[3][t] * py + mirror[2][t] * mx + mirror[3][t] * my;
                        let fx = fold[0][t] * px + fold[1][t] * py;
                        let fy = fold[2][t] * px + fold[3][t] * py;
                        let scale = ux.abs().max(uy.abs()).max(1e-30);
                        assert!((ux - fx).abs() <= 1e-12 * scale && (uy - fy).abs() <= 1e-12 * scale);
                    }
                }
            }
            // Own flexibility: diagonal.
            for iy in 0..f.half_rows() {
                assert!(folded.own(iy)[1].abs() < 1e-12 * folded.own(iy)[0]);
            }
        }
    }
}
