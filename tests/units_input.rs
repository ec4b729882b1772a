//! Values with units (`"70km/h"`, `"20MN/m"`) in the file and in `--set`,
//! their conversion to SI and the refusals; notes on likely unit mistakes;
//! "did you mean" for unknown keys; the wrong kind of file for `run`,
//! `resume` and `sweep`.
use corrugation::config::load_str;
use corrugation::config::quantity::parse_quantity;
use proptest::prelude::*;
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_corrugation");
const STEADY: &str = include_str!("../configs/paper_steady.toml");
const FASTSIM: &str = include_str!("../configs/growth_fastsim.toml");

fn corrugation(args: &[&str]) -> Output {
    Command::new(BIN).args(args).output().expect("binary runs")
}

/// (unit, the SI unit of its kind, factor to SI).
const UNITS: [(&str, &str, f64); 9] = [
    ("mm", "m", 1e-3),
    ("um", "m", 1e-6),
    ("km/h", "m/s", 1.0 / 3.6),
    ("kN", "N", 1e3),
    ("MN", "N", 1e6),
    ("MN/m", "N/m", 1e6),
    ("GPa", "Pa", 1e9),
    ("MPa", "Pa", 1e6),
    ("t", "kg", 1e3),
];

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// A number with a unit is the number times the unit's factor (to the
    /// last bit but one), with or without a blank.
    #[test]
    fn converts_any_number(mantissa in 1u32..1_000_000, exp in -6i32..6, u in 0usize..UNITS.len(), blank: bool) {
        let (unit, si, factor) = UNITS[u];
        let text = format!("{mantissa}e{exp}{}{unit}", if blank { " " } else { "" });
        let v = parse_quantity(&text, si).unwrap();
        let expected = mantissa as f64 * 10f64.powi(exp) * factor;
        prop_assert!((v - expected).abs() <= 2.0 * f64::EPSILON * expected, "{text}: {v} vs {expected}");
    }

    /// A unit of another kind is always refused, naming the expected unit.
    #[test]
    fn refuses_the_wrong_kind(value in 0.001f64..1000.0, u in 0usize..UNITS.len(), k in 0usize..UNITS.len()) {
        let (unit, si, _) = UNITS[u];
        let (_, want, _) = UNITS[k];
        prop_assume!(si != want);
        let e = parse_quantity(&format!("{value}{unit}"), want).unwrap_err();
        prop_assert!(e.contains(want), "{e}");
    }

    /// Any text gives a value or an error, never a panic (a number then a
    /// backslash escape made rink-core panic: `0\\u`).
    #[test]
    fn any_text_is_answered(text in "[0-9.]{0,3}[ -~]{0,13}") {
        let _ = parse_quantity(&text, "m/s");
    }
}

#[test]
fn values_with_units_in_set_and_file_give_the_si_scene() {
    let plain =
        load_str(STEADY, "s", &["rolling.speed=19.444444444444443".into(), "load.normal_force=70e3".into()]).unwrap();
    let united = load_str(STEADY, "s", &["rolling.speed=70km/h".into(), "load.normal_force=70kN".into()]).unwrap();
    assert_eq!(plain.toml, united.toml);
    let quoted = load_str(STEADY, "s", &["rolling.speed=\"70 km/h\"".into()]).unwrap();
    assert_eq!(quoted.scene.speed, 70.0 / 3.6);
    // In the file: a string with its unit.
    let file = STEADY.replace("speed = 27.78", "speed = \"100km/h\"");
    assert!(file.contains("\"100km/h\""));
    assert_eq!(load_str(&file, "s", &[]).unwrap().scene.speed, 100.0 / 3.6);
    // The track's keys.
    let r =
        load_str(FASTSIM, "f", &["track.pad_stiffness=20MN/m".into(), "track.rail_bending_stiffness=6.4MN m2".into()])
            .unwrap();
    let t: toml::Table = r.toml.parse().unwrap();
    assert_eq!(t["track"]["pad_stiffness"].as_float(), Some(20e6));
    assert_eq!(t["track"]["rail_bending_stiffness"].as_float(), Some(6.4e6));
}

#[test]
fn a_unit_of_the_wrong_kind_names_the_key_and_its_unit() {
    let e = load_str(STEADY, "s", &["rolling.speed=70kN".into()]).unwrap_err().to_string();
    assert!(e.contains("rolling.speed: `70kN` is a force") && e.contains("m/s") && e.contains("70km/h"), "{e}");
    let e = load_str(STEADY, "s", &["material.poisson_ratio=0.3mm".into()]).unwrap_err().to_string();
    assert!(e.contains("material.poisson_ratio") && e.contains("plain number"), "{e}");
    // In range after conversion: 900 km/h = 250 m/s > 200 m/s.
    let e = load_str(STEADY, "s", &["rolling.speed=900km/h".into()]).unwrap_err().to_string();
    assert!(e.contains("rolling.speed: = 250 is out of range"), "{e}");
}

