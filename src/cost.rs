//! A rough cost model of a scene: CPU time per passage on 2 cores, the
//! set-up of the discrete track's receptances, and memory. `check` prints
//! it; sweeps use it for their plan and their Slurm time and memory limits.
//! The times are fitted to measurements (book: docs/src/performance/); they are
//! upper estimates on the development machines, not promises.

use crate::build::{derive, fixed_grid_spec, periodic_grid};
use crate::contact::grid::GridSolver;
use crate::contact::transient::StepSolver;
use crate::loads::LoadQuantity;
use crate::params::{
    ContactGrid, ContactModel, ContactModelKind, CreepForces, Directions, DynamicsKind, FixedGridParams, NormalContact,
    Scene,
};

/// What a scene is expected to cost.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CostEstimate {
    /// CPU time of one passage (s, 2 cores).
    pub per_passage: f64,
    /// Passages planned.
    pub passes: usize,
    /// Time before the first passage: the discrete track's receptance
    /// tables, one per traffic class (s), the dynamics in every direction's
    /// included.
    pub setup: f64,
    /// What the dynamics in every direction adds to `setup`, where the
    /// study has it.
    pub directions: Option<DirectionsCost>,
    /// Peak memory (bytes).
    pub memory: f64,
}

/// What the dynamics in every direction costs before the first passage
/// (s, 2 cores), summed over the traffic classes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DirectionsCost {
    /// The rail head's and the wheel's receptances in three directions per
    /// harmonic (at 16 places of the bay on the discrete track).
    pub tables: f64,
    /// The creep forces' frequency response measured on the passage's own
    /// contact solver (`dynamics.creep_forces = "transient"`).
    pub creep_response: f64,
}

/// CPU seconds per harmonic of the discrete track's head receptances at
/// the 16 places of the bay (the Floquet integral in three directions; one
/// core, release build): 0.46 s wall on 2 cores for the 108 harmonics of
/// growth_discrete.toml with the steady creep slopes (one wheel or one
/// wheelset: the places past mid-bay the mirror images of those before).
const DISCRETE3_PER_HARMONIC: f64 = 0.0085;
/// CPU seconds per harmonic of a track layout's head receptances in every
/// direction at the 16 places of each support interval (the waves'
/// scattering, one wheel): a base and a share per support of the period,
/// fitted to `cargo bench --bench kernels -- layout_tables` (0.31, 0.40,
/// 0.76, 1.17 and 2.45 ms for 1, 2, 5, 10 and 20 bays).
const LAYOUT3_PER_HARMONIC: (f64, f64) = (2e-4, 1.1e-4);
/// The same on the continuous track (a 12 x 12 eigenproblem).
const CONTINUOUS3_PER_HARMONIC: f64 = 2e-4;

impl CostEstimate {
    /// The whole run (s).
    pub fn total(&self) -> f64 {
        self.setup + self.per_passage * self.passes as f64
    }
}

/// Whether scene `s` is a growth study with the dynamics in every
/// direction (its steps unfold the grid; its tables are the head's).
fn every_direction(s: &Scene) -> bool {
    s.growth
        .as_ref()
        .is_some_and(|g| matches!(g.directions, Directions::All { .. }) && g.dynamics.unsprung_mass().is_some())
}

