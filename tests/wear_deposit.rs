//! The wear kernel: analytic depth of a uniform rate, volume conservation,
//! and convergence of the interpolated sub-steps (issue "Must show: Wear").
use crate::common;
use common::{STEEL, paper_coefficients, paper_shape, rel};
use corrugation::contact::fastsim::Fastsim;
use corrugation::contact::{EllipseMesh, PressureShape, StepInput};
use corrugation::rail_grid::RailGrid;
use corrugation::wear::{PatchWear, WearDeposit, archard_rates};
use ndarray::Array2;

const V: f64 = 27.78;

/// Rolls a patch of constant semi-axes and rates over the grid from `x0` to
/// `x1` in steps of `h`.
#[allow(clippy::too_many_arguments)]
fn roll(
    dep: &WearDeposit,
    grid: &RailGrid,
    a: f64,
    b: f64,
    rates: &[f64],
    x0: f64,
    x1: f64,
    h: f64,
    substeps: usize,
) -> Array2<f64> {
    let mut w = Array2::zeros((grid.ny, grid.nx));
    let n = ((x1 - x0) / h).round() as usize;
    for k in 0..n {
        let from = PatchWear { x_c: x0 + k as f64 * h, a, b, rates };
        let to = PatchWear { x_c: x0 + (k + 1) as f64 * h, a, b, rates };
        dep.accumulate(grid, &mut w, &from, &to, h / V, substeps);
    }
    w
}

#[test]
fn uniform_rate_gives_chord_over_speed() {
    // W(Y) = rate * 2 a sqrt(1 - (Y/b)^2) / V for every node the patch passes
    // over entirely, within 1 % for |Y| <= 0.4 b on a 100 x 100 mesh. The
    // zero-rate boundary points make the interpolated field ramp down over the
    // last half element: a deficit of about 1/(2 nx) on the centre line that
    // grows towards the lateral edges and vanishes under refinement.
    let (a, b, rate) = (6e-3, 10e-3, 1e-9);
    let grid = RailGrid::new(0.0, 0.01, 1e-4, 0.012, 5e-4);
    let centre = grid.ny / 2;
    let mut centre_errors = Vec::new();
    for n in [20, 40, 100] {
        let mesh = EllipseMesh::new(n, n);
        let dep = WearDeposit::new(&mesh);
        let rates = vec![rate; mesh.len()];
        let w = roll(&dep, &grid, a, b, &rates, -0.007, 0.017, 2e-4, 8);
        let exact = |y: f64| rate * 2.0 * a * (1.0 - (y / b).powi(2)).sqrt() / V;
        let mean_centre = w.row(centre).mean().unwrap();
        centre_errors.push(rel(mean_centre, exact(0.0)));
        assert!(w.row(0).iter().all(|v| *v == 0.0), "no wear outside the patch");
        if n == 100 {
            for j in 0..grid.ny {
                if grid.y(j).abs() <= 0.4 * b {
                    for i in 0..grid.nx {
                        let e = exact(grid.y(j));
                        assert!(rel(w[[j, i]], e) < 0.01, "node ({i},{j}): {} vs {e}", w[[j, i]]);
                    }
                }
            }
        }
    }
    // First-order convergence of the centre-line deficit: 1/(2 nx) (the
    // last half element's ramp), within 5 % (measured 1.023, 1.012, 0.976
    // times it), and an observed order of 1 within 0.1 between meshes.
    for (err, n) in centre_errors.iter().zip([20.0, 40.0, 100.0]) {
        assert!((err * 2.0 * n - 1.0).abs() < 0.05, "centre-line deficit {err} at n = {n}");
    }
    for (pair, ratio) in centre_errors.windows(2).zip([2.0f64, 2.5]) {
        let order = (pair[0] / pair[1]).ln() / ratio.ln();
        assert!((order - 1.0).abs() < 0.1, "observed order {order}");
    }
}

fn fastsim_rates(n: usize) -> (EllipseMesh, Vec<f64>, f64, f64) {
    let patch = paper_shape(true).patch(1e5).unwrap();
    let f = Fastsim::new(n, n, PressureShape::Parabolic, paper_coefficients(true), STEEL.shear_modulus());
    let input = StepInput {
        patch,
        speed: V,
        dt: 0.0,
        friction: 0.4,
        characteristic: Default::default(),
        memory: None,
        force_x: 2e4,
        creepage_x: None,
        creepage_y: 0.0,
        spin: 0.0,
        position: 0.0,
    };
    let sol = f.solve_force(&input).unwrap();
    (EllipseMesh::new(n, n), archard_rates(3.4e-14, &sol), patch.a, patch.b)
}

