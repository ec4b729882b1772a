//! The rail surface under the patch, for the normal problem on the fixed
//! grid (`contact.normal = "profile"`).
//!
//! The undeformed gap at the element centre `(x, y)` of the patch at
//! `X_c` is
//!
//! ```text
//! h(x, y) = A x^2 + B y^2 - r(X_c + x, y),
//! ```
//!
//! the quadratic gap of the curvature sums `A`, `B` (Hertz's gap; the
//! transverse profiles of wheel and rail) less the height `r` (m, positive
//! up: a crest closes the gap) of the rail's longitudinal profile. This is
//! Kalker's discrete normal problem with an arbitrary gap function
//! (Kalker 1990, sec. 5.2; CONTACT's `h(x, y)` input), and it makes the
//! contact non-Hertzian: pressure concentrates on crests, the patch shortens,
//! splits, and leaves troughs (Johnson, *Contact Mechanics*, 1985, sec. 13.2).
//!
//! `r` is interpolated bilinearly between the nodes of a rail lattice;
//! along the rail it is periodic (a growth study's stretch) or held at its
//! end values, across it held at the edge rows.

use crate::rail_grid::RailGrid;
use ndarray::Array2;

/// Heights of the rail surface on a lattice (m).
#[derive(Debug, Clone, PartialEq)]
pub struct RailSurface {
    /// First node along the rail (m).
    pub x0: f64,
    /// Node spacing along the rail (m).
    pub dx: f64,
    /// First node across the rail (m).
    pub y0: f64,
    /// Node spacing across the rail (m).
    pub dy: f64,
    /// Heights (m, positive up), shape (ny, nx).
    pub heights: Array2<f64>,
    /// Whether the lattice is one period along the rail (period `nx dx`).
    pub periodic: bool,
}

impl RailSurface {
    /// The corrugation of a growth study's profile on its periodic grid:
    /// each row less its mean along the rail. The mean transverse shape of
    /// the worn band is not part of the longitudinal profile: the
    /// transverse profiles are the fixed curvatures of the gap (the model
    /// follows corrugation, not the co-wear of wheel and rail profiles).
    pub fn corrugation(profile: &Array2<f64>, grid: &RailGrid) -> Self {
        let mut heights = profile.clone();
        for mut row in heights.rows_mut() {
            let mean = row.sum() / row.len().max(1) as f64;
            row.mapv_inplace(|v| v - mean);
        }
        RailSurface { x0: grid.x_min, dx: grid.dx, y0: grid.y(0), dy: grid.dy, heights, periodic: true }
    }

    /// [`RailSurface::corrugation`] without the harmonics shorter than
    /// `min_wavelength` (m) along the rail (each row's discrete Fourier
    /// series cut there): what a contact model that resolves the surface
    /// on a coarser mesh than the rail grid's may see of it.
    pub fn corrugation_above(profile: &Array2<f64>, grid: &RailGrid, min_wavelength: f64) -> Self {
        use num_complex::Complex64;
        use rustfft::FftPlanner;
        let mut surface = Self::corrugation(profile, grid);
        let n = grid.nx;
        let kmax = (n as f64 * grid.dx / min_wavelength).floor() as usize;
        if kmax >= n / 2 {
            return surface;
        }
        let mut planner = FftPlanner::new();
        let (fwd, inv) = (planner.plan_fft_forward(n), planner.plan_fft_inverse(n));
        for mut row in surface.heights.rows_mut() {
            let mut buf: Vec<Complex64> = row.iter().map(|v| Complex64::new(*v, 0.0)).collect();
            fwd.process(&mut buf);
            for (k, v) in buf.iter_mut().enumerate() {
                if k.min(n - k) > kmax {
                    *v = Complex64::default();
                }
            }
            inv.process(&mut buf);
            row.iter_mut().zip(&buf).for_each(|(r, v)| *r = v.re / n as f64);
        }
        surface
    }

    /// A profile uniform across the rail: `line[i]` at `x0 + i dx`.
    pub fn line(x0: f64, dx: f64, line: &[f64], periodic: bool) -> Self {
        let heights = Array2::from_shape_fn((1, line.len()), |(_, i)| line[i]);
        RailSurface { x0, dx, y0: 0.0, dy: 1.0, heights, periodic }
    }

    /// Height (m) at rail coordinates `(x, y)`, bilinear.
    pub fn height(&self, x: f64, y: f64) -> f64 {
        let nx = self.heights.ncols();
        self.blend(self.along(x, nx), self.across(y))
    }

    /// The heights (m) at every `(xs[i], ys[j])`, `j` outer: the values of
    /// [`RailSurface::height`] (the same operations), each column's and
    /// row's nodes and weights found once (the fixed grid's gap at every
    /// step).
    pub fn heights_on(&self, xs: &[f64], ys: &[f64]) -> Vec<f64> {
        let nx = self.heights.ncols();
        let columns: Vec<_> = xs.iter().map(|&x| self.along(x, nx)).collect();
        ys.iter()
            .flat_map(|&y| {
                let row = self.across(y);
                columns.iter().map(move |&column| self.blend(column, row))
            })
            .collect()
    }

    /// The bilinear blend of the nodes `(i0, i1, wx)` along and `(j0, j1,
    /// wy)` across the rail.
    fn blend(&self, (i0, i1, wx): (usize, usize, f64), (j0, j1, wy): (usize, usize, f64)) -> f64 {
        let h = &self.heights;
        let row = |j: usize| (1.0 - wx) * h[[j, i0]] + wx * h[[j, i1]];
        (1.0 - wy) * row(j0) + wy * row(j1)
    }

