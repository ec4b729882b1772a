//! FASTSIM against Kalker's linear theory, the friction limit, and CONTACT's
//! FASTSIM creepages for the paper's patch (scenes a and b of the reference).
use crate::common;
use common::{STEEL, paper_coefficients, paper_shape, rel, table};
use corrugation::contact::fastsim::Fastsim;
use corrugation::contact::{ContactError, Creepage, PressureShape, StepInput};
use corrugation::creep_coefficients::creep_coefficients;
use corrugation::hertz::{Curvatures, HertzShape};

const MU: f64 = 0.4;
const V: f64 = 27.78;

fn fastsim(concave: bool, n: usize, shape: PressureShape) -> Fastsim {
    Fastsim::new(n, n, shape, paper_coefficients(concave), STEEL.shear_modulus())
}

fn input(concave: bool, force_x: f64) -> StepInput {
    StepInput {
        patch: paper_shape(concave).patch(1e5).unwrap(),
        speed: V,
        dt: 0.0,
        friction: MU,
        characteristic: Default::default(),
        memory: None,
        force_x,
        creepage_x: None,
        creepage_y: 0.0,
        spin: 0.0,
        position: 0.0,
    }
}

#[test]
fn linear_theory_limit() {
    // F_x = -G a b C11 xi at vanishing creepage (Kalker's linear theory), for a
    // circle and both paper patches, within 2 % on a 40 x 40 mesh.
    let g = STEEL.shear_modulus();
    for curv in [
        Curvatures { a: 1.0, b: 1.0 },
        Curvatures::wheel_on_rail(0.5, -0.409, 0.3),
        Curvatures::wheel_on_rail(0.5, 0.409, 0.3),
    ] {
        let shape = HertzShape::new(curv, STEEL).unwrap();
        let c = creep_coefficients(shape.aspect(), 0.3).unwrap();
        let p = shape.patch(1e5).unwrap();
        for bound in [PressureShape::Parabolic, PressureShape::Hertz] {
            let f = Fastsim::new(40, 40, bound, c, g);
            let xi = -1e-7;
            let s = f.solve_creepage(&p, Creepage { x: xi, ..Default::default() }, MU, V);
            let linear = -g * p.a * p.b * c.c11 * xi;
            assert!(rel(s.force_x, linear) < 0.02, "{curv:?} {bound:?}: {} vs {linear}", s.force_x);
            assert!(s.stick.iter().all(|x| *x), "all stick at vanishing creepage");
        }
    }
}

#[test]
fn saturates_to_friction_limit_and_respects_bound() {
    for bound in [PressureShape::Parabolic, PressureShape::Hertz] {
        let f = fastsim(true, 20, bound);
        let p = paper_shape(true).patch(1e5).unwrap();
        for xi in [-1e-4, -1e-3, -3e-3, -1e-2, -1.0] {
            let s = f.solve_creepage(&p, Creepage { x: xi, ..Default::default() }, MU, V);
            for k in 0..s.pressure.len() {
                let t = s.traction_x[k].hypot(s.traction_y[k]);
                assert!(t <= MU * s.pressure[k] * (1.0 + 1e-12), "|p| > mu p3 at {k}");
                if !s.stick[k] {
                    // Slip opposes traction.
                    let dot = s.slip_x[k] * s.traction_x[k] + s.slip_y[k] * s.traction_y[k];
                    assert!(dot < 0.0 && s.slip_x[k] < 0.0);
                } else {
                    assert_eq!((s.slip_x[k], s.slip_y[k]), (0.0, 0.0));
                }
            }
            assert!(s.force_y.abs() < 1e-9 * 1e5, "no lateral force without lateral creepage");
        }
        let full = f.solve_creepage(&p, Creepage { x: -1.0, ..Default::default() }, MU, V);
        assert!(rel(full.force_x, MU * 1e5) < 1e-12, "full sliding gives mu N: {}", full.force_x);
        let mirror = f.solve_creepage(&p, Creepage { x: 1e-3, ..Default::default() }, MU, V);
        let plain = f.solve_creepage(&p, Creepage { x: -1e-3, ..Default::default() }, MU, V);
        assert!((mirror.force_x + plain.force_x).abs() < 1e-9 * plain.force_x.abs());
    }
}

// CONTACT's FASTSIM numbers carry a discretisation bias of about -1.8 % in
// creepage: at F_x = 0.05 mu N its parabolic-bound creepage is *below* the
// linear-theory value computed from its own printed L1, which the continuum
// FASTSIM cannot give (partial slip always adds creepage). Our FASTSIM
// converges under mesh refinement (see `converges_under_refinement`) to values
// 1.6-2.2 % above CONTACT's at low and moderate force. The tolerances below
// are set from that bias, and the creep curves are also compared in force at
// the reference creepage, the quantity FASTSIM is built to reproduce.

