//! The rail as a beam that moves in every direction: the section's six
//! degrees of freedom, the free rail's dynamic stiffness per wavenumber, the
//! supports' stiffness at the foot, and the map from the section's motion to
//! the rail head's at the wheel contact. The continuous
//! ([`super::continuous3`]) and the discrete ([`super::discrete3`]) track
//! models build on it.
//!
//! Time dependence `exp(+i w t)`; fields along the rail `exp(i k x)`.
//! Axes: `x` along the rail (the direction of travel), `y` across it (to the
//! right looking in `+x`), `z` down: right-handed, and down positive as the
//! vertical models' forces and displacements (a passive receptance has
//! `Im <= 0` on its diagonal).
//!
//! # Degrees of freedom of a section ([`Dof`])
//! `w` (vertical displacement of the neutral axis), `psi` (rotation in the
//! vertical plane: a point `z` below the neutral axis moves by `-z psi`
//! along the rail), `u` (axial displacement), `v` (lateral displacement of
//! the shear centre), `chi` (rotation in the horizontal plane: a point `y`
//! right of the centre line moves by `-y chi` along the rail), `phi`
//! (twist about `+x`: a point `z` below the shear centre moves by `-z phi`
//! across, a point `y` right of it by `+y phi` down).
//!
//! # Free rail (Timoshenko in both planes, rod, Saint-Venant torsion)
//! With the complex moduli `EI* = EI (1 + i eta_r)` and so on, the load per
//! length that holds the field `q exp(i k x)` is `K(k) q` with
//! ```text
//! K_ww = kGA* k^2 - m w^2          K_wpsi = i kGA* k = conj-transpose of K_psiw
//! K_psipsi = EI* k^2 + kGA* - rho I w^2
//! K_uu = EA* k^2 - m w^2
//! K_vv = kGA_y* k^2 - m w^2        K_vchi = i kGA_y* k
//! K_chichi = EI_z* k^2 + kGA_y* - rho I_z w^2
//! K_phiphi = GJ* k^2 - (rho I_p + m z_s^2) w^2,   K_vphi = K_phiv = -m z_s w^2   (1)
//! ```
//! (Timoshenko's beam per plane; Vlasov's thin-walled beam for the lateral
//! bending and torsion referred to the shear centre, `z_s` the shear
//! centre's depth below the centroid, whose offset couples the two through
//! the inertia only; warping torsion left out). `K(k)^T = K(-k)`, which
//! makes every receptance reciprocal.
//!
//! # Supports (at the foot, per support)
//! Pad in series with the sleeper mass on the ballast in each direction,
//! `s = k_p* (k_b* - M_s w^2) / (k_p* + k_b* - M_s w^2)` (vertical,
//! lateral, longitudinal), and the pad's roll and pitch stiffness `k_p* b^2 /
//! 12`, `k_p* l^2 / 12` against a sleeper that does not rotate. The foot's
//! motions: `w`, `u - e_n psi` (`e_n` the neutral axis's height above the
//! foot), `v - e_s phi` (`e_s` the shear centre's), `phi`, `psi`; so the
//! support's stiffness in the section's freedoms is `C^T diag(s) C`  (2).
//!
//! # The head (at the contact: the head top, `y_c` right of the centre line)
//! ```text
//! u_head = u + h_n psi - y_c chi,   v_head = v + h_s phi,   w_head = w + y_c phi     (3)
//! ```
//! `h_n`, `h_s` the head top's height above the neutral axis and the shear
//! centre: a force `F` on the head loads the section by `B F`, and the head
//! moves by `B^T q` ([`Section::head_map`]): the head's receptance is `B^T
//! G B`, `G` the section's. With the head's rotation about the vertical,
//! `chi_head = chi` (a moment about `+z` on the head loads `chi` alone), the
//! map has a fourth column and the receptance is 4 x 4
//! ([`Section::head_map4`]): what the spin creepage's variation needs.

use super::rail::RailSection;
use super::{Damping, TrackConfig};
use nalgebra::{SMatrix, SVector};
use num_complex::Complex64;

/// A 6 x 6 complex matrix over the section's freedoms.
pub type Mat6 = SMatrix<Complex64, 6, 6>;
/// The head's 3 x 3 receptance (x, y, z).
pub type Mat3 = SMatrix<Complex64, 3, 3>;
/// The map from head forces (x, y, z) to section loads.
pub type Map63 = SMatrix<Complex64, 6, 3>;
/// The head's 4 x 4 receptance (x, y, z, and the rotation about `z`:
/// displacements in m, the rotation in rad; forces in N, the moment in N m).
pub type Mat4 = SMatrix<Complex64, 4, 4>;
/// The map from head forces and the moment about `z` to section loads.
pub type Map64 = SMatrix<Complex64, 6, 4>;

