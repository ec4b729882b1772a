//! The rail profile in the normal contact (`contact.normal = "profile"`):
//! the fixed grid's discrete normal problem with the gap of the curvatures
//! less the rail's height, against closed forms:
//!
//! - a flat rail gives the fixed grid's Hertz solution, bit for bit;
//! - a small sinusoidal profile gives Westergaard's linear pressure
//!   perturbation `E* k Delta / 2 cos(k X)` (Johnson, *Contact Mechanics*,
//!   1985, sec. 13.2, the line-contact limit `lambda << a, b`);
//! - full contact of the wavy surface ends where the closed form says: the
//!   trough at the patch centre opens at `Delta = p0 lambda / (pi E*)`, and
//!   the contact splits into strips beyond;
//! - the equivalent roughness of a small harmonic is the profile averaged
//!   with the weight dp/dN, the flat-punch pressure of the Hertz ellipse,
//!   uniform along x across the rail: `sin(k a) / (k a)` for a profile
//!   uniform across the rail;
//! - force balance and complementarity at every step of a passage over a
//!   corrugated rail.
use crate::common;
use common::{STEEL, paper_fixed_grid, paper_shape, rel};
use corrugation::build::{build_deposit, build_solver, derive};
use corrugation::config::load_str;
use corrugation::contact::grid::convolution::{FftConvolution, FftScratch, ToeplitzKernel};
use corrugation::contact::grid::{FixedGrid, RailSurface};
use corrugation::contact::{RailContact, StepInput, TangentialSolver};
use corrugation::growth::equivalent_roughness;
use corrugation::hertz::Curvatures;
use corrugation::passage::{PassageError, run_passage};
use corrugation::rail_grid::RailGrid;
use std::f64::consts::PI;
use std::sync::Arc;

const N: f64 = 1e5;

fn curvatures() -> Curvatures {
    Curvatures::wheel_on_rail(0.5, -0.409, 0.3)
}

/// Combined modulus E* of two steel bodies: 1/E* = 2 (1 - nu^2) / E.
fn e_star() -> f64 {
    STEEL.young_modulus / (2.0 * (1.0 - STEEL.poisson_ratio.powi(2)))
}

/// The paper's concave contact on a fixed grid of `dx x dy`, sized for the
/// Hertz patch at `N` times `length` along x and y.
fn solver(dx: f64, dy: f64, length: f64) -> FixedGrid {
    sized(dx, dy, length, N)
}

/// As [`solver`], sized for the patch at `n_max` N.
fn sized(dx: f64, dy: f64, length: f64, n_max: f64) -> FixedGrid {
    paper_fixed_grid(dx, dy, length, n_max)
}

/// A step of the paper's rolling (100 km/h, F_x = 20 kN, mu = 0.4) on a
/// grid of element `dx`, with the patch centre at `position`.
fn rolling(patch: corrugation::hertz::HertzPatch, dx: f64, position: f64) -> StepInput {
    StepInput {
        patch,
        speed: 27.78,
        dt: dx / 27.78,
        friction: 0.4,
        characteristic: Default::default(),
        memory: None,
        force_x: 2e4,
        creepage_x: None,
        creepage_y: 0.0,
        spin: 0.0,
        position,
    }
}

/// A harmonic rail `Delta cos(2 pi X / lambda)`, uniform across, sampled
/// every `lambda / 200` over one period.
fn wave(amplitude: f64, wavelength: f64) -> Arc<RailSurface> {
    let n = 200;
    let line: Vec<f64> = (0..n).map(|i| amplitude * (2.0 * PI * i as f64 / n as f64).cos()).collect();
    Arc::new(RailSurface::line(0.0, wavelength / n as f64, &line, true))
}

