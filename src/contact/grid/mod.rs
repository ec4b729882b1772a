//! The fixed-grid exact model: Kalker's discretisation of the transient
//! rolling contact problem as in CONTACT (Kalker, *Three-dimensional elastic
//! bodies in rolling contact*, 1990, ch. 5; Vollebregt, *User guide for
//! CONTACT*, 2022), in place of the paper's patch-adapted mesh.
//!
//! A uniform rectangular grid of `nx x ny` elements of `dx x dy` is fixed in
//! the contact frame and holds the largest patch of the passage
//! ([`PotentialGrid`]). At every step:
//!
//! 1. the normal problem is solved on the grid ([`normal`]): pressure >= 0,
//!    gap >= 0, complementarity, the normal force prescribed, for a gap
//!    function `h(x, y)` (the quadratic gap of the curvatures here); the
//!    elements in contact follow from it, so the patch grows and shrinks
//!    inside the grid as N varies;
//! 2. the tangential problem on the elements in contact ([`tangential`]):
//!    with the patch moving by exactly one element per step
//!    (`V dt = dx`), the material now at element `(ix, iy)` was at
//!    `(ix - 1, iy)` one step earlier, so the earlier displacement is the
//!    previous displacement field shifted by one column: no interpolation
//!    (Kalker 1990, sec. 5.2; CONTACT's transient rolling);
//! 3. the displacements `u = C p` everywhere on the grid, by zero-padded FFT
//!    ([`convolution`]): on a uniform grid the influence matrix is
//!    block-Toeplitz. A problem symmetric about y = 0 (no lateral creepage,
//!    no spin, a symmetric gap) is solved on the lower half of the grid, its
//!    products by transforms of symmetric fields ([`symmetric`]: about two
//!    thirds of the transform work), the CG solver's inner products on the
//!    block of the grid that holds the contact area.
//!
//! Element order: row by row (y increasing), each row from the leading edge
//! (x > 0, where rail material enters) to the trailing edge, as the adapted
//! mesh's strips.

pub mod cg;
pub mod convolution;
pub mod coupling;
pub mod kernel;
pub mod normal;
pub mod solver;
pub mod spec;
pub mod surface;
pub mod symmetric;
pub mod tangential;

pub use solver::FixedGrid;
pub use spec::{GridScheme, GridSolver};
pub use surface::RailSurface;

/// A uniform rectangular grid of elements in the contact frame.
///
/// Column `ix` spans `x_front - (ix + 1) dx .. x_front - ix dx` (leading edge
/// first), row `iy` spans `y_low + iy dy .. y_low + (iy + 1) dy`; element
/// `k = iy nx + ix`.
#[derive(Debug, Clone, PartialEq)]
pub struct PotentialGrid {
    /// Columns (along x).
    pub nx: usize,
    /// Rows (along y).
    pub ny: usize,
    /// Element length along x (m).
    pub dx: f64,
    /// Element width along y (m).
    pub dy: f64,
    /// x of the leading edge of the grid (m).
    pub x_front: f64,
    /// y of the lower edge of the grid (m).
    pub y_low: f64,
}

/// Where a grid must put an element edge: at `edge + k period` for some
/// integer k (a rail-cell boundary, so that the wear of an element falls on
/// whole rail cells); `period = 0` asks nothing.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Alignment {
    /// A coordinate (m) on which an element edge should fall, modulo `period`.
    pub edge: f64,
    /// The period of the allowed edge positions (m); 0 = no constraint.
    pub period: f64,
    /// With no constraint (`period = 0`): an even number of elements, an
    /// element edge on the centre (else the fewer elements of the two
    /// equally centred grids).
    pub even: bool,
}

impl Alignment {
    /// The shift in `[-period/2, period/2)` that moves `at` onto an allowed
    /// edge.
    fn shift(&self, at: f64) -> f64 {
        if self.period <= 0.0 {
            return 0.0;
        }
        let d = (self.edge - at).rem_euclid(self.period);
        if d >= 0.5 * self.period { d - self.period } else { d }
    }
}

/// Relative margin of the grid around the largest patch, besides whole
/// elements on every side: one along y, and along x as many as the columns
/// that supply the earlier displacements of the first columns in contact
/// (two, three for the third-order difference): the discrete contact area
/// of a quadratic gap lies within one element of the Hertz ellipse.
pub const GRID_MARGIN: f64 = 0.05;

