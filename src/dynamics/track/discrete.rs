//! A Timoshenko rail on discrete supports (pad, sleeper mass, ballast at
//! every `d`): the point receptance at any position in the sleeper bay, by
//! the periodic-structure (Floquet) method of the extended linear models
//! (Hempelmann and Knothe, *Arch. Appl. Mech.* 66 (1996) 321-339; Heckl,
//! *J. Sound Vib.* 257 (2002) 207-220; Thompson, *Railway Noise and
//! Vibration*, 2009, ch. 3).
//!
//! Time dependence `exp(+i w t)`, displacement down and force down
//! positive: a passive track has `Im alpha <= 0`.
//!
//! # Equations
//!
//! **Rail** (Timoshenko: shear stiffness `kappa G A`, rotary inertia
//! `rho I`; hysteretic loss factor `eta_r` on `EI` and `kappa G A`). For a
//! load `Q exp(i k x)` the displacement is `alpha^(k) Q exp(i k x)` with
//! ```text
//! alpha^(k) = D / (kGA k^2 (EI k^2 - rho I w^2) - m w^2 D),
//! D = EI k^2 + kGA - rho I w^2,                                       (1)
//! ```
//! (the shear angle eliminated; `kGA -> inf`, `rho I -> 0` gives Euler-
//! Bernoulli's `1 / (EI k^4 - m w^2)`).
//!
//! **Support** at `x_n = n d`: pad `k_p*` in series with the sleeper mass
//! `M_s` on ballast `k_b*` (`k* = k (1 + i eta) + i w c`):
//! `k_s = k_p* (k_b* - M_s w^2) / (k_p* + k_b* - M_s w^2)`; its reaction
//! `R_n = k_s w(x_n)`.                                                  (2)
//!
//! **Floquet.** With `kappa_j = kappa + 2 pi j / d` and the lattice sums
//! `T(kappa, x) = sum_j alpha^(kappa_j) exp(i kappa_j x)`, the displacement
//! at the supports of a unit load at `x0` has the Floquet transform
//! `U(kappa) = T(kappa, -x0) / (d + k_s T(kappa, 0))`, and the point
//! receptance at the load is
//! ```text
//! alpha(x0) = 1/(2 pi) int_{-pi/d}^{pi/d} [T(kappa, 0)
//!             - k_s T(kappa, x0) T(kappa, -x0) / (d + k_s T(kappa, 0))] d kappa   (3)
//! ```
//! the free rail's receptance less what the supports take back. Where the
//! rail is watched at `x1` instead of at the load, the transfer receptance
//! ```text
//! alpha(x1; x0) = 1/(2 pi) int [T(kappa, x1 - x0)
//!                 - k_s T(kappa, x1) T(kappa, -x0) / (d + k_s T(kappa, 0))] d kappa   (4)
//! ```
//! (reciprocal: `alpha(x1; x0) = alpha(x0; x1)`). The sums
//! run over `|j| <= J` with the tail of `T(kappa, 0)` (`alpha^ ~ 1 /
//! (kGA k^2)`) added in closed form; the integral is the midpoint rule.

use super::layout::{Layout, Support};
use super::rail::RailSection;
use super::scattering::{self, ScatteringError, Supported};
use super::{Damping, TrackConfig};
use nalgebra::{SMatrix, SVector};
use num_complex::Complex64;
use std::f64::consts::PI;

/// Rail loss factor (1): the rail's own damping, which keeps the lattice
/// sums finite at the propagating waves' wavenumbers (the default of
/// `track.rail_loss_factor`).
pub use super::RAIL_LOSS_FACTOR;

/// Harmonics `|j| <= J` of the lattice sums.
const LATTICE_TERMS: i64 = 384;

/// Midpoint-rule points over the Brillouin zone.
const ZONE_POINTS: usize = 768;

/// A Timoshenko rail on discrete supports.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DiscreteTrack {
    /// The rail section.
    pub rail: RailSection,
    /// Rail loss factor (1).
    pub rail_loss_factor: f64,
    /// Support spacing d (m).
    pub spacing: f64,
    /// Pad stiffness per support (N/m).
    pub pad_stiffness: f64,
    /// Pad damping.
    pub pad_damping: Damping,
    /// Sleeper mass per support (kg).
    pub sleeper_mass: f64,
    /// Ballast stiffness per support (N/m).
    pub ballast_stiffness: f64,
    /// Ballast damping.
    pub ballast_damping: Damping,
}

fn dynamic(k: f64, d: Damping, omega: f64) -> Complex64 {
    match d {
        Damping::LossFactor(eta) => Complex64::new(k, k * eta),
        Damping::Viscous(c) => Complex64::new(k, omega * c),
    }
}

