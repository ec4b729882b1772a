//! The growth loop as a type (book: docs/src/theory/growth-loop.md): one simulated
//! passage at a time,
//!
//! ```text
//! for each simulated passage n:
//!     class = the traffic class furthest behind its share
//!     W_n   = passage(r_n)                   (dynamics -> contact -> wear)
//!     m_n   = traffic scaling(rho(r_n, W_n))  (fixed, or adaptive)
//!     r_n+1 = r_n - m_n W_n
//!     record rms, spectra (centre line, contact-filtered), growth rate;
//!     stop rule
//! ```
//!
//! [`Study::advance`] does one passage and appends its row to the
//! [`RunState`]; the caller ([`crate::run`]) keeps the checkpoints, the
//! file and the terminal. A single passage is the study of one passage
//! without a profile. The passage carries no state from one passage to the
//! next (every passage starts with a run-in from a reset solver), so a
//! study continued from a stored state computes bit for bit what the
//! uninterrupted study would have.

use super::RailPass;
use super::hertz_check::HertzCheck;
use super::mix::{next_class, tally};
use super::roughness::profile_line;
use super::row::RowKeep;
use super::state::RunState;
use super::stop::rails_stop_reason;
use super::traffic::change_rate;
use super::wear_map::WearMap;
use crate::build::{DynamicsError, study_grid};
use crate::contact::{ContactError, Elements};
use crate::harmonics::wavelengths;
use crate::levels::{BandLevels, level_rates};
use crate::metrics::centre_row;
use crate::model_choice::hertz_validity::{PROFILE_NOISE_AMPLITUDE, PROFILE_NOISE_ELEMENT};
use crate::params::{GrowthParams, NormalContact, Scene, StopRule, TrafficClass, TrafficScaling};
use crate::passage::PassageError;
use crate::rail_grid::RailGrid;
use ndarray::Array2;

/// What a study reports while it goes.
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
        /// rms corrugation after it (m): the first rail's.
        rms: f64,
        /// With the wheelset's second rail: the first rail's name, the
        /// second's, and the second's rms corrugation after it (m).
        second_rail: Option<(String, String, f64)>,
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
    /// The run file is about to be rewritten with `done` passages
    /// (reported by the run, which keeps the file; a `Checkpoint` follows a
    /// checkpoint's write).
    Writing {
        /// Passages the file will hold.
        done: usize,
    },
    /// The run file was rewritten after `done` passages (reported by the
    /// run, which keeps the file).
    Checkpoint {
        /// Passages in the file.
        done: usize,
    },
}

/// A passage whose physics could not be solved.
#[derive(Debug, thiserror::Error)]
#[error("passage {pass} failed: {source}")]
pub struct PassageFailed {
    /// Simulated passage index.
    pub pass: usize,
    /// Cause.
    pub source: PassageError,
}

/// What one passage left besides its row.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Advanced {
    /// CPU seconds of the passage.
    pub cpu_seconds: f64,
    /// Maximum wear depth of the passage, unscaled (m).
    pub max_wear: f64,
}

/// A growth study (or a single passage) in progress: the scene's kernels,
/// built once, and the state after the passages done.
pub struct Study<'a> {
    scene: &'a Scene,
    growth: Option<&'a GrowthParams>,
    /// The passage's wear as a function of the rails, per traffic class.
    map: WearMap,
    elements: Elements,
    grid: RailGrid,
    passes: usize,
    scaling: TrafficScaling,
    classes: Vec<TrafficClass>,
    shares: Vec<f64>,
    waves: Vec<f64>,
    centre: usize,
    mean_patch: (f64, f64),
    hertz_check: HertzCheck,
    /// Passages in the state when the study was built.
    first: usize,
    stopped: Option<String>,
    state: RunState,
    /// The band levels of the profile, and each band's limit (dB re 1 um).
    levels: BandLevels,
    limit: Vec<f64>,
}

