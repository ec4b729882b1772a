//! The `[track]` section: defaults reproduce the built-in track bit for
//! bit, presets and overrides, the two forms of damping, the continuous
//! model's response to the parameters engineers change, and bad input.
use corrugation::config::load_str;
use corrugation::dynamics::rail::RailSection;
use corrugation::dynamics::receptance::TrackParams;
use corrugation::dynamics::track::Damping;
use std::f64::consts::PI;

const GROWTH: &str = include_str!("../configs/growth_fastsim.toml");

fn load(set: &[&str]) -> Result<corrugation::config::Resolved, corrugation::config::ConfigErrors> {
    load_str(GROWTH, "growth", &set.iter().map(|s| s.to_string()).collect::<Vec<_>>())
}

fn errors(set: &[&str]) -> Vec<String> {
    match load(set) {
        Ok(_) => Vec::new(),
        Err(e) => e.errors.iter().map(|e| e.to_string()).collect(),
    }
}

#[test]
fn defaults_are_the_built_in_track() {
    let r = load(&[]).unwrap();
    assert_eq!(r.scene.track.smeared(), TrackParams::uic60_default());
    // The resolved config records the section, and reads back the same.
    assert!(r.toml.contains("[track]") && r.toml.contains("rail = \"UIC60\""), "{}", r.toml);
    assert_eq!(load_str(&r.toml, "resolved", &[]).unwrap().scene, r.scene);
    // A single passage has no [track] unless it gives one.
    let single = load_str(include_str!("../configs/paper_normal_30mm.toml"), "p", &[]).unwrap();
    assert!(!single.toml.contains("[track]"));
}

#[test]
fn presets_overrides_and_damping() {
    let r = load(&["track.rail=\"54E1\"", "track.rail_mass=55.0", "track.sleeper_spacing=0.65"]).unwrap();
    let t = r.scene.track;
    let preset = RailSection::preset("54E1").unwrap();
    assert_eq!((t.rail.bending_stiffness, t.rail.mass), (preset.bending_stiffness, 55.0));
    assert_eq!(t.rail.shear_stiffness, preset.shear_stiffness);
    assert!((t.smeared().pad_stiffness - 200e6 / 0.65).abs() < 1e-6);
    // A viscous pad c = eta k / w0 is the loss factor eta at w0 (and only there).
    let w0 = 2.0 * PI * 500.0;
    let c = 0.25 * 200e6 / w0;
    let v = load(&[&format!("track.pad_damping={c}")]).unwrap().scene.track;
    assert_eq!(v.pad_damping, Damping::Viscous(c));
    let (hyst, visc) = (TrackParams::uic60_default(), v.smeared());
    let d = (visc.foundation_stiffness(w0) - hyst.foundation_stiffness(w0)).norm();
    assert!(d < 1e-9 * hyst.foundation_stiffness(w0).norm(), "{d}");
    assert!(
        (visc.foundation_stiffness(2.0 * w0) - hyst.foundation_stiffness(2.0 * w0)).norm()
            > 1e-3 * hyst.foundation_stiffness(w0).norm()
    );
}

#[test]
fn softer_pads_lower_the_track_resonance_and_stay_passive() {
    // The rail-on-pad resonance sqrt(s_p / m_r) of the sleeper-blocked rail
    // falls with the pad stiffness as its square root.
    let stiff = load(&[]).unwrap().scene.track.smeared();
    let soft = load(&["track.pad_stiffness=100e6", "track.pad_damping=2e4"]).unwrap().scene.track.smeared();
    let f = |t: &TrackParams| (t.pad_stiffness / t.rail_mass).sqrt() / (2.0 * PI);
    assert!((f(&stiff) / f(&soft) - 2f64.sqrt()).abs() < 1e-12);
    for t in [stiff, soft] {
        for k in 0..400 {
            let w = 2.0 * PI * 10f64.powf(1.0 + 2.7 * k as f64 / 399.0);
            assert!(t.rail_receptance(w).im <= 0.0, "active at {w} rad/s");
        }
    }
}

#[test]
fn bad_track_keys() {
    let cases: &[(&[&str], &str)] = &[
        (&["track.rail=S49"], "track.rail: = \"S49\" is not allowed; expected one of \"UIC60\", \"54E1\""),
        (&["track.sleeper_spacing=2"], "track.sleeper_spacing: = 2 is out of range; expected a number in [0.3, 1.5]"),
        (&["track.pad_stiffness=0"], "track.pad_stiffness: = 0 is out of range"),
        (&["track.rail_mass=-1"], "track.rail_mass: = -1 is out of range"),
        (
            &["track.pad_loss_factor=0.2", "track.pad_damping=1e4"],
            "track.pad_damping: and track.pad_loss_factor both damp the pad: give one of them",
        ),
        (
            &["track.ballast_loss_factor=20"],
            "track.ballast_loss_factor: = 20 is out of range; expected a number in [0, 10]",
        ),
        (&["track.gauge=1.435"], "track.gauge: unknown key"),
    ];
    for (set, expected) in cases {
        let e = errors(set);
        assert_eq!(e.len(), 1, "{set:?}: {e:?}");
        assert!(e[0].contains(expected), "{set:?}:\n  got      {}\n  expected {expected}", e[0]);
    }
}
