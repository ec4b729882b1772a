//! The fixed-grid exact model (CONTACT's discretisation) against Hertz,
//! Cattaneo, CONTACT's scene c ("from Cattaneo to Carter"), Kalker's
//! classic case, exact Coulomb as the limit of the regularised law, and its
//! invariants: the earlier displacement by shifting, force balance, the
//! friction bound, wear volume.
use crate::common;
use common::{STEEL, paper_shape, peak, rel};
use corrugation::build::{build_deposit, build_solver, derive};
use corrugation::config::load_str;
use corrugation::contact::friction::FrictionLaw;
use corrugation::contact::grid::convolution::{FftConvolution, FftScratch, ToeplitzKernel};
use corrugation::contact::grid::normal::NormalProducts;
use corrugation::contact::grid::{Alignment, FixedGrid, GridScheme, GridSolver, PotentialGrid, normal};
use corrugation::contact::influence::{Rect, influence};
use corrugation::contact::{StepInput, TangentialSolver};
use corrugation::hertz::{Curvatures, Elastic, HertzShape};
use corrugation::passage::run_passage;

/// The friction law, difference scheme and regularisation of a test grid.
type Model = (FrictionLaw, GridScheme, f64);

/// A fixed grid of `cell` elements for `curvatures` and `elastic`, sized for
/// the Hertz patch at `n_max` N.
fn grid_solver(
    shape: &HertzShape,
    curvatures: Curvatures,
    elastic: Elastic,
    n_max: f64,
    cell: (f64, f64),
    model: Model,
) -> FixedGrid {
    common::fixed_grid(shape, (curvatures, elastic), n_max, cell, model, GridSolver::Auto)
}

fn paper_curvatures(concave: bool) -> Curvatures {
    Curvatures::wheel_on_rail(0.5, if concave { -0.409 } else { 0.409 }, 0.3)
}

/// Rolls at constant N = 100 kN and F_x from a virgin start; the creepage of
/// every step.
fn roll(solver: &mut FixedGrid, shape: &HertzShape, force_x: f64, steps: usize) -> Vec<f64> {
    let patch = shape.patch(1e5).unwrap();
    let dx = solver.grid().dx;
    let speed = 27.778;
    let input = StepInput {
        patch,
        speed,
        dt: dx / speed,
        friction: 0.4,
        characteristic: Default::default(),
        memory: None,
        force_x,
        creepage_x: None,
        creepage_y: 0.0,
        spin: 0.0,
        position: 0.0,
    };
    solver.reset();
    (0..steps)
        .map(|_| {
            let sol = solver.step(&input).expect("converges");
            // Force balance and the friction bound on every element.
            assert!(rel(sol.force_x, force_x) < 1e-7, "force {} vs {force_x}", sol.force_x);
            for k in 0..sol.pressure.len() {
                let t = sol.traction_x[k].hypot(sol.traction_y[k]);
                assert!(
                    t <= 0.4 * sol.pressure[k] * (1.0 + 1e-12),
                    "friction bound at {k}: |p| = {t:e}, mu p3 = {:e}",
                    0.4 * sol.pressure[k]
                );
            }
            sol.creepage.x
        })
        .collect()
}

