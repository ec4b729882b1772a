//! Sections of a growth study: `[growth]`, `[roughness]`, `[dynamics]`.
//! Without `[growth]` the scene is a single passage and the other two
//! sections are not allowed.

use super::ConfigError;
use super::reader::{Range, Section};
use super::traffic::BaseClass;
use crate::growth::roughness::band_harmonics;
use crate::growth::traffic::DEFAULT_MAX_UPDATE_RATIO;
use crate::params::{CreepForces, Directions, DynamicsKind, GrowthParams, StopRule};
use crate::params::{LevelBand, TrafficScaling};
use toml::{Table, Value};

/// Default `growth.saturation_rate` (dB per 1e5 real passages): a tenth of
/// a decibel, about 1 % of rms, per 1e5 passages.
pub const DEFAULT_SATURATION_RATE: f64 = 0.1;

/// Reads the growth sections; `Ok(None)` for a single-passage scene, `Err`
/// when a key is invalid (the errors are recorded).
pub fn read(
    root: &mut Table,
    resolved: &mut Table,
    base: BaseClass,
    roughness: &super::roughness::Context,
    errors: &mut Vec<ConfigError>,
) -> Result<Option<GrowthParams>, ()> {
    if !root.contains_key("growth") {
        for name in ["roughness", "dynamics", "traffic"] {
            if root.remove(name).is_some() {
                errors.push(ConfigError::new(name, "is only allowed with a [growth] section".into()));
            }
        }
        return Ok(None);
    }
    let mut s = Section::new(root, "", "growth", errors);
    let passes = s.usize("passes", None, 1, 1_000_000);
    let traffic_scale = s.f64("traffic_scale", Some(1.0), Range::Closed(1.0, 1e9));
    let adaptive = s.bool("adaptive", false);
    let scale_max = s.f64("traffic_scale_max", Some(1e9), Range::Closed(1.0, 1e9));
    let ratio = s.f64("max_update_ratio", Some(DEFAULT_MAX_UPDATE_RATIO), Range::OpenClosed(0.0, 1.0));
    let traffic_scaling = match (traffic_scale, adaptive, scale_max, ratio) {
        (Some(scale), Some(false), Some(_), Some(max_update_ratio)) => {
            Some(TrafficScaling::Fixed { scale, max_update_ratio })
        }
        (Some(initial), Some(true), Some(max), Some(max_update_ratio)) if initial <= max => {
            Some(TrafficScaling::Adaptive { initial, max, max_update_ratio })
        }
        (Some(initial), Some(true), Some(max), Some(_)) => {
            s.error("traffic_scale_max", format!("= {max} must be >= growth.traffic_scale = {initial}"));
            None
        }
        _ => None,
    };
    let store_every = s.usize("store_every", Some(1), 1, 1_000_000);
    let checkpoint_every = s.usize("checkpoint_every", Some(10), 1, 1_000_000);
    let history = s.usize_list("contact_history", vec![0], 1_000_000);
    let stop = s.choice("stop", Some("never"), &["never", "saturation", "limit"]);
    let rate = s.f64("saturation_rate", Some(DEFAULT_SATURATION_RATE), Range::OpenClosed(0.0, 100.0));
    let stop = match (stop.as_deref(), rate) {
        (Some("saturation"), Some(rate)) => Some(StopRule::Saturation { rate }),
        (Some("limit"), Some(_)) => Some(StopRule::Limit),
        (Some(_), Some(_)) => Some(StopRule::Never),
        _ => None,
    };
    resolved.insert("growth".into(), Value::Table(s.finish()));

    let roughness = super::roughness::read(root, resolved, roughness, errors);

    let mut s = Section::new(root, "", "dynamics", errors);
    let model = s.choice("model", Some("imposed"), &["imposed", "receptance", "discrete"]);
    // Read for every model so that --set can switch models.
    let mass = s.f64("unsprung_mass", Some(600.0), Range::OpenClosed(0.0, 1e4));
    let directions = s.choice("directions", Some("all"), &["all", "vertical"]);
    let offset = s.f64("contact_offset", Some(0.0), Range::Closed(-0.04, 0.04));
    let creep_forces = s.choice("creep_forces", Some("transient"), &["transient", "steady"]);
    let spin = s.bool("spin", true);
    let directions = match (directions.as_deref(), offset, creep_forces.as_deref(), spin) {
        (Some("vertical"), Some(_), Some(_), Some(_)) => Some(Directions::Vertical),
        (Some(_), Some(contact_offset), Some(c), Some(spin)) => Some(Directions::All {
            contact_offset,
            creep_forces: if c == "steady" { CreepForces::Steady } else { CreepForces::Transient },
            spin,
        }),
        _ => None,
    };
    let dynamics = match (model.as_deref(), mass) {
        (Some("receptance"), Some(m)) => Some(DynamicsKind::Receptance { unsprung_mass: m }),
        (Some("discrete"), Some(m)) => Some(DynamicsKind::Discrete { unsprung_mass: m }),
        (Some(_), Some(_)) => Some(DynamicsKind::Imposed),
        _ => None,
    };
    resolved.insert("dynamics".into(), Value::Table(s.finish()));
    let traffic = super::traffic::read(root, resolved, BaseClass { unsprung_mass: mass, ..base }, errors);
    let (classes, operation) = match traffic {
        Some((c, o)) => (Some(c), Some(o)),
        None => (None, None),
    };

    match (
        passes,
        traffic_scaling,
        store_every,
        checkpoint_every,
        history,
        roughness,
        dynamics,
        stop,
        classes,
        (operation, directions),
    ) {
        (
            Some(passes),
            Some(traffic),
            Some(store_every),
            Some(checkpoint_every),
            Some(contact_history),
            Some(roughness),
            Some(dynamics),
            Some(stop),
            Some(classes),
            (Some(operation), Some(directions)),
        ) => Ok(Some(GrowthParams {
            passes,
            traffic,
            store_every,
            checkpoint_every,
            contact_history,
            roughness,
            dynamics,
            directions,
            stop,
            classes,
            operation,
        })),
        _ => Err(()),
    }
}

