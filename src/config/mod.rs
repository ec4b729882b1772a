//! Scene configuration: TOML text -> validated [`Scene`].
//!
//! Every key is documented in the book's configuration reference
//! (`docs/src/reference/configuration.md`, checked against [`schema`]). Unknown
//! keys, missing keys, wrong types and out-of-range values are all collected
//! and reported together, each naming its dotted key and the allowed range;
//! then the cross-checks that need several keys (curvature sign, load
//! amplitudes against the mean, the friction limit, wavelengths against the
//! rail grid, Kalker's table range) run on the keys that were valid.

mod auto;
mod consistency;
pub mod contact;
pub mod curve;
mod friction;
mod growth;
mod levels;
mod load;
mod overrides;
pub mod quantity;
mod reader;
pub mod record;
pub mod roughness;
pub mod schema;
mod second_rail;
mod spectrum;
mod track;
pub mod traffic;
pub mod units;
pub mod vehicle;
mod wear;
pub mod wheelset;

use consistency::{check_geometry, check_growth, check_sleeper_bays, plausibility};

use crate::contact::friction::FrictionLaw;
use crate::contact::grid::GridScheme;
use crate::creep_coefficients::creep_coefficients;
use crate::dynamics::track::layout::LayoutSpec;
use crate::hertz::{Elastic, HertzShape};
use crate::loads::ImposedLoads;
use crate::model_choice::FIXED_ASPECT;
use crate::params::{
    ContactGrid, ContactModel, ContactModelKind, ContactParams, FixedGridParams, Geometry, Material, Mesh,
    OutputParams, RailParams, Scene,
};
pub use auto::AUTO;
pub use contact::{DEFAULT_GRID_DX, DEFAULT_GRID_DY};
use reader::{Range, Section};
pub use roughness::RecordSource;
use std::fmt;
use std::path::Path;
use toml::{Table, Value};

/// One problem with one key.
#[derive(Debug, Clone, PartialEq)]
pub struct ConfigError {
    /// Dotted key (or `--set ...`).
    pub key: String,
    /// What is wrong and what is allowed.
    pub message: String,
}

impl ConfigError {
    /// A new error on `key`.
    pub fn new(key: &str, message: String) -> Self {
        ConfigError { key: key.to_string(), message }
    }
}

impl fmt::Display for ConfigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.key, self.message)
    }
}

/// All problems found in a config.
#[derive(Debug, Clone, PartialEq)]
pub struct ConfigErrors {
    /// Where the config came from.
    pub source: String,
    /// The problems, in reading order.
    pub errors: Vec<ConfigError>,
}

impl fmt::Display for ConfigErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "invalid config {} ({} problem{}):",
            self.source,
            self.errors.len(),
            if self.errors.len() == 1 { "" } else { "s" }
        )?;
        for e in &self.errors {
            writeln!(f, "  - {e}")?;
        }
        Ok(())
    }
}

impl std::error::Error for ConfigErrors {}

/// A validated scene and its resolved config (defaults filled in).
#[derive(Debug, Clone)]
pub struct Resolved {
    /// The typed parameters.
    pub scene: Scene,
    /// The resolved config as TOML text (stored in the run file).
    pub toml: String,
    /// Notes on values that look like unit mistakes (a number written
    /// without its unit outside the key's usual range); the run goes on.
    pub warnings: Vec<String>,
    /// The `[curve]` section's steady curving, where the config has one.
    pub curve: Option<curve::CurveSetup>,
}

/// Reads and validates the config file at `path` with `--set` overrides
/// (files it names are relative to its folder).
pub fn load_file(path: &Path, overrides: &[String]) -> Result<Resolved, ConfigErrors> {
    let source = path.display().to_string();
    if is_hdf5(path) {
        return Err(ConfigErrors {
            source,
            errors: vec![ConfigError::new(
                "file",
                format!(
                    "is an HDF5 run file, not a config (TOML): `corrugation resume {}` continues it; its config is \
                     stored in it (h5dump -a config, or xarray's attrs[\"config\"])",
                    path.display()
                ),
            )],
        });
    }
    let text = std::fs::read_to_string(path).map_err(|e| ConfigErrors {
        source: source.clone(),
        errors: vec![ConfigError::new("file", format!("cannot read: {e}"))],
    })?;
    let dir = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    load_str_with(&text, &source, overrides, &RecordSource::Dir(dir.to_path_buf()))
}

