//! Linear frequency-domain wheel-track model (`corrugation::dynamics`):
//! static and high-frequency limits, resonances against hand formulas, and
//! the periodic application of H(f) to a rail profile.
use corrugation::dynamics::model::{Directions, Track, VehicleTrack, Wheel};
use corrugation::dynamics::receptance::{SWEEP_MAX_HZ, SWEEP_MIN_HZ};
use corrugation::dynamics::wheelset::side::Wheel3;
use corrugation::dynamics::{
    ContactVariations, ReceptanceModel, TrackDynamics, TrackParams, WheelParams, hertz_stiffness,
    winkler_point_receptance,
};
use corrugation::hertz::{Curvatures, Elastic, HertzShape};
use num_complex::Complex64;
use std::f64::consts::PI;

fn rel(x: Complex64, y: Complex64) -> f64 {
    (x - y).norm() / y.norm()
}

/// k_H of the paper's concave wheel on the UIC60 head at N0 = 100 kN
/// (R = 0.5 m, wheel profile -0.409 m, rail head 0.3 m, E = 210 GPa, nu = 0.3).
fn paper_contact_stiffness() -> f64 {
    let steel = Elastic { young_modulus: 2.1e11, poisson_ratio: 0.3 };
    let shape = HertzShape::new(Curvatures::wheel_on_rail(0.5, -0.409, 0.3), steel).unwrap();
    let n0 = 1e5;
    hertz_stiffness(n0, shape.patch(n0).unwrap().approach)
}

fn default_model() -> ReceptanceModel {
    ReceptanceModel::new(TrackParams::uic60_default(), WheelParams::default_freight(), paper_contact_stiffness())
        .unwrap()
}

fn undamped(mut t: TrackParams) -> TrackParams {
    t.pad_loss_factor = 0.0;
    t.ballast_loss_factor = 0.0;
    t
}

#[test]
fn hertz_stiffness_matches_the_hertz_solver_derivative() {
    // dN/d delta by central differences of the Hertz solver's approach.
    let steel = Elastic { young_modulus: 2.1e11, poisson_ratio: 0.3 };
    let shape = HertzShape::new(Curvatures::wheel_on_rail(0.5, -0.409, 0.3), steel).unwrap();
    let (n0, dn) = (1e5, 10.0);
    let d_delta = shape.patch(n0 + dn).unwrap().approach - shape.patch(n0 - dn).unwrap().approach;
    let fd = 2.0 * dn / d_delta;
    let k = paper_contact_stiffness();
    assert!((k - fd).abs() / fd < 1e-6, "k_H {k} vs finite difference {fd}");
    // 1.5 * 100 kN / 0.0818 mm (CONTACT's approach for this geometry).
    assert!((k - 1.834e9).abs() / 1.834e9 < 2e-3, "k_H = {k}");
}

