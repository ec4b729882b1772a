//! `corrugation spectrum CONFIG.toml -o SPECTRUM.h5`: the linear growth
//! spectrum of a growth study's passage ([`corrugation::spectrum`]),
//! written to one file, with the fastest modes printed.

use corrugation::config::Resolved;
use corrugation::growth::study::initial_state;
use corrugation::spectrum::{Base, Progress, Spectrum, linear_spectrum};
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

/// Modes printed at the end.
const PRINTED: usize = 8;

/// The rail a run file's study holds: its profile after the passages
/// stored, or with `pass` (from 1) that passage's stored snapshot; each
/// rail's.
pub fn stored_rail(file: &Path, resolved: &Resolved, pass: Option<usize>) -> Result<Vec<ndarray::Array2<f64>>, String> {
    let state = corrugation::run::stored_state(file, resolved).map_err(|e| e.to_string())?;
    let pick = |s: &corrugation::growth::state::RunState| match pass {
        None => Ok(s.profile.clone()),
        Some(p) => s.rail.iter().find(|r| r.index as usize + 1 == p).map(|r| r.profile.clone()).ok_or_else(|| {
            let kept: Vec<String> = s.rail.iter().map(|r| (r.index + 1).to_string()).collect();
            format!(
                "{}: passage {p} is not stored (rail snapshots of passages {}; growth.store_every sets them)",
                file.display(),
                kept.join(", ")
            )
        }),
    };
    std::iter::once(&state).chain(state.second_rail.as_deref()).map(pick).collect()
}

/// Measures and writes the spectrum of `resolved` to `out`, about `stored`
/// (a run file's rail) or the config's `spectrum.base`; with `part = (k,
/// n)` only its rounds `t mod n = k`, written as a part file for
/// `corrugation spectrum-merge`; the passages on `jobs` threads.
pub fn spectrum(
    resolved: &Resolved,
    stored: Option<Vec<ndarray::Array2<f64>>>,
    part: Option<(usize, usize)>,
    jobs: usize,
    out: &Path,
) -> ExitCode {
    let scene = &resolved.scene;
    if scene.growth.is_none() {
        say!(
            "error: corrugation spectrum linearises a growth study's passage: the config needs a [growth] section \
             (with its [dynamics], [track] and [roughness])"
        );
        return ExitCode::from(2);
    }
    let params = scene.spectrum.unwrap_or_default();
    let state = initial_state(scene);
    // About a run file's rail the roughness now is that rail, not the
    // config's initial roughness: no forecast of the latter.
    let forecast = stored.is_none();
    let base: Vec<ndarray::Array2<f64>> = match (stored, params.base) {
        (Some(rails), _) => rails,
        (None, Base::Smooth) => {
            let z = ndarray::Array2::zeros(state.profile.raw_dim());
            vec![z; 1 + usize::from(state.second_rail.is_some())]
        }
        (None, Base::Roughness) => std::iter::once(state.profile.clone())
            .chain(state.second_rail.as_ref().map(|s| s.profile.clone()))
            .collect(),
    };
    let bar = std::io::stderr().is_terminal().then(|| {
        let b = ProgressBar::new(1);
        b.set_style(
            ProgressStyle::with_template("spectrum [{bar:20}] {pos}/{len} passages, {elapsed}, ETA {eta}")
                .expect("valid template")
                .progress_chars("=> "),
        );
        b
    });
    let start = Instant::now();
    let mut last = Instant::now();
    let mut report = |p: Progress| match &bar {
        Some(b) => {
            b.set_length(p.total as u64);
            b.set_position(p.done as u64);
        }
        None if p.done == p.total || last.elapsed().as_secs_f64() >= 10.0 => {
            last = Instant::now();
            let secs = start.elapsed().as_secs_f64();
            say!("spectrum: {}/{} passages ({secs:.0} s)", p.done, p.total);
        }
        None => {}
    };
    if let Some((k, n)) = part {
        let result = corrugation::spectrum::measure::measure(scene, &base, &params, part, jobs, &mut report);
        if let Some(b) = &bar {
            b.finish_and_clear();
        }
        return match result.map_err(|e| e.to_string()).and_then(|r| {
            corrugation::output::spectrum_part::write_part(out, &r, (k, n), &resolved.toml)
                .map(|()| r)
                .map_err(|e| e.to_string())
        }) {
            Ok(r) => {
                let measured = r.columns.iter().flatten().filter(|c| !c.is_empty()).count();
                say!(
                    "wrote {}: part {} of {n} ({measured} perturbations, {} passages, {:.1} s CPU); \
                     `corrugation spectrum-merge` the {n} parts into the spectrum",
                    out.display(),
                    k + 1,
                    r.passages,
                    r.cpu_seconds
                );
                ExitCode::SUCCESS
            }
            Err(e) => {
                say!("error: {e}");
                say!("{} was not written", out.display());
                ExitCode::from(1)
            }
        };
    }
    let result = linear_spectrum(scene, &base, &params, jobs, &mut report);
    if let Some(b) = &bar {
        b.finish_and_clear();
    }
    let s = match result {
        Ok(s) => s,
        Err(e) => {
            say!("error: {e}");
            say!("{} was not written", out.display());
            return ExitCode::from(1);
        }
    };
    for w in &s.warnings {
        say!("warning: {w}");
    }
    write(resolved, &s, out, forecast)
}

