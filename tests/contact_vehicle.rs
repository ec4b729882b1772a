//! Several wheels in every direction (src/dynamics/model/): one wheel is
//! the single contact's closed form (src/dynamics/coupling/contact_point.rs
//! per harmonic); without creep slopes the normal forces are the vertical
//! coupled closed form with the head's vertical receptances; wheels
//! far apart are each the single wheel; a bogie study in every direction
//! runs and resumes bit for bit.
use crate::common;
use corrugation::config::load_str;
use corrugation::dynamics::coupling::contact_point::{ContactLaw, respond};
use corrugation::dynamics::model::{Directions, VehicleTrack, Wheel, harmonics};
use corrugation::dynamics::track::TrackConfig;
use corrugation::dynamics::track::continuous3::Continuous3;
use corrugation::dynamics::wheelset::side::{Wheel3, WheelSide};
use corrugation::output::netcdf::read_f64;
use corrugation::run::{resume, run_scene};
use nalgebra::DMatrix;
use num_complex::Complex64;
use std::f64::consts::PI;

fn c(v: f64) -> Complex64 {
    Complex64::new(v, 0.0)
}

fn law(slopes: bool) -> ContactLaw {
    let s = if slopes { 1.0 } else { 0.0 };
    ContactLaw {
        stiffness: 1.83e9,
        force_per_normal: [c(0.21 * s), c(0.0)],
        force_per_creepage: [[c(-3.1e7 * s), c(0.0)], [c(0.0), c(-3.3e7 * s)]],
        force_per_spin: None,
    }
}

fn wheel() -> Wheel3 {
    Wheel3 { mass: 600.0, radius: 0.5, polar_inertia: 30.0, torsion: None }
}

fn vehicle(behind: &[f64], slopes: bool, nodes: usize, dx: f64, speed: f64) -> VehicleTrack {
    let rail = common::model::continuous(&TrackConfig::default(), 0.005);
    let wheels = behind
        .iter()
        .map(|&b| Wheel {
            behind: b,
            side: WheelSide::Rigid(wheel()),
            law: law(slopes),
            response: None,
            mean_load: 1e5,
            rail: 0,
        })
        .collect();
    VehicleTrack::new(rail, wheels, Directions::All, nodes, dx, speed).unwrap()
}

fn worst(a: &[f64], b: &[f64]) -> f64 {
    common::worst_scaled(a, b, 1.0)
}

/// A profile of three harmonics of the stretch.
fn profile(nodes: usize, dx: f64) -> Vec<f64> {
    common::three_harmonics(nodes, dx, 0.0)
}

#[test]
fn one_wheel_is_the_single_contacts_closed_form() {
    // Per harmonic of the stretch the single contact's 3 x 3 system
    // (contact_point::respond, its own elimination) with the wheel's and
    // the head's receptances, summed over the profile's DFT written out.
    let (nodes, dx, speed) = (600, 2e-4, 27.78);
    let one = vehicle(&[0.0], true, nodes, dx, speed);
    let head = Continuous3::new(&TrackConfig::default(), 0.005);
    let r = profile(nodes, dx);
    let a = one.signals(std::slice::from_ref(&r), dx, speed).remove(0);
    let length = nodes as f64 * dx;
    let mut b = [vec![0.0; nodes], vec![0.0; nodes], vec![0.0; nodes], vec![0.0; nodes]];
    for k in 1..=harmonics(nodes, dx, speed) {
        let rk = common::dft(&r, k);
        let w = 2.0 * PI * speed * k as f64 / length;
        let rail = head.heads(w, &[0.0], false).unwrap()[0];
        let h = respond(&(WheelSide::Rigid(wheel()).receptance(w, speed) + rail), &law(true), w, speed);
        let weight = if 2 * k == nodes { 1.0 } else { 2.0 } / nodes as f64;
        for (channel, hc) in b.iter_mut().zip([h.normal, h.force[0], h.creepage[0], h.creepage[1]]) {
            for (m, v) in channel.iter_mut().enumerate() {
                *v += weight * (hc * rk * Complex64::from_polar(1.0, 2.0 * PI * (k * m) as f64 / nodes as f64)).re;
            }
        }
    }
    for (x, y, what) in [
        (&a.normal, &b[0], "normal"),
        (&a.force_x, &b[1], "force"),
        (&a.creepage_x, &b[2], "creepage x"),
        (&a.creepage_y, &b[3], "creepage y"),
    ] {
        let e = worst(x, y);
        eprintln!("{what}: {e:.1e}");
        assert!(e < 1e-10, "{what}: {e}");
    }
}

