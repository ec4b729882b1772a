//! The `[load]` section and the loads' checks against friction: the mean
//! forces, what is prescribed longitudinally (`load.control`: the force, or
//! the creepage `rolling.creepage_x`), the imposed harmonics; and the
//! loads of every traffic class and every wheel kept in contact and below
//! full sliding.

use super::ConfigError;
use super::reader::{Range, Section};
use super::traffic;
use crate::loads::{Harmonic, ImposedLoads, LoadQuantity};
use crate::params::{TrafficClass, VehicleParams};
use toml::{Table, Value};

/// The keys of `[load]`, each None where invalid (recorded).
pub(super) struct LoadKeys {
    /// Mean normal force (N).
    pub normal: Option<f64>,
    /// Mean longitudinal force (N; 0 under creepage control).
    pub longitudinal: Option<f64>,
    /// Imposed harmonics.
    pub harmonics: Option<Vec<Harmonic>>,
    /// The prescribed creepage (`Some(None)` under force control).
    pub creepage_x: Option<Option<f64>>,
}

/// Reads `[load]`; `(given, value)` is `rolling.creepage_x` as read (whether
/// the key was given, its value), checked here against `load.control`.
pub(super) fn read(
    root: &mut Table,
    resolved: &mut Table,
    (given, value): (bool, Option<f64>),
    errors: &mut Vec<ConfigError>,
) -> LoadKeys {
    let mut s = Section::new(root, "", "load", errors);
    let normal = s.f64("normal_force", None, Range::Positive);
    // Creepage control: the creepage rolling.creepage_x is prescribed and
    // the longitudinal force is the result; force control (the default):
    // the force is prescribed and the creepage found.
    let control = s.choice("control", Some("force"), &["force", "creepage"]);
    let by_creepage = control.as_deref() == Some("creepage");
    let longitudinal = if by_creepage {
        if s.has("longitudinal_force") {
            s.f64("longitudinal_force", None, Range::Finite);
            s.error(
                "longitudinal_force",
                "is a force, but load.control = \"creepage\" prescribes the creepage rolling.creepage_x (the force \
                 is its result): remove it, or set load.control = \"force\""
                    .into(),
            );
            None
        } else {
            Some(0.0)
        }
    } else {
        s.f64("longitudinal_force", None, Range::Finite)
    };
    let harmonics = s.array_of_tables("harmonics", read_harmonic);
    resolved.insert("load".into(), Value::Table(s.finish()));
    let creepage_x = match (control.as_deref(), given) {
        (Some("creepage"), false) => {
            errors.push(ConfigError::new(
                "rolling.creepage_x",
                "is required with load.control = \"creepage\" (the longitudinal creepage, in [-0.1, 0.1])".into(),
            ));
            None
        }
        (Some("creepage"), true) => value.map(Some),
        (_, true) => {
            errors.push(ConfigError::new(
                "rolling.creepage_x",
                "is a creepage, but load.control = \"force\" (the default) prescribes load.longitudinal_force and \
                 finds the creepage: remove it, or set load.control = \"creepage\""
                    .into(),
            ));
            None
        }
        _ => Some(None),
    };
    if by_creepage && let Some(hs) = &harmonics {
        for (i, h) in hs.iter().enumerate().filter(|(_, h)| h.quantity == LoadQuantity::LongitudinalForce) {
            errors.push(ConfigError::new(
                &format!("load.harmonics[{i}].quantity"),
                format!(
                    "= \"longitudinal_force\" (amplitude {} N) is a force, but load.control = \"creepage\" \
                     prescribes the creepage",
                    h.amplitude
                ),
            ));
        }
    }
    LoadKeys { normal, longitudinal, harmonics, creepage_x }
}

/// Each traffic class of a mix must keep contact where it pulls and stay
/// below full sliding, as [`check_loads`] requires of `[load]` (the one
/// class of a study without `[traffic]` is `[load]` itself).
pub(super) fn check_classes(classes: &[TrafficClass], loads: &ImposedLoads, mu: f64, errors: &mut Vec<ConfigError>) {
    if !traffic::is_mix(classes) {
        return;
    }
    for (i, c) in classes.iter().enumerate() {
        let (key, message) = match load_problem(&c.loads(loads), mu) {
            Some(LoadProblem::PullsWithoutContact { n_min, f_max }) => (
                "normal_force",
                format!(
                    "= {:.6e} N: with the load.harmonics the normal force reaches {n_min:.6e} N <= 0 (contact lost) \
                     while the class pulls with |F_x| up to {f_max:.6e} N; it must stay > 0",
                    c.normal_force
                ),
            ),
            Some(LoadProblem::FullSliding { limit, f_max }) => (
                "longitudinal_force",
                format!(
                    "= {:.6e} N: |F_x| reaches {f_max:.6e} N, which must be < mu * min N = {limit:.6e} N (full sliding)",
                    c.longitudinal_force
                ),
            ),
            None => continue,
        };
        errors.push(ConfigError::new(&format!("traffic.mix[{i}].{key}"), message));
    }
}

