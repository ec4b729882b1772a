//! The discrete track in the growth loop (`dynamics.model = "discrete"`):
//! the sleeper-passing force of a smooth rail against a direct estimate,
//! the pinned-pinned band in the force transfer, sleeper-bay stretches, and
//! bit-for-bit resume.
use crate::common;
use common::model::{OneWheel, discrete};
use corrugation::config::load_str;
use corrugation::dynamics::track::TrackConfig;
use corrugation::dynamics::track::discrete::DiscreteTrack;
use corrugation::output::netcdf::read_f64;
use corrugation::run::{resume, run_scene};
use num_complex::Complex64;
use std::f64::consts::PI;

/// Amplitude of harmonic `k` of a periodic signal.
fn harmonic(v: &[f64], k: usize) -> f64 {
    let n = v.len() as f64;
    let (mut c, mut s) = (0.0, 0.0);
    for (i, x) in v.iter().enumerate() {
        let a = 2.0 * PI * k as f64 * i as f64 / n;
        c += x * a.cos();
        s += x * a.sin();
    }
    2.0 * (c * c + s * s).sqrt() / n
}

/// growth_fastsim.toml's overrides for one sleeper bay of the discrete
/// track, and `extra`.
fn discrete_bay(extra: &[&str]) -> Vec<String> {
    common::DISCRETE_BAY.iter().chain(extra).map(|s| s.to_string()).collect()
}

#[test]
fn sleeper_passing_force_of_a_smooth_rail() {
    // At 10 m/s the sleeper-passing frequency V/d = 16.7 Hz lies far below
    // the wheel-on-track resonance (about 80 Hz): the wheel follows the
    // path its own load presses into the rail, and the force is its mass
    // times that path's acceleration, M w^2 |r_1| (a direct estimate).
    let (nodes, dx, speed, mass) = (300, 2e-3, 10.0, 600.0);
    let m = OneWheel::vertical(discrete(&TrackConfig::default(), None, 0.0), mass, 1.8e9, 1e5, nodes, dx, speed);
    let path = m.parametric_profile();
    let r1 = harmonic(&path, 1);
    // The rail deflects more at mid-span than above a sleeper by the span's
    // bending under the load, P d^3 / (c EI), the continuous rail's span
    // between a clamped (c = 192) and a pinned one (c = 48); the path's
    // first harmonic is about half that difference (UIC60: 1.75e-5 to
    // 7.0e-5 m under 100 kN at d = 0.6 m).
    let t = TrackConfig::default();
    let span = 1e5 * t.sleeper_spacing.powi(3) / t.rail.bending_stiffness;
    assert!((span / 192.0..=span / 48.0).contains(&(2.0 * r1)), "path harmonic {r1} against {:e}", span / 96.0);
    let force = m.force_from_profile(&vec![0.0; nodes], dx, speed);
    let w = 2.0 * PI * speed / 0.6;
    let direct = mass * w * w * r1;
    let p1 = harmonic(&force, 1);
    eprintln!("sleeper passing: path {r1:.4e} m, force {p1:.4e} N, direct estimate {direct:.4e} N");
    assert!((p1 - direct).abs() < 0.1 * direct, "{p1} vs {direct}");
}

#[test]
fn the_pinned_pinned_band_shows_in_the_force_transfer() {
    // A 1 um harmonic at the pinned-pinned frequency (about 1070 Hz: 26 mm
    // at 100 km/h): the rail's receptance has its resonance at mid-span and
    // its anti-resonance above the sleepers, so the force it drives is far
    // larger above the sleepers (H = 1 / (alpha_w + alpha_c + alpha_r)).
    let (nodes, dx, speed) = (3000, 2e-4, 27.78);
    let m = OneWheel::vertical(discrete(&TrackConfig::default(), None, 0.0), 600.0, 1.8e9, 1e5, nodes, dx, speed);
    let k = 23; // 0.6 m / 23 = 26.1 mm, 1065 Hz
    let profile: Vec<f64> = (0..nodes).map(|i| 1e-6 * (2.0 * PI * k as f64 * i as f64 / nodes as f64).cos()).collect();
    let smooth = m.force_from_profile(&vec![0.0; nodes], dx, speed);
    let force: Vec<f64> = m.force_from_profile(&profile, dx, speed).iter().zip(&smooth).map(|(a, b)| a - b).collect();
    // The envelope of the harmonic's force near mid-span and near a sleeper.
    let env = |lo: usize, hi: usize| force[lo..hi].iter().fold(0.0f64, |a, b| a.max(b.abs()));
    let (mid, over) = (env(1300, 1700), env(0, 200).max(env(2800, 3000)));
    eprintln!("pinned-pinned harmonic: force {mid:.4e} N near mid-span, {over:.4e} N near a sleeper");
    assert!(over > 2.0 * mid, "{over} vs {mid}");
}