#[test]
fn static_limit_is_the_winkler_beam() {
    let omega = 2.0 * PI * 1e-3;
    // Undamped support: Hetenyi's 1/(8 EI beta^3), beta = (s / 4 EI)^(1/4), s = s_p s_b / (s_p + s_b).
    let t = undamped(TrackParams::uic60_default());
    let s = t.pad_stiffness * t.ballast_stiffness / (t.pad_stiffness + t.ballast_stiffness);
    let beta = (s / (4.0 * t.bending_stiffness)).powf(0.25);
    let hetenyi = 1.0 / (8.0 * t.bending_stiffness * beta.powi(3));
    let alpha_r = t.rail_receptance(omega);
    assert!(rel(alpha_r, Complex64::new(hetenyi, 0.0)) < 1e-6, "{alpha_r} vs {hetenyi}");
    assert!((t.static_rail_receptance() - hetenyi).abs() / hetenyi < 1e-14);
    // UIC60 on this support: about 154 kN/mm at the rail head.
    assert!((1.0 / hetenyi - 1.5405e8).abs() / 1.5405e8 < 1e-3, "static stiffness {}", 1.0 / hetenyi);

    // Damped support: the same formula with the complex series stiffness, root taken in polar form.
    let d = TrackParams::uic60_default();
    let sp = Complex64::new(d.pad_stiffness, d.pad_stiffness * d.pad_loss_factor);
    let sb = Complex64::new(d.ballast_stiffness, d.ballast_stiffness * d.ballast_loss_factor);
    let b4 = sp * sb / (sp + sb) / (4.0 * d.bending_stiffness);
    let beta_c = Complex64::from_polar(b4.norm().powf(0.25), b4.arg() / 4.0);
    let expect = 1.0 / (8.0 * d.bending_stiffness * beta_c.powi(3));
    assert!(rel(d.rail_receptance(omega), expect) < 1e-6, "{} vs {expect}", d.rail_receptance(omega));
    assert!(expect.im < 0.0, "damped static receptance must lag: {expect}");

    // Contact + track compliances in series; with the wheel held still, H is their inverse.
    let k_h = paper_contact_stiffness();
    let held = ReceptanceModel::new(t, WheelParams { unsprung_mass: f64::INFINITY }, k_h).unwrap();
    let (aw, ac, ar) = held.receptances(omega);
    assert_eq!(aw, Complex64::new(0.0, 0.0));
    let series = Complex64::new(1.0 / k_h + hetenyi, 0.0);
    assert!(rel(ac + ar, series) < 1e-6, "{} vs {series}", ac + ar);
    let h = held.force_per_roughness(1e-3);
    assert!(rel(h, 1.0 / series) < 1e-6, "H {h} vs {}", 1.0 / series);
}

#[test]
fn low_frequency_wheel_follows_the_profile() {
    // Below all resonances H -> -M w^2: the wheel rides the profile, a crest unloads it.
    let m = default_model();
    for f in [0.1, 0.5] {
        let w = 2.0 * PI * f;
        let expect = Complex64::new(-m.wheel.unsprung_mass * w * w, 0.0);
        let h = m.force_per_roughness(f);
        assert!(rel(h, expect) < 1e-3, "f = {f}: H = {h}, -M w^2 = {expect}");
    }
}

#[test]
fn high_frequency_limit_is_the_contact_spring() {
    let m = default_model();
    let k_h = m.contact_stiffness;
    let (ei, mr) = (m.track.bending_stiffness, m.track.rail_mass);
    let mut prev_dev = f64::INFINITY;
    for f in [5e3, 2e4, 2e5] {
        let w = 2.0 * PI * f;
        let (aw, ac, ar) = m.receptances(w);
        // Wheel: exactly the mass line.
        let mass_line = -1.0 / (m.wheel.unsprung_mass * w * w);
        assert!(aw.im == 0.0 && (aw.re - mass_line).abs() <= 1e-15 * mass_line.abs(), "{aw} vs {mass_line}");
        assert_eq!(ac, Complex64::new(1.0 / k_h, 0.0));
        // Rail: the free infinite beam -(1 + i)/(4 EI k^3), k^4 = m_r w^2 / EI (support negligible).
        let kb = (mr * w * w / ei).powf(0.25);
        let free = Complex64::new(-1.0, -1.0) / (4.0 * ei * kb.powi(3));
        let tol = if f >= 2e4 { 1e-3 } else { 1e-2 };
        assert!(rel(ar, free) < tol, "f = {f}: alpha_r {ar} vs free beam {free}");
        // H = k_H / (1 + k_H (alpha_w + alpha_r)) -> k_H; the deviation is first order in k_H (alpha_w + alpha_r).
        let h = m.force_per_roughness(f);
        let dev = rel(h, Complex64::new(k_h, 0.0));
        let first_order = k_h * (aw + ar).norm();
        assert!((dev - first_order).abs() < 0.1 * first_order, "f = {f}: |H/k_H - 1| = {dev} vs {first_order}");
        assert!(dev < prev_dev, "deviation from k_H must shrink with f");
        prev_dev = dev;
    }
    // At 20 kHz H is within 2 % of k_H (k_H |alpha_r| = 1.3 %), at 200 kHz within 0.1 %.
    assert!(rel(m.force_per_roughness(2e4), Complex64::new(k_h, 0.0)) < 2e-2);
    assert!(rel(m.force_per_roughness(2e5), Complex64::new(k_h, 0.0)) < 1e-3);
}

