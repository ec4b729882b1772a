//! A scene run end to end: the validated scene -> contact model -> one
//! passage -> run file. The terminal and the file system stay out of the
//! kernels: progress is a callback, output goes through [`crate::output`].

use crate::config::Resolved;
use crate::contact::fastsim::Fastsim;
use crate::contact::transient::elastic::{ExactElastic, WinklerElastic};
use crate::contact::transient::{ElasticModel, Transient};
use crate::contact::{EllipseMesh, PressureShape, TangentialSolver};
use crate::creep_coefficients::creep_coefficients;
use crate::hertz::{HertzPatch, HertzShape};
use crate::metrics::rms_corrugation;
use crate::output::netcdf::NcError;
use crate::output::run_file::{PassRow, RailSnapshot, RunRecord, write_run_file};
use crate::params::{ContactModelKind, Scene};
use crate::passage::{PassageError, PassageResult, PassageSpec, run_passage};
use crate::wear::{RailGrid, WearDeposit};
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
    #[error("passage failed: {0}")]
    Passage(#[from] PassageError),
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
    /// The passage result.
    pub passage: PassageResult,
    /// CPU seconds of the passage.
    pub cpu_seconds: f64,
    /// Volume removed (m^3).
    pub removed_volume: f64,
    /// Maximum wear depth (m).
    pub max_wear: f64,
}

/// Runs the scene (one passage) and writes the run file to `out`.
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
    let clock = cpu_time::ProcessTime::now();
    let result =
        run_passage(&d.passage, &d.shape, solver.as_mut(), &deposit, &d.grid, scene.output.store_fields, progress)?;
    let cpu_seconds = clock.elapsed().as_secs_f64();
    let profile = result.wear.mapv(|w| -w);
    let removed_volume = result.wear.sum() * d.grid.dx * d.grid.dy;
    let passes = [PassRow {
        index: 0,
        traffic: 1.0,
        traffic_scale: 1.0,
        rms_corrugation: rms_corrugation(profile.view(), &d.grid),
        removed_volume,
        cpu_seconds,
    }];
    let rail = [RailSnapshot { index: 0, traffic: 1.0, profile, wear: result.wear.clone() }];
    let contact = [(0, &result.history)];
    let title = if scene.output.title.is_empty() { "corrugation run" } else { scene.output.title.as_str() };
    write_run_file(
        out,
        &RunRecord {
            title,
            contact_model: scene.contact.model.name(),
            config: &resolved.toml,
            grid: &d.grid,
            mesh: &mesh,
            passes: &passes,
            rail: &rail,
            contact: &contact,
        },
    )?;
    let max_wear = result.wear.iter().cloned().fold(0.0, f64::max);
    Ok(RunSummary { passage: result, cpu_seconds, removed_volume, max_wear })
}