#[test]
fn growth_with_the_discrete_track_resumes_bit_for_bit() {
    let base = include_str!("../configs/growth_fastsim.toml");
    let set = |extra: &[&str]| {
        discrete_bay(
            &[&["growth.adaptive=false", "growth.traffic_scale=100", "growth.contact_history=[]"], extra].concat(),
        )
    };
    let dir = tempfile::tempdir().unwrap();
    let full = dir.path().join("full.h5");
    run_scene(&load_str(base, "g", &set(&["growth.passes=3"])).unwrap(), &full, &mut |_| {}).unwrap();
    let part = dir.path().join("part.h5");
    run_scene(&load_str(base, "g", &set(&["growth.passes=2"])).unwrap(), &part, &mut |_| {}).unwrap();
    resume(&part, Some(1), None, &mut |_| {}).unwrap();
    for (g, v) in [("rail", "state"), ("passes", "rms_corrugation"), ("passes", "spectrum")] {
        let (a, b) = (read_f64(&full, g, v).unwrap(), read_f64(&part, g, v).unwrap());
        assert!(a.iter().zip(b.iter()).all(|(x, y)| x.to_bits() == y.to_bits()), "{g}/{v}");
    }
    // A stretch that is not a whole number of bays is refused, naming both keys.
    let e = load_str(base, "g", &["dynamics.model=discrete".to_string()]).unwrap_err().to_string();
    assert!(e.contains("rail.x_max") && e.contains("track.sleeper_spacing"), "{e}");
}

#[test]
fn forced_wear_is_left_out_of_the_update_bound() {
    // On the discrete track the supports' parametric excitation wears the
    // sleeper-passing harmonics whatever the profile; the Euler update
    // integrates that exactly, so the adaptive bound leaves it out. The
    // study with the adaptive m (4 passages) must wear the rail as the same
    // traffic in 16 equal steps does, within the bound's accuracy.
    let base = include_str!("../configs/growth_fastsim.toml");
    let set = |extra: &[&str]| discrete_bay(&[&["growth.contact_history=[]", "growth.store_every=1"], extra].concat());
    let dir = tempfile::tempdir().unwrap();
    let adaptive = dir.path().join("adaptive.h5");
    let cfg = set(&["growth.passes=4", "growth.adaptive=true", "growth.traffic_scale=2e3"]);
    run_scene(&load_str(base, "g", &cfg).unwrap(), &adaptive, &mut |_| {}).unwrap();
    let traffic = read_f64(&adaptive, "passes", "traffic").unwrap();
    let ratio = read_f64(&adaptive, "passes", "update_ratio").unwrap();
    let total = traffic[traffic.len() - 1];
    assert!(ratio.iter().all(|q| *q <= 0.05 * (1.0 + 1e-9)), "{ratio:?}");
    let fine = dir.path().join("fine.h5");
    let m = format!("growth.traffic_scale={}", total / 16.0);
    let cfg = set(&["growth.passes=16", "growth.adaptive=false", &m]);
    run_scene(&load_str(base, "g", &cfg).unwrap(), &fine, &mut |_| {}).unwrap();
    // The centre line's change over the study, its mean (the uniform
    // wear-down) removed: from the initial profile (the first snapshot plus
    // its passage's wear times its m) to the last.
    let change = |f: &std::path::Path| -> Vec<f64> {
        let (p, w) = (read_f64(f, "rail", "profile").unwrap(), read_f64(f, "rail", "wear").unwrap());
        let m0 = read_f64(f, "passes", "traffic_scale").unwrap()[0];
        let (n, row) = (p.shape()[0], p.shape()[1] / 2);
        let c: Vec<f64> =
            (0..p.shape()[2]).map(|i| p[[n - 1, row, i]] - (p[[0, row, i]] + m0 * w[[0, row, i]])).collect();
        let mean = c.iter().sum::<f64>() / c.len() as f64;
        c.iter().map(|v| v - mean).collect()
    };
    let (ca, cb) = (change(&adaptive), change(&fine));
    // The m taken is beyond what a bound counting the forced wear allows.
    let (p, w) = (read_f64(&adaptive, "rail", "profile").unwrap(), read_f64(&adaptive, "rail", "wear").unwrap());
    let ms = read_f64(&adaptive, "passes", "traffic_scale").unwrap();
    let row = p.shape()[1] / 2;
    let centre =
        |a: &ndarray::ArrayD<f64>, s: usize| -> Vec<f64> { (0..a.shape()[2]).map(|i| a[[s, row, i]]).collect() };
    let with_forced = (1..ms.len())
        .map(|i| ms[i] * corrugation::growth::traffic::change_rate(&centre(&p, i - 1), &centre(&w, i)))
        .fold(0.0f64, f64::max);
    assert!(with_forced > 0.1, "the forced wear would not have bounded m: {with_forced}");
    // The sleeper-passing harmonics (600 and 300 mm), forced, and the whole
    // line.
    for k in [1, 2] {
        let (ha, hb) = (harmonic(&ca, k), harmonic(&cb, k));
        assert!((ha - hb).abs() <= 0.02 * hb, "harmonic {k}: {ha:e} vs {hb:e}");
    }
    let rms = |v: &[f64]| (v.iter().map(|x| x * x).sum::<f64>() / v.len() as f64).sqrt();
    let diff: Vec<f64> = ca.iter().zip(&cb).map(|(x, y)| x - y).collect();
    assert!(rms(&diff) <= 0.03 * rms(&cb), "change {:e} vs {:e} (diff {:e})", rms(&ca), rms(&cb), rms(&diff));
}

