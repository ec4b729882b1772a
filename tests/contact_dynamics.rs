//! The growth loop's dynamics in every direction
//! (src/dynamics/model/, one wheel in every direction): on the continuous track, where the
//! head's cross terms vanish under the load, the normal force of a profile
//! harmonic is the vertical chain's `r / (a_w + a_c + a_r,zz)` and the
//! longitudinal creepage the rim's and the head's motion under the creep
//! force that the normal force's variation drives; on the discrete track
//! the responses vary across the bay; a study with it resumes bit for bit.
use crate::common::model::{OneWheel, continuous, discrete};
use corrugation::config::load_str;
use corrugation::dynamics::coupling::contact_point::ContactLaw;
use corrugation::dynamics::coupling::creep_response::CreepResponse;
use corrugation::dynamics::track::TrackConfig;
use corrugation::dynamics::track::continuous3::Continuous3;
use corrugation::dynamics::wheelset::side::{Wheel3, WheelSide};
use corrugation::output::netcdf::read_f64;
use corrugation::run::{resume, run_scene};
use num_complex::Complex64;
use std::f64::consts::PI;

fn c(v: f64) -> Complex64 {
    Complex64::new(v, 0.0)
}

fn law() -> ContactLaw {
    ContactLaw {
        stiffness: 1.83e9,
        force_per_normal: [c(0.21), c(0.0)],
        force_per_creepage: [[c(-3.1e7), c(0.0)], [c(0.0), c(-3.3e7)]],
        force_per_spin: None,
    }
}

fn wheel() -> Wheel3 {
    Wheel3 { mass: 600.0, radius: 0.5, polar_inertia: 30.0, torsion: None }
}

/// `Re[h r exp(i k x)]` for the profile `r cos(k x)`.
fn harmonic(h: Complex64, r: f64, k: f64, x: f64) -> f64 {
    (h * r * Complex64::from_polar(1.0, k * x)).re
}

#[test]
fn continuous_track_against_the_vertical_chain_and_the_rims_motion() {
    let (nodes, dx, speed) = (600, 2e-4, 27.78);
    let track = TrackConfig::default();
    let rail = Continuous3::new(&track, 0.0);
    let model = OneWheel::every(continuous(&track, 0.0), WheelSide::Rigid(wheel()), law(), None, 1e5, nodes, dx, speed);
    for wavelength in [0.03, 0.12 / 7.0, 0.06] {
        let k = 2.0 * PI / wavelength;
        let r = 1e-6;
        let profile: Vec<f64> = (0..nodes).map(|i| r * (k * i as f64 * dx).cos()).collect();
        let s = model.signals(&profile, dx, speed);
        let w = k * speed;
        let head = rail.head_receptances(w, &[0.0]).unwrap()[0];
        let a_w = wheel().receptance(w, speed);
        // Under the load the continuous head's cross terms vanish.
        assert!(head[(0, 2)].norm() < 1e-9 * head[(2, 2)].norm() && head[(0, 1)].norm() < 1e-9 * head[(0, 0)].norm());
        let a_zz = a_w[(2, 2)] + head[(2, 2)];
        let normal = 1.0 / (a_zz + 1.0 / law().stiffness);
        // F_x = C_N N + C_xi xi, xi = (i w / V) a_xx F_x.
        let t = Complex64::new(0.0, w / speed) * (a_w[(0, 0)] + head[(0, 0)]);
        let force = law().force_per_normal[0] * normal / (1.0 - law().force_per_creepage[0][0] * t);
        let creepage = t * force;
        let (mut worst_n, mut worst_f, mut worst_xi) = (0.0f64, 0.0f64, 0.0f64);
        for i in 0..nodes {
            let x = i as f64 * dx;
            worst_n = worst_n.max((s.normal[i] - harmonic(normal, r, k, x)).abs() / (normal.norm() * r));
            worst_f = worst_f.max((s.force_x[i] - harmonic(force, r, k, x)).abs() / (force.norm() * r));
            worst_xi = worst_xi.max((s.creepage_x[i] - harmonic(creepage, r, k, x)).abs() / (creepage.norm() * r));
            assert!(s.creepage_y[i].abs() < 1e-12 * creepage.norm() * r, "no lateral creepage on the centre line");
        }
        eprintln!("{wavelength} m: normal within {worst_n:.1e}, force {worst_f:.1e}, creepage {worst_xi:.1e}");
        assert!(worst_n < 1e-9 && worst_f < 1e-9 && worst_xi < 1e-9, "{wavelength} m");
    }
}

