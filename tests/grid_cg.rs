//! The fixed grid's Newton-Krylov (CG) tangential solver against its
//! Gauss-Seidel solver: both solve the same discrete equations to the same
//! tolerance, so they must give the same steps (contact::grid::cg).

use crate::common;

use common::{STEEL, fixed_grid, paper_shape, rel};
use corrugation::contact::friction::FrictionLaw;
use corrugation::contact::grid::{FixedGrid, GridScheme, GridSolver};
use corrugation::contact::{PatchSolution, StepInput, TangentialSolver};
use corrugation::hertz::{Curvatures, Elastic, HertzShape};

/// The largest differences of two solvers over a run, each relative to
/// its scale: creepage x and y (to the largest |creepage x|), the wear
/// integral `INT p3 |s| dA` (to its largest), tractions (to mu p3 max);
/// and the stick counts of the CG run.
#[derive(Debug, Default)]
struct Agreement {
    creepage: f64,
    wear: f64,
    traction: f64,
    stick: Vec<usize>,
    /// The largest difference of the two runs' stick counts.
    stick_diff: usize,
}

/// Runs `inputs` through the CG and the Gauss-Seidel grids; checks every
/// CG step's force balance (1e-7) and friction bound (|p| <= mu p3).
fn compare(cg: &mut FixedGrid, gs: &mut FixedGrid, inputs: &[StepInput]) -> Agreement {
    let (mut creep, mut wear) = (Vec::new(), Vec::new());
    let mut out = Agreement::default();
    let integral = |s: &PatchSolution| -> f64 {
        (0..s.pressure.len()).map(|k| s.pressure[k] * s.slip_x[k].hypot(s.slip_y[k])).sum()
    };
    for (n, input) in inputs.iter().enumerate() {
        let a = cg.step(input).expect("CG step");
        let b = gs.step(input).expect("Gauss-Seidel step");
        assert!(rel(a.force_x, input.force_x) < 1e-7, "step {n}: force {} vs {}", a.force_x, input.force_x);
        let mu_p3 = a.pressure.iter().fold(0.0f64, |m, p| m.max(input.friction * p));
        for k in 0..a.pressure.len() {
            let t = a.traction_x[k].hypot(a.traction_y[k]);
            assert!(t <= input.friction * a.pressure[k] * (1.0 + 1e-12), "step {n}: friction bound at {k}");
            let d = (a.traction_x[k] - b.traction_x[k]).hypot(a.traction_y[k] - b.traction_y[k]);
            out.traction = out.traction.max(d / mu_p3);
        }
        creep.push((a.creepage.x, b.creepage.x));
        wear.push((integral(&a), integral(&b)));
        let count = |s: &PatchSolution| s.stick.iter().filter(|s| **s).count();
        out.stick.push(count(&a));
        out.stick_diff = out.stick_diff.max(count(&a).abs_diff(count(&b)));
    }
    let worst = |pairs: &[(f64, f64)]| {
        let largest = pairs.iter().fold(0.0f64, |m, w| m.max(w.1.abs()));
        pairs.iter().map(|(a, b)| (a - b).abs() / largest).fold(0.0, f64::max)
    };
    (out.creepage, out.wear) = (worst(&creep), worst(&wear));
    out
}

/// The paper's Fig. 7 loads (N = 100 kN + 45 kN sin(2 pi X / 30 mm), F_x =
/// 20 kN) over `steps` steps of the grid's element, with lateral creepage
/// and spin.
fn fig7_inputs(shape: &HertzShape, dx: f64, steps: usize, creepage_y: f64, spin: f64) -> Vec<StepInput> {
    let speed = 27.778;
    (0..steps)
        .map(|n| {
            let x = n as f64 * dx;
            let normal = 1e5 + 4.5e4 * (2.0 * std::f64::consts::PI * x / 0.03).sin();
            StepInput {
                patch: shape.patch(normal).unwrap(),
                speed,
                dt: dx / speed,
                friction: 0.4,
                characteristic: Default::default(),
                memory: None,
                force_x: 2e4,
                creepage_x: None,
                creepage_y,
                spin,
                position: x,
            }
        })
        .collect()
}

fn paper_pair_with(law: FrictionLaw) -> (FixedGrid, FixedGrid, HertzShape) {
    let shape = paper_shape(true);
    let curv = Curvatures::wheel_on_rail(0.5, -0.409, 0.3);
    let make =
        |solver| fixed_grid(&shape, (curv, STEEL), 1.45e5, (4e-4, 1e-3), (law, GridScheme::SecondOrder, 1e-5), solver);
    (make(GridSolver::Cg), make(GridSolver::GaussSeidel), shape)
}

fn paper_pair() -> (FixedGrid, FixedGrid, HertzShape) {
    paper_pair_with(FrictionLaw::Regularised)
}