impl DiscreteTrack {
    /// The configured track.
    pub fn new(t: &TrackConfig) -> Self {
        DiscreteTrack {
            rail: t.rail,
            rail_loss_factor: t.rail_loss_factor,
            spacing: t.sleeper_spacing,
            pad_stiffness: t.pad_stiffness,
            pad_damping: t.pad_damping,
            sleeper_mass: t.sleeper_mass,
            ballast_stiffness: t.ballast_stiffness,
            ballast_damping: t.ballast_damping,
        }
    }

    /// The free rail's spectral receptance `alpha^(k)` (m/N per N/m), eq. 1.
    pub fn spectral(&self, k: f64, omega: f64) -> Complex64 {
        let r = &self.rail;
        let loss = Complex64::new(1.0, self.rail_loss_factor);
        let (ei, kga) = (loss * r.bending_stiffness, loss * r.shear_stiffness);
        let w2 = omega * omega;
        let k2 = k * k;
        let d = ei * k2 + kga - r.rotary_inertia * w2;
        d / (kga * k2 * (ei * k2 - r.rotary_inertia * w2) - r.mass * w2 * d)
    }

    /// The dynamic stiffness of one support seen by the rail (N/m), eq. 2.
    pub fn support_stiffness(&self, omega: f64) -> Complex64 {
        let kp = dynamic(self.pad_stiffness, self.pad_damping, omega);
        let kb = dynamic(self.ballast_stiffness, self.ballast_damping, omega);
        let inertia = self.sleeper_mass * omega * omega;
        kp * (kb - inertia) / (kp + kb - inertia)
    }

    /// The point receptance (m/N) at `x0` (m from a support) at angular
    /// frequency `omega` (rad/s), eq. 3.
    pub fn receptance(&self, x0: f64, omega: f64) -> Complex64 {
        self.receptances(&[x0], omega)[0]
    }

    /// The point receptances (m/N) at the places `xs` (m from a support) at
    /// angular frequency `omega` (rad/s), eq. 3: the free rail's spectral
    /// receptances are evaluated once for all places (they do not depend
    /// on the place); each place's sums are those of [`Self::receptance`].
    pub fn receptances(&self, xs: &[f64], omega: f64) -> Vec<Complex64> {
        let d = self.spacing;
        let ks = self.support_stiffness(omega);
        let g = 2.0 * PI / d;
        // Phasors exp(i 2 pi j x0 / d) of the harmonics, j = -J..=J.
        let phases: Vec<Vec<Complex64>> = xs.iter().map(|&x0| self.phasors(x0)).collect();
        let mut sums = vec![Complex64::new(0.0, 0.0); xs.len()];
        self.over_zone(omega, |kappa, a, t0| {
            for ((sum, phase), &x0) in sums.iter_mut().zip(&phases).zip(xs) {
                let (tp, tm) = place_sums(a, phase, kappa, x0);
                *sum += t0 - ks * tp * tm / (d + ks * t0);
            }
        });
        sums.iter().map(|s| s / (2.0 * PI) * (g / ZONE_POINTS as f64)).collect()
    }

    /// The transfer receptances (m/N) at angular frequency `omega` (rad/s):
    /// the rail's displacement at `x0 + L` for each `L` of `distances` (m)
    /// under a unit force at `x0` (m from a support), eq. 4; at `L = 0` the
    /// point receptance of [`Self::receptances`]. The tail of the lattice
    /// sum is added where `L` is a whole number of bays (where its terms do
    /// not oscillate); elsewhere it is below 1e-3 of the receptance.
    pub fn transfer_receptances(&self, x0: f64, distances: &[f64], omega: f64) -> Vec<Complex64> {
        if distances.is_empty() {
            return Vec::new();
        }
        let d = self.spacing;
        let ks = self.support_stiffness(omega);
        let g = 2.0 * PI / d;
        let source = self.phasors(x0);
        let watched: Vec<Vec<Complex64>> = distances.iter().map(|&l| self.phasors(x0 + l)).collect();
        let free: Vec<Vec<Complex64>> = distances.iter().map(|&l| self.phasors(l)).collect();
        let tail = self.lattice_tail();
        let whole_bays: Vec<bool> = distances.iter().map(|&l| ((l / d) - (l / d).round()).abs() < 1e-12).collect();
        let mut sums = vec![Complex64::new(0.0, 0.0); distances.len()];
        self.over_zone(omega, |kappa, a, t0| {
            // T(kappa, -x0), the source's side of the supports' response.
            let tm = place_sums(a, &source, kappa, x0).1;
            for (k, &l) in distances.iter().enumerate() {
                let tp = place_sums(a, &watched[k], kappa, x0 + l).0;
                let tl = free_sum(a, &free[k], kappa, l, whole_bays[k].then_some(tail));
                sums[k] += tl - ks * tp * tm / (d + ks * t0);
            }
        });
        sums.iter().map(|s| s / (2.0 * PI) * (g / ZONE_POINTS as f64)).collect()
    }

