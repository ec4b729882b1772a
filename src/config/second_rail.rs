//! The `[second_rail]` section: the wheelset's second rail, its contact's
//! steady state and its initial roughness, read into
//! [`SecondRail`]. Absent, the study has one rail (as before the section
//! existed).
//!
//! Keys (SI units): `name` (default "right rail") and `first_name` (the
//! scene's own rail, default "left rail"); `normal_force` (N, default
//! `load.normal_force`); `longitudinal_force` (N, force control, default
//! `load.longitudinal_force`) or `creepage_x` (1, creepage control,
//! default `rolling.creepage_x`); `creepage_y` (1, default
//! `rolling.creepage_y`); `spin` (1/m, default minus `rolling.spin`: the
//! mirror image in the common axes); `roughness_seed` (default the
//! roughness's seed plus 1, for the seeded kinds).

use super::ConfigError;
use super::reader::{Range, Section};
use crate::params::{Directions, Scene, SecondRail};
use toml::{Table, Value};

/// The first rail's values the second's default to (None where the first's
/// key is itself invalid).
#[derive(Debug, Clone, Copy)]
pub(super) struct FirstRail {
    /// `load.normal_force` (N).
    pub normal_force: Option<f64>,
    /// `load.longitudinal_force` (N).
    pub longitudinal_force: Option<f64>,
    /// `rolling.creepage_x` where given (creepage control).
    pub creepage_x: Option<Option<f64>>,
    /// `rolling.creepage_y` (1).
    pub creepage_y: Option<f64>,
    /// `rolling.spin` (1/m).
    pub spin: Option<f64>,
}

/// Reads `[second_rail]`: Some(None) without it, None when a key is
/// invalid.
pub(super) fn read(
    root: &mut Table,
    resolved: &mut Table,
    first: FirstRail,
    errors: &mut Vec<ConfigError>,
) -> Option<Option<SecondRail>> {
    if !root.contains_key("second_rail") {
        return Some(None);
    }
    let mut s = Section::new(root, "", "second_rail", errors);
    let name = s.string("name", "right rail");
    let first_name = s.string("first_name", "left rail");
    let normal_force = s.f64("normal_force", first.normal_force, Range::Positive);
    let creepage_control = first.creepage_x.map(|c| c.is_some());
    let (longitudinal_force, creepage_x) = match creepage_control {
        Some(true) => {
            s.reject(
                "longitudinal_force",
                "is a force, but load.control = \"creepage\" prescribes the creepage: use second_rail.creepage_x",
            );
            let c = s.f64("creepage_x", first.creepage_x.flatten(), Range::Closed(-0.1, 0.1));
            (Some(0.0), c.map(Some))
        }
        Some(false) => {
            s.reject(
                "creepage_x",
                "is a creepage, but load.control = \"force\" prescribes the force: use second_rail.longitudinal_force",
            );
            (s.f64("longitudinal_force", first.longitudinal_force, Range::Finite), Some(None))
        }
        None => (None, None),
    };
    let creepage_y = s.f64("creepage_y", first.creepage_y, Range::Closed(-0.1, 0.1));
    // (0 - v: no negative zero for a first rail without spin.)
    let spin = s.f64("spin", first.spin.map(|v| 0.0 - v), Range::Closed(-100.0, 100.0));
    let seed = if s.has("roughness_seed") {
        s.usize("roughness_seed", None, 0, usize::MAX >> 1).map(Some)
    } else {
        Some(None)
    };
    resolved.insert("second_rail".into(), Value::Table(s.finish()));
    Some(Some(SecondRail {
        names: [first_name?, name?],
        normal_force: normal_force?,
        longitudinal_force: longitudinal_force?,
        creepage_x: creepage_x?,
        creepage_y: creepage_y?,
        spin: spin?,
        roughness_seed: seed?.map(|v| v as u64),
    }))
}

/// Fills in the roughness seed's default (the first rail's plus 1) and
/// checks that the scene can carry a second rail: a growth study with the
/// dynamics in every direction, the modal wheelset (each wheelset's two
/// contacts are coupled through it), without a traffic mix. Under a
/// vehicle of several wheels (`vehicle.wheels`) every wheelset has its
/// second wheel on the second rail, at the second rail's steady state.
pub(super) fn check(scene: &mut Scene, errors: &mut Vec<ConfigError>) {
    let Some(second) = scene.second_rail.as_mut() else { return };
    let Some(growth) = scene.growth.as_ref() else {
        errors.push(ConfigError::new(
            "second_rail",
            "needs a growth study ([growth]): a single passage has one rail".into(),
        ));
        return;
    };
    match (second.roughness_seed, growth.roughness.seed()) {
        (None, seed) => second.roughness_seed = seed.map(|s| s.wrapping_add(1)),
        (Some(_), None) => errors.push(ConfigError::new(
            "second_rail.roughness_seed",
            "seeds a random roughness: only with roughness.kind = \"random\" or \"levels\" (the other kinds are \
             the first rail's on both rails)"
                .into(),
        )),
        _ => {}
    }
    if second.names[0] == second.names[1] {
        errors.push(ConfigError::new(
            "second_rail.name",
            format!(
                "= \"{}\" is the first rail's name too (second_rail.first_name): the rails need two names",
                second.names[1]
            ),
        ));
    }
    let loads = crate::loads::ImposedLoads {
        normal_force: second.normal_force,
        longitudinal_force: second.longitudinal_force,
        ..scene.loads.clone()
    };
    if let Some(problem) = super::load::second_rail_problem(&loads, scene.material.friction) {
        errors.push(ConfigError::new(
            "second_rail.normal_force",
            format!(
                "{problem} on the second rail: its N is second_rail.normal_force = {:.6e} N, its F_x \
                 second_rail.longitudinal_force (load.longitudinal_force unless given) = {:.6e} N, with \
                 load.harmonics",
                second.normal_force, second.longitudinal_force
            ),
        ));
    }
    if !matches!(growth.directions, Directions::All { .. }) || growth.dynamics.unsprung_mass().is_none() {
        errors.push(ConfigError::new(
            "second_rail",
            "needs the dynamics in every direction on a track model (dynamics.model = \"receptance\" or \
             \"discrete\", dynamics.directions = \"all\"): the two contacts are coupled through the wheelset"
                .into(),
        ));
    }
    if scene.wheelset.as_ref().is_none_or(|w| w.modal.is_none()) {
        errors.push(ConfigError::new(
            "second_rail",
            "needs the modal wheelset (wheelset.model = \"modal\"): it couples the two wheels' contacts".into(),
        ));
    }
    if super::traffic::is_mix(&growth.classes) {
        errors.push(ConfigError::new(
            "second_rail",
            "goes without a traffic mix: the second rail's loads are given for the scene's wheelset, not per \
             class of [[traffic.mix]]"
                .into(),
        ));
    }
}
