//! Both rails of a wheelset (`[second_rail]`, src/dynamics/model/ with
//! wheels on two rails): the second rail without its contact is the
//! one-rail model; a mirror-symmetric wheelset on mirror-image contacts and
//! equal profiles answers mirror-symmetrically; the second rail's profile
//! reaches the first rail's contact through the wheelset; a two-rail study
//! resumes bit for bit, both rails; a second rail the scene cannot carry is
//! refused naming the key.
use crate::common;
use common::model::{OneWheel, continuous};
use common::{largest, worst_scaled};
use corrugation::build::wheelset_model;
use corrugation::config::load_str;
use corrugation::dynamics::coupling::contact_point::ContactLaw;
use corrugation::dynamics::model::{Directions, Track, VehicleTrack, Wheel};
use corrugation::dynamics::track::TrackConfig;
use corrugation::dynamics::wheelset::side::WheelSide;
use corrugation::output::netcdf::{read_attr_str, read_f64};
use corrugation::run::{resume, run_scene};
use num_complex::Complex64;

const CURVE: &str = include_str!("../configs/curve_two_rails.toml");

fn c(v: f64) -> Complex64 {
    Complex64::new(v, 0.0)
}

/// A contact law with cross terms (so that the mirror image differs).
fn law() -> ContactLaw {
    ContactLaw {
        stiffness: 1.83e9,
        force_per_normal: [c(0.21), c(0.05)],
        force_per_creepage: [[c(-3.1e7), c(1.2e6)], [c(-0.8e6), c(-3.3e7)]],
        force_per_spin: Some([c(1.5e3), c(-2.6e4)]),
    }
}

/// The law's mirror image in the common axes (y to the right): the
/// lateral force and creepage change sign.
fn mirrored(l: &ContactLaw) -> ContactLaw {
    let f = l.force_per_creepage;
    ContactLaw {
        stiffness: l.stiffness,
        force_per_normal: [l.force_per_normal[0], -l.force_per_normal[1]],
        force_per_creepage: [[f[0][0], -f[0][1]], [-f[1][0], f[1][1]]],
        // The spin changes sign with the lateral direction.
        force_per_spin: l.force_per_spin.map(|s| [-s[0], s[1]]),
    }
}

/// The default modal wheelset spinning at 60 km/h.
fn side() -> WheelSide {
    let scene = load_str(CURVE, "curve", &[]).unwrap().scene;
    WheelSide::Modal { model: wheelset_model(&scene).unwrap(), spin: scene.speed / scene.geometry.wheel_radius }
}

const NODES: usize = 300;
const DX: f64 = 1e-3;
const SPEED: f64 = 16.67;

fn rail() -> Track {
    continuous(&TrackConfig::default(), 0.0)
}

fn wheelset(second: ContactLaw) -> VehicleTrack {
    let side = side();
    let wheel = |law: ContactLaw, rail: usize| Wheel {
        behind: 0.0,
        side: side.clone(),
        law,
        response: None,
        mean_load: 1e5,
        rail,
    };
    VehicleTrack::new(rail(), vec![wheel(law(), 0), wheel(second, 1)], Directions::All, NODES, DX, SPEED).unwrap()
}

/// Three harmonics of the stretch, phase `p`.
fn profile(p: f64) -> Vec<f64> {
    common::three_harmonics(NODES, DX, p)
}

#[test]
fn the_second_rail_without_its_contact_is_one_rail() {
    // No contact spring (1e-6 N/m) and no creep slopes on the second rail:
    // its wheel is free, as the one-rail model's other wheel.
    let free = ContactLaw {
        stiffness: 1e-6,
        force_per_normal: [c(0.0); 2],
        force_per_creepage: [[c(0.0); 2]; 2],
        force_per_spin: None,
    };
    let two = wheelset(free);
    let one = OneWheel::every(rail(), side(), law(), None, 1e5, NODES, DX, SPEED);
    let (r0, r1) = (profile(0.0), profile(1.0));
    let both = two.signals(&[r0.clone(), r1], DX, SPEED);
    let single = one.signals(&r0, DX, SPEED);
    for (name, a, b) in [
        ("normal", &both[0].normal, &single.normal),
        ("force_x", &both[0].force_x, &single.force_x),
        ("creepage_x", &both[0].creepage_x, &single.creepage_x),
        ("creepage_y", &both[0].creepage_y, &single.creepage_y),
        ("spin", &both[0].spin, &single.spin),
    ] {
        // The free wheel's spring carries 1e-6 N/m x 1e-6 m: nothing.
        assert!(worst_scaled(a, b, 1.0) < 1e-9, "{name}: {}", worst_scaled(a, b, 1.0));
    }
}