/// A creep response whose creepage columns lag like a first-order system,
/// `C / (1 + i W)` (`W = w a0 / V`), the normal force's steady.
fn lagging_response(speed: f64) -> CreepResponse {
    let l = law();
    let reduced: Vec<f64> = (0..=8).map(|n| n as f64 * PI / 4.0).collect();
    let table = reduced
        .iter()
        .map(|w| {
            let lag = 1.0 / Complex64::new(1.0, *w);
            let mut h = [[c(0.0); 4]; 2];
            for (i, row) in h.iter_mut().enumerate() {
                row[0] = l.force_per_creepage[i][0] * lag;
                row[1] = l.force_per_creepage[i][1] * lag;
                row[3] = l.force_per_normal[i];
            }
            h
        })
        .collect();
    CreepResponse {
        speed,
        semi_axis: 6e-3,
        creepage_x: 0.0,
        force: [0.0; 2],
        reduced,
        table,
        measured: [true, true, false, true],
    }
}

/// With `dynamics.creep_forces = "transient"` each harmonic closes with
/// the creep forces' response at its own frequency: the chain's closed form
/// with the response's slopes, and not the steady ones.
#[test]
fn each_harmonic_closes_with_the_creep_response_at_its_frequency() {
    let (nodes, dx, speed) = (600, 2e-4, 27.78);
    let rail = Continuous3::new(&TrackConfig::default(), 0.0);
    let response = lagging_response(speed);
    let track = || continuous(&TrackConfig::default(), 0.0);
    let model =
        OneWheel::every(track(), WheelSide::Rigid(wheel()), law(), Some(response.clone()), 1e5, nodes, dx, speed);
    let steady = OneWheel::every(track(), WheelSide::Rigid(wheel()), law(), None, 1e5, nodes, dx, speed);
    for wavelength in [0.03, 0.12 / 7.0, 0.06] {
        let k = 2.0 * PI / wavelength;
        let r = 1e-6;
        let profile: Vec<f64> = (0..nodes).map(|i| r * (k * i as f64 * dx).cos()).collect();
        let (s, s0) = (model.signals(&profile, dx, speed), steady.signals(&profile, dx, speed));
        let w = k * speed;
        let h = response.at(w / (2.0 * PI));
        let head = rail.head_receptances(w, &[0.0]).unwrap()[0];
        let a_w = wheel().receptance(w, speed);
        let normal = 1.0 / (a_w[(2, 2)] + head[(2, 2)] + 1.0 / law().stiffness);
        let t = Complex64::new(0.0, w / speed) * (a_w[(0, 0)] + head[(0, 0)]);
        let force = h[0][3] * normal / (1.0 - h[0][0] * t);
        let (mut worst, mut apart) = (0.0f64, 0.0f64);
        for i in 0..nodes {
            let x = i as f64 * dx;
            worst = worst.max((s.force_x[i] - harmonic(force, r, k, x)).abs() / (force.norm() * r));
            apart = apart.max((s.force_x[i] - s0.force_x[i]).abs() / (force.norm() * r));
        }
        eprintln!(
            "{wavelength} m (W = {:.2}): within {worst:.1e}, {apart:.1e} from the steady slopes",
            w * 6e-3 / speed
        );
        assert!(worst < 1e-9, "{wavelength} m");
        // The lag is not negligible at these reduced frequencies (0.6-1.3).
        assert!(apart > 1e-2, "{wavelength} m");
    }
}

