//! `corrugation sweep ...`: the command line of parameter sweeps
//! ([`corrugation::sweep`]): plan, run here, submit to Slurm, run one
//! member, status, collect.

use clap::Subcommand;
use corrugation::config::Resolved;
use corrugation::sweep::collect::{collect, describe};
use corrugation::sweep::member::{MemberError, MemberStatus, Outcome, run_member, status};
use corrugation::sweep::spec::SweepSpec;
use corrugation::sweep::{array_job, costs, slurm};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

#[derive(Subcommand)]
pub enum SweepCommand {
    /// List the members, their overrides and estimated costs.
    Plan {
        /// Sweep spec (TOML).
        spec: PathBuf,
    },
    /// Run the members on this machine, N at a time (each its own process).
    Run {
        /// Sweep spec (TOML).
        spec: PathBuf,
        /// Members at once; the cores are shared among them.
        #[arg(short = 'j', long = "jobs", default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=256))]
        jobs: u32,
    },
    /// Write an sbatch job-array script (one task per member) and submit it;
    /// prints the job id on stdout.
    Slurm {
        /// Sweep spec (TOML).
        spec: PathBuf,
        /// An argument for sbatch (repeatable), e.g. --sbatch-arg=--partition=short.
        #[arg(long = "sbatch-arg", allow_hyphen_values = true, value_name = "ARG")]
        sbatch_args: Vec<String>,
        /// Only the members that are not complete (checkpointed, failed, missing).
        #[arg(long)]
        only_unfinished: bool,
        /// At most this many array tasks at once.
        #[arg(long, default_value_t = 8, value_parser = clap::value_parser!(u32).range(1..=10000))]
        max_concurrent: u32,
        /// CPUs (threads) per member.
        #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u32).range(1..=256))]
        cpus_per_task: u32,
        /// Write the script, do not submit it.
        #[arg(long)]
        no_submit: bool,
        /// The cluster's MaxArraySize (task ids stay below it; larger sweeps
        /// are submitted as several arrays).
        #[arg(long, default_value_t = 1001, value_parser = clap::value_parser!(u32).range(2..))]
        max_array_size: u32,
    },
    /// Run one member (what an array task, or any scheduler, calls): resumes
    /// its checkpoint, leaves it alone if complete.
    Member {
        /// Sweep spec (TOML).
        spec: PathBuf,
        /// Member index (`sweep plan` lists them).
        #[arg(long)]
        index: usize,
    },
    /// Where every member stands: complete, checkpoint, failed, missing.
    Status {
        /// Sweep spec (TOML).
        spec: PathBuf,
    },
    /// Merge the members' results into one netCDF-4 dataset whose
    /// dimensions are the sweep's axes.
    Collect {
        /// Sweep spec (TOML).
        spec: PathBuf,
        /// Output file.
        #[arg(short, long)]
        output: PathBuf,
        /// Write NaN for members that are not complete (status = 1) instead
        /// of refusing.
        #[arg(long)]
        allow_missing: bool,
    },
}

/// Runs a sweep command.
pub fn main(command: SweepCommand) -> ExitCode {
    match command {
        SweepCommand::Plan { spec } => with_members(&spec, plan),
        SweepCommand::Run { spec, jobs } => with_members(&spec, |s, r| run_local(s, r, jobs as usize)),
        SweepCommand::Slurm {
            spec,
            sbatch_args,
            only_unfinished,
            max_concurrent,
            cpus_per_task,
            no_submit,
            max_array_size,
        } => {
            let opts = SlurmOptions {
                args: sbatch_args,
                only_unfinished,
                max_concurrent: max_concurrent as usize,
                cpus: cpus_per_task as usize,
                submit: !no_submit,
                max_array_size: max_array_size as usize,
            };
            with_members(&spec, |s, r| submit(s, r, &opts))
        }
        SweepCommand::Member { spec, index } => member(&spec, index),
        SweepCommand::Status { spec } => with_members(&spec, print_status),
        SweepCommand::Collect { spec, output, allow_missing } => {
            with_members(&spec, |s, r| collect_cmd(s, r, &output, allow_missing))
        }
    }
}

