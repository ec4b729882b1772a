//! Command line of `corrugation` (book: docs/src/reference/cli.md).
//!
//! Exit codes: 0 success, 1 the run failed (solver or output), 2 bad input
//! (command line or config).

/// A line on stderr. A closed stderr (`... 2>&1 | head`) must not stop a
/// run: write errors are ignored. Defined before the modules that use it.
macro_rules! say {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr(), $($arg)*);
    }};
}

/// [`say!`] without the newline.
macro_rules! say_raw {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = write!(std::io::stderr(), $($arg)*);
    }};
}

mod check;
mod forecast_cli;
mod interrupt;
mod progress;
mod spectrum_cli;
mod sweep_cli;

use clap::{Parser, Subcommand};
use corrugation::config::{self, Resolved};
use corrugation::run::{ResumeError, RunSummary, run_scene};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Rail corrugation: transient wheel-rail contact, Archard wear, growth.
#[derive(Parser)]
#[command(name = "corrugation", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run a scene and write one HDF5 run file.
    Run {
        /// Scene config (TOML).
        config: PathBuf,
        /// Output file (default: out/ and the config's name with .h5).
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Override a config key, e.g. --set contact.elements_x=30 (repeatable).
        #[arg(long = "set", value_name = "SECTION.KEY=VALUE")]
        set: Vec<String>,
        /// Replace the output file if it exists (without it, an existing
        /// file is never replaced: it may hold a study's checkpoint).
        #[arg(long)]
        overwrite: bool,
    },
    /// Continue a growth study from its run file (a checkpoint or a finished
    /// run), bit for bit as if it had never stopped.
    Resume {
        /// Run file written by `corrugation run` (rewritten atomically).
        file: PathBuf,
        /// Run this many passages more than the file holds (default: up to
        /// the stored growth.passes); extends a finished study.
        #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
        passes: Option<u32>,
        /// Write the continued run here instead of rewriting FILE.
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Replace the -o file if it exists.
        #[arg(long)]
        overwrite: bool,
    },
    /// Write the receptances of the configured track and wheel (20-5000 Hz,
    /// positions across a sleeper bay) and their resonances.
    Track {
        /// Scene config (TOML) with a [track] section (or its defaults).
        config: PathBuf,
        /// Output file (default: out/ and the config's name with _track.h5).
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Override a config key (repeatable).
        #[arg(long = "set", value_name = "SECTION.KEY=VALUE")]
        set: Vec<String>,
        /// Replace the output file if it exists.
        #[arg(long)]
        overwrite: bool,
        /// Frequencies of the sweep, log-spaced over 20-5000 Hz.
        #[arg(long, default_value_t = corrugation::dynamics::track::response::SWEEP_POINTS as u64,
              value_parser = clap::value_parser!(u64).range(2..=100_000))]
        points: u64,
    },
    /// A curve's steady curving from its [curve] section: the contact
    /// geometry against the lateral shift (rolling-radius difference,
    /// contact angles, equivalent conicity) and every wheel's load,
    /// creepages, spin, contact and flange contact.
    Curve {
        /// Scene config (TOML) with a [curve] section.
        config: PathBuf,
        /// Output file (default: out/ and the config's name with _curve.h5).
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Override a config key (repeatable).
        #[arg(long = "set", value_name = "SECTION.KEY=VALUE")]
        set: Vec<String>,
        /// Replace the output file if it exists.
        #[arg(long)]
        overwrite: bool,
    },
    /// The linear growth spectrum of a growth study's passage: each Bloch
    /// class's modes (growth rate, wavelength, drift, pattern) and the
    /// smooth rail's forced pattern.
    Spectrum {
        /// Scene config (TOML) of a growth study ([spectrum] optional), or
        /// a growth study's run file: the spectrum about its stored rail.
        config: PathBuf,
        /// With a run file: about the rail stored after this passage (from
        /// 1; default: the last passage's).
        #[arg(long = "pass", value_parser = clap::value_parser!(u32).range(1..))]
        pass: Option<u32>,
        /// Measure part K of N only (K from 1): its rounds, written as a
        /// part file for `corrugation spectrum-merge` (a job array's task).
        #[arg(long, value_name = "K/N", value_parser = part_arg, conflicts_with = "slurm")]
        part: Option<(usize, usize)>,
        /// Spread the measurement over a Slurm job array of N parts and a
        /// merge job (writes OUT's folder OUT.parts/, submits, prints the
        /// merge job's id).
        #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1000))]
        slurm: Option<u32>,
        /// With --slurm: CPUs per array task.
        #[arg(long, default_value_t = 1, requires = "slurm")]
        cpus_per_task: usize,
        /// With --slurm: an argument for sbatch (repeatable), e.g.
        /// --sbatch-arg=--partition=long.
        #[arg(long = "sbatch-arg", allow_hyphen_values = true, requires = "slurm")]
        sbatch_arg: Vec<String>,
        /// With --slurm: write the scripts, do not submit them.
        #[arg(long, requires = "slurm")]
        no_submit: bool,
        /// Threads measuring the passages side by side, each with its own
        /// passage model (its memory once per thread); the result is the
        /// same whatever their number (default: the cores this process may
        /// use).
        #[arg(short = 'j', long = "jobs", value_parser = clap::value_parser!(u32).range(1..=256))]
        jobs: Option<u32>,
        /// Output file (default: out/ and the config's name with _spectrum.h5).
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Override a config key (repeatable), e.g. --set spectrum.classes=4.
        #[arg(long = "set", value_name = "SECTION.KEY=VALUE")]
        set: Vec<String>,
        /// Replace the output file if it exists.
        #[arg(long)]
        overwrite: bool,
    },
    /// Merge the parts of one spectrum's measurement (`spectrum --part
    /// K/N`, every K) into its spectrum file.
    SpectrumMerge {
        /// The part files.
        #[arg(required = true)]
        parts: Vec<PathBuf>,
        /// Output spectrum file.
        #[arg(short, long)]
        output: PathBuf,
        /// Replace the output file if it exists.
        #[arg(long)]
        overwrite: bool,
    },
    /// Parameter sweeps: plan, run here or on Slurm, status, collect.
    Sweep {
        #[command(subcommand)]
        command: sweep_cli::SweepCommand,
    },
    /// Validate a config and print derived quantities.
    Check {
        /// Scene config (TOML).
        config: PathBuf,
        /// Override a config key (repeatable).
        #[arg(long = "set", value_name = "SECTION.KEY=VALUE")]
        set: Vec<String>,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Check { config, set } => {
            // `check` only prints: end quietly, as other Unix tools do, when
            // the reader of stdout has gone (`corrugation check f | head`).
            reset_sigpipe();
            match load(&config, &set) {
                Ok(r) => {
                    check::print_check(&r);
                    ExitCode::SUCCESS
                }
                Err(code) => code,
            }
        }
        Command::Run { config, output, set, overwrite } => {
            let resolved = match load(&config, &set) {
                Ok(r) => r,
                Err(code) => return code,
            };
            let out = output.unwrap_or_else(|| default_output(&config, "run", ""));
            if let Err(code) = new_output(&out, overwrite, true).and_then(|_| writable(&out)) {
                return code;
            }
            if let Some(corrugation::params::Roughness::Measured(m)) =
                resolved.scene.growth.as_ref().map(|g| &g.roughness)
            {
                for line in check::record_lines(m) {
                    say!("record: {line}");
                }
            }
            run(&resolved, &out)
        }
        Command::Resume { file, passes, output, overwrite } => {
            // `-o` naming the input itself (by any path) is the in-place resume.
            let output = output.filter(|o| !same_file(o, &file));
            if let Some(o) = output.as_deref()
                && let Err(code) = new_output(o, overwrite, false)
            {
                return code;
            }
            if let Err(code) = writable(output.as_deref().unwrap_or(&file)) {
                return code;
            }
            resume(&file, passes.map(|n| n as usize), output.as_deref())
        }
        Command::Sweep { command } => sweep_cli::main(command),
        Command::SpectrumMerge { parts, output, overwrite } => {
            if let Err(code) = new_output(&output, overwrite, false).and_then(|_| writable(&output)) {
                return code;
            }
            spectrum_cli::merge(&parts, &output)
        }
        Command::Spectrum {
            config,
            pass,
            part,
            slurm,
            cpus_per_task,
            sbatch_arg,
            no_submit,
            jobs,
            output,
            set,
            overwrite,
        } => {
            let run_file = corrugation::config::is_hdf5(&config);
            let resolved = if run_file {
                match corrugation::run::stored_config(&config, &set) {
                    Ok(r) => r,
                    Err(e) => {
                        say!("error: {e}");
                        return ExitCode::from(2);
                    }
                }
            } else {
                if pass.is_some() {
                    say!("error: --pass picks a stored passage of a run file; {} is a config", config.display());
                    return ExitCode::from(2);
                }
                match load(&config, &set) {
                    Ok(r) => r,
                    Err(code) => return code,
                }
            };
            let out = output.unwrap_or_else(|| default_output(&config, "run", "_spectrum"));
            if let Err(code) = new_output(&out, overwrite, false).and_then(|_| writable(&out)) {
                return code;
            }
            if let Some(n) = slurm {
                let job =
                    spectrum_cli::SlurmJob { parts: n as usize, cpus_per_task, sbatch_args: sbatch_arg, no_submit };
                let set = if pass.is_some() {
                    say!("error: --slurm measures about the config's rail; --pass picks a run file's");
                    return ExitCode::from(2);
                } else {
                    set
                };
                return spectrum_cli::slurm(&resolved, &config, &set, &out, &job);
            }
            let stored = match run_file.then(|| spectrum_cli::stored_rail(&config, &resolved, pass.map(|p| p as usize)))
            {
                Some(Ok(rails)) => Some(rails),
                Some(Err(e)) => {
                    say!("error: {e}");
                    return ExitCode::from(2);
                }
                None => None,
            };
            let jobs = jobs.map_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()), |j| j as usize);
            spectrum_cli::spectrum(&resolved, stored, part.map(|(k, n)| (k - 1, n)), jobs, &out)
        }
        Command::Curve { config, output, set, overwrite } => {
            let out = output.unwrap_or_else(|| default_output(&config, "curve", "_curve"));
            if let Err(code) = new_output(&out, overwrite, false) {
                return code;
            }
            let resolved = match load(&config, &set) {
                Ok(r) => r,
                Err(code) => return code,
            };
            curve(&resolved, &config, &out)
        }
        Command::Track { config, output, set, overwrite, points } => {
            let resolved = match load(&config, &set) {
                Ok(r) => r,
                Err(code) => return code,
            };
            let out = output.unwrap_or_else(|| default_output(&config, "track", "_track"));
            if let Err(code) = new_output(&out, overwrite, false) {
                return code;
            }
            track(&resolved, &out, points as usize)
        }
    }
}