#[test]
fn a_symmetric_wheelset_on_mirror_image_contacts_answers_symmetrically() {
    // Equal profiles, the second contact the first's mirror image: equal
    // normal forces and longitudinal creepages, opposite lateral
    // creepages. The spin about the axle keeps the mirror symmetry (an
    // axial vector normal to the mirror plane), the gyroscopic coupling
    // included.
    let two = wheelset(mirrored(&law()));
    let r = profile(0.0);
    let s = two.signals(&[r.clone(), r], DX, SPEED);
    assert!(largest(&s[0].normal) > 100.0 && largest(&s[0].creepage_y) > 1e-9);
    assert!(worst_scaled(&s[1].normal, &s[0].normal, 1.0) < 1e-9, "{}", worst_scaled(&s[1].normal, &s[0].normal, 1.0));
    assert!(worst_scaled(&s[1].creepage_x, &s[0].creepage_x, 1.0) < 1e-9);
    assert!(worst_scaled(&s[1].creepage_y, &s[0].creepage_y, -1.0) < 1e-9);
    // The spin, as the lateral creepage, changes sign in the mirror.
    assert!(largest(&s[0].spin) > 0.0);
    assert!(worst_scaled(&s[1].spin, &s[0].spin, -1.0) < 1e-9, "{}", worst_scaled(&s[1].spin, &s[0].spin, -1.0));
}

#[test]
fn the_second_rails_profile_reaches_the_first_rails_contact_through_the_wheelset() {
    // Only the second rail is rough: the first rail's contact varies by
    // the wheelset's transfer receptances (roll, bending, torsion), less
    // than the second's own, and not by nothing.
    let two = wheelset(law());
    let s = two.signals(&[vec![0.0; NODES], profile(0.0)], DX, SPEED);
    let (first, second) = (largest(&s[0].normal), largest(&s[1].normal));
    assert!(first > 1e-3 * second && first < second, "first {first} N, second {second} N");
    assert!(largest(&s[0].creepage_x) > 0.0);
}

fn study(passes: usize, extra: &[&str]) -> corrugation::config::Resolved {
    let set: Vec<String> = [
        "contact.elements_x=8",
        "contact.elements_y=8",
        "growth.contact_history=[0]",
        "dynamics.creep_forces=steady",
        "wheelset.model=\"modal\"",
        "second_rail.normal_force=1.1e5",
        "second_rail.name=\"high rail\"",
    ]
    .iter()
    .chain(extra)
    .map(|s| s.to_string())
    .chain([format!("growth.passes={passes}")])
    .collect();
    load_str(include_str!("../configs/growth_fastsim.toml"), "g", &set).unwrap()
}

#[test]
fn a_two_rail_study_writes_both_rails_and_resumes_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let (full, part) = (dir.path().join("full.h5"), dir.path().join("part.h5"));
    run_scene(&study(3, &[]), &full, &mut |_| {}).unwrap();
    assert_eq!(read_attr_str(&full, "", "rail_name").unwrap(), "left rail");
    assert_eq!(read_attr_str(&full, "second_rail", "rail_name").unwrap(), "high rail");
    // Each rail wears, each its own way (its own roughness and load).
    let v1 = read_f64(&full, "passes", "removed_volume").unwrap();
    let v2 = read_f64(&full, "second_rail/passes", "removed_volume").unwrap();
    assert!(v1.iter().all(|v| *v > 0.0) && v2.iter().all(|v| *v > 0.0));
    assert!(v1.iter().zip(&v2).all(|(a, b)| a != b));
    assert_eq!(
        read_f64(&full, "passes", "traffic").unwrap(),
        read_f64(&full, "second_rail/passes", "traffic").unwrap()
    );
    let n2 = read_f64(&full, "second_rail/contact/pass_00000", "normal_force").unwrap();
    assert!(n2.iter().all(|n| (n - 1.1e5).abs() < 0.2e5), "the second rail's load about its mean");
    // The spin varies on both rails (dynamics.spin, the default), about
    // each rail's mean (the first's 0, the second's its mirror image, 0).
    for g in ["", "second_rail/"] {
        let spin = read_f64(&full, &format!("{g}contact/pass_00000"), "spin").unwrap();
        let (lo, hi) = spin.iter().fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(*v), b.max(*v)));
        assert!(hi - lo > 1e-9 && lo < 0.0 && hi > 0.0, "{g}: spin in [{lo}, {hi}] 1/m");
    }
    run_scene(&study(2, &[]), &part, &mut |_| {}).unwrap();
    resume(&part, Some(1), None, &mut |_| {}).unwrap();
    for g in ["", "second_rail/"] {
        for (group, v) in [("passes", "rms_corrugation"), ("rail", "state"), ("rail", "profile")] {
            let group = format!("{g}{group}");
            let (a, b) = (read_f64(&full, &group, v).unwrap(), read_f64(&part, &group, v).unwrap());
            assert!(a == b, "{group}/{v}: {:?} vs {:?}", a.shape(), b.shape());
        }
    }
}

