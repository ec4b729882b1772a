//! Convergence study of the exact transient model (issue 3): steady-state
//! creepage of the paper's concave patch at F_x = 20 kN after 2.5 contact
//! lengths, under mesh refinement and decreasing regularisation, against
//! CONTACT's exact value -1.242e-3 (scene a, steady rolling).
//! Run: `cargo run --release --example convergence`.
use corrugation::contact::transient::elastic::ExactElastic;
use corrugation::contact::transient::{ElasticModel, Transient};
use corrugation::contact::{EllipseMesh, PressureShape, StepInput, TangentialSolver};
use corrugation::hertz::{Curvatures, Elastic, HertzShape};

fn steady(nx: usize, ny: usize, eps: f64) -> (f64, f64) {
    let el = Elastic { young_modulus: 2.1e11, poisson_ratio: 0.3 };
    let shape = HertzShape::new(Curvatures::wheel_on_rail(0.5, -0.409, 0.3), el).unwrap();
    let patch = shape.patch(1e5).unwrap();
    let mesh = EllipseMesh::new(nx, ny);
    let e = ExactElastic::new(&mesh, shape.aspect(), el.shear_modulus(), el.poisson_ratio);
    let mut s = Transient::new(mesh, ElasticModel::Exact(Box::new(e)), PressureShape::Hertz, eps);
    let input = StepInput {
        patch,
        speed: 27.778,
        dt: 2e-4 / 27.778,
        friction: 0.4,
        characteristic: Default::default(),
        memory: None,
        force_x: 2e4,
        creepage_x: None,
        creepage_y: 0.0,
        spin: 0.0,
        position: 0.0,
    };
    let t = std::time::Instant::now();
    let mut xi = 0.0;
    for _ in 0..150 {
        xi = s.step(&input).unwrap().creepage.x;
    }
    (xi, t.elapsed().as_secs_f64() / 150.0)
}

fn main() {
    let reference = -1.242e-3;
    println!("mesh (nx x ny)  eps (m/s)  creepage     vs CONTACT  ms/step");
    let meshes: &[(usize, usize)] =
        if std::env::args().any(|a| a == "--eps-only") { &[] } else { &[(10, 4), (20, 8), (30, 12), (40, 16)] };
    for &(nx, ny) in meshes {
        let (xi, t) = steady(nx, ny, 1e-5);
        println!(
            "{nx:>3} x {ny:<3}       1e-5     {xi:.5e}  {:+.3} %   {:.1}",
            100.0 * (xi / reference - 1.0),
            1e3 * t
        );
    }
    for eps in [1e-4, 1e-5, 1e-6] {
        let (xi, t) = steady(30, 12, eps);
        println!(" 30 x 12        {eps:.0e}    {xi:.5e}  {:+.3} %   {:.1}", 100.0 * (xi / reference - 1.0), 1e3 * t);
    }
}
