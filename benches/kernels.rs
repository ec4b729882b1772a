//! Benchmarks of the kernels (issue: "criterion benchmarks for one FASTSIM
//! solve (20 x 20 mesh) and the wear interpolation of one step"), plus a
//! whole paper_normal_30mm FASTSIM passage. Run: `cargo bench --bench kernels`.
use corrugation::build::{build_deposit, build_solver, derive};
use corrugation::config::load_str;
use corrugation::contact::fastsim::Fastsim;
use corrugation::contact::friction::FrictionLaw;
use corrugation::contact::grid::convolution::{FftConvolution, FftScratch, ToeplitzKernel};
use corrugation::contact::grid::spec::FixedGridSpec;
use corrugation::contact::grid::symmetric::{SymmetricConvolution, SymmetricScratch};
use corrugation::contact::grid::{FixedGrid, GridScheme, GridSolver};
use corrugation::contact::transient::elastic::ExactElastic;
use corrugation::contact::transient::{ElasticModel, StepSolver, Transient};
use corrugation::contact::{Creepage, EllipseMesh, PressureShape, StepInput, TangentialSolver};
use corrugation::creep_coefficients::creep_coefficients;
use corrugation::dynamics::model::places::Places;
use corrugation::dynamics::track::TrackConfig;
use corrugation::dynamics::track::discrete::DiscreteTrack;
use corrugation::dynamics::track::discrete3::Discrete3;
use corrugation::dynamics::track::layout::{Layout, LayoutSpec, Spacing, Spread};
use corrugation::hertz::{Curvatures, Elastic, HertzShape};
use corrugation::passage::run_passage;
use corrugation::rail_grid::RailGrid;
use corrugation::wear::{PatchWear, WearDeposit, archard_rates};
use criterion::{Criterion, criterion_group, criterion_main};
use ndarray::Array2;
use std::hint::black_box;

fn paper() -> (HertzShape, Fastsim) {
    let el = Elastic { young_modulus: 2.1e11, poisson_ratio: 0.3 };
    let shape = HertzShape::new(Curvatures::wheel_on_rail(0.5, -0.409, 0.3), el).unwrap();
    let c = creep_coefficients(shape.aspect(), 0.3).unwrap();
    (shape, Fastsim::new(20, 20, PressureShape::Parabolic, c, el.shear_modulus()))
}

fn fastsim(c: &mut Criterion) {
    let (shape, f) = paper();
    let patch = shape.patch(1e5).unwrap();
    let input = StepInput {
        patch,
        speed: 27.78,
        dt: 0.0,
        friction: 0.4,
        characteristic: Default::default(),
        memory: None,
        force_x: 2e4,
        creepage_x: None,
        creepage_y: 0.0,
        spin: 0.0,
        position: 0.0,
    };
    c.bench_function("fastsim_20x20_force_control", |b| b.iter(|| f.solve_force(black_box(&input)).unwrap()));
    c.bench_function("fastsim_20x20_creepage_control", |b| {
        b.iter(|| f.solve_creepage(black_box(&patch), Creepage { x: -1.3e-3, ..Default::default() }, 0.4, 27.78))
    });
}

fn wear_step(c: &mut Criterion) {
    let (shape, f) = paper();
    let patch = shape.patch(1e5).unwrap();
    let input = StepInput {
        patch,
        speed: 27.78,
        dt: 0.0,
        friction: 0.4,
        characteristic: Default::default(),
        memory: None,
        force_x: 2e4,
        creepage_x: None,
        creepage_y: 0.0,
        spin: 0.0,
        position: 0.0,
    };
    let rates = archard_rates(3.4e-14, &f.solve_force(&input).unwrap());
    let mesh = EllipseMesh::new(20, 20);
    let dep = WearDeposit::new(&mesh);
    let grid = RailGrid::new(0.0, 0.06, 1e-4, 0.012, 2.5e-4);
    let mut w = Array2::zeros((grid.ny, grid.nx));
    let from = PatchWear { x_c: 0.03, a: patch.a, b: patch.b, rates: &rates };
    let to = PatchWear { x_c: 0.0302, a: patch.a, b: patch.b, rates: &rates };
    c.bench_function("wear_step_20x20_4substeps_paper_grid", |b| {
        b.iter(|| dep.accumulate(&grid, &mut w, &from, &to, 7.2e-6, 4))
    });
    c.bench_function("wear_triangulation_20x20", |b| b.iter(|| WearDeposit::new(black_box(&mesh))));
}

