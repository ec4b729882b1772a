//! The modal wheelset against closed forms: today's torsion (eq. 1 of
//! `torsion`), the rigid wheelset on its suspension solved directly
//! (Euler's equations), the gyroscopic split of a symmetric pair, a free
//! beam's bending frequencies; reciprocity; the default's modes as cited.

use super::rigid::RigidWheelset;
use super::standard::{self, Beam, Design};
use super::*;
use crate::dynamics::wheelset::torsion::WheelsetTorsion;
use nalgebra::SMatrix;

const TORSION: WheelsetTorsion = WheelsetTorsion { stiffness: 3e6, loss_factor: 0.02, inertia: 30.0, radius: 0.5 };

fn rigid() -> RigidWheelset {
    RigidWheelset {
        mass: standard::WHEELSET_MASS,
        roll_inertia: standard::WHEELSET_ROLL_INERTIA,
        yaw_inertia: 700.0,
        spin_inertia: 60.0,
        stiffness_x: standard::SUSPENSION_STIFFNESS_X,
        stiffness_y: standard::SUSPENSION_STIFFNESS_Y,
        stiffness_z: standard::SUSPENSION_STIFFNESS_Z,
        loss_factor: standard::SUSPENSION_LOSS_FACTOR,
        axle_box_half_spacing: 1.0,
        contact_half_spacing: 0.75,
        radius: 0.5,
    }
}

fn design() -> Design {
    Design {
        rigid: RigidWheelset { yaw_inertia: standard::WHEELSET_ROLL_INERTIA, ..rigid() },
        torsional_stiffness: 3e6,
        torsional_loss_factor: 0.02,
        bending_damping: standard::BENDING_DAMPING,
        wheel_damping: standard::WHEEL_DAMPING,
    }
}

fn log_sweep(from: f64, to: f64, n: usize) -> impl Iterator<Item = f64> {
    (0..n).map(move |k| from * (to / from).powf(k as f64 / (n - 1) as f64))
}

fn max_abs(m: &Receptance) -> f64 {
    m.iter().fold(0.0f64, |a, v| a.max(v.norm()))
}

#[test]
fn the_torsion_alone_is_eq_1_of_the_torsional_model() {
    // The two modes (free spin, torsion with the axle's loss factor) sum to
    // eq. 1 and 2 of `torsion`: T(w) = i w H_x0x0 / V and the rotation per
    // moment (k* - J w^2) / (J w^2 (J w^2 - 2 k*)), to round-off (1e-12),
    // across the resonance (71.2 Hz) and the anti-resonance (50.3 Hz).
    let model = WheelsetModel::torsion(&TORSION);
    let speed = 27.78;
    let mut worst = 0.0f64;
    for f in log_sweep(1.0, 5000.0, 2001).chain([50.329, 71.176]) {
        let w = 2.0 * PI * f;
        let h = model.receptance(w, 0.0);
        let t = Complex64::new(0.0, w) * h[(dof(0, Dir::X), dof(0, Dir::X))] / speed;
        let expected = TORSION.creepage_per_force(w, speed);
        worst = worst.max((t - expected).norm() / expected.norm());
        let k = Complex64::new(3e6, 3e6 * 0.02);
        let jw2 = 30.0 * w * w;
        let theta = (k - jw2) / (jw2 * (jw2 - 2.0 * k));
        let got = h[(dof(0, Dir::Theta), dof(0, Dir::Theta))];
        worst = worst.max((got - theta).norm() / theta.norm());
        // A force at the contact turns the wheel by -r times the moment's.
        let per_force = h[(dof(0, Dir::Theta), dof(0, Dir::X))];
        worst = worst.max((per_force + 0.5 * theta).norm() / (0.5 * theta.norm()));
    }
    eprintln!("torsion: worst relative difference {worst:.2e}");
    assert!(worst < 1e-12, "{worst:e}");
}

