//! The `[track]` section: the track under the wheel, for the track models
//! of a growth study (`dynamics.model = "receptance"`), read into
//! [`TrackConfig`]; defaults where absent.

use super::ConfigError;
use super::reader::{Range, Section};
use crate::dynamics::receptance::{
    BALLAST_LOSS_FACTOR, BALLAST_STIFFNESS_PER_HALF_SLEEPER, HALF_SLEEPER_MASS, PAD_LOSS_FACTOR, PAD_STIFFNESS_PER_PAD,
    SLEEPER_SPACING,
};
use crate::dynamics::track::layout::{Layout, LayoutError, LayoutSpec, PerSupport, Property, Spacing, Spread};
use crate::dynamics::track::rail::RailSection;
use crate::dynamics::track::{Damping, RAIL_LOSS_FACTOR, Supports3, TrackConfig};
use crate::params::DynamicsKind;
use toml::{Table, Value};

/// Reads `[track]` (defaults where absent) into `resolved`: the track and
/// its layout's keys; None when a key is invalid (the errors are
/// recorded).
pub(super) fn read(
    root: &mut Table,
    resolved: &mut Table,
    errors: &mut Vec<ConfigError>,
) -> Option<(TrackConfig, LayoutSpec)> {
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
    // The layout's keys are read whatever the rest holds (their bounds'
    // defaults about the configured means, or the defaults).
    let means = [
        pad.unwrap_or(PAD_STIFFNESS_PER_PAD),
        sleeper.unwrap_or(HALF_SLEEPER_MASS),
        match pad_damping {
            Some(Damping::LossFactor(eta)) => eta,
            Some(Damping::Viscous(_)) => f64::NAN,
            None => PAD_LOSS_FACTOR,
        },
        ballast.unwrap_or(BALLAST_STIFFNESS_PER_HALF_SLEEPER),
    ];
    let layout = layout_spec(&mut s, spacing.unwrap_or(SLEEPER_SPACING), means);
    resolved.insert("track".into(), Value::Table(s.finish()));
    let track = TrackConfig {
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
    };
    Some((track, layout?))
}

/// The layout's keys: the sleepers' positions (`sleeper_positions`, m from
/// the stretch's start, or `spacing_std` with `spacing_min` and
/// `spacing_max`), each [`Property`]'s per support (`<name>_pattern` or
/// `<name>_std` with its bounds), and the `seed` of the random forms; `d`
/// the configured spacing (m), `means` the configured values in the order
/// of [`Property::ALL`] (NaN: a viscous pad's loss factor, which a layout
/// cannot set). Bounds default to four standard deviations about the mean
/// (above a tenth of it).
fn layout_spec(s: &mut Section, d: f64, means: [f64; 4]) -> Option<LayoutSpec> {
    let positions = s
        .has("sleeper_positions")
        .then(|| s.f64_list("sleeper_positions", Vec::new(), Range::NonNegative, MAX_SUPPORTS));
    let drawn = random(s, "spacing", d, (Range::Closed(0.0, 0.2), Range::Positive));
    let spacing = match (positions, drawn) {
        (Some(_), Some(_)) => {
            s.error("spacing_std", "and track.sleeper_positions both place the sleepers: give one of them".into());
            None
        }
        (Some(p), None) => p.map(Spacing::Positions),
        (None, Some(Some(Spread { std: 0.0, .. }))) => Some(Spacing::Uniform),
        (None, Some(r)) => r.map(Spacing::Random),
        (None, None) => Some(Spacing::Uniform),
    };
    let values = Property::ALL.map(|p| {
        let range = match p {
            Property::PadStiffness | Property::BallastStiffness => Range::Positive,
            Property::SleeperMass => Range::NonNegative,
            Property::PadLossFactor => Range::Closed(0.0, 10.0),
        };
        per_support(s, p.name(), means[p as usize], range)
    });
    let any_drawn =
        matches!(spacing, Some(Spacing::Random(_))) || values.iter().any(|v| matches!(v, Some(PerSupport::Random(_))));
    let seed =
        if any_drawn || s.has("seed") { s.usize("seed", None, 0, usize::MAX >> 1).map(|v| v as u64) } else { Some(0) };
    let [pad, mass, loss, ballast] = values;
    Some(LayoutSpec { spacing: spacing?, values: [pad?, mass?, loss?, ballast?], seed: seed? })
}

