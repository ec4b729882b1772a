//! The wheelset's torsional mode (`[wheelset]`): its resonance and
//! anti-resonance against the closed form, the closed loop's limits (the
//! torque held far below the resonance, the creepage far above), the
//! creepage it feeds into a growth study, and resume bit for bit.
use corrugation::config::load_str;
use corrugation::dynamics::wheelset::torsion::{TorsionFeedback, WheelsetTorsion};
use corrugation::output::netcdf::read_f64;
use corrugation::run::{resume, run_scene};
use std::f64::consts::PI;

const WHEELSET: WheelsetTorsion = WheelsetTorsion { stiffness: 3e6, loss_factor: 0.02, inertia: 30.0, radius: 0.5 };

#[test]
fn the_torsional_resonance_is_the_closed_forms() {
    // |T| peaks where the wheels twist against each other, sqrt(2 k / J),
    // and vanishes where the other wheel holds this one, sqrt(k / J)
    // (undamped: 71.18 and 50.33 Hz); the loss factor shifts the peak by
    // O(eta^2).
    let speed = 27.78;
    let t = |f: f64| WHEELSET.creepage_per_force(2.0 * PI * f, speed).norm();
    let sweep: Vec<f64> = (0..200_000).map(|k| 30.0 + k as f64 * 1e-3).collect();
    let peak =
        sweep.iter().cloned().filter(|f| *f > 60.0).fold((0.0, 0.0), |m, f| if t(f) > m.1 { (f, t(f)) } else { m }).0;
    let dip = sweep
        .iter()
        .cloned()
        .filter(|f| *f < 60.0)
        .fold((0.0, f64::MAX), |m, f| if t(f) < m.1 { (f, t(f)) } else { m })
        .0;
    let (resonance, anti) = (WHEELSET.resonance(), (3e6f64 / 30.0).sqrt() / (2.0 * PI));
    assert!((resonance - (2.0 * 3e6f64 / 30.0).sqrt() / (2.0 * PI)).abs() < 1e-12);
    eprintln!("peak {peak:.3} Hz (closed form {resonance:.3}), dip {dip:.3} Hz ({anti:.3})");
    assert!((peak - resonance).abs() < 1e-3 * resonance, "{peak} vs {resonance}");
    assert!((dip - anti).abs() < 1e-3 * anti, "{dip} vs {anti}");
    // Far below: the free wheelset, T = -i r^2 / (2 J w V).
    let w = 2.0 * PI * 1.0;
    let free = -0.25 / (2.0 * 30.0 * w * speed);
    let low = WHEELSET.creepage_per_force(w, speed);
    assert!((low.im - free).abs() < 1e-3 * free.abs() && low.re.abs() < 0.05 * free.abs(), "{low} vs {free}i");
}

#[test]
fn the_loop_holds_the_torque_below_and_at_the_resonance_and_the_creepage_far_above() {
    // dF/dN = C_N / (1 - C_xi T): 0 far below the resonance (the wheelset
    // spins up and the drive torque holds the force) and at it (the
    // wheels twist freely); C_N at the anti-resonance (the other wheel
    // holds this one) and far above the corner w_c = |C_xi| r^2 / (J V)
    // where the creep force's damping of the wheel's spin, |C_xi| r^2 / V,
    // meets its inertia (there |dF/dN| = C_N / sqrt(2) within the
    // resonance's k / (J w^2), 0.5 %).
    let (c_n, c_xi, speed) = (0.2, -1.5e7, 27.78);
    let loop_ = TorsionFeedback { torsion: WHEELSET, force_per_normal: c_n, force_per_creepage: c_xi };
    let at = |f: f64| loop_.force_per_normal_force(f, speed).norm();
    let anti = (3e6f64 / 30.0).sqrt() / (2.0 * PI);
    let corner = c_xi.abs() * 0.25 / (30.0 * speed) / (2.0 * PI);
    eprintln!(
        "corner {corner:.1} Hz: {:.4}; anti-resonance {:.4}; resonance {:.3e}",
        at(corner),
        at(anti),
        at(WHEELSET.resonance())
    );
    assert!(at(0.1) < 0.01 * c_n, "{}", at(0.1));
    assert!(at(WHEELSET.resonance()) < 0.01 * c_n, "{}", at(WHEELSET.resonance()));
    assert!(at(anti) > 0.5 * c_n, "{}", at(anti));
    assert!((at(corner) - c_n / 2f64.sqrt()).abs() < 0.01 * c_n, "{}", at(corner));
    assert!((at(2e4) - c_n).abs() < 0.01 * c_n, "{}", at(2e4));
}