#[test]
fn quadratic_gap_gives_hertz_in_the_limit() {
    // The discrete normal problem of the quadratic gap A x^2 + B y^2 against
    // Hertz (concave reading, N = 100 kN): the approach, the peak pressure
    // and the extent of the contact area converge to Hertz's as the grid is
    // refined.
    let shape = paper_shape(true);
    let curv = paper_curvatures(true);
    let hz = shape.patch(1e5).unwrap();
    let mut errors = Vec::new();
    for (dx, dy) in [(4e-4, 1e-3), (2e-4, 5e-4), (1e-4, 2.5e-4)] {
        let grid = PotentialGrid::covering(hz.a, hz.b, (dx, dy), 2, Alignment::default(), Alignment::default());
        let kernel = ToeplitzKernel::normal(&grid, STEEL.shear_modulus(), STEEL.poisson_ratio);
        let conv = FftConvolution::new(&kernel);
        let (xs, ys) = grid.centres();
        let h: Vec<f64> = xs.iter().zip(&ys).map(|(x, y)| curv.a * x * x + curv.b * y * y).collect();
        let plain =
            normal::solve(NormalProducts::Full(&conv, None), &mut FftScratch::default(), &h, grid.area(), 1e5, None)
                .unwrap();
        // The FFT preconditioner (the default): the same solution in fewer
        // iterations.
        let inverse = FftConvolution::circulant_inverse(&kernel);
        let sol = normal::solve(
            NormalProducts::Full(&conv, Some(&inverse)),
            &mut FftScratch::default(),
            &h,
            grid.area(),
            1e5,
            None,
        )
        .unwrap();
        let p_max = sol.pressure.iter().fold(0.0f64, |m, v| m.max(*v));
        let diff = sol.pressure.iter().zip(&plain.pressure).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        eprintln!("dx {dx:.1e}: iterations {} plain, {} preconditioned", plain.iterations, sol.iterations);
        assert!(diff < 1e-8 * p_max, "dx {dx:.1e}: preconditioned pressure {diff:e} off");
        assert!(rel(sol.approach, plain.approach) < 1e-9);
        assert!(sol.iterations < plain.iterations, "{} vs {}", sol.iterations, plain.iterations);
        let (mut a, mut b) = (0.0f64, 0.0f64);
        for k in 0..grid.len() {
            if sol.pressure[k] > 0.0 {
                a = a.max(xs[k].abs() + 0.5 * dx);
                b = b.max(ys[k].abs() + 0.5 * dy);
            }
        }
        let e = [rel(sol.approach, hz.approach), rel(p_max, hz.p0), (a - hz.a).abs() / dx, (b - hz.b).abs() / dy];
        eprintln!(
            "dx {dx:.1e}: approach {:.5e} vs {:.5e}, p_max {:.5e} vs {:.5e}, a {a:.4e} vs {:.4e}, b {b:.4e} vs {:.4e}",
            sol.approach, hz.approach, p_max, hz.p0, hz.a, hz.b
        );
        errors.push(e);
    }
    // The finest grid: approach within 0.01 %, peak pressure 0.02 %, the
    // contact area's extent within one element.
    let fine = errors[2];
    assert!(fine[0] < 1e-4 && fine[1] < 2e-4 && fine[2] <= 1.0 && fine[3] <= 1.0, "{fine:?}");
    // Converging: each refinement reduces the approach error; the peak
    // pressure (sampled at the element centres) is within 0.2 % on every grid.
    assert!(errors[1][0] < errors[0][0] && errors[2][0] < errors[1][0], "{errors:?}");
    assert!(errors.iter().all(|e| e[1] < 2e-3), "{errors:?}");
}

#[test]
fn earlier_displacement_by_shifting_is_the_field_one_element_ahead() {
    // On a uniform grid, the displacement field of the previous tractions
    // shifted by one column equals that field evaluated at x + dx (what the
    // adapted model computes point by point): the shift transport is exact.
    let grid = PotentialGrid { nx: 14, ny: 9, dx: 2e-4, dy: 5e-4, x_front: 1.4e-3, y_low: -2.25e-3 };
    let (g, nu) = (STEEL.shear_modulus(), STEEL.poisson_ratio);
    let kernel = ToeplitzKernel::tangential(&grid, g, nu);
    let conv = FftConvolution::new(&kernel);
    let n = grid.len();
    let px: Vec<f64> = (0..n).map(|k| 1e8 * (k as f64 * 0.37).sin()).collect();
    let py: Vec<f64> = (0..n).map(|k| 3e7 * (k as f64 * 0.71).cos()).collect();
    let (mut ux, mut uy) = (vec![0.0; n], vec![0.0; n]);
    conv.tangential(&mut FftScratch::default(), (&px, &py), (&mut ux, &mut uy));
    let scale = ux.iter().chain(&uy).fold(0.0f64, |m, v| m.max(v.abs()));
    for iy in 0..grid.ny {
        for ix in 1..grid.nx {
            let (x, y) = (grid.x(ix) + grid.dx, grid.y(iy));
            let (mut fx, mut fy) = (0.0, 0.0);
            for j in 0..n {
                let rect = Rect { x: grid.x(j % grid.nx), y: grid.y(j / grid.nx), hx: 1e-4, hy: 2.5e-4 };
                let c = influence(&rect, x, y, g, nu);
                fx += c.xx * px[j] + c.xy * py[j];
                fy += c.xy * px[j] + c.yy * py[j];
            }
            let shifted = iy * grid.nx + ix - 1;
            assert!((ux[shifted] - fx).abs() < 1e-12 * scale && (uy[shifted] - fy).abs() < 1e-12 * scale);
        }
    }
}

