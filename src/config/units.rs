//! The unit of every numeric config key, for outputs that name keys, such
//! as a sweep's axes. The book's configuration reference
//! (`docs/src/reference/configuration.md`) gives the same units: the test
//! `tests/config_reference.rs` holds the two together and asks for an entry
//! here for every key that holds a number.
//! It also serves values written with their unit ([`super::quantity`]) and
//! `check`'s engineering units.

/// (key with array indices removed, unit).
const UNITS: &[(&str, &str)] = &[
    ("material.young_modulus", "Pa"),
    ("material.poisson_ratio", "1"),
    ("material.friction_coefficient", "1"),
    ("material.kinetic_friction", "1"),
    ("material.friction_speed", "m/s"),
    ("material.friction_memory", "m"),
    ("material.memory_speed", "m/s"),
    ("geometry.wheel_radius", "m"),
    ("geometry.wheel_profile_radius", "m"),
    ("geometry.rail_head_radius", "m"),
    ("rolling.speed", "m/s"),
    ("rolling.creepage_x", "1"),
    ("rolling.creepage_y", "1"),
    ("rolling.spin", "1/m"),
    ("load.normal_force", "N"),
    ("load.longitudinal_force", "N"),
    ("load.harmonics.amplitude", "N"),
    ("load.harmonics.wavelength", "m"),
    ("load.harmonics.phase", "rad"),
    ("contact.tolerance", "1"),
    ("contact.elements_x", "1"),
    ("contact.elements_y", "1"),
    ("contact.regularisation", "m/s"),
    ("contact.dx", "m"),
    ("contact.dy", "m"),
    ("contact.profile_grid_scale", "1"),
    ("wear.k_over_h", "m2/N"),
    ("wear.work_coefficients", "1"),
    ("wear.density", "kg/m3"),
    ("wear.map_coefficients", "1"),
    ("wear.map_speeds", "m/s"),
    ("wear.hardness", "Pa"),
    ("wear.substeps", "1"),
    ("passage.start", "m"),
    ("passage.end", "m"),
    ("passage.step_length", "m"),
    ("rail.x_min", "m"),
    ("rail.x_max", "m"),
    ("rail.dx", "m"),
    ("rail.dy", "m"),
    ("rail.half_width", "m"),
    ("growth.passes", "1"),
    ("growth.traffic_scale", "1"),
    ("growth.traffic_scale_max", "1"),
    ("growth.max_update_ratio", "1"),
    ("growth.store_every", "1"),
    ("growth.checkpoint_every", "1"),
    ("growth.contact_history", "1"),
    ("growth.saturation_rate", "dB/1e5 passages"),
    ("spectrum.wavelength_min", "m"),
    ("spectrum.wavelength_max", "m"),
    ("spectrum.classes", "1"),
    ("spectrum.resolution", "m"),
    ("spectrum.perturbation", "m"),
    ("roughness.seed", "1"),
    ("roughness.rms", "m"),
    ("roughness.wavelength_min", "m"),
    ("roughness.wavelength_max", "m"),
    ("roughness.harmonics.amplitude", "m"),
    ("roughness.harmonics.wavelength", "m"),
    ("roughness.harmonics.phase", "rad"),
    ("roughness.bands.wavelength", "m"),
    ("roughness.bands.level", "dB"),
    ("roughness.window_start", "m"),
    ("roughness.spike_threshold", "1"),
    ("roughness.curvature_radius", "m"),
    ("roughness.position_column", "1"),
    ("roughness.height_column", "1"),
    ("dynamics.unsprung_mass", "kg"),
    ("dynamics.contact_offset", "m"),
    ("track.rail_bending_stiffness", "N m2"),
    ("track.rail_mass", "kg/m"),
    ("track.rail_shear_stiffness", "N"),
    ("track.rail_rotary_inertia", "kg m"),
    ("track.sleeper_spacing", "m"),
    ("track.pad_stiffness", "N/m"),
    ("track.pad_loss_factor", "1"),
    ("track.pad_damping", "N s/m"),
    ("track.sleeper_mass", "kg"),
    ("track.sleeper_positions", "m"),
    ("track.spacing_std", "m"),
    ("track.spacing_min", "m"),
    ("track.spacing_max", "m"),
    ("track.pad_stiffness_pattern", "N/m"),
    ("track.pad_stiffness_std", "N/m"),
    ("track.pad_stiffness_min", "N/m"),
    ("track.pad_stiffness_max", "N/m"),
    ("track.sleeper_mass_pattern", "kg"),
    ("track.sleeper_mass_std", "kg"),
    ("track.sleeper_mass_min", "kg"),
    ("track.sleeper_mass_max", "kg"),
    ("track.pad_loss_factor_pattern", "1"),
    ("track.pad_loss_factor_std", "1"),
    ("track.pad_loss_factor_min", "1"),
    ("track.pad_loss_factor_max", "1"),
    ("track.ballast_stiffness_pattern", "N/m"),
    ("track.ballast_stiffness_std", "N/m"),
    ("track.ballast_stiffness_min", "N/m"),
    ("track.ballast_stiffness_max", "N/m"),
    ("track.seed", "1"),
    ("track.ballast_stiffness", "N/m"),
    ("track.ballast_loss_factor", "1"),
    ("track.ballast_damping", "N s/m"),
    ("track.rail_loss_factor", "1"),
    ("track.rail_axial_stiffness", "N"),
    ("track.rail_lateral_bending_stiffness", "N m2"),
    ("track.rail_lateral_shear_stiffness", "N"),
    ("track.rail_lateral_rotary_inertia", "kg m"),
    ("track.rail_torsional_stiffness", "N m2"),
    ("track.rail_polar_inertia", "kg m"),
    ("track.rail_height", "m"),
    ("track.rail_neutral_axis_height", "m"),
    ("track.rail_shear_centre_height", "m"),
    ("track.pad_lateral_stiffness", "N/m"),
    ("track.pad_longitudinal_stiffness", "N/m"),
    ("track.pad_width", "m"),
    ("track.pad_length", "m"),
    ("track.ballast_lateral_stiffness", "N/m"),
    ("track.ballast_longitudinal_stiffness", "N/m"),
    ("vehicle.wheels", "m"),
    ("vehicle.unsprung_mass", "kg"),
    ("vehicle.normal_force", "N"),
    ("vehicle.longitudinal_force", "N"),
    ("wheelset.torsional_stiffness", "N m/rad"),
    ("wheelset.polar_inertia", "kg m2"),
    ("wheelset.torsional_loss_factor", "1"),
    ("wheelset.mass", "kg"),
    ("wheelset.roll_inertia", "kg m2"),
    ("wheelset.yaw_inertia", "kg m2"),
    ("wheelset.suspension_stiffness_x", "N/m"),
    ("wheelset.suspension_stiffness_y", "N/m"),
    ("wheelset.suspension_stiffness_z", "N/m"),
    ("wheelset.suspension_loss_factor", "1"),
    ("wheelset.axle_box_spacing", "m"),
    ("traffic.axle_load", "kg"),
    ("traffic.mix.axle_load", "kg"),
    ("traffic.axles_per_day", "1/d"),
    ("traffic.trains_per_day", "1/d"),
    ("traffic.axles_per_train", "1"),
    ("levels.limit_table.wavelength", "m"),
    ("levels.limit_table.level", "dB"),
    ("wheelset.contact_spacing", "m"),
    ("wheelset.bending_damping", "1"),
    ("wheelset.wheel_damping", "1"),
    ("traffic.mix.speed", "m/s"),
    ("traffic.mix.normal_force", "N"),
    ("traffic.mix.longitudinal_force", "N"),
    ("traffic.mix.unsprung_mass", "kg"),
    ("traffic.mix.share", "1"),
    ("traffic.mix.wheels", "m"),
    ("curve.radius", "m"),
    ("curve.cant", "m"),
    ("curve.rail_spacing", "m"),
    ("curve.gauge", "m"),
    ("curve.gauge_depth", "m"),
    ("curve.flange_back", "m"),
    ("curve.rail_inclination", "1"),
    ("curve.wheel_radius", "m"),
    ("curve.wheelbase", "m"),
    ("curve.primary_longitudinal_stiffness", "N/m"),
    ("curve.primary_lateral_stiffness", "N/m"),
    ("curve.axlebox_spacing", "m"),
    ("curve.axle_load", "N"),
    ("curve.centre_height", "m"),
    ("curve.traction", "N"),
    ("second_rail.normal_force", "N"),
    ("second_rail.longitudinal_force", "N"),
    ("second_rail.creepage_x", "1"),
    ("second_rail.creepage_y", "1"),
    ("second_rail.spin", "1/m"),
    ("second_rail.roughness_seed", "1"),
];

