//! From a validated scene to what its passages are made of: the quantities
//! derived from it (Hertz patches, passage, rail grids), the tangential
//! solver, the wear deposit and the track dynamics. Used by the run, the
//! growth loop, `check` and the cost model alike; knows nothing of files.

pub mod creep_response;

use crate::contact::Creepage;
use crate::contact::fastsim::Fastsim;
use crate::contact::grid::{Alignment, FixedGrid, spec::FixedGridSpec};
use crate::contact::transient::elastic::{ExactElastic, WinklerElastic};
use crate::contact::transient::{ElasticModel, Transient};
use crate::contact::{Elements, EllipseMesh, PressureShape, StepInput, TangentialSolver};
use crate::creep_coefficients::creep_coefficients;
use crate::dynamics::TrackDynamics;
use crate::dynamics::coupling::contact_point::ContactLaw;
use crate::dynamics::coupling::creep_response::CreepResponse;
use crate::dynamics::model::{self, Track, VehicleTrack, Wheel};
use crate::dynamics::receptance::hertz_stiffness;
use crate::dynamics::track::continuous3::Continuous3;
use crate::dynamics::track::discrete::DiscreteTrack;
use crate::dynamics::track::discrete3::Discrete3;
use crate::dynamics::track::discrete3::Discrete3Error;
use crate::dynamics::wheelset::rigid::RigidWheelset;
use crate::dynamics::wheelset::side::{Wheel3, WheelSide};
use crate::dynamics::wheelset::torsion::{TorsionFeedback, WHEEL_POLAR_INERTIA, WheelsetTorsion};
use crate::dynamics::wheelset::{WheelsetModel, standard};
use crate::hertz::{HertzPatch, HertzShape};
use crate::params::{
    ContactGrid, ContactModel, CreepForces, Directions, DynamicsKind, NormalContact, Scene, WheelsetModes,
};
use crate::passage::PassageSpec;
use crate::rail_grid::RailGrid;
use crate::wear::{CellDeposit, WearDeposit, WearKernel};
use num_complex::Complex64;

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

/// (The creepage-control run-in is the contact's own: see its doc.)
pub use creep_response::CREEPAGE_RUN_IN;

/// The run-in of a growth passage under force control, in patch lengths
/// `2 a` at the largest imposed load: the material in the patch at the
/// virgin start must have left it, and the creepage settled (about 1 % of
/// its steady value after one patch length, 2e-5 after four), before the
/// window whose wear is kept: 3 x 2a leaves the material at the window's
/// start a settled history of 2 x 2a. Shorter, the window's first patch
/// length deposits the start's transient where the periodic stretch joins
/// (measured on growth_exact.toml with its 10 mm run-in, 0.8 x 2a: a wear
/// step of 4 % of the mean at 3 mm before the stretch's end, every passage,
/// gone at 2.5 x 2a).
pub const FORCE_RUN_IN: f64 = 3.0;