/// growth_fastsim.toml under creepage control, with `set`.
fn scene(set: &[&str]) -> Result<corrugation::config::Resolved, corrugation::config::ConfigErrors> {
    let text: String = include_str!("../configs/growth_fastsim.toml")
        .lines()
        .filter(|l| !l.starts_with("longitudinal_force"))
        .collect::<Vec<_>>()
        .join("\n");
    // The torsional feedback of the vertical dynamics (eq. 3 of
    // dynamics::wheelset::torsion); the dynamics in every direction has its own
    // tests (tests/contact_dynamics.rs).
    let mut all: Vec<String> = [
        "load.control=creepage",
        "rolling.creepage_x=-1.3e-3",
        "growth.contact_history=[0]",
        "dynamics.directions=vertical",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    all.extend(set.iter().map(|s| s.to_string()));
    load_str(&format!("{text}\n[wheelset]\nmodel = \"torsion\"\n"), "g", &all)
}

#[test]
fn a_growth_study_with_the_torsional_mode_varies_the_creepage_and_resumes_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let (full, part) = (dir.path().join("full.h5"), dir.path().join("part.h5"));
    run_scene(&scene(&["growth.passes=3"]).unwrap(), &full, &mut |_| {}).unwrap();
    // The creepage of the first passage is the torsion's answer to its
    // normal force's variation, eq. 3 per harmonic: rebuilt from the
    // history's normal force over the stretch (the steps on the rail
    // nodes, one period) with the scene's own feedback.
    let resolved = scene(&["growth.passes=3"]).unwrap();
    assert_creepage_is_eq3(&resolved, &full, "contact/pass_00000");
    run_scene(&scene(&["growth.passes=2"]).unwrap(), &part, &mut |_| {}).unwrap();
    resume(&part, Some(1), None, &mut |_| {}).unwrap();
    for (g, v) in [("rail", "state"), ("passes", "rms_corrugation")] {
        let (a, b) = (read_f64(&full, g, v).unwrap(), read_f64(&part, g, v).unwrap());
        assert!(a.iter().zip(b.iter()).all(|(x, y)| x.to_bits() == y.to_bits()), "{g}/{v}");
    }
}

#[test]
fn the_torsional_mode_needs_creepage_control_and_a_track_model() {
    let errors = |r: Result<corrugation::config::Resolved, corrugation::config::ConfigErrors>| match r {
        Ok(_) => Vec::new(),
        Err(e) => e.errors.iter().map(|e| e.to_string()).collect::<Vec<_>>(),
    };
    let e = errors(scene(&["dynamics.model=imposed"]));
    assert!(e.len() == 1 && e[0].starts_with("wheelset") && e[0].contains("dynamics.model"), "{e:?}");
    // The vertical dynamics' torsional feedback acts on a prescribed
    // creepage; in every direction the wheel's rotation is part of the
    // contact's dynamics under either control.
    let forced = format!("{}\n[wheelset]\nmodel = \"torsion\"\n", include_str!("../configs/growth_fastsim.toml"));
    let e = errors(load_str(&forced, "g", &["dynamics.directions=vertical".into()]));
    assert!(e.len() == 1 && e[0].starts_with("wheelset") && e[0].contains("load.control = \"creepage\""), "{e:?}");
    assert!(errors(load_str(&forced, "g", &[])).is_empty());
    let e = errors(scene(&["wheelset.polar_inertia=0"]));
    assert!(e.len() == 1 && e[0].starts_with("wheelset.polar_inertia"), "{e:?}");
}

