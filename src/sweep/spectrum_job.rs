//! `corrugation spectrum CONFIG --slurm N`: a spectrum's measurement
//! spread over a Slurm job array. Its rounds split into `N` parts (rounds
//! `t mod N = k`, [`crate::spectrum::measure`]), one array task each
//! (`corrugation spectrum CONFIG --part K/N -o DIR/part_K.h5`), and a merge
//! job that starts when every task has ended well (`--dependency=afterok`)
//! and writes the spectrum file (`corrugation spectrum-merge`). Limits from
//! the cost model as the sweep's ([`super::slurm`]).

use super::slurm::{TIME_FACTOR, TIME_MARGIN, shell_quote, slurm_time};
use std::path::Path;

/// What the job array is made of.
#[derive(Debug, Clone)]
pub struct SpectrumJob {
    /// Parts (array tasks).
    pub parts: usize,
    /// CPUs per task.
    pub cpus_per_task: usize,
    /// The whole measurement's estimated time on 2 cores (s).
    pub estimate: f64,
    /// Memory per task (bytes).
    pub memory: f64,
}

impl SpectrumJob {
    /// Time limit of one part (s): its share of the estimate, scaled to its
    /// cores, times the safety factor, plus the margin (a part also runs
    /// the base and smooth rails' passages and sets up the dynamics).
    pub fn time_limit(&self) -> f64 {
        let cores = 2.0 / self.cpus_per_task.max(1) as f64;
        self.estimate / self.parts.max(1) as f64 * cores * TIME_FACTOR + TIME_MARGIN
    }
}

/// The part file of part `k` (from 0) in `dir`.
pub fn part_file(dir: &Path, k: usize, parts: usize) -> std::path::PathBuf {
    let width = parts.to_string().len();
    dir.join(format!("part_{:0width$}.h5", k + 1))
}

/// The array script: task `k` measures part `k + 1` of `parts` of
/// `config` (with its `set` overrides) into `dir`.
pub fn array_script(job: &SpectrumJob, exe: &Path, config: &Path, set: &[String], dir: &Path) -> String {
    let q = |p: &Path| shell_quote(&p.display().to_string());
    let sets: String = set.iter().map(|s| format!(" --set {}", shell_quote(s))).collect();
    let width = job.parts.to_string().len();
    format!(
        "#!/bin/bash\n\
         # Written by `corrugation spectrum --slurm {n}` for {config}: task K measures part K+1\n\
         # of {n} of the linear growth spectrum; merge.sbatch merges them.\n\
         #SBATCH --job-name=corrugation-spectrum\n\
         #SBATCH --array=0-{last}\n\
         #SBATCH --ntasks=1\n\
         #SBATCH --cpus-per-task={cpus}\n\
         #SBATCH --time={time}\n\
         #SBATCH --mem={mem}M\n\
         #SBATCH --output={logs}/slurm-%A_%a.out\n\
         set -euo pipefail\n\
         part=$((SLURM_ARRAY_TASK_ID + 1))\n\
         export RAYON_NUM_THREADS=\"${{SLURM_CPUS_PER_TASK:-1}}\"\n\
         exec {exe} spectrum {config_q}{sets} --overwrite --part \"$part/{n}\" \\\n\
           -o {dir_q}/part_$(printf '%0{width}d' \"$part\").h5\n",
        n = job.parts,
        config = config.display(),
        last = job.parts.max(1) - 1,
        cpus = job.cpus_per_task.max(1),
        time = slurm_time(job.time_limit()),
        mem = (job.memory / (1 << 20) as f64).ceil() as u64,
        logs = dir.display().to_string().replace('%', "%%"),
        exe = q(exe),
        config_q = q(config),
        dir_q = q(dir),
    )
}

/// The merge script: the parts in `dir` into `out`.
pub fn merge_script(parts: usize, exe: &Path, dir: &Path, out: &Path) -> String {
    let q = |p: &Path| shell_quote(&p.display().to_string());
    let files: Vec<String> = (0..parts).map(|k| q(&part_file(dir, k, parts))).collect();
    format!(
        "#!/bin/bash\n\
         # Written by `corrugation spectrum --slurm {parts}`: merges the parts into the spectrum file.\n\
         #SBATCH --job-name=corrugation-spectrum-merge\n\
         #SBATCH --ntasks=1\n\
         #SBATCH --cpus-per-task=1\n\
         #SBATCH --time=0-00:10:00\n\
         #SBATCH --output={logs}/slurm-merge-%j.out\n\
         set -euo pipefail\n\
         exec {exe} spectrum-merge --overwrite -o {out} {files}\n",
        logs = dir.display().to_string().replace('%', "%%"),
        exe = q(exe),
        out = q(out),
        files = files.join(" "),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_scripts_run_every_part_and_merge_them() {
        let job = SpectrumJob { parts: 12, cpus_per_task: 1, estimate: 1200.0, memory: 3e8 };
        // 1200 s on 2 cores, 12 parts on 1 core each: 200 s, x 3, + 120 s.
        assert!((job.time_limit() - 720.0).abs() < 1e-9);
        let dir = Path::new("/w/bay.parts");
        let s = array_script(&job, Path::new("/bin/corrugation"), Path::new("/w/bay.toml"), &["a.b=1".into()], dir);
        assert!(s.contains("#SBATCH --array=0-11\n") && s.contains("#SBATCH --time=0-00:12:00"));
        assert!(s.contains("spectrum /w/bay.toml --set a.b=1 --overwrite --part \"$part/12\""));
        assert!(s.contains("/w/bay.parts/part_$(printf '%02d' \"$part\").h5"));
        let m = merge_script(12, Path::new("/bin/corrugation"), dir, Path::new("/w/bay.h5"));
        assert!(m.contains("spectrum-merge --overwrite -o /w/bay.h5 /w/bay.parts/part_01.h5"));
        assert!(m.contains("/w/bay.parts/part_12.h5\n"));
        assert_eq!(part_file(dir, 0, 12), Path::new("/w/bay.parts/part_01.h5"));
    }
}
