//! `sweep slurm`: an sbatch job-array script, one array task per member,
//! each task `corrugation sweep member SPEC --index $SLURM_ARRAY_TASK_ID`.
//! The time and memory limits come from the cost model (the largest
//! member's, with a safety factor); the user's sbatch arguments are given
//! to `sbatch` on its command line, where they override the script's
//! `#SBATCH` lines.

use super::spec::SweepSpec;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Safety factor on the cost model's time (it is a rough estimate, and a
/// shared node may be slower than the development machine).
pub const TIME_FACTOR: f64 = 3.0;

/// Time added to every task's limit (s): start-up, HDF5 writes, a resume.
pub const TIME_MARGIN: f64 = 120.0;

/// What the job array is made of.
#[derive(Debug, Clone)]
pub struct ArrayJob {
    /// The members to run.
    pub members: Vec<usize>,
    /// At most this many tasks at once (`--array=...%K`).
    pub max_concurrent: usize,
    /// CPUs per task (threads of each member).
    pub cpus_per_task: usize,
    /// Time limit per task (s).
    pub time_limit: f64,
    /// Memory per task (bytes).
    pub memory: f64,
}

/// `0-3,7,9-11`: the Slurm array index list of sorted `members`.
pub fn array_ranges(members: &[usize]) -> String {
    let mut parts = Vec::new();
    let mut i = 0;
    while i < members.len() {
        let start = members[i];
        let mut end = start;
        while i + 1 < members.len() && members[i + 1] == end + 1 {
            i += 1;
            end = members[i];
        }
        parts.push(if end > start { format!("{start}-{end}") } else { start.to_string() });
        i += 1;
    }
    parts.join(",")
}

/// `D-HH:MM:SS`, rounded up to the minute.
pub fn slurm_time(seconds: f64) -> String {
    let minutes = (seconds / 60.0).ceil().max(1.0) as u64;
    format!("{}-{:02}:{:02}:00", minutes / 1440, (minutes / 60) % 24, minutes % 60)
}

/// The array task ids of `job` less `offset` (Slurm's task ids stay below
/// its MaxArraySize: a sweep with more members is submitted as several
/// arrays, each with its offset).
pub fn chunks(members: &[usize], max_array_size: usize) -> Vec<(usize, Vec<usize>)> {
    let size = max_array_size.max(1);
    let mut out: Vec<(usize, Vec<usize>)> = Vec::new();
    for &m in members {
        let offset = m / size * size;
        match out.last_mut() {
            Some((o, ids)) if *o == offset => ids.push(m - offset),
            _ => out.push((offset, vec![m - offset])),
        }
    }
    out
}