/// Derived quantities of a validated scene.
pub fn derive(scene: &Scene) -> Derived {
    let shape = HertzShape::new(scene.geometry.curvatures(), scene.material.elastic).expect("validated geometry");
    let patch = |n: f64| shape.patch(n).expect("validated loads keep N > 0");
    let loads = &scene.loads;
    // A growth passage's run-in holds at least CREEPAGE_RUN_IN patch
    // lengths under creepage control and FORCE_RUN_IN under force control
    // (whole steps added before passage.start): the exact theory's force
    // settles far more slowly at a prescribed creepage than the creepage at
    // a prescribed force.
    let start = match (&scene.growth, scene.creepage_x) {
        (Some(_), control) => {
            let patches = if control.is_some() { CREEPAGE_RUN_IN } else { FORCE_RUN_IN };
            let need = scene.rail.x_min - patches * 2.0 * patch(scene.vehicle.max_normal_force(loads)).a;
            let step = scene.contact.model.fixed_grid().map_or(scene.step_length, |f| f.dx);
            scene.start - ((scene.start - need) / step).ceil().max(0.0) * step
        }
        _ => scene.start,
    };
    // On the fixed grid the patch moves exactly one element per step: the
    // last step is the first at or beyond passage.end.
    let end = match scene.contact.model.fixed_grid() {
        Some(f) => start + ((scene.end - start) / f.dx - 1e-9).ceil() * f.dx,
        None => scene.end,
    };
    let passage = PassageSpec {
        speed: scene.speed,
        friction: scene.material.friction,
        characteristic: scene.material.characteristic,
        memory: scene.material.memory,
        creepage_x: scene.creepage_x,
        creepage_y: scene.creepage_y,
        spin: scene.spin,
        loads: loads.clone(),
        wheel_loads: match (&scene.vehicle.normal_force, &scene.vehicle.longitudinal_force) {
            (None, None) => Vec::new(),
            _ => (0..scene.vehicle.wheels.len()).map(|i| scene.vehicle.wheel_loads(i, loads)).collect(),
        },
        start,
        end,
        step_length: scene.step_length,
        wear_law: scene.wear,
        substeps: scene.wear_substeps,
        wear_window: (f64::NEG_INFINITY, f64::INFINITY),
        dynamic_normal_force: None,
        torsion: match scene.vehicle.normal_force {
            Some(_) => (0..scene.vehicle.wheels.len())
                .filter_map(|i| torsion_feedback(scene, &shape, scene.vehicle.wheel_loads(i, loads).normal_force))
                .collect(),
            None => torsion_feedback(scene, &shape, loads.normal_force).into_iter().collect(),
        },
        dynamic_creepage_x: None,
        dynamic_longitudinal_force: None,
        dynamic_creepage_y: None,
        dynamic_spin: None,
        surface: None,
    };
    Derived {
        shape,
        patch_mean: patch(loads.normal_force),
        patch_min: shape.patch(loads.min_normal_force()).ok(),
        patch_max: patch(scene.vehicle.max_normal_force(loads)),
        passage,
        grid: derive_grid(scene),
    }
}

/// The tangential solver a scene asks for.
pub fn build_solver(scene: &Scene, shape: &HertzShape) -> Box<dyn TangentialSolver> {
    let c = &scene.contact;
    // The adapted mesh's linear profile contact: its solution operator, for
    // the growth studies that may take it.
    let linear =
        scene.growth.is_some() && matches!(c.normal, NormalContact::Linear { .. } | NormalContact::Auto { .. });
    match c.model {
        ContactModel::Fastsim { mesh, bound } => {
            let coefficients =
                creep_coefficients(shape.aspect(), scene.material.elastic.poisson_ratio).expect("validated aspect");
            let f = Fastsim::new(mesh.nx, mesh.ny, bound, coefficients, scene.material.elastic.shear_modulus());
            Box::new(if linear { f.with_linear_contact(shape) } else { f })
        }
        ContactModel::ExactTransient(ContactGrid::Fixed(f)) => {
            let grid = FixedGrid::new(fixed_grid_spec(scene, shape, f));
            // Auto's grid holds the nonlinear contact; its linear passages
            // run on a block of it that holds the linear contact's patch.
            match c.normal {
                NormalContact::Auto { .. } if scene.growth.is_some() => {
                    Box::new(grid.with_linear_window(fixed_grid_load(scene), f.linear_solver))
                }
                _ => Box::new(grid),
            }
        }
        ContactModel::ExactTransient(ContactGrid::Adapted { mesh, solver }) => {
            let el = scene.material.elastic;
            let mesh = EllipseMesh::new(mesh.nx, mesh.ny);
            let exact = ExactElastic::new(&mesh, shape.aspect(), el.shear_modulus(), el.poisson_ratio);
            let t = Transient::new(mesh, ElasticModel::Exact(Box::new(exact)), PressureShape::Hertz, c.regularisation)
                .with_solver(solver);
            Box::new(if linear { t.with_linear_contact(shape) } else { t })
        }
        ContactModel::SimplifiedTransient { mesh, bound } => {
            let el = scene.material.elastic;
            let coefficients = creep_coefficients(shape.aspect(), el.poisson_ratio).expect("validated aspect");
            let g = el.shear_modulus();
            let winkler = WinklerElastic {
                l1_unit: 8.0 / (3.0 * coefficients.c11 * g),
                l2_unit: 8.0 / (3.0 * coefficients.c22 * g),
            };
            let mesh = EllipseMesh::new(mesh.nx, mesh.ny);
            let t = Transient::new(mesh, ElasticModel::Winkler(winkler), bound, c.regularisation);
            Box::new(if linear { t.with_linear_contact(shape) } else { t })
        }
    }
}

