//! The `[contact]` section: the model, its discretisation (the adapted mesh
//! or the fixed grid) and its solver settings.

use super::reader::{Range, Section};
use super::{AUTO, ConfigError};
use crate::contact::PressureShape;
use crate::contact::friction::FrictionLaw;
use crate::contact::grid::{GridScheme, GridSolver};
use crate::contact::transient::StepSolver;
use crate::params::{ContactModelKind, FixedGridParams, GridKind, NormalContact, NormalKind};
use strum::VariantNames;
use toml::{Table, Value};

/// Default element length of the fixed grid along x (m), and so its step.
pub const DEFAULT_GRID_DX: f64 = 2e-4;
/// Default element width of the fixed grid along y (m).
pub const DEFAULT_GRID_DY: f64 = 5e-4;

/// Default size of the potential-contact grid with the profile in the
/// normal problem, relative to the largest Hertz patch, along x and y: a
/// trough whose curvature is half the wheel's lengthens the patch over it by
/// about 2^(1/3) = 1.26 (Hertz a ~ A^(-1/3)); a crest narrows it along x and
/// widens it across (at fixed load); 1.5 holds both up to about 70 % of
/// the wheel's curvature.
pub const DEFAULT_PROFILE_GRID_SCALE: f64 = 1.5;

/// Default `contact.profile_grid_scale` of the linear profile contact on
/// the fixed grid ([`crate::build::LINEAR_GRID_SCALE`]).
pub const DEFAULT_LINEAR_GRID_SCALE: f64 = crate::build::LINEAR_GRID_SCALE;

/// The keys of `[contact]` as read (each None when invalid).
pub(super) struct ContactKeys {
    pub model: Option<String>,
    pub nx: Option<usize>,
    pub ny: Option<usize>,
    pub tolerance: Option<f64>,
    pub eps: Option<f64>,
    pub bound: Option<String>,
    pub solver: Option<String>,
    /// `contact.normal` as read.
    pub normal: Option<String>,
    /// `contact.profile_grid_scale` (read for the nonlinear profile contact
    /// on the fixed grid).
    pub grid_scale: Option<f64>,
    /// `Some` for `grid = "fixed"`.
    pub fixed: Option<FixedKeys>,
}

/// The fixed grid's keys as read.
pub(super) struct FixedKeys {
    pub dx: Option<f64>,
    /// Whether the config gave `contact.dx`.
    pub dx_given: bool,
    pub dy: Option<f64>,
    pub law: Option<String>,
    pub scheme: Option<String>,
}

/// Reads `[contact]` from `root` into `resolved`.
pub(super) fn read(root: &mut Table, resolved: &mut Table, errors: &mut Vec<ConfigError>) -> ContactKeys {
    let mut s = Section::new(root, "", "contact", errors);
    let names = ContactModelKind::ALL.map(ContactModelKind::name);
    let model = s.choice("model", Some(ContactModelKind::Fastsim.name()), &[&names[..], &[AUTO]].concat());
    let auto = model.as_deref() == Some(AUTO);
    let grid = s.choice("grid", Some(GridKind::Adapted.into()), GridKind::VARIANTS);
    let fixed = grid.as_deref().and_then(|g| g.parse().ok()) == Some(GridKind::Fixed);
    // "auto" chooses the mesh and reads a tolerance; the other models take a
    // mesh and have no tolerance. The fixed grid ignores the adapted mesh's
    // keys and the other way round (so that `--set contact.grid=...`
    // switches a config over).
    let (nx, ny, tolerance) = if auto {
        for key in ["elements_x", "elements_y"] {
            if s.has(key) {
                s.usize(key, None, 2, 200);
                s.error(key, "is chosen by contact.model = \"auto\"; remove it, or name a model".into());
            }
        }
        (Some(0), Some(0), s.f64("tolerance", Some(0.1), Range::OpenClosed(0.0, 1.0)))
    } else {
        if s.has("tolerance") {
            s.f64("tolerance", None, Range::Finite);
            s.error("tolerance", "applies to contact.model = \"auto\" only; remove it, or set model = \"auto\"".into());
        }
        (s.usize("elements_x", Some(20), 2, 200), s.usize("elements_y", Some(20), 2, 200), Some(0.0))
    };
    let eps = s.f64("regularisation", Some(1e-5), Range::Positive);
    let bound = s.choice("fastsim_bound", Some(PressureShape::Parabolic.into()), PressureShape::VARIANTS);
    // One key names the fixed grid's solvers and the adapted mesh's.
    let mut solvers: Vec<&str> = GridSolver::VARIANTS.to_vec();
    solvers.extend(StepSolver::VARIANTS.iter().filter(|s| !GridSolver::VARIANTS.contains(s)));
    let solver = s.choice("solver", Some(GridSolver::Auto.name()), &solvers);
    let normal = s.choice("normal", Some(NormalKind::Auto.into()), NormalKind::VARIANTS);
    let normal_kind = normal.as_deref().and_then(|n| n.parse::<NormalKind>().ok());
    let default_scale = match normal_kind {
        Some(NormalKind::Profile | NormalKind::Auto) => Some(DEFAULT_PROFILE_GRID_SCALE),
        Some(NormalKind::Linear) => Some(DEFAULT_LINEAR_GRID_SCALE),
        _ => None,
    };
    let length_range = Range::Closed(1.0, 4.0);
    let grid_scale = if let Some(default) = default_scale.filter(|_| fixed || auto) {
        s.f64("profile_grid_scale", Some(default), length_range)
    } else {
        if s.has("profile_grid_scale") {
            s.f64("profile_grid_scale", None, length_range);
        }
        Some(1.0)
    };
    let fixed_keys = if fixed {
        let given = s.has("dx");
        let dx = s.f64("dx", Some(DEFAULT_GRID_DX), Range::OpenClosed(0.0, 0.01));
        let dy = s.f64("dy", Some(DEFAULT_GRID_DY), Range::OpenClosed(0.0, 0.01));
        let law = s.choice("friction_law", Some(FrictionLaw::default().name()), FrictionLaw::VARIANTS);
        let scheme = s.choice("scheme", Some(GridScheme::default().name()), GridScheme::VARIANTS);
        Some(FixedKeys { dx, dx_given: given, dy, law, scheme })
    } else {
        // The fixed grid's keys on the adapted mesh: checked, kept in the
        // resolved config, unused (so that `--set contact.grid=adapted`
        // switches a fixed-grid config over).
        for key in ["dx", "dy"] {
            if s.has(key) {
                s.f64(key, None, Range::OpenClosed(0.0, 0.01));
            }
        }
        if s.has("friction_law") {
            s.choice("friction_law", None, FrictionLaw::VARIANTS);
        }
        if s.has("scheme") {
            s.choice("scheme", None, GridScheme::VARIANTS);
        }
        None
    };
    resolved.insert("contact".into(), Value::Table(s.finish()));
    ContactKeys { model, nx, ny, tolerance, eps, bound, solver, normal, grid_scale, fixed: fixed_keys }
}

