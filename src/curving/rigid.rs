//! The rigid contact of the wheelset with the track: for a lateral shift,
//! the height and roll at which both wheels touch their rails (the closest
//! points' gaps both zero), and the contact geometry's tables against the
//! shift (rolling-radius difference, contact angles; EN 15302 section 4).

use super::conicity::RadiusDifference;
use super::geometry::{Closest, Geometry, GeometryError, Pose, Side};
use crate::numerics::{Tolerance, brent};

/// Largest roll searched (rad).
const MAX_ROLL: f64 = 0.05;

/// Both wheels touching their rails.
#[derive(Debug, Clone, PartialEq)]
pub struct RigidContact {
    /// The wheelset's pose.
    pub pose: Pose,
    /// Each wheel's contact point (left, right).
    pub contact: [Closest; 2],
    /// Each wheel's next-closest point, where the gap has a second valley
    /// (its gap is the clearance to a second contact point).
    pub second: [Option<Closest>; 2],
}

impl RigidContact {
    /// Rolling-radius difference, left minus right (m).
    pub fn radius_difference(&self) -> f64 {
        self.contact[0].rolling_radius - self.contact[1].rolling_radius
    }

    /// Contact angles, left and right (rad).
    pub fn contact_angles(&self) -> [f64; 2] {
        [self.contact[0].contact_angle(Side::Left), self.contact[1].contact_angle(Side::Right)]
    }
}

impl Geometry {
    /// The lowest gap on `side` at `pose` and where it is.
    fn lowest(&self, side: Side, pose: &Pose) -> Result<Vec<Closest>, GeometryError> {
        let c = self.closest(side, pose);
        if c.is_empty() {
            return Err(GeometryError::OffRail { side: side.name(), y_mm: pose.y * 1e3 });
        }
        Ok(c)
    }

    /// The rigid contact at lateral shift `y` (m).
    pub fn rigid(&self, y: f64) -> Result<RigidContact, GeometryError> {
        let at = |roll: f64| Pose { y, z: 0.0, roll };
        let difference = |roll: f64| -> f64 {
            match (self.lowest(Side::Left, &at(roll)), self.lowest(Side::Right, &at(roll))) {
                (Ok(l), Ok(r)) => l[0].gap - r[0].gap,
                _ => f64::NAN,
            }
        };
        self.lowest(Side::Left, &at(0.0))?;
        self.lowest(Side::Right, &at(0.0))?;
        let tol = Tolerance { residual: 1e-12, x_rel: 0.0, x_abs: 1e-10, max_iter: 200 };
        let roll = brent(-MAX_ROLL, MAX_ROLL, difference, tol).map_err(|_| GeometryError::NoRoll(MAX_ROLL, y * 1e3))?;
        let left = self.lowest(Side::Left, &at(roll))?;
        // Lower the wheelset onto the rails.
        let pose = Pose { y, z: -left[0].gap, roll };
        let (l, r) = (self.lowest(Side::Left, &pose)?, self.lowest(Side::Right, &pose)?);
        Ok(RigidContact { pose, contact: [l[0], r[0]], second: [l.get(1).copied(), r.get(1).copied()] })
    }

    /// The rigid contact at each shift of `shifts` (m).
    pub fn rigid_table(&self, shifts: &[f64]) -> Result<Vec<RigidContact>, GeometryError> {
        shifts.iter().map(|&y| self.rigid(y)).collect()
    }
}

/// The rolling-radius difference of a table.
pub fn radius_difference(shifts: &[f64], table: &[RigidContact]) -> RadiusDifference {
    RadiusDifference { shift: shifts.to_vec(), difference: table.iter().map(RigidContact::radius_difference).collect() }
}
