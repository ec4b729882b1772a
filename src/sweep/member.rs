//! One member of a sweep: where it stands (from its files) and running it.
//!
//! A member writes `member_<i>.h5` as `corrugation run` does (checkpoints
//! included). Run again, it resumes a checkpoint (bit for bit the run that
//! never stopped) and leaves a complete file alone; a failure leaves its
//! error in `member_<i>.error`, which a later success removes. A member
//! file whose stored config is not the member's (the spec changed since) is
//! never resumed or overwritten: the user must delete it. A member runs in
//! one process at a time: it holds `member_<i>.lock` (an advisory file
//! lock, released by the system when the process ends, however it ends);
//! a second process for the same member refuses to start.

use super::spec::SweepSpec;
use crate::config::ConfigErrors;
use crate::output::netcdf::{Attrs, NcError};
use crate::run::{Event, ResumeError, RunError, RunSummary, resume, run_scene};
use std::path::{Path, PathBuf};

/// Where a member stands.
#[derive(Debug, Clone, PartialEq)]
pub enum MemberStatus {
    /// Its file is complete.
    Complete {
        /// Passages in the file.
        passes: usize,
    },
    /// Another process runs it now (it holds the member's lock).
    Running {
        /// Passages in its last checkpoint (0 before the first).
        done: usize,
        /// Passages planned (0 before the first checkpoint).
        planned: usize,
    },
    /// Its file is a checkpoint (a killed member).
    Checkpoint {
        /// Passages done.
        done: usize,
        /// Passages planned.
        planned: usize,
    },
    /// It failed (its error file), possibly after a checkpoint.
    Failed {
        /// The error it wrote.
        error: String,
    },
    /// Its file holds another config than the member's (the spec changed).
    Stale,
    /// Nothing written yet.
    Missing,
}

impl MemberStatus {
    /// Whether the member is complete.
    pub fn is_complete(&self) -> bool {
        matches!(self, MemberStatus::Complete { .. })
    }

    /// A word for tables: complete, checkpoint, failed, stale, missing.
    pub fn word(&self) -> &'static str {
        match self {
            MemberStatus::Complete { .. } => "complete",
            MemberStatus::Running { .. } => "running",
            MemberStatus::Checkpoint { .. } => "checkpoint",
            MemberStatus::Failed { .. } => "failed",
            MemberStatus::Stale => "stale",
            MemberStatus::Missing => "missing",
        }
    }
}

/// The state of a member's run file: (status attribute, passes done,
/// passes planned, stored config).
fn file_state(path: &Path) -> Result<(String, usize, usize, String), NcError> {
    let root = Attrs::open(path, "")?;
    let count = |name: &str| root.i64(name).map(|v| v.max(0) as usize);
    Ok((root.str("status")?, count("passes_done")?, count("passes_planned")?, root.str("config")?))
}

/// Whether another process holds member `index`'s lock (it is running).
fn running(spec: &SweepSpec, index: usize) -> bool {
    let Ok(f) = std::fs::OpenOptions::new().read(true).open(spec.lock_file(index)) else {
        return false;
    };
    match f.try_lock() {
        Ok(()) => {
            let _ = f.unlock();
            false
        }
        Err(std::fs::TryLockError::WouldBlock) => true,
        Err(_) => false,
    }
}

/// Where member `index` of `spec` stands, `config` being its resolved
/// config (TOML text). A complete file of the member's config is complete
/// whatever else lies around; then a member whose lock is held is running;
/// then an error file means failed.
pub fn status(spec: &SweepSpec, index: usize, config: &str) -> MemberStatus {
    let file = spec.member_file(index);
    let state = file.exists().then(|| file_state(&file));
    if let Some(Ok((s, done, _, stored))) = &state
        && s == "complete"
        && stored == config
    {
        return MemberStatus::Complete { passes: *done };
    }
    if running(spec, index) {
        let (done, planned) = match &state {
            Some(Ok((_, done, planned, _))) => (*done, *planned),
            _ => (0, 0),
        };
        return MemberStatus::Running { done, planned };
    }
    if let Ok(error) = std::fs::read_to_string(spec.error_file(index)) {
        return MemberStatus::Failed { error: error.trim().to_string() };
    }
    match state {
        None => MemberStatus::Missing,
        Some(Ok((_, _, _, stored))) if stored != config => MemberStatus::Stale,
        Some(Ok((_, done, planned, _))) => MemberStatus::Checkpoint { done, planned },
        Some(Err(e)) => MemberStatus::Failed { error: format!("unreadable run file: {e}") },
    }
}

