//! The `[curve]` section: a curve from its radius, cant and the vehicle
//! (the wheel and rail profiles, a wheelset or a bogie), whose steady
//! curving ([`crate::curving::steady`]) sets the study's steady state: the
//! followed wheel's normal force, creepages, spin and contact curvatures,
//! written into the keys they replace (`load.normal_force`,
//! `rolling.creepage_y`, `rolling.spin`, `rolling.creepage_x` under
//! creepage control or `load.longitudinal_force` under force control,
//! `geometry.wheel_radius`, `geometry.wheel_profile_radius`,
//! `geometry.rail_head_radius`, and `[second_rail]`'s when it is there),
//! so that the study is the one with the computed state given by hand. A
//! key the curve sets may be given only with the value the curve gives it
//! (as a resumed run's stored config has it).
//!
//! The curve turns left in the curving calculation (the low rail is the
//! wheelset's left wheel); the study's axes (y to the right of the
//! direction of travel, the spin about the downward normal) turn its
//! lateral creepage and spin; `curve.rail = "high"` follows the high rail,
//! as the first rail of the mirror-image curve.

use super::ConfigError;
use super::reader::{Range, Section};
use crate::curving::geometry::{Geometry, Side, TrackShape, WheelsetShape};
use crate::curving::profile::Profile;
use crate::curving::steady::{ContactModel, CreepLaw, Patch, Problem, SteadyState, TABLE};
use crate::curving::table::ContactTable;
use crate::curving::vehicle::{Curve, Loads, Primary, Vehicle};
use crate::hertz::Elastic;
use std::path::Path;
use toml::{Table, Value};

/// The keys `[curve]` sets that have no default: reported missing only
/// when the curve itself could be solved.
pub const SETS: [&str; 8] = [
    "load.normal_force",
    "load.longitudinal_force",
    "rolling.creepage_x",
    "rolling.creepage_y",
    "rolling.spin",
    "geometry.wheel_radius",
    "geometry.wheel_profile_radius",
    "geometry.rail_head_radius",
];

/// A curve and its steady curving, as the config gives it.
#[derive(Debug, Clone)]
pub struct CurveSetup {
    /// The profiles, placed.
    pub geometry: Geometry,
    /// The contact table.
    pub table: std::sync::Arc<ContactTable>,
    /// The curve.
    pub curve: Curve,
    /// The vehicle.
    pub vehicle: Vehicle,
    /// The loads.
    pub loads: Loads,
    /// The contact.
    pub contact: ContactModel,
    /// The steady state.
    pub state: SteadyState,
    /// The wheelset the study follows (0 the leading).
    pub wheelset: usize,
    /// The rail the study follows.
    pub rail: Side,
}

impl CurveSetup {
    /// The followed wheel's patch and the other wheel's.
    pub fn patches(&self) -> (&Patch, &Patch) {
        let w = &self.state.wheelsets[self.wheelset];
        (w.on(self.rail), w.on(if self.rail == Side::Left { Side::Right } else { Side::Left }))
    }
}

/// A number from another section, as given (a number or a quantity in its
/// key's unit).
fn raw(root: &Table, section: &str, key: &str) -> Option<f64> {
    let unit = super::units::key_units(&format!("{section}.{key}")).unwrap_or("1");
    super::quantity::number(root.get(section)?.get(key)?, unit)
}

/// A profile by name ("S1002", "cone 1:N", "60E1") or file (relative to
/// the config's folder).
fn profile(s: &mut Section, key: &str, default: &str, dir: &Path) -> Option<Profile> {
    let name = s.string(key, default)?;
    let lower = name.trim().to_lowercase();
    if lower == "s1002" && key == "wheel_profile" {
        return Some(Profile::s1002());
    }
    if (lower == "60e1" || lower == "uic60") && key == "rail_profile" {
        return Some(Profile::rail_60e1());
    }
    if let Some(n) = lower.strip_prefix("cone 1:").and_then(|n| n.trim().parse::<f64>().ok())
        && key == "wheel_profile"
    {
        if !(5.0..=1000.0).contains(&n) {
            s.error(key, format!("= \"{name}\": the cone's slope 1:N needs N in [5, 1000]"));
            return None;
        }
        return Some(Profile::cone(1.0 / n));
    }
    match Profile::measured(&dir.join(&name)) {
        Ok(p) => Some(p),
        Err(e) => {
            let named = if key == "wheel_profile" { "\"S1002\", \"cone 1:N\"" } else { "\"60E1\"" };
            s.error(key, format!("= \"{name}\" is not {named} or a profile file: {e}"));
            None
        }
    }
}