/// Least-squares amplitude of cos(k x) in `v(x)` over the points given,
/// with sin(k x), 1 and x^2 as nuisance terms.
fn cos_amplitude(xs: &[f64], v: &[f64], k: f64) -> f64 {
    let basis = |x: f64| [(k * x).cos(), (k * x).sin(), 1.0, x * x];
    let mut a = nalgebra::DMatrix::zeros(xs.len(), 4);
    for (i, &x) in xs.iter().enumerate() {
        for (j, b) in basis(x).into_iter().enumerate() {
            a[(i, j)] = b;
        }
    }
    let b = nalgebra::DVector::from_column_slice(v);
    let c = a.svd(true, true).solve(&b, 1e-14).unwrap();
    c[0]
}

#[test]
fn flat_rail_gives_the_hertz_solution_of_the_grid() {
    let shape = paper_shape(true);
    let patch = shape.patch(N).unwrap();
    let dx = 4e-4;
    let input = rolling(patch, dx, 0.013);
    let mut hertz = solver(dx, 1e-3, 1.0);
    let mut flat = solver(dx, 1e-3, 1.0);
    flat.set_surface(Some(RailContact::Profile(Arc::new(RailSurface::line(0.0, 1e-3, &[0.0; 50], true))))).unwrap();
    for step in 0..5 {
        let x = 0.013 + step as f64 * dx;
        let a = hertz.step(&StepInput { position: x, ..input }).unwrap();
        let b = flat.step(&StepInput { position: x, ..input }).unwrap();
        assert_eq!(a, b, "step {step}");
    }
    // And the approach of the flat rail is Hertz's to the grid's accuracy.
    let d = flat.approach(0.0, N).unwrap();
    assert!(rel(d, patch.approach) < 5e-3, "approach {d:.6e} vs Hertz {:.6e}", patch.approach);
}

#[test]
fn small_wave_gives_westergaards_linear_pressure_perturbation() {
    // lambda = 1.5 mm (15 elements) under a 14 x 20 mm patch; Delta = 0.05 um.
    let (dx, lambda, delta) = (1e-4, 1.5e-3, 5e-8);
    let mut flat = solver(dx, 2.5e-4, 1.0);
    let mut wavy = solver(dx, 2.5e-4, 1.0);
    wavy.set_surface(Some(RailContact::Profile(wave(delta, lambda)))).unwrap();
    let p_flat = flat.normal_solution(0.0, N).unwrap().pressure;
    let p_wavy = wavy.normal_solution(0.0, N).unwrap().pressure;
    let g = flat.grid().clone();
    let a = paper_shape(true).patch(N).unwrap().a;
    let row = g.ny / 2;
    let (mut xs, mut dp) = (Vec::new(), Vec::new());
    for ix in 0..g.nx {
        let x = g.x(ix);
        if x.abs() < 0.5 * a {
            xs.push(x);
            dp.push(p_wavy[row * g.nx + ix] - p_flat[row * g.nx + ix]);
        }
    }
    let k = 2.0 * PI / lambda;
    let amplitude = cos_amplitude(&xs, &dp, k);
    let expect = e_star() * k * delta / 2.0;
    eprintln!("pressure wave {amplitude:.5e} Pa, Westergaard {expect:.5e} Pa");
    // Crests carry more pressure (positive amplitude); the discrete answer
    // with 15 elements per wavelength is within 1.5 % (0.6 % measured).
    assert!(rel(amplitude, expect) < 0.015, "pressure wave {amplitude:.4e} Pa vs Westergaard {expect:.4e} Pa");
}

