//! Checkpoints and resume: a resumed growth study is bit for bit the study
//! that was never interrupted, also after a kill -9.
use corrugation::config::load_str;
use corrugation::output::netcdf::{read_attr_str, read_f64, read_i64};
use corrugation::run::{resume, run_scene};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

const GROWTH: &str = include_str!("../configs/growth_fastsim.toml");

/// The coarse growth study of the tests (about 0.05 s per passage).
fn overrides(extra: &[&str]) -> Vec<String> {
    let coarse =
        ["contact.elements_x=6", "contact.elements_y=6", "rail.dx=5e-4", "rail.dy=1e-3", "passage.step_length=5e-4"];
    coarse.iter().chain(extra).map(|s| s.to_string()).collect()
}

fn run(dir: &Path, name: &str, extra: &[&str]) -> PathBuf {
    let r = load_str(GROWTH, "growth", &overrides(extra)).unwrap_or_else(|e| panic!("{e}"));
    let out = dir.join(name);
    run_scene(&r, &out, &mut |_| {}).unwrap();
    out
}

/// Every dataset of the file as raw bits, by path (`passes/cpu_seconds`, a
/// wall-clock measurement, left out), and the root attributes.
fn contents(path: &Path) -> Vec<(String, Vec<u64>)> {
    use hdf5::types::{IntSize, TypeDescriptor as TD};
    fn walk(g: &hdf5::Group, prefix: &str, out: &mut Vec<(String, Vec<u64>)>) {
        let mut names = g.member_names().unwrap();
        names.sort();
        for name in names {
            let full = format!("{prefix}/{name}");
            if let Ok(sub) = g.group(&name) {
                walk(&sub, &full, out);
                continue;
            }
            if full == "/passes/cpu_seconds" {
                continue;
            }
            let ds = g.dataset(&name).unwrap();
            let bits: Vec<u64> = match ds.dtype().unwrap().to_descriptor().unwrap() {
                TD::Float(_) => ds.read_raw::<f64>().unwrap().iter().map(|v| v.to_bits()).collect(),
                TD::Integer(IntSize::U8) => ds.read_raw::<i64>().unwrap().iter().map(|v| *v as u64).collect(),
                TD::Integer(IntSize::U1) => ds.read_raw::<i8>().unwrap().iter().map(|v| *v as u64).collect(),
                other => panic!("{full}: unexpected type {other:?}"),
            };
            out.push((full, bits));
        }
    }
    let file = corrugation::output::netcdf::open_file(path).unwrap();
    let mut out = Vec::new();
    walk(&file.group("/").unwrap(), "", &mut out);
    for attr in ["config", "status", "contact_model", "title"] {
        let text = read_attr_str(path, "", attr).unwrap();
        out.push((format!("@{attr}"), text.bytes().map(u64::from).collect()));
    }
    let root = file.group("/").unwrap();
    for attr in ["passes_done", "passes_planned"] {
        out.push((format!("@{attr}"), vec![root.attr(attr).unwrap().read_scalar::<i64>().unwrap() as u64]));
    }
    out
}

fn assert_same(a: &Path, b: &Path) {
    let (ca, cb) = (contents(a), contents(b));
    let names = |c: &[(String, Vec<u64>)]| c.iter().map(|(n, _)| n.clone()).collect::<Vec<_>>();
    assert_eq!(names(&ca), names(&cb), "same variables");
    for ((name, x), (_, y)) in ca.iter().zip(&cb) {
        assert!(x == y, "{name} differs between {} and {}", a.display(), b.display());
    }
}

