//! The `[track]` section: defaults reproduce the built-in track bit for
//! bit, presets and overrides, the two forms of damping, the continuous
//! model's response to the parameters engineers change, and bad input.
use corrugation::config::load_str;
use corrugation::dynamics::receptance::TrackParams;
use corrugation::dynamics::track::Damping;
use corrugation::dynamics::track::rail::RailSection;
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

#[test]
fn the_vehicle_section_places_the_wheels() {
    // One wheel without [vehicle]; a bogie's and a car's distances; the
    // wheels must start at the leading one and run backwards.
    assert_eq!(load(&[]).unwrap().scene.vehicle.wheels, vec![0.0]);
    let vertical = "dynamics.directions=vertical";
    let bogie = load(&["vehicle.wheels=[0.0, 2.5]", vertical]).unwrap().scene.vehicle;
    assert_eq!(bogie.distances(), vec![2.5]);
    // The dynamics in every direction takes several wheels too.
    assert_eq!(load(&["vehicle.wheels=[0.0, 2.5]"]).unwrap().scene.vehicle.distances(), vec![2.5]);
    let car = load(&["vehicle.wheels=[0, 2.5, 17.5, 20.0]", vertical]).unwrap().scene.vehicle;
    assert_eq!(car.distances(), vec![2.5, 15.0, 17.5, 20.0]);
    for (set, expected) in [
        ("vehicle.wheels=[1.0, 2.5]", "vehicle.wheels: starts at 1 m; the first is the leading wheel, at 0 m"),
        ("vehicle.wheels=[0.0, 2.5, 2.5]", "vehicle.wheels: must increase: wheel 3 at 2.5 m is not behind wheel 2"),
        ("vehicle.wheels=[0.0, 60.0]", "vehicle.wheels: contains `60.0`; expected a list of 1 to 8 numbers"),
        ("vehicle.wheels=[]", "vehicle.wheels: expected a list of 1 to 8 numbers"),
        ("vehicle.axles=2", "vehicle.axles: unknown key"),
    ] {
        let e = errors(&[set, vertical]);
        assert_eq!(e.len(), 1, "{set}: {e:?}");
        assert!(e[0].starts_with(expected), "{set}: {}", e[0]);
    }
}

#[test]
fn track_writes_the_transfer_between_the_wheels() {
    use corrugation::dynamics::track::discrete::DiscreteTrack;
    use corrugation::output::netcdf::read_f64;
    let dir = tempfile::tempdir().unwrap();
    let config = dir.path().join("bogie.toml");
    std::fs::write(&config, format!("{GROWTH}\n[vehicle]\nwheels = [0.0, 2.5]\n")).unwrap();
    let out = dir.path().join("bogie_track.h5");
    let bin = env!("CARGO_BIN_EXE_corrugation");
    let o = std::process::Command::new(bin)
        .arg("track")
        .arg(&config)
        .args(["--set", "dynamics.directions=vertical", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // The file's transfer at 2.5 m from a force above a sleeper and at
    // mid-span is the discrete track's, at every 60th frequency.
    let (f, re, im) = (
        read_f64(&out, "track", "frequency").unwrap(),
        read_f64(&out, "track", "transfer_real").unwrap(),
        read_f64(&out, "track", "transfer_imag").unwrap(),
    );
    assert_eq!(re.shape(), &[2, 1, f.len()]);
    let track = DiscreteTrack::new(&load(&[]).unwrap().scene.track);
    for (s, x0) in [(0, 0.0), (1, 0.3)] {
        for k in (0..f.len()).step_by(60) {
            let a = track.transfer_receptances(x0, &[2.5], 2.0 * PI * f[k])[0];
            assert_eq!((re[[s, 0, k]], im[[s, 0, k]]), (a.re, a.im), "source {x0}, {} Hz", f[k]);
        }
    }
}
