//! The rail head's receptances in three directions (src/dynamics/track/section.rs,
//! continuous3.rs, discrete3.rs) against closed forms: where the directions
//! uncouple (the foot at the neutral axis and the shear centre), the
//! longitudinal receptance is the rod on an elastic foundation plus the
//! head height squared times the beam's rotational receptance (Hetenyi),
//! the lateral one the lateral beam's plus the torsion rod's; reciprocity
//! and passivity of the coupled matrices; the discrete track against an
//! independent finite row of supports, and with close supports against the
//! continuous model; the vertical freedom against the vertical models; the
//! head's rotation about the vertical (the 4 x 4 receptances) against the
//! lateral beam's rotational receptance, reciprocal and passive.
use corrugation::dynamics::track::TrackConfig;
use corrugation::dynamics::track::continuous3::Continuous3;
use corrugation::dynamics::track::discrete::DiscreteTrack;
use corrugation::dynamics::track::discrete3::{Discrete3, ROTATION_ARM};
use corrugation::dynamics::track::scattering::RailWaves;
use corrugation::dynamics::track::section::{Mat4, Mat6, Section, translations};
use nalgebra::SMatrix;
use num_complex::Complex64;
use std::f64::consts::PI;

fn c(v: f64) -> Complex64 {
    Complex64::new(v, 0.0)
}

/// The default track with the foot at the neutral axis and the shear
/// centre (the directions uncoupled by the supports and the inertia).
fn uncoupled() -> TrackConfig {
    let mut t = TrackConfig::default();
    t.rail.transverse.neutral_axis_height = 0.0;
    t.rail.transverse.shear_centre_height = 0.0;
    t
}

/// `1 / (2 pi) int N(k^2) / P(k^2) dk` for `P(S) = a S^2 + b S + c0` and
/// `N(S) = n1 S + n0`, by residues: `sum_m N(S_m) / (a (S_m - S_o) 2 q_m)`,
/// `q_m = sqrt(-S_m)` with `Re q_m > 0` (`1/(2 pi) int dk / (k^2 + q^2) =
/// 1 / (2 q)`).
fn quadratic_integral(a: Complex64, b: Complex64, c0: Complex64, n1: Complex64, n0: Complex64) -> Complex64 {
    let disc = (b * b - 4.0 * a * c0).sqrt();
    let roots = [(-b + disc) / (2.0 * a), (-b - disc) / (2.0 * a)];
    let mut g = c(0.0);
    for (m, &s) in roots.iter().enumerate() {
        let mut q = (-s).sqrt();
        if q.re < 0.0 {
            q = -q;
        }
        g += (n1 * s + n0) / (a * (s - roots[1 - m]) * 2.0 * q);
    }
    g
}

/// A Timoshenko beam (`EI*`, `kGA*`, mass `m`, rotary inertia `rho I`) on a
/// Winkler foundation `s_w` (on the displacement) and a rotational one
/// `s_r` (on the rotation), per length: (displacement per force, rotation
/// per moment) at the load, by residues.
fn timoshenko_on_foundation(
    ei: Complex64,
    kga: Complex64,
    m: f64,
    ri: f64,
    s_w: Complex64,
    s_r: Complex64,
    w: f64,
) -> (Complex64, Complex64) {
    let cw = s_w - m * w * w;
    let e = kga - ri * w * w + s_r;
    // det = (kGA S + cw)(EI S + e) - kGA^2 S.
    let (a, b, c0) = (kga * ei, kga * e + cw * ei - kga * kga, cw * e);
    (quadratic_integral(a, b, c0, ei, e), quadratic_integral(a, b, c0, kga, cw))
}

/// Pad in series with the sleeper mass on the ballast (per support).
fn series(kp: f64, kb: f64, eta_p: f64, eta_b: f64, ms: f64, w: f64) -> Complex64 {
    let (kp, kb) = (Complex64::new(kp, kp * eta_p), Complex64::new(kb, kb * eta_b));
    kp * (kb - ms * w * w) / (kp + kb - ms * w * w)
}

