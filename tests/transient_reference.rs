//! The transient (non-stationary) contact model against Cattaneo-Mindlin,
//! Kalker's linear theory, Kalker's "from Cattaneo to Carter", and CONTACT's
//! exact-theory solutions for the paper's patch (shared reference, scene c).
use crate::common;
use common::{STEEL, paper_coefficients, paper_shape, peak, rel};
use corrugation::contact::fastsim::Fastsim;
use corrugation::contact::transient::elastic::{ExactElastic, WinklerElastic};
use corrugation::contact::transient::{ElasticModel, Transient};
use corrugation::contact::{EllipseMesh, PatchSolution, PressureShape, StepInput, TangentialSolver};
use corrugation::hertz::{Curvatures, Elastic, HertzPatch, HertzShape};

fn exact(shape: &HertzShape, el: Elastic, nx: usize, ny: usize, eps: f64) -> Transient {
    let mesh = EllipseMesh::new(nx, ny);
    let e = ExactElastic::new(&mesh, shape.aspect(), el.shear_modulus(), el.poisson_ratio);
    Transient::new(mesh, ElasticModel::Exact(Box::new(e)), PressureShape::Hertz, eps)
}

fn input(patch: HertzPatch, speed: f64, step: f64, mu: f64, force_x: f64) -> StepInput {
    StepInput {
        patch,
        speed,
        dt: step / speed,
        friction: mu,
        characteristic: Default::default(),
        memory: None,
        force_x,
        creepage_x: None,
        creepage_y: 0.0,
        spin: 0.0,
        position: 0.0,
    }
}

/// Area fraction of stick elements.
fn stick_area_fraction(mesh: &EllipseMesh, sol: &PatchSolution) -> f64 {
    let total: f64 = (0..mesh.len()).map(|k| mesh.area(k)).sum();
    (0..mesh.len()).filter(|k| sol.stick[*k]).map(|k| mesh.area(k)).sum::<f64>() / total
}

/// Rolls `steps` steps at constant force; returns the creepage history.
fn roll(solver: &mut dyn TangentialSolver, inp: &StepInput, steps: usize) -> Vec<f64> {
    solver.reset();
    (0..steps).map(|_| solver.step(inp).expect("converges").creepage.x).collect()
}

#[test]
fn cattaneo_mindlin_circle() {
    // Circle with a = 6 mm at N = 100 kN; F = 0.5 mu N applied at rest.
    // Stick radius c/a = (1 - F/(mu N))^(1/3); relative shift of the bodies
    // delta = 3 mu N (2 - nu)/(8 G a) [1 - (1 - F/(mu N))^(2/3)]
    // (Johnson 1985, eqs. 7.39-7.42). Within 3 % on a 30 x 30 mesh.
    let (n, mu, a): (f64, f64, f64) = (1e5, 0.4, 6e-3);
    let curv = 3.0 * n / (8.0 * STEEL.contact_modulus() * a.powi(3));
    let shape = HertzShape::new(Curvatures { a: curv, b: curv }, STEEL).unwrap();
    let patch = shape.patch(n).unwrap();
    assert!(rel(patch.a, a) < 1e-9);
    let mut solver = exact(&shape, STEEL, 30, 30, 1e-5);
    let (v, step) = (27.78, 2e-4);
    for ratio in [0.3, 0.5, 0.8] {
        solver.reset();
        let sol = solver.step(&input(patch, v, step, mu, ratio * mu * n)).unwrap();
        let shift = sol.creepage.x * v * (step / v);
        let g = STEEL.shear_modulus();
        let expected = 3.0 * mu * n * (2.0 - 0.3) / (8.0 * g * a) * (1.0 - (1.0 - ratio).powf(2.0 / 3.0));
        let c_over_a = stick_area_fraction(solver.mesh(), &sol).sqrt();
        let c_expected = (1.0 - ratio).cbrt();
        eprintln!("F/muN {ratio}: shift {shift:.4e} vs {expected:.4e}; c/a {c_over_a:.4} vs {c_expected:.4}");
        assert!(rel(shift.abs(), expected) < 0.03, "shift {shift} vs {expected}");
        assert!((c_over_a - c_expected).abs() < 0.03, "c/a {c_over_a} vs {c_expected}");
        // Force balance and the friction bound on every element.
        assert!(rel(sol.force_x, ratio * mu * n) < 1e-9);
        for k in 0..sol.pressure.len() {
            assert!(sol.traction_x[k].hypot(sol.traction_y[k]) <= mu * sol.pressure[k] * (1.0 + 1e-12));
        }
    }
}