#[test]
fn transfer_receptances_are_reciprocal_periodic_and_carried_by_the_supports() {
    // The displacement at x0 + L under a unit force at x0 (eq. 4 of
    // dynamics::track::discrete): the point receptance at L = 0, the same with
    // force and watch point exchanged (Maxwell-Betti), the same one bay on,
    // and, where the rail's inertia is negligible (1 Hz), the supports'
    // reactions k_s w(x_n) add up to the load.
    let t = DiscreteTrack::new(&TrackConfig::default());
    let d = t.spacing;
    for (f, x0) in [(300.0, 0.13), (1100.0, 0.3)] {
        let w = 2.0 * PI * f;
        let (ls, rel) = ([0.0, 0.85, 2.5], |a: Complex64, b: Complex64| (a - b).norm() / b.norm());
        let forward = t.transfer_receptances(x0, &ls, w);
        assert!(rel(forward[0], t.receptance(x0, w)) < 1e-12, "{f} Hz: L = 0 is the point receptance");
        for (l, a) in ls.iter().zip(&forward).skip(1) {
            let back = t.transfer_receptances(x0 + l, &[-l], w)[0];
            assert!(rel(back, *a) < 1e-9, "{f} Hz, L = {l}: reciprocity {back} vs {a}");
            let on = t.transfer_receptances(x0 + d, &[*l], w)[0];
            assert!(rel(on, *a) < 1e-9, "{f} Hz, L = {l}: one bay on {on} vs {a}");
        }
    }
    let w = 2.0 * PI;
    let x0 = 0.13;
    let supports: Vec<f64> = (-30..=30).map(|n| n as f64 * d - x0).collect();
    let carried: Complex64 =
        t.transfer_receptances(x0, &supports, w).iter().sum::<Complex64>() * t.support_stiffness(w);
    assert!((carried - 1.0).norm() < 1e-4, "the supports carry {carried} of the load");
}

#[test]
fn the_smeared_track_transfer_receptance_carries_the_load() {
    // Hetenyi's beam on a Winkler foundation: the foundation carries the
    // load, s int w dx = 1, and the transfer receptance is the point one at
    // L = 0 and even in L (trapezoid over +-20 m, 0.5 mm).
    use corrugation::dynamics::receptance::winkler_transfer_receptance;
    let (ei, s) = (6.42e6, 1.1e8);
    let net = Complex64::new(s, 0.0);
    let h = 5e-4;
    let integral: Complex64 = (-40_000..=40_000).map(|i| winkler_transfer_receptance(ei, net, i as f64 * h) * h).sum();
    assert!((integral * s - 1.0).norm() < 1e-6, "carried {}", integral * s);
    let point = corrugation::dynamics::receptance::winkler_point_receptance(ei, net);
    assert_eq!(winkler_transfer_receptance(ei, net, 0.0), point);
    assert_eq!(winkler_transfer_receptance(ei, net, -0.7), winkler_transfer_receptance(ei, net, 0.7));
}

