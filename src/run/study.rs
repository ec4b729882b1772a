//! The pass loop (book: docs/src/guide/checkpoints.md), with checkpoints and resume:
//!
//! ```text
//! for each simulated passage n:
//!     W_n   = passage(r_n)                  (dynamics -> contact -> wear)
//!     m_n   = traffic scaling(rho(r_n, W_n)) (fixed, or adaptive)
//!     r_n+1 = r_n - m_n W_n
//!     record rms, spectra (centre line, contact-filtered), growth rate;
//!     store / checkpoint
//! ```
//!
//! A checkpoint rewrites the whole run file atomically; it holds the
//! current profile (`rail/state`), every passage row, the stored snapshots
//! and histories, and the resolved config, which is all a resumed run
//! needs. The passage itself carries no state from one passage to the next
//! (every passage starts with a run-in from a reset solver), so a resumed
//! run computes bit for bit what the uninterrupted run would have.

use crate::build::study_grid;
use crate::config::{ConfigErrors, RecordSource, Resolved, load_str_with};
pub use crate::growth::state::RunState;
pub use crate::growth::study::Event;
use crate::growth::study::{PassageFailed, Study, initial_state};
use crate::harmonics::wavelengths;
use crate::output::checkpoint::{StateLayout, read_run_state};
use crate::output::netcdf::{NcError, read_attr_str, read_f64};
use crate::output::run_file::{RunRecord, read_record, write_run_file};
use std::path::{Path, PathBuf};

/// The largest `growth.passes` the config accepts.
const MAX_PASSES: usize = 1_000_000;

/// Why a run failed.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// The physics could not be solved.
    #[error(transparent)]
    Passage(#[from] PassageFailed),
    /// Writing the run file failed.
    #[error("{0}")]
    Output(#[from] NcError),
    /// The dynamics could not be set up (before the first passage; nothing
    /// is written).
    #[error("{0}")]
    Dynamics(#[from] crate::build::DynamicsError),
}

/// Why a run could not be resumed.
#[derive(Debug, thiserror::Error)]
pub enum ResumeError {
    /// The file cannot be opened at all (missing, unreadable).
    #[error("cannot resume from {path}: {source}")]
    Open {
        /// The file.
        path: PathBuf,
        /// Cause.
        source: std::io::Error,
    },
    /// The file could not be read as a run file.
    #[error("cannot resume from {path}: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// Cause.
        source: NcError,
    },
    /// The file is not an HDF5 file (a TOML config, say).
    #[error("cannot resume from {path}: it is not a run file (HDF5){hint}")]
    NotRunFile {
        /// The file.
        path: PathBuf,
        /// What it looks like instead.
        hint: String,
    },
    /// The config stored in the file is not valid (any more).
    #[error("cannot resume from {path}: its stored config is not valid:\n{source}")]
    Config {
        /// The file.
        path: PathBuf,
        /// The problems.
        source: ConfigErrors,
    },
    /// The file is a single-passage run.
    #[error("cannot resume from {path}: it is a single-passage run, not a growth study (no [growth] section)")]
    NotGrowth {
        /// The file.
        path: PathBuf,
    },
    /// `--passes` would take the study beyond the largest `growth.passes`.
    #[error(
        "cannot resume from {path}: --passes {more} on top of its {done} passages exceeds growth.passes <= {MAX_PASSES}"
    )]
    TooMany {
        /// The file.
        path: PathBuf,
        /// Passages in the file.
        done: usize,
        /// Passages asked for.
        more: usize,
    },
    /// The study is complete and no `--passes` asked for more: nothing to
    /// do (the file is left as it is).
    #[error(
        "{path} holds a complete study ({done} passages): nothing to do, the file is left as it is; --passes N runs N more"
    )]
    Complete {
        /// The file.
        path: PathBuf,
        /// Passages in the file.
        done: usize,
    },
    /// The resumed run failed (nothing more was written than its checkpoints).
    #[error("{0}")]
    Run(#[from] RunError),
}

