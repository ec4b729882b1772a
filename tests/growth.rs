//! The growth loop's passage over the periodic stretch.
use crate::common;
use common::{STEEL, paper_coefficients, paper_shape, rel};
use corrugation::contact::PressureShape;
use corrugation::contact::fastsim::Fastsim;
use corrugation::growth::growth_passage;
use corrugation::loads::ImposedLoads;
use corrugation::passage::PassageSpec;
use corrugation::rail_grid::RailGrid;
use corrugation::wear::WearDeposit;
use ndarray::Array2;

fn setup(length: f64) -> (PassageSpec, RailGrid, Fastsim) {
    let spec = PassageSpec {
        speed: 27.78,
        friction: 0.4,
        characteristic: Default::default(),
        memory: None,
        creepage_x: None,
        creepage_y: 0.0,
        spin: 0.0,
        loads: ImposedLoads { normal_force: 1e5, longitudinal_force: 2e4, harmonics: vec![] },
        wheel_loads: vec![],
        start: -0.015,
        end: length,
        step_length: 2e-4,
        wear_law: corrugation::wear::WearLaw::Archard { k_over_h: 3.4e-14 },
        substeps: 4,
        wear_window: (f64::NEG_INFINITY, f64::INFINITY),
        dynamic_normal_force: None,
        torsion: vec![],
        dynamic_creepage_x: None,
        dynamic_longitudinal_force: None,
        dynamic_creepage_y: None,
        dynamic_spin: None,
        surface: None,
    };
    let dx = 1e-4;
    let grid = RailGrid { x_min: 0.0, dx, nx: (length / dx).round() as usize, half_width: 0.012, dy: 5e-4, ny: 49 };
    let f = Fastsim::new(10, 10, PressureShape::Parabolic, paper_coefficients(true), STEEL.shear_modulus());
    (spec, grid, f)
}

#[test]
fn periodic_passage_wears_every_node_once() {
    // Constant loads: every node of the periodic stretch sees one full
    // passage of the same steady patch, so the wear does not depend on X
    // (within 1 %), and the folded volume equals the unfolded one.
    let (spec, grid, mut f) = setup(0.03);
    let dep = WearDeposit::new(f.mesh());
    let flat = Array2::zeros((grid.ny, grid.nx));
    let g = growth_passage(
        &spec,
        &paper_shape(true),
        &mut f,
        &dep,
        &grid,
        &flat,
        corrugation::params::NormalContact::Hertz,
        None,
        false,
        &mut |_, _| {},
    )
    .unwrap();
    let centre = g.rails[0].wear.row(grid.ny / 2).to_vec();
    let mean = centre.iter().sum::<f64>() / centre.len() as f64;
    assert!(mean > 0.0);
    for (i, w) in centre.iter().enumerate() {
        assert!(rel(*w, mean) < 0.01, "node {i}: {w} vs {mean}");
    }
    assert!(rel(g.rails[0].wear.sum(), g.rails[0].leading.wear.sum()) < 1e-12);
}

use corrugation::config::load_str;
use corrugation::output::netcdf::read_f64;
use corrugation::run::run_scene;

const GROWTH: &str = include_str!("../configs/growth_fastsim.toml");

/// Runs the growth config with overrides into a temporary file.
fn run_growth(set: &[&str]) -> (tempfile::TempDir, std::path::PathBuf) {
    let mut all: Vec<String> =
        ["contact.elements_x=6", "contact.elements_y=6", "rail.dx=5e-4", "rail.dy=1e-3", "passage.step_length=5e-4"]
            .iter()
            .chain(&["growth.adaptive=false", "growth.traffic_scale=2e4"])
            .map(|s| s.to_string())
            .collect();
    all.extend(set.iter().map(|s| s.to_string()));
    let r = load_str(GROWTH, "growth", &all).unwrap_or_else(|e| panic!("{e}"));
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("g.h5");
    run_scene(&r, &out, &mut |_| {}).unwrap();
    (dir, out)
}

#[test]
fn imposed_dynamics_traffic_scaling_is_exact() {
    // Without feedback every passage is the same: n passages with m = 1
    // remove n times one passage's material, and equal one passage with
    // m = n (within 1e-9 relative).
    let base = ["dynamics.model=imposed", "roughness.rms=0", "growth.contact_history=[]"];
    let (_d1, f1) = run_growth(&[&base[..], &["growth.passes=1", "growth.traffic_scale=1"]].concat());
    let (_d3, f3) =
        run_growth(&[&base[..], &["growth.passes=3", "growth.traffic_scale=1", "growth.store_every=3"]].concat());
    let (_dm, fm) = run_growth(&[&base[..], &["growth.passes=1", "growth.traffic_scale=3"]].concat());
    let v1 = read_f64(&f1, "passes", "removed_volume").unwrap();
    let v3 = read_f64(&f3, "passes", "removed_volume").unwrap();
    assert!(v3.iter().all(|v| rel(*v, v1[0]) < 1e-12), "identical passages");
    let p3 = read_f64(&f3, "rail", "profile").unwrap();
    let pm = read_f64(&fm, "rail", "profile").unwrap();
    let p1 = read_f64(&f1, "rail", "profile").unwrap();
    let scale = p1.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for ((a, b), c) in p3.iter().zip(pm.iter()).zip(p1.iter()) {
        assert!((a - b).abs() <= 1e-9 * 3.0 * scale, "3 x m=1 vs m=3");
        assert!((a - 3.0 * c).abs() <= 1e-9 * 3.0 * scale, "3 x one passage");
    }
    let traffic = read_f64(&f3, "passes", "traffic").unwrap();
    assert_eq!(traffic.as_slice().unwrap(), &[1.0, 2.0, 3.0]);
}