#[test]
fn contact_scene_c_shift_at_rest() {
    // CONTACT: Cattaneo shift at rest with F_x = 20 kN: cvx -2.057e-2 mm,
    // ccv -1.436e-2 mm (within 3 % on 20 x 20).
    for (concave, expected) in [(false, -2.057e-5), (true, -1.436e-5)] {
        let shape = paper_shape(concave);
        let patch = shape.patch(1e5).unwrap();
        let mut solver = exact(&shape, STEEL, 20, 20, 1e-5);
        let sol = solver.step(&input(patch, 27.778, 2e-4, 0.4, 2e4)).unwrap();
        let shift = sol.creepage.x * 2e-4;
        eprintln!("concave {concave}: shift {shift:.4e} vs {expected:.4e}");
        assert!(rel(shift, expected) < 0.03);
    }
}

#[test]
fn contact_scene_c_from_cattaneo_to_carter() {
    // CONTACT (0.2 mm steps, F_x = 20 kN, N = 100 kN): creepage at the first
    // rolling step, overshoot peak and its position, steady state; within 3 %
    // (position within one step). Mesh: 30 x 12 (ccv), 40 x 10 (cvx), i.e.
    // element length about 0.4 mm = 2 steps along the centre strip.
    let cases = [
        (true, (30, 12), -0.721e-3, 1.380e-3, 7.6e-3, -1.245e-3, 180),
        (false, (40, 10), -0.959e-3, 2.016e-3, 10.0e-3, -1.748e-3, 240),
    ];
    for (concave, (nx, ny), first, peak_value, peak_at, steady, steps) in cases {
        let shape = paper_shape(concave);
        let patch = shape.patch(1e5).unwrap();
        let mut solver = exact(&shape, STEEL, nx, ny, 1e-5);
        let h = roll(&mut solver, &input(patch, 27.778, 2e-4, 0.4, 2e4), steps + 1);
        let (pv, pa) = peak(&h, 2e-4);
        eprintln!("concave {concave}: first {:.4e} peak {pv:.4e} at {pa:.4e} steady {:.4e}", h[1], h[steps]);
        assert!(rel(h[1], first) < 0.03, "first step {} vs {first}", h[1]);
        assert!(rel(pv, peak_value) < 0.03, "peak {pv} vs {peak_value}");
        assert!((pa - peak_at).abs() <= 2e-4 + 1e-9, "peak at {pa} vs {peak_at}");
        assert!(rel(h[steps], steady) < 0.03, "steady {} vs {steady}", h[steps]);
    }
}

#[test]
fn kalker_cattaneo_to_carter_classic() {
    // Kalker 1990 sec. 5.2.2.5 (CONTACT `catt_to_cart`): G = 1, nu = 0.28,
    // mu = 0.4013, N = 0.4705, circle a = 3.5 mm, F_x = -0.657 mu N from the
    // start. CONTACT (0.25 mm grid): |creepage| 1.824e-3 after 0.25 mm, peak
    // 3.403e-3 near 3.4 mm, undershoot 3.062e-3 near 6 mm, 3.101e-3 steady.
    // Units: G = 1 N/mm^2, lengths mm -> SI: G = 1e6 Pa, N = 0.4705 N.
    let el = Elastic::from_shear(1e6, 0.28);
    let (n, a, mu): (f64, f64, f64) = (0.4705, 3.5e-3, 0.4013);
    let curv = 3.0 * n / (8.0 * el.contact_modulus() * a.powi(3));
    let shape = HertzShape::new(Curvatures { a: curv, b: curv }, el).unwrap();
    let patch = shape.patch(n).unwrap();
    // 28 elements of 0.25 mm across the centre strip; eps small against the
    // slip speeds at V = 1 m/s.
    let mut solver = exact(&shape, el, 28, 14, 1e-6);
    let step = 2.5e-4;
    let h = roll(&mut solver, &input(patch, 1.0, step, mu, -0.657 * mu * n), 61);
    let (pv, pa) = peak(&h, step);
    let (under, under_at) = h
        .iter()
        .enumerate()
        .skip(16)
        .take(20)
        .fold((f64::MAX, 0.0), |(m, at), (i, c)| if c.abs() < m { (c.abs(), i as f64 * step) } else { (m, at) });
    eprintln!("first {:.4e} peak {pv:.4e} at {pa:.3e} under {under:.4e} at {under_at:.3e} steady {:.4e}", h[1], h[60]);
    assert!(rel(h[1].abs(), 1.824e-3) < 0.03);
    assert!(rel(pv, 3.403e-3) < 0.03 && (pa - 3.4e-3).abs() < 0.5e-3);
    assert!(rel(under, 3.062e-3) < 0.03 && (under_at - 6e-3).abs() < 1e-3);
    assert!(rel(h[60].abs(), 3.101e-3) < 0.03);
}