/// Writes the spectrum `s` of `resolved`, with its forecasts where
/// `forecast`, to `out` and prints them.
fn write(resolved: &Resolved, s: &Spectrum, out: &Path, forecast: bool) -> ExitCode {
    let params = resolved.scene.spectrum.unwrap_or_default();
    let forecasts = match if forecast { crate::forecast_cli::forecasts(resolved, s) } else { Ok(Vec::new()) } {
        Ok(f) => f,
        Err(e) => {
            say!("warning: no forecast: {e}");
            Vec::new()
        }
    };
    // A forecast with no band is printed (what it left out, and why), not
    // written: netCDF has no empty fixed dimension.
    let groups: Vec<_> = forecasts.iter().filter(|f| !f.is_empty()).map(|f| f.group()).collect();
    if let Err(e) = corrugation::output::spectrum_file::write_spectrum_file(out, s, &params, &resolved.toml, &groups) {
        say!("error: {e}");
        return ExitCode::from(1);
    }
    summary(s, out);
    crate::forecast_cli::print(&forecasts);
    ExitCode::SUCCESS
}

/// `corrugation spectrum-merge PARTS -o OUT`: the parts of one
/// measurement (every part of `--part K/N`, of one config) as its
/// spectrum file.
pub fn merge(parts: &[std::path::PathBuf], out: &Path) -> ExitCode {
    let fail = |e: String| {
        say!("error: {e}");
        ExitCode::from(2)
    };
    let Some(first) = parts.first() else { return fail("no part file given".into()) };
    let config = match corrugation::output::netcdf::read_attr_str(first, "", "config") {
        Ok(c) => c,
        Err(e) => return fail(e.to_string()),
    };
    let resolved = match corrugation::config::load_str(&config, &format!("stored in {}", first.display()), &[]) {
        Ok(r) => r,
        Err(e) => return fail(format!("{}: its stored config is not valid:\n{e}", first.display())),
    };
    let scene = &resolved.scene;
    let params = scene.spectrum.unwrap_or_default();
    let rails = 1 + usize::from(scene.second_rail.is_some());
    let mut read = Vec::new();
    let mut seen = std::collections::BTreeSet::new();
    let mut count = None;
    for path in parts {
        let layout = match corrugation::spectrum::measure::empty(scene, &params, rails) {
            Ok(l) => l,
            Err(e) => return fail(e.to_string()),
        };
        let part = match corrugation::output::spectrum_part::read_part(path, layout) {
            Ok(p) => p,
            Err(e) => return fail(e.to_string()),
        };
        if part.config != config {
            return fail(format!("{} is a part of another config than {}'s", path.display(), first.display()));
        }
        if *count.get_or_insert(part.part.1) != part.part.1 || !seen.insert(part.part.0) {
            return fail(format!(
                "{}: part {} of {} does not fit the others",
                path.display(),
                part.part.0 + 1,
                part.part.1
            ));
        }
        read.push(part.responses);
    }
    let n = count.unwrap_or(0);
    if seen.len() != n {
        let missing: Vec<String> = (0..n).filter(|k| !seen.contains(k)).map(|k| (k + 1).to_string()).collect();
        return fail(format!("parts {} of {n} are missing", missing.join(", ")));
    }
    let spectrum = corrugation::spectrum::measure::Responses::merge(read)
        .and_then(|r| corrugation::spectrum::Spectrum::from_responses(scene, &params, r));
    match spectrum {
        Ok(s) => write(&resolved, &s, out, true),
        Err(e) => fail(e.to_string()),
    }
}