/// Loads the spec and validates every member (all errors at once, exit 2),
/// then runs `f`.
fn with_members(path: &Path, f: impl FnOnce(&SweepSpec, &[Resolved]) -> ExitCode) -> ExitCode {
    let spec = match SweepSpec::load(path) {
        Ok(s) => s,
        Err(e) => {
            say_raw!("error: {e}");
            return ExitCode::from(2);
        }
    };
    match spec.resolve_all() {
        Ok(r) => f(&spec, &r),
        Err(e) => {
            say_raw!("error: {e}");
            ExitCode::from(2)
        }
    }
}

/// Creates the sweep's directory and its `logs` folder (exit 2 naming the
/// path when it cannot).
fn prepare_output(spec: &SweepSpec) -> Result<(), ExitCode> {
    spec.prepare_output().map_err(|e| {
        say!("error: cannot write the sweep's directory {}: {e}", spec.output.display());
        ExitCode::from(2)
    })
}

/// This program's path, which members are run with (exit 1 when the
/// system cannot tell it).
fn this_program() -> Result<PathBuf, ExitCode> {
    std::env::current_exe().map_err(|e| {
        say!("error: cannot find this program's path to run the members with: {e}");
        ExitCode::from(1)
    })
}

fn hms(seconds: f64) -> String {
    let s = seconds.round() as u64;
    format!("{}:{:02}:{:02}", s / 3600, (s / 60) % 60, s % 60)
}

fn plan(spec: &SweepSpec, resolved: &[Resolved]) -> ExitCode {
    let c = costs(resolved);
    println!(
        "sweep {}: {} members of {} (base {}), output {}",
        spec.path.display(),
        spec.len(),
        spec.dims.iter().map(|d| format!("{} x {}", d.len(), d.keys.join(" + "))).collect::<Vec<_>>().join(", "),
        spec.base.display(),
        spec.output.display()
    );
    if !spec.set.is_empty() {
        println!("every member: {}", spec.set.join(", "));
    }
    for (i, (m, c)) in spec.members().iter().zip(&c).enumerate() {
        println!(
            "{}  {:<60} {:>6} passages  {:>9} ({:.2} s per passage)  {:>6.0} MB",
            spec.member_name(i),
            m.overrides.join(", "),
            c.passes,
            hms(c.total()),
            c.per_passage,
            c.memory / 1e6
        );
    }
    let total: f64 = c.iter().map(|c| c.total()).sum();
    let job = array_job((0..spec.len()).collect(), &c, 8, 2);
    println!(
        "estimated cost {} in all on 2 cores (rough, from the benchmarks); Slurm limits per task: --time={} \
         --mem={:.0}M (largest member x {} + {} s)",
        hms(total),
        slurm::slurm_time(job.time_limit),
        (job.memory / (1 << 20) as f64).ceil(),
        slurm::TIME_FACTOR,
        slurm::TIME_MARGIN
    );
    ExitCode::SUCCESS
}

fn member(path: &Path, index: usize) -> ExitCode {
    let spec = match SweepSpec::load(path) {
        Ok(s) => s,
        Err(e) => {
            say_raw!("error: {e}");
            return ExitCode::from(2);
        }
    };
    say!("sweep member {index}: {}", if index < spec.len() { spec.describe(index) } else { "?".into() });
    let growth = spec.resolve(index).map_or(true, |r| r.scene.growth.is_some());
    let mut bar = crate::progress::Progress::new(&format!("member {index}"), growth);
    let result = run_member(&spec, index, &mut |e| bar.event(e));
    bar.finish();
    match result {
        Ok(Outcome::AlreadyComplete) => {
            say!("{} is complete already", spec.member_file(index).display());
            ExitCode::SUCCESS
        }
        Ok(Outcome::Ran { resumed, summary }) => {
            let how = if resumed { "resumed from its checkpoint, " } else { "" };
            say!(
                "wrote {}: {how}{} passage(s), traffic {:.4e}, rms corrugation {:.4e} m",
                spec.member_file(index).display(),
                summary.passes,
                summary.traffic,
                summary.rms_corrugation
            );
            ExitCode::SUCCESS
        }
        Err(e) => {
            say_raw!("error: {e}\n");
            if e.is_bad_input() {
                ExitCode::from(2)
            } else {
                if let MemberError::Run(_) = e {
                    say!("the error is in {}", spec.error_file(index).display());
                }
                ExitCode::from(1)
            }
        }
    }
}

