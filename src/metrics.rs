//! Corrugation measures of a rail profile.

use crate::rail_grid::RailGrid;
use ndarray::ArrayView2;

/// Index of the grid row closest to the rail centre line y = 0.
pub fn centre_row(grid: &RailGrid) -> usize {
    ((grid.half_width / grid.dy).round() as usize).min(grid.ny - 1)
}

/// rms of the centre-line profile minus its mean (m); `profile` has shape
/// (ny, nx).
pub fn rms_corrugation(profile: ArrayView2<f64>, grid: &RailGrid) -> f64 {
    let line = profile.row(centre_row(grid));
    let mean = line.mean().unwrap_or(0.0);
    (line.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / line.len() as f64).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use ndarray::Array2;

    #[test]
    fn sine_has_rms_amplitude_over_sqrt2() {
        let grid = RailGrid::new(0.0, 0.03, 1e-4, 0.01, 1e-3);
        let mut p = Array2::zeros((grid.ny, grid.nx));
        for i in 0..grid.nx - 1 {
            p[[centre_row(&grid), i]] = 1e-6 * (2.0 * std::f64::consts::PI * grid.x(i) / 0.03).sin() - 3e-6;
        }
        // The last node closes the period; drop it from the mean.
        let line = p.slice(ndarray::s![.., ..grid.nx - 1]).to_owned();
        let g2 = RailGrid { nx: grid.nx - 1, ..grid.clone() };
        assert!((rms_corrugation(line.view(), &g2) - 1e-6 / 2f64.sqrt()).abs() < 1e-12);
    }
}