#[test]
fn without_creep_slopes_the_normal_forces_are_the_vertical_coupled_closed_form() {
    // 2.4 m apart on a 2.4 m stretch's harmonics (whole wavelengths and
    // others), the lateral offset coupling the head's twist in.
    let (nodes, dx, speed) = (1200, 2e-3, 27.78);
    let behind = [0.0, 1.1];
    let model = vehicle(&behind, false, nodes, dx, speed);
    let rail = Continuous3::new(&TrackConfig::default(), 0.005);
    let length = nodes as f64 * dx;
    for n in [3usize, 11, 40] {
        let k = 2.0 * PI * n as f64 / length;
        let r: Vec<f64> = (0..nodes).map(|i| 1e-6 * (k * i as f64 * dx).cos()).collect();
        let s = model.signals(&[r.clone(), r.clone()], dx, speed);
        let w = k * speed;
        let a_w = wheel().receptance(w, speed)[(2, 2)] + 1.0 / law(false).stiffness;
        let a = rail.head_receptances(w, &[0.0, behind[1], -behind[1]]).unwrap();
        // A_jl: at wheel j under a force at wheel l, distance s_l - s_j.
        let at = |j: usize, l: usize| match behind[l] - behind[j] {
            0.0 => a[0][(2, 2)],
            d if d > 0.0 => a[1][(2, 2)],
            _ => a[2][(2, 2)],
        };
        let m = DMatrix::from_fn(2, 2, |j, l| at(j, l) + if j == l { a_w } else { c(0.0) });
        let inv = m.try_inverse().unwrap();
        for i in 0..2 {
            let h: Complex64 =
                (0..2).map(|j| inv[(i, j)] * Complex64::from_polar(1.0, k * (behind[i] - behind[j]))).sum();
            let expected: Vec<f64> =
                (0..nodes).map(|m| (h * 1e-6 * Complex64::from_polar(1.0, k * m as f64 * dx)).re).collect();
            let e = worst(&s[i].normal, &expected);
            eprintln!("harmonic {n}, wheel {i}: {e:.1e}");
            assert!(e < 1e-9, "harmonic {n}, wheel {i}: {e}");
            assert!(s[i].force_x.iter().all(|f| *f == 0.0));
        }
    }
}

#[test]
fn on_the_discrete_track_without_creep_slopes_the_normal_forces_are_the_vertical_vehicles() {
    // The vertical closure on the discrete track (src/dynamics/track/discrete.rs,
    // its own Floquet method) and this model's head receptances agree where the
    // section moves vertically alone: no pad pitch restraint, the
    // longitudinal pads and the shear centre at the neutral axis (as
    // tests/rail_head.rs, 5e-4 there).
    let mut track = TrackConfig::default();
    track.rail.transverse.neutral_axis_height = 0.0;
    track.rail.transverse.shear_centre_height = 0.0;
    track.supports.pad_length = 0.0;
    let (nodes, dx, speed) = (300, 2e-3, 27.78);
    let behind = [0.0, 2.5];
    let rail = common::model::discrete(&track, Some(0.0), 0.0);
    let wheels = behind
        .iter()
        .map(|&b| Wheel {
            behind: b,
            side: WheelSide::Rigid(wheel()),
            law: law(false),
            response: None,
            mean_load: 1e5,
            rail: 0,
        })
        .collect();
    let model = VehicleTrack::new(rail, wheels, Directions::All, nodes, dx, speed).unwrap();
    let coupled = behind.iter().map(|&b| Wheel::vertical(b, wheel(), law(false).stiffness, 1e5)).collect();
    let rail = common::model::discrete(&track, None, 0.0);
    let vertical = VehicleTrack::new(rail, coupled, Directions::Vertical, nodes, dx, speed).unwrap();
    let r = profile(nodes, dx);
    let (a, b) =
        (model.signals(&[r.clone(), r.clone()], dx, speed), vertical.normal_forces(&[r.clone(), r], dx, speed));
    for i in 0..2 {
        let e = worst(&a[i].normal, &b[i]);
        eprintln!("wheel {i}: {e:.1e}");
        assert!(e < 5e-4, "wheel {i}: {e}");
    }
}

