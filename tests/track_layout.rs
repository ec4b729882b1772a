//! Track layouts (`[track]`'s layout keys): read, refused with the key
//! named, deterministic with their seed, identical bays the one-bay track
//! exactly, and the vehicle-track model on an irregular layout against
//! its closure written out from the layout's receptances.
use corrugation::config::load_str;
use corrugation::dynamics::TrackDynamics;
use corrugation::dynamics::model::{Directions, Track, VehicleTrack, Wheel};
use corrugation::dynamics::track::discrete::DiscreteTrack;
use corrugation::dynamics::track::layout::Layout;
use corrugation::dynamics::track::{Damping, TrackConfig};
use corrugation::dynamics::wheelset::side::Wheel3;
use num_complex::Complex64;
use std::f64::consts::PI;

const DISCRETE: &str = include_str!("../configs/growth_discrete.toml");

/// growth_discrete.toml over two bays with `set` (key=value overrides).
fn load(set: &[&str]) -> Result<corrugation::config::Resolved, Vec<String>> {
    let mut all: Vec<String> = vec!["rail.x_max=1.2".into(), "passage.end=1.2".into()];
    all.extend(set.iter().map(|s| s.to_string()));
    load_str(DISCRETE, "test.toml", &all).map_err(|e| e.errors.iter().map(|e| e.to_string()).collect())
}

fn error(set: &[&str]) -> String {
    load(set).expect_err("refused").join("\n")
}

#[test]
fn identical_bays_given_by_position_are_the_one_bay_track_exactly() {
    let plain = load(&[]).unwrap();
    let listed = load(&["track.sleeper_positions=[0.0, 0.6]", "track.pad_stiffness_pattern=[2e8]"]).unwrap();
    assert_eq!(listed.scene.layout, Layout::uniform(&listed.scene.track));
    // The passage is a function of the scene: the same scene, the same
    // growth passage bit for bit.
    assert_eq!(listed.scene, plain.scene);
}

#[test]
fn one_support_of_its_own_is_the_track_with_that_support() {
    // A pattern of one value other than the configured one, for each of
    // the support's values: the layout's own support, not the configured
    // track's.
    let d = TrackConfig::default();
    let (k_h, speed, dx, nodes) = (1.8e9, 30.0, 1e-3, 600);
    let model = |track: TrackConfig, layout: Layout| {
        let wheel = Wheel::vertical(0.0, Wheel3::new(600.0, 0.46), k_h, 1e5);
        let track = Track::Discrete { vertical: DiscreteTrack::new(&track), head: None, sleeper_x0: 0.0, layout };
        VehicleTrack::new(track, vec![wheel], Directions::Vertical, nodes, dx, speed).unwrap()
    };
    let plain = model(d, Layout::uniform(&d));
    for (set, own) in [
        ("track.pad_stiffness_pattern=[3e8]", TrackConfig { pad_stiffness: 3e8, ..d }),
        ("track.pad_loss_factor_pattern=[0.4]", TrackConfig { pad_damping: Damping::LossFactor(0.4), ..d }),
        ("track.sleeper_mass_pattern=[100.0]", TrackConfig { sleeper_mass: 100.0, ..d }),
        ("track.ballast_stiffness_pattern=[5e7]", TrackConfig { ballast_stiffness: 5e7, ..d }),
    ] {
        let r = load(&[set]).unwrap();
        assert_eq!(r.scene.layout.len(), 1);
        assert!(!r.scene.layout.is_one_bay(&r.scene.track), "{set}");
        assert!(r.scene.layout.is_one_bay(&own), "{set}");
        let layout = model(d, r.scene.layout.clone());
        let own = model(own, Layout::uniform(&own));
        let (mut worst, mut moved) = (0.0f64, 0.0f64);
        for k in [3, 20, 21, 45] {
            for place in [0, 5, 8] {
                let (a, b) = (layout.response(k, place)[(0, 0)], own.response(k, place)[(0, 0)]);
                worst = worst.max((a - b).norm() / b.norm());
                let c = plain.response(k, place)[(0, 0)];
                moved = moved.max((c - b).norm() / b.norm());
            }
        }
        // The one-bay model's truncated lattice sums against the layout's
        // closed form: 1.5e-4 of the receptance; the support's own value
        // moves it by far more.
        assert!(worst < 1e-3, "{set}: {worst:e}");
        assert!(moved > 1e-2, "{set}: the value moves the response by only {moved:e}");
    }
}

#[test]
fn a_viscous_pad_takes_no_loss_factors() {
    let viscous = DISCRETE.replace("pad_loss_factor = 0.25", "pad_damping = 2e4");
    for (set, key) in [
        (vec!["track.pad_loss_factor_pattern=[0.3]"], "track.pad_loss_factor_pattern"),
        (vec!["track.pad_loss_factor_std=0.05", "track.seed=1"], "track.pad_loss_factor_std"),
    ] {
        let mut sets = vec!["rail.x_max=1.2".to_string(), "passage.end=1.2".into()];
        sets.extend(set.iter().map(|s| s.to_string()));
        let e = load_str(&viscous, "test.toml", &sets).expect_err("refused").errors;
        assert_eq!(e.len(), 1, "{e:?}");
        let e = e[0].to_string();
        assert!(e.contains(&format!("{key}: gives the pads loss factors")), "{e}");
    }
}

#[test]
fn a_random_layout_is_its_seeds() {
    let set = |seed: &str| {
        let seed = format!("track.seed={seed}");
        load(&["rail.x_max=3.0", "passage.end=3.0", "track.spacing_std=0.02", "track.pad_stiffness_std=3e7", &seed])
            .unwrap()
            .scene
            .layout
    };
    let (a, b) = (set("4"), set("4"));
    assert_eq!(a, b);
    assert_eq!(a.len(), 5);
    assert_ne!(a, set("5"));
    assert!(a.supports.iter().any(|s| s.pad_stiffness != 2e8));
}