/// The rigid wheelset solved directly: `(K* - w^2 M + i w Omega G) a = T^T f`
/// in the body coordinates (u, v, w, phi, theta, psi), `H = T (...)^-1
/// T^T`, with Euler's gyroscopic terms and the contacts' kinematics.
fn rigid_direct(r: &RigidWheelset, omega: f64, spin: f64) -> Receptance {
    let mut a = SMatrix::<Complex64, 6, 6>::zeros();
    let eta = Complex64::new(1.0, r.loss_factor);
    let b2 = r.axle_box_half_spacing.powi(2);
    let stiff = [
        2.0 * r.stiffness_x,
        2.0 * r.stiffness_y,
        2.0 * r.stiffness_z,
        2.0 * r.stiffness_z * b2,
        0.0,
        2.0 * r.stiffness_x * b2,
    ];
    let mass = [r.mass, r.mass, r.mass, r.roll_inertia, r.spin_inertia, r.yaw_inertia];
    for i in 0..6 {
        a[(i, i)] = stiff[i] * eta - omega * omega * mass[i];
    }
    // I_x phi'' - I_y Omega psi' = M_x, I_z psi'' + I_y Omega phi' = M_z.
    a[(3, 5)] = Complex64::new(0.0, -omega * spin * r.spin_inertia);
    a[(5, 3)] = Complex64::new(0.0, omega * spin * r.spin_inertia);
    let mut t = SMatrix::<Complex64, DOFS, 6>::zeros();
    for (w, y) in [(0, r.contact_half_spacing), (1, -r.contact_half_spacing)] {
        let row = |d: Dir| dof(w, d);
        let one = Complex64::from(1.0);
        t[(row(Dir::X), 0)] = one;
        t[(row(Dir::X), 4)] = Complex64::from(-r.radius);
        t[(row(Dir::X), 5)] = Complex64::from(-y);
        t[(row(Dir::Y), 1)] = one;
        t[(row(Dir::Y), 3)] = Complex64::from(r.radius);
        t[(row(Dir::Z), 2)] = one;
        t[(row(Dir::Z), 3)] = Complex64::from(y);
        t[(row(Dir::Theta), 4)] = one;
        t[(row(Dir::Psi), 5)] = one;
    }
    t * a.try_inverse().expect("regular") * t.transpose()
}

#[test]
fn the_rigid_modes_are_the_rigid_wheelset_solved_directly() {
    // Six modes against the 6 x 6 equations of the body with Euler's
    // gyroscopic moments, at rest and spinning at 100 km/h (55.6 rad/s)
    // and 300 km/h: equal to round-off (1e-11 of the largest entry; the
    // free spin makes the x-x entries 1e3 times the rest at 1 Hz).
    let r = rigid();
    let tilted = r.modes();
    let couplings = rigid::tilt_couplings(&tilted, 0, r.spin_inertia / 2.0);
    let model = WheelsetModel::new(tilted.into_iter().map(|t| t.mode).collect(), couplings).unwrap();
    for spin in [0.0, 55.6, -55.6, 166.7] {
        for f in log_sweep(0.5, 2000.0, 301) {
            let w = 2.0 * PI * f;
            let (got, expected) = (model.receptance(w, spin), rigid_direct(&r, w, spin));
            let err = max_abs(&(got - expected)) / max_abs(&expected);
            assert!(err < 1e-11, "spin {spin} rad/s, {f} Hz: {err:e}");
        }
    }
}

#[test]
fn without_rotation_the_receptance_is_symmetric_and_passive_and_rotation_reverses_with_the_spin() {
    // Reciprocity: H = H^T bit for bit at rest (a sum of phi phi^T / d);
    // spinning, H(Omega)^T = H(-Omega) (G skew) to round-off; passivity:
    // Im H_ii <= 0 at rest (exp(+i w t)). The default model, 1 Hz-5 kHz.
    let model = standard::default_model(&design()).unwrap();
    for f in log_sweep(1.0, 5000.0, 400) {
        let w = 2.0 * PI * f;
        let h = model.receptance(w, 0.0);
        assert_eq!(h, h.transpose(), "{f} Hz");
        for i in 0..DOFS {
            assert!(h[(i, i)].im <= 0.0, "{f} Hz, dof {i}: {}", h[(i, i)]);
        }
        let (plus, minus) = (model.receptance(w, 55.6), model.receptance(w, -55.6));
        let err = max_abs(&(plus.transpose() - minus)) / max_abs(&plus);
        assert!(err < 1e-12, "{f} Hz: {err:e}");
    }
    // Spinning, the bending planes couple: at the first bending mode the
    // vertical displacement per longitudinal force is not the longitudinal
    // displacement per vertical force.
    let h = model.receptance(2.0 * PI * 87.0, 55.6);
    let (zx, xz) = (h[(dof(0, Dir::Z), dof(0, Dir::X))], h[(dof(0, Dir::X), dof(0, Dir::Z))]);
    eprintln!("87 Hz, 55.6 rad/s: H_zx {zx:.3e}, H_xz {xz:.3e}, H_zz {:.3e}", h[(2, 2)]);
    assert!((zx - xz).norm() > 0.01 * h[(2, 2)].norm());
}

