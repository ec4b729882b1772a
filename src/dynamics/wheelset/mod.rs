//! The wheelset as a flexible rotating body: a modal model whose receptance
//! at the two wheels' contacts, in the three directions and in rotation about
//! the axle, includes the gyroscopic coupling of the wheelset's spin
//! (`[wheelset] model = "modal"`; the book's theory chapter
//! `docs/src/theory/wheelset.md`).
//!
//! # Coordinates, degrees of freedom, signs
//!
//! Track frame, not rotating with the wheels: `x` forwards (the rolling
//! direction), `z` up, `y = z x x` lateral (to the left of the direction of
//! travel). The wheelset's centre is the origin; wheel `w` (0 or 1) has its
//! contact at `(0, y_w, -r)`, `y_0 = +l`, `y_1 = -l` (`l` half the distance
//! between the contact points, `r` the rolling radius). The spin `Omega =
//! V / r > 0` turns the wheelset about `+y` when it rolls forwards.
//!
//! The ten degrees of freedom, index `5 w + d` ([`dof`]), `d` in [`Dir`]:
//! - `d = 0` (`x`): the longitudinal displacement (m) of the wheel's
//!   material at the contact, all of it: the axle's bending in the
//!   horizontal plane and `-r theta` from the rotation about the axle
//!   included, so that the wheel's contribution to the longitudinal
//!   creepage is `i w u_x / V`; its force `F_x` (N), on the wheel at the
//!   contact, positive forwards;
//! - `d = 1` (`y`): the lateral displacement (m) at the contact, force
//!   `F_y` (N) on the wheel, positive `+y`;
//! - `d = 2` (`z`): the vertical displacement (m) at the contact, up; force
//!   `F_z` (N) on the wheel, up (the contact's compressive force);
//! - `d = 3` (`theta`): the wheel's rotation about the axle (rad), positive
//!   in the sense of the rolling spin (`+y`); its load is a moment `M` (N m)
//!   about `+y` applied to that wheel (a brake or drive torque). A force
//!   `F_x` at the contact already turns the wheel: its moment `-r F_x` is
//!   part of the `x` column (the `theta` row of the `x` column is the
//!   rotation per longitudinal force).
//! - `d = 4` (`psi`): the rotation (rad) of the wheel's tread at the
//!   contact about the vertical (`+z`, up): the wheelset's yaw, the rims'
//!   tilt about `z` in the axle's horizontal bending, the local slope of a
//!   wheel's axial (out-of-plane) mode along the rim; its load a moment
//!   about `+z` at the contact (N m). The wheel's share of the spin
//!   creepage's variation is `i w psi / V` (in the rail's axes, `z` down,
//!   with the opposite sign: [`crate::dynamics::coupling::contact_point`]).
//!
//! Time dependence `exp(+i w t)`, as in [`crate::dynamics`]: a passive
//! receptance has a negative imaginary point receptance.
//!
//! # Equations
//!
//! Modes `k` with natural angular frequencies `w_k` (the undamped free
//! wheelset's or the rigid wheelset's on its suspension), mass-normalised
//! participations `phi_k` (the mode's displacement at the ten degrees of
//! freedom per unit modal coordinate: `1/sqrt(kg)` for displacements,
//! `rad/(m sqrt(kg))` for the rotation) and modal coordinates `q_k`
//! (`u = Phi q`). In the non-rotating (Eulerian) frame the spinning
//! wheelset obeys (Baeza, Vila, Xie, Iwnicki, *J. Sound Vib.* 330 (2011)
//! 4493-4507; Vila et al., *Veh. Syst. Dyn.* 52
//! (2014))
//!
//! ```text
//! q'' + Omega G q' + diag(w_k^2 (1 + i eta_k)) q = Phi^T f                (1)
//! ```
//!
//! with `G = -G^T` the gyroscopic coupling between modal coordinates
//! ([`Gyroscopic`]), a loss factor `eta_k` (or a viscous ratio `zeta_k`:
//! `w_k^2 + 2 i zeta_k w_k w` in place of `w_k^2 (1 + i eta_k)`), hence the
//! receptance
//!
//! ```text
//! H(w, Omega) = Phi D^-1 Phi^T,  D = diag(d_k(w)) + i w Omega G,  d_k = w_k^2 (1 + i eta_k) - w^2.   (2)
//! ```
//!
//! Without rotation `H` is a sum of `phi_k phi_k^T / d_k`: symmetric
//! (reciprocal), bit for bit. With rotation `H(Omega)^T = H(-Omega)`.
//!
//! **Which modes couple.** (a) The rigid wheelset's roll (about `x`) and yaw
//! (about `z`), and the axle's bending modes in the vertical and the
//! horizontal plane, through the tilt of the spinning wheels (Euler's
//! equations linearised about the spin: `I_x phi'' - I_y Omega psi' = M_x`,
//! `I_z psi'' + I_y Omega phi' = M_z`):
//!
//! ```text
//! G_ij = sum_w J_w (a_z,w^i a_x,w^j - a_x,w^i a_z,w^j)                     (3)
//! ```
//!
//! with `a_x,w^i` and `a_z,w^i` the tilts of wheel `w` about `x` and `z` in
//! mode `i` (mass-normalised) and `J_w` its polar moment of inertia: the
//! classic rotor's gyroscopic moment, the forward and backward whirls of
//! the bending pairs separating with speed. (b) A wheel's modes with `n`
//! nodal diameters come in pairs (`cos n phi` and `sin n phi` about the
//! contact). Seen from the non-rotating frame a pattern fixed in the wheel
//! passes the contact, and the pair splits into `w_k +- beta n Omega`
//! travelling waves: for the axial (out-of-plane) modes `beta = 1` (the
//! convective term of the Eulerian description, no Coriolis force acts on
//! motion parallel to the spin axis), for the radial (in-plane) modes of a
//! ring `beta = (n^2 - 1) / (n^2 + 1)` (the Coriolis force lets the pattern
//! lag the wheel by `2 Omega / (n^2 + 1)`; Bryan, *Proc. Camb. Phil. Soc.* 7
//! (1890) 101-111). With `G_cs = 2 beta n` between the pair, eq. 1 gives
//! `w = sqrt(w_k^2 + (beta n Omega)^2) +- beta n Omega`: the split to first
//! order in `Omega`, as the rotating wheel's measured and computed
//! receptances show (Zhong, Chen, Sheng et al., *J. Mod. Transport.* 26
//! (2018) 81-95: the rotation splits the peaks of the vertical receptance
//! at the contact into two). Terms of order `Omega^2` (centrifugal
//! stiffening, the convective term's second order) are left out: they
//! shift a mode by `(beta n Omega)^2 / (2 w_k)`, 0.4 Hz for `n = 3` at 1
//! kHz and 100 km/h.
//!
//! The rigid spin (a mode of zero frequency whose participation is the
//! rotation of both wheels) is free: the receptance needs `w > 0`.