/// The fixed grid's CPU time per step (s, 2 cores) of scene `s` with the
/// tangential solver `solver` (Cg or GaussSeidel) on the fixed grid `f`.
fn fixed_grid_step(s: &Scene, d: &crate::build::Derived, f: FixedGridParams, solver: GridSolver) -> f64 {
    // The fixed grid (ADAPTED=0 scripts/solver_scaling.sh, paper_normal_30mm,
    // 2026-11-26 with the symmetric products and the contact blocks, wall
    // on 2 cores; the next step's pressure on the second core): with the
    // CG solver 1.09 / 1.54 / 2.60 / 5.31 ms per step with 478 / 975 /
    // 1912 / 3902 elements in contact at the mean load, fitted by 0.99 ms
    // (N/478)^0.76 (least squares; exact Coulomb friction as the
    // regularised law's limit costs the same within 3 %); with
    // Gauss-Seidel 3.39 / 8.70 / 24.8 / 81.1 ms, 5-23 % below its earlier
    // fit 3.56 ms (N/478)^1.54, which is kept (an upper estimate; exact
    // Coulomb friction about 20 % more sweeps); the wear deposit is in it.
    // A scene that is not symmetric about the centre line (lateral
    // creepage, spin) solves the whole grid: 2.7 times for Gauss-Seidel
    // (scripts/stability_map.sh); with CG, which then has no symmetric
    // products but its own contact block (paper_normal_30mm with lateral
    // creepage 2e-3, median of 3: 0.46 -> 0.39 s at 0.4 mm, 3.61 -> 3.24 s
    // at 0.2 mm with that block, against 0.22-0.28 and 1.43-1.45 s folded:
    // 1.4-1.8 and 2.2 times), taken as 2.3, an upper estimate. The
    // dynamics in every direction vary the lateral creepage and the spin
    // about a symmetric mean state: the whole grid again, with fewer
    // slipping elements, 1.51 times on growth_exact.toml (10 passages,
    // median of 3) and 1.44-1.57 times on growth_discrete.toml
    // (scripts/dynamics_cost.sh, two runs) with CG, taken as 1.5 for both
    // solvers (Gauss-Seidel's not measured).
    let n_c = std::f64::consts::PI * d.patch_mean.a * d.patch_mean.b / (f.dx * f.dy);
    let every_direction = every_direction(s);
    let symmetric = s.creepage_y == 0.0 && s.spin == 0.0;
    let cg = solver == GridSolver::Cg;
    // With the profile in the contact (the default in growth studies):
    // a grid 1.5 times the patch both ways, the gap of every step, the
    // normal solves of the steps (on the second core) and of the
    // equivalent-roughness pre-pass (two chains, one per core); measured
    // 2026-11-26 with the symmetric products and the contact blocks (the
    // CG's inner products and the normal solves on the block of the grid
    // that holds the contact), against the per-step fits above: with CG
    // 0.76 times (growth_exact.toml, 0.245 s per passage of 325 steps) and
    // 0.77 times (growth_discrete.toml, 1.17 s per passage of 1526 steps),
    // taken as 0.8; with Gauss-Seidel, which sweeps the contact area only,
    // 1.0 and 1.3 times (measured before the symmetric products), kept.
    // The linear profile contact (auto's passages in its range: its
    // pressure's cell means on a window of the grid): with CG 0.57 and
    // 0.56 times (0.183 and 0.85 s per passage), taken as 0.6; with
    // Gauss-Seidel 0.74 and 0.93 times (before the symmetric products),
    // taken as 0.95.
    // `auto` is costed as the nonlinear contact (its grid holds it; a
    // passage in the linear range costs less).
    let profile = match s.contact.normal {
        NormalContact::Profile { .. } | NormalContact::Auto { .. } if s.growth.is_some() => {
            if cg {
                0.8
            } else {
                1.3
            }
        }
        NormalContact::Linear { .. } if s.growth.is_some() => {
            if cg {
                0.6
            } else {
                0.95
            }
        }
        _ => 1.0,
    };
    let per_step = if cg { 0.99e-3 * (n_c / 478.0).powf(0.76) } else { 3.56e-3 * (n_c / 478.0).powf(1.54) };
    let whole = match (symmetric, cg) {
        (true, _) if every_direction => 1.5,
        (true, _) => 1.0,
        (false, true) => 2.3,
        (false, false) => 2.7,
    };
    per_step * whole * profile
}

/// What `contact.solver = "auto"` runs on the fixed grid of scene `s`: the
/// cheaper of CG and Gauss-Seidel by this cost model, for both friction
/// laws (CG on every grid measured since its FFT preconditioner, 3.1-15
/// times faster per passage at 0.4-0.14 mm with the symmetric products,
/// Gauss-Seidel by these fits below about 50-100 elements in contact;
/// exact Coulomb friction as the regularised
/// law's limit, `contact::grid::cg::COULOMB_LIMIT`).
pub fn auto_grid_solver(s: &Scene) -> GridSolver {
    let Some(f) = s.contact.model.fixed_grid() else {
        return GridSolver::GaussSeidel;
    };
    if f.solver != GridSolver::Auto {
        return f.solver.resolve();
    }
    let d = derive(s);
    if fixed_grid_step(s, &d, f, GridSolver::Cg) <= fixed_grid_step(s, &d, f, GridSolver::GaussSeidel) {
        GridSolver::Cg
    } else {
        GridSolver::GaussSeidel
    }
}