/// The initial state of a scene: the profile of its roughness (none for a
/// single passage), no passages done.
pub fn initial_state(scene: &Scene) -> RunState {
    let grid = study_grid(scene);
    let second_rail = scene.second_rail_scene().map(|second| Box::new(initial_state(&second)));
    let profile = match &scene.growth {
        Some(g) => {
            let line = profile_line(&g.roughness, &grid.xs(), grid.nx as f64 * grid.dx);
            Array2::from_shape_fn((grid.ny, grid.nx), |(_, i)| line[i])
        }
        None => Array2::zeros((grid.ny, grid.nx)),
    };
    RunState {
        profile,
        rows: Vec::new(),
        rail: Vec::new(),
        histories: Vec::new(),
        wheel_histories: Vec::new(),
        initial_level: Vec::new(),
        second_rail,
    }
}

/// The band levels of a study of `scene` on `grid` whose mean patch has
/// the lateral semi-axis `b` (m): the lines of its running band.
fn band_levels(scene: &Scene, grid: &RailGrid, b: f64) -> (BandLevels, Vec<f64>) {
    let levels = BandLevels::new(scene.levels.bands, grid, b);
    let limit = scene.levels.limit.on(levels.bands());
    (levels, limit)
}

/// Fills in the levels of a state read from a run file written before the
/// roughness levels existed: each passage's from its centre-line spectrum
/// (`passes/spectrum`), the rates between them (the first passage's 0), and
/// the initial levels as the first passage's.
fn fill_legacy_levels(state: &mut RunState, levels: &BandLevels) {
    let mut before: Option<Vec<f64>> = None;
    for row in &mut state.rows {
        row.roughness_level = levels.levels_of_spectrum(&row.spectrum);
        let previous = before.take().unwrap_or_else(|| row.roughness_level.clone());
        row.level_rate = level_rates(&previous, &row.roughness_level, row.traffic_scale);
        before = Some(row.roughness_level.clone());
    }
    state.initial_level = state.rows.first().map_or_else(Vec::new, |r| r.roughness_level.clone());
}

impl<'a> Study<'a> {
    /// The study of `scene` continuing from `state`. One solver serves every
    /// traffic class: its grid is sized for the largest load of any class,
    /// and the speed and loads come with each step. Fails where the
    /// dynamics in every direction cannot be set up (before any passage).
    pub fn new(scene: &'a Scene, mut state: RunState) -> Result<Self, DynamicsError> {
        let growth = scene.growth.as_ref();
        let grid = study_grid(scene);
        let classes: Vec<TrafficClass> = growth.map_or_else(Vec::new, |g| g.classes.clone());
        let map = WearMap::new(scene, &classes)?;
        let elements = map.elements();
        let d = map.derived();
        let has_dynamics = (0..classes.len()).any(|c| map.dynamics(c).is_some());
        // What the wheel sees: the profile weighted across the mean patch
        // width. The mean patch: of the mean load, or under mixed traffic
        // the classes' patches weighted by their shares (one line for every
        // passage, so that growth rates compare across passages of
        // different classes).
        let mean_patch = super::mean_patch(scene, &d.shape);
        let hertz_check = HertzCheck {
            active: scene.contact.normal == NormalContact::Hertz && has_dynamics,
            fixed: scene.contact.model.fixed_grid().is_some(),
            from: match scene.contact.model.fixed_grid() {
                Some(f) => PROFILE_NOISE_AMPLITUDE * f.dx / PROFILE_NOISE_ELEMENT,
                None => PROFILE_NOISE_AMPLITUDE,
            },
        };
        // The rail's band levels over the running band of the mean patch.
        let (levels, limit) = band_levels(scene, &grid, mean_patch.1);
        let fill = |state: &mut RunState| {
            if state.initial_level.is_empty() {
                if state.rows.is_empty() {
                    state.initial_level = levels.levels(&state.profile);
                } else {
                    fill_legacy_levels(state, &levels);
                }
            }
        };
        fill(&mut state);
        if let Some(second) = state.second_rail.as_deref_mut() {
            fill(second);
        }
        // A study that stopped (growth.stop) stays stopped when resumed: the
        // rule reads the stored rows.
        let stopped = rails_stop_reason(scene, &state, &levels, &limit);
        Ok(Study {
            scene,
            growth,
            elements,
            passes: growth.map_or(1, |g| g.passes),
            scaling: growth.map_or(TrafficScaling::Fixed { scale: 1.0, max_update_ratio: 1.0 }, |g| g.traffic),
            shares: classes.iter().map(|c| c.share).collect(),
            classes,
            waves: wavelengths(grid.nx, grid.dx),
            centre: centre_row(&grid),
            grid,
            mean_patch,
            hertz_check,
            first: state.rows.len(),
            stopped,
            state,
            map,
            levels,
            limit,
        })
    }