/// The closed forms of the uncoupled head (x, y, z diagonal) at `w`.
fn closed_forms(t: &TrackConfig, w: f64) -> [Complex64; 3] {
    let r = &t.rail;
    let tr = &r.transverse;
    let s3 = &t.supports;
    let d = t.sleeper_spacing;
    let loss = Complex64::new(1.0, t.rail_loss_factor);
    let (eta_p, eta_b) = (0.25, 1.0);
    let pad = Complex64::new(t.pad_stiffness, t.pad_stiffness * eta_p);
    let pitch = pad * (s3.pad_length.powi(2) / 12.0) / d;
    let roll = pad * (s3.pad_width.powi(2) / 12.0) / d;
    let vertical = series(t.pad_stiffness, t.ballast_stiffness, eta_p, eta_b, t.sleeper_mass, w) / d;
    let longitudinal =
        series(s3.pad_longitudinal_stiffness, s3.ballast_longitudinal_stiffness, eta_p, eta_b, t.sleeper_mass, w) / d;
    let lateral = series(s3.pad_lateral_stiffness, s3.ballast_lateral_stiffness, eta_p, eta_b, t.sleeper_mass, w) / d;
    let (ww, pp) = timoshenko_on_foundation(
        loss * r.bending_stiffness,
        loss * r.shear_stiffness,
        r.mass,
        r.rotary_inertia,
        vertical,
        pitch,
        w,
    );
    let (vv, _) = timoshenko_on_foundation(
        loss * tr.lateral_bending_stiffness,
        loss * tr.lateral_shear_stiffness,
        r.mass,
        tr.lateral_rotary_inertia,
        lateral,
        c(0.0),
        w,
    );
    // Rods on elastic foundations: 1 / (2 EA gamma), gamma^2 = (s - m w^2) / EA.
    let rod = |stiffness: Complex64, foundation: Complex64, inertia: f64| {
        let mut g = ((foundation - inertia * w * w) / stiffness).sqrt();
        if g.re < 0.0 {
            g = -g;
        }
        1.0 / (2.0 * stiffness * g)
    };
    let uu = rod(loss * tr.axial_stiffness, longitudinal, r.mass);
    let ff = rod(loss * tr.torsional_stiffness, roll, tr.polar_inertia);
    let h = tr.height;
    [uu + h * h * pp, vv + h * h * ff, ww]
}

fn rel(a: Complex64, b: Complex64) -> f64 {
    (a - b).norm() / b.norm()
}

#[test]
fn uncoupled_continuous_head_against_the_closed_forms() {
    let t = uncoupled();
    let model = Continuous3::new(&t, 0.0);
    for f in [10.0, 100.0, 400.0, 1000.0, 2500.0, 5000.0] {
        let w = 2.0 * PI * f;
        let a = model.head_receptances(w, &[0.0]).unwrap()[0];
        let closed = closed_forms(&t, w);
        for (i, cf) in closed.iter().enumerate() {
            let e = rel(a[(i, i)], *cf);
            eprintln!("{f} Hz, {}: model {:.4e}, closed form {cf:.4e} ({e:.1e})", ["x", "y", "z"][i], a[(i, i)]);
            // Both are exact: the tolerance is round-off of the 12 x 12
            // eigendecomposition.
            assert!(e < 1e-8, "{f} Hz, direction {i}: {} vs {cf}", a[(i, i)]);
        }
        // Uncoupled: the cross terms vanish.
        for (i, j) in [(0, 1), (0, 2), (1, 2)] {
            assert!(a[(i, j)].norm() < 1e-9 * a[(i, i)].norm().max(a[(j, j)].norm()), "{f} Hz ({i},{j})");
        }
    }
}