/// `corrugation curve`: prints and writes the steady curving of the
/// config's `[curve]`.
fn curve(resolved: &Resolved, config: &Path, out: &Path) -> ExitCode {
    let Some(setup) = &resolved.curve else {
        say!(
            "error: {} has no [curve] section (radius, cant, the vehicle and profiles): nothing to curve",
            config.display()
        );
        return ExitCode::from(2);
    };
    if let Err(code) = writable(out) {
        return code;
    }
    let c = &setup.curve;
    say!(
        "curve R = {} m, cant {:.1} mm, {:.1} km/h: cant deficiency {:.1} mm; {} iterations",
        c.radius,
        c.cant * 1e3,
        c.speed * 3.6,
        c.cant_deficiency() * 1e3,
        setup.state.iterations
    );
    if let Some((y, yaw)) = setup.state.frame {
        say!("bogie frame: lateral shift {:+.2} mm (towards the high rail), yaw {:+.2} mrad", -y * 1e3, yaw * 1e3);
    }
    say!(
        "{:<14} {:>8} {:>10} {:>10} {:>8} {:>7} {:>8} {:>9} {:>6} {:>7}",
        "wheel",
        "N (kN)",
        "creep x",
        "creep y",
        "spin 1/m",
        "y (mm)",
        "AoA mrad",
        "angle deg",
        "flange",
        "2-point"
    );
    let followed = setup.patches().0;
    for (name, w, p) in setup.state.wheels() {
        let (creepage_y, spin, _) = p.study_axes(false);
        say!(
            "{:<14} {:>8.2} {:>10.3e} {:>10.3e} {:>8.3} {:>+7.2} {:>+8.2} {:>9.1} {:>6} {:>7}{}",
            name,
            p.normal_force * 1e-3,
            p.creepage.x,
            creepage_y,
            spin,
            -w.shift * 1e3,
            w.angle_of_attack() * 1e3,
            p.contact_angle().to_degrees(),
            if p.on_flange() { "yes" } else { "no" },
            if p.two_point() { "yes" } else { "no" },
            if std::ptr::eq(p, followed) { "  <- the study's rail" } else { "" }
        );
    }
    match corrugation::output::curve_file::write_curve_file(out, setup, &resolved.toml) {
        Ok(()) => {
            say!("wrote {}", out.display());
            ExitCode::SUCCESS
        }
        Err(e) => {
            say!("error: cannot write {}: {e}", out.display());
            ExitCode::from(1)
        }
    }
}

