//! The linear growth spectrum (`corrugation::spectrum`) against the growth
//! study it linearises, on the shipped chain (growth_exact.toml: the exact
//! transient model on the 0.4 mm fixed grid, the consistent chain, the
//! receptance track in every direction) over a 60 mm stretch, so that a
//! passage is cheap. (A coarse FASTSIM mesh is no test scene: its cells
//! switch between adhesion and slip, a piecewise-linear map whose finite
//! differences move by 0.03 dB per 1e5 with the perturbation.)
use corrugation::config::{Resolved, load_str};
use corrugation::growth::study::initial_state;
use corrugation::output::netcdf::read_f64;
use corrugation::run::run_scene;
use corrugation::spectrum::{Spectrum, SpectrumParams, linear_spectrum};
use ndarray::Ix2;

const GROWTH: &str = include_str!("../configs/growth_exact.toml");

/// The coarse scene with overrides.
fn scene(set: &[&str]) -> Resolved {
    let mut all: Vec<String> = [
        "rail.x_max=0.06",
        "passage.end=0.06",
        "roughness.wavelength_max=0.06",
        "growth.adaptive=false",
        "growth.traffic_scale=1e3",
        "growth.contact_history=[]",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    all.extend(set.iter().map(|s| s.to_string()));
    load_str(GROWTH, "growth", &all).unwrap_or_else(|e| panic!("{e}"))
}

/// The spectrum of `r` about the smooth rail with `params`.
fn spectrum_of(r: &Resolved, params: &SpectrumParams) -> Spectrum {
    let state = initial_state(&r.scene);
    let base = vec![ndarray::Array2::zeros(state.profile.raw_dim())];
    linear_spectrum(&r.scene, &base, params, 1, &mut |_| {}).unwrap()
}

/// The band of every test: the 60 mm stretch's harmonics 60 to 10 mm.
fn band() -> SpectrumParams {
    SpectrumParams { wavelength_min: 0.0099, wavelength_max: 0.061, ..SpectrumParams::default() }
}

/// The spectra the tests share, measured once per test process: the
/// continuous track's and the coupled scene's at the default perturbation.
fn shared(coupled: bool) -> &'static Spectrum {
    static CONTINUOUS: std::sync::OnceLock<Spectrum> = std::sync::OnceLock::new();
    static COUPLED_SPECTRUM: std::sync::OnceLock<Spectrum> = std::sync::OnceLock::new();
    if coupled {
        COUPLED_SPECTRUM.get_or_init(|| spectrum_of(&scene(&COUPLED), &band()))
    } else {
        CONTINUOUS.get_or_init(|| spectrum_of(&scene(&[]), &band()))
    }
}

/// The diagonal entry `J(s, s)` of the harmonic of positive index `n` of
/// the stretch (class 0 of one class), its rate (dB per 1e5 wheel
/// passages), and the largest off-diagonal entry of its row and column
/// relative to it.
fn diagonal(s: &Spectrum, n: i64) -> (f64, f64) {
    let class = &s.classes[0];
    let m = class.basis.len();
    let k = class.basis.iter().position(|b| b.index == n).unwrap();
    let j = &s.matrices[0];
    let d = j[k * m + k];
    let off = (0..m).filter(|&i| i != k).map(|i| j[i * m + k].norm().max(j[k * m + i].norm())).fold(0.0, f64::max);
    (-corrugation::spectrum::modes::DB_PER_NEPER * d.re * 1e5, off / d.norm())
}