impl PotentialGrid {
    /// The grid of `dx x dy` elements that holds the patch `|x| <= a`,
    /// `|y| <= b` with [`GRID_MARGIN`] and `lead` elements more along x, one
    /// along y, on every side, shifted by less than half a rail cell so that
    /// its element edges fall on `align_x` and `align_y`.
    pub fn covering(a: f64, b: f64, (dx, dy): (f64, f64), lead: usize, align_x: Alignment, align_y: Alignment) -> Self {
        let half_x = a * (1.0 + GRID_MARGIN) + lead as f64 * dx + 0.5 * align_x.period;
        let half_y = b * (1.0 + GRID_MARGIN) + dy + 0.5 * align_y.period;
        // Of two successive counts, the one whose centred grid needs the
        // smaller shift: a grid symmetric about the patch centre where the
        // rail grid allows it.
        let place = |half: f64, d: f64, align: Alignment, sign: f64| {
            let n = (2.0 * half / d).ceil() as usize;
            let n = if align.period <= 0.0 && align.even { n + n % 2 } else { n };
            [n, n + 1]
                .map(|n| {
                    let edge = sign * 0.5 * n as f64 * d;
                    (n, edge + align.shift(edge))
                })
                .into_iter()
                .min_by(|p, q| {
                    (p.1.abs() - 0.5 * p.0 as f64 * d).abs().total_cmp(&(q.1.abs() - 0.5 * q.0 as f64 * d).abs())
                })
                .expect("two candidates")
        };
        let (nx, x_front) = place(half_x, dx, align_x, 1.0);
        let (ny, y_low) = place(half_y, dy, align_y, -1.0);
        PotentialGrid { nx, ny, dx, dy, x_front, y_low }
    }

    /// Number of elements.
    pub fn len(&self) -> usize {
        self.nx * self.ny
    }

    /// Whether the grid has no elements.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Element area (m^2).
    pub fn area(&self) -> f64 {
        self.dx * self.dy
    }

    /// Centre x of column `ix` (m).
    pub fn x(&self, ix: usize) -> f64 {
        self.x_front - (ix as f64 + 0.5) * self.dx
    }

    /// Centre y of row `iy` (m).
    pub fn y(&self, iy: usize) -> f64 {
        self.y_low + (iy as f64 + 0.5) * self.dy
    }

    /// Element centres (x, y) in element order (m).
    pub fn centres(&self) -> (Vec<f64>, Vec<f64>) {
        let xs = (0..self.len()).map(|k| self.x(k % self.nx)).collect();
        let ys = (0..self.len()).map(|k| self.y(k / self.nx)).collect();
        (xs, ys)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn covering_grid_holds_the_patch_and_lines_up() {
        let (a, b, dx, dy) = (6.0e-3, 10.0e-3, 2e-4, 5e-4);
        let ax = Alignment { edge: 0.13e-4, period: 1e-4, even: false };
        let ay = Alignment { edge: -0.012 + 1.25e-4, period: 2.5e-4, even: false };
        let g = PotentialGrid::covering(a, b, (dx, dy), 2, ax, ay);
        // Every element edge falls on an allowed position.
        for k in 0..=g.nx {
            let e = g.x_front - k as f64 * dx;
            let r = ((e - ax.edge) / ax.period).round() * ax.period + ax.edge - e;
            assert!(r.abs() < 1e-12, "x edge {e}");
        }
        for k in 0..=g.ny {
            let e = g.y_low + k as f64 * dy;
            let r = ((e - ay.edge) / ay.period).round() * ay.period + ay.edge - e;
            assert!(r.abs() < 1e-12, "y edge {e}");
        }
        // The patch with its margin and one element lies inside.
        assert!(g.x_front >= a * (1.0 + GRID_MARGIN) + 2.0 * dx - 1e-12);
        assert!(g.x_front - g.nx as f64 * dx <= -(a * (1.0 + GRID_MARGIN) + 2.0 * dx) + 1e-12);
        assert!(g.y_low <= -(b * (1.0 + GRID_MARGIN) + dy) + 1e-12);
        assert!(g.y_low + g.ny as f64 * dy >= b * (1.0 + GRID_MARGIN) + dy - 1e-12);
        // No alignment asked: symmetric about the patch centre.
        let s = PotentialGrid::covering(a, b, (dx, dy), 2, Alignment::default(), Alignment::default());
        assert!((s.x(0) + s.x(s.nx - 1)).abs() < 1e-15 && (s.y(0) + s.y(s.ny - 1)).abs() < 1e-15);
    }

    #[test]
    fn grids_of_any_size_put_their_elements_at_the_same_places() {
        // A growth study's alignment (edges on a lattice of the element's
        // period along x, an even number of rows across): grids sized for 1
        // to 2 times the patch have their element centres on one lattice
        // along x and element edges on the centre line across.
        let (a, b, dx, dy) = (6.0e-3, 10.0e-3, 4e-4, 1e-3);
        let ax = Alignment { edge: 10.1e-3, period: dx, even: false };
        let ay = Alignment { even: true, ..Alignment::default() };
        let reference = PotentialGrid::covering(a, b, (dx, dy), 2, ax, ay);
        for scale in [1.0, 1.1, 1.2, 1.25, 1.5, 1.7, 2.0] {
            let g = PotentialGrid::covering(scale * a, scale * b, (dx, dy), 2, ax, ay);
            let offset = (g.x(0) - reference.x(0)) / dx;
            assert!((offset - offset.round()).abs() < 1e-9, "{scale}: x offset {offset} elements");
            assert_eq!(g.ny % 2, 0, "{scale}: {} rows", g.ny);
            assert!((g.y(0) + g.y(g.ny - 1)).abs() < 1e-15, "{scale}: symmetric across");
        }
    }
}