    /// The receptance matrices (m/N) of a vehicle's wheels at angular
    /// frequency `omega` (rad/s), eq. 4: for each place `x_L` of `leaders`
    /// (m from a support) the wheels stand at `x_L + offsets[a]` (m), and
    /// entry `a * n + b` (`n` wheels) is the rail's displacement at wheel
    /// `a` under a unit force at wheel `b` (reciprocal: symmetric). One
    /// sweep of the Brillouin zone serves every place: the supports' sums
    /// `T(kappa, x)` once per wheel place, the free rail's `T(kappa, x_a -
    /// x_b)` once per pair of wheels (the same at every leader place), with
    /// the tail where the pair is whole bays apart (as
    /// [`Self::transfer_receptances`]).
    pub fn vehicle_receptances(&self, leaders: &[f64], offsets: &[f64], omega: f64) -> Vec<Vec<Complex64>> {
        let n = offsets.len();
        let d = self.spacing;
        let ks = self.support_stiffness(omega);
        let g = 2.0 * PI / d;
        let places: Vec<f64> = leaders.iter().flat_map(|x| offsets.iter().map(move |o| x + o)).collect();
        let phases: Vec<Vec<Complex64>> = places.iter().map(|&x| self.phasors(x)).collect();
        let pairs: Vec<f64> = offsets.iter().flat_map(|a| offsets.iter().map(move |b| a - b)).collect();
        let free: Vec<Vec<Complex64>> = pairs.iter().map(|&l| self.phasors(l)).collect();
        let tail = self.lattice_tail();
        let whole_bays: Vec<bool> = pairs.iter().map(|&l| ((l / d) - (l / d).round()).abs() < 1e-12).collect();
        let mut sums = vec![vec![Complex64::new(0.0, 0.0); n * n]; leaders.len()];
        let mut tp = vec![Complex64::new(0.0, 0.0); places.len()];
        let mut tm = vec![Complex64::new(0.0, 0.0); places.len()];
        let mut tl = vec![Complex64::new(0.0, 0.0); pairs.len()];
        self.over_zone(omega, |kappa, a, t0| {
            for (k, (&x, phase)) in places.iter().zip(&phases).enumerate() {
                (tp[k], tm[k]) = place_sums(a, phase, kappa, x);
            }
            for (k, &l) in pairs.iter().enumerate() {
                tl[k] = free_sum(a, &free[k], kappa, l, whole_bays[k].then_some(tail));
            }
            let support = ks / (d + ks * t0);
            for (p, sum) in sums.iter_mut().enumerate() {
                for wa in 0..n {
                    for wb in 0..n {
                        sum[wa * n + wb] += tl[wa * n + wb] - support * tp[p * n + wa] * tm[p * n + wb];
                    }
                }
            }
        });
        let scale = g / ZONE_POINTS as f64 / (2.0 * PI);
        sums.into_iter().map(|s| s.into_iter().map(|v| v * scale).collect()).collect()
    }

    /// The phasors `exp(i 2 pi j x / d)` of the lattice harmonics,
    /// `j = -J..=J`.
    fn phasors(&self, x: f64) -> Vec<Complex64> {
        let g = 2.0 * PI / self.spacing;
        (-LATTICE_TERMS..=LATTICE_TERMS).map(|j| Complex64::from_polar(1.0, g * j as f64 * x)).collect()
    }

    /// Tail of `T(kappa, 0)` beyond the harmonics kept: `alpha^ ~ 1 / (kGA
    /// k^2)`, `sum_{|j| > J} 1 / (kGA (2 pi j / d)^2) ~ d^2 / (2 pi^2 kGA
    /// (J + 1/2))`.
    fn lattice_tail(&self) -> Complex64 {
        let d = self.spacing;
        let kga = Complex64::new(1.0, self.rail_loss_factor) * self.rail.shear_stiffness;
        d * d / (2.0 * PI * PI * (LATTICE_TERMS as f64 + 0.5)) / kga
    }

