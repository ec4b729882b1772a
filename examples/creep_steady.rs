//! Steady forces of a scene's contact against one input's offset about the
//! mean state (`corrugation::dynamics::coupling::creep_response::steady_forces`):
//! the steady creep curve that the creep response's zero-frequency limit
//! is the slope of.
//!
//! `cargo run --release --example creep_steady -- CONFIG INPUT(x|y|s|n) STEP_REL COUNT [set=SECTION.KEY=VALUE ...]`
//!
//! Prints `offset F_x F_y` for offsets `k STEP_REL scale`, `|k| <= COUNT`,
//! the scale that of `input_scale`.

use corrugation::build::creep_response as scene;
use corrugation::dynamics::coupling::creep_response::{Input, input_scale, steady_forces};

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    anyhow::ensure!(args.len() >= 4, "usage: creep_steady CONFIG INPUT STEP_REL COUNT [set=...]");
    let sets: Vec<String> = args[4..].iter().filter_map(|a| a.strip_prefix("set=").map(str::to_string)).collect();
    let sc = corrugation::config::load_file(std::path::Path::new(&args[0]), &sets)?.scene;
    let input = match args[1].as_str() {
        "x" => Input::CreepageX,
        "y" => Input::CreepageY,
        "s" => Input::Spin,
        _ => Input::NormalForce,
    };
    let (rel, count): (f64, i32) = (args[2].parse()?, args[3].parse()?);
    let mean = scene::mean_state(&sc, sc.loads.normal_force, sc.loads.longitudinal_force);
    let shape = scene::shape(&sc);
    let ex = scene::default_excitation(&sc, &shape, &mean)?;
    let scale = input_scale(&shape, &mean)?;
    let two_a = 2.0 * shape.patch(mean.normal_force)?.a;
    let settle: f64 = std::env::var("SETTLE").map_or(Ok(4.0), |v| v.parse())? * two_a;
    let mut solver = corrugation::build::build_solver(&sc, &shape);
    for k in -count..=count {
        let mut offset = [0.0; 4];
        offset[input.index()] = k as f64 * rel * scale[input.index()];
        let f = steady_forces(solver.as_mut(), &shape, &mean, (ex.step, ex.run_in, settle), offset)?;
        println!("{:.6e} {:.9e} {:.9e}", offset[input.index()], f[0], f[1]);
    }
    Ok(())
}