#[test]
fn simplified_transient_reaches_fastsim_steady_state() {
    // Same elastic model (Winkler, L1 from C11) and bound as FASTSIM: after
    // rolling three contact lengths at constant force, the creepage equals
    // FASTSIM's steady value (within 1 %, 20 x 20, parabolic bound).
    let shape = paper_shape(true);
    let patch = shape.patch(1e5).unwrap();
    let c = paper_coefficients(true);
    let g = STEEL.shear_modulus();
    let mesh = EllipseMesh::new(20, 20);
    let w = WinklerElastic { l1_unit: 8.0 / (3.0 * c.c11 * g), l2_unit: 8.0 / (3.0 * c.c22 * g) };
    let mut solver = Transient::new(mesh, ElasticModel::Winkler(w), PressureShape::Parabolic, 1e-5);
    let inp = input(patch, 27.778, 2e-4, 0.4, 2e4);
    let h = roll(&mut solver, &inp, 181);
    let f = Fastsim::new(20, 20, PressureShape::Parabolic, c, g).solve_force(&inp).unwrap();
    eprintln!("simplified {:.5e} fastsim {:.5e}", h[180], f.creepage.x);
    assert!(rel(h[180], f.creepage.x) < 0.01);
}

/// Steady creepage after rolling `steps` steps of 0.2 mm at constant force.
fn steady_creepage(concave: bool, mesh: (usize, usize), fx: f64, steps: usize) -> f64 {
    let shape = paper_shape(concave);
    let patch = shape.patch(1e5).unwrap();
    let mut solver = exact(&shape, STEEL, mesh.0, mesh.1, 1e-5);
    let h = roll(&mut solver, &input(patch, 27.778, 2e-4, 0.4, fx), steps);
    h[steps - 1]
}

// After rolling 2.5 contact lengths at constant force the transient model
// is in steady state. At F_x = 0.05 mu N its creepage is Kalker's linear
// theory xi = -F_x/(G a b C11) within 3 %; along CONTACT's exact creep curve
// (scene b, F_x/(mu N) <= 0.85) within 3 % (one test per patch, which run
// side by side).

#[test]
fn steady_state_is_kalker_linear_theory_at_small_force() {
    let g = STEEL.shear_modulus();
    let patch = paper_shape(true).patch(1e5).unwrap();
    let linear = -2000.0 / (g * patch.a * patch.b * paper_coefficients(true).c11);
    let xi = steady_creepage(true, (30, 12), 2000.0, 150);
    eprintln!("0.05 mu N: {xi:.4e} vs linear theory {linear:.4e}");
    assert!(rel(xi, linear) < 0.03);
}

/// (F_x/(mu N), CONTACT exact creepage) on the concave or convex patch.
fn meets_contact_creep_curve(concave: bool, points: &[(f64, f64)]) {
    for &(frac, expected) in points {
        let mesh = if concave { (30, 12) } else { (40, 10) };
        let steps = if concave { 150 } else { 200 };
        let xi = steady_creepage(concave, mesh, frac * 4e4, steps);
        eprintln!("concave {concave} {frac}: {xi:.4e} vs CONTACT {expected:.4e}");
        assert!(rel(xi, expected) < 0.03);
    }
}

#[test]
fn steady_state_meets_contact_creep_curve_concave() {
    meets_contact_creep_curve(true, &[(0.25, -5.597e-4), (0.55, -1.401e-3), (0.85, -2.706e-3)]);
}

#[test]
fn steady_state_meets_contact_creep_curve_convex() {
    meets_contact_creep_curve(false, &[(0.45, -1.531e-3), (0.85, -3.855e-3)]);
}

#[test]
fn cattaneo_shift_converges_in_mesh_and_regularisation() {
    // Mindlin's shift at F = 0.5 mu N for the circle: the error decreases under
    // mesh refinement (10, 20, 30 elements) and the solution converges as
    // eps decreases (1e-3, 1e-4, 1e-5 m/s at V dt = 0.2 mm).
    let (n, mu, a): (f64, f64, f64) = (1e5, 0.4, 6e-3);
    let curv = 3.0 * n / (8.0 * STEEL.contact_modulus() * a.powi(3));
    let shape = HertzShape::new(Curvatures { a: curv, b: curv }, STEEL).unwrap();
    let patch = shape.patch(n).unwrap();
    let mindlin = 3.0 * mu * n * 1.7 / (8.0 * STEEL.shear_modulus() * a) * (1.0 - 0.5f64.powf(2.0 / 3.0));
    let shift = |m: usize, eps: f64| {
        let mut s = exact(&shape, STEEL, m, m, eps);
        s.step(&input(patch, 27.78, 2e-4, mu, 0.5 * mu * n)).unwrap().creepage.x.abs() * 2e-4
    };
    let errors: Vec<f64> = [10, 20, 30].iter().map(|m| rel(shift(*m, 1e-5), mindlin)).collect();
    eprintln!("mesh errors {errors:?}");
    assert!(errors[0] > errors[1] && errors[1] > errors[2], "{errors:?}");
    let by_eps: Vec<f64> = [1e-3, 1e-4, 1e-5].iter().map(|e| shift(16, *e)).collect();
    let (d1, d2) = ((by_eps[0] - by_eps[2]).abs(), (by_eps[1] - by_eps[2]).abs());
    eprintln!("eps shifts {by_eps:?}");
    assert!(d2 < d1 && d2 < 0.01 * by_eps[2], "{by_eps:?}");
}