#[test]
fn removed_volume_equals_time_integral_of_patch_wear_rate() {
    // sum_nodes W dx dy = int dt int_patch rate dA (the interpolated field the
    // kernel deposits), within 1 %, for the steady FASTSIM field of the
    // paper's patch at F_x = 20 kN.
    for n in [20, 40] {
        let (mesh, rates, a, b) = fastsim_rates(n);
        let dep = WearDeposit::new(&mesh);
        let grid = RailGrid::new(-0.03, 0.03, 5e-5, 0.012, 1e-4);
        let (x0, x1, h) = (-0.01, 0.01, 2e-4);
        let w = roll(&dep, &grid, a, b, &rates, x0, x1, h, 4);
        let removed = w.sum() * grid.dx * grid.dy;
        let expected = dep.integral(&rates, a, b) * (x1 - x0) / V;
        assert!(rel(removed, expected) < 0.01, "{n}x{n}: {removed:e} vs {expected:e}");
    }
}

#[test]
fn interpolated_field_converges_to_element_sum() {
    // The zero-boundary interpolation and the element midpoint sum are two
    // discretisations of the same patch integral: they agree better and
    // better under refinement (parabolic-bound FASTSIM field).
    let ratio = |n: usize| {
        let (mesh, rates, a, b) = fastsim_rates(n);
        WearDeposit::new(&mesh).integral(&rates, a, b) / mesh.integrate(&rates, a, b)
    };
    let (r20, r40, r80) = (ratio(20), ratio(40), ratio(80));
    assert!((1.0 - r20) > (1.0 - r40) && (1.0 - r40) > (1.0 - r80), "{r20} {r40} {r80}");
    assert!((1.0 - r80).abs() < 0.005, "80 x 80: {r80}");
}

#[test]
fn substeps_converge() {
    // A patch whose size and rates change between two solutions: the depth
    // converges as the sub-steps are refined (first order: the entry and exit
    // of a node are resolved to one sub-step).
    let (mesh, rates, a, b) = fastsim_rates(20);
    let dep = WearDeposit::new(&mesh);
    let grid = RailGrid::new(-0.004, 0.004, 1e-4, 0.012, 2.5e-4);
    let doubled: Vec<f64> = rates.iter().map(|r| 2.0 * r).collect();
    let depth = |m: usize| {
        let mut w = Array2::zeros((grid.ny, grid.nx));
        let from = PatchWear { x_c: -0.0005, a, b, rates: &rates };
        let to = PatchWear { x_c: 0.0005, a: 1.2 * a, b: 1.2 * b, rates: &doubled };
        dep.accumulate(&grid, &mut w, &from, &to, 1e-3 / V, m);
        w
    };
    let reference = depth(1024);
    let scale = reference.iter().cloned().fold(0.0, f64::max);
    let err =
        |m: usize| (&depth(m) - &reference).iter().map(|v| v.abs()).sum::<f64>() / (scale * reference.len() as f64);
    let errs: Vec<f64> = [2, 4, 8, 16, 32].iter().map(|m| err(*m)).collect();
    for w in errs.windows(2) {
        assert!(w[1] < 0.75 * w[0], "sub-step errors must decrease: {errs:?}");
    }
    assert!(errs[4] < 0.1 * errs[0], "{errs:?}");
}

#[test]
fn a_growth_passage_on_the_fixed_grid_wears_nothing_shorter_than_two_elements() {
    // growth_exact.toml's chain (0.4 mm elements, one per step, on the
    // 0.2 mm rail grid) over a 60 mm stretch, one passage of 1e5 wheel
    // passages from 1 um of 10-60 mm roughness: the rail's harmonics
    // shorter than two elements (0.8 mm), where the cells' hold of the
    // elements' wear put its images (a 0.417 mm ripple on 120 mm), hold
    // round-off only; the wear itself reaches the profile (its 10-60 mm
    // harmonics moved).
    use corrugation::output::netcdf::read_f64;
    let set: Vec<String> = [
        "rail.x_max=0.06",
        "passage.end=0.06",
        "roughness.wavelength_max=0.06",
        "growth.adaptive=false",
        "growth.traffic_scale=1e5",
        "growth.passes=1",
        "growth.contact_history=[]",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let r = corrugation::config::load_str(include_str!("../configs/growth_exact.toml"), "g", &set).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("g.h5");
    corrugation::run::run_scene(&r, &out, &mut |_| {}).unwrap();
    let w = read_f64(&out, "passes", "wavelength").unwrap();
    let a = read_f64(&out, "passes", "spectrum").unwrap();
    let a = a.as_slice().unwrap();
    let short = w.iter().zip(a).filter(|(l, _)| **l < 8e-4 * (1.0 - 1e-9)).map(|(_, v)| *v).fold(0.0, f64::max);
    let band = w.iter().zip(a).filter(|(l, _)| **l >= 0.01).map(|(_, v)| *v).fold(0.0, f64::max);
    assert!(band > 1e-7, "{band:e}");
    assert!(short < 1e-12 * band, "shorter than two elements: {short:e} m against {band:e} m");
}