#[test]
fn discrete_track_varies_the_response_across_the_bay_and_feeds_the_lateral_creepage_off_centre() {
    // One harmonic of the pinned-pinned band (1 kHz at 27.78 m/s: 27.8 mm
    // is not a divisor of the bay, so 24 mm, 1157 Hz): its normal force's
    // amplitude differs above a sleeper and mid-span; the contact 12 mm
    // off the centre line twists the head, which moves it across: a lateral
    // creepage the centred contact does not have.
    let (nodes, dx, speed) = (3000, 2e-4, 27.78);
    let track = TrackConfig::default();
    let build = |offset: f64| {
        let rail = discrete(&track, Some(offset), 0.0);
        OneWheel::every(rail, WheelSide::Rigid(wheel()), law(), None, 1e5, nodes, dx, speed)
    };
    let k = 2.0 * PI / 0.024;
    let profile: Vec<f64> = (0..nodes).map(|i| 1e-6 * (k * i as f64 * dx).cos()).collect();
    let centred = build(0.0).signals(&profile, dx, speed);
    let off = build(0.012).signals(&profile, dx, speed);
    // The normal force's envelope over a wavelength at a sleeper (x = 0)
    // and mid-span (0.3 m), less the parametric excitation's share (the
    // smooth rail's force at the same places).
    let smooth = build(0.0).signals(&vec![0.0; nodes], dx, speed);
    let envelope = |at: f64| {
        let i0 = (at / dx) as i64;
        (i0 - 60..i0 + 60)
            .map(|i| i.rem_euclid(nodes as i64) as usize)
            .map(|i| (centred.normal[i] - smooth.normal[i]).abs())
            .fold(0.0f64, f64::max)
    };
    let (sleeper, mid) = (envelope(0.0), envelope(0.3));
    eprintln!("normal force of 1 um at 24 mm: {sleeper:.0} N above a sleeper, {mid:.0} N mid-span");
    assert!((sleeper - mid).abs() > 0.05 * sleeper.max(mid), "{sleeper} vs {mid}");
    let lateral = |s: &corrugation::dynamics::ContactSignals| s.creepage_y.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let longitudinal = centred.creepage_x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    eprintln!(
        "lateral creepage: centred {:.2e}, 12 mm off {:.2e} (longitudinal {longitudinal:.2e})",
        lateral(&centred),
        lateral(&off)
    );
    assert!(lateral(&centred) < 1e-6 * longitudinal);
    assert!(lateral(&off) > 1e-3 * longitudinal);
}

fn study(set: &[&str]) -> corrugation::config::Resolved {
    let mut all: Vec<String> =
        ["contact.elements_x=8", "contact.elements_y=8", "growth.passes=3", "growth.contact_history=[0]"]
            .iter()
            .map(|s| s.to_string())
            .collect();
    all.extend(set.iter().map(|s| s.to_string()));
    load_str(include_str!("../configs/growth_fastsim.toml"), "g", &all).unwrap()
}

#[test]
fn a_study_in_every_direction_varies_the_force_and_resumes_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let (full, part) = (dir.path().join("full.h5"), dir.path().join("part.h5"));
    run_scene(&study(&[]), &full, &mut |_| {}).unwrap();
    // Force control: the longitudinal force the dynamics transmits varies
    // along the stretch.
    let f = read_f64(&full, "contact/pass_00000", "longitudinal_force").unwrap();
    let (lo, hi) = f.iter().fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(*v), b.max(*v)));
    assert!(hi - lo > 1.0, "the force varies: {lo} .. {hi} N");
    run_scene(&study(&["growth.passes=2"]), &part, &mut |_| {}).unwrap();
    resume(&part, Some(1), None, &mut |_| {}).unwrap();
    for (g, v) in [("rail", "profile"), ("passes", "rms_corrugation")] {
        assert_eq!(read_f64(&full, g, v).unwrap(), read_f64(&part, g, v).unwrap(), "{g}/{v}");
    }
}
