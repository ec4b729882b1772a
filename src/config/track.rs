//! The `[track]` section: the track under the wheel, for the track models
//! of a growth study (`dynamics.model = "receptance"`), read into
//! [`TrackConfig`]; defaults where absent.

use super::ConfigError;
use super::reader::{Range, Section};
use crate::dynamics::receptance::{
    BALLAST_LOSS_FACTOR, BALLAST_STIFFNESS_PER_HALF_SLEEPER, HALF_SLEEPER_MASS, PAD_LOSS_FACTOR, PAD_STIFFNESS_PER_PAD,
    SLEEPER_SPACING,
};
use crate::dynamics::track::rail::RailSection;
use crate::dynamics::track::{Damping, RAIL_LOSS_FACTOR, Supports3, TrackConfig};
use toml::{Table, Value};

/// Reads `[track]` (defaults where absent) into `resolved`; None when a key
/// is invalid (the errors are recorded).
pub(super) fn read(root: &mut Table, resolved: &mut Table, errors: &mut Vec<ConfigError>) -> Option<TrackConfig> {
    let mut s = Section::new(root, "", "track", errors);
    let name = s.choice("rail", Some("UIC60"), &RailSection::PRESETS);
    let preset = name.as_deref().and_then(RailSection::preset);
    let mut rail = preset.unwrap_or(RailSection::preset("UIC60").expect("preset"));
    let mut ok = preset.is_some();
    let t = &mut rail.transverse;
    for (key, field) in [
        ("rail_bending_stiffness", &mut rail.bending_stiffness),
        ("rail_mass", &mut rail.mass),
        ("rail_shear_stiffness", &mut rail.shear_stiffness),
        ("rail_rotary_inertia", &mut rail.rotary_inertia),
        ("rail_axial_stiffness", &mut t.axial_stiffness),
        ("rail_lateral_bending_stiffness", &mut t.lateral_bending_stiffness),
        ("rail_lateral_shear_stiffness", &mut t.lateral_shear_stiffness),
        ("rail_lateral_rotary_inertia", &mut t.lateral_rotary_inertia),
        ("rail_torsional_stiffness", &mut t.torsional_stiffness),
        ("rail_polar_inertia", &mut t.polar_inertia),
        ("rail_height", &mut t.height),
        ("rail_neutral_axis_height", &mut t.neutral_axis_height),
        ("rail_shear_centre_height", &mut t.shear_centre_height),
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
    let rail_loss = s.f64("rail_loss_factor", Some(RAIL_LOSS_FACTOR), Range::Closed(1e-4, 1.0));
    let d3 = Supports3::default();
    let mut supports = d3;
    let mut supports_ok = true;
    for (key, field, default, range) in [
        ("pad_lateral_stiffness", &mut supports.pad_lateral_stiffness, d3.pad_lateral_stiffness, Range::Positive),
        (
            "pad_longitudinal_stiffness",
            &mut supports.pad_longitudinal_stiffness,
            d3.pad_longitudinal_stiffness,
            Range::Positive,
        ),
        ("pad_width", &mut supports.pad_width, d3.pad_width, Range::Closed(0.0, 0.5)),
        ("pad_length", &mut supports.pad_length, d3.pad_length, Range::Closed(0.0, 0.5)),
        (
            "ballast_lateral_stiffness",
            &mut supports.ballast_lateral_stiffness,
            d3.ballast_lateral_stiffness,
            Range::Positive,
        ),
        (
            "ballast_longitudinal_stiffness",
            &mut supports.ballast_longitudinal_stiffness,
            d3.ballast_longitudinal_stiffness,
            Range::Positive,
        ),
    ] {
        match s.f64(key, Some(default), range) {
            Some(v) => *field = v,
            None => supports_ok = false,
        }
    }
    let heights = &rail.transverse;
    if ok && !(heights.shear_centre_height < heights.height && heights.neutral_axis_height < heights.height) {
        s.error(
            "rail_height",
            format!(
                "= {} m must exceed the neutral axis's ({} m) and the shear centre's ({} m) heights above the foot",
                heights.height, heights.neutral_axis_height, heights.shear_centre_height
            ),
        );
        ok = false;
    }
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
        rail_loss_factor: rail_loss?,
        supports: supports_ok.then_some(supports)?,
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
