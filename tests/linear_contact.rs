//! The linear profile contact on the fixed grid (`contact.normal =
//! "linear"`, and `"auto"` within the linear range): the Hertz ellipse
//! moved and stretched to first order with the rail under it, the rest of
//! the normal problem's linear response on it, its pressure averaged over
//! the grid's elements. Against closed forms and the nonlinear profile
//! contact:
//!
//! - a flat rail: the cell means of Hertz's pressure, which hold the force
//!   and converge to Hertz's peak;
//! - a tilted rail `r = alpha X`: the patch moves by `R alpha` (the contact
//!   point of a wheel of radius R on the slope);
//! - a short wave: Westergaard's pressure ripple `E* k Delta / 2` inside the
//!   patch (Johnson, *Contact Mechanics*, 1985, sec. 13.2);
//! - a harmonic corrugation: the patch's move and the crest's pressure
//!   those of the nonlinear contact to first order in the amplitude;
//! - a passage over a corrugated rail balances the forces at every step;
//! - `auto` takes the linear contact while the corrugation is shallow and
//!   the nonlinear one beyond.
use crate::common;
use common::{STEEL, paper_fixed_grid, paper_shape, rel};
use corrugation::config::load_str;
use corrugation::contact::grid::{FixedGrid, RailSurface};
use corrugation::contact::{PatchSolution, RailContact, StepInput, TangentialSolver};
use corrugation::hertz::Curvatures;
use std::f64::consts::PI;
use std::sync::Arc;

const N: f64 = 1e5;

fn curvatures() -> Curvatures {
    Curvatures::wheel_on_rail(0.5, -0.409, 0.3)
}

/// The paper's contact on a fixed grid of `dx x dy` sized for the Hertz
/// patch at `N` times `length`.
fn solver(dx: f64, dy: f64, length: f64) -> FixedGrid {
    paper_fixed_grid(dx, dy, length, N)
}

/// A step of the paper's rolling (100 km/h, F_x = 20 kN, mu = 0.4) with the
/// patch centre at `position`.
fn rolling(dx: f64, position: f64) -> StepInput {
    let patch = paper_shape(true).patch(N).unwrap();
    StepInput {
        patch,
        speed: 27.78,
        dt: dx / 27.78,
        friction: 0.4,
        characteristic: Default::default(),
        memory: None,
        force_x: 2e4,
        creepage_x: None,
        creepage_y: 0.0,
        spin: 0.0,
        position,
    }
}

/// A line `f(X)` along the rail, uniform across, sampled every 10 um.
fn line(f: impl Fn(f64) -> f64) -> Arc<RailSurface> {
    let (x0, dx, n) = (-0.03, 1e-5, 6001);
    let v: Vec<f64> = (0..n).map(|i| f(x0 + i as f64 * dx)).collect();
    Arc::new(RailSurface::line(x0, dx, &v, false))
}

/// One step's solution on the grid `(dx, dy)` with `surface` as the
/// linear (`linear`) or nonlinear contact.
fn step(dx: f64, dy: f64, surface: Arc<RailSurface>, linear: bool, position: f64) -> (PatchSolution, FixedGrid) {
    let mut s = solver(dx, dy, 1.3);
    s.set_surface(Some(if linear { RailContact::Linear(surface) } else { RailContact::Profile(surface) })).unwrap();
    let sol = s.step(&rolling(dx, position)).unwrap();
    (sol, s)
}

/// The pressure's centroid along x (m).
fn centroid(sol: &PatchSolution, s: &FixedGrid) -> f64 {
    let g = s.grid();
    let total: f64 = sol.pressure.iter().sum();
    sol.pressure.iter().enumerate().map(|(k, p)| p * g.x(k % g.nx)).sum::<f64>() / total
}

/// Least-squares amplitude of cos(k x) in `v(x)`, with sin(k x), 1 and x^2
/// as nuisance terms.
fn cos_amplitude(xs: &[f64], v: &[f64], k: f64) -> f64 {
    let basis = |x: f64| [(k * x).cos(), (k * x).sin(), 1.0, x * x];
    let mut m = nalgebra::DMatrix::zeros(xs.len(), 4);
    for (i, &x) in xs.iter().enumerate() {
        for (j, b) in basis(x).into_iter().enumerate() {
            m[(i, j)] = b;
        }
    }
    m.svd(true, true).solve(&nalgebra::DVector::from_column_slice(v), 1e-14).unwrap()[0]
}

