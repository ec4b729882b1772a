//! The wheel's side of the contact: its receptance at the contact point
//! in the rail's axes, from the rigid wheel (free above its suspension,
//! the rim's rotation about the axle folded into the longitudinal
//! direction: the rigid wheelset's spin or its torsion,
//! [`super::torsion`]) or the wheelset's modal model ([`super`]).

use super::torsion::{WHEEL_POLAR_INERTIA, WheelsetTorsion};
use super::{Dir, WheelsetModel, dof};
use crate::dynamics::track::section::{Mat3, Mat4, pad};
use num_complex::Complex64;

/// The wheel's side of the contact.
#[derive(Debug, Clone)]
pub enum WheelSide {
    /// The rigid wheel (module docs).
    Rigid(Wheel3),
    /// The wheelset's modal model ([`super`]), the modelled
    /// rail's wheel its wheel 0, spinning at `spin` (rad/s, `V / r`), the
    /// other wheel's creep forces uncorrelated with this rail's profile.
    Modal {
        /// The wheelset.
        model: WheelsetModel,
        /// Spin speed (rad/s).
        spin: f64,
    },
}

impl WheelSide {
    /// The wheel's receptance at the contact in the rail's axes (m/N; x
    /// along with the rim's rotation, y across to the right, z down, and
    /// the tread's rotation about z in rad/N, rad/(N m)) at `omega`
    /// (rad/s) and `speed` (m/s). The wheelset's axes have y to the left
    /// and z up: its (x, y, z, psi) block of wheel 0 turns by `S = diag(1,
    /// -1, -1, -1)` on both sides (the rotation about z is an axial vector:
    /// turned half round x it changes sign with z).
    pub fn receptance(&self, omega: f64, speed: f64) -> Mat4 {
        self.receptance_between(omega, speed, 0, 0)
    }

    /// The displacement of wheel `at`'s contact per unit force at wheel
    /// `from`'s (m/N; wheel 0 the first rail's, 1 the second's; both in
    /// the rail's common axes, x along, y to the right, z down): the
    /// modal wheelset's block `S H_(at, from) S` (the point receptance for
    /// `at == from`), with the tread's rotation about z. The rigid wheel has
    /// no second wheel (zero between two) and no rotation about z.
    pub fn receptance_between(&self, omega: f64, speed: f64, at: usize, from: usize) -> Mat4 {
        match self {
            WheelSide::Rigid(w) if at == from => pad(&w.receptance(omega, speed)),
            WheelSide::Rigid(_) => Mat4::zeros(),
            WheelSide::Modal { model, spin } => {
                let h = model.receptance(omega, *spin);
                let sign = [1.0, -1.0, -1.0, -1.0];
                Mat4::from_fn(|a, b| h[(dof(at, DIRECTIONS[a]), dof(from, DIRECTIONS[b]))] * (sign[a] * sign[b]))
            }
        }
    }

    /// The wheel's resonances for reports (label, Hz).
    pub fn resonances(&self) -> Vec<(String, f64)> {
        match self {
            WheelSide::Rigid(w) => w.torsion.map_or_else(Vec::new, |t| {
                vec![("the wheelset's torsion: the wheels twisting against each other".into(), t.resonance())]
            }),
            // The modes at rest (`check` prints their split while spinning).
            WheelSide::Modal { model, .. } => model
                .modes()
                .iter()
                .filter(|m| m.frequency > 0.0)
                .map(|m| (format!("wheelset: {}", m.name), m.frequency))
                .collect(),
        }
    }
}

/// The wheelset's directions of the rail's x, y, z and the rotation about z.
const DIRECTIONS: [Dir; 4] = [Dir::X, Dir::Y, Dir::Z, Dir::Psi];

/// The wheel at the contact (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wheel3 {
    /// Unsprung mass per wheel M (kg).
    pub mass: f64,
    /// Rolling radius r (m).
    pub radius: f64,
    /// Polar moment of inertia of one wheel with its half axle J (kg m^2).
    pub polar_inertia: f64,
    /// The wheelset's torsion, where configured.
    pub torsion: Option<WheelsetTorsion>,
}

impl Wheel3 {
    /// A rigid wheel of unsprung mass `mass` (kg) and rolling radius
    /// `radius` (m), the standard wheel's polar inertia
    /// ([`WHEEL_POLAR_INERTIA`]), no torsion.
    pub fn new(mass: f64, radius: f64) -> Self {
        Wheel3 { mass, radius, polar_inertia: WHEEL_POLAR_INERTIA, torsion: None }
    }

    /// The wheel's receptance at the contact (m/N; x along with the rim's
    /// rotation, y across, z down) at `omega` (rad/s) and `speed` (m/s).
    pub fn receptance(&self, omega: f64, speed: f64) -> Mat3 {
        let mass = Complex64::new(-1.0 / (self.mass * omega * omega), 0.0);
        let rotation = match self.torsion {
            Some(t) => t.creepage_per_force(omega, speed) / Complex64::new(0.0, omega / speed),
            None => Complex64::new(-self.radius * self.radius / (2.0 * self.polar_inertia * omega * omega), 0.0),
        };
        Mat3::from_diagonal(&nalgebra::Vector3::new(mass + rotation, mass, mass))
    }
}
