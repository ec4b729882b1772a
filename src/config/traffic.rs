//! Section `[traffic]` of a growth study: the mix of wheel classes,
//! `[[traffic.mix]]`, and the traffic in the operator's units. Each class's
//! `speed`, `normal_force`, `longitudinal_force` and `unsprung_mass` default
//! to the base config's `rolling.speed`, `load.normal_force`,
//! `load.longitudinal_force` and `dynamics.unsprung_mass`; `share` is
//! required (relative, normalised to sum 1). Without `mix` (or without the
//! section) the study has one class, the base config.
//!
//! The operator's units, all optional (the run file then gives the traffic
//! in million gross tonnes and days beside the wheel passages):
//! `axle_load` (kg, gross mass per axle; a class's own `axle_load` in
//! `[[traffic.mix]]` overrides it), and `axles_per_day` (axles over the
//! rail per day, each a wheel passage of the rail) or `trains_per_day`
//! with `axles_per_train`. Keys not given are not added to the resolved
//! config (configs without them resolve as before).

use super::ConfigError;
use super::reader::{Range, Section};
use crate::params::{Operation, TrafficClass};
use toml::{Table, Value};

/// The most classes a mix may have.
pub const MAX_CLASSES: usize = 64;

/// The base config's values a class defaults to (None where the base key
/// itself is invalid: its error is already recorded).
#[derive(Debug, Clone, Copy)]
pub struct BaseClass {
    /// `rolling.speed` (m/s).
    pub speed: Option<f64>,
    /// `load.normal_force` (N).
    pub normal_force: Option<f64>,
    /// `load.longitudinal_force` (N).
    pub longitudinal_force: Option<f64>,
    /// `dynamics.unsprung_mass` (kg).
    pub unsprung_mass: Option<f64>,
}

pub use crate::params::{BASE_NAME, is_mix};

/// The one class of a study without a mix: the base values.
fn base_class(base: BaseClass) -> Option<TrafficClass> {
    let BaseClass { speed, normal_force, longitudinal_force, unsprung_mass } = base;
    Some(TrafficClass {
        name: BASE_NAME.into(),
        speed: speed?,
        normal_force: normal_force?,
        longitudinal_force: longitudinal_force?,
        unsprung_mass: unsprung_mass?,
        share: 1.0,
        wheels: None,
    })
}

/// Reads `[traffic]`: the classes with their shares normalised (or one
/// class of the base values) and the traffic in the operator's units.
/// `None` when a key is invalid (recorded).
pub fn read(
    root: &mut Table,
    resolved: &mut Table,
    base: BaseClass,
    errors: &mut Vec<ConfigError>,
) -> Option<(Vec<TrafficClass>, Operation)> {
    if !root.contains_key("traffic") {
        return Some((vec![base_class(base)?], Operation::default()));
    }
    let mut s = Section::new(root, "", "traffic", errors);
    let operation = read_operation(&mut s);
    if !s.has("mix") {
        let class = base_class(base);
        resolved.insert("traffic".into(), Value::Table(s.finish()));
        let (operation, class) = (operation?, class?);
        let axle_loads = operation.axle_load.map(|a| vec![a]);
        return Some((vec![class], Operation { axle_loads, axles_per_day: operation.axles_per_day }));
    }
    let mut index = 0;
    let classes = s.array_of_tables("mix", |c| {
        let class = read_class(c, index, base);
        index += 1;
        class
    });
    let classes = match classes {
        Some(cs) if cs.is_empty() => {
            s.error("mix", "must list at least one class ([[traffic.mix]])".into());
            None
        }
        Some(cs) if cs.len() > MAX_CLASSES => {
            s.error("mix", format!("lists {} classes; at most {MAX_CLASSES} allowed", cs.len()));
            None
        }
        Some(cs) => {
            let mut seen = std::collections::HashSet::new();
            if let Some((i, (c, _))) = cs.iter().enumerate().find(|(_, (c, _))| !seen.insert(c.name.clone())) {
                s.error(
                    &format!("mix[{i}].name"),
                    format!("= \"{}\" names an earlier class too; names must differ", c.name),
                );
                None
            } else {
                Some(cs)
            }
        }
        None => None,
    };
    // A class's own axle load, or the section's; tonnes only where every
    // class has one.
    let axle_loads = match (&classes, operation.as_ref().map(|o| o.axle_load)) {
        (Some(cs), Some(section)) => {
            let loads: Vec<Option<f64>> = cs.iter().map(|(_, own)| own.or(section)).collect();
            match loads.iter().position(Option::is_none) {
                Some(i) if loads.iter().any(Option::is_some) => {
                    s.error(
                        &format!("mix[{i}].axle_load"),
                        "missing: some classes give an axle load; give every class one (or traffic.axle_load for \
                         all), in kg, > 0"
                            .into(),
                    );
                    None
                }
                _ => Some(loads.into_iter().collect::<Option<Vec<f64>>>()),
            }
        }
        _ => None,
    };
    resolved.insert("traffic".into(), Value::Table(s.finish()));
    let mut classes: Vec<TrafficClass> = classes?.into_iter().map(|(c, _)| c).collect();
    let total: f64 = classes.iter().map(|c| c.share).sum();
    for c in &mut classes {
        c.share /= total;
    }
    Some((classes, Operation { axle_loads: axle_loads?, axles_per_day: operation?.axles_per_day }))
}