#[test]
fn wheels_far_apart_are_each_the_single_wheel() {
    // 40 m apart the rail's transfer receptances have decayed (by 1e-4 of
    // the point receptance at 100 Hz and far more above).
    let (nodes, dx, speed) = (4000, 1e-2, 27.78);
    let pair = vehicle(&[0.0, 40.0], true, nodes, dx, speed);
    let one = vehicle(&[0.0], true, nodes, dx, speed);
    let r = profile(nodes, dx);
    let s = pair.signals(&[r.clone(), r.clone()], dx, speed);
    let single = one.signals(std::slice::from_ref(&r), dx, speed).remove(0);
    // The second wheel meets the profile 40 m later: a whole number of the
    // stretch's periods, the same signal.
    for (i, w) in s.iter().enumerate() {
        let (en, ef) = (worst(&w.normal, &single.normal), worst(&w.force_x, &single.force_x));
        eprintln!("wheel {i}: normal {en:.1e}, force {ef:.1e}");
        assert!(en < 1e-4 && ef < 1e-4, "wheel {i}");
    }
}

#[test]
fn a_bogie_in_every_direction_runs_and_resumes_bit_for_bit() {
    let study = |passes: usize| {
        let set: Vec<String> = [
            "contact.elements_x=8",
            "contact.elements_y=8",
            "growth.contact_history=[0]",
            "vehicle.wheels=[0.0, 2.5]",
            "dynamics.creep_forces=steady",
        ]
        .iter()
        .map(|s| s.to_string())
        .chain([format!("growth.passes={passes}")])
        .collect();
        load_str(include_str!("../configs/growth_fastsim.toml"), "g", &set).unwrap()
    };
    let dir = tempfile::tempdir().unwrap();
    let (full, part) = (dir.path().join("full.h5"), dir.path().join("part.h5"));
    run_scene(&study(3), &full, &mut |_| {}).unwrap();
    // Each wheel's longitudinal force varies, differently.
    let lead: Vec<f64> = read_f64(&full, "contact/pass_00000", "longitudinal_force").unwrap().iter().copied().collect();
    let second: Vec<f64> =
        read_f64(&full, "contact/pass_00000/wheel_2", "longitudinal_force").unwrap().iter().copied().collect();
    let spread = |f: &[f64]| f.iter().fold(f64::MIN, |m, v| m.max(*v)) - f.iter().fold(f64::MAX, |m, v| m.min(*v));
    assert!(spread(&lead) > 1.0 && spread(&second) > 1.0);
    assert!(lead.iter().zip(&second).any(|(a, b)| (a - b).abs() > 1.0));
    run_scene(&study(2), &part, &mut |_| {}).unwrap();
    resume(&part, Some(1), None, &mut |_| {}).unwrap();
    for (g, v) in [("rail", "profile"), ("passes", "rms_corrugation")] {
        assert_eq!(read_f64(&full, g, v).unwrap(), read_f64(&part, g, v).unwrap(), "{g}/{v}");
    }
}