pub mod rigid;
pub mod side;
pub mod standard;
pub mod table;
pub mod torsion;

use nalgebra::{DMatrix, SMatrix};
use num_complex::Complex64;
use std::f64::consts::PI;
use std::fmt;

/// The number of degrees of freedom of the receptance: 2 wheels x [x, y, z, theta, psi].
pub const DOFS: usize = 10;

/// The receptance matrix at the contacts (module docs: index [`dof`]).
pub type Receptance = SMatrix<Complex64, DOFS, DOFS>;

/// A direction at a wheel's contact (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dir {
    /// Longitudinal displacement at the contact (m), force forwards (N).
    X = 0,
    /// Lateral displacement (m), force (N), `+y` to the left.
    Y = 1,
    /// Vertical displacement (m), force (N), up.
    Z = 2,
    /// Rotation about the axle (rad), moment about `+y` (N m).
    Theta = 3,
    /// Rotation of the tread at the contact about the vertical `+z` (rad),
    /// moment about `+z` (N m).
    Psi = 4,
}

impl Dir {
    /// The four directions in their order.
    pub const ALL: [Dir; 5] = [Dir::X, Dir::Y, Dir::Z, Dir::Theta, Dir::Psi];

    /// The name used in tables and messages: `x`, `y`, `z`, `theta`, `psi`.
    pub fn name(self) -> &'static str {
        ["x", "y", "z", "theta", "psi"][self as usize]
    }
}