#[test]
fn on_continuous_track_the_map_is_diagonal_linear_and_its_diagonal_is_each_harmonics_study_rate() {
    // The continuous track and a uniform smooth rail are invariant under
    // any shift: J couples no two harmonics (measured: off-diagonal entries
    // below 8e-4 of the diagonal at the default 10 nm, the solvers'
    // tolerance; at 0.1 um the contact's third-order response puts 5e-3
    // on the third harmonic), and each diagonal entry is the rate a study
    // of that harmonic alone measures in its first passage (within 0.02 dB
    // per 1e5; m = 1e3, 1 nm).
    let s = shared(false);
    assert_eq!(s.classes.len(), 1);
    assert_eq!(s.classes[0].basis.len(), 12, "6 harmonics, both signs");
    for n in 1..=6i64 {
        let (rate, off) = diagonal(s, n);
        assert!(off < 2e-3, "harmonic {n}: off-diagonal {off:.2e} of the diagonal");
        // (The study's rate at the band's ends and its middle.)
        if ![1, 3, 6].contains(&n) {
            continue;
        }
        let wavelength = 0.06 / n as f64;
        let study = scene(&[
            "growth.passes=1",
            "roughness.kind=harmonics",
            &format!("roughness.harmonics=[{{amplitude=1e-9, wavelength={wavelength}, phase=0.3}}]"),
        ]);
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("g.h5");
        run_scene(&study, &out, &mut |_| {}).unwrap();
        let waves = read_f64(&out, "passes", "wavelength").unwrap();
        let i = waves.iter().position(|w| (w - wavelength).abs() < 1e-9).unwrap();
        let rates = read_f64(&out, "passes", "growth_rate").unwrap().into_dimensionality::<Ix2>().unwrap();
        assert!((rates[[0, i]] - rate).abs() < 0.02, "{wavelength} m: study {} vs spectrum {rate}", rates[[0, i]]);
    }
    // The modes are the harmonics, one each, with their rates.
    assert_eq!(s.modes.len(), 6);
    for k in 0..6 {
        let n = (0.06 / s.wavelength(k)).round() as i64;
        assert!((s.modes[k].growth_rate() - diagonal(s, n).0).abs() < 1e-3);
        assert!(s.modes[k].purity() > 0.999);
    }
    // Sorted fastest first.
    assert!(s.modes.windows(2).all(|w| w[0].growth_rate() >= w[1].growth_rate()));
    // No forced pattern on a continuous track (uniform wear: its harmonics
    // are round-off against the mean wear of a passage).
    let mean = s.mean_wear[0];
    assert!(mean > 1e-12, "a passage wears the rail: {mean}");
    assert!(s.forced_wear[0].iter().all(|f| *f < 1e-6 * mean), "{:?} vs {mean}", s.forced_wear[0]);
    the_spectrum_is_linear_a_decade_either_side_of_the_default_perturbation();
}

/// Part of the continuous track's test (it shares that spectrum, measured
/// once per test process).
fn the_spectrum_is_linear_a_decade_either_side_of_the_default_perturbation() {
    // Central differences at 1 nm and 10 nm (the default) within 0.02 dB
    // per 1e5 at every wavelength (measured 0.004; at 0.1 um the 10 mm
    // harmonic's rate moves by 0.029, the linear regime's end for a single
    // harmonic: docs/src/theory/growth-spectrum.md). Forward differences at
    // 10 nm within 0.02 of central ones (measured 0.001).
    // (The two spectra on 60-15 mm, four harmonics, to save passages.)
    let r = scene(&[]);
    let at = |perturbation: f64, difference| {
        let s = spectrum_of(&r, &SpectrumParams { perturbation, difference, wavelength_min: 0.0149, ..band() });
        (1..=4).map(|n| diagonal(&s, n).0).collect::<Vec<f64>>()
    };
    use corrugation::spectrum::Difference::{Central, Forward};
    let default: Vec<f64> = (1..=4).map(|n| diagonal(shared(false), n).0).collect();
    let (small, forward) = (at(1e-9, Central), at(1e-8, Forward));
    for n in 0..4 {
        assert!((small[n] - default[n]).abs() < 0.02, "{}: {} vs {}", n + 1, small[n], default[n]);
        assert!((forward[n] - default[n]).abs() < 0.02, "{}: forward {} vs {}", n + 1, forward[n], default[n]);
    }
}

/// The coupled scene: a 10 kN imposed normal-force harmonic of 30 mm on
/// the 60 mm stretch, so that the base state repeats every 30 mm and the
/// passage's map couples the harmonics n and n +- 2 (two Bloch classes of
/// the 30 mm cell: n even and n odd).
const COUPLED: [&str; 1] = ["load.harmonics=[{quantity = \"normal_force\", amplitude = 1e4, wavelength = 0.03}]"];

/// The rate of every mode, with its wavelength, sorted by wavelength then
/// rate.
fn rates(s: &Spectrum) -> Vec<(f64, f64)> {
    let mut v: Vec<(f64, f64)> = (0..s.modes.len()).map(|k| (s.wavelength(k), s.modes[k].growth_rate())).collect();
    v.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    v
}