#[test]
fn flat_rail_cell_means_hold_the_force_and_converge_to_hertz() {
    let p0 = paper_shape(true).patch(N).unwrap().p0;
    let mut errors = Vec::new();
    for (dx, dy) in [(4e-4, 1e-3), (2e-4, 5e-4), (1e-4, 2.5e-4)] {
        let (flat, s) = step(dx, dy, line(|_| 0.0), true, 0.0);
        let total: f64 = flat.pressure.iter().sum::<f64>() * s.grid().area();
        assert!(rel(total, N) < 1e-12, "force {total}");
        assert!(centroid(&flat, &s).abs() < 1e-7 * dx, "a flat rail does not move the patch");
        let peak = flat.pressure.iter().cloned().fold(0.0, f64::max);
        errors.push(1.0 - peak / p0);
    }
    // Cell means of the square root: second order in the element (measured
    // 2.4e-3, 5.9e-4, 1.5e-4).
    assert!(errors[2] > 0.0 && errors[2] < 5e-4, "{errors:?}");
    assert!(errors[0] > 3.0 * errors[1] && errors[1] > 3.0 * errors[2], "{errors:?}");
}

#[test]
fn a_tilted_rail_moves_the_patch_by_r_alpha() {
    // r = alpha X: the gap A x^2 - alpha x is Hertz's about x = alpha / (2 A)
    // = R alpha, the contact point of a wheel of radius R on the slope.
    let alpha = 2e-4;
    let expected = alpha / (2.0 * curvatures().a);
    for (dx, dy) in [(4e-4, 1e-3), (2e-4, 5e-4)] {
        let (sol, s) = step(dx, dy, line(|x| alpha * x), true, 0.0);
        let c = centroid(&sol, &s);
        assert!(rel(c, expected) < 1e-3, "{dx}: centroid {c:e} vs R alpha {expected:e}");
    }
}

#[test]
fn a_short_wave_gives_westergaards_pressure_ripple() {
    // lambda = 4 mm inside a 12 x 19 mm patch on a 0.1 mm grid; Delta =
    // 0.05 um: the ripple E* k Delta / 2 inside (line contact). The linear
    // contact's normal mesh has 10.7 elements per wavelength (2.3 % short,
    // 3.6 % at 8, 1.8 % at 16); the nonlinear contact on the grid 0.1 %.
    let e_star = STEEL.young_modulus / (2.0 * (1.0 - STEEL.poisson_ratio.powi(2)));
    let a = paper_shape(true).patch(N).unwrap().a;
    let (lambda, delta, dx, dy) = (4e-3, 5e-8, 1e-4, 2.5e-4);
    let k = 2.0 * PI / lambda;
    let (wavy, s) = step(dx, dy, line(move |x| delta * (k * x).cos()), true, 0.0);
    let (flat, _) = step(dx, dy, line(|_| 0.0), true, 0.0);
    let g = s.grid();
    let row = g.ny / 2;
    let (xs, dp): (Vec<f64>, Vec<f64>) = (0..g.nx)
        .filter(|&ix| g.x(ix).abs() < 0.5 * a)
        .map(|ix| (g.x(ix), wavy.pressure[row * g.nx + ix] - flat.pressure[row * g.nx + ix]))
        .unzip();
    let amplitude = cos_amplitude(&xs, &dp, k);
    let expect = e_star * k * delta / 2.0;
    assert!(rel(amplitude, expect) < 0.04, "ripple {amplitude:.4e} Pa vs Westergaard {expect:.4e} Pa");
}

#[test]
fn a_harmonic_corrugation_moves_and_loads_the_patch_as_the_nonlinear_contact() {
    // On a 0.1 mm grid, where 1 um moves the nonlinear contact's edge by an
    // element: the patch's move with the slope under it (the wave's
    // quarter point) and the pressure change at the centre over a crest,
    // linear against nonlinear (measured: the move within 0.03 % at 30 mm
    // and 1.3 % at 15 mm, the crest's pressure within 0.8 % and 3.1 %).
    let (dx, dy) = (1e-4, 2.5e-4);
    let centre = |s: &FixedGrid| (s.grid().ny / 2) * s.grid().nx + s.grid().nx / 2;
    for (lambda, tol_move, tol_crest) in [(0.03, 0.01, 0.02), (0.015, 0.02, 0.05)] {
        let k = 2.0 * PI / lambda;
        let wave = line(move |x| 1e-6 * (k * x).cos());
        let moved = |linear| {
            let (sol, s) = step(dx, dy, wave.clone(), linear, lambda / 4.0);
            centroid(&sol, &s)
        };
        let (lin, nonlin) = (moved(true), moved(false));
        assert!(rel(lin, nonlin) < tol_move, "{lambda}: patch moved {lin:e} vs {nonlin:e} m");
        let crest = |linear| {
            let (sol, s) = step(dx, dy, wave.clone(), linear, 0.0);
            let (flat, _) = step(dx, dy, line(|_| 0.0), linear, 0.0);
            sol.pressure[centre(&s)] - flat.pressure[centre(&s)]
        };
        let (lin, nonlin) = (crest(true), crest(false));
        assert!(lin > 0.0 && rel(lin, nonlin) < tol_crest, "{lambda}: crest pressure {lin:e} vs {nonlin:e} Pa");
    }
}

