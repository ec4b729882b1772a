//! End to end through the binary: check, run, the run file's contents against
//! the physics invariants, determinism, and bad input leaving files intact.
use corrugation::output::netcdf::{read_attr_str, read_f64, read_i8};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_corrugation");
/// A cheap version of a paper scene for the tests.
const FAST: [&str; 6] = ["--set", "contact.elements_x=10", "--set", "contact.elements_y=10", "--set", "rail.dx=2e-4"];

fn corrugation(args: &[&str]) -> Output {
    Command::new(BIN).args(args).output().expect("binary runs")
}

fn config(name: &str) -> String {
    format!("{}/configs/{name}.toml", env!("CARGO_MANIFEST_DIR"))
}

fn run_to(dir: &Path, name: &str, scene: &str) -> PathBuf {
    let out = dir.join(name);
    let c = config(scene);
    let mut args = vec!["run", c.as_str(), "-o", out.to_str().unwrap()];
    args.extend(FAST);
    let o = corrugation(&args);
    assert!(o.status.success(), "run failed: {}", String::from_utf8_lossy(&o.stderr));
    out
}

#[test]
fn check_prints_derived_quantities() {
    let o = corrugation(&["check", &config("paper_normal_30mm")]);
    assert!(o.status.success());
    let text = String::from_utf8_lossy(&o.stdout);
    // Concave reading at 100 kN: a = 5.96 mm, b = 10.22 mm, p0 = 785 MPa.
    assert!(text.contains("a = 5.9566 mm"), "{text}");
    assert!(text.contains("b = 10.2157 mm"), "{text}");
    assert!(text.contains("p0 = 784.6 MPa"), "{text}");
    assert!(text.contains("491 steps"), "{text}");
    // Every line in the project's words, no Rust debug text.
    let o = corrugation(&["check", &config("growth_discrete")]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("dynamics discrete (Timoshenko rail on discrete supports), unsprung mass 600 kg"), "{text}");
    assert!(!text.contains(" { "), "{text}");
}

#[test]
fn run_file_satisfies_invariants() {
    let dir = tempfile::tempdir().unwrap();
    let f = run_to(dir.path(), "n15.h5", "paper_normal_15mm");
    let g = "contact/pass_00000";
    let x_c = read_f64(&f, g, "x_c").unwrap();
    let n = read_f64(&f, g, "normal_force").unwrap();
    let fx = read_f64(&f, g, "longitudinal_force").unwrap();
    let a = read_f64(&f, g, "semi_axis_a").unwrap();
    let b = read_f64(&f, g, "semi_axis_b").unwrap();
    let p = read_f64(&f, g, "pressure").unwrap();
    let tx = read_f64(&f, g, "traction_x").unwrap();
    let ty = read_f64(&f, g, "traction_y").unwrap();
    let w = read_f64(&f, g, "wear_rate").unwrap();
    let stick = read_i8(&f, g, "stick").unwrap();
    let sx = read_f64(&f, g, "slip_x").unwrap();
    let sy = read_f64(&f, g, "slip_y").unwrap();
    let d_xi = read_f64(&f, g, "d_xi").unwrap();
    let d_eta = read_f64(&f, g, "d_eta").unwrap();
    assert_eq!(p.shape()[1], 100);
    for s in 0..x_c.len() {
        // Imposed loads: N = 100 kN + 45 kN sin(2 pi X / 15 mm), F_x = 20 kN.
        let expected_n = 1e5 + 4.5e4 * (2.0 * std::f64::consts::PI * x_c[s] / 0.015).sin();
        assert!((n[s] - expected_n).abs() < 1e-6, "N at step {s}");
        assert!((fx[s] - 2e4).abs() < 1e-6 * 2e4, "force balance F_x at step {s}: {}", fx[s]);
        let mut force_n = 0.0;
        let mut force_x = 0.0;
        for k in 0..100 {
            let area = d_xi[k] * d_eta[k] * a[s] * b[s];
            force_n += p[[s, k]] * area;
            force_x += tx[[s, k]] * area;
            let t = tx[[s, k]].hypot(ty[[s, k]]);
            assert!(t <= 0.4 * p[[s, k]] * (1.0 + 1e-12), "|p| <= mu p3 at step {s} element {k}");
            // Archard: w = (k/H) p3 |s|, k/H = 3.4e-14 m^2/N in the config.
            let archard = 3.4e-14 * p[[s, k]] * sx[[s, k]].hypot(sy[[s, k]]);
            assert!((w[[s, k]] - archard).abs() <= 1e-12 * archard, "Archard at step {s} element {k}");
            assert!(stick[[s, k]] == 0 || stick[[s, k]] == 1);
            if stick[[s, k]] == 1 {
                assert_eq!(sx[[s, k]], 0.0);
            }
        }
        assert!((force_n - n[s]).abs() < 1e-9 * n[s], "normal force balance at step {s}");
        assert!((force_x - fx[s]).abs() < 1e-9 * 2e4, "tangential force balance at step {s}");
    }
    // Rail: wear positive, profile = -wear for one passage, rms recorded.
    let wear = read_f64(&f, "rail", "wear").unwrap();
    let profile = read_f64(&f, "rail", "profile").unwrap();
    assert!(wear.iter().all(|v| *v >= 0.0) && wear.iter().any(|v| *v > 0.0));
    assert!(wear.iter().zip(profile.iter()).all(|(w, p)| *p == -*w));
    let rms = read_f64(&f, "passes", "rms_corrugation").unwrap();
    assert!(rms[0] > 0.0);
    let cfg = read_attr_str(&f, "/", "config").unwrap();
    assert!(cfg.contains("elements_x = 10"), "resolved config with overrides stored");
}