/// The index of direction `dir` at wheel `wheel` (0 or 1): `5 wheel + dir`.
pub const fn dof(wheel: usize, dir: Dir) -> usize {
    5 * wheel + dir as usize
}

/// A mode's damping.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Damping {
    /// Viscous damping ratio zeta (1): `d_k = w_k^2 + 2 i zeta w_k w - w^2`.
    Ratio(f64),
    /// Loss factor eta (1), hysteretic: `d_k = w_k^2 (1 + i eta) - w^2`.
    LossFactor(f64),
}

impl Damping {
    fn value(self) -> f64 {
        match self {
            Damping::Ratio(v) | Damping::LossFactor(v) => v,
        }
    }
}

impl fmt::Display for Damping {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Damping::Ratio(z) => write!(f, "{} % damping", percent(z)),
            Damping::LossFactor(e) => write!(f, "loss factor {}", significant(e)),
        }
    }
}

fn percent(v: f64) -> String {
    significant(100.0 * v)
}

/// A number with up to three significant figures, without trailing zeros.
fn significant(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let digits = (2 - v.abs().log10().floor() as i32).max(0) as usize;
    let s = format!("{v:.digits$}");
    if s.contains('.') { s.trim_end_matches('0').trim_end_matches('.').to_string() } else { s }
}

/// One mode of the wheelset (module docs, eq. 1).
#[derive(Debug, Clone, PartialEq)]
pub struct Mode {
    /// What the mode is, e.g. "first symmetric bending (vertical plane)".
    pub name: String,
    /// Natural frequency w_k / (2 pi) (Hz), >= 0 (0: a free rigid-body mode).
    pub frequency: f64,
    /// Damping.
    pub damping: Damping,
    /// Mass-normalised participation at the ten degrees of freedom
    /// ([`dof`]): 1/sqrt(kg) for the displacements, rad/(m sqrt(kg)) for
    /// the rotations.
    pub shape: [f64; DOFS],
}

impl Mode {
    /// Natural angular frequency (rad/s).
    pub fn omega(&self) -> f64 {
        2.0 * PI * self.frequency
    }

    /// The modal dynamic stiffness `d_k(w)` (1/s^2) of eq. 2.
    fn dynamic_stiffness(&self, omega: f64) -> Complex64 {
        let wk = self.omega();
        match self.damping {
            Damping::LossFactor(eta) => Complex64::new(wk * wk - omega * omega, wk * wk * eta),
            Damping::Ratio(zeta) => Complex64::new(wk * wk - omega * omega, 2.0 * zeta * wk * omega),
        }
    }

    /// "first symmetric bending (vertical plane), 87.0 Hz, 1 % damping".
    pub fn describe(&self) -> String {
        format!("{}, {:.1} Hz, {}", self.name, self.frequency, self.damping)
    }
}

/// A skew-symmetric gyroscopic coupling between modes `a` and `b` (indices
/// into the model's modes): `G_ab = coefficient`, `G_ba = -coefficient` in
/// eq. 1 (dimensionless with mass-normalised modes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gyroscopic {
    /// The first mode.
    pub a: usize,
    /// The second mode.
    pub b: usize,
    /// `G_ab` (1).
    pub coefficient: f64,
}

/// An invalid modal model.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum WheelsetError {
    /// A mode's number is out of range.
    #[error("mode {index} ({name}): {what}")]
    Mode {
        /// The mode's index.
        index: usize,
        /// Its name.
        name: String,
        /// What is wrong.
        what: String,
    },
    /// A coupling is invalid.
    #[error("gyroscopic coupling between modes {a} and {b}: {what}")]
    Coupling {
        /// First mode.
        a: usize,
        /// Second mode.
        b: usize,
        /// What is wrong.
        what: String,
    },
    /// No mode at all.
    #[error("the model has no mode")]
    Empty,
}

/// The wheelset's modal model (module docs): modes and their gyroscopic
/// couplings; [`WheelsetModel::receptance`] is eq. 2.
#[derive(Debug, Clone, PartialEq)]
pub struct WheelsetModel {
    modes: Vec<Mode>,
    couplings: Vec<Gyroscopic>,
    /// The modes grouped into sets that the couplings connect (each sorted).
    blocks: Vec<Vec<usize>>,
}

