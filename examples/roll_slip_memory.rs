//! Roll-slip under a falling friction law with and without friction memory
//! (issue 36; the book's friction chapter): the exact model on the fixed
//! grid at a prescribed creepage near saturation, the paper's convex patch
//! at 100 km/h, N = 100 kN, mu = 0.4 at zero slip, Polach's dry law,
//! regularised law (eps 1e-5 m/s), second-order scheme. For each memory
//! distance `d_c` (0: none; 1 um is CONTACT's default) and element size,
//! 60 mm of steady rolling; the force's mean, smallest and largest over the
//! last 30 mm. CSV on stdout:
//! `creepage,d_c,dx,mean,min,max,steps`.
//!
//! `cargo run --release --example roll_slip_memory [creepage ...] >
//! out/roll_slip_memory.csv` (creepages 0.01 and 0.04 by default; the
//! environment's `DX` and `DC`, comma-separated lists in m, replace the
//! element sizes 0.5 and 0.25 mm and the distances 0, 1, 10, 100 um).

use corrugation::contact::friction::{Characteristic, FrictionLaw, FrictionMemory};
use corrugation::contact::grid::spec::FixedGridSpec;
use corrugation::contact::grid::{FixedGrid, GridScheme, GridSolver};
use corrugation::contact::{StepInput, TangentialSolver};
use corrugation::hertz::{Curvatures, Elastic, HertzShape};

const MU: f64 = 0.4;
const V: f64 = 27.78;

fn main() {
    let el = Elastic { young_modulus: 2.1e11, poisson_ratio: 0.3 };
    let curv = Curvatures::wheel_on_rail(0.5, 0.409, 0.3);
    let shape = HertzShape::new(curv, el).expect("the paper's patch");
    let patch = shape.patch(1e5).expect("N > 0");
    let polach = Characteristic::Exponential { ratio: 0.4, speed: 1.0 / 0.6 };
    let args: Vec<f64> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    let creepages = if args.is_empty() { vec![0.01, 0.04] } else { args };
    let list = |key: &str, default: &[f64]| -> Vec<f64> {
        std::env::var(key).map_or(default.to_vec(), |v| v.split(',').filter_map(|x| x.trim().parse().ok()).collect())
    };
    let (sizes, distances) = (list("DX", &[0.5e-3, 0.25e-3]), list("DC", &[0.0, 1e-6, 1e-5, 1e-4]));
    println!("creepage,d_c,dx,mean,min,max,steps");
    for &xi in &creepages {
        for &dx in &sizes {
            let spec = FixedGridSpec::unaligned(
                (curv, el),
                (dx, dx),
                (patch.a, patch.b),
                (FrictionLaw::Regularised, GridScheme::SecondOrder, 1e-5),
                GridSolver::Auto,
            );
            let mut grid = FixedGrid::new(spec);
            for &d_c in &distances {
                let memory = (d_c > 0.0).then_some(FrictionMemory { distance: d_c, floor: 0.01 });
                let input = StepInput {
                    patch,
                    speed: V,
                    dt: dx / V,
                    friction: MU,
                    characteristic: polach,
                    memory,
                    force_x: 0.0,
                    creepage_x: Some(-xi),
                    creepage_y: 0.0,
                    spin: 0.0,
                    position: 0.0,
                };
                grid.reset();
                let steps = (0.06 / dx).round() as usize;
                let forces: Result<Vec<f64>, _> =
                    (0..steps).map(|_| grid.step(&input).map(|s| s.force_x / patch.normal_force)).collect();
                let forces = match forces {
                    Ok(f) => f,
                    Err(e) => {
                        eprintln!("creepage {xi}, d_c {d_c:e}, dx {dx:e}: {e}");
                        println!("{xi:e},{d_c:e},{dx:e},nan,nan,nan,{steps}");
                        continue;
                    }
                };
                let tail = &forces[steps / 2..];
                let mean = tail.iter().sum::<f64>() / tail.len() as f64;
                let (lo, hi) = tail.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), f| (a.min(*f), b.max(*f)));
                println!("{xi:e},{d_c:e},{dx:e},{mean},{lo},{hi},{steps}");
            }
        }
    }
}