/// `a` with a zero fourth row and column (no rotation about `z`).
pub fn pad(a: &Mat3) -> Mat4 {
    Mat4::from_fn(|r, c| if r < 3 && c < 3 { a[(r, c)] } else { ZERO })
}

/// The translations' 3 x 3 block of `a`.
pub fn translations(a: &Mat4) -> Mat3 {
    a.fixed_view::<3, 3>(0, 0).into_owned()
}

/// The section's freedoms, in the order of the matrices (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dof {
    /// Vertical displacement, down (m).
    W = 0,
    /// Rotation in the vertical plane (rad).
    Psi = 1,
    /// Axial displacement (m).
    U = 2,
    /// Lateral displacement of the shear centre (m).
    V = 3,
    /// Rotation in the horizontal plane (rad).
    Chi = 4,
    /// Twist (rad).
    Phi = 5,
}

/// The head's directions in [`Mat3`]: along, across, down.
pub const HEAD_DIRECTIONS: [&str; 3] = ["x", "y", "z"];

const ZERO: Complex64 = Complex64::new(0.0, 0.0);
const ONE: Complex64 = Complex64::new(1.0, 0.0);

/// The rail and its supports, with the damping made complex (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section {
    /// The rail section.
    pub rail: RailSection,
    /// Rail loss factor eta_r (1).
    pub loss: f64,
    /// The track's supports and their spacing, as configured.
    pub track: TrackConfig,
    /// Lateral offset of the contact from the rail's centre line, `y_c` (m).
    pub contact_offset: f64,
}

/// The stiffness `k` of a layer with its damping `d` at `omega` (rad/s),
/// the damper scaled by `scale` (the layer's stiffness relative to the
/// vertical one whose damper is configured).
fn layer(k: f64, d: Damping, omega: f64, scale: f64) -> Complex64 {
    match d {
        Damping::LossFactor(eta) => Complex64::new(k, k * eta),
        Damping::Viscous(c) => Complex64::new(k, omega * c * scale),
    }
}

impl Section {
    /// The configured track, the contact `contact_offset` (m) right of the
    /// rail's centre line.
    pub fn new(track: &TrackConfig, contact_offset: f64) -> Self {
        Section { rail: track.rail, loss: track.rail_loss_factor, track: *track, contact_offset }
    }

    /// The shear centre's depth below the centroid `z_s` (m).
    fn shear_centre_depth(&self) -> f64 {
        let t = &self.rail.transverse;
        t.neutral_axis_height - t.shear_centre_height
    }

    /// The free rail's dynamic stiffness `K(k)` of eq. 1 as `(A2, A1, A0)`
    /// with `K(k) = A2 k^2 + A1 k + A0` at angular frequency `omega`.
    pub fn free_polynomial(&self, omega: f64) -> (Mat6, Mat6, Mat6) {
        let r = &self.rail;
        let t = &r.transverse;
        let c = Complex64::new(1.0, self.loss);
        let w2 = omega * omega;
        let (kga, ei, ea) = (c * r.shear_stiffness, c * r.bending_stiffness, c * t.axial_stiffness);
        let (kgay, eiz, gj) =
            (c * t.lateral_shear_stiffness, c * t.lateral_bending_stiffness, c * t.torsional_stiffness);
        let zs = self.shear_centre_depth();
        let m = r.mass;
        let mut a2 = Mat6::zeros();
        let mut a1 = Mat6::zeros();
        let mut a0 = Mat6::zeros();
        use Dof::*;
        let i = Complex64::i();
        for (d, v) in [(W, kga), (Psi, ei), (U, ea), (V, kgay), (Chi, eiz), (Phi, gj)] {
            a2[(d as usize, d as usize)] = v;
        }
        for (a, b, v) in [(W, Psi, kga), (V, Chi, kgay)] {
            a1[(a as usize, b as usize)] = i * v;
            a1[(b as usize, a as usize)] = -i * v;
        }
        let mw2 = Complex64::new(-m * w2, 0.0);
        a0[(W as usize, W as usize)] = mw2;
        a0[(Psi as usize, Psi as usize)] = kga - r.rotary_inertia * w2;
        a0[(U as usize, U as usize)] = mw2;
        a0[(V as usize, V as usize)] = mw2;
        a0[(Chi as usize, Chi as usize)] = kgay - t.lateral_rotary_inertia * w2;
        a0[(Phi as usize, Phi as usize)] = Complex64::new(-(t.polar_inertia + m * zs * zs) * w2, 0.0);
        a0[(V as usize, Phi as usize)] = Complex64::new(-m * zs * w2, 0.0);
        a0[(Phi as usize, V as usize)] = Complex64::new(-m * zs * w2, 0.0);
        (a2, a1, a0)
    }

