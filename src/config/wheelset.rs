//! The `[wheelset]` section: the rigid wheel, the wheelset's torsional
//! mode ([`crate::dynamics::wheelset::torsion`]) or the flexible rotating wheelset
//! ([`crate::dynamics::wheelset`]), read into [`WheelsetParams`] (None: the
//! rigid wheel). `model = "auto"`, the default (also without the section),
//! takes the physics the scene needs ([`auto_model`]).
//!
//! Keys (SI units): `model` = `"auto"`, `"rigid"`, `"torsion"` (the
//! torsional mode alone) or `"modal"`; `torsional_stiffness` (N m/rad),
//! `polar_inertia` (kg m^2, per wheel with its half axle),
//! `torsional_loss_factor`; with `"modal"` (and `"auto"`) `modes`
//! (`"default"` or a CSV table's path,
//! relative to the config file), `mass` (kg), `roll_inertia`, `yaw_inertia`
//! (kg m^2), `suspension_stiffness_x`, `_y`, `_z` (N/m per axle box),
//! `suspension_loss_factor`, `axle_box_spacing`, `contact_spacing` (m) and,
//! with the default modes, `bending_damping` and `wheel_damping` (damping
//! ratios).

use super::ConfigError;
use super::reader::{Range, Section};
use crate::dynamics::wheelset::torsion::{AXLE_TORSIONAL_LOSS_FACTOR, AXLE_TORSIONAL_STIFFNESS, WHEEL_POLAR_INERTIA};
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

/// The wheelset a config asks for (`wheelset.model`), before the scene
/// says what `auto` is.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct WheelsetKeys {
    /// `auto`, `rigid`, `torsion` or `modal`.
    pub(super) model: String,
    /// The torsional mode's keys (every model but the rigid wheel's).
    pub(super) torsion: (f64, f64, f64),
    /// The modal model's keys (`auto` and `modal`).
    pub(super) modal: Option<ModalWheelsetParams>,
}

/// Reads `[wheelset]` (absent: every key at its default, `model =
/// "auto"`); None when a key is invalid. A table's path is relative to
/// `base` (the config file's directory). The resolved config records
/// `model` wherever the section is given (a stored config with a section
/// and no `model` was written before `auto`, when that meant the torsional
/// mode: [`crate::run::stored_config`] reads it so), and no section where
/// there was none.
pub(super) fn read(
    root: &mut Table,
    resolved: &mut Table,
    base: &Path,
    errors: &mut Vec<ConfigError>,
) -> Option<WheelsetKeys> {
    let given = root.contains_key("wheelset");
    let mut s = Section::new(root, "", "wheelset", errors);
    let model = s.choice("model", Some("auto"), &["auto", "rigid", "torsion", "modal"]);
    let rigid = model.as_deref() == Some("rigid");
    let (stiffness, inertia, loss_factor) = if rigid {
        for key in ["torsional_stiffness", "polar_inertia", "torsional_loss_factor"] {
            s.reject(key, "is a key of the wheelset's torsion: not with wheelset.model = \"rigid\"");
        }
        (Some(AXLE_TORSIONAL_STIFFNESS), Some(WHEEL_POLAR_INERTIA), Some(AXLE_TORSIONAL_LOSS_FACTOR))
    } else {
        (
            s.f64("torsional_stiffness", Some(AXLE_TORSIONAL_STIFFNESS), Range::Closed(1e4, 1e9)),
            s.f64("polar_inertia", Some(WHEEL_POLAR_INERTIA), Range::Closed(1.0, 1e3)),
            s.f64("torsional_loss_factor", Some(AXLE_TORSIONAL_LOSS_FACTOR), Range::Closed(0.0, 1.0)),
        )
    };
    let modal = match model.as_deref() {
        Some("modal") | Some("auto") => read_modal(&mut s, base).map(Some),
        Some(_) => {
            for key in MODAL_KEYS {
                s.reject(key, "is a key of the modal model: only with wheelset.model = \"modal\" or \"auto\"");
            }
            Some(None)
        }
        None => None,
    };
    let table = s.finish();
    if given {
        resolved.insert("wheelset".into(), Value::Table(table));
    }
    Some(WheelsetKeys { model: model?, torsion: (stiffness?, inertia?, loss_factor?), modal: modal? })
}

/// What `wheelset.model = "auto"` takes for a scene whose growth study is
/// `growth` (None: a single passage) under creepage control (`creepage`)
/// or force control, and why: the flexible rotating wheelset wherever the
/// dynamics has a track model in every direction (it moves the spectrum
/// beyond the chain's tolerance there: docs/src/theory/wheelset.md,
/// scripts/wheelset_rule.sh); with the vertical model under creepage
/// control its torsional mode, the one wheelset body that model couples
/// (the creepage's answer to the normal force); the rigid wheel elsewhere
/// (imposed loads; the vertical model under force control, where the
/// torsion has nothing to vary).
pub fn auto_model(growth: Option<&crate::params::GrowthParams>, creepage: bool) -> (&'static str, &'static str) {
    match growth {
        None => ("rigid", "a single passage has no dynamics"),
        Some(g) if g.dynamics == DynamicsKind::Imposed => ("rigid", "imposed loads: no dynamics to couple"),
        Some(g) if g.directions == Directions::Vertical && creepage => (
            "torsion",
            "the vertical model under creepage control couples the wheelset's torsion (the creepage's answer to the \
             normal force)",
        ),
        Some(g) if g.directions == Directions::Vertical => (
            "rigid",
            "the vertical model under force control: its wheel is the unsprung mass, the torsion has no creepage \
             to vary",
        ),
        Some(_) => (
            "modal",
            "a track model in every direction: the wheelset's modes move the growth spectrum (the rigid wheel \
             leaves them out)",
        ),
    }
}

/// The wheelset of `keys` for a scene whose growth study is `growth`:
/// `auto` resolved ([`auto_model`]), None for the rigid wheel; with the
/// choice's reason where `auto` made it.
pub(super) fn resolve(
    keys: WheelsetKeys,
    growth: Option<&crate::params::GrowthParams>,
    creepage: bool,
) -> (Option<WheelsetParams>, Option<String>) {
    let (model, why) = match keys.model.as_str() {
        "auto" => {
            let (m, why) = auto_model(growth, creepage);
            (m, Some(format!("{m}: {why}")))
        }
        m => (
            if m == "rigid" {
                "rigid"
            } else if m == "modal" {
                "modal"
            } else {
                "torsion"
            },
            None,
        ),
    };
    let (stiffness, inertia, loss_factor) = keys.torsion;
    let params = match model {
        "rigid" => None,
        "modal" => Some(WheelsetParams { stiffness, inertia, loss_factor, modal: keys.modal }),
        _ => Some(WheelsetParams { stiffness, inertia, loss_factor, modal: None }),
    };
    (params, why)
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