    /// The passage `advance` computes next, if the study goes on.
    pub fn next_pass(&self) -> Option<usize> {
        let done = self.state.rows.len();
        (self.stopped.is_none() && done < self.passes).then_some(done)
    }

    /// Runs the next passage and updates the profile: appends its row (and
    /// its rail snapshot and patch history where the study stores them).
    /// `Ok(None)` when the passage ended the study instead (full sliding at
    /// saturation; [`Study::stopped`] says why), or the study had ended
    /// already ([`Study::next_pass`] is `None`).
    pub fn advance(&mut self, progress: &mut dyn FnMut(Event)) -> Result<Option<Advanced>, PassageFailed> {
        let Some(pass) = self.next_pass() else { return Ok(None) };
        let fail = |source| PassageFailed { pass, source };
        let scene = self.scene;
        let growth = self.growth;
        let line = |p: &Array2<f64>| p.row(self.centre).to_vec();
        // The class of this passage: the one furthest behind its share.
        let class = match self.classes.len() {
            0 | 1 => 0,
            n => {
                next_class(&self.shares, &tally(n, self.state.rows.iter().map(|r| (r.traffic_class, r.traffic_scale))))
            }
        };
        let keep_history = growth.is_none_or(|g| g.contact_history.contains(&pass));
        let record_fields = keep_history && scene.output.store_fields;
        let normal = self.map.normal();
        let clock = cpu_time::ProcessTime::now();
        // Progress in units of the longest passage of any class: this
        // passage's own steps (its class's run-in and wheels) scaled to it.
        let steps = self.steps_per_passage();
        let (first, passes) = (self.first, self.passes);
        let total_steps = (passes - first) * steps;
        let mut report = |done: usize, total: usize| {
            let scaled = (done * steps).checked_div(total).unwrap_or(0);
            progress(Event::Steps { done: (pass - first) * steps + scaled, total: total_steps })
        };
        let mut linear_contact = false;
        let fallbacks;
        let rails: Vec<RailPass> = match growth {
            None => {
                let mut r = self.map.single(record_fields, &mut report).map_err(fail)?;
                fallbacks = r.fallback_steps;
                let wear = std::mem::take(&mut r.wear);
                vec![RailPass {
                    leading: r,
                    wheel_histories: Vec::new(),
                    wear,
                    dynamic_force: Vec::new(),
                    contact_loss_steps: 0,
                    clipped_steps: 0,
                }]
            }
            Some(_) => {
                let profiles: Vec<&Array2<f64>> = std::iter::once(&self.state.profile)
                    .chain(self.state.second_rail.as_ref().map(|s| &s.profile))
                    .collect();
                let g = self.map.passage(class, &profiles, record_fields, &mut report);
                // At saturation the dynamic force may take N below F_x / mu:
                // the prescribed force can no longer be transmitted, the end
                // of what the model describes; the study stops there.
                let g = match g {
                    Err(source) if sliding_stops(growth, &source) => {
                        let reason = format!("full sliding in passage {}: {source}", pass + 1);
                        progress(Event::Stopped { pass, reason: reason.clone() });
                        self.stopped = Some(reason);
                        return Ok(None);
                    }
                    g => g.map_err(fail)?,
                };
                linear_contact = g.linear_contact;
                let names = self.scene.second_rail.as_ref().map(|r| r.names.clone());
                let on = |k: usize| names.as_ref().map_or_else(String::new, |n| format!(" (the {})", n[k]));
                let clipped = g.rails.iter().enumerate().map(|(k, r)| (r.clipped_steps, on(k)));
                for (steps, rail) in clipped.filter(|(c, _)| *c > 0) {
                    progress(Event::Warning {
                        pass,
                        message: format!(
                            "the linear profile contact's patch opened inside (the pressure vanished well inside \
                             the patch) at {steps} steps{rail}: the corrugation is beyond the linearisation's range \
                             (contact.normal = \"profile\", the nonlinear profile contact of the fixed grid, \
                             solves it)"
                        ),
                    });
                }
                if let Some(reason) = &g.rerun {
                    progress(Event::Warning {
                        pass,
                        message: format!(
                            "the linear profile contact stopped ({reason}); the passage was run again with the \
                             nonlinear profile contact (its CPU time counts both)"
                        ),
                    });
                }
                let lost = g.rails.iter().enumerate().map(|(k, r)| (r.contact_loss_steps, on(k)));
                for (steps, rail) in lost.filter(|(c, _)| *c > 0) {
                    progress(Event::Warning {
                        pass,
                        message: format!(
                            "the wheel left the rail{rail} at {steps} of the stretch's steps (N <= 0): the linear \
                             track model is not valid there, and the growth this passage drives is not reliable"
                        ),
                    });
                }
                fallbacks = g.fallback_steps;
                // The wear one passage of this class leaves on the smooth
                // rail, where it wears a pattern there (the discrete
                // supports' parametric excitation, imposed load harmonics):
                // it does not depend on the profile, the update integrates
                // it exactly, and the update bound and the growth rate
                // count the rest (growth::traffic).
                self.map.forced(class).map_err(fail)?;
                g.rails
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
        let wear_lines: Vec<Vec<f64>> = rails.iter().map(|r| line(&r.wear)).collect();
        let (m, rho) = self.traffic_scale(class, &wear_lines);
        let profile_contact = match normal {
            NormalContact::Hertz => 0.0,
            _ if linear_contact => PROFILE_LINEAR,
            _ => PROFILE_NONLINEAR,
        };
        let keep = RowKeep {
            pass,
            class,
            cpu_seconds,
            m,
            update_ratio: m * rho,
            profile_contact,
            grid: &self.grid,
            centre: self.centre,
            mean_b: self.mean_patch.1,
            levels: &self.levels,
            store: {
                let store_every = growth.map_or(1, |g| g.store_every);
                (pass + 1) % store_every == 0 || pass + 1 == passes
            },
            keep_history,
        };
        let max_wear = rails[0].wear.iter().cloned().fold(0.0, f64::max);
        let mut rails = rails.into_iter();
        let forced = self.map.forced_if_known(class);
        let kept = |state: &mut RunState, r: RailPass, k: usize| {
            let share = regime_share(&r.leading.regime_volume);
            keep.apply(
                state,
                (r.wear, share),
                forced.and_then(|f| f.get(k)),
                (r.leading.history, r.wheel_histories),
                (r.contact_loss_steps, r.clipped_steps),
            )
        };
        let row = kept(&mut self.state, rails.next().expect("the first rail"), 0);
        let second_row = match (self.state.second_rail.as_deref_mut(), rails.next()) {
            (Some(state), Some(r)) => Some(kept(state, r, 1)),
            _ => None,
        };
        let names = self.scene.second_rail.as_ref().map(|r| &r.names);
        for (k, row) in std::iter::once(&row).chain(second_row.as_ref()).enumerate() {
            if let Some(message) = self.hertz_check.check(&self.waves, &row.filtered_spectrum) {
                let message = match names {
                    Some(n) => format!("{}: {message}", n[k]),
                    None => message,
                };
                progress(Event::Warning { pass, message });
            }
        }
        progress(Event::Passage {
            done: pass + 1,
            total: passes,
            traffic: row.traffic,
            scale: m,
            rms: row.rms_corrugation,
            second_rail: second_row.as_ref().zip(names).map(|(r, n)| (n[0].clone(), n[1].clone(), r.rms_corrugation)),
            update_ratio: row.update_ratio,
            class: (self.classes.len() > 1).then(|| self.classes[class].name.clone()),
        });
        self.stopped = rails_stop_reason(scene, &self.state, &self.levels, &self.limit);
        if let Some(reason) = &self.stopped {
            progress(Event::Stopped { pass, reason: reason.clone() });
        }
        Ok(Some(Advanced { cpu_seconds, max_wear }))
    }

    /// The traffic scale m of a passage of `class` whose centre-line wear
    /// is `wear` on each rail (the first rail's first), and the relative
    /// profile change rho per real passage it bounds. With imposed dynamics the wear does not depend on the
    /// profile: the update is exact for any m (growth::traffic), rho = 0.
    /// The adaptive m rises from the last m of the same class: classes
    /// whose wear changes the profile faster keep a smaller m.
    fn traffic_scale(&self, class: usize, wear: &[Vec<f64>]) -> (f64, f64) {
        // Each rail's rate (the second rail's against its own profile);
        // the faster one bounds the update.
        let rate = |k: usize, profile: &Array2<f64>, wear: &[f64]| {
            let mut w = wear.to_vec();
            if let Some(w0) = self.map.forced_if_known(class).and_then(|f| f.get(k)) {
                w.iter_mut().zip(w0.row(self.centre)).for_each(|(w, f)| *w -= f);
            }
            change_rate(&profile.row(self.centre).to_vec(), &w)
        };
        let rho = match self.map.dynamics(class) {
            Some(_) => {
                let profiles =
                    std::iter::once(&self.state).chain(self.state.second_rail.as_deref()).map(|s| &s.profile);
                profiles.zip(wear).enumerate().map(|(k, (p, w))| rate(k, p, w)).fold(f64::MIN, f64::max)
            }
            _ => 0.0,
        };
        let previous = self.state.rows.iter().rev().find(|r| r.traffic_class == class).map(|r| r.traffic_scale);
        (self.scaling.scale(previous, rho), rho)
    }

    /// Contact steps of the longest simulated passage of any class (its
    /// run-in and all its wheels), the unit of [`Event::Steps`].
    fn steps_per_passage(&self) -> usize {
        self.map.steps_per_passage()
    }

    /// Passages the study will have (`growth.passes`; 1 for one passage).
    pub fn passes(&self) -> usize {
        self.passes
    }

    /// Passages done when the study was built (before this invocation).
    pub fn first(&self) -> usize {
        self.first
    }

    /// Why the study stopped before its planned passages (`growth.stop`).
    pub fn stopped(&self) -> Option<&str> {
        self.stopped.as_deref()
    }

    /// The state after the passages done.
    pub fn state(&self) -> &RunState {
        &self.state
    }

    /// The bound on the update ratio (1): the adaptive scaling keeps to it,
    /// a fixed scale is checked against it.
    pub fn update_bound(&self) -> f64 {
        self.scaling.max_update_ratio()
    }

    /// The periodic rail grid (a single passage's rail grid).
    pub fn grid(&self) -> &RailGrid {
        &self.grid
    }

    /// The contact elements the fields are stored on.
    pub fn elements(&self) -> &Elements {
        &self.elements
    }

    /// Wavelengths of the spectra (m), longest first.
    pub fn wavelengths(&self) -> &[f64] {
        &self.waves
    }

    /// Hertz semi-axes (a, b) of the mean patch the contact-filtered line is
    /// weighted with (m).
    pub fn mean_patch(&self) -> (f64, f64) {
        self.mean_patch
    }

    /// The traffic classes (empty for one passage).
    pub fn classes(&self) -> &[TrafficClass] {
        &self.classes
    }

    /// The bands of the roughness levels, and each band's limit (dB re 1
    /// um; inf: none).
    pub fn bands(&self) -> (&[crate::levels::Band], &[f64]) {
        (self.levels.bands(), &self.limit)
    }
}

/// `passes/profile_contact` of a passage in the nonlinear profile contact
/// with the dynamics of its nonlinear equivalent roughness.
const PROFILE_NONLINEAR: f64 = 1.0;
/// `passes/profile_contact` of a passage in the linear profile contact.
/// (3, the nonlinear contact with the linear contact's equivalent
/// roughness, was written by versions before the fixed grid's linear
/// contact.)
const PROFILE_LINEAR: f64 = 2.0;

/// Whether a passage that failed with `e` ends a study that stops at
/// saturation: the prescribed longitudinal force reached the friction limit
/// (full sliding), which the growing dynamic force brings about before the
/// wheel leaves the rail.
fn sliding_stops(growth: Option<&GrowthParams>, e: &PassageError) -> bool {
    matches!(growth.map(|g| g.stop), Some(StopRule::Saturation { .. }))
        && matches!(e, PassageError::Tangential { source: ContactError::ForceExceedsFriction { .. }, .. })
}

/// Each wear regime's share of the volume a passage wore (1; all zero where
/// it wore nothing).
fn regime_share(volume: &[f64]) -> Vec<f64> {
    let total: f64 = volume.iter().sum();
    volume.iter().map(|v| if total > 0.0 { v / total } else { 0.0 }).collect()
}
