//! Long-term corrugation growth on a periodic stretch of rail (DESIGN.md
//! section 3): the outer loop over wheel passages
//!
//! ```text
//! r_n(X, Y) -> N_n(X) = imposed + dynamic(r_n) -> passage -> W_n(X, Y)
//!           -> r_{n+1} = r_n - m W_n
//! ```
//!
//! One simulated passage stands for `m` real ones (traffic scaling). The
//! stretch `[x_min, x_min + L)` is periodic: the patch starts a run-in before
//! it, in the contact state the previous lap would have left, and the wear of
//! the patch positions inside the stretch is folded onto the periodic grid,
//! so every node receives exactly one full passage of the patch.

pub mod roughness;
pub mod spectrum;
pub mod traffic;

use crate::contact::TangentialSolver;
use crate::dynamics::TrackDynamics;
use crate::hertz::HertzShape;
use crate::metrics::centre_row;
use crate::passage::{PassageError, PassageResult, PassageSpec, PeriodicSignal, run_passage};
use crate::wear::{RailGrid, WearKernel};
use ndarray::Array2;

/// Wear on an extended grid (same node lattice) folded onto the periodic
/// grid `grid` (node x_min + i dx, i = 0..nx, period nx dx).
pub fn fold_periodic(ext: &Array2<f64>, ext_grid: &RailGrid, grid: &RailGrid) -> Array2<f64> {
    let mut out = Array2::zeros((grid.ny, grid.nx));
    let n = grid.nx as i64;
    for i in 0..ext_grid.nx {
        let k = ((ext_grid.x(i) - grid.x_min) / grid.dx).round() as i64;
        let col = k.rem_euclid(n) as usize;
        for j in 0..grid.ny {
            out[[j, col]] += ext[[j, i]];
        }
    }
    out
}

/// The centre-line profile seen by the wheel: the profile averaged across
/// the patch width with the Hertz line-load weight: the pressure integrated
/// along x, `int p dx = (pi/2) a p0 (1 - (y/b)^2)`, so the weight is
/// `1 - (y/b)^2` (the profile as the pressure-weighted patch sees it across
/// the rail).
pub fn contact_filtered_line(profile: &Array2<f64>, grid: &RailGrid, b: f64) -> Vec<f64> {
    let weights: Vec<(usize, f64)> =
        (0..grid.ny).map(|j| (j, (1.0 - (grid.y(j) / b).powi(2)).max(0.0))).filter(|(_, w)| *w > 0.0).collect();
    if weights.is_empty() {
        return profile.row(centre_row(grid)).to_vec();
    }
    let total: f64 = weights.iter().map(|(_, w)| w).sum();
    (0..grid.nx).map(|i| weights.iter().map(|(j, w)| w * profile[[*j, i]]).sum::<f64>() / total).collect()
}

/// What one growth passage produced.
#[derive(Debug, Clone)]
pub struct GrowthPass {
    /// The passage on the extended grid (history, unfolded wear).
    pub passage: PassageResult,
    /// Wear of one simulated passage on the periodic grid (m).
    pub wear: Array2<f64>,
    /// Dynamic normal force on the periodic grid (N).
    pub dynamic_force: Vec<f64>,
}

/// Runs one passage over the periodic stretch with the current `profile`:
/// the dynamic force of the contact-filtered profile (if `dynamics`) adds to
/// the imposed loads; wear is deposited for patch positions inside the
/// stretch and folded onto `grid`.
#[allow(clippy::too_many_arguments)]
pub fn growth_passage(
    spec: &PassageSpec,
    shape: &HertzShape,
    solver: &mut dyn TangentialSolver,
    deposit: &dyn WearKernel,
    grid: &RailGrid,
    profile: &Array2<f64>,
    dynamics: Option<&dyn TrackDynamics>,
    record_fields: bool,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<GrowthPass, PassageError> {
    let length = grid.nx as f64 * grid.dx;
    let b_mean = shape.patch(spec.loads.normal_force).map(|p| p.b).unwrap_or(grid.half_width);
    let dynamic_force = match dynamics {
        Some(d) => d.force_from_profile(&contact_filtered_line(profile, grid, b_mean), grid.dx, spec.speed),
        None => vec![0.0; grid.nx],
    };
    let mut spec = spec.clone();
    spec.wear_window = (grid.x_min, grid.x_min + length);
    spec.dynamic_normal_force = Some(PeriodicSignal { x0: grid.x_min, dx: grid.dx, values: dynamic_force.clone() });
    // Extended grid on the same lattice, wide enough for the largest patch
    // of this passage (imposed plus dynamic normal force), so no wear is
    // clipped at its ends.
    let peak_force = spec.loads.max_normal_force() + dynamic_force.iter().fold(0.0f64, |m, f| m.max(f.abs()));
    let a_max = shape.patch(peak_force).map(|p| p.a).unwrap_or(0.0);
    let reach = (a_max / grid.dx).ceil() as usize + 2;
    let ext = RailGrid { x_min: grid.x_min - reach as f64 * grid.dx, nx: grid.nx + 2 * reach, ..grid.clone() };
    let passage = run_passage(&spec, shape, solver, deposit, &ext, record_fields, progress)?;
    let wear = fold_periodic(&passage.wear, &ext, grid);
    Ok(GrowthPass { passage, wear, dynamic_force })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn filtered_line_is_the_line_load_weighted_mean_across_the_patch() {
        // Uniform across the head: the line itself. A profile (y/b)^2: the
        // mean of u^2 under the weight 1 - u^2 is (2/3 - 2/5) / (4/3) = 1/5.
        let grid = RailGrid { x_min: 0.0, dx: 1e-3, nx: 3, half_width: 0.012, dy: 1e-5, ny: 2401 };
        let b = 0.01;
        let flat = Array2::from_shape_fn((grid.ny, grid.nx), |(_, i)| i as f64);
        assert!(contact_filtered_line(&flat, &grid, b).iter().enumerate().all(|(i, v)| (v - i as f64).abs() < 1e-12));
        let bowl = Array2::from_shape_fn((grid.ny, grid.nx), |(j, _)| (grid.y(j) / b).powi(2));
        let line = contact_filtered_line(&bowl, &grid, b);
        assert!((line[0] - 0.2).abs() < 1e-6, "{}", line[0]);
    }
}