#[test]
fn longitudinal_head_is_hetenyis_rod_plus_the_rotation_in_the_euler_bernoulli_limit() {
    // Euler-Bernoulli bending (shear stiff, no rotary inertia), no pitch
    // restraint: 1 / (2 EA gamma) + h^2 / (4 EI beta), beta^4 = (s - m
    // w^2) / (4 EI) (Hetenyi 1946: a moment M turns the beam by M / (4 EI
    // beta)); the shear left, EI |beta|^2 / kGA, is at most 2e-5 here (700
    // Hz), which bounds the difference.
    let mut t = uncoupled();
    t.rail.shear_stiffness *= 1e4;
    t.rail.rotary_inertia = 0.0;
    t.supports.pad_length = 0.0;
    let model = Continuous3::new(&t, 0.0);
    let loss = Complex64::new(1.0, t.rail_loss_factor);
    let d = t.sleeper_spacing;
    for f in [20.0, 150.0, 700.0] {
        let w = 2.0 * PI * f;
        let s = series(t.pad_stiffness, t.ballast_stiffness, 0.25, 1.0, t.sleeper_mass, w) / d;
        let sx = series(
            t.supports.pad_longitudinal_stiffness,
            t.supports.ballast_longitudinal_stiffness,
            0.25,
            1.0,
            t.sleeper_mass,
            w,
        ) / d;
        let ei = loss * t.rail.bending_stiffness;
        let ea = loss * t.rail.transverse.axial_stiffness;
        let beta4 = (s - t.rail.mass * w * w) / (4.0 * ei);
        let mut beta = beta4.sqrt().sqrt();
        if beta.re < 0.0 {
            beta = -beta;
        }
        let mut gamma = ((sx - t.rail.mass * w * w) / ea).sqrt();
        if gamma.re < 0.0 {
            gamma = -gamma;
        }
        let h = t.rail.transverse.height;
        let hetenyi = 1.0 / (2.0 * ea * gamma) + h * h / (4.0 * ei * beta);
        let a = model.head_receptances(w, &[0.0]).unwrap()[0][(0, 0)];
        eprintln!("{f} Hz: model {a:.5e}, Hetenyi {hetenyi:.5e}");
        assert!(rel(a, hetenyi) < 5e-5, "{f} Hz: {a} vs {hetenyi}");
    }
}

#[test]
fn the_heads_rotation_about_the_vertical_is_the_lateral_beams_rotational_receptance() {
    // Uncoupled (the foot at the neutral axis and the shear centre), the
    // contact y_c right of the centre line: a moment about z turns the
    // section by the lateral Timoshenko beam's rotational receptance on its
    // lateral foundation (no yaw restraint of the pads), a longitudinal
    // force at y_c by -y_c times it (its moment about z), a lateral or
    // vertical force under the load not at all (the point response's
    // slope is odd). Both exact: round-off of the eigendecomposition.
    let t = uncoupled();
    let y_c = 0.012;
    let model = Continuous3::new(&t, y_c);
    let loss = Complex64::new(1.0, t.rail_loss_factor);
    let s3 = &t.supports;
    for f in [10.0, 100.0, 400.0, 1000.0, 2500.0, 5000.0] {
        let w = 2.0 * PI * f;
        let lateral = series(s3.pad_lateral_stiffness, s3.ballast_lateral_stiffness, 0.25, 1.0, t.sleeper_mass, w)
            / t.sleeper_spacing;
        let tr = &t.rail.transverse;
        let (_, rot) = timoshenko_on_foundation(
            loss * tr.lateral_bending_stiffness,
            loss * tr.lateral_shear_stiffness,
            t.rail.mass,
            tr.lateral_rotary_inertia,
            lateral,
            c(0.0),
            w,
        );
        let a = model.head_receptances4(w, &[0.0]).unwrap()[0];
        eprintln!("{f} Hz: yaw per moment {:.4e}, closed form {rot:.4e} ({:.1e})", a[(3, 3)], rel(a[(3, 3)], rot));
        assert!(rel(a[(3, 3)], rot) < 1e-8, "{f} Hz: {} vs {rot}", a[(3, 3)]);
        assert!(rel(a[(3, 0)], -y_c * rot) < 1e-8 && rel(a[(0, 3)], -y_c * rot) < 1e-8, "{f} Hz");
        assert!(a[(3, 1)].norm() < 1e-9 * rot.norm() && a[(3, 2)].norm() < 1e-9 * rot.norm(), "{f} Hz: {a}");
        // The translations' block is the 3 x 3 receptance's.
        let a3 = model.head_receptances(w, &[0.0]).unwrap()[0];
        assert!((translations(&a) - a3).norm() <= 1e-14 * a3.norm(), "{f} Hz");
    }
}

