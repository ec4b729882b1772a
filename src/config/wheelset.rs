//! The `[wheelset]` section: the wheelset's torsional mode
//! ([`crate::dynamics::torsion`]) and, with `model = "modal"`, the flexible
//! rotating wheelset ([`crate::dynamics::wheelset`]), read into
//! [`WheelsetParams`]. Absent, none: the creepage (or the force) is held as
//! prescribed.
//!
//! Keys (SI units): `torsional_stiffness` (N m/rad), `polar_inertia` (kg
//! m^2, per wheel with its half axle), `torsional_loss_factor`; `model` =
//! `"torsion"` (the default: the torsional mode alone, as before `model`
//! existed; the resolved config records `model` only where given) or
//! `"modal"`, which adds `modes` (`"default"` or a CSV table's path,
//! relative to the config file), `mass` (kg), `roll_inertia`, `yaw_inertia`
//! (kg m^2), `suspension_stiffness_x`, `_y`, `_z` (N/m per axle box),
//! `suspension_loss_factor`, `axle_box_spacing`, `contact_spacing` (m) and,
//! with the default modes, `bending_damping` and `wheel_damping` (damping
//! ratios).

use super::ConfigError;
use super::reader::{Range, Section};
use crate::dynamics::torsion::{AXLE_TORSIONAL_LOSS_FACTOR, AXLE_TORSIONAL_STIFFNESS, WHEEL_POLAR_INERTIA};
use crate::dynamics::wheelset::{standard as ws, table};
use crate::params::{Directions, DynamicsKind, ModalWheelsetParams, Scene, WheelsetModes, WheelsetParams};
use std::path::Path;
use toml::{Table, Value};

/// The keys of the modal model (only with `model = "modal"`).
const MODAL_KEYS: [&str; 12] = [
    "modes",
    "mass",
    "roll_inertia",
    "yaw_inertia",
    "suspension_stiffness_x",
    "suspension_stiffness_y",
    "suspension_stiffness_z",
    "suspension_loss_factor",
    "axle_box_spacing",
    "contact_spacing",
    "bending_damping",
    "wheel_damping",
];

/// Reads `[wheelset]` where the config has one: Some(None) without it,
/// None when a key is invalid. A table's path is relative to `base` (the
/// config file's directory).
pub(super) fn read(
    root: &mut Table,
    resolved: &mut Table,
    base: &Path,
    errors: &mut Vec<ConfigError>,
) -> Option<Option<WheelsetParams>> {
    if !root.contains_key("wheelset") {
        return Some(None);
    }
    let mut s = Section::new(root, "", "wheelset", errors);
    let stiffness = s.f64("torsional_stiffness", Some(AXLE_TORSIONAL_STIFFNESS), Range::Closed(1e4, 1e9));
    let inertia = s.f64("polar_inertia", Some(WHEEL_POLAR_INERTIA), Range::Closed(1.0, 1e3));
    let loss_factor = s.f64("torsional_loss_factor", Some(AXLE_TORSIONAL_LOSS_FACTOR), Range::Closed(0.0, 1.0));
    // `model` is recorded only where given: the torsion's resolved config
    // (and its run files) stay as they were.
    let model =
        if s.has("model") { s.choice("model", None, &["rigid", "torsion", "modal"]) } else { Some("torsion".into()) };
    if model.as_deref() == Some("rigid") {
        // The rigid wheel: no wheelset model (its torsion's keys unused).
        for key in MODAL_KEYS {
            s.reject(key, "is a key of the modal model: only with wheelset.model = \"modal\"");
        }
        resolved.insert("wheelset".into(), Value::Table(s.finish()));
        return Some(None);
    }
    let modal = match model.as_deref() {
        Some("modal") => read_modal(&mut s, base).map(Some),
        Some(_) => {
            for key in MODAL_KEYS {
                s.reject(key, "is a key of the modal model: only with wheelset.model = \"modal\"");
            }
            Some(None)
        }
        None => None,
    };
    resolved.insert("wheelset".into(), Value::Table(s.finish()));
    Some(Some(WheelsetParams { stiffness: stiffness?, inertia: inertia?, loss_factor: loss_factor?, modal: modal? }))
}

