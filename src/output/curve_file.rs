//! The file `corrugation curve` writes.
//!
//! - Group `geometry`, on dimension `lateral_shift` (m, the wheelset's
//!   shift to the left of the direction of travel): the rigid contact's
//!   `rolling_radius_difference` (m, left minus right), `contact_angle_left`
//!   and `contact_angle_right` (rad), `roll` (rad), `contact_left` and
//!   `contact_right` (m, the contact on each wheel profile from its tape
//!   circle, positive to the field side); on dimension `amplitude` (m) the
//!   equivalent conicity (EN 15302's method) `conicity`; the scalar
//!   `equivalent_conicity` at 3 mm.
//! - Group `curving`, on dimension `wheel` (each wheelset's low and high
//!   wheel, the leading first; names in the coordinate): `normal_force` (N),
//!   `creepage_x`, `creepage_y` (1), `spin` (1/m), `longitudinal_force`,
//!   `lateral_force` (N, on the wheel), `lateral_shift` (m) and
//!   `angle_of_attack` (rad) of its wheelset, `contact_angle` (rad),
//!   `rolling_radius` (m), `contact_wheel` and `contact_rail` (m, on each
//!   profile from its tape circle or axis, positive to the field side),
//!   `flange_contact` and `two_point` (0/1). Creepages, spin and forces in
//!   the study's axes (x forward, y to the right, the spin about the
//!   downward normal) for a curve turning left: the low rail on the left;
//!   the lateral shift and the angle of attack positive towards the high
//!   rail. Attributes: the curve, the cant deficiency, the vehicle.

use super::netcdf::{NcError, write_atomically};
use crate::config::curve::CurveSetup;
use crate::curving::conicity::RadiusDifference;
use crate::curving::geometry::Side;
use crate::curving::vehicle::Vehicle;
use ndarray::{Array0, Array1};
use std::path::Path;

/// The amplitudes of the conicity curve (m).
pub fn amplitudes() -> Vec<f64> {
    (2..=16).map(|k| k as f64 * 0.5e-3).collect()
}