/// Summary of a finished run.
#[derive(Debug, Clone)]
pub struct RunSummary {
    /// Passages in the run file.
    pub passes: usize,
    /// Passages computed by this invocation.
    pub computed: usize,
    /// CPU seconds of the passages computed by this invocation.
    pub cpu_seconds: f64,
    /// Volume removed by the last simulated passage, unscaled (m^3).
    pub removed_volume: f64,
    /// Maximum wear depth of the last simulated passage computed (m).
    pub max_wear: f64,
    /// rms corrugation of the final profile (m).
    pub rms_corrugation: f64,
    /// Real passages represented (1).
    pub traffic: f64,
    /// Largest relative profile change of an update, and its passage.
    pub max_update_ratio: (f64, usize),
    /// The bound the update ratio should stay under (1).
    pub update_bound: f64,
    /// Why the study stopped before its planned passages (`growth.stop`).
    pub stop_reason: Option<String>,
    /// Where the rail stands against the roughness limit, in words
    /// ([`crate::levels::forecast::outlook`]; empty for one passage).
    pub outlook: Vec<String>,
    /// With the wheelset's second rail: both rails' names and the second
    /// rail's last removed volume (m^3) and rms corrugation (m); the
    /// fields above are the first rail's.
    pub second_rail: Option<([String; 2], f64, f64)>,
}

/// Runs the scene (one passage, or a growth study over `growth.passes`
/// passages) and writes the run file to `out`, with checkpoints.
pub fn run_scene(resolved: &Resolved, out: &Path, progress: &mut dyn FnMut(Event)) -> Result<RunSummary, RunError> {
    continue_run(resolved, initial_state(&resolved.scene), out, progress)
}

/// Continues the growth study in the run file `path`: to the stored
/// config's `growth.passes`, or for `more` passages beyond those it holds
/// (the stored `growth.passes` becomes their sum). Writes to `out`
/// (default: `path` itself, rewritten atomically).
pub fn resume(
    path: &Path,
    more: Option<usize>,
    out: Option<&Path>,
    progress: &mut dyn FnMut(Event),
) -> Result<RunSummary, ResumeError> {
    let read = |source| ResumeError::Read { path: path.to_owned(), source };
    let mut resolved = stored_config(path, &[])?;
    let done = read_f64(path, "passes", "traffic").map_err(read)?.len();
    if let Some(more) = more {
        if done + more > MAX_PASSES {
            return Err(ResumeError::TooMany { path: path.to_owned(), done, more });
        }
        resolved = stored_config(path, &[format!("growth.passes={}", done + more)])?;
    }
    let scene = &resolved.scene;
    let Some(growth) = &scene.growth else {
        return Err(ResumeError::NotGrowth { path: path.to_owned() });
    };
    if done > growth.passes {
        let msg = format!("holds {done} passages, more than its config's growth.passes = {}", growth.passes);
        return Err(read(NcError::Invalid { path: path.to_owned(), what: "passes/pass".into(), msg }));
    }
    let complete = read_attr_str(path, "", "status").map_err(read)? == "complete";
    // Complete and nothing more asked: in place there is nothing to do (a
    // copy to another file is written as before).
    if complete && more.is_none() && out.is_none_or(|o| o == path) {
        return Err(ResumeError::Complete { path: path.to_owned(), done });
    }
    let mut state = stored_state(path, &resolved)?;
    // A snapshot stored only because the earlier run ended there is not one
    // the longer run stores.
    // (Each rail's: the second rail stores with the first.)
    let drop_end = |state: &mut RunState| {
        if growth.passes > done
            && let Some(last) = state.rail.last()
            && !(last.index as usize + 1).is_multiple_of(growth.store_every)
        {
            state.rail.pop();
        }
    };
    drop_end(&mut state);
    if let Some(second) = state.second_rail.as_deref_mut() {
        drop_end(second);
    }
    Ok(continue_run(&resolved, state, out.unwrap_or(path), progress)?)
}