#[test]
fn receptance_feedback_changes_the_spectrum_and_is_recorded() {
    let (_d, f) = run_growth(&["growth.passes=3", "growth.store_every=1", "growth.contact_history=[0]"]);
    let spectrum = read_f64(&f, "passes", "spectrum").unwrap().into_dimensionality::<ndarray::Ix2>().unwrap();
    let wavelengths = read_f64(&f, "passes", "wavelength").unwrap();
    assert_eq!(spectrum.shape(), &[3, wavelengths.len()]);
    assert!((wavelengths[0] - 0.12).abs() < 1e-12, "longest wavelength = stretch length");
    // The roughness band 10-120 mm carries the initial 1 um rms.
    let rms = read_f64(&f, "passes", "rms_corrugation").unwrap();
    assert!(rms.iter().all(|r| *r > 5e-7 && *r < 2e-6), "{rms:?}");
    assert!(spectrum.row(2).iter().zip(spectrum.row(0).iter()).any(|(a, b)| (a - b).abs() > 1e-3 * b.abs()));
    let profile = read_f64(&f, "rail", "profile").unwrap();
    assert_eq!(profile.shape()[0], 3);
    // growth_rate of passage k = 20 log10(A_k / A_{k-1}) * 1e5 / m (dB per
    // 1e5 passages), A the amplitudes of the contact-filtered profile.
    let rate = read_f64(&f, "passes", "growth_rate").unwrap().into_dimensionality::<ndarray::Ix2>().unwrap();
    let filtered = read_f64(&f, "passes", "filtered_spectrum").unwrap().into_dimensionality::<ndarray::Ix2>().unwrap();
    let m = read_f64(&f, "passes", "traffic_scale").unwrap()[0];
    for k in 0..wavelengths.len().min(12) {
        let expected = 20.0 * (filtered[[2, k]] / filtered[[1, k]]).log10() * 1e5 / m;
        assert!((rate[[2, k]] - expected).abs() < 1e-9 * expected.abs().max(1.0), "harmonic {k}");
    }
}

#[test]
fn growth_config_errors() {
    let errors = |set: &[&str]| match load_str(GROWTH, "g", &set.iter().map(|s| s.to_string()).collect::<Vec<_>>()) {
        Ok(_) => Vec::new(),
        Err(e) => e.errors.iter().map(|e| e.to_string()).collect(),
    };
    let e = errors(&["roughness.kind=harmonics", "roughness.harmonics=[{amplitude = 1e-6, wavelength = 0.035}]"]);
    assert!(
        e.iter().any(|m| m.contains("roughness.harmonics[0].wavelength: = 0.035 m does not fit the periodic stretch")),
        "{e:?}"
    );
    // A one-third-octave level spectrum: the 100 mm band (89-112 mm) holds no
    // harmonic of the 120 mm stretch (120, 60, 40 mm ...).
    let levels = [
        "roughness.kind=levels",
        "roughness.bands=[{wavelength = 0.016, level = 0.0}, {wavelength = 0.1, level = 3.0}]",
    ];
    let e = errors(&levels);
    assert!(
        e.iter().any(|m| m.starts_with("roughness.bands[1].wavelength: = 0.1 m: its one-third-octave band")),
        "{e:?}"
    );
    assert_eq!(e.len(), 1, "{e:?}");
    assert!(errors(&["roughness.kind=levels", "roughness.bands=[{wavelength = 0.016, level = -3.0}]"]).is_empty());
    let e = errors(&["roughness.kind=levels", "roughness.bands=[{wavelength = 0.016, level = 300.0}]"]);
    assert!(e.iter().any(|m| m.starts_with("roughness.bands[0].level: ")), "{e:?}");
    let e = errors(&["roughness.kind=levels", "roughness.bands=[{wavelength = 4e-4, level = 0.0}]"]);
    assert!(e.iter().any(|m| m.contains("roughness.bands[0].wavelength: = 0.0004 m: its band's lower edge")), "{e:?}");
    let e = errors(&["roughness.wavelength_min=3e-4"]);
    assert!(e.iter().any(|m| m.starts_with("roughness.wavelength_min: = 0.0003 m must be > 2 rail.dx")), "{e:?}");
    let e = errors(&["passage.start=0"]);
    assert!(e.iter().any(|m| m.starts_with("passage.start: = 0 m must be <= rail.x_min - a")), "{e:?}");
    let e = errors(&["growth.checkpoint_every=0"]);
    assert!(e.iter().any(|m| m.starts_with("growth.checkpoint_every: ")), "{e:?}");
    let e = errors(&["growth.adaptive=true", "growth.traffic_scale_max=10"]);
    assert!(e.iter().any(|m| m.contains("growth.traffic_scale_max: = 10 must be >= growth.traffic_scale")), "{e:?}");
    let e = errors(&["growth.max_update_ratio=0"]);
    assert!(e.iter().any(|m| m.starts_with("growth.max_update_ratio: ")), "{e:?}");
    let e = errors(&["growth.stop=forever"]);
    assert!(e.iter().any(|m| m.contains("growth.stop: = \"forever\" is not allowed; expected one of \"never\", \"saturation\"")), "{e:?}");
    let e = errors(&["growth.stop=saturation", "growth.saturation_rate=0"]);
    assert!(
        e.iter().any(|m| m.contains("growth.saturation_rate: = 0 is out of range; expected a number in (0, 100]")),
        "{e:?}"
    );
    let single = include_str!("../configs/paper_normal_30mm.toml").to_string() + "\n[dynamics]\nmodel = \"imposed\"\n";
    let e = load_str(&single, "x", &[]).unwrap_err();
    assert!(e.to_string().contains("dynamics: is only allowed with a [growth] section"));
}