#[test]
fn resumed_run_equals_the_uninterrupted_run_bit_for_bit() {
    // 4 passages straight, against 2 + resume to 4. store_every = 3 makes the
    // short run store an end-of-run snapshot (passage 1) that the long run
    // does not have; contact_history = [3, 0, 0] asks for a history the short
    // run does not reach; the patch fields are stored.
    let dir = tempfile::tempdir().unwrap();
    // The history list out of order and with a repeat reads back as stored.
    let set = [
        "growth.store_every=3",
        "growth.contact_history=[3, 0, 0]",
        "output.store_fields=true",
        "growth.adaptive=false",
        "traffic.axle_load=22.5e3",
        "traffic.axles_per_day=4000",
    ];
    let full = run(dir.path(), "full.h5", &[&set[..], &["growth.passes=4"]].concat());
    let part = run(dir.path(), "part.h5", &[&set[..], &["growth.passes=2"]].concat());
    assert_eq!(read_attr_str(&part, "", "status").unwrap(), "complete");
    let resumed = dir.path().join("resumed.h5");
    let s = resume(&part, Some(2), Some(&resumed), &mut |_| {}).unwrap();
    assert_eq!((s.passes, s.computed), (4, 2));
    assert_same(&full, &resumed);
    // The field-unit variables are among those compared.
    let names: Vec<String> = contents(&resumed).into_iter().map(|(n, _)| n).collect();
    for v in [
        "/passes/band",
        "/passes/initial_level",
        "/passes/roughness_level",
        "/passes/level_rate",
        "/passes/limit_level",
        "/passes/passages_to_limit",
        "/passes/traffic_mgt",
        "/passes/mgt_to_limit",
        "/passes/days_to_limit",
        "/rail/traffic_days",
    ] {
        assert!(names.iter().any(|n| n == v), "{v} not written");
    }
    assert_eq!(read_i64(&resumed, "rail", "pass").unwrap().as_slice().unwrap(), &[2, 3]);
    // The source file is left as it was.
    assert_eq!(read_f64(&part, "passes", "traffic").unwrap().len(), 2);
}

/// In place, and an adaptive study (its m depends on the stored rows).
#[test]
fn adaptive_study_resumes_in_place_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let adaptive = ["growth.adaptive=true", "growth.traffic_scale=1e3", "growth.contact_history=[]"];
    let full = run(dir.path(), "afull.h5", &[&adaptive[..], &["growth.passes=5"]].concat());
    let part = run(dir.path(), "apart.h5", &[&adaptive[..], &["growth.passes=3"]].concat());
    resume(&part, Some(2), None, &mut |_| {}).unwrap();
    assert_same(&full, &part);
    let m = read_f64(&full, "passes", "traffic_scale").unwrap();
    assert!(m[1] > m[0], "adaptive m grows: {m:?}");
}

/// The exact model under a constant load (imposed dynamics, flat rail):
/// its cached earlier-displacement matrix must not carry from one passage
/// to the next, or a resumed run would differ.
#[test]
fn exact_model_resumes_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let exact = [
        "contact.model=exact-transient",
        "contact.elements_x=4",
        "contact.elements_y=4",
        "dynamics.model=imposed",
        "roughness.kind=none",
        "growth.adaptive=false",
        "growth.contact_history=[]",
    ];
    let full = run(dir.path(), "efull.h5", &[&exact[..], &["growth.passes=3"]].concat());
    let part = run(dir.path(), "epart.h5", &[&exact[..], &["growth.passes=2"]].concat());
    resume(&part, Some(1), None, &mut |_| {}).unwrap();
    assert_same(&full, &part);
}

/// The fixed grid (0.5 x 1 mm, the step): receptance dynamics on random
/// roughness, the patch fields on the grid stored and read back; `auto`
/// takes the linear contact on a window of its grid here.
const FIXED: [&str; 6] = [
    "contact.model=exact-transient",
    "contact.grid=fixed",
    "contact.dy=1e-3",
    "growth.adaptive=false",
    "growth.contact_history=[0, 2]",
    "output.store_fields=true",
];

#[test]
fn fixed_grid_resumes_bit_for_bit_and_repeats_itself() {
    let dir = tempfile::tempdir().unwrap();
    let fixed = FIXED;
    let full = run(dir.path(), "ffull.h5", &[&fixed[..], &["growth.passes=3"]].concat());
    let contact = read_f64(&full, "passes", "profile_contact").unwrap();
    assert!(contact.iter().all(|c| *c == 2.0), "{contact:?}");
    let part = run(dir.path(), "fpart.h5", &[&fixed[..], &["growth.passes=2"]].concat());
    resume(&part, Some(1), None, &mut |_| {}).unwrap();
    assert_same(&full, &part);
    // Deterministic: the same config twice gives the same bits.
    let again = run(dir.path(), "fagain.h5", &[&fixed[..], &["growth.passes=3"]].concat());
    assert_same(&full, &again);
}

