//! The wheel-rail contact closed in three directions per harmonic: the
//! moving-irregularity model (Grassie, Gregory, Harrison, Johnson, *J. Mech.
//! Eng. Sci.* 24 (1982); the tangential extension of Hempelmann and Knothe,
//! *Arch. Appl. Mech.* 66 (1996) 321-339, and Groß-Thebing's linearised
//! creep forces) with the rail head's and the wheel's receptances in
//! three directions.
//!
//! Axes as [`crate::dynamics::track::section`]: `x` along the rail (travel), `y` across (to
//! the right), `z` down. Time dependence `exp(+i w t)`; the load stands
//! still and the rail is pulled through, so a profile harmonic is met at
//! `w = k V`.
//!
//! # Equations
//! Unknown: the force on the wheel at the contact `f = (F_x, F_y, -N)`
//! (the creep forces, and the normal force `N` that pushes the wheel up);
//! the rail carries `-f`. The wheel's contact point moves by `A_w f`
//! (its receptance at the contact, the rim's rotation about the axle
//! folded into `x`), the rail head by `-A_r f`; their difference
//! `d = (A_w + A_r) f = A f`, and the same for the rotation about `z` of the wheel's
//! tread and of the rail head at the contact, `d_psi` (the 4 x 4
//! receptances' fourth row; the contact's own moment about `z`, second
//! order in the patch's size, is left out). With the profile `r` (rail top
//! higher: positive):
//! ```text
//! N = k_H (r + d_z)                                  (Hertz, linearised)
//! xi = (i w / V) d_xy                                (creepages: the contact points' relative velocity over V)
//! phi = (i w / V) d_psi                              (spin: the relative rotation rate about z over V)
//! (F_x, F_y) = C_N N + C_xi xi + C_phi phi           (the creep forces' slopes)    (1)
//! ```
//! a 3 x 3 linear system per harmonic ([`respond`]). The contact's axes are
//! the rail's (`x` along, `y` to the right, `z` down), so that the spin is
//! the rotation rate about `+z` of the contact solvers' rigid slip `(xi_x
//! - phi y, xi_y + phi x)`. Without the spin's slopes (`C_phi` absent) the
//! spin's row is not formed and the system is the three directions' alone,
//! bit for bit. Its limits: without
//! the tangential directions `N = r / (a_z + 1 / k_H)`, the vertical
//! model's eq. 5 of [`crate::dynamics::receptance`]; with the wheel's rotation alone
//! in `A_xx` (`(i w / V) A_xx = T`, the torsion's creepage per force) the
//! creepage `T C_N / (1 - C_xi T) N`, eq. 3 of [`crate::dynamics::wheelset::torsion`].

use crate::dynamics::track::section::{Mat4, translations};
use nalgebra::{SMatrix, SVector};
use num_complex::Complex64;

/// The linearised contact at the mean state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactLaw {
    /// Hertz stiffness `k_H = dN / d delta` (N/m).
    pub stiffness: f64,
    /// `d(F_x, F_y) / dN` at constant creepage (1), at the harmonic's
    /// frequency.
    pub force_per_normal: [Complex64; 2],
    /// `d(F_x, F_y) / d(xi_x, xi_y)` at constant normal force (N), at the
    /// harmonic's frequency.
    pub force_per_creepage: [[Complex64; 2]; 2],
    /// `d(F_x, F_y) / dphi` (N m), at the harmonic's frequency: the spin's
    /// channel, `None` where the loop leaves it out (`dynamics.spin =
    /// false`).
    pub force_per_spin: Option<[Complex64; 2]>,
}

impl ContactLaw {
    /// The Hertz spring `stiffness` (N/m) alone, without creep slopes: the
    /// vertical closure's contact.
    pub fn normal(stiffness: f64) -> ContactLaw {
        let zero = Complex64::new(0.0, 0.0);
        ContactLaw { stiffness, force_per_normal: [zero; 2], force_per_creepage: [[zero; 2]; 2], force_per_spin: None }
    }

