//! Linear frequency-domain wheel-track model: wheel unsprung mass, linearised
//! Hertz spring, and the point receptance of an infinite Euler-Bernoulli rail
//! on a continuous two-layer (pad / sleeper mass / ballast) support, coupled
//! by the moving-irregularity model (Grassie, Gregory, Harrison, Johnson,
//! *J. Mech. Eng. Sci.* 24 (1982) 77-90; Thompson, *Railway Noise and
//! Vibration*, Elsevier 2009, ch. 3 and 5).
//!
//! Time dependence `exp(+i w t)`; a receptance `alpha = displacement / force`
//! (m/N) of a passive, damped structure then has `Im alpha <= 0` (the
//! displacement lags the force).
//!
//! # Equations
//!
//! **Wheel** (unsprung mass `M`, free above: the primary suspension is far
//! below the frequencies of interest). The contact force `P` pushes the wheel
//! up: `-M w^2 y_w = P`, so the upward wheel displacement is `y_w = alpha_w P`
//! with
//! ```text
//! alpha_w = -1 / (M w^2)                                              (1)
//! ```
//!
//! **Contact**: Hertz `N ~ delta^(3/2)` (Johnson, *Contact Mechanics*, 1985,
//! section 4.2), linearised at the mean load `N0` with Hertz approach
//! `delta0`: `k_H = dN/d delta = 3 N0 / (2 delta0)` ([`hertz_stiffness`]),
//! `alpha_c = 1 / k_H`.                                                (2)
//!
//! **Support** (per unit rail length): pad `s_p* = s_p (1 + i eta_p) + i w c_p`
//! between rail and a distributed sleeper mass `m_s`, ballast
//! `s_b* = s_b (1 + i eta_b) + i w c_b` between sleeper and rigid ground
//! (hysteretic loss factors or viscous dampers, `[track]`). Eliminating
//! the sleeper displacement (`-m_s w^2 w_s = s_p* (w_r - w_s) - s_b* w_s`)
//! gives the foundation stiffness seen by the rail (Thompson 2009, ch. 3)
//! ```text
//! s(w) = s_p* (s_b* - m_s w^2) / (s_p* + s_b* - m_s w^2)              (3)
//! ```
//! which is `s_p* s_b* / (s_p* + s_b*)` (pad and ballast in series) at `w = 0`
//! and tends to `s_p*` (sleeper blocked by its inertia) as `w -> inf`.
//!
//! **Rail**: `EI w'''' - m_r w^2 w + s(w) w = F delta(x)`. With
//! `beta^4 = (s(w) - m_r w^2) / (4 EI)` the characteristic roots are
//! `lambda = beta (+-1 +- i)`. For `x > 0` keep the two roots
//! `lambda = -beta (1 +- i)`; symmetry (`w'(0) = 0`) and the shear jump
//! (`EI w'''(0+) = F / 2`) give `w(x) = F/(8 EI beta^3) exp(-beta x)
//! (cos beta x + sin beta x)`, so the point receptance is
//! ```text
//! alpha_r(w) = 1 / (8 EI beta^3)                                      (4)
//! ```
//! ([`winkler_point_receptance`]). **Branch**: both kept roots decay
//! (`Re lambda <= 0`) iff `|arg beta| <= pi/4`, i.e. `beta` is the principal
//! fourth root of `beta^4`. With damping `Im s > 0`, `arg beta^4` lies in
//! `(0, pi)` and `arg beta` in `(0, pi/4)`: both waves decay. Above the
//! cut-on (`Re s < m_r w^2`) without damping, `arg beta^4 = pi` (the limit
//! from positive damping), `beta = |beta| exp(i pi/4)`, and the roots are
//! `-sqrt(2)|beta|` (near field) and `-i sqrt(2)|beta|`, i.e.
//! `exp(i (w t - k x))`: a wave travelling away from the load, the radiation
//! condition for `exp(+i w t)`. Then `arg alpha_r = -3 arg beta` lies in
//! `[-3 pi/4, 0]`: `Im alpha_r <= 0` as required.
//! Limits: static, `beta_s = (s(0) / (4 EI))^(1/4)` and
//! `alpha_r = 1 / (8 EI beta_s^3)` (Hetenyi, *Beams on Elastic Foundation*,
//! 1946); high frequency, `s << m_r w^2` and `alpha_r -> -(1 + i) / (4 EI k_b^3)`,
//! `k_b = (m_r w^2 / EI)^(1/4)`, the free infinite beam (Cremer, Heckl,
//! Petersson, *Structure-Borne Sound*, 2005).
//!
//! **Coupling** (moving irregularity: the load stands still, the roughness
//! `r` is pulled through the contact at speed `V`; Grassie et al. 1982).
//! With `r > 0` meaning the rail top is higher, the Hertz compression is
//! `delta = r - y_w - y_r` (wheel up `y_w = alpha_w P`, rail down
//! `y_r = alpha_r P`, `delta = alpha_c P`), hence
//! ```text
//! P = r / (alpha_w + alpha_c + alpha_r),   H(f) = dP/dr = 1 / (alpha_w + alpha_c + alpha_r)   (5)
//! ```
//! (Grassie et al. write `P = -r / (...)` with the opposite sign of `r`).
//! Checks of the sign: below the resonances the wheel follows the profile,
//! `H -> -M w^2` (a crest, where the wheel decelerates upward, unloads the
//! contact); far above them the wheel and the rail stand still and
//! `H -> k_H`, the contact spring alone.
//!
//! # What is not modelled
//! - Discrete sleeper support: the *pinned-pinned* resonance of the rail
//!   between sleepers (about 1 kHz for 0.6 m spacing; the Euler-Bernoulli
//!   estimate `pi / (2 d^2) sqrt(EI / m_r)` gives 1.4 kHz, shear lowers it)
//!   and the variation of the receptance along a sleeper bay are absent, so
//!   pinned-pinned corrugation cannot be predicted by this model.
//! - Shear deformation and rotary inertia of the rail (Timoshenko beam),
//!   which soften the rail above about 500 Hz, and the rail's own damping.
//! - The load's motion along the rail (valid for `V` far below the critical
//!   speed of the track), the other rail, the primary suspension, wheel
//!   modes, and contact filtering (done by the caller). Several wheels on
//!   this rail are coupled by [`super::model`] (the transfer receptance
//!   [`winkler_transfer_receptance`] between them), which is also the
//!   growth loop's model of one wheel.

