//! Steady rolling on the fixed grid (CONTACT's scene c, concave reading):
//! from a Cattaneo start, roll at constant N and F_x until steady, and print
//! the creepage and the wear integral `INT p3 |s| / V dA` (N) of the last
//! step, for the grid-convergence study of the book (docs/src/theory/fixed-grid.md).
//!
//! `cargo run --release --example grid_steady -- DX DY [N F_X ROLLED LAW SCHEME TOLERANCE SOLVER]`
//! (m, m, N, N, m, regularised|coulomb, first-|second-|third-order, units of eps,
//! auto|cg|gauss-seidel);
//! with `HISTORY=1` in the environment, every step's creepage and sweeps on stderr.

use corrugation::contact::friction::FrictionLaw;
use corrugation::contact::grid::spec::FixedGridSpec;
use corrugation::contact::grid::{FixedGrid, GridScheme, GridSolver};
use corrugation::contact::{StepInput, TangentialSolver};
use corrugation::hertz::{Curvatures, Elastic, HertzShape};
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let num = |i: usize, default: f64| args.get(i).map_or(default, |a| a.parse().expect("a number"));
    let (dx, dy) = (num(0, 2e-4), num(1, 8e-4));
    let (n, fx, rolled) = (num(2, 1e5), num(3, 2e4), num(4, 0.036));
    let law = if args.get(5).map(String::as_str) == Some("coulomb") {
        FrictionLaw::Coulomb
    } else {
        FrictionLaw::Regularised
    };
    let scheme = match args.get(6).map(String::as_str) {
        Some("first-order") => GridScheme::FirstOrder,
        Some("third-order") => GridScheme::ThirdOrder,
        _ => GridScheme::SecondOrder,
    };
    let elastic = Elastic { young_modulus: 2.1e11, poisson_ratio: 0.3 };
    let curvatures = Curvatures::wheel_on_rail(0.5, -0.409, 0.3);
    let shape = HertzShape::new(curvatures, elastic).unwrap();
    let patch = shape.patch(n).unwrap();
    let solver = match args.get(8).map(String::as_str) {
        Some("cg") => GridSolver::Cg,
        Some("gauss-seidel") => GridSolver::GaussSeidel,
        _ => GridSolver::Auto,
    };
    let spec =
        FixedGridSpec::unaligned((curvatures, elastic), (dx, dy), (patch.a, patch.b), (law, scheme, 1e-5), solver);
    let tolerance = num(7, corrugation::contact::grid::spec::GRID_TOLERANCE);
    let mut solver = FixedGrid::new(spec).with_tolerance(tolerance);
    let speed = 27.778;
    let input = StepInput {
        patch,
        speed,
        dt: dx / speed,
        friction: 0.4,
        characteristic: Default::default(),
        memory: None,
        force_x: fx,
        creepage_x: None,
        creepage_y: 0.0,
        spin: 0.0,
        position: 0.0,
    };
    let steps = (rolled / dx).round() as usize;
    let clock = Instant::now();
    let mut sweeps = 0;
    let mut in_contact = 0;
    let mut last = None;
    for n in 0..=steps {
        let sol = solver.step(&input).unwrap_or_else(|e| panic!("{e}"));
        if std::env::var("HISTORY").is_ok() {
            eprintln!("{:.2} mm {:.6e} sweeps {}", n as f64 * dx * 1e3, -sol.creepage.x, sol.iterations);
        }
        sweeps += sol.iterations;
        in_contact = sol.pressure.iter().filter(|p| **p > 0.0).count();
        last = Some(sol);
    }
    let sol = last.unwrap();
    let area = dx * dy;
    let wear: f64 = (0..sol.pressure.len()).map(|k| sol.pressure[k] * sol.slip_x[k].hypot(sol.slip_y[k])).sum::<f64>()
        * area
        / speed;
    let g = solver.grid();
    println!(
        "dx {:.4} mm dy {:.4} mm grid {}x{} in contact {} steps {} creepage {:.6e} wear_int {:.6} N sweeps/step {:.1} ms/step {:.2} fallbacks {}",
        dx * 1e3,
        dy * 1e3,
        g.nx,
        g.ny,
        in_contact,
        steps + 1,
        -sol.creepage.x,
        wear,
        sweeps as f64 / (steps + 1) as f64,
        clock.elapsed().as_secs_f64() * 1e3 / (steps + 1) as f64,
        solver.fallbacks()
    );
}