#[test]
fn a_symmetric_pair_splits_by_its_closed_form() {
    // Two modes of equal frequency w0 coupled by g: det = 0 at w = sqrt(w0^2
    // + (g Omega / 2)^2) +- g Omega / 2, exactly (1e-9 relative).
    let mode = |name: &str, shape: [f64; DOFS]| Mode {
        name: name.into(),
        frequency: 360.0,
        damping: Damping::Ratio(1e-3),
        shape,
    };
    let mut a = [0.0; DOFS];
    a[dof(0, Dir::Y)] = 0.1;
    let model = WheelsetModel::new(
        vec![mode("cos", a), mode("sin", [0.0; DOFS])],
        vec![Gyroscopic { a: 0, b: 1, coefficient: 4.0 }],
    )
    .unwrap();
    let w0 = 2.0 * PI * 360.0;
    for spin in [0.0, 30.0, 55.6, 200.0] {
        let half = 4.0 * spin / 2.0;
        let root = (w0 * w0 + half * half).sqrt();
        let expected = [(root - half) / (2.0 * PI), (root + half) / (2.0 * PI)];
        let got = model.frequencies(spin);
        eprintln!("Omega {spin}: {got:?} vs {expected:?}");
        for (g, e) in got.iter().zip(expected) {
            assert!((g - e).abs() < 1e-9 * e, "{g} vs {e}");
        }
        // The receptance peaks there: the cos mode's receptance at the two
        // roots exceeds its value halfway between by far (light damping).
        if spin > 0.0 {
            let at = |f: f64| model.receptance(2.0 * PI * f, spin)[(1, 1)].norm();
            let mid = 0.5 * (expected[0] + expected[1]);
            assert!(at(expected[0]) > 10.0 * at(mid) && at(expected[1]) > 10.0 * at(mid));
        }
    }
}

#[test]
fn roll_and_yaw_split_by_euler_s_equations() {
    // The rigid roll and yaw on their springs, coupled by I_y Omega:
    // (w_r^2 - w^2)(w_y^2 - w^2) = (g Omega w)^2 with g^2 = I_y^2 / (I_x
    // I_z): the quadratic in w^2, to 1e-9.
    let r = rigid();
    let tilted = r.modes();
    let couplings = rigid::tilt_couplings(&tilted, 0, r.spin_inertia / 2.0);
    let model = WheelsetModel::new(tilted.into_iter().map(|t| t.mode).collect(), couplings).unwrap();
    let (wr2, wy2) = (2.0 * r.stiffness_z / r.roll_inertia, 2.0 * r.stiffness_x / r.yaw_inertia);
    let g2 = r.spin_inertia.powi(2) / (r.roll_inertia * r.yaw_inertia);
    let spin = 166.7;
    let s = wr2 + wy2 + g2 * spin * spin;
    let disc = (s * s - 4.0 * wr2 * wy2).sqrt();
    let expected = [((s - disc) / 2.0).sqrt() / (2.0 * PI), ((s + disc) / 2.0).sqrt() / (2.0 * PI)];
    let got = model.frequencies(spin);
    for e in expected {
        assert!(got.iter().any(|g| (g - e).abs() < 1e-9 * e), "{e} not in {got:?}");
    }
}