/// The most supports a layout lists.
const MAX_SUPPORTS: usize = 10_000;

/// `<name>_std` and its bounds `<name>_min`, `<name>_max` (defaults: four
/// standard deviations about `mean`, above a tenth of it), where
/// `<name>_std` is given (`Some(None)` where a key is invalid); a zero
/// deviation draws nothing (the bounds are read and the mean kept).
#[allow(clippy::option_option)]
fn random(s: &mut Section, name: &str, mean: f64, (std_range, value_range): (Range, Range)) -> Option<Option<Spread>> {
    let key = format!("{name}_std");
    if !s.has(&key) {
        return None;
    }
    let std = s.f64(&key, None, std_range);
    let spread = std.unwrap_or(0.0);
    let lo = s.f64(&format!("{name}_min"), Some((mean - 4.0 * spread).max(0.1 * mean)), Range::NonNegative);
    let hi = s.f64(&format!("{name}_max"), Some(mean + 4.0 * spread), value_range);
    Some(match (std, lo, hi) {
        (Some(std), Some(lo), Some(hi)) => Some(Spread { std, bounds: (lo, hi) }),
        _ => None,
    })
}

/// `<name>_pattern` (a value per support, repeated) or `<name>_std` with
/// its bounds, not both; the configured value at every support otherwise
/// (and with a zero deviation).
fn per_support(s: &mut Section, name: &str, mean: f64, range: Range) -> Option<PerSupport> {
    let pattern = format!("{name}_pattern");
    let listed = s.has(&pattern).then(|| s.f64_list(&pattern, Vec::new(), range, MAX_SUPPORTS));
    // A viscous pad's loss factor (NaN) draws about a finite stand-in, so
    // that only the refusal below is reported.
    let drawn = random(s, name, if mean.is_nan() { 1.0 } else { mean }, (Range::NonNegative, range));
    if mean.is_nan() && (listed.is_some() || drawn.is_some()) {
        let key = if listed.is_some() { pattern } else { format!("{name}_std") };
        s.error(&key, "gives the pads loss factors: the pads are damped viscously (track.pad_damping)".into());
        return None;
    }
    match (listed, drawn) {
        (Some(_), Some(_)) => {
            s.error(
                &format!("{name}_std"),
                format!("and track.{pattern} both set the supports' {name}: give one of them"),
            );
            None
        }
        (Some(p), None) => p.map(PerSupport::Pattern),
        (None, Some(Some(Spread { std: 0.0, .. }))) => Some(PerSupport::Uniform),
        (None, Some(r)) => r.map(PerSupport::Random),
        (None, None) => Some(PerSupport::Uniform),
    }
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

/// The layout of `spec` over the stretch `stretch` (m, its ends): one bay
/// of `track` where the layout's keys are absent; refused (recorded in
/// `errors`, naming the key) where it cannot be laid out or the study's
/// track has no discrete supports.
pub(super) fn layout(
    track: &TrackConfig,
    spec: &LayoutSpec,
    stretch: Option<(f64, f64)>,
    dynamics: Option<DynamicsKind>,
    errors: &mut Vec<ConfigError>,
) -> Layout {
    let one_bay = Layout::uniform(track);
    if spec.is_uniform() {
        return one_bay;
    }
    let key = match &spec.spacing {
        Spacing::Positions(_) => "track.sleeper_positions".to_string(),
        Spacing::Random(_) => "track.spacing_std".to_string(),
        Spacing::Uniform => Property::ALL
            .into_iter()
            .find_map(|p| match spec.value(p) {
                PerSupport::Uniform => None,
                PerSupport::Pattern(_) => Some(format!("track.{}_pattern", p.name())),
                PerSupport::Random(_) => Some(format!("track.{}_std", p.name())),
            })
            .expect("not uniform"),
    };
    if !matches!(dynamics, Some(DynamicsKind::Discrete { .. })) {
        errors.push(ConfigError::new(
            &key,
            "lays out the discrete track's supports: it needs a growth study with dynamics.model = \"discrete\"".into(),
        ));
        return one_bay;
    }
    let Some((a, b)) = stretch else {
        return one_bay;
    };
    Layout::from_spec(track, spec, b - a).unwrap_or_else(|e| {
        errors.push(match e {
            LayoutError::Positions(why) => ConfigError::new("track.sleeper_positions", why),
            LayoutError::Bounds(key, why) => ConfigError::new(&key, why),
        });
        one_bay
    })
}