    /// The free rail's spectral receptance `K(k)^-1` (eq. 1) at wavenumber
    /// `k` (rad/m) and angular frequency `omega`: its blocks (w, psi), (u)
    /// and (v, chi, phi) inverted in closed form.
    pub fn free_receptance(&self, k: f64, omega: f64) -> Mat6 {
        let r = &self.rail;
        let t = &r.transverse;
        let c = Complex64::new(1.0, self.loss);
        let w2 = omega * omega;
        let k2 = k * k;
        let i = Complex64::i();
        let mut g = Mat6::zeros();
        // (w, psi): [[a, i b], [-i b, d]], det a d - b^2.
        let kga = c * r.shear_stiffness;
        let a = kga * k2 - r.mass * w2;
        let b = kga * k;
        let d = c * r.bending_stiffness * k2 + kga - r.rotary_inertia * w2;
        let det = a * d - b * b;
        g[(0, 0)] = d / det;
        g[(0, 1)] = -i * b / det;
        g[(1, 0)] = i * b / det;
        g[(1, 1)] = a / det;
        // (u)
        g[(2, 2)] = 1.0 / (c * t.axial_stiffness * k2 - r.mass * w2);
        // (v, chi, phi): [[p, i q, s], [-i q, e, 0], [s, 0, f]].
        let kgay = c * t.lateral_shear_stiffness;
        let zs = self.shear_centre_depth();
        let p = kgay * k2 - r.mass * w2;
        let q = kgay * k;
        let e = c * t.lateral_bending_stiffness * k2 + kgay - t.lateral_rotary_inertia * w2;
        let s = Complex64::new(-r.mass * zs * w2, 0.0);
        let f = c * t.torsional_stiffness * k2 - (t.polar_inertia + r.mass * zs * zs) * w2;
        // Cofactors of the symmetric-in-structure 3 x 3 (rows v, chi, phi).
        let det3 = p * e * f - q * q * f - s * s * e;
        g[(3, 3)] = e * f / det3;
        g[(3, 4)] = -i * q * f / det3;
        g[(4, 3)] = i * q * f / det3;
        g[(3, 5)] = -s * e / det3;
        g[(5, 3)] = -s * e / det3;
        g[(4, 4)] = (p * f - s * s) / det3;
        g[(4, 5)] = -i * q * s / det3;
        g[(5, 4)] = i * q * s / det3;
        g[(5, 5)] = (p * e - q * q) / det3;
        g
    }

    /// The large-wavenumber limit of [`Self::free_receptance`]'s diagonal
    /// times `k^2`: `1 / (kGA*, EI*, EA*, kGA_y*, EI_z*, GJ*)`, for the
    /// tails of lattice sums.
    pub fn free_tail(&self) -> [Complex64; 6] {
        let r = &self.rail;
        let t = &r.transverse;
        let c = Complex64::new(1.0, self.loss);
        [
            r.shear_stiffness,
            r.bending_stiffness,
            t.axial_stiffness,
            t.lateral_shear_stiffness,
            t.lateral_bending_stiffness,
            t.torsional_stiffness,
        ]
        .map(|v| 1.0 / (c * v))
    }

