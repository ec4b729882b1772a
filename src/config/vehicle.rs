//! The `[vehicle]` section: where the wheels of a vehicle run on one rail,
//! read into [`VehicleParams`]. Absent, one wheel.

use super::ConfigError;
use super::reader::{Range, Section};
use crate::params::{DynamicsKind, Scene, VehicleParams};
use toml::{Table, Value};

/// Most wheels on one rail (a four-axle car).
pub const MAX_WHEELS: usize = 8;

/// Longest distance of a wheel behind the leading one (m): a car.
pub const MAX_WHEEL_DISTANCE: f64 = 50.0;

/// The key `wheels` of section `s`: positions behind the leading wheel,
/// the first 0, increasing (`[vehicle]`, or a traffic class's own).
pub(super) fn positions(s: &mut Section) -> Option<Vec<f64>> {
    let w = s.f64_list("wheels", vec![0.0], Range::Closed(0.0, MAX_WHEEL_DISTANCE), MAX_WHEELS)?;
    if w[0] != 0.0 {
        s.error("wheels", format!("starts at {} m; the first is the leading wheel, at 0 m", w[0]));
        return None;
    }
    if let Some(k) = (1..w.len()).find(|&k| w[k] <= w[k - 1]) {
        s.error(
            "wheels",
            format!("must increase: wheel {} at {} m is not behind wheel {} at {} m", k + 1, w[k], k, w[k - 1]),
        );
        return None;
    }
    Some(w)
}

/// Reads `[vehicle]` where the config has one (the resolved config of a
/// config without it gets none); None when a key is invalid.
pub(super) fn read(root: &mut Table, resolved: &mut Table, errors: &mut Vec<ConfigError>) -> Option<VehicleParams> {
    if !root.contains_key("vehicle") {
        return Some(VehicleParams::default());
    }
    let mut s = Section::new(root, "", "vehicle", errors);
    let wheels = positions(&mut s);
    // Per wheel where they differ: lists as long as `wheels`.
    let n = wheels.as_ref().map_or(0, Vec::len);
    let mut per_wheel = |key: &str, range: Range, unit: &str| -> Option<Option<Vec<f64>>> {
        if !s.has(key) {
            return Some(None);
        }
        let v = s.f64_list(key, Vec::new(), range, MAX_WHEELS)?;
        if n > 0 && v.len() != n {
            s.error(key, format!("has {} values; one per wheel of vehicle.wheels ({n}), in {unit}", v.len()));
            return None;
        }
        Some(Some(v))
    };
    let unsprung_mass = per_wheel("unsprung_mass", Range::OpenClosed(0.0, 1e4), "kg");
    let normal_force = per_wheel("normal_force", Range::Positive, "N");
    let longitudinal_force = per_wheel("longitudinal_force", Range::Finite, "N");
    resolved.insert("vehicle".into(), Value::Table(s.finish()));
    Some(VehicleParams {
        wheels: wheels?,
        unsprung_mass: unsprung_mass?,
        normal_force: normal_force?,
        longitudinal_force: longitudinal_force?,
    })
}

/// Whether the scene's wheels fit the model that couples them: several
/// wheels need a growth study with a track model (they are coupled
/// through the rail's receptances; a single passage and imposed dynamics
/// roll one wheel), and no two wheels closer than a wheel's diameter.
pub(super) fn check(scene: &Scene, errors: &mut Vec<ConfigError>) {
    check_wheels("vehicle.wheels", &scene.vehicle.wheels, scene, errors);
    check_lists(scene, errors);
    if let Some(g) = &scene.growth {
        for (i, c) in g.classes.iter().enumerate() {
            if let Some(w) = &c.wheels {
                check_wheels(&format!("traffic.mix[{i}].wheels"), w, scene, errors);
            }
        }
    }
}

/// [`check`] of one vehicle's `wheels`, named `key`.
fn check_wheels(key: &str, wheels: &[f64], scene: &Scene, errors: &mut Vec<ConfigError>) {
    if wheels.len() < 2 {
        return;
    }
    let coupled = "several wheels are coupled through the track's receptances";
    match scene.growth.as_ref().map(|g| g.dynamics) {
        None => errors.push(ConfigError::new(
            key,
            format!(
                "= {wheels:?} m: {coupled} in a growth study (a [growth] section with dynamics.model = \"receptance\" \
                 or \"discrete\"); a single passage rolls one wheel: set vehicle.wheels = [0.0]"
            ),
        )),
        Some(DynamicsKind::Imposed) => errors.push(ConfigError::new(
            key,
            format!(
                "= {wheels:?} m with dynamics.model = \"imposed\": {coupled}; set dynamics.model = \"receptance\" \
                 or \"discrete\", or vehicle.wheels = [0.0]"
            ),
        )),
        Some(_) => {}
    }
    let diameter = 2.0 * scene.geometry.wheel_radius;
    if let Some(k) = (1..wheels.len()).find(|&k| wheels[k] - wheels[k - 1] < diameter) {
        errors.push(ConfigError::new(
            key,
            format!(
                "wheels {k} and {} are {} m apart, closer than a wheel's diameter (2 geometry.wheel_radius = {diameter} m)",
                k + 1,
                wheels[k] - wheels[k - 1]
            ),
        ));
    }
}

/// The per-wheel lists of `[vehicle]` against the scene: growth studies
/// only, not with a traffic mix (its classes set one value each), and no
/// force under creepage control.
fn check_lists(scene: &Scene, errors: &mut Vec<ConfigError>) {
    let v = &scene.vehicle;
    let mix = scene.growth.as_ref().is_some_and(|g| crate::params::is_mix(&g.classes));
    let lists = [
        ("unsprung_mass", v.unsprung_mass.is_some()),
        ("normal_force", v.normal_force.is_some()),
        ("longitudinal_force", v.longitudinal_force.is_some()),
    ];
    for (key, _) in lists.iter().filter(|(_, given)| *given) {
        let why = if scene.growth.is_none() {
            "is per wheel of a growth study's vehicle; a single passage takes load.* and dynamics.*"
        } else if *key == "longitudinal_force" && scene.creepage_x.is_some() {
            "is a force, but load.control = \"creepage\" prescribes the creepage rolling.creepage_x"
        } else if mix {
            "per wheel with a [traffic] mix: the classes set one value per class; give it per class"
        } else {
            continue;
        };
        errors.push(ConfigError::new(&format!("vehicle.{key}"), why.into()));
    }
}