#[test]
fn bloch_classes_of_a_cell_are_the_stretch_of_two_cells_own_and_its_leading_mode_grows_at_its_eigenvalue() {
    // On the 60 mm stretch (one class) the map couples the harmonics of
    // each class of the 30 mm cell only: the entries between n even and n
    // odd vanish (below 2e-3 of the diagonal, the solvers' tolerance),
    // those within a class do not (the imposed load's modulation). The
    // 30 mm cell's two classes, measured on its supercell of two cells with
    // every class perturbed in the same passages, give the same modes
    // within 0.02 dB per 1e5.
    let period = ["rail.x_max=0.03", "passage.end=0.03", "roughness.wavelength_max=0.03"];
    let two = shared(true);
    let class = &two.classes[0];
    let m = class.basis.len();
    let j = &two.matrices[0];
    let (mut across, mut within) = (0.0f64, 0.0f64);
    for (r, a) in class.basis.iter().enumerate() {
        for (c, b) in class.basis.iter().enumerate() {
            let scale = j[r * m + r].norm().min(j[c * m + c].norm());
            let v = j[r * m + c].norm() / scale;
            if (a.index - b.index).rem_euclid(2) == 1 {
                across = across.max(v);
            } else if r != c {
                within = within.max(v);
            }
        }
    }
    assert!(across < 2e-3, "between the classes: {across:.2e}");
    assert!(within > 1e-2, "within a class the load couples the harmonics: {within:.2e}");
    // (The cell's spectrum by forward differences, half the passages:
    // within 1e-3 dB per 1e5 of central ones on these scenes.)
    let forward = corrugation::spectrum::Difference::Forward;
    let cell = spectrum_of(
        &scene(&[&COUPLED[..], &period[..]].concat()),
        &SpectrumParams { classes: 2, difference: forward, ..band() },
    );
    assert_eq!(cell.classes.len(), 2, "kappa = 0 and pi / (30 mm)");
    assert_eq!(cell.supercell(), two.stretch);
    let (a, b) = (rates(two), rates(&cell));
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(&b) {
        assert!((x.0 - y.0).abs() < 1e-9 && (x.1 - y.1).abs() < 0.02, "{x:?} vs {y:?}");
    }
    // The forced pattern: the imposed load's, at 30 mm and its harmonics,
    // as the study's smooth-rail passage records it.
    let k = two.wavelengths.iter().position(|w| (w - 0.03).abs() < 1e-9).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("g.h5");
    run_scene(&scene(&[&COUPLED[..], &["growth.passes=1"]].concat()), &out, &mut |_| {}).unwrap();
    let forced = read_f64(&out, "passes", "forced_wear").unwrap().into_dimensionality::<Ix2>().unwrap();
    assert!(two.forced_wear[0][k] > 1e-3 * two.mean_wear[0], "{} vs {}", two.forced_wear[0][k], two.mean_wear[0]);
    for (n, f) in two.forced_wear[0].iter().enumerate() {
        assert!(
            (f - forced[[0, n]]).abs() <= 1e-9 * two.forced_wear[0][k],
            "harmonic {}: {f} vs {}",
            n + 1,
            forced[[0, n]]
        );
    }
    a_study_started_from_the_leading_mode_grows_at_its_eigenvalue();
}