fn print_status(spec: &SweepSpec, resolved: &[Resolved]) -> ExitCode {
    let mut counts = std::collections::BTreeMap::new();
    for (i, r) in resolved.iter().enumerate() {
        let s = status(spec, i, &r.toml);
        *counts.entry(s.word()).or_insert(0) += 1;
        println!("{}  {:<60} {}", spec.member_name(i), spec.member(i).overrides.join(", "), describe(&s));
    }
    let summary: Vec<String> = counts.iter().map(|(w, n)| format!("{n} {w}")).collect();
    println!("{} members: {}", spec.len(), summary.join(", "));
    ExitCode::SUCCESS
}

fn collect_cmd(spec: &SweepSpec, resolved: &[Resolved], out: &Path, allow_missing: bool) -> ExitCode {
    if let Err(e) = corrugation::output::check_writable(out) {
        say!("error: cannot write {}: {e}", out.display());
        return ExitCode::from(2);
    }
    let configs: Vec<String> = resolved.iter().map(|r| r.toml.clone()).collect();
    match collect(spec, &configs, out, allow_missing) {
        Ok(c) => {
            let missing = if c.missing.is_empty() {
                String::new()
            } else {
                format!(" ({} not complete, written as NaN: members {:?})", c.missing.len(), c.missing)
            };
            say!("wrote {}: {} members{missing}", out.display(), c.members);
            ExitCode::SUCCESS
        }
        Err(e) => {
            say!("error: {e}");
            ExitCode::from(1)
        }
    }
}

struct SlurmOptions {
    args: Vec<String>,
    only_unfinished: bool,
    max_concurrent: usize,
    cpus: usize,
    submit: bool,
    /// Members per array: Slurm task ids stay below MaxArraySize.
    max_array_size: usize,
}

fn submit(spec: &SweepSpec, resolved: &[Resolved], o: &SlurmOptions) -> ExitCode {
    if let Err(code) = prepare_output(spec) {
        return code;
    }
    let mut stale = Vec::new();
    let members: Vec<usize> = (0..spec.len())
        .filter(|i| {
            if !o.only_unfinished {
                return true;
            }
            match status(spec, *i, &resolved[*i].toml) {
                MemberStatus::Complete { .. } => false,
                MemberStatus::Running { .. } => {
                    say!("member {i} is running; not submitted again");
                    false
                }
                MemberStatus::Stale => {
                    stale.push(*i);
                    false
                }
                _ => true,
            }
        })
        .collect();
    if !stale.is_empty() {
        say!(
            "warning: members {stale:?} hold runs of another config (the spec changed); not submitted: delete their \
             files to run them anew"
        );
    }
    if members.is_empty() {
        say!("all {} members are complete; nothing to submit", spec.len());
        return ExitCode::SUCCESS;
    }
    let exe = match this_program() {
        Ok(e) => e,
        Err(code) => return code,
    };
    let spec_path = std::path::absolute(&spec.path).unwrap_or_else(|_| spec.path.clone());
    // The script runs from the submission folder: absolute paths throughout.
    let spec_abs =
        SweepSpec { output: std::path::absolute(&spec.output).unwrap_or(spec.output.clone()), ..spec.clone() };
    let job = array_job(members, &costs(resolved), o.max_concurrent, o.cpus);
    let chunks = slurm::chunks(&job.members, o.max_array_size);
    let mut scripts = Vec::new();
    for (k, (offset, ids)) in chunks.iter().enumerate() {
        let text = slurm::script(&spec_abs, &job, &exe, &spec_path, *offset, ids);
        let name = if chunks.len() == 1 { "sweep.sbatch".to_string() } else { format!("sweep_{k}.sbatch") };
        let script_path = spec.output.join(name);
        if let Err(e) = std::fs::write(&script_path, &text) {
            say!("error: cannot write {}: {e}", script_path.display());
            return ExitCode::from(2);
        }
        say!(
            "wrote {}: {} array tasks ({}, member = task + {offset}), at most {} at once, {} CPUs, --time={} --mem={:.0}M",
            script_path.display(),
            ids.len(),
            slurm::array_ranges(ids),
            job.max_concurrent,
            job.cpus_per_task,
            slurm::slurm_time(job.time_limit),
            (job.memory / (1 << 20) as f64).ceil()
        );
        scripts.push(script_path);
    }
    if !o.submit {
        return ExitCode::SUCCESS;
    }
    for script_path in &scripts {
        match slurm::submit(script_path, &o.args) {
            Ok(id) => {
                say!("submitted job {id}; `corrugation sweep status {}` tells where it stands", spec.path.display());
                println!("{id}");
            }
            Err(e) => {
                say!("error: {e}");
                return ExitCode::from(1);
            }
        }
    }
    ExitCode::SUCCESS
}