impl ContactModel {
    /// CPU time per contact step (s, 2 cores) of this model in scene `s`
    /// (whose model it is), from measurements (book: docs/src/performance/):
    /// FASTSIM ~ 18 ns per element and solve, 25 solves; simplified-transient
    /// ~ 3 us per element; the exact model with constant N ~ 60 ms at 400
    /// elements, growing as N^3 (dense LU); with a varying N (harmonics or
    /// track dynamics) 2.5 ms at 100 and 175 ms at 400 elements, both
    /// fitted by 2.7e-9 N^3 s. The Gauss-Seidel solver
    /// (scripts/solver_scaling.sh, wall): 2.4 ms at 100 and 11.8 ms at 400
    /// elements (~N^1.15 while C fits in cache), ~N^2.2 beyond. Measured on
    /// the old AMD development machine; the newer Intel one (book,
    /// docs/src/performance/) takes 0.45-0.6 of these times: an upper estimate. The
    /// fixed grid: its step's fit (`fixed_grid_step`).
    pub fn step_cost(&self, s: &Scene, d: &crate::build::Derived) -> f64 {
        let n_el = self.mesh().map_or(0, |m| m.len()) as f64;
        match *self {
            ContactModel::ExactTransient(ContactGrid::Fixed(f)) => fixed_grid_step(s, d, f, f.solver.resolve()),
            ContactModel::Fastsim { .. } => 25.0 * 18e-9 * n_el,
            ContactModel::SimplifiedTransient { .. } => 3e-6 * n_el,
            ContactModel::ExactTransient(ContactGrid::Adapted { solver: StepSolver::GaussSeidel, .. }) => {
                if n_el <= 400.0 { 2.4e-3 * (n_el / 100.0).powf(1.15) } else { 11.8e-3 * (n_el / 400.0).powf(2.2) }
            }
            ContactModel::ExactTransient(ContactGrid::Adapted { .. }) => {
                let varying = s.loads.harmonics.iter().any(|h| h.quantity == LoadQuantity::NormalForce)
                    || s.growth.as_ref().is_some_and(|g| g.dynamics != DynamicsKind::Imposed);
                if varying { 2.7e-9 * n_el.powi(3) } else { 0.06 * (n_el / 400.0).powi(3) }
            }
        }
    }
}

/// The cost model of `s`.
pub fn estimate(s: &Scene) -> CostEstimate {
    let d = derive(s);
    let p = &d.passage;
    let g = if s.growth.is_some() { periodic_grid(s) } else { d.grid.clone() };
    let fixed = s.contact.model.fixed_grid().map(|f| (f, fixed_grid_spec(s, &d.shape, f)));
    let nodes = std::f64::consts::PI * d.patch_max.a * d.patch_max.b / (g.dx * g.dy);
    let contact = s.contact.model.step_cost(s, &d);
    // With "auto", the map's own measurement of the chosen model.
    // (per 0.2 mm rolled: per step of the fixed grid in proportion to its element).
    let contact =
        s.contact.auto.map_or(contact, |a| a.chosen.cpu_per_step * a.chosen.grid_dx().map_or(1.0, |dx| dx / 2e-4));
    // Wear ~ 20 ns per node visit (the fixed grid's cell deposit is in its
    // step's fit).
    let deposit = if fixed.is_some() { 0.0 } else { p.substeps as f64 * nodes * 20e-9 };
    // Every wheel of the vehicle rolls over the stretch in a passage (under
    // a mix whose classes are vehicles of their own, the share-weighted
    // mean of their wheels).
    let wheels = s.vehicle.wheels.len();
    let mean_wheels = match &s.growth {
        Some(g) if g.classes.iter().any(|c| c.wheels.is_some()) => {
            g.classes.iter().map(|c| c.share * c.wheels.as_ref().map_or(wheels, Vec::len) as f64).sum::<f64>()
                / g.classes.iter().map(|c| c.share).sum::<f64>()
        }
        _ => wheels as f64,
    };
    // The wheelset's second rail doubles the contacts, but its wheels run
    // beside the first rail's: on two cores a two-rail passage measured
    // 1.14 times a straight single contact's (scripts/two_rails_cost.sh),
    // and a curve's unfolded grid takes about 1.3 of that; 1.3 here.
    let rails = if s.second_rail.is_some() { 1.3 } else { 1.0 };
    let per_passage = p.n_steps() as f64 * (contact + deposit) * mean_wheels * rails;
    let passes = s.growth.as_ref().map_or(1, |g| g.passes);
    // The discrete model tabulates its vertical receptances once per
    // traffic class where the dynamics is vertical (0.55 s on 2 cores for
    // the 108 harmonics up to 5 kHz of growth_discrete.toml, the
    // vehicle's matrices at 9 places over the half bay, the others their
    // mirror images; a vehicle's at all 16: 1.4 s for two wheels, 2.9 s
    // for four, about 1.3 times the one wheel's per wheel), the
    // tables in every direction counted in `directions_cost`, and runs one
    // passage per class over the smooth rail for the update bound (its
    // forced wear).
    let every_direction = every_direction(s);
    let table = |n: usize| {
        if every_direction {
            0.0
        } else if n > 1 {
            0.8 * n as f64
        } else {
            1.0
        }
    };
    let setup: f64 = match &s.growth {
        Some(gr) if matches!(gr.dynamics, DynamicsKind::Discrete { .. }) => gr
            .classes
            .iter()
            .map(|c| {
                let n = c.wheels.as_ref().map_or(wheels, Vec::len);
                let harmonics = crate::dynamics::model::harmonics(g.nx, g.dx, c.speed) as f64;
                0.005 * table(n) * harmonics + per_passage * n as f64 / mean_wheels
            })
            .sum(),
        _ => 0.0,
    };
    let directions = directions_cost(s, &g, contact + deposit, &d);
    let setup = setup + directions.map_or(0.0, |c| c.tables + c.creep_response);
    CostEstimate {
        per_passage,
        passes,
        setup,
        directions,
        memory: memory(s, &g, p.n_steps(), fixed.as_ref().map(|(_, f)| f.grid().len())),
    }
}