impl WheelsetModel {
    /// A model of `modes` coupled by `couplings`, validated: frequencies
    /// finite and >= 0, damping finite and >= 0 (a ratio < 1), shapes
    /// finite, couplings between two distinct existing modes, finite, each
    /// pair at most once.
    pub fn new(modes: Vec<Mode>, couplings: Vec<Gyroscopic>) -> Result<Self, WheelsetError> {
        if modes.is_empty() {
            return Err(WheelsetError::Empty);
        }
        for (index, m) in modes.iter().enumerate() {
            let fail = |what: String| Err(WheelsetError::Mode { index, name: m.name.clone(), what });
            if !(m.frequency.is_finite() && m.frequency >= 0.0) {
                return fail(format!("frequency = {} Hz must be finite and >= 0", m.frequency));
            }
            let d = m.damping.value();
            let ratio = matches!(m.damping, Damping::Ratio(_));
            if !(d.is_finite() && d >= 0.0 && (!ratio || d < 1.0)) {
                return fail(format!(
                    "{} must be finite and >= 0{}",
                    m.damping,
                    if ratio { " and < 100 %" } else { "" }
                ));
            }
            if let Some(v) = m.shape.iter().find(|v| !v.is_finite()) {
                return fail(format!("participation {v} must be finite"));
            }
        }
        let mut seen = Vec::new();
        for c in &couplings {
            let fail = |what: &str| Err(WheelsetError::Coupling { a: c.a, b: c.b, what: what.into() });
            if c.a >= modes.len() || c.b >= modes.len() {
                return fail(&format!("the model has {} modes", modes.len()));
            }
            if c.a == c.b {
                return fail("a mode cannot couple with itself (G is skew-symmetric)");
            }
            if !c.coefficient.is_finite() {
                return fail("the coefficient must be finite");
            }
            let key = (c.a.min(c.b), c.a.max(c.b));
            if seen.contains(&key) {
                return fail("given twice");
            }
            seen.push(key);
        }
        let blocks = connected_blocks(modes.len(), &couplings);
        Ok(WheelsetModel { modes, couplings, blocks })
    }

    /// Today's torsional model ([`torsion`]) as modes: the rigid spin
    /// (free, 0 Hz) and the torsional mode `sqrt(2 k_t / J)` with the axle's
    /// loss factor, each wheel's rotation `+-1 / sqrt(2 J)` and its contact's
    /// longitudinal displacement `-r` times that. Its `x`-`x` receptance
    /// times `i w / V` is [`torsion::WheelsetTorsion::creepage_per_force`].
    pub fn torsion(t: &torsion::WheelsetTorsion) -> Self {
        let (spin, twist) = standard::torsion_modes(t.inertia, t.stiffness, t.loss_factor, t.radius);
        WheelsetModel::new(vec![spin, twist], Vec::new()).expect("valid torsion modes")
    }

    /// The modes, in the model's order.
    pub fn modes(&self) -> &[Mode] {
        &self.modes
    }

    /// The gyroscopic couplings.
    pub fn couplings(&self) -> &[Gyroscopic] {
        &self.couplings
    }