/// CONTACT scene c (shared reference: N = 100 kN, F_x = 20 kN, 0.2 mm steps,
/// first-order difference, Coulomb friction).
struct SceneC {
    concave: bool,
    /// CONTACT's element (dx, dy) (m).
    cell: (f64, f64),
    /// Rigid shift at rest (m).
    shift: f64,
    /// Creepage at the first rolling step.
    first: f64,
    /// Peak |creepage| and where it occurs (m rolled).
    peak: (f64, f64),
    /// Steady creepage.
    steady: f64,
    /// Steps to the steady state.
    steps: usize,
}

const SCENE_C: [SceneC; 2] = [
    SceneC {
        concave: true,
        cell: (2e-4, 8e-4),
        shift: -1.436e-5,
        first: -0.721e-3,
        peak: (1.380e-3, 7.6e-3),
        steady: -1.245e-3,
        steps: 180,
    },
    SceneC {
        concave: false,
        cell: (2e-4, 4e-4),
        shift: -2.057e-5,
        first: -0.959e-3,
        peak: (2.016e-3, 10.0e-3),
        steady: -1.748e-3,
        steps: 240,
    },
];

/// Scene c rolled on a grid of `cell` with `law` and `scheme`: (shift at
/// rest (m), first step, (peak, its position (m)), steady creepage).
fn scene_c(case: &SceneC, cell: (f64, f64), law: FrictionLaw, scheme: GridScheme) -> (f64, f64, (f64, f64), f64) {
    let shape = paper_shape(case.concave);
    let mut solver = grid_solver(&shape, paper_curvatures(case.concave), STEEL, 1e5, cell, (law, scheme, 1e-5));
    let h = roll(&mut solver, &shape, 2e4, case.steps + 1);
    let got = (h[0] * cell.0, h[1], peak(&h, cell.0), h[case.steps]);
    eprintln!("concave {} {law:?} {scheme:?} {cell:?}: shift, first, (peak, at), steady {got:?}", case.concave);
    got
}

#[test]
fn contact_scene_c_on_contacts_own_grid() {
    // With CONTACT's discretisation (first-order difference, its grid), both
    // friction laws reproduce CONTACT's shift at rest, first step, peak and
    // steady creepage within 0.5 %, the peak at the same step.
    for case in &SCENE_C {
        for law in [FrictionLaw::Coulomb, FrictionLaw::Regularised] {
            let (shift, first, (pv, pa), steady) = scene_c(case, case.cell, law, GridScheme::FirstOrder);
            assert!(rel(shift, case.shift) < 5e-3, "shift {shift} vs {}", case.shift);
            assert!(rel(first, case.first) < 5e-3, "first step {first} vs {}", case.first);
            assert!(rel(pv, case.peak.0) < 5e-3, "peak {pv} vs {:?}", case.peak);
            assert!((pa - case.peak.1).abs() <= case.cell.0 + 1e-9, "peak at {pa} vs {:?}", case.peak);
            assert!(rel(steady, case.steady) < 5e-3, "steady {steady} vs {}", case.steady);
        }
    }
}