/// Whether the file at `path` starts with the HDF5 signature (at offset 0
/// or at one of the user-block offsets 512, 1024, 2048).
pub fn is_hdf5(path: &Path) -> bool {
    use std::io::Read;
    const SIGNATURE: &[u8; 8] = b"\x89HDF\r\n\x1a\n";
    let mut head = [0u8; 2056];
    let Ok(mut f) = std::fs::File::open(path) else { return false };
    let mut n = 0;
    while n < head.len() {
        match f.read(&mut head[n..]) {
            Ok(0) | Err(_) => break,
            Ok(k) => n += k,
        }
    }
    [0, 512, 1024, 2048].iter().any(|&o| n >= o + 8 && &head[o..o + 8] == SIGNATURE)
}

/// Validates config `text` (from `source`, for messages) with overrides; a
/// measured record's path is taken relative to the current folder.
pub fn load_str(text: &str, source: &str, overrides: &[String]) -> Result<Resolved, ConfigErrors> {
    load_str_with(text, source, overrides, &RecordSource::Dir(".".into()))
}

/// Validates config `text` with overrides, a measured record from `records`.
pub fn load_str_with(
    text: &str,
    source: &str,
    overrides: &[String],
    records: &RecordSource,
) -> Result<Resolved, ConfigErrors> {
    let fail = |errors| ConfigErrors { source: source.to_string(), errors };
    let mut root: Table = text.parse().map_err(|e: toml::de::Error| {
        fail(vec![ConfigError::new("TOML syntax", e.to_string().trim().replace('\n', "\n    "))])
    })?;
    // The file's config with defaults filled in says which keys hold strings
    // (the track's too where the config does not read it: a single passage).
    let defaults = if overrides.is_empty() {
        Table::new()
    } else {
        let mut d = read_scene(root.clone(), records, &mut Vec::new()).1;
        if !d.contains_key("track") {
            track::read(&mut Table::new(), &mut d, &mut Vec::new());
        }
        d
    };
    let mut errors: Vec<ConfigError> =
        overrides.iter().filter_map(|o| overrides::apply(&mut root, o, &defaults).err()).collect();
    overridden_step_sets_both(&mut root, overrides);
    let mut warnings = Vec::new();
    plausibility(&root, "", &mut warnings);
    let dir = match records {
        RecordSource::Dir(d) => d.clone(),
        RecordSource::Stored(_) => std::path::PathBuf::from("."),
    };
    let curve = curve::apply(&mut root, &dir, &mut errors);
    let (scene, mut resolved) = read_scene(root, records, &mut errors);
    let curve = curve.map(|(table, setup)| {
        resolved.insert("curve".into(), Value::Table(table));
        setup
    });
    if matches!(curve, Some(None)) {
        // A curve that failed (its own errors say why) sets no keys.
        errors.retain(|e| !(curve::SETS.contains(&e.key.as_str()) && e.message.starts_with("missing")));
    }
    match scene {
        Some(scene) if errors.is_empty() => Ok(Resolved {
            scene,
            toml: toml::to_string(&resolved).expect("resolved config serialises"),
            warnings,
            curve: curve.flatten(),
        }),
        _ => Err(fail(errors)),
    }
}

/// The sections of a config, in the order they are documented.
pub const SECTIONS: [&str; 19] = [
    "material",
    "geometry",
    "rolling",
    "load",
    "contact",
    "wear",
    "passage",
    "rail",
    "output",
    "growth",
    "roughness",
    "dynamics",
    "traffic",
    "vehicle",
    "wheelset",
    "second_rail",
    "track",
    "spectrum",
    "curve",
];