/// `a` with its rotation row and column per [`ROTATION_ARM`] (every entry
/// in m/N), for norms.
fn on_the_arm(a: &Mat4) -> Mat4 {
    let s = [1.0, 1.0, 1.0, ROTATION_ARM];
    Mat4::from_fn(|r, col| a[(r, col)] * (s[r] * s[col]))
}

/// Reciprocity: the response at 1 to a force at 0 is the transposed
/// response at 0 to a force at 1.
fn reciprocal<const N: usize>(a: &SMatrix<Complex64, N, N>, b_t: &SMatrix<Complex64, N, N>, what: &str) {
    let scale = a.norm();
    assert!((a - b_t).norm() < 1e-9 * scale, "{what}: not reciprocal: {a} vs {b_t}");
}

/// Passivity: the power a force F puts in, -w Im(F^H A F) / 2, is
/// positive for every F: (A - A^H) / (2 i) is negative semi-definite.
fn passive<const N: usize>(a: &SMatrix<Complex64, N, N>, what: &str) {
    let anti = (a - a.adjoint()) / Complex64::new(0.0, 2.0);
    let eig = nalgebra::DMatrix::from_iterator(N, N, anti.iter().copied()).symmetric_eigenvalues();
    assert!(eig.iter().all(|e| *e <= 1e-12 * a.norm()), "{what}: eigenvalues {eig}");
}

/// The continuous head's point and +-0.9 m transfer receptances `p` and
/// the discrete head's at 0.11 m and between 0.11 and 0.47 m `d` (both
/// ways) reciprocal, the point receptances passive.
fn reciprocal_and_passive<const N: usize>(p: &[SMatrix<Complex64, N, N>], d: &[SMatrix<Complex64, N, N>], what: &str) {
    // The point receptance symmetric (not enforced by the residues).
    reciprocal(&p[0], &p[0].transpose(), &format!("{what}: continuous point"));
    reciprocal(&p[1], &p[2].transpose(), &format!("{what}: continuous transfer"));
    reciprocal(&d[0], &d[0].transpose(), &format!("{what}: discrete point"));
    reciprocal(&d[1], &d[2].transpose(), &format!("{what}: discrete transfer"));
    passive(&p[0], &format!("{what}: continuous"));
    passive(&d[0], &format!("{what}: discrete"));
}

#[test]
fn coupled_receptances_are_reciprocal_and_passive() {
    // The 3 x 3 receptances, and the 4 x 4 with the rotation about z (its
    // row and column per the integral's arm: every entry in m/N).
    let t = TrackConfig::default();
    let cont = Continuous3::new(&t, 0.012);
    let disc = Discrete3::new(&t, 0.012);
    let (distances, pairs) = ([0.0, 0.9, -0.9], [(0.11, 0.11), (0.11, 0.47), (0.47, 0.11)]);
    for f in [60.0, 500.0, 1050.0, 3000.0] {
        let w = 2.0 * PI * f;
        let (p, d) = (cont.head_receptances(w, &distances).unwrap(), disc.head_receptances(&pairs, w).unwrap());
        reciprocal_and_passive(&p, &d, &format!("3 x 3, {f} Hz"));
        let arm = |a: Vec<Mat4>| -> Vec<Mat4> { a.iter().map(on_the_arm).collect() };
        let (p4, d4) =
            (arm(cont.head_receptances4(w, &distances).unwrap()), arm(disc.head_receptances4(&pairs, w).unwrap()));
        reciprocal_and_passive(&p4, &d4, &format!("4 x 4, {f} Hz"));
        // Off the sleeper and mid-span the bay turns the head about z
        // under a lateral force.
        assert!(d4[0][(3, 1)].norm() > 1e-3 * d4[0][(1, 1)].norm(), "{f} Hz: {}", d4[0]);
    }
}

