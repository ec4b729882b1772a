//! Checks across keys and sections once the scene is read: plausibility
//! warnings, the growth study's consistency, the geometry's Hertz shape,
//! the stretch against the sleeper bays.

use super::*;

/// Notes on the numbers of `table` (at dotted `prefix`) written without a
/// unit (bare, or as a string without one) that lie outside their key's
/// usual range ([`quantity::plausibility`]).
pub(super) fn plausibility(table: &Table, prefix: &str, out: &mut Vec<String>) {
    for (k, v) in table {
        let key = if prefix.is_empty() { k.clone() } else { format!("{prefix}.{k}") };
        match v {
            Value::Table(t) => plausibility(t, &key, out),
            Value::Array(a) => {
                for (i, item) in a.iter().enumerate() {
                    if let Value::Table(t) = item {
                        plausibility(t, &format!("{key}[{i}]"), out);
                    }
                }
            }
            Value::Float(_) | Value::Integer(_) => {
                let x = v.as_float().or(v.as_integer().map(|i| i as f64)).unwrap_or(0.0);
                out.extend(quantity::plausibility(&key, x));
            }
            // A number without its unit in a string: a key the file writes
            // with its unit ("100km/h") and `--set` overrides without one.
            Value::String(text) => {
                if let Ok(x) = text.trim().parse::<f64>() {
                    out.extend(quantity::plausibility(&key, x));
                }
            }
            _ => {}
        }
    }
}

#[allow(clippy::too_many_arguments)]
pub(super) fn check_growth(
    g: &crate::params::GrowthParams,
    loads: &ImposedLoads,
    max_normal: f64,
    start: f64,
    end: f64,
    (x_min, x_max, dx): (f64, f64, f64),
    shape: Option<&HertzShape>,
    errors: &mut Vec<ConfigError>,
) {
    let length = x_max - x_min;
    for (i, h) in loads.harmonics.iter().enumerate() {
        growth::check_periodic(&format!("load.harmonics[{i}].wavelength"), h.wavelength, length, errors);
    }
    match &g.roughness {
        crate::params::Roughness::Harmonics(hs) => {
            for (i, h) in hs.iter().enumerate() {
                growth::check_periodic(&format!("roughness.harmonics[{i}].wavelength"), h.wavelength, length, errors);
            }
        }
        crate::params::Roughness::Levels { bands, .. } => growth::check_bands(bands, length, dx, errors),
        crate::params::Roughness::Measured(m) if m.processing.wavelength_min <= 2.0 * dx => {
            errors.push(ConfigError::new(
                "roughness.wavelength_min",
                format!(
                    "= {} m must be > 2 rail.dx = {} m (resolved on the rail grid)",
                    m.processing.wavelength_min,
                    2.0 * dx
                ),
            ));
        }
        crate::params::Roughness::Random { wavelength_min, .. } if *wavelength_min <= 2.0 * dx => {
            errors.push(ConfigError::new(
                "roughness.wavelength_min",
                format!("= {wavelength_min} m must be > 2 rail.dx = {} m (resolved on the rail grid)", 2.0 * dx),
            ));
        }
        _ => {}
    }
    if let Some(p) = shape.and_then(|s| s.patch(max_normal).ok())
        && start > x_min - p.a
    {
        errors.push(ConfigError::new(
            "passage.start",
            format!("= {start} m must be <= rail.x_min - a = {:.6e} m: the growth passage needs a run-in before the stretch", x_min - p.a),
        ));
    }
    if end < x_max {
        errors.push(ConfigError::new(
            "passage.end",
            format!("= {end} m must be >= rail.x_max = {x_max} m in a growth study"),
        ));
    }
}

pub(super) fn check_geometry(
    material: &Material,
    geometry: &Geometry,
    errors: &mut Vec<ConfigError>,
) -> Option<HertzShape> {
    let c = geometry.curvatures();
    if c.b <= 0.0 {
        errors.push(ConfigError::new(
            "geometry.wheel_profile_radius",
            format!(
                "= {} m gives a lateral curvature sum B = {:.4e} 1/m <= 0 (a concave wheel profile must have |radius| > geometry.rail_head_radius = {} m)",
                geometry.wheel_profile_radius, c.b, geometry.rail_head_radius
            ),
        ));
        return None;
    }
    let shape = match HertzShape::new(c, material.elastic) {
        Ok(s) => s,
        Err(e) => {
            errors.push(ConfigError::new("geometry", e.to_string()));
            return None;
        }
    };
    if let Err(e) = creep_coefficients(shape.aspect(), material.elastic.poisson_ratio) {
        errors.push(ConfigError::new(
            "geometry",
            format!("the Hertz patch is outside Kalker's creep-coefficient table: {e}"),
        ));
    }
    Some(shape)
}

/// With the discrete track the periodic stretch is a whole number of
/// sleeper bays (its first node above a sleeper).
pub(super) fn check_sleeper_bays(scene: &Scene, errors: &mut Vec<ConfigError>) {
    let Some(g) = &scene.growth else {
        return;
    };
    if !matches!(g.dynamics, crate::params::DynamicsKind::Discrete { .. }) {
        return;
    }
    let (length, d) = (scene.rail.x_max - scene.rail.x_min, scene.layout.period);
    let bays = length / d;
    if bays < 0.5 || (bays - bays.round()).abs() > 1e-6 * bays.max(1.0) {
        let what = if scene.layout.is_one_bay(&scene.track) {
            format!("sleeper bays (track.sleeper_spacing = {d} m)")
        } else {
            format!("the track layout's periods ({d} m, its {} supports)", scene.layout.len())
        };
        errors.push(ConfigError::new(
            "rail.x_max",
            format!(
                "- rail.x_min = {length} m must be a whole number of {what} with dynamics.model = \"discrete\" (it is \
                 {bays:.3})"
            ),
        ));
    }
}