/// The section's own operator keys.
struct SectionOperation {
    /// `traffic.axle_load` (kg).
    axle_load: Option<f64>,
    /// Axles per day, from `axles_per_day` or `trains_per_day` x
    /// `axles_per_train`.
    axles_per_day: Option<f64>,
}

/// The largest axle load accepted (kg).
const MAX_AXLE_LOAD: f64 = 1e5;

/// Reads the operator keys of `[traffic]`; a key not given stays out of the
/// resolved config. None when one is invalid (recorded).
fn read_operation(s: &mut Section) -> Option<SectionOperation> {
    fn optional(s: &mut Section, key: &str, range: Range) -> Option<Option<f64>> {
        if s.has(key) { s.f64(key, None, range).map(Some) } else { Some(None) }
    }
    let axle_load = optional(s, "axle_load", Range::OpenClosed(0.0, MAX_AXLE_LOAD));
    let axles = optional(s, "axles_per_day", Range::OpenClosed(0.0, 1e7));
    let trains = optional(s, "trains_per_day", Range::OpenClosed(0.0, 1e5));
    let per_train = optional(s, "axles_per_train", Range::OpenClosed(0.0, 1e4));
    let axles_per_day = match (axles?, trains?, per_train?) {
        (Some(a), None, None) => Some(a),
        (None, Some(t), Some(n)) => Some(t * n),
        (None, None, None) => None,
        (Some(_), _, _) => {
            s.error(
                "axles_per_day",
                "is given with traffic.trains_per_day / axles_per_train: give one of the two (axles per day, or \
                 trains per day and axles per train)"
                    .into(),
            );
            return None;
        }
        (None, Some(_), None) => {
            s.error("axles_per_train", "missing: traffic.trains_per_day needs it (axles per train, > 0)".into());
            return None;
        }
        (None, None, Some(_)) => {
            s.error("trains_per_day", "missing: traffic.axles_per_train needs it (trains per day, > 0)".into());
            return None;
        }
    };
    Some(SectionOperation { axle_load: axle_load?, axles_per_day })
}

/// One class, and its own axle load (kg) where given.
fn read_class(s: &mut Section, index: usize, base: BaseClass) -> Option<(TrafficClass, Option<f64>)> {
    let default_name = format!("class{index}");
    let name = s.string("name", &default_name);
    let valid = |n: &str| !n.is_empty() && n.chars().all(|ch| ch.is_ascii_alphanumeric() || ch == '_' || ch == '-');
    if name.as_deref() == Some(BASE_NAME) {
        s.error(
            "name",
            format!("= \"{BASE_NAME}\" is reserved for the base config's class (a study without [traffic])"),
        );
        return None;
    }
    if let Some(n) = name.as_deref().filter(|n| !valid(n)) {
        s.error(
            "name",
            format!("= \"{n}\" must be non-empty letters, digits, '_' or '-' (it names the class in the output)"),
        );
    }
    // A key the class leaves out takes the base value; where that base key
    // is itself invalid its error is already recorded.
    let mut number = |key: &str, base: Option<f64>, range: Range| match base {
        None if !s.has(key) => None,
        _ => s.f64(key, base, range),
    };
    let speed = number("speed", base.speed, Range::OpenClosed(0.0, 200.0));
    let normal_force = number("normal_force", base.normal_force, Range::Positive);
    let longitudinal_force = number("longitudinal_force", base.longitudinal_force, Range::Finite);
    let unsprung_mass = number("unsprung_mass", base.unsprung_mass, Range::OpenClosed(0.0, 1e4));
    let share = s.f64("share", None, Range::OpenClosed(0.0, 1e9));
    // A class may be a vehicle of its own.
    let wheels = if s.has("wheels") { super::vehicle::positions(s).map(Some) } else { Some(None) };
    let axle_load = if s.has("axle_load") {
        s.f64("axle_load", None, Range::OpenClosed(0.0, MAX_AXLE_LOAD)).map(Some)
    } else {
        Some(None)
    };
    let class = TrafficClass {
        name: name.filter(|n| valid(n))?,
        speed: speed?,
        normal_force: normal_force?,
        longitudinal_force: longitudinal_force?,
        unsprung_mass: unsprung_mass?,
        share: share?,
        wheels: wheels?,
    };
    Some((class, axle_load?))
}
