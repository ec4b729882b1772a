//! A scene run end to end: the validated scene -> contact model -> passages
//! -> run file. The terminal and the file system stay out of the kernels:
//! progress is a callback, output goes through [`crate::output`].

mod study;

pub use study::{Event, ResumeError, RunError, RunState, RunSummary, resume, run_scene};

use crate::contact::fastsim::Fastsim;
use crate::contact::transient::elastic::{ExactElastic, WinklerElastic};
use crate::contact::transient::{ElasticModel, Transient};
use crate::contact::{EllipseMesh, PressureShape, TangentialSolver};
use crate::creep_coefficients::creep_coefficients;
use crate::dynamics::receptance::{ReceptanceModel, TrackParams, WheelParams, hertz_stiffness};
use crate::hertz::{HertzPatch, HertzShape};
use crate::params::{ContactModelKind, DynamicsKind, Scene};
use crate::passage::PassageSpec;
use crate::wear::RailGrid;

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
            Box::new(
                Transient::new(mesh, ElasticModel::Exact(Box::new(exact)), PressureShape::Hertz, c.regularisation)
                    .with_solver(c.solver),
            )
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
