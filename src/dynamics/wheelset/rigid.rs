//! The rigid wheelset on its primary suspension: the six rigid-body modes
//! that carry the model below the flexible modes.
//!
//! # Equations
//!
//! A rigid body of mass `m` and moments of inertia `I_x` (roll, about the
//! longitudinal axis through its centre), `I_y` (spin, about the axle) and
//! `I_z` (yaw), on two axle boxes at `y = +-b` (the bearings, at the axle's
//! height), each with springs `k_x`, `k_y`, `k_z` (complex `k (1 + i
//! eta_s)`) to a frame held still (the bogie frame, heavy and isolated by
//! the secondary suspension above the wheelset's own resonances). Small
//! motion: translations `(u, v, w)` of the centre, rotations `(phi, theta,
//! psi)` about `x`, `y`, `z`. The springs at the axle's height couple no
//! translation with a rotation, so each coordinate is a mode:
//!
//! ```text
//! mode         w_k^2              participation (mass-normalised)
//! longitudinal 2 k_x / m          u = 1/sqrt(m)
//! lateral      2 k_y / m          v = 1/sqrt(m)
//! bounce       2 k_z / m          w = 1/sqrt(m)
//! roll         2 k_z b^2 / I_x    phi = 1/sqrt(I_x)
//! yaw          2 k_x b^2 / I_z    psi = 1/sqrt(I_z)
//! spin         0 (free)           theta = 1/sqrt(I_y)
//! ```
//!
//! The contact of wheel `w` at `p = (0, y_w, -r)` moves by `t + rot x p`:
//! `u_x = u - r theta - y_w psi`, `u_y = v + r phi`, `u_z = w + y_w phi`,
//! the wheel turns by `theta` about the axle and its tread at the contact
//! by `psi` about the vertical. Roll and yaw are coupled by the spin
//! (Euler's equations: `I_x phi'' - I_y Omega psi' = M_x`, `I_z psi'' + I_y
//! Omega phi' = M_z`), eq. 3 of [`super`] with the wheels' tilts.

use super::{Damping, Dir, Mode, dof};

/// The rigid wheelset's mass and inertias, its primary suspension and the
/// positions of its contacts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidWheelset {
    /// Mass m of the wheelset with its axle boxes (kg).
    pub mass: f64,
    /// Moment of inertia I_x about the longitudinal axis (roll) (kg m^2).
    pub roll_inertia: f64,
    /// Moment of inertia I_z about the vertical axis (yaw) (kg m^2).
    pub yaw_inertia: f64,
    /// Polar moment of inertia I_y of the spinning parts about the axle (kg
    /// m^2): twice a wheel's with its half axle ([`super::torsion`]'s
    /// J).
    pub spin_inertia: f64,
    /// Primary suspension stiffness per axle box, longitudinal k_x (N/m).
    pub stiffness_x: f64,
    /// Lateral k_y (N/m) per axle box.
    pub stiffness_y: f64,
    /// Vertical k_z (N/m) per axle box.
    pub stiffness_z: f64,
    /// Loss factor eta_s of the primary suspension (1).
    pub loss_factor: f64,
    /// Half the distance between the axle boxes, b (m).
    pub axle_box_half_spacing: f64,
    /// Half the distance between the two contact points, l (m).
    pub contact_half_spacing: f64,
    /// Rolling radius r (m).
    pub radius: f64,
}

/// A mode with the tilts of the two wheels (rad per unit modal coordinate,
/// `[wheel][0]` about `x`, `[wheel][1]` about `z`), from which eq. 3 of
/// [`super`] couples modes.
#[derive(Debug, Clone, PartialEq)]
pub struct TiltedMode {
    /// The mode.
    pub mode: Mode,
    /// Tilts of wheel 0 and 1 about x and z.
    pub tilt: [[f64; 2]; 2],
}

impl RigidWheelset {
    /// The six rigid-body modes (module docs), in the order longitudinal,
    /// lateral, bounce, roll, yaw, spin.
    pub fn modes(&self) -> Vec<TiltedMode> {
        let (r, l, b) = (self.radius, self.contact_half_spacing, self.axle_box_half_spacing);
        let ys = [l, -l];
        let hz = |k: f64| k.sqrt() / (2.0 * std::f64::consts::PI);
        let susp = Damping::LossFactor(self.loss_factor);
        let mut out = Vec::new();
        let mut push = |name: &str, w2: f64, damping: Damping, f: &dyn Fn(usize, Dir) -> f64, tilt: [[f64; 2]; 2]| {
            let mut shape = [0.0; super::DOFS];
            for w in 0..2 {
                for d in Dir::ALL {
                    shape[dof(w, d)] = f(w, d);
                }
                // The tread turns about the vertical with the wheel.
                shape[dof(w, Dir::Psi)] = tilt[w][1];
            }
            out.push(TiltedMode { mode: Mode { name: name.into(), frequency: hz(w2), damping, shape }, tilt });
        };
        let sm = 1.0 / self.mass.sqrt();
        let (sx, sz, sy) =
            (1.0 / self.roll_inertia.sqrt(), 1.0 / self.yaw_inertia.sqrt(), 1.0 / self.spin_inertia.sqrt());
        push(
            "rigid longitudinal (primary suspension)",
            2.0 * self.stiffness_x / self.mass,
            susp,
            &|_, d| if d == Dir::X { sm } else { 0.0 },
            [[0.0; 2]; 2],
        );
        push(
            "rigid lateral (primary suspension)",
            2.0 * self.stiffness_y / self.mass,
            susp,
            &|_, d| if d == Dir::Y { sm } else { 0.0 },
            [[0.0; 2]; 2],
        );
        push(
            "rigid bounce (primary suspension)",
            2.0 * self.stiffness_z / self.mass,
            susp,
            &|_, d| if d == Dir::Z { sm } else { 0.0 },
            [[0.0; 2]; 2],
        );
        push(
            "rigid roll (primary suspension)",
            2.0 * self.stiffness_z * b * b / self.roll_inertia,
            susp,
            &|w, d| match d {
                Dir::Y => r * sx,
                Dir::Z => ys[w] * sx,
                _ => 0.0,
            },
            [[sx, 0.0]; 2],
        );
        push(
            "rigid yaw (primary suspension)",
            2.0 * self.stiffness_x * b * b / self.yaw_inertia,
            susp,
            &|w, d| if d == Dir::X { -ys[w] * sz } else { 0.0 },
            [[0.0, sz]; 2],
        );
        push(
            "rigid spin (free)",
            0.0,
            Damping::LossFactor(0.0),
            &|_, d| match d {
                Dir::X => -r * sy,
                Dir::Theta => sy,
                _ => 0.0,
            },
            [[0.0; 2]; 2],
        );
        out
    }
}

/// The gyroscopic couplings of eq. 3 of [`super`] between the modes `modes`
/// (their indices offset by `first`), each wheel of polar moment of inertia
/// `polar` (kg m^2); couplings below 1e-9 (round-off between modes that
/// symmetry decouples) are dropped.
pub fn tilt_couplings(modes: &[TiltedMode], first: usize, polar: f64) -> Vec<super::Gyroscopic> {
    let mut out = Vec::new();
    for i in 0..modes.len() {
        for j in i + 1..modes.len() {
            let (a, b) = (&modes[i].tilt, &modes[j].tilt);
            let g: f64 = (0..2).map(|w| polar * (a[w][1] * b[w][0] - a[w][0] * b[w][1])).sum();
            if g.abs() > 1e-9 {
                out.push(super::Gyroscopic { a: first + i, b: first + j, coefficient: g });
            }
        }
    }
    out
}