/// Whether the trough at the patch centre is in contact, and the number of
/// separate contact strips along the centre line, for a wave of amplitude
/// `delta` with its trough at the patch centre.
fn trough(s: &mut FixedGrid, delta: f64, lambda: f64) -> (bool, usize) {
    s.set_surface(Some(RailContact::Profile(wave(delta, lambda)))).unwrap();
    let p = s.normal_solution(0.5 * lambda, N).unwrap().pressure;
    let g = s.grid();
    let row = &p[(g.ny / 2) * g.nx..(g.ny / 2 + 1) * g.nx];
    let centre = (0..g.nx).min_by(|&i, &j| g.x(i).abs().total_cmp(&g.x(j).abs())).unwrap();
    // Strips over the central half of the patch (towards its ends the
    // local mean pressure falls to zero and troughs open at any amplitude).
    let a = paper_shape(true).patch(N).unwrap().a;
    let inner: Vec<f64> = (0..g.nx).filter(|&i| g.x(i).abs() < 0.5 * a).map(|i| row[i]).collect();
    let strips = inner.windows(2).filter(|w| w[0] == 0.0 && w[1] > 0.0).count() + usize::from(inner[0] > 0.0);
    (row[centre] > 0.0, strips)
}

#[test]
fn full_contact_ends_where_the_closed_form_says() {
    // Full contact of a wavy surface under the mean pressure p ends at
    // Delta = p lambda / (pi E*); at the patch centre p = p0 (lambda << a).
    let (dx, lambda) = (1e-4, 1.6e-3);
    let mut s = solver(dx, 5e-4, 1.0);
    let p0 = paper_shape(true).patch(N).unwrap().p0;
    let critical = p0 * lambda / (PI * e_star());
    // Bisection on the amplitude at which the centre trough opens.
    let (mut lo, mut hi) = (0.5 * critical, 1.5 * critical);
    assert!(trough(&mut s, lo, lambda).0 && !trough(&mut s, hi, lambda).0);
    for _ in 0..7 {
        let mid = 0.5 * (lo + hi);
        if trough(&mut s, mid, lambda).0 { lo = mid } else { hi = mid }
    }
    let opens = 0.5 * (lo + hi);
    eprintln!("centre trough opens at {opens:.5e} m, closed form {critical:.5e} m");
    assert!(rel(opens, critical) < 0.02, "trough opens at {opens:.4e} m, closed form {critical:.4e} m");
    // Below: one strip over the centre line; above: split into strips.
    assert_eq!(trough(&mut s, 0.8 * critical, lambda).1, 1);
    let (_, strips) = trough(&mut s, 1.3 * critical, lambda);
    assert!(strips >= 3, "{strips} strips");
}

#[test]
fn equivalent_roughness_of_a_small_wave_is_its_mean_over_the_patch_length() {
    let (dx, delta) = (2e-4, 1e-7);
    let a = paper_shape(true).patch(N).unwrap().a;
    for lambda in [0.016, 0.024, 0.04, 0.1] {
        let mut s = solver(dx, 5e-4, 1.0);
        s.set_surface(Some(RailContact::Profile(wave(delta, lambda)))).unwrap();
        let n = (lambda / dx).round() as usize;
        let r = equivalent_roughness(&mut s, 0.0, dx, n, N).unwrap();
        let xs: Vec<f64> = (0..n).map(|j| j as f64 * dx).collect();
        let k = 2.0 * PI / lambda;
        let amplitude = 2.0 / n as f64 * xs.iter().zip(&r).map(|(x, v)| v * (k * x).cos()).sum::<f64>();
        let z = k * a;
        let filter = z.sin() / z;
        eprintln!(
            "lambda {lambda}: equivalent roughness {:.5} of the profile, sin(ka)/ka {filter:.5}",
            amplitude / delta
        );
        assert!(
            (amplitude / delta - filter).abs() < 0.005,
            "lambda {lambda}: equivalent roughness {:.4} of the profile, sin(ka)/ka {filter:.4}",
            amplitude / delta
        );
    }
}