use super::apply_periodic_response;
use num_complex::Complex64;
use std::f64::consts::PI;

/// Young's modulus of rail steel (Pa): 210 GPa, the usual value for rail steel.
pub const RAIL_YOUNG_MODULUS: f64 = 210e9;
/// Second moment of area of the UIC60 rail about the horizontal axis (m^4):
/// 3055 cm^4, the nominal UIC60 value (UIC leaflet 861-3); with
/// [`RAIL_YOUNG_MODULUS`] EI = 6.4e6 N m^2, the value used by Thompson 2009, ch. 3.
pub const UIC60_SECOND_MOMENT: f64 = 30.55e-6;
/// Mass per length of the UIC60 rail (kg/m): nominal 60.3 kg/m (UIC leaflet 861-3;
/// Thompson 2009, ch. 3, rounds it to 60 kg/m).
pub const UIC60_MASS: f64 = 60.3;
/// Sleeper spacing (m): 0.6 m, the usual spacing of concrete monobloc sleepers
/// on European main lines (Thompson 2009, ch. 3).
pub const SLEEPER_SPACING: f64 = 0.6;
/// Rail pad stiffness per pad (N/m): 200 MN/m, a medium-stiffness studded
/// pad (Thompson 2009, ch. 3, which spans 100 MN/m soft to 1000 MN/m stiff).
pub const PAD_STIFFNESS_PER_PAD: f64 = 200e6;
/// Rail pad loss factor (1): 0.25, typical of rubber pads (Thompson 2009, ch. 3).
pub const PAD_LOSS_FACTOR: f64 = 0.25;
/// Sleeper mass carried by one rail (kg): half of a 280 kg concrete monobloc
/// sleeper (concrete monobloc sleepers weigh roughly 250-320 kg; Thompson
/// 2009, ch. 3; Knothe and Grassie, *Veh. Syst. Dyn.* 22 (1993) 209-262).
pub const HALF_SLEEPER_MASS: f64 = 140.0;
/// Ballast stiffness under one half sleeper (N/m): 100 MN/m, a typical
/// ballast bed (Thompson 2009, ch. 3).
pub const BALLAST_STIFFNESS_PER_HALF_SLEEPER: f64 = 100e6;
/// Ballast loss factor (1): 1.0, a heavily damped ballast layer (Thompson
/// 2009, ch. 3).
pub const BALLAST_LOSS_FACTOR: f64 = 1.0;
/// Unsprung mass per wheel of a freight wagon (kg): 600 kg, about half of a
/// freight wheelset with its axle boxes (roughly 1.1-1.4 t).
pub const FREIGHT_UNSPRUNG_MASS: f64 = 600.0;