/// The linear profile contact's grid on the fixed grid, relative to the
/// largest Hertz patch (`contact.profile_grid_scale`'s default for
/// `"linear"`): the shipped scenes' 1 um rms moves and stretches the patch
/// by a few per cent, which the grid's 5 % margin holds (and with track
/// dynamics the grid is sized for 1.3 times the largest load); a steeper
/// or longer wave moves it by up to half of it (the linearisation's limit),
/// and a step whose patch reaches the grid's edge says which key to raise.
/// The grid's size is the chain's cost: 1.1 made a passage of
/// growth_exact.toml 1.3 times the Hertz chain's, 1.0 1.16 times.
pub const LINEAR_GRID_SCALE: f64 = 1.0;

/// Load factor on the largest imposed normal force for which the fixed grid
/// of a growth study with track dynamics is sized: the dynamic force of the
/// worn profile adds to the imposed loads (a too small grid stops the run
/// with an error naming the step).
pub const DYNAMIC_LOAD_FACTOR: f64 = 1.3;

/// The fixed grid of a scene: sized for the largest normal force (times
/// [`DYNAMIC_LOAD_FACTOR`] with track dynamics), its element edges on the
/// rail cells' boundaries at the first step.
pub fn fixed_grid_spec(scene: &Scene, shape: &HertzShape, f: crate::params::FixedGridParams) -> FixedGridSpec {
    let largest = shape.patch(fixed_grid_load(scene)).expect("validated loads keep N > 0");
    let rail = if scene.growth.is_some() { periodic_grid(scene) } else { derive_grid(scene) };
    // The profile's troughs lengthen the patch over them, its crests widen
    // it (a growth study's; a single passage has no profile in its contact).
    let scale = if scene.growth.is_some() { scene.contact.normal.grid_scale() } else { 1.0 };
    FixedGridSpec {
        curvatures: scene.geometry.curvatures(),
        elastic: scene.material.elastic,
        dx: f.dx,
        dy: f.dy,
        a_max: scale * largest.a,
        b_max: scale * largest.b,
        // Rail cell boundaries x_i + dx/2 in the contact frame of the first
        // step (the deposit spreads an element over the rail cells it
        // overlaps). Across, symmetric about the centre line (a symmetric
        // problem keeps a symmetric answer). In a growth study, whose grid's
        // size follows contact.profile_grid_scale, the elements keep their
        // places under the wheel at any size: along x on one lattice of the
        // element's period where it holds whole cells, across an element
        // edge on the centre line (with the rail cell's period and the
        // fewer rows, a grid 1.5 times the patch and one 1.0 times it sat
        // half an element apart, and one 1.2 times it had an element on the
        // centre line: growth rates of growth_exact.toml moved by up to 0.6
        // dB per 1e5 passages with the key).
        align_x: Alignment {
            edge: rail.x_min + 0.5 * rail.dx - scene.start,
            period: if scene.growth.is_some() { element_period(f.dx, rail.dx) } else { rail.dx },
            even: false,
        },
        align_y: Alignment { even: scene.growth.is_some(), ..Alignment::default() },
        law: f.friction_law,
        eps: scene.contact.regularisation,
        scheme: f.scheme,
        solver: f.solver,
    }
}

/// The period (m) of the lattice the fixed grid's element edges lie on: the
/// element `dx` where it is a whole number of rail cells `cell`, the cell
/// otherwise.
fn element_period(dx: f64, cell: f64) -> f64 {
    let cells = dx / cell;
    if cells >= 1.0 && (cells - cells.round()).abs() < 1e-9 { dx } else { cell }
}

/// The normal force (N) whose Hertz patch the fixed grid is sized for.
pub fn fixed_grid_load(scene: &Scene) -> f64 {
    let dynamic = scene.growth.as_ref().is_some_and(|g| g.dynamics != DynamicsKind::Imposed);
    scene.max_normal_force() * if dynamic { DYNAMIC_LOAD_FACTOR } else { 1.0 }
}

/// The rail grid of a single passage.
fn derive_grid(scene: &Scene) -> RailGrid {
    let r = &scene.rail;
    RailGrid::new(r.x_min, r.x_max, r.dx, r.half_width, r.dy)
}

/// How a solver's element rates reach the rail: the Delaunay deposit on the
/// adapted mesh, the conservative cell deposit on the fixed grid.
pub fn build_deposit(elements: &Elements) -> Box<dyn WearKernel> {
    match elements {
        Elements::Adapted(mesh) => Box::new(WearDeposit::new(mesh)),
        Elements::Grid(grid) => Box::new(CellDeposit::new(grid.clone())),
    }
}

