//! The pass loop (README: Growth studies), with checkpoints and resume:
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

use super::hertz_check::HertzCheck;
use super::{build_deposit, build_solver, derive, element_count, study_grid, track_dynamics};
use crate::config::contact::{PROFILE_NOISE_AMPLITUDE, PROFILE_NOISE_ELEMENT};
use crate::config::{ConfigErrors, Resolved, load_str};
use crate::dynamics::TrackDynamics;
use crate::growth::mix::{TrafficClass, next_class, tally};
use crate::growth::roughness::profile_line;
use crate::growth::spectrum::{amplitudes, growth_rates, wavelengths};
use crate::growth::traffic::{TrafficScaling, change_rate};
use crate::growth::{contact_filtered_line, growth_passage};
use crate::metrics::{centre_row, rms_corrugation};
use crate::output::checkpoint::{StateLayout, read_run_state};
use crate::output::netcdf::{NcError, read_attr_str, read_f64};
pub use crate::output::run_file::RunState;
use crate::output::run_file::{PassRow, RailSnapshot, RunRecord, write_run_file};
use crate::params::NormalContact;
use crate::passage::{PassageError, PassageSpec, run_passage};
use ndarray::Array2;
use std::path::{Path, PathBuf};

/// The largest `growth.passes` the config accepts.
const MAX_PASSES: usize = 1_000_000;

/// What a run reports while it goes.
#[derive(Debug, Clone, PartialEq)]
pub enum Event {
    /// Contact steps done, of the steps this invocation computes.
    Steps {
        /// Steps done.
        done: usize,
        /// Steps in all.
        total: usize,
    },
    /// A passage finished.
    Passage {
        /// Passages done (all, including those before a resume).
        done: usize,
        /// Passages the run will have.
        total: usize,
        /// Real passages represented so far (1).
        traffic: f64,
        /// Real passages this one stood for (1).
        scale: f64,
        /// rms corrugation after it (m).
        rms: f64,
        /// Relative profile change of its update (1).
        update_ratio: f64,
        /// Its traffic class, in a mixed-traffic study.
        class: Option<String>,
    },
    /// What the run did (not a problem).
    Note {
        /// Simulated passage index (0-based).
        pass: usize,
        /// What happened.
        message: String,
    },
    /// Something the user must know about a passage's results.
    Warning {
        /// Simulated passage index (0-based).
        pass: usize,
        /// What happened.
        message: String,
    },
    /// The study stopped after this passage (`growth.stop`).
    Stopped {
        /// Simulated passage index (0-based).
        pass: usize,
        /// Why.
        reason: String,
    },
    /// The run file was rewritten after `done` passages.
    Checkpoint {
        /// Passages in the file.
        done: usize,
    },
}

/// Why a run failed.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// The physics could not be solved.
    #[error("passage {pass} failed: {source}")]
    Passage {
        /// Simulated passage index.
        pass: usize,
        /// Cause.
        source: PassageError,
    },
    /// Writing the run file failed.
    #[error("{0}")]
    Output(#[from] NcError),
}

/// Why a run could not be resumed.
#[derive(Debug, thiserror::Error)]
pub enum ResumeError {
    /// The file could not be read as a run file.
    #[error("cannot resume from {path}: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// Cause.
        source: NcError,
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
}