    /// One support's dynamic stiffness in the section's freedoms (eq. 2)
    /// at angular frequency `omega` (rad/s).
    pub fn support(&self, omega: f64) -> Mat6 {
        let tr = &self.track;
        let s3 = &tr.supports;
        let w2 = omega * omega;
        let series = |kp: f64, kb: f64| {
            let kp = layer(kp, tr.pad_damping, omega, kp / tr.pad_stiffness);
            let kb = layer(kb, tr.ballast_damping, omega, kb / tr.ballast_stiffness);
            let inertia = tr.sleeper_mass * w2;
            kp * (kb - inertia) / (kp + kb - inertia)
        };
        let vertical = series(tr.pad_stiffness, tr.ballast_stiffness);
        let longitudinal = series(s3.pad_longitudinal_stiffness, s3.ballast_longitudinal_stiffness);
        let lateral = series(s3.pad_lateral_stiffness, s3.ballast_lateral_stiffness);
        let pad = layer(tr.pad_stiffness, tr.pad_damping, omega, 1.0);
        let roll = pad * (s3.pad_width * s3.pad_width / 12.0);
        let pitch = pad * (s3.pad_length * s3.pad_length / 12.0);
        let t = &self.rail.transverse;
        let (e_n, e_s) = (t.neutral_axis_height, t.shear_centre_height);
        // Rows of C: the foot's motions in the section's freedoms.
        let rows: [([f64; 6], Complex64); 5] = [
            ([1.0, 0.0, 0.0, 0.0, 0.0, 0.0], vertical),
            ([0.0, -e_n, 1.0, 0.0, 0.0, 0.0], longitudinal),
            ([0.0, 0.0, 0.0, 1.0, 0.0, -e_s], lateral),
            ([0.0, 0.0, 0.0, 0.0, 0.0, 1.0], roll),
            ([0.0, 1.0, 0.0, 0.0, 0.0, 0.0], pitch),
        ];
        let mut k = Mat6::zeros();
        for (c, s) in rows {
            for a in 0..6 {
                for b in 0..6 {
                    if c[a] != 0.0 && c[b] != 0.0 {
                        k[(a, b)] += s * (c[a] * c[b]);
                    }
                }
            }
        }
        k
    }

    /// The map `B` of eq. 3: the section's loads of a unit force on the head
    /// in each direction (columns x, y, z).
    pub fn head_map(&self) -> Map63 {
        let t = &self.rail.transverse;
        let (h_n, h_s, y_c) = (t.head_above_neutral_axis(), t.head_above_shear_centre(), self.contact_offset);
        let col = |v: [f64; 6]| SVector::<Complex64, 6>::from_iterator(v.iter().map(|x| Complex64::new(*x, 0.0)));
        Map63::from_columns(&[
            col([0.0, h_n, 1.0, 0.0, -y_c, 0.0]),
            col([0.0, 0.0, 0.0, 1.0, 0.0, h_s]),
            col([1.0, 0.0, 0.0, 0.0, 0.0, y_c]),
        ])
    }

    /// The map of [`Self::head_map`] with a fourth column, the moment
    /// about `z` on the head (module docs).
    pub fn head_map4(&self) -> Map64 {
        let b = self.head_map();
        Map64::from_fn(|r, c| {
            if c < 3 {
                b[(r, c)]
            } else if r == Dof::Chi as usize {
                ONE
            } else {
                ZERO
            }
        })
    }

    /// The head's receptance `B^T G B` of the section's `g`.
    pub fn head(&self, g: &Mat6) -> Mat3 {
        project(&self.head_map(), g)
    }

    /// The head's 4 x 4 receptance (with the rotation about `z`) of the
    /// section's `g`.
    pub fn head4(&self, g: &Mat6) -> Mat4 {
        project(&self.head_map4(), g)
    }
}

/// `B^T G B`.
pub fn project<const N: usize>(b: &SMatrix<Complex64, 6, N>, g: &Mat6) -> SMatrix<Complex64, N, N> {
    b.transpose() * g * b
}

/// Zero 6 x 6 (a lattice sum's start).
pub fn zero6() -> Mat6 {
    Mat6::from_element(ZERO)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_spectral_receptance_inverts_the_dynamic_stiffness() {
        let s = Section::new(&TrackConfig::default(), 0.01);
        for (k, f) in [(0.3, 50.0), (7.0, 800.0), (40.0, 3000.0)] {
            let w = 2.0 * std::f64::consts::PI * f;
            let (a2, a1, a0) = s.free_polynomial(w);
            let kk = a2 * Complex64::new(k * k, 0.0) + a1 * Complex64::new(k, 0.0) + a0;
            let e = (kk * s.free_receptance(k, w) - Mat6::identity()).norm();
            assert!(e < 1e-12, "k {k}, f {f}: |K G - I| = {e:e}");
            // K(k)^T = K(-k): the reciprocity of every receptance built on it.
            let km = a2 * Complex64::new(k * k, 0.0) - a1 * Complex64::new(k, 0.0) + a0;
            assert!((kk.transpose() - km).norm() < 1e-9 * kk.norm());
        }
    }

    #[test]
    fn the_support_is_symmetric_and_the_vertical_one_as_the_vertical_model_has_it() {
        let t = TrackConfig::default();
        let s = Section::new(&t, 0.0);
        let w = 2.0 * std::f64::consts::PI * 400.0;
        let k = s.support(w);
        assert!((k - k.transpose()).norm() == 0.0);
        let vertical = crate::dynamics::track::discrete::DiscreteTrack::new(&t).support_stiffness(w);
        assert!((k[(0, 0)] - vertical).norm() < 1e-9 * vertical.norm());
    }
}