/// The fastest modes, the forced pattern's deepest harmonics and the cost.
fn summary(s: &Spectrum, out: &Path) {
    say!(
        "wrote {}: {} modes of {} Bloch class(es) on the {} m stretch ({} harmonics perturbed), {:.0} passage \
         equivalents, {:.1} s CPU, {:.1} s wall",
        out.display(),
        s.modes.len(),
        s.classes.len(),
        s.stretch,
        s.classes.iter().map(|c| c.basis.len()).sum::<usize>(),
        s.passage_equivalents,
        s.cpu_seconds,
        s.wall_seconds,
    );
    say!("fastest modes (dB per 1e5 wheel passages; drift in mm per 1e5 wheel passages):");
    let deepest = if s.supports.is_empty() { "" } else { "deepest in span   " };
    say!("  rate      wavelength  frequency  drift     purity  sleeper/mid-span  {deepest}near");
    for k in 0..s.modes.len().min(PRINTED) {
        let m = &s.modes[k];
        let class = s.class_of(k);
        let deepest = s.deepest(k).map_or(String::new(), |(_, share)| format!("{share:5.2}             "));
        let near = s.near_resonance(k).map_or(String::new(), |i| {
            let (label, f) = &s.resonances[i];
            format!("{label} ({f:.0} Hz)")
        });
        say!(
            "  {:+8.3}  {:7.2} mm  {:7.1} Hz  {:+8.3}  {:5.2}   {:5.2}             {deepest}{near}",
            m.growth_rate(),
            s.wavelength(k) * 1e3,
            s.frequency(k),
            m.drift(class, s.supercell()) * 1e5 * 1e3,
            m.purity(),
            s.support_ratio(k),
        );
    }
    let forced = &s.forced_wear[0];
    let mut order: Vec<usize> = (0..forced.len()).collect();
    order.sort_by(|a, b| forced[*b].total_cmp(&forced[*a]));
    // Harmonics below 1e-6 of the mean wear are the round-off of a uniform
    // wear along the stretch.
    if forced.iter().any(|f| *f > 1e-6 * s.mean_wear[0]) {
        let top: Vec<String> = order
            .iter()
            .take(4)
            .map(|&k| format!("{:.1} mm {:.3} nm", s.wavelengths[k] * 1e3, forced[k] * 1e5 * 1e9))
            .collect();
        say!(
            "forced pattern (the smooth rail's wear per 1e5 wheel passages, of {:.3} um in all): {}",
            s.mean_wear[0] * 1e5 * 1e6,
            top.join(", ")
        );
    } else {
        say!("forced pattern: none (the smooth rail wears uniformly along the stretch)");
    }
}