/// The normal contact named by `contact.normal` (None when invalid), for a
/// scene on the fixed grid or not (`chosen` by `contact.model = "auto"`).
pub(super) fn normal_contact(
    normal: Option<&str>,
    grid_scale: Option<f64>,
    fixed: bool,
    chosen: bool,
    errors: &mut Vec<ConfigError>,
) -> Option<NormalContact> {
    let grid_scale = if fixed { grid_scale? } else { 1.0 };
    // With contact.model = "auto" the grid is the choice's, not the key's.
    let by_auto = if chosen { " (contact.model = \"auto\" chose it)" } else { "" };
    Some(match normal?.parse::<NormalKind>().ok()? {
        NormalKind::Hertz => NormalContact::Hertz,
        NormalKind::Profile if !fixed => {
            errors.push(ConfigError::new(
                "contact.normal",
                format!(
                    "= \"profile\" solves the discrete (nonlinear) normal problem on the rail profile, which needs \
                     contact.grid = \"fixed\"; allowed with contact.grid = \"adapted\"{by_auto}: {}",
                    allowed_normal(NormalKind::Profile)
                ),
            ));
            return None;
        }
        NormalKind::Linear => NormalContact::Linear { grid_scale },
        NormalKind::Profile => NormalContact::Profile { grid_scale },
        NormalKind::Auto => NormalContact::Auto { grid_scale },
    })
}

/// The `contact.normal` names but `not` (the one the grid does not take).
fn allowed_normal(not: NormalKind) -> String {
    let not: &str = not.into();
    NormalKind::VARIANTS.iter().filter(|n| **n != not).copied().collect::<Vec<_>>().join(", ")
}

/// The fixed grid's `contact.solver` names.
pub(super) fn grid_solvers() -> String {
    GridSolver::VARIANTS.join(", ")
}

/// The step length of a fixed-grid passage: `passage.step_length` and
/// `contact.dx` must be equal (the patch moves one element per step); one
/// of them given sets the other. Patches `resolved` so that it records
/// both. Returns the fixed-grid parameters, if the grid is fixed (None when
/// invalid).
pub(super) fn reconcile_step(
    keys: &ContactKeys,
    step_length: Option<f64>,
    step_given: bool,
    resolved: &mut Table,
    errors: &mut Vec<ConfigError>,
) -> Option<Option<FixedGridParams>> {
    let Some(f) = &keys.fixed else {
        return Some(None);
    };
    let (dx, dy, law, scheme) = (f.dx?, f.dy?, f.law.as_deref()?, f.scheme.as_deref()?);
    let dx = match (f.dx_given, step_given, step_length) {
        (true, true, Some(h)) if (h - dx).abs() > 1e-9 * dx => {
            errors.push(ConfigError::new(
                "passage.step_length",
                format!(
                    "= {h} m must equal contact.dx = {dx} m with contact.grid = \"fixed\" (the patch moves one element \
                     per step); remove one of them or make them equal"
                ),
            ));
            return None;
        }
        (false, true, Some(h)) => h,
        _ => dx,
    };
    for (section, key) in [("contact", "dx"), ("passage", "step_length")] {
        if let Some(Value::Table(t)) = resolved.get_mut(section) {
            t.insert(key.into(), Value::Float(dx));
        }
    }
    Some(Some(FixedGridParams {
        dx,
        dy,
        friction_law: law.parse().expect("a validated choice"),
        scheme: scheme.parse().expect("a validated choice"),
        solver: GridSolver::Auto,
        linear_solver: GridSolver::Auto,
    }))
}