/// One exact-transient step in steady rolling (paper patch, F_x = 20 kN),
/// after rolling one contact length so the warm start is representative.
fn transient_step(c: &mut Criterion) {
    let el = Elastic { young_modulus: 2.1e11, poisson_ratio: 0.3 };
    let shape = HertzShape::new(Curvatures::wheel_on_rail(0.5, -0.409, 0.3), el).unwrap();
    let patch = shape.patch(1e5).unwrap();
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
    let mut g = c.benchmark_group("exact_transient_step");
    g.sample_size(20);
    for n in [10, 20, 30] {
        for (name, kind) in [("gauss_seidel", StepSolver::GaussSeidel), ("newton", StepSolver::Newton)] {
            let mesh = EllipseMesh::new(n, n);
            let e = ExactElastic::new(&mesh, shape.aspect(), el.shear_modulus(), el.poisson_ratio);
            let mut solver =
                Transient::new(mesh, ElasticModel::Exact(Box::new(e)), PressureShape::Hertz, 1e-5).with_solver(kind);
            for _ in 0..60 {
                solver.step(&input).unwrap();
            }
            g.bench_function(format!("{n}x{n}_steady_{name}"), |b| b.iter(|| solver.step(black_box(&input)).unwrap()));
        }
    }
    g.finish();
}

fn passage(c: &mut Criterion) {
    let r = load_str(include_str!("../configs/paper_normal_30mm.toml"), "paper_normal_30mm", &[]).unwrap();
    let d = derive(&r.scene);
    let mut g = c.benchmark_group("passage");
    g.sample_size(10);
    g.bench_function("paper_normal_30mm_fastsim", |b| {
        b.iter(|| {
            let mut solver = build_solver(&r.scene, &d.shape);
            let dep = build_deposit(&solver.elements());
            run_passage(&d.passage, &d.shape, solver.as_mut(), dep.as_ref(), &d.grid, true, &mut |_, _| {}).unwrap()
        })
    });
    // The target scene for the exact model: a varying load, a new
    // patch every step (Gauss-Seidel, the default solver).
    let r = load_str(
        include_str!("../configs/paper_normal_30mm.toml"),
        "paper_normal_30mm",
        &["contact.model=exact-transient".into()],
    )
    .unwrap();
    // The same passage on the fixed grid at its default, 0.2 x 0.5 mm.
    let fixed = load_str(
        include_str!("../configs/paper_normal_30mm.toml"),
        "paper_normal_30mm",
        &["contact.model=exact-transient".into(), "contact.grid=fixed".into()],
    )
    .unwrap();
    let fd = derive(&fixed.scene);
    g.bench_function("paper_normal_30mm_exact_fixed_0.2mm", |b| {
        b.iter(|| {
            let mut solver = build_solver(&fixed.scene, &fd.shape);
            let dep = build_deposit(&solver.elements());
            run_passage(&fd.passage, &fd.shape, solver.as_mut(), dep.as_ref(), &fd.grid, true, &mut |_, _| {}).unwrap()
        })
    });
    g.bench_function("paper_normal_30mm_exact_20x20", |b| {
        b.iter(|| {
            let mut solver = build_solver(&r.scene, &d.shape);
            let dep = build_deposit(&solver.elements());
            run_passage(&d.passage, &d.shape, solver.as_mut(), dep.as_ref(), &d.grid, true, &mut |_, _| {}).unwrap()
        })
    });
    g.finish();
}