/// The config a growth study's run file `path` stores, with `set`
/// overrides (a measured initial roughness from the file's own copy).
pub fn stored_config(path: &Path, set: &[String]) -> Result<Resolved, ResumeError> {
    // The file system's word for a missing or unreadable file, not the
    // HDF5 library's.
    if let Err(source) = std::fs::File::open(path) {
        return Err(ResumeError::Open { path: path.to_owned(), source });
    }
    if !crate::config::is_hdf5(path) {
        let toml = std::fs::read_to_string(path).is_ok_and(|t| t.parse::<toml::Table>().is_ok());
        let hint = if toml {
            format!(
                "; it is a TOML file, a config: `corrugation run {}` runs it (resume continues the run file a run wrote)",
                path.display()
            )
        } else {
            String::new()
        };
        return Err(ResumeError::NotRunFile { path: path.to_owned(), hint });
    }
    let read = |source| ResumeError::Read { path: path.to_owned(), source };
    let toml = read_attr_str(path, "", "config").map_err(read)?;
    let source = format!("stored in {}", path.display());
    let config_err = |source| ResumeError::Config { path: path.to_owned(), source };
    let records = match read_record(path).map_err(read)? {
        Some(r) => RecordSource::Stored(r),
        None => RecordSource::Dir(".".into()),
    };
    // A stored [wheelset] without `model` was written before `auto`
    // existed, when it meant the torsional mode (now the resolved config
    // always records it): it resumes as it ran.
    let legacy = toml
        .parse::<toml::Table>()
        .ok()
        .and_then(|t| t.get("wheelset").cloned())
        .is_some_and(|w| w.as_table().is_some_and(|w| !w.contains_key("model")));
    let mut set = set.to_vec();
    if legacy {
        set.insert(0, "wheelset.model=torsion".into());
    }
    let resolved = load_str_with(&toml, &source, &set, &records).map_err(config_err)?;
    if resolved.scene.growth.is_none() {
        return Err(ResumeError::NotGrowth { path: path.to_owned() });
    }
    Ok(resolved)
}

/// The state a growth study's run file `path` holds (its profile after
/// the passages stored, their rows, the rail snapshots), read with the
/// layout of its config `resolved` ([`stored_config`]).
pub fn stored_state(path: &Path, resolved: &Resolved) -> Result<RunState, ResumeError> {
    let read = |source| ResumeError::Read { path: path.to_owned(), source };
    let scene = &resolved.scene;
    let Some(growth) = &scene.growth else {
        return Err(ResumeError::NotGrowth { path: path.to_owned() });
    };
    let grid = study_grid(scene);
    let layout = StateLayout {
        grid_shape: (grid.ny, grid.nx),
        wavelengths: wavelengths(grid.nx, grid.dx).len(),
        bands: crate::levels::resolved_bands(scene.levels.bands, grid.nx, grid.dx).len(),
        elements: scene.contact.model.elements(scene),
        fields: scene.output.store_fields,
        history_passes: &growth.contact_history,
        classes: growth.classes.len(),
        class_wheels: growth
            .classes
            .iter()
            .map(|c| c.wheels.as_ref().map_or(scene.vehicle.wheels.len(), Vec::len))
            .collect(),
        second_rail: scene.second_rail.is_some(),
    };
    read_run_state(path, &layout).map_err(read)
}