/// The modal model's keys.
fn read_modal(s: &mut Section, base: &Path) -> Option<ModalWheelsetParams> {
    let modes = s.string("modes", "default");
    let mass = s.f64("mass", Some(ws::WHEELSET_MASS), Range::Closed(100.0, 1e4));
    let roll = s.f64("roll_inertia", Some(ws::WHEELSET_ROLL_INERTIA), Range::Closed(10.0, 1e4));
    let yaw = s.f64("yaw_inertia", Some(ws::WHEELSET_ROLL_INERTIA), Range::Closed(10.0, 1e4));
    let kx = s.f64("suspension_stiffness_x", Some(ws::SUSPENSION_STIFFNESS_X), Range::Closed(1e4, 1e10));
    let ky = s.f64("suspension_stiffness_y", Some(ws::SUSPENSION_STIFFNESS_Y), Range::Closed(1e4, 1e10));
    let kz = s.f64("suspension_stiffness_z", Some(ws::SUSPENSION_STIFFNESS_Z), Range::Closed(1e4, 1e10));
    let eta = s.f64("suspension_loss_factor", Some(ws::SUSPENSION_LOSS_FACTOR), Range::Closed(0.0, 1.0));
    let boxes = s.f64("axle_box_spacing", Some(ws::AXLE_BOX_SPACING), Range::Closed(0.5, 3.5));
    let contacts = s.f64("contact_spacing", Some(ws::CONTACT_SPACING), Range::Closed(0.5, 2.5));
    let modes = match modes?.as_str() {
        "default" => {
            let bending = s.f64("bending_damping", Some(ws::BENDING_DAMPING), Range::OpenClosed(0.0, 0.5));
            let wheel = s.f64("wheel_damping", Some(ws::WHEEL_DAMPING), Range::OpenClosed(0.0, 0.5));
            WheelsetModes::Default { bending_damping: bending?, wheel_damping: wheel? }
        }
        file => {
            for key in ["bending_damping", "wheel_damping"] {
                s.reject(key, "sets the default modes' damping: only with wheelset.modes = \"default\"");
            }
            let path = base.join(file);
            let read = std::fs::canonicalize(&path)
                .and_then(|p| Ok((std::fs::read_to_string(&p)?, p)))
                .map_err(|e| format!("cannot read the modal table {}: {e}", path.display()));
            let parsed = read.and_then(|(text, p)| {
                table::parse(&text).map(|t| (t, p.clone())).map_err(|e| format!("{}: {e}", p.display()))
            });
            match parsed {
                Ok((table, p)) => {
                    let path = p.display().to_string();
                    // The resolved config names the file absolutely (resume reads it again).
                    s.resolved.insert("modes".into(), Value::String(path.clone()));
                    WheelsetModes::Table { path, table }
                }
                Err(message) => {
                    s.error(
                        "modes",
                        format!("{message} (\"default\" or a CSV table of modes; see the wheelset chapter)"),
                    );
                    return None;
                }
            }
        }
    };
    Some(ModalWheelsetParams {
        mass: mass?,
        roll_inertia: roll?,
        yaw_inertia: yaw?,
        suspension_stiffness: [kx?, ky?, kz?],
        suspension_loss_factor: eta?,
        axle_box_spacing: boxes?,
        contact_spacing: contacts?,
        modes,
    })
}

/// Whether the torsional mode fits the scene: it turns the dynamic normal
/// force into a creepage variation, so it needs a growth study with a track
/// model and the creepage prescribed.
pub(super) fn check(scene: &Scene, errors: &mut Vec<ConfigError>) {
    if scene.wheelset.is_none() {
        return;
    }
    let why = "the torsional mode varies the prescribed creepage with the dynamic normal force";
    let every_direction = scene.growth.as_ref().is_some_and(|g| matches!(g.directions, Directions::All { .. }));
    // (A second rail without every direction has its own message.)
    if scene.creepage_x.is_none() && !every_direction && scene.second_rail.is_none() {
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