impl ContactModel {
    /// Number of contact elements the fields of `scene` (whose model this
    /// is) are stored on: the adapted mesh's, or the fixed grid's (built
    /// without its influence coefficients).
    pub fn elements(&self, scene: &Scene) -> usize {
        match *self {
            ContactModel::ExactTransient(ContactGrid::Fixed(f)) => {
                fixed_grid_spec(scene, &derive(scene).shape, f).grid().len()
            }
            ContactModel::Fastsim { mesh, .. }
            | ContactModel::SimplifiedTransient { mesh, .. }
            | ContactModel::ExactTransient(ContactGrid::Adapted { mesh, .. }) => mesh.len(),
        }
    }
}

/// The rail grid of a scene's run file: periodic for a growth study.
pub fn study_grid(scene: &Scene) -> RailGrid {
    match scene.growth {
        Some(_) => periodic_grid(scene),
        None => derive(scene).grid,
    }
}

/// The periodic grid of a growth study: nodes `x_min + i dx`, `i < nx`,
/// period `x_max - x_min`.
pub fn periodic_grid(scene: &Scene) -> RailGrid {
    let r = &scene.rail;
    let nx = ((r.x_max - r.x_min) / r.dx).round().max(2.0) as usize;
    let full = RailGrid::new(r.x_min, r.x_max, r.dx, r.half_width, r.dy);
    RailGrid { x_min: r.x_min, dx: (r.x_max - r.x_min) / nx as f64, nx, ..full }
}

/// The wheelset's torsional feedback (`[wheelset]` with the creepage
/// prescribed): the torsion of [`crate::dynamics::wheelset::torsion`] with the steady
/// creep curve's slopes `dF/dN` and `dF/dxi` at the mean load and
/// creepage, by central differences (1e-3 relative steps) of FASTSIM's
/// steady solution on a 40 x 40 mesh with the Hertz pressure (Kalker,
/// *Veh. Syst. Dyn.* 11 (1982) 1-13; quasi-static), for a wheel of mean
/// normal force `n0` (N).
pub fn torsion_feedback(scene: &Scene, shape: &HertzShape, n0: f64) -> Option<TorsionFeedback> {
    let (w, xi0) = (scene.wheelset.as_ref()?, scene.creepage_x?);
    let elastic = scene.material.elastic;
    let coefficients = creep_coefficients(shape.aspect(), elastic.poisson_ratio).expect("validated aspect");
    let fastsim = Fastsim::new(40, 40, PressureShape::Hertz, coefficients, elastic.shear_modulus());
    let force = |n: f64, xi: f64| {
        let input = StepInput {
            patch: shape.patch(n).expect("validated loads keep N > 0"),
            speed: scene.speed,
            dt: 0.0,
            friction: scene.material.friction,
            characteristic: scene.material.characteristic,
            memory: scene.material.memory,
            force_x: 0.0,
            creepage_x: Some(xi),
            creepage_y: scene.creepage_y,
            spin: scene.spin,
            position: 0.0,
        };
        fastsim.solve_force(&input).expect("FASTSIM at a prescribed creepage").force_x
    };
    let (dn, dxi) = (1e-3 * n0, 1e-3 * xi0.abs().max(1e-5));
    let force_per_normal = (force(n0 + dn, xi0) - force(n0 - dn, xi0)) / (2.0 * dn);
    let force_per_creepage = (force(n0, xi0 + dxi) - force(n0, xi0 - dxi)) / (2.0 * dxi);
    let torsion = WheelsetTorsion {
        stiffness: w.stiffness,
        loss_factor: w.loss_factor,
        inertia: w.inertia,
        radius: scene.geometry.wheel_radius,
    };
    Some(TorsionFeedback { torsion, force_per_normal, force_per_creepage })
}