/// `--slurm N`'s options.
pub struct SlurmJob {
    /// Parts (array tasks).
    pub parts: usize,
    /// CPUs per task.
    pub cpus_per_task: usize,
    /// The user's sbatch arguments.
    pub sbatch_args: Vec<String>,
    /// Write the scripts only.
    pub no_submit: bool,
}

/// `corrugation spectrum CONFIG --slurm N -o OUT`: the measurement as a job
/// array of N parts into `OUT.parts/` and a merge job into OUT
/// ([`corrugation::sweep::spectrum_job`]); prints the merge job's id.
pub fn slurm(resolved: &Resolved, config: &Path, set: &[String], out: &Path, job: &SlurmJob) -> ExitCode {
    use corrugation::sweep::spectrum_job::{SpectrumJob, array_script, merge_script};
    let scene = &resolved.scene;
    if scene.growth.is_none() {
        say!("error: corrugation spectrum linearises a growth study's passage: the config needs a [growth] section");
        return ExitCode::from(2);
    }
    let params = scene.spectrum.unwrap_or_default();
    let rails = 1 + usize::from(scene.second_rail.is_some());
    let Some(plan) = corrugation::spectrum::plan(scene, &params, rails) else {
        say!("error: spectrum.wavelength_min to _max holds no harmonic of the stretch");
        return ExitCode::from(2);
    };
    if job.parts > plan.rounds {
        say!(
            "error: --slurm {} splits {} rounds: at most one part per round (--slurm {} or fewer)",
            job.parts,
            plan.rounds,
            plan.rounds
        );
        return ExitCode::from(2);
    }
    let cost = corrugation::cost::estimate(scene);
    let absolute = |p: &Path| std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf());
    let dir = {
        let mut name = out.as_os_str().to_owned();
        name.push(".parts");
        std::path::PathBuf::from(name)
    };
    if let Err(e) = std::fs::create_dir_all(&dir) {
        say!("error: cannot create {}: {e}", dir.display());
        return ExitCode::from(2);
    }
    let (dir, config) = (absolute(&dir), absolute(config));
    let out = absolute(out.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new(".")))
        .join(out.file_name().unwrap_or_default());
    let exe = std::env::current_exe().unwrap_or_else(|_| "corrugation".into());
    let spec = SpectrumJob {
        parts: job.parts,
        cpus_per_task: job.cpus_per_task,
        estimate: plan.passage_equivalents as f64 * cost.per_passage + cost.setup * params.classes as f64,
        memory: (cost.memory * params.classes as f64).max(256e6),
    };
    let (array, merge) = (dir.join("spectrum.sbatch"), dir.join("merge.sbatch"));
    let written = std::fs::write(&array, array_script(&spec, &exe, &config, set, &dir))
        .and_then(|()| std::fs::write(&merge, merge_script(job.parts, &exe, &dir, &out)));
    if let Err(e) = written {
        say!("error: cannot write the scripts in {}: {e}", dir.display());
        return ExitCode::from(2);
    }
    say!(
        "wrote {} ({} array tasks, {} rounds, {} passages in all, about {:.0} s each on {} CPU(s)) and {}",
        array.display(),
        job.parts,
        plan.rounds,
        plan.passages,
        spec.time_limit(),
        job.cpus_per_task,
        merge.display()
    );
    if job.no_submit {
        return ExitCode::SUCCESS;
    }
    let first = match corrugation::sweep::slurm::submit(&array, &job.sbatch_args) {
        Ok(id) => id,
        Err(e) => {
            say!("error: {e}");
            return ExitCode::from(1);
        }
    };
    let mut args = job.sbatch_args.clone();
    args.push(format!("--dependency=afterok:{first}"));
    match corrugation::sweep::slurm::submit(&merge, &args) {
        Ok(id) => {
            say!("submitted the array {first} and the merge {id} (it writes {})", out.display());
            println!("{id}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            say!("error: {e} (the array {first} is submitted; merge its parts with corrugation spectrum-merge)");
            ExitCode::from(1)
        }
    }
}