/// Runs the scene (one passage, or a growth study over `growth.passes`
/// passages) and writes the run file to `out`, with checkpoints.
pub fn run_scene(resolved: &Resolved, out: &Path, progress: &mut dyn FnMut(Event)) -> Result<RunSummary, RunError> {
    let scene = &resolved.scene;
    let grid = study_grid(scene);
    let profile = match &scene.growth {
        Some(g) => {
            let line = profile_line(&g.roughness, &grid.xs(), grid.nx as f64 * grid.dx);
            Array2::from_shape_fn((grid.ny, grid.nx), |(_, i)| line[i])
        }
        None => Array2::zeros((grid.ny, grid.nx)),
    };
    let state = RunState { profile, rows: Vec::new(), rail: Vec::new(), histories: Vec::new() };
    continue_run(resolved, state, out, progress)
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
    let toml = read_attr_str(path, "", "config").map_err(read)?;
    let source = format!("stored in {}", path.display());
    let config_err = |source| ResumeError::Config { path: path.to_owned(), source };
    let mut resolved = load_str(&toml, &source, &[]).map_err(config_err)?;
    if resolved.scene.growth.is_none() {
        return Err(ResumeError::NotGrowth { path: path.to_owned() });
    }
    let done = read_f64(path, "passes", "traffic").map_err(read)?.len();
    if let Some(more) = more {
        if done + more > MAX_PASSES {
            return Err(ResumeError::TooMany { path: path.to_owned(), done, more });
        }
        resolved = load_str(&toml, &source, &[format!("growth.passes={}", done + more)]).map_err(config_err)?;
    }
    let scene = &resolved.scene;
    let Some(growth) = &scene.growth else {
        return Err(ResumeError::NotGrowth { path: path.to_owned() });
    };
    let grid = study_grid(scene);
    let elements = element_count(scene);
    let layout = StateLayout {
        grid_shape: (grid.ny, grid.nx),
        wavelengths: wavelengths(grid.nx, grid.dx).len(),
        elements,
        fields: scene.output.store_fields,
        history_passes: &growth.contact_history,
        classes: growth.classes.len(),
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
    let mut state = read_run_state(path, &layout).map_err(read)?;
    // A snapshot stored only because the earlier run ended there is not one
    // the longer run stores.
    if growth.passes > done
        && let Some(last) = state.rail.last()
        && !(last.index as usize + 1).is_multiple_of(growth.store_every)
    {
        state.rail.pop();
    }
    Ok(continue_run(&resolved, state, out.unwrap_or(path), progress)?)
}

/// Runs the passages from `state.rows.len()` to the planned number, with
/// checkpoints, and writes the run file.
fn continue_run(
    resolved: &Resolved,
    mut state: RunState,
    out: &Path,
    progress: &mut dyn FnMut(Event),
) -> Result<RunSummary, RunError> {
    let scene = &resolved.scene;
    let d = derive(scene);
    // One solver for every traffic class: its grid is sized for the largest
    // load of any class, and the speed and loads come with each step.
    let mut solver = build_solver(scene, &d.shape);
    let elements = solver.elements();
    let deposit = build_deposit(&elements);
    let growth = scene.growth.as_ref();
    let grid = study_grid(scene);
    let passes = growth.map_or(1, |g| g.passes);
    let scaling = growth.map_or(TrafficScaling::Fixed { scale: 1.0, max_update_ratio: 1.0 }, |g| g.traffic);
    // Each class's passage (speed, mean loads) and track dynamics (speed,
    // contact spring at its load, unsprung mass).
    let classes: Vec<TrafficClass> = growth.map_or_else(Vec::new, |g| g.classes.clone());
    let shares: Vec<f64> = classes.iter().map(|c| c.share).collect();
    let class_models: Vec<(PassageSpec, Option<Box<dyn TrackDynamics>>)> = classes
        .iter()
        .map(|c| {
            let cs = scene.for_class(c);
            let cd = derive(&cs);
            let dynamics = track_dynamics(&cs, &cd);
            (cd.passage, dynamics)
        })
        .collect();
    let has_dynamics = class_models.iter().any(|(_, dy)| dy.is_some());
    let steps = d.passage.n_steps();
    let first = state.rows.len();
    let waves = wavelengths(grid.nx, grid.dx);
    let centre = centre_row(&grid);
    let line = |p: &Array2<f64>| p.row(centre).to_vec();
    // What the wheel sees: the profile weighted across the mean patch width.
    // The mean patch: of the mean load, or under mixed traffic the classes'
    // patches weighted by their shares (one line for every passage, so that
    // growth rates compare across passages of different classes).
    let mean_patch = if classes.is_empty() {
        (d.patch_mean.a, d.patch_mean.b)
    } else {
        classes.iter().fold((0.0, 0.0), |(a, b), c| {
            let p = d.shape.patch(c.normal_force).expect("validated loads keep N > 0");
            (a + c.share * p.a, b + c.share * p.b)
        })
    };
    let filtered = |p: &Array2<f64>| contact_filtered_line(p, &grid, mean_patch.1);
    let write = |state: &RunState, stop_reason: Option<&str>| {
        let title = if scene.output.title.is_empty() { "corrugation run" } else { scene.output.title.as_str() };
        let record = RunRecord {
            title,
            contact_model: scene.contact.model.name(),
            config: &resolved.toml,
            grid: &grid,
            elements: &elements,
            mean_patch,
            wavelengths: &waves,
            state,
            passes_planned: passes,
            stop_reason,
            classes: &classes,
        };
        write_run_file(out, &record)
    };
    let mut summary = RunSummary {
        passes,
        computed: passes - first,
        cpu_seconds: 0.0,
        removed_volume: state.rows.last().map_or(0.0, |r| r.removed_volume),
        max_wear: 0.0,
        rms_corrugation: rms_corrugation(state.profile.view(), &grid),
        traffic: state.rows.last().map_or(0.0, |r| r.traffic),
        max_update_ratio: (0.0, 0),
        update_bound: scaling.max_update_ratio(),
        stop_reason: None,
    };
    let fixed_grid = matches!(scene.contact.grid, crate::params::ContactGrid::Fixed(_));
    let mut hertz_check = HertzCheck {
        active: scene.contact.normal == NormalContact::Hertz && has_dynamics,
        fixed: fixed_grid,
        from: match scene.contact.grid {
            crate::params::ContactGrid::Fixed(f) => PROFILE_NOISE_AMPLITUDE * f.dx / PROFILE_NOISE_ELEMENT,
            crate::params::ContactGrid::Adapted => PROFILE_NOISE_AMPLITUDE,
        },
    };
    // A study that stopped (growth.stop) stays stopped when resumed: the rule
    // reads the stored rows.
    let mut stopped = stop_reason(growth, &state.rows);
    // Each class's forced wear (below), from its first passage here on.
    let mut forced: Vec<Option<Vec<f64>>> = vec![None; class_models.len()];
    for pass in first..passes {
        if stopped.is_some() {
            break;
        }
        // The class of this passage: the one furthest behind its share.
        let class = match classes.len() {
            0 | 1 => 0,
            n => next_class(&shares, &tally(n, state.rows.iter().map(|r| (r.traffic_class, r.traffic_scale)))),
        };
        let keep_history = growth.is_none_or(|g| g.contact_history.contains(&pass));
        let record_fields = keep_history && scene.output.store_fields;
        // What the normal contact of this passage sees of the rail: the
        // consistent chain's is the linear contact on the adapted mesh and
        // the nonlinear profile contact on the fixed grid.
        let normal = match scene.contact.normal {
            NormalContact::Auto { .. } if !fixed_grid => NormalContact::Linear,
            normal => normal,
        };
        let clock = cpu_time::ProcessTime::now();
        let total_steps = (passes - first) * steps;
        let mut report =
            |done: usize, _: usize| progress(Event::Steps { done: (pass - first) * steps + done, total: total_steps });
        let (mut loss, mut clipped, mut linear_filter) = (0, 0, false);
        let fallbacks;
        let (wear, history) = match growth {
            None => {
                let r = run_passage(
                    &d.passage,
                    &d.shape,
                    solver.as_mut(),
                    deposit.as_ref(),
                    &grid,
                    record_fields,
                    &mut report,
                )
                .map_err(|source| RunError::Passage { pass, source })?;
                fallbacks = r.fallback_steps;
                (r.wear, r.history)
            }
            Some(_) => {
                let (class_passage, class_dynamics) = &class_models[class];
                let mut passage = |profile: &Array2<f64>, record: bool, report: &mut dyn FnMut(usize, usize)| {
                    growth_passage(
                        class_passage,
                        &d.shape,
                        solver.as_mut(),
                        deposit.as_ref(),
                        &grid,
                        profile,
                        normal,
                        class_dynamics.as_deref(),
                        record,
                        report,
                    )
                };
                let g = passage(&state.profile, record_fields, &mut report);
                // At saturation the dynamic force may take N below F_x / mu:
                // the prescribed force can no longer be transmitted, the
                // end of what the model describes; the study stops there.
                let g = match g {
                    Err(source) if sliding_stops(growth, &source) => {
                        let reason = format!("full sliding in passage {}: {source}", pass + 1);
                        progress(Event::Stopped { pass, reason: reason.clone() });
                        stopped = Some(reason);
                        break;
                    }
                    g => g.map_err(|source| RunError::Passage { pass, source })?,
                };
                loss = g.contact_loss_steps;
                clipped = g.clipped_steps;
                linear_filter = g.linear_filter;
                if clipped > 0 {
                    progress(Event::Warning {
                        pass,
                        message: format!(
                            "the linear profile contact's patch opened inside (the pressure vanished well inside \
                             the patch) at {clipped} steps: the corrugation is beyond the linearisation's range \
                             (the nonlinear profile contact needs contact.grid = \"fixed\")"
                        ),
                    });
                }
                if g.contact_loss_steps > 0 {
                    progress(Event::Warning {
                        pass,
                        message: format!(
                            "the wheel left the rail at {} of the stretch's steps (N <= 0): the linear track model \
                             is not valid there, and the growth this passage drives is not reliable",
                            g.contact_loss_steps
                        ),
                    });
                }
                fallbacks = g.passage.fallback_steps;
                // The wear one passage of this class leaves on the smooth
                // rail, where its track forces a dynamic force there (the
                // discrete supports' parametric excitation): it does not
                // depend on the profile, the update integrates it exactly,
                // and the update bound counts the rest (growth::traffic).
                // Computed at the class's first passage of this invocation.
                if forced[class].is_none() && class_dynamics.as_deref().is_some_and(|dy| dy.forces_smooth_rail()) {
                    let smooth = Array2::zeros(state.profile.raw_dim());
                    let w0 =
                        passage(&smooth, false, &mut |_, _| {}).map_err(|source| RunError::Passage { pass, source })?;
                    forced[class] = Some(line(&w0.wear));
                }
                (g.wear, g.passage.history)
            }
        };
        if fallbacks > 0 {
            progress(Event::Warning {
                pass,
                message: format!(
                    "the fixed grid's CG solver did not converge at {fallbacks} steps, which Gauss-Seidel solved \
                     (same equations; set contact.solver = \"gauss-seidel\" to use it throughout)"
                ),
            });
        }
        let cpu_seconds = clock.elapsed().as_secs_f64();
        // With imposed dynamics the wear does not depend on the profile: the
        // update is exact for any m (growth::traffic).
        let class_dynamics = class_models.get(class).is_some_and(|(_, dy)| dy.is_some());
        let rho = if class_dynamics {
            let mut w = line(&wear);
            if let Some(w0) = forced.get(class).and_then(Option::as_ref) {
                w.iter_mut().zip(w0).for_each(|(w, f)| *w -= f);
            }
            change_rate(&line(&state.profile), &w)
        } else {
            0.0
        };
        let previous = state.rows.last();
        // The adaptive m rises from the last m of the same class: classes
        // whose wear changes the profile faster keep a smaller m.
        let previous_scale = state.rows.iter().rev().find(|r| r.traffic_class == class).map(|r| r.traffic_scale);
        let m = scaling.scale(previous_scale, rho);
        let before = match previous {
            Some(r) => r.filtered_spectrum.clone(),
            None => amplitudes(&filtered(&state.profile)),
        };
        let traffic = previous.map_or(0.0, |r| r.traffic) + m;
        state.profile.scaled_add(-m, &wear);
        let spectrum = amplitudes(&line(&state.profile));
        let filtered_spectrum = amplitudes(&filtered(&state.profile));
        if let Some(message) = hertz_check.check(&waves, &filtered_spectrum) {
            progress(Event::Warning { pass, message });
        }
        let row = PassRow {
            index: pass as i64,
            traffic,
            traffic_scale: m,
            rms_corrugation: rms_corrugation(state.profile.view(), &grid),
            removed_volume: wear.sum() * grid.dx * grid.dy,
            cpu_seconds,
            update_ratio: m * rho,
            traffic_class: class,
            contact_loss_steps: loss as f64,
            profile_contact: match normal {
                NormalContact::Hertz => 0.0,
                NormalContact::Linear => PROFILE_LINEAR,
                _ if linear_filter => PROFILE_LINEAR_FILTER,
                _ => PROFILE_NONLINEAR,
            },
            clipped_steps: clipped as f64,
            // Below 1e-12 m (1 pm) an amplitude is numerical noise.
            growth_rate: growth_rates(&before, &filtered_spectrum, m, 1e-12),
            spectrum,
            filtered_spectrum,
        };
        progress(Event::Passage {
            done: pass + 1,
            total: passes,
            traffic,
            scale: m,
            rms: row.rms_corrugation,
            update_ratio: row.update_ratio,
            class: (classes.len() > 1).then(|| classes[class].name.clone()),
        });
        summary.cpu_seconds += cpu_seconds;
        summary.removed_volume = row.removed_volume;
        summary.max_wear = wear.iter().cloned().fold(0.0, f64::max);
        summary.rms_corrugation = row.rms_corrugation;
        summary.traffic = traffic;
        let store_every = growth.map_or(1, |g| g.store_every);
        if (pass + 1) % store_every == 0 || pass + 1 == passes {
            state.rail.push(RailSnapshot { index: pass as i64, traffic, profile: state.profile.clone(), wear });
        }
        if keep_history {
            state.histories.push((pass as i64, history));
        }
        state.rows.push(row);
        stopped = stop_reason(growth, &state.rows);
        if let Some(reason) = &stopped {
            progress(Event::Stopped { pass, reason: reason.clone() });
        }
        if let Some(g) = growth
            && (pass + 1) % g.checkpoint_every == 0
            && pass + 1 < passes
            && stopped.is_none()
        {
            write(&state, None)?;
            progress(Event::Checkpoint { done: pass + 1 });
        }
    }
    write(&state, stopped.as_deref())?;
    summary.passes = state.rows.len();
    summary.computed = state.rows.len() - first;
    summary.stop_reason = stopped;
    summary.max_update_ratio = state
        .rows
        .iter()
        .map(|r| (r.update_ratio, r.index as usize))
        .fold((0.0, 0), |a, b| if b.0 > a.0 { b } else { a });
    Ok(summary)
}

/// Why a growth study stops after its last row, by its `growth.stop` rule.
fn stop_reason(growth: Option<&crate::params::GrowthParams>, rows: &[PassRow]) -> Option<String> {
    let crate::params::StopRule::Saturation { rate } = growth?.stop else {
        return None;
    };
    let last = rows.last()?;
    let rms: Vec<f64> = rows.iter().map(|r| r.rms_corrugation).collect();
    let traffic: Vec<f64> = rows.iter().map(|r| r.traffic).collect();
    crate::growth::stop::saturation(&rms, &traffic, last.contact_loss_steps, rate)
}

/// `passes/profile_contact` of a passage in the nonlinear profile contact
/// with the dynamics of its nonlinear equivalent roughness.
const PROFILE_NONLINEAR: f64 = 1.0;
/// `passes/profile_contact` of a passage in the linear profile contact.
const PROFILE_LINEAR: f64 = 2.0;
/// `passes/profile_contact` of a passage in the nonlinear profile contact
/// with the dynamics of the linear contact's equivalent roughness.
const PROFILE_LINEAR_FILTER: f64 = 3.0;

/// Whether a passage that failed with `e` ends a study that stops at
/// saturation: the prescribed longitudinal force reached the friction limit
/// (full sliding), which the growing dynamic force brings about before the
/// wheel leaves the rail.
fn sliding_stops(growth: Option<&crate::params::GrowthParams>, e: &PassageError) -> bool {
    matches!(growth.map(|g| g.stop), Some(crate::params::StopRule::Saturation { .. }))
        && matches!(
            e,
            PassageError::Tangential { source: crate::contact::ContactError::ForceExceedsFriction { .. }, .. }
        )
}