#[test]
fn contact_scene_c_at_the_default_grid() {
    // The default discretisation (second-order difference, 0.2 x 0.5 mm)
    // against CONTACT's 0.2 mm first-order run. Shift and first step (a
    // first-order step in both) within 1 %. CONTACT's later creepages are
    // biased low by its first-order difference: its steady creepage rises by
    // 0.8-1.1 % from 0.2 to 0.025 mm (reference README, "Grid convergence"),
    // so the steady creepage is held to that grid limit, 1.0095 times the
    // 0.2 mm value, within 0.5 %; the peak, where the first-order bias is
    // larger (the same grid with the first-order difference gives CONTACT's
    // peak within 0.2 %, test above), within 2.5 %.
    for case in &SCENE_C {
        for law in [FrictionLaw::Coulomb, FrictionLaw::Regularised] {
            let (shift, first, (pv, pa), steady) = scene_c(case, (2e-4, 5e-4), law, GridScheme::SecondOrder);
            assert!(rel(shift, case.shift) < 0.01, "shift {shift} vs {}", case.shift);
            assert!(rel(first, case.first) < 0.01, "first step {first} vs {}", case.first);
            assert!(rel(pv, case.peak.0) < 0.025, "peak {pv} vs {:?}", case.peak);
            assert!((pa - case.peak.1).abs() <= 0.6e-3, "peak at {pa} vs {:?}", case.peak);
            assert!(rel(steady, 1.0095 * case.steady) < 0.005, "steady {steady} vs {}", case.steady);
        }
    }
}