/// Checks that every band of a level spectrum is resolved on the rail grid
/// (lower edge above 2 `dx`) and holds at least one harmonic of the periodic
/// stretch of length `length`.
pub fn check_bands(bands: &[LevelBand], length: f64, dx: f64, errors: &mut Vec<ConfigError>) {
    let edge = 2f64.powf(1.0 / 6.0);
    if let Some((i, b)) = bands.iter().enumerate().find(|(_, b)| b.wavelength / edge <= 2.0 * dx) {
        errors.push(ConfigError::new(
            &format!("roughness.bands[{i}].wavelength"),
            format!(
                "= {} m: its band's lower edge {:.4e} m must be > 2 rail.dx = {} m (resolved on the rail grid)",
                b.wavelength,
                b.wavelength / edge,
                2.0 * dx
            ),
        ));
        return;
    }
    for (i, (b, ns)) in bands.iter().zip(band_harmonics(length, bands)).enumerate() {
        if ns.is_empty() {
            errors.push(ConfigError::new(
                &format!("roughness.bands[{i}].wavelength"),
                format!(
                    "= {} m: its one-third-octave band [{:.4e}, {:.4e}] m holds no harmonic L/n of the periodic \
                     stretch L = {length} m (or each lies nearer another band); lengthen the stretch or drop the band",
                    b.wavelength,
                    b.wavelength / edge,
                    b.wavelength * edge
                ),
            ));
        }
    }
}

/// Checks that every wavelength fits the periodic stretch of length `length`
/// a whole number of times.
pub fn check_periodic(key: &str, wavelength: f64, length: f64, errors: &mut Vec<ConfigError>) {
    let n = length / wavelength;
    if (n - n.round()).abs() > 1e-6 * n.max(1.0) || n.round() < 1.0 {
        errors.push(ConfigError::new(
            key,
            format!("= {wavelength} m does not fit the periodic stretch rail.x_max - rail.x_min = {length} m a whole number of times"),
        ));
    }
}