/// Default frequency sweep of [`ReceptanceModel::resonances`]: from (Hz).
pub const SWEEP_MIN_HZ: f64 = 1.0;
/// Default frequency sweep of [`ReceptanceModel::resonances`]: to (Hz).
pub const SWEEP_MAX_HZ: f64 = 5000.0;
/// Default frequency sweep of [`ReceptanceModel::resonances`]: log-spaced
/// points (a ratio of 1.0021 between neighbours).
pub const SWEEP_POINTS: usize = 4001;

/// Invalid parameters of a dynamics model.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum DynamicsError {
    /// A parameter is out of its physical range.
    #[error("{name} = {value} {unit} must be {requirement}")]
    InvalidParameter {
        /// Parameter name.
        name: &'static str,
        /// The offending value.
        value: f64,
        /// Its unit.
        unit: &'static str,
        /// What it must satisfy.
        requirement: &'static str,
    },
}

fn check(
    name: &'static str,
    value: f64,
    unit: &'static str,
    requirement: &'static str,
    ok: bool,
) -> Result<(), DynamicsError> {
    if ok { Ok(()) } else { Err(DynamicsError::InvalidParameter { name, value, unit, requirement }) }
}

/// Linearised Hertz contact stiffness `k_H = dN/d delta = 3 N0 / (2 delta0)`
/// (N/m) at the mean load `n0` (N) with Hertz approach `approach0` (m) at that
/// load (`delta ~ N^(2/3)`; Johnson, *Contact Mechanics*, 1985, section 4.2).
/// For example [`crate::hertz::HertzPatch::approach`] at `N0 = 100 kN` on the
/// paper's concave geometry (0.0818 mm) gives `k_H = 1.83e9 N/m`.
pub fn hertz_stiffness(n0: f64, approach0: f64) -> f64 {
    1.5 * n0 / approach0
}

/// Point receptance (m/N) of an infinite Euler-Bernoulli beam of bending
/// stiffness `ei` (N m^2) on a Winkler foundation of net dynamic stiffness per
/// length `net_stiffness` (N/m^2; foundation stiffness minus `m w^2` for a beam
/// of mass `m` per length): `1 / (8 EI beta^3)` with `beta` the principal
/// fourth root of `net_stiffness / (4 EI)` (`|arg beta| <= pi/4`, decaying or
/// outgoing waves for `exp(+i w t)`; module docs, eq. 4). A negative zero
/// imaginary part is read as `+0`, the limit of a positive (passive) damping.
pub fn winkler_point_receptance(ei: f64, net_stiffness: Complex64) -> Complex64 {
    let beta = winkler_beta(ei, net_stiffness);
    1.0 / (8.0 * ei * beta * beta * beta)
}

/// The principal fourth root `beta` of `net_stiffness / (4 EI)` (module
/// docs, eq. 4), a negative zero imaginary part read as `+0`.
fn winkler_beta(ei: f64, net_stiffness: Complex64) -> Complex64 {
    let mut b4 = net_stiffness / (4.0 * ei);
    if b4.im == 0.0 {
        b4.im = 0.0; // -0.0 -> +0.0: the damped limit, arg = +pi above cut-on.
    }
    b4.sqrt().sqrt()
}