/// The unit of config key `key` (`load.harmonics[0].amplitude` counts as
/// `load.harmonics.amplitude`); None for keys without a number.
pub fn key_units(key: &str) -> Option<&'static str> {
    let plain = strip_indices(key);
    UNITS.iter().find(|(k, _)| *k == plain).map(|(_, u)| *u)
}

/// The numeric keys (array indices removed) with their SI units.
pub fn all_keys() -> impl Iterator<Item = (&'static str, &'static str)> {
    UNITS.iter().copied()
}

/// `load.harmonics[0].amplitude` -> `load.harmonics.amplitude`.
pub fn strip_indices(key: &str) -> String {
    let mut plain = String::with_capacity(key.len());
    let mut depth = 0;
    for c in key.chars() {
        match c {
            '[' => depth += 1,
            ']' => depth -= 1,
            _ if depth == 0 => plain.push(c),
            _ => {}
        }
    }
    plain
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_of_plain_and_indexed_keys() {
        assert_eq!(key_units("rolling.speed"), Some("m/s"));
        assert_eq!(key_units("load.harmonics[2].amplitude"), Some("N"));
        assert_eq!(key_units("roughness.harmonics[0].amplitude"), Some("m"));
        assert_eq!(key_units("contact.model"), None);
        assert_eq!(key_units("traffic.mix[1].axle_load"), Some("kg"));
    }
}