/// `corrugation track`: the receptances of the configured track and wheel.
fn track(resolved: &Resolved, out: &Path, points: usize) -> ExitCode {
    use corrugation::dynamics::receptance::{WheelParams, hertz_stiffness};
    // Before computing: the output can be written.
    if let Err(code) = writable(out) {
        return code;
    }
    let s = &resolved.scene;
    let d = corrugation::build::derive(s);
    let k_h = hertz_stiffness(d.patch_mean.normal_force, d.patch_mean.approach);
    let mass = match s.growth.as_ref().map(|g| g.dynamics) {
        Some(
            corrugation::params::DynamicsKind::Receptance { unsprung_mass }
            | corrugation::params::DynamicsKind::Discrete { unsprung_mass },
        ) => unsprung_mass,
        _ => corrugation::dynamics::receptance::FREIGHT_UNSPRUNG_MASS,
    };
    let distances = s.vehicle.distances();
    let r = corrugation::dynamics::track::response::track_response(
        &s.track,
        WheelParams { unsprung_mass: mass },
        k_h,
        &distances,
        points,
    );
    // The head in three directions where the growth loop uses it (the
    // default, and a config without a growth study).
    let offset = match s.growth.as_ref().map(|g| g.directions) {
        Some(corrugation::params::Directions::Vertical) => None,
        Some(corrugation::params::Directions::All { contact_offset, .. }) => Some(contact_offset),
        None => Some(0.0),
    };
    let head = match offset.map(|o| {
        corrugation::dynamics::track::head::head_response(&s.track, o, &r.frequency, &r.position, &r.source, &distances)
    }) {
        Some(Ok(h)) => Some(h),
        Some(Err(e)) => {
            say!("error: the rail head's receptances in three directions: {e}");
            return ExitCode::FAILURE;
        }
        None => None,
    };
    let layout = if s.layout.is_one_bay(&s.track) {
        None
    } else {
        match corrugation::dynamics::track::response::layout_response(&s.track, &s.layout, &r.frequency, offset) {
            Ok(l) => Some(l),
            Err(e) => {
                say!("error: the receptances on the track layout: {e}");
                return ExitCode::FAILURE;
            }
        }
    };
    let written = corrugation::output::track_file::write_track_file(
        out,
        &r,
        head.as_ref(),
        layout.as_ref(),
        s.track.rail_name,
        &resolved.toml,
    );
    match written {
        Ok(()) => {
            say!(
                "wrote {}: {} rail on {} m sleeper spacing; pinned-pinned {:.0} Hz (simply supported span {:.0} Hz), \
                 rail on pad {:.0} Hz, track on ballast {:.0} Hz; contact spring {:.3e} N/m, wheel {mass} kg{}{}",
                out.display(),
                s.track.rail_name,
                s.track.sleeper_spacing,
                r.pinned_pinned,
                r.span_frequency,
                r.rail_on_pad,
                r.track_on_ballast,
                k_h,
                if distances.is_empty() {
                    String::new()
                } else {
                    format!("; transfer receptances between the wheels at {distances:?} m")
                },
                if head.is_some() { "; the rail head in three directions" } else { "" }
            );
            if let Some(l) = &layout {
                let peaks: Vec<String> =
                    l.pinned_pinned.iter().map(|(_, f, a)| format!("{f:.0} Hz {a:.2e} m/N")).collect();
                say!(
                    "the layout: {} supports over {} m; each span's pinned-pinned peak at mid-span: {}",
                    l.layout.len(),
                    l.layout.period,
                    peaks.join(", ")
                );
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            say!("error: {e}");
            ExitCode::from(1)
        }
    }
}

/// `K/N` of `--part`: part K (from 1) of N.
fn part_arg(s: &str) -> Result<(usize, usize), String> {
    let bad = || format!("{s:?}: expected K/N with 1 <= K <= N, e.g. 2/8");
    let (k, n) = s.split_once('/').ok_or_else(bad)?;
    let (k, n): (usize, usize) = (k.trim().parse().map_err(|_| bad())?, n.trim().parse().map_err(|_| bad())?);
    if k == 0 || k > n { Err(bad()) } else { Ok((k, n)) }
}

/// Restores the default action of SIGPIPE (end the process), which Rust's
/// runtime sets to ignore, so that printing to a closed pipe ends `check`
/// instead of panicking.
fn reset_sigpipe() {
    #[cfg(unix)]
    // SAFETY: called before any other thread exists; SIG_DFL is a valid
    // disposition for SIGPIPE.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

fn load(path: &Path, set: &[String]) -> Result<Resolved, ExitCode> {
    let r = config::load_file(path, set).map_err(|e| {
        say_raw!("error: {e}");
        ExitCode::from(2)
    })?;
    for w in &r.warnings {
        say!("warning: {w}");
    }
    Ok(r)
}

/// Before computing anything: an existing `out` is replaced only with
/// `--overwrite` (exit 2 naming the file otherwise; it may hold a growth
/// study's checkpoint, which `resume` continues when `resumable`).
fn new_output(out: &Path, overwrite: bool, resumable: bool) -> Result<(), ExitCode> {
    if overwrite || !out.exists() {
        return Ok(());
    }
    let continue_hint = if resumable {
        format!("; if it holds a growth study, `corrugation resume {}` continues it", out.display())
    } else {
        String::new()
    };
    say!(
        "error: {} exists and is not replaced unasked: pass --overwrite to replace it, or -o another file{continue_hint}",
        out.display()
    );
    Err(ExitCode::from(2))
}

/// Runs `work` (a run or a resume writing `out`) with its events shown on
/// `bar` and a watch for SIGINT / SIGTERM that says which checkpoint `out`
/// keeps: `kept` passages at the start, `target` the passages a `resume
/// --passes` is to reach ([`interrupt::watch`]).
fn watched<T, E>(
    out: &Path,
    kept: usize,
    target: Option<usize>,
    bar: &mut progress::Progress,
    work: impl FnOnce(&mut dyn FnMut(corrugation::run::Event)) -> Result<T, E>,
) -> Result<T, E> {
    let checkpoint = interrupt::Checkpoint::default();
    checkpoint.written(kept);
    bar.set_file(out);
    interrupt::watch(out.to_path_buf(), &checkpoint, target);
    let result = work(&mut |e| {
        match e {
            corrugation::run::Event::Writing { .. } => checkpoint.writing(),
            corrugation::run::Event::Checkpoint { done } => checkpoint.written(done),
            _ => {}
        }
        bar.event(e)
    });
    if result.is_ok() {
        checkpoint.finished();
    } else {
        // A failed write leaves the file as it was.
        checkpoint.settled();
    }
    bar.finish();
    result
}

/// Whether `a` and `b` name the same existing file.
fn same_file(a: &Path, b: &Path) -> bool {
    match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
        (Ok(x), Ok(y)) => x == y,
        _ => a == b,
    }
}

/// Before computing anything: the output can be written (exit 2 naming the
/// path otherwise).
fn writable(out: &Path) -> Result<(), ExitCode> {
    corrugation::output::check_writable(out).map_err(|e| {
        say!("error: cannot write {}: {e}", out.display());
        ExitCode::from(2)
    })
}

/// The output a command writes without `-o`: `out/<config name><suffix>.h5`
/// under the current directory (`out/` made where missing), so that a run
/// never litters the folder it was started in.
fn default_output(config: &Path, fallback: &str, suffix: &str) -> PathBuf {
    let stem = config.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| fallback.into());
    let dir = PathBuf::from(DEFAULT_OUTPUT_DIR);
    // (A folder that cannot be made is reported by the writability check.)
    let _ = std::fs::create_dir_all(&dir);
    dir.join(format!("{stem}{suffix}.h5"))
}