/// On the fixed grid the step is the element: `--set contact.dx` or
/// `--set passage.step_length` alone sets both, so the file's value of the
/// other key, which the override would contradict, is dropped.
fn overridden_step_sets_both(root: &mut Table, overrides: &[String]) {
    let grid = root.get("contact").and_then(|c| c.get("grid")).and_then(Value::as_str);
    let fixed = grid.and_then(|g| g.parse().ok()) == Some(crate::params::GridKind::Fixed);
    let set = |key: &str| overrides.iter().any(|o| o.split_once('=').is_some_and(|(k, _)| k.trim() == key));
    let other = match (set("contact.dx"), set("passage.step_length")) {
        (true, false) => ("passage", "step_length"),
        (false, true) => ("contact", "dx"),
        _ => return,
    };
    // Only a valid value replaces the file's other key (an invalid one is
    // reported as such, and the file's key stays).
    let given = if other.0 == "passage" { ("contact", "dx") } else { ("passage", "step_length") };
    let value = root.get(given.0).and_then(|t| t.get(given.1));
    let valid = value.and_then(|v| quantity::number(v, "m")).is_some_and(|v| v > 0.0 && v <= 0.01);
    if fixed
        && valid
        && let Some(Value::Table(t)) = root.get_mut(other.0)
    {
        t.remove(other.1);
    }
}