#[test]
fn each_wheel_of_a_vehicle_gets_the_torsion_of_its_own_normal_force() {
    // Two wheels 2.5 m apart with the torsional feedback of the vertical
    // dynamics: each wheel's creepage variation is eq. 3 of its own
    // normal force's variation (before the two rails' change the second
    // wheel took the leading wheel's).
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("bogie.h5");
    let resolved = scene(&["growth.passes=1", "vehicle.wheels=[0.0, 2.5]"]).unwrap();
    run_scene(&resolved, &out, &mut |_| {}).unwrap();
    assert_creepage_is_eq3(&resolved, &out, "contact/pass_00000/wheel_2");
}

/// The creepage of the passage history `group` of the run file `file` (of
/// the study `resolved`) is the torsion's answer to the same history's
/// normal force's variation, eq. 3 per harmonic: rebuilt from the normal
/// force over the stretch (the steps on the rail nodes, one period) with
/// the scene's own feedback, within 1e-6 of its span.
fn assert_creepage_is_eq3(resolved: &corrugation::config::Resolved, file: &std::path::Path, group: &str) {
    let feedback = corrugation::build::derive(&resolved.scene).passage.torsion[0];
    let (x, xi, n) = (
        read_f64(file, group, "x_c").unwrap(),
        read_f64(file, group, "creepage_x").unwrap(),
        read_f64(file, group, "normal_force").unwrap(),
    );
    let inside: Vec<usize> = (0..x.len()).filter(|&k| x[k] >= -1e-9 && x[k] < 0.12 - 1e-9).collect();
    assert_eq!(inside.len(), 600);
    let variation: Vec<f64> = inside.iter().map(|&k| n[k] - 1e5).collect();
    let expected = feedback.creepage(&variation, 2e-4, 27.78);
    let span = expected.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let worst = inside.iter().zip(&expected).fold(0.0f64, |m, (&k, e)| m.max((xi[k] + 1.3e-3 - e).abs()));
    eprintln!("{group}: creepage variation up to {span:.3e}; against eq. 3 within {worst:.3e}");
    assert!(span > 1e-7 && worst < 1e-6 * span, "{group}: {worst:e} of {span:e}");
}

#[test]
fn a_run_file_written_before_the_automatic_wheelset_resumes_with_its_torsional_mode() {
    // Before `wheelset.model = "auto"`, a [wheelset] without `model` was
    // the torsional mode, and the resolved config did not record it: such
    // a file (its stored config without the line) resumes bit for bit as
    // the torsional study it was.
    let dir = tempfile::tempdir().unwrap();
    let (full, part) = (dir.path().join("full.h5"), dir.path().join("part.h5"));
    run_scene(&scene(&["growth.passes=2"]).unwrap(), &full, &mut |_| {}).unwrap();
    run_scene(&scene(&["growth.passes=1"]).unwrap(), &part, &mut |_| {}).unwrap();
    let old = {
        let f = hdf5::File::open(&part).unwrap();
        let text: hdf5::types::VarLenUnicode = f.attr("config").unwrap().read_scalar().unwrap();
        text.as_str().lines().filter(|l| !l.starts_with("model = \"torsion\"")).collect::<Vec<_>>().join("\n")
    };
    assert!(old.contains("[wheelset]") && !old.contains("model = \"torsion\""));
    {
        let f = hdf5::File::open_rw(&part).unwrap();
        f.delete_attr("config").unwrap();
        let v: hdf5::types::VarLenUnicode = old.parse().unwrap();
        f.new_attr::<hdf5::types::VarLenUnicode>().create("config").unwrap().write_scalar(&v).unwrap();
    }
    resume(&part, Some(1), None, &mut |_| {}).unwrap();
    for (g, v) in [("rail", "state"), ("passes", "rms_corrugation")] {
        let (a, b) = (read_f64(&full, g, v).unwrap(), read_f64(&part, g, v).unwrap());
        assert!(a.iter().zip(b.iter()).all(|(x, y)| x.to_bits() == y.to_bits()), "{g}/{v}");
    }
}
