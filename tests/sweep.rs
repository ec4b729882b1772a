//! Parameter sweeps through the binary: bad specs refused before anything
//! runs (one clear error each, all members' at once), a local run, status,
//! collect (dimensions named after the keys, refusing unfinished members
//! unless told), a member resumed from its checkpoint bit for bit, and
//! outputs that cannot be written refused before computing (exit 2).
//! The real-Slurm test is scripts/slurm_test.sh.
use corrugation::output::netcdf::{read_attr_str, read_f64, read_i8, read_i64};
use corrugation::run::{Event, run_scene};
use corrugation::sweep::spec::SweepSpec;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_corrugation");

fn corrugation(args: &[&str]) -> Output {
    Command::new(BIN).args(args).output().expect("binary runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A coarse growth study: 2 speeds x 2 pad stiffnesses, `passes` passages.
fn write_spec(dir: &Path, name: &str, passes: usize, extra: &str) -> PathBuf {
    let base = format!("{}/configs/growth_fastsim.toml", env!("CARGO_MANIFEST_DIR"));
    let text = format!(
        r#"base = "{base}"
output = "{name}"
set = ["contact.elements_x=6", "contact.elements_y=6", "rail.dx=5e-4", "rail.dy=1e-3", "passage.step_length=5e-4",
       "growth.passes={passes}", "growth.checkpoint_every=2", "growth.contact_history=[]"]

[[axis]]
key = "rolling.speed"
values = [22.22, 27.78]

[[axis]]
key = "track.pad_stiffness"
values = [100e6, 500e6]
{extra}"#
    );
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn bad_specs_get_one_clear_error_each_before_anything_runs() {
    let dir = tempfile::tempdir().unwrap();
    let check = |name: &str, extra: &str, expected: &[&str]| {
        let spec = write_spec(dir.path(), name, 2, extra);
        for cmd in ["plan", "run", "status"] {
            let o = corrugation(&["sweep", cmd, spec.to_str().unwrap()]);
            assert_eq!(o.status.code(), Some(2), "{name} {cmd}: {}", stderr(&o));
            for e in expected {
                assert!(stderr(&o).contains(e), "{name} {cmd}: expected {e:?} in:\n{}", stderr(&o));
            }
        }
        assert!(!dir.path().join(name).exists(), "{name}: nothing may be written");
    };
    check(
        "unknown_key",
        "[[axis]]\nkey = \"rolling.sped\"\nvalues = [1.0]\n",
        &["all 4 members: rolling.sped: unknown key"],
    );
    check(
        "empty_axis",
        "[[axis]]\nkey = \"material.friction_coefficient\"\nvalues = []\n",
        &["axis[2].values: is empty; an axis needs at least one value"],
    );
    check(
        "zip",
        "[[axis]]\nkey = \"rolling.creepage_y\"\nvalues = [0.0, 0.001, 0.002]\nzip = true\n\n[[axis]]\nkey = \
         \"rolling.spin\"\nvalues = [0.0]\nzip = true\n",
        &["axis[3].values: has 1 values, but the zipped axis \"rolling.creepage_y\" has 3"],
    );
    // One member out of range: named with its overrides, the others fine.
    check(
        "range",
        "[[axis]]\nkey = \"material.friction_coefficient\"\nvalues = [0.4, 1.5]\n",
        &["member 1 (rolling.speed=22.22, track.pad_stiffness=100000000.0, material.friction_coefficient=1.5) and 3 \
         more members: material.friction_coefficient: = 1.5 is out of range"],
    );
    // Members on different stretches cannot share a wavelength dimension.
    check(
        "stretch",
        "[[axis]]\nkey = \"rail.x_max\"\nvalues = [0.12, 0.24]\nzip = true\n\n[[axis]]\nkey = \"passage.end\"\n\
         values = [0.12, 0.24]\nzip = true\n",
        &["a sweep's members must share the stretch and rail grid"],
    );
    // An unknown key of the spec itself.
    let top = dir.path().join("top.toml");
    let text = std::fs::read_to_string(write_spec(dir.path(), "top", 2, "")).unwrap();
    std::fs::write(&top, format!("colour = 1\n{text}")).unwrap();
    let o = corrugation(&["sweep", "plan", top.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("colour: unknown key; allowed: base, output, set, axis"), "{}", stderr(&o));
    // Two problems at once, both reported.
    check(
        "two",
        "colour = 1\n[[axis]]\nkey = \"rolling.speed\"\nvalues = [1.0]\n",
        &[
            "axis[1].colour: unknown key; allowed: key, values, zip",
            "axis[2].key: = \"rolling.speed\" is already axis[0]'s key",
        ],
    );
}

#[test]
fn local_sweep_status_collect_and_resume() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "s", 4, "");
    let s = spec.to_str().unwrap();
    let out = dir.path().join("s.h5");
    let o = corrugation(&["sweep", "plan", s]);
    assert!(o.status.success(), "{}", stderr(&o));
    let plan = String::from_utf8_lossy(&o.stdout);
    assert!(plan.contains("member_0003  rolling.speed=27.78, track.pad_stiffness=500000000.0"), "{plan}");
    // Before running: every member missing, collect refuses.
    let o = corrugation(&["sweep", "status", s]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("4 members: 4 missing"));
    let o = corrugation(&["sweep", "collect", s, "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("4 of 4 members are not complete"), "{}", stderr(&o));
    // One member alone (as a scheduler would run it), then the rest here.
    let o = corrugation(&["sweep", "member", s, "--index", "2"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = corrugation(&["sweep", "collect", s, "-o", out.to_str().unwrap(), "--allow-missing"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let rms = read_f64(&out, "", "final_rms").unwrap();
    assert_eq!(rms.shape(), &[2, 2]);
    assert!(rms[[1, 0]] > 0.0 && rms[[0, 0]].is_nan() && rms[[1, 1]].is_nan());
    assert_eq!(read_i8(&out, "", "status").unwrap().iter().copied().collect::<Vec<_>>(), vec![1, 1, 0, 1]);
    assert_eq!(read_attr_str(&out, "", "missing_members").unwrap(), "0 1 3");
    let o = corrugation(&["sweep", "run", s, "-j", "2"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("1 of 4 members are complete already"), "{}", stderr(&o));
    let o = corrugation(&["sweep", "status", s]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("4 members: 4 complete"));
    let o = corrugation(&["sweep", "collect", s, "-o", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    // Dimensions named after the keys, with the keys' units.
    let speed = read_f64(&out, "", "rolling_speed").unwrap();
    assert_eq!(speed.as_slice().unwrap(), &[22.22, 27.78]);
    let rate = read_f64(&out, "", "growth_rate").unwrap();
    let waves = read_f64(&out, "", "wavelength").unwrap();
    assert_eq!(rate.shape(), &[2, 2, waves.len()]);
    assert_eq!(read_i64(&out, "", "member").unwrap().iter().copied().collect::<Vec<_>>(), vec![0, 1, 2, 3]);
    // The collected growth rate is the member's mean rate: its passages'
    // rates weighted by their traffic.
    let member = dir.path().join("s/member_0003.h5");
    let m = read_f64(&member, "passes", "traffic_scale").unwrap();
    let r = read_f64(&member, "passes", "growth_rate").unwrap();
    let k = 7;
    let mean = (0..m.len()).map(|p| r[[p, k]] * m[p]).sum::<f64>() / m.iter().sum::<f64>();
    assert!((rate[[1, 1, k]] - mean).abs() <= 1e-12 * mean.abs().max(1e-300));

    // A member file of another config (here the 2-passage study's) is
    // stale: reported, never resumed or overwritten.
    let complete = dir.path().join("complete.h5");
    std::fs::copy(&member, &complete).unwrap();
    let short = dir.path().join("short.toml");
    std::fs::write(
        &short,
        std::fs::read_to_string(&spec)
            .unwrap()
            .replace("growth.passes=4", "growth.passes=2")
            .replace("output = \"s\"", "output = \"short\""),
    )
    .unwrap();
    let o = corrugation(&["sweep", "member", short.to_str().unwrap(), "--index", "3"]);
    assert!(o.status.success(), "{}", stderr(&o));
    std::fs::copy(dir.path().join("short/member_0003.h5"), &member).unwrap();
    let o = corrugation(&["sweep", "status", s]);
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(text.contains("stale (its file holds another config"), "{text}");
    let o = corrugation(&["sweep", "member", s, "--index", "3"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("holds a run of another config than member 3's"), "{}", stderr(&o));

    // A member killed after its checkpoint of 2 of its 4 passages (the
    // run stopped by a panic right after writing it): reported so, and
    // `sweep member` resumes it, bit for bit the uninterrupted member.
    std::fs::remove_file(&member).unwrap();
    let sweep = SweepSpec::load(&spec).unwrap();
    let resolved = sweep.resolve(3).unwrap();
    let killed = std::panic::catch_unwind(|| {
        run_scene(&resolved, &member, &mut |e| {
            if let Event::Checkpoint { done: 2 } = e {
                panic!("killed after the checkpoint");
            }
        })
    });
    assert!(killed.is_err());
    let o = corrugation(&["sweep", "status", s]);
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(text.contains("checkpoint (2 of 4 passages)"), "{text}");
    let o = corrugation(&["sweep", "member", s, "--index", "3"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("resumed from its checkpoint"), "{}", stderr(&o));
    for (g, v) in [("rail", "state"), ("passes", "spectrum"), ("passes", "traffic"), ("passes", "growth_rate")] {
        let (a, b) = (read_f64(&complete, g, v).unwrap(), read_f64(&member, g, v).unwrap());
        assert!(a.iter().zip(b.iter()).all(|(x, y)| x.to_bits() == y.to_bits()), "{g}/{v}");
    }
}

#[test]
fn outputs_that_cannot_be_written_are_refused_before_computing() {
    let dir = tempfile::tempdir().unwrap();
    let config = format!("{}/configs/paper_normal_30mm.toml", env!("CARGO_MANIFEST_DIR"));
    let o = corrugation(&["run", &config, "-o", "/no/such/dir/x.h5"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("cannot write /no/such/dir/x.h5: the folder /no/such/dir does not exist"),
        "{}",
        stderr(&o)
    );
    // Refused before the passage: no step was computed (the run logs its
    // steps as it goes).
    assert!(!stderr(&o).contains("steps"), "{}", stderr(&o));
    let o = corrugation(&["resume", "/no/such/run.h5", "-o", "/no/such/dir/y.h5"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("cannot write /no/such/dir/y.h5"), "{}", stderr(&o));
    let spec = write_spec(dir.path(), "s", 2, "");
    let o = corrugation(&["sweep", "collect", spec.to_str().unwrap(), "-o", "/no/such/dir/c.h5"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("cannot write /no/such/dir/c.h5"), "{}", stderr(&o));
    // A sweep whose directory cannot be made (a file is in the way).
    let blocked = dir.path().join("blocked.toml");
    std::fs::write(dir.path().join("file"), "").unwrap();
    std::fs::write(&blocked, std::fs::read_to_string(&spec).unwrap().replace("output = \"s\"", "output = \"file/x\""))
        .unwrap();
    for args in [vec!["run"], vec!["slurm", "--no-submit"]] {
        let mut a = vec!["sweep"];
        a.extend(&args);
        a.push(blocked.to_str().unwrap());
        let o = corrugation(&a);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains("cannot write the sweep's directory"), "{}", stderr(&o));
    }
}

#[test]
fn slurm_script_runs_each_member_as_an_array_task() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "s", 2, "");
    let o = corrugation(&["sweep", "slurm", spec.to_str().unwrap(), "--no-submit", "--max-concurrent", "3"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let script = std::fs::read_to_string(dir.path().join("s/sweep.sbatch")).unwrap();
    assert!(script.contains("#SBATCH --array=0-3%3"), "{script}");
    assert!(script.contains("#SBATCH --cpus-per-task=2"), "{script}");
    assert!(script.contains("index=$((SLURM_ARRAY_TASK_ID + 0))"), "{script}");
    assert!(script.contains("sweep member") && script.contains("--index \"$index\" >>\"$log\" 2>&1"), "{script}");
    assert!(script.contains("#SBATCH --open-mode=append"), "{script}");
    assert!(script.contains("#SBATCH --mem=256M"), "at least 256 MB: {script}");
    // Beyond the cluster's MaxArraySize: several arrays with offsets.
    let o = corrugation(&["sweep", "slurm", spec.to_str().unwrap(), "--no-submit", "--max-array-size", "3"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let second = std::fs::read_to_string(dir.path().join("s/sweep_1.sbatch")).unwrap();
    assert!(
        second.contains("#SBATCH --array=0%8") && second.contains("index=$((SLURM_ARRAY_TASK_ID + 3))"),
        "{second}"
    );
    let first = std::fs::read_to_string(dir.path().join("s/sweep_0.sbatch")).unwrap();
    assert!(first.contains("#SBATCH --array=0-2%8"), "{first}");
    assert!(script.contains("export RAYON_NUM_THREADS=\"${SLURM_CPUS_PER_TASK:-1}\""), "{script}");
    assert!(script.lines().any(|l| l.starts_with("#SBATCH --time=0-00:")), "{script}");
    assert!(dir.path().join("s/logs").is_dir(), "Slurm does not create the log folder");
}
