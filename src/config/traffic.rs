//! Section `[traffic]` of a growth study: the mix of wheel classes,
//! `[[traffic.mix]]`. Each class's `speed`, `normal_force`,
//! `longitudinal_force` and `unsprung_mass` default to the base config's
//! `rolling.speed`, `load.normal_force`, `load.longitudinal_force` and
//! `dynamics.unsprung_mass`; `share` is required (relative, normalised to
//! sum 1). Without the section the study has one class, the base config.

use super::ConfigError;
use super::reader::{Range, Section};
use crate::params::TrafficClass;
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

/// Name of the one class of a study without `[traffic]`.
pub const BASE_NAME: &str = "base";

/// Whether `classes` are a mix from `[traffic]` rather than the one class
/// of the base config.
pub fn is_mix(classes: &[TrafficClass]) -> bool {
    !matches!(classes, [c] if c.name == BASE_NAME)
}

/// Reads `[traffic]`: the classes with their shares normalised, or one
/// class of the base values. `None` when a key is invalid (recorded).
pub fn read(
    root: &mut Table,
    resolved: &mut Table,
    base: BaseClass,
    errors: &mut Vec<ConfigError>,
) -> Option<Vec<TrafficClass>> {
    if !root.contains_key("traffic") {
        let BaseClass { speed, normal_force, longitudinal_force, unsprung_mass } = base;
        return Some(vec![TrafficClass {
            name: BASE_NAME.into(),
            speed: speed?,
            normal_force: normal_force?,
            longitudinal_force: longitudinal_force?,
            unsprung_mass: unsprung_mass?,
            share: 1.0,
            wheels: None,
        }]);
    }
    let mut s = Section::new(root, "", "traffic", errors);
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
            if let Some((i, c)) = cs.iter().enumerate().find(|(_, c)| !seen.insert(c.name.clone())) {
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
    resolved.insert("traffic".into(), Value::Table(s.finish()));
    let mut classes = classes?;
    let total: f64 = classes.iter().map(|c| c.share).sum();
    for c in &mut classes {
        c.share /= total;
    }
    Some(classes)
}

fn read_class(s: &mut Section, index: usize, base: BaseClass) -> Option<TrafficClass> {
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
    Some(TrafficClass {
        name: name.filter(|n| valid(n))?,
        speed: speed?,
        normal_force: normal_force?,
        longitudinal_force: longitudinal_force?,
        unsprung_mass: unsprung_mass?,
        share: share?,
        wheels: wheels?,
    })
}
