//! The wheelset's contact table: the rigid contact of each wheel against
//! the lateral shift, on a fine grid, interpolated linearly between its
//! rows. A curving calculation reads each wheel's contact point, angle,
//! rolling radius and curvatures from it (the classical contact table of
//! vehicle-dynamics codes, e.g. Iwnicki (ed.), *Handbook of Railway
//! Vehicle Dynamics*, 2006, ch. 4); where the rigid contact jumps (the
//! tread to the gauge corner, to the flange) the interpolation spreads the
//! jump over one step.

use super::geometry::{Closest, Geometry, GeometryError, Side};
use rayon::prelude::*;
use std::sync::{Arc, LazyLock, Mutex};

/// One wheel's rigid contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WheelContact {
    /// Lateral position in the track (m).
    pub lateral: f64,
    /// Height of the contact point (m).
    pub height: f64,
    /// Rolling radius (m).
    pub rolling_radius: f64,
    /// The contact's normal out of the rail `(n_Y, n_Z)`.
    pub normal: (f64, f64),
    /// Curvature sums of the gap `A` (rolling direction), `B` (across)
    /// (1/m).
    pub curvatures: (f64, f64),
    /// The wheel profile's lateral coordinate at the contact (m from the
    /// tape circle, positive to the field side).
    pub wheel_lateral: f64,
    /// The rail profile's lateral coordinate at the contact (m from its
    /// axis, positive to the field side).
    pub rail_lateral: f64,
    /// The clearance to a second contact point (m), where the gap has one.
    pub second_clearance: f64,
    /// The rail profile's curvature at the contact in its normal plane (1/m,
    /// convex positive).
    pub rail_curvature: f64,
}

impl WheelContact {
    fn new(g: &Geometry, side: Side, c: &Closest, second: Option<&Closest>) -> WheelContact {
        WheelContact {
            lateral: c.lateral,
            height: g.rail_height(side, c.lateral).unwrap_or(0.0),
            rolling_radius: c.rolling_radius,
            normal: c.normal(),
            curvatures: (c.curvature_a(), c.curvature_b()),
            wheel_lateral: c.wheel_lateral,
            rail_lateral: (c.lateral - g.rail_axis(side)) * side.outwards(),
            second_clearance: second.map_or(f64::INFINITY, |s| s.gap),
            rail_curvature: c.rail_curvature,
        }
    }

    /// The contact angle (rad) on `side`.
    pub fn contact_angle(&self, side: Side) -> f64 {
        (-self.normal.0 * side.outwards()).atan2(self.normal.1)
    }

    fn lerp(&self, o: &WheelContact, t: f64) -> WheelContact {
        let l = |a: f64, b: f64| a + t * (b - a);
        let (ny, nz) = (l(self.normal.0, o.normal.0), l(self.normal.1, o.normal.1));
        let k = (ny * ny + nz * nz).sqrt();
        WheelContact {
            lateral: l(self.lateral, o.lateral),
            height: l(self.height, o.height),
            rolling_radius: l(self.rolling_radius, o.rolling_radius),
            normal: (ny / k, nz / k),
            curvatures: (l(self.curvatures.0, o.curvatures.0), l(self.curvatures.1, o.curvatures.1)),
            wheel_lateral: l(self.wheel_lateral, o.wheel_lateral),
            rail_lateral: l(self.rail_lateral, o.rail_lateral),
            second_clearance: if t < 0.5 { self.second_clearance } else { o.second_clearance },
            rail_curvature: l(self.rail_curvature, o.rail_curvature),
        }
    }
}

/// One row: the wheelset's rigid contact at a lateral shift.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Row {
    /// Lateral shift (m).
    pub shift: f64,
    /// Height of the axle's centre (m).
    pub z: f64,
    /// Roll (rad).
    pub roll: f64,
    /// Left and right wheels' contacts.
    pub wheel: [WheelContact; 2],
}

/// The contact table.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactTable {
    rows: Vec<Row>,
    step: f64,
}

impl ContactTable {
    /// The table over shifts `-half_range..=half_range` (m) every `step` (m).
    pub fn new(g: &Geometry, half_range: f64, step: f64) -> Result<ContactTable, GeometryError> {
        let n = (half_range / step).round() as i64;
        let rows: Result<Vec<Row>, GeometryError> = (-n..=n)
            .into_par_iter()
            .map(|k| {
                let y = k as f64 * step;
                let c = g.rigid(y)?;
                Ok(Row {
                    shift: y,
                    z: c.pose.z,
                    roll: c.pose.roll,
                    wheel: [Side::Left, Side::Right]
                        .map(|s| WheelContact::new(g, s, &c.contact[s as usize], c.second[s as usize].as_ref())),
                })
            })
            .collect();
        Ok(ContactTable { rows: rows?, step })
    }

    /// The table of [`ContactTable::new`], shared with earlier calls for
    /// the same geometry in this process (the last 8 geometries are kept):
    /// a config read again (its overrides, a resumed run) reuses it.
    pub fn cached(g: &Geometry, half_range: f64, step: f64) -> Result<Arc<ContactTable>, GeometryError> {
        type Cache = Mutex<Vec<(String, Arc<ContactTable>)>>;
        static CACHE: LazyLock<Cache> = LazyLock::new(|| Mutex::new(Vec::new()));
        let key = format!("{:?} {:?} {half_range:e} {step:e}", g.wheelset(), g.track());
        if let Some((_, t)) = CACHE.lock().expect("cache lock").iter().find(|(k, _)| *k == key) {
            return Ok(t.clone());
        }
        let table = Arc::new(ContactTable::new(g, half_range, step)?);
        let mut cache = CACHE.lock().expect("cache lock");
        if cache.len() >= 8 {
            cache.remove(0);
        }
        cache.push((key, table.clone()));
        Ok(table)
    }

    /// The rows.
    pub fn rows(&self) -> &[Row] {
        &self.rows
    }

    /// The shifts the table covers (m).
    pub fn range(&self) -> (f64, f64) {
        (self.rows[0].shift, self.rows[self.rows.len() - 1].shift)
    }

    /// The contact at shift `y` (m), linear between rows; None outside.
    pub fn at(&self, y: f64) -> Option<Row> {
        let (lo, hi) = self.range();
        if !(lo..=hi).contains(&y) {
            return None;
        }
        let pos = (y - lo) / self.step;
        let i = (pos.floor() as usize).min(self.rows.len() - 2);
        let t = pos - i as f64;
        let (a, b) = (&self.rows[i], &self.rows[i + 1]);
        let l = |p: f64, q: f64| p + t * (q - p);
        Some(Row {
            shift: y,
            z: l(a.z, b.z),
            roll: l(a.roll, b.roll),
            wheel: [a.wheel[0].lerp(&b.wheel[0], t), a.wheel[1].lerp(&b.wheel[1], t)],
        })
    }
}