/// The wheelset's modal model ([`crate::dynamics::wheelset`]) where the
/// scene has `[wheelset]`: with `model = "modal"` the rigid wheelset on its
/// primary suspension and the default's or the user's table's flexible
/// modes; with the torsional model alone (`model = "torsion"`) its two
/// modes ([`WheelsetModel::torsion`]), whose receptance is the torsion's
/// eq. 1. The rolling radius is the scene's wheel radius.
pub fn wheelset_model(scene: &Scene) -> Option<WheelsetModel> {
    let w = scene.wheelset.as_ref()?;
    let radius = scene.geometry.wheel_radius;
    let Some(m) = &w.modal else {
        let torsion =
            WheelsetTorsion { stiffness: w.stiffness, loss_factor: w.loss_factor, inertia: w.inertia, radius };
        return Some(WheelsetModel::torsion(&torsion));
    };
    let rigid = RigidWheelset {
        mass: m.mass,
        roll_inertia: m.roll_inertia,
        yaw_inertia: m.yaw_inertia,
        spin_inertia: 2.0 * w.inertia,
        stiffness_x: m.suspension_stiffness[0],
        stiffness_y: m.suspension_stiffness[1],
        stiffness_z: m.suspension_stiffness[2],
        loss_factor: m.suspension_loss_factor,
        axle_box_half_spacing: m.axle_box_spacing / 2.0,
        contact_half_spacing: m.contact_spacing / 2.0,
        radius,
    };
    let model = match &m.modes {
        WheelsetModes::Default { bending_damping, wheel_damping } => standard::default_model(&standard::Design {
            rigid,
            torsional_stiffness: w.stiffness,
            torsional_loss_factor: w.loss_factor,
            bending_damping: *bending_damping,
            wheel_damping: *wheel_damping,
        }),
        WheelsetModes::Table { table, .. } => standard::table_model(&rigid, table),
    };
    Some(model.expect("validated keys and table make a valid model"))
}

/// The contact at the mean state of a wheel of mean normal force `n0`
/// (N), for the dynamics in every direction: the Hertz stiffness and the
/// steady creep curve's slopes `d(F_x, F_y) / dN` and `d(F_x, F_y) /
/// d(xi_x, xi_y)` by central differences (1e-3 relative steps) of FASTSIM's
/// steady solution on a 40 x 40 mesh with the Hertz pressure (as
/// [`torsion_feedback`]), at the mean creepage: the prescribed one, or
/// under force control the one FASTSIM finds for the mean force; with
/// `spin`, the spin's slopes `d(F_x, F_y) / dphi` too (steps of 1e-3 of the
/// mean spin, at least 1e-6 1/m).
pub fn steady_contact_law(scene: &Scene, shape: &HertzShape, n0: f64, fx0: f64, spin: bool) -> ContactLaw {
    let elastic = scene.material.elastic;
    let coefficients = creep_coefficients(shape.aspect(), elastic.poisson_ratio).expect("validated aspect");
    let fastsim = Fastsim::new(40, 40, PressureShape::Hertz, coefficients, elastic.shear_modulus());
    let patch0 = shape.patch(n0).expect("validated loads keep N > 0");
    let input = StepInput {
        patch: patch0,
        speed: scene.speed,
        dt: 0.0,
        friction: scene.material.friction,
        characteristic: scene.material.characteristic,
        memory: scene.material.memory,
        force_x: fx0,
        creepage_x: scene.creepage_x,
        creepage_y: scene.creepage_y,
        spin: scene.spin,
        position: 0.0,
    };
    let xi0 = match scene.creepage_x {
        Some(xi) => xi,
        None => fastsim.solve_force(&input).map(|s| s.creepage.x).unwrap_or(0.0),
    };
    let forces_at = |n: f64, x: f64, y: f64, spin: f64| {
        let patch = shape.patch(n).expect("validated loads keep N > 0");
        let friction = (scene.material.friction, scene.material.characteristic, scene.material.memory);
        let s = fastsim.solve_creepage_with(&patch, Creepage { x, y, spin }, friction, scene.speed);
        [s.force_x, s.force_y]
    };
    let forces = |n: f64, x: f64, y: f64| forces_at(n, x, y, scene.spin);
    let y0 = scene.creepage_y;
    let (dn, dx, dy) = (1e-3 * n0, 1e-3 * xi0.abs().max(1e-5), 1e-3 * y0.abs().max(1e-5));
    let diff = |a: [f64; 2], b: [f64; 2], h: f64| [0, 1].map(|i| Complex64::new((a[i] - b[i]) / (2.0 * h), 0.0));
    let per_normal = diff(forces(n0 + dn, xi0, y0), forces(n0 - dn, xi0, y0), dn);
    let per_x = diff(forces(n0, xi0 + dx, y0), forces(n0, xi0 - dx, y0), dx);
    let per_y = diff(forces(n0, xi0, y0 + dy), forces(n0, xi0, y0 - dy), dy);
    let per_spin = spin.then(|| {
        let dphi = 1e-3 * scene.spin.abs().max(1e-3);
        diff(forces_at(n0, xi0, y0, scene.spin + dphi), forces_at(n0, xi0, y0, scene.spin - dphi), dphi)
    });
    ContactLaw {
        stiffness: hertz_stiffness(patch0.normal_force, patch0.approach),
        force_per_normal: per_normal,
        force_per_creepage: [[per_x[0], per_y[0]], [per_x[1], per_y[1]]],
        force_per_spin: per_spin,
    }
}