/// Transfer receptance (m/N) of the same beam: the displacement at distance
/// `distance` (m, either side) from a unit force,
/// `exp(-beta |x|) (cos beta |x| + sin beta |x|) / (8 EI beta^3)` (module
/// docs, eq. 4; Hetenyi 1946 in the static case), `beta` as in
/// [`winkler_point_receptance`], which it equals at `distance = 0`.
/// Evaluated as `[(1 - i) exp((-1 + i) z) + (1 + i) exp((-1 - i) z)] / 2`,
/// `z = beta |x|`, whose exponents have non-positive real parts (`|arg
/// beta| <= pi/4`): `cos z` and `sin z` alone overflow where the wave has
/// long decayed (tens of metres), and their product with `exp(-z)` was NaN.
pub fn winkler_transfer_receptance(ei: f64, net_stiffness: Complex64, distance: f64) -> Complex64 {
    let beta = winkler_beta(ei, net_stiffness);
    let z = beta * distance.abs();
    let (up, down) = (Complex64::new(-1.0, 1.0), Complex64::new(-1.0, -1.0));
    let wave = 0.5 * (Complex64::new(1.0, -1.0) * (up * z).exp() + Complex64::new(1.0, 1.0) * (down * z).exp());
    wave / (8.0 * ei * beta * beta * beta)
}

/// Rail and two-layer support, as continuous properties per rail length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrackParams {
    /// Rail bending stiffness EI (N m^2).
    pub bending_stiffness: f64,
    /// Rail mass per length m_r (kg/m).
    pub rail_mass: f64,
    /// Pad stiffness per rail length s_p = pad stiffness / sleeper spacing (N/m^2).
    pub pad_stiffness: f64,
    /// Pad loss factor eta_p (1).
    pub pad_loss_factor: f64,
    /// Sleeper mass per rail length m_s = half-sleeper mass / spacing (kg/m).
    pub sleeper_mass: f64,
    /// Ballast stiffness per rail length s_b = half-sleeper ballast stiffness / spacing (N/m^2).
    pub ballast_stiffness: f64,
    /// Ballast loss factor eta_b (1).
    pub ballast_loss_factor: f64,
    /// Viscous pad damping per rail length c_p (N s/m^2): `s_p*` gains
    /// `i w c_p` (0 with a loss factor).
    pub pad_damping: f64,
    /// Viscous ballast damping per rail length c_b (N s/m^2).
    pub ballast_damping: f64,
}

impl TrackParams {
    /// UIC60 rail on 200 MN/m pads, 0.6 m spaced concrete monobloc sleepers
    /// (140 kg per rail) and 100 MN/m ballast per half sleeper; see the
    /// constants of this module for the sources. Per length: EI = 6.4155e6
    /// N m^2, m_r = 60.3 kg/m, s_p = 333.3 MN/m^2 (eta 0.25), m_s = 233.3 kg/m,
    /// s_b = 166.7 MN/m^2 (eta 1.0).
    pub fn uic60_default() -> Self {
        TrackParams {
            bending_stiffness: RAIL_YOUNG_MODULUS * UIC60_SECOND_MOMENT,
            rail_mass: UIC60_MASS,
            pad_stiffness: PAD_STIFFNESS_PER_PAD / SLEEPER_SPACING,
            pad_loss_factor: PAD_LOSS_FACTOR,
            sleeper_mass: HALF_SLEEPER_MASS / SLEEPER_SPACING,
            ballast_stiffness: BALLAST_STIFFNESS_PER_HALF_SLEEPER / SLEEPER_SPACING,
            ballast_loss_factor: BALLAST_LOSS_FACTOR,
            pad_damping: 0.0,
            ballast_damping: 0.0,
        }
    }