#[test]
fn track_is_passive_over_the_sweep() {
    // exp(+i w t): Im alpha_r <= 0 and hence Im H >= 0 at every frequency.
    let m = default_model();
    let undamped_track = undamped(m.track);
    for i in 0..=400 {
        let f = 10f64.powf(i as f64 / 100.0); // 1 Hz .. 10 kHz
        let w = 2.0 * PI * f;
        let ar = m.track.rail_receptance(w);
        assert!(ar.im < 0.0, "f = {f}: Im alpha_r = {}", ar.im);
        assert!(m.force_per_roughness(f).im >= 0.0, "f = {f}");
        assert!(undamped_track.rail_receptance(w).im <= 0.0, "undamped, f = {f}");
    }
    // The undamped track radiates above the cut-on (net stiffness < 0): Im alpha_r < 0 there, 0 below.
    let below = undamped_track.rail_receptance(2.0 * PI * 10.0);
    assert!(below.im.abs() <= 1e-12 * below.norm(), "undamped below cut-on {below}");
    let above = undamped_track.rail_receptance(2.0 * PI * 3000.0);
    assert!(above.im < -0.1 * above.norm(), "undamped above cut-on {above}");
    // And agrees with the direct formula on the negative real axis.
    let net = undamped_track.foundation_stiffness(2.0 * PI * 3000.0)
        - undamped_track.rail_mass * (2.0 * PI * 3000.0f64).powi(2);
    assert!(rel(above, winkler_point_receptance(undamped_track.bending_stiffness, net)) < 1e-15);
}

#[test]
fn rigid_track_resonance_is_wheel_on_contact_spring() {
    // Support 1e5 times stiffer than UIC60's: the rail barely moves.
    let mut t = TrackParams::uic60_default();
    t.pad_stiffness = 1e14;
    t.ballast_stiffness = 1e14;
    let k_h = paper_contact_stiffness();
    let m = ReceptanceModel::new(t, WheelParams::default_freight(), k_h).unwrap();
    let hand = (k_h / 600.0).sqrt() / (2.0 * PI);
    assert!((m.wheel_on_contact_spring_frequency() - hand).abs() < 1e-12 * hand);
    let peaks = m.resonances(SWEEP_MIN_HZ, SWEEP_MAX_HZ, 4001);
    assert_eq!(peaks.len(), 1, "peaks {peaks:?}");
    assert!((peaks[0] - hand).abs() < 0.01 * hand, "peak {} Hz vs sqrt(k_H/M)/2pi = {hand} Hz", peaks[0]);
    // The residual rail compliance lowers it a little (series spring), never raises it.
    assert!(peaks[0] < hand);
    let described = m.describe_resonances();
    assert_eq!(described.len(), 1);
    assert!(described[0].0.contains("contact spring"), "{described:?}");
}

#[test]
fn uic60_default_resonances() {
    let m = default_model();
    let peaks = m.describe_resonances();
    for (label, f) in &peaks {
        println!("{f:9.2} Hz  {label}");
    }
    // P2 (wheel unsprung mass on the track) lies in the usual 50-100 Hz band.
    let p2: Vec<f64> = peaks.iter().filter(|(l, _)| l.starts_with("P2")).map(|p| p.1).collect();
    assert_eq!(p2.len(), 1, "{peaks:?}");
    assert!((50.0..100.0).contains(&p2[0]), "P2 at {} Hz", p2[0]);
    assert!(peaks[0].1 == p2[0], "P2 must be the lowest peak: {peaks:?}");
    // P1 (rail on the contact spring) in the kHz range.
    let p1: Vec<f64> = peaks.iter().filter(|(l, _)| l.starts_with("P1")).map(|p| p.1).collect();
    assert_eq!(p1.len(), 1, "{peaks:?}");
    assert!((500.0..2500.0).contains(&p1[0]), "P1 at {} Hz", p1[0]);
    // Each reported frequency is a local maximum of |H|.
    for &(_, f) in &peaks {
        let a = m.force_per_roughness(f).norm();
        for g in [f * (1.0 - 1e-4), f * (1.0 + 1e-4)] {
            assert!(m.force_per_roughness(g).norm() <= a, "{f} Hz is not a maximum");
        }
    }
}