#[test]
fn without_the_spins_channel_the_spin_stays_at_its_mean() {
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("off.h5");
    run_scene(&study(1, &["dynamics.spin=false", "rolling.spin=0.5"]), &f, &mut |_| {}).unwrap();
    for (g, mean) in [("", 0.5), ("second_rail/", -0.5)] {
        let spin = read_f64(&f, &format!("{g}contact/pass_00000"), "spin").unwrap();
        assert!(spin.iter().all(|v| *v == mean), "{g}: the spin left its mean {mean}");
    }
}

#[test]
fn a_second_rail_the_scene_cannot_carry_is_refused_naming_the_key() {
    let set = ["second_rail.normal_force=1.1e5".to_string(), "wheelset.model=torsion".to_string()];
    let base = include_str!("../configs/growth_fastsim.toml");
    let Err(e) = load_str(base, "g", &set) else { panic!("accepted without the modal wheelset") };
    let e = e.to_string();
    assert!(e.contains("second_rail") && e.contains("wheelset.model"), "{e}");
    let set = ["second_rail.normal_force=1.1e5", "wheelset.model=\"modal\"", "dynamics.directions=\"vertical\""];
    let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    let Err(e) = load_str(base, "g", &set) else { panic!("accepted with the vertical dynamics only") };
    let e = e.to_string();
    assert!(e.contains("second_rail") && e.contains("dynamics.directions"), "{e}");
    // Two rails of one name; the second rail's load in full sliding.
    let set = ["second_rail.name=\"left rail\"", "wheelset.model=\"modal\"", "second_rail.normal_force=2e4"];
    let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    let Err(e) = load_str(base, "g", &set) else { panic!("accepted two rails of one name") };
    let e = e.to_string();
    assert!(e.contains("second_rail.name") && e.contains("second_rail.longitudinal_force"), "{e}");
}

#[test]
fn a_bogie_on_two_rails_runs_and_resumes_bit_for_bit() {
    // Two wheelsets 2.5 m apart, each with its wheel on each rail: the
    // second rail's second wheel has its own history, unlike its first's.
    let dir = tempfile::tempdir().unwrap();
    let (full, part) = (dir.path().join("full.h5"), dir.path().join("part.h5"));
    let bogie = ["vehicle.wheels=[0.0, 2.5]"];
    run_scene(&study(3, &bogie), &full, &mut |_| {}).unwrap();
    let group = "second_rail/contact/pass_00000";
    let lead = read_f64(&full, group, "normal_force").unwrap();
    let second = read_f64(&full, &format!("{group}/wheel_2"), "normal_force").unwrap();
    assert_eq!(lead.shape(), second.shape());
    assert!(lead.iter().zip(second.iter()).any(|(a, b)| (a - b).abs() > 1.0));
    run_scene(&study(2, &bogie), &part, &mut |_| {}).unwrap();
    resume(&part, Some(1), None, &mut |_| {}).unwrap();
    for g in ["", "second_rail/"] {
        for (group, v) in [("passes", "rms_corrugation"), ("rail", "state"), ("rail", "profile")] {
            let group = format!("{g}{group}");
            let (a, b) = (read_f64(&full, &group, v).unwrap(), read_f64(&part, &group, v).unwrap());
            assert!(a == b, "{group}/{v}");
        }
    }
}