/// Runs the members here, `jobs` at a time, each as its own process
/// (`corrugation sweep member`) with its share of the cores, its output in
/// its log; one progress bar over the members (a plain log off a terminal).
fn run_local(spec: &SweepSpec, resolved: &[Resolved], jobs: usize) -> ExitCode {
    if let Err(code) = prepare_output(spec) {
        return code;
    }
    let exe = match this_program() {
        Ok(e) => e,
        Err(code) => return code,
    };
    let todo: Vec<usize> = (0..spec.len()).filter(|i| !status(spec, *i, &resolved[*i].toml).is_complete()).collect();
    let skipped = spec.len() - todo.len();
    if skipped > 0 {
        say!("{skipped} of {} members are complete already", spec.len());
    }
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let jobs = jobs.min(todo.len()).max(1);
    let threads = (cores / jobs).max(1);
    say!(
        "running {} members, {jobs} at a time, {threads} thread(s) each; logs in {}",
        todo.len(),
        spec.output.join("logs").display()
    );
    let bar = crate::progress::MemberBar::new(todo.len());
    let next = AtomicUsize::new(0);
    let failed = Mutex::new(Vec::new());
    let start = Instant::now();
    std::thread::scope(|scope| {
        for _ in 0..jobs {
            scope.spawn(|| {
                loop {
                    let k = next.fetch_add(1, Ordering::SeqCst);
                    let Some(&i) = todo.get(k) else { break };
                    let log = spec.log_file(i);
                    let ok = std::fs::OpenOptions::new()
                        .create(true)
                        .append(true)
                        .open(&log)
                        .and_then(|f| {
                            let err = f.try_clone()?;
                            std::process::Command::new(&exe)
                                .args(["sweep", "member"])
                                .arg(&spec.path)
                                .args(["--index", &i.to_string()])
                                .env("RAYON_NUM_THREADS", threads.to_string())
                                .stdout(f)
                                .stderr(err)
                                .status()
                        })
                        .map(|s| s.success())
                        .unwrap_or(false);
                    if !ok {
                        failed.lock().expect("no panics hold it").push(i);
                    }
                    bar.done(i, ok, start.elapsed().as_secs_f64());
                }
            });
        }
    });
    bar.finish();
    let mut failed = failed.into_inner().expect("no panics hold it");
    failed.sort_unstable();
    for i in &failed {
        let s = status(spec, *i, &resolved[*i].toml);
        say!("member {i} failed: {}; log {}", describe(&s), spec.log_file(*i).display());
    }
    say!(
        "{} of {} members complete ({:.1} s); `corrugation sweep collect {} -o SWEEP.h5` merges them",
        spec.len() - failed.len(),
        spec.len(),
        start.elapsed().as_secs_f64(),
        spec.path.display()
    );
    if failed.is_empty() { ExitCode::SUCCESS } else { ExitCode::from(1) }
}