/// Why imposed loads cannot be run.
enum LoadProblem {
    /// N reaches `n_min` <= 0 (contact lost) while |F_x| reaches `f_max` > 0.
    PullsWithoutContact {
        /// Smallest normal force (N).
        n_min: f64,
        /// Largest |F_x| (N).
        f_max: f64,
    },
    /// |F_x| reaches `f_max` >= `limit` = mu min N.
    FullSliding {
        /// mu times the smallest normal force (N).
        limit: f64,
        /// Largest |F_x| (N).
        f_max: f64,
    },
}

impl LoadProblem {
    /// The problem in words.
    fn describe(&self) -> String {
        match self {
            LoadProblem::PullsWithoutContact { n_min, f_max } => {
                format!("N reaches {n_min:.6e} N <= 0 (contact lost) while |F_x| reaches {f_max:.6e} N")
            }
            LoadProblem::FullSliding { limit, f_max } => {
                format!("|F_x| reaches {f_max:.6e} N, which must be < mu * min N = {limit:.6e} N (full sliding)")
            }
        }
    }
}

/// What keeps the wheelset's second rail's loads (`second`, the first
/// rail's harmonics kept) from being run with friction `mu`, in words.
pub(super) fn second_rail_problem(second: &ImposedLoads, mu: f64) -> Option<String> {
    match load_problem(second, mu) {
        Some(p) => Some(p.describe()),
        None if second.min_normal_force() <= 0.0 => Some(format!(
            "N reaches {:.6e} N <= 0 with load.harmonics: the second rail's wheel leaves its rail",
            second.min_normal_force()
        )),
        None => None,
    }
}

/// What keeps `loads` from being run with friction `mu`, if anything.
fn load_problem(loads: &ImposedLoads, mu: f64) -> Option<LoadProblem> {
    let (n_min, f_max) = (loads.min_normal_force(), loads.max_longitudinal_force());
    if n_min <= 0.0 && f_max > 0.0 {
        Some(LoadProblem::PullsWithoutContact { n_min, f_max })
    } else if n_min > 0.0 && f_max >= mu * n_min {
        Some(LoadProblem::FullSliding { limit: mu * n_min, f_max })
    } else {
        None
    }
}

fn read_harmonic(s: &mut Section) -> Option<Harmonic> {
    let quantity = s.choice("quantity", None, &["normal_force", "longitudinal_force"]);
    let amplitude = s.f64("amplitude", None, Range::NonNegative);
    let wavelength = s.f64("wavelength", None, Range::OpenClosed(0.0, 1000.0));
    let phase = s.f64("phase", Some(0.0), Range::Finite);
    let quantity =
        if quantity? == "normal_force" { LoadQuantity::NormalForce } else { LoadQuantity::LongitudinalForce };
    Some(Harmonic { quantity, amplitude: amplitude?, wavelength: wavelength?, phase: phase? })
}

pub(super) fn check_loads(loads: &ImposedLoads, mu: f64, rail_dx: Option<f64>, errors: &mut Vec<ConfigError>) {
    match load_problem(loads, mu) {
        Some(LoadProblem::PullsWithoutContact { n_min, f_max }) => errors.push(ConfigError::new(
            "load.harmonics",
            format!(
                "normal-force amplitudes sum to {:.6e} N >= load.normal_force = {:.6e} N: contact is lost where N <= 0, \
                 which is only allowed with no longitudinal force (|F_x| reaches {f_max:.6e} N)",
                loads.normal_force - n_min,
                loads.normal_force
            ),
        )),
        Some(p @ LoadProblem::FullSliding { .. }) => {
            errors.push(ConfigError::new("load.longitudinal_force", p.describe()))
        }
        None => {}
    }
    if let Some(dx) = rail_dx {
        for (i, h) in loads.harmonics.iter().enumerate() {
            if h.wavelength < 2.0 * dx {
                errors.push(ConfigError::new(
                    &format!("load.harmonics[{i}].wavelength"),
                    format!("= {} m is shorter than two rail-grid cells (2 * rail.dx = {} m)", h.wavelength, 2.0 * dx),
                ));
            }
        }
    }
}

/// Each wheel's own loads (`[vehicle]` per wheel) against friction.
pub(super) fn check_wheel_loads(vehicle: &VehicleParams, loads: &ImposedLoads, mu: f64, errors: &mut Vec<ConfigError>) {
    if vehicle.normal_force.is_none() && vehicle.longitudinal_force.is_none() {
        return;
    }
    let key = if vehicle.longitudinal_force.is_some() { "longitudinal_force" } else { "normal_force" };
    for i in 0..vehicle.wheels.len() {
        if let Some(problem) = load_problem(&vehicle.wheel_loads(i, loads), mu) {
            errors
                .push(ConfigError::new(&format!("vehicle.{key}"), format!("wheel {}: {}", i + 1, problem.describe())));
        }
    }
}