/// The dynamics in every direction's tables and creep response (one wheel;
/// `step` the contact's cost per step of the passage, s): the tables per
/// harmonic on 2 cores; the creep response's runs (each input two runs of
/// opposite sign, the longitudinal and lateral creepage, the spin with
/// `dynamics.spin` and the normal force; 10 patch lengths each with the
/// creepage's run-in, the lateral and the spin's runs twice the others:
/// they break the symmetry the fixed grid folds) two at a time on 2 cores.
fn directions_cost(
    s: &Scene,
    g: &crate::rail_grid::RailGrid,
    step: f64,
    d: &crate::build::Derived,
) -> Option<DirectionsCost> {
    let gr = s.growth.as_ref()?;
    let (Directions::All { creep_forces, spin, .. }, Some(_)) = (gr.directions, gr.dynamics.unsprung_mass()) else {
        return None;
    };
    let per_harmonic = match gr.dynamics {
        DynamicsKind::Discrete { .. } if !s.layout.is_one_bay(&s.track) => {
            LAYOUT3_PER_HARMONIC.0 + LAYOUT3_PER_HARMONIC.1 * s.layout.len() as f64
        }
        DynamicsKind::Discrete { .. } => DISCRETE3_PER_HARMONIC,
        _ => CONTINUOUS3_PER_HARMONIC,
    };
    let classes = gr.classes.len().max(1) as f64;
    let tables: f64 = gr
        .classes
        .iter()
        .map(|c| crate::dynamics::model::harmonics(g.nx, g.dx, c.speed) as f64 * per_harmonic / 2.0)
        .sum();
    let creep_response = match creep_forces {
        CreepForces::Steady => 0.0,
        CreepForces::Transient => {
            let step_length = s.contact.model.fixed_grid().map_or(s.step_length, |f| f.dx);
            let steps = 10.0 * 2.0 * d.patch_mean.a / step_length;
            // 2 + 2 + 2 x 2 run-equivalents (+ 2 x 2 for the spin), two
            // at a time.
            let runs = if spin { 12.0 } else { 8.0 };
            classes * runs * steps * step / 2.0
        }
    };
    Some(DirectionsCost { tables, creep_response })
}

/// Peak memory (bytes): a base of 30 MB (program, HDF5, buffers; 20 MB
/// measured for growth_fastsim.toml, 33 MB for growth_discrete.toml), the
/// stored rail snapshots (profile and wear) twice (in memory and while the
/// run file is written), the stored patch histories, and the contact
/// model's matrices (the adapted exact model's influence matrices and
/// Newton Jacobian, about 40 N^2 bytes; the fixed grid's FFT tables, about
/// 2 kB per element); all times 1.5.
fn memory(s: &Scene, g: &crate::rail_grid::RailGrid, steps: usize, grid_elements: Option<usize>) -> f64 {
    let n_el = s.contact.model.mesh().map_or(0, |m| m.len()) as f64;
    let nodes = (g.nx * g.ny) as f64;
    let (snapshots, histories) = match &s.growth {
        Some(gr) => {
            (gr.passes.div_ceil(gr.store_every) + 1, gr.contact_history.iter().filter(|k| **k < gr.passes).count())
        }
        None => (1, 1),
    };
    let elements = grid_elements.map_or(n_el, |n| n as f64);
    let fields = if s.output.store_fields { 7.0 * 8.0 * elements } else { 0.0 };
    let history = (histories * steps) as f64 * (16.0 * 8.0 + fields);
    let solver = match grid_elements {
        Some(n) => 2e3 * n as f64,
        None if s.contact.model.kind() == ContactModelKind::ExactTransient => 40.0 * n_el * n_el,
        None => 1e3 * n_el,
    };
    1.5 * (30e6 + 2.0 * snapshots as f64 * nodes * 16.0 + history + solver)
}