    /// Checks that stiffnesses are positive and finite, masses and loss
    /// factors non-negative and finite.
    pub fn validate(&self) -> Result<(), DynamicsError> {
        let pos = |v: f64| v.is_finite() && v > 0.0;
        let nonneg = |v: f64| v.is_finite() && v >= 0.0;
        check("bending_stiffness", self.bending_stiffness, "N m^2", "finite and > 0", pos(self.bending_stiffness))?;
        check("rail_mass", self.rail_mass, "kg/m", "finite and >= 0", nonneg(self.rail_mass))?;
        check("pad_stiffness", self.pad_stiffness, "N/m^2", "finite and > 0", pos(self.pad_stiffness))?;
        check("pad_loss_factor", self.pad_loss_factor, "", "finite and >= 0", nonneg(self.pad_loss_factor))?;
        check("sleeper_mass", self.sleeper_mass, "kg/m", "finite and >= 0", nonneg(self.sleeper_mass))?;
        check("ballast_stiffness", self.ballast_stiffness, "N/m^2", "finite and > 0", pos(self.ballast_stiffness))?;
        check(
            "ballast_loss_factor",
            self.ballast_loss_factor,
            "",
            "finite and >= 0",
            nonneg(self.ballast_loss_factor),
        )?;
        check("pad_damping", self.pad_damping, "N s/m^2", "finite and >= 0", nonneg(self.pad_damping))?;
        check("ballast_damping", self.ballast_damping, "N s/m^2", "finite and >= 0", nonneg(self.ballast_damping))
    }

    /// Foundation stiffness per length `s(w)` (N/m^2) of the pad / sleeper /
    /// ballast layers at angular frequency `omega` (rad/s); module docs, eq. 3.
    pub fn foundation_stiffness(&self, omega: f64) -> Complex64 {
        // Hysteretic (loss factor) and viscous damping: s (1 + i eta) + i w c.
        let sp =
            Complex64::new(self.pad_stiffness, self.pad_stiffness * self.pad_loss_factor + omega * self.pad_damping);
        let sb = Complex64::new(
            self.ballast_stiffness,
            self.ballast_stiffness * self.ballast_loss_factor + omega * self.ballast_damping,
        );
        let inertia = self.sleeper_mass * omega * omega;
        sp * (sb - inertia) / (sp + sb - inertia)
    }

    /// Static, undamped foundation stiffness per length: pad and ballast in
    /// series, `s_p s_b / (s_p + s_b)` (N/m^2).
    pub fn static_foundation_stiffness(&self) -> f64 {
        self.pad_stiffness * self.ballast_stiffness / (self.pad_stiffness + self.ballast_stiffness)
    }

    /// Rail point receptance `alpha_r(w)` (m/N) at angular frequency `omega`
    /// (rad/s, >= 0); module docs, eq. 4.
    pub fn rail_receptance(&self, omega: f64) -> Complex64 {
        let net = self.foundation_stiffness(omega) - self.rail_mass * omega * omega;
        winkler_point_receptance(self.bending_stiffness, net)
    }

    /// Rail transfer receptance (m/N) at distance `distance` (m) from the
    /// force, at angular frequency `omega` (rad/s, >= 0):
    /// [`winkler_transfer_receptance`].
    pub fn rail_transfer_receptance(&self, omega: f64, distance: f64) -> Complex64 {
        let net = self.foundation_stiffness(omega) - self.rail_mass * omega * omega;
        winkler_transfer_receptance(self.bending_stiffness, net, distance)
    }

    /// Static, undamped rail point receptance (m/N): Hetenyi's
    /// `1 / (8 EI beta_s^3)`, `beta_s = (s / (4 EI))^(1/4)` with `s` from
    /// [`Self::static_foundation_stiffness`].
    pub fn static_rail_receptance(&self) -> f64 {
        let beta = (self.static_foundation_stiffness() / (4.0 * self.bending_stiffness)).powf(0.25);
        1.0 / (8.0 * self.bending_stiffness * beta.powi(3))
    }
}

/// The wheel as a rigid unsprung mass.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WheelParams {
    /// Unsprung mass per wheel M_w (kg); `f64::INFINITY` holds the wheel
    /// still (a fixed axle: `alpha_w = 0`).
    pub unsprung_mass: f64,
}

impl WheelParams {
    /// 600 kg per wheel ([`FREIGHT_UNSPRUNG_MASS`]).
    pub fn default_freight() -> Self {
        WheelParams { unsprung_mass: FREIGHT_UNSPRUNG_MASS }
    }