/// Checks that combine the model with its grid and solver.
pub(super) fn check_model(model: &str, grid: Option<&FixedGridParams>, solver: &str, errors: &mut Vec<ConfigError>) {
    let solver = (solver.parse::<GridSolver>().ok(), solver.parse::<StepSolver>().ok());
    if grid.is_some() {
        if model != ContactModelKind::ExactTransient.name() {
            errors.push(ConfigError::new(
                "contact.grid",
                format!(
                    "= \"fixed\" is a discretisation of the exact-transient model, not of contact.model = \"{model}\"; \
                     allowed with \"fixed\": exact-transient"
                ),
            ));
        }
        if solver.1 == Some(StepSolver::Newton) {
            errors.push(ConfigError::new(
                "contact.solver",
                format!(
                    "= \"newton\" is the adapted mesh's reference solver (dense Jacobian); allowed with contact.grid \
                     = \"fixed\": {}",
                    grid_solvers()
                ),
            ));
        }
    }
    // "cg" off the fixed grid: the adapted mesh takes Gauss-Seidel, as with
    // "auto" (kept, unused, like the fixed grid's other keys, so that
    // `--set contact.grid=adapted` switches a fixed-grid config over).
}

/// The fixed grid's tangential solver named by `contact.solver` (`auto`
/// for `newton`, which [`check_model`] refuses on the fixed grid).
pub(super) fn grid_solver(solver: &str) -> GridSolver {
    solver.parse().unwrap_or(GridSolver::Auto)
}

/// The FASTSIM traction bound and the adapted mesh's step solver named by
/// their keys (Gauss-Seidel for the fixed grid's `auto` and `cg`).
pub(super) fn bound_and_solver(bound: &str, solver: &str) -> (PressureShape, StepSolver) {
    (bound.parse().expect("a validated choice"), solver.parse().unwrap_or(StepSolver::GaussSeidel))
}

/// Largest potential-contact grid along x and y (elements): the folded
/// coupling table (half the rows squared, times 2 nx - 1 offsets, 4
/// components) is 256 MB there, and one step takes minutes.
pub const MAX_GRID: (usize, usize) = (400, 200);

/// The fixed grid of a valid scene must fit [`MAX_GRID`].
pub(super) fn check_grid_size(scene: &crate::params::Scene, errors: &mut Vec<ConfigError>) {
    let Some(f) = scene.contact.model.fixed_grid() else {
        return;
    };
    let shape = crate::build::derive(scene).shape;
    let s = crate::build::fixed_grid_spec(scene, &shape, f);
    let g = s.grid();
    if g.nx > MAX_GRID.0 || g.ny > MAX_GRID.1 {
        errors.push(ConfigError::new(
            if g.nx > MAX_GRID.0 { "contact.dx" } else { "contact.dy" },
            format!(
                "= {} m x {} m gives a potential-contact grid of {} x {} elements for the largest patch; at most {} x {} \
                 (use larger contact.dx / contact.dy)",
                f.dx, f.dy, g.nx, g.ny, MAX_GRID.0, MAX_GRID.1
            ),
        ));
    }
}

/// In a growth study the fixed grid's element (the step) must divide the
/// periodic stretch: a passage then deposits exactly one period of patch
/// travel. Otherwise one step more or less than a period is deposited, and
/// its wear, all at the wrap point, drives every harmonic (0.5 dB per 1e5
/// passages at 17 mm with 0.28 mm steps on 120 mm, scripts/growth_accuracy.sh).
pub(super) fn check_periodic_steps(scene: &crate::params::Scene, errors: &mut Vec<ConfigError>) {
    let (Some(f), Some(_)) = (scene.contact.model.fixed_grid(), &scene.growth) else {
        return;
    };
    let length = scene.rail.x_max - scene.rail.x_min;
    let steps = length / f.dx;
    if (steps - steps.round()).abs() > 1e-6 * steps.max(1.0) {
        let (fewer, more) = (length / steps.floor().max(1.0), length / steps.ceil());
        errors.push(ConfigError::new(
            "contact.dx",
            format!(
                "= {} m must divide the periodic stretch rail.x_max - rail.x_min = {length} m a whole number of times \
                 (it is {steps:.3} steps); e.g. {more:.6e} or {fewer:.6e} m",
                f.dx
            ),
        ));
    }
}
