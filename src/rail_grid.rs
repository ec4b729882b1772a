//! The regular grid of nodes on the rail running surface where wear depth is
//! accumulated (Baeza et al. 2008, Fig. 5), the profile evolves and the
//! contact reads the rail: shared by contact, wear, growth and output.

/// Rail-surface grid: nodes `x_i = x_min + i dx`, `y_j = -half_width + j dy`.
#[derive(Debug, Clone, PartialEq)]
pub struct RailGrid {
    /// First node along the rail (m).
    pub x_min: f64,
    /// Node spacing along the rail (m).
    pub dx: f64,
    /// Number of nodes along the rail.
    pub nx: usize,
    /// Lateral half-width of the grid (m); nodes from -half_width.
    pub half_width: f64,
    /// Node spacing across the rail (m).
    pub dy: f64,
    /// Number of nodes across the rail.
    pub ny: usize,
}

impl RailGrid {
    /// Grid covering `[x_min, x_max]` and `[-half_width, half_width]` with
    /// spacings close to `dx`, `dy` (adjusted so that both ends are nodes).
    pub fn new(x_min: f64, x_max: f64, dx: f64, half_width: f64, dy: f64) -> Self {
        let nx = ((x_max - x_min) / dx).round().max(1.0) as usize + 1;
        let ny = (2.0 * half_width / dy).round().max(1.0) as usize + 1;
        RailGrid {
            x_min,
            dx: (x_max - x_min) / (nx - 1) as f64,
            nx,
            half_width,
            dy: 2.0 * half_width / (ny - 1) as f64,
            ny,
        }
    }

    /// Node coordinate along the rail (m).
    pub fn x(&self, i: usize) -> f64 {
        self.x_min + i as f64 * self.dx
    }

    /// Node coordinate across the rail (m).
    pub fn y(&self, j: usize) -> f64 {
        -self.half_width + j as f64 * self.dy
    }

    /// All x coordinates (m).
    pub fn xs(&self) -> Vec<f64> {
        (0..self.nx).map(|i| self.x(i)).collect()
    }

    /// All y coordinates (m).
    pub fn ys(&self) -> Vec<f64> {
        (0..self.ny).map(|j| self.y(j)).collect()
    }

    /// Index range of nodes along x within `[lo, hi]` (m), clipped to the grid.
    pub fn x_range(&self, lo: f64, hi: f64) -> std::ops::Range<usize> {
        index_range(self.x_min, self.dx, self.nx, lo, hi)
    }

    /// Index range of nodes across y within `[lo, hi]` (m), clipped to the grid.
    pub fn y_range(&self, lo: f64, hi: f64) -> std::ops::Range<usize> {
        index_range(-self.half_width, self.dy, self.ny, lo, hi)
    }
}

fn index_range(origin: f64, step: f64, n: usize, lo: f64, hi: f64) -> std::ops::Range<usize> {
    // A relative slack keeps nodes that sit on the bounds up to round-off.
    let first = ((lo - origin) / step - 1e-9).ceil().max(0.0);
    let last = ((hi - origin) / step + 1e-9).floor();
    if last < 0.0 || first > last || first >= n as f64 {
        return 0..0;
    }
    first as usize..(last as usize + 1).min(n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_are_clipped_and_inclusive() {
        let g = RailGrid::new(0.0, 0.01, 0.001, 0.005, 0.001);
        assert_eq!((g.nx, g.ny), (11, 11));
        assert_eq!(g.x_range(0.0025, 0.0051), 3..6);
        assert_eq!(g.x_range(-1.0, 0.0), 0..1);
        assert_eq!(g.x_range(0.02, 0.03), 0..0);
        assert_eq!(g.y_range(-0.001, 0.001), 4..7);
    }
}