#[test]
fn force_balance_and_complementarity_at_every_step_over_a_corrugated_rail() {
    // 15 mm corrugation of 50 um: Westergaard's pressure amplitude
    // E* k Delta / 2 = 1.2 GPa exceeds p0, so the patch splits over the
    // crests when a trough passes under its centre.
    let (dx, dy) = (4e-4, 1e-3);
    let mut s = sized(dx, dy, 2.0, 1.3 * N);
    let (lambda, delta) = (0.015, 5e-5);
    s.set_surface(Some(RailContact::Profile(wave(delta, lambda)))).unwrap();
    let shape = paper_shape(true);
    let g = s.grid().clone();
    let kernel = ToeplitzKernel::normal(&g, STEEL.shear_modulus(), STEEL.poisson_ratio);
    let conv = FftConvolution::new(&kernel);
    let mut scratch = FftScratch::default();
    let speed = 27.78;
    let mut multiple = 0;
    for step in 0..(lambda / dx) as usize {
        let x = step as f64 * dx;
        let n = N * (1.0 + 0.3 * (2.0 * PI * x / lambda).sin());
        let patch = shape.patch(n).unwrap();
        let input = StepInput {
            patch,
            speed,
            dt: dx / speed,
            friction: 0.4,
            characteristic: Default::default(),
            memory: None,
            force_x: 0.2 * n,
            creepage_x: None,
            creepage_y: 0.0,
            spin: 0.0,
            position: x,
        };
        let sol = s.step(&input).unwrap();
        let total: f64 = sol.pressure.iter().sum::<f64>() * g.area();
        assert!(rel(total, n) < 1e-10, "step {step}: force {total} vs {n}");
        let fx: f64 = sol.traction_x.iter().sum::<f64>() * g.area();
        assert!(rel(fx, 0.2 * n) < 1e-6, "step {step}: F_x {fx} vs {}", 0.2 * n);
        for (q, p) in sol.traction_x.iter().zip(&sol.pressure) {
            assert!(q.abs() <= 0.4 * p * (1.0 + 1e-9), "traction bound");
        }
        let h = s.gap(x);
        let mut u = vec![0.0; g.len()];
        conv.normal(&mut scratch, &sol.pressure, &mut u);
        let in_contact: Vec<usize> = (0..g.len()).filter(|&k| sol.pressure[k] > 0.0).collect();
        let approach = in_contact.iter().map(|&k| h[k] + u[k]).sum::<f64>() / in_contact.len() as f64;
        for k in 0..g.len() {
            let gap = h[k] + u[k] - approach;
            if sol.pressure[k] > 0.0 {
                assert!(gap.abs() < 1e-8 * approach.abs(), "step {step}: gap {gap:e} in contact");
            } else {
                assert!(gap > -1e-8 * approach.abs(), "step {step}: penetration {gap:e}");
            }
        }
        let row = &sol.pressure[(g.ny / 2) * g.nx..(g.ny / 2 + 1) * g.nx];
        let strips = row.windows(2).filter(|w| w[0] == 0.0 && w[1] > 0.0).count();
        multiple = multiple.max(strips);
    }
    assert!(multiple >= 2, "the patch never split ({multiple} strips)");
}

#[test]
fn wear_off_the_rail_grid_stops_the_passage() {
    // A rail grid narrower than the patch: its wear would be lost, so the
    // passage stops naming the key.
    let set = [
        "contact.model=exact-transient",
        "contact.grid=fixed",
        "contact.dx=4e-4",
        "contact.dy=1e-3",
        "passage.step_length=4e-4",
        "passage.end=0.002",
    ];
    let r = load_str(include_str!("../configs/paper_normal_15mm.toml"), "n15", &set.map(String::from)).unwrap();
    let d = derive(&r.scene);
    let mut solver = build_solver(&r.scene, &d.shape);
    let dep = build_deposit(&solver.elements());
    let narrow = RailGrid { half_width: 0.004, ny: 9, dy: 1e-3, ..d.grid.clone() };
    let e =
        run_passage(&d.passage, &d.shape, solver.as_mut(), dep.as_ref(), &narrow, false, &mut |_, _| {}).unwrap_err();
    assert!(matches!(e, PassageError::OffRail { step: 0, .. }), "{e}");
    assert!(e.to_string().contains("raise rail.half_width"), "{e}");
}