    /// Wheel receptance `alpha_w = -1 / (M w^2)` (m/N, upward displacement
    /// per contact force) at angular frequency `omega` (rad/s); module docs,
    /// eq. 1. `-inf` at `omega = 0` for a finite mass, `0` for an infinite one.
    pub fn receptance(&self, omega: f64) -> Complex64 {
        if self.unsprung_mass.is_infinite() {
            Complex64::new(0.0, 0.0)
        } else {
            Complex64::new(-1.0 / (self.unsprung_mass * omega * omega), 0.0)
        }
    }

    /// Checks that the mass is positive (infinity allowed).
    pub fn validate(&self) -> Result<(), DynamicsError> {
        check("unsprung_mass", self.unsprung_mass, "kg", "> 0 (inf allowed)", self.unsprung_mass > 0.0)
    }
}

/// Wheel mass + linearised Hertz spring + rail on a two-layer support, coupled
/// in series (module docs, eq. 5).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReceptanceModel {
    /// Rail and support.
    pub track: TrackParams,
    /// Wheel.
    pub wheel: WheelParams,
    /// Linearised Hertz contact stiffness k_H (N/m), see [`hertz_stiffness`];
    /// `f64::INFINITY` makes the contact rigid.
    pub contact_stiffness: f64,
}

impl ReceptanceModel {
    /// Validates and builds the model.
    pub fn new(track: TrackParams, wheel: WheelParams, contact_stiffness: f64) -> Result<Self, DynamicsError> {
        track.validate()?;
        wheel.validate()?;
        check("contact_stiffness", contact_stiffness, "N/m", "> 0 (inf allowed)", contact_stiffness > 0.0)?;
        Ok(ReceptanceModel { track, wheel, contact_stiffness })
    }

    /// The three receptances (m/N) at angular frequency `omega` (rad/s, > 0):
    /// `(alpha_w, alpha_c, alpha_r)` = (wheel, contact, rail); eqs. 1, 2, 4.
    pub fn receptances(&self, omega: f64) -> (Complex64, Complex64, Complex64) {
        let alpha_c = Complex64::new(1.0 / self.contact_stiffness, 0.0);
        (self.wheel.receptance(omega), alpha_c, self.track.rail_receptance(omega))
    }

    /// Transfer function `H(f) = dP/dr = 1 / (alpha_w + alpha_c + alpha_r)`
    /// (N/m) from roughness (rail top up) to contact force at frequency
    /// `f_hz` (Hz); eq. 5. `H(-f) = conj(H(f))`; `H(0) = 0` for a finite
    /// wheel mass (a wheel following a static height change keeps its load).
    pub fn force_per_roughness(&self, f_hz: f64) -> Complex64 {
        if f_hz < 0.0 {
            return self.force_per_roughness(-f_hz).conj();
        }
        if f_hz == 0.0 && self.wheel.unsprung_mass.is_finite() {
            return Complex64::new(0.0, 0.0);
        }
        let (aw, ac, ar) = self.receptances(2.0 * PI * f_hz);
        1.0 / (aw + ac + ar)
    }

    /// Hand formula of the wheel bouncing on the contact spring against a
    /// rigid rail: `f = sqrt(k_H / M_w) / (2 pi)` (Hz).
    pub fn wheel_on_contact_spring_frequency(&self) -> f64 {
        (self.contact_stiffness / self.wheel.unsprung_mass).sqrt() / (2.0 * PI)
    }

    /// Frequencies (Hz, ascending) of the local maxima of `|H(f)|` inside
    /// `(f_min, f_max)`: `points` log-spaced samples locate them, a
    /// golden-section search in `ln f` between the neighbours of each sampled
    /// maximum refines them (to a relative 1e-12). Peaks narrower than the
    /// grid spacing can be missed; maxima at the ends are not reported.
    ///
    /// # Panics
    /// If not `0 < f_min < f_max` or `points < 3`.
    pub fn resonances(&self, f_min: f64, f_max: f64, points: usize) -> Vec<f64> {
        assert!(f_min > 0.0 && f_max > f_min && f_max.is_finite(), "need 0 < f_min < f_max");
        assert!(points >= 3, "need at least 3 points");
        let (u0, u1) = (f_min.ln(), f_max.ln());
        let u: Vec<f64> = (0..points).map(|i| u0 + (u1 - u0) * i as f64 / (points - 1) as f64).collect();
        let g = |u: f64| self.force_per_roughness(u.exp()).norm();
        let a: Vec<f64> = u.iter().map(|&u| g(u)).collect();
        let mut peaks = Vec::new();
        for i in 1..points - 1 {
            if a[i] > a[i - 1] && a[i] >= a[i + 1] {
                peaks.push(golden_max(&g, u[i - 1], u[i + 1]).exp());
            }
        }
        peaks
    }