#[test]
fn kalker_cattaneo_to_carter_classic_on_the_grid() {
    // Kalker 1990 sec. 5.2.2.5 (CONTACT `catt_to_cart`, 0.25 mm grid): G = 1,
    // nu = 0.28, mu = 0.4013, N = 0.4705, circle a = 3.5 mm, F_x = -0.657 mu
    // N held from the start: |creepage| 1.824e-3 after 0.25 mm, peak
    // 3.403e-3 near 3.4 mm, 3.101e-3 steady. Coulomb, first order, 0.25 mm:
    // within 1 %.
    let el = Elastic::from_shear(1e6, 0.28);
    let (n, a, mu): (f64, f64, f64) = (0.4705, 3.5e-3, 0.4013);
    let curv = 3.0 * n / (8.0 * el.contact_modulus() * a.powi(3));
    let curvatures = Curvatures { a: curv, b: curv };
    let shape = HertzShape::new(curvatures, el).unwrap();
    let patch = shape.patch(n).unwrap();
    let step = 2.5e-4;
    let mut solver =
        grid_solver(&shape, curvatures, el, n, (step, step), (FrictionLaw::Coulomb, GridScheme::FirstOrder, 1e-6));
    let input = StepInput {
        patch,
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
    let h: Vec<f64> = (0..61).map(|_| solver.step(&input).unwrap().creepage.x).collect();
    let (pv, pa) = peak(&h, step);
    eprintln!("classic: first {:.4e} peak {pv:.4e} at {pa:.3e} steady {:.4e}", h[1], h[60]);
    assert!(rel(h[1].abs(), 1.824e-3) < 0.01);
    assert!(rel(pv, 3.403e-3) < 0.01 && (pa - 3.4e-3).abs() <= 0.5e-3);
    assert!(rel(h[60].abs(), 3.101e-3) < 0.01);
}

#[test]
fn coulomb_is_the_limit_of_the_regularised_law() {
    // Scene c (concave) on a coarse grid: the regularised creepage history
    // approaches the exact Coulomb one as eps falls, about linearly.
    let shape = paper_shape(true);
    let cell = (4e-4, 1e-3);
    let run = |law, eps| {
        let mut s = grid_solver(&shape, paper_curvatures(true), STEEL, 1e5, cell, (law, GridScheme::SecondOrder, eps));
        roll(&mut s, &shape, 2e4, 40)
    };
    let coulomb = run(FrictionLaw::Coulomb, 1e-5);
    let diffs: Vec<f64> = [1e-3, 1e-4, 1e-5, 1e-6]
        .iter()
        .map(|&eps| {
            let h = run(FrictionLaw::Regularised, eps);
            h.iter().zip(&coulomb).skip(1).map(|(a, b)| rel(*a, *b)).fold(0.0, f64::max)
        })
        .collect();
    eprintln!("largest relative creepage difference from Coulomb at eps 1e-3..1e-6: {diffs:?}");
    for w in diffs.windows(2) {
        assert!(w[1] < 0.5 * w[0], "converging to Coulomb: {diffs:?}");
    }
    assert!(diffs[3] < 1e-3, "{diffs:?}");
}

#[test]
fn wear_volume_is_the_time_integral_of_the_patch_wear_rate() {
    // paper_normal_15mm on a coarse fixed grid: the volume deposited on the
    // rail equals sum dt * (wear rate integrated over the patch) over the
    // steps whose interval is deposited, to rounding.
    // A rail grid under the whole passage, so that no wear falls beside it.
    let set = [
        "contact.model=exact-transient",
        "contact.grid=fixed",
        "contact.dx=4e-4",
        "contact.dy=1e-3",
        "passage.step_length=4e-4",
        "rail.x_min=-0.025",
        "rail.x_max=0.05",
    ];
    let r = load_str(include_str!("../configs/paper_normal_15mm.toml"), "n15", &set.map(String::from)).unwrap();
    let d = derive(&r.scene);
    let mut solver = build_solver(&r.scene, &d.shape);
    let dep = build_deposit(&solver.elements());
    let res = run_passage(&d.passage, &d.shape, solver.as_mut(), dep.as_ref(), &d.grid, false, &mut |_, _| {}).unwrap();
    let deposited = res.wear.sum() * d.grid.dx * d.grid.dy;
    let dt = d.passage.dt();
    let integral: f64 = res.history.wear_volume_rate.iter().skip(1).sum::<f64>() * dt;
    eprintln!("deposited {deposited:.6e} m^3, time integral {integral:.6e} m^3");
    assert!(rel(deposited, integral) < 1e-12, "{deposited} vs {integral}");
}

#[test]
fn higher_order_differences_approach_contacts_grid_limit() {
    // Steady rolling (concave, N = 100 kN, F_x = 20 kN) on 0.4 x 0.8 mm
    // elements: the wear integral INT p3 |s| / V dA against CONTACT's grid
    // limit, 63.05 N (reference README, "Grid convergence": Richardson of
    // 0.2 ... 0.025 mm). The first-order difference (CONTACT's) is some 16 %
    // low at this element, the second-order 1.9 %, the third-order 0.5 %.
    let shape = paper_shape(true);
    let patch = shape.patch(1e5).unwrap();
    let cell = (4e-4, 8e-4);
    let integral = |scheme| {
        let mut solver =
            grid_solver(&shape, paper_curvatures(true), STEEL, 1e5, cell, (FrictionLaw::Regularised, scheme, 1e-5));
        roll(&mut solver, &shape, 2e4, 90);
        let input = StepInput {
            patch,
            speed: 27.778,
            dt: cell.0 / 27.778,
            friction: 0.4,
            characteristic: Default::default(),
            memory: None,
            force_x: 2e4,
            creepage_x: None,
            creepage_y: 0.0,
            spin: 0.0,
            position: 0.0,
        };
        let sol = solver.step(&input).unwrap();
        let area = cell.0 * cell.1;
        (0..sol.pressure.len()).map(|k| sol.pressure[k] * sol.slip_x[k].hypot(sol.slip_y[k])).sum::<f64>() * area
            / 27.778
    };
    let errors: Vec<f64> = [GridScheme::FirstOrder, GridScheme::SecondOrder, GridScheme::ThirdOrder]
        .map(|s| integral(s) / 63.05 - 1.0)
        .to_vec();
    eprintln!("wear integral at 0.4 mm against CONTACT's limit, first / second / third order: {errors:?}");
    assert!(errors[0] < -0.10, "{errors:?}");
    assert!(errors[1].abs() < 0.025, "{errors:?}");
    assert!(errors[2].abs() < 0.01, "{errors:?}");
}