/// Reads `[curve]`, solves its steady curving and writes the state into the
/// keys it sets; returns the resolved section and the setup (None without
/// the section, or with errors).
pub(super) fn apply(
    root: &mut Table,
    dir: &Path,
    errors: &mut Vec<ConfigError>,
) -> Option<(Table, Option<CurveSetup>)> {
    if !root.contains_key("curve") {
        return None;
    }
    let mut s = Section::new(root, "", "curve", errors);
    let radius = s.f64("radius", None, Range::Closed(20.0, 1e5));
    let cant = s.f64("cant", Some(0.0), Range::Closed(0.0, 0.2));
    let rail_spacing = s.f64("rail_spacing", Some(1.5), Range::Closed(0.5, 2.5));
    let gauge = s.f64("gauge", Some(1.435), Range::Closed(0.6, 2.0));
    let gauge_depth = s.f64("gauge_depth", Some(0.014), Range::Closed(0.0, 0.03));
    let flange_back = s.f64("flange_back", Some(1.360), Range::Closed(0.5, 2.0));
    let inclination = s.f64("rail_inclination", Some(40.0), Range::Closed(0.0, 1000.0));
    let wheel_radius = s.f64("wheel_radius", Some(0.46), Range::Closed(0.1, 1.0));
    let wheel = profile(&mut s, "wheel_profile", "S1002", dir);
    let rail = profile(&mut s, "rail_profile", "60E1", dir);
    let vehicle = s.choice("vehicle", Some("bogie"), &["bogie", "wheelset"]);
    let bogie = vehicle.as_deref() == Some("bogie");
    let (wheelbase, kx, ky, spacing) = if bogie {
        (
            s.f64("wheelbase", Some(2.5), Range::Closed(0.5, 5.0)),
            s.f64("primary_longitudinal_stiffness", Some(30e6), Range::Closed(1e4, 1e10)),
            s.f64("primary_lateral_stiffness", Some(4e6), Range::Closed(1e4, 1e10)),
            s.f64("axlebox_spacing", Some(2.0), Range::Closed(0.5, 3.0)),
        )
    } else {
        for key in ["wheelbase", "primary_longitudinal_stiffness", "primary_lateral_stiffness", "axlebox_spacing"] {
            s.reject(key, "is a bogie's; curve.vehicle = \"wheelset\" has no suspension");
        }
        (Some(0.0), Some(0.0), Some(0.0), Some(0.0))
    };
    let axle_load = s.f64("axle_load", None, Range::Closed(1e3, 5e5));
    let centre_height = s.f64("centre_height", Some(1.0), Range::Closed(0.0, 4.0));
    let traction = s.f64("traction", Some(0.0), Range::Finite);
    let mut wheelset = s.choice("wheelset", Some("leading"), &["leading", "trailing"]);
    if !bogie && wheelset.as_deref() == Some("trailing") {
        s.error("wheelset", "= \"trailing\" needs curve.vehicle = \"bogie\" (a single wheelset leads)".into());
        wheelset = None;
    }
    let followed = s.choice("rail", Some("low"), &["low", "high"]);
    let resolved = s.finish();

    let speed = raw(root, "rolling", "speed");
    let (young, nu, mu) = (
        raw(root, "material", "young_modulus"),
        raw(root, "material", "poisson_ratio"),
        raw(root, "material", "friction_coefficient"),
    );
    let creepage_control = root.get("load").and_then(|l| l.get("control")).and_then(Value::as_str) == Some("creepage");
    let (
        Some(radius),
        Some(cant),
        Some(rail_spacing),
        Some(gauge),
        Some(gauge_depth),
        Some(flange_back),
        Some(inclination),
        Some(wheel_radius),
        Some(wheel),
        Some(rail),
        Some(wheelbase),
        Some(kx),
        Some(ky),
        Some(spacing),
        Some(axle_load),
        Some(centre_height),
        Some(traction),
        Some(wheelset),
        Some(followed),
    ) = (
        radius,
        cant,
        rail_spacing,
        gauge,
        gauge_depth,
        flange_back,
        inclination,
        wheel_radius,
        wheel,
        rail,
        wheelbase,
        kx,
        ky,
        spacing,
        axle_load,
        centre_height,
        traction,
        wheelset,
        followed,
    )
    else {
        return Some((resolved, None));
    };
    // The other sections' errors are reported by their readers.
    let (Some(speed), Some(young), Some(nu), Some(mu)) = (speed, young, nu, mu) else {
        return Some((resolved, None));
    };
    if !(speed > 0.0 && young > 0.0 && (0.0..0.5).contains(&nu) && mu > 0.0 && mu <= 1.0) {
        return Some((resolved, None));
    }
    let fail = |errors: &mut Vec<ConfigError>, message: String| errors.push(ConfigError::new("curve", message));
    let inclination = if inclination > 0.0 { (1.0 / inclination).atan() } else { 0.0 };
    let wheelset_shape = WheelsetShape { wheels: [wheel.clone(), wheel], radius: [wheel_radius; 2], flange_back };
    let track = TrackShape { rails: [rail.clone(), rail], gauge, gauge_depth, inclination };
    let geometry = match Geometry::new(wheelset_shape, track) {
        Ok(g) => g,
        Err(e) => {
            fail(errors, format!("the profiles cannot be placed: {e}"));
            return Some((resolved, None));
        }
    };
    let table = match ContactTable::cached(&geometry, TABLE.0, TABLE.1) {
        Ok(t) => t,
        Err(e) => {
            fail(errors, format!("the contact table fails: {e} (check curve.gauge and curve.flange_back)"));
            return Some((resolved, None));
        }
    };
    let curve = Curve { radius, cant, rail_spacing, speed };
    let vehicle = if bogie {
        Vehicle::Bogie {
            half_wheelbase: 0.5 * wheelbase,
            primary: Primary { longitudinal: kx, lateral: ky, half_spacing: 0.5 * spacing },
        }
    } else {
        Vehicle::Wheelset
    };
    let loads = Loads { axle_load, centre_height, traction };
    let contact = ContactModel {
        elastic: Elastic { young_modulus: young, poisson_ratio: nu },
        friction: mu,
        creep: CreepLaw::Fastsim,
    };
    let problem = Problem { geometry: &geometry, table: &table, curve, vehicle, loads, contact };
    let state = match problem.solve() {
        Ok(s) => s,
        Err(e) => {
            fail(errors, format!("no steady curving: {e}"));
            return Some((resolved, None));
        }
    };
    let setup = CurveSetup {
        geometry: geometry.clone(),
        table: table.clone(),
        curve,
        vehicle,
        loads,
        contact,
        state,
        wheelset: usize::from(wheelset == "trailing"),
        rail: if followed == "low" { Side::Left } else { Side::Right },
    };
    let (first, second) = setup.patches();
    let has_second = root.contains_key("second_rail");
    let mut set = |key: &str, value: f64| {
        let (section, name) = key.split_once('.').expect("section.key");
        let table = root.entry(section).or_insert_with(|| Value::Table(Table::new()));
        let Some(table) = table.as_table_mut() else { return };
        let unit = super::units::key_units(key).unwrap_or("1");
        match table.get(name).map(|v| super::quantity::number(v, unit)) {
            Some(Some(g)) if g.to_bits() == value.to_bits() => {}
            Some(_) => errors.push(ConfigError::new(
                key,
                format!("is set by [curve] (to {value:e}); remove it, or the [curve] section"),
            )),
            None => {
                table.insert(name.into(), Value::Float(value));
            }
        }
    };
    // Each rail's steady state in the study's axes (y to the right, spin
    // about the downward normal); the high rail as the mirror image's first
    // rail.
    let rails = [
        (
            first,
            [
                "load.normal_force",
                "rolling.creepage_y",
                "rolling.spin",
                "rolling.creepage_x",
                "load.longitudinal_force",
            ],
        ),
        (
            second,
            [
                "second_rail.normal_force",
                "second_rail.creepage_y",
                "second_rail.spin",
                "second_rail.creepage_x",
                "second_rail.longitudinal_force",
            ],
        ),
    ];
    for (p, [normal, creepage_y, spin, creepage_x, longitudinal]) in rails.into_iter().take(1 + usize::from(has_second))
    {
        let (y, phi, _) = p.study_axes(setup.rail == Side::Right);
        set(normal, p.normal_force);
        set(creepage_y, y);
        set(spin, phi);
        if creepage_control {
            set(creepage_x, p.creepage.x);
        } else {
            set(longitudinal, p.force_x);
        }
    }
    // The followed wheel's contact curvatures (the Hertz problem's).
    let c = &first.contact;
    set("geometry.wheel_radius", c.rolling_radius / c.normal.1);
    let rail_curvature = c.rail_curvature.max(1e-9);
    let wheel_curvature = 2.0 * first.curvatures.1 - rail_curvature;
    set("geometry.rail_head_radius", if rail_curvature <= 1e-9 { f64::INFINITY } else { 1.0 / rail_curvature });
    set(
        "geometry.wheel_profile_radius",
        if wheel_curvature.abs() < 1e-9 { f64::INFINITY } else { 1.0 / wheel_curvature },
    );
    Some((resolved, Some(setup)))
}