/// Growth rate of the 40 mm harmonic per real passage over a study of
/// `passes` passages (dB per 1e5 passages), and the run's largest update
/// ratio.
fn rate_40mm(set: &[&str]) -> (f64, f64) {
    // The vertical dynamics: the traffic scaling's accuracy against the
    // growth rate it was measured on.
    let harmonic = [
        "roughness.kind=harmonics",
        "roughness.harmonics=[{amplitude=1e-6, wavelength=0.04}]",
        "dynamics.directions=vertical",
    ];
    let (_d, f) = run_growth(&[&harmonic[..], &["growth.contact_history=[]"], set].concat());
    let waves = read_f64(&f, "passes", "wavelength").unwrap();
    let k = waves.iter().position(|w| (w - 0.04).abs() < 1e-9).unwrap();
    // The contact-filtered amplitude (what the wheel sees) evolves as one
    // exponential per harmonic; the centre line beats between the initial
    // roughness, uniform across the head, and the worn pattern.
    let spectrum = read_f64(&f, "passes", "filtered_spectrum").unwrap().into_dimensionality::<ndarray::Ix2>().unwrap();
    let traffic = read_f64(&f, "passes", "traffic").unwrap();
    let last = traffic.len() - 1;
    let rate = 20.0 * (spectrum[[last, k]] / 1e-6).log10() * 1e5 / traffic[last];
    let q = read_f64(&f, "passes", "update_ratio").unwrap().iter().fold(0.0f64, |a, b| a.max(*b));
    (rate, q)
}

#[test]
fn traffic_scaling_keeps_the_growth_rate_until_the_criterion_flags_it() {
    // Receptance feedback on a 1 um, 40 mm harmonic: its contact-filtered
    // amplitude decays at -0.247 dB per 1e5 passages on this coarse mesh.
    // Three passages with m = 1, 10, 100 give the same rate per real passage
    // (within 5 %; measured 2e-6); the update ratio q (growth::traffic, on
    // the centre line, which changes faster than the filtered line) stays
    // under the 0.05 bound. Where the rate is off by more than 5 %, q is over
    // the bound: m = 1e6 (q = 0.67) is 5.1 % off, m = 3e6 (q = 1.7) 77 %.
    let bound = corrugation::growth::traffic::DEFAULT_MAX_UPDATE_RATIO;
    let (reference, q1) = rate_40mm(&["growth.passes=3", "growth.traffic_scale=1"]);
    assert!(reference < -0.1, "the harmonic decays: {reference}");
    assert!(q1 < 1e-5);
    let mut flagged = Vec::new();
    for m in ["10", "100", "1e4", "1e6", "3e6"] {
        let (rate, q) = rate_40mm(&["growth.passes=3", &format!("growth.traffic_scale={m}")]);
        let error = (rate / reference - 1.0).abs();
        if ["10", "100"].contains(&m) {
            assert!(error < 0.05 && q < bound, "m = {m}: rate {rate} vs {reference}, q = {q}");
        }
        if error > 0.05 {
            assert!(q > bound, "m = {m}: rate off by {error:.3} but the criterion did not flag it (q = {q})");
            flagged.push(m);
        }
    }
    assert!(flagged.contains(&"3e6") && !flagged.contains(&"1e4"), "off by > 5 %: {flagged:?}");
    // Adaptive m from 1e3 doubles up to the bound and keeps the rate.
    let (rate, q) = rate_40mm(&["growth.passes=10", "growth.traffic_scale=1e3", "growth.adaptive=true"]);
    assert!(q <= bound * (1.0 + 1e-12), "q = {q}");
    assert!((rate / reference - 1.0).abs() < 0.05, "adaptive: {rate} vs {reference}");
}