    /// The receptance matrix (eq. 2) at angular frequency `omega` (rad/s, >
    /// 0) and spin `spin` (rad/s; `V / r` rolling forwards): displacement
    /// (rotation) at degree of freedom `i` per force (moment) at `j`, in m/N,
    /// m/(N m) = rad/N, rad/(N m) ([`dof`]).
    ///
    /// A mode without damping is singular at its own frequency (the table
    /// and the default's keys require damping; the torsion's loss factor
    /// may be 0, as in [`torsion`]).
    ///
    /// # Panics
    /// If `omega` is not finite and > 0 or `spin` is not finite, or a
    /// coupled block is singular (an undamped mode hit exactly).
    pub fn receptance(&self, omega: f64, spin: f64) -> Receptance {
        assert!(omega.is_finite() && omega > 0.0, "omega = {omega} rad/s must be finite and > 0");
        assert!(spin.is_finite(), "spin = {spin} rad/s must be finite");
        let mut h = Receptance::zeros();
        for block in &self.blocks {
            if block.len() == 1 || spin == 0.0 {
                for &k in block {
                    let m = &self.modes[k];
                    let inv = 1.0 / m.dynamic_stiffness(omega);
                    for i in 0..DOFS {
                        if m.shape[i] == 0.0 {
                            continue;
                        }
                        for j in 0..DOFS {
                            h[(i, j)] += (m.shape[i] * m.shape[j]) * inv;
                        }
                    }
                }
                continue;
            }
            // D q = Phi_b^T f for the block's modes (eq. 2).
            let n = block.len();
            let mut d = DMatrix::<Complex64>::zeros(n, n);
            for (p, &k) in block.iter().enumerate() {
                d[(p, p)] = self.modes[k].dynamic_stiffness(omega);
            }
            for c in &self.couplings {
                let (Some(p), Some(q)) = (block.iter().position(|&k| k == c.a), block.iter().position(|&k| k == c.b))
                else {
                    continue;
                };
                let g = Complex64::new(0.0, omega * spin * c.coefficient);
                d[(p, q)] += g;
                d[(q, p)] -= g;
            }
            let rhs = DMatrix::<Complex64>::from_fn(n, DOFS, |p, j| Complex64::new(self.modes[block[p]].shape[j], 0.0));
            let x = d.lu().solve(&rhs).expect("a damped block is regular at w > 0");
            for (p, &k) in block.iter().enumerate() {
                let shape = &self.modes[k].shape;
                for i in 0..DOFS {
                    if shape[i] == 0.0 {
                        continue;
                    }
                    for j in 0..DOFS {
                        h[(i, j)] += shape[i] * x[(p, j)];
                    }
                }
            }
        }
        h
    }

    /// The undamped natural frequencies (Hz, ascending, each once) of the
    /// spinning wheelset at spin `spin` (rad/s): the positive roots `w` of
    /// `det(diag(w_k^2) - w^2 + i w Omega G) = 0`, from the eigenvalues of
    /// the first-order form per coupled block. The free rigid spin is 0.
    pub fn frequencies(&self, spin: f64) -> Vec<f64> {
        let mut out = Vec::new();
        for block in &self.blocks {
            let n = block.len();
            // State z = [q, q']: z' = [[0, I], [-W, -Omega G]] z.
            let mut a = DMatrix::<f64>::zeros(2 * n, 2 * n);
            for (p, &k) in block.iter().enumerate() {
                a[(p, n + p)] = 1.0;
                a[(n + p, p)] = -self.modes[k].omega().powi(2);
            }
            for c in &self.couplings {
                let (Some(p), Some(q)) = (block.iter().position(|&k| k == c.a), block.iter().position(|&k| k == c.b))
                else {
                    continue;
                };
                a[(n + p, n + q)] -= spin * c.coefficient;
                a[(n + q, n + p)] += spin * c.coefficient;
            }
            let mut im: Vec<f64> = a.complex_eigenvalues().iter().map(|l| l.im).filter(|w| *w >= 0.0).collect();
            im.sort_by(f64::total_cmp);
            // Each undamped root appears as +-i w: keep the n largest (the
            // zero roots of a free mode come as a pair of zeros).
            let keep = im.len().saturating_sub(n);
            out.extend(im[keep..].iter().map(|w| w / (2.0 * PI)));
        }
        out.sort_by(f64::total_cmp);
        out
    }
}

/// The connected components of the coupling graph (each sorted, in order
/// of their smallest mode).
fn connected_blocks(n: usize, couplings: &[Gyroscopic]) -> Vec<Vec<usize>> {
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for c in couplings {
        let (a, b) = (root(&mut parent, c.a), root(&mut parent, c.b));
        if a != b {
            parent[a.max(b)] = a.min(b);
        }
    }
    let mut blocks: Vec<Vec<usize>> = Vec::new();
    let mut index_of_root = vec![usize::MAX; n];
    for i in 0..n {
        let r = root(&mut parent, i);
        if index_of_root[r] == usize::MAX {
            index_of_root[r] = blocks.len();
            blocks.push(Vec::new());
        }
        blocks[index_of_root[r]].push(i);
    }
    blocks
}

#[cfg(test)]
mod tests;