    /// Nodes and weight of `y` across the rail (held at the edge rows).
    fn across(&self, y: f64) -> (usize, usize, f64) {
        let ny = self.heights.nrows();
        let v = (y - self.y0) / self.dy;
        if ny == 1 || v <= 0.0 {
            (0, 0, 0.0)
        } else if v >= (ny - 1) as f64 {
            (ny - 1, ny - 1, 0.0)
        } else {
            let j = (v.floor() as usize).min(ny - 2);
            (j, j + 1, v - j as f64)
        }
    }

    /// Nodes and weight of `x` along the rail.
    fn along(&self, x: f64, nx: usize) -> (usize, usize, f64) {
        let u = (x - self.x0) / self.dx;
        if self.periodic {
            let u = u.rem_euclid(nx as f64);
            let i = (u.floor() as usize).min(nx - 1);
            (i, (i + 1) % nx, u - i as f64)
        } else if nx == 1 || u <= 0.0 {
            (0, 0, 0.0)
        } else if u >= (nx - 1) as f64 {
            (nx - 1, nx - 1, 0.0)
        } else {
            let i = (u.floor() as usize).min(nx - 2);
            (i, i + 1, u - i as f64)
        }
    }

    /// The largest curvature `d^2 r / dX^2` (1/m) of the profile along the
    /// rail (second differences over all rows): a trough's, which lengthens
    /// the patch over it.
    pub fn max_curvature(&self) -> f64 {
        self.curvature_range().1
    }

    /// The smallest and the largest curvature `d^2 r / dX^2` (1/m) of the
    /// profile along the rail (second differences over all rows; 0 for a
    /// flat one): a crest's and a trough's.
    pub fn curvature_range(&self) -> (f64, f64) {
        let (ny, nx) = self.heights.dim();
        if nx < 3 {
            return (0.0, 0.0);
        }
        let h = &self.heights;
        let (mut min, mut max) = (0.0f64, 0.0f64);
        for j in 0..ny {
            let range = if self.periodic { 0..nx } else { 1..nx - 1 };
            for i in range {
                let (l, r) = ((i + nx - 1) % nx, (i + 1) % nx);
                let c = (h[[j, l]] - 2.0 * h[[j, i]] + h[[j, r]]) / (self.dx * self.dx);
                (min, max) = (min.min(c), max.max(c));
            }
        }
        (min, max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bilinear_periodic_and_clamped() {
        let s = RailSurface::line(1.0, 0.5, &[0.0, 1.0, 4.0, 2.0], true);
        assert_eq!(s.height(1.0, 0.3), 0.0);
        assert!((s.height(1.25, 0.0) - 0.5).abs() < 1e-15);
        // One period on, and the wrap from the last node to the first.
        assert!((s.height(3.25, 0.0) - 0.5).abs() < 1e-15);
        assert!((s.height(2.75, 0.0) - 1.0).abs() < 1e-15);
        let c = RailSurface { periodic: false, ..s.clone() };
        assert_eq!(c.height(0.0, 0.0), 0.0);
        assert_eq!(c.height(9.0, 0.0), 2.0);
        let grid = RailGrid { x_min: 0.0, dx: 1.0, nx: 4, half_width: 1.0, dy: 1.0, ny: 3 };
        let p = Array2::from_shape_fn((3, 4), |(j, i)| (j * 10 + i) as f64);
        let r = RailSurface::corrugation(&p, &grid);
        // Row means removed: 1.5 along each row.
        assert!((r.height(0.0, -1.0) + 1.5).abs() < 1e-15);
        assert!((r.height(0.5, 0.5) - (-1.0)).abs() < 1e-15);
        // Cut above 2 dx: a line of two harmonics keeps the long one.
        let n = 64;
        let two = Array2::from_shape_fn((1, n), |(_, i)| {
            let x = i as f64 / n as f64 * 2.0 * std::f64::consts::PI;
            x.cos() + 0.5 * (16.0 * x).cos()
        });
        let g = RailGrid { x_min: 0.0, dx: 1.0 / n as f64, nx: n, half_width: 0.0, dy: 1.0, ny: 1 };
        let cut = RailSurface::corrugation_above(&two, &g, 0.1);
        for i in 0..n {
            let x = i as f64 / n as f64 * 2.0 * std::f64::consts::PI;
            assert!((cut.heights[[0, i]] - x.cos()).abs() < 1e-12);
        }
        // The lattice of heights: each value the point's, bit for bit.
        let (xs, ys) = ([-0.3, 0.0, 0.7, 2.2, 9.1], [-1.5, -0.2, 0.5, 3.0]);
        for surface in [r.clone(), RailSurface { periodic: false, ..r.clone() }] {
            let on = surface.heights_on(&xs, &ys);
            for (j, y) in ys.iter().enumerate() {
                for (i, x) in xs.iter().enumerate() {
                    let point = surface.height(*x, *y);
                    assert_eq!(on[j * xs.len() + i].to_bits(), point.to_bits(), "({x}, {y})");
                }
            }
        }
        // A trough of curvature 2 (r = x^2 near it).
        let t = RailSurface::line(0.0, 0.1, &[0.01, 0.0, 0.01, 0.04], false);
        assert!((t.max_curvature() - 2.0).abs() < 1e-12);
        // A crest of curvature -2 and a straight run: the range (-2, 0).
        let (lo, hi) = RailSurface::line(0.0, 0.1, &[0.0, 0.01, 0.0, -0.01], false).curvature_range();
        assert!((lo + 2.0).abs() < 1e-12 && hi.abs() < 1e-12, "{lo} {hi}");
    }
}