#[test]
fn cg_and_gauss_seidel_solve_the_same_steps() {
    // Fig. 7's loads rolled over 30 mm from a virgin start (the first step
    // is Cattaneo's shift problem): the stick area changes at every step
    // with the load. Every step's creepage agrees to 1e-6 of the passage's
    // largest, its wear integral to 2e-6, its tractions to 1e-4 of mu p3
    // max; none falls back to Gauss-Seidel.
    let (mut cg, mut gs, shape) = paper_pair();
    let inputs = fig7_inputs(&shape, cg.grid().dx, 75, 0.0, 0.0);
    let r = compare(&mut cg, &mut gs, &inputs);
    eprintln!("Fig. 7: {r:?}, CG fallbacks {}", cg.fallbacks());
    let changes = r.stick.windows(2).filter(|w| w[0] != w[1]).count();
    assert!(changes >= 70, "the stick area changes at {changes} of 74 steps");
    assert!(r.creepage < 1e-6 && r.wear < 2e-6 && r.traction < 1e-4, "{r:?}");
    assert_eq!(cg.fallbacks(), 0);
}

#[test]
fn cg_solves_exact_coulomb_friction_as_gauss_seidel_does() {
    // Exact Coulomb friction: Gauss-Seidel solves the law itself, the CG
    // solver its regularised limit at 1e-5 eps (cg::COULOMB_LIMIT). Fig. 7's
    // loads from a virgin start: the same tolerances as the regularised
    // law's comparison.
    let (mut cg, mut gs, shape) = paper_pair_with(FrictionLaw::Coulomb);
    let inputs = fig7_inputs(&shape, cg.grid().dx, 75, 0.0, 0.0);
    let r = compare(&mut cg, &mut gs, &inputs);
    eprintln!("Coulomb: {r:?}, CG fallbacks {}", cg.fallbacks());
    assert!(r.creepage < 1e-6 && r.wear < 2e-6 && r.traction < 1e-4, "{r:?}");
    // The same stick areas (CG's stick: slips below 10 times its eps).
    assert!(r.stick.iter().all(|n| *n > 0) && r.stick_diff <= 2, "{r:?}");
    assert_eq!(cg.fallbacks(), 0);
}

#[test]
fn cg_and_gauss_seidel_agree_with_lateral_creepage_and_spin() {
    // The same loads with lateral creepage 2e-3 and spin 0.5 1/m (a curving
    // wheel): not symmetric about the centre line, both solve the whole
    // grid. Same tolerances.
    let (mut cg, mut gs, shape) = paper_pair();
    let inputs = fig7_inputs(&shape, cg.grid().dx, 40, 2e-3, 0.5);
    let r = compare(&mut cg, &mut gs, &inputs);
    eprintln!("lateral creepage and spin: {r:?}, CG fallbacks {}", cg.fallbacks());
    assert!(r.creepage < 1e-6 && r.wear < 2e-6 && r.traction < 1e-4, "{r:?}");
    assert_eq!(cg.fallbacks(), 0);
}

#[test]
fn cg_and_gauss_seidel_agree_from_cattaneo_to_carter() {
    // Kalker's classic (1990, sec. 5.2.2.5; the Coulomb version is
    // fixed_grid.rs's kalker_cattaneo_to_carter_classic_on_the_grid) with
    // the regularised law at eps = 1e-6 V: G = 1, nu = 0.28, mu = 0.4013, a
    // circle of 3.5 mm, F_x = -0.657 mu N held from a virgin start, first
    // order, 0.25 mm: from Cattaneo's shift through the transient to
    // Carter's steady state.
    let el = Elastic::from_shear(1e6, 0.28);
    let (n, a, mu): (f64, f64, f64) = (0.4705, 3.5e-3, 0.4013);
    let curv = 3.0 * n / (8.0 * el.contact_modulus() * a.powi(3));
    let curvatures = Curvatures { a: curv, b: curv };
    let shape = HertzShape::new(curvatures, el).unwrap();
    let step = 2.5e-4;
    let model = (FrictionLaw::Regularised, GridScheme::FirstOrder, 1e-6);
    let make = |solver| fixed_grid(&shape, (curvatures, el), n, (step, step), model, solver);
    let (mut cg, mut gs) = (make(GridSolver::Cg), make(GridSolver::GaussSeidel));
    let input = StepInput {
        patch: shape.patch(n).unwrap(),
        speed: 1.0,
        dt: step,
        friction: mu,
        characteristic: Default::default(),
        memory: None,
        force_x: -0.657 * mu * n,
        creepage_x: None,
        creepage_y: 0.0,
        spin: 0.0,
        position: 0.0,
    };
    let r = compare(&mut cg, &mut gs, &vec![input; 40]);
    eprintln!("Cattaneo to Carter: {r:?}, CG fallbacks {}", cg.fallbacks());
    assert!(r.creepage < 1e-6 && r.wear < 2e-6 && r.traction < 1e-4, "{r:?}");
    assert_eq!(cg.fallbacks(), 0);
}

#[test]
fn cg_steps_are_deterministic_and_the_look_ahead_changes_nothing() {
    // Bit for bit: the same run twice, and the next step's pressure
    // computed ahead on a second thread (step_ahead, as a passage runs)
    // against the steps one by one.
    let (mut one, _, shape) = paper_pair();
    let (mut two, _, _) = paper_pair();
    let (mut ahead, _, _) = paper_pair();
    let inputs = fig7_inputs(&shape, one.grid().dx, 20, 0.0, 0.0);
    for (n, input) in inputs.iter().enumerate() {
        let a = one.step(input).unwrap();
        let b = two.step(input).unwrap();
        let c = ahead.step_ahead(input, inputs.get(n + 1)).unwrap();
        assert_eq!(a, b, "step {n}: two runs differ");
        assert_eq!(a, c, "step {n}: the look-ahead changed the step");
    }
}
