//! The `[wheelset]` section: the wheelset's torsional mode
//! ([`crate::dynamics::torsion`]), read into [`WheelsetParams`]. Absent,
//! none: the creepage (or the force) is held as prescribed.

use super::ConfigError;
use super::reader::{Range, Section};
use crate::dynamics::torsion::{AXLE_TORSIONAL_LOSS_FACTOR, AXLE_TORSIONAL_STIFFNESS, WHEEL_POLAR_INERTIA};
use crate::params::{DynamicsKind, Scene, WheelsetParams};
use toml::{Table, Value};

/// Reads `[wheelset]` where the config has one: Some(None) without it,
/// None when a key is invalid.
pub(super) fn read(
    root: &mut Table,
    resolved: &mut Table,
    errors: &mut Vec<ConfigError>,
) -> Option<Option<WheelsetParams>> {
    if !root.contains_key("wheelset") {
        return Some(None);
    }
    let mut s = Section::new(root, "", "wheelset", errors);
    let stiffness = s.f64("torsional_stiffness", Some(AXLE_TORSIONAL_STIFFNESS), Range::Closed(1e4, 1e9));
    let inertia = s.f64("polar_inertia", Some(WHEEL_POLAR_INERTIA), Range::Closed(1.0, 1e3));
    let loss_factor = s.f64("torsional_loss_factor", Some(AXLE_TORSIONAL_LOSS_FACTOR), Range::Closed(0.0, 1.0));
    resolved.insert("wheelset".into(), Value::Table(s.finish()));
    Some(Some(WheelsetParams { stiffness: stiffness?, inertia: inertia?, loss_factor: loss_factor? }))
}

/// Whether the torsional mode fits the scene: it turns the dynamic normal
/// force into a creepage variation, so it needs a growth study with a track
/// model and the creepage prescribed.
pub(super) fn check(scene: &Scene, errors: &mut Vec<ConfigError>) {
    if scene.wheelset.is_none() {
        return;
    }
    let why = "the torsional mode varies the prescribed creepage with the dynamic normal force";
    if scene.creepage_x.is_none() {
        errors.push(ConfigError::new(
            "wheelset",
            format!(
                "needs load.control = \"creepage\" (with rolling.creepage_x, the mean creepage: {why}; the mean drive \
                 or brake torque is r times the force it transmits)"
            ),
        ));
    }
    if scene.growth.as_ref().is_none_or(|g| g.dynamics == DynamicsKind::Imposed) {
        errors.push(ConfigError::new(
            "wheelset",
            format!(
                "needs a growth study with dynamics.model = \"receptance\" or \"discrete\" ({why}, which only a track \
                 model gives)"
            ),
        ));
    }
}