/// The free (unsupported) Timoshenko rail's response at distance `x` (m) to
/// a unit force, by residues: with `K = k^2` the roots `K_1, K_2` of
/// `EI kGA K^2 - (kGA rho I + m EI) w^2 K - m w^2 (kGA - rho I w^2) = 0`,
/// `G(x) = i sum_j D(k_j) exp(i k_j |x|) / (EI kGA 2 k_j (K_j - K_other))`,
/// `k_j = sqrt(K_j)` in the upper half plane, `D = EI k^2 + kGA - rho I w^2`
/// (the inverse transform of dynamics::track::discrete's eq. 1 closed in the upper
/// half plane).
fn free_rail(t: &DiscreteTrack, w: f64, x: f64) -> Complex64 {
    let loss = Complex64::new(1.0, t.rail_loss_factor);
    let (ei, kga) = (loss * t.rail.bending_stiffness, loss * t.rail.shear_stiffness);
    let (ri, m, w2) = (t.rail.rotary_inertia, t.rail.mass, w * w);
    let (a, b, c) = (ei * kga, -(kga * ri + m * ei) * w2, -m * w2 * (kga - ri * w2));
    let disc = (b * b - 4.0 * a * c).sqrt();
    let roots = [(-b + disc) / (2.0 * a), (-b - disc) / (2.0 * a)];
    let mut g = Complex64::new(0.0, 0.0);
    for (j, &kj2) in roots.iter().enumerate() {
        let mut k = kj2.sqrt();
        if k.im < 0.0 {
            k = -k;
        }
        let other = roots[1 - j];
        let d = ei * kj2 + kga - ri * w2;
        g += Complex64::i() * d * (Complex64::i() * k * x.abs()).exp() / (a * 2.0 * k * (kj2 - other));
    }
    g
}

#[test]
fn transfer_receptances_against_a_long_finite_row_of_supports() {
    // An independent model: the free rail loaded by the unit force and by
    // the reactions k_s w_n of 401 supports (+-120 m; the rest left out),
    // w_m + k_s sum_n G(x_m - x_n) w_n = G(x_m - x0), solved directly;
    // the displacement at x0 + L is then G(L) - k_s sum_n G(x0 + L - x_n)
    // w_n. Against the Floquet transfer receptances (eq. 4), below and
    // above the pinned-pinned resonance, from a sleeper and mid-span.
    use nalgebra::{DMatrix, DVector};
    let t = DiscreteTrack::new(&TrackConfig::default());
    let d = t.spacing;
    let supports: Vec<f64> = (-200..=200).map(|n| n as f64 * d).collect();
    let mut worst = 0.0f64;
    for f in [150.0, 600.0, 1100.0, 2000.0] {
        let w = 2.0 * PI * f;
        let ks = t.support_stiffness(w);
        let n = supports.len();
        let a = DMatrix::from_fn(n, n, |i, j| {
            ks * free_rail(&t, w, supports[i] - supports[j]) + if i == j { 1.0 } else { 0.0 }
        });
        let lu = a.lu();
        for x0 in [0.0, 0.3, 0.13] {
            let rhs = DVector::from_fn(n, |i, _| free_rail(&t, w, supports[i] - x0));
            let wn = lu.solve(&rhs).unwrap();
            let ls = [0.0, 0.85, 2.5];
            let floquet = t.transfer_receptances(x0, &ls, w);
            for (l, fl) in ls.iter().zip(&floquet) {
                let x = x0 + l;
                let direct = free_rail(&t, w, *l)
                    - ks * supports
                        .iter()
                        .zip(wn.iter())
                        .map(|(xn, wv)| free_rail(&t, w, x - xn) * wv)
                        .sum::<Complex64>();
                let e = (direct - fl).norm() / floquet[0].norm();
                worst = worst.max(e);
                assert!(e < 2e-3, "{f} Hz, x0 {x0}, L {l}: direct {direct} vs Floquet {fl} ({e:.2e})");
            }
        }
    }
    eprintln!("Floquet against the finite row of supports: within {worst:.2e} of the point receptance");
}
