//! Friction memory (CONTACT's: the coefficient of a material point relaxes
//! to the characteristic's value over a slip distance `d_c`) in the
//! tangential models: its limits (a vanishing distance is no memory, a
//! very long one keeps the static coefficient: the constant law), its
//! monotone effect in between, agreement of solvers, and the roll-slip of
//! a falling law settled by it on the fixed grid.
use crate::common;
use common::{STEEL, paper_coefficients, paper_shape, rel};
use corrugation::contact::fastsim::Fastsim;
use corrugation::contact::friction::{Characteristic, FrictionMemory};
use corrugation::contact::grid::GridSolver;
use corrugation::contact::transient::elastic::{ExactElastic, WinklerElastic};
use corrugation::contact::transient::{ElasticModel, StepSolver, Transient};
use corrugation::contact::{Creepage, EllipseMesh, PatchSolution, PressureShape, StepInput, TangentialSolver};
use std::f64::consts::PI;

const MU: f64 = 0.4;
const V: f64 = 27.78;
/// Polach's dry-rail law (A = 0.4, B = 0.6 s/m).
const FALLING: Characteristic = Characteristic::Exponential { ratio: 0.4, speed: 1.0 / 0.6 };

fn memory(distance: f64) -> Option<FrictionMemory> {
    Some(FrictionMemory { distance, floor: 0.01 })
}

fn input(dt: f64, xi: f64, ch: Characteristic, memory: Option<FrictionMemory>) -> StepInput {
    StepInput {
        patch: paper_shape(false).patch(1e5).unwrap(),
        speed: V,
        dt,
        friction: MU,
        characteristic: ch,
        memory,
        force_x: 0.0,
        creepage_x: Some(xi),
        creepage_y: 0.0,
        spin: 0.0,
        position: 0.0,
    }
}

/// The forces (N) of `steps` steps of steady rolling from a virgin start.
fn roll(solver: &mut dyn TangentialSolver, input: &StepInput, steps: usize) -> (Vec<f64>, PatchSolution) {
    solver.reset();
    let mut forces = Vec::new();
    let mut last = PatchSolution::default();
    for _ in 0..steps {
        last = solver.step(input).expect("converges");
        forces.push(last.force_x);
    }
    (forces, last)
}

/// With memory the coefficient at an element lies between the kept one and
/// the characteristic's: for a falling law from 1 (static) down to `A`, so
/// `A mu p3 h(|s|) <= |p| <= mu p3 h(|s|)` (regularised law: `h = (2/pi)
/// atan(|s|/eps)`; Coulomb: `h = 1` in slip, `|p| <= mu p3` in stick).
fn assert_bounds(sol: &PatchSolution, eps: Option<f64>) {
    for k in 0..sol.pressure.len() {
        let (t, q) = (sol.traction_x[k].hypot(sol.traction_y[k]), sol.slip_x[k].hypot(sol.slip_y[k]));
        let h = match eps {
            Some(e) => 2.0 / PI * (q / e).atan(),
            None if q > 0.0 => 1.0,
            None => {
                assert!(t <= MU * sol.pressure[k] * (1.0 + 1e-12), "stick element {k} beyond the bound");
                continue;
            }
        };
        let top = MU * sol.pressure[k] * h;
        assert!(t <= top * (1.0 + 1e-9) + 1e-6, "element {k}: |p| {t:e} above {top:e}");
        assert!(t >= 0.4 * top * (1.0 - 1e-9) - 1e-6, "element {k}: |p| {t:e} below {:e}", 0.4 * top);
    }
}