    /// [`Self::resonances`] over the default sweep ([`SWEEP_MIN_HZ`] to
    /// [`SWEEP_MAX_HZ`], [`SWEEP_POINTS`] points).
    pub fn default_resonances(&self) -> Vec<f64> {
        self.resonances(SWEEP_MIN_HZ, SWEEP_MAX_HZ, SWEEP_POINTS)
    }

    /// Dynamic contact force (N, zero mean) at the points `X_j = j dx` of one
    /// period of the rail profile `profile_line` (m, rail top up) for a wheel
    /// at speed `speed` (m/s, sign = direction along X): each harmonic `n` of
    /// the profile times `H(f = V n / L)`, `L = N dx`, mean dropped; see
    /// [`super::apply_periodic_response`]. The static load is not included.
    ///
    /// # Panics
    /// If `dx` is not finite and positive or `speed` is not finite.
    pub fn dynamic_force(&self, profile_line: &[f64], dx: f64, speed: f64) -> Vec<f64> {
        apply_periodic_response(profile_line, dx, speed, |f| self.force_per_roughness(f))
    }
}

/// Golden-section search for a maximum of `g` on `[a, b]`.
fn golden_max<G: Fn(f64) -> f64>(g: &G, mut a: f64, mut b: f64) -> f64 {
    let inv_phi = (5f64.sqrt() - 1.0) / 2.0;
    let mut c = b - inv_phi * (b - a);
    let mut d = a + inv_phi * (b - a);
    let (mut gc, mut gd) = (g(c), g(d));
    for _ in 0..200 {
        if (b - a).abs() <= 1e-12 {
            break;
        }
        if gc >= gd {
            b = d;
            d = c;
            gd = gc;
            c = b - inv_phi * (b - a);
            gc = g(c);
        } else {
            a = c;
            c = d;
            gc = gd;
            d = a + inv_phi * (b - a);
            gd = g(d);
        }
    }
    0.5 * (a + b)
}