#[test]
fn the_beam_model_gives_a_free_free_beam_s_frequencies() {
    // A uniform steel Euler-Bernoulli beam, 2 m, 0.18 m diameter, free-free
    // on 40 elements: w_n = (beta_n L)^2 sqrt(EI / (rho A L^4)), beta_n L =
    // 4.7300408, 7.8532046, 10.9956078 (Blevins, Formulas for natural
    // frequency and mode shape, 1979, table 8-1); the cubic elements
    // converge as h^4: 1e-5 at 40 elements.
    let n = 40;
    let (len, d) = (2.0, 0.18);
    let beam = Beam {
        nodes: (0..=n).map(|k| len * k as f64 / n as f64).collect(),
        diameters: vec![d; n],
        young: 210e9,
        density: 7850.0,
        ei_scale: 1.0,
        shear: false,
        masses: vec![],
        wheels: vec![],
    };
    let (area, second) = (PI * d * d / 4.0, PI * d.powi(4) / 64.0);
    let scale = (210e9 * second / (7850.0 * area * len.powi(4))).sqrt() / (2.0 * PI);
    let modes = beam.flexible_modes();
    for (m, bl) in modes.iter().zip([4.7300408f64, 7.8532046, 10.9956078]) {
        let expected = bl * bl * scale;
        eprintln!("{:.4} Hz vs {expected:.4} Hz", m.frequency);
        assert!((m.frequency / expected - 1.0).abs() < 1e-5, "{} vs {expected}", m.frequency);
    }
    // Mass-normalised: the first mode's end deflection is 2 / sqrt(m L)
    // (the free-free mode's end value is 2 on a shape of mean square 1).
    let end = modes[0].deflection[0].abs();
    let expected = 2.0 / (7850.0 * area * len).sqrt();
    assert!((end / expected - 1.0).abs() < 1e-4, "{end} vs {expected}");
}

#[test]
fn the_default_modes_are_at_their_cited_frequencies() {
    let model = standard::default_model(&design()).unwrap();
    let at = |name: &str| {
        model.modes().iter().find(|m| m.name == name).unwrap_or_else(|| panic!("no mode {name}")).frequency
    };
    for m in model.modes() {
        eprintln!("{}", m.describe());
    }
    // Torsion: sqrt(2 k_t / J) (today's 71.18 Hz); bending: Wu et al.
    // (2020) 87 and 143 Hz, to the fit's 0.2 Hz; the rest as tabulated.
    assert!((at("torsion") - (2.0 * 3e6f64 / 30.0).sqrt() / (2.0 * PI)).abs() < 1e-12);
    for plane in ["vertical", "horizontal"] {
        assert!((at(&format!("first symmetric bending ({plane} plane)")) - 87.0).abs() < 0.2);
        assert!((at(&format!("first antisymmetric bending ({plane} plane)")) - 143.0).abs() < 0.2);
    }
    assert_eq!(at("umbrella (0 nodal diameters, axial), symmetric: both rims outwards"), 450.0);
    for w in 0..2 {
        for (n, family, f) in [(2, "axial", 360.0), (3, "axial", 1000.0), (2, "radial", 1900.0), (3, "radial", 2150.0)]
        {
            assert_eq!(at(&format!("wheel {w}: {n} nodal diameters, {family} (cos)")), f);
        }
    }
    // The rigid modes: sqrt(2 k / m) etc.
    assert!((at("rigid bounce (primary suspension)") - (2.0 * 1.22e6 / 1200.0f64).sqrt() / (2.0 * PI)).abs() < 1e-12);
    assert_eq!(at("rigid spin (free)"), 0.0);
}

#[test]
fn the_default_beam_is_the_documented_wheelset() {
    // The beam model's mass and roll inertia are the defaults' (1200 kg,
    // 660 kg m^2) to their rounding: the rigid modes (from the keys) and
    // the flexible ones (from the beam) describe one body.
    let beam = standard::default_beam();
    let (mut mass, mut roll) = (0.0, 0.0);
    for (e, d) in beam.diameters.iter().enumerate() {
        let (a, b) = (beam.nodes[e], beam.nodes[e + 1]);
        let m = 7850.0 * PI * d * d / 4.0;
        mass += m * (b - a);
        roll += m * (b.powi(3) - a.powi(3)) / 3.0;
    }
    for &(y, m) in &beam.masses {
        mass += m;
        roll += m * y * y;
    }
    for &(y, m, i, _) in &beam.wheels {
        mass += m;
        roll += m * y * y + i;
    }
    eprintln!("beam: {mass:.1} kg, roll {roll:.1} kg m^2");
    assert!((mass / standard::WHEELSET_MASS - 1.0).abs() < 0.005, "{mass}");
    assert!((roll / standard::WHEELSET_ROLL_INERTIA - 1.0).abs() < 0.01, "{roll}");
}

