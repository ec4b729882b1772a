//! Transient models inside a passage: invariants on every step, contact loss,
//! and non-convergence reported with where and why.
use corrugation::build::{build_deposit, build_solver, derive};
use corrugation::config::load_str;
use corrugation::contact::transient::elastic::ExactElastic;
use corrugation::contact::transient::{DEFAULT_TOLERANCE, ElasticModel, StepSolver, Transient};
use corrugation::contact::{EllipseMesh, PressureShape, StepInput, TangentialSolver};
use corrugation::passage::{PassageError, PassageResult, run_passage};
use corrugation::wear::WearDeposit;

const BASE: &str = include_str!("../configs/paper_normal_15mm.toml");

fn passage(model: &str, extra: &[&str]) -> (PassageResult, f64) {
    let mut set: Vec<String> =
        ["contact.elements_x=10", "contact.elements_y=10", "rail.dx=2e-4"].iter().map(|s| s.to_string()).collect();
    set.push(format!("contact.model={model}"));
    set.extend(extra.iter().map(|s| s.to_string()));
    let r = load_str(BASE, "paper_normal_15mm", &set).unwrap_or_else(|e| panic!("{e}"));
    let d = derive(&r.scene);
    let mut solver = build_solver(&r.scene, &d.shape);
    let dep = build_deposit(&solver.elements());
    let res = run_passage(&d.passage, &d.shape, solver.as_mut(), dep.as_ref(), &d.grid, true, &mut |_, _| {}).unwrap();
    (res, r.scene.material.friction)
}

#[test]
fn invariants_on_every_step() {
    for model in ["exact-transient", "simplified-transient"] {
        let (res, mu) = passage(model, &[]);
        let h = &res.history;
        let f = h.fields.as_ref().unwrap();
        for s in 0..h.time.len() {
            assert!((h.longitudinal_force[s] - 2e4).abs() < 1e-6 * 2e4, "{model}: force balance at step {s}");
            assert!(h.newton_iterations[s] >= 1.0, "{model}: the step solver ran at step {s}");
            for k in 0..f.pressure.ncols() {
                let t = f.traction_x[[s, k]].hypot(f.traction_y[[s, k]]);
                assert!(t <= mu * f.pressure[[s, k]] * (1.0 + 1e-12), "{model}: |p| <= mu p3 at ({s},{k})");
                // Archard (Baeza et al. 2008, Eq. 8): w = (k/H) p3 |s|, k/H
                // = 3.4e-14 m^2/N in the config.
                let archard = 3.4e-14 * f.pressure[[s, k]] * f.slip_x[[s, k]].hypot(f.slip_y[[s, k]]);
                let w = f.wear_rate[[s, k]];
                assert!((w - archard).abs() <= 1e-12 * archard, "{model}: Archard at ({s},{k}): {w:e} vs {archard:e}");
            }
        }
        assert!(res.wear.iter().all(|w| w.is_finite() && *w >= 0.0));
        assert!(res.wear.iter().any(|w| *w > 0.0));
    }
}

#[test]
fn contact_loss_restarts_the_history() {
    // N = 100 kN + 120 kN sin(2 pi X / 15 mm), no longitudinal force: the
    // wheel leaves the rail on part of every wavelength.
    let (res, _) = passage(
        "exact-transient",
        &["load.harmonics[0].amplitude=1.2e5", "load.longitudinal_force=0", "rail.half_width=0.014"],
    );
    let h = &res.history;
    let f = h.fields.as_ref().unwrap();
    let lost: Vec<usize> = (0..h.time.len()).filter(|s| h.in_contact[*s] == 0.0).collect();
    assert!(!lost.is_empty() && lost.len() < h.time.len());
    for s in lost {
        assert!(h.normal_force[s] <= 0.0);
        assert_eq!((h.semi_axis_a[s], h.creepage_x[s]), (0.0, 0.0));
        assert!(f.pressure.row(s).iter().chain(f.traction_x.row(s).iter()).all(|v| *v == 0.0));
    }
    assert!(res.wear.iter().all(|w| w.is_finite() && *w >= 0.0));
}

#[test]
fn non_convergence_is_reported_with_step_and_residuals() {
    let shape = corrugation::hertz::HertzShape::new(
        corrugation::hertz::Curvatures::wheel_on_rail(0.5, -0.409, 0.3),
        corrugation::hertz::Elastic { young_modulus: 2.1e11, poisson_ratio: 0.3 },
    )
    .unwrap();
    let mesh = EllipseMesh::new(8, 8);
    let e = ExactElastic::new(&mesh, shape.aspect(), 8.0769e10, 0.3);
    let mut solver =
        Transient::new(mesh, ElasticModel::Exact(Box::new(e)), PressureShape::Hertz, 1e-5).with_max_iterations(2);
    let patch = shape.patch(1e5).unwrap();
    let input = StepInput {
        patch,
        speed: 27.78,
        dt: 7.2e-6,
        friction: 0.4,
        characteristic: Default::default(),
        memory: None,
        force_x: 2e4,
        creepage_x: None,
        creepage_y: 0.0,
        spin: 0.0,
        position: 0.0,
    };
    let err = solver.step(&input).unwrap_err().to_string();
    assert!(err.contains("Newton-Raphson on the local slips failed"), "{err}");
    assert!(err.contains("max |R|") && err.contains("m/s in 2 iterations"), "{err}");
    // Through the passage the error names the step, position and loads.
    let r = load_str(
        BASE,
        "x",
        &["contact.model=exact-transient".into(), "contact.elements_x=8".into(), "contact.elements_y=8".into()],
    )
    .unwrap();
    let d = derive(&r.scene);
    let dep = WearDeposit::new(solver.mesh());
    let e = run_passage(&d.passage, &d.shape, &mut solver, &dep, &d.grid, false, &mut |_, _| {}).unwrap_err();
    assert!(matches!(e, PassageError::Tangential { step: 0, .. }));
    let msg = e.to_string();
    assert!(msg.starts_with("step 0 at X = -1.500000e-2 m (N = 1.000000e5 N, F_x = 2.000000e4 N)"), "{msg}");
}