/// FASTSIM (each cell remembers its upstream neighbour's coefficient):
/// a vanishing memory distance gives the law without memory, a very long
/// one (1 km) the constant law (the static coefficient is never forgotten); in
/// between the saturated force grows with the distance.
#[test]
fn fastsim_memory_limits_and_monotone_effect() {
    let f = Fastsim::new(40, 40, PressureShape::Hertz, paper_coefficients(false), STEEL.shear_modulus());
    let patch = paper_shape(false).patch(1e5).unwrap();
    let at = |xi: f64, ch, m| {
        let s = f.solve_creepage_with(&patch, Creepage { x: xi, ..Default::default() }, (MU, ch, m), V);
        assert_bounds(&s, None);
        s.force_x
    };
    for xi in [-2e-3, -0.02, -0.2] {
        let plain = at(xi, FALLING, None);
        let constant = at(xi, Characteristic::Constant, None);
        assert!(rel(at(xi, FALLING, memory(1e-15)), plain) < 1e-8, "xi {xi}: vanishing memory");
        assert!(rel(at(xi, FALLING, memory(1e3)), constant) < 1e-4, "xi {xi}: long memory");
        let forces: Vec<f64> =
            [1e-7, 1e-6, 1e-5, 1e-4, 1e-3].iter().map(|&d| at(xi, FALLING, memory(d)).abs()).collect();
        assert!(forces.windows(2).all(|w| w[1] >= w[0] * (1.0 - 1e-12)), "xi {xi}: {forces:?}");
        assert!(forces[0] >= plain.abs() * (1.0 - 1e-12) && forces[4] <= constant.abs() * (1.0 + 1e-12));
    }
}

/// The exact model on the 0.5 mm fixed grid at 1 % creepage, just beyond
/// saturation, with Polach's law: without memory the rolling cycles
/// (roll-slip; the force swings by more than 5 % of N over the last 30
/// mm); with a memory of 0.1 mm it settles (the last 30 mm within 1e-6 of
/// N) above the memoryless mean, and both solvers give it; a memory of 1 km
/// gives the constant law's force.
#[test]
fn exact_grid_memory_settles_roll_slip() {
    let shape = paper_shape(false);
    let (eps, cell) = (1e-5, (0.5e-3, 0.5e-3));
    let grid = common::paper_convex_grid;
    let n = shape.patch(1e5).unwrap().normal_force;
    let dt = cell.0 / V;
    let (mut cg, mut gs) = (grid(GridSolver::Cg), grid(GridSolver::GaussSeidel));
    let range = |f: &[f64]| {
        let tail = &f[f.len() / 2..];
        let (lo, hi) = tail.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(*v), b.max(*v)));
        ((hi - lo) / n, tail.iter().sum::<f64>() / tail.len() as f64)
    };
    let (plain, _) = roll(&mut cg, &input(dt, -0.01, FALLING, None), 120);
    let (swing, plain_mean) = range(&plain);
    assert!(swing > 0.05, "no memory: swing {swing}");
    let (kept, sol) = roll(&mut cg, &input(dt, -0.01, FALLING, memory(1e-4)), 120);
    let (settled, mean) = range(&kept);
    assert!(settled < 1e-6, "memory 0.1 mm: swing {settled}");
    assert!(mean > plain_mean, "{mean} vs {plain_mean}");
    assert_bounds(&sol, Some(eps));
    let (other, _) = roll(&mut gs, &input(dt, -0.01, FALLING, memory(1e-4)), 120);
    assert!(rel(other[119], kept[119]) < 1e-6, "GS {} vs CG {}", other[119], kept[119]);
    let (long, _) = roll(&mut cg, &input(dt, -0.01, FALLING, memory(1e3)), 30);
    let (constant, _) = roll(&mut cg, &input(dt, -0.01, Characteristic::Constant, None), 30);
    assert!(rel(long[29], constant[29]) < 1e-4, "{} vs {}", long[29], constant[29]);
    // A constant characteristic ignores the memory, bit for bit.
    let (with, _) = roll(&mut cg, &input(dt, -3e-3, Characteristic::Constant, memory(1e-5)), 10);
    let (without, _) = roll(&mut cg, &input(dt, -3e-3, Characteristic::Constant, None), 10);
    assert_eq!(with, without);
}