#[test]
fn below_the_flexible_modes_the_model_is_the_rigid_wheelset_plus_their_static_compliance() {
    // At 2 Hz the flexible modes respond quasi-statically: the model is the
    // rigid wheelset on its suspension plus S = sum phi phi^T / w_k^2 over
    // the flexible modes, within (w / w_1)^2 + 2 zeta w / w_1 = 1e-3 of S
    // (first flexible mode 71 Hz). Vertically S is below 1e-3 of the rigid
    // receptance (the suspension's 1.22 MN/m against the axle's bending);
    // laterally it is not: a lateral force at the contact, r below the
    // axle, tilts the wheel on the web and the bending axle (11 % of the
    // rigid wheelset's lateral receptance).
    let d = design();
    let full = standard::default_model(&d).unwrap();
    let tilted = d.rigid.modes();
    let couplings = rigid::tilt_couplings(&tilted, 0, d.rigid.spin_inertia / 2.0);
    let rigid_only = WheelsetModel::new(tilted.into_iter().map(|t| t.mode).collect(), couplings).unwrap();
    let w = 2.0 * PI * 2.0;
    let (a, b) = (full.receptance(w, 0.0), rigid_only.receptance(w, 0.0));
    for i in 0..DOFS {
        // The static compliance, a loss factor's included (it stays at w -> 0).
        let s: Complex64 = full.modes()[6..].iter().map(|m| m.shape[i] * m.shape[i] / m.dynamic_stiffness(0.0)).sum();
        let flexible = a[(i, i)] - b[(i, i)];
        eprintln!("dof {i}: rigid {:.3e}, flexible {:.3e}, static {:.3e}", b[(i, i)].norm(), flexible.norm(), s.norm());
        assert!((flexible - s).norm() < 2e-3 * s.norm() + 1e-13 * b[(i, i)].norm(), "dof {i}: {flexible} vs {s}");
    }
    for wheel in 0..2 {
        let z = dof(wheel, Dir::Z);
        assert!((a[(z, z)] - b[(z, z)]).norm() < 1e-3 * b[(z, z)].norm());
    }
}

#[test]
fn the_table_reads_the_documented_example() {
    let text = "# a comment\n\
        name,frequency,damping_ratio,loss_factor,x0,y0,z0,theta0,x1,y1,z1,theta1,partner,coefficient\n\
        torsion,71.18,,0.02,-0.0645,0,0,0.129,0.0645,0,0,-0.129,,\n\
        first symmetric bending,87.0,0.01,,0,0.0694,-0.0041,0,0,-0.0694,-0.0041,0,,\n\
        \n\
        wheel 0 n=2 axial cos,360,0.001,,0,0.0962,0,0,0,0,0,0,wheel 0 n=2 axial sin,4\n\
        wheel 0 n=2 axial sin,360,0.001,,0,0,0,0,0,0,0,0,wheel 0 n=2 axial cos,-4\n";
    let t = table::parse(text).unwrap();
    assert_eq!(t.modes.len(), 4);
    assert_eq!(t.modes[0].damping, Damping::LossFactor(0.02));
    assert_eq!(t.modes[1].shape[dof(0, Dir::Z)], -0.0041);
    assert_eq!(t.couplings, vec![Gyroscopic { a: 2, b: 3, coefficient: 4.0 }]);
    let model = standard::table_model(&rigid(), &t).unwrap();
    assert_eq!(model.modes().len(), 10);
    assert!(model.couplings().iter().any(|c| (c.a, c.b, c.coefficient) == (8, 9, 4.0)));
}