#[test]
fn tiny_regularisation_converges_through_eps_continuation() {
    // Stability map, eps row: at eps = 1e-7 m/s (8 x 8) one step needs
    // Newton's continuation 100 eps -> 10 eps -> eps after the direct attempt
    // (60 iterations) fails; the passage completes and its wear is within 1 %
    // of the eps = 1e-6 passage (the regularised law converges as eps -> 0).
    // Gauss-Seidel needs no continuation (each element problem is solved
    // exactly) and lands on the same wear.
    let run = |solver: &str, eps: &str| {
        let (solver, eps) = (format!("contact.solver={solver}"), format!("contact.regularisation={eps}"));
        passage("exact-transient", &["contact.elements_x=8", "contact.elements_y=8", &solver, &eps]).0
    };
    let rel = |a: &PassageResult, b: &PassageResult| {
        (&a.wear - &b.wear).mapv(|v| v * v).sum().sqrt() / b.wear.mapv(|v| v * v).sum().sqrt()
    };
    let (tiny, small) = (run("newton", "1e-7"), run("newton", "1e-6"));
    let most = tiny.history.newton_iterations.iter().fold(0.0f64, |m, v| m.max(*v));
    assert!(most > 60.0, "continuation used: {most} iterations on the hardest step");
    assert!(rel(&tiny, &small) < 0.01, "wear 1e-7 vs 1e-6: {}", rel(&tiny, &small));
    let gs = run("gauss-seidel", "1e-7");
    assert!(rel(&gs, &tiny) < 1e-6, "Gauss-Seidel vs Newton at eps = 1e-7: {}", rel(&gs, &tiny));
}

/// The first 19 mm of paper_normal_15mm (95 steps, more than a wavelength)
/// with the exact model on 8 x 8, solved by `solver` to `tolerance` eps.
fn exact_passage(solver: StepSolver, tolerance: f64) -> PassageResult {
    let set: Vec<String> =
        ["contact.elements_x=8", "contact.elements_y=8", "passage.end=0.004"].iter().map(|s| s.to_string()).collect();
    let r = load_str(BASE, "x", &set).unwrap();
    let d = derive(&r.scene);
    let mesh = EllipseMesh::new(8, 8);
    let el = r.scene.material.elastic;
    let e = ExactElastic::new(&mesh, d.shape.aspect(), el.shear_modulus(), el.poisson_ratio);
    let mut solver = Transient::new(mesh, ElasticModel::Exact(Box::new(e)), PressureShape::Hertz, 1e-5)
        .with_solver(solver)
        .with_tolerance(tolerance);
    let dep = WearDeposit::new(solver.mesh());
    let res = run_passage(&d.passage, &d.shape, &mut solver, &dep, &d.grid, true, &mut |_, _| {}).unwrap();
    assert_eq!(solver.gauss_seidel_fallbacks(), 0, "every Gauss-Seidel step converged on its own");
    res
}

/// Largest difference of `a` and `b`, relative to the largest |b|.
fn rel_diff<'a>(a: impl IntoIterator<Item = &'a f64>, b: impl IntoIterator<Item = &'a f64> + Clone) -> f64 {
    let scale = b.clone().into_iter().fold(0.0f64, |m, v| m.max(v.abs()));
    a.into_iter().zip(b).fold(0.0f64, |m, (x, y)| m.max((x - y).abs())) / scale
}

#[test]
fn gauss_seidel_converges_to_the_newton_solution() {
    // The same equations to the same tolerance: the two solvers differ by
    // what the tolerance leaves, and by less when it is tightened.
    for (tolerance, bound) in [(DEFAULT_TOLERANCE, 5e-8), (1e-8, 1e-11)] {
        let gs = exact_passage(StepSolver::GaussSeidel, tolerance);
        let nr = exact_passage(StepSolver::Newton, tolerance);
        let (g, n) = (gs.history.fields.as_ref().unwrap(), nr.history.fields.as_ref().unwrap());
        let creepage = rel_diff(&gs.history.creepage_x, &nr.history.creepage_x);
        let traction = rel_diff(g.traction_x.iter(), n.traction_x.iter());
        let wear = rel_diff(gs.wear.iter(), nr.wear.iter());
        eprintln!("tolerance {tolerance:e}: creepage {creepage:.2e}, traction {traction:.2e}, wear {wear:.2e}");
        assert!(creepage < bound && traction < bound && wear < bound, "tolerance {tolerance:e}");
    }
}
