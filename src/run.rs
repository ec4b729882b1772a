//! A scene run end to end: the validated scene -> contact model -> one
//! passage -> run file. The terminal and the file system stay out of the
//! kernels: progress is a callback, output goes through [`crate::output`].

use crate::config::Resolved;
use crate::contact::fastsim::Fastsim;
use crate::contact::transient::elastic::{ExactElastic, WinklerElastic};
use crate::contact::transient::{ElasticModel, Transient};
use crate::contact::{EllipseMesh, PressureShape, TangentialSolver};
use crate::creep_coefficients::creep_coefficients;
use crate::dynamics::TrackDynamics;
use crate::dynamics::receptance::{ReceptanceModel, TrackParams, WheelParams, hertz_stiffness};
use crate::growth::growth_passage;
use crate::growth::roughness::profile_line;
use crate::growth::spectrum::{amplitudes, growth_rates, wavelengths};
use crate::hertz::{HertzPatch, HertzShape};
use crate::metrics::centre_row;
use crate::metrics::rms_corrugation;
use crate::output::netcdf::NcError;
use crate::output::run_file::{PassRow, RailSnapshot, RunRecord, write_run_file};
use crate::params::{ContactModelKind, DynamicsKind, Scene};
use crate::passage::PatchHistory;
use crate::passage::{PassageError, PassageSpec, run_passage};
use crate::wear::{RailGrid, WearDeposit};
use ndarray::Array2;
use std::path::Path;