/// The profile in the normal contact: the surface and the equivalent
/// roughness are rebuilt from the stored profile at every passage; the
/// growth differs from the Hertz contact's.
#[test]
fn profile_contact_resumes_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let fixed = FIXED;
    let profile = [&fixed[..], &["contact.normal=profile", "roughness.rms=5e-6"]].concat();
    let full = run(dir.path(), "pfull.h5", &[&profile[..], &["growth.passes=3"]].concat());
    let part = run(dir.path(), "ppart.h5", &[&profile[..], &["growth.passes=2"]].concat());
    resume(&part, Some(1), None, &mut |_| {}).unwrap();
    assert_same(&full, &part);
    let hertz = run(
        dir.path(),
        "phertz.h5",
        &[&fixed[..], &["roughness.rms=5e-6", "growth.passes=3", "contact.normal=hertz"]].concat(),
    );
    let (w_profile, w_hertz) =
        (read_f64(&full, "passes", "rms_corrugation").unwrap(), read_f64(&hertz, "passes", "rms_corrugation").unwrap());
    assert!(w_profile != w_hertz, "the profile in the contact changes the growth");
}

/// The friction and wear laws: falling friction with its memory (CONTACT's
/// default) on the fixed grid with the frictional-work law's regimes, their
/// fields and shares stored and read back.
#[test]
fn friction_and_wear_laws_resume_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let fixed = FIXED;
    let laws = [
        &fixed[..],
        &["material.friction_characteristic=exponential", "wear.law=frictional-work", "growth.contact_history=[1, 2]"],
    ]
    .concat();
    let full = run(dir.path(), "lfull.h5", &[&laws[..], &["growth.passes=3"]].concat());
    let part = run(dir.path(), "lpart.h5", &[&laws[..], &["growth.passes=2"]].concat());
    resume(&part, Some(1), None, &mut |_| {}).unwrap();
    assert_same(&full, &part);
    let share = read_f64(&full, "passes", "wear_regime_share").unwrap();
    assert_eq!(share.shape(), &[3, 3]);
    for row in share.outer_iter() {
        assert!((row.sum() - 1.0).abs() < 1e-12, "{row:?}");
    }
}