impl ReceptanceModel {
    /// The peaks of [`ReceptanceModel::default_resonances`], labelled by the
    /// receptances that balance at each peak frequency:
    /// - rail mass-like (`Re alpha_r < 0`) and `|alpha_w| < alpha_c`: the rail's
    ///   effective mass on the contact spring, the wheel nearly at rest
    ///   ("P1 type"; Jenkins, Stephenson, Clayton, Morland, Lyon, *Railw. Eng. J.*
    ///   3 (1974) 2-16; several hundred Hz to 2 kHz);
    /// - rail spring-like and softer than the contact (`Re alpha_r > alpha_c`):
    ///   the wheel mass on the track, the lowest one being P2 (typically
    ///   50-100 Hz); a higher one lies near the track's sleeper anti-resonance
    ///   `sqrt((s_p + s_b) / m_s) / (2 pi)`;
    /// - otherwise the wheel mass on the contact spring (the rigid-track limit
    ///   `sqrt(k_H / M_w) / (2 pi)`).
    pub fn describe_resonances(&self) -> Vec<(String, f64)> {
        let mut p2_seen = false;
        self.default_resonances()
            .into_iter()
            .map(|f| {
                let (aw, ac, ar) = self.receptances(2.0 * PI * f);
                let label = if ar.re < 0.0 && aw.norm() < ac.re {
                    "P1: rail effective mass on the contact spring, wheel nearly at rest"
                } else if ar.re > ac.re && !p2_seen {
                    p2_seen = true;
                    "P2: wheel unsprung mass on the track support"
                } else if ar.re > ac.re {
                    "wheel unsprung mass on the track support (near the sleeper anti-resonance)"
                } else {
                    "wheel unsprung mass on the contact spring"
                };
                (label.to_string(), f)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(x: Complex64, y: Complex64) -> f64 {
        (x - y).norm() / y.norm()
    }

    #[test]
    fn foundation_limits() {
        let t = TrackParams::uic60_default();
        let sp = Complex64::new(t.pad_stiffness, t.pad_stiffness * t.pad_loss_factor);
        let sb = Complex64::new(t.ballast_stiffness, t.ballast_stiffness * t.ballast_loss_factor);
        assert!(rel(t.foundation_stiffness(0.0), sp * sb / (sp + sb)) < 1e-14);
        assert!(rel(t.foundation_stiffness(2.0 * PI * 1e6), sp) < 1e-6);
    }

    #[test]
    fn winkler_branch_decays_and_dissipates() {
        // Damped below and above cut-on, and undamped above cut-on with both zero signs.
        for net in
            [Complex64::new(1e8, 1e7), Complex64::new(-1e9, 1e7), Complex64::new(-1e9, 0.0), Complex64::new(-1e9, -0.0)]
        {
            let a = winkler_point_receptance(6.4e6, net);
            assert!(a.im <= 0.0, "Im alpha = {} > 0 for {net}", a.im);
            // Recover beta from alpha and check the decay of both kept roots -beta (1 +- i).
            // The principal cube root recovers beta: |arg beta| <= pi/4 < pi/3.
            let beta = (1.0 / (8.0 * 6.4e6 * a)).cbrt();
            let b4 = beta.powi(4) * 4.0 * 6.4e6;
            assert!(rel(b4, net) < 1e-12, "beta^4 {b4} vs {net}");
            for root in [-beta * Complex64::new(1.0, 1.0), -beta * Complex64::new(1.0, -1.0)] {
                assert!(root.re <= 1e-12 * root.norm(), "growing root {root} for {net}");
            }
        }
        // Undamped, above cut-on: alpha = -(1 + i)/(4 EI k^3), k^4 = -net/EI.
        let (ei, net): (f64, f64) = (6.4e6, -1e9);
        let k = (-net / ei).powf(0.25);
        let expect = Complex64::new(-1.0, -1.0) / (4.0 * ei * k.powi(3));
        assert!(rel(winkler_point_receptance(ei, Complex64::new(net, -0.0)), expect) < 1e-14);
    }

    #[test]
    fn hertz_stiffness_is_the_derivative_of_a_three_halves_law() {
        // N = c delta^(3/2): dN/d delta = 1.5 c delta^(1/2) = 1.5 N / delta.
        let (c, d0): (f64, f64) = (1e15, 8e-5);
        let n0 = c * d0.powf(1.5);
        let h = 1e-5 * d0;
        let fd = (c * (d0 + h).powf(1.5) - c * (d0 - h).powf(1.5)) / (2.0 * h);
        assert!((hertz_stiffness(n0, d0) - fd).abs() / fd < 1e-8);
    }

    #[test]
    fn invalid_parameters_are_rejected() {
        let mut t = TrackParams::uic60_default();
        t.pad_stiffness = 0.0;
        assert!(matches!(
            ReceptanceModel::new(t, WheelParams::default_freight(), 1e9),
            Err(DynamicsError::InvalidParameter { name: "pad_stiffness", .. })
        ));
        assert!(ReceptanceModel::new(TrackParams::uic60_default(), WheelParams { unsprung_mass: -1.0 }, 1e9).is_err());
        assert!(ReceptanceModel::new(TrackParams::uic60_default(), WheelParams::default_freight(), f64::NAN).is_err());
    }

    #[test]
    fn transfer_is_hermitian_and_zero_at_dc() {
        let m = ReceptanceModel::new(TrackParams::uic60_default(), WheelParams::default_freight(), 1.5e9).unwrap();
        assert_eq!(m.force_per_roughness(0.0), Complex64::new(0.0, 0.0));
        let h = m.force_per_roughness(321.0);
        assert_eq!(m.force_per_roughness(-321.0), h.conj());
    }
}