/// The dynamics in every direction of a growth study's wheel
/// ([`VehicleTrack`] in every direction): the track of `dynamics.model`, the wheelset's
/// modal model (`[wheelset] model = "modal"`) or the rigid wheel of
/// unsprung mass `mass` (kg) with the wheelset's torsion where configured,
/// and the steady contact law at the wheel's mean loads.
fn contact_dynamics(
    scene: &Scene,
    d: &Derived,
    mass: f64,
    contact_offset: f64,
    creep_forces: CreepForces,
    spin: bool,
) -> Result<Box<dyn TrackDynamics>, DynamicsError> {
    let v = &scene.vehicle;
    // Each distinct load's law and creep response (measured once).
    let mut laws: Vec<((f64, f64), ContactLaw, Option<CreepResponse>)> = Vec::new();
    for i in 0..v.wheels.len() {
        let loads = v.wheel_loads(i, &scene.loads);
        let key = (loads.normal_force, loads.longitudinal_force);
        if laws.iter().any(|(k, ..)| *k == key) {
            continue;
        }
        let law = steady_contact_law(scene, &d.shape, key.0, key.1, spin);
        // The dynamics loop needs the creepages' and the normal force's
        // columns, and the spin's with the spin's channel.
        let response = match creep_forces {
            CreepForces::Steady => None,
            CreepForces::Transient => Some(
                creep_response::default_response(scene, key.0, key.1, [true, true, spin, true], &|| {
                    build_solver(scene, &creep_response::shape(scene))
                })
                .map_err(|e| DynamicsError::CreepResponse(e.to_string()))?,
            ),
        };
        laws.push((key, law, response));
    }
    let grid = periodic_grid(scene);
    let track = match scene.growth.as_ref().map(|g| g.dynamics) {
        Some(DynamicsKind::Discrete { .. }) => Track::Discrete {
            vertical: DiscreteTrack::new(&scene.track),
            head: Some(Discrete3::new(&scene.track, contact_offset)),
            sleeper_x0: grid.x_min,
            layout: scene.layout.clone(),
        },
        _ => Track::Continuous {
            vertical: scene.track.smeared(),
            head: Some(Continuous3::new(&scene.track, contact_offset)),
        },
    };
    let modal = scene.wheelset.as_ref().is_some_and(|w| w.modal.is_some());
    let side = |mass: f64| {
        let wheel = Wheel3 {
            mass,
            radius: scene.geometry.wheel_radius,
            polar_inertia: scene.wheelset.as_ref().map_or(WHEEL_POLAR_INERTIA, |w| w.inertia),
            torsion: scene.wheelset.as_ref().map(|w| WheelsetTorsion {
                stiffness: w.stiffness,
                loss_factor: w.loss_factor,
                inertia: w.inertia,
                radius: scene.geometry.wheel_radius,
            }),
        };
        match wheelset_model(scene).filter(|_| modal) {
            Some(model) => WheelSide::Modal { model, spin: scene.speed / scene.geometry.wheel_radius },
            None => WheelSide::Rigid(wheel),
        }
    };
    let fail = |e: Discrete3Error| DynamicsError::Receptances(e.to_string());
    let wheels: Vec<Wheel> = (0..v.wheels.len())
        .map(|i| {
            let loads = v.wheel_loads(i, &scene.loads);
            let key = (loads.normal_force, loads.longitudinal_force);
            let (_, law, response) = laws.iter().find(|(k, ..)| *k == key).expect("a law per load").clone();
            Wheel {
                behind: v.wheels[i],
                side: side(v.wheel_mass(i, mass)),
                law,
                response,
                mean_load: loads.normal_force,
                rail: 0,
            }
        })
        .collect();
    // The wheelsets' second rail: each wheelset's other wheel, at the same
    // place, its contact at the second rail's steady state.
    let mut wheels = wheels;
    if let Some(second) = scene.second_rail_scene() {
        let (n0, fx) = (second.loads.normal_force, second.loads.longitudinal_force);
        let law = steady_contact_law(&second, &d.shape, n0, fx, spin);
        let response = match creep_forces {
            CreepForces::Steady => None,
            CreepForces::Transient => Some(
                creep_response::default_response(&second, n0, fx, [true, true, spin, true], &|| {
                    build_solver(&second, &creep_response::shape(&second))
                })
                .map_err(|e| DynamicsError::CreepResponse(format!("second rail: {e}")))?,
            ),
        };
        for i in 0..v.wheels.len() {
            let (law, response) = (law, response.clone());
            let side = side(v.wheel_mass(i, mass));
            wheels.push(Wheel { behind: v.wheels[i], side, law, response, mean_load: n0, rail: 1 });
        }
    }
    let model =
        VehicleTrack::new(track, wheels, model::Directions::All, grid.nx, grid.dx, scene.speed).map_err(fail)?;
    Ok(Box::new(model))
}