/// Sections and their readers, in the order they are documented.
fn read_scene(mut root: Table, records: &RecordSource, errors: &mut Vec<ConfigError>) -> (Option<Scene>, Table) {
    // Files other than a measured record (levels.limit_file) are read
    // relative to the config's folder; a resumed run has their contents.
    let dir = match records {
        RecordSource::Dir(d) => d.as_path(),
        RecordSource::Stored(_) => Path::new("."),
    };
    let mut resolved = Table::new();
    fn section<'e>(root: &mut Table, name: &str, errors: &'e mut Vec<ConfigError>) -> Section<'e> {
        Section::new(root, "", name, errors)
    }

    let mut s = section(&mut root, "material", errors);
    let young = s.f64("young_modulus", None, Range::Positive);
    let nu = s.f64("poisson_ratio", None, Range::ClosedOpen(0.0, 0.5));
    let mu = s.f64("friction_coefficient", None, Range::OpenClosed(0.0, 1.0));
    let characteristic = friction::read(&mut s, mu);
    resolved.insert("material".into(), Value::Table(s.finish()));

    let mut s = section(&mut root, "geometry", errors);
    let wheel_radius = s.f64("wheel_radius", None, Range::Positive);
    let profile = s.f64("wheel_profile_radius", None, Range::NonZeroOrInf);
    let rail_head = s.f64("rail_head_radius", None, Range::PositiveOrInf);
    resolved.insert("geometry".into(), Value::Table(s.finish()));

    let mut s = section(&mut root, "rolling", errors);
    let speed = s.f64("speed", None, Range::OpenClosed(0.0, 200.0));
    let creepage_x_given = s.has("creepage_x");
    // (Recorded in the resolved config only where given: force control has none.)
    let creepage_x = if creepage_x_given { s.f64("creepage_x", None, Range::Closed(-0.1, 0.1)) } else { Some(0.0) };
    let creepage_y = s.f64("creepage_y", Some(0.0), Range::Closed(-0.1, 0.1));
    let spin = s.f64("spin", Some(0.0), Range::Closed(-100.0, 100.0));
    resolved.insert("rolling".into(), Value::Table(s.finish()));

    let load::LoadKeys { normal, longitudinal, harmonics, creepage_x } =
        load::read(&mut root, &mut resolved, (creepage_x_given, creepage_x), errors);

    let contact = contact::read(&mut root, &mut resolved, errors);

    let mut s = section(&mut root, "wear", errors);
    let wear_law = wear::read(&mut s);
    let substeps = s.usize("substeps", Some(4), 1, 64);
    resolved.insert("wear".into(), Value::Table(s.finish()));

    let mut s = section(&mut root, "passage", errors);
    let start = s.f64("start", None, Range::Finite);
    let end = s.f64("end", None, Range::Finite);
    // With the fixed grid the step is the element length: either key sets it.
    let step_given = s.has("step_length");
    let step_default = contact.fixed.as_ref().and_then(|f| f.dx);
    let step_length = s.f64("step_length", step_default, Range::OpenClosed(0.0, 0.01));
    resolved.insert("passage".into(), Value::Table(s.finish()));

    let mut s = section(&mut root, "rail", errors);
    let x_min = s.f64("x_min", None, Range::Finite);
    let x_max = s.f64("x_max", None, Range::Finite);
    let dx = s.f64("dx", None, Range::OpenClosed(0.0, 0.01));
    let dy = s.f64("dy", None, Range::OpenClosed(0.0, 0.01));
    let half_width = s.f64("half_width", None, Range::OpenClosed(0.0, 0.1));
    resolved.insert("rail".into(), Value::Table(s.finish()));

    let mut s = section(&mut root, "output", errors);
    let store_fields = s.bool("store_fields", true);
    let title = s.string("title", "");
    resolved.insert("output".into(), Value::Table(s.finish()));
    let base =
        traffic::BaseClass { speed, normal_force: normal, longitudinal_force: longitudinal, unsprung_mass: None };
    let stretch = match (x_min, x_max) {
        (Some(a), Some(b)) if b > a => Some((a, b)),
        _ => None,
    };
    let ctx = roughness::Context { source: records, stretch, wheel_radius };
    let growth = growth::read(&mut root, &mut resolved, base, &ctx, errors);
    let spectrum = spectrum::read(
        &mut root,
        &mut resolved,
        growth.as_ref().is_ok_and(|g| g.is_some()),
        stretch.map(|(a, b)| b - a),
        errors,
    );
    let levels = levels::read(&mut root, &mut resolved, dir, errors);
    let vehicle = vehicle::read(&mut root, &mut resolved, errors);
    let wheelset = wheelset::read(&mut root, &mut resolved, dir, errors);
    let first_rail =
        second_rail::FirstRail { normal_force: normal, longitudinal_force: longitudinal, creepage_x, creepage_y, spin };
    let second = second_rail::read(&mut root, &mut resolved, first_rail, errors);
    // The track matters to growth studies (and is read when given).
    let track = if growth.as_ref().is_ok_and(|g| g.is_some()) || root.contains_key("track") {
        track::read(&mut root, &mut resolved, errors)
    } else {
        Some((Default::default(), LayoutSpec::uniform()))
    };

    for (k, _) in root {
        let message = match reader::nearest(&k, SECTIONS.iter().copied()) {
            Some(near) => format!("unknown section or key; did you mean [{near}]?"),
            None => format!("unknown section or key; the sections are {}", SECTIONS.join(", ")),
        };
        errors.push(ConfigError::new(&k, message));
    }

    // Everything below needs the keys it combines to be valid.
    let (Some(young), Some(nu), Some(mu), Some(characteristic), Some(wheel_radius), Some(profile), Some(rail_head)) =
        (young, nu, mu, characteristic, wheel_radius, profile, rail_head)
    else {
        return (None, resolved);
    };
    let (characteristic, memory) = characteristic;
    let material =
        Material { elastic: Elastic { young_modulus: young, poisson_ratio: nu }, friction: mu, characteristic, memory };
    let geometry = Geometry { wheel_radius, wheel_profile_radius: profile, rail_head_radius: rail_head };
    let shape = check_geometry(&material, &geometry, errors);

    let (
        Some(speed),
        Some(creepage_x),
        Some(creepage_y),
        Some(spin),
        Some(normal),
        Some(longitudinal),
        Some(harmonics),
    ) = (speed, creepage_x, creepage_y, spin, normal, longitudinal, harmonics)
    else {
        return (None, resolved);
    };
    let loads = ImposedLoads { normal_force: normal, longitudinal_force: longitudinal, harmonics };
    load::check_loads(&loads, mu, dx, errors);

    let Some(mut fixed_grid) = contact::reconcile_step(&contact, step_length, step_given, &mut resolved, errors) else {
        return (None, resolved);
    };
    let step_length = match fixed_grid {
        Some(f) => Some(f.dx),
        None => step_length,
    };
    let contact::ContactKeys { model, nx, ny, tolerance, eps, bound, solver, normal: normal_key, grid_scale, .. } =
        contact;
    let (Some(model), Some(nx), Some(ny), Some(eps), Some(bound), Some(solver), Some(tolerance)) =
        (model, nx, ny, eps, bound, solver, tolerance)
    else {
        return (None, resolved);
    };
    contact::check_model(&model, fixed_grid.as_ref(), &solver, errors);
    if let Some(f) = &mut fixed_grid {
        f.solver = contact::grid_solver(&solver);
        f.linear_solver = f.solver;
    }
    let (Some(wear), Some(substeps), Some(start), Some(end), Some(mut step_length)) =
        (wear_law, substeps, start, end, step_length)
    else {
        return (None, resolved);
    };
    if end <= start {
        errors.push(ConfigError::new("passage.end", format!("= {end} must be > passage.start = {start}")));
    } else if (end - start) / step_length > 1e6 {
        errors.push(ConfigError::new(
            "passage.step_length",
            format!("gives {:.0} steps; at most 1e6 allowed", (end - start) / step_length),
        ));
    }
    let (Some(x_min), Some(x_max), Some(dx), Some(dy), Some(half_width), Some(store_fields), Some(title)) =
        (x_min, x_max, dx, dy, half_width, store_fields, title)
    else {
        return (None, resolved);
    };
    if x_max <= x_min {
        errors.push(ConfigError::new("rail.x_max", format!("= {x_max} must be > rail.x_min = {x_min}")));
    } else if ((x_max - x_min) / dx) * (2.0 * half_width / dy) > 5e7 {
        errors.push(ConfigError::new(
            "rail.dx",
            "the rail grid would have more than 5e7 nodes; use a larger rail.dx / rail.dy or a shorter stretch".into(),
        ));
    }
    let (Some(vehicle), Some(wheelset), Some(levels), Some(second_rail)) = (vehicle, wheelset, levels, second) else {
        return (None, resolved);
    };
    // The wheelset `auto` takes for this study.
    let (wheelset, wheelset_choice) = match &growth {
        Ok(g) => wheelset::resolve(wheelset, g.as_ref(), creepage_x.is_some()),
        Err(()) => return (None, resolved),
    };
    let Some((track, layout_spec)) = track else {
        return (None, resolved);
    };
    let Ok(growth) = growth else {
        return (None, resolved);
    };
    // The largest normal force of any traffic class.
    let max_normal = match &growth {
        Some(g) => {
            load::check_classes(&g.classes, &loads, mu, errors);
            g.classes.iter().map(|c| vehicle.max_normal_force(&c.loads(&loads))).fold(0.0, f64::max)
        }
        None => vehicle.max_normal_force(&loads),
    };
    // The second rail's patch must fit the rail grid too.
    let max_normal = max_normal.max(
        second_rail
            .as_ref()
            .map_or(0.0, |r| ImposedLoads { normal_force: r.normal_force, ..loads.clone() }.max_normal_force()),
    );
    load::check_wheel_loads(&vehicle, &loads, mu, errors);
    if let Some(p) = shape.and_then(|s| s.patch(max_normal).ok())
        && half_width < p.b
    {
        errors.push(ConfigError::new(
            "rail.half_width",
            format!(
                "= {half_width} m is narrower than the largest patch half-width b = {:.4e} m (at N = {max_normal:.6e} N); \
                 it must be >= b",
                p.b
            ),
        ));
    }
    if let (Some(g), Some(_)) = (&growth, creepage_x) {
        for (i, c) in g.classes.iter().enumerate().filter(|(_, c)| c.longitudinal_force != 0.0) {
            errors.push(ConfigError::new(
                &format!("traffic.mix[{i}].longitudinal_force"),
                format!(
                    "= {} N is a force, but load.control = \"creepage\" prescribes the creepage rolling.creepage_x",
                    c.longitudinal_force
                ),
            ));
        }
    }
    if let Some(g) = &growth {
        check_growth(g, &loads, max_normal, start, end, (x_min, x_max, dx), shape.as_ref(), errors);
    }
    let (fastsim_bound, step_solver) = contact::bound_and_solver(&bound, &solver);
    let (model, nx, ny, auto) = if model == AUTO {
        if step_solver == crate::contact::transient::StepSolver::Newton {
            errors.push(ConfigError::new(
                "contact.solver",
                format!(
                    "= \"newton\" cannot go with contact.model = \"auto\": the map's costs are those of the \
                     gauss-seidel solver (same results, 7x faster at 20 x 20); allowed: {}",
                    contact::grid_solvers()
                ),
            ));
        }
        let Some(shape) = shape.as_ref() else {
            return (None, resolved);
        };
        let Some(mut choice) = auto::resolve(tolerance, &loads, growth.as_ref(), shape, errors) else {
            return (None, resolved);
        };
        choice.hertz_difference = auto::hertz_difference(growth.as_ref(), x_max - x_min, dx);
        // The fixed grid of the map: its element, dy = 2.5 dx, the step the
        // element (the map measured it so); the adapted mesh n x n.
        let chosen = choice.chosen;
        let mesh = match chosen.grid_dx() {
            Some(dx) => {
                // A growth study's step must divide its stretch: the next
                // finer element that does (at least as accurate).
                let length = x_max - x_min;
                let dx = if growth.is_some() { length / (length / dx - 1e-9).ceil() } else { dx };
                fixed_grid = Some(FixedGridParams {
                    dx,
                    dy: FIXED_ASPECT * dx,
                    friction_law: FrictionLaw::Regularised,
                    scheme: GridScheme::SecondOrder,
                    solver: contact::grid_solver(&solver),
                    linear_solver: contact::grid_solver(&solver),
                });
                step_length = dx;
                nx
            }
            None => chosen.mesh,
        };
        (chosen.model, mesh, mesh, Some(choice))
    } else {
        (model.parse().expect("a validated choice"), nx, ny, None)
    };
    let Some(normal_contact) =
        contact::normal_contact(normal_key.as_deref(), grid_scale, fixed_grid.is_some(), auto.is_some(), errors)
    else {
        return (None, resolved);
    };
    let mesh = Mesh { nx, ny };
    let contact_model = match (model, fixed_grid) {
        (ContactModelKind::Fastsim, _) => ContactModel::Fastsim { mesh, bound: fastsim_bound },
        (ContactModelKind::SimplifiedTransient, _) => ContactModel::SimplifiedTransient { mesh, bound: fastsim_bound },
        (ContactModelKind::ExactTransient, Some(f)) => ContactModel::ExactTransient(ContactGrid::Fixed(f)),
        (ContactModelKind::ExactTransient, None) => {
            ContactModel::ExactTransient(ContactGrid::Adapted { mesh, solver: step_solver })
        }
    };
    let layout = track::layout(&track, &layout_spec, stretch, growth.as_ref().map(|g| g.dynamics), errors);
    let mut scene = Scene {
        material,
        geometry,
        speed,
        creepage_x,
        creepage_y,
        spin,
        loads,
        contact: ContactParams { model: contact_model, regularisation: eps, auto, normal: normal_contact },
        wear,
        wear_substeps: substeps,
        start,
        end,
        step_length,
        rail: RailParams { x_min, x_max, dx, dy, half_width },
        output: OutputParams { store_fields, title },
        levels,
        growth,
        track,
        layout,
        vehicle,
        wheelset,
        wheelset_choice,
        second_rail,
        spectrum,
    };
    second_rail::check(&mut scene, errors);
    check_sleeper_bays(&scene, errors);
    vehicle::check(&scene, errors);
    wheelset::check(&scene, errors);
    contact::check_grid_size(&scene, errors);
    contact::check_periodic_steps(&scene, errors);
    // contact.solver = "auto" on the fixed grid: the cheaper tangential
    // solver by the cost model (the config keeps "auto"), for the scene's
    // normal contact and for the linear contact's passages of "auto".
    if errors.is_empty() && scene.contact.model.fixed_grid().is_some() {
        let choice = crate::cost::auto_grid_solver(&scene);
        let mut linear = scene.clone();
        linear.contact.normal = crate::params::NormalContact::Linear { grid_scale: crate::build::LINEAR_GRID_SCALE };
        let linear_choice = crate::cost::auto_grid_solver(&linear);
        if let ContactModel::ExactTransient(ContactGrid::Fixed(f)) = &mut scene.contact.model {
            f.solver = choice;
            f.linear_solver = linear_choice;
        }
    }
    (Some(scene), resolved)
}