#[test]
fn same_config_same_result_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let f1 = run_to(dir.path(), "a.h5", "paper_longitudinal_15mm");
    let f2 = run_to(dir.path(), "b.h5", "paper_longitudinal_15mm");
    for (g, v) in [
        ("rail", "wear"),
        ("contact/pass_00000", "creepage_x"),
        ("contact/pass_00000", "slip_x"),
        ("contact/pass_00000", "wear_rate"),
    ] {
        let (x, y) = (read_f64(&f1, g, v).unwrap(), read_f64(&f2, g, v).unwrap());
        assert!(x.iter().zip(y.iter()).all(|(a, b)| a.to_bits() == b.to_bits()), "{g}/{v} differs");
    }
}

#[test]
fn bad_config_exits_2_and_keeps_existing_output() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("keep.h5");
    std::fs::write(&out, b"previous results").unwrap();
    let c = config("paper_normal_30mm");
    let o = corrugation(&[
        "run",
        &c,
        "-o",
        out.to_str().unwrap(),
        "--set",
        "material.friction_coefficient=3",
        "--set",
        "contact.elements_x=1",
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("material.friction_coefficient: = 3 is out of range; expected a number in (0, 1]"), "{err}");
    assert!(err.contains("contact.elements_x: = 1 is out of range"), "{err}");
    assert_eq!(std::fs::read(&out).unwrap(), b"previous results");
    let o = corrugation(&["check", "/nonexistent/scene.toml"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("/nonexistent/scene.toml"));
    // A missing run file to resume: the file system's words, not HDF5's.
    let missing = Path::new(env!("CARGO_TARGET_TMPDIR")).join("no_such_run.h5");
    let o = corrugation(&["resume", missing.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains(&format!("cannot resume from {}: No such file or directory", missing.display())), "{err}");
    assert!(!err.contains("H5F"), "{err}");
}

#[test]
fn check_and_run_with_the_transient_models() {
    let c = config("paper_normal_15mm");
    let o = corrugation(&["check", &c, "--set", "contact.model=exact-transient"]);
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stdout).contains("contact model      exact-transient"));
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("t.h5");
    let o = corrugation(&[
        "run",
        &c,
        "-o",
        out.to_str().unwrap(),
        "--set",
        "contact.model=simplified-transient",
        "--set",
        "contact.elements_x=8",
        "--set",
        "contact.elements_y=8",
        "--set",
        "rail.dx=5e-4",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(read_attr_str(&out, "/", "contact_model").unwrap(), "simplified-transient");
    let it = read_f64(&out, "contact/pass_00000", "newton_iterations").unwrap();
    assert!(it.iter().all(|v| *v >= 0.0) && it.iter().any(|v| *v > 0.0));
    let in_contact = read_f64(&out, "contact/pass_00000", "in_contact").unwrap();
    assert!(in_contact.iter().all(|v| *v == 1.0));
}

#[cfg(unix)]
#[test]
fn a_closed_pipe_ends_check_quietly_and_does_not_stop_a_run() {
    use std::os::unix::process::ExitStatusExt;
    use std::process::Stdio;
    // `corrugation check f | head -0`: the reader is gone before the first
    // line. check ends without a panic message (by SIGPIPE, as Unix tools do).
    let c = config("paper_normal_30mm");
    let mut child = Command::new(BIN)
        .args(["check", c.as_str()])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("binary runs");
    drop(child.stdout.take());
    let o = child.wait_with_output().expect("check ends");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!err.contains("panicked"), "check panicked on a closed pipe: {err}");
    // Ended by SIGPIPE, as Unix tools are; or, should the whole report have
    // fitted in the pipe before the reader went, successfully.
    let by_sigpipe = o.status.signal() == Some(libc::SIGPIPE);
    assert!(by_sigpipe || o.status.success(), "check on a closed pipe: {:?}", o.status);
    // A run whose stderr reader is gone still completes and writes its file.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run.h5");
    let mut args = vec!["run", c.as_str(), "-o", out.to_str().unwrap()];
    args.extend(FAST);
    let mut child = Command::new(BIN).args(&args).stderr(Stdio::piped()).stdout(Stdio::null()).spawn().unwrap();
    drop(child.stderr.take());
    assert!(child.wait().unwrap().success(), "run with a closed stderr");
    assert!(read_f64(&out, "rail", "wear").is_ok(), "the run file was written");
}

#[test]
fn an_existing_output_is_replaced_only_with_overwrite() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("keep.h5");
    std::fs::write(&out, b"a checkpoint").unwrap();
    let c = config("paper_normal_30mm");
    let o_path = out.to_str().unwrap();
    // run, track and resume -o each refuse to replace it, naming the file
    // and the way to replace it; the file is untouched.
    let mut run_args = vec!["run", c.as_str(), "-o", o_path];
    run_args.extend(FAST);
    for args in [run_args.clone(), vec!["track", c.as_str(), "-o", o_path], vec!["resume", "other.h5", "-o", o_path]] {
        let o = corrugation(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(o_path) && err.contains("--overwrite"), "{args:?}: {err}");
        assert_eq!(std::fs::read(&out).unwrap(), b"a checkpoint", "{args:?}");
    }
    let o = corrugation(&run_args);
    assert!(String::from_utf8_lossy(&o.stderr).contains("corrugation resume"), "run names resume");
    // With --overwrite the run replaces it.
    run_args.push("--overwrite");
    let o = corrugation(&run_args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(read_f64(&out, "rail", "wear").is_ok(), "the run file replaced it");
}

#[test]
fn auto_takes_the_cheaper_fixed_grid_solver() {
    // The cost model: CG on the 0.4 mm grid a growth study enlarges for
    // the profile contact (measured 0.97 against 1.21 s per passage of
    // growth_exact.toml with the nonlinear contact, 0.48 against 0.92 with
    // auto's linear one), on the paper's default 0.2 mm grid and on a 0.2
    // mm growth grid, and for exact Coulomb friction (its regularised
    // limit). `check` prints the choice (one call: each computes the
    // creep forces' response); the others from the resolved config.
    let o = corrugation(&["check", config("growth_exact").as_str()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = String::from_utf8_lossy(&o.stdout).to_string();
    let printed = text.split("tangential solver ").nth(1).unwrap_or("").split_whitespace().next().unwrap_or("");
    assert_eq!(printed, "cg");
    let solver_of = |scene: &str, set: &[&str]| {
        let text = std::fs::read_to_string(config(scene)).unwrap();
        let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
        let r = corrugation::config::load_str(&text, scene, &set).unwrap();
        r.scene.contact.model.fixed_grid().expect("a fixed grid").solver.resolve().name().to_string()
    };
    let fixed = ["contact.model=exact-transient", "contact.grid=fixed"];
    let fine = ["contact.dx=2e-4", "contact.dy=5e-4", "passage.step_length=2e-4"];
    assert_eq!(solver_of("growth_exact", &fine), "cg");
    assert_eq!(solver_of("paper_normal_30mm", &fixed), "cg");
    assert_eq!(solver_of("paper_normal_30mm", &[&fixed[..], &["contact.friction_law=coulomb"]].concat()), "cg");
    assert_eq!(solver_of("growth_exact", &["contact.solver=gauss-seidel"]), "gauss-seidel");
}

#[test]
fn without_an_output_a_run_writes_under_out() {
    // `run` without `-o` writes out/<config name>.h5 in the folder it was
    // started in (out/ made), nothing beside it.
    let dir = tempfile::tempdir().unwrap();
    let c = config("paper_normal_15mm");
    let mut args = vec!["run", c.as_str()];
    args.extend(FAST);
    let o = Command::new(BIN).args(&args).current_dir(dir.path()).output().expect("binary runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(dir.path().join("out/paper_normal_15mm.h5").is_file());
    let names: Vec<String> =
        std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    assert_eq!(names, vec!["out".to_string()], "only out/ in the start folder");
}