/// Quantities derived from a scene (what `corrugation check` prints).
#[derive(Debug, Clone)]
pub struct Derived {
    /// Hertz shape (fixed curvatures).
    pub shape: HertzShape,
    /// Patch at the mean, smallest and largest normal force.
    pub patch_mean: HertzPatch,
    /// Patch at the smallest normal force (None when contact is lost).
    pub patch_min: Option<HertzPatch>,
    /// Patch at the largest normal force.
    pub patch_max: HertzPatch,
    /// The passage discretisation.
    pub passage: PassageSpec,
    /// Rail grid.
    pub grid: RailGrid,
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

/// Derived quantities of a validated scene.
pub fn derive(scene: &Scene) -> Derived {
    let shape = HertzShape::new(scene.geometry.curvatures(), scene.material.elastic).expect("validated geometry");
    let patch = |n: f64| shape.patch(n).expect("validated loads keep N > 0");
    let loads = &scene.loads;
    let passage = PassageSpec {
        speed: scene.speed,
        friction: scene.material.friction,
        creepage_y: scene.creepage_y,
        spin: scene.spin,
        loads: loads.clone(),
        start: scene.start,
        end: scene.end,
        step_length: scene.step_length,
        k_over_h: scene.k_over_h,
        substeps: scene.wear_substeps,
        wear_window: (f64::NEG_INFINITY, f64::INFINITY),
        dynamic_normal_force: None,
    };
    let r = &scene.rail;
    Derived {
        shape,
        patch_mean: patch(loads.normal_force),
        patch_min: shape.patch(loads.min_normal_force()).ok(),
        patch_max: patch(loads.max_normal_force()),
        passage,
        grid: RailGrid::new(r.x_min, r.x_max, r.dx, r.half_width, r.dy),
    }
}

/// The tangential solver a scene asks for.
pub fn build_solver(scene: &Scene, shape: &HertzShape) -> Box<dyn TangentialSolver> {
    let c = &scene.contact;
    match c.model {
        ContactModelKind::Fastsim => {
            let coefficients =
                creep_coefficients(shape.aspect(), scene.material.elastic.poisson_ratio).expect("validated aspect");
            Box::new(Fastsim::new(
                c.elements_x,
                c.elements_y,
                c.fastsim_bound,
                coefficients,
                scene.material.elastic.shear_modulus(),
            ))
        }
        ContactModelKind::ExactTransient => {
            let mesh = EllipseMesh::new(c.elements_x, c.elements_y);
            let el = scene.material.elastic;
            let exact = ExactElastic::new(&mesh, shape.aspect(), el.shear_modulus(), el.poisson_ratio);
            Box::new(Transient::new(mesh, ElasticModel::Exact(exact), PressureShape::Hertz, c.regularisation))
        }
        ContactModelKind::SimplifiedTransient => {
            let el = scene.material.elastic;
            let coefficients = creep_coefficients(shape.aspect(), el.poisson_ratio).expect("validated aspect");
            let g = el.shear_modulus();
            let winkler = WinklerElastic {
                l1_unit: 8.0 / (3.0 * coefficients.c11 * g),
                l2_unit: 8.0 / (3.0 * coefficients.c22 * g),
            };
            let mesh = EllipseMesh::new(c.elements_x, c.elements_y);
            Box::new(Transient::new(mesh, ElasticModel::Winkler(winkler), c.fastsim_bound, c.regularisation))
        }
    }
}

/// Summary of a finished run.
#[derive(Debug, Clone)]
pub struct RunSummary {
    /// Simulated passages.
    pub passes: usize,
    /// CPU seconds of all passages.
    pub cpu_seconds: f64,
    /// Volume removed by the last simulated passage, unscaled (m^3).
    pub removed_volume: f64,
    /// Maximum wear depth of the last simulated passage (m).
    pub max_wear: f64,
    /// rms corrugation of the final profile (m).
    pub rms_corrugation: f64,
}

/// Contact steps per passage of a scene.
pub fn steps_per_passage(scene: &Scene) -> usize {
    derive(scene).passage.n_steps()
}

/// The periodic grid of a growth study: nodes `x_min + i dx`, `i < nx`,
/// period `x_max - x_min`.
pub fn periodic_grid(scene: &Scene) -> RailGrid {
    let r = &scene.rail;
    let nx = ((r.x_max - r.x_min) / r.dx).round().max(2.0) as usize;
    let full = RailGrid::new(r.x_min, r.x_max, r.dx, r.half_width, r.dy);
    RailGrid { x_min: r.x_min, dx: (r.x_max - r.x_min) / nx as f64, nx, ..full }
}

/// The track model of a growth study, if it has one.
pub fn track_dynamics(scene: &Scene, d: &Derived) -> Option<ReceptanceModel> {
    match scene.growth.as_ref()?.dynamics {
        DynamicsKind::Imposed => None,
        DynamicsKind::Receptance { unsprung_mass } => {
            let k_h = hertz_stiffness(d.patch_mean.normal_force, d.patch_mean.approach);
            let wheel = WheelParams { unsprung_mass };
            Some(ReceptanceModel::new(TrackParams::uic60_default(), wheel, k_h).expect("validated parameters"))
        }
    }
}

/// Runs the scene (one passage, or a growth study over `growth.passes`
/// passages) and writes the run file to `out`. `progress(done, total)`
/// counts contact steps over all passages.
pub fn run_scene(
    resolved: &Resolved,
    out: &Path,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<RunSummary, RunError> {
    let scene = &resolved.scene;
    let d = derive(scene);
    let mut solver = build_solver(scene, &d.shape);
    let mesh: EllipseMesh = solver.mesh().clone();
    let deposit = WearDeposit::new(&mesh);
    let growth = scene.growth.as_ref();
    let (grid, passes, m) = match growth {
        Some(g) => (periodic_grid(scene), g.passes, g.traffic_scale),
        None => (d.grid.clone(), 1, 1.0),
    };
    let dynamics = track_dynamics(scene, &d);
    let mut profile = match growth {
        Some(g) => {
            let line = profile_line(&g.roughness, &grid.xs(), grid.nx as f64 * grid.dx);
            Array2::from_shape_fn((grid.ny, grid.nx), |(_, i)| line[i])
        }
        None => Array2::zeros((grid.ny, grid.nx)),
    };
    let steps = d.passage.n_steps();
    let centre_line = |p: &Array2<f64>| amplitudes(p.row(centre_row(&grid)).as_slice().expect("contiguous row"));
    let mut spectrum = centre_line(&profile);
    let (mut rows, mut rail, mut histories) = (Vec::new(), Vec::new(), Vec::new());
    let mut summary = RunSummary { passes, cpu_seconds: 0.0, removed_volume: 0.0, max_wear: 0.0, rms_corrugation: 0.0 };
    for pass in 0..passes {
        let keep_history = growth.is_none_or(|g| g.contact_history.contains(&pass));
        let record_fields = keep_history && scene.output.store_fields;
        let clock = cpu_time::ProcessTime::now();
        let mut report = |done: usize, _: usize| progress(pass * steps + done, passes * steps);
        let (wear, history) = match growth {
            None => {
                let r = run_passage(&d.passage, &d.shape, solver.as_mut(), &deposit, &grid, record_fields, &mut report)
                    .map_err(|source| RunError::Passage { pass, source })?;
                (r.wear, r.history)
            }
            Some(_) => {
                let dyn_ref = dynamics.as_ref().map(|t| t as &dyn TrackDynamics);
                let g = growth_passage(
                    &d.passage,
                    &d.shape,
                    solver.as_mut(),
                    &deposit,
                    &grid,
                    &profile,
                    dyn_ref,
                    record_fields,
                    &mut report,
                )
                .map_err(|source| RunError::Passage { pass, source })?;
                (g.wear, g.passage.history)
            }
        };
        let cpu_seconds = clock.elapsed().as_secs_f64();
        profile.scaled_add(-m, &wear);
        let traffic = (pass + 1) as f64 * m;
        let removed_volume = wear.sum() * grid.dx * grid.dy;
        let rms = rms_corrugation(profile.view(), &grid);
        let after = centre_line(&profile);
        // Below 1e-12 m (1 pm) an amplitude is numerical noise.
        let growth_rate = growth_rates(&spectrum, &after, m, 1e-12);
        spectrum = after;
        rows.push(PassRow {
            index: pass as i64,
            traffic,
            traffic_scale: m,
            rms_corrugation: rms,
            removed_volume,
            cpu_seconds,
            spectrum: spectrum.clone(),
            growth_rate,
        });
        let store_every = growth.map_or(1, |g| g.store_every);
        if (pass + 1) % store_every == 0 || pass + 1 == passes {
            rail.push(RailSnapshot { index: pass as i64, traffic, profile: profile.clone(), wear: wear.clone() });
        }
        if keep_history {
            histories.push((pass as i64, history));
        }
        summary.cpu_seconds += cpu_seconds;
        summary.removed_volume = removed_volume;
        summary.max_wear = wear.iter().cloned().fold(0.0, f64::max);
        summary.rms_corrugation = rms;
    }
    let contact: Vec<(i64, &PatchHistory)> = histories.iter().map(|(k, h)| (*k, h)).collect();
    let title = if scene.output.title.is_empty() { "corrugation run" } else { scene.output.title.as_str() };
    write_run_file(
        out,
        &RunRecord {
            title,
            contact_model: scene.contact.model.name(),
            config: &resolved.toml,
            grid: &grid,
            mesh: &mesh,
            passes: &rows,
            wavelengths: &wavelengths(grid.nx, grid.dx),
            rail: &rail,
            contact: &contact,
        },
    )?;
    Ok(summary)
}
