//! The `[track]` section: the track under the wheel, for the track models
//! of a growth study (`dynamics.model = "receptance"`), read into
//! [`TrackConfig`]; defaults where absent.

use super::ConfigError;
use super::reader::{Range, Section};
use crate::dynamics::rail::RailSection;
use crate::dynamics::receptance::{
    BALLAST_LOSS_FACTOR, BALLAST_STIFFNESS_PER_HALF_SLEEPER, HALF_SLEEPER_MASS, PAD_LOSS_FACTOR, PAD_STIFFNESS_PER_PAD,
    SLEEPER_SPACING,
};
use crate::dynamics::track::{Damping, TrackConfig};
use toml::{Table, Value};

/// Reads `[track]` (defaults where absent) into `resolved`; None when a key
/// is invalid (the errors are recorded).
pub(super) fn read(root: &mut Table, resolved: &mut Table, errors: &mut Vec<ConfigError>) -> Option<TrackConfig> {
    let mut s = Section::new(root, "", "track", errors);
    let name = s.choice("rail", Some("UIC60"), &RailSection::PRESETS);
    let preset = name.as_deref().and_then(RailSection::preset);
    let mut rail =
        preset.unwrap_or(RailSection { bending_stiffness: 1.0, mass: 1.0, shear_stiffness: 1.0, rotary_inertia: 1.0 });
    let mut ok = preset.is_some();
    for (key, field) in [
        ("rail_bending_stiffness", &mut rail.bending_stiffness),
        ("rail_mass", &mut rail.mass),
        ("rail_shear_stiffness", &mut rail.shear_stiffness),
        ("rail_rotary_inertia", &mut rail.rotary_inertia),
    ] {
        if s.has(key) {
            match s.f64(key, None, Range::Positive) {
                Some(v) => *field = v,
                None => ok = false,
            }
        }
    }
    let spacing = s.f64("sleeper_spacing", Some(SLEEPER_SPACING), Range::Closed(0.3, 1.5));
    let pad = s.f64("pad_stiffness", Some(PAD_STIFFNESS_PER_PAD), Range::Positive);
    let pad_damping = damping(&mut s, "pad", PAD_LOSS_FACTOR);
    let sleeper = s.f64("sleeper_mass", Some(HALF_SLEEPER_MASS), Range::NonNegative);
    let ballast = s.f64("ballast_stiffness", Some(BALLAST_STIFFNESS_PER_HALF_SLEEPER), Range::Positive);
    let ballast_damping = damping(&mut s, "ballast", BALLAST_LOSS_FACTOR);
    resolved.insert("track".into(), Value::Table(s.finish()));
    Some(TrackConfig {
        rail_name: RailSection::PRESETS.into_iter().find(|p| Some(*p) == name.as_deref())?,
        rail: ok.then_some(rail)?,
        sleeper_spacing: spacing?,
        pad_stiffness: pad?,
        pad_damping: pad_damping?,
        sleeper_mass: sleeper?,
        ballast_stiffness: ballast?,
        ballast_damping: ballast_damping?,
    })
}

/// `<layer>_loss_factor` or `<layer>_damping`, not both; the loss factor
/// `default` when neither is given.
fn damping(s: &mut Section, layer: &str, default: f64) -> Option<Damping> {
    let (eta_key, c_key) = (format!("{layer}_loss_factor"), format!("{layer}_damping"));
    match (s.has(&eta_key), s.has(&c_key)) {
        (true, true) => {
            s.f64(&eta_key, None, Range::NonNegative);
            s.f64(&c_key, None, Range::NonNegative);
            s.error(&c_key, format!("and track.{eta_key} both damp the {layer}: give one of them"));
            None
        }
        (false, true) => s.f64(&c_key, None, Range::NonNegative).map(Damping::Viscous),
        _ => s.f64(&eta_key, Some(default), Range::Closed(0.0, 10.0)).map(Damping::LossFactor),
    }
}