#[test]
fn discrete_head_against_a_long_finite_row_of_supports() {
    // An independent model: the free rail (its Green's matrix by residues,
    // the waves of src/dynamics/track/waves.rs)
    // loaded by the unit force and by the reactions K_s q_n of the 201
    // supports within +-60 m, q_m + sum_n G(x_m - x_n) K_s q_n = G(x_m - x0)
    // solved directly (1206 unknowns), the section at x1 then G(x1 - x0) -
    // sum_n G(x1 - x_n) K_s q_n; against the Floquet matrices (eq. 1)
    // below, near and above the pinned-pinned resonance.
    use faer::Mat;
    use faer::linalg::solvers::Solve;
    // A rail loss factor of 0.15 lets the waves that the truncation of the
    // row reflects decay before they return (the longitudinal waves above
    // their 190 Hz cut-on carry only the rail's damping: 280 m at 0.02).
    let t = TrackConfig { rail_loss_factor: 0.15, ..TrackConfig::default() };
    let model = Discrete3::new(&t, 0.01);
    let section = Section::new(&t, 0.01);
    let d = t.sleeper_spacing;
    let supports: Vec<f64> = (-100..=100).map(|n| n as f64 * d).collect();
    let n = supports.len();
    let mut worst = 0.0f64;
    for f in [120.0, 1050.0, 2200.0] {
        let w = 2.0 * PI * f;
        let ks = section.support(w);
        let waves = model.free_waves(w).unwrap();
        let free_rail = |x: f64| waves.green(x);
        // Green's matrices at every support distance (i - j) d.
        let by_offset: Vec<Mat6> = (-(n as i64 - 1)..=(n as i64 - 1)).map(|o| free_rail(o as f64 * d)).collect();
        let gk: Vec<Mat6> = by_offset.iter().map(|g| g * ks).collect();
        let a = Mat::<Complex64>::from_fn(6 * n, 6 * n, |r, col| {
            let (i, a) = (r / 6, r % 6);
            let (j, b) = (col / 6, col % 6);
            gk[i + n - 1 - j][(a, b)] + if r == col { c(1.0) } else { c(0.0) }
        });
        let lu = a.partial_piv_lu();
        for (x0, x1) in [(0.0, 0.0), (0.3, 0.3), (0.13, 0.13), (0.13, 0.95)] {
            let to_supports: Vec<Mat6> = supports.iter().map(|xm| free_rail(xm - x0)).collect();
            let rhs = Mat::<Complex64>::from_fn(6 * n, 6, |r, b| to_supports[r / 6][(r % 6, b)]);
            let q = lu.solve(&rhs);
            let mut g = free_rail(x1 - x0);
            for (m, xm) in supports.iter().enumerate() {
                let qm = Mat6::from_fn(|a, b| q[(6 * m + a, b)]);
                g -= free_rail(x1 - xm) * ks * qm;
            }
            let direct = section.head(&g);
            let floquet = model.head_receptances(&[(x0, x1)], w).unwrap()[0];
            let e = (direct - floquet).norm() / floquet.norm();
            // With the rotation about z (per the integral's arm).
            let (direct4, floquet4) =
                (on_the_arm(&section.head4(&g)), on_the_arm(&model.head_receptances4(&[(x0, x1)], w).unwrap()[0]));
            let e4 = (direct4 - floquet4).norm() / floquet4.norm();
            eprintln!("{f} Hz, x0 {x0}, x1 {x1}: |Floquet - finite row| / |Floquet| = {e:.2e}, 4 x 4 {e4:.2e}");
            worst = worst.max(e).max(e4);
            // The zone integral's tolerance is 1e-5 of the supports' share.
            assert!(e < 1e-4, "{f} Hz, x0 {x0}, x1 {x1}: finite {direct} vs Floquet {floquet}");
            assert!(e4 < 1e-4, "{f} Hz, x0 {x0}, x1 {x1}: finite {direct4} vs Floquet {floquet4}");
        }
    }
    eprintln!("Floquet against the finite row of supports: within {worst:.2e}");
}

