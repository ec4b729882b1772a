//! Creep curves with the friction characteristics (issue 36; the book's
//! friction chapter): F_x / N against the longitudinal creepage for the
//! paper's convex patch at 100 km/h, N = 100 kN, mu = 0.4 at zero slip,
//! with FASTSIM (40 x 40) and the exact model on the 0.5 mm fixed grid, no
//! friction memory (60 steps of steady rolling under the prescribed
//! creepage; the last step's force, and the smallest and largest of the
//! last 20 where the rolling does not settle; nan where a step does not
//! converge, said on stderr). CSV on stdout:
//! `model,law,creepage,force_ratio,force_ratio_min,force_ratio_max`.
//!
//! `cargo run --release --example creep_curves > out/creep_curves.csv`

use corrugation::contact::fastsim::Fastsim;
use corrugation::contact::friction::{Characteristic, FrictionLaw};
use corrugation::contact::grid::spec::FixedGridSpec;
use corrugation::contact::grid::{FixedGrid, GridScheme, GridSolver};
use corrugation::contact::{Creepage, PressureShape, StepInput, TangentialSolver};
use corrugation::creep_coefficients::creep_coefficients;
use corrugation::hertz::{Curvatures, Elastic, HertzShape};

const MU: f64 = 0.4;
const V: f64 = 27.78;

fn main() {
    let el = Elastic { young_modulus: 2.1e11, poisson_ratio: 0.3 };
    let curv = Curvatures::wheel_on_rail(0.5, 0.409, 0.3);
    let shape = HertzShape::new(curv, el).expect("the paper's patch");
    let patch = shape.patch(1e5).expect("N > 0");
    let laws = [
        ("constant", Characteristic::Constant),
        ("Polach dry (A 0.4; v_c 1.67 m/s)", Characteristic::Exponential { ratio: 0.4, speed: 1.0 / 0.6 }),
        ("rational (A 0.4; v_c 1.67 m/s)", Characteristic::Rational { ratio: 0.4, speed: 1.0 / 0.6 }),
        ("modifier (A 1.25; v_c 0.1 m/s)", Characteristic::Exponential { ratio: 1.25, speed: 0.1 }),
    ];
    let xis: Vec<f64> = (0..=40).map(|i| 1e-4 * 10f64.powf(i as f64 / 10.0)).collect();
    println!("model,law,creepage,force_ratio,force_ratio_min,force_ratio_max");
    let coefficients = creep_coefficients(shape.aspect(), el.poisson_ratio).expect("aspect in range");
    let fastsim = Fastsim::new(40, 40, PressureShape::Hertz, coefficients, el.shear_modulus());
    for (name, ch) in laws {
        for &xi in &xis {
            let s = fastsim.solve_creepage_with(&patch, Creepage { x: -xi, ..Default::default() }, (MU, ch, None), V);
            let f = s.force_x / patch.normal_force;
            println!("fastsim,{name},{xi:e},{f},{f},{f}");
        }
    }
    let cell = (0.5e-3, 0.5e-3);
    let spec = FixedGridSpec::unaligned(
        (curv, el),
        cell,
        (patch.a, patch.b),
        (FrictionLaw::Regularised, GridScheme::SecondOrder, 1e-5),
        GridSolver::Auto,
    );
    let mut grid = FixedGrid::new(spec);
    for (name, ch) in laws {
        for &xi in xis.iter().step_by(2) {
            let input = StepInput {
                patch,
                speed: V,
                dt: cell.0 / V,
                friction: MU,
                characteristic: ch,
                memory: None,
                force_x: 0.0,
                creepage_x: Some(-xi),
                creepage_y: 0.0,
                spin: 0.0,
                position: 0.0,
            };
            grid.reset();
            let forces: Result<Vec<f64>, _> =
                (0..60).map(|_| grid.step(&input).map(|s| s.force_x / patch.normal_force)).collect();
            let forces = match forces {
                Ok(f) => f,
                Err(e) => {
                    eprintln!("{name} at creepage {xi:e}: {e}");
                    println!("exact grid,{name},{xi:e},nan,nan,nan");
                    continue;
                }
            };
            let tail = &forces[40..];
            let (lo, hi) = tail.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), f| (a.min(*f), b.max(*f)));
            println!("exact grid,{name},{xi:e},{},{lo},{hi}", forces[59]);
        }
    }
}