#[test]
fn a_bad_table_is_reported_with_its_line() {
    let head = "name,frequency,damping_ratio,x0,y0,z0,theta0,x1,y1,z1,theta1";
    let err = |body: &str| table::parse(&format!("{head}\n{body}")).unwrap_err().to_string();
    assert_eq!(err("a,10,0.01,0,0,0,0,0,0,0,zero"), "line 2: theta1 `zero` is not a finite number");
    assert!(err("a,10,0.01,0,0,0,0,0,0,0,0\na,20,0.01,0,0,0,0,0,0,0,0").starts_with("line 3: mode `a` is named twice"));
    assert!(err("a,0,0.01,0,0,0,0,0,0,0,0").starts_with("line 2: frequency = 0 Hz must be >= 1 Hz"));
    assert!(err("a,10,1.5,0,0,0,0,0,0,0,0").starts_with("line 2: damping_ratio = 1.5 must be in (0, 1)"));
    assert!(err("a,10,0,0,0,0,0,0,0,0,0").contains("undamped mode"));
    assert!(err("a,10,0.01,0,0,0,0,0,0,0").starts_with("line 2:"), "{}", err("a,10,0.01,0,0,0,0,0,0,0"));
    assert!(err("").contains("no mode"));
    let e = table::parse("name,frequency,damping_ratio,x0,y0,z0,theta0,x1,y1,z1,speed\n").unwrap_err().to_string();
    assert!(e.starts_with("line 1: unknown column `speed`"), "{e}");
    let e = table::parse("name,frequency,x0,y0,z0,theta0,x1,y1,z1,theta1\n").unwrap_err().to_string();
    assert!(e.contains("damping column"), "{e}");
    let skew = format!("{head},partner,coefficient\na,10,0.01,0,0,0,0,0,0,0,0,b,2\nb,10,0.01,0,0,0,0,0,0,0,0,a,2");
    let e = table::parse(&skew).unwrap_err().to_string();
    assert!(e.starts_with("line 3: coefficient 2 contradicts line 2's 2"), "{e}");
    let unknown = format!("{head},partner,coefficient\na,10,0.01,0,0,0,0,0,0,0,0,c,2");
    assert!(table::parse(&unknown).unwrap_err().to_string().starts_with("line 2: partner `c` is not a mode"));
}

proptest::proptest! {
    #[test]
    fn a_written_table_reads_back_exactly(
        rows in proptest::collection::vec(
            (1.0f64..1e4, 1e-6f64..0.5, proptest::bool::ANY, proptest::array::uniform10(-1.0f64..1.0)),
            1..12,
        ),
        g in -10.0f64..10.0,
    ) {
        // Rust prints an f64 as the shortest text that reads back to the
        // same number: a table written with `{}` is read bit for bit.
        let mut text = format!("name,frequency,damping_ratio,loss_factor,{},partner,coefficient\n", table::SHAPE_COLUMNS.join(","));
        for (i, (f, d, ratio, shape)) in rows.iter().enumerate() {
            let (r, l) = if *ratio { (format!("{d}"), String::new()) } else { (String::new(), format!("{d}")) };
            let s: Vec<String> = shape.iter().map(|v| format!("{v}")).collect();
            let partner = if i == 1 { format!("\"mode, 0\",{g}") } else { ",".into() };
            text += &format!("\"mode, {i}\",{f},{r},{l},{},{partner}\n", s.join(","));
        }
        let t = table::parse(&text).unwrap();
        proptest::prop_assert_eq!(t.modes.len(), rows.len());
        for (m, (f, d, ratio, shape)) in t.modes.iter().zip(&rows) {
            proptest::prop_assert_eq!(m.frequency.to_bits(), f.to_bits());
            proptest::prop_assert_eq!(m.damping, if *ratio { Damping::Ratio(*d) } else { Damping::LossFactor(*d) });
            proptest::prop_assert_eq!(&m.shape, shape);
        }
        if rows.len() > 1 {
            proptest::prop_assert_eq!(t.couplings.clone(), vec![Gyroscopic { a: 1, b: 0, coefficient: g }]);
        }
    }

    #[test]
    fn any_text_is_a_table_or_an_error(text in "[a-z0-9,.#\"\\n -]{0,200}") {
        let _ = table::parse(&text);
    }
}