/// Part of the Bloch classes' test (it shares the coupled scene's
/// spectrum, measured once per test process).
fn a_study_started_from_the_leading_mode_grows_at_its_eigenvalue() {
    // The leading mode of the coupled scene (its harmonics locked together
    // by the imposed load's modulation, 60 mm with 20 and 12 mm) as the
    // initial roughness, 0.1 um at its largest harmonic: over 20 passages
    // of m = 100 the mode's amplitude in the study's contact-filtered
    // profile (its dual vector applied to the profile's harmonics) grows at
    // the mode's rate within 2 % (measured 0.9 %). Harmonic by harmonic the
    // rate beats (the load couples q with -q, and a real pattern holds the
    // mode and its conjugate). The smooth rail's spectrum holds while the
    // rail is near smooth: with m = 1e3 the forced 30 mm pattern grows to
    // 0.4 um in the 20 passages, four times the mode, and the mode's rate
    // has moved by 15 % at the last passage (8 % over the 20): the spectrum
    // of a worn rail is taken about it (spectrum.base).
    let s = shared(true);
    let mode = &s.modes[0];
    let class = &s.classes[mode.class];
    assert!((s.wavelength(0) - 0.06).abs() < 1e-9);
    // The real pattern Re sum v_s exp(i q_s X) as sines: per positive
    // harmonic a_s = v_s + conj(v_-s), amplitude |a_s|, phase arg a_s + pi/2.
    let at = |i: i64| class.basis.iter().position(|b| b.index == i).map_or(Default::default(), |k| mode.vector[k]);
    let parts: Vec<(i64, num_complex::Complex64)> = (1..=6i64).map(|n| (n, at(n) + at(-n).conj())).collect();
    let peak = parts.iter().map(|(_, a)| a.norm()).fold(0.0, f64::max);
    let harmonics: Vec<String> = parts
        .iter()
        .filter(|(_, a)| a.norm() > 1e-4 * peak)
        .map(|(n, a)| {
            format!(
                "{{amplitude = {:e}, wavelength = {:e}, phase = {:e}}}",
                1e-7 * a.norm() / peak,
                0.06 / *n as f64,
                a.arg() + 0.5 * std::f64::consts::PI
            )
        })
        .collect();
    assert!(harmonics.len() >= 2, "the mode holds several harmonics: {harmonics:?}");
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("g.h5");
    let set = ["growth.passes=20", "growth.store_every=20", "roughness.kind=harmonics", "growth.traffic_scale=1e2"];
    let study =
        scene(&[&COUPLED[..], &set[..], &[&format!("roughness.harmonics=[{}]", harmonics.join(", "))]].concat());
    run_scene(&study, &out, &mut |_| {}).unwrap();
    // The mode's amplitude in a profile: its filtered line's harmonics on
    // the class's basis.
    let grid = corrugation::build::study_grid(&study.scene);
    let b = corrugation::growth::mean_patch(&study.scene, &corrugation::build::derive(&study.scene).shape).1;
    let amplitude = |profile: &ndarray::Array2<f64>| {
        let line = corrugation::growth::contact_filtered_line(profile, &grid, b);
        let buf = corrugation::spectrum::bloch::dft(&line);
        let roughness: Vec<_> =
            class.basis.iter().map(|h| corrugation::spectrum::bloch::coefficient(&buf, h.index)).collect();
        mode.amplitude(&roughness)
    };
    let before = amplitude(&initial_state(&study.scene).profile);
    let profile = read_f64(&out, "rail", "profile").unwrap().into_dimensionality::<ndarray::Ix3>().unwrap();
    let traffic = read_f64(&out, "passes", "traffic").unwrap();
    let after = amplitude(&profile.index_axis(ndarray::Axis(0), 0).to_owned());
    let rate = 20.0 * (after.norm() / before.norm()).log10() * 1e5 / traffic[traffic.len() - 1];
    let want = mode.growth_rate();
    assert!((rate / want - 1.0).abs() < 0.02, "the mode's amplitude grew at {rate}, its rate is {want}");
}

#[test]
fn where_the_wear_does_not_see_the_profile_the_map_is_zero_and_the_wear_all_forced() {
    // The paper's chain: imposed loads and the Hertz contact. The profile
    // enters neither, so J = 0 exactly, every rate 0, and a study's
    // roughness-driven rates 0 while its harmonics deepen by m W0 each
    // passage.
    let hertz = ["dynamics.model=imposed", "contact.normal=hertz"];
    let s = spectrum_of(&scene(&[&COUPLED[..], &hertz[..]].concat()), &band());
    assert!(s.matrices.iter().flatten().all(|v| v.norm() == 0.0), "J = 0");
    assert!(s.modes.iter().all(|m| m.growth_rate() == 0.0));
    assert_eq!(s.forced_wear, s.base_wear);
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("g.h5");
    run_scene(&scene(&[&COUPLED[..], &hertz[..], &["growth.passes=2"]].concat()), &out, &mut |_| {}).unwrap();
    // (The second passage's rates are the round-off of (r - m W) + m W0.)
    let rate = read_f64(&out, "passes", "growth_rate").unwrap();
    assert!(rate.iter().all(|r| r.abs() < 1e-6), "{rate:?}");
}