#[test]
fn contact_scene_a_steady_creepage() {
    // CONTACT, F_x = 20 kN: FASTSIM elliptic bound cvx -1.593e-3, ccv -1.147e-3;
    // parabolic bound cvx -1.773e-3, ccv -1.277e-3.
    for (concave, shape, expected) in [
        (false, PressureShape::Hertz, -1.593e-3),
        (true, PressureShape::Hertz, -1.147e-3),
        (false, PressureShape::Parabolic, -1.773e-3),
        (true, PressureShape::Parabolic, -1.277e-3),
    ] {
        let s = fastsim(concave, 60, shape).solve_force(&input(concave, 2e4)).unwrap();
        assert!(rel(s.creepage.x, expected) < 0.025, "{concave} {shape:?}: {} vs {expected}", s.creepage.x);
        assert!(rel(s.force_x, 2e4) < 1e-9);
    }
}

#[test]
fn contact_scene_b_creep_curves() {
    // CONTACT's FASTSIM creep curves, F_x/(mu N) = 0.05 ... 0.95, both bounds
    // and both readings. At CONTACT's creepage our force is within 1.5 % of
    // mu N of CONTACT's; with the parabolic bound (Kalker's original, our
    // default) the creepage itself is within 2.5 % over the whole curve.
    let rows = table(include_str!("data/contact_creep_curves.txt"));
    assert_eq!(rows.len(), 20);
    for r in rows {
        let concave = r[0] == "ccv";
        let frac: f64 = r[1].parse().unwrap();
        let fx: f64 = r[2].parse().unwrap();
        let patch = paper_shape(concave).patch(1e5).unwrap();
        for (shape, col) in [(PressureShape::Hertz, 4), (PressureShape::Parabolic, 5)] {
            let expected: f64 = r[col].parse().unwrap();
            let f = fastsim(concave, 60, shape);
            let at_ref = f.solve_creepage(&patch, Creepage { x: expected, ..Default::default() }, MU, V);
            let df = (at_ref.force_x - fx).abs() / (MU * 1e5);
            assert!(df < 0.015, "{} {frac} {shape:?}: force {} vs {fx}", r[0], at_ref.force_x);
            if shape == PressureShape::Parabolic {
                let s = f.solve_force(&input(concave, fx)).unwrap();
                assert!(rel(s.creepage.x, expected) < 0.025, "{} {frac}: {} vs {expected}", r[0], s.creepage.x);
            }
        }
    }
}

/// Continuum FASTSIM with the parabolic bound, longitudinal creepage only.
/// Strip of half-length c: bound mu k (c^2 - x^2), k = 2N/(pi a^3 b); adhesion
/// traction q (c - x), q = -xi/L1; slip zone length d = q/(mu k) at the
/// trailing edge; strip force mu k (2 c^2 d - c d^2 + d^3/6) for d < 2c, else
/// the full-slip mu k 4c^3/3. Integrated over y with a 20000-point midpoint rule.
fn continuum_parabolic_force(xi: f64, a: f64, b: f64, n: f64, l1: f64) -> f64 {
    let k = 2.0 * n / (std::f64::consts::PI * a.powi(3) * b);
    let d = (-xi / l1).abs() / (MU * k);
    let m = 20000;
    let dy = 2.0 * b / m as f64;
    let mut f = 0.0;
    for j in 0..m {
        let y = -b + (j as f64 + 0.5) * dy;
        let c = a * (1.0 - (y / b).powi(2)).sqrt();
        let strip = if d < 2.0 * c { 2.0 * c * c * d - c * d * d + d.powi(3) / 6.0 } else { 4.0 * c.powi(3) / 3.0 };
        f += MU * k * strip * dy;
    }
    f * -xi.signum()
}

#[test]
fn parabolic_bound_matches_continuum_theory() {
    let f = fastsim(true, 100, PressureShape::Parabolic);
    let p = paper_shape(true).patch(1e5).unwrap();
    let l1 = f.flexibilities(p.a, p.b).l1;
    for xi in [-1e-4, -5e-4, -1.2e-3, -2.5e-3, -5e-3] {
        let s = f.solve_creepage(&p, Creepage { x: xi, ..Default::default() }, MU, V);
        let exact = continuum_parabolic_force(xi, p.a, p.b, 1e5, l1);
        assert!((s.force_x - exact).abs() < 0.003 * MU * 1e5, "xi {xi}: {} vs {exact}", s.force_x);
    }
}

#[test]
fn converges_under_refinement() {
    for shape in [PressureShape::Hertz, PressureShape::Parabolic] {
        let coarse = fastsim(true, 30, shape).solve_force(&input(true, 2e4)).unwrap();
        let fine = fastsim(true, 120, shape).solve_force(&input(true, 2e4)).unwrap();
        assert!(rel(coarse.creepage.x, fine.creepage.x) < 0.005, "{shape:?}");
    }
}

#[test]
fn force_beyond_friction_is_an_error() {
    let f = fastsim(true, 10, PressureShape::Parabolic);
    let e = f.solve_force(&input(true, 4e4)).unwrap_err();
    assert!(matches!(e, ContactError::ForceExceedsFriction { .. }));
    assert!(e.to_string().contains("friction limit"));
    // Just below the limit still converges.
    let s = f.solve_force(&input(true, 0.999 * 4e4)).unwrap();
    assert!(rel(s.force_x, 0.999 * 4e4) < 1e-9);
}