/// Why the dynamics in every direction could not be set up before the
/// first passage.
#[derive(Debug, thiserror::Error)]
pub enum DynamicsError {
    /// The creep forces' frequency response (`dynamics.creep_forces =
    /// "transient"`).
    #[error(
        "the creep forces' frequency response could not be measured on the passage's contact solver: {0}; \
         dynamics.creep_forces = \"steady\" closes the loop with FASTSIM's steady slopes instead"
    )]
    CreepResponse(String),
    /// The rail head's receptances in three directions.
    #[error(
        "the rail head's receptances in three directions could not be computed: {0}; dynamics.directions = \
         \"vertical\" uses the vertical models"
    )]
    Receptances(String),
}

/// The vehicle-track model of a growth study ([`VehicleTrack`]), if it
/// has one: the track of `dynamics.model` (continuous or discrete; the
/// discrete model tabulated for the study's speed and periodic stretch,
/// the first rail node above a sleeper), the wheels of `[vehicle]`
/// coupled through the rail, and the contacts closed in the directions of
/// `dynamics.directions`.
pub fn track_dynamics(scene: &Scene, d: &Derived) -> Result<Option<Box<dyn TrackDynamics>>, DynamicsError> {
    let v = &scene.vehicle;
    let Some(growth) = scene.growth.as_ref() else {
        return Ok(None);
    };
    // The dynamics in every direction, of one wheel or several.
    if let (Directions::All { contact_offset, creep_forces, spin }, Some(mass)) =
        (growth.directions, growth.dynamics.unsprung_mass())
    {
        return contact_dynamics(scene, d, mass, contact_offset, creep_forces, spin).map(Some);
    }
    let grid = periodic_grid(scene);
    let (track, mass) = match growth.dynamics {
        DynamicsKind::Imposed => return Ok(None),
        DynamicsKind::Receptance { unsprung_mass } => {
            (Track::Continuous { vertical: scene.track.smeared(), head: None }, unsprung_mass)
        }
        DynamicsKind::Discrete { unsprung_mass } => (
            Track::Discrete {
                vertical: DiscreteTrack::new(&scene.track),
                head: None,
                sleeper_x0: grid.x_min,
                layout: scene.layout.clone(),
            },
            unsprung_mass,
        ),
    };
    // Each wheel's mass, and its contact spring at its mean load.
    let wheels: Vec<Wheel> = (0..v.wheels.len())
        .map(|i| {
            let n0 = v.wheel_loads(i, &scene.loads).normal_force;
            let p = d.shape.patch(n0).expect("validated loads keep N > 0");
            let wheel = Wheel3::new(v.wheel_mass(i, mass), scene.geometry.wheel_radius);
            Wheel::vertical(v.wheels[i], wheel, hertz_stiffness(p.normal_force, p.approach), n0)
        })
        .collect();
    let model = VehicleTrack::new(track, wheels, model::Directions::Vertical, grid.nx, grid.dx, scene.speed)
        .map_err(|e| DynamicsError::Receptances(e.to_string()))?;
    Ok(Some(Box::new(model)))
}
