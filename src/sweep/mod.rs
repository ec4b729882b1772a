//! Parameter sweeps: one spec ([`spec`]), its members run locally, on a
//! Slurm cluster as a job array ([`slurm`]) or by any scheduler through
//! `corrugation sweep member SPEC --index I` ([`member`]), and one merged
//! netCDF-4 dataset whose dimensions are the sweep's axes ([`collect`]).
//!
//! A member is the base config with the spec's overrides; it runs and
//! checkpoints exactly as `corrugation run` does, so a killed member
//! resumes bit for bit. Everything a sweep command needs to know about a
//! member is in its files in the sweep's directory: `member_<i>.h5` (the
//! run file, with its status attribute), `member_<i>.error` (the error of
//! a failed run) and `logs/member_<i>.log`.

pub mod collect;
pub mod member;
pub mod slurm;
pub mod spec;
pub mod spectrum_job;

use crate::config::Resolved;
use crate::cost::{CostEstimate, estimate};

/// The least memory a Slurm task asks for (bytes).
pub const MIN_MEMORY: f64 = 256.0 * 1048576.0;

/// The cost model's estimate of every member (s, bytes).
pub fn costs(resolved: &[Resolved]) -> Vec<CostEstimate> {
    resolved.iter().map(|r| estimate(&r.scene)).collect()
}

/// The job of `members` (their costs `costs`): the time limit is the
/// largest member's estimate times [`slurm::TIME_FACTOR`] plus
/// [`slurm::TIME_MARGIN`] (the estimates are for 2 cores: times 2 with one
/// core), the memory the largest member's, at least [`MIN_MEMORY`].
pub fn array_job(members: Vec<usize>, costs: &[CostEstimate], max_concurrent: usize, cpus: usize) -> slurm::ArrayJob {
    let slowest = members.iter().map(|i| costs[*i].total()).fold(0.0, f64::max);
    // At least MIN_MEMORY: clusters that enforce the limit kill a task
    // beyond it, and the estimate is rough.
    let memory = members.iter().map(|i| costs[*i].memory).fold(MIN_MEMORY, f64::max);
    // The estimates are for 2 cores; a task with one core takes up to twice.
    let cores = (2.0 / cpus.max(1) as f64).max(1.0);
    slurm::ArrayJob {
        members,
        max_concurrent,
        cpus_per_task: cpus,
        time_limit: slowest * cores * slurm::TIME_FACTOR + slurm::TIME_MARGIN,
        memory,
    }
}