    /// Calls `f(kappa, a, T(kappa, 0))` at the midpoints `kappa` of the
    /// Brillouin zone, `a` the free rail's spectral receptances
    /// `alpha^(kappa + 2 pi j / d)`, `j = -J..=J`, the sum with its tail.
    fn over_zone(&self, omega: f64, mut f: impl FnMut(f64, &[Complex64], Complex64)) {
        let d = self.spacing;
        let g = 2.0 * PI / d;
        let tail = self.lattice_tail();
        let mut a = vec![Complex64::new(0.0, 0.0); 2 * LATTICE_TERMS as usize + 1];
        for q in 0..ZONE_POINTS {
            let kappa = -PI / d + (q as f64 + 0.5) * g / ZONE_POINTS as f64;
            let mut t0 = tail;
            for (ai, j) in a.iter_mut().zip(-LATTICE_TERMS..=LATTICE_TERMS) {
                *ai = self.spectral(kappa + g * j as f64, omega);
                t0 += *ai;
            }
            f(kappa, &a, t0);
        }
    }

    /// The first bending frequency (Hz) of one span `d` of this rail simply
    /// supported at both ends (undamped Timoshenko beam, `k = pi / d`): the
    /// lower root of `m rho I W^2 - (kGA k^2 rho I + m (EI k^2 + kGA)) W +
    /// kGA EI k^4 = 0`, `W = w^2`. The pinned-pinned resonance of the track
    /// lies near it.
    pub fn pinned_pinned_frequency(&self) -> f64 {
        let r = &self.rail;
        let k = PI / self.spacing;
        let (ei, kga, ri, m) = (r.bending_stiffness, r.shear_stiffness, r.rotary_inertia, r.mass);
        let a = m * ri;
        let b = kga * k * k * ri + m * (ei * k * k + kga);
        let c = kga * ei * k.powi(4);
        let w2 = if a > 0.0 { (b - (b * b - 4.0 * a * c).sqrt()) / (2.0 * a) } else { c / b };
        w2.sqrt() / (2.0 * PI)
    }
}

/// The free Timoshenko rail's two vertical waves at one frequency: eq. 1's
/// denominator is a quadratic in `s = k^2`, `P(s) = EI kGA s^2 - (kGA rho
/// I + m EI) w^2 s - m w^2 (kGA - rho I w^2)`, with numerator `N(s) = EI s +
/// kGA - rho I w^2`; by residues in the upper half plane (as
/// [`super::waves`] eq. 1)
/// ```text
/// G(x) = sum_r c_r exp(i k_r |x|),   c_r = i N(s_r) / (2 k_r P'(s_r)),   k_r = sqrt(s_r), Im k_r > 0   (5)
/// ```
/// (Euler-Bernoulli's limit: `G(0) = -(1 + i) / (4 EI k_b^3)`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VerticalWaves {
    /// Wavenumbers `k_r` (rad/m), `Im > 0`.
    pub k: [Complex64; 2],
    /// Their residues `c_r` (m/N).
    pub c: [Complex64; 2],
}

impl super::scattering::RailWaves<1> for VerticalWaves {
    fn wavenumbers(&self) -> Vec<Complex64> {
        self.k.to_vec()
    }

    fn factors(&self) -> Vec<(SVector<Complex64, 1>, SVector<Complex64, 1>)> {
        self.c.iter().map(|c| (SVector::from_element(*c), SVector::from_element(Complex64::new(1.0, 0.0)))).collect()
    }
}

impl DiscreteTrack {
    /// Whether `layout` is one bay of this track (its own spacing, pad,
    /// sleeper and ballast): the one-bay models then serve it.
    pub fn is_one_bay(&self, layout: &Layout) -> bool {
        let support = Support {
            x: 0.0,
            pad_stiffness: self.pad_stiffness,
            pad_damping: self.pad_damping,
            sleeper_mass: self.sleeper_mass,
            ballast_stiffness: self.ballast_stiffness,
        };
        layout.is_one_bay_of(self.spacing, support)
    }

    /// This track with support `m` of `layout`'s pad, sleeper and ballast.
    pub fn at_support(&self, layout: &Layout, m: usize) -> DiscreteTrack {
        let s = &layout.supports[m];
        DiscreteTrack {
            pad_stiffness: s.pad_stiffness,
            pad_damping: s.pad_damping,
            sleeper_mass: s.sleeper_mass,
            ballast_stiffness: s.ballast_stiffness,
            ..*self
        }
    }

    /// `layout`'s supports at `omega` (rad/s): each one's place (m) and
    /// dynamic stiffness (N/m, eq. 2 with its own pad, sleeper and ballast).
    pub fn layout_supports(&self, layout: &Layout, omega: f64) -> Vec<Supported<1>> {
        (0..layout.len())
            .map(|m| (layout.supports[m].x, SMatrix::from_element(self.at_support(layout, m).support_stiffness(omega))))
            .collect()
    }