#[test]
fn force_balance_and_the_traction_bound_at_every_step_of_a_corrugated_passage() {
    // 5 um at 30 mm under a normal force varying by 30 %: every step holds
    // the normal force, the prescribed longitudinal force and |q| <= mu p.
    let (dx, dy) = (4e-4, 1e-3);
    let mut s = solver(dx, dy, 1.5);
    let lambda = 0.03;
    let k = 2.0 * PI / lambda;
    s.set_surface(Some(RailContact::Linear(line(move |x| 5e-6 * (k * x).cos())))).unwrap();
    let shape = paper_shape(true);
    let area = s.grid().area();
    for step in 0..(lambda / dx) as usize {
        let x = step as f64 * dx;
        let n = N * (1.0 + 0.3 * (k * x).sin());
        let input = StepInput { patch: shape.patch(n).unwrap(), force_x: 0.2 * n, creepage_x: None, ..rolling(dx, x) };
        let sol = s.step(&input).unwrap();
        // (The normal force holds by the pressure's scaling; a NaN would not.)
        let total: f64 = sol.pressure.iter().sum::<f64>() * area;
        assert!(rel(total, n) < 1e-10, "step {step}: force {total} vs {n}");
        assert!(sol.pressure.iter().all(|p| *p >= 0.0), "step {step}: a negative pressure");
        let fx: f64 = sol.traction_x.iter().sum::<f64>() * area;
        assert!(rel(fx, 0.2 * n) < 1e-6, "step {step}: F_x {fx} vs {}", 0.2 * n);
        for (q, p) in sol.traction_x.iter().zip(&sol.pressure) {
            assert!(q.abs() <= 0.4 * p * (1.0 + 1e-9), "step {step}: traction bound");
        }
        assert_eq!(sol.clipped, 0, "step {step}");
    }
}

/// One passage of growth_exact.toml's scene with one harmonic of
/// `amplitude` (m) at `wavelength` (m) under `contact.normal = normal`:
/// `passes/profile_contact` and the wear.
fn one_harmonic(dir: &std::path::Path, amplitude: f64, wavelength: f64, normal: &str) -> (f64, ndarray::ArrayD<f64>) {
    let set: Vec<String> = [
        "growth.passes=1",
        "growth.adaptive=false",
        "growth.traffic_scale=1",
        "growth.contact_history=[]",
        "roughness.kind=harmonics",
        "rail.half_width=0.02",
        "contact.profile_grid_scale=2",
    ]
    .iter()
    .map(|s| s.to_string())
    .chain([
        format!("roughness.harmonics=[{{amplitude = {amplitude}, wavelength = {wavelength}}}]"),
        format!("contact.normal={normal}"),
    ])
    .collect();
    let r = load_str(include_str!("../configs/growth_exact.toml"), "auto", &set).unwrap();
    let out = dir.join(format!("{amplitude}_{wavelength}_{normal}.h5"));
    corrugation::run::run_scene(&r, &out, &mut |_| {}).unwrap();
    let read = |group, name| corrugation::output::netcdf::read_f64(&out, group, name).unwrap();
    (read("passes", "profile_contact")[[0]], read("rail", "wear"))
}

#[test]
fn auto_takes_the_linear_contact_while_the_corrugation_is_shallow() {
    // 1 um at 60 mm (R r'' = 0.005) in the linear contact
    // (passes/profile_contact 2). Auto's grid (here 2 times the patch)
    // holds the nonlinear contact; its linear passages run on a block of it
    // that holds the patch the corrugation moves and stretches: the same
    // wear as `"linear"` on its own grid to the solvers' tolerance.
    let dir = tempfile::tempdir().unwrap();
    let (contact, auto) = one_harmonic(dir.path(), 1e-6, 0.06, "auto");
    assert_eq!(contact, 2.0);
    let (contact, linear) = one_harmonic(dir.path(), 1e-6, 0.06, "linear");
    assert_eq!(contact, 2.0);
    let scale = linear.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let worst = auto.iter().zip(linear.iter()).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(scale > 0.0 && worst < 2e-3 * scale, "auto's linear passage {worst:e} m from linear's (wear {scale:e} m)");
}

#[test]
fn auto_leaves_the_linear_contact_where_the_linearisation_fails() {
    // 20 um at 30 mm (R r'' = 0.44, the patch stretched) and 30 um at 60 mm
    // (the patch moved by a quarter of it) in the linear contact, 20 um at
    // 15 mm (R r'' = 1.75) in the nonlinear one, and 65 um at 60 mm (R r''
    // = 0.36, but a move of half the patch, which the linearisation
    // refuses) run again in the nonlinear one.
    let dir = tempfile::tempdir().unwrap();
    assert_eq!(one_harmonic(dir.path(), 2e-5, 0.03, "auto").0, 2.0);
    assert_eq!(one_harmonic(dir.path(), 3e-5, 0.06, "auto").0, 2.0);
    assert_eq!(one_harmonic(dir.path(), 2e-5, 0.015, "auto").0, 1.0);
    assert_eq!(one_harmonic(dir.path(), 6.5e-5, 0.06, "auto").0, 1.0);
}