    /// The law at one frequency: this law's Hertz stiffness with the creep
    /// forces' slopes taken from the frequency response `h` at that
    /// frequency ([`super::creep_response`], eq. 1: rows `(F_x, F_y)`,
    /// columns `(xi_x, xi_y, phi, N)`; the spin's column where this law
    /// has the spin's channel).
    pub fn at_frequency(&self, h: &super::creep_response::Matrix) -> ContactLaw {
        ContactLaw {
            stiffness: self.stiffness,
            force_per_normal: [h[0][3], h[1][3]],
            force_per_creepage: [[h[0][0], h[0][1]], [h[1][0], h[1][1]]],
            force_per_spin: self.force_per_spin.map(|_| [h[0][2], h[1][2]]),
        }
    }
}

/// The contact's variation per unit profile harmonic (per metre of `r`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactResponse {
    /// Normal force `N` (N/m).
    pub normal: Complex64,
    /// Creep forces on the wheel `(F_x, F_y)` (N/m).
    pub force: [Complex64; 2],
    /// Creepages `(xi_x, xi_y)` (1/m).
    pub creepage: [Complex64; 2],
    /// Spin `phi` ((1/m)/m; zero without the spin's channel).
    pub spin: Complex64,
}

/// Solves eq. 1 for a unit profile harmonic at angular frequency `omega`
/// (rad/s, > 0) and speed `speed` (m/s, > 0): `a` the wheel's plus the
/// rail head's receptance at the contact (`A_w + A_r`, 4 x 4: x, y, z in
/// m/N, the rotation about `z` in rad/N and rad/(N m)), `law` the contact
/// at that frequency.
pub fn respond(a: &Mat4, law: &ContactLaw, omega: f64, speed: f64) -> ContactResponse {
    let iwv = Complex64::new(0.0, omega / speed);
    let kh = law.stiffness;
    let mut m = SMatrix::<Complex64, 3, 3>::zeros();
    let mut rhs = SVector::<Complex64, 3>::zeros();
    // Rows 0, 1: F_j - C_N,j N - sum_l C_xi,jl (i w / V) (A f)_l
    // [- C_phi,j (i w / V) (A f)_psi] = 0, N = -f_z.
    for j in 0..2 {
        m[(j, j)] += Complex64::new(1.0, 0.0);
        m[(j, 2)] += law.force_per_normal[j];
        for l in 0..2 {
            let c = law.force_per_creepage[j][l] * iwv;
            for col in 0..3 {
                m[(j, col)] -= c * a[(l, col)];
            }
        }
        if let Some(per_spin) = law.force_per_spin {
            let c = per_spin[j] * iwv;
            for col in 0..3 {
                m[(j, col)] -= c * a[(3, col)];
            }
        }
    }
    // Row 2: (A f)_z + f_z / k_H = -r.
    for col in 0..3 {
        m[(2, col)] = a[(2, col)];
    }
    m[(2, 2)] += Complex64::new(1.0 / kh, 0.0);
    rhs[2] = Complex64::new(-1.0, 0.0);
    let f = m.lu().solve(&rhs).expect("the contact's system is regular for a passive wheel and track");
    let d = translations(a) * f;
    let spin = match law.force_per_spin {
        Some(_) => iwv * (0..3).map(|col| a[(3, col)] * f[col]).sum::<Complex64>(),
        None => Complex64::new(0.0, 0.0),
    };
    ContactResponse { normal: -f[2], force: [f[0], f[1]], creepage: [iwv * d[0], iwv * d[1]], spin }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::wheelset::torsion::{TorsionFeedback, WheelsetTorsion};

    fn c(v: f64) -> Complex64 {
        Complex64::new(v, 0.0)
    }

    #[test]
    fn vertical_alone_is_the_vertical_models_transfer() {
        let (alpha_w, alpha_r) = (c(-1.0 / (600.0 * 4e6)), Complex64::new(2e-9, -1e-9));
        let mut a = Mat4::zeros();
        a[(2, 2)] = alpha_w + alpha_r;
        let law = ContactLaw {
            stiffness: 1.83e9,
            force_per_normal: [c(0.0); 2],
            force_per_creepage: [[c(0.0); 2]; 2],
            force_per_spin: None,
        };
        let r = respond(&a, &law, 2000.0, 30.0);
        let expected = 1.0 / (alpha_w + alpha_r + 1.0 / 1.83e9);
        assert!((r.normal - expected).norm() < 1e-12 * expected.norm());
        assert_eq!(r.creepage, [c(0.0); 2]);
    }

    #[test]
    fn the_spins_row_closes_the_rotation_about_z_with_the_spin_slopes() {
        // A rotation about z per longitudinal force alone (the wheelset's
        // yaw lever): F_x = C_N N, phi = (i w / V) R F_x, F_y = C_phi,y phi
        // (no creepage slopes, no translation but the vertical). And
        // without the spin's channel the rotation is not seen.
        let (w, speed) = (2.0 * std::f64::consts::PI * 300.0, 27.78);
        let iwv = Complex64::new(0.0, w / speed);
        let mut a = Mat4::zeros();
        a[(2, 2)] = Complex64::new(-1.0 / (600.0 * w * w), 0.0) + Complex64::new(2e-9, -1e-9);
        a[(3, 0)] = Complex64::new(-2.1e-7, 3e-9);
        a[(0, 3)] = a[(3, 0)];
        let law = ContactLaw {
            stiffness: 1.83e9,
            force_per_normal: [c(0.21), c(0.0)],
            force_per_creepage: [[c(0.0); 2]; 2],
            force_per_spin: Some([c(0.0), c(-2.6e4)]),
        };
        let r = respond(&a, &law, w, speed);
        let normal = 1.0 / (a[(2, 2)] + 1.0 / law.stiffness);
        let fx = 0.21 * normal;
        let spin = iwv * a[(3, 0)] * fx;
        assert!((r.normal - normal).norm() < 1e-12 * normal.norm());
        assert!((r.spin - spin).norm() < 1e-12 * spin.norm(), "{} vs {spin}", r.spin);
        assert!((r.force[1] - (-2.6e4) * spin).norm() < 1e-12 * (2.6e4 * spin).norm());
        let without = respond(&a, &ContactLaw { force_per_spin: None, ..law }, w, speed);
        assert_eq!((without.spin, without.force[1]), (c(0.0), c(0.0)));
    }

    #[test]
    fn the_wheels_rotation_alone_is_the_torsional_feedback() {
        let torsion = WheelsetTorsion { stiffness: 3e6, loss_factor: 0.02, inertia: 30.0, radius: 0.5 };
        let fb = TorsionFeedback { torsion, force_per_normal: 0.21, force_per_creepage: -3.1e7 };
        let (speed, kh) = (27.78, 1.83e9);
        for f in [30.0, 71.0, 400.0, 1500.0] {
            let w = 2.0 * std::f64::consts::PI * f;
            // A_xx whose (i w / V) A_xx is the torsion's T(w).
            let t = torsion.creepage_per_force(w, speed);
            let mut a = Mat4::zeros();
            a[(0, 0)] = t / Complex64::new(0.0, w / speed);
            a[(2, 2)] = c(-1.0 / (600.0 * w * w)) + Complex64::new(1e-9, -3e-10);
            let law = ContactLaw {
                stiffness: kh,
                force_per_normal: [c(fb.force_per_normal), c(0.0)],
                force_per_creepage: [[c(fb.force_per_creepage), c(0.0)], [c(0.0), c(0.0)]],
                force_per_spin: None,
            };
            let r = respond(&a, &law, w, speed);
            let expected = fb.creepage_per_normal_force(f, speed) * r.normal;
            assert!((r.creepage[0] - expected).norm() < 1e-10 * expected.norm(), "{f} Hz");
        }
    }
}
