//! `material.friction_characteristic` and its keys: how the friction
//! coefficient varies with the local slip speed
//! ([`crate::contact::friction::Characteristic`]), and its memory
//! (`material.friction_memory`, `material.memory_speed`:
//! [`crate::contact::friction::FrictionMemory`]).

use super::reader::{Range, Section};
use crate::contact::friction::{Characteristic, FrictionMemory};

/// The names of `material.friction_characteristic`.
pub const NAMES: [&str; 4] = ["constant", "exponential", "rational", "modifier"];

/// Polach's dry-rail fit (Wear 258 (2005) 992-1000, Table 2): `mu_inf =
/// 0.4 mu_0`, `B = 0.6 s/m`; the default of the falling laws.
pub const POLACH_DRY_RATIO: f64 = 0.4;
/// `1/B` of Polach's dry fit (m/s).
pub const POLACH_DRY_SPEED: f64 = 1.0 / 0.6;

/// The range of `material.friction_memory` (m): 0 (no memory) to 1 mm.
const MEMORY_RANGE: Range = Range::Closed(0.0, 1e-3);
/// The range of `material.memory_speed` (m/s).
const MEMORY_SPEED_RANGE: Range = Range::OpenClosed(0.0, 10.0);

/// Reads the characteristic and its memory with `mu` the coefficient at
/// zero slip (`material.friction_coefficient`; None when invalid).
pub(super) fn read(s: &mut Section, mu: Option<f64>) -> Option<(Characteristic, Option<FrictionMemory>)> {
    let characteristic = read_characteristic(s, mu);
    // CONTACT's defaults where the coefficient varies; checked, kept and
    // unused under the constant law.
    let varies = characteristic.is_some_and(|c| !c.is_constant());
    let distance = if varies || s.has("friction_memory") {
        s.f64("friction_memory", Some(FrictionMemory::CONTACT.distance), MEMORY_RANGE)
    } else {
        Some(0.0)
    };
    let floor = if varies || s.has("memory_speed") {
        s.f64("memory_speed", Some(FrictionMemory::CONTACT.floor), MEMORY_SPEED_RANGE)
    } else {
        Some(FrictionMemory::CONTACT.floor)
    };
    let (characteristic, distance, floor) = (characteristic?, distance?, floor?);
    let memory = (varies && distance > 0.0).then_some(FrictionMemory { distance, floor });
    Some((characteristic, memory))
}

fn read_characteristic(s: &mut Section, mu: Option<f64>) -> Option<Characteristic> {
    let name = s.choice("friction_characteristic", Some("constant"), &NAMES)?;
    let speed_range = Range::OpenClosed(0.0, 100.0);
    if name == "constant" {
        // Checked, kept in the resolved config, unused (so that `--set
        // material.friction_characteristic=constant` switches a config over).
        if s.has("kinetic_friction") {
            s.f64("kinetic_friction", None, Range::OpenClosed(0.0, 1.0));
        }
        if s.has("friction_speed") {
            s.f64("friction_speed", None, speed_range);
        }
        return Some(Characteristic::Constant);
    }
    let mu = mu?;
    let modifier = name == "modifier";
    let kinetic_range = Range::OpenClosed(0.0, 1.0);
    let (kinetic, speed) = if modifier {
        // A modifier's level and rise have no default: they are the
        // product's.
        (s.f64("kinetic_friction", None, kinetic_range), s.f64("friction_speed", None, speed_range))
    } else {
        let kinetic = s.f64("kinetic_friction", Some(POLACH_DRY_RATIO * mu), kinetic_range);
        (kinetic, s.f64("friction_speed", Some(POLACH_DRY_SPEED), speed_range))
    };
    let (kinetic, speed) = (kinetic?, speed?);
    if modifier && kinetic <= mu {
        let message = format!(
            "= {kinetic} must exceed material.friction_coefficient = {mu}: a friction modifier's characteristic rises with the slip speed"
        );
        s.error("kinetic_friction", message);
        return None;
    }
    if !modifier && kinetic > mu {
        let message = format!(
            "= {kinetic} must not exceed material.friction_coefficient = {mu} for a falling law (\"{name}\"); a rising one is \"modifier\""
        );
        s.error("kinetic_friction", message);
        return None;
    }
    let ratio = kinetic / mu;
    Some(match name.as_str() {
        "rational" => Characteristic::Rational { ratio, speed },
        _ => Characteristic::Exponential { ratio, speed },
    })
}