/// r(X) = A cos(k X + phi) sampled on one period.
fn sinusoid(n: usize, dx: f64, harmonic: usize, amplitude: f64, phase: f64) -> Vec<f64> {
    let k = 2.0 * PI * harmonic as f64 / (n as f64 * dx);
    (0..n).map(|j| amplitude * (k * j as f64 * dx + phase).cos()).collect()
}

#[test]
fn dynamic_force_of_a_sinusoid_is_h_times_the_amplitude() {
    let m = default_model();
    let (dx, amplitude, phase) = (1e-3, 10e-6, 0.3);
    // Power-of-two-free and prime-factor lengths; a forward and a backward wheel.
    for (n, harmonic, speed) in [(1000, 25, 30.0), (999, 7, 22.2), (1000, 25, -30.0), (1024, 300, 80.0)] {
        let profile = sinusoid(n, dx, harmonic, amplitude, phase);
        let length = n as f64 * dx;
        let f = speed * harmonic as f64 / length; // V / lambda, signed by the direction
        let h = m.force_per_roughness(f);
        let k = 2.0 * PI * harmonic as f64 / length;
        let force = m.dynamic_force(&profile, dx, speed);
        let scale = amplitude * h.norm();
        for (j, got) in force.iter().enumerate() {
            let expect = amplitude * h.norm() * (k * j as f64 * dx + phase + h.arg()).cos();
            assert!((got - expect).abs() < 1e-9 * scale, "n = {n}, V = {speed}, j = {j}: {got} vs {expect}");
        }
        // The vehicle-track model of this one wheel gives the same force bit
        // for bit, as the normal force alone.
        let track = Track::Continuous { vertical: m.track, head: None };
        let wheel = Wheel::vertical(0.0, Wheel3::new(m.wheel.unsprung_mass, 0.46), m.contact_stiffness, 1e5);
        let model = VehicleTrack::new(track, vec![wheel], Directions::Vertical, n, dx, speed).unwrap();
        let dynamics: &dyn TrackDynamics = &model;
        assert_eq!(
            dynamics.contact_variations(std::slice::from_ref(&profile), dx, speed),
            [ContactVariations::Normal(force)]
        );
    }
    // Backward travel conjugates H: the phase lag flips sign.
    let h = m.force_per_roughness(750.0);
    assert_eq!(m.force_per_roughness(-750.0), h.conj());
}

#[test]
fn dynamic_force_drops_the_mean_and_superposes() {
    let m = default_model();
    let (n, dx, speed) = (800, 5e-4, 25.0);
    let constant = vec![3e-3; n];
    let k_h = m.contact_stiffness;
    let zero = m.dynamic_force(&constant, dx, speed);
    assert!(
        zero.iter().all(|f| f.abs() < 1e-12 * 3e-3 * k_h),
        "max {}",
        zero.iter().fold(0.0f64, |a, f| a.max(f.abs()))
    );
    // Mean + two harmonics: the force is the sum of the harmonics' forces.
    let a = sinusoid(n, dx, 10, 5e-6, 0.0);
    let b = sinusoid(n, dx, 57, 2e-6, 1.1);
    let sum: Vec<f64> = (0..n).map(|j| 1e-3 + a[j] + b[j]).collect();
    let fa = m.dynamic_force(&a, dx, speed);
    let fb = m.dynamic_force(&b, dx, speed);
    let fs = m.dynamic_force(&sum, dx, speed);
    let scale = fa.iter().chain(&fb).fold(0.0f64, |acc, f| acc.max(f.abs()));
    for j in 0..n {
        assert!((fs[j] - fa[j] - fb[j]).abs() < 1e-9 * scale, "j = {j}");
    }
    let mean = fs.iter().sum::<f64>() / n as f64;
    assert!(mean.abs() < 1e-12 * scale, "mean force {mean}");
    // Deterministic: the same input gives bit-identical output.
    assert_eq!(m.dynamic_force(&sum, dx, speed), fs);
    // A standing wheel sees no dynamic force (H(0) = 0 for a finite wheel mass).
    assert!(m.dynamic_force(&sum, dx, 0.0).iter().all(|f| *f == 0.0));
}