/// Writes the curve's geometry tables and steady state to `path` atomically.
pub fn write_curve_file(path: &Path, setup: &CurveSetup, config: &str) -> Result<(), NcError> {
    write_atomically(path, |root| {
        root.attr_str("title", "steady curving")?;
        root.attr_str("program", "corrugation")?;
        root.attr_str("version", env!("CARGO_PKG_VERSION"))?;
        root.attr_str("config", config)?;
        let rows = setup.table.rows();
        let g = root.group("geometry")?;
        let shift: Vec<f64> = rows.iter().map(|r| r.shift).collect();
        g.coord_f64("lateral_shift", &shift, "m", "the wheelset's lateral shift, to the left (the low rail)", false)?;
        let dr: Vec<f64> = rows.iter().map(|r| r.wheel[0].rolling_radius - r.wheel[1].rolling_radius).collect();
        let var = |name: &str, v: Vec<f64>, units: &str, long: &str| {
            g.var_f64(name, &["lateral_shift"], Array1::from(v).into_dyn().view(), units, long)
        };
        var("rolling_radius_difference", dr.clone(), "m", "rigid contact: rolling radius left minus right")?;
        for side in Side::BOTH {
            let i = side as usize;
            let angle = rows.iter().map(|r| r.wheel[i].contact_angle(side)).collect();
            var(&format!("contact_angle_{}", side.name()), angle, "rad", "rigid contact angle")?;
            let on = rows.iter().map(|r| r.wheel[i].wheel_lateral).collect();
            var(&format!("contact_{}", side.name()), on, "m", "contact on the wheel profile from its tape circle")?;
        }
        var("roll", rows.iter().map(|r| r.roll).collect(), "rad", "the wheelset's roll, raising the left wheel")?;
        let conicity_of = RadiusDifference { shift, difference: dr };
        let amplitudes = amplitudes();
        g.coord_f64("amplitude", &amplitudes, "m", "amplitude of the kinematic oscillation", false)?;
        let conicity: Vec<f64> =
            amplitudes.iter().map(|&a| conicity_of.equivalent_conicity(a).unwrap_or(f64::NAN)).collect();
        g.var_f64(
            "conicity",
            &["amplitude"],
            Array1::from(conicity).into_dyn().view(),
            "1",
            "equivalent conicity (EN 15302)",
        )?;
        let e3 = conicity_of.equivalent_conicity(3e-3).unwrap_or(f64::NAN);
        g.var_f64(
            "equivalent_conicity",
            &[],
            Array0::from_elem((), e3).into_dyn().view(),
            "1",
            "equivalent conicity at 3 mm",
        )?;

        let c = root.group("curving")?;
        c.attr_f64("radius_m", setup.curve.radius)?;
        c.attr_f64("cant_m", setup.curve.cant)?;
        c.attr_f64("speed_m_per_s", setup.curve.speed)?;
        c.attr_f64("cant_deficiency_m", setup.curve.cant_deficiency())?;
        c.attr_f64("axle_load_n", setup.loads.axle_load)?;
        c.attr_str("vehicle", if matches!(setup.vehicle, Vehicle::Bogie { .. }) { "bogie" } else { "wheelset" })?;
        if let Some((y, yaw)) = setup.state.frame {
            c.attr_f64("frame_lateral_shift_m", -y)?;
            c.attr_f64("frame_yaw_rad", yaw)?;
        }
        let mut names = Vec::new();
        let mut cols: Vec<Vec<f64>> = vec![Vec::new(); 14];
        for (name, w, p) in setup.state.wheels() {
            names.push(name);
            let (creepage_y, spin, lateral_force) = p.study_axes(false);
            let v = [
                p.normal_force,
                p.creepage.x,
                creepage_y,
                spin,
                p.force_x,
                lateral_force,
                -w.shift,
                w.angle_of_attack(),
                p.contact_angle(),
                p.contact.rolling_radius,
                p.contact.wheel_lateral,
                p.contact.rail_lateral,
                f64::from(u8::from(p.on_flange())),
                f64::from(u8::from(p.two_point())),
            ];
            for (col, x) in cols.iter_mut().zip(v) {
                col.push(x);
            }
        }
        c.coord_str("wheel", &names, "", "wheelset and rail")?;
        let meta = [
            ("normal_force", "N", "normal force"),
            ("creepage_x", "1", "longitudinal creepage"),
            ("creepage_y", "1", "lateral creepage in the contact plane (y to the right)"),
            ("spin", "1/m", "spin creepage (about the downward normal)"),
            ("longitudinal_force", "N", "longitudinal creep force on the wheel"),
            ("lateral_force", "N", "lateral creep force on the wheel in the contact plane (y to the right)"),
            ("lateral_shift", "m", "the wheelset's lateral shift, towards the high rail"),
            ("angle_of_attack", "rad", "the wheelset's yaw from the radial, heading towards the high rail"),
            ("contact_angle", "rad", "contact angle"),
            ("rolling_radius", "m", "rolling radius at the contact"),
            ("contact_wheel", "m", "contact on the wheel profile from its tape circle (field side positive)"),
            ("contact_rail", "m", "contact on the rail profile from its axis (field side positive)"),
        ];
        for ((name, units, long), col) in meta.iter().zip(&cols) {
            c.var_f64(name, &["wheel"], Array1::from(col.clone()).into_dyn().view(), units, long)?;
        }
        for (k, (name, long)) in [
            ("flange_contact", "1: the contact angle above 45 degrees"),
            ("two_point", "1: a second point within the Hertz approach"),
        ]
        .iter()
        .enumerate()
        {
            let flags: Vec<i8> = cols[12 + k].iter().map(|&v| v as i8).collect();
            c.var_i8(name, &["wheel"], Array1::from(flags).into_dyn().view(), "1", long)?;
        }
        Ok(())
    })
}