#[test]
fn a_number_far_outside_its_usual_range_is_noted_with_the_likely_unit() {
    let r = load_str(STEADY, "s", &["rolling.speed=70".into()]).unwrap();
    assert!(r.warnings.iter().any(|w| w.contains("rolling.speed") && w.contains("\"70km/h\"")), "{:?}", r.warnings);
    let r = load_str(FASTSIM, "f", &["track.pad_stiffness=20".into()]).unwrap();
    assert!(r.warnings.iter().any(|w| w.contains("\"20MN/m\"")), "{:?}", r.warnings);
    // A key the file writes with its unit, overridden without one, is
    // noted too.
    let with_unit = STEADY.replace("speed = 27.78", "speed = \"100km/h\"");
    assert!(with_unit.contains("100km/h"), "the scene's speed line");
    let r = load_str(&with_unit, "s", &["rolling.speed=70".into()]).unwrap();
    assert!(r.warnings.iter().any(|w| w.contains("rolling.speed") && w.contains("\"70km/h\"")), "{:?}", r.warnings);
    // An axle load in tonnes written as a number.
    let traffic = format!("{FASTSIM}\n[traffic]\naxle_load = 22.5\naxles_per_day = 2000\n");
    let r = load_str(&traffic, "f", &[]).unwrap();
    assert!(r.warnings.iter().any(|w| w.contains("traffic.axle_load") && w.contains("\"22.5t\"")), "{:?}", r.warnings);
    // Written with the unit, or a usual value: no note; the shipped configs
    // have none.
    assert!(load_str(STEADY, "s", &["rolling.speed=70km/h".into()]).unwrap().warnings.is_empty());
    for c in [STEADY, FASTSIM, include_str!("../configs/growth_discrete.toml")] {
        assert!(load_str(c, "c", &[]).unwrap().warnings.is_empty());
    }
    // The binary prints it and runs.
    let o = corrugation(&[
        "check",
        &format!("{}/configs/paper_steady.toml", env!("CARGO_MANIFEST_DIR")),
        "--set",
        "rolling.speed=70",
    ]);
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("warning: rolling.speed = 70 m/s (252 km/h)"));
}

#[test]
fn an_unknown_key_gets_the_nearest_known_one() {
    let e = load_str(STEADY, "s", &["rolling.sped=1".into()]).unwrap_err().to_string();
    assert!(e.contains("rolling.sped: unknown key; did you mean `speed`?"), "{e}");
    let e = load_str(STEADY, "s", &["geometri.wheel_radius=1".into()]).unwrap_err().to_string();
    assert!(e.contains("geometri: unknown section or key; did you mean [geometry]?"), "{e}");
    // A key read only for some choices is known too.
    let e = load_str(FASTSIM, "f", &["track.pad_stifness=1e8".into()]).unwrap_err().to_string();
    assert!(e.contains("did you mean `pad_stiffness`?"), "{e}");
    // A key of another section: that section named.
    let e = load_str(STEADY, "s", &["load.speed=20".into()]).unwrap_err().to_string();
    assert!(e.contains("load.speed: unknown key here; did you mean `rolling.speed` (in [rolling])?"), "{e}");
    // Nothing near: the known keys are listed.
    let e = load_str(STEADY, "s", &["wear.colour=1".into()]).unwrap_err().to_string();
    assert!(e.contains("wear.colour: unknown key; known here: density, hardness, k_over_h, law, map_coefficients, map_speeds, substeps, work_coefficients"), "{e}");
}

#[test]
fn the_wrong_kind_of_file_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let h5 = dir.path().join("run.h5");
    let mut bytes = b"\x89HDF\r\n\x1a\n".to_vec();
    bytes.extend([0u8; 64]);
    std::fs::write(&h5, &bytes).unwrap();
    let toml = format!("{}/configs/paper_steady.toml", env!("CARGO_MANIFEST_DIR"));
    let cases: [(&[&str], &str); 5] = [
        (&["run", h5.to_str().unwrap()], "is an HDF5 run file, not a config (TOML): `corrugation resume"),
        (&["check", h5.to_str().unwrap()], "is an HDF5 run file"),
        (&["resume", &toml], "it is a TOML file, a config: `corrugation run"),
        (&["sweep", "run", &toml], "is a run config (it has [material], [geometry]"),
        (&["sweep", "plan", h5.to_str().unwrap()], "is an HDF5 file"),
    ];
    for (args, says) in cases {
        let o = corrugation(args);
        let e = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {e}");
        assert!(e.contains(says), "{args:?}: {e}");
    }
}