#[test]
fn bad_layouts_are_refused_naming_the_key() {
    for (set, expect) in [
        (
            vec!["track.sleeper_positions=[0.0, 0.7, 0.5]"],
            "track.sleeper_positions: sleeper 3 at 0.5 m does not follow",
        ),
        (vec!["track.sleeper_positions=[0.1, 0.7]"], "track.sleeper_positions: the first sleeper must be at 0 m"),
        (vec!["track.sleeper_positions=[0.0, 1.2]"], "track.sleeper_positions: the last sleeper at 1.2 m"),
        (vec!["track.spacing_std=0.02"], "track.seed: missing"),
        (
            vec!["track.spacing_std=0.02", "track.seed=1", "track.spacing_min=0.61"],
            "track.spacing_min: = 0.61 m and track.spacing_max",
        ),
        (
            vec!["track.pad_stiffness_std=1e7", "track.seed=1", "track.pad_stiffness_max=1.5e8"],
            "track.pad_stiffness_min: = 1.6e8 and track.pad_stiffness_max = 1.5e8 must hold the mean track.pad_stiffness = 2e8",
        ),
        (
            vec!["track.sleeper_positions=[0.0, 0.6]", "track.spacing_std=0.02"],
            "track.spacing_std: and track.sleeper_positions",
        ),
        (vec!["track.sleeper_positions=[0.0, 0.6]", "dynamics.model=receptance"], "track.sleeper_positions: lays out"),
        (
            vec!["track.sleeper_mass_std=10.0", "track.seed=1", "dynamics.model=receptance"],
            "track.sleeper_mass_std: lays out",
        ),
        (vec!["track.spacing_std=0.02", "track.seed=1", "rail.x_max=1.5", "passage.end=1.5"], "rail.x_max:"),
        (
            vec!["track.ballast_stiffness_std=1e7", "track.seed=1", "track.ballast_stiffness_min=1.2e8"],
            "track.ballast_stiffness_min: = 1.2e8 and track.ballast_stiffness_max",
        ),
        (vec!["track.pad_loss_factor_pattern=[0.3, 11.0]"], "track.pad_loss_factor_pattern"),
        (
            vec!["track.pad_loss_factor_pattern=[0.3]", "track.pad_loss_factor_std=0.05", "track.seed=1"],
            "track.pad_loss_factor_std: and track.pad_loss_factor_pattern both",
        ),
    ] {
        let e = error(&set);
        assert!(e.contains(expect), "{set:?}: expected `{expect}` in:\n{e}");
    }
}

#[test]
fn the_model_on_an_irregular_layout_is_its_closure_at_every_place() {
    // One wheel vertically: G = 1 / (alpha_rail(x) + alpha_wheel + 1 /
    // k_H) at each tabulated place, alpha_rail from the layout's own
    // receptances; the places divide each support interval in 16.
    let t = TrackConfig::default();
    let mut layout = Layout::at_positions(&t, 1.2, &[0.0, 0.5]).unwrap();
    layout.supports[1].pad_stiffness = 4e8;
    let (mass, k_h, speed, dx) = (600.0, 1.8e9, 30.0, 1e-3);
    let nodes = 1200;
    let track =
        Track::Discrete { vertical: DiscreteTrack::new(&t), head: None, sleeper_x0: 0.0, layout: layout.clone() };
    let wheel = Wheel::vertical(0.0, Wheel3::new(mass, 0.46), k_h, 1e5);
    let model = VehicleTrack::new(track, vec![wheel], Directions::Vertical, nodes, dx, speed).unwrap();
    let vertical = DiscreteTrack::new(&t);
    let mut worst = 0.0f64;
    for k in [7, 40, 43, 90] {
        let omega = 2.0 * PI * speed * k as f64 / (nodes as f64 * dx);
        for (place, x) in [(0, 0.0), (8, 0.25), (16, 0.5), (24, 0.85)] {
            let rail = vertical.layout_receptances(&layout, &[(x, x)], omega).unwrap()[0];
            let own = Complex64::new(-1.0 / (mass * omega * omega) + 1.0 / k_h, 0.0);
            let expected = 1.0 / (rail + own);
            let got = model.response(k, place)[(0, 0)];
            worst = worst.max((got - expected).norm() / expected.norm());
        }
    }
    // The same exact method twice, over different sets of places.
    assert!(worst < 1e-12, "{worst:e}");
    // On a smooth rail the wheel dips more at mid-span than over a
    // support, and more over the softer support than over the stiffer.
    let path = &model.parametric_paths()[0];
    let at = |x: f64| path[(x / dx).round() as usize];
    assert!(
        at(0.25) < at(0.5) && at(0.85) < at(0.0) && at(0.0) < at(0.5),
        "{} {} {} {}",
        at(0.0),
        at(0.25),
        at(0.5),
        at(0.85)
    );
    // Its resonances: the pinned-pinned of each span, the shorter higher
    // (a simply supported span's first bending frequency goes nearly as
    // the span to the power -2 below the shear's correction).
    let r = model.describe_resonances();
    let f = |label: &str| r.iter().find(|(l, _)| l.as_str() == label).map(|(_, f)| *f).expect(label);
    let (short, long) = (f("pinned-pinned: a span of 500 mm"), f("pinned-pinned: a span of 700 mm"));
    assert!(short > 1.5 * long && short < (0.7f64 / 0.5).powi(2) * long, "{short} {long}");
}