/// The fixed grid: one FFT product of the tangential kernel, and one step in
/// steady rolling (scene c, after one contact length), per element size.
fn fixed_grid(c: &mut Criterion) {
    let el = Elastic { young_modulus: 2.1e11, poisson_ratio: 0.3 };
    let curvatures = Curvatures::wheel_on_rail(0.5, -0.409, 0.3);
    let shape = HertzShape::new(curvatures, el).unwrap();
    let patch = shape.patch(1e5).unwrap();
    let mut g = c.benchmark_group("fixed_grid");
    g.sample_size(20);
    for dx in [4e-4, 2e-4, 1e-4] {
        let spec = FixedGridSpec::unaligned(
            (curvatures, el),
            (dx, 2.5 * dx),
            (patch.a, patch.b),
            (FrictionLaw::Regularised, GridScheme::SecondOrder, 1e-5),
            GridSolver::Auto,
        );
        let mut solver = FixedGrid::new(spec);
        let grid = solver.grid().clone();
        let kernel = ToeplitzKernel::tangential(&grid, el.shear_modulus(), el.poisson_ratio);
        let conv = FftConvolution::new(&kernel);
        let n = grid.len();
        let (px, py) = (vec![1e8; n], vec![1e7; n]);
        let (mut ux, mut uy) = (vec![0.0; n], vec![0.0; n]);
        let mut scratch = FftScratch::default();
        let mm = dx * 1e3;
        g.bench_function(format!("fft_product_{mm}mm_{}x{}", grid.nx, grid.ny), |b| {
            b.iter(|| conv.tangential(&mut scratch, (black_box(&px), &py), (&mut ux, &mut uy)))
        });
        // The CG solver's inner product (single precision) and its
        // preconditioner (the circulant inverse, unpadded, single).
        let single = FftConvolution::single(&kernel);
        let mut scratch_single = FftScratch::default();
        g.bench_function(format!("fft_product_single_{mm}mm_{}x{}", grid.nx, grid.ny), |b| {
            b.iter(|| single.tangential(&mut scratch_single, (black_box(&px), &py), (&mut ux, &mut uy)))
        });
        let inverse = FftConvolution::circulant_inverse_single(&kernel);
        g.bench_function(format!("fft_preconditioner_{mm}mm_{}x{}", grid.nx, grid.ny), |b| {
            b.iter(|| inverse.tangential(&mut scratch_single, (black_box(&px), &py), (&mut ux, &mut uy)))
        });
        // The same three on a folded grid's symmetric fields (x even, y
        // odd about the centre line).
        let py_odd: Vec<f64> = (0..n)
            .map(|k| match (2 * (k / grid.nx) + 1).cmp(&grid.ny) {
                std::cmp::Ordering::Less => 1e7,
                std::cmp::Ordering::Equal => 0.0,
                std::cmp::Ordering::Greater => -1e7,
            })
            .collect();
        let exact = SymmetricConvolution::padded(&kernel);
        let mut sym_scratch = SymmetricScratch::default();
        g.bench_function(format!("symmetric_product_{mm}mm_{}x{}", grid.nx, grid.ny), |b| {
            b.iter(|| exact.tangential(&mut sym_scratch, (black_box(&px), &py_odd), (&mut ux, &mut uy)))
        });
        let single = exact.to_single();
        let mut sym_single = SymmetricScratch::default();
        g.bench_function(format!("symmetric_product_single_{mm}mm_{}x{}", grid.nx, grid.ny), |b| {
            b.iter(|| single.tangential(&mut sym_single, (black_box(&px), &py_odd), (&mut ux, &mut uy)))
        });
        let inverse = SymmetricConvolution::circulant_inverse(&kernel).to_single();
        g.bench_function(format!("symmetric_preconditioner_{mm}mm_{}x{}", grid.nx, grid.ny), |b| {
            b.iter(|| inverse.tangential(&mut sym_single, (black_box(&px), &py_odd), (&mut ux, &mut uy)))
        });
        let input = StepInput {
            patch,
            speed: 27.778,
            dt: dx / 27.778,
            friction: 0.4,
            characteristic: Default::default(),
            memory: None,
            force_x: 2e4,
            creepage_x: None,
            creepage_y: 0.0,
            spin: 0.0,
            position: 0.0,
        };
        for _ in 0..(0.012 / dx) as usize {
            solver.step(&input).unwrap();
        }
        g.bench_function(format!("steady_step_{mm}mm"), |b| b.iter(|| solver.step(black_box(&input)).unwrap()));
    }
    g.finish();
}

/// One harmonic's tables of a track layout (the rail's receptances at the
/// 16 places of every support interval, one wheel), vertically and in
/// every direction, against the supports of the period: the waves'
/// scattering costs one pass over the supports plus each place's own
/// (linear in the supports).
fn layout_tables(c: &mut Criterion) {
    let t = TrackConfig::default();
    let mut g = c.benchmark_group("layout_tables_1khz");
    g.sample_size(20);
    let omega = 2.0 * std::f64::consts::PI * 1000.0;
    let (vertical, head) = (DiscreteTrack::new(&t), Discrete3::new(&t, 0.01));
    for bays in [1usize, 2, 5, 10, 20] {
        let spec =
            LayoutSpec { spacing: Spacing::Random(Spread { std: 0.02, bounds: (0.5, 0.7) }), ..LayoutSpec::uniform() };
        let layout = Layout::from_spec(&t, &LayoutSpec { seed: 1, ..spec }, bays as f64 * 0.6).unwrap();
        let pairs: Vec<(f64, f64)> = Places::new(&layout, 0.0).positions().iter().map(|&x| (x, x)).collect();
        g.bench_function(format!("vertical_{bays}_bays"), |b| {
            b.iter(|| vertical.layout_receptances(black_box(&layout), &pairs, omega).unwrap())
        });
        g.bench_function(format!("every_direction_{bays}_bays"), |b| {
            b.iter(|| head.layout_heads(black_box(&layout), &pairs, omega, true).unwrap())
        });
    }
}

criterion_group!(benches, fastsim, wear_step, transient_step, fixed_grid, passage, layout_tables);
criterion_main!(benches);