/// The sbatch script for `job` of `spec` running `exe`, for the array task
/// ids `ids` (member index = task id + `offset`). Each member's output is
/// appended to its log (a re-run keeps the earlier attempt's), Slurm's own
/// messages (a time limit, a cancellation) go to `logs/slurm-<job>_<task>.out`.
pub fn script(spec: &SweepSpec, job: &ArrayJob, exe: &Path, spec_path: &Path, offset: usize, ids: &[usize]) -> String {
    let logs = spec.output.join("logs");
    let width = spec.member_name(0).len() - "member_".len();
    let name = spec.path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "sweep".into());
    let quote = |p: &Path| shell_quote(&p.display().to_string());
    // In #SBATCH lines `%` starts a file-name pattern, and a value with
    // blanks must be quoted.
    let escape = |v: &str| v.replace('%', "%%");
    let blanks = |v: String| if v.chars().any(char::is_whitespace) { format!("\"{v}\"") } else { v };
    format!(
        "#!/bin/bash\n\
         # Written by `corrugation sweep slurm` for {spec}: {n} of its {total} members\n\
         # (member index = array task id + {offset}). Each array task runs one member;\n\
         # a member killed at its time limit or by a node failure resumes from its\n\
         # checkpoint when submitted again (`corrugation sweep slurm {spec} --only-unfinished`).\n\
         #SBATCH --job-name={job_name}\n\
         #SBATCH --array={array}%{concurrent}\n\
         #SBATCH --ntasks=1\n\
         #SBATCH --cpus-per-task={cpus}\n\
         #SBATCH --time={time}\n\
         #SBATCH --mem={mem}M\n\
         #SBATCH --output={slurm_out}\n\
         #SBATCH --open-mode=append\n\
         set -euo pipefail\n\
         index=$((SLURM_ARRAY_TASK_ID + {offset}))\n\
         log={logs_q}/member_$(printf '%0{width}d' \"$index\").log\n\
         # task/none binds no CPUs: keep each member to its own cores.\n\
         export RAYON_NUM_THREADS=\"${{SLURM_CPUS_PER_TASK:-1}}\"\n\
         exec {exe} sweep member {spec_q} --index \"$index\" >>\"$log\" 2>&1\n",
        spec = spec_path.display(),
        n = ids.len(),
        total = spec.len(),
        job_name = blanks(escape(&format!("corrugation-{name}"))),
        array = array_ranges(ids),
        concurrent = job.max_concurrent.max(1),
        cpus = job.cpus_per_task.max(1),
        time = slurm_time(job.time_limit),
        mem = (job.memory / (1 << 20) as f64).ceil() as u64,
        slurm_out = blanks(format!("{}/slurm-%A_%a.out", escape(&logs.display().to_string()))),
        logs_q = quote(&logs),
        exe = quote(exe),
        spec_q = quote(spec_path),
    )
}

/// Quotes `s` for a POSIX shell when it needs it.
pub fn shell_quote(s: &str) -> String {
    if !s.is_empty() && s.chars().all(|c| c.is_ascii_alphanumeric() || "/._-+=:,@".contains(c)) {
        s.to_string()
    } else {
        format!("'{}'", s.replace('\'', "'\\''"))
    }
}

/// Why a submission failed.
#[derive(Debug, thiserror::Error)]
pub enum SubmitError {
    /// sbatch could not be started.
    #[error("cannot run sbatch ({0}): is Slurm installed and on PATH? The script is {1}")]
    Spawn(std::io::Error, PathBuf),
    /// sbatch refused the job.
    #[error("sbatch refused the job (exit {code}): {stderr}")]
    Refused {
        /// Its exit status.
        code: i32,
        /// What it said.
        stderr: String,
    },
}

/// Submits `script` with `sbatch --parsable [args] script`; returns the
/// job id.
pub fn submit(script: &Path, args: &[String]) -> Result<String, SubmitError> {
    let out = Command::new("sbatch")
        .arg("--parsable")
        .args(args)
        .arg(script)
        .output()
        .map_err(|e| SubmitError::Spawn(e, script.to_owned()))?;
    if !out.status.success() {
        return Err(SubmitError::Refused {
            code: out.status.code().unwrap_or(-1),
            stderr: String::from_utf8_lossy(&out.stderr).trim().to_string(),
        });
    }
    // --parsable prints "jobid" or "jobid;cluster".
    let text = String::from_utf8_lossy(&out.stdout);
    Ok(text.trim().split(';').next().unwrap_or("").to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn array_lists_chunks_and_times() {
        assert_eq!(
            chunks(&[0, 1, 999, 1000, 1001, 2500], 1000),
            vec![(0, vec![0, 1, 999]), (1000, vec![0, 1]), (2000, vec![500])]
        );
        assert_eq!(array_ranges(&[0, 1, 2, 3, 7, 9, 10, 11]), "0-3,7,9-11");
        assert_eq!(array_ranges(&[5]), "5");
        assert_eq!(slurm_time(59.0), "0-00:01:00");
        assert_eq!(slurm_time(3601.0), "0-01:01:00");
        assert_eq!(slurm_time(90000.0), "1-01:00:00");
        assert_eq!(shell_quote("/a/b.toml"), "/a/b.toml");
        assert_eq!(shell_quote("/a b/it's"), "'/a b/it'\\''s'");
    }
}
