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

/// Reads `[vehicle]` where the config has one (the resolved config of a
/// config without it gets none); None when a key is invalid.
pub(super) fn read(root: &mut Table, resolved: &mut Table, errors: &mut Vec<ConfigError>) -> Option<VehicleParams> {
    if !root.contains_key("vehicle") {
        return Some(VehicleParams::default());
    }
    let mut s = Section::new(root, "", "vehicle", errors);
    let wheels = s.f64_list("wheels", vec![0.0], Range::Closed(0.0, MAX_WHEEL_DISTANCE), MAX_WHEELS);
    let wheels = wheels.and_then(|w| {
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
    });
    resolved.insert("vehicle".into(), Value::Table(s.finish()));
    Some(VehicleParams { wheels: wheels? })
}

/// Whether the scene's wheels fit the model that couples them: several
/// wheels need a growth study with a track model (they are coupled
/// through the rail's receptances; a single passage and imposed dynamics
/// roll one wheel), and no two wheels closer than a wheel's diameter.
pub(super) fn check(scene: &Scene, errors: &mut Vec<ConfigError>) {
    let wheels = &scene.vehicle.wheels;
    if wheels.len() < 2 {
        return;
    }
    let coupled = "several wheels are coupled through the track's receptances";
    match scene.growth.as_ref().map(|g| g.dynamics) {
        None => errors.push(ConfigError::new(
            "vehicle.wheels",
            format!(
                "= {wheels:?} m: {coupled} in a growth study (a [growth] section with dynamics.model = \"receptance\" \
                 or \"discrete\"); a single passage rolls one wheel: set vehicle.wheels = [0.0]"
            ),
        )),
        Some(DynamicsKind::Imposed) => errors.push(ConfigError::new(
            "vehicle.wheels",
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
            "vehicle.wheels",
            format!(
                "wheels {k} and {} are {} m apart, closer than a wheel's diameter (2 geometry.wheel_radius = {diameter} m)",
                k + 1,
                wheels[k] - wheels[k - 1]
            ),
        ));
    }
}