/// The memory travels with the material: in full sliding (uniform slip,
/// 20 % creepage) with a long memory (1 mm) fresh material enters at the
/// leading edge (grid column 0) with the static coefficient and relaxes
/// towards Polach's value as it moves back through the patch, so along the
/// centre row `|p| / (mu p3)` falls from column to column, from near 1 to
/// near `r(V |xi|)`.
#[test]
fn memory_relaxes_from_the_leading_edge_backwards() {
    let cell = (0.5e-3, 0.5e-3);
    let mut grid = common::paper_convex_grid(GridSolver::GaussSeidel);
    let (_, sol) = roll(&mut grid, &input(cell.0 / V, -0.2, FALLING, memory(1e-3)), 40);
    let nx = grid.grid().nx;
    let centre = (0..sol.pressure.len()).max_by(|&a, &b| sol.pressure[a].total_cmp(&sol.pressure[b])).unwrap() / nx;
    let ratios: Vec<f64> = (0..nx)
        .map(|ix| centre * nx + ix)
        .filter(|&k| sol.pressure[k] > 0.0)
        .map(|k| sol.traction_x[k].hypot(sol.traction_y[k]) / (MU * sol.pressure[k]))
        .collect();
    assert!(ratios.len() > 10, "{ratios:?}");
    assert!(ratios.windows(2).all(|w| w[1] < w[0]), "falls from the leading edge: {ratios:?}");
    let sliding = FALLING.ratio(V * 0.2).0;
    assert!(ratios[0] > 0.9 && ratios[ratios.len() - 1] < sliding + 0.1, "{ratios:?} (sliding {sliding})");
}

/// The adapted mesh (the kept coefficient interpolated from the previous
/// patch as the earlier displacement is): Newton and Gauss-Seidel agree
/// with memory; a very long memory gives the constant law (exact and
/// simplified models).
#[test]
fn adapted_mesh_memory() {
    let shape = paper_shape(false);
    let (nx, eps) = (16, 1e-5);
    let mesh = EllipseMesh::new(nx, nx);
    let patch = shape.patch(1e5).unwrap();
    let exact = |solver| {
        let e = ExactElastic::new(&mesh, shape.aspect(), STEEL.shear_modulus(), STEEL.poisson_ratio);
        Transient::new(mesh.clone(), ElasticModel::Exact(Box::new(e)), PressureShape::Hertz, eps).with_solver(solver)
    };
    let c = paper_coefficients(false);
    let g = STEEL.shear_modulus();
    let winkler = WinklerElastic { l1_unit: 8.0 / (3.0 * c.c11 * g), l2_unit: 8.0 / (3.0 * c.c22 * g) };
    let mut simplified = Transient::new(mesh.clone(), ElasticModel::Winkler(winkler), PressureShape::Hertz, eps);
    let (mut newton, mut gs) = (exact(StepSolver::Newton), exact(StepSolver::GaussSeidel));
    let dt = 2.0 * patch.a / nx as f64 / V;
    let with = input(dt, -3e-3, FALLING, memory(1e-5));
    let (a, sa) = roll(&mut newton, &with, 32);
    let (b, _) = roll(&mut gs, &with, 32);
    assert!(rel(a[31], b[31]) < 1e-6, "Newton {} vs GS {}", a[31], b[31]);
    assert_bounds(&sa, Some(eps));
    let (plain, _) = roll(&mut newton, &input(dt, -3e-3, FALLING, None), 32);
    assert!(a[31].abs() > plain[31].abs(), "memory {} vs none {}", a[31], plain[31]);
    for solver in [&mut newton as &mut dyn TangentialSolver, &mut simplified] {
        let (long, _) = roll(solver, &input(dt, -0.02, FALLING, memory(1e3)), 32);
        let (constant, _) = roll(solver, &input(dt, -0.02, Characteristic::Constant, None), 32);
        assert!(rel(long[31], constant[31]) < 1e-4, "{} vs {}", long[31], constant[31]);
    }
}