#[test]
fn close_supports_give_the_continuous_model() {
    // Supports 0.1 m apart carrying a sixth of the 0.6 m bay's each (the
    // same stiffness and mass per length): the discrete head against the
    // continuous model at every entry, within 3 % of the largest (the
    // vertical model's test allows the same for its 0.1 m spacing).
    let base = TrackConfig::default();
    let mut t = base;
    let r = 0.1 / base.sleeper_spacing;
    t.sleeper_spacing = 0.1;
    t.pad_stiffness *= r;
    t.ballast_stiffness *= r;
    t.sleeper_mass *= r;
    t.supports.pad_lateral_stiffness *= r;
    t.supports.pad_longitudinal_stiffness *= r;
    t.supports.ballast_lateral_stiffness *= r;
    t.supports.ballast_longitudinal_stiffness *= r;
    let cont = Continuous3::new(&base, 0.01);
    let disc = Discrete3::new(&t, 0.01);
    for f in [50.0, 200.0, 600.0] {
        let w = 2.0 * PI * f;
        let a = disc.head_receptances(&[(0.05, 0.05)], w).unwrap()[0];
        let b = cont.head_receptances(w, &[0.0]).unwrap()[0];
        for i in 0..3 {
            let e = (a[(i, i)] - b[(i, i)]).norm() / b[(i, i)].norm();
            eprintln!(
                "{f} Hz {}: discrete {:.4e}, continuous {:.4e} ({e:.1e})",
                ["x", "y", "z"][i],
                a[(i, i)],
                b[(i, i)]
            );
            assert!(e < 0.03, "{f} Hz direction {i}");
        }
        assert!((a - b).norm() < 0.03 * b.norm(), "{f} Hz: {a} vs {b}");
    }
}

#[test]
fn vertical_freedom_of_the_discrete_head_is_the_vertical_models() {
    // Without the pitch restraint and with the longitudinal pads at the
    // neutral axis, a vertical force moves the section as in the vertical
    // model (src/dynamics/track/discrete.rs): the same Floquet method, there with
    // 769 harmonics, a tail in closed form and a 768-point midpoint rule
    // over the zone, here with the lattice sums in closed form and an
    // adaptive rule; they differ by that model's truncation (measured
    // 1e-4 and less).
    let mut t = uncoupled();
    t.supports.pad_length = 0.0;
    let model = Discrete3::new(&t, 0.0);
    let vertical = DiscreteTrack::new(&t);
    let mut worst = 0.0f64;
    for f in [100.0, 1000.0, 3000.0] {
        let w = 2.0 * PI * f;
        for x in [0.0, 0.17, 0.3] {
            let a = model.head_receptances(&[(x, x)], w).unwrap()[0];
            let b = vertical.receptance(x, w);
            worst = worst.max(rel(a[(2, 2)], b));
            assert!(rel(a[(2, 2)], b) < 5e-4, "{f} Hz, x {x}: {} vs {b}", a[(2, 2)]);
            // A vertical force does not move the head across; along only
            // where it turns the section (not above a sleeper or mid-span,
            // where the bay is symmetric about the load).
            assert!(a[(1, 2)].norm() < 1e-9 * b.norm(), "{f} Hz, x {x}: {a}");
            if x != 0.17 {
                assert!(a[(0, 2)].norm() < 1e-6 * b.norm(), "{f} Hz, x {x}: {a}");
            } else {
                assert!(a[(0, 2)].norm() > 1e-3 * b.norm(), "{f} Hz, x {x}: {a}");
            }
        }
    }
    eprintln!("vertical models within {worst:.1e}");
}