/// Runs the passages from `state.rows.len()` to the planned number, with
/// checkpoints, and writes the run file.
fn continue_run(
    resolved: &Resolved,
    state: RunState,
    out: &Path,
    progress: &mut dyn FnMut(Event),
) -> Result<RunSummary, RunError> {
    let scene = &resolved.scene;
    let mut study = Study::new(scene, state)?;
    let write = |study: &Study| {
        let title = if scene.output.title.is_empty() { "corrugation run" } else { scene.output.title.as_str() };
        let record = RunRecord {
            title,
            contact_model: scene.contact.model.name(),
            config: &resolved.toml,
            grid: study.grid(),
            elements: study.elements(),
            mean_patch: study.mean_patch(),
            wavelengths: study.wavelengths(),
            state: study.state(),
            passes_planned: study.passes(),
            stop_reason: study.stopped(),
            classes: study.classes(),
            record: match scene.growth.as_ref().map(|g| &g.roughness) {
                Some(crate::params::Roughness::Measured(m)) => Some(&m.samples),
                _ => None,
            },
            bands: study.bands().0,
            limit: study.bands().1,
            limit_name: &scene.levels.limit.name,
            operation: scene.growth.as_ref().map(|g| &g.operation),
            rail_names: scene.second_rail.as_ref().map(|r| &r.names),
            wear_regimes: scene.wear.regimes(),
        };
        write_run_file(out, &record)
    };
    let (mut cpu_seconds, mut max_wear) = (0.0, 0.0);
    while let Some(pass) = study.next_pass() {
        let Some(done) = study.advance(progress)? else { break };
        cpu_seconds += done.cpu_seconds;
        max_wear = done.max_wear;
        if let Some(g) = &scene.growth
            && (pass + 1) % g.checkpoint_every == 0
            && pass + 1 < study.passes()
            && study.stopped().is_none()
        {
            progress(Event::Writing { done: pass + 1 });
            write(&study)?;
            progress(Event::Checkpoint { done: pass + 1 });
        }
    }
    progress(Event::Writing { done: study.state().rows.len() });
    write(&study)?;
    let rows = &study.state().rows;
    // Each rail's standing, named where the wheelset has two.
    let standing = |state: &RunState| match &scene.growth {
        Some(g) => {
            let (bands, limit) = study.bands();
            let rows = &state.rows;
            let levels: Vec<Vec<f64>> = rows.iter().map(|r| r.roughness_level.clone()).collect();
            let rates: Vec<Vec<f64>> = rows.iter().map(|r| r.level_rate.clone()).collect();
            let forced: Vec<Vec<f64>> = rows.iter().map(|r| r.forced_band_wear.clone()).collect();
            let traffic: Vec<f64> = rows.iter().map(|r| r.traffic).collect();
            let shares: Vec<f64> = study.classes().iter().map(|c| c.share).collect();
            let grew_rates: Vec<&[f64]> = rows.iter().map(|r| r.growth_rate.as_slice()).collect();
            let first = rows.first().map_or(&[][..], |r| r.filtered_spectrum.as_slice());
            let grew = crate::harmonics::what_grew(first, &grew_rates, study.wavelengths(), 3);
            let mut lines: Vec<String> = grew.into_iter().collect();
            lines.extend(crate::levels::forecast::outlook(&crate::levels::forecast::Standing {
                bands,
                limit,
                limit_name: &scene.levels.limit.name,
                initial: &state.initial_level,
                levels: &levels,
                rates: &rates,
                forced: &forced,
                traffic: &traffic,
                units: g.operation.units(&shares),
            }));
            lines
        }
        None => Vec::new(),
    };
    let outlook = match (study.state().second_rail.as_deref(), scene.second_rail.as_ref()) {
        (Some(second), Some(r)) => {
            let named = |name: &String, lines: Vec<String>| -> Vec<String> {
                lines.into_iter().map(|l| format!("{name}: {l}")).collect()
            };
            let mut lines = named(&r.names[0], standing(study.state()));
            lines.extend(named(&r.names[1], standing(second)));
            lines
        }
        _ => standing(study.state()),
    };
    Ok(RunSummary {
        passes: rows.len(),
        computed: rows.len() - study.first(),
        cpu_seconds,
        removed_volume: rows.last().map_or(0.0, |r| r.removed_volume),
        max_wear,
        rms_corrugation: rows.last().map_or_else(
            || crate::metrics::rms_corrugation(study.state().profile.view(), study.grid()),
            |r| r.rms_corrugation,
        ),
        traffic: rows.last().map_or(0.0, |r| r.traffic),
        max_update_ratio: rows
            .iter()
            .map(|r| (r.update_ratio, r.index as usize))
            .fold((0.0, 0), |a, b| if b.0 > a.0 { b } else { a }),
        update_bound: study.update_bound(),
        stop_reason: study.stopped().map(str::to_owned),
        outlook,
        second_rail: study.state().second_rail.as_deref().zip(scene.second_rail.as_ref()).map(|(state, r)| {
            let last = state.rows.last();
            (
                r.names.clone(),
                last.map_or(0.0, |x| x.removed_volume),
                last.map_or_else(
                    || crate::metrics::rms_corrugation(state.profile.view(), study.grid()),
                    |x| x.rms_corrugation,
                ),
            )
        }),
    })
}