#[test]
fn a_measurement_in_parts_merges_into_the_one_piece_spectrum_bit_for_bit() {
    // Three parts (rounds t mod 3), each written to a part file and read
    // back, merged: the same J, modes and forced pattern as the one-piece
    // measurement, bit for bit, also where a part ran on two threads; a missing part or one measured twice is
    // refused.
    use corrugation::spectrum::measure::{Responses, empty, measure};
    let r = scene(&[]);
    // (Forward differences: the merge is bookkeeping, half the passages.)
    let params =
        SpectrumParams { wavelength_min: 0.029, difference: corrugation::spectrum::Difference::Forward, ..band() };
    let state = initial_state(&r.scene);
    let base = vec![ndarray::Array2::zeros(state.profile.raw_dim())];
    let whole = linear_spectrum(&r.scene, &base, &params, 1, &mut |_| {}).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let parts: Vec<Responses> = (0..3)
        .map(|k| {
            // (Part 1 on two threads, each with its own passage model: the
            // same responses bit for bit.)
            let jobs = if k == 0 { 2 } else { 1 };
            let part = measure(&r.scene, &base, &params, Some((k, 3)), jobs, &mut |_| {}).unwrap();
            let path = dir.path().join(format!("part_{k}.h5"));
            corrugation::output::spectrum_part::write_part(&path, &part, (k, 3), &r.toml).unwrap();
            let read = corrugation::output::spectrum_part::read_part(&path, empty(&r.scene, &params, 1).unwrap());
            let read = read.unwrap();
            assert_eq!(read.part, (k, 3));
            assert_eq!(read.config, r.toml);
            assert_eq!(read.responses.columns, part.columns, "part {k} reads back as written");
            read.responses
        })
        .collect();
    assert!(Spectrum::from_responses(&r.scene, &params, parts[0].clone()).is_err(), "a part alone is not a spectrum");
    assert!(Responses::merge(vec![parts[0].clone(), parts[0].clone()]).is_err(), "a part twice");
    let merged = Spectrum::from_responses(&r.scene, &params, Responses::merge(parts).unwrap()).unwrap();
    assert_eq!(merged.matrices, whole.matrices);
    assert_eq!(merged.forced_wear, whole.forced_wear);
    let rates = |s: &Spectrum| s.modes.iter().map(|m| m.growth_rate().to_bits()).collect::<Vec<_>>();
    assert_eq!(rates(&merged), rates(&whole));
}

#[test]
fn the_forecast_deepens_the_forced_pattern_as_a_smooth_rails_study_does() {
    // The imposed load's forced pattern on a smooth rail: a study's 15 mm
    // harmonic of the contact-filtered line (the line the spectrum's
    // forced pattern is of) after three passages of 1e4 wheel passages each
    // against the
    // forecast's forced part in a band around it (the pattern's complex
    // coefficients carried by Phi(n)), within 3 % (the study updates the
    // rail once per passage, the forecast integrates the update).
    use corrugation::levels::density::RoughnessDensity;
    use corrugation::spectrum::forecast::BandGrowth;
    use corrugation::spectrum::outlook::{Inputs, outlook};
    let smooth = ["roughness.kind=none", "growth.traffic_scale=1e4", "growth.passes=3"];
    let r = scene(&[&COUPLED[..], &smooth[..]].concat());
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("g.h5");
    run_scene(&r, &out, &mut |_| {}).unwrap();
    let amplitude = read_f64(&out, "passes", "filtered_spectrum").unwrap().into_dimensionality::<Ix2>().unwrap();
    let wavelengths = read_f64(&out, "passes", "wavelength").unwrap();
    let traffic = read_f64(&out, "passes", "traffic").unwrap();
    let k = wavelengths.iter().position(|w| (w - 0.015).abs() < 1e-9).unwrap();
    let s = shared(true);
    let growth = BandGrowth::new(s).unwrap();
    let band = corrugation::levels::Band { wavelength: 0.015, lower: 0.0145, upper: 0.0155 };
    let n = traffic[traffic.len() - 1];
    let o = outlook(&Inputs {
        growth: &growth,
        rail: 0,
        density: &RoughnessDensity::none(),
        record_length: None,
        measured: (0.0099, 0.061),
        bands: &[(band, f64::INFINITY)],
        traffic: &[n],
    });
    let forecast = 1e-6 * 10f64.powf(o.rows[0].levels[0] / 20.0) * std::f64::consts::SQRT_2;
    let study = amplitude[[amplitude.nrows() - 1, k]];
    assert!((forecast / study - 1.0).abs() < 0.03, "15 mm after {n} wheel passages: {forecast:e} vs {study:e} m");
    assert!(study > 1e-9, "the pattern deepened: {study:e} m");
}