/// What running a member did.
#[derive(Debug)]
pub enum Outcome {
    /// It was complete already.
    AlreadyComplete,
    /// It ran (from the start, or resumed from its checkpoint).
    Ran {
        /// Whether it resumed a checkpoint.
        resumed: bool,
        /// The run's summary.
        summary: RunSummary,
    },
}

/// Why a member could not run.
#[derive(Debug, thiserror::Error)]
pub enum MemberError {
    /// `--index` beyond the members.
    #[error("member {index} does not exist: the sweep has {len} members (0 .. {})", len - 1)]
    NoSuchMember {
        /// The index asked for.
        index: usize,
        /// Members in the sweep.
        len: usize,
    },
    /// The member's config is not valid.
    #[error("{0}")]
    Config(ConfigErrors),
    /// The sweep's directory cannot be written.
    #[error("cannot write the sweep's directory {path}: {source}")]
    Output {
        /// The directory.
        path: PathBuf,
        /// Cause.
        source: std::io::Error,
    },
    /// The member's file holds another config.
    #[error(
        "{path} holds a run of another config than member {index}'s (the spec changed since it ran); delete it to \
         run the member anew"
    )]
    Stale {
        /// The member's file.
        path: PathBuf,
        /// The member.
        index: usize,
    },
    /// Another process runs the member (holds its lock).
    #[error("member {index} is running in another process (it holds {lock}); wait for it or stop it (scancel) first")]
    Running {
        /// The member.
        index: usize,
        /// The lock file.
        lock: PathBuf,
    },
    /// The run failed (the error file holds this message).
    #[error("{0}")]
    Run(String),
}

impl MemberError {
    /// Whether the input was at fault (exit 2) rather than the run (exit 1).
    pub fn is_bad_input(&self) -> bool {
        !matches!(self, MemberError::Run(_) | MemberError::Running { .. })
    }
}

/// Runs member `index` of `spec`: resumes its checkpoint, leaves a
/// complete file alone, or runs it from the start. A failed run leaves its
/// message in the member's error file.
pub fn run_member(spec: &SweepSpec, index: usize, progress: &mut dyn FnMut(Event)) -> Result<Outcome, MemberError> {
    if index >= spec.len() {
        return Err(MemberError::NoSuchMember { index, len: spec.len() });
    }
    let resolved = spec.resolve(index).map_err(MemberError::Config)?;
    let output_err = |source| MemberError::Output { path: spec.output.clone(), source };
    spec.prepare_output().map_err(output_err)?;
    let file = spec.member_file(index);
    let error_file = spec.error_file(index);
    // One process per member: the lock is held until the member ends (and
    // released by the system if it is killed). A few tries, as `status`
    // takes the lock for an instant to tell whether the member runs.
    let lock_path = spec.lock_file(index);
    let lock =
        std::fs::OpenOptions::new().create(true).truncate(false).write(true).open(&lock_path).map_err(output_err)?;
    let mut tries = 0;
    loop {
        match lock.try_lock() {
            Ok(()) => break,
            Err(std::fs::TryLockError::WouldBlock) if tries < 20 => {
                tries += 1;
                std::thread::sleep(std::time::Duration::from_millis(50));
            }
            Err(std::fs::TryLockError::WouldBlock) => {
                return Err(MemberError::Running { index, lock: lock_path });
            }
            Err(std::fs::TryLockError::Error(e)) => return Err(output_err(e)),
        }
    }
    // A task killed while writing leaves its temporary file behind (no
    // other process writes this member: we hold its lock).
    crate::output::remove_stale_temporaries(&file);
    let previous = file.exists().then(|| file_state(&file));
    let result = match previous {
        Some(Ok((_, _, _, stored))) if stored != resolved.toml => {
            return Err(MemberError::Stale { path: file, index });
        }
        Some(Ok((status, ..))) if status == "complete" => {
            let _ = std::fs::remove_file(&error_file);
            return Ok(Outcome::AlreadyComplete);
        }
        Some(Ok(_)) => resume(&file, None, None, progress)
            .map(|summary| Outcome::Ran { resumed: true, summary })
            .map_err(|e: ResumeError| e.to_string()),
        // No file, or one that cannot be read (it is then replaced).
        _ => run_scene(&resolved, &file, progress)
            .map(|summary| Outcome::Ran { resumed: false, summary })
            .map_err(|e: RunError| e.to_string()),
    };
    match result {
        Ok(outcome) => {
            let _ = std::fs::remove_file(&error_file);
            Ok(outcome)
        }
        Err(message) => {
            // The error file is written atomically too (a reader sees the
            // whole message or none).
            let tmp = error_file.with_extension(format!("error.tmp-{}", std::process::id()));
            let _ = std::fs::write(&tmp, format!("{message}\n")).and_then(|_| std::fs::rename(&tmp, &error_file));
            Err(MemberError::Run(message))
        }
    }
}