    /// The free rail's vertical waves (eq. 5) at `omega` (rad/s); the
    /// rail's loss factor (> 0) keeps them off the real axis.
    pub fn waves(&self, omega: f64) -> VerticalWaves {
        let r = &self.rail;
        let loss = Complex64::new(1.0, self.rail_loss_factor);
        let (ei, kga) = (loss * r.bending_stiffness, loss * r.shear_stiffness);
        let w2 = omega * omega;
        let (a, b, c) =
            (ei * kga, -(kga * r.rotary_inertia + r.mass * ei) * w2, -(kga - r.rotary_inertia * w2) * r.mass * w2);
        // The roots without cancellation: q = -(b + sign root) / 2 with the
        // sign that adds, s = q / a and c / q.
        let root = (b * b - 4.0 * a * c).sqrt();
        let root = if (b.conj() * root).re >= 0.0 { root } else { -root };
        let q = -0.5 * (b + root);
        let s = [q / a, c / q];
        let k = s.map(|s| {
            let k = s.sqrt();
            if k.im < 0.0 { -k } else { k }
        });
        let c = std::array::from_fn(|i| {
            Complex64::i() * (ei * s[i] + kga - r.rotary_inertia * w2) / (2.0 * k[i] * (2.0 * a * s[i] + b))
        });
        VerticalWaves { k, c }
    }

    /// The receptances (m/N) on `layout`, each support with its own pad,
    /// sleeper and ballast: the rail's displacement at `x1` under a unit
    /// force at `x0` for each `(x0, x1)` of `pairs` (m from the layout's
    /// start) at angular frequency `omega` (rad/s), by the waves'
    /// scattering ([`super::scattering`]) with the waves of eq. 5.
    ///
    /// # Errors
    /// Where the semi-infinite track does not converge (an undamped track).
    pub fn layout_receptances(
        &self,
        layout: &Layout,
        pairs: &[(f64, f64)],
        omega: f64,
    ) -> Result<Vec<Complex64>, ScatteringError> {
        let supports = self.layout_supports(layout, omega);
        let one = SMatrix::<Complex64, 1, 1>::from_element(Complex64::new(1.0, 0.0));
        let out = scattering::response(&self.waves(omega), &supports, layout.period, &one, pairs)?;
        Ok(out.into_iter().map(|g| g[(0, 0)]).collect())
    }
}

/// The supports' lattice sums at the place `x` (m from a support):
/// `T(kappa, x) = sum_j alpha^(kappa_j) exp(i kappa_j x)` and `T(kappa, -x)`,
/// from the free rail's spectral receptances `a` and the place's phasors
/// `phase` ([`DiscreteTrack::phasors`]).
fn place_sums(a: &[Complex64], phase: &[Complex64], kappa: f64, x: f64) -> (Complex64, Complex64) {
    let (mut p, mut m) = (Complex64::new(0.0, 0.0), Complex64::new(0.0, 0.0));
    for (ai, ph) in a.iter().zip(phase) {
        p += ai * ph;
        m += ai * ph.conj();
    }
    let shift = Complex64::from_polar(1.0, kappa * x);
    (p * shift, m * shift.conj())
}

/// The free rail's `T(kappa, l)` at the distance `l` (m) from the load
/// (phasors `phase` of `l`), with the lattice tail `tail` where given (`l`
/// a whole number of bays, where its terms do not oscillate).
fn free_sum(a: &[Complex64], phase: &[Complex64], kappa: f64, l: f64, tail: Option<Complex64>) -> Complex64 {
    let shift = Complex64::from_polar(1.0, kappa * l);
    let tail_l = tail.map_or(Complex64::new(0.0, 0.0), |t| t * shift);
    a.iter().zip(phase).map(|(ai, ph)| ai * ph).sum::<Complex64>() * shift + tail_l
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn euler_bernoulli_limit_of_the_spectral_receptance() {
        let mut t = DiscreteTrack::new(&TrackConfig::default());
        t.rail.shear_stiffness = 1e20;
        t.rail.rotary_inertia = 0.0;
        t.rail_loss_factor = 0.0;
        let (k, w): (f64, f64) = (7.0, 2.0 * PI * 300.0);
        let eb = 1.0 / (t.rail.bending_stiffness * k.powi(4) - t.rail.mass * w * w);
        assert!((t.spectral(k, w).re - eb).abs() < 1e-9 * eb.abs());
    }
}