#[test]
fn killed_run_resumes_from_its_last_checkpoint() {
    let dir = tempfile::tempdir().unwrap();
    let set = ["growth.passes=40", "growth.checkpoint_every=2", "growth.store_every=4"];
    let reference = run(dir.path(), "reference.h5", &set);
    let out = dir.path().join("killed.h5");
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_corrugation"));
    cmd.arg("run").arg("configs/growth_fastsim.toml").arg("-o").arg(&out);
    for s in overrides(&set) {
        cmd.arg("--set").arg(s);
    }
    let mut child = cmd.stderr(std::process::Stdio::null()).spawn().unwrap();
    // Kill -9 once the second checkpoint (4 passages) is on disk.
    let clock = Instant::now();
    let done = loop {
        let done = out.exists().then(|| read_f64(&out, "passes", "traffic").map(|t| t.len()).unwrap_or(0));
        if done.unwrap_or(0) >= 4 || clock.elapsed() > Duration::from_secs(120) {
            break done;
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    child.kill().unwrap();
    child.wait().unwrap();
    let done = done.expect("a checkpoint appeared");
    // The file at the moment of the kill is a valid checkpoint.
    let held = read_f64(&out, "passes", "traffic").unwrap().len();
    assert!(held >= done && held.is_multiple_of(2) && held < 40, "killed at a checkpoint (every 2 passages): {held}");
    assert_eq!(read_attr_str(&out, "", "status").unwrap(), "checkpoint");
    let status = Command::new(env!("CARGO_BIN_EXE_corrugation")).arg("resume").arg(&out).output().unwrap();
    assert!(status.status.success(), "{}", String::from_utf8_lossy(&status.stderr));
    assert_same(&reference, &out);
}

#[cfg(unix)]
#[test]
fn a_terminated_run_says_which_checkpoint_it_keeps() {
    // SIGTERM once a checkpoint is on disk: exit 143 (128 + 15), the file a
    // checkpoint, and the last line names its passage and `corrugation resume`.
    let dir = tempfile::tempdir().unwrap();
    let set = ["growth.passes=40", "growth.checkpoint_every=2", "growth.store_every=4"];
    let out = dir.path().join("terminated.h5");
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_corrugation"));
    cmd.arg("run").arg("configs/growth_fastsim.toml").arg("-o").arg(&out);
    for s in overrides(&set) {
        cmd.arg("--set").arg(s);
    }
    let child = cmd.stderr(std::process::Stdio::piped()).spawn().unwrap();
    let clock = Instant::now();
    while !(out.exists() && read_f64(&out, "passes", "traffic").is_ok_and(|t| t.len() >= 2)) {
        assert!(clock.elapsed() < Duration::from_secs(120), "no checkpoint appeared");
        std::thread::sleep(Duration::from_millis(5));
    }
    // SAFETY: kill(2) on our own child's pid.
    unsafe { libc::kill(child.id() as i32, libc::SIGTERM) };
    let o = child.wait_with_output().unwrap();
    assert_eq!(o.status.code(), Some(143));
    let err = String::from_utf8_lossy(&o.stderr);
    let last = err.lines().last().unwrap_or("");
    let held = read_f64(&out, "passes", "traffic").unwrap().len();
    assert_eq!(read_attr_str(&out, "", "status").unwrap(), "checkpoint");
    let said: usize = last
        .split("checkpoint after passage ")
        .nth(1)
        .and_then(|t| t.split(':').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no checkpoint named: {last}"));
    assert!(said >= 2 && said <= held && said.is_multiple_of(2), "said {said}, file holds {held}");
    assert!(last.starts_with("stopped by SIGTERM") && last.contains("corrugation resume"), "{last}");
}

#[test]
fn resume_refuses_what_it_cannot_continue() {
    let dir = tempfile::tempdir().unwrap();
    let part = run(dir.path(), "part.h5", &["growth.passes=2", "growth.contact_history=[]"]);
    let resume_cli = |args: &[&str]| {
        let o = Command::new(env!("CARGO_BIN_EXE_corrugation")).arg("resume").args(args).output().unwrap();
        (o.status.code(), String::from_utf8_lossy(&o.stderr).to_string())
    };
    let before = std::fs::read(&part).unwrap();
    let (code, err) = resume_cli(&[part.to_str().unwrap(), "--passes", "0"]);
    assert_eq!(code, Some(2));
    assert!(err.contains("--passes") && err.contains("0"), "{err}");
    assert_eq!(std::fs::read(&part).unwrap(), before, "file untouched");
    // A complete study: nothing to do, said so, the file left as it is.
    let (code, err) = resume_cli(&[part.to_str().unwrap()]);
    assert_eq!(code, Some(0), "{err}");
    assert!(err.contains("complete study (2 passages): nothing to do"), "{err}");
    assert_eq!(std::fs::read(&part).unwrap(), before, "complete file untouched");
    // -o naming the same file by another path is the same in-place resume.
    let same = dir.path().join(".").join("part.h5");
    let (code, err) = resume_cli(&[part.to_str().unwrap(), "-o", same.to_str().unwrap()]);
    assert_eq!(code, Some(0), "{err}");
    assert!(err.contains("nothing to do"), "{err}");
    // -o another file writes the complete study there.
    let copy = dir.path().join("copy.h5");
    let (code, err) = resume_cli(&[part.to_str().unwrap(), "-o", copy.to_str().unwrap()]);
    assert_eq!(code, Some(0), "{err}");
    assert_eq!(read_f64(&copy, "passes", "traffic").unwrap().len(), 2);
    let corrupt = dir.path().join("corrupt.h5");
    std::fs::write(&corrupt, b"not an HDF5 file").unwrap();
    let (code, err) = resume_cli(&[corrupt.to_str().unwrap()]);
    assert_eq!(code, Some(2));
    assert!(err.contains("cannot resume from") && err.contains("corrupt.h5"), "{err}");
    let missing = dir.path().join("missing.h5");
    let (code, err) = resume_cli(&[missing.to_str().unwrap()]);
    assert_eq!(code, Some(2));
    assert!(err.contains("cannot resume from") && err.contains("missing.h5"), "{err}");
    let single = dir.path().join("single.h5");
    let r = load_str(include_str!("../configs/paper_steady.toml"), "steady", &[]).unwrap();
    run_scene(&r, &single, &mut |_| {}).unwrap();
    let (code, err) = resume_cli(&[single.to_str().unwrap()]);
    assert_eq!(code, Some(2));
    assert!(err.contains("single-passage run, not a growth study"), "{err}");
}

#[test]
fn a_study_that_stops_at_saturation_resumes_to_the_same_stop() {
    // growth.stop = "saturation" with a rate no corrugation of this study
    // reaches: it stops after the first full window (11 passages) of the 20
    // planned, complete, with its reason; a run resumed from passage 6 stops
    // at the same passage, bit for bit.
    let dir = tempfile::tempdir().unwrap();
    let set =
        ["growth.stop=saturation", "growth.saturation_rate=100", "growth.adaptive=false", "growth.contact_history=[]"];
    let full = run(dir.path(), "sfull.h5", &[&set[..], &["growth.passes=20"]].concat());
    assert_eq!(read_f64(&full, "passes", "traffic").unwrap().len(), 11);
    assert_eq!(read_attr_str(&full, "", "status").unwrap(), "complete");
    assert!(read_attr_str(&full, "", "stop_reason").unwrap().starts_with("saturation: the rms grew by"));
    let part = run(dir.path(), "spart.h5", &[&set[..], &["growth.passes=6"]].concat());
    assert_eq!(read_attr_str(&part, "", "stop_reason").unwrap(), "");
    let s = resume(&part, Some(14), None, &mut |_| {}).unwrap();
    assert_eq!((s.passes, s.computed), (11, 5));
    assert!(s.stop_reason.is_some());
    assert_same(&full, &part);
    // Resuming a stopped study computes nothing more.
    let s = resume(&full, Some(5), Some(&dir.path().join("again.h5")), &mut |_| {}).unwrap();
    assert_eq!((s.passes, s.computed), (11, 0));
}

#[test]
fn a_study_that_stops_at_saturation_ends_at_full_sliding() {
    // A 100 um corrugation takes N below F_x / mu in the first passage:
    // an error without growth.stop, the end of a complete study with it.
    // (The Hertz chain: the linear contact's patch would leave the rail
    // grid first at this amplitude, far beyond its range.)
    let dir = tempfile::tempdir().unwrap();
    let big = [
        "roughness.kind=harmonics",
        "roughness.harmonics=[{amplitude = 1e-4, wavelength = 0.03}]",
        "contact.normal=hertz",
    ];
    let r = load_str(GROWTH, "growth", &overrides(&big)).unwrap();
    assert!(run_scene(&r, &dir.path().join("x.h5"), &mut |_| {}).is_err());
    let out = run(dir.path(), "slide.h5", &[&big[..], &["growth.stop=saturation"]].concat());
    assert_eq!(read_attr_str(&out, "", "status").unwrap(), "complete");
    let reason = read_attr_str(&out, "", "stop_reason").unwrap();
    assert!(reason.starts_with("full sliding in passage 1: ") && reason.contains("friction limit"), "{reason}");
}

#[test]
fn a_file_written_before_the_levels_resumes_with_levels_from_its_spectra() {
    // A run file of a version without the band levels (they are removed
    // here): the resumed run derives the stored passages' levels from their
    // centre-line spectra and goes on; the new passage's rate follows them.
    let dir = tempfile::tempdir().unwrap();
    let part = run(dir.path(), "old.h5", &["growth.passes=2", "growth.adaptive=false", "growth.contact_history=[]"]);
    {
        let file = hdf5::File::open_rw(&part).unwrap();
        let passes = file.group("passes").unwrap();
        for v in ["roughness_level", "level_rate", "initial_level", "passages_to_limit"] {
            passes.unlink(v).unwrap();
        }
    }
    let s = resume(&part, Some(1), None, &mut |_| {}).unwrap();
    assert_eq!((s.passes, s.computed), (3, 1));
    let level = read_f64(&part, "passes", "roughness_level").unwrap().into_dimensionality::<ndarray::Ix2>().unwrap();
    let rate = read_f64(&part, "passes", "level_rate").unwrap().into_dimensionality::<ndarray::Ix2>().unwrap();
    let m = read_f64(&part, "passes", "traffic_scale").unwrap();
    assert_eq!(level.dim().0, 3);
    for k in 0..level.dim().1 {
        assert!(level.column(k).iter().all(|l| l.is_finite()));
        if level[[1, k]] > -120.0 && level[[2, k]] > -120.0 {
            assert!((rate[[2, k]] - (level[[2, k]] - level[[1, k]]) * 1e5 / m[2]).abs() < 1e-9);
        }
    }
}