#[test]
fn linear_contact_on_a_flat_rail_is_the_hertz_chain_bit_for_bit() {
    // FASTSIM in a growth study without roughness: the linear profile
    // contact sees a flat rail in the first passage and leaves the Hertz
    // chain's wear bit for bit (later passages see the rounding of the
    // uniform wear along the rail, which the two chains filter differently).
    let dir = tempfile::tempdir().unwrap();
    let run = |normal: &str| {
        let set: Vec<String> = [
            "contact.elements_x=8",
            "contact.elements_y=8",
            "rail.dx=5e-4",
            "rail.dy=1e-3",
            "passage.step_length=5e-4",
            "roughness.kind=none",
            "growth.passes=1",
            "growth.contact_history=[]",
        ]
        .iter()
        .map(|s| s.to_string())
        .chain([format!("contact.normal={normal}")])
        .collect();
        let r = load_str(include_str!("../configs/growth_fastsim.toml"), "flat", &set).unwrap();
        let out = dir.path().join(format!("{normal}.h5"));
        corrugation::run::run_scene(&r, &out, &mut |_| {}).unwrap();
        corrugation::output::netcdf::read_f64(&out, "rail", "state").unwrap()
    };
    let (linear, hertz) = (run("linear"), run("hertz"));
    assert!(linear.iter().zip(hertz.iter()).all(|(a, b)| a.to_bits() == b.to_bits()));
    assert!(hertz.iter().any(|v| *v != 0.0), "the passages wear the rail");
}

#[test]
fn a_patch_that_outgrows_the_grid_names_the_grid_that_holds_it() {
    // 20 um at 30 mm: the trough's curvature Delta k^2 = 0.88 1/m, 44 % of
    // the wheel's 2A, lengthens the patch over it (Hertz with the curvature
    // sum A - r''/2) beyond a grid sized for the smooth rail's patch.
    let (delta, lambda) = (2e-5, 0.03);
    let (dx, dy) = (2e-4, 5e-4);
    let surface = || Some(RailContact::Profile(wave(delta, lambda)));
    let patch = paper_shape(true).patch(N).unwrap();
    let input = rolling(patch, dx, 0.5 * lambda);
    let mut tight = solver(dx, dy, 1.0);
    tight.set_surface(surface()).unwrap();
    let e = tight.step(&input).unwrap_err().to_string();
    assert!(e.contains("reaches the edge of the potential-contact grid"), "{e}");
    assert!(e.contains("set contact.profile_grid_scale to at least 1.40 times its value"), "{e}");
    // The grid it names holds the patch.
    let mut named = solver(dx, dy, 1.4);
    named.set_surface(surface()).unwrap();
    named.step(&input).unwrap();
    // The estimate against the patch the normal problem gives: the local
    // quadratic leaves out the cosine's quartic term, which flattens the
    // trough towards the patch ends ((k a)^2 / 12 = 0.2 of the curvature
    // there), so the estimate is long (8 % here), never short.
    let k = 2.0 * PI / lambda;
    let c = curvatures();
    let local = Curvatures { a: c.a - 0.5 * delta * k * k, b: c.b };
    let estimate = corrugation::hertz::HertzShape::new(local, STEEL).unwrap().patch(N).unwrap().a;
    let p = named.normal_solution(0.5 * lambda, N).unwrap().pressure;
    let g = named.grid();
    let row = &p[(g.ny / 2) * g.nx..(g.ny / 2 + 1) * g.nx];
    let length = row.iter().filter(|v| **v > 0.0).count() as f64 * dx;
    eprintln!("patch length over the trough {length:.4e} m, local Hertz estimate {:.4e} m", 2.0 * estimate);
    let excess = 2.0 * estimate / length - 1.0;
    assert!((0.0..0.15).contains(&excess), "{length} vs {}", 2.0 * estimate);
}