/// The folder of the outputs written without `-o`.
const DEFAULT_OUTPUT_DIR: &str = "out";

fn run(resolved: &Resolved, out: &Path) -> ExitCode {
    let passes = resolved.scene.growth.as_ref().map_or(1, |g| g.passes);
    let label = if passes == 1 { "passage".to_string() } else { format!("{passes} passages") };
    let mut bar = progress::Progress::new(&label, resolved.scene.growth.is_some());
    let result = watched(out, 0, None, &mut bar, |events| run_scene(resolved, out, events));
    match result {
        Ok(s) => {
            report(&s, out);
            ExitCode::SUCCESS
        }
        Err(e) => {
            say!("error: {e}");
            say!("{} was not written (or holds the last checkpoint of a growth study)", out.display());
            ExitCode::from(1)
        }
    }
}

fn resume(file: &Path, passes: Option<usize>, output: Option<&Path>) -> ExitCode {
    let mut bar = progress::Progress::new("resume", true);
    let out = output.unwrap_or(file);
    // Until its first checkpoint, a resume onto another file has written
    // nothing; one in place keeps the file's own checkpoint.
    let held = corrugation::output::netcdf::read_f64(file, "passes", "traffic").map_or(0, |t| t.len());
    let kept = if output.is_none() { held } else { 0 };
    let result = watched(out, kept, passes.map(|p| held + p), &mut bar, |events| {
        corrugation::run::resume(file, passes, output, events)
    });
    match result {
        Ok(s) => {
            report(&s, out);
            ExitCode::SUCCESS
        }
        Err(ResumeError::Run(e)) => {
            say!("error: {e}");
            say!("{} holds the last checkpoint", out.display());
            ExitCode::from(1)
        }
        Err(e @ ResumeError::Complete { .. }) => {
            say!("{e}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            say!("error: {e}");
            ExitCode::from(2)
        }
    }
}

fn report(s: &RunSummary, out: &Path) {
    say!(
        "wrote {}: {} passage(s) ({} computed now, {:.3} s CPU), traffic {:.4e}; last passage: max wear {:.4e} m, \
         removed volume {:.4e} m^3; rms corrugation {:.4e} m",
        out.display(),
        s.passes,
        s.computed,
        s.cpu_seconds,
        s.traffic,
        s.max_wear,
        s.removed_volume,
        s.rms_corrugation,
    );
    if let Some(([first, second], volume, rms)) = &s.second_rail {
        say!(
            "(those are the {first}'s; the {second}: removed volume {volume:.4e} m^3, rms corrugation {rms:.4e} m, \
             in group second_rail)"
        );
    }
    if let Some(reason) = &s.stop_reason {
        say!("the study stopped before its planned passages (growth.stop): {reason}");
    }
    let (q, pass) = s.max_update_ratio;
    if q > s.update_bound * (1.0 + 1e-9) {
        let effect = if q <= 1.0 {
            format!("growth rates are off by about {:.0} % for standing patterns, more for travelling ones", 50.0 * q)
        } else {
            "harmonics can change sign between updates: growth is spurious".to_string()
        };
        say!(
            "warning: traffic scaling too coarse: the update of passage {pass} changed the corrugation by {q:.3} of \
             its amplitude (bound {}); {effect}. Lower growth.traffic_scale or set growth.adaptive = true.",
            s.update_bound
        );
    }
    // The last lines: where the rail stands against the roughness limit.
    for line in &s.outlook {
        say!("{line}");
    }
}
